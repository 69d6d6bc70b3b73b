//! The maximum over speed of the friction of the Chapter 4 model, for fixed (lambda, W, k)
//! (thesis Section 4.3.5, Figs. 4.6-4.7): a log-spaced bracketing grid over V0, then
//! golden-section search in log V0 between the neighbours of the best grid point, so that
//! only the speeds the search needs are solved.

use super::solver::{self, Friction, Mesh, Params};
use crate::numerics::roots::maximize;
use std::cell::RefCell;

#[derive(Clone, Copy, Debug)]
pub struct Maximum {
    pub v0: f64,
    pub friction: Friction,
    /// Number of BEM solves.
    pub evaluations: usize,
    /// Whether every solve of the search converged.
    pub all_converged: bool,
}

/// Searches V0 in [v0_min, v0_max] with `grid` log-spaced points, refining to `tol` in
/// log10 V0. Unconverged solves count as -inf (never the maximum) and are reported.
pub fn max_over_speed(base: &Params, mesh: Mesh, v0_min: f64, v0_max: f64, grid: usize, tol: f64) -> Maximum {
    let log: RefCell<Vec<(f64, Friction, bool)>> = RefCell::new(Vec::new());
    let eval = |lv: f64| {
        let v0 = 10f64.powf(lv);
        let s = solver::solve(&Params { v0, ..*base }, mesh);
        let f = s.friction();
        log.borrow_mut().push((v0, f, s.converged));
        if s.converged && f.mu_star.is_finite() {
            f.mu_star
        } else {
            f64::NEG_INFINITY
        }
    };
    let (lv, _) = maximize(eval, v0_min.log10(), v0_max.log10(), grid, tol);
    let log = log.into_inner();
    let v0 = 10f64.powf(lv);
    let best = log.iter().filter(|e| e.2).min_by(|a, b| (a.0 / v0).ln().abs().total_cmp(&(b.0 / v0).ln().abs()));
    let friction = best.map_or(Friction { mu_star: 0.0, mu_adh: 0.0, mu_comp: 0.0 }, |e| e.1);
    Maximum { v0, friction, evaluations: log.len(), all_converged: log.iter().all(|e| e.2) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adhesionless_maximum_at_k_0_1() {
        // At W = 100 adhesion is negligible: max mu* = 0.483 near V0 = 1.3 (the thesis:
        // about 0.48; Persson's approximation 0.479 at V0 = 1.2).
        let base = Params { lambda: 0.5, w: 100.0, k: 0.1, v0: 1.0 };
        let m = max_over_speed(&base, Mesh { n: 300, half_length: 28.0 }, 0.01, 100.0, 9, 0.01);
        assert!(m.all_converged);
        assert!((m.friction.mu_star - 0.483).abs() < 0.003, "{m:?}");
        assert!(m.v0 > 1.0 && m.v0 < 1.7, "{m:?}");
        assert!(m.evaluations < 30, "{m:?}");
    }
}
