//! The `figure` kind: a paper-style x–y plot (plotters, SVG) of columns from the tables of
//! the stages it needs, with optional power-law guide lines. Its table is the plotted
//! data in long format: `series`, `x`, `y`, `x_name`, `y_name` (one row per point).
//! Log axes are drawn by plotting log10 values on a linear axis labelled in powers of ten.

use crate::pipeline::kind::{FieldError, Inputs, Kind, Output, ShownRange};
use crate::pipeline::table::{format_number, ColumnData, Table};
use anyhow::{bail, Context, Result};
use plotters::prelude::*;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Style {
    #[default]
    Line,
    Dashed,
    /// Short dashes (e.g. states past a stability test that the model still holds).
    Dotted,
    Points,
    /// A line through markers at the data points.
    LinePoints,
    /// A line with the region between it and the bottom of the axes shaded.
    Area,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum LegendPosition {
    UpperRight,
    UpperLeft,
    LowerRight,
    LowerLeft,
    /// Where the legend box covers no drawn point, line or shaded area: the corners first,
    /// then the middles of the sides; outside the axes, on the right, where every place
    /// inside covers some (the default).
    #[default]
    Auto,
}

/// Curves from a stage's table.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DataLayer {
    /// The stage whose table is plotted (must be in `needs`).
    pub from: String,
    /// Column for the horizontal axis.
    pub x: String,
    /// Column for the vertical axis.
    pub y: String,
    /// One curve per distinct value of this column.
    #[serde(default)]
    pub group_by: Option<String>,
    /// Legend label; `{column}` is replaced by that column's value for the curve. Empty or
    /// absent: no legend entry.
    #[serde(default)]
    pub label: String,
    #[serde(default)]
    pub style: Style,
    /// Keep only rows where each named column equals the given value.
    #[serde(default)]
    pub filter: BTreeMap<String, f64>,
    /// Break a curve's line where rows of its group are left out by `filter` (default:
    /// the line joins the kept rows across them).
    #[serde(default)]
    pub gaps: bool,
    /// Scale the y values by this factor.
    #[serde(default = "one")]
    pub y_scale: f64,
    /// Column of the y values' error estimates (in y's units, scaled by `y_scale` too):
    /// drawn as error bars y - e .. y + e and tabulated as `y_error`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_error: Option<String>,
    /// Palette index (0 black, 1 blue, 2 red, 3 green, 4 purple, 5 orange, ...) of the
    /// table's first group; the k-th group (in table order, whether `filter` keeps it or not)
    /// takes the k-th next colour. Default: continue the palette after the previous curves.
    /// Give two layers the same `color` to pair their curves (e.g. +W solid and -W dashed of
    /// the same lambda).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<usize>,
}

fn one() -> f64 {
    1.0
}

/// A power law y = y0 (x / x0)^slope drawn from x_from to x_to.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GuideLayer {
    pub slope: f64,
    /// A point (x0, y0) on the line.
    pub through: [f64; 2],
    pub x_from: f64,
    pub x_to: f64,
    pub label: String,
    #[serde(default = "dashed")]
    pub style: Style,
}

fn dashed() -> Style {
    Style::Dashed
}

/// The power laws y = prefactor x^slope of a `fit.powerlaw` stage, one curve per row
/// (group), drawn over the fitted range or over `x_range`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FitLayer {
    /// The fit stage (must be in `needs`).
    pub from: String,
    /// Legend label; `{slope}` and `{slope_std_error}` are replaced by the fitted values
    /// (the error to two significant digits, the slope to the same decimal), other
    /// `{column}`s by the row's value. Omitted: no legend entry.
    #[serde(default)]
    pub label: String,
    /// Draw over this x range instead of the fitted one.
    #[serde(default)]
    pub x_range: Option<[f64; 2]>,
    #[serde(default = "dashed")]
    pub style: Style,
    /// Keep only rows where each named column equals the given value.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub filter: BTreeMap<String, f64>,
    /// Palette index (as for data layers) of every curve of this layer: fitted laws drawn
    /// as one family. Default: continue the palette.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<usize>,
}

#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Layer {
    Data(DataLayer),
    Guide(GuideLayer),
    Fit(FitLayer),
}

fn default_width() -> u32 {
    800
}
fn default_height() -> u32 {
    560
}

#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FigureParams {
    pub title: String,
    /// Axis label, with units or the dimensionless symbol.
    pub x_label: String,
    pub y_label: String,
    #[serde(default)]
    pub log_x: bool,
    #[serde(default)]
    pub log_y: bool,
    /// Axis ranges (data units); default: the data's extent. `x_range` is also the range
    /// this figure shows of each data layer's `x` column: a sweep of that parameter may
    /// sample it (`{shown: n}`) and is checked against it.
    #[serde(default)]
    pub x_range: Option<[f64; 2]>,
    #[serde(default)]
    pub y_range: Option<[f64; 2]>,
    #[serde(default = "default_width")]
    pub width: u32,
    #[serde(default = "default_height")]
    pub height: u32,
    #[serde(default)]
    pub legend: LegendPosition,
    pub layers: Vec<Layer>,
}

struct Series {
    label: String,
    style: Style,
    /// Palette index; None: the series' position in the figure.
    color: Option<usize>,
    x_name: String,
    y_name: String,
    points: Vec<(f64, f64)>,
    /// Error estimates of the points' y (empty: none drawn).
    errors: Vec<f64>,
    /// Indices of `points` before which the line is broken.
    breaks: Vec<usize>,
    /// The layer's `group_by` column, the group's value as shown, and as a number where
    /// the column is numeric.
    group: Option<(String, String, Option<f64>)>,
}

/// One group's curve while a layer's rows are read: its first row, its points, where its
/// line breaks, whether rows were left out since its last point, and its points' errors.
type Curve = (usize, Vec<(f64, f64)>, Vec<usize>, bool, Vec<f64>);

/// Curves of one data layer, in the order their group values first appear.
fn data_series(layer: &DataLayer, inputs: &Inputs) -> Result<Vec<Series>> {
    let t = inputs.table(&layer.from)?;
    let xs = t.f64_column(&layer.x).with_context(|| format!("layer from `{}`", layer.from))?;
    let ys = t.f64_column(&layer.y).with_context(|| format!("layer from `{}`", layer.from))?;
    let es = match &layer.y_error {
        Some(e) => Some(t.f64_column(e).with_context(|| format!("y_error of layer from `{}`", layer.from))?),
        None => None,
    };
    let mut keep = vec![true; t.n_rows()];
    for (col, value) in &layer.filter {
        let c = t.f64_column(col).with_context(|| format!("filter of layer from `{}`", layer.from))?;
        for (k, v) in keep.iter_mut().zip(c) {
            *k &= (v - value).abs() <= 1e-9 * value.abs().max(1e-300);
        }
    }
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
            groups.insert(gkey.clone(), (row, Vec::new(), Vec::new(), false, Vec::new()));
        }
        let g = groups.get_mut(&gkey).unwrap();
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
            let (first_row, points, breaks, _, errors) = groups.remove(&g).unwrap();
            let mut label = layer.label.clone();
            for (name, col) in &t.columns {
                let pat = format!("{{{name}}}");
                if label.contains(&pat) {
                    label = label.replace(&pat, &col.display_at(first_row));
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

fn guide_series(g: &GuideLayer, log_x: bool) -> Series {
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
fn with_uncertainty(v: f64, e: f64) -> (String, String) {
    if !(e > 0.0 && e.is_finite() && v.is_finite()) {
        return (format_number(v), "0".into());
    }
    let decimals = (1 - e.log10().floor() as i32).clamp(0, 12) as usize;
    (format!("{v:.decimals$}"), format!("{e:.decimals$}"))
}

fn fit_series(layer: &FitLayer, inputs: &Inputs, log_x: bool) -> Result<Vec<Series>> {
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

/// Sixteen colours: black, the ten of matplotlib's tab10, navy, maroon, dark green, olive
/// and teal (so that a figure of up to fifteen families repeats none: the bench's BEM
/// figure has fifteen, its FEM figure twelve).
const PALETTE: [RGBColor; 16] = [
    RGBColor(0, 0, 0),
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
    RGBColor(188, 189, 34),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(0, 0, 128),
    RGBColor(128, 0, 0),
    RGBColor(0, 100, 0),
    RGBColor(128, 128, 0),
    RGBColor(0, 128, 128),
];

/// "10⁻³" for an integer exponent.
fn power_of_ten(e: i32) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits: String = e.unsigned_abs().to_string().chars().map(|c| SUP[c.to_digit(10).unwrap() as usize]).collect();
    format!("10{}{digits}", if e < 0 { "⁻" } else { "" })
}

/// A tick label; on linear axes values within 1e-9 of the span of zero are 0 (plotters'
/// tick positions carry rounding: -2.2e-17 was printed on Fig. 5.2d).
fn axis_label(v: f64, log: bool, span: f64) -> String {
    if log {
        let r = v.round();
        if (v - r).abs() < 1e-6 {
            power_of_ten(r as i32)
        } else {
            String::new()
        }
    } else if v.abs() < 1e-9 * span {
        "0".into()
    } else {
        // Rounded to 12 significant digits first: a tick at 3 x 5e-6 is 1.5000000000000002e-5.
        format_number(format!("{v:.11e}").parse().unwrap_or(v))
    }
}

/// The range of the transformed values, padded by 3% on linear axes.
fn extent(given: Option<[f64; 2]>, log: bool, values: impl Iterator<Item = f64>) -> Result<(f64, f64)> {
    let (lo, hi) = match given {
        Some([a, b]) => {
            if log && (a <= 0.0 || b <= 0.0) {
                bail!("a log axis needs a positive range, got [{a}, {b}]");
            }
            if log {
                (a.log10(), b.log10())
            } else {
                (a, b)
            }
        }
        None => {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for v in values {
                lo = lo.min(v);
                hi = hi.max(v);
            }
            if !lo.is_finite() {
                bail!("nothing to plot");
            }
            if log {
                (lo.floor(), hi.ceil().max(lo.floor() + 1.0))
            } else {
                let pad = 0.03 * (hi - lo).max(1e-12);
                (lo - pad, hi + pad)
            }
        }
    };
    if !(hi > lo) {
        bail!("empty axis range [{lo}, {hi}]");
    }
    Ok((lo, hi))
}

/// The SVG of a figure. An automatic legend that would cover a drawn mark wherever it goes
/// inside the axes is drawn outside them, on the right.
fn render(p: &FigureParams, series: &[Series]) -> Result<String> {
    let (svg, covered) = draw(p, series, false)?;
    if covered == 0 || p.legend != LegendPosition::Auto {
        return Ok(svg);
    }
    Ok(draw(p, series, true)?.0)
}

/// The title's lines: words wrapped so that each line fits in `width` pixels at `font`.
fn title_lines(title: &str, font: &TextStyle, width: u32) -> Vec<String> {
    let fits = |line: &str| {
        let mut t = MultiLineText::<_, &str>::new((0, 0), font);
        t.push_line(line);
        t.estimate_dimension().map(|(w, _)| w as u32 <= width).unwrap_or(true)
    };
    let mut lines: Vec<String> = Vec::new();
    for word in title.split(' ') {
        match lines.last_mut() {
            Some(line) if fits(&format!("{line} {word}")) => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Draws the figure, the legend outside the axes if `legend_outside`; returns the SVG and
/// how many drawn marks the legend covers.
fn draw(p: &FigureParams, series: &[Series], legend_outside: bool) -> Result<(String, usize)> {
    let tx = |x: f64| if p.log_x { x.log10() } else { x };
    let ty = |y: f64| if p.log_y { y.log10() } else { y };
    let xs = series.iter().flat_map(|s| s.points.iter().map(|q| tx(q.0)));
    let (x0, x1) = extent(p.x_range, p.log_x, xs)?;
    // The automatic y range covers the points inside the x range only.
    let ys = series.iter().flat_map(|s| s.points.iter().filter(|q| tx(q.0) >= x0 && tx(q.0) <= x1).map(|q| ty(q.1)));
    let (y0, y1) = extent(p.y_range, p.log_y, ys)?;
    let mut svg = String::new();
    let covered = {
        let root = SVGBackend::with_string(&mut svg, (p.width, p.height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let title_font: TextStyle = ("sans-serif", 22).into_font().into();
        let mut area = root.clone();
        for line in title_lines(&p.title, &title_font, p.width.saturating_sub(36)) {
            area = area.titled(&line, title_font.clone()).map_err(|e| anyhow::anyhow!("{e:?}"))?;
        }
        let labels: Vec<&str> = series.iter().filter(|s| !s.label.is_empty()).map(|s| s.label.as_str()).collect();
        let (legend_w, _) = legend_size(&labels);
        let mut chart = ChartBuilder::on(&area)
            .margin(18)
            .margin_right(if legend_outside { 18 + legend_w as u32 + 10 } else { 18 })
            .x_label_area_size(52)
            .y_label_area_size(72)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let fx = |v: &f64| axis_label(*v, p.log_x, x1 - x0);
        let fy = |v: &f64| axis_label(*v, p.log_y, y1 - y0);
        let n_x = if p.log_x { ((x1 - x0).round() as usize + 1).clamp(2, 13) } else { 8 };
        let n_y = if p.log_y { ((y1 - y0).round() as usize + 1).clamp(2, 13) } else { 8 };
        chart
            .configure_mesh()
            .x_desc(p.x_label.as_str())
            .y_desc(p.y_label.as_str())
            .x_labels(n_x)
            .y_labels(n_y)
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .axis_desc_style(("sans-serif", 18))
            .label_style(("sans-serif", 14))
            .light_line_style(RGBColor(244, 244, 244))
            .bold_line_style(RGBColor(215, 215, 215))
            .draw()
            .map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let inside = |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite();
        for (i, s) in series.iter().enumerate() {
            let color = PALETTE[s.color.unwrap_or(i) % PALETTE.len()];
            let style = ShapeStyle::from(&color).stroke_width(2);
            let err = |e| anyhow::anyhow!("{e:?}");
            // Lines are drawn as the runs of points inside the axes: a curve that leaves
            // the plotted range is not clamped to its border. A run also ends at the
            // series' breaks.
            let in_view = |&(x, y): &(f64, f64)| x >= x0 && x <= x1 && y >= y0 && y <= y1;
            let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for (k, &(x, y)) in s.points.iter().enumerate() {
                if s.breaks.contains(&k) && !runs.last().unwrap().is_empty() {
                    runs.push(Vec::new());
                }
                let q = (tx(x), ty(y));
                if !inside(&q) {
                    continue;
                }
                if in_view(&q) {
                    runs.last_mut().unwrap().push(q);
                } else if !runs.last().unwrap().is_empty() {
                    runs.push(Vec::new());
                }
            }
            runs.retain(|r| !r.is_empty());
            // Error bars, clipped to the axes (on a log axis a bar reaching zero or below
            // runs to the bottom).
            let bars: Vec<_> = s
                .points
                .iter()
                .zip(&s.errors)
                .filter(|&(&(x, y), &e)| e > 0.0 && in_view(&(tx(x), ty(y))))
                .map(|(&(x, y), &e)| {
                    let lo = if p.log_y && y - e <= 0.0 { y0 } else { ty(y - e).max(y0) };
                    ErrorBar::new_vertical(tx(x), lo, ty(y), ty(y + e).min(y1), style.stroke_width(1), 6)
                })
                .collect();
            chart.draw_series(bars).map_err(err)?;
            for run in runs {
                match s.style {
                    Style::Line => chart.draw_series(LineSeries::new(run, style)).map_err(err)?,
                    Style::Dashed => chart.draw_series(DashedLineSeries::new(run, 8, 5, style)).map_err(err)?,
                    Style::Dotted => chart.draw_series(DashedLineSeries::new(run, 2, 4, style)).map_err(err)?,
                    Style::Points => {
                        chart.draw_series(run.into_iter().map(|q| Circle::new(q, 3, color.filled()))).map_err(err)?
                    }
                    Style::LinePoints => {
                        chart.draw_series(run.iter().map(|&q| Circle::new(q, 3, color.filled()))).map_err(err)?;
                        chart.draw_series(LineSeries::new(run, style)).map_err(err)?
                    }
                    Style::Area => chart
                        .draw_series(AreaSeries::new(run, y0, color.mix(0.18).filled()).border_style(style))
                        .map_err(err)?,
                };
            }
        }
        let area = chart.plotting_area().dim_in_pixel();
        let base = chart.plotting_area().get_base_pixel();
        let pinned = |p: SeriesLabelPosition| (legend_corner(&p, legend_size(&labels), area), 0);
        let (corner, covered) = match p.legend {
            LegendPosition::UpperRight => pinned(SeriesLabelPosition::UpperRight),
            LegendPosition::UpperLeft => pinned(SeriesLabelPosition::UpperLeft),
            LegendPosition::LowerRight => pinned(SeriesLabelPosition::LowerRight),
            LegendPosition::LowerLeft => pinned(SeriesLabelPosition::LowerLeft),
            LegendPosition::Auto if legend_outside => ((area.0 as i32 + 10, 0), 0),
            LegendPosition::Auto if labels.is_empty() => ((0, 0), 0),
            LegendPosition::Auto => {
                // The drawn marks in pixels of the plotting area: points, lines sampled
                // between them, and the shaded region under an area's line.
                let px = |q: (f64, f64)| {
                    let (x, y) = chart.backend_coord(&q);
                    (x - base.0, y - base.1)
                };
                let mut marks = Vec::new();
                for s in series {
                    let q: Vec<(f64, f64)> = s
                        .points
                        .iter()
                        .map(|&(x, y)| (tx(x), ty(y)))
                        .filter(|&(x, y)| x.is_finite() && y.is_finite() && x >= x0 && x <= x1 && y >= y0 && y <= y1)
                        .collect();
                    for (k, &a) in q.iter().enumerate() {
                        marks.push(px(a));
                        if s.style == Style::Area {
                            marks.extend((1..=12).map(|j| px((a.0, a.1 - (a.1 - y0) * j as f64 / 12.0))));
                        }
                        if s.style != Style::Points {
                            if let Some(&b) = q.get(k + 1) {
                                // A sample every 2 pixels or so: no line crosses the box unseen.
                                let (pa, pb) = (px(a), px(b));
                                let n = ((pb.0 - pa.0).abs().max((pb.1 - pa.1).abs()) / 2).clamp(1, 2000);
                                marks.extend((1..n).map(|j| {
                                    let t = j as f64 / n as f64;
                                    px((a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t))
                                }));
                            }
                        }
                    }
                }
                let (best, covered) = least_covering_legend(&labels, area, &marks);
                (legend_corner(&best, legend_size(&labels), area), covered)
            }
        };
        let entries: Vec<(&str, Style, RGBColor)> = series
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.label.is_empty())
            .map(|(i, s)| (s.label.as_str(), s.style, PALETTE[s.color.unwrap_or(i) % PALETTE.len()]))
            .collect();
        draw_legend(&root, &entries, (base.0 + corner.0, base.1 + corner.1))?;
        root.present().map_err(|e| anyhow::anyhow!("{e:?}"))?;
        covered
    };
    Ok((svg, covered))
}

/// The legend position (a box of the labels at 14 px plus the 30 px sample and 10 px
/// margins, 5 px from the plotting area's edges) that covers the fewest of `marks` (pixels of the plotting area of size `area`), the corners
/// first on a tie.
fn least_covering_legend(labels: &[&str], area: (u32, u32), marks: &[(i32, i32)]) -> (SeriesLabelPosition, usize) {
    use SeriesLabelPosition::*;
    let candidates = [UpperRight, UpperLeft, LowerRight, LowerLeft, MiddleRight, MiddleLeft, UpperMiddle, LowerMiddle];
    let (w, h) = legend_size(labels);
    let covered = |p: &SeriesLabelPosition| {
        let (x, y) = legend_corner(p, (w, h), area);
        marks.iter().filter(|&&(mx, my)| mx >= x && mx <= x + w && my >= y && my <= y + h).count()
    };
    candidates
        .into_iter()
        .map(|p| {
            let n = covered(&p);
            (p, n)
        })
        .min_by_key(|&(_, n)| n)
        .unwrap_or((UpperRight, 0))
}

/// The top left corner of a legend box of size `(w, h)` at position `p` of a plotting area
/// of size `area`, 5 px from its edges, in pixels of the plotting area.
fn legend_corner(p: &SeriesLabelPosition, (w, h): (i32, i32), area: (u32, u32)) -> (i32, i32) {
    use SeriesLabelPosition::*;
    let (aw, ah) = (area.0 as i32, area.1 as i32);
    let x = match p {
        UpperLeft | MiddleLeft | LowerLeft => 5,
        UpperMiddle | MiddleMiddle | LowerMiddle => (aw - w) / 2,
        _ => aw - w - 5,
    };
    let y = match p {
        UpperLeft | UpperMiddle | UpperRight => 5,
        MiddleLeft | MiddleMiddle | MiddleRight => (ah - h) / 2,
        _ => ah - h - 5,
    };
    (x, y)
}

/// Draws the legend box with its top left corner at `at` (pixels of `root`): per entry a
/// 22 px sample of the series' style and colour, then its label.
fn draw_legend(
    root: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    entries: &[(&str, Style, RGBColor)],
    at: (i32, i32),
) -> Result<()> {
    if entries.is_empty() {
        return Ok(());
    }
    let err = |e| anyhow::anyhow!("{e:?}");
    let labels: Vec<&str> = entries.iter().map(|e| e.0).collect();
    let (w, h) = legend_size(&labels);
    let (x, y) = at;
    root.draw(&Rectangle::new([(x, y), (x + w, y + h)], WHITE.mix(0.85).filled())).map_err(err)?;
    root.draw(&Rectangle::new([(x, y), (x + w, y + h)], RGBColor(120, 120, 120))).map_err(err)?;
    let row = (h - 20) as f64 / entries.len() as f64;
    let font: TextStyle = ("sans-serif", 14).into_font().into();
    let font = font.pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Left,
        plotters::style::text_anchor::VPos::Center,
    ));
    for (k, &(label, style, color)) in entries.iter().enumerate() {
        let (sx, sy) = (x + 10, y + 10 + (row * (k as f64 + 0.5)).round() as i32);
        let stroke = ShapeStyle::from(&color).stroke_width(2);
        let segments: &[(i32, i32)] = match style {
            Style::Points => &[],
            Style::Dotted => &[(0, 3), (9, 12), (18, 21)],
            Style::Dashed => &[(0, 8), (13, 22)],
            Style::Line | Style::LinePoints | Style::Area => &[(0, 22)],
        };
        for &(a, b) in segments {
            root.draw(&PathElement::new(vec![(sx + a, sy), (sx + b, sy)], stroke)).map_err(err)?;
        }
        if matches!(style, Style::Points | Style::LinePoints) {
            root.draw(&Circle::new((sx + 11, sy), 3, color.filled())).map_err(err)?;
        }
        root.draw(&Text::new(label, (sx + 30, sy), font.clone())).map_err(err)?;
    }
    Ok(())
}

/// The legend box in pixels: the labels at 14 px plus the 30 px sample and 10 px margins.
fn legend_size(labels: &[&str]) -> (i32, i32) {
    let font: TextStyle = ("sans-serif", 14).into_font().into();
    let mut text = MultiLineText::<_, &str>::new((0, 0), &font);
    for l in labels {
        text.push_line(*l);
    }
    let (w, h) = text.estimate_dimension().unwrap_or((0, 0));
    (w + 30 + 20, h + 20)
}

pub struct Figure;

impl Kind for Figure {
    const NAME: &'static str = "figure";
    const VERSION: u32 = 13;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str = "An x-y figure (SVG) of columns of the needed stages, with its data as a long table";
    const COLUMNS: &'static [&'static str] =
        &["series", "x", "y", "x_name", "y_name", "group_by", "group", "group_value", "y_error"];
    type Params = FigureParams;

    fn validate(p: &FigureParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        if p.layers.is_empty() {
            e.push(FieldError::new("layers", "a figure needs at least one layer"));
        }
        for (name, r, log) in [("x_range", p.x_range, p.log_x), ("y_range", p.y_range, p.log_y)] {
            if let Some([a, b]) = r {
                if !(b > a) || (log && a <= 0.0) {
                    e.push(FieldError::new(
                        name,
                        format!(
                            "needs from < to{}, got [{a}, {b}]",
                            if log { " and a positive start (log axis)" } else { "" }
                        ),
                    ));
                }
            }
        }
        for (i, l) in p.layers.iter().enumerate() {
            if let Layer::Fit(FitLayer { x_range: Some([a, b]), .. }) = l {
                if !(*a > 0.0 && b > a) {
                    e.push(FieldError::new(&format!("layers[{i}].fit.x_range"), "needs 0 < from < to"));
                }
            }
            if let Layer::Guide(g) = l {
                if !(g.through[0] > 0.0 && g.x_from > 0.0 && g.x_to > g.x_from) {
                    e.push(FieldError::new(
                        &format!("layers[{i}].guide"),
                        "needs positive x values with x_from < x_to",
                    ));
                }
            }
        }
        if !(100..=4000).contains(&p.width) || !(100..=4000).contains(&p.height) {
            e.push(FieldError::new("width", "width and height must lie in 100..=4000 pixels"));
        }
        e
    }

    fn referenced_stages(p: &FigureParams) -> Vec<(String, String)> {
        p.layers
            .iter()
            .enumerate()
            .filter_map(|(i, l)| match l {
                Layer::Data(d) => Some((format!("layers[{i}].data.from"), d.from.clone())),
                Layer::Fit(f) => Some((format!("layers[{i}].fit.from"), f.from.clone())),
                Layer::Guide(_) => None,
            })
            .collect()
    }

    /// With an `x_range`, every data layer shows its `x` column of its stage over it.
    fn shown_ranges(p: &FigureParams) -> Vec<ShownRange> {
        let Some([from, to]) = p.x_range else { return Vec::new() };
        p.layers
            .iter()
            .filter_map(|l| match l {
                Layer::Data(d) => Some(ShownRange {
                    stage: d.from.clone(),
                    column: d.x.clone(),
                    from,
                    to,
                    log: p.log_x,
                    path: "x_range".into(),
                }),
                _ => None,
            })
            .collect()
    }

    fn run(p: &FigureParams, inputs: &Inputs) -> Result<Output> {
        let mut series = Vec::new();
        for l in &p.layers {
            match l {
                Layer::Data(d) => series.extend(data_series(d, inputs)?),
                Layer::Guide(g) => series.push(guide_series(g, p.log_x)),
                Layer::Fit(f) => series.extend(fit_series(f, inputs, p.log_x)?),
            }
        }
        // On log axes, points at or below zero cannot be drawn: leave them out of both the
        // figure and its table.
        for s in &mut series {
            let drawable = |&(x, y): &(f64, f64)| (!p.log_x || x > 0.0) && (!p.log_y || y > 0.0);
            if !s.errors.is_empty() {
                let kept: Vec<bool> = s.points.iter().map(drawable).collect();
                let mut k = kept.iter();
                s.errors.retain(|_| *k.next().unwrap());
            }
            s.points.retain(drawable);
        }
        let svg = render(p, &series)?;
        let rows = series.iter().flat_map(|s| s.points.iter().map(move |&(x, y)| (s, x, y)));
        let table = Table::new()
            .with("series", ColumnData::Str(rows.clone().map(|(s, _, _)| s.label.clone()).collect()))
            .with_f64("x", rows.clone().map(|(_, x, _)| x).collect())
            .with_f64("y", rows.clone().map(|(_, _, y)| y).collect())
            .with("x_name", ColumnData::Str(rows.clone().map(|(s, _, _)| s.x_name.clone()).collect()))
            .with("y_name", ColumnData::Str(rows.map(|(s, _, _)| s.y_name.clone()).collect()));
        // The error column only where a layer has errors (0 for the other series' points).
        let table = if series.iter().any(|s| !s.errors.is_empty()) {
            let errors =
                series.iter().flat_map(|s| (0..s.points.len()).map(|i| s.errors.get(i).copied().unwrap_or(0.0)));
            table.with_f64("y_error", errors.collect())
        } else {
            table
        };
        // The group of each point where a layer groups its rows: the grouping column, its
        // value as shown, and as a number (0 where not numeric) for filtering in a data frame.
        let table = if series.iter().any(|s| s.group.is_some()) {
            let per_point = |f: &dyn Fn(&Series) -> String| -> Vec<String> {
                series.iter().flat_map(|s| std::iter::repeat_n(f(s), s.points.len())).collect()
            };
            let values: Vec<f64> = series
                .iter()
                .flat_map(|s| {
                    let v = s.group.as_ref().and_then(|g| g.2).filter(|v| v.is_finite()).unwrap_or(0.0);
                    std::iter::repeat_n(v, s.points.len())
                })
                .collect();
            table
                .with(
                    "group_by",
                    ColumnData::Str(per_point(&|s| s.group.as_ref().map_or(String::new(), |g| g.0.clone()))),
                )
                .with("group", ColumnData::Str(per_point(&|s| s.group.as_ref().map_or(String::new(), |g| g.1.clone()))))
                .with_f64("group_value", values)
        } else {
            table
        };
        let mut out = Output::from(table);
        out.artifacts.insert("svg".into(), svg);
        Ok(out)
    }
}

pub fn register(r: &mut crate::pipeline::kind::Registry) {
    r.add::<Figure>();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_tick_labels_carry_no_rounding_noise() {
        assert_eq!(axis_label(3.0 * 5e-6, false, 2e-5), "1.5e-5");
        assert_eq!(axis_label(0.1 + 0.2, false, 1.0), "0.3");
        assert_eq!(axis_label(-2.2e-17, false, 1.0), "0");
        assert_eq!(axis_label(250.0, false, 1000.0), "250");
    }

    fn layer(y: &str, color: Option<usize>) -> DataLayer {
        DataLayer {
            from: "t".into(),
            x: "x".into(),
            y: y.into(),
            group_by: Some("g".into()),
            label: "g = {g}".into(),
            style: Style::Line,
            filter: BTreeMap::new(),
            gaps: false,
            y_scale: 1.0,
            y_error: None,
            color,
        }
    }

    /// A 400 x 300 figure of `layers` with placeholder labels.
    fn test_figure(layers: Vec<Layer>) -> FigureParams {
        FigureParams {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            log_x: false,
            log_y: false,
            x_range: None,
            y_range: None,
            width: 400,
            height: 300,
            legend: LegendPosition::UpperRight,
            layers,
        }
    }

    #[test]
    fn a_filtered_group_keeps_its_colour_and_gaps_break_the_line() {
        // Group 0 has a row the filter drops between two kept ones; group 1 has only dropped
        // rows, group 2 kept ones: group 2 is still the third colour, and with `gaps` group 0
        // is drawn as two lines.
        let t = Table::new()
            .with_f64("x", vec![1.0, 2.0, 3.0, 1.0, 2.0, 1.0, 2.0])
            .with_f64("a", vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0])
            .with_f64("keep", vec![1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0])
            .with_f64("g", vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0]);
        let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
        let mut l = layer("a", Some(1));
        l.filter = BTreeMap::from([("keep".to_string(), 1.0)]);
        let joined = data_series(&l, &inputs).unwrap();
        assert_eq!(joined.iter().map(|s| s.color).collect::<Vec<_>>(), vec![Some(1), Some(3)]);
        assert!(joined.iter().all(|s| s.breaks.is_empty()));
        l.gaps = true;
        let broken = data_series(&l, &inputs).unwrap();
        assert_eq!(broken[0].points, vec![(1.0, 1.0), (3.0, 3.0)]);
        assert_eq!((broken[0].breaks.clone(), broken[1].breaks.clone()), (vec![1], vec![]));
        let fig = test_figure(vec![Layer::Data(l.clone())]);
        let lines = |series: &[Series]| render(&fig, series).unwrap().matches("<polyline").count();
        assert_eq!(lines(&broken), lines(&joined) + 1);
    }

    #[test]
    fn each_point_carries_its_group_as_text_and_number() {
        // Two numeric groups (g = 0.25 and 1.5) and a guide without a group: the table has
        // the grouping column's name, the group as shown and as a number, empty and 0 for the
        // guide's points.
        let t = Table::new()
            .with_f64("x", vec![1.0, 2.0, 1.0])
            .with_f64("a", vec![1.0, 2.0, 3.0])
            .with_f64("g", vec![0.25, 0.25, 1.5]);
        let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
        let guide = GuideLayer {
            slope: 1.0,
            through: [1.0, 1.0],
            x_from: 1.0,
            x_to: 2.0,
            label: "guide".into(),
            style: Style::Dashed,
        };
        let fig = test_figure(vec![Layer::Data(layer("a", None)), Layer::Guide(guide)]);
        let out = Figure::run(&fig, &inputs).unwrap();
        let n = out.table.n_rows();
        assert_eq!(n, 3 + 50);
        let text = |c: &str| match out.table.column(c).unwrap() {
            ColumnData::Str(v) => v.clone(),
            _ => panic!("{c} is not text"),
        };
        assert_eq!(&text("group_by")[..4], ["g", "g", "g", ""]);
        assert_eq!(&text("group")[..4], ["0.25", "0.25", "1.5", ""]);
        assert_eq!(&out.table.f64_column("group_value").unwrap()[..4], [0.25, 0.25, 1.5, 0.0]);
        // Without a grouped layer there are no group columns.
        let mut plain = layer("a", None);
        plain.group_by = None;
        let out = Figure::run(&test_figure(vec![Layer::Data(plain)]), &inputs).unwrap();
        assert!(out.table.column("group_by").is_none());
    }

    #[test]
    fn the_automatic_legend_goes_where_it_covers_nothing() {
        // A 700 x 400 plotting area: marks filling the upper half push the legend to a lower
        // corner; marks everywhere but the middle of the right side put it there.
        use SeriesLabelPosition as P;
        let labels = ["a curve", "another curve"];
        let area = (700u32, 400u32);
        let grid = |keep: &dyn Fn(i32, i32) -> bool| -> Vec<(i32, i32)> {
            (0..700)
                .step_by(7)
                .flat_map(|x| (0..400).step_by(7).map(move |y| (x, y)))
                .filter(|&(x, y)| keep(x, y))
                .collect()
        };
        let upper = grid(&|_, y| y < 200);
        assert!(matches!(least_covering_legend(&labels, area, &upper).0, P::LowerRight));
        let all_but_middle_right = grid(&|x, y| !(x > 450 && (150..250).contains(&y)));
        assert!(matches!(least_covering_legend(&labels, area, &all_but_middle_right).0, P::MiddleRight));
        // Nothing drawn: the first corner.
        assert!(matches!(least_covering_legend(&labels, area, &[]).0, P::UpperRight));
    }

    #[test]
    fn a_legend_that_covers_data_everywhere_inside_goes_outside_the_axes() {
        // Ten horizontal lines across the whole 400 x 300 figure leave no place inside the
        // axes for a legend of ten labels: the automatic legend is drawn right of the axes
        // (its labels start past the last x tick label), a pinned one stays inside.
        let x: Vec<f64> = (0..10).flat_map(|_| [0.0, 1.0]).collect();
        let y: Vec<f64> = (0..10).flat_map(|i| [i as f64, i as f64]).collect();
        let g: Vec<f64> = (0..10).flat_map(|i| [i as f64, i as f64]).collect();
        let t = Table::new().with_f64("x", x).with_f64("a", y).with_f64("g", g);
        let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
        let mut l = layer("a", None);
        l.label = "curve number {g}".into();
        let mut fig = test_figure(vec![Layer::Data(l)]);
        fig.legend = LegendPosition::Auto;
        let series = data_series(
            match &fig.layers[0] {
                Layer::Data(d) => d,
                _ => unreachable!(),
            },
            &inputs,
        )
        .unwrap();
        let (_, covered) = draw(&fig, &series, false).unwrap();
        assert!(covered > 0);
        let label_x = |svg: &str| -> f64 {
            let at = svg.find(">\ncurve number 0\n<").expect("label drawn");
            let tag = &svg[svg[..at].rfind("<text").unwrap()..at];
            let x = tag.split("x=\"").nth(1).unwrap();
            x[..x.find('"').unwrap()].parse().unwrap()
        };
        // The rightmost point of the data's lines (those longer than a legend's 22 px sample).
        let line_end = |svg: &str| -> f64 {
            svg.split("<polyline")
                .skip(1)
                .map(|p| {
                    let pts = p.split("points=\"").nth(1).unwrap();
                    let xs: Vec<f64> = pts[..pts.find('"').unwrap()]
                        .split_whitespace()
                        .map(|xy| xy.split(',').next().unwrap().parse::<f64>().unwrap())
                        .collect();
                    let (lo, hi) = xs.iter().fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
                    if hi - lo > 30.0 {
                        hi
                    } else {
                        f64::MIN
                    }
                })
                .fold(f64::MIN, f64::max)
        };
        let outside = render(&fig, &series).unwrap();
        assert!(line_end(&outside) < label_x(&outside) - 30.0, "{} {}", line_end(&outside), label_x(&outside));
        fig.legend = LegendPosition::UpperRight;
        let inside = render(&fig, &series).unwrap();
        assert!(line_end(&inside) > label_x(&inside), "{} {}", line_end(&inside), label_x(&inside));
    }

    #[test]
    fn a_long_title_is_wrapped_to_the_figure_width() {
        let font: TextStyle = ("sans-serif", 22).into_font().into();
        let title =
            "Fig. 3.9: critical surface energy against thickness, loading to δ/R = 0.35, four friction coefficients";
        let lines = title_lines(title, &font, 764);
        assert!(lines.len() >= 2, "{lines:?}");
        assert_eq!(lines.join(" "), title);
        assert_eq!(title_lines("short", &font, 764), vec!["short".to_string()]);
    }

    #[test]
    fn fit_labels_carry_the_error_to_two_significant_digits() {
        assert_eq!(with_uncertainty(0.666_712, 0.001_234), ("0.6667".into(), "0.0012".into()));
        assert_eq!(with_uncertainty(1.5049, 0.0871), ("1.505".into(), "0.087".into()));
        assert_eq!(with_uncertainty(12.34, 3.2), ("12.3".into(), "3.2".into()));
        assert_eq!(with_uncertainty(120.0, 31.0), ("120".into(), "31".into()));
        assert_eq!(with_uncertainty(0.5, 0.0), ("0.5".into(), "0".into()));
    }

    #[test]
    fn error_bars_are_drawn_and_tabulated_with_their_points() {
        // Two groups, errors in column `e` (scaled with y); on a log y axis the point at
        // y <= 0 is dropped together with its error, and a bar reaching below zero runs to
        // the bottom of the axes.
        let t = Table::new()
            .with_f64("x", vec![1.0, 2.0, 3.0, 1.0, 2.0])
            .with_f64("a", vec![1.0, 2.0, -1.0, 4.0, 5.0])
            .with_f64("e", vec![0.1, 3.0, 0.1, 0.0, 0.5])
            .with_f64("g", vec![0.0, 0.0, 0.0, 1.0, 1.0]);
        let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
        let mut l = layer("a", None);
        (l.y_error, l.y_scale) = (Some("e".into()), 2.0);
        let series = data_series(&l, &inputs).unwrap();
        assert_eq!(series[0].errors, vec![0.2, 6.0, 0.2]);
        assert_eq!(series[1].errors, vec![0.0, 1.0]);
        let mut fig = test_figure(vec![Layer::Data(l.clone())]);
        fig.log_y = true;
        let out = Figure::run(&fig, &inputs).unwrap();
        assert_eq!(out.table.f64_column("y_error").unwrap(), vec![0.2, 6.0, 0.0, 1.0]);
        // Three bars (a zero error draws none), each a stem and two caps, more than without.
        let strokes = |svg: &str| svg.matches("<line").count() + svg.matches("<polyline").count();
        l.y_error = None;
        let plain = Figure::run(&test_figure(vec![Layer::Data(l.clone())]), &inputs).unwrap();
        let mut plain_fig = test_figure(vec![Layer::Data(l.clone())]);
        plain_fig.log_y = true;
        let plain_log = Figure::run(&plain_fig, &inputs).unwrap();
        assert!(plain.table.f64_column("y_error").is_err());
        assert_eq!(strokes(&out.artifacts["svg"]) - strokes(&plain_log.artifacts["svg"]), 3 * 3);
        l.y_error = Some("missing".into());
        let e = data_series(&l, &inputs).err().unwrap();
        assert!(format!("{e:#}").contains("y_error"), "{e:#}");
    }

    #[test]
    fn layers_with_the_same_color_pair_their_curves() {
        let t = Table::new()
            .with_f64("x", vec![1.0, 2.0, 1.0, 2.0])
            .with_f64("a", vec![1.0, 2.0, 3.0, 4.0])
            .with_f64("b", vec![1.5, 2.5, 3.5, 4.5])
            .with_f64("g", vec![0.0, 0.0, 1.0, 1.0]);
        let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
        let colors = |l: &DataLayer| -> Vec<Option<usize>> {
            data_series(l, &inputs).unwrap().iter().map(|s| s.color).collect()
        };
        assert_eq!(colors(&layer("a", None)), vec![None, None]);
        assert_eq!(colors(&layer("b", Some(2))), vec![Some(2), Some(3)]);
        // Rendered: the first layer is blue and red (color 1); without `color` the second
        // layer takes the palette by position (red, green), with color 1 it repeats blue, red.
        let fig = |c: Option<usize>| test_figure(vec![Layer::Data(layer("a", Some(1))), Layer::Data(layer("b", c))]);
        let svg = |c| {
            let series: Vec<Series> =
                [layer("a", Some(1)), layer("b", c)].iter().flat_map(|l| data_series(l, &inputs).unwrap()).collect();
            render(&fig(c), &series).unwrap()
        };
        let count = |s: &str, rgb: &str| s.matches(&format!("stroke=\"#{rgb}\"")).count();
        let (free, paired) = (svg(None), svg(Some(1)));
        assert!(count(&free, "2CA02C") > 0);
        assert_eq!(count(&paired, "2CA02C"), 0);
        assert_eq!(count(&paired, "1F77B4"), 2 * count(&free, "1F77B4"));
    }
}
