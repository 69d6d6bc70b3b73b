//! Hyperelastic laws of the shell's solid elements, in the axisymmetric components of the
//! deformation gradient F = (F_rR, F_rZ, F_zR, F_zZ, F_tt) (the in-plane block and the hoop
//! stretch; F is block diagonal in 3D).
//!
//! Three laws, each with the Lame constants (mu, lambda) of E and nu, so that all reduce to
//! linear elasticity with E and nu at small strain and differ only at finite strain:
//! - compressible neo-Hookean: W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,
//!   P = mu (F - F^-T) + lambda ln J F^-T (the default: it stays stiff under strong
//!   compression, which an inverting shell pressed on a plate reaches locally);
//! - St Venant-Kirchhoff: W = lambda/2 (tr E)^2 + mu tr(E^2), E = (F^T F - I)/2, P = F S,
//!   S = lambda tr(E) I + 2 mu E (CalculiX's `*ELASTIC` with NLGEOM; it softens in
//!   compression);
//! - Hencky: W = mu tr(eps^2) + lambda/2 (tr eps)^2 with the logarithmic strain
//!   eps = ln V = (1/2) ln(F F^T), Kirchhoff stress tau = 2 mu eps + lambda tr(eps) I and
//!   P = tau F^-T (the large-strain analogue of a "linear elastic" material with large
//!   deflection in commercial codes).
//!
//! Units: stresses in the units of E. The tangent A = dP/dF is exact for the first two; for
//! Hencky it is the central difference of P (step 1e-6, symmetrised: A is symmetric for a
//! hyperelastic law), accurate to about 1e-9 relative, enough for Newton's quadratic rate.

// Index loops over tensor components read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

/// Lame constants (mu, lambda) of Young's modulus and Poisson's ratio.
pub fn lame(e: f64, nu: f64) -> (f64, f64) {
    (e / (2.0 * (1.0 + nu)), e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)))
}

/// Which strain energy.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Law {
    #[default]
    NeoHookean,
    SaintVenantKirchhoff,
    Hencky,
}

/// A law with its Lame constants.
#[derive(Clone, Copy, Debug)]
pub struct Material {
    pub law: Law,
    pub mu: f64,
    pub lambda: f64,
}

/// (i, J) of each component, in 3D indices r = 0, z = 1, theta = 2.
pub(crate) const INDEX: [(usize, usize); 5] = [(0, 0), (0, 1), (1, 0), (1, 1), (2, 2)];

/// ln J and F^-1 (3 x 3, block diagonal) of F, or None if J <= 0.
#[inline(always)]
fn kinematics(f: &[f64; 5]) -> Option<(f64, [[f64; 3]; 3])> {
    let det2 = f[0] * f[3] - f[1] * f[2];
    let j = det2 * f[4];
    if !(j > 0.0) {
        return None;
    }
    let mut inv = [[0.0; 3]; 3];
    // One division for the four entries (the element kernels' inner loop).
    let r = 1.0 / det2;
    inv[0][0] = f[3] * r;
    inv[0][1] = -f[1] * r;
    inv[1][0] = -f[2] * r;
    inv[1][1] = f[0] * r;
    inv[2][2] = 1.0 / f[4];
    Some((j.ln(), inv))
}

/// F as a 3 x 3 matrix.
#[inline(always)]
fn full(f: &[f64; 5]) -> [[f64; 3]; 3] {
    [[f[0], f[1], 0.0], [f[2], f[3], 0.0], [0.0, 0.0, f[4]]]
}

/// The components of a 3 x 3 tensor.
#[inline(always)]
fn components(t: &[[f64; 3]; 3]) -> [f64; 5] {
    std::array::from_fn(|c| t[INDEX[c].0][INDEX[c].1])
}

/// ln of a symmetric positive-definite 2 x 2 matrix [[a, b], [b, d]] and the logs of its
/// eigenvalues, by the divided difference of ln over the eigenvalues (stable when they
/// coincide). None if not positive definite.
#[inline(always)]
fn log_sym2(a: f64, b: f64, d: f64) -> Option<([f64; 3], [f64; 2])> {
    let mean = 0.5 * (a + d);
    let radius = (0.25 * (a - d) * (a - d) + b * b).sqrt();
    let (l1, l2) = (mean + radius, mean - radius);
    if !(l2 > 0.0) {
        return None;
    }
    // ln M = ln(l2) I + (M - l2 I) (ln l1 - ln l2)/(l1 - l2).
    let x = (l1 - l2) / l2;
    let slope = if x > 1e-8 { x.ln_1p() / (l1 - l2) } else { (1.0 - 0.5 * x + x * x / 3.0) / l2 };
    let (ln1, ln2) = (l1.ln(), l2.ln());
    Some(([ln2 + (a - l2) * slope, b * slope, ln2 + (d - l2) * slope], [ln1, ln2]))
}

impl Material {
    pub fn new(law: Law, e: f64, nu: f64) -> Material {
        let (mu, lambda) = lame(e, nu);
        Material { law, mu, lambda }
    }

    /// The first Piola-Kirchhoff stress P (components), or None if J <= 0.
    #[inline(always)]
    pub fn piola(&self, f: &[f64; 5]) -> Option<[f64; 5]> {
        let (mu, lambda) = (self.mu, self.lambda);
        match self.law {
            Law::NeoHookean => {
                let (lnj, inv) = kinematics(f)?;
                Some(neo_hookean_piola(f, lnj, &inv, mu, lambda))
            }
            Law::SaintVenantKirchhoff => {
                kinematics(f)?;
                Some(components(&svk_pk2(f, mu, lambda).1))
            }
            Law::Hencky => {
                let (_, inv) = kinematics(f)?;
                let tau = hencky_kirchhoff(f, mu, lambda)?;
                // P = tau F^-T: P_iJ = tau_ik F^-1_Jk.
                Some(std::array::from_fn(|c| {
                    let (i, jj) = INDEX[c];
                    (0..3).map(|k| tau[i][k] * inv[jj][k]).sum()
                }))
            }
        }
    }

    /// P (components) and A = dP/dF (5 x 5), or None if J <= 0.
    #[inline(always)]
    pub fn stress(&self, f: &[f64; 5]) -> Option<([f64; 5], [[f64; 5]; 5])> {
        let (mu, lambda) = (self.mu, self.lambda);
        let mut a = [[0.0; 5]; 5];
        match self.law {
            Law::NeoHookean => {
                let (lnj, inv) = kinematics(f)?;
                let p = neo_hookean_piola(f, lnj, &inv, mu, lambda);
                for (c, &(i, jj)) in INDEX.iter().enumerate() {
                    for (d, &(k, l)) in INDEX.iter().enumerate() {
                        let delta = if i == k && jj == l { 1.0 } else { 0.0 };
                        a[c][d] =
                            mu * delta + lambda * inv[jj][i] * inv[l][k] + (mu - lambda * lnj) * inv[l][i] * inv[jj][k];
                    }
                }
                Some((p, a))
            }
            Law::SaintVenantKirchhoff => {
                kinematics(f)?;
                let (s, p) = svk_pk2(f, mu, lambda);
                let g = full(f);
                // A_iJkL = delta_ik S_JL + lambda F_iJ F_kL + mu ((F F^T)_ik delta_JL + F_iL F_kJ).
                let b = |i: usize, k: usize| (0..3).map(|m| g[i][m] * g[k][m]).sum::<f64>();
                for (c, &(i, jj)) in INDEX.iter().enumerate() {
                    for (d, &(k, l)) in INDEX.iter().enumerate() {
                        let dik = if i == k { 1.0 } else { 0.0 };
                        let djl = if jj == l { 1.0 } else { 0.0 };
                        a[c][d] =
                            dik * s[jj][l] + lambda * g[i][jj] * g[k][l] + mu * (b(i, k) * djl + g[i][l] * g[k][jj]);
                    }
                }
                Some((components(&p), a))
            }
            Law::Hencky => {
                let p = self.piola(f)?;
                let h = 1e-6;
                for d in 0..5 {
                    let mut fp = *f;
                    let mut fm = *f;
                    fp[d] += h;
                    fm[d] -= h;
                    let (pp, pm) = (self.piola(&fp)?, self.piola(&fm)?);
                    for c in 0..5 {
                        a[c][d] = (pp[c] - pm[c]) / (2.0 * h);
                    }
                }
                for c in 0..5 {
                    for d in 0..c {
                        let m = 0.5 * (a[c][d] + a[d][c]);
                        a[c][d] = m;
                        a[d][c] = m;
                    }
                }
                Some((p, a))
            }
        }
    }

    /// The strain energy density W per reference volume, or None if J <= 0.
    #[inline(always)]
    pub fn energy(&self, f: &[f64; 5]) -> Option<f64> {
        let (mu, lambda) = (self.mu, self.lambda);
        let j = (f[0] * f[3] - f[1] * f[2]) * f[4];
        if !(j > 0.0) {
            return None;
        }
        match self.law {
            Law::NeoHookean => {
                let i1: f64 = f.iter().map(|v| v * v).sum();
                Some(0.5 * mu * (i1 - 3.0) - mu * j.ln() + 0.5 * lambda * j.ln().powi(2))
            }
            Law::SaintVenantKirchhoff => {
                let e = green(f);
                let tr: f64 = (0..3).map(|i| e[i][i]).sum();
                let ee: f64 = (0..3).flat_map(|i| (0..3).map(move |k| (i, k))).map(|(i, k)| e[i][k] * e[i][k]).sum();
                Some(0.5 * lambda * tr * tr + mu * ee)
            }
            Law::Hencky => {
                let (_, [ln1, ln2]) = left_log(f)?;
                let ln3 = 2.0 * f[4].abs().ln();
                let eps = [0.5 * ln1, 0.5 * ln2, 0.5 * ln3];
                let tr: f64 = eps.iter().sum();
                Some(mu * eps.iter().map(|e| e * e).sum::<f64>() + 0.5 * lambda * tr * tr)
            }
        }
    }
}

/// Neo-Hookean P from F, ln J and F^-1 (F^-T_iJ = F^-1_Ji), kinematics computed once by
/// the caller (the tangent kernel's hot path).
#[inline(always)]
fn neo_hookean_piola(f: &[f64; 5], lnj: f64, inv: &[[f64; 3]; 3], mu: f64, lambda: f64) -> [f64; 5] {
    std::array::from_fn(|c| {
        let (i, jj) = INDEX[c];
        mu * (f[c] - inv[jj][i]) + lambda * lnj * inv[jj][i]
    })
}

/// Green-Lagrange strain E = (F^T F - I)/2.
#[inline(always)]
fn green(f: &[f64; 5]) -> [[f64; 3]; 3] {
    let g = full(f);
    let mut e = [[0.0; 3]; 3];
    for i in 0..3 {
        for k in 0..3 {
            let c: f64 = (0..3).map(|m| g[m][i] * g[m][k]).sum();
            e[i][k] = 0.5 * (c - if i == k { 1.0 } else { 0.0 });
        }
    }
    e
}

/// St Venant-Kirchhoff: the second Piola-Kirchhoff stress S and P = F S (3 x 3).
#[inline(always)]
fn svk_pk2(f: &[f64; 5], mu: f64, lambda: f64) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
    let e = green(f);
    let tr = e[0][0] + e[1][1] + e[2][2];
    let mut s = [[0.0; 3]; 3];
    for i in 0..3 {
        for k in 0..3 {
            s[i][k] = 2.0 * mu * e[i][k] + if i == k { lambda * tr } else { 0.0 };
        }
    }
    let g = full(f);
    let mut p = [[0.0; 3]; 3];
    for i in 0..3 {
        for k in 0..3 {
            p[i][k] = (0..3).map(|m| g[i][m] * s[m][k]).sum();
        }
    }
    (s, p)
}

/// ln b of the in-plane block of b = F F^T ([ln b_rr, ln b_rz, ln b_zz]) and the logs of its
/// eigenvalues; None if degenerate.
#[inline(always)]
fn left_log(f: &[f64; 5]) -> Option<([f64; 3], [f64; 2])> {
    let a = f[0] * f[0] + f[1] * f[1];
    let b = f[0] * f[2] + f[1] * f[3];
    let d = f[2] * f[2] + f[3] * f[3];
    log_sym2(a, b, d)
}

/// Hencky: the Kirchhoff stress tau = 2 mu eps + lambda tr(eps) I, eps = (1/2) ln(F F^T).
#[inline(always)]
fn hencky_kirchhoff(f: &[f64; 5], mu: f64, lambda: f64) -> Option<[[f64; 3]; 3]> {
    let ([lrr, lrz, lzz], _) = left_log(f)?;
    let ltt = 2.0 * f[4].abs().ln();
    let (err, erz, ezz, ett) = (0.5 * lrr, 0.5 * lrz, 0.5 * lzz, 0.5 * ltt);
    let tr = err + ezz + ett;
    Some([
        [2.0 * mu * err + lambda * tr, 2.0 * mu * erz, 0.0],
        [2.0 * mu * erz, 2.0 * mu * ezz + lambda * tr, 0.0],
        [0.0, 0.0, 2.0 * mu * ett + lambda * tr],
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAWS: [Law; 3] = [Law::NeoHookean, Law::SaintVenantKirchhoff, Law::Hencky];

    fn stretched(scale: f64) -> [f64; 5] {
        [1.0 + 0.8 * scale, 0.3 * scale, -0.5 * scale, 1.0 - 0.6 * scale, 1.0 + 0.4 * scale]
    }

    #[test]
    fn stress_is_the_energy_gradient_and_the_tangent_its_jacobian() {
        for law in LAWS {
            let m = Material::new(law, 1.3, 0.45);
            for scale in [0.05, 0.3] {
                let f = stretched(scale);
                let (p, a) = m.stress(&f).unwrap();
                let h = 1e-6;
                for d in 0..5 {
                    let (mut fp, mut fm) = (f, f);
                    fp[d] += h;
                    fm[d] -= h;
                    let dw = (m.energy(&fp).unwrap() - m.energy(&fm).unwrap()) / (2.0 * h);
                    assert!((dw - p[d]).abs() < 1e-7, "{law:?} P[{d}]: {dw} vs {}", p[d]);
                    let (pp, pm) = (m.piola(&fp).unwrap(), m.piola(&fm).unwrap());
                    for c in 0..5 {
                        let fd = (pp[c] - pm[c]) / (2.0 * h);
                        assert!((fd - a[c][d]).abs() < 1e-6, "{law:?} A[{c}][{d}]: {fd} vs {}", a[c][d]);
                    }
                }
            }
        }
    }

    #[test]
    fn the_laws_agree_at_small_strain_and_differ_at_finite_strain() {
        // At strain 1e-4 the three stresses agree to O(strain^2)/strain = 1e-4 relative; at 30 %
        // they differ by tens of per cent (the laws' second-order terms differ).
        let stresses = |scale: f64| LAWS.map(|law| Material::new(law, 1.3, 0.45).piola(&stretched(scale)).unwrap());
        let spread = |s: &[[f64; 5]; 3]| {
            let norm = s[0].iter().map(|v| v.abs()).fold(0.0, f64::max);
            let d = (0..5).map(|c| (s[1][c] - s[0][c]).abs().max((s[2][c] - s[0][c]).abs())).fold(0.0, f64::max);
            d / norm
        };
        assert!(spread(&stresses(1e-4)) < 1e-3, "{}", spread(&stresses(1e-4)));
        assert!(spread(&stresses(0.3)) > 0.05, "{}", spread(&stresses(0.3)));
    }

    #[test]
    fn the_matrix_log_is_exact_at_equal_and_distinct_eigenvalues() {
        // Diagonal: the logs of the entries; equal eigenvalues: ln(l) I.
        let (l, e) = log_sym2(2.0, 0.0, 0.5).unwrap();
        assert!((l[0] - 2f64.ln()).abs() < 1e-15 && l[1].abs() < 1e-15 && (l[2] - 0.5f64.ln()).abs() < 1e-15);
        assert!((e[0] - 2f64.ln()).abs() < 1e-15);
        let (l, _) = log_sym2(1.3, 0.0, 1.3).unwrap();
        assert!((l[0] - 1.3f64.ln()).abs() < 1e-15 && (l[2] - 1.3f64.ln()).abs() < 1e-15);
        // A rotated diagonal matrix: exp of the log gives it back (2 x 2 exp by eigenvalues).
        let (c, s) = (0.6f64, 0.8f64);
        let (d1, d2) = (3.0f64, 0.7f64);
        let m = [c * c * d1 + s * s * d2, c * s * (d1 - d2), s * s * d1 + c * c * d2];
        let (l, _) = log_sym2(m[0], m[1], m[2]).unwrap();
        let expect =
            [c * c * d1.ln() + s * s * d2.ln(), c * s * (d1.ln() - d2.ln()), s * s * d1.ln() + c * c * d2.ln()];
        for k in 0..3 {
            assert!((l[k] - expect[k]).abs() < 1e-14, "{k}: {} vs {}", l[k], expect[k]);
        }
    }
}
