//! Adaptive sampling of a sweep (`{adaptive: ...}`): refined where the curve bends or
//! peaks, deterministic, content-addressed (reruns and dry runs), with located errors.
//! Uses Persson's friction (`theory.persson`), whose peak in V0 is sharp and cheap.

use crate::common;
use common::{column, Scratch};

fn pipeline(v0: &str) -> String {
    format!("stages:\n  - name: mu\n    kind: theory.persson\n    params:\n      inv_k: 10\n      V0: {v0}\n")
}

const ADAPTIVE: &str = "{adaptive: {logspace: [-3, 3, 7], y: mu_star, tol: 0.01}}";

/// Piecewise-linear interpolation in log10(x).
fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let t = x.log10();
    let j = xs.partition_point(|&s| s.log10() <= t).clamp(1, xs.len() - 1);
    let w = (t - xs[j - 1].log10()) / (xs[j].log10() - xs[j - 1].log10());
    ys[j - 1] + w * (ys[j] - ys[j - 1])
}

#[test]
fn the_peak_is_resolved_with_fewer_points_than_a_uniform_grid() {
    let s = Scratch::new("adaptive-peak");
    s.write("p.yaml", &pipeline(ADAPTIVE));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    let df = s.table("mu");
    let (v0, mu) = (column(&df, "V0"), column(&df, "mu_star"));
    // Published along the axis.
    assert!(v0.windows(2).all(|w| w[0] < w[1]), "{v0:?}");
    // Every task table carries its task's wall time (added by the executor where the kind
    // reports none, as theory.persson does not).
    assert!(column(&df, "wall_time_s").iter().all(|t| t.is_finite() && *t >= 0.0));
    let n = v0.len();
    assert_eq!(r.count(Some("mu"), "computed"), n);
    // Refined (more than the 7 initial points), but far fewer than the uniform grid at the
    // finest spacing allowed (3 halvings: 49 points).
    assert!(n > 12 && n < 40, "{n} points");
    // The later rounds are reported as such.
    let refined = r.tasks().iter().filter(|t| t["reason"]["why"] == "adaptive_round").count();
    assert_eq!(refined, n - 7);
    // Against a uniform reference grid of 121 points: the piecewise-linear curve through the
    // adaptive points is within 3 % of the peak everywhere, and it finds the peak's height
    // to 1 %.
    let r2 = Scratch::new("adaptive-peak-ref");
    r2.run_pipeline(&pipeline("{logspace: [-3, 3, 121]}"));
    let rdf = r2.table("mu");
    let (rv, rm) = (column(&rdf, "V0"), column(&rdf, "mu_star"));
    let peak = rm.iter().copied().fold(0.0, f64::max);
    let worst = rv.iter().zip(&rm).map(|(&x, &y)| (interpolate(&v0, &mu, x) - y).abs()).fold(0.0, f64::max);
    assert!(worst < 0.03 * peak, "worst {worst} of peak {peak}");
    let found = mu.iter().copied().fold(0.0, f64::max);
    assert!((found - peak).abs() < 0.01 * peak, "{found} vs {peak}");
    // Where the curve is nearly straight (the far low-speed decades), no refinement: the
    // densest spacing is near the peak.
    let i_peak = mu.iter().position(|&y| y == found).unwrap();
    let gap = |i: usize| v0[i + 1].log10() - v0[i].log10();
    assert!(gap(i_peak.min(n - 2)) < gap(0), "{v0:?}");
}

#[test]
fn reruns_and_dry_runs_reproduce_the_same_points() {
    let s = Scratch::new("adaptive-rerun");
    s.write("p.yaml", &pipeline(ADAPTIVE));
    // A dry run on an empty cache lists the first round and says the rest is unknown.
    let (code, err, r) = s.run("p.yaml", &["--dry-run"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(Some("mu"), "would_run"), 7);
    assert_eq!(r.count(Some("mu"), "unknown"), 1);
    s.run("p.yaml", &[]);
    let first = s.read("tables/mu.parquet");
    let n = s.table("mu").height();
    // A rerun computes nothing and rewrites nothing; a dry run follows every round from the
    // cache: nothing would run, nothing is unknown.
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!((r.count(Some("mu"), "computed"), r.count(Some("mu"), "cached")), (0, n));
    assert_eq!(s.read("tables/mu.parquet"), first);
    let (_, _, r) = s.run("p.yaml", &["--dry-run"]);
    assert_eq!((r.count(Some("mu"), "would_run"), r.count(Some("mu"), "unknown")), (0, 0));
    // From an empty cache again: the same points with the same values (and keys).
    let before = s.table("mu");
    std::fs::remove_dir_all(s.path("cache")).unwrap();
    s.run("p.yaml", &[]);
    let after = s.table("mu");
    for c in ["V0", "mu_star"] {
        assert_eq!(column(&before, c), column(&after, c), "{c}");
    }
    assert!(before.column("task_key").unwrap().equals(after.column("task_key").unwrap()));
    // A looser tolerance keeps a subset of the points: all cached.
    s.write("p.yaml", &pipeline("{adaptive: {logspace: [-3, 3, 7], y: mu_star, tol: 0.05}}"));
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(Some("mu"), "computed"), 0);
    assert!(s.table("mu").height() < n);
    // A tighter one computes only the new points.
    s.write("p.yaml", &pipeline("{adaptive: {logspace: [-3, 3, 7], y: mu_star, tol: 0.003, levels: 4}}"));
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(Some("mu"), "cached"), n, "every earlier point is reused");
    assert!(r.count(Some("mu"), "computed") > 0);
}

#[test]
fn each_curve_of_a_product_is_refined_on_its_own() {
    let s = Scratch::new("adaptive-curves");
    s.run_pipeline(&format!(
        "stages:\n  - name: mu\n    kind: theory.persson\n    params:\n      inv_k: [2, 100]\n      V0: {ADAPTIVE}\n"
    ));
    let df = s.table("mu");
    let (k, v0) = (column(&df, "inv_k"), column(&df, "V0"));
    // Curve by curve, each along the axis.
    let split = k.iter().position(|&x| x == 100.0).unwrap();
    assert!(k[..split].iter().all(|&x| x == 2.0) && k[split..].iter().all(|&x| x == 100.0));
    assert!(v0[..split].windows(2).all(|w| w[0] < w[1]) && v0[split..].windows(2).all(|w| w[0] < w[1]));
    // The two curves peak at different speeds, so they get different points.
    assert_ne!(v0[..split].to_vec(), v0[split..].to_vec());
}

#[test]
fn mistakes_are_reported_with_their_place() {
    let s = Scratch::new("adaptive-errors");
    let cases = [
        ("{adaptive: {logspace: [-3, 3, 7], y: mu_star, tol: 2}}", "6:", "`tol` must be a number in (0, 1)"),
        ("{adaptive: {logspace: [-3, 3, 7], tol: 0.01}}", "6:", "`y` must name the output column"),
        ("{adaptive: {logspace: [-3, 3, 2], y: mu_star, tol: 0.01}}", "6:", "at least 3 points"),
        ("{adaptive: {y: mu_star, tol: 0.01}}", "6:", "exactly one of `logspace`, `linspace` and `shown`"),
        ("{adaptive: {logspace: [-3, 3, 7], y: mu_star, tol: 0.01, step: 2}}", "6:", "unknown field `step`"),
    ];
    for (v0, at, msg) in cases {
        s.write("p.yaml", &pipeline(v0));
        let (code, err, _) = s.run("p.yaml", &[]);
        assert_ne!(code, 0, "{v0}");
        assert!(err.contains(&format!("p.yaml:{at}")) && err.contains(msg), "{v0}: {err}");
    }
    // Two adaptive parameters.
    s.write(
        "p.yaml",
        &format!("stages:\n  - name: mu\n    kind: theory.persson\n    params:\n      inv_k: {{adaptive: {{linspace: [2, 10, 3], y: mu_star, tol: 0.1}}}}\n      V0: {ADAPTIVE}\n"),
    );
    let (_, err, _) = s.run("p.yaml", &[]);
    assert!(err.contains("p.yaml:6:") && err.contains("only one parameter may be adaptive"), "{err}");
    // A column the kind does not produce: the stage fails after its first round, naming it.
    s.write("p.yaml", &pipeline("{adaptive: {logspace: [-3, 3, 7], y: mu_starr, tol: 0.01}}"));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_ne!(code, 0);
    let failed: Vec<String> = r
        .tasks()
        .iter()
        .filter(|t| t["status"] == "failed")
        .map(|t| t["error"].as_str().unwrap_or("").to_string())
        .collect();
    assert_eq!(failed.len(), 1, "{err}");
    assert!(failed[0].contains("`mu_starr`") && failed[0].contains("mu_star"), "{}", failed[0]);
}

/// The curves of a published table, grouped by `group` (or one curve): (x, y) sorted in x.
fn curves(df: &polars::prelude::DataFrame, group: Option<&str>, x: &str, y: &str) -> Vec<(f64, Vec<(f64, f64)>)> {
    let (xs, ys) = (column(df, x), column(df, y));
    let gs = group.map_or(vec![0.0; xs.len()], |g| column(df, g));
    let mut keys: Vec<f64> = gs.clone();
    keys.sort_by(f64::total_cmp);
    keys.dedup();
    keys.into_iter()
        .map(|k| {
            let mut c: Vec<(f64, f64)> = (0..xs.len()).filter(|&i| gs[i] == k).map(|i| (xs[i], ys[i])).collect();
            c.sort_by(|a, b| a.0.total_cmp(&b.0));
            (k, c)
        })
        .collect()
}

/// The worst distance of the piecewise-linear curves through `sampled` (in log10 x, and in
/// log10 y if `log_y`) from a `reference` computed on a dense grid, relative to each
/// reference curve's largest |y| (in decades if `log_y`).
fn worst_deviation(sampled: &[(f64, Vec<(f64, f64)>)], reference: &[(f64, Vec<(f64, f64)>)], log_y: bool) -> f64 {
    let f = |y: f64| if log_y { y.abs().log10() } else { y };
    let mut worst: f64 = 0.0;
    for ((k, s), (kr, r)) in sampled.iter().zip(reference) {
        assert_eq!(k, kr);
        let (xs, ys): (Vec<f64>, Vec<f64>) = s.iter().map(|&(x, y)| (x, f(y))).unzip();
        let scale = if log_y { 1.0 } else { r.iter().map(|p| p.1.abs()).fold(0.0, f64::max) };
        for &(x, y) in r {
            worst = worst.max((interpolate(&xs, &ys, x) - f(y)).abs() / scale);
        }
    }
    worst
}

/// Runs one stage of the committed thesis pipeline (and nothing else) in a scratch directory.
fn thesis_stage(s: &Scratch, stage: &str) -> polars::prelude::DataFrame {
    let yaml = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/pipelines/thesis.yaml")).unwrap();
    s.write("pipelines/thesis.yaml", &yaml);
    let (code, err, _) = s.run("pipelines/thesis.yaml", &["--target", stage]);
    assert_eq!(code, 0, "{err}");
    s.table(stage)
}

/// The curves of `kind` with `params` on a uniform grid of `n` speeds V0 over 10^from..10^to,
/// grouped by `group`, y = `y` (the dense references and the grids the thesis replaced).
fn uniform_curves(
    kind: &str,
    params: &str,
    group: &str,
    y: &str,
    (from, to): (i32, i32),
    n: usize,
) -> Vec<(f64, Vec<(f64, f64)>)> {
    let r = Scratch::new(&format!("adaptive-uniform-{kind}-{n}"));
    r.run_pipeline(&format!(
        "stages:\n  - name: u\n    kind: {kind}\n    params: {{{params}, V0: {{logspace: [{from}, {to}, {n}]}}}}\n"
    ));
    curves(&r.table("u"), Some(group), "V0", y)
}

/// Persson's curves of Fig. 7.3 (`persson`, adaptive from 13 points over the range shown):
/// fewer points than two uniform grids and more accurate than the one of the same size,
/// against 385 points per curve. Measured: 256 points within 0.21 % of each peak; uniform
/// 49 per curve (245) 0.81 %, 97 per curve (485) 0.21 %.
#[test]
fn the_thesis_persson_curves_beat_a_uniform_grid_of_their_size() {
    let s = Scratch::new("adaptive-thesis-persson");
    let adaptive = thesis_stage(&s, "persson");
    let grid =
        |n: usize| uniform_curves("theory.persson", "inv_k: [1.1, 2, 10, 100, 1000]", "inv_k", "mu_star", (-3, 3), n);
    let reference = grid(385);
    let sampled = curves(&adaptive, Some("inv_k"), "V0", "mu_star");
    let n = adaptive.height();
    let (e_adaptive, e_49, e_97) = (
        worst_deviation(&sampled, &reference, false),
        worst_deviation(&grid(49), &reference, false),
        worst_deviation(&grid(97), &reference, false),
    );
    assert!((5 * 40..5 * 60).contains(&n), "{n} points");
    assert!(e_adaptive < 0.003, "{e_adaptive}");
    assert!(e_adaptive < 0.5 * e_49, "{e_adaptive} vs {e_49} with 49 per curve");
    assert!(e_adaptive < 1.2 * e_97 && n < 5 * 97 * 6 / 10, "{e_adaptive} vs {e_97} with 97 per curve");
}

/// The SLS curves of Fig. 5.9b-c (`rolling_sls_wide`, BEM, adaptive in log-log from one point
/// per decade): as accurate as a uniform grid of more than twice as many points, against
/// 161 per curve. Measured: 62 points within 0.0072 decades; uniform 41 per curve (82)
/// 0.026 decades, 81 per curve (162) 0.0072.
#[test]
fn the_thesis_sls_rolling_curves_match_a_grid_twice_their_size() {
    let s = Scratch::new("adaptive-thesis-sls");
    let adaptive = thesis_stage(&s, "rolling_sls_wide");
    assert!(column(&adaptive, "converged").iter().all(|&c| c == 1.0));
    let grid = |n: usize| uniform_curves("bem.sweep", "lambda: [1, 3], W: 0.1, k: 0.001", "lambda", "F_T", (-4, 6), n);
    let reference = grid(161);
    let n = adaptive.height();
    let e_adaptive = worst_deviation(&curves(&adaptive, Some("lambda"), "V0", "F_T"), &reference, true);
    let (e_41, e_81) = (worst_deviation(&grid(41), &reference, true), worst_deviation(&grid(81), &reference, true));
    assert!((2 * 25..2 * 40).contains(&n), "{n} points");
    assert!(e_adaptive < 0.01, "{e_adaptive} decades");
    assert!(e_adaptive < 0.5 * e_41, "{e_adaptive} vs {e_41} with 41 per curve");
    assert!(e_adaptive < 1.2 * e_81 && n < 81, "{e_adaptive} vs {e_81} with 81 per curve");
}
