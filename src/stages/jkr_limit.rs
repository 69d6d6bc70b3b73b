//! The limits the maxima of the sliding cylinder's friction tend to, computed from the load
//! and modulus ratio of the needed stage's table, as lines across a range, so that a figure
//! draws them beside the maxima and an override of their W or k moves them with them:
//! `theory.jkr_friction_limit`, mu* = pi^(1/2) / (2 W^(3/2) k) as lambda grows (the
//! equation after the thesis' Fig. 4.6), and `theory.adhesionless_friction_limit`, Persson's
//! adhesionless maximum over V0 for k (Appendix A), which large loads approach.

use anyhow::{bail, Result};
use physics::theory::line_contact::jkr_friction_limit;
use physics::theory::persson;
use pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::Table;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JkrLimitParams {
    /// The stage whose distinct (W, k) pairs are bounded (must be in `needs`; its table has
    /// the columns `W` and `k`).
    pub from: String,
    /// The lambda range the line spans, [from, to], 0 < from < to.
    pub lambda_range: [f64; 2],
}

pub struct JkrFrictionLimit;

/// The error of a range parameter `name` that is not [from, to] with 0 < from < to.
fn range_errors(name: &str, [a, b]: [f64; 2]) -> Vec<FieldError> {
    if a > 0.0 && b > a && b.is_finite() {
        Vec::new()
    } else {
        vec![FieldError::new(name, format!("must be [from, to] with 0 < from < to, got [{a}, {b}]"))]
    }
}

impl Kind for JkrFrictionLimit {
    const NAME: &'static str = "theory.jkr_friction_limit";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "The JKR limit of the friction mu* = pi^(1/2) / (2 W^(3/2) k) for each (W, k) of a needed stage, across a lambda range";
    const COLUMNS: &'static [&'static str] = &["W", "k", "lambda", "mu_star_jkr"];
    type Params = JkrLimitParams;

    fn validate(p: &JkrLimitParams) -> Vec<FieldError> {
        range_errors("lambda_range", p.lambda_range)
    }

    fn referenced_stages(p: &JkrLimitParams) -> Vec<(String, String)> {
        vec![("from".into(), p.from.clone())]
    }

    fn run(p: &JkrLimitParams, inputs: &Inputs) -> Result<Output> {
        let t = inputs.table(&p.from)?;
        let (ws, ks) = (t.f64_column("W")?, t.f64_column("k")?);
        let mut pairs: Vec<(f64, f64)> = Vec::new();
        for pair in ws.into_iter().zip(ks) {
            if !pairs.contains(&pair) {
                pairs.push(pair);
            }
        }
        if let Some(&(w, k)) = pairs.iter().find(|&&(w, k)| !(w != 0.0 && w.is_finite() && k > 0.0 && k < 1.0)) {
            bail!("`{}` has W = {w}, k = {k}: the limit needs W nonzero and 0 < k < 1", p.from);
        }
        let mut out = Table::new();
        for (w, k) in pairs {
            out.append(
                &Table::new()
                    .with_f64("W", vec![w; 2])
                    .with_f64("k", vec![k; 2])
                    .with_f64("lambda", p.lambda_range.to_vec())
                    .with_f64("mu_star_jkr", vec![jkr_friction_limit(w, k); 2]),
            )?;
        }
        Ok(out.into())
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct AdhesionlessLimitParams {
    /// The stage whose distinct modulus ratios are bounded (must be in `needs`; its table has
    /// the column `k`).
    pub from: String,
    /// The load range the line spans, [from, to], 0 < from < to (the column `W`).
    pub W_range: [f64; 2],
}

pub struct AdhesionlessFrictionLimit;

/// Relative tolerance of Persson's quadrature for the maximum.
const PERSSON_REL_TOL: f64 = 1e-8;

impl Kind for AdhesionlessFrictionLimit {
    const NAME: &'static str = "theory.adhesionless_friction_limit";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "Persson's adhesionless maximum of mu* over V0 (Appendix A) for each k of a needed stage, across a load range";
    const COLUMNS: &'static [&'static str] = &["k", "W", "mu_star_max_adhesionless", "error_estimate"];
    type Params = AdhesionlessLimitParams;

    fn validate(p: &AdhesionlessLimitParams) -> Vec<FieldError> {
        range_errors("W_range", p.W_range)
    }

    fn referenced_stages(p: &AdhesionlessLimitParams) -> Vec<(String, String)> {
        vec![("from".into(), p.from.clone())]
    }

    fn run(p: &AdhesionlessLimitParams, inputs: &Inputs) -> Result<Output> {
        let mut ks: Vec<f64> = Vec::new();
        for k in inputs.table(&p.from)?.f64_column("k")? {
            if !(k > 0.0 && k < 1.0) {
                bail!("`{}` has k = {k}: the limit needs 0 < k < 1", p.from);
            }
            if !ks.contains(&k) {
                ks.push(k);
            }
        }
        let mut out = Table::new();
        for k in ks {
            let (_, max) = persson::max_mu_star(k, PERSSON_REL_TOL);
            out.append(
                &Table::new()
                    .with_f64("k", vec![k; 2])
                    .with_f64("W", p.W_range.to_vec())
                    .with_f64("mu_star_max_adhesionless", vec![max.mu_star; 2])
                    .with_f64("error_estimate", vec![max.error_estimate; 2]),
            )?;
        }
        Ok(out.into())
    }
}

pub fn register(r: &mut Registry) {
    r.add::<JkrFrictionLimit>().add::<AdhesionlessFrictionLimit>();
}
