//! A BEM sweep started from states of another stage (`bem.sweep`'s `start`, read row by row):
//! the same mu* as from scratch, for fewer Newton iterations, and the start each point used.

use crate::common;
use common::{column, rejected, Scratch};

const PIPELINE: &str = r#"stages:
  - name: starts
    kind: bem.profile
    publish: false
    params: {lambda: 1, W: 1, k: 0.1, V0: [0.1, 10]}
  - name: scratch
    kind: bem.sweep
    params: {lambda: [1, 2], W: 1, k: 0.1, V0: [0.003, 0.3, 1, 30]}
  - name: started
    kind: bem.sweep
    needs: [{stage: starts, match: [lambda, W, k]}]
    params: {lambda: [1, 2], W: 1, k: 0.1, V0: [0.003, 0.3, 1, 30], start: starts}
  - name: other_material
    kind: bem.sweep
    needs: [{stage: starts, match: [lambda, W, k]}]
    params: {lambda: 1, W: 1, k: 0.1, V0: 0.3, s: 0.25, start: starts}
"#;

#[test]
fn a_started_sweep_gives_the_same_friction_for_fewer_iterations() {
    let s = Scratch::new("bem-starts");
    s.write("p.yaml", PIPELINE);
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    // lambda = 2 matches no start: a warning, and those points are solved from scratch.
    assert!(err.contains("4 of its 8 points match no point of `starts`"), "{err}");
    let (a, b) = (s.table("scratch"), s.table("started"));
    let (mu_a, mu_b) = (column(&a, "mu_star"), column(&b, "mu_star"));
    let (est, it_a, it_b) = (column(&b, "error_estimate"), column(&a, "iterations"), column(&b, "iterations"));
    // The nearest start in log V0 (V0 = 1 lies as near to 0.1 as to 10: the lower).
    assert_eq!(column(&b, "start_V0"), vec![0.1, 0.1, 0.1, 10.0, -1.0, -1.0, -1.0, -1.0]);
    for i in 0..4 {
        // Newton's tolerance (1e-9 of H) apart, far inside the error estimate.
        assert!((mu_a[i] - mu_b[i]).abs() <= 1e-6 * est[i], "V0 point {i}: {} vs {}", mu_a[i], mu_b[i]);
        assert!(it_b[i] < 0.6 * it_a[i], "V0 point {i}: {} iterations started, {} from scratch", it_b[i], it_a[i]);
    }
    for i in 4..8 {
        // No start: the very solve from scratch.
        assert_eq!(mu_a[i], mu_b[i]);
        assert_eq!(it_a[i], it_b[i]);
    }
    assert_eq!(column(&a, "n"), column(&b, "n"), "the same meshes");
    // The starts are of the standard linear solid: a power-law material matches none of them.
    assert_eq!(column(&s.table("other_material"), "start_V0"), vec![-1.0]);
    // Starts for lambda = 2 too: only the points that match them are recomputed.
    let yaml = PIPELINE.replace(
        "params: {lambda: 1, W: 1, k: 0.1, V0: [0.1, 10]}",
        "params: {lambda: [1, 2], W: 1, k: 0.1, V0: [0.1, 10]}",
    );
    s.write("p.yaml", &yaml);
    let (code, err, r2) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r2.count(Some("starts"), "computed"), 2);
    assert_eq!(r2.count(Some("started"), "computed"), 4, "only the lambda = 2 points");
    assert_eq!(r2.count(Some("scratch"), "computed"), 0);
    assert!(column(&s.table("started"), "start_V0")[4..].iter().all(|&v| v == 0.1 || v == 10.0));
}

#[test]
fn a_start_needs_the_refinement_and_a_needed_stage() {
    let up = "stages:\n  - name: starts\n    kind: bem.profile\n    params: {lambda: 1, W: 1, k: 0.1, V0: 1}\n";
    for (name, stage, expected) in [
        (
            "bem-start-fixed-n",
            "  - name: a\n    kind: bem.sweep\n    needs: [starts]\n    params: {lambda: 1, W: 1, k: 0.1, V0: 2, n: 200, start: starts}\n",
            "p.yaml:8:61: error: stage `a` (bem.sweep): parameter `start`: starts the refinement's first mesh: not with a fixed `n`",
        ),
        (
            "bem-start-not-needed",
            "  - name: a\n    kind: bem.sweep\n    params: {lambda: 1, W: 1, k: 0.1, V0: 2, start: starts}\n",
            "`start` refers to stage `starts`, which is not in its `needs`",
        ),
    ] {
        let err = rejected(name, &format!("{up}{stage}"));
        assert!(err.contains(expected), "{err}");
    }
}
