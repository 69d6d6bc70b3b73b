//! Property-based stress tests (proptest, bounded cases) over the admissible parameter
//! space of each solver and theory: no NaN or infinity, a converged result or an explicit
//! non-converged record, continuity in the parameters where the physics is continuous, and
//! invariants (friction >= 0, load balance, symmetric pressure in the elastic limits,
//! Maugis-Dugdale between DMT and JKR).

use proptest::prelude::*;
use repro::bem::solver::{solve, Mesh, Params};
use repro::theory::{classical, persson, persson_brener};

/// A fixed seed: CI runs the same cases every time (change it, or set PROPTEST_CASES, to
/// explore further; failures found that way are kept as comments in the tests).
fn cfg(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20261122),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(cfg(200))]

    /// Persson's adhesionless friction (Appendix A) for k in [1e-4, 0.99] and twelve
    /// decades of speed: finite, non-negative, bounded by its maximum over speed, and
    /// continuous (a 0.1 % change of V0 changes mu* by well under 1 %).
    #[test]
    fn persson_friction_is_finite_positive_and_continuous(lk in -4.0f64..-0.0044, lv in -6.0f64..6.0) {
        let (k, v0) = (10f64.powf(lk), 10f64.powf(lv));
        let f = persson::mu_star(k, v0, 1e-6);
        prop_assert!(f.mu_star.is_finite() && f.mu_star >= 0.0 && f.error_estimate.is_finite());
        let g = persson::mu_star(k, v0 * 1.001, 1e-6);
        prop_assert!((g.mu_star - f.mu_star).abs() <= 1e-2 * f.mu_star.max(1e-12) + 1e-9, "{} {}", f.mu_star, g.mu_star);
    }

    /// Persson-Brener (Eq. 5.13): f_T >= 0 for every k and speed, and monotone in speed.
    #[test]
    fn persson_brener_friction_is_finite_positive_and_monotone(lk in -4.0f64..-0.0044, lu in -6.0f64..6.0) {
        let (k, u) = (10f64.powf(lk), 10f64.powf(lu));
        let f = persson_brener::friction(u, k);
        prop_assert!(f.is_finite() && f >= 0.0, "{f}");
        prop_assert!(persson_brener::friction(u * 1.01, k) >= f * (1.0 - 1e-12));
    }

    /// Maugis-Dugdale (sphere): a solution for every contact radius and lambda; adhesion
    /// lowers the load at a given radius (P < A^3, Hertz); at lambda -> 0 it is DMT.
    /// (Not an invariant: P_MD >= P_DMT. At A = 0.3546, lambda = 0.0127 the MD load is
    /// -1.95787, below DMT's -1.95542; proptest found it and a 40-digit mpmath solution of
    /// the same equations confirms it.)
    #[test]
    fn maugis_dugdale_is_below_hertz_and_tends_to_dmt(la in -2.0f64..1.0, ll in -2.0f64..1.5) {
        let (a, lambda) = (10f64.powf(la), 10f64.powf(ll));
        let m = classical::maugis_dugdale(a, lambda).expect("a solution for every a, lambda > 0");
        prop_assert!(m.load.is_finite() && m.approach.is_finite() && m.m >= 1.0);
        prop_assert!(m.load < classical::hertz_load(a), "P_MD = {} at A = {a}, lambda = {lambda}", m.load);
        // The adhesive force A^3 - P tends to DMT's 2 as lambda A -> 0.
        let small = classical::maugis_dugdale(a, 1e-7).unwrap();
        let force = classical::hertz_load(a) - small.load;
        prop_assert!((force - 2.0).abs() < 1e-3, "adhesive force {force} at A = {a}, lambda = 1e-7 (DMT: 2)");
    }
}

proptest! {
    #![proptest_config(cfg(60))]

    /// The theories' error bounds (`numerics::roots::bisect_root`) over their whole
    /// admissible range: finite, positive and small everywhere (Maugis-Dugdale for A in
    /// [1e-4, 10] and lambda in [1e-3, 1e3]; Persson-Brener for k in [1e-4, 0.99] and u in
    /// [1e-6, 1e12]).
    #[test]
    fn theory_error_bounds_are_finite_and_small(la in -4.0f64..1.0, ll in -3.0f64..3.0, lk in -4.0f64..-0.0044, lu in -6.0f64..12.0) {
        let (a, lambda) = (10f64.powf(la), 10f64.powf(ll));
        let m = classical::maugis_dugdale(a, lambda).unwrap();
        let scale = a.powi(3) + (a.powi(3) - m.load).abs();
        prop_assert!(m.load_error > 0.0 && m.load_error < 1e-10 * scale, "A {a}, lambda {lambda}: {m:?}");
        let (k, u) = (10f64.powf(lk), 10f64.powf(lu));
        let (f, e) = persson_brener::friction_spectrum_bounded(u, k, &repro::rheology::Spectrum::sls());
        prop_assert!(f.is_finite() && e > 0.0 && e < 1e-9 * (1.0 + f), "k {k}, u {u}: {f} +- {e}");
    }

    /// Pull-offs (sphere and line contact) for lambda in [1e-3, 1e3]: between their DMT-like
    /// and JKR limits, continuous in lambda (a 1 % change moves them by under 1 %), with a
    /// finite bound, and never on the searched range's end (the line contact's A -> 0 limit
    /// is radius 0).
    #[test]
    fn pull_offs_lie_between_their_limits_and_are_continuous(ll in -3.0f64..3.0) {
        use repro::theory::line_contact::{maugis_dugdale_line_pull_off, zero_width_limit};
        let lambda = 10f64.powf(ll);
        let s = classical::maugis_pull_off(lambda).unwrap();
        prop_assert!(s.load >= classical::DMT_PULL_OFF - 1e-9 && s.load <= classical::JKR_PULL_OFF + 1e-9, "{s:?}");
        prop_assert!(s.error.is_finite() && s.error < 1e-10 && s.radius > 1.0001e-4, "{s:?}");
        let s2 = classical::maugis_pull_off(lambda * 1.01).unwrap();
        prop_assert!((s2.load - s.load).abs() < 1e-2 * s.load.abs(), "{s:?} {s2:?}");
        let l = maugis_dugdale_line_pull_off(lambda).unwrap();
        let jkr = repro::theory::line_contact::jkr_pull_off();
        prop_assert!(l.load >= jkr - 1e-9 && l.load <= zero_width_limit(lambda), "{l:?} (JKR {jkr})");
        prop_assert!(l.error.is_finite() && l.error < 1e-10 && (l.radius == 0.0 || l.radius > 1.0001e-6), "{l:?}");
        let l2 = maugis_dugdale_line_pull_off(lambda * 1.01).unwrap();
        prop_assert!((l2.load - l.load).abs() < 1e-2 * l.load.abs(), "{l:?} {l2:?}");
    }
}

proptest! {
    #![proptest_config(cfg(16))]

    /// The BEM (Chapter 4) on a small mesh anywhere in lambda [0.05, 3], W [0.1, 5],
    /// k [0.01, 0.9], V0 [1e-3, 1e3]: converged with the load carried equal to W and
    /// mu* >= 0 (a sliding cylinder is resisted), or an explicit record; never NaN.
    #[test]
    fn bem_points_converge_balance_the_load_and_resist_sliding(
        ll in -1.3f64..0.48, lw in -1.0f64..0.7, lk in -2.0f64..-0.046, lv in -3.0f64..3.0
    ) {
        let p = Params::sls(10f64.powf(ll), 10f64.powf(lw), 10f64.powf(lk), 10f64.powf(lv));
        let s = solve(&p, Mesh { n: 240, half_length: 4.0 });
        let f = s.friction();
        prop_assert!(s.residual.is_finite() || !s.converged());
        if s.converged() {
            prop_assert!(s.p.iter().chain(&s.h).all(|v| v.is_finite()));
            prop_assert!(f.mu_star.is_finite() && f.mu_star >= -1e-9, "mu* = {}", f.mu_star);
            prop_assert!((s.load() - p.w).abs() <= 1e-6 * p.w.abs(), "load {} vs W {}", s.load(), p.w);
        } else {
            prop_assert!(s.cost.iterations > 0);
        }
    }

    /// Elastic limits: at vanishing speed (relaxed) and with k close to 1 (nearly elastic
    /// at every speed) the pressure is symmetric and the friction vanishes.
    #[test]
    fn bem_elastic_limits_are_symmetric(ll in -1.0f64..0.3, lw in -0.5f64..0.5, relaxed in any::<bool>()) {
        let (k, v0) = if relaxed { (0.1, 1e-7) } else { (0.99999, 1.0) };
        let p = Params::sls(10f64.powf(ll), 10f64.powf(lw), k, v0);
        let s = solve(&p, Mesh { n: 240, half_length: 4.0 });
        prop_assert!(s.converged());
        let n = s.p.len();
        let peak = s.p.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let asym = (0..n).map(|i| (s.p[i] - s.p[n - 1 - i]).abs()).fold(0.0, f64::max);
        prop_assert!(asym <= 1e-3 * peak, "asymmetry {asym} of peak {peak}");
        prop_assert!(s.friction().mu_star.abs() <= 2e-3, "mu* = {}", s.friction().mu_star);
    }
}

proptest! {
    #![proptest_config(cfg(6))]

    /// The shell (Chapter 3, adhesionless, frictionless) on a coarse mesh for h/R in
    /// [0.02, 0.3] and E, nu anywhere admissible: every converged state is finite, the plate
    /// force is compressive and balances the reaction at the clamped base (load balance),
    /// and the force grows along the stable part of the path.
    #[test]
    fn shell_states_balance_the_load(h_over_r in 0.02f64..0.3, e in 0.1f64..100.0, nu in 0.0f64..0.49) {
        use repro::fem::contact::Plate;
        use repro::fem::indent::load_path;
        use repro::fem::mesh::ShellMesh;
        use repro::fem::system::{Base, Model};
        let r = 15.0;
        let model = Model::new(ShellMesh::hemisphere(r, h_over_r * r, 40, 2, 3.0), e, nu, Base::Clamped);
        let plate = Plate::new(&model.mesh, e, 1000.0);
        let path = load_path(&model, &plate, e, 0.1 * r, 8, 6);
        prop_assert!(!path.is_empty());
        let mut last_stable = 0.0;
        for s in path.iter().filter(|s| s.converged()) {
            prop_assert!(s.u.iter().all(|v| v.is_finite()) && s.residual.is_finite());
            let f = s.contact.force;
            prop_assert!(f.is_finite() && f >= 0.0, "plate force {f}");
            let (fint, _) = model.assemble(&s.u).unwrap();
            let reaction: f64 = model.mesh.base.iter().map(|&a| fint[2 * a + 1]).sum();
            prop_assert!((f - reaction).abs() <= 1e-6 * f.max(e * (h_over_r * r).powi(2)),
                "plate {f} vs base reaction {reaction} at delta {}", s.delta);
            if s.stable {
                prop_assert!(f >= last_stable * (1.0 - 1e-9), "force fell on a stable step: {f} < {last_stable}");
                last_stable = f;
            }
        }
    }
}

proptest! {
    #![proptest_config(cfg(6))]

    /// Loads at pull-off (Chapter 5): the minimum load along the branch (`branch::pull_off`)
    /// and the stable state at a prescribed tensile load (`branch::descend_to_load`) agree:
    /// 95 % of the pull-off load converges on the branch, 105 % is reported as not converged
    /// with the missing load as its residual. The pull-off is tensile, and relaxed
    /// (V0 -> 0) it is no stronger than JKR's -1.744 (the Lennard-Jones range softens it).
    #[test]
    fn pull_off_and_descent_agree_at_the_pull_off(ll in -0.5f64..0.5, lk in -1.3f64..-0.3) {
        use repro::bem::solver::branch::{descend_to_load, pull_off};
        let p = Params::sls(10f64.powf(ll), 1.0, 10f64.powf(lk), 1e-6);
        // Lambda up to 3.2: above about 2 the descent to 95 % of the pull-off by load control
        // from the interpolated guess fails next to the ripples of the discrete crack front,
        // and is caught by the search along the path (`branch::along_the_path`; the cases it found are
        // `the_descent_reaches_95_percent_of_the_pull_off_at_large_lambda`).
        let start = solve(&p, repro::bem::solver::starting_mesh(&p, 1e-3));
        prop_assert!(start.converged());
        let po = pull_off(&start, 1e-4);
        prop_assert!(po.converged && po.load < 0.0 && po.load.is_finite(), "pull-off {}", po.load);
        prop_assert!(po.load >= repro::theory::line_contact::jkr_pull_off() - 1e-3, "{} beyond JKR", po.load);
        let inside = descend_to_load(&start, 0.95 * po.load);
        prop_assert!(inside.converged() && (inside.load() - 0.95 * po.load).abs() < 1e-6, "{}", inside.load());
        prop_assert_eq!(inside.termination, repro::bem::solver::Termination::Converged);
        let beyond = descend_to_load(&start, 1.05 * po.load);
        prop_assert!(!beyond.converged());
        // Why: past the pull-off the stable branch has no state at that load.
        prop_assert_eq!(beyond.termination, repro::bem::solver::Termination::BeyondPullOff);
        prop_assert!(beyond.residual > 0.0 && beyond.residual.is_finite());
    }
}

/// The two cases proptest found where the descent to 95 % of the pull-off failed though the
/// pull-off search succeeded (lambda above 2, where the discrete crack front makes the
/// branch ripple): lambda = 2.19, k = 0.5 on the production starting mesh, and lambda =
/// 2.63, k = 0.103 on 600 elements. The descent must land on the branch at the prescribed
/// load, and past the pull-off report a not-converged record.
#[test]
fn the_descent_reaches_95_percent_of_the_pull_off_at_large_lambda() {
    use repro::bem::solver::branch::{descend_to_load, pull_off};
    use repro::bem::solver::starting_mesh;
    let cases = [(2.19, 0.5, None), (2.63, 0.103, Some(600))];
    for (lambda, k, n) in cases {
        let p = Params::sls(lambda, 1.0, k, 1e-6);
        let mesh = starting_mesh(&p, 1e-3);
        let mesh = n.map_or(mesh, |n| Mesh { n, ..mesh });
        let start = solve(&p, mesh);
        assert!(start.converged(), "lambda {lambda}: start");
        let po = pull_off(&start, 1e-4);
        assert!(po.converged && po.load < 0.0, "lambda {lambda}: pull-off {}", po.load);
        let inside = descend_to_load(&start, 0.95 * po.load);
        assert!(
            inside.converged() && (inside.load() - 0.95 * po.load).abs() < 1e-6,
            "lambda {lambda}, k {k}: descent to {} ended at {} (converged {}, residual {:e})",
            0.95 * po.load,
            inside.load(),
            inside.converged(),
            inside.residual
        );
        let beyond = descend_to_load(&start, 1.05 * po.load);
        assert!(!beyond.converged() && beyond.residual > 0.0 && beyond.residual.is_finite());
        assert_eq!(beyond.termination, repro::bem::solver::Termination::BeyondPullOff);
    }
}
