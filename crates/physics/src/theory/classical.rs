//! Classical adhesive contact of a rigid sphere on an elastic half-space: Hertz, JKR, DMT
//! and the Maugis–Dugdale transition (thesis Section 2.4.2, Eqs. 2.10–2.17).
//!
//! Nondimensionalisation (Maugis 1992), with K = 4E*/3 (Eq. 2.12), w the work of adhesion
//! (the thesis' gamma), R the sphere radius:
//!   A = a (K / (pi w R^2))^(1/3),   P = F / (pi w R),   D = d (K^2 / (pi^2 w^2 R))^(1/3),
//!   lambda = 2 sigma0 (R / (pi w K^2))^(1/3)  (Maugis' transition parameter).
//! In these units Hertz is P = A^3 (Eq. 2.10 as corrected in ERRATA item 18:
//! a^3 = F R / K), JKR is P = A^3 - sqrt(6 A^3) (Eq. 2.13, corrected form), with pull-off
//! P = -3/2 (Eq. 2.14), and DMT is P = A^3 - 2 with pull-off -2 (Eq. 2.16).
//! The thesis prints Eqs. 2.10, 2.11 and 2.13 with wrong factors (ERRATA 18); the tests
//! of this module check the corrected forms against the pull-off values it also prints.

use crate::numerics::roots::{bisect_root, maximize, rounding_of};

/// Hertz load for contact radius A.
pub fn hertz_load(a: f64) -> f64 {
    a.powi(3)
}

/// JKR load for contact radius A (both branches: A^3 >= 0).
pub fn jkr_load(a: f64) -> f64 {
    a.powi(3) - (6.0 * a.powi(3)).sqrt()
}

/// JKR contact radius on the stable branch for load P >= -3/2 (corrected Eq. 2.13:
/// A^3 = P + 3 + sqrt(6P + 9)).
pub fn jkr_radius(p: f64) -> Option<f64> {
    let disc = 6.0 * p + 9.0;
    (disc >= 0.0).then(|| (p + 3.0 + disc.sqrt()).cbrt())
}

/// DMT load for contact radius A.
pub fn dmt_load(a: f64) -> f64 {
    a.powi(3) - 2.0
}

pub const JKR_PULL_OFF: f64 = -1.5;
pub const DMT_PULL_OFF: f64 = -2.0;

/// Hertz pressure at r / aH = rho, in units of its peak p0 = 3F/(2 pi aH^2).
pub fn hertz_pressure(rho: f64) -> f64 {
    if rho < 1.0 {
        (1.0 - rho * rho).sqrt()
    } else {
        0.0
    }
}

/// JKR pressure at r / aH = rho for load P (Maugis units), in units of the Hertz peak
/// pressure at the same load. Derivation (units R = K = 1, w = 1/pi so that A = a and
/// P = F): p(r) = (3 a / (2 pi)) s - sqrt(3 / (2 pi^2 a)) / s with s = sqrt(1 - r^2/a^2),
/// and p0 = 3 aH / (2 pi). Negative (tensile) inside the edge; infinite at r = a.
pub fn jkr_pressure(rho: f64, p: f64) -> Option<f64> {
    let a_h = p.cbrt();
    let a = jkr_radius(p)?;
    let r = rho * a_h;
    if r >= a {
        return Some(0.0);
    }
    let s = (1.0 - (r / a).powi(2)).sqrt();
    let pi = std::f64::consts::PI;
    let p0 = 3.0 * a_h / (2.0 * pi);
    Some(((3.0 * a / (2.0 * pi)) * s - (3.0 / (2.0 * pi * pi * a)).sqrt() / s) / p0)
}

/// g1(t) = t + (t^2 - 1) atan t, evaluated without cancellation for small t
/// (series 4/3 t^3 - 8/15 t^5 + 12/35 t^7 - ...).
fn g1(t: f64) -> f64 {
    if t < 0.05 {
        let t2 = t * t;
        let mut sum = 0.0;
        let mut pow = t * t2;
        for k in 1..12 {
            let kf = k as f64;
            let c = (1.0 / (2.0 * kf - 1.0) + 1.0 / (2.0 * kf + 1.0)) * if k % 2 == 1 { 1.0 } else { -1.0 };
            sum += c * pow;
            pow *= t2;
        }
        sum
    } else {
        t + (t * t - 1.0) * t.atan()
    }
}

/// g2(t) = t atan t - (m - 1), m = sqrt(1 + t^2), without cancellation.
fn g2(t: f64) -> f64 {
    t * t.atan() - t * t / ((1.0 + t * t).sqrt() + 1.0)
}

/// A point of the Maugis–Dugdale solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaugisPoint {
    /// Contact radius A.
    pub a: f64,
    /// Ratio m = c/a of the cohesive-zone radius to the contact radius.
    pub m: f64,
    /// Load P.
    pub load: f64,
    /// Approach D.
    pub approach: f64,
    /// A bound on the error of `load`: the root's bound (`roots::Root`) carried through
    /// the load formula, plus the formula's own rounding.
    pub load_error: f64,
}

/// The Maugis–Dugdale solution at contact radius A for transition parameter lambda:
/// solves for m the energy condition
///   (lambda A^2/2)[sqrt(m^2-1) + (m^2-2) atan sqrt(m^2-1)]
///     + (4 lambda^2 A/3)[sqrt(m^2-1) atan sqrt(m^2-1) - m + 1] = 1,
/// then P = A^3 - lambda A^2 [sqrt(m^2-1) + m^2 atan sqrt(m^2-1)],
///      D = A^2 - (4/3) A lambda sqrt(m^2-1).
/// The unknown is t = sqrt(m^2 - 1), found by bisection in log t.
pub fn maugis_dugdale(a: f64, lambda: f64) -> Option<MaugisPoint> {
    maugis_dugdale_to(a, lambda, 1e-14)
}

/// `maugis_dugdale` with the bisection stopped at a bracket of `tol` in log t.
fn maugis_dugdale_to(a: f64, lambda: f64, tol: f64) -> Option<MaugisPoint> {
    if !(a > 0.0 && lambda > 0.0) {
        return None;
    }
    let terms = |t: f64| [0.5 * lambda * a * a * g1(t), (4.0 / 3.0) * lambda * lambda * a * g2(t), -1.0];
    let energy = |u: f64| terms(u.exp()).iter().sum::<f64>();
    let noise = |u: f64| rounding_of(&terms(u.exp()));
    let root = bisect_root(energy, noise, -60.0, 60.0, tol)?;
    let load_terms = |u: f64| {
        let t = u.exp();
        [a.powi(3), -lambda * a * a * (t + (1.0 + t * t) * t.atan())]
    };
    let t = root.x.exp();
    let m = (1.0 + t * t).sqrt();
    let load = a.powi(3) - lambda * a * a * (t + m * m * t.atan());
    let approach = a * a - (4.0 / 3.0) * a * lambda * t;
    let load_error = root.propagate(|u| load_terms(u).iter().sum()) + rounding_of(&load_terms(root.x));
    Some(MaugisPoint { a, m, load, approach, load_error })
}

/// A pull-off: the least load of a load-radius curve and the radius where it is reached.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PullOff {
    pub load: f64,
    pub radius: f64,
    /// A bound on the error of `load`: the point's own error at the minimum plus the
    /// change of the load across the minimisation's last bracket.
    pub error: f64,
}

/// The minimum of a load curve P(log A) over [log a_min, log a_max] (`n_grid` samples, then
/// golden section to 1e-10 in log A); `point` gives (P, its error bound) or None.
pub fn least_load<F: Fn(f64) -> Option<(f64, f64)>>(
    point: F,
    a_min: f64,
    a_max: f64,
    n_grid: usize,
) -> Option<PullOff> {
    const TOL: f64 = 1e-10;
    let load = |la: f64| point(la).map_or(f64::INFINITY, |p| p.0);
    let (la, neg) = maximize(|la| -load(la), a_min.ln(), a_max.ln(), n_grid, TOL);
    let (p, e) = point(la)?;
    let across = (load(la + TOL) - p).abs().max((load(la - TOL) - p).abs());
    (neg.is_finite() && across.is_finite()).then(|| PullOff { load: p, radius: la.exp(), error: e + across })
}

/// The pull-off load under load control: the minimum of P over the contact radius A
/// (A in [1e-4, 10]), and the radius where it is reached.
pub fn maugis_pull_off(lambda: f64) -> Option<PullOff> {
    least_load(|la| maugis_dugdale(la.exp(), lambda).map(|p| (p.load, p.load_error)), 1e-4, 10.0, 200)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jkr_pull_off_is_three_halves() {
        // Minimum of A^3 - sqrt(6 A^3) at A^3 = 3/2 (Eqs. 2.14, 2.15: a_min^3 = 3 pi w R^2 / (2K)).
        let a_min = 1.5f64.cbrt();
        assert!((jkr_load(a_min) - JKR_PULL_OFF).abs() < 1e-12);
        assert!(jkr_load(a_min * 1.01) > JKR_PULL_OFF && jkr_load(a_min * 0.99) > JKR_PULL_OFF);
        // The radius formula inverts the load formula on the stable branch.
        for p in [-1.5, -1.0, 0.0, 2.0, 10.0] {
            let a = jkr_radius(p).unwrap();
            assert!((jkr_load(a) - p).abs() < 1e-10, "P = {p}");
            assert!(a >= a_min - 1e-9);
        }
        // Zero load: A^3 = 6.
        assert!((jkr_radius(0.0).unwrap().powi(3) - 6.0).abs() < 1e-12);
    }

    #[test]
    fn jkr_pressure_integrates_to_the_load() {
        // Integral of p 2 pi r dr over the contact must give F, in units of p0 pi aH^2 / (3/2):
        // F / (p0 pi aH^2) = 2/3 for any load.
        for p in [0.5, 3.0] {
            let a_h = f64::cbrt(p);
            let a = jkr_radius(p).unwrap();
            // Substitute r = a sin(th) to remove the edge singularity.
            let f = |th: f64| {
                let r = a * th.sin();
                jkr_pressure(r / a_h, p).unwrap() * 2.0 * r * a * th.cos() / (a_h * a_h)
            };
            let (v, _) = crate::numerics::quad::integrate(&f, 0.0, std::f64::consts::FRAC_PI_2 - 1e-12, 1e-12, 30);
            assert!((v - 2.0 / 3.0).abs() < 1e-6, "P = {p}: {v}");
        }
    }

    #[test]
    fn maugis_tends_to_jkr_and_dmt() {
        // Large lambda: the JKR load at the same radius; small lambda: DMT.
        for a in [0.8, 1.2, 2.0] {
            let big = maugis_dugdale(a, 1e3).unwrap();
            assert!((big.load - jkr_load(a)).abs() < 0.01, "A={a}: {} vs {}", big.load, jkr_load(a));
            // The DMT limit is approached linearly in lambda: the deviation drops tenfold
            // per decade of lambda (about -3 lambda A^2/2 here).
            let dev = |l: f64| maugis_dugdale(a, l).unwrap().load - dmt_load(a);
            assert!(dev(1e-4).abs() < 2e-3, "A={a}: {}", dev(1e-4));
            let ratio = dev(1e-3) / dev(1e-4);
            assert!((ratio - 10.0).abs() < 0.5, "A={a}: ratio {ratio}");
        }
    }

    #[test]
    fn the_maugis_error_bounds_cover_a_looser_solution_and_are_rounding_when_tight() {
        for (a, lambda) in [(0.05, 0.01), (0.3, 0.3), (1.0, 1.0), (2.0, 5.0), (0.7, 30.0)] {
            let tight = maugis_dugdale(a, lambda).unwrap();
            let scale = a.powi(3) + (a.powi(3) - tight.load).abs();
            crate::numerics::roots::assert_bound_covers(&format!("A {a}, lambda {lambda}"), scale, 1e-12, |tol| {
                let p = maugis_dugdale_to(a, lambda, tol).unwrap();
                (p.load, p.load_error)
            });
        }
        // The pull-off's bound: rounding-sized, and it covers the distance to a minimum found
        // on a finer grid (the golden section's bracket moved).
        for lambda in [0.01, 0.1, 1.0, 10.0] {
            let p = maugis_pull_off(lambda).unwrap();
            assert!(p.error > 0.0 && p.error < 1e-11, "lambda {lambda}: {p:?}");
            let fine =
                least_load(|la| maugis_dugdale(la.exp(), lambda).map(|q| (q.load, q.load_error)), 1e-4, 10.0, 997)
                    .unwrap();
            assert!((fine.load - p.load).abs() <= p.error + fine.error, "lambda {lambda}: {fine:?} {p:?}");
            assert!(p.radius > 1.0001e-4, "lambda {lambda}: the minimum sits on the searched range's end");
        }
    }

    #[test]
    fn maugis_pull_off_spans_jkr_to_dmt() {
        let p_big = maugis_pull_off(20.0).unwrap().load;
        assert!((p_big - JKR_PULL_OFF).abs() < 0.02, "{p_big}");
        let p_small = maugis_pull_off(0.01).unwrap().load;
        assert!((p_small - DMT_PULL_OFF).abs() < 0.02, "{p_small}");
        // Monotone in between (Maugis 1992, Fig. 4), e.g. about -1.65 near lambda = 1.
        let mut last = -2.1;
        for l in [0.05, 0.3, 1.0, 3.0, 10.0] {
            let p = maugis_pull_off(l).unwrap().load;
            assert!(p > last && p < -1.45, "lambda {l}: {p}");
            last = p;
        }
    }

    #[test]
    fn small_t_series_matches_direct_formula() {
        for t in [0.01, 0.03, 0.049] {
            let direct = t + (t * t - 1.0) * f64::atan(t);
            assert!((g1(t) / direct - 1.0).abs() < 1e-7, "{t}");
        }
    }
}
