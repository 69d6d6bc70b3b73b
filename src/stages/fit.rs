//! `fit.powerlaw`: a power law y = c x^s fitted to columns of a needed stage's table over
//! a declared x range, per group, with the standard errors of slope and prefactor.

use anyhow::{bail, Context, Result};
use physics::numerics::fit::power_law;
use pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FitParams {
    /// The stage whose table is fitted (must be in `needs`).
    pub from: String,
    pub x: String,
    pub y: String,
    /// Only points with x in [x_min, x_max] are fitted.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub x_min: f64,
    pub x_max: f64,
    /// One fit per distinct value of this (numeric) column.
    #[serde(default)]
    pub group_by: Option<String>,
    /// A reference slope (e.g. 5/4), reported beside the fitted one.
    #[serde(default)]
    pub expected_slope: Option<f64>,
}

pub struct FitPowerLaw;

impl Kind for FitPowerLaw {
    const NAME: &'static str = "fit.powerlaw";
    const VERSION: u32 = 1;
    /// The group column is named after the fitted table's (`group_by`).
    const OPEN_COLUMNS: bool = true;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "Power law y = c x^s fitted over an x range (log-log least squares), with standard errors";
    const COLUMNS: &'static [&'static str] = &[
        "slope",
        "slope_std_error",
        "prefactor",
        "prefactor_std_error",
        "r_squared",
        "n_points",
        "x_min",
        "x_max",
        "expected_slope",
    ];
    type Params = FitParams;

    fn validate(p: &FitParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        if !(p.x_max > p.x_min) {
            e.push(FieldError::new("x_max", format!("must exceed x_min ({}), got {}", p.x_min, p.x_max)));
        }
        e
    }

    fn referenced_stages(p: &FitParams) -> Vec<(String, String)> {
        vec![("from".into(), p.from.clone())]
    }

    fn run(p: &FitParams, inputs: &Inputs) -> Result<Output> {
        let t = inputs.table(&p.from)?;
        let xs = t.f64_column(&p.x)?;
        let ys = t.f64_column(&p.y)?;
        let groups = match &p.group_by {
            Some(g) => t.f64_column(g).with_context(|| format!("group_by `{g}`"))?,
            None => vec![0.0; xs.len()],
        };
        let mut keys: Vec<f64> = Vec::new();
        for g in &groups {
            if !keys.contains(g) {
                keys.push(*g);
            }
        }
        let mut out = Table::new();
        for key in keys {
            let pts: Vec<(f64, f64)> = (0..xs.len())
                .filter(|&i| groups[i] == key && xs[i] >= p.x_min && xs[i] <= p.x_max)
                .map(|i| (xs[i], ys[i]))
                .collect();
            let Some(f) = power_law(&pts) else {
                bail!("fewer than 3 positive points of `{}` in [{}, {}] to fit", p.from, p.x_min, p.x_max)
            };
            let mut row = Table::new();
            if let Some(g) = &p.group_by {
                row = row.with_f64(g, vec![key]);
            }
            row = row
                .with_f64("slope", vec![f.slope])
                .with_f64("slope_std_error", vec![f.slope_std_error])
                .with_f64("prefactor", vec![f.prefactor])
                .with_f64("prefactor_std_error", vec![f.prefactor_std_error])
                .with_f64("r_squared", vec![f.r_squared])
                .with("n_points", ColumnData::I64(vec![f.n as i64]))
                .with_f64("x_min", vec![p.x_min])
                .with_f64("x_max", vec![p.x_max]);
            if let Some(s) = p.expected_slope {
                row = row.with_f64("expected_slope", vec![s]);
            }
            out.append(&row)?;
        }
        Ok(out.into())
    }
}

pub fn register(r: &mut Registry) {
    r.add::<FitPowerLaw>();
}
