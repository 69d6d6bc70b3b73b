//! The thesis' claims as data: `claim` checks one statement of the thesis against a
//! published table, `claims` gathers the verdicts into one table and the run's verdict line.
//!
//! A claim names where the thesis states it, the statement in a few words, the quantity
//! (a column of a stage's table, rows kept by a filter and an x range, reduced by an
//! aggregate: the value at a point, a maximum, where it lies, a fitted log-log slope,
//! monotonicity, a count), the thesis' value with the tolerance its text implies (or a
//! bound), an independent value where one exists (a closed form, a limit), and the verdict
//! recorded when the claim was last reviewed (`expect`). A claim that is recorded as
//! reproduced and no longer is, is a regression: the run exits non-zero. A claim recorded as
//! differing carries its reason and the docs section that explains it.

use super::values::check;
use anyhow::{bail, Context, Result};
use physics::numerics::fit::{linear_r_squared, power_law};
use pipeline::kind::{ColumnRead, FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::{format_number, ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// How the kept rows of a column are reduced to one number.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, PartialEq, Eq, Debug)]
#[serde(rename_all = "snake_case")]
pub enum Aggregate {
    /// The value of the one kept row (an error if not exactly one).
    Value,
    Max,
    Min,
    Mean,
    /// The x of the largest (smallest) y.
    Argmax,
    Argmin,
    /// The log-log least-squares slope of y against x (at least 3 positive points).
    Slope,
    /// 1 if y rises (falls) strictly with x over the kept rows, else 0.
    Increasing,
    Decreasing,
    /// The number of kept rows (`y` unused).
    Count,
    /// The coefficient of determination R² of the least-squares straight line through
    /// (x, y): 1 when y is linear in x (at least 3 rows, y not constant).
    Linearity,
    /// The largest y over the smallest (a spread: 1 when constant; y > 0).
    MaxOverMin,
    /// y at the largest x over y at the smallest x.
    LastOverFirst,
}

impl Aggregate {
    fn needs_x(self) -> bool {
        matches!(
            self,
            Aggregate::Argmax
                | Aggregate::Argmin
                | Aggregate::Slope
                | Aggregate::Increasing
                | Aggregate::Decreasing
                | Aggregate::LastOverFirst
                | Aggregate::Linearity
        )
    }
}

/// The measured quantity.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Debug)]
#[serde(deny_unknown_fields)]
pub struct Quantity {
    /// The stage whose table is read (must be in `needs`).
    pub from: String,
    /// The column reduced (any numeric or boolean column).
    pub y: String,
    /// A column that divides `y` row by row before the reduction (a ratio of two results of
    /// one row, e.g. an estimate over the computed value).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub over: Option<String>,
    /// The error estimate of `y` (a column of the same table): `increasing` and `decreasing`
    /// then judge within it (no step back larger than the two points' errors together, and
    /// an overall change larger than the ends' errors).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_error: Option<String>,
    /// The abscissa of `argmax`, `argmin`, `slope`, `increasing`, `decreasing`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<String>,
    /// Rows kept: every named column equal to its value (numbers to 1e-9 relative,
    /// booleans as 0 and 1, text exactly).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub filter: BTreeMap<String, FilterValue>,
    /// Rows kept: x within [x_min, x_max].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x_min: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x_max: Option<f64>,
    pub aggregate: Aggregate,
}

impl Quantity {
    /// The column reduced as it reads: `y`, or `y / over`.
    pub fn column(&self) -> String {
        match &self.over {
            Some(d) => format!("{} / {d}", self.y),
            None => self.y.clone(),
        }
    }

    /// What is compared, in words: "value of `stage.y` where a = 1, b = 2", "argmax of
    /// `stage.y` against `x` for x in [1, 10]".
    pub fn describe(&self) -> String {
        let aggregate = serde_json::to_value(self.aggregate).ok().and_then(|v| v.as_str().map(str::to_string));
        let mut s = format!("{} of {}.{}", aggregate.unwrap_or_default(), self.from, self.column());
        if let Some(x) = &self.x {
            s.push_str(&format!(" against {x}"));
        }
        if let Some(e) = &self.y_error {
            s.push_str(&format!(" within {e}"));
        }
        if !self.filter.is_empty() {
            let kept: Vec<String> = self
                .filter
                .iter()
                .map(|(k, v)| match v {
                    FilterValue::Number(n) => format!("{k} = {}", format_number(*n)),
                    FilterValue::Text(t) => format!("{k} = {t}"),
                })
                .collect();
            s.push_str(&format!(" where {}", kept.join(", ")));
        }
        if self.x_min.is_some() || self.x_max.is_some() {
            let x = self.x.as_deref().unwrap_or("x");
            let (lo, hi) =
                (self.x_min.map_or("-∞".into(), format_number), self.x_max.map_or("∞".into(), format_number));
            s.push_str(&format!(" for {x} in [{lo}, {hi}]"));
        }
        s
    }
}

/// The value a filtered column must equal.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Debug, PartialEq)]
#[serde(untagged)]
pub enum FilterValue {
    Number(f64),
    Text(String),
}

/// A value with a tolerance, or bounds (every condition given must hold).
#[derive(Serialize, Deserialize, JsonSchema, Clone, Debug, Default)]
#[serde(deny_unknown_fields)]
pub struct Expected {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    /// Relative tolerance on `value` (0.05: within 5 %).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rel_tol: Option<f64>,
    /// Absolute tolerance on `value`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub abs_tol: Option<f64>,
    /// Strict bounds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub above: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub below: Option<f64>,
}

impl Expected {
    fn holds(&self, x: f64) -> bool {
        let near = self.value.is_none_or(|v| {
            let tol = self.abs_tol.unwrap_or(0.0).max(self.rel_tol.unwrap_or(0.0) * v.abs());
            (x - v).abs() <= tol
        });
        near && self.above.is_none_or(|a| x > a) && self.below.is_none_or(|b| x < b)
    }

    /// The condition in words, e.g. "-1.5 ± 2 %", "> 0", "in (0.3, 0.5)".
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if let Some(v) = self.value {
            parts.push(match (self.rel_tol, self.abs_tol) {
                (Some(r), _) => format!("{} ± {} %", format_number(v), format_number(100.0 * r)),
                (None, Some(a)) => format!("{} ± {}", format_number(v), format_number(a)),
                (None, None) => format_number(v),
            });
        }
        match (self.above, self.below) {
            (Some(a), Some(b)) => parts.push(format!("in ({}, {})", format_number(a), format_number(b))),
            (Some(a), None) => parts.push(format!("> {}", format_number(a))),
            (None, Some(b)) => parts.push(format!("< {}", format_number(b))),
            (None, None) => {}
        }
        parts.join(", ")
    }

    /// The number that stands for the condition in the table: the value, else a bound.
    fn representative(&self) -> f64 {
        self.value.or(self.above).or(self.below).unwrap_or(0.0)
    }

    fn validate(&self, e: &mut Vec<FieldError>, path: &str) {
        if self.value.is_none() && self.above.is_none() && self.below.is_none() {
            e.push(FieldError::new(path, "give a `value` (with `rel_tol` or `abs_tol`) or a bound (`above`, `below`)"));
        }
        if self.value.is_none() && (self.rel_tol.is_some() || self.abs_tol.is_some()) {
            e.push(FieldError::new(path, "a tolerance needs a `value`"));
        }
        for (name, t) in [("rel_tol", self.rel_tol), ("abs_tol", self.abs_tol)] {
            if let Some(t) = t {
                check::non_negative(e, &format!("{path}.{name}"), t);
            }
        }
        if let (Some(a), Some(b)) = (self.above, self.below) {
            if !(a < b) {
                e.push(FieldError::new(&format!("{path}.below"), format!("must exceed `above` ({a}), got {b}")));
            }
        }
    }
}

/// An independent value of the quantity (a closed form, a limit, another code).
#[derive(Serialize, Deserialize, JsonSchema, Clone, Debug)]
#[serde(deny_unknown_fields)]
pub struct Independent {
    pub value: f64,
    /// What it is, e.g. "JKR closed form, Eq. 2.32".
    pub source: String,
}

/// The verdict of a claim: `reproduced` (the quantity meets the thesis' condition),
/// `calibrated` (it meets it because the model was tuned to that value: no evidence) or
/// `differs`.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, PartialEq, Eq, Debug)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    Reproduced,
    Calibrated,
    Differs,
}

impl Verdict {
    fn as_str(self) -> &'static str {
        match self {
            Verdict::Reproduced => "reproduced",
            Verdict::Calibrated => "calibrated",
            Verdict::Differs => "differs",
        }
    }
}

#[derive(Serialize, Deserialize, JsonSchema, Clone, Debug)]
#[serde(deny_unknown_fields)]
pub struct ClaimParams {
    /// A short identifier, e.g. `ch2.jkr_pulloff`.
    pub id: String,
    /// Where the thesis states it: section, equation or figure.
    pub source: String,
    /// The statement, in a few words.
    pub statement: String,
    pub quantity: Quantity,
    /// The thesis' value with the tolerance its text implies, or its bound.
    pub thesis: Expected,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub independent: Option<Independent>,
    /// The verdict recorded at the last review: a claim recorded as reproduced that no
    /// longer is, is a regression.
    pub expect: Verdict,
    /// Why the reproduction differs (required with `expect: differs`).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub reason: String,
    /// The docs section that explains it, e.g. `docs/shell.md#claims`.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub docs: String,
}

/// The rows of `q.from` kept by the filter and the x range, as (x, y, error of y) (x = 0
/// without `x`, the error 0 without `y_error`).
fn kept_rows(q: &Quantity, inputs: &Inputs) -> Result<Vec<(f64, f64, f64)>> {
    let t = inputs.table(&q.from)?;
    let n = t.n_rows();
    let mut ys = if q.aggregate == Aggregate::Count { vec![0.0; n] } else { t.f64_column(&q.y)? };
    if let Some(d) = &q.over {
        let ds = t.f64_column(d).with_context(|| format!("over `{d}`"))?;
        for (y, d) in ys.iter_mut().zip(ds) {
            *y /= d;
        }
    }
    let xs = match &q.x {
        Some(x) => t.f64_column(x).with_context(|| format!("x `{x}`"))?,
        None => vec![0.0; n],
    };
    let es = match &q.y_error {
        Some(e) => t.f64_column(e).with_context(|| format!("y_error `{e}`"))?,
        None => vec![0.0; n],
    };
    // Per filter, whether each row passes.
    let passes: Vec<Vec<bool>> = q
        .filter
        .iter()
        .map(|(c, v)| match (t.column(c), v) {
            (Some(ColumnData::Str(col)), FilterValue::Text(v)) => Ok(col.iter().map(|x| x == v).collect()),
            (Some(ColumnData::Str(_)), FilterValue::Number(v)) => {
                bail!("filter column `{c}` holds text; {v} is a number")
            }
            (_, FilterValue::Text(v)) => bail!("filter column `{c}` is not text; `{v}` is"),
            (_, FilterValue::Number(v)) => {
                let col = t.f64_column(c).with_context(|| format!("filter column `{c}`"))?;
                Ok(col.iter().map(|x| (x - v).abs() <= 1e-9 * x.abs().max(v.abs())).collect())
            }
        })
        .collect::<Result<_>>()?;
    let rows: Vec<(f64, f64, f64)> = (0..n)
        .filter(|&i| passes.iter().all(|p| p[i]))
        .filter(|&i| q.x_min.is_none_or(|a| xs[i] >= a) && q.x_max.is_none_or(|b| xs[i] <= b))
        .map(|i| (xs[i], ys[i], es[i]))
        .collect();
    if let Some(r) = rows.iter().find(|r| !r.1.is_finite()) {
        bail!("`{}` is not finite at x = {} (a division by zero?)", q.column(), r.0);
    }
    Ok(rows)
}

/// The quantity's value.
pub fn measure(q: &Quantity, inputs: &Inputs) -> Result<f64> {
    let mut rows = kept_rows(q, inputs)?;
    if rows.is_empty() && q.aggregate != Aggregate::Count {
        bail!("no row of `{}` passes the filter {:?}", q.from, q.filter);
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let by_y = |a: &&(f64, f64, f64), b: &&(f64, f64, f64)| a.1.total_cmp(&b.1);
    let ys = rows.iter().map(|r| r.1);
    let pairs: Vec<(f64, f64)> = rows.iter().map(|r| (r.0, r.1)).collect();
    Ok(match q.aggregate {
        Aggregate::Value => {
            if rows.len() != 1 {
                bail!("`value` needs exactly one row of `{}`; the filter keeps {}", q.from, rows.len());
            }
            rows[0].1
        }
        Aggregate::Max => ys.fold(f64::NEG_INFINITY, f64::max),
        Aggregate::Min => ys.fold(f64::INFINITY, f64::min),
        Aggregate::Mean => ys.sum::<f64>() / rows.len() as f64,
        Aggregate::Argmax => rows.iter().max_by(by_y).unwrap().0,
        Aggregate::Argmin => rows.iter().min_by(by_y).unwrap().0,
        Aggregate::Slope => {
            let Some(f) = power_law(&pairs) else {
                bail!("fewer than 3 positive points of `{}` to fit a slope", q.from)
            };
            f.slope
        }
        Aggregate::Increasing => f64::from(u8::from(monotone(&rows, 1.0))),
        Aggregate::Decreasing => f64::from(u8::from(monotone(&rows, -1.0))),
        Aggregate::Count => rows.len() as f64,
        Aggregate::Linearity => linear_r_squared(&pairs)
            .with_context(|| format!("`linearity` of `{}` needs at least 3 rows and a y that varies", q.from))?,
        Aggregate::MaxOverMin => {
            let (lo, hi) = rows.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), r| (a.min(r.1), b.max(r.1)));
            if !(lo > 0.0) {
                bail!("`max_over_min` needs positive values; the smallest is {lo}");
            }
            hi / lo
        }
        Aggregate::LastOverFirst => {
            let (first, last) = (rows[0].1, rows[rows.len() - 1].1);
            if first == 0.0 {
                bail!("`last_over_first`: y at the smallest x is 0");
            }
            last / first
        }
    })
}

/// Whether y rises (`sign` 1) or falls (-1) with x over the rows (x, y, error), sorted by
/// x: strictly where the errors are 0; else no step the other way larger than the two
/// points' errors together, and a change from the first to the last larger than theirs.
fn monotone(rows: &[(f64, f64, f64)], sign: f64) -> bool {
    let steps = rows.windows(2).all(|w| sign * (w[1].1 - w[0].1) > -(w[0].2 + w[1].2));
    let (first, last) = (rows[0], rows[rows.len() - 1]);
    steps && (rows.len() < 2 || sign * (last.1 - first.1) > first.2 + last.2)
}

pub struct Claim;

impl Kind for Claim {
    const NAME: &'static str = "claim";
    const VERSION: u32 = 2;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "A statement of the thesis checked against a published table: the quantity, the thesis' value, the verdict";
    const COLUMNS: &'static [&'static str] = &[
        "id",
        "source",
        "statement",
        "stage",
        "column",
        "aggregate",
        "value",
        "thesis",
        "thesis_value",
        "has_independent",
        "independent_value",
        "independent_source",
        "verdict",
        "expected",
        "regression",
        "reason",
        "docs",
    ];
    type Params = ClaimParams;

    fn validate(p: &ClaimParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        if p.id.trim().is_empty() {
            e.push(FieldError::new("id", "must not be empty"));
        }
        if p.quantity.aggregate.needs_x() && p.quantity.x.is_none() {
            e.push(FieldError::new("quantity.x", format!("`{:?}` needs an x column", p.quantity.aggregate)));
        }
        if (p.quantity.x_min.is_some() || p.quantity.x_max.is_some()) && p.quantity.x.is_none() {
            e.push(FieldError::new("quantity.x", "an x range needs an x column"));
        }
        p.thesis.validate(&mut e, "thesis");
        if p.expect == Verdict::Differs && p.reason.trim().is_empty() {
            e.push(FieldError::new("reason", "a claim expected to differ needs its reason"));
        }
        e
    }

    fn referenced_stages(p: &ClaimParams) -> Vec<(String, String)> {
        vec![("quantity.from".into(), p.quantity.from.clone())]
    }

    fn read_columns(p: &ClaimParams) -> Vec<ColumnRead> {
        let q = &p.quantity;
        let read = |path: String, column: &str| ColumnRead { path, stage: Some(q.from.clone()), column: column.into() };
        let mut reads = Vec::new();
        // `count` reads no y.
        if q.aggregate != Aggregate::Count {
            reads.push(read("quantity.y".into(), &q.y));
        }
        reads.extend(q.over.iter().map(|d| read("quantity.over".into(), d)));
        reads.extend(q.y_error.iter().map(|e| read("quantity.y_error".into(), e)));
        reads.extend(q.x.iter().map(|x| read("quantity.x".into(), x)));
        reads.extend(q.filter.keys().map(|k| read(format!("quantity.filter.{k}"), k)));
        reads
    }

    fn run(p: &ClaimParams, inputs: &Inputs) -> Result<Output> {
        let value = measure(&p.quantity, inputs).with_context(|| format!("claim `{}`", p.id))?;
        // A calibrated claim holds by construction: it says so, not "reproduced".
        let verdict = match (p.thesis.holds(value), p.expect) {
            (false, _) => Verdict::Differs,
            (true, Verdict::Calibrated) => Verdict::Calibrated,
            (true, _) => Verdict::Reproduced,
        };
        let regression = p.expect != Verdict::Differs && verdict == Verdict::Differs;
        let (ind_value, ind_source) =
            p.independent.as_ref().map_or((0.0, String::new()), |i| (i.value, i.source.clone()));
        let table = Table::new()
            .with("id", ColumnData::Str(vec![p.id.clone()]))
            .with("source", ColumnData::Str(vec![p.source.clone()]))
            .with("statement", ColumnData::Str(vec![p.statement.clone()]))
            .with("stage", ColumnData::Str(vec![p.quantity.from.clone()]))
            .with("column", ColumnData::Str(vec![p.quantity.column()]))
            .with("aggregate", ColumnData::Str(vec![format!("{:?}", p.quantity.aggregate).to_lowercase()]))
            .with_f64("value", vec![value])
            .with("thesis", ColumnData::Str(vec![p.thesis.describe()]))
            .with_f64("thesis_value", vec![p.thesis.representative()])
            .with("has_independent", ColumnData::Bool(vec![p.independent.is_some()]))
            .with_f64("independent_value", vec![ind_value])
            .with("independent_source", ColumnData::Str(vec![ind_source]))
            .with("verdict", ColumnData::Str(vec![verdict.as_str().into()]))
            .with("expected", ColumnData::Str(vec![p.expect.as_str().into()]))
            .with("regression", ColumnData::Bool(vec![regression]))
            .with("reason", ColumnData::Str(vec![p.reason.clone()]))
            .with("docs", ColumnData::Str(vec![p.docs.clone()]));
        let mut out = Output::from(table);
        if regression {
            out.regressions.push(format!(
                "claim {} ({}: {}) was reproduced and is not: {} = {}, the thesis {}",
                p.id,
                p.source,
                p.statement,
                p.quantity.y,
                format_number(value),
                p.thesis.describe()
            ));
        }
        Ok(out)
    }
}

#[derive(Serialize, Deserialize, JsonSchema, Clone, Debug)]
#[serde(deny_unknown_fields)]
pub struct ClaimsParams {
    /// The `claim` stages gathered (each must be in `needs`).
    pub claims: Vec<String>,
}

/// The verdicts of the `claim` stages in one table (`tables/<stage>.parquet`) and the run's
/// verdict line.
pub struct Claims;

impl Kind for Claims {
    const NAME: &'static str = "claims";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str = "The verdicts of claim stages in one table, and the run's verdict line";
    const COLUMNS: &'static [&'static str] = &["id", "verdict", "expected"];
    type Params = ClaimsParams;

    fn validate(p: &ClaimsParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        if p.claims.is_empty() {
            e.push(FieldError::new("claims", "name at least one claim stage"));
        }
        e
    }

    fn referenced_stages(p: &ClaimsParams) -> Vec<(String, String)> {
        p.claims.iter().enumerate().map(|(i, c)| (format!("claims[{i}]"), c.clone())).collect()
    }

    fn run(p: &ClaimsParams, inputs: &Inputs) -> Result<Output> {
        let mut table = Table::new();
        for c in &p.claims {
            table.append(inputs.table(c)?).with_context(|| format!("claim stage `{c}`"))?;
        }
        let text = |name: &str| -> Result<Vec<String>> {
            match table.column(name) {
                Some(ColumnData::Str(v)) => Ok(v.clone()),
                _ => bail!("the claim stages have no `{name}` column"),
            }
        };
        let (verdicts, expected, ids) = (text("verdict")?, text("expected")?, text("id")?);
        let n = verdicts.len();
        let mut out = Output::from(table);
        out.notes.push(verdict_line(&verdicts, &expected, None));
        let newly: Vec<&str> = (0..n)
            .filter(|&i| verdicts[i] == "reproduced" && expected[i] == "differs")
            .map(|i| ids[i].as_str())
            .collect();
        if !newly.is_empty() {
            out.notes.push(format!("  now reproduced (recorded as differing): {}", newly.join(", ")));
        }
        Ok(out)
    }
}

/// The verdict line of claims with these verdicts and recorded expectations: "45 of 58
/// thesis claims reproduced, 1 calibrated (the model tuned to them), 12 differ (explained)",
/// ", 2 regressed" where some are. With `of_all`, the claims of a run that reached only
/// some of the pipeline's `of_all`: "3 of 3 claims in scope reproduced, ..., 62 not run".
pub fn verdict_line(verdicts: &[String], expected: &[String], of_all: Option<usize>) -> String {
    let n = verdicts.len();
    let reproduced = verdicts.iter().filter(|v| *v == "reproduced").count();
    let calibrated = verdicts.iter().filter(|v| *v == "calibrated").count();
    let explained = verdicts.iter().zip(expected).filter(|(v, e)| *v == "differs" && *e == "differs").count();
    let regressed = n - reproduced - calibrated - explained;
    let mut line = match of_all {
        None => format!("{reproduced} of {n} thesis claims reproduced, "),
        Some(_) => format!("{reproduced} of {n} claims in scope reproduced, "),
    };
    if calibrated > 0 {
        line.push_str(&format!("{calibrated} calibrated (the model tuned to them), "));
    }
    line.push_str(&format!("{explained} differ (explained)"));
    if regressed > 0 {
        line.push_str(&format!(", {regressed} regressed"));
    }
    if let Some(all) = of_all {
        line.push_str(&format!(", {} not run", all.saturating_sub(n)));
    }
    line
}

/// The verdict line of a run that did not reach the `claims` stage, from the tables of the
/// claim tasks it ran or found cached (`of_all`: the pipeline's claim stages); none if it
/// reached no claim.
pub fn partial_verdict_line(claim_tables: &[&Table], of_all: usize) -> Option<String> {
    let text = |t: &Table, name: &str| match t.column(name) {
        Some(ColumnData::Str(v)) => v.clone(),
        _ => Vec::new(),
    };
    let verdicts: Vec<String> = claim_tables.iter().flat_map(|t| text(t, "verdict")).collect();
    let expected: Vec<String> = claim_tables.iter().flat_map(|t| text(t, "expected")).collect();
    (!verdicts.is_empty() && verdicts.len() == expected.len()).then(|| verdict_line(&verdicts, &expected, Some(of_all)))
}

pub fn register(r: &mut Registry) {
    r.add::<Claim>();
    r.add::<Claims>();
}

#[cfg(test)]
mod tests {
    use super::{monotone, verdict_line};

    #[test]
    fn a_run_of_some_claims_says_how_many_it_did_not_run() {
        let v = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        let (verdicts, expected) =
            (v(&["reproduced", "reproduced", "differs"]), v(&["reproduced", "reproduced", "differs"]));
        assert_eq!(verdict_line(&verdicts, &expected, None), "2 of 3 thesis claims reproduced, 1 differ (explained)");
        assert_eq!(
            verdict_line(&verdicts, &expected, Some(65)),
            "2 of 3 claims in scope reproduced, 1 differ (explained), 62 not run"
        );
        let regressed = v(&["reproduced", "differs", "differs"]);
        assert_eq!(
            verdict_line(&regressed, &expected, Some(3)),
            "1 of 3 claims in scope reproduced, 1 differ (explained), 1 regressed, 0 not run"
        );
    }

    #[test]
    fn monotonicity_is_judged_within_the_error_estimates() {
        // Fig. 3.6b's shape: a step back of 0.01 at the snap's location error (0.04 each).
        let dip = [(0.0, 7.70, 0.04), (1.0, 7.94, 0.04), (2.0, 7.93, 0.04), (3.0, 12.0, 0.06)];
        assert!(monotone(&dip, 1.0));
        // Without errors, strictly: the same step back breaks it.
        let strict: Vec<_> = dip.iter().map(|r| (r.0, r.1, 0.0)).collect();
        assert!(!monotone(&strict, 1.0));
        // A step back larger than the two errors together breaks it too (0.14 > 0.08).
        assert!(!monotone(&[(0.0, 7.70, 0.04), (1.0, 7.94, 0.04), (2.0, 7.80, 0.04), (3.0, 12.0, 0.06)], 1.0));
        // A change within the ends' errors is no rise.
        assert!(!monotone(&[(0.0, 1.0, 0.1), (1.0, 1.05, 0.1)], 1.0));
        assert!(monotone(&[(0.0, 3.0, 0.0), (1.0, 2.0, 0.0)], -1.0));
        assert!(!monotone(&[(0.0, 3.0, 0.0), (1.0, 2.0, 0.0)], 1.0));
    }
}
