//! Lennard-Jones adhesion between the shell's outer surface and the rigid plate (thesis
//! Section 3.2, Eqs. 3.1-3.4).
//!
//! Model: the 3-9 law of Eq. 3.1 with the gap shifted by the equilibrium distance g0
//! (Eq. 3.3), acting only where the shifted gap g' = z_plate - z is positive (the penalty
//! contact of `contact` carries the compression):
//!
//!   p(g') = -(8 dgamma / (3 g0)) [ x^3 - x^9 ],   x = g0 / (g' + g0),
//!
//! tension negative; its work of separation from g' = 0 is exactly dgamma. It derives from the
//! interaction energy per unit plate area (Derjaguin)
//!
//!   phi(g') = -(8 dgamma / 3) [ x^2 / 2 - x^8 / 8 ]   (g' > 0),   phi = -dgamma (g' <= 0),
//!
//! which is C1 at g' = 0 (p(0) = 0); its curvature jumps there from 0 to 16 dgamma / g0^2,
//! the stiffness with which adhesion resists lifting a touching point off the plate.
//!
//! Quadrature: the thesis lumps p(g') A_i on annuli A_i = pi (x_{i+1}^2 - x_i^2) of the
//! current nodes (Eq. 3.4) and iterates (staggered). Here the energy
//! U = Int phi(g'(s)) 2 pi r(s) r'(s) ds over the current outer meridian (quadratic edges,
//! `GAUSS_POINTS` Gauss points each: the projected annulus of Eq. 3.4 made consistent) is
//! differentiated exactly: nodal forces dU/du, the symmetric tangent d2U/du2 (including the
//! radial terms of the moving annuli) and d(dU/du)/d delta for the arc length, so that
//! Newton converges quadratically with adhesion in the monolithic system.
//!
//! Units: lengths of the mesh (mm), dgamma in force per length (N/mm), consistent with E.

use super::mesh::ShellMesh;
use super::system::TangentSink;
use crate::lennard_jones::{shifted_potential, Potential as Law};
use std::f64::consts::PI;

/// Gauss-Legendre points per outer edge for the adhesive energy.
pub const GAUSS_POINTS: usize = 5;

const GAUSS5: [(f64, f64); GAUSS_POINTS] = [
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (-0.538_469_310_105_683, 0.478_628_670_499_366_5),
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// Which adhesive tangent to assemble.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tangent {
    /// The exact second derivative (Newton's quadratic convergence).
    Exact,
    /// Exact, but with the lifting side's curvature 16 dgamma / g0^2 where the surface
    /// touches (the stability test's `AdhesiveHold::LennardJones`).
    Lifting,
    /// The curvature clipped at zero where the law softens (g' > 0.2 g0): a positive
    /// semi-definite adhesive stiffness for the Newton direction when the exact one, with
    /// strong adhesion, is indefinite enough to send every step into inverted elements.
    Convex,
}

/// The Lennard-Jones interface law of Eq. 3.3.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adhesion {
    /// Work of adhesion dgamma (force per length).
    pub gamma: f64,
    /// Equilibrium distance g0 (length).
    pub g0: f64,
}

impl Adhesion {
    /// The traction p(g') of Eq. 3.3 (negative: tension), zero for g' <= 0.
    pub fn traction(&self, g: f64) -> f64 {
        -self.law(g, false).d1
    }

    /// The largest tension, -min p = (8 dgamma / 3 g0) (2 / 3^(3/2)) at x^6 = 1/3.
    pub fn peak_tension(&self) -> f64 {
        16.0 * self.gamma / (9.0 * 3f64.sqrt() * self.g0)
    }

    /// phi(g') and its derivatives (`lennard_jones::shifted_potential`).
    fn law(&self, g: f64, lifting: bool) -> Law {
        shifted_potential(self.gamma, self.g0, g, lifting)
    }

    /// Adds dU/du to `residual`, d2U/du2 to `triplets` and d(dU/du)/d delta to `q` (all on
    /// the full dof vector) for displacements `u` and the plate at z = `z_plate`; returns
    /// the adhesive part of the plate force (dU/d delta, counted like a pressing force:
    /// negative, a pull) and the energy U. `tangent` chooses the tangent (`Tangent`).
    ///
    /// Its arguments: the state it reads (mesh, u, plate) and the three accumulators of the
    /// assembly it adds to, which the caller owns across the interface laws.
    #[allow(clippy::too_many_arguments)]
    pub fn apply(
        &self,
        mesh: &ShellMesh,
        u: &[f64],
        z_plate: f64,
        residual: &mut [f64],
        triplets: &mut impl TangentSink,
        q: &mut [f64],
        tangent: Tangent,
    ) -> (f64, f64) {
        let (mut force, mut energy) = (0.0, 0.0);
        for e in 0..(mesh.outer.len() - 1) / 2 {
            let nodes: [usize; 3] = std::array::from_fn(|k| mesh.outer[2 * e + k]);
            let r: [f64; 3] = std::array::from_fn(|k| mesh.nodes[nodes[k]][0] + u[2 * nodes[k]]);
            let z: [f64; 3] = std::array::from_fn(|k| mesh.nodes[nodes[k]][1] + u[2 * nodes[k] + 1]);
            let zr = |k: usize| 2 * nodes[k];
            let zz = |k: usize| 2 * nodes[k] + 1;
            // The edge's 6 x 6 tangent (local dofs 2k: r, 2k + 1: z of its node k), summed over
            // the Gauss points before it goes to the sink.
            let mut local = [[0.0; 6]; 6];
            for &(xi, w) in &GAUSS5 {
                let n = [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)];
                let dn = [xi - 0.5, -2.0 * xi, xi + 0.5];
                let rq: f64 = (0..3).map(|k| n[k] * r[k]).sum();
                let rx: f64 = (0..3).map(|k| dn[k] * r[k]).sum();
                let zq: f64 = (0..3).map(|k| n[k] * z[k]).sum();
                let law = self.law(z_plate - zq, tangent == Tangent::Lifting);
                let d2 = if tangent == Tangent::Convex { law.d2.max(0.0) } else { law.d2 };
                let jac = 2.0 * PI * rq * rx;
                let djac: [f64; 3] = std::array::from_fn(|k| 2.0 * PI * (n[k] * rx + rq * dn[k]));
                energy += w * law.phi * jac;
                force -= w * law.d1 * jac;
                for k in 0..3 {
                    residual[zz(k)] -= w * law.d1 * n[k] * jac;
                    residual[zr(k)] += w * law.phi * djac[k];
                    q[zz(k)] += w * law.d2 * n[k] * jac;
                    q[zr(k)] -= w * law.d1 * djac[k];
                    for l in 0..3 {
                        let kzr = -w * law.d1 * n[k] * djac[l];
                        local[2 * k + 1][2 * l + 1] += w * d2 * jac * (n[k] * n[l]);
                        local[2 * k + 1][2 * l] += kzr;
                        local[2 * l][2 * k + 1] += kzr;
                        local[2 * k][2 * l] += w * law.phi * 2.0 * PI * (n[k] * dn[l] + dn[k] * n[l]);
                    }
                }
            }
            let dof = |a: usize| 2 * nodes[a / 2] + a % 2;
            for (a, row) in local.iter().enumerate() {
                for (b, &v) in row.iter().enumerate() {
                    if v != 0.0 {
                        triplets.push((dof(a), dof(b), v));
                    }
                }
            }
        }
        (force, energy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law() -> Adhesion {
        Adhesion { gamma: 2e-3, g0: 0.1 }
    }

    #[test]
    fn the_law_is_eq_3_3_with_work_of_separation_dgamma() {
        let a = law();
        // Eq. 3.3 directly.
        for g in [0.01, 0.05, 0.1, 0.3, 1.0] {
            let x: f64 = a.g0 / (g + a.g0);
            let p = -(8.0 * a.gamma / (3.0 * a.g0)) * (x.powi(3) - x.powi(9));
            assert!((a.traction(g) - p).abs() < 1e-15, "{g}");
        }
        assert_eq!(a.traction(0.0), 0.0);
        assert_eq!(a.traction(-0.2), 0.0);
        // Work of separation: Int_0^inf -p dg' = dgamma (substituting g' = g0 (1/x - 1)).
        let n = 20000;
        let work: f64 = (0..n)
            .map(|i| {
                let x = (i as f64 + 0.5) / n as f64;
                -a.traction(a.g0 * (1.0 / x - 1.0)) * a.g0 / (x * x) / n as f64
            })
            .sum();
        assert!((work / a.gamma - 1.0).abs() < 1e-6, "{work}");
        // Peak tension at x^6 = 1/3.
        let g_peak = a.g0 * (3f64.powf(1.0 / 6.0) - 1.0);
        assert!((-a.traction(g_peak) / a.peak_tension() - 1.0).abs() < 1e-12);
        // phi' = -p, phi'' by differences; the lifting curvature at 0 is 16 dgamma / g0^2.
        for g in [1e-3, 0.02, 0.2] {
            let h = 1e-6;
            let fd1 = (a.law(g + h, false).phi - a.law(g - h, false).phi) / (2.0 * h);
            let fd2 = (a.law(g + h, false).d1 - a.law(g - h, false).d1) / (2.0 * h);
            assert!((fd1 + a.traction(g)).abs() < 1e-8 * a.peak_tension(), "{g}");
            assert!((fd2 / a.law(g, false).d2 - 1.0).abs() < 1e-5, "{g}");
        }
        let lift = a.law(-1.0, true).d2;
        assert!((a.law(1e-9, false).d2 / lift - 1.0).abs() < 1e-6);
        assert!((lift - 16.0 * a.gamma / (a.g0 * a.g0)).abs() < 1e-12);
    }

    #[test]
    fn forces_tangent_and_delta_derivative_are_the_energys_derivatives() {
        // A coarse shell, displaced (radially and vertically) so that the outer surface has
        // points in contact, near the plate and far from it; central differences of U and of
        // the forces against the analytic forces, tangent and d/d delta.
        let mesh = ShellMesh::hemisphere(1.0, 0.1, 12, 1, 3.0);
        let a = Adhesion { gamma: 1.0, g0: 0.05 };
        let nd = 2 * mesh.n_nodes();
        let u: Vec<f64> = (0..nd).map(|i| 0.01 * ((i as f64 * 0.7).sin())).collect();
        let z_plate = 1.1 - 0.02;
        let eval = |u: &[f64], zp: f64| {
            let mut res = vec![0.0; nd];
            let mut trip = Vec::new();
            let mut q = vec![0.0; nd];
            let (f, en) = a.apply(&mesh, u, zp, &mut res, &mut trip, &mut q, Tangent::Exact);
            let mut k = vec![vec![0.0; nd]; nd];
            for (i, j, v) in trip {
                k[i][j] += v;
            }
            (res, k, q, f, en)
        };
        let (res, k, q, force, _) = eval(&u, z_plate);
        let h = 1e-7;
        let (mut worst_f, mut worst_k): (f64, f64) = (0.0, 0.0);
        let max_abs = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0f64, |m, x| m.max(x.abs()));
        let scale = max_abs(&mut res.iter().copied());
        let k_scale = max_abs(&mut k.iter().flatten().copied());
        let q_scale = max_abs(&mut q.iter().copied());
        assert!(scale > 0.0 && k_scale > 0.0 && q_scale > 0.0);
        for i in 0..nd {
            let mut up = u.clone();
            up[i] += h;
            let mut um = u.clone();
            um[i] -= h;
            let (rp, _, _, _, ep) = eval(&up, z_plate);
            let (rm, _, _, _, em) = eval(&um, z_plate);
            worst_f = worst_f.max(((ep - em) / (2.0 * h) - res[i]).abs());
            for j in 0..nd {
                worst_k = worst_k.max(((rp[j] - rm[j]) / (2.0 * h) - k[j][i]).abs());
            }
        }
        assert!(worst_f < 1e-6 * scale, "forces: worst {worst_f} of {scale}");
        assert!(worst_k < 1e-5 * k_scale, "tangent: worst {worst_k} of {k_scale}");
        // delta moves the plate down: z_plate = z0 - delta.
        let (rp, _, _, _, ep) = eval(&u, z_plate - h);
        let (rm, _, _, _, em) = eval(&u, z_plate + h);
        assert!(((ep - em) / (2.0 * h) - force).abs() < 1e-6 * force.abs(), "{force}");
        for j in 0..nd {
            assert!(((rp[j] - rm[j]) / (2.0 * h) - q[j]).abs() < 1e-5 * q_scale, "{j}");
        }
        assert!(force < 0.0);
    }

    #[test]
    fn the_consistent_quadrature_converges() {
        // A shell held in its reference shape 0.01 below the plate: the adhesive force from
        // the 5-point rule on the mesh against the exact integral over the sphere,
        // F = -Int p(g'(r)) ... = Int phi'(g') 2 pi r dr with g' = 0.01 + R_o - sqrt(R_o^2 - r^2).
        let a = Adhesion { gamma: 1e-3, g0: 0.1 };
        let ro = 16.0;
        let exact: f64 = {
            let n = 200000;
            (0..n)
                .map(|i| {
                    let r = ro * (i as f64 + 0.5) / n as f64;
                    let g = 0.01 + ro - (ro * ro - r * r).sqrt();
                    a.law(g, false).d1 * 2.0 * PI * r * ro / n as f64
                })
                .sum()
        };
        for (n, tol) in [(60, 2e-3), (100, 5e-4)] {
            let mesh = ShellMesh::hemisphere(15.0, 1.0, n, 1, 3.0);
            let nd = 2 * mesh.n_nodes();
            let mut res = vec![0.0; nd];
            let mut q = vec![0.0; nd];
            let (f, _) = a.apply(&mesh, &vec![0.0; nd], ro + 0.01, &mut res, &mut Vec::new(), &mut q, Tangent::Exact);
            assert!((-f / exact - 1.0).abs() < tol, "{n}: {} vs {exact}", -f);
        }
    }
}
