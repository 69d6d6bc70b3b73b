//! The `figure` kind: a paper-style x–y plot (plotters, SVG) of columns from the tables of
//! the stages it needs, with optional power-law guide lines. Its table is the plotted
//! data in long format: `series`, `x`, `y`, `x_name`, `y_name` (one row per point).
//! Log axes are drawn by plotting log10 values on a linear axis labelled in powers of ten.

mod draw;
mod legend;
mod series;
mod template;

use anyhow::Result;
use draw::render;
use pipeline::kind::{ColumnRead, FieldError, Inputs, Kind, Output, ShownRange};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use series::{data_series, fit_series, guide_series, Series};
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
    /// A wide translucent line: a leg that another curve retraces (a loading leg under its
    /// dashed unloading), which stays visible beneath the curve drawn over it.
    Band,
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
    /// Below the axes, in as many columns as the width holds: the axes keep the figure's
    /// width (a long legend).
    Below,
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

pub(super) fn one() -> f64 {
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

pub(super) fn dashed() -> Style {
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

pub(super) fn default_width() -> u32 {
    800
}

pub(super) fn default_height() -> u32 {
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

pub struct Figure;

impl Kind for Figure {
    const NAME: &'static str = "figure";
    const VERSION: u32 = 19;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str = "An x-y figure (SVG) of columns of the needed stages, with its data as a long table";
    const COLUMNS: &'static [&'static str] = &[
        "series",
        "x",
        "y",
        "x_name",
        "y_name",
        "x_unit",
        "y_unit",
        "group_by",
        "group",
        "group_value",
        "group_unit",
        "y_error",
    ];
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

    /// Each data layer's columns (x, y, y_error, group_by, the filter's and its label's
    /// `{column}`s) of its stage, each fit layer's filter and label columns of its fit, and
    /// the title's and axis labels' `{column}`s of any stage the figure needs.
    fn read_columns(p: &FigureParams) -> Vec<ColumnRead> {
        let mut reads = template::text_reads(p);
        for (i, l) in p.layers.iter().enumerate() {
            let (kind, from, label, filter) = match l {
                Layer::Data(d) => ("data", &d.from, &d.label, &d.filter),
                Layer::Fit(f) => ("fit", &f.from, &f.label, &f.filter),
                Layer::Guide(_) => continue,
            };
            let path = |field: &str| format!("layers[{i}].{kind}.{field}");
            let read = |field: &str, column: &str| ColumnRead {
                path: path(field),
                stage: Some(from.clone()),
                column: column.to_string(),
            };
            if let Layer::Data(d) = l {
                reads.push(read("x", &d.x));
                reads.push(read("y", &d.y));
                reads.extend(d.y_error.iter().map(|c| read("y_error", c)));
                reads.extend(d.group_by.iter().map(|c| read("group_by", c)));
            }
            reads.extend(filter.keys().map(|c| read("filter", c)));
            reads.extend(template::placeholders(label).iter().map(|c| read("label", c)));
        }
        reads
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
        for s in &mut series {
            s.label = template::superscripts(&s.label);
        }
        let svg = render(&template::filled(p, inputs)?, &series)?;
        let rows = series.iter().flat_map(|s| s.points.iter().map(move |&(x, y)| (s, x, y)));
        let table = Table::new()
            .with("series", ColumnData::Str(rows.clone().map(|(s, _, _)| s.label.clone()).collect()))
            .with_f64("x", rows.clone().map(|(_, x, _)| x).collect())
            .with_f64("y", rows.clone().map(|(_, _, y)| y).collect())
            .with("x_name", ColumnData::Str(rows.clone().map(|(s, _, _)| s.x_name.clone()).collect()))
            .with("y_name", ColumnData::Str(rows.clone().map(|(s, _, _)| s.y_name.clone()).collect()));
        // Each point's units: its columns' (docs/outputs.md), the axis' for guide and fit
        // lines (the first data series' with a documented unit).
        let units = column_units();
        let unit = |name: &str| units.get(name).cloned();
        let axis_x = series.iter().find_map(|s| unit(&s.x_name)).unwrap_or_default();
        let axis_y = series.iter().find_map(|s| unit(&s.y_name)).unwrap_or_default();
        let table = table
            .with(
                "x_unit",
                ColumnData::Str(
                    rows.clone().map(|(s, _, _)| unit(&s.x_name).unwrap_or_else(|| axis_x.clone())).collect(),
                ),
            )
            .with(
                "y_unit",
                ColumnData::Str(rows.map(|(s, _, _)| unit(&s.y_name).unwrap_or_else(|| axis_y.clone())).collect()),
            );
        // The error column only where a layer has errors (0 for the other series' points).
        let table = if series.iter().any(|s| !s.errors.is_empty()) {
            let errors =
                series.iter().flat_map(|s| (0..s.points.len()).map(|i| s.errors.get(i).copied().unwrap_or(0.0)));
            table.with_f64("y_error", errors.collect())
        } else {
            table
        };
        // The group of each point where a layer groups its rows: the grouping column, its
        // value as shown, as a number (0 where not numeric) for filtering in a data frame, and
        // its unit (docs/outputs.md).
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
                .with(
                    "group_unit",
                    ColumnData::Str(per_point(&|s| s.group.as_ref().and_then(|g| unit(&g.0)).unwrap_or_default())),
                )
        } else {
            table
        };
        let mut out = Output::from(table);
        out.artifacts.insert("svg".into(), svg);
        Ok(out)
    }
}

/// The unit of every documented output column (docs/outputs.md; the first entry of a name),
/// read once per process.
fn column_units() -> &'static BTreeMap<String, String> {
    static UNITS: std::sync::OnceLock<BTreeMap<String, String>> = std::sync::OnceLock::new();
    UNITS.get_or_init(|| {
        let mut units = BTreeMap::new();
        for (name, doc) in crate::stages::documented_columns() {
            units.entry(name).or_insert(doc.unit);
        }
        units
    })
}

pub fn register(r: &mut pipeline::kind::Registry) {
    r.add::<Figure>();
}

#[cfg(test)]
mod tests;
