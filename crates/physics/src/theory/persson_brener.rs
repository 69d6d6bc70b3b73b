//! Persson–Brener energy release at the trailing edge of a viscoelastic contact and the
//! adhesive friction it implies (thesis Eqs. 5.9–5.15, with ERRATA items 13 and 14).
//!
//! Units: u = v / v0 with v0 = c0 / (2 pi tau) (Eq. 5.15), c0 = E0 dgamma / (2 pi sigma_c^2)
//! (Eq. 5.11, with the relaxed modulus E0 as in ERRATA 14); x = c(v)/c0 = G_trail/dgamma
//! (Eq. 5.10). Eq. 5.12 reads
//!   x = [1 - (1 - k) (sqrt(1 + z^-2) - z^-1)]^-1,   z = u / x,
//! x runs from 1 (u -> 0) to 1/k (u -> inf). It is solved for ln x as
//!   ln x + ln B = 0,   B = 1 - (1 - k) phi = k + (1 - k) psi,
//! psi = 1 - phi = (1 + 1/(r + z)) / (r + 1), phi = z / (r + 1), r = sqrt(1 + z^2) (for a
//! spectrum Sum_j w_j phi_j and Sum_j w_j psi_j, the weights summing to 1), with ln B as
//! log1p(-(1 - k) phi) while (1 - k) phi < 1/2 and as ln(k + (1 - k) psi) beyond, and the
//! friction as x - 1/x = 2 sinh(ln x): no cancellation at any speed. (The
//! residual x (1 - (1 - k) phi) - 1 and f = (x - 1)(x + 1)/x lose log10(1/k) digits near
//! saturation and log10(1/u) at low speed: the roots' error bounds show 3e-11 and 6e-11
//! relative there.)
//! The friction per unit width (Eq. 5.13 normalised, ERRATA 13) is
//!   f_T / dgamma = x - 1/x   (G_lead = dgamma^2 / G_trail),
//! with the limits (ERRATA 14): (1 - k) u for u << 1, sqrt(u / (1 - k)) for
//! 1 << u << (1 - k)/k^2, and 1/k - k for u -> inf.
//!
//! In the units of Chapters 4-5 (Eq. 5.6: F_T* = mu* |W| = (beta/a0) f_T/dgamma, with
//! f_T/dgamma = lambda Int P dU/dX dX), with sigma_c = alpha_PB sigma0 (Eq. 5.18; not the
//! alpha of the Lennard-Jones law, ERRATA 14): sigma0^2/(E0* dgamma) = lambda^2/beta, so
//!   u = v/v0 = (2 pi)^2 alpha_PB^2 lambda^2 v tau/beta = (2 pi)^2 alpha_PB^2 lambda^2 V0 a0/beta,
//! a0/beta = 2 sqrt(|W|/pi) (Eq. 5.19 as corrected in ERRATA 4). Hence (checked here, the
//! thesis' prefactors confirmed; the factors of 1 - k are ERRATA 14's):
//!   Eq. 5.20: F_T1* = (1 - k) (2 pi)^2 alpha_PB^2 lambda^2 V0,
//!   Eq. 5.21: F_T2* = sqrt 2 pi^(5/4) alpha_PB lambda |W|^(-1/4) V0^(1/2) / sqrt(1 - k)
//! (pi sqrt(2 pi) (1/pi)^(1/4) = sqrt 2 pi^(5/4)).
//!
//! Power-law materials (Eqs. 5.24-5.28): `g_trailing_spectrum` solves Eq. 5.27 for a discrete
//! retardation spectrum (a discretised S(tau)); for a broad power law, G/dgamma ~ u^n with
//! n = (1-s)/(2-s) (Eq. 5.28; checked by the local slope in the tests).

use crate::numerics::roots::{bisect_root, rounding_of, Root};
use crate::rheology::Spectrum;

/// (phi(z), psi(z)) with phi(z) = sqrt(1 + z^-2) - 1/z = z / (r + 1) and psi = 1 - phi =
/// (1 + 1/(r + z)) / (r + 1), r = hypot(1, z): both without cancellation or overflow.
fn phi_psi(z: f64) -> (f64, f64) {
    if z.is_infinite() {
        return (1.0, 0.0);
    }
    let r = 1f64.hypot(z);
    (z / (r + 1.0), (1.0 + 1.0 / (r + z)) / (r + 1.0))
}

/// Solves Eq. 5.12 for x = G_trail / dgamma at u = v/v0, modulus ratio k in (0, 1].
/// ln x + ln B(x) (module header) is negative at x = 1 and positive at x = 1/k;
/// bisection in log x to machine precision.
pub fn g_trailing(u: f64, k: f64) -> f64 {
    g_trailing_spectrum(u, k, &Spectrum::sls())
}

/// Eq. 5.27 for a retardation spectrum (`rheology::Spectrum`, times t_j in units of the tau
/// of v0): x = [1 - (1-k) Sum_j w_j phi(u t_j / x)]^-1, with b(tau) = 2 pi v tau/c = u t_j/x.
/// One term at t = 1 is Eq. 5.12. The same bracket [1, 1/k] holds (0 <= phi <= 1).
pub fn g_trailing_spectrum(u: f64, k: f64, spectrum: &Spectrum) -> f64 {
    g_trailing_root(u, k, spectrum, 0.0).map_or(1.0, |r| r.x.exp())
}

/// The root of Eq. 5.27 in log x with its bound (`roots::Root`), bisected to a bracket of
/// `tol` (0: to adjacent floats, which keeps ln x's relative accuracy at low speed, where
/// ln x ~ u/2 is small); None where x = 1 exactly (u = 0 or k = 1).
fn g_trailing_root(u: f64, k: f64, spectrum: &Spectrum, tol: f64) -> Option<Root> {
    assert!(u >= 0.0 && k > 0.0 && k <= 1.0);
    if u == 0.0 || k == 1.0 {
        return None;
    }
    let terms = spectrum.terms();
    let n = terms.len() as f64;
    // ln B at x and the rounding of its evaluation: the sums of n terms round by n ulps or
    // so; log1p of a value a carries a's relative rounding as an absolute a (n + 3) eps,
    // the logarithm of B its relative rounding as an absolute (n + 3) eps.
    let ln_b = |x: f64| {
        let (mut relaxed, mut unrelaxed) = (0.0, 0.0);
        for &(w, t) in terms {
            let (phi, psi) = phi_psi(u * t / x);
            relaxed += w * phi;
            unrelaxed += w * psi;
        }
        let a = (1.0 - k) * relaxed;
        if a < 0.5 {
            ((-a).ln_1p(), rounding_of(&[a * (n + 3.0)]))
        } else {
            let ln_b = (k + (1.0 - k) * unrelaxed).ln();
            (ln_b, rounding_of(&[ln_b, n + 3.0]))
        }
    };
    let h = |lx: f64| lx + ln_b(lx.exp()).0;
    let noise = |lx: f64| rounding_of(&[lx]) + ln_b(lx.exp()).1;
    Some(bisect_root(h, noise, 0.0, (1.0 / k).ln(), tol).expect("Eq. 5.27 brackets its root on [1, 1/k]"))
}

/// f_T / dgamma = x - 1/x (Eq. 5.13 normalised) for a retardation spectrum.
pub fn friction_spectrum(u: f64, k: f64, spectrum: &Spectrum) -> f64 {
    friction_spectrum_bounded(u, k, spectrum).0
}

/// `friction_spectrum` and a bound on its error: the root's bound carried through
/// x - 1/x = 2 sinh(ln x), plus that formula's rounding.
pub fn friction_spectrum_bounded(u: f64, k: f64, spectrum: &Spectrum) -> (f64, f64) {
    friction_bounded_to(u, k, spectrum, 0.0)
}

fn friction_bounded_to(u: f64, k: f64, spectrum: &Spectrum, tol: f64) -> (f64, f64) {
    let f = |lx: f64| 2.0 * lx.sinh();
    match g_trailing_root(u, k, spectrum, tol) {
        None => (0.0, 0.0),
        Some(root) => (f(root.x), root.propagate(f) + rounding_of(&[f(root.x)])),
    }
}

/// The exponent n = (1 - s)/(2 - s) of G/dgamma ~ v^n for a broad power-law spectrum
/// (Eq. 5.28). Derivation: for tau1 << tau* = c/(2 pi v) << tau2 and k << 1/x << 1,
/// 1/x ~ Int_tau1^tau* S + Int_tau*^tau2 S tau*/tau ~ tau*^(1-s) ~ (x/u)^(1-s).
pub fn power_law_exponent(s: f64) -> f64 {
    (1.0 - s) / (2.0 - s)
}

/// f_T / dgamma = x - 1/x (Eq. 5.13, normalised) for the standard linear solid.
pub fn friction(u: f64, k: f64) -> f64 {
    friction_spectrum(u, k, &Spectrum::sls())
}

/// u = v/v0 of a rolling point (see the module header).
fn rolling_u(alpha_pb: f64, lambda: f64, w: f64, v0: f64) -> f64 {
    let a0_over_beta = 2.0 * (w.abs() / std::f64::consts::PI).sqrt();
    (2.0 * std::f64::consts::PI * alpha_pb * lambda).powi(2) * v0 * a0_over_beta
}

/// The Persson-Brener rolling friction F_T* = (beta/a0) f_T/dgamma at V0 (Eqs. 5.10-5.13 in
/// the units of Eq. 5.6).
pub fn rolling_friction(alpha_pb: f64, lambda: f64, w: f64, k: f64, v0: f64) -> f64 {
    let beta_over_a0 = 0.5 * (std::f64::consts::PI / w.abs()).sqrt();
    beta_over_a0 * friction(rolling_u(alpha_pb, lambda, w, v0), k)
}

/// The low-speed law, Eq. 5.20 (with the factor 1 - k): F_T* = (1-k) (2 pi)^2 alpha^2 lambda^2 V0.
pub fn rolling_linear(alpha_pb: f64, lambda: f64, k: f64, v0: f64) -> f64 {
    (1.0 - k) * (2.0 * std::f64::consts::PI * alpha_pb * lambda).powi(2) * v0
}

/// The intermediate law, Eq. 5.21 (with 1/sqrt(1 - k)):
/// F_T* = sqrt 2 pi^(5/4) alpha lambda |W|^(-1/4) V0^(1/2) / sqrt(1 - k).
pub fn rolling_sqrt(alpha_pb: f64, lambda: f64, w: f64, k: f64, v0: f64) -> f64 {
    2f64.sqrt() * std::f64::consts::PI.powf(1.25) * alpha_pb * lambda * w.abs().powf(-0.25) * v0.sqrt()
        / (1.0 - k).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rolling_laws_are_the_limits_of_the_rolling_friction() {
        use std::f64::consts::PI;
        let (alpha, lambda, w, k) = (0.3, 2.0, 0.1, 1e-4);
        // u = 1e-4: the linear law; u = 1e3 << (1-k)/k^2: the square-root law.
        let v_low = 1e-4 / rolling_u(alpha, lambda, w, 1.0);
        let v_mid = 1e3 / rolling_u(alpha, lambda, w, 1.0);
        let low = rolling_friction(alpha, lambda, w, k, v_low) / rolling_linear(alpha, lambda, k, v_low);
        let mid = rolling_friction(alpha, lambda, w, k, v_mid) / rolling_sqrt(alpha, lambda, w, k, v_mid);
        assert!((low - 1.0).abs() < 1e-3 && (mid - 1.0).abs() < 0.01, "{low} {mid}");
        // The thesis' printed prefactors: (2 pi)^2 and pi sqrt(2 pi) (1/pi)^(1/4) (k -> 0).
        assert!((rolling_linear(1.0, 1.0, 0.0, 1.0) - 4.0 * PI * PI).abs() < 1e-12);
        let printed = PI * (2.0 * PI).sqrt() * (1.0 / PI).powf(0.25);
        assert!((rolling_sqrt(1.0, 1.0, 1.0, 0.0, 1.0) - printed).abs() < 1e-12);
    }

    #[test]
    fn the_friction_bound_covers_a_looser_root_and_is_rounding_when_tight() {
        let power_law = crate::rheology::Spectrum::power_law(0.5, 1e-3, 4).unwrap();
        for spectrum in [Spectrum::sls(), power_law] {
            for k in [1e-4, 0.1, 0.9] {
                for u in [1e-6, 1e-2, 1.0, 1e3, 1e9] {
                    let f = friction_spectrum(u, k, &spectrum);
                    assert_eq!(friction_spectrum_bounded(u, k, &spectrum).0, f);
                    // Tight to 1e-13 of f at every speed: near saturation (k = 1e-4, u = 1e9) and
                    // at low speed (u = 1e-6), where the former residual lost four and six
                    // digits (bounds 3e-11 and 6e-11 relative).
                    crate::numerics::roots::assert_bound_covers(&format!("k {k}, u {u}"), f, 1e-13, |tol| {
                        friction_bounded_to(u, k, &spectrum, tol)
                    });
                }
            }
        }
        // x = 1 exactly: no friction, no error.
        assert_eq!(friction_spectrum_bounded(0.0, 0.1, &Spectrum::sls()), (0.0, 0.0));
    }

    #[test]
    fn the_cancellation_free_form_agrees_with_eq_5_12_as_printed() {
        // Eq. 5.12 as printed, x = [1 - (1-k) phi(u/x)]^-1, solved with its own rounding bound:
        // the two roots agree within that bound, and near saturation the printed form's bound
        // is far wider than the cancellation-free one's.
        use crate::numerics::roots::{bisect_root, rounding_of};
        let phi = |z: f64| z / (1f64.hypot(z) + 1.0);
        for k in [1e-4, 0.01, 0.5] {
            for u in [1e-3, 1.0, 1e3, 1e6, 1e9] {
                let g = |lx: f64| lx.exp() * (1.0 - (1.0 - k) * phi(u / lx.exp())) - 1.0;
                let noise = |lx: f64| rounding_of(&[lx.exp(), 3.0 * lx.exp() * (1.0 - k) * phi(u / lx.exp()), 1.0]);
                let printed = bisect_root(g, noise, 0.0, (1.0 / k).ln(), 1e-15).unwrap();
                let ours = g_trailing_root(u, k, &Spectrum::sls(), 0.0).unwrap();
                let d = (printed.x - ours.x).abs();
                assert!(d <= printed.half_width + ours.half_width, "k {k}, u {u}: {printed:?} {ours:?}");
                if k == 1e-4 && u == 1e9 {
                    assert!(printed.half_width > 1e3 * ours.half_width, "{printed:?} {ours:?}");
                }
            }
        }
    }

    #[test]
    fn low_speed_slope_one_with_prefactor_one_minus_k() {
        for k in [0.1, 0.001] {
            let u = 1e-6;
            assert!((friction(u, k) / ((1.0 - k) * u) - 1.0).abs() < 1e-5, "k={k}");
        }
    }

    #[test]
    fn square_root_regime_and_saturation() {
        // ERRATA 14: sqrt(u/(1-k)) for 1 << u << (1-k)/k^2; here k = 1e-4, u = 1e3.
        let k = 1e-4;
        let f = friction(1e3, k);
        assert!((f / (1e3 / (1.0 - k)).sqrt() - 1.0).abs() < 0.01, "{f}");
        // Local slope d ln f / d ln u = 1/2 there.
        let slope = (friction(2e3, k) / friction(5e2, k)).ln() / 4f64.ln();
        assert!((slope - 0.5).abs() < 0.01, "{slope}");
        // Saturation at 1/k - k.
        for k in [0.1, 0.01] {
            let f = friction(1e14, k);
            assert!((f / (1.0 / k - k) - 1.0).abs() < 1e-4, "k={k}: {f}");
        }
    }

    #[test]
    fn power_law_exponent_of_eq_5_28() {
        // A very broad spectrum (tau1/tau2 = 1e-12) and k = 1e-8 leave room for the
        // intermediate regime; the local slope d ln x / d ln u at its flattest point is n.
        for s in [0.25, 0.5, 0.6, 0.75] {
            let spec = Spectrum::power_law(s, 1e-12, 8).unwrap();
            let k = 1e-8;
            let slope = |u: f64| {
                let (a, b) = (g_trailing_spectrum(u / 1.5, k, &spec), g_trailing_spectrum(u * 1.5, k, &spec));
                (b / a).ln() / 2.25f64.ln()
            };
            // x rises from 1 to 1/k; the slope's plateau is where it varies least.
            let us: Vec<f64> = (0..=80).map(|i| 10f64.powf(-2.0 + 0.25 * i as f64)).collect();
            let slopes: Vec<f64> = us.iter().map(|&u| slope(u)).collect();
            let flattest = (1..slopes.len() - 1)
                .min_by(|&i, &j| {
                    let d = |i: usize| (slopes[i + 1] - slopes[i - 1]).abs();
                    d(i).total_cmp(&d(j))
                })
                .unwrap();
            let n = power_law_exponent(s);
            // The flattest slopes this code finds: 0.4274, 0.33333, 0.28584, 0.2013 against 3/7, 1/3, 2/7, 1/5.
            assert!(
                (slopes[flattest] - n).abs() < 0.003,
                "s={s}: slope {} at u={:e}, n={n}",
                slopes[flattest],
                us[flattest]
            );
        }
    }

    #[test]
    fn the_sls_is_the_one_term_spectrum() {
        for (u, k) in [(0.3, 0.1), (1e5, 0.001)] {
            let one = Spectrum::from_relaxation(k, &[(1.0, k)]).unwrap();
            let (a, b) = (g_trailing_spectrum(u, k, &one), g_trailing(u, k));
            assert!((a / b - 1.0).abs() < 1e-12, "{a} {b}");
        }
    }

    #[test]
    fn solution_satisfies_eq_5_12() {
        for (u, k) in [(0.3, 0.1), (30.0, 0.01), (1e5, 0.001)] {
            let x = g_trailing(u, k);
            let z = u / x;
            let rhs = 1.0 / (1.0 - (1.0 - k) * ((1.0 + z.powi(-2)).sqrt() - 1.0 / z));
            assert!((x / rhs - 1.0).abs() < 1e-10, "u={u} k={k}");
            assert!(x >= 1.0 && x <= 1.0 / k);
        }
    }
}
