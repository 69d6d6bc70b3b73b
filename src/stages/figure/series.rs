//! The data of a figure's layers: the series drawn from the needed stages' columns (with
//! their error bars and groups), the power-law guide lines, and the fitted lines.

use super::{DataLayer, FitLayer, GuideLayer, Style};
use anyhow::Context;
use anyhow::Result;
use pipeline::kind::Inputs;
use pipeline::table::{format_number, ColumnData, Table};
use std::collections::{BTreeMap, BTreeSet};

pub(super) struct Series {
    pub(super) label: String,
    pub(super) style: Style,
    /// Palette index; None: the series' position in the figure.
    pub(super) color: Option<usize>,
    pub(super) x_name: String,
    pub(super) y_name: String,
    pub(super) points: Vec<(f64, f64)>,
    /// Error estimates of the points' y (empty: none drawn).
    pub(super) errors: Vec<f64>,
    /// Indices of `points` before which the line is broken.
    pub(super) breaks: Vec<usize>,
    /// The layer's `group_by` column, the group's value as shown, and as a number where
    /// the column is numeric.
    pub(super) group: Option<(String, String, Option<f64>)>,
}

/// One group's curve while a layer's rows are read: its rows, its points, where its line
/// breaks, whether rows were left out since its last point, and its points' errors.
pub(super) type Curve = (Vec<usize>, Vec<(f64, f64)>, Vec<usize>, bool, Vec<f64>);

/// Which rows of the layer's table `t` its filter keeps.
pub(super) fn kept_rows(layer: &DataLayer, t: &Table) -> Result<Vec<bool>> {
    let mut keep = vec![true; t.n_rows()];
    for (col, value) in &layer.filter {
        let c = t.f64_column(col).with_context(|| format!("filter of layer from `{}`", layer.from))?;
        for (k, v) in keep.iter_mut().zip(c) {
            *k &= (v - value).abs() <= 1e-9 * value.abs().max(1e-300);
        }
    }
    Ok(keep)
}

/// Curves of one data layer, in the order their group values first appear.
pub(super) fn data_series(layer: &DataLayer, inputs: &Inputs) -> Result<Vec<Series>> {
    let t = inputs.table(&layer.from)?;
    let xs = t.f64_column(&layer.x).with_context(|| format!("layer from `{}`", layer.from))?;
    let ys = t.f64_column(&layer.y).with_context(|| format!("layer from `{}`", layer.from))?;
    let es = match &layer.y_error {
        Some(e) => Some(t.f64_column(e).with_context(|| format!("y_error of layer from `{}`", layer.from))?),
        None => None,
    };
    let keep = kept_rows(layer, t)?;
    let group: Option<&ColumnData> = match &layer.group_by {
        Some(g) => Some(t.column(g).with_context(|| format!("no column `{g}` to group by in `{}`", layer.from))?),
        None => None,
    };
    let mut order: Vec<String> = Vec::new();
    let mut groups: BTreeMap<String, Curve> = BTreeMap::new();
    for row in 0..t.n_rows() {
        let gkey = group.map(|g| g.display_at(row)).unwrap_or_default();
        if !keep[row] {
            if let Some(g) = groups.get_mut(&gkey) {
                g.3 = layer.gaps;
            }
            continue;
        }
        if !groups.contains_key(&gkey) {
            order.push(gkey.clone());
            groups.insert(gkey.clone(), (Vec::new(), Vec::new(), Vec::new(), false, Vec::new()));
        }
        let g = groups.get_mut(&gkey).unwrap();
        g.0.push(row);
        if std::mem::take(&mut g.3) {
            g.2.push(g.1.len());
        }
        g.1.push((xs[row], ys[row] * layer.y_scale));
        if let Some(es) = &es {
            g.4.push((es[row] * layer.y_scale).abs());
        }
    }
    // A curve's colour follows its group's place among all the table's groups, kept or
    // not, so that layers with the same `color` pair the same groups whatever they filter.
    let mut palette_order: Vec<String> = Vec::new();
    for row in 0..t.n_rows() {
        let gkey = group.map(|g| g.display_at(row)).unwrap_or_default();
        if !palette_order.contains(&gkey) {
            palette_order.push(gkey);
        }
    }
    Ok(order
        .into_iter()
        .map(|g| {
            let i = palette_order.iter().position(|k| *k == g).unwrap_or(0);
            let (rows, points, breaks, _, errors) = groups.remove(&g).unwrap();
            let first_row = rows[0];
            // A `{column}` is the value the column takes on the curve's rows, or all of them
            // where it takes several (a label never claims one value for points drawn at
            // several).
            let mut label = layer.label.clone();
            for (name, col) in &t.columns {
                let pat = format!("{{{name}}}");
                if label.contains(&pat) {
                    let values: BTreeSet<String> = rows.iter().map(|&r| col.display_at(r)).collect();
                    label = label.replace(&pat, &listed(&values));
                }
            }
            let group = layer.group_by.as_ref().zip(group).map(|(name, col)| {
                let value = match col {
                    ColumnData::F64(v) => Some(v[first_row]),
                    ColumnData::I64(v) => Some(v[first_row] as f64),
                    ColumnData::Bool(v) => Some(f64::from(u8::from(v[first_row]))),
                    ColumnData::Str(_) => None,
                };
                (name.clone(), col.display_at(first_row), value)
            });
            Series {
                label,
                style: layer.style,
                color: layer.color.map(|c| c + i),
                x_name: layer.x.clone(),
                y_name: layer.y.clone(),
                points,
                errors,
                breaks,
                group,
            }
        })
        .collect())
}

pub(super) fn guide_series(g: &GuideLayer, log_x: bool) -> Series {
    let n = 50;
    let points = (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64;
            let x = if log_x { g.x_from * (g.x_to / g.x_from).powf(t) } else { g.x_from + (g.x_to - g.x_from) * t };
            (x, g.through[1] * (x / g.through[0]).powf(g.slope))
        })
        .collect();
    Series {
        label: g.label.clone(),
        style: g.style,
        color: None,
        x_name: "guide".into(),
        y_name: "guide".into(),
        points,
        errors: Vec::new(),
        breaks: Vec::new(),
        group: None,
    }
}

/// A value and its standard error as a paper writes them: the error to two significant
/// digits and the value to the same decimal place (0.6667 and 0.0012); without an error
/// (zero or not finite), the value as tables show it and the error as "0".
pub(super) fn with_uncertainty(v: f64, e: f64) -> (String, String) {
    if !(e > 0.0 && e.is_finite() && v.is_finite()) {
        return (format_number(v), "0".into());
    }
    let decimals = (1 - e.log10().floor() as i32).clamp(0, 12) as usize;
    (format!("{v:.decimals$}"), format!("{e:.decimals$}"))
}

pub(super) fn fit_series(layer: &FitLayer, inputs: &Inputs, log_x: bool) -> Result<Vec<Series>> {
    let t = inputs.table(&layer.from)?;
    let col = |name: &str| t.f64_column(name).with_context(|| format!("fit layer from `{}`", layer.from));
    let (slope, err, pre, lo, hi) =
        (col("slope")?, col("slope_std_error")?, col("prefactor")?, col("x_min")?, col("x_max")?);
    let filters: Vec<(Vec<f64>, f64)> =
        layer.filter.iter().map(|(name, v)| Ok((col(name)?, *v))).collect::<Result<_>>()?;
    // Rows outside the filter, or without a fitted range (e.g. a regime not found), are skipped.
    let keep = |row: usize| {
        filters.iter().all(|(c, v)| c[row] == *v) && (layer.x_range.is_some() || (lo[row] > 0.0 && hi[row] > lo[row]))
    };
    Ok((0..t.n_rows())
        .filter(|&row| keep(row))
        .map(|row| {
            let (slope_text, err_text) = with_uncertainty(slope[row], err[row]);
            let mut label = layer.label.replace("{slope}", &slope_text).replace("{slope_std_error}", &err_text);
            for (name, c) in &t.columns {
                label = label.replace(&format!("{{{name}}}"), &c.display_at(row));
            }
            let [x_from, x_to] = layer.x_range.unwrap_or([lo[row], hi[row]]);
            let guide =
                GuideLayer { slope: slope[row], through: [1.0, pre[row]], x_from, x_to, label, style: layer.style };
            let mut s = guide_series(&guide, log_x);
            (s.x_name, s.y_name) = ("fit".into(), "fit".into());
            s.color = layer.color;
            s
        })
        .collect())
}

/// Values in numeric order where they are numbers, as a sentence lists them: "1", "0.1 and
/// 1", "0.1, 1 and 10".
pub(super) fn listed(values: &BTreeSet<String>) -> String {
    let mut v: Vec<&String> = values.iter().collect();
    v.sort_by(|a, b| match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(x), Ok(y)) => x.total_cmp(&y),
        _ => a.cmp(b),
    });
    match v.split_last() {
        Some((last, [])) => last.to_string(),
        Some((last, rest)) => format!("{} and {last}", rest.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(", ")),
        None => String::new(),
    }
}
