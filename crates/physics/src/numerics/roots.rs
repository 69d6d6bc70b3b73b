//! Root bracketing and one-dimensional maximisation.

/// Bisection for a sign change of f on [a, b] (f(a) and f(b) of opposite signs), to
/// |b - a| <= tol or exact zero. Returns None when the bracket does not hold.
pub fn bisect<F: Fn(f64) -> f64>(f: F, a: f64, b: f64, tol: f64) -> Option<f64> {
    bisect_bracket(f, a, b, tol).map(|(lo, hi)| 0.5 * (lo + hi))
}

/// `bisect`'s last bracket: the root lies between its ends (they are equal where f was
/// exactly zero), and `bisect` returns their midpoint.
pub fn bisect_bracket<F: Fn(f64) -> f64>(f: F, mut a: f64, mut b: f64, tol: f64) -> Option<(f64, f64)> {
    let mut fa = f(a);
    let fb = f(b);
    if fa == 0.0 {
        return Some((a, a));
    }
    if fb == 0.0 {
        return Some((b, b));
    }
    if !(fa.is_finite() && fb.is_finite()) || fa.signum() == fb.signum() {
        return None;
    }
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (b - a).abs() <= tol || m == a || m == b {
            return Some((a, b));
        }
        let fm = f(m);
        if fm == 0.0 {
            return Some((m, m));
        }
        if fm.signum() == fa.signum() {
            a = m;
            fa = fm;
        } else {
            b = m;
        }
    }
    Some((a, b))
}

/// A root and how far from it the true root can lie.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Root {
    pub x: f64,
    /// The true root lies within x +- half_width: half the last bracket plus the rounding
    /// of f near the root (where |f| is below the rounding of its evaluation, the sign
    /// test cannot tell; that stretch is noise / |f'| long). Infinite if f' vanishes.
    pub half_width: f64,
}

impl Root {
    /// A bound on the error of q(root): the larger change of q from x to either end of
    /// x +- half_width (first order in the half-width; q's own rounding is the caller's).
    pub fn propagate<Q: Fn(f64) -> f64>(&self, q: Q) -> f64 {
        let q0 = q(self.x);
        let d = (q(self.x + self.half_width) - q0).abs().max((q(self.x - self.half_width) - q0).abs());
        if d.is_nan() {
            f64::INFINITY
        } else {
            d
        }
    }
}

/// `bisect` with the bound of `Root`. `noise(x)` is the rounding error of evaluating f at
/// x (typically a few ulps of the sum of the magnitudes of f's terms); f' is taken by a
/// central difference of relative step 1e-6.
pub fn bisect_root<F: Fn(f64) -> f64, N: Fn(f64) -> f64>(f: F, noise: N, a: f64, b: f64, tol: f64) -> Option<Root> {
    let (lo, hi) = bisect_bracket(&f, a, b, tol)?;
    let x = 0.5 * (lo + hi);
    let h = 1e-6 * x.abs().max(1.0);
    let slope = ((f(x + h) - f(x - h)) / (2.0 * h)).abs();
    let rounding = noise(x) / slope;
    let half_width = 0.5 * (hi - lo).abs() + if rounding.is_nan() { f64::INFINITY } else { rounding };
    Some(Root { x, half_width })
}

/// Test check of an error bound: `solve(tol)` gives (value, bound) with the root bisected to
/// a bracket of `tol`. The tight solve's (tol 0) bound must be positive and below
/// `tight_rel scale`; stopped at 1e-3 and 1e-6, the bound must cover the distance to the tight
/// value and not exceed it by more than 1000 times (or 1e-14 scale, where both are rounding).
#[cfg(test)]
pub(crate) fn assert_bound_covers(what: &str, scale: f64, tight_rel: f64, solve: impl Fn(f64) -> (f64, f64)) {
    let (tight, tight_bound) = solve(0.0);
    assert!(tight_bound > 0.0 && tight_bound < tight_rel * scale, "{what}: {tight} +- {tight_bound}");
    for tol in [1e-3, 1e-6] {
        let (loose, bound) = solve(tol);
        let err = (loose - tight).abs();
        assert!(err <= bound, "{what}, tol {tol}: {loose} +- {bound} against {tight}");
        assert!(bound < 1e3 * err.max(1e-14 * scale), "{what}, tol {tol}: bound {bound} against error {err}");
    }
}

/// A few ulps (4 eps) of a sum of magnitudes: the rounding error of evaluating a short
/// formula whose terms have these sizes.
pub fn rounding_of(magnitudes: &[f64]) -> f64 {
    4.0 * f64::EPSILON * magnitudes.iter().map(|m| m.abs()).sum::<f64>()
}

/// The maximum of f over [a, b]: the best of `n_grid` evenly spaced samples, refined by
/// golden-section search between its neighbours to |dx| <= tol. Returns (x, f(x)).
pub fn maximize<F: Fn(f64) -> f64>(f: F, a: f64, b: f64, n_grid: usize, tol: f64) -> (f64, f64) {
    let n = n_grid.max(3);
    let xs: Vec<f64> = (0..n).map(|i| a + (b - a) * i as f64 / (n - 1) as f64).collect();
    let fs: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
    let best = (0..n).max_by(|&i, &j| fs[i].total_cmp(&fs[j])).unwrap();
    let refined = golden_section_max(&f, xs[best.saturating_sub(1)], xs[(best + 1).min(n - 1)], tol);
    [refined, (xs[best], fs[best])].into_iter().max_by(|p, q| p.1.total_cmp(&q.1)).unwrap()
}

/// `maximize` for an f that is unimodal over the grid, evaluating only the grid points a
/// climb needs: from the middle point, step to the better neighbour while it is better.
/// For a unimodal f the climb stops at the best grid point, so the result (and the
/// evaluations of the golden-section stage) are those of `maximize`; the grid points far
/// down the slopes are never evaluated. If every point the climb saw is -inf or NaN (say,
/// unconverged solves), the rest of the grid is evaluated. Returns (x, f(x)).
pub fn maximize_climbing<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, n_grid: usize, tol: f64) -> (f64, f64) {
    let n = n_grid.max(3);
    let x = |i: usize| a + (b - a) * i as f64 / (n - 1) as f64;
    let mut fs: Vec<Option<f64>> = vec![None; n];
    let mut at = |i: usize, f: &mut F| *fs[i].get_or_insert_with(|| f(x(i)));
    let mut best = (n - 1) / 2;
    loop {
        let here = at(best, &mut f);
        let left = if best > 0 { at(best - 1, &mut f) } else { f64::NEG_INFINITY };
        let right = if best + 1 < n { at(best + 1, &mut f) } else { f64::NEG_INFINITY };
        if left > here && left >= right {
            best -= 1;
        } else if right > here {
            best += 1;
        } else {
            break;
        }
    }
    if !(at(best, &mut f) > f64::NEG_INFINITY) {
        let all: Vec<f64> = (0..n).map(|i| at(i, &mut f)).collect();
        best = (0..n).max_by(|&i, &j| all[i].total_cmp(&all[j])).unwrap();
    }
    let f_best = at(best, &mut f);
    let refined = golden_section_max(&mut f, x(best.saturating_sub(1)), x((best + 1).min(n - 1)), tol);
    [refined, (x(best), f_best)].into_iter().max_by(|p, q| p.1.total_cmp(&q.1)).unwrap()
}

/// Golden-section search for the maximum of a unimodal f on [lo, hi], to a bracket of
/// width <= tol. f may carry state (warm starts, counters). Returns the better of the two
/// last interior points, (x, f(x)).
pub fn golden_section_max<F: FnMut(f64) -> f64>(mut f: F, mut lo: f64, mut hi: f64, tol: f64) -> (f64, f64) {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let mut x1 = hi - g * (hi - lo);
    let mut x2 = lo + g * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    while hi - lo > tol {
        if f1 < f2 {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + g * (hi - lo);
            f2 = f(x2);
        } else {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - g * (hi - lo);
            f1 = f(x1);
        }
    }
    if f1 >= f2 {
        (x1, f1)
    } else {
        (x2, f2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisect_and_maximize() {
        let r = bisect(|x| x * x - 2.0, 0.0, 2.0, 1e-14).unwrap();
        assert!((r - 2f64.sqrt()).abs() < 1e-13);
        assert!(bisect(|x| x * x + 1.0, 0.0, 2.0, 1e-14).is_none());
        let (x, fx) = maximize(|x| -(x - 0.3).powi(2) + 1.0, -2.0, 2.0, 11, 1e-10);
        assert!((x - 0.3).abs() < 1e-8 && (fx - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_bisected_root_carries_a_bound_that_covers_it() {
        // Loose tolerance: the bound is the bracket (a quarter of 1e-3 on each side at most).
        let f = |x: f64| x * x - 2.0;
        let noise = |x: f64| rounding_of(&[x * x, 2.0]);
        let loose = bisect_root(f, noise, 0.0, 2.0, 1e-3).unwrap();
        assert!((loose.x - 2f64.sqrt()).abs() <= loose.half_width && loose.half_width <= 1e-3, "{loose:?}");
        // Tight tolerance: the rounding of f sets the bound, a few ulps of the root.
        let r = bisect_root(f, noise, 0.0, 2.0, 0.0).unwrap();
        assert!((r.x - 2f64.sqrt()).abs() <= r.half_width, "{r:?}");
        assert!(r.half_width > 0.0 && r.half_width < 1e-14, "{r:?}");
        // A flat f near its root (a triple root): the rounding dominates and the bound
        // widens accordingly instead of claiming the bracket's 1e-15.
        let g = |x: f64| (x - 1.0).powi(3);
        let wide = bisect_root(g, |x| rounding_of(&[x.powi(3), 3.0 * x * x, 3.0 * x, 1.0]), 0.5, 1.7, 1e-15).unwrap();
        assert!(wide.half_width > 1e-6, "{wide:?}");
        assert!((wide.x - 1.0).abs() <= wide.half_width, "{wide:?}");
        // The propagated error of q = x^2 at the root is |2 x| times the half-width.
        let e = loose.propagate(|x| x * x);
        assert!((e / (2.0 * loose.x * loose.half_width) - 1.0).abs() < 1e-3, "{e}");
        // bisect returns the bracket's midpoint, bit for bit.
        let (lo, hi) = bisect_bracket(f, 0.0, 2.0, 1e-9).unwrap();
        assert_eq!(bisect(f, 0.0, 2.0, 1e-9).unwrap(), 0.5 * (lo + hi));
        assert!(lo <= 2f64.sqrt() && 2f64.sqrt() <= hi);
    }

    /// `f`, counting its calls in `calls`.
    fn counted<'a>(calls: &'a std::cell::Cell<usize>, f: impl Fn(f64) -> f64 + 'a) -> impl Fn(f64) -> f64 + 'a {
        move |x| {
            calls.set(calls.get() + 1);
            f(x)
        }
    }

    #[test]
    fn the_climb_finds_what_the_grid_finds_with_fewer_evaluations() {
        use std::cell::Cell;
        // Unimodal, the peak on either side of the middle, next to it, and at an end of
        // the range: the same (x, f) as the full grid, bit for bit, from fewer evaluations.
        for (peak, saved) in [(-1.7, 3), (-0.4, 5), (0.1, 6), (0.9, 4), (2.0, 3), (2.6, 3)] {
            let f = |x: f64| 1.0 / (1.0 + (x - peak) * (x - peak));
            let (full, climb) = (Cell::new(0), Cell::new(0));
            let a = maximize(counted(&full, f), -2.0, 2.0, 9, 1e-3);
            let b = maximize_climbing(counted(&climb, f), -2.0, 2.0, 9, 1e-3);
            assert_eq!(a, b, "peak {peak}");
            assert_eq!(full.get() - climb.get(), saved, "peak {peak}");
        }
        // Nothing finite where the climb looks: the whole grid is evaluated.
        let (x, fx) = maximize_climbing(|x| if x > 1.5 { 1.0 - x } else { f64::NEG_INFINITY }, -2.0, 2.0, 9, 1e-3);
        assert!(x > 1.5 && fx > -0.51, "{x} {fx}");
    }
}
