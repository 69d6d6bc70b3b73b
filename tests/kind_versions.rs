//! Guards the rule "a change to a stage's code that can change its results bumps its
//! VERSION" (docs/pipelines.md, "Code versions"). Every kind is run on reference parameters; the
//! hash of its output is recorded per `kind@vN` in tests/kind_fingerprints.json. If the
//! output changes while the version stays, this test fails: bump the kind's VERSION (which
//! invalidates exactly that kind's cached results and what depends on them), then record
//! the new fingerprint with `REPRO_BLESS=1 cargo test --test integration kind_versions`.

use repro::pipeline::cache::output_hash;
use repro::pipeline::kind::{Inputs, Output};
use repro::pipeline::table::Table;
use serde_json::{json, Value};
use std::collections::BTreeMap;

/// A few elements and two load steps: the map stages' reference runs take milliseconds.
fn tiny_map_model() -> Value {
    json!({"n_meridian": 12, "n_thickness": 2, "delta_max": 0.02, "steps": 2})
}

pub(crate) fn reference_params() -> BTreeMap<&'static str, Value> {
    BTreeMap::from([
        ("theory.maugis_dugdale", json!({"lambda": 0.7, "A_min": 0.1, "A_max": 2.0, "n": 7})),
        ("theory.maugis_pulloff", json!({"lambda": 0.7})),
        ("theory.line_pulloff", json!({"lambda": 0.7})),
        ("theory.lennard_jones", json!({"z_min": 0.9, "z_max": 3.0, "n": 7})),
        ("theory.sphere_limits", json!({"A_min": 0.1, "A_max": 2.0, "n": 5})),
        ("theory.hertz_jkr_pressure", json!({"P_bar": 1.0, "n": 12})),
        ("theory.persson", json!({"inv_k": 10, "V0": 1.3})),
        ("theory.persson_max", json!({"inv_k": 10})),
        // Materials beyond the SLS exercise the spectral code paths (same output for the SLS).
        ("theory.persson_brener", json!({"k": 0.01, "V_PB": 30, "s": 0.5, "per_decade": 2})),
        ("util.sleep", json!({"x": 1.25})),
        ("bench.summary", json!({"stages": ["rolling", "bench_a"]})),
        (
            "bench.pareto",
            json!({"candidates": ["bench_a", "bench_b"], "reference": "bench_ref", "match": ["x"], "value": "v",
                   "tolerance": 0.005, "default": "bench_b"}),
        ),
        (
            "bem.sweep",
            json!({"lambda": 0.5, "W": 1.0, "k": 0.1, "V0": 1.0, "n": 80, "half_length": 5.0, "prony": [[0.5, 0.01], [0.5, 0.1]]}),
        ),
        ("bem.profile", json!({"lambda": 0.5, "W": 1.0, "k": 0.1, "V0": 1.0, "n": 40, "half_length": 5.0})),
        ("bem.pulloff", json!({"lambda": 1.0, "k": 0.1, "V": 1.0, "n": 64})),
        ("pb.calibrate", json!({"from": "rolling"})),
        ("util.fail", json!({"message": "m", "x": 2})),
        ("fem.mesh", json!({"R": 15.0, "h": 1.0, "n_meridian": 8, "n_thickness": 2})),
        (
            "fem.indent",
            json!({"shell": {"R": 15.0, "h": 1.0, "n_meridian": 12, "n_thickness": 2}, "delta_max": 0.02, "steps": 2}),
        ),
        (
            "fem.profile",
            json!({"cycle": {"shell": {"R": 15.0, "h": 1.0, "n_meridian": 12, "n_thickness": 2}, "delta_max": 0.02, "steps": 2},
                   "points": [{"label": "a", "delta": 0.02}]}),
        ),
        ("fem.buckling", json!({"h_over_R": 0.06, "gamma_over_Eh": 0.001, "mu": 0.3, "model": tiny_map_model()})),
        ("fem.gamma_c", json!({"h_over_R": 0.06, "rel_tol": 1.0, "gamma_max": 0.01, "model": tiny_map_model()})),
        ("fem.buckling_limit", json!({"h_lo": 0.1, "h_hi": 0.2, "model": tiny_map_model()})),
        ("fem.gamma_c_map", json!({"gamma_c": "gc"})),
        (
            "bem.maxima",
            json!({"lambda": 0.5, "W": 1.0, "k": 0.1, "V0_range": [0.1, 10.0], "grid": 4, "log_tol": 0.2, "n": 40, "half_length": 5.0}),
        ),
        (
            "claim",
            json!({"id": "c", "source": "Fig. 1", "statement": "s", "expect": "reproduced",
                   "quantity": {"from": "input", "y": "b", "x": "a", "filter": {"g": 2}, "aggregate": "slope"},
                   "thesis": {"value": 0.0, "abs_tol": 0.1}, "independent": {"value": 0.0, "source": "flat"}}),
        ),
        ("claims", json!({"claims": ["claim_row", "claim_row"]})),
        (
            "fit.powerlaw",
            json!({"from": "input", "x": "a", "y": "b", "x_min": 0.1, "x_max": 10, "group_by": "g", "expected_slope": 0.5}),
        ),
        ("theory.jkr_friction_limit", json!({"from": "rolling", "lambda_range": [0.1, 10.0]})),
        ("theory.adhesionless_friction_limit", json!({"from": "rolling", "W_range": [0.1, 100.0]})),
        (
            "figure",
            json!({
                "title": "t", "x_label": "x", "y_label": "y", "log_x": true,
                "layers": [
                    {"data": {"from": "input", "x": "a", "y": "b", "group_by": "g", "label": "g = {g}"}},
                    {"data": {"from": "input", "x": "a", "y": "b", "label": "points", "style": "points"}},
                    {"guide": {"slope": 1, "through": [1, 1], "x_from": 0.1, "x_to": 10, "label": "g"}}
                ]
            }),
        ),
    ])
}

/// The input tables of the reference runs, by name (`Inputs` borrows them).
fn reference_inputs() -> BTreeMap<String, Table> {
    // Twelve curves (one per palette colour, and one more) of three points each.
    let n = 12;
    let input = Table::new()
        .with_f64("a", (0..3 * n).map(|i| [0.1, 1.0, 10.0][i % 3]).collect())
        .with_f64("b", (0..3 * n).map(|i| 1.0 + (i / 3) as f64 + [0.0, 0.5, 0.2][i % 3]).collect())
        .with_f64("g", (0..3 * n).map(|i| (i / 3) as f64).collect());
    // A rolling curve for pb.calibrate: F = V0 below 1, sqrt(V0) above (2 points per decade).
    let v0: Vec<f64> = (0..13).map(|i| 10f64.powf(-3.0 + 0.5 * i as f64)).collect();
    let rolling = Table::new()
        .with_f64("lambda", vec![3.0; 13])
        .with_f64("W", vec![0.1; 13])
        .with_f64("k", vec![0.001; 13])
        .with_f64("V0", v0.clone())
        .with_f64("F_T", v0.iter().map(|&v| if v < 1.0 { v } else { v.sqrt() }).collect())
        .with("converged", repro::pipeline::table::ColumnData::Bool(vec![true; 13]));
    // A gamma_c sweep for fem.gamma_c_map: two h/R at two mu.
    let gc = Table::new()
        .with_f64("h_over_R", vec![0.04, 0.06, 0.04, 0.06])
        .with_f64("mu", vec![0.0, 0.0, 0.5, 0.5])
        .with_f64("gamma_c_over_Eh", vec![0.01, 0.02, 0.005, 0.01])
        .with_f64("gamma_lo_over_Eh", vec![0.009, 0.018, 0.0045, 0.009])
        .with_f64("gamma_hi_over_Eh", vec![0.011, 0.022, 0.0055, 0.011])
        .with_f64("eq3_7_over_Eh", vec![0.03, 0.04, 0.0, 0.0])
        .with("reliable", repro::pipeline::table::ColumnData::Bool(vec![true, true, false, true]))
        .with("found", repro::pipeline::table::ColumnData::Bool(vec![true, true, true, true]))
        .with_f64("error_estimate", vec![0.001, 0.002, 0.0005, 0.001])
        .with_f64("delta_max_over_R", vec![0.35; 4])
        .with_f64("gamma_max_over_Eh", vec![0.1; 4])
        .with("criterion", repro::pipeline::table::ColumnData::Str(vec!["energy".to_string(); 4]));
    // A claim's verdict for claims: recorded as reproduced, now differing.
    let text = |v: &str| repro::pipeline::table::ColumnData::Str(vec![v.to_string()]);
    let claim_row =
        Table::new().with("id", text("c")).with("verdict", text("differs")).with("expected", text("reproduced"));
    // Two solver configurations and a reference for bench.pareto.
    let timed = |v: [f64; 2], t: f64| {
        Table::new().with_f64("x", vec![1.0, 2.0]).with_f64("v", v.to_vec()).with_f64("wall_time_s", vec![t, t])
    };
    let (bench_ref, bench_a, bench_b) = (timed([1.0, 2.0], 9.0), timed([1.1, 2.0], 1.0), timed([1.0, 2.002], 2.0));
    BTreeMap::from([
        ("bench_ref".to_string(), bench_ref),
        ("bench_a".to_string(), bench_a),
        ("bench_b".to_string(), bench_b),
        ("input".to_string(), input),
        ("rolling".to_string(), rolling),
        ("gc".to_string(), gc),
        ("claim_row".to_string(), claim_row),
    ])
}

/// Every registered kind with its version and its output on the reference parameters and
/// inputs (None: the kind has no reference parameters yet).
fn reference_runs() -> Vec<(String, u32, Option<Output>)> {
    let params = reference_params();
    let tables = reference_inputs();
    let inputs = Inputs { tables: tables.iter().map(|(k, v)| (k.clone(), v)).collect() };
    repro::stages::registry()
        .iter()
        .map(|kind| {
            let out = params.get(kind.name()).map(|p| {
                let (canonical, _) = kind.check(p).unwrap_or_else(|e| panic!("{}: {e:?}", kind.name()));
                kind.run(&canonical, &inputs).unwrap_or_else(|e| panic!("{}: {e:#}", kind.name()))
            });
            (kind.name().to_string(), kind.version(), out)
        })
        .collect()
}

#[test]
fn outputs_change_only_with_a_version_bump() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/kind_fingerprints.json");
    let recorded: BTreeMap<String, String> =
        std::fs::read(&path).ok().and_then(|b| serde_json::from_slice(&b).ok()).unwrap_or_default();
    let mut current = BTreeMap::new();
    let mut problems = Vec::new();
    for (name, version, out) in reference_runs() {
        let Some(out) = out else {
            problems.push(format!("{name}: add reference parameters to tests/kind_versions.rs"));
            continue;
        };
        let id = format!("{name}@v{version}");
        let hash = output_hash(&out);
        match recorded.get(&id) {
            Some(h) if *h != hash => problems.push(format!(
                "{id}: its output changed but its VERSION did not; bump VERSION in the kind, then record with REPRO_BLESS=1"
            )),
            None => problems.push(format!("{id}: no recorded fingerprint; record with REPRO_BLESS=1")),
            _ => {}
        }
        current.insert(id, hash);
    }
    if std::env::var("REPRO_BLESS").is_ok() {
        std::fs::write(&path, serde_json::to_string_pretty(&current).unwrap() + "\n").unwrap();
        return;
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The kinds that solve something, with the column(s) that carry their error estimate: every
/// row of their output has a finite, non-negative estimate. The wall time is the
/// kind's own `wall_time_s` where it measures one, else the executor's measurement of the
/// task, added to every task table (tests/adaptive.rs checks it on `theory.persson`).
/// Closed forms (Hertz, JKR, DMT limits), fits (their standard errors), figures, calibrations
/// and the utilities are not listed; a new kind must be classified here.
const SOLVER_ERROR_COLUMNS: &[(&str, &[&str])] = &[
    ("theory.maugis_dugdale", &["error_estimate"]),
    ("theory.maugis_pulloff", &["error_estimate"]),
    ("theory.line_pulloff", &["error_estimate"]),
    ("theory.persson", &["error_estimate"]),
    ("theory.persson_max", &["error_estimate"]),
    ("theory.persson_brener", &["error_estimate"]),
    ("theory.adhesionless_friction_limit", &["error_estimate"]),
    ("bem.sweep", &["error_estimate"]),
    ("bem.profile", &["error_estimate"]),
    ("bem.pulloff", &["error_estimate"]),
    ("bem.maxima", &["error_estimate"]),
    ("fem.indent", &["F_error_bar"]),
    ("fem.profile", &["F_error_bar"]),
    ("fem.buckling", &["F_buckling_error_bar", "W_error_bar"]),
    ("fem.gamma_c", &["error_estimate"]),
    ("fem.buckling_limit", &["error_estimate"]),
    ("fem.gamma_c_map", &["error_estimate"]),
];

/// Kinds that solve nothing (no error estimate to carry).
const NOT_SOLVERS: &[&str] = &[
    "theory.sphere_limits",
    "theory.hertz_jkr_pressure",
    "theory.lennard_jones",
    "util.sleep",
    "util.fail",
    "bench.summary",
    "bench.pareto",
    "pb.calibrate",
    "fem.mesh",
    "fit.powerlaw",
    // A closed form, exact to rounding.
    "theory.jkr_friction_limit",
    "figure",
    "claim",
    "claims",
];

#[test]
fn every_solver_result_carries_an_error_estimate() {
    let mut problems = Vec::new();
    for (name, _, out) in reference_runs() {
        let Some((_, errors)) = SOLVER_ERROR_COLUMNS.iter().find(|(k, _)| *k == name) else {
            if !NOT_SOLVERS.contains(&name.as_str()) {
                problems.push(format!("{name}: classify it in SOLVER_ERROR_COLUMNS or NOT_SOLVERS"));
            }
            continue;
        };
        let out = out.unwrap_or_else(|| panic!("{name}: no reference parameters"));
        assert!(out.table.n_rows() > 0, "{name}: no rows");
        for column in errors.iter() {
            match out.table.f64_column(column) {
                Ok(v) if v.iter().all(|x| x.is_finite() && *x >= 0.0) => {}
                Ok(v) => problems.push(format!("{name}: `{column}` has {v:?}")),
                Err(e) => problems.push(format!("{name}: {e:#}")),
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Every column a kind emits (on its reference parameters) is listed in docs/outputs.md with a
/// unit; the util kinds, which exist to test the orchestrator, aside.
#[test]
fn every_output_column_is_documented_with_its_unit() {
    let docs =
        std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/outputs.md")).unwrap();
    let mut problems = Vec::new();
    for (name, _, out) in reference_runs() {
        if name.starts_with("util.") {
            continue;
        }
        let Some(out) = out else { continue };
        for column in out.table.column_names() {
            // A fit's group column is named after the fitted table's column (here `g`).
            if name == "fit.powerlaw" && column == "g" {
                continue;
            }
            let row = docs.lines().find(|l| l.starts_with(&format!("| `{column}` |")));
            match row.map(|l| l.split('|').map(str::trim).collect::<Vec<_>>()) {
                Some(cells) if cells.len() >= 4 && !cells[2].is_empty() && !cells[3].is_empty() => {}
                _ => problems.push(format!("{name}: `{column}` is not in docs/outputs.md with a unit and a meaning")),
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn every_column_a_kind_emits_is_among_those_it_declares() {
    // `repro kinds KIND` lists a kind's declared columns (Kind::COLUMNS) with their units.
    let registry = repro::stages::registry();
    let mut problems = Vec::new();
    for (name, _, out) in reference_runs() {
        let Some(out) = out else { continue };
        let declared = registry.get(&name).unwrap().columns();
        for column in out.table.column_names() {
            // A fit's group column is named after the fitted table's column (here `g`).
            if !(declared.contains(&column.as_str()) || (name == "fit.powerlaw" && column == "g")) {
                problems.push(format!("{name}: emits `{column}`, which its COLUMNS do not list"));
            }
        }
        if !name.starts_with("util.") {
            for column in declared {
                if registry.column(column).is_none() {
                    problems.push(format!("{name}: declares `{column}`, which docs/outputs.md does not document"));
                }
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
