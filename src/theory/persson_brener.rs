//! Persson–Brener energy release at the trailing edge of a viscoelastic contact and the
//! adhesive friction it implies (thesis Eqs. 5.9–5.15, with ERRATA items 13 and 14).
//!
//! Units: u = v / v0 with v0 = c0 / (2 pi tau) (Eq. 5.15), c0 = E0 dgamma / (2 pi sigma_c^2)
//! (Eq. 5.11, with the relaxed modulus E0 as in ERRATA 14); x = c(v)/c0 = G_trail/dgamma
//! (Eq. 5.10). Eq. 5.12 reads
//!   x = [1 - (1 - k) (sqrt(1 + z^-2) - z^-1)]^-1,   z = u / x,
//! and sqrt(1 + z^-2) - z^-1 = z / (sqrt(1 + z^2) + 1) is evaluated in that form (no
//! cancellation at large z). x runs from 1 (u -> 0) to 1/k (u -> inf).
//! The friction per unit width (Eq. 5.13 normalised, ERRATA 13) is
//!   f_T / dgamma = x - 1/x   (G_lead = dgamma^2 / G_trail),
//! with the limits (ERRATA 14): (1 - k) u for u << 1, sqrt(u / (1 - k)) for
//! 1 << u << (1 - k)/k^2, and 1/k - k for u -> inf.

/// phi(z) = sqrt(1 + z^-2) - 1/z, written without cancellation.
fn phi(z: f64) -> f64 {
    if z.is_infinite() {
        return 1.0;
    }
    z / ((1.0 + z * z).sqrt() + 1.0)
}

/// Solves Eq. 5.12 for x = G_trail / dgamma at u = v/v0, modulus ratio k in (0, 1].
/// g(x) = x (1 - (1-k) phi(u/x)) - 1 is negative at x = 1 and positive at x = 1/k;
/// bisection in log x to machine precision.
pub fn g_trailing(u: f64, k: f64) -> f64 {
    assert!(u >= 0.0 && k > 0.0 && k <= 1.0);
    if u == 0.0 || k == 1.0 {
        return 1.0;
    }
    let g = |lx: f64| {
        let x = lx.exp();
        x * (1.0 - (1.0 - k) * phi(u / x)) - 1.0
    };
    let lx =
        crate::numerics::roots::bisect(g, 0.0, (1.0 / k).ln(), 1e-15).expect("Eq. 5.12 brackets its root on [1, 1/k]");
    lx.exp()
}

/// f_T / dgamma = x - 1/x (Eq. 5.13, normalised), computed as (x - 1)(x + 1)/x.
pub fn friction(u: f64, k: f64) -> f64 {
    let x = g_trailing(u, k);
    (x - 1.0) * (x + 1.0) / x
}

#[cfg(test)]
mod tests {
    use super::*;

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
