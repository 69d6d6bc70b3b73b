//! The Chapter 3 stages end to end: `fem.indent` (load-unload cycle) and `fem.profile`
//! (Fig. 3.3 states) on a coarse mesh of the thesis shell (R = 15, h = 1, E = 1.3).

mod common;
use common::{column, Scratch};

const SHELL: &str = "{R: 15, h: 1, n_meridian: 60, n_thickness: 3, grading: 8}";

#[test]
fn the_cycle_and_the_three_regimes_reach_the_tables() {
    let s = Scratch::new("shell-stages");
    s.run_pipeline(&format!(
        "stages:
  - name: cycle
    kind: fem.indent
    params: {{shell: {SHELL}, delta_max: 0.3, steps: 30}}
  - name: states
    kind: fem.profile
    params:
      cycle: {{shell: {SHELL}, delta_max: 0.3, steps: 30}}
      points:
        - {{label: I, delta: 0.01}}
        - {{label: II, delta: 0.15}}
        - {{label: III, delta: 0.25}}
"
    ));
    let t = s.table("cycle");
    let f = column(&t, "F_bar");
    let leg = column(&t, "leg_id");
    assert!(f.iter().all(|v| v.is_finite()));
    // Snap-through at delta/R = 0.194 from F R/(E h^3) = 9.29 (the unit tests' numbers),
    // snap-back at 0.1735; all three legs present; every state converged.
    assert!((column(&t, "F_buckling_bar")[0] - 9.29).abs() < 0.1);
    assert!((column(&t, "delta_snap_back_over_R")[0] - 0.1735).abs() < 1e-3);
    for id in [0.0, 1.0, 2.0] {
        assert!(leg.iter().filter(|&&l| l == id).count() > 5, "leg {id}");
    }
    let w = column(&t, "W_bar")[0];
    assert!(w > 0.015 && w < 0.03, "{w}");

    let p = s.table("states");
    let (pt, surf, r, pres, z) = (
        column(&p, "point"),
        column(&p, "surface_id"),
        column(&p, "r_over_R"),
        column(&p, "p_over_E"),
        column(&p, "z_over_R"),
    );
    let touching = |k: f64| -> Vec<f64> {
        (0..pt.len()).filter(|&i| pt[i] == k && surf[i] == 0.0 && pres[i] > 0.0).map(|i| r[i]).collect()
    };
    // I: a small disk at the apex; II: a wide disk from the axis; III: a ring, the apex
    // pulled in below the plate (the inverted cap).
    let (one, two, three) = (touching(0.0), touching(1.0), touching(2.0));
    assert!(one[0] == 0.0 && one.iter().copied().fold(0.0, f64::max) < 0.06);
    assert!(two[0] == 0.0 && two.iter().copied().fold(0.0, f64::max) > 0.3);
    assert!(three.iter().copied().fold(1.0, f64::min) > 0.4, "{three:?}");
    let apex_iii = (0..pt.len()).find(|&i| pt[i] == 2.0 && surf[i] == 0.0).unwrap();
    assert!(z[apex_iii] < (16.0 / 15.0) - 0.25 - 2.0 / 15.0, "apex at z/R = {}", z[apex_iii]);
    // The inner surface lies one thickness inside the outer one at the apex.
    let inner_apex = (0..pt.len()).find(|&i| pt[i] == 0.0 && surf[i] == 1.0).unwrap();
    let outer_apex = (0..pt.len()).find(|&i| pt[i] == 0.0 && surf[i] == 0.0).unwrap();
    assert!((z[outer_apex] - z[inner_apex] - 1.0 / 15.0).abs() < 0.01 / 15.0);
}

#[test]
fn a_profile_point_outside_the_cycle_names_its_field() {
    let s = Scratch::new("shell-profile-bad");
    s.write(
        "p.yaml",
        "stages:\n  - name: states\n    kind: fem.profile\n    params:\n      cycle: {shell: {R: 15, h: 20}, delta_max: 0.3, steps: 3}\n      points: [{label: I, delta: 0.5}]\n",
    );
    let out = s.repro(&["run", "p.yaml", "-q"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("p.yaml:") && err.contains("points[0].delta") && err.contains("cycle.shell.h"), "{err}");
}
