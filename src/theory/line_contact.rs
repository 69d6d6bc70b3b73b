//! Adhesive line contact of a rigid cylinder on an elastic half-plane: the limits the
//! Chapter 4 model tends to at very low and very high speed (thesis Section 4.3; the JKR
//! line contact itself is `bem::solver::jkr_half_width`).
//!
//! Units of Chapter 4 (Eq. 4.6): beta = (dgamma R^2/E*)^(1/3), X = x/beta, A = a/beta,
//! P = p/sigma0, H = h R/beta^2, W = w R/(E* beta^2) = w/(E* R dgamma^2)^(1/3), and the
//! Maugis-Tabor parameter lambda = sigma0 R/(E* beta), so that the work of adhesion is
//! 1/lambda in units of sigma0 beta^2/R.
//!
//! Maugis-Dugdale line contact (Baney & Hui 1997; derived here by superposing the Hertz
//! pressure on |x| < a and the Dugdale tension sigma0 on a < |x| < c with the bounded
//! correction inside, m = c/a, s = sqrt(m^2 - 1)):
//!   W = (pi/4) A^2 - 2 lambda A s,
//!   (lambda A^2/2) [m s - ln(m + s)] + (4 lambda^2 A/pi) [s ln(m + s) - m ln m] = 1,
//! the second the opening at c equal to the Dugdale range 1/lambda (its Dugdale term was
//! checked by quadrature of the surface slope, 1e-15 at m = 1.5, 2, 4). lambda -> inf gives
//! the JKR line contact W = (pi/4) A^2 - sqrt(2 pi A); lambda -> 0 the rigid cylinder,
//! pull-off -2 sqrt(2 lambda).
//!
//! Rigid limit of the Lennard-Jones law of Eq. 4.8 (what the model tends to at small
//! lambda): a rigid cylinder at gap H = X^2/2 - D carries W = lambda Int P(H) dX
//!   = sqrt(2 lambda/alpha) I(d),  I(d) = Int_0^inf 2 P(t^2 - d) dt,  d = alpha lambda D,
//! so the pull-off is -kappa sqrt(lambda) with kappa = sqrt(2/alpha) |min_d I(d)| = 2.434
//! (Dugdale: 2 sqrt 2 = 2.828; the ratio 0.861 is the shape factor between the two laws).

use crate::bem::traction::{self, ALPHA};
use crate::numerics::quad::integrate_panels;
use crate::numerics::roots::{bisect, maximize};
use std::f64::consts::PI;

/// A Maugis-Dugdale line-contact state: half-width A, m = c/A, load W.
#[derive(Clone, Copy, Debug)]
pub struct LinePoint {
    pub a: f64,
    pub m: f64,
    pub load: f64,
}

/// The Maugis-Dugdale line contact at half-width A (see the module header).
pub fn maugis_dugdale_line(a: f64, lambda: f64) -> Option<LinePoint> {
    if !(a > 0.0 && lambda > 0.0) {
        return None;
    }
    let opening = |s: f64| {
        let m = (1.0 + s * s).sqrt();
        let l = (m + s).ln();
        0.5 * lambda * a * a * (m * s - l) + 4.0 * lambda * lambda * a / PI * (s * l - m * m.ln()) - 1.0
    };
    // The opening grows from 0 at s = 0; bisect in log s.
    let ls = bisect(|u: f64| opening(u.exp()), -60.0, 60.0, 1e-14)?;
    let s = ls.exp();
    Some(LinePoint { a, m: (1.0 + s * s).sqrt(), load: PI / 4.0 * a * a - 2.0 * lambda * a * s })
}

/// The Maugis-Dugdale line-contact pull-off (load control): (min W, A there). At small
/// lambda the minimum is reached as A -> 0 (the rigid limit): the search floor is A = 1e-6.
pub fn maugis_dugdale_line_pull_off(lambda: f64) -> Option<(f64, f64)> {
    let load = |la: f64| maugis_dugdale_line(la.exp(), lambda).map_or(f64::INFINITY, |p| p.load);
    let (la, neg) = maximize(|la| -load(la), (1e-6f64).ln(), 10f64.ln(), 300, 1e-10);
    neg.is_finite().then(|| (-neg, la.exp()))
}

/// I(d) = Int_0^inf 2 P(t^2 - d) dt for the Lennard-Jones law (lambda = 1/alpha, so that
/// z = 1 + t^2 - d).
fn rigid_integral(d: f64) -> f64 {
    let f = |t: f64| 2.0 * traction::pressure(t * t - d, 1.0 / ALPHA).0;
    integrate_panels(&f, &[0.0, 0.5, 1.0, 2.0, 5.0, 20.0, 200.0, 1e4], 1e-12).0
}

/// kappa of the rigid-cylinder pull-off -kappa sqrt(lambda) with the Lennard-Jones law.
pub fn lj_rigid_pull_off_coefficient() -> f64 {
    // The most tensile approach lies at negative d (surfaces apart): measured d = -0.1009.
    let (_, neg) = maximize(|d| -rigid_integral(d), -0.6, 0.3, 19, 1e-9);
    (2.0 / ALPHA).sqrt() * neg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maugis_dugdale_line_contact_has_the_jkr_and_rigid_limits() {
        let jkr = -3.0 * (PI / 16.0).powf(1.0 / 3.0);
        let (w, a) = maugis_dugdale_line_pull_off(30.0).unwrap();
        assert!((w / jkr - 1.0).abs() < 1e-4, "{w} vs {jkr}");
        assert!((a / (2.0 / PI).powf(1.0 / 3.0) - 1.0).abs() < 0.02, "{a}");
        // JKR load at a given width for large lambda.
        let p = maugis_dugdale_line(1.5, 100.0).unwrap();
        let jkr_load = PI / 4.0 * 2.25 - (2.0 * PI * 1.5f64).sqrt();
        assert!((p.load - jkr_load).abs() < 2e-3, "{} vs {jkr_load}", p.load);
        // Rigid (Dugdale) limit: -2 sqrt(2 lambda) (measured -0.28267 vs -0.28284 at 0.01).
        let (w, _) = maugis_dugdale_line_pull_off(0.01).unwrap();
        assert!((w / (-2.0 * (0.02f64).sqrt()) - 1.0).abs() < 2e-3, "{w}");
        // The transition (values of this implementation: -0.8770 at 0.1, -1.7245 at 1).
        assert!((maugis_dugdale_line_pull_off(0.1).unwrap().0 + 0.8770).abs() < 1e-3);
        assert!((maugis_dugdale_line_pull_off(1.0).unwrap().0 + 1.7245).abs() < 1e-3);
    }

    #[test]
    fn rigid_lennard_jones_coefficient() {
        // Cross-checked with mpmath quadrature: min I = -1.698913 at d = -0.100925.
        let kappa = lj_rigid_pull_off_coefficient();
        assert!((kappa - 2.434_134).abs() < 1e-5, "{kappa}");
    }
}
