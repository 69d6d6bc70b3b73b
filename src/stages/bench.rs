//! `bench.pareto`: run time against error. Each candidate stage is one configuration of a
//! solver (mesh, domain, tolerance, load steps) run over the same representative physical
//! points as a reference stage (a converged, finer configuration). Per configuration: the
//! largest relative error of a quantity over the points, the total wall time, whether every
//! point converged, whether the configuration is on the Pareto front (no other one is both
//! faster and more accurate) and whether it meets a declared tolerance. With declared
//! resolutions of the error and of the time (how far apart two values must be to differ
//! beyond the measurement's noise), also whether it is on the front at that resolution
//! (`on_front_resolved`): no other configuration is as accurate and as fast within the
//! resolutions and clearly better in one.

use anyhow::{bail, Context, Result};
use pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Errors below this are reported as this (a configuration identical to the reference
/// still shows on a log axis).
pub const ERROR_FLOOR: f64 = 1e-9;

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ParetoParams {
    /// The configurations: stages with one row per physical point (each must be in `needs`).
    pub candidates: Vec<String>,
    /// The converged reference: a stage with the same physical points.
    pub reference: String,
    /// Columns that identify a physical point (matched between candidates and reference).
    #[serde(rename = "match")]
    pub match_on: Vec<String>,
    /// The quantity whose relative error is measured (e.g. `mu_star`, `F_buckling_bar`).
    pub value: String,
    /// The declared tolerance on the relative error (e.g. 0.005).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub tolerance: f64,
    /// The candidate that the thesis pipeline uses (its defaults).
    pub default: String,
    /// The candidates' column holding the error estimate of `value` (absolute, in its
    /// units), if any: each candidate is then checked against the reference, with the
    /// columns `estimate_covers` (the fraction of its points whose actual error is within
    /// the estimate) and `error_over_estimate` (the largest actual error over estimate).
    #[serde(default)]
    pub error: Option<String>,
    /// Relative errors within this fraction of each other count as equal (default 0:
    /// compared exactly).
    #[serde(default)]
    pub error_resolution: f64,
    /// Wall times within this fraction of each other count as equal (default 0).
    #[serde(default)]
    pub time_resolution: f64,
}

/// Whether configuration `i` is on the front of (error, time) among the converged ones,
/// with errors and times that differ by less than the resolutions (fractions) counted as
/// equal: dominated when another is no worse in both within them and clearly better in one.
fn on_front(i: usize, error: &[f64], time: &[f64], ok: &[bool], error_res: f64, time_res: f64) -> bool {
    let no_worse = |a: f64, b: f64, r: f64| a <= b * (1.0 + r);
    let better = |a: f64, b: f64, r: f64| a < b * (1.0 - r);
    ok[i]
        && !(0..error.len()).any(|j| {
            j != i
                && ok[j]
                && no_worse(error[j], error[i], error_res)
                && no_worse(time[j], time[i], time_res)
                && (better(error[j], error[i], error_res) || better(time[j], time[i], time_res))
        })
}

fn rows_by_point(t: &Table, stage: &str, match_on: &[String]) -> Result<Vec<Vec<f64>>> {
    let cols = match_on
        .iter()
        .map(|c| t.f64_column(c).with_context(|| format!("stage `{stage}`: match column `{c}`")))
        .collect::<Result<Vec<_>>>()?;
    Ok((0..t.n_rows()).map(|r| cols.iter().map(|c| c[r]).collect()).collect())
}

fn same_point(a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1e-300))
}

pub struct Pareto;

impl Kind for Pareto {
    const NAME: &'static str = "bench.pareto";
    const VERSION: u32 = 4;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "Run time against error: per solver configuration, max relative error vs a reference, wall time, Pareto front";
    const COLUMNS: &'static [&'static str] = &[
        "config",
        "rel_error",
        "wall_time_s",
        "points",
        "configs",
        "converged",
        "on_front",
        "on_front_resolved",
        "is_default",
        "meets_tolerance",
        "tolerance",
        "value",
    ];
    type Params = ParetoParams;

    fn validate(p: &ParetoParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        for (name, r) in [("error_resolution", p.error_resolution), ("time_resolution", p.time_resolution)] {
            if !(0.0..1.0).contains(&r) {
                e.push(FieldError::new(name, format!("must lie in [0, 1), got {r}")));
            }
        }
        if p.candidates.is_empty() {
            e.push(FieldError::new("candidates", "needs at least one stage"));
        }
        if !p.candidates.contains(&p.default) {
            e.push(FieldError::new("default", format!("`{}` is not among the candidates", p.default)));
        }
        if p.match_on.is_empty() {
            e.push(FieldError::new("match", "needs at least one column"));
        }
        e
    }

    fn referenced_stages(p: &ParetoParams) -> Vec<(String, String)> {
        let mut v: Vec<(String, String)> =
            p.candidates.iter().enumerate().map(|(i, c)| (format!("candidates[{i}]"), c.clone())).collect();
        v.push(("reference".into(), p.reference.clone()));
        v
    }

    fn run(p: &ParetoParams, inputs: &Inputs) -> Result<Output> {
        let rt = inputs.table(&p.reference)?;
        let ref_points = rows_by_point(rt, &p.reference, &p.match_on)?;
        let ref_values = rt.f64_column(&p.value).with_context(|| format!("reference `{}`", p.reference))?;
        let converged_col = |t: &Table| -> Vec<bool> {
            match t.column("converged") {
                Some(ColumnData::Bool(b)) => b.clone(),
                _ => vec![true; t.n_rows()],
            }
        };
        let ref_ok = converged_col(rt);
        let (mut error, mut time, mut ok, mut n_points) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let (mut covers, mut over) = (Vec::new(), Vec::new());
        // Newton iterations per row, when every candidate reports them.
        let mut per_point: Option<Vec<f64>> = Some(Vec::new());
        for c in &p.candidates {
            let t = inputs.table(c)?;
            let points = rows_by_point(t, c, &p.match_on)?;
            let values = t.f64_column(&p.value).with_context(|| format!("candidate `{c}`"))?;
            let walls = t.f64_column("wall_time_s").with_context(|| format!("candidate `{c}`"))?;
            let conv = converged_col(t);
            per_point = per_point.and_then(|mut v| {
                let it = t.f64_column("iterations").ok()?;
                v.push(it.iter().sum::<f64>() / it.len().max(1) as f64);
                Some(v)
            });
            let estimates = match &p.error {
                Some(col) => Some(t.f64_column(col).with_context(|| format!("candidate `{c}`: error column"))?),
                None => None,
            };
            let mut worst: f64 = 0.0;
            let mut all_ok = true;
            let (mut covered, mut worst_ratio) = (0usize, 0.0f64);
            for (r, pt) in points.iter().enumerate() {
                let Some(j) = ref_points.iter().position(|q| same_point(pt, q)) else {
                    bail!("candidate `{c}` row {r}: no reference point with {:?} = {pt:?}", p.match_on);
                };
                if !(ref_ok[j] && ref_values[j] != 0.0) {
                    bail!("reference `{}` point {pt:?} did not converge or is zero", p.reference);
                }
                worst = worst.max(((values[r] - ref_values[j]) / ref_values[j]).abs());
                all_ok &= conv[r];
                if let Some(est) = &estimates {
                    let actual = (values[r] - ref_values[j]).abs();
                    covered += usize::from(actual <= est[r]);
                    // An estimate of 0 against a nonzero error: the ratio is capped (finite).
                    worst_ratio = worst_ratio.max(if actual == 0.0 { 0.0 } else { (actual / est[r]).min(1e12) });
                }
            }
            covers.push(covered as f64 / points.len().max(1) as f64);
            over.push(worst_ratio);
            error.push(worst.max(ERROR_FLOOR));
            time.push(walls.iter().sum::<f64>());
            ok.push(all_ok);
            n_points.push(points.len() as i64);
        }
        // Front: no other converged configuration is at least as fast and as accurate, and
        // strictly better in one; the resolved front compares within the resolutions.
        let flag = |b: bool| if b { 1.0 } else { 0.0 };
        let front: Vec<f64> =
            (0..p.candidates.len()).map(|i| flag(on_front(i, &error, &time, &ok, 0.0, 0.0))).collect();
        let resolved: Vec<f64> = (0..p.candidates.len())
            .map(|i| flag(on_front(i, &error, &time, &ok, p.error_resolution, p.time_resolution)))
            .collect();
        // Rows by wall time, so that the front draws as a line.
        let n = p.candidates.len();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| time[a].total_cmp(&time[b]));
        let pick = |v: &[f64]| order.iter().map(|&i| v[i]).collect::<Vec<f64>>();
        let t = Table::new()
            .with("config", ColumnData::Str(order.iter().map(|&i| p.candidates[i].clone()).collect()))
            .with_f64("rel_error", pick(&error))
            .with_f64("wall_time_s", pick(&time))
            .with("points", ColumnData::I64(order.iter().map(|&i| n_points[i]).collect()))
            // How many configurations the table compares (a figure's title counts them).
            .with("configs", ColumnData::I64(vec![order.len() as i64; n]))
            .with("converged", ColumnData::Bool(order.iter().map(|&i| ok[i]).collect()))
            .with_f64("on_front", pick(&front))
            .with_f64("on_front_resolved", pick(&resolved))
            .with_f64("is_default", order.iter().map(|&i| (p.candidates[i] == p.default) as u8 as f64).collect())
            .with_f64("meets_tolerance", order.iter().map(|&i| (error[i] <= p.tolerance) as u8 as f64).collect())
            .with_f64("tolerance", vec![p.tolerance; n])
            .with("value", ColumnData::Str(vec![p.value.clone(); n]));
        let t = if p.error.is_some() {
            t.with_f64("estimate_covers", pick(&covers)).with_f64("error_over_estimate", pick(&over))
        } else {
            t
        };
        let t = match per_point {
            Some(v) => t.with_f64("iterations_per_point", pick(&v)),
            None => t,
        };
        Ok(t.into())
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SummaryParams {
    /// The stages summarised (each must be in `needs`), one row each.
    pub stages: Vec<String>,
}

/// Per stage of a stress grid: how many points, how many converged, the most Newton
/// iterations and the worst residual. Reads the solver diagnostics the solver stages
/// publish: `converged` (bool; a stage without it counts every row as converged),
/// `iterations` or `max_iterations`, `residual` or `max_residual`.
pub struct Summary;

impl Kind for Summary {
    const NAME: &'static str = "bench.summary";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str = "Summary of a stress grid: per stage points, converged, max iterations, worst residual";
    const COLUMNS: &'static [&'static str] =
        &["stage", "points", "converged", "not_converged", "max_iterations", "worst_residual"];
    type Params = SummaryParams;

    fn validate(p: &SummaryParams) -> Vec<FieldError> {
        if p.stages.is_empty() {
            return vec![FieldError::new("stages", "needs at least one stage")];
        }
        Vec::new()
    }

    fn referenced_stages(p: &SummaryParams) -> Vec<(String, String)> {
        p.stages.iter().enumerate().map(|(i, c)| (format!("stages[{i}]"), c.clone())).collect()
    }

    fn run(p: &SummaryParams, inputs: &Inputs) -> Result<Output> {
        let (mut points, mut converged, mut iterations, mut residual) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for name in &p.stages {
            let t = inputs.table(name)?;
            let n = t.n_rows();
            let ok = match t.column("converged") {
                Some(ColumnData::Bool(b)) => b.iter().filter(|&&c| c).count(),
                Some(_) => bail!("stage `{name}`: column `converged` is not boolean"),
                None => n,
            };
            let first = |names: [&str; 2]| names.iter().find_map(|c| t.f64_column(c).ok());
            let it = first(["iterations", "max_iterations"]).map_or(0.0, |v| v.iter().fold(0.0, |a: f64, &b| a.max(b)));
            let res = first(["residual", "max_residual"]).map_or(0.0, |v| v.iter().fold(0.0, |a: f64, &b| a.max(b)));
            points.push(n as i64);
            converged.push(ok as i64);
            iterations.push(it);
            residual.push(res);
        }
        let not: Vec<i64> = points.iter().zip(&converged).map(|(a, b)| a - b).collect();
        Ok(Table::new()
            .with("stage", ColumnData::Str(p.stages.clone()))
            .with("points", ColumnData::I64(points))
            .with("converged", ColumnData::I64(converged))
            .with("not_converged", ColumnData::I64(not))
            .with_f64("max_iterations", iterations)
            .with_f64("worst_residual", residual)
            .into())
    }
}

pub fn register(r: &mut Registry) {
    r.add::<Pareto>();
    r.add::<Summary>();
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    fn stage(xs: &[f64], vs: &[f64], ts: &[f64]) -> Table {
        Table::new().with_f64("x", xs.to_vec()).with_f64("v", vs.to_vec()).with_f64("wall_time_s", ts.to_vec())
    }

    #[test]
    fn errors_times_and_the_front() {
        let reference = stage(&[1.0, 2.0], &[10.0, 20.0], &[9.0, 9.0]);
        let coarse = stage(&[2.0, 1.0], &[21.0, 10.1], &[0.5, 0.5]); // 5 % (row order differs)
        let fine = stage(&[1.0, 2.0], &[10.0, 20.02], &[2.0, 2.0]); // 0.1 %
        let wasteful = stage(&[1.0, 2.0], &[10.0, 20.2], &[3.0, 3.0]); // 1 %, slower than fine
        let tables: BTreeMap<String, &Table> =
            [("ref", &reference), ("coarse", &coarse), ("fine", &fine), ("waste", &wasteful)]
                .into_iter()
                .map(|(n, t)| (n.to_string(), t))
                .collect();
        let p = ParetoParams {
            candidates: vec!["coarse".into(), "fine".into(), "waste".into()],
            reference: "ref".into(),
            match_on: vec!["x".into()],
            value: "v".into(),
            tolerance: 0.005,
            default: "fine".into(),
            error: None,
            error_resolution: 0.0,
            time_resolution: 0.0,
        };
        let out = Pareto::run(&p, &Inputs { tables }).unwrap().table;
        let err = out.f64_column("rel_error").unwrap();
        assert!((err[0] - 0.05).abs() < 1e-12 && (err[1] - 0.001).abs() < 1e-12 && (err[2] - 0.01).abs() < 1e-12);
        assert_eq!(out.f64_column("wall_time_s").unwrap(), vec![1.0, 4.0, 6.0]);
        assert_eq!(out.f64_column("on_front").unwrap(), vec![1.0, 1.0, 0.0]);
        assert_eq!(out.f64_column("meets_tolerance").unwrap(), vec![0.0, 1.0, 0.0]);
        assert_eq!(out.f64_column("is_default").unwrap(), vec![0.0, 1.0, 0.0]);
    }

    #[test]
    fn the_resolved_front_treats_differences_below_the_resolutions_as_ties() {
        // a: error 1.000e-3 in 10 s; b: 1.0000001e-3 (the same within noise) in 8 s;
        // c: 0.5e-3 in 10.1 s (as fast as a within 5 %, clearly more accurate).
        let error = [1e-3, 1.0000001e-3, 0.5e-3];
        let time = [10.0, 8.0, 10.1];
        let ok = [true; 3];
        let exact: Vec<bool> = (0..3).map(|i| on_front(i, &error, &time, &ok, 0.0, 0.0)).collect();
        assert_eq!(exact, vec![true, true, true]);
        // At 1 % in error and 5 % in time, a is dominated by b (faster, as accurate) and by c.
        let resolved: Vec<bool> = (0..3).map(|i| on_front(i, &error, &time, &ok, 0.01, 0.05)).collect();
        assert_eq!(resolved, vec![false, true, true]);
        // A configuration that did not converge is on no front and dominates nothing.
        let ok = [true, false, true];
        let r: Vec<bool> = (0..3).map(|i| on_front(i, &error, &time, &ok, 0.01, 0.05)).collect();
        assert_eq!(r, vec![false, false, true]);
    }

    /// Candidate `c` against reference `ref`, points matched on `x`, value `v`.
    /// The inputs of `one_candidate`: the reference table as "ref", the candidate as "c".
    fn reference_and_candidate<'a>(reference: &'a Table, cand: &'a Table) -> BTreeMap<String, &'a Table> {
        [("ref", reference), ("c", cand)].into_iter().map(|(n, t)| (n.to_string(), t)).collect()
    }

    fn one_candidate(error: Option<&str>) -> ParetoParams {
        ParetoParams {
            candidates: vec!["c".into()],
            reference: "ref".into(),
            match_on: vec!["x".into()],
            value: "v".into(),
            tolerance: 0.005,
            default: "c".into(),
            error: error.map(String::from),
            error_resolution: 0.0,
            time_resolution: 0.0,
        }
    }

    #[test]
    fn newton_iterations_are_averaged_over_a_candidates_points() {
        let reference = stage(&[1.0, 2.0], &[10.0, 20.0], &[9.0, 9.0]);
        let cand = stage(&[1.0, 2.0], &[10.0, 20.0], &[1.0, 1.0]).with_f64("iterations", vec![3.0, 8.0]);
        let tables = reference_and_candidate(&reference, &cand);
        let out = Pareto::run(&one_candidate(None), &Inputs { tables }).unwrap().table;
        assert_eq!(out.f64_column("iterations_per_point").unwrap(), vec![5.5]);
    }

    #[test]
    fn error_estimates_are_checked_against_the_reference() {
        // Actual errors 0.1 and 0.02; estimates 0.2 (covers) and 0.01 (half the error).
        let reference = stage(&[1.0, 2.0], &[10.0, 20.0], &[9.0, 9.0]);
        let cand = stage(&[1.0, 2.0], &[10.1, 19.98], &[1.0, 1.0]).with_f64("err", vec![0.2, 0.01]);
        let tables = reference_and_candidate(&reference, &cand);
        let mut p = one_candidate(Some("err"));
        let out = Pareto::run(&p, &Inputs { tables: tables.clone() }).unwrap().table;
        assert_eq!(out.f64_column("estimate_covers").unwrap(), vec![0.5]);
        // Without an `iterations` column, no iterations per point.
        assert!(out.column("iterations_per_point").is_none());
        assert!((out.f64_column("error_over_estimate").unwrap()[0] - 2.0).abs() < 1e-9);
        // Without an error column the columns are absent; a missing one names the candidate.
        p.error = None;
        assert!(Pareto::run(&p, &Inputs { tables: tables.clone() }).unwrap().table.column("estimate_covers").is_none());
        p.error = Some("nope".into());
        let e = Pareto::run(&p, &Inputs { tables }).unwrap_err();
        assert!(format!("{e:#}").contains("candidate `c`"), "{e:#}");
    }
}
