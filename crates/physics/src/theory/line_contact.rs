//! Adhesive line contact of a rigid cylinder on an elastic half-plane: the limits the
//! Chapter 4 model tends to at very low and very high speed (thesis Section 4.3; the JKR
//! line contact itself is `jkr_half_width`, `jkr_pull_off`).
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

use crate::lennard_jones::{self, ALPHA};
use crate::numerics::quad::integrate_panels;
use crate::numerics::roots::{bisect_root, maximize, rounding_of};
use crate::theory::classical::{least_load, PullOff};
use std::f64::consts::PI;

/// A Maugis-Dugdale line-contact state: half-width A, m = c/A, load W and a bound on its
/// error (the root's bound carried through the load, plus the load's rounding).
#[derive(Clone, Copy, Debug)]
pub struct LinePoint {
    pub a: f64,
    pub m: f64,
    pub load: f64,
    pub load_error: f64,
}

/// The Maugis-Dugdale line contact at half-width A (see the module header).
pub fn maugis_dugdale_line(a: f64, lambda: f64) -> Option<LinePoint> {
    maugis_dugdale_line_to(a, lambda, 1e-14)
}

/// `maugis_dugdale_line` with the bisection stopped at a bracket of `tol` in log s.
fn maugis_dugdale_line_to(a: f64, lambda: f64, tol: f64) -> Option<LinePoint> {
    if !(a > 0.0 && lambda > 0.0) {
        return None;
    }
    let terms = |s: f64| {
        let m = (1.0 + s * s).sqrt();
        let l = (m + s).ln();
        [0.5 * lambda * a * a * (m * s - l), 4.0 * lambda * lambda * a / PI * (s * l - m * m.ln()), -1.0]
    };
    // The opening grows from 0 at s = 0; bisect in log s.
    let opening = |u: f64| terms(u.exp()).iter().sum::<f64>();
    let root = bisect_root(opening, |u| rounding_of(&terms(u.exp())), -60.0, 60.0, tol)?;
    let load_terms = |u: f64| [PI / 4.0 * a * a, -2.0 * lambda * a * u.exp()];
    let s = root.x.exp();
    let load = PI / 4.0 * a * a - 2.0 * lambda * a * s;
    let load_error = root.propagate(|u| load_terms(u).iter().sum()) + rounding_of(&load_terms(root.x));
    Some(LinePoint { a, m: (1.0 + s * s).sqrt(), load, load_error })
}

/// The line-contact pull-off under load control: the least W over the half-width A, the
/// lesser of the minimum over A in [1e-6, 10] and the limit A -> 0 (`zero_width_limit`).
/// Below lambda ~ 0.18 the limit is the pull-off: W falls monotonically towards it as the
/// contact closes (no compressive zone at pull-off, ERRATA 19), and the radius is 0; above,
/// an interior minimum whose A grows continuously from 0 (both sides tested:
/// `at_small_lambda_the_line_pull_off_is_the_zero_width_limit`). The minimum over [1e-6, 10] taken as it stands would sit,
/// at small lambda, on the range's end, 8e-13 above the limit.
pub fn maugis_dugdale_line_pull_off(lambda: f64) -> Option<PullOff> {
    let interior =
        least_load(|la| maugis_dugdale_line(la.exp(), lambda).map(|p| (p.load, p.load_error)), 1e-6, 10.0, 300)?;
    let limit = zero_width_limit(lambda);
    Some(if limit < interior.load {
        PullOff { load: limit, radius: 0.0, error: rounding_of(&[limit]) }
    } else {
        interior
    })
}

/// The load of the Maugis-Dugdale line contact as its half-width A -> 0: with y = A s
/// fixed, the opening condition tends to (lambda/2) y^2 + (4 lambda^2 ln 2 / pi) y = 1 (m s -
/// ln(m + s) ~ s^2, s ln(m + s) - m ln m ~ s ln 2 for s -> inf) and W -> -2 lambda y. Tends
/// to the rigid Dugdale cylinder's -2 sqrt(2 lambda) as lambda -> 0.
pub fn zero_width_limit(lambda: f64) -> f64 {
    let b = 4.0 * lambda * lambda * std::f64::consts::LN_2 / PI;
    // The positive root of (lambda/2) y^2 + b y - 1, written without cancellation.
    let y = 2.0 / (b + (b * b + 2.0 * lambda).sqrt());
    -2.0 * lambda * y
}

/// I(d) = Int_0^inf 2 P(t^2 - d) dt for the Lennard-Jones law (lambda = 1/alpha, so that
/// z = 1 + t^2 - d).
fn rigid_integral(d: f64) -> f64 {
    let f = |t: f64| 2.0 * lennard_jones::pressure(t * t - d, 1.0 / ALPHA).0;
    integrate_panels(&f, &[0.0, 0.5, 1.0, 2.0, 5.0, 20.0, 200.0, 1e4], 1e-12).0
}

/// kappa of the rigid-cylinder pull-off -kappa sqrt(lambda) with the Lennard-Jones law.
pub fn lj_rigid_pull_off_coefficient() -> f64 {
    // The most tensile approach lies at negative d (surfaces apart; the test below finds it).
    let (_, neg) = maximize(|d| -rigid_integral(d), -0.6, 0.3, 19, 1e-9);
    (2.0 / ALPHA).sqrt() * neg
}

/// The JKR half-width of the 2D line contact for load W (relaxed modulus), from
/// W = (pi/4) A^2 - sqrt(2 pi A) on its stable branch; None below the pull-off
/// -3 (pi/16)^(1/3).
pub fn jkr_half_width(w: f64) -> Option<f64> {
    let load = |a: f64| PI / 4.0 * a * a - (2.0 * PI * a).sqrt();
    let a_po = (2.0 / PI).powf(1.0 / 3.0);
    if w < load(a_po) {
        return None;
    }
    crate::numerics::roots::bisect(|a| load(a) - w, a_po, 10.0 + 4.0 * w.abs().sqrt(), 1e-13)
}

/// The 2D JKR pull-off load, -3 (pi/16)^(1/3) (load control, relaxed modulus).
pub fn jkr_pull_off() -> f64 {
    -3.0 * (PI / 16.0).powf(1.0 / 3.0)
}

/// The JKR limit of the sliding cylinder's friction, mu* = pi^(1/2) / (2 W^(3/2) k): what
/// max mu* over V0 tends to as lambda grows (the equation after the thesis' Fig. 4.6, about
/// 280 at W = 0.1, k = 0.1). W is the load (its magnitude), k = E0/E_inf.
pub fn jkr_friction_limit(w: f64, k: f64) -> f64 {
    PI.sqrt() / (2.0 * w.abs().powf(1.5) * k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maugis_dugdale_line_contact_has_the_jkr_and_rigid_limits() {
        let jkr = -3.0 * (PI / 16.0).powf(1.0 / 3.0);
        let PullOff { load: w, radius: a, .. } = maugis_dugdale_line_pull_off(30.0).unwrap();
        assert!((w / jkr - 1.0).abs() < 1e-4, "{w} vs {jkr}");
        assert!((a / (2.0 / PI).powf(1.0 / 3.0) - 1.0).abs() < 0.02, "{a}");
        // JKR load at a given width for large lambda.
        let p = maugis_dugdale_line(1.5, 100.0).unwrap();
        let jkr_load = PI / 4.0 * 2.25 - (2.0 * PI * 1.5f64).sqrt();
        assert!((p.load - jkr_load).abs() < 2e-3, "{} vs {jkr_load}", p.load);
        // Rigid (Dugdale) limit: -2 sqrt(2 lambda) (measured -0.28267 vs -0.28284 at 0.01).
        let w = maugis_dugdale_line_pull_off(0.01).unwrap().load;
        assert!((w / (-2.0 * (0.02f64).sqrt()) - 1.0).abs() < 2e-3, "{w}");
        // The transition (values of this implementation: -0.8770 at 0.1, -1.7245 at 1).
        assert!((maugis_dugdale_line_pull_off(0.1).unwrap().load + 0.8770).abs() < 1e-3);
        assert!((maugis_dugdale_line_pull_off(1.0).unwrap().load + 1.7245).abs() < 1e-3);
    }

    #[test]
    fn the_line_error_bounds_cover_a_looser_solution() {
        for (a, lambda) in [(0.01, 0.01), (0.4, 0.3), (1.0, 1.0), (1.5, 100.0)] {
            let tight = maugis_dugdale_line(a, lambda).unwrap();
            let scale = a * a + (a * a - tight.load).abs();
            crate::numerics::roots::assert_bound_covers(&format!("A {a}, lambda {lambda}"), scale, 1e-12, |tol| {
                let p = maugis_dugdale_line_to(a, lambda, tol).unwrap();
                (p.load, p.load_error)
            });
        }
        for lambda in [0.01, 0.3, 3.0, 30.0] {
            let p = maugis_dugdale_line_pull_off(lambda).unwrap();
            assert!(p.error > 0.0 && p.error < 1e-11, "lambda {lambda}: {p:?}");
            // Never the searched range's end: either an interior minimum or the A -> 0 limit.
            assert!(p.radius == 0.0 || p.radius > 1.0001e-6, "lambda {lambda}: {p:?}");
        }
    }

    #[test]
    fn at_small_lambda_the_line_pull_off_is_the_zero_width_limit() {
        for lambda in [0.01, 0.03, 0.1] {
            let limit = zero_width_limit(lambda);
            // W(A) falls monotonically towards the limit as A -> 0 and reaches it, within
            // rounding, by A = 1e-9.
            let w = |a: f64| maugis_dugdale_line(a, lambda).unwrap();
            let mut last = f64::INFINITY;
            for a in [1e-1, 1e-2, 1e-3, 1e-4, 1e-6] {
                assert!(w(a).load < last && w(a).load > limit, "lambda {lambda}, A {a}: {:?}", w(a));
                last = w(a).load;
            }
            assert!((w(1e-9).load - limit).abs() < 1e-12 + w(1e-9).load_error, "{:?} against {limit}", w(1e-9));
            let p = maugis_dugdale_line_pull_off(lambda).unwrap();
            assert_eq!((p.load, p.radius), (limit, 0.0));
        }
        // The transition: still the limit at lambda = 0.158; at 0.1995 an interior minimum at
        // a half-width that has grown from 0 only to about 2e-5.
        assert_eq!(maugis_dugdale_line_pull_off(0.158).unwrap().radius, 0.0);
        let a = maugis_dugdale_line_pull_off(0.1995).unwrap().radius;
        assert!(a > 1e-5 && a < 5e-5, "A = {a}");
        // The rigid Dugdale cylinder as lambda -> 0, to first order in lambda^(3/2).
        let l = 1e-6;
        assert!((zero_width_limit(l) / (-2.0 * (2.0 * l).sqrt()) - 1.0).abs() < 1e-5);
        // Large lambda: an interior minimum with a finite contact (JKR-like).
        assert!(maugis_dugdale_line_pull_off(3.0).unwrap().radius > 0.1);
    }

    #[test]
    fn the_jkr_friction_limit_is_the_thesis_280() {
        // The thesis' value at W = 0.1, k = 0.1 ("about 280"): sqrt(pi) / (2 0.1^1.5 0.1).
        assert!((jkr_friction_limit(0.1, 0.1) - 280.2495).abs() < 1e-4, "{}", jkr_friction_limit(0.1, 0.1));
        // W^(-3/2) and 1/k: ten times the load, 10^-1.5 of the limit.
        let ratio = jkr_friction_limit(1.0, 0.1) / jkr_friction_limit(0.1, 0.1);
        assert!((ratio - 10f64.powf(-1.5)).abs() < 1e-12);
        assert_eq!(jkr_friction_limit(-0.1, 0.1), jkr_friction_limit(0.1, 0.1));
    }

    #[test]
    fn rigid_lennard_jones_coefficient() {
        // Cross-checked with mpmath quadrature: min I = -1.698913 at d = -0.100925.
        let kappa = lj_rigid_pull_off_coefficient();
        assert!((kappa - 2.434_134).abs() < 1e-5, "{kappa}");
    }
}
