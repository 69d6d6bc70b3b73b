//! The maximum over speed of the friction of the Chapter 4 model, for fixed (lambda, W, k)
//! (thesis Section 4.3.5, Figs. 4.6-4.7): a log-spaced bracketing grid over V0, climbed
//! from its middle point (only the grid points uphill of it and their neighbours are
//! solved; mu*(V0) has one maximum, so this is the best grid point of the whole grid),
//! then golden-section search in log V0 between the neighbours of the best grid point, so
//! that only the speeds the search needs are solved. The far ends of the grid are the
//! dearest solves at large lambda (docs/tuning.md).

use super::solver::{Friction, Params, Solution};
use crate::numerics::roots::maximize_climbing;
use std::cell::RefCell;

#[derive(Clone, Copy, Debug)]
pub struct Maximum {
    pub v0: f64,
    pub friction: Friction,
    /// The error estimate of mu* at the maximum (that of the solve nearest to it).
    pub error_estimate: f64,
    /// Number of BEM solves.
    pub evaluations: usize,
    /// Newton iterations summed over the solves.
    pub iterations: usize,
    /// Whether every solve of the search converged.
    pub all_converged: bool,
}

/// One solve of the search.
struct Solve {
    v0: f64,
    friction: Friction,
    converged: bool,
    estimate: f64,
    iterations: usize,
}

/// Searches V0 in [v0_min, v0_max] with `grid` log-spaced points, refining to `tol` in
/// log10 V0; `solve` gives the solution of a point and the error estimate of its mu*,
/// given the converged solve so far nearest in log V0 (a start it may use; the search's
/// order of solves is fixed, so the result is a function of the arguments). Unconverged
/// solves count as -inf (never the maximum) and are reported.
pub fn max_over_speed(
    base: &Params,
    v0_min: f64,
    v0_max: f64,
    grid: usize,
    tol: f64,
    solve: impl Fn(&Params, Option<&Solution>) -> (Solution, f64),
) -> Maximum {
    let log: RefCell<Vec<Solve>> = RefCell::new(Vec::new());
    let solved: RefCell<Vec<Solution>> = RefCell::new(Vec::new());
    let eval = |lv: f64| {
        let v0 = 10f64.powf(lv);
        let (s, estimate) = {
            let solved = solved.borrow();
            let near =
                solved.iter().min_by(|a, b| (a.params.v0 / v0).ln().abs().total_cmp(&(b.params.v0 / v0).ln().abs()));
            solve(&Params { v0, ..base.clone() }, near)
        };
        let f = s.friction();
        log.borrow_mut().push(Solve {
            v0,
            friction: f,
            converged: s.converged(),
            estimate,
            iterations: s.cost.iterations,
        });
        let value = if s.converged() && f.mu_star.is_finite() { f.mu_star } else { f64::NEG_INFINITY };
        if s.converged() {
            solved.borrow_mut().push(s);
        }
        value
    };
    let (lv, _) = maximize_climbing(eval, v0_min.log10(), v0_max.log10(), grid, tol);
    let log = log.into_inner();
    let v0 = 10f64.powf(lv);
    let best =
        log.iter().filter(|e| e.converged).min_by(|a, b| (a.v0 / v0).ln().abs().total_cmp(&(b.v0 / v0).ln().abs()));
    let friction = best.map_or(Friction { mu_star: 0.0, mu_adh: 0.0, mu_comp: 0.0 }, |e| e.friction);
    let error_estimate = best.map_or(f64::MAX, |e| e.estimate);
    Maximum {
        v0,
        friction,
        error_estimate,
        evaluations: log.len(),
        iterations: log.iter().map(|e| e.iterations).sum(),
        all_converged: log.iter().all(|e| e.converged),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adhesionless_maximum_at_k_0_1() {
        // At W = 100 adhesion is negligible: max mu* = 0.483 near V0 = 1.3 (the thesis:
        // about 0.48; Persson's approximation 0.479 at V0 = 1.2).
        let base = Params::sls(0.5, 100.0, 0.1, 1.0);
        let mesh = crate::bem::solver::Mesh { n: 300, half_length: 28.0 };
        let m = max_over_speed(&base, 0.01, 100.0, 9, 0.01, |p, _| crate::bem::solver::solve_with_estimate(p, mesh));
        assert!(m.all_converged);
        assert!((m.friction.mu_star - 0.483).abs() < 0.003, "{m:?}");
        assert!(m.v0 > 1.0 && m.v0 < 1.7, "{m:?}");
        assert!(m.evaluations < 30, "{m:?}");
    }

    #[test]
    fn solves_started_from_their_neighbours_find_the_same_maximum_for_less() {
        // The bench's maximum at lambda = 1, W = 1, k = 0.1 (`pipelines/bench.yaml`,
        // maxima_default): each solve's first level started from the nearest solve so far
        // lands on the same mu* at every speed as the full continuation (to Newton's
        // tolerance), hence the same maximum, in fewer than half the Newton iterations.
        use crate::bem::solver::{solve_to_tolerance, solve_to_tolerance_from, starting_mesh, DEFAULT_REL_TOL};
        let base = Params::sls(1.0, 1.0, 0.1, 1.0);
        let mesh = starting_mesh(&base, DEFAULT_REL_TOL);
        let cold =
            max_over_speed(&base, 1e-3, 1e3, 13, 0.01, |p, _| solve_to_tolerance(p, mesh, DEFAULT_REL_TOL, 16_000));
        let warm = max_over_speed(&base, 1e-3, 1e3, 13, 0.01, |p, near| {
            solve_to_tolerance_from(p, mesh, DEFAULT_REL_TOL, 16_000, near.and_then(Solution::start).as_ref())
        });
        assert!(cold.all_converged && warm.all_converged);
        assert_eq!((cold.v0, cold.evaluations), (warm.v0, warm.evaluations));
        let (a, b) = (cold.friction.mu_star, warm.friction.mu_star);
        assert!((a - b).abs() < 1e-8 * a, "{a} vs {b}");
        assert!((cold.error_estimate - warm.error_estimate).abs() < 1e-6 * cold.error_estimate);
        assert!(2 * warm.iterations < cold.iterations, "{} vs {} iterations", warm.iterations, cold.iterations);
    }
}
