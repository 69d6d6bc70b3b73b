//! The stress grid at reduced size (the full grid is pipelines/stress.yaml, run by
//! `make bench`): the extremes of every solver either converge or are recorded as not
//! converged with their residual and iterations; no task fails, no NaN or infinity reaches
//! a table (the executor rejects such outputs), and the summary says what converged.

use crate::common;
use common::{column, Scratch};

const GRID: &str = r#"stages:
  - name: stress_speed
    kind: bem.sweep
    params: {lambda: 1, W: 1, k: 0.1, V0: {logspace: [-6, 6, 7]}}
  - name: stress_lambda
    kind: bem.sweep
    params: {lambda: [0.01, 10], W: 1, k: 0.1, V0: 1}
  - name: stress_k
    kind: bem.sweep
    params: {lambda: 1, W: 1, k: [0.0001, 0.99], V0: [0.01, 100]}
  - name: stress_pulloff
    kind: bem.sweep
    params: {lambda: 3, W: [-1, -1.9], k: 0.1, V0: 0.001}
  - name: stress_persson
    kind: theory.persson
    params: {inv_k: [1.0101010101, 10000], V0: {logspace: [-6, 6, 7]}}
  - name: stress_persson_brener
    kind: theory.persson_brener
    params: {k: [0.0001, 0.99], V_PB: {logspace: [-6, 6, 4]}}
  - name: stress_shell
    kind: fem.buckling
    params: {h_over_R: [0.01, 0.4], dissipation: false, model: {n_meridian: 60, n_thickness: 3}}
  - name: stress_summary
    kind: bench.summary
    needs: [stress_speed, stress_lambda, stress_k, stress_pulloff, stress_persson, stress_persson_brener, stress_shell]
    params: {stages: [stress_speed, stress_lambda, stress_k, stress_pulloff, stress_persson, stress_persson_brener, stress_shell]}
"#;

fn bools(df: &polars::prelude::DataFrame, name: &str) -> Vec<bool> {
    column(df, name).iter().map(|&x| x != 0.0).collect()
}

#[test]
fn the_reduced_stress_grid_converges_or_says_so() {
    let s = Scratch::new("stress");
    s.write("p.yaml", GRID);
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "no task fails, even where a point does not converge: {err}");
    assert_eq!(r.count(None, "failed"), 0);
    // Twelve decades of speed, the lambda and k extremes: all converged, mu* > 0.
    for stage in ["stress_speed", "stress_lambda", "stress_k"] {
        let t = s.table(stage);
        assert!(bools(&t, "converged").iter().all(|&c| c), "{stage}");
        assert!(column(&t, "mu_star").iter().all(|&m| m > 0.0), "{stage}: friction is positive");
        assert!(column(&t, "residual").iter().all(|&r| r < 1e-6), "{stage}");
    }
    // mu* vanishes at both ends of the speed range (elastic limits), peaks between.
    let mu = column(&s.table("stress_speed"), "mu_star");
    let peak = mu.iter().cloned().fold(0.0, f64::max);
    assert!(mu[0] < 0.05 * peak && mu[6] < 0.05 * peak, "{mu:?}");
    // Nearly relaxed (V0 = 1e-3): below pull-off converged; beyond (W = -1.9 < -1.744, the
    // JKR pull-off) a record. (At V0 = 1 viscoelasticity carries W = -2.5.)
    let t = s.table("stress_pulloff");
    assert_eq!(bools(&t, "converged"), vec![true, false]);
    assert!(column(&t, "iterations")[1] > 0.0);
    // Theories: finite everywhere, Persson's friction non-negative.
    assert!(column(&s.table("stress_persson"), "mu_star").iter().all(|&m| m >= 0.0));
    // Shells: the thin one snaps, the thick one does not, both cycles converged.
    let t = s.table("stress_shell");
    assert_eq!(bools(&t, "buckled"), vec![true, false]);
    // The summary: one row per stage, converged + not converged = points.
    let sum = s.table("stress_summary");
    let (points, ok, not) = (column(&sum, "points"), column(&sum, "converged"), column(&sum, "not_converged"));
    assert_eq!(points, vec![7.0, 2.0, 4.0, 2.0, 14.0, 8.0, 2.0]);
    assert_eq!(not, vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    assert!(points.iter().zip(&ok).zip(&not).all(|((p, o), n)| p == &(o + n)));
}
