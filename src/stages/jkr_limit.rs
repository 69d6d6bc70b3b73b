//! `theory.jkr_friction_limit`: the JKR limit of the sliding cylinder's friction, mu* =
//! pi^(1/2) / (2 W^(3/2) k) (the equation after the thesis' Fig. 4.6), for each load and
//! modulus ratio of a needed stage's table, as a line across a lambda range: a figure draws
//! it beside the maxima it bounds, and an override of their W or k moves it with them.

use anyhow::{bail, Result};
use physics::theory::line_contact::jkr_friction_limit;
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

impl Kind for JkrFrictionLimit {
    const NAME: &'static str = "theory.jkr_friction_limit";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "The JKR limit of the friction mu* = pi^(1/2) / (2 W^(3/2) k) for each (W, k) of a needed stage, across a lambda range";
    const COLUMNS: &'static [&'static str] = &["W", "k", "lambda", "mu_star_jkr"];
    type Params = JkrLimitParams;

    fn validate(p: &JkrLimitParams) -> Vec<FieldError> {
        let [a, b] = p.lambda_range;
        if a > 0.0 && b > a && b.is_finite() {
            Vec::new()
        } else {
            vec![FieldError::new("lambda_range", format!("must be [from, to] with 0 < from < to, got [{a}, {b}]"))]
        }
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

pub fn register(r: &mut Registry) {
    r.add::<JkrFrictionLimit>();
}
