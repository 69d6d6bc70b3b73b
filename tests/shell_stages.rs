//! The Chapter 3 stages end to end: `fem.indent` (load-unload cycle) and `fem.profile`
//! (Fig. 3.3 states) on a coarse mesh of the thesis shell (R = 15, h = 1, E = 1.3).

use crate::common;
use common::{column, strings, Scratch};

const SHELL: &str = "{R: 15, h: 1, n_meridian: 60, n_thickness: 3, grading: 8}";

#[test]
fn the_cycle_and_the_three_regimes_reach_the_tables() {
    let s = Scratch::new("shell-stages");
    s.run_pipeline(&format!(
        "stages:
  - name: cycle
    kind: fem.indent
    params: {{shell: {SHELL}, delta_max: 0.3, steps: 30, mesh_study: true}}
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
    // The mesh study (the cycle on 120 elements alongside) against the same cycle on 240
    // (measured: F_buckling 9.338, W_bar 0.02477; F at delta/R = 0.05 and 0.19 on
    // the loading leg 1.659493 and 9.000983). Here F_buckling is 9.289 +- 0.147 and W_bar
    // 0.0230 +- 0.0103: the estimates cover the errors, without being vacuous.
    assert_eq!(strings(&t, "mesh_error_source")[0], "study");
    assert_eq!(column(&t, "mesh_study_agrees")[0], 1.0);
    assert_eq!(column(&t, "n_meridian")[0], 60.0);
    let (fb, fe, fm) = (
        column(&t, "F_buckling_bar")[0],
        column(&t, "F_buckling_error_bar")[0],
        column(&t, "F_buckling_mesh_error_bar")[0],
    );
    assert!(fm > 0.0 && fe > fm && (fb - 9.338).abs() <= fe && fe < 0.05 * fb, "F_buckling {fb} +- {fe}");
    let (we, wm) = (column(&t, "W_error_bar")[0], column(&t, "W_mesh_error_bar")[0]);
    assert!(wm > 0.0 && we > wm && (w - 0.02477).abs() <= we && we < w, "W {w} +- {we}");
    let (delta, fe_row) = (column(&t, "delta_over_R"), column(&t, "F_error_bar"));
    assert!(fe_row.iter().all(|e| e.is_finite() && *e >= 0.0));
    for (at, reference) in [(0.05, 1.659493), (0.19, 9.000983)] {
        let i = (0..f.len()).find(|&i| leg[i] == 0.0 && (delta[i] - at).abs() < 1e-9).unwrap();
        assert!(
            fe_row[i] > 0.0 && (f[i] - reference).abs() <= fe_row[i] && fe_row[i] < 0.01 * f[i],
            "F({at}) {} +- {}",
            f[i],
            fe_row[i]
        );
    }

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

/// A coarse, short map model: the shell of h/R = 0.06 snaps by delta/R = 0.3 without
/// adhesion.
const MAP_MODEL: &str = "{n_meridian: 60, n_thickness: 3, grading: 8, delta_max: 0.3, steps: 30, bisections: 4}";

#[test]
fn the_buckling_map_stages_reach_their_tables() {
    // fem.buckling over mu (friction raises F_buckling), fem.gamma_c at one (h/R, mu) with
    // its bracket, and the map stage that joins them with a buckling limit. Each point is a
    // task: its parameters are columns of the table.
    let s = Scratch::new("shell-map");
    s.run_pipeline(&format!(
        "stages:
  - name: b
    kind: fem.buckling
    params: {{h_over_R: 0.06, mu: [0, 0.5], dissipation: false, model: {MAP_MODEL}}}
  - name: gc
    kind: fem.gamma_c
    params: {{h_over_R: 0.06, mu: 0, guess: 0.008, rel_tol: 0.3, model: {MAP_MODEL}}}
  - name: lim
    kind: fem.buckling_limit
    params: {{mu: 0, h_lo: 0.06, h_hi: 0.2, tol: 0.02, model: {MAP_MODEL}}}
  - name: map
    kind: fem.gamma_c_map
    needs: [gc, lim]
    params: {{gamma_c: gc, limit: lim}}
"
    ));
    let b = s.table("b");
    let (mu, fb, buckled) = (column(&b, "mu"), column(&b, "F_buckling_bar"), column(&b, "buckled"));
    assert_eq!(mu, vec![0.0, 0.5]);
    assert!(buckled.iter().all(|&x| x == 1.0) && fb[1] > 1.1 * fb[0], "{fb:?}");
    let g = s.table("gc");
    let (lo, hi, mid) =
        (column(&g, "gamma_lo_over_Eh")[0], column(&g, "gamma_hi_over_Eh")[0], column(&g, "gamma_c_over_Eh")[0]);
    // On this mesh the answer is not monotonic in gamma near the threshold: this bracket
    // (starting at 0.008) closes on [0.0067, 0.0080] (0.008 does not snap), the unit test's
    // (starting at 0.003) on [0.0085, 0.0101] (0.0085 does); a 10% bracket gave [0.0095,
    // 0.0104]. The bounds cover that window of about 1.5 and no factor of 2.
    assert!(lo < mid && mid < hi && hi / lo - 1.0 <= 0.3 && lo > 0.006 && hi < 0.0125, "{lo} {mid} {hi}");
    assert_eq!(column(&g, "found")[0], 1.0);
    assert!((column(&g, "error_estimate")[0] - 0.5 * (hi - lo)).abs() < 1e-12 * hi);
    let r = column(&g, "r_over_R")[0];
    assert!(r > 0.3 && r < 0.9 && (column(&g, "eq3_7_over_Eh")[0] - r.powi(4)).abs() < 1e-12);
    // The thickness above which nothing snaps, bisected to 0.02 in h/R from [0.06, 0.2]:
    // its error estimate is the half-bracket.
    let l = s.table("lim");
    let (hl, lo, hi, err) = (
        column(&l, "h_limit_over_R")[0],
        column(&l, "h_lo_over_R")[0],
        column(&l, "h_hi_over_R")[0],
        column(&l, "error_estimate")[0],
    );
    assert_eq!(column(&l, "found")[0], 1.0);
    assert!(lo < hl && hl < hi && hi - lo <= 0.02 && (err - 0.5 * (hi - lo)).abs() < 1e-15, "{lo} {hl} {hi} {err}");
    // The map: the gamma_c point (h/R exact) and the limit row closing the curve at gamma 0,
    // with the limit's half-bracket as the error of h/R.
    let m = s.table("map");
    assert_eq!(column(&m, "gamma_c_over_Eh"), vec![mid, 0.0]);
    assert_eq!(column(&m, "h_over_R"), vec![0.06, hl]);
    assert_eq!(column(&m, "h_error_over_R"), vec![0.0, err]);
}

#[test]
fn the_mesh_study_covers_the_error_of_a_coarse_mesh() {
    // fem.buckling with `mesh_study` on 60 elements (grading 8, 3 through the thickness,
    // steps of 0.01 R), mu = 0, no adhesion: the cycle on 120 runs alongside. On this mesh
    // F_bar is 9.314 and W 0.0206 N mm; the 480-element cycle gives 9.304 and 0.0200, and
    // the sequence 30 ... 480 (9.107, 9.314, 9.352, 9.258, 9.304) scatters by about +-0.05
    // about 9.29 (measured). The estimate covers that and is not vacuous.
    let s = Scratch::new("shell-mesh-study");
    s.run_pipeline(&format!(
        "stages:
  - name: b
    kind: fem.buckling
    params: {{h_over_R: 0.06, mesh_study: true, model: {MAP_MODEL}}}
"
    ));
    let t = s.table("b");
    let one = |c: &str| column(&t, c)[0];
    assert_eq!(one("n_meridian"), 60.0);
    assert_eq!(one("mesh_study_agrees"), 1.0);
    let (f, fe, fm) = (one("F_buckling_bar"), one("F_buckling_error_bar"), one("F_buckling_mesh_error_bar"));
    assert!((f - 9.314).abs() < 0.01, "F_bar {f}");
    assert!(fm > 0.0 && fe > fm, "{fe} {fm}");
    assert!((f - 9.304).abs() + 0.05 <= fe && fe < 0.03 * f, "F {f} +- {fe}");
    let (w, we, wm) = (one("W_Nmm"), one("W_error_Nmm"), one("W_mesh_error_Nmm"));
    assert!(wm > 0.0 && we > wm && (w - 0.0200).abs() <= we && we < 0.5 * w, "W {w} +- {we} (mesh {wm})");
    assert_eq!(strings(&t, "mesh_error_source"), vec!["study"]);
    // Without friction none of W is done against it.
    assert_eq!(one("W_friction_Nmm"), 0.0);
}

#[test]
fn a_bad_map_model_field_names_its_path() {
    let s = Scratch::new("shell-map-bad");
    s.write(
        "p.yaml",
        "stages:\n  - name: gc\n    kind: fem.gamma_c\n    params: {h_over_R: 0.7, growth: 1, model: {R: -1}}\n",
    );
    let out = s.repro(&["run", "p.yaml", "-q"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("p.yaml:") && err.contains("model.R") && err.contains("h_over_R") && err.contains("growth"),
        "{err}"
    );
}

#[test]
fn the_default_mesh_gives_the_converged_adhesive_snap() {
    // Fig. 3.2's adhesive case (R = 15, h = 1, gamma = 1e-3 N/mm, mu = 0) on the default mesh
    // (1.5 (R + h) / g0 = 240 x 2). Reference: the mesh convergence study (`make bench`, the FEM
    // candidates of pipelines/bench.yaml): F R/(E h^3) = 7.873 at 480 x 4 (70 steps, 8 bisections), 7.86-7.87 from 240
    // elements on; the unresolved 100 x 4 gave 10.6, the adhesionless snap is at 9.36. The
    // thesis reads ~7.5.
    let s = Scratch::new("shell-default-mesh");
    s.run_pipeline(
        "stages:
  - name: b
    kind: fem.buckling
    params: {h_over_R: 0.0666666666667, gamma_over_Eh: 0.00077, dissipation: false}
",
    );
    let t = s.table("b");
    let (f, d) = (column(&t, "F_buckling_bar")[0], column(&t, "delta_buckling_over_R")[0]);
    assert!((f / 7.873 - 1.0).abs() < 0.01, "F_buckling_bar {f}");
    assert!((d - 0.1885).abs() < 0.002, "delta_b/R {d}");
    // The error estimates cover the actual error against the reference without being
    // vacuous: bisection bracket plus the default mesh's 0.5 %, of order 1 %, not 10 %.
    let (fe, de) = (column(&t, "F_buckling_error_bar")[0], column(&t, "delta_buckling_error_over_R")[0]);
    assert!((f - 7.873).abs() <= fe && fe < 0.02 * f, "F {f} +- {fe}");
    assert!(de > 0.0 && de <= 0.35 / 35.0 / 32.0 * 1.0001, "delta bracket {de}");
}

#[test]
fn the_landing_criterion_counts_only_the_drops_an_experiment_sees() {
    // h/R = 0.06 on the default mesh, mu = 0, to delta/R = 0.25. gamma/(E h) = 1e-3: the
    // stability test gives up the flattened state at delta/R = 0.1916 and the drop comes at
    // 0.21 (measured), so both criteria see a snap, with the same F_buckling. 2e-2: the
    // stability test gives up a state before 0.25 (at delta/R 0.2156 with the band solver;
    // at 3e-4, the marginal "start instability" of the gamma_c map, with a sparse LU: where
    // it fails depends on rounding), but no inverted state is
    // reachable before 0.25: a snap under `instability`, none under `landing`.
    let s = Scratch::new("shell-landing");
    s.run_pipeline(
        "stages:
  - name: inst
    kind: fem.buckling
    params: {h_over_R: 0.06, gamma_over_Eh: [0.001, 0.02], dissipation: false, model: {delta_max: 0.25, steps: 25}}
  - name: land
    kind: fem.buckling
    params: {h_over_R: 0.06, gamma_over_Eh: [0.001, 0.02], dissipation: false, model: {delta_max: 0.25, steps: 25, snap: landing}}
",
    );
    let (inst, land) = (s.table("inst"), s.table("land"));
    let col = |t, c| column(t, c);
    assert_eq!(col(&inst, "gamma_over_Eh"), vec![0.001, 0.02]);
    assert_eq!(col(&land, "gamma_over_Eh"), vec![0.001, 0.02]);
    let buckled = |t| col(t, "F_buckling_bar").iter().map(|&f| f != 0.0).collect::<Vec<_>>();
    assert_eq!(buckled(&inst), vec![true, true]);
    assert_eq!(buckled(&land), vec![true, false]);
    assert_eq!(col(&inst, "F_buckling_bar")[0], col(&land, "F_buckling_bar")[0]);
    assert!(col(&inst, "delta_buckling_over_R")[1] > 0.0 && col(&inst, "delta_buckling_over_R")[1] < 0.25);
    // Stopped at the instability, the first never looked for a landing; the second found it.
    assert_eq!(col(&inst, "delta_landing_over_R")[0], 0.0);
    let landing = col(&land, "delta_landing_over_R")[0];
    assert!((landing - 0.21).abs() < 0.006, "landing at delta/R {landing}");
}

#[test]
fn the_frictional_unloadings_of_fig_3_8_reach_zero() {
    // Fig. 3.8's rough and moderate shells (`exp_rough`, `exp_moderate` of
    // pipelines/thesis.yaml: R = 25, h = 0.9, gamma 0.11e-3 and 0.145e-3 N/mm, mu 0.75 and
    // 1) pressed to delta/R = 0.35 without a snap and unloaded on the flattened branch. Near
    // delta/R 0.22-0.28 the unloading's stick-slip pattern changes and converging steps take
    // 40-57 Newton iterations (measured); a halving walk whose runs stopped at 30 ended one
    // of the two legs there (which one depended on the factorisations' rounding), though
    // the path goes on smoothly to delta = 0.
    let s = Scratch::new("shell-fig38-unloading");
    s.run_pipeline(
        "stages:
  - name: rough
    kind: fem.indent
    params: {shell: {R: 25, h: 0.9, imperfection: {apex_force: 0.05}}, delta_max: 0.35, steps: 35, stability: tangent, gamma: 0.00011, mu: 0.75}
  - name: moderate
    kind: fem.indent
    params: {shell: {R: 25, h: 0.9, imperfection: {apex_force: 0.05}}, delta_max: 0.35, steps: 35, stability: tangent, gamma: 0.000145, mu: 1}
",
    );
    for stage in ["rough", "moderate"] {
        let t = s.table(stage);
        let (leg, delta, converged) = (column(&t, "leg_id"), column(&t, "delta_over_R"), column(&t, "converged"));
        assert_eq!(column(&t, "complete")[0], 1.0, "{stage}: the cycle is incomplete");
        let unloading: Vec<usize> = (0..leg.len()).filter(|&i| leg[i] == 1.0).collect();
        assert!(unloading.iter().all(|&i| converged[i] == 1.0), "{stage}: an unloading state did not converge");
        // Down through every loading displacement, 0.35 to 0 in steps of 0.01.
        assert!(unloading.len() >= 36, "{stage}: {} unloading states", unloading.len());
        assert!(delta[*unloading.last().unwrap()].abs() < 1e-12, "{stage}: the unloading ends above delta = 0");
    }
}
