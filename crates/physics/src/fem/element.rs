//! The 8-node axisymmetric solid element of the Chapter 3 model (as ANSYS PLANE183),
//! geometrically nonlinear (total Lagrangian), with a hyperelastic law of `material`.
//!
//! Kinematics: reference coordinates (R, Z), displacements (u_r, u_z); the deformation
//! gradient has the in-plane block d(r, z)/d(R, Z) and the hoop stretch F_tt = 1 + u_r/R.
//! Material: `material::Material` (neo-Hookean by default), which reduces to linear
//! elasticity with E and nu at small strain. Nodal forces f_a = Int G_a^T P dV0 and the consistent tangent
//! K_ab = Int G_a^T (dP/dF) G_b dV0 (material and geometric parts together), dV0 = 2 pi R
//! dR dZ. G_a maps the nodal displacements of node a to the components (F_rR, F_rZ, F_zR,
//! F_zZ, F_tt).
//!
//! Gauss rule (`Integration`): 3 x 3 points by default, or 2 x 2, PLANE183's own rule for
//! its quadrilateral (ANSYS Theory Reference, PLANE183: "Stiffness and Stress Stiffness
//! Matrices ... 2 x 2"). With two elements through the thickness the 3 x 3 rule is too
//! stiff where adhesion and friction load the surface: at h/R = 0.06, mu = 0.5 its
//! dissipated energy is 1.4 % and its snap force 0.3 % above the values converged in the
//! thickness, which the 2 x 2 rule meets to 0.02 % on the same mesh (the two agree to
//! 0.03 % without adhesion and friction); but under an apex point force its spurious mode
//! makes the contact pressure at the apex oscillate (its peak nine times the converged
//! one), and on a thick shell (h/R >= 0.15) the elements at the load give way at once
//! (docs/shell.md, "The element's Gauss rule").

// Index loops over nodes and components read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use crate::numerics::vectorized_fn;

pub use super::material::lame;
use super::material::Material;

/// Natural coordinates of the 8 nodes (corners, then mid-sides).
const NODES: [(f64, f64); 8] =
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (0.0, -1.0), (1.0, 0.0), (0.0, 1.0), (-1.0, 0.0)];

/// Serendipity shape functions and their derivatives in (xi, eta).
pub fn shape(xi: f64, eta: f64) -> ([f64; 8], [[f64; 2]; 8]) {
    let mut n = [0.0; 8];
    let mut d = [[0.0; 2]; 8];
    for (a, &(xa, ya)) in NODES.iter().enumerate() {
        if a < 4 {
            n[a] = 0.25 * (1.0 + xi * xa) * (1.0 + eta * ya) * (xi * xa + eta * ya - 1.0);
            d[a] = [
                0.25 * xa * (1.0 + eta * ya) * (2.0 * xi * xa + eta * ya),
                0.25 * ya * (1.0 + xi * xa) * (xi * xa + 2.0 * eta * ya),
            ];
        } else if xa == 0.0 {
            n[a] = 0.5 * (1.0 - xi * xi) * (1.0 + eta * ya);
            d[a] = [-xi * (1.0 + eta * ya), 0.5 * ya * (1.0 - xi * xi)];
        } else {
            n[a] = 0.5 * (1.0 + xi * xa) * (1.0 - eta * eta);
            d[a] = [0.5 * xa * (1.0 - eta * eta), -eta * (1.0 + xi * xa)];
        }
    }
    (n, d)
}

/// 3-point Gauss-Legendre rule on [-1, 1].
pub const GAUSS: [(f64, f64); 3] =
    [(-0.774_596_669_241_483_4, 5.0 / 9.0), (0.0, 8.0 / 9.0), (0.774_596_669_241_483_4, 5.0 / 9.0)];

/// 2-point Gauss-Legendre rule on [-1, 1].
pub const GAUSS2: [(f64, f64); 2] = [(-0.577_350_269_189_625_8, 1.0), (0.577_350_269_189_625_8, 1.0)];

/// The Gauss rule of an element's forces and tangent.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Integration {
    /// 3 x 3 points (the default): exact for the small-strain stiffness of an undistorted
    /// element (CalculiX's CAX8).
    #[default]
    Full,
    /// 2 x 2 points: ANSYS PLANE183's rule for its quadrilateral (the thesis' element) and
    /// CalculiX's CAX8R. Its one spurious mode per element (of zero energy in plane strain,
    /// of a little here, from the hoop strain) is not shared by neighbours: it does not
    /// propagate through a mesh.
    Reduced,
}

impl Integration {
    fn rule(self) -> &'static [(f64, f64)] {
        match self {
            Integration::Reduced => &GAUSS2,
            Integration::Full => &GAUSS,
        }
    }
}

/// A Gauss point in the reference configuration: the shape functions' R and Z derivatives,
/// the hoop terms N/R and the weight 2 pi R det(J) w.
#[derive(Clone, Copy)]
struct Point {
    dn: [[f64; 2]; 8],
    /// N_a / R, what u_r of node a adds to the hoop stretch F_tt: divided once here (three
    /// divisions per node and Gauss point had been a third of an element's tangent, perf).
    hoop: [f64; 8],
    dv: f64,
}

/// The reference geometry of one element at its Gauss points (shape derivatives, hoop
/// terms, weight; 2 x 2 or 3 x 3, the first `count` of `points`): it depends only on the
/// mesh, so a model computes it once instead of at every assembly.
#[derive(Clone, Copy)]
pub struct Geometry {
    points: [Point; 9],
    count: usize,
}

impl Geometry {
    /// Panics on an element with a non-positive Jacobian (a broken mesh).
    pub fn new(x: &[[f64; 2]; 8], integration: Integration) -> Geometry {
        let rule = integration.rule();
        let mut out = [Point { dn: [[0.0; 2]; 8], hoop: [0.0; 8], dv: 0.0 }; 9];
        for (i, &(xi, wx)) in rule.iter().enumerate() {
            for (k, &(eta, wy)) in rule.iter().enumerate() {
                let (n, d) = shape(xi, eta);
                let mut j = [[0.0; 2]; 2]; // j[c][k] = dX_c / dxi_k
                let mut radius = 0.0;
                for a in 0..8 {
                    radius += n[a] * x[a][0];
                    for c in 0..2 {
                        for k in 0..2 {
                            j[c][k] += x[a][c] * d[a][k];
                        }
                    }
                }
                let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                assert!(det > 0.0, "element with non-positive Jacobian {det}");
                // dN/dX_c = dN/dxi_k (J^-1)_kc.
                let inv = [[j[1][1] / det, -j[0][1] / det], [-j[1][0] / det, j[0][0] / det]];
                let mut dn = [[0.0; 2]; 8];
                for a in 0..8 {
                    for c in 0..2 {
                        dn[a][c] = d[a][0] * inv[0][c] + d[a][1] * inv[1][c];
                    }
                }
                let hoop = std::array::from_fn(|a| n[a] / radius);
                out[rule.len() * i + k] = Point { dn, hoop, dv: 2.0 * std::f64::consts::PI * radius * det * wx * wy };
            }
        }
        Geometry { points: out, count: rule.len() * rule.len() }
    }

    fn points(&self) -> &[Point] {
        &self.points[..self.count]
    }
}

/// Components (F_rR, F_rZ, F_zR, F_zZ, F_tt) at a point.
#[inline(always)]
fn deformation(p: &Point, u: &[[f64; 2]; 8]) -> [f64; 5] {
    let mut f = [1.0, 0.0, 0.0, 1.0, 1.0];
    for a in 0..8 {
        f[0] += p.dn[a][0] * u[a][0];
        f[1] += p.dn[a][1] * u[a][0];
        f[2] += p.dn[a][0] * u[a][1];
        f[3] += p.dn[a][1] * u[a][1];
        f[4] += p.hoop[a] * u[a][0];
    }
    f
}

/// Node b's internal force (r, z) at a Gauss point with stress p (one term of Int G^T P dV0).
#[inline(always)]
fn nodal_force(pt: &Point, b: usize, p: &[f64; 5]) -> [f64; 2] {
    let (dr, dz, t) = (pt.dn[b][0], pt.dn[b][1], pt.hoop[b]);
    [(dr * p[0] + dz * p[1] + t * p[4]) * pt.dv, (dr * p[2] + dz * p[3]) * pt.dv]
}

vectorized_fn! {
    /// The internal forces of `forces_and_tangent_of` alone (bitwise the same), without the
    /// tangent: what a line search needs of a trial step.
    pub fn forces_of(geometry: &Geometry, u: &[[f64; 2]; 8], m: Material) -> Option<[f64; 16]> = forces_kernel;
}

#[inline(always)]
fn forces_kernel(geometry: &Geometry, u: &[[f64; 2]; 8], m: Material) -> Option<[f64; 16]> {
    let mut fint = [0.0; 16];
    for pt in geometry.points() {
        let f = deformation(pt, u);
        let p = m.piola(&f)?;
        for b in 0..8 {
            let [fr, fz] = nodal_force(pt, b, &p);
            fint[2 * b] += fr;
            fint[2 * b + 1] += fz;
        }
    }
    Some(fint)
}

/// The element's strain energy or None if inverted somewhere.
pub fn energy(x: &[[f64; 2]; 8], u: &[[f64; 2]; 8], m: Material, integration: Integration) -> Option<f64> {
    energy_of(&Geometry::new(x, integration), u, m)
}

/// `energy` of an element whose Gauss-point geometry is known.
pub fn energy_of(geometry: &Geometry, u: &[[f64; 2]; 8], m: Material) -> Option<f64> {
    let mut w = 0.0;
    for p in geometry.points() {
        w += p.dv * m.energy(&deformation(p, u))?;
    }
    Some(w)
}

/// Internal forces (16: node a's r then z) and tangent (16 x 16), or None if the element is
/// inverted at a Gauss point (the caller cuts the step).
pub fn forces_and_tangent(
    x: &[[f64; 2]; 8],
    u: &[[f64; 2]; 8],
    m: Material,
    integration: Integration,
) -> Option<ForcesAndTangent> {
    forces_and_tangent_of(&Geometry::new(x, integration), u, m)
}

/// An element's internal forces and tangent.
pub type ForcesAndTangent = ([f64; 16], [[f64; 16]; 16]);

/// `forces_and_tangent` of an element whose Gauss-point geometry is known.
pub fn forces_and_tangent_of(geometry: &Geometry, u: &[[f64; 2]; 8], m: Material) -> Option<ForcesAndTangent> {
    let mut out = ([0.0; 16], [[0.0; 16]; 16]);
    forces_and_tangent_into(geometry, u, m, &mut out).then_some(out)
}

vectorized_fn! {
    /// `forces_and_tangent_of` written into `out` (every entry), false if the element is
    /// inverted: an assembly's blocks are written in place, not returned (a 2 kB copy per
    /// element had been 1 % of a frictional shell point, perf).
    ///
    /// G (5 x 16) is sparse: the column of u_r at node b is (dN_b/dR, dN_b/dZ, 0, 0, N_b/R), that
    /// of u_z (0, 0, dN_b/dR, dN_b/dZ, 0); the products below use only its nonzeros, and K =
    /// Int G^T A G dV0 is symmetric (A = dP/dF is, W being a potential), so only r >= q is
    /// summed and mirrored.
    pub fn forces_and_tangent_into(geometry: &Geometry, u: &[[f64; 2]; 8], m: Material, out: &mut ForcesAndTangent)
        -> bool = tangent_kernel;
}

#[inline(always)]
fn tangent_kernel(geometry: &Geometry, u: &[[f64; 2]; 8], m: Material, out: &mut ForcesAndTangent) -> bool {
    let (fint, k) = out;
    *fint = [0.0; 16];
    // The tangent by blocks of node pairs (b, c): rr[b][c] couples u_r of b with u_r of c,
    // rz u_r with u_z, zr u_z with u_r, zz u_z with u_z; interleaved into K at the end. In
    // this layout the loops over c run over contiguous memory and vectorise.
    let (mut rr, mut rz, mut zr, mut zz) = ([[0.0; 8]; 8], [[0.0; 8]; 8], [[0.0; 8]; 8], [[0.0; 8]; 8]);
    for pt in geometry.points() {
        let f = deformation(pt, u);
        let Some((p, a)) = m.stress(&f) else {
            return false;
        };
        let dr: [f64; 8] = std::array::from_fn(|b| pt.dn[b][0]);
        let dz: [f64; 8] = std::array::from_fn(|b| pt.dn[b][1]);
        let hoop = pt.hoop;
        // (A G)_{c, q} dV0 for the u_r columns (ar[c][b]) and the u_z ones (az[c][b]).
        let mut ar = [[0.0; 8]; 5];
        let mut az = [[0.0; 8]; 5];
        for c in 0..5 {
            for b in 0..8 {
                ar[c][b] = (a[c][0] * dr[b] + a[c][1] * dz[b] + a[c][4] * hoop[b]) * pt.dv;
                az[c][b] = (a[c][2] * dr[b] + a[c][3] * dz[b]) * pt.dv;
            }
        }
        for b in 0..8 {
            let [fr, fz] = nodal_force(pt, b, &p);
            fint[2 * b] += fr;
            fint[2 * b + 1] += fz;
            let (gr, gz, t) = (dr[b], dz[b], hoop[b]);
            // Every pair, in whole vectors (a triangular range needs masked loads and
            // stores, slower than the products they save); the upper triangle of K is read
            // from them below and mirrored.
            for c in 0..8 {
                rr[b][c] += gr * ar[0][c] + gz * ar[1][c] + t * ar[4][c];
                rz[b][c] += gr * az[0][c] + gz * az[1][c] + t * az[4][c];
                zr[b][c] += gr * ar[2][c] + gz * ar[3][c];
                zz[b][c] += gr * az[2][c] + gz * az[3][c];
            }
        }
    }
    for b in 0..8 {
        for c in b..8 {
            k[2 * b][2 * c] = rr[b][c];
            k[2 * b][2 * c + 1] = rz[b][c];
            k[2 * b + 1][2 * c + 1] = zz[b][c];
            if c > b {
                k[2 * b + 1][2 * c] = zr[b][c];
            }
        }
    }
    for q in 0..16 {
        for r in 0..q {
            k[q][r] = k[r][q];
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::material::Law;

    /// A curved element of a shell section near the axis (r from 0.2).
    fn element() -> [[f64; 2]; 8] {
        let node = |phi: f64, rho: f64| [rho * phi.sin(), rho * phi.cos()];
        let (p0, p1, r0, r1) = (0.2, 0.35, 1.0, 1.1);
        let (pm, rm) = (0.5 * (p0 + p1), 0.5 * (r0 + r1));
        [node(p0, r0), node(p1, r0), node(p1, r1), node(p0, r1), node(pm, r0), node(p1, rm), node(pm, r1), node(p0, rm)]
    }

    fn displacement(scale: f64) -> [[f64; 2]; 8] {
        let mut u = [[0.0; 2]; 8];
        for (a, v) in u.iter_mut().enumerate() {
            *v = [scale * (0.3 * (a as f64 * 1.3).sin()), scale * (0.2 * (a as f64 * 0.7).cos() - 0.1)];
        }
        u
    }

    #[test]
    fn shape_functions_partition_unity_and_interpolate() {
        for &(xi, eta) in &[(0.3, -0.7), (-1.0, 0.2), (0.0, 0.0)] {
            let (n, d) = shape(xi, eta);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            assert!(
                d.iter().map(|g| g[0]).sum::<f64>().abs() < 1e-14 && d.iter().map(|g| g[1]).sum::<f64>().abs() < 1e-14
            );
        }
        for (a, &(xa, ya)) in NODES.iter().enumerate() {
            let (n, _) = shape(xa, ya);
            for (b, v) in n.iter().enumerate() {
                assert!((v - f64::from(u8::from(a == b))).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn forces_are_the_energy_gradient_and_the_tangent_their_jacobian() {
        let m = Material::new(Law::NeoHookean, 1.3, 0.45);
        let x = element();
        let u = displacement(0.05);
        for rule in [Integration::Reduced, Integration::Full] {
            let (f, k) = forces_and_tangent(&x, &u, m, rule).unwrap();
            let h = 1e-6;
            let bump = |q: usize, s: f64| {
                let mut v = u;
                v[q / 2][q % 2] += s;
                v
            };
            for q in 0..16 {
                let fd = (energy(&x, &bump(q, h), m, rule).unwrap() - energy(&x, &bump(q, -h), m, rule).unwrap())
                    / (2.0 * h);
                assert!(
                    (fd - f[q]).abs() < 1e-6 * f.iter().map(|v| v.abs()).fold(0.0, f64::max),
                    "{rule:?} f[{q}]: {fd} vs {}",
                    f[q]
                );
                let (fp, _) = forces_and_tangent(&x, &bump(q, h), m, rule).unwrap();
                let (fm, _) = forces_and_tangent(&x, &bump(q, -h), m, rule).unwrap();
                for r in 0..16 {
                    let kd = (fp[r] - fm[r]) / (2.0 * h);
                    assert!(
                        (kd - k[r][q]).abs() < 1e-5 * k[r][r].abs().max(1.0),
                        "{rule:?} K[{r}][{q}]: {kd} vs {}",
                        k[r][q]
                    );
                }
            }
        }
    }

    /// The number of eigenvalues of a symmetric 16 x 16 matrix below `tol` times its largest
    /// in magnitude.
    fn null_space_dimension(k: &[[f64; 16]; 16], tol: f64) -> usize {
        let eigenvalues =
            faer::Mat::from_fn(16, 16, |i, j| k[i][j]).self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
        let largest = eigenvalues.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        eigenvalues.iter().filter(|v| v.abs() < tol * largest).count()
    }

    #[test]
    fn the_reduced_rule_leaves_one_soft_spurious_mode_per_element_the_full_rule_none() {
        // An axisymmetric element's only rigid motion is the translation along the axis
        // (an exact zero eigenvalue under both rules); the 2 x 2 rule adds the serendipity
        // element's spurious mode (Zienkiewicz and Taylor, "The Finite Element Method", vol.
        // 1, on reduced integration of the 8-node quadrilateral), of zero energy in plane
        // strain and of a little here, from the hoop strain: 7e-7 of the largest eigenvalue
        // on this element (the next one 1.4e-4). A mesh does not share it between neighbours (a whole
        // shell's tangent is positive definite: `system::tests`).
        let m = Material::new(Law::NeoHookean, 1.3, 0.45);
        let u = [[0.0; 2]; 8];
        let small = |rule, tol| null_space_dimension(&forces_and_tangent(&element(), &u, m, rule).unwrap().1, tol);
        assert_eq!(small(Integration::Full, 1e-10), 1);
        assert_eq!(small(Integration::Full, 1e-4), 1);
        assert_eq!(small(Integration::Reduced, 1e-8), 1);
        assert_eq!(small(Integration::Reduced, 1e-5), 2);
    }

    #[test]
    fn the_vectorized_kernels_give_the_baselines_bits() {
        // `forces_and_tangent_of` and `forces_of` run the kernels compiled for AVX2 where the
        // CPU has it; called directly here, the kernels are compiled for the baseline.
        let m = Material::new(Law::NeoHookean, 1.3, 0.45);
        for (rule, scale) in
            [Integration::Reduced, Integration::Full].into_iter().flat_map(|r| [(r, 0.0), (r, 0.01), (r, 0.05)])
        {
            let geometry = Geometry::new(&element(), rule);
            let u = displacement(scale);
            let (f, k) = forces_and_tangent_of(&geometry, &u, m).unwrap();
            let mut baseline = ([1.0; 16], [[1.0; 16]; 16]);
            assert!(tangent_kernel(&geometry, &u, m, &mut baseline));
            let (f0, k0) = baseline;
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&f), bits(&f0));
            assert_eq!(bits(k.as_flattened()), bits(k0.as_flattened()));
            assert_eq!(bits(&forces_of(&geometry, &u, m).unwrap()), bits(&f0));
            assert_eq!(bits(&forces_kernel(&geometry, &u, m).unwrap()), bits(&f0));
        }
    }

    #[test]
    fn rigid_translation_along_the_axis_is_force_free() {
        let m = Material::new(Law::NeoHookean, 1.3, 0.45);
        let u = [[0.0, 0.37]; 8];
        for rule in [Integration::Reduced, Integration::Full] {
            let (f, _) = forces_and_tangent(&element(), &u, m, rule).unwrap();
            assert!(f.iter().all(|v| v.abs() < 1e-12), "{rule:?}: {f:?}");
        }
    }

    #[test]
    fn small_strain_limit_is_linear_elasticity_with_e_and_nu() {
        // Uniaxial stress along z with lateral contraction nu: u_z = eps Z, u_r = -nu eps R.
        // Forces on the element are then those of sigma_zz = E eps alone: zero net radial
        // force, and the resultant axial force equals E eps times the annulus area.
        let (e, nu) = (1.3, 0.45);
        let m = Material::new(Law::NeoHookean, e, nu);
        // A rectangular element r in [0.5, 0.7], z in [0, 0.3].
        let x = [[0.5, 0.0], [0.7, 0.0], [0.7, 0.3], [0.5, 0.3], [0.6, 0.0], [0.7, 0.15], [0.6, 0.3], [0.5, 0.15]];
        let eps = 1e-7;
        let mut u = [[0.0; 2]; 8];
        for a in 0..8 {
            u[a] = [-nu * eps * x[a][0], eps * x[a][1]];
        }
        for rule in [Integration::Reduced, Integration::Full] {
            let (f, _) = forces_and_tangent(&x, &u, m, rule).unwrap();
            let top: f64 = [2usize, 3, 6].iter().map(|&a| f[2 * a + 1]).sum();
            let area = std::f64::consts::PI * (0.7f64.powi(2) - 0.5f64.powi(2));
            assert!((top / (e * eps * area) - 1.0).abs() < 1e-5, "{rule:?}: {}", top / (e * eps * area));
            // sigma_rr = sigma_tt = 0: no radial force on any node.
            let radial = (0..8).map(|a| f[2 * a].abs()).fold(0.0, f64::max);
            assert!(radial < 1e-6 * top.abs(), "{rule:?}: {radial}");
        }
    }
}
