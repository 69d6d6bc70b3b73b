//! Stage kind `pb.calibrate`: the Persson-Brener prefactor alpha_PB (sigma_c = alpha_PB
//! sigma0, Eq. 5.18) calibrated on computed rolling-friction curves (thesis Section 5.3.3,
//! Figs. 5.3, 5.5-5.7), from the low-speed law (Eq. 5.20, F_T* ~ V0) and the intermediate
//! law (Eq. 5.21, F_T* ~ V0^(1/2)) of `theory::persson_brener`.

use anyhow::Result;
use physics::numerics::fit::{power_law, power_law_regime};
use physics::theory::persson_brener::{rolling_linear, rolling_sqrt};
use pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

fn default_y() -> String {
    "F_T".into()
}
fn default_tol() -> f64 {
    0.1
}
fn default_min_points() -> usize {
    3
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CalibrateParams {
    /// A `bem.sweep` stage (in `needs`): columns lambda, W, k, V0, converged and `y` (and s,
    /// for a power-law material: one curve per s; the laws are the SLS ones, so alpha is
    /// then an effective prefactor).
    pub from: String,
    /// The friction column (default F_T = mu* |W|, Eq. 5.6).
    #[serde(default = "default_y")]
    pub y: String,
    /// A regime is the longest run of points whose local slopes d ln F / d ln V0 lie within
    /// this of the law's slope (1 or 1/2); default 0.1.
    #[serde(default = "default_tol")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 0.25))]
    pub slope_tolerance: f64,
    /// The fewest points a regime may have (default 3).
    #[serde(default = "default_min_points")]
    #[schemars(range(min = 3))]
    pub min_points: usize,
    /// Fixed V0 ranges instead of the detected regimes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub linear_range: Option<[f64; 2]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sqrt_range: Option<[f64; 2]>,
}

/// One regime of one curve: the points, alpha from each, and the fitted power law.
struct Regime {
    name: &'static str,
    law_slope: f64,
    v0: Vec<f64>,
    alphas: Vec<f64>,
    fit: Option<physics::numerics::fit::PowerLaw>,
}

/// Calibrates alpha_PB on each (lambda, W, k) curve, per regime: alpha is the geometric mean
/// of the alphas that make the law pass through each point of the regime, with the standard
/// error of that mean; the free power-law fit over the same points is reported beside it.
/// A regime with fewer than `min_points` points has no row.
pub struct PbCalibrate;

impl Kind for PbCalibrate {
    const NAME: &'static str = "pb.calibrate";
    const VERSION: u32 = 2;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "Persson-Brener prefactor alpha (Eq. 5.18) fitted to F_T*(V0) curves: linear (Eq. 5.20) and square-root (Eq. 5.21) regimes";
    const COLUMNS: &'static [&'static str] = &[
        "lambda",
        "W",
        "k",
        "s",
        "regime",
        "alpha",
        "alpha_std_error",
        "alpha_spread",
        "n_points",
        "x_min",
        "x_max",
        "slope",
        "slope_std_error",
        "prefactor",
        "fitted_slope",
        "fitted_slope_std_error",
    ];
    type Params = CalibrateParams;

    fn validate(p: &CalibrateParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        for (name, r) in [("linear_range", p.linear_range), ("sqrt_range", p.sqrt_range)] {
            if let Some([a, b]) = r {
                if !(a > 0.0 && b > a) {
                    e.push(FieldError::new(name, format!("needs 0 < from < to, got [{a}, {b}]")));
                }
            }
        }
        e
    }

    fn referenced_stages(p: &CalibrateParams) -> Vec<(String, String)> {
        vec![("from".into(), p.from.clone())]
    }

    fn run(p: &CalibrateParams, inputs: &Inputs) -> Result<Output> {
        let t = inputs.table(&p.from)?;
        let (lam, w, k, v0, y) =
            (t.f64_column("lambda")?, t.f64_column("W")?, t.f64_column("k")?, t.f64_column("V0")?, t.f64_column(&p.y)?);
        let ok: Vec<bool> = match t.column("converged") {
            Some(ColumnData::Bool(b)) => b.clone(),
            _ => vec![true; v0.len()],
        };
        // Curves: one per (lambda, W, k) and, for a power-law material, per s.
        let spectral = t.column("s").is_some();
        let s_col = if spectral { t.f64_column("s")? } else { vec![-1.0; v0.len()] };
        let key = |i: usize| (lam[i], w[i], k[i], s_col[i]);
        let mut keys: Vec<(f64, f64, f64, f64)> = Vec::new();
        for i in 0..v0.len() {
            if !keys.contains(&key(i)) {
                keys.push(key(i));
            }
        }
        let mut out = Table::new();
        for (l, wk, kk, sk) in keys {
            let mut pts: Vec<(f64, f64)> = (0..v0.len())
                .filter(|&i| key(i) == (l, wk, kk, sk) && ok[i] && v0[i] > 0.0 && y[i] > 0.0)
                .map(|i| (v0[i], y[i]))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let regime = |name: &'static str, law_slope: f64, range: Option<[f64; 2]>| -> Regime {
                let chosen: Vec<(f64, f64)> = match range {
                    Some([a, b]) => pts.iter().copied().filter(|(x, _)| *x >= a && *x <= b).collect(),
                    None => power_law_regime(&pts, law_slope, p.slope_tolerance, p.min_points)
                        .map(|(a, b)| pts[a..=b].to_vec())
                        .unwrap_or_default(),
                };
                let alphas = chosen
                    .iter()
                    .map(|&(x, f)| {
                        if law_slope == 1.0 {
                            (f / rolling_linear(1.0, l, kk, x)).sqrt()
                        } else {
                            f / rolling_sqrt(1.0, l, wk, kk, x)
                        }
                    })
                    .collect();
                Regime { name, law_slope, v0: chosen.iter().map(|q| q.0).collect(), alphas, fit: power_law(&chosen) }
            };
            for r in [regime("linear", 1.0, p.linear_range), regime("sqrt", 0.5, p.sqrt_range)] {
                let n = r.alphas.len();
                if n < p.min_points {
                    continue; // the regime is not there (e.g. no square-root regime at small lambda)
                }
                let logs: Vec<f64> = r.alphas.iter().map(|a| a.ln()).collect();
                let mean = if n > 0 { logs.iter().sum::<f64>() / n as f64 } else { 0.0 };
                let sd = if n > 1 {
                    (logs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
                } else {
                    0.0
                };
                let alpha = if n > 0 { mean.exp() } else { 0.0 };
                // The law with the calibrated alpha, as y = prefactor V0^slope (a figure's fit layer).
                let prefactor = if r.law_slope == 1.0 {
                    rolling_linear(alpha, l, kk, 1.0)
                } else {
                    rolling_sqrt(alpha, l, wk, kk, 1.0)
                };
                let (x_min, x_max) = (r.v0.first().copied().unwrap_or(0.0), r.v0.last().copied().unwrap_or(0.0));
                let row = Table::new().with_f64("lambda", vec![l]).with_f64("W", vec![wk]).with_f64("k", vec![kk]);
                let row = if spectral { row.with_f64("s", vec![sk]) } else { row };
                let row = row
                    .with("regime", ColumnData::Str(vec![r.name.to_string()]))
                    .with_f64("alpha", vec![alpha])
                    .with_f64("alpha_std_error", vec![alpha * sd / (n.max(1) as f64).sqrt()])
                    .with_f64("alpha_spread", vec![alpha * sd])
                    .with("n_points", ColumnData::I64(vec![n as i64]))
                    .with_f64("x_min", vec![x_min])
                    .with_f64("x_max", vec![x_max])
                    .with_f64("slope", vec![r.law_slope])
                    .with_f64("slope_std_error", vec![0.0])
                    .with_f64("prefactor", vec![prefactor])
                    .with_f64("fitted_slope", vec![r.fit.map_or(0.0, |f| f.slope)])
                    .with_f64("fitted_slope_std_error", vec![r.fit.map_or(0.0, |f| f.slope_std_error)]);
                out.append(&row)?;
            }
        }
        Ok(out.into())
    }
}

pub fn register(r: &mut Registry) {
    r.add::<PbCalibrate>();
}
