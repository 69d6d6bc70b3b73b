//! The Lennard-Jones 3-9 law of the interface, used by the boundary element model of
//! Chapters 4-5 (`bem`, in its units) and by the shell of Chapter 3 (`fem::adhesion`, in
//! the shell's), and drawn in Fig. 2.3.
//!
//! Chapter 4 (ERRATA items 1, 8):
//!
//! sigma(h) = (8 dgamma / 3 eps) [(eps/h)^9 - (eps/h)^3], compression positive, with
//! dgamma = alpha sigma0 eps, alpha = 9 sqrt(3)/16. In the units of Eq. 4.6 (P = p/sigma0,
//! H = (h - eps) R/beta^2), h/eps = 1 + alpha lambda H and (Eq. 4.8)
//!   P(H) = (3 sqrt(3)/2) [z^-9 - z^-3],  z = 1 + alpha lambda H.
//! P = 0 at H = 0 (equilibrium separation), min P = -1 (the theoretical strength) at
//! z = 3^(1/6); the work of separation Int_0^inf -P dH = 1/lambda, i.e. dgamma.

pub const ALPHA: f64 = 0.974_278_579_257_493_4; // 9 sqrt(3) / 16

const C: f64 = 2.598_076_211_353_316; // 3 sqrt(3) / 2

/// z = 1 + alpha lambda H; callers keep it positive.
pub fn z_of(h: f64, lambda: f64) -> f64 {
    1.0 + ALPHA * lambda * h
}

/// P(H) and dP/dH.
pub fn pressure(h: f64, lambda: f64) -> (f64, f64) {
    let z = z_of(h, lambda);
    let z3 = z.powi(-3);
    let z9 = z3 * z3 * z3;
    let p = C * (z9 - z3);
    let dp = C * ALPHA * lambda * (-9.0 * z9 + 3.0 * z3) / z;
    (p, dp)
}

/// The interaction energy per unit area at separation h = z eps, in units of dgamma: the
/// potential of the law, sigma = -d(energy)/dh, zero at infinite separation:
///   energy(z) / dgamma = z^-8 / 3 - 4 z^-2 / 3,
/// -1 at equilibrium (z = 1: the work of adhesion), the disjoining pressure's minimum -sigma0
/// at z = 3^(1/6) where the energy bends (Fig. 2.3).
pub fn energy(z: f64) -> f64 {
    let z2 = z.powi(-2);
    z2.powi(4) / 3.0 - 4.0 * z2 / 3.0
}

/// The gap at which the repulsive branch (H <= 0) carries a compressive pressure P >= 0.
pub fn gap_for_pressure(p: f64, lambda: f64) -> f64 {
    assert!(p >= 0.0, "the repulsive branch carries P >= 0, got {p}");
    // P(z) = C (z^-9 - z^-3) decreases from +inf to 0 on (0, 1].
    let z = crate::numerics::roots::bisect(|z: f64| C * (z.powi(-9) - z.powi(-3)) - p, 1e-3, 1.0, 1e-15).unwrap_or(1.0);
    (z - 1.0) / (ALPHA * lambda)
}

/// The interaction energy per unit area as the shell's interface law uses it (Eq. 3.3:
/// the gap g' shifted by the equilibrium distance g0, so that g' = 0 touches), with its
/// first two derivatives in g': for g' > 0, with x = g0 / (g' + g0) = 1/z,
///   phi(g') = -(8 dgamma / 3) [x^2 / 2 - x^8 / 8],
/// the `energy` above in units of dgamma; phi = -dgamma for g' <= 0, where the penalty
/// contact carries the compression. `lifting`: for g' <= 0, the curvature of the g' > 0
/// side, 16 dgamma / g0^2 (the stiffness against lifting a touching point off).
pub fn shifted_potential(gamma: f64, g0: f64, g: f64, lifting: bool) -> Potential {
    let c = 8.0 * gamma / 3.0;
    if g <= 0.0 {
        let d2 = if lifting { 16.0 * gamma / (g0 * g0) } else { 0.0 };
        return Potential { phi: -gamma, d1: 0.0, d2 };
    }
    let x = g0 / (g + g0);
    let (x2, x4) = (x * x, x.powi(4));
    let x8 = x4 * x4;
    Potential {
        phi: -c * (0.5 * x2 - 0.125 * x8),
        d1: c / g0 * (x2 * x - x8 * x),
        d2: 3.0 * c / (g0 * g0) * (3.0 * x8 * x2 - x4),
    }
}

/// An energy per unit area and its first two derivatives in the gap.
#[derive(Clone, Copy, Debug)]
pub struct Potential {
    pub phi: f64,
    pub d1: f64,
    pub d2: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equilibrium_strength_and_work_of_adhesion() {
        assert_eq!(pressure(0.0, 1.0).0, 0.0);
        assert!((ALPHA - 9.0 * 3f64.sqrt() / 16.0).abs() < 1e-15);
        // Minimum -1 at z = 3^(1/6).
        let lambda = 2.0;
        let h_min = (3f64.powf(1.0 / 6.0) - 1.0) / (ALPHA * lambda);
        let (p, dp) = pressure(h_min, lambda);
        assert!((p + 1.0).abs() < 1e-12 && dp.abs() < 1e-10, "{p} {dp}");
        // Work of separation = 1/lambda (dgamma in these units), by quadrature.
        let f = |u: f64| -pressure(u.exp(), lambda).0 * u.exp();
        let (w, _) = crate::numerics::quad::integrate(&f, (1e-9f64).ln(), (1e6f64).ln(), 1e-13, 40);
        assert!((w * lambda - 1.0).abs() < 1e-6, "{}", w * lambda);
        // The inverse of the repulsive branch.
        for p in [0.0, 0.3, 5.0, 200.0] {
            let h = gap_for_pressure(p, lambda);
            assert!(h <= 0.0 && (pressure(h, lambda).0 - p).abs() < 1e-9 * (1.0 + p), "{p}");
        }
        // The energy is the pressure's potential: -d(energy dgamma)/dh = sigma, i.e. in these
        // units dgamma/(sigma0 eps) = alpha times -d energy/dz = P at z.
        for z in [0.9, 1.0, 1.12, 1.5, 3.0] {
            let d = (energy(z + 1e-6) - energy(z - 1e-6)) / 2e-6;
            let h = (z - 1.0) / (ALPHA * lambda);
            assert!((-ALPHA * d - pressure(h, lambda).0).abs() < 1e-8, "{z}");
        }
        assert_eq!(energy(1.0), -1.0);
        // Derivative by finite differences.
        let h = 0.05;
        let fd = (pressure(h + 1e-7, lambda).0 - pressure(h - 1e-7, lambda).0) / 2e-7;
        assert!((fd - pressure(h, lambda).1).abs() < 1e-5 * fd.abs());
    }
}
