//! Contact of the shell's outer surface with a rigid flat plate (thesis Section 3.2; the
//! thesis uses ANSYS' penalty-based CONTA172/TARGE169), node to plate, penalty method, with
//! optional Lennard-Jones adhesion (`adhesion`, Eq. 3.3) and Coulomb friction.
//!
//! The plate is the plane z = z_p, pressing down on the shell (material below it). An outer
//! node a penetrates by d_a = z_a - z_p > 0 (z_a current), and then carries the pressure
//! p_a = k_n d_a over its tributary area w_a = Int N_a 2 pi r ds (reference outer surface,
//! quadratic edges): nodal force -p_a w_a along z, tangent k_n w_a. k_n = penalty E/h, so
//! that the penetration is p h/(penalty E): the penalty is the inverse of the tolerated
//! penetration per unit of p/E, in units of h.
//!
//! Coulomb friction (radial, the only tangential direction of the axisymmetric problem),
//! penalty regularised with a return mapping: each outer node carries an anchor xi_a, the
//! plate point it sticks to (for a node out of contact: its radius at the last converged
//! state, where it will touch). The trial tangential force t = k_t w_a (r_a - xi_a) (k_t =
//! 0.1 k_n) is kept if |t| <= mu p_a w_a (stick), else cut back to mu p_a w_a sign(t) (slip, the
//! anchor following the node). The anchors are the history of the load path: each converged
//! state hands its anchors to the next solve (backward Euler). The consistent tangent is
//! k_t w_a (stick) or the non-symmetric mu k_n w_a sign(t) coupling of the shear to the
//! penetration (slip).

use super::adhesion::{Adhesion, Tangent};
use super::mesh::ShellMesh;
use super::system::{NoTangent, TangentSink};
use std::sync::Arc;

/// The contact state of the outer nodes at one configuration.
#[derive(Clone, Debug, Default)]
pub struct ContactState {
    /// Per outer node (apex first): pressure p_a (>= 0) and whether it is in contact.
    pub pressure: Vec<f64>,
    pub active: Vec<bool>,
    /// Total plate force (positive, pressing: contact minus adhesive pull), contact area (sum
    /// of active tributary areas), outermost contact radius (current r), largest
    /// penetration.
    pub force: f64,
    pub area: f64,
    pub radius: f64,
    pub max_penetration: f64,
    /// The adhesive part of `force` (<= 0).
    pub adhesive: f64,
    /// Per outer node: frictional shear stress (radial, on the shell, per reference area),
    /// whether it slips, and its anchor after this state (the history for the next state).
    pub shear: Vec<f64>,
    pub slipping: Vec<bool>,
    pub stick: Vec<f64>,
}

/// Tangential penalty over the normal one: soft enough that Newton does not cycle between
/// stick and slip, stiff enough that the elastic slip before sliding, mu p / k_t, stays
/// below 1e-3 h at p ~ 0.01 E.
pub const TANGENTIAL_PENALTY: f64 = 0.1;

/// Coulomb friction with the plate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    pub mu: f64,
    /// Tangential penalty stiffness per unit area.
    pub stiffness: f64,
}

/// Penalty contact with a plate, with adhesion and friction if given.
#[derive(Clone)]
pub struct Plate {
    /// Tributary areas of the outer nodes (reference configuration).
    pub weights: Vec<f64>,
    /// Penalty stiffness per unit area, k_n = penalty E / h.
    pub stiffness: f64,
    pub adhesion: Option<Adhesion>,
    pub friction: Option<Friction>,
    /// Adhesive forces frozen as dead loads (`FrozenAdhesion`: the structural solve of the
    /// thesis' staggered procedure, Section 3.2); none in the monolithic model.
    pub frozen: Option<Arc<FrozenAdhesion>>,
}

/// The adhesive forces of one configuration, applied as dead loads: the gradient dU/du of
/// the adhesive energy there (full dof vector, as `Adhesion::apply` writes it; the load on
/// the shell is its negative) and the plate force it makes (the adhesive pull, <= 0).
#[derive(Clone, Debug)]
pub struct FrozenAdhesion {
    pub gradient: Vec<f64>,
    pub pull: f64,
}

impl FrozenAdhesion {
    /// The adhesive forces of `adhesion` at displacements `u`, the plate at z = `z_plate`.
    pub fn at(adhesion: &Adhesion, mesh: &ShellMesh, u: &[f64], z_plate: f64) -> FrozenAdhesion {
        let n = 2 * mesh.n_nodes();
        let mut gradient = vec![0.0; n];
        let (pull, _) =
            adhesion.apply(mesh, u, z_plate, &mut gradient, &mut NoTangent, &mut vec![0.0; n], Tangent::Exact);
        FrozenAdhesion { gradient, pull }
    }
}

impl Plate {
    pub fn new(mesh: &ShellMesh, e: f64, penalty: f64) -> Plate {
        let mut weights = vec![0.0; mesh.outer.len()];
        for q in mesh.outer_edge_points() {
            for k in 0..3 {
                weights[q.outer[k]] += q.shape[k] * 2.0 * std::f64::consts::PI * q.r * q.ds * q.weight;
            }
        }
        Plate { weights, stiffness: penalty * e / mesh.thickness, adhesion: None, friction: None, frozen: None }
    }

    /// With Lennard-Jones adhesion of work `gamma` and range `g0` (none if gamma = 0).
    pub fn with_adhesion(mut self, gamma: f64, g0: f64) -> Plate {
        self.adhesion = (gamma > 0.0).then_some(Adhesion { gamma, g0 });
        self
    }

    /// With Coulomb friction of coefficient `mu` (none if mu = 0), tangential penalty
    /// `TANGENTIAL_PENALTY` times the normal one.
    pub fn with_friction(mut self, mu: f64) -> Plate {
        self.friction = (mu > 0.0).then_some(Friction { mu, stiffness: TANGENTIAL_PENALTY * self.stiffness });
        self
    }

    /// The same plate without friction.
    pub fn frictionless(&self) -> Plate {
        Plate { friction: None, ..self.clone() }
    }

    /// The anchors of the reference state (the outer nodes' radii).
    pub fn initial_stick(mesh: &ShellMesh) -> Vec<f64> {
        mesh.outer.iter().map(|&a| mesh.nodes[a][0]).collect()
    }

    /// The penalty energy Sum k_n w_a d_a^2 / 2 of the penetrations plus the adhesive energy
    /// (the potential of the conservative interface forces; friction is not).
    pub fn energy(&self, mesh: &ShellMesh, u: &[f64], z_plate: f64) -> f64 {
        let penalty: f64 = mesh
            .outer
            .iter()
            .zip(&self.weights)
            .map(|(&a, &w)| {
                let d = mesh.nodes[a][1] + u[2 * a + 1] - z_plate;
                if d > 0.0 {
                    0.5 * self.stiffness * w * d * d
                } else {
                    0.0
                }
            })
            .sum();
        let frozen = self.frozen.as_ref().map_or(0.0, |f| f.gradient.iter().zip(u).map(|(g, x)| g * x).sum());
        penalty + self.adhesive_energy(mesh, u, z_plate) + frozen
    }

    /// The adhesive energy of the Lennard-Jones law alone (<= 0; 0 without adhesion). It is
    /// proportional to the work of adhesion at fixed displacements.
    pub fn adhesive_energy(&self, mesh: &ShellMesh, u: &[f64], z_plate: f64) -> f64 {
        self.adhesion.map_or(0.0, |ad| {
            let n = 2 * mesh.n_nodes();
            ad.apply(mesh, u, z_plate, &mut vec![0.0; n], &mut Vec::new(), &mut vec![0.0; n], Tangent::Exact).1
        })
    }

    /// Interface forces (added to `f_ext`, full dof vector), tangent entries of the residual
    /// f_int - f_ext (pushed to `triplets`, with the adhesive tangent chosen by `tangent`), the
    /// residual's derivative with respect to the plate displacement delta (added to `q`) and
    /// the state, for the plate at z = z_plate, displacements u and the anchors `stick` of the
    /// last converged state (empty: the reference radii).
    ///
    /// Its arguments: the state it reads (mesh, u, plate, anchors) and the three accumulators
    /// of the assembly it adds to, which the caller owns across the interface laws.
    #[allow(clippy::too_many_arguments)]
    pub fn apply(
        &self,
        mesh: &ShellMesh,
        u: &[f64],
        z_plate: f64,
        stick: &[f64],
        f_ext: &mut [f64],
        triplets: &mut impl TangentSink,
        q: &mut [f64],
        tangent: Tangent,
    ) -> ContactState {
        let n = mesh.outer.len();
        let mut s = ContactState {
            pressure: vec![0.0; n],
            active: vec![false; n],
            shear: vec![0.0; n],
            slipping: vec![false; n],
            stick: vec![0.0; n],
            ..Default::default()
        };
        for (k, &a) in mesh.outer.iter().enumerate() {
            let (r, z) = (mesh.nodes[a][0] + u[2 * a], mesh.nodes[a][1] + u[2 * a + 1]);
            s.stick[k] = r;
            let d = z - z_plate;
            if d <= 0.0 {
                continue;
            }
            let p = self.stiffness * d;
            let w = self.weights[k];
            f_ext[2 * a + 1] -= p * w;
            triplets.push((2 * a + 1, 2 * a + 1, self.stiffness * w));
            q[2 * a + 1] += self.stiffness * w;
            s.pressure[k] = p;
            s.active[k] = true;
            s.force += p * w;
            s.area += w;
            s.radius = s.radius.max(r);
            s.max_penetration = s.max_penetration.max(d);
            if let Some(fr) = self.friction {
                let anchor = stick.get(k).copied().unwrap_or(mesh.nodes[a][0]);
                let trial = fr.stiffness * w * (r - anchor);
                let limit = fr.mu * p * w;
                if trial.abs() <= limit {
                    f_ext[2 * a] -= trial;
                    triplets.push((2 * a, 2 * a, fr.stiffness * w));
                    s.stick[k] = anchor;
                    s.shear[k] = -trial / w;
                } else {
                    let sign = trial.signum();
                    f_ext[2 * a] -= sign * limit;
                    triplets.push((2 * a, 2 * a + 1, sign * fr.mu * self.stiffness * w));
                    q[2 * a] += sign * fr.mu * self.stiffness * w;
                    s.stick[k] = r - sign * limit / (fr.stiffness * w);
                    s.shear[k] = -sign * limit / w;
                    s.slipping[k] = true;
                }
            }
        }
        if let Some(ad) = self.adhesion {
            let mut grad = vec![0.0; f_ext.len()];
            let (pull, _) = ad.apply(mesh, u, z_plate, &mut grad, triplets, q, tangent);
            f_ext.iter_mut().zip(&grad).for_each(|(f, g)| *f -= g);
            s.adhesive = pull;
            s.force += pull;
        }
        if let Some(frozen) = &self.frozen {
            f_ext.iter_mut().zip(&frozen.gradient).for_each(|(f, g)| *f -= g);
            s.adhesive += frozen.pull;
            s.force += frozen.pull;
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tributary_areas_sum_to_the_hemisphere() {
        let mesh = ShellMesh::hemisphere(1.0, 0.1, 40, 2, 5.0);
        let plate = Plate::new(&mesh, 1.0, 100.0);
        let total: f64 = plate.weights.iter().sum();
        let exact = 2.0 * std::f64::consts::PI * 1.1f64.powi(2);
        assert!((total / exact - 1.0).abs() < 1e-6, "{total} vs {exact}");
    }

    /// The shell pressed flat against the plate by `d` at every outer node within r < 0.3,
    /// with the radial displacements `ur` (per outer node).
    fn pressed(mesh: &ShellMesh, d: f64, ur: impl Fn(usize) -> f64) -> (Vec<f64>, f64) {
        let mut u = vec![0.0; 2 * mesh.n_nodes()];
        let z_plate = 1.1 - 0.02;
        for (k, &a) in mesh.outer.iter().enumerate() {
            if mesh.nodes[a][0] < 0.3 {
                u[2 * a + 1] = z_plate + d - mesh.nodes[a][1];
                u[2 * a] = ur(k);
            }
        }
        (u, z_plate)
    }

    #[test]
    fn stick_patch_test_uniform_slip_gives_uniform_shear() {
        // Every contact node displaced by the same s from its anchor: in stick each carries
        // k_t s per unit area, so the total shear is exactly k_t s times the contact area; past
        // mu p the same patch slips with exactly mu p per area, and its anchors then sit at
        // mu p / k_t behind the nodes, so that re-evaluating from them is stick at the limit.
        let mesh = ShellMesh::hemisphere(1.0, 0.1, 40, 2, 5.0);
        let plate = Plate::new(&mesh, 1.0, 100.0).with_friction(0.5);
        let anchors = Plate::initial_stick(&mesh);
        let d = 1e-3;
        let p = plate.stiffness * d;
        let nd = 2 * mesh.n_nodes();
        let s_star = 0.5 * d / TANGENTIAL_PENALTY; // mu p / k_t
        for (s_disp, slips) in [(0.2 * s_star, false), (3.0 * s_star, true)] {
            let (u, zp) = pressed(&mesh, d, |_| s_disp);
            let mut f = vec![0.0; nd];
            let st = plate.apply(&mesh, &u, zp, &anchors, &mut f, &mut Vec::new(), &mut vec![0.0; nd], Tangent::Exact);
            let shear: f64 = mesh.outer.iter().map(|&a| f[2 * a]).sum();
            let traction = if slips { 0.5 * p } else { plate.friction.unwrap().stiffness * s_disp };
            assert!(((-shear) / (traction * st.area) - 1.0).abs() < 1e-12, "{shear} vs {}", traction * st.area);
            for (k, &act) in st.active.iter().enumerate() {
                if act {
                    assert_eq!(st.slipping[k], slips);
                    assert!((st.shear[k] + traction).abs() < 1e-12 * traction);
                    // With the returned anchors the same state carries the same shear (at the limit).
                    let mut f2 = vec![0.0; nd];
                    let st2 = plate.apply(
                        &mesh,
                        &u,
                        zp,
                        &st.stick,
                        &mut f2,
                        &mut Vec::new(),
                        &mut vec![0.0; nd],
                        Tangent::Exact,
                    );
                    assert!((st2.shear[k] - st.shear[k]).abs() < 1e-9 * traction);
                }
            }
        }
    }

    #[test]
    fn the_frictional_tangent_and_delta_derivative_are_consistent() {
        // Central differences of the interface residual -f_ext against its tangent entries and
        // q, with nodes in stick and in slip (away from the switch), and with adhesion on.
        let mesh = ShellMesh::hemisphere(1.0, 0.1, 20, 1, 3.0);
        let plate = Plate::new(&mesh, 1.0, 100.0).with_friction(0.3).with_adhesion(1e-3, 0.02);
        let anchors = Plate::initial_stick(&mesh);
        let d = 1e-3;
        // Alternate small (stick) and large (slip) radial offsets.
        let s_star = 0.3 * d / TANGENTIAL_PENALTY;
        let (u, zp) = pressed(&mesh, d, |k| if k % 2 == 0 { 0.05 * s_star } else { 4.0 * s_star });
        let nd = 2 * mesh.n_nodes();
        let eval = |u: &[f64], zp: f64| {
            let mut f = vec![0.0; nd];
            let mut t = Vec::new();
            let mut q = vec![0.0; nd];
            let st = plate.apply(&mesh, u, zp, &anchors, &mut f, &mut t, &mut q, Tangent::Exact);
            let mut k = vec![vec![0.0; nd]; nd];
            for (i, j, v) in t {
                k[i][j] += v;
            }
            (f.iter().map(|v| -v).collect::<Vec<f64>>(), k, q, st)
        };
        let (_, k, q, st) = eval(&u, zp);
        assert!(st.slipping.iter().any(|&s| s) && st.active.iter().zip(&st.slipping).any(|(&a, &s)| a && !s));
        let h = 1e-9;
        let scale = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..nd {
            let mut up = u.clone();
            up[i] += h;
            let mut um = u.clone();
            um[i] -= h;
            let (rp, ..) = eval(&up, zp);
            let (rm, ..) = eval(&um, zp);
            for j in 0..nd {
                let fd = (rp[j] - rm[j]) / (2.0 * h);
                assert!((fd - k[j][i]).abs() < 1e-6 * scale, "K[{j}][{i}] {} vs {fd}", k[j][i]);
            }
        }
        let (rp, ..) = eval(&u, zp - h);
        let (rm, ..) = eval(&u, zp + h);
        for j in 0..nd {
            assert!(((rp[j] - rm[j]) / (2.0 * h) - q[j]).abs() < 1e-6 * scale, "q[{j}]");
        }
    }
}
