//! Discretisation error estimates from solutions on successively halved meshes (Richardson
//! extrapolation). For a method of order p, the error of a solution on mesh size h falls as
//! h^p: halving h divides it by 2^p, so the difference d between the solutions on h and h/2
//! is (2^p - 1) times the error of the finer one. Before the sequence is asymptotic the
//! differences shrink by less (or cross zero); the three-level estimate covers that.

/// The error of `fine` from `coarse` (twice its mesh size) for a method of order `order`:
/// |fine - coarse| / (2^order - 1).
pub fn richardson(fine: f64, coarse: f64, order: f64) -> f64 {
    (fine - coarse).abs() / (2f64.powf(order) - 1.0)
}

/// The error of `coarse` from `fine` (half its mesh size) for a method of order `order`:
/// |coarse - fine| 2^order / (2^order - 1) (the companion is the finer mesh where the
/// coarser may lie outside the asymptotic range).
pub fn coarse_error(coarse: f64, fine: f64, order: f64) -> f64 {
    let rate = 2f64.powf(order);
    (coarse - fine).abs() * rate / (rate - 1.0)
}

/// The error of `fine` from three solutions on meshes halved in turn (`coarser`, `coarse`,
/// `fine`), for a method of order `order` at most, with d1 = coarse - coarser and d2 = fine -
/// coarse: the largest of the two-level `richardson` |d2|/(2^p - 1), one more halving of
/// the previous difference |d1|/(2^p (2^p - 1)) (both the same in the asymptotic regime,
/// where |d1| = 2^p |d2|), and, when d1 and d2 have one sign, the geometric tail of the
/// differences |d2|/(r - 1) at the observed ratio r = |d1/d2| taken in [`min_ratio`, 2^p].
/// Infinite or NaN when an input is.
pub fn three_level(coarser: f64, coarse: f64, fine: f64, order: f64, min_ratio: f64) -> f64 {
    let rate = 2f64.powf(order);
    let (d1, d2) = (coarse - coarser, fine - coarse);
    let two_level = d2.abs() / (rate - 1.0);
    let tail = if d1 * d2 > 0.0 { d2.abs() / ((d1 / d2).abs().clamp(min_ratio, rate) - 1.0) } else { 0.0 };
    tail.max(d1.abs() / (rate * (rate - 1.0))).max(two_level)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn richardson_recovers_the_error_of_an_asymptotic_sequence() {
        // u(h) = 1 + c h^2: the error of u(h/2) is c h^2 / 4, exactly what two levels give.
        let u = |h: f64| 1.0 + 0.3 * h * h;
        let (fine, coarse) = (u(0.05), u(0.1));
        assert!((richardson(fine, coarse, 2.0) - (fine - 1.0)).abs() < 1e-15);
        // Three levels of the same sequence: the same.
        assert!((three_level(u(0.2), coarse, fine, 2.0, 1.1) - (fine - 1.0)).abs() < 1e-15);
        // The coarse solution's error from the finer one: first order, u(h) = 1 + c h.
        let u1 = |h: f64| 1.0 + 0.3 * h;
        assert!((coarse_error(u1(0.1), u1(0.05), 1.0) - (u1(0.1) - 1.0)).abs() < 1e-15);
        assert!((coarse_error(coarse, fine, 2.0) - (coarse - 1.0)).abs() < 1e-15);
    }

    #[test]
    fn three_levels_cover_slow_and_crossing_sequences() {
        // Differences that shrink by 1.2 per halving: the error of the finest is the tail,
        // 5 times the last difference; two levels say a third of it.
        let d = [0.1, 0.1 / 1.2];
        let fine_error = d[1] / 1.2 / (1.0 - 1.0 / 1.2);
        let (coarser, coarse, fine) = (0.0, d[0], d[0] + d[1]);
        let e = three_level(coarser, coarse, fine, 2.0, 1.1);
        assert!((e - fine_error).abs() < 1e-12 && e > 10.0 * richardson(fine, coarse, 2.0), "{e}");
        // A crossing: the last difference is small by chance (the sequence of
        // bem::solver at lambda = 3, W = 1, k = 0.1, V0 = 0.01): the previous one bounds it.
        let e = three_level(0.249837, 0.232609, 0.232518, 2.0, 1.1);
        assert!((e - 0.017228 / 12.0).abs() < 1e-9 && e > (0.232518f64 - 0.233332).abs(), "{e}");
    }
}
