//! Least-squares power laws: y = c x^s fitted as a straight line in (ln x, ln y), with
//! the standard errors of the slope and of the prefactor (delta method: se(c) = c se(ln c)).

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerLaw {
    pub slope: f64,
    pub slope_std_error: f64,
    pub prefactor: f64,
    pub prefactor_std_error: f64,
    pub r_squared: f64,
    pub n: usize,
}

/// The longest run of consecutive points (sorted by x, x and y > 0) over which every local
/// slope d ln y / d ln x between neighbours lies within `tol` of `slope`: a power-law
/// regime. Returns the index range [first, last] (at least `min_points` points).
pub fn power_law_regime(points: &[(f64, f64)], slope: f64, tol: f64, min_points: usize) -> Option<(usize, usize)> {
    let ok = |i: usize| {
        let ((x0, y0), (x1, y1)) = (points[i], points[i + 1]);
        x0 > 0.0 && y0 > 0.0 && x1 > x0 && y1 > 0.0 && ((y1 / y0).ln() / (x1 / x0).ln() - slope).abs() <= tol
    };
    let mut best: Option<(usize, usize)> = None;
    let mut start = None;
    for i in 0..points.len().saturating_sub(1) {
        if ok(i) {
            let s = *start.get_or_insert(i);
            if best.is_none_or(|(a, b)| i + 1 - s > b - a) {
                best = Some((s, i + 1));
            }
        } else {
            start = None;
        }
    }
    best.filter(|(a, b)| b + 1 - a >= min_points)
}

/// The sums of a least-squares straight line through points: their means and centred
/// second moments.
struct Moments {
    n: usize,
    mx: f64,
    my: f64,
    sxx: f64,
    sxy: f64,
    syy: f64,
}

impl Moments {
    fn of(points: &[(f64, f64)]) -> Moments {
        let n = points.len();
        let nf = n as f64;
        let mx = points.iter().map(|p| p.0).sum::<f64>() / nf;
        let my = points.iter().map(|p| p.1).sum::<f64>() / nf;
        let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
        let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let syy: f64 = points.iter().map(|p| (p.1 - my).powi(2)).sum();
        Moments { n, mx, my, sxx, sxy, syy }
    }
}

/// The coefficient of determination R² of the least-squares straight line y = a + b x
/// through the points: 1 when they lie on a line; None with fewer than 3 points or no
/// spread in x or in y.
pub fn linear_r_squared(points: &[(f64, f64)]) -> Option<f64> {
    let m = Moments::of(points);
    (m.n >= 3 && m.sxx > 0.0 && m.syy > 0.0).then(|| m.sxy * m.sxy / (m.sxx * m.syy))
}

/// Fits y = c x^s to the points with x, y > 0; None with fewer than 3 such points or no
/// spread in x.
pub fn power_law(points: &[(f64, f64)]) -> Option<PowerLaw> {
    let logs: Vec<(f64, f64)> =
        points.iter().filter(|(x, y)| *x > 0.0 && *y > 0.0).map(|(x, y)| (x.ln(), y.ln())).collect();
    let Moments { n, mx, my, sxx, sxy, syy } = Moments::of(&logs);
    if n < 3 || sxx <= 0.0 {
        return None;
    }
    let nf = n as f64;
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let rss: f64 = logs.iter().map(|p| (p.1 - intercept - slope * p.0).powi(2)).sum();
    let sigma2 = rss / (nf - 2.0);
    let se_slope = (sigma2 / sxx).sqrt();
    let se_intercept = (sigma2 * (1.0 / nf + mx * mx / sxx)).sqrt();
    let prefactor = intercept.exp();
    let r_squared = if syy > 0.0 { 1.0 - rss / syy } else { 1.0 };
    Some(PowerLaw {
        slope,
        slope_std_error: se_slope,
        prefactor,
        prefactor_std_error: prefactor * se_intercept,
        r_squared,
        n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_line_has_r_squared_one_and_a_parabola_less() {
        let line: Vec<(f64, f64)> = (0..5).map(|i| (i as f64, 2.0 + 3.0 * i as f64)).collect();
        assert!((linear_r_squared(&line).unwrap() - 1.0).abs() < 1e-12);
        // y = x^2 on x = 0..4: R^2 = Sxy^2 / (Sxx Syy) = 40^2 / (10 * 174) = 0.91954.
        let parabola: Vec<(f64, f64)> = (0..5).map(|i| (i as f64, (i * i) as f64)).collect();
        assert!((linear_r_squared(&parabola).unwrap() - 1600.0 / 1740.0).abs() < 1e-12);
        assert_eq!(linear_r_squared(&line[..2]), None);
        assert_eq!(linear_r_squared(&[(0.0, 1.0), (1.0, 1.0), (2.0, 1.0)]), None);
    }

    #[test]
    fn regimes_are_the_longest_runs_of_matching_local_slope() {
        // y = x below 1, sqrt(x) (continuous) from 1 to 100, flat beyond.
        let pts: Vec<(f64, f64)> = (0..25)
            .map(|i| {
                let x = 10f64.powf(-3.0 + 0.25 * i as f64);
                (
                    x,
                    if x < 1.0 {
                        x
                    } else if x <= 100.0 {
                        x.sqrt()
                    } else {
                        10.0
                    },
                )
            })
            .collect();
        let (a, b) = power_law_regime(&pts, 1.0, 0.1, 3).unwrap();
        assert_eq!((pts[a].0, pts[b].0), (1e-3, 1.0));
        let (a, b) = power_law_regime(&pts, 0.5, 0.1, 3).unwrap();
        assert!((pts[a].0 - 1.0).abs() < 1e-12 && (pts[b].0 - 100.0).abs() < 1e-9);
        assert!(power_law_regime(&pts, 2.0, 0.1, 3).is_none());
    }

    #[test]
    fn recovers_an_exact_power_law_and_scales_its_errors_with_the_noise() {
        let exact: Vec<(f64, f64)> = (1..20).map(|i| (i as f64, 3.0 * (i as f64).powf(-4.0 / 3.0))).collect();
        let f = power_law(&exact).unwrap();
        assert!((f.slope + 4.0 / 3.0).abs() < 1e-12 && (f.prefactor - 3.0).abs() < 1e-11);
        assert!(f.slope_std_error < 1e-12 && (f.r_squared - 1.0).abs() < 1e-12);
        // Deterministic +-1% multiplicative noise: the slope stays within a few standard
        // errors, which are of order 0.01 / (spread of ln x).
        let noisy: Vec<(f64, f64)> = exact
            .iter()
            .enumerate()
            .map(|(i, &(x, y))| (x, y * (1.0 + 0.01 * if i % 2 == 0 { 1.0 } else { -1.0 })))
            .collect();
        let g = power_law(&noisy).unwrap();
        assert!((g.slope + 4.0 / 3.0).abs() < 4.0 * g.slope_std_error + 1e-6, "{g:?}");
        assert!(g.slope_std_error > 1e-4 && g.slope_std_error < 1e-2, "{g:?}");
        assert!(power_law(&exact[..2]).is_none());
    }
}
