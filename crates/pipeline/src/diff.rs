//! `repro diff`: what changed between two recorded runs (DVC's `params diff` and `metrics
//! diff` in one): the pipeline file and the parameters set with `-S`, the tasks the second
//! run computed and why, and, per stage, the table values and figures whose results differ.
//!
//! Results are compared through the cache: a task's output is a function of its key, so two
//! runs' tasks at the same sweep point with different keys are loaded from the cache and
//! compared column by column (numbers to a relative tolerance, anything else exactly). An
//! entry no longer in the cache (removed by `repro gc`) is said to be so.

use super::cache::Cache;
use super::report::{RunReport, Status};
use super::table::ColumnData;
use std::collections::BTreeMap;
use std::fmt::Write;

/// One column's largest change between two outputs of a task.
#[derive(Clone, Debug, PartialEq)]
pub struct ColumnChange {
    pub stage: String,
    pub point: String,
    pub column: String,
    /// The largest relative difference |a - b| / max(|a|, |b|) over the rows (1 for a change
    /// of text, of the number of rows, or of a column present on one side only).
    pub max_rel: f64,
}

/// What changed between run `a` and run `b`.
#[derive(Clone, Debug, Default)]
pub struct RunDiff {
    pub pipelines: (String, String),
    pub overrides: (Vec<String>, Vec<String>),
    /// The tasks run `b` computed: (stage, point, reason).
    pub computed: Vec<(String, String, String)>,
    pub changes: Vec<ColumnChange>,
    /// Figures whose drawing differs.
    pub figures: Vec<String>,
    /// Tasks whose outputs could not be compared (an entry no longer in the cache).
    pub missing: Vec<(String, String)>,
}

fn columns_differ(a: &ColumnData, b: &ColumnData) -> f64 {
    match (a, b) {
        (ColumnData::F64(x), ColumnData::F64(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .map(|(p, q)| {
                let scale = p.abs().max(q.abs());
                if scale == 0.0 {
                    0.0
                } else {
                    (p - q).abs() / scale
                }
            })
            .fold(0.0, f64::max),
        (a, b) => {
            if a == b {
                0.0
            } else {
                1.0
            }
        }
    }
}

/// Compares run `a` with run `b`, reading outputs from `cache`; differences below `rel_tol`
/// are not reported. Timing columns are not results and are left out.
pub fn diff(a: &RunReport, b: &RunReport, cache: &Cache, rel_tol: f64) -> RunDiff {
    let mut d = RunDiff {
        pipelines: (a.pipeline.clone(), b.pipeline.clone()),
        overrides: (a.overrides.clone(), b.overrides.clone()),
        ..Default::default()
    };
    for t in b.tasks.iter().filter(|t| t.status == Status::Computed) {
        d.computed.push((
            t.stage.clone(),
            t.point.clone(),
            t.reason.as_ref().map(|r| r.to_string()).unwrap_or_default(),
        ));
    }
    let keys_a: BTreeMap<(&str, &str), &str> =
        a.tasks.iter().filter_map(|t| Some(((t.stage.as_str(), t.point.as_str()), t.key.as_deref()?))).collect();
    for t in &b.tasks {
        let (Some(kb), Some(&ka)) = (t.key.as_deref(), keys_a.get(&(t.stage.as_str(), t.point.as_str()))) else {
            continue;
        };
        if ka == kb {
            continue;
        }
        let (Ok(ea), Ok(eb)) = (cache.get(ka), cache.get(kb)) else {
            d.missing.push((t.stage.clone(), t.point.clone()));
            continue;
        };
        if ea.output.artifacts != eb.output.artifacts {
            d.figures.push(t.stage.clone());
        }
        let (ta, tb) = (&ea.output.table, &eb.output.table);
        let mut names: Vec<String> = ta.column_names();
        names.extend(tb.column_names().into_iter().filter(|n| !ta.column_names().contains(n)));
        for name in names.into_iter().filter(|n| n != "wall_time_s") {
            let max_rel = match (ta.column(&name), tb.column(&name)) {
                (Some(x), Some(y)) => columns_differ(x, y),
                _ => 1.0,
            };
            if max_rel > rel_tol {
                d.changes.push(ColumnChange { stage: t.stage.clone(), point: t.point.clone(), column: name, max_rel });
            }
        }
    }
    d
}

impl RunDiff {
    /// The diff as text, section by section.
    pub fn render(&self) -> String {
        let mut s = String::new();
        if self.pipelines.0 != self.pipelines.1 {
            let _ = writeln!(s, "pipeline: {} -> {}", self.pipelines.0, self.pipelines.1);
        }
        if self.overrides.0 != self.overrides.1 {
            let show = |o: &[String]| if o.is_empty() { "(none)".to_string() } else { o.join(" ") };
            let _ = writeln!(s, "parameters set with -S: {} -> {}", show(&self.overrides.0), show(&self.overrides.1));
        }
        let _ = writeln!(s, "computed: {} task(s)", self.computed.len());
        let mut reasons: BTreeMap<(&str, &str), usize> = BTreeMap::new();
        for (stage, _, why) in &self.computed {
            *reasons.entry((stage.as_str(), why.as_str())).or_default() += 1;
        }
        for ((stage, why), n) in reasons {
            let _ = writeln!(s, "  {stage}: {n} ({why})");
        }
        if self.changes.is_empty() && self.figures.is_empty() {
            let _ = writeln!(s, "results: no table value or figure changed");
        } else {
            let mut per: BTreeMap<(&str, &str), (f64, usize)> = BTreeMap::new();
            for c in &self.changes {
                let e = per.entry((c.stage.as_str(), c.column.as_str())).or_default();
                e.0 = e.0.max(c.max_rel);
                e.1 += 1;
            }
            let _ = writeln!(s, "results changed (largest relative change over the points that changed):");
            for ((stage, column), (max_rel, n)) in per {
                let _ = writeln!(s, "  {stage}.{column}: {max_rel:.3e} at {n} point(s)");
            }
            for f in &self.figures {
                let _ = writeln!(s, "  figure {f} changed");
            }
        }
        for (stage, point) in &self.missing {
            let _ = writeln!(s, "not compared (no longer in the cache): {stage} {point}");
        }
        s
    }
}
