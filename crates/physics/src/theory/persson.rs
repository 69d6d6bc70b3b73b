//! Persson's (2010) adhesionless friction of a rigid cylinder rolling or sliding on a
//! standard linear solid (thesis Appendix A, Eqs. 7.1–7.2, with ERRATA items 15 and 16).
//!
//! Model. The creep function of the standard linear solid is
//!   J(t) = (1/E0) [1 - (1 - k) exp(-t/tau)],  k = E0/E_inf,  tau the creep (retardation) time,
//! so the complex compliance, with time dependence exp(i w t), is
//!   C(w) = (1/E0) [k + (1 - k)/(1 + i w tau)],   E(w) = 1/C(w),
//! relaxed (E0) at w -> 0 and instantaneous (E_inf = E0/k) at w -> inf; -Im C > 0.
//! All moduli are plane-strain moduli (E* = E/(1 - nu^2)).
//!
//! Friction (ERRATA 15, the Fourier derivation for a Hertzian line pressure; Eq. 7.1 as
//! printed gives mu proportional to (a/R)^2):
//!   mu = (8 w / pi) Int_0^inf dq [-Im 1/E(q v)] J1(q a)^2 / (a^2 q^2),
//!   a(q) = sqrt(4 w R / (pi |E(q v)|))   (Eq. 7.2, used in both places),
//! with w the load per unit length. With a0 = sqrt(4 w R / (pi E0)) (the relaxed Hertz
//! half-width), s = q a0, V0 = v tau / a0 and c = E0 C:
//!   mu* = mu R / a0 = 2 Int_0^inf ds (-Im c(s V0)) J1(s sqrt|c|)^2 / (|c| s^2).
//! Limits: mu* -> (1 - k) V0 for V0 -> 0 (since Int J1(x)^2/x dx = 1/2), mu* = 0 for k = 1.
//!
//! Quadrature: Gauss–Kronrod panels, log-spaced up to x = s sqrt|c| = 10 and one panel
//! per half-period of J1^2 beyond, up to x = X_TAIL; past X_TAIL, J1(x)^2 is replaced by its
//! average 1/(pi x) (the oscillating remainder contributes a relative 1/X_TAIL of a tail
//! that is itself small, and is counted in the error estimate).

use crate::numerics::quad::{integrate, integrate_panels};

const X_TAIL: f64 = 2000.0;

/// The dimensionless compliance c = E0 C at w tau = omega: (real, imaginary).
pub fn sls_compliance(k: f64, omega: f64) -> (f64, f64) {
    let d = 1.0 + omega * omega;
    (k + (1.0 - k) / d, -(1.0 - k) * omega / d)
}

/// |c| without cancellation: sqrt(1 + k^2 w^2) / sqrt(1 + w^2); written in 1/w where w^2
/// would overflow (w ~ 1e154 on).
fn abs_c(k: f64, omega: f64) -> f64 {
    if omega.abs() < BIG {
        ((1.0 + (k * omega).powi(2)) / (1.0 + omega * omega)).sqrt()
    } else {
        let u = 1.0 / omega;
        ((u * u + k * k) / (u * u + 1.0)).sqrt()
    }
}

/// Beyond this w, w^2 is near overflow: the forms in 1/w take over.
const BIG: f64 = 1e150;

/// c w / (1 + w^2), as c / (w + 1/w) where w^2 would overflow.
fn lorentzian(c: f64, w: f64) -> f64 {
    if w.abs() < BIG {
        c * w / (1.0 + w.powi(2))
    } else {
        c / (w + 1.0 / w)
    }
}

/// A friction value with its quadrature error estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    pub mu_star: f64,
    pub error_estimate: f64,
}

/// mu* = mu R / a0 at V0 = v tau / a0 for modulus ratio k (0 < k <= 1).
pub fn mu_star(k: f64, v0: f64, rel_tol: f64) -> Friction {
    assert!(k > 0.0 && k <= 1.0 && v0 > 0.0, "k in (0, 1], V0 > 0");
    let r = |s: f64| abs_c(k, s * v0).sqrt();
    let loss = |s: f64| lorentzian(1.0 - k, s * v0);
    let f = |s: f64| {
        if s == 0.0 {
            return 0.0;
        }
        let rs = r(s);
        let j = libm::j1(s * rs);
        2.0 * loss(s) * j * j / (rs * rs * s * s)
    };
    // x(s) = s r(s) is increasing; find s where it reaches 10 and X_TAIL.
    let s_at = |x: f64| {
        crate::numerics::roots::bisect(|ls: f64| ls.exp() * r(ls.exp()) - x, -60.0, 60.0, 1e-12)
            .map(f64::exp)
            .expect("s r(s) spans every positive value")
    };
    let s10 = s_at(10.0);
    let s_tail = s_at(X_TAIL);
    // Log-spaced panels from far below both scales (1 and 1/V0) up to s10.
    let s_lo = 1e-6 * s10.min(1.0 / v0);
    let mut breaks = vec![0.0];
    let n_log = ((s10 / s_lo).log10() * 8.0).ceil() as usize;
    for i in 0..=n_log {
        breaks.push(s_lo * (s10 / s_lo).powf(i as f64 / n_log as f64));
    }
    // Half-period panels of J1^2 beyond: x advances by pi/2.
    let mut s = s10;
    while s < s_tail {
        s = (s + std::f64::consts::FRAC_PI_2 / r(s)).min(s_tail);
        breaks.push(s);
    }
    let (body, body_err) = integrate_panels(&f, &breaks, rel_tol);
    // Tail: J1(x)^2 ~ 1/(pi x) on average. Integrate in log s over 20 decades.
    let tail_f = |u: f64| {
        let s = u.exp();
        let rs = r(s);
        2.0 * loss(s) / (std::f64::consts::PI * rs.powi(3) * s * s * s) * s
    };
    let (tail, _) = integrate(&tail_f, s_tail.ln(), s_tail.ln() + 46.0, rel_tol * body.abs().max(1e-300), 40);
    let tail_err = tail.abs() * 10.0 / X_TAIL;
    Friction { mu_star: body + tail, error_estimate: body_err + tail_err }
}

/// The maximum of mu* over V0 in [1e-4, 1e4] (log-spaced search refined by golden
/// section): (V0 at the maximum, the maximum).
pub fn max_mu_star(k: f64, rel_tol: f64) -> (f64, Friction) {
    let (lv, _) =
        crate::numerics::roots::maximize(|lv: f64| mu_star(k, 10f64.powf(lv), rel_tol).mu_star, -4.0, 4.0, 41, 1e-5);
    let v = 10f64.powf(lv);
    (v, mu_star(k, v, rel_tol))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compliance_limits() {
        // Relaxed at low frequency, instantaneous (k/E0) at high, loss positive.
        assert!((sls_compliance(0.1, 1e-9).0 - 1.0).abs() < 1e-12);
        assert!((sls_compliance(0.1, 1e9).0 - 0.1).abs() < 1e-9);
        assert!(sls_compliance(0.1, 1.0).1 < 0.0);
        let (re, im) = sls_compliance(0.3, 2.0);
        assert!((abs_c(0.3, 2.0) - (re * re + im * im).sqrt()).abs() < 1e-14);
    }

    #[test]
    fn low_speed_limit_is_one_minus_k_times_v0() {
        // mu* -> 2 (1-k) V0 Int J1(x)^2/x dx = (1-k) V0 (closed form, Int = 1/2).
        for k in [0.1, 0.01] {
            let v0 = 1e-4;
            let m = mu_star(k, v0, 1e-9).mu_star;
            assert!((m / ((1.0 - k) * v0) - 1.0).abs() < 2e-3, "k={k}: {m}");
        }
    }

    #[test]
    fn elastic_material_has_no_friction() {
        assert_eq!(mu_star(1.0, 1.0, 1e-8).mu_star, 0.0);
    }

    #[test]
    fn maxima_match_the_thesis_and_the_errata() {
        // Thesis (Section 4.2.5, Appendix A): max mu* about 0.48 at k = 0.1.
        let (v, m) = max_mu_star(0.1, 1e-8);
        assert!((m.mu_star - 0.48).abs() < 0.01, "k = 0.1: max {} at V0 = {v}", m.mu_star);
        assert!(v > 0.1 && v < 10.0, "{v}");
        // ERRATA 16: still rising past 1/k = 10, near 0.58 by 1/k = 100.
        let (_, m100) = max_mu_star(0.01, 1e-8);
        assert!((m100.mu_star - 0.58).abs() < 0.02, "k = 0.01: {}", m100.mu_star);
        assert!(m100.mu_star > m.mu_star + 0.05);
    }

    #[test]
    fn quadrature_converges() {
        let a = mu_star(0.01, 3.0, 1e-6).mu_star;
        let b = mu_star(0.01, 3.0, 1e-10).mu_star;
        assert!((a - b).abs() < 1e-5 * b.abs(), "{a} {b}");
    }
}
