//! Utility kinds for exercising the orchestrator (tests, demos): they compute nothing
//! physical. `util.sleep` waits and returns its parameters; `util.fail` always fails.

use anyhow::Result;
use pipeline::kind::{FieldError, Inputs, Kind, Output};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SleepParams {
    /// Value echoed into the output table (sweepable).
    pub x: f64,
    /// Milliseconds to wait before returning (a checkpoint of the time limit every 10 ms).
    #[serde(default)]
    pub ms: u64,
    /// Output `x` rounded to this many decimals (lets tests produce identical outputs
    /// from different parameters).
    #[serde(default)]
    pub round: Option<i32>,
}

/// Sleeps, then returns x (and the row count of its inputs, and the sum of their `x`).
pub struct Sleep;

impl Kind for Sleep {
    const NAME: &'static str = "util.sleep";
    const VERSION: u32 = 2;
    const DOC: &'static str = "Waits `ms` milliseconds and returns `x` (for testing the orchestrator)";
    const SWEEPABLE: &'static [&'static str] = &["x"];
    const COLUMNS: &'static [&'static str] = &["x", "upstream_rows", "upstream_x"];
    type Params = SleepParams;

    fn validate(p: &SleepParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        if p.ms > 600_000 {
            e.push(FieldError::new("ms", "must be at most 600000"));
        }
        e
    }

    fn run(p: &SleepParams, inputs: &Inputs) -> Result<Output> {
        // In slices of at most 10 ms, each a checkpoint of the time limit, as a solver's
        // iterations are.
        let end = std::time::Instant::now() + std::time::Duration::from_millis(p.ms);
        while let Some(left) = end.checked_duration_since(std::time::Instant::now()).filter(|d| !d.is_zero()) {
            physics::numerics::budget::checkpoint();
            std::thread::sleep(left.min(std::time::Duration::from_millis(10)));
        }
        let x = match p.round {
            Some(d) => (p.x * 10f64.powi(d)).round() / 10f64.powi(d),
            None => p.x,
        };
        let upstream_rows: i64 = inputs.tables.values().map(|t| t.n_rows() as i64).sum();
        let upstream_x: f64 =
            inputs.tables.values().filter_map(|t| t.f64_column("x").ok()).map(|c| c.iter().sum::<f64>()).sum();
        Ok(Table::new()
            .with_f64("x", vec![x])
            .with("upstream_rows", ColumnData::I64(vec![upstream_rows]))
            .with_f64("upstream_x", vec![upstream_x])
            .into())
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FailParams {
    /// The error message.
    pub message: String,
    /// Also panic instead of returning an error.
    #[serde(default)]
    pub panic: bool,
    /// Positive: output this value instead of failing; the failure happens when `x <= 0`.
    #[serde(default)]
    pub x: f64,
}

/// Fails with a message when x <= 0 (for testing keep-going).
pub struct Fail;

impl Kind for Fail {
    const NAME: &'static str = "util.fail";
    const VERSION: u32 = 1;
    const DOC: &'static str = "Fails with `message` when x <= 0 (for testing the orchestrator)";
    const SWEEPABLE: &'static [&'static str] = &["x"];
    const COLUMNS: &'static [&'static str] = &["x"];
    type Params = FailParams;

    fn run(p: &FailParams, _inputs: &Inputs) -> Result<Output> {
        if p.x > 0.0 {
            return Ok(Table::new().with_f64("x", vec![p.x]).into());
        }
        if p.panic {
            panic!("{}", p.message);
        }
        anyhow::bail!("{}", p.message)
    }
}

pub fn register(r: &mut pipeline::kind::Registry) {
    r.add::<Sleep>().add::<Fail>();
}
