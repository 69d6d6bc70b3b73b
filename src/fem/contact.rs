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
//! k_n) is kept if |t| <= mu p_a w_a (stick), else cut back to mu p_a w_a sign(t) (slip, the
//! anchor following the node). The anchors are the history of the load path: each converged
//! state hands its anchors to the next solve (backward Euler). The consistent tangent is
//! k_t w_a (stick) or the non-symmetric mu k_n w_a sign(t) coupling of the shear to the
//! penetration (slip).

use super::adhesion::Adhesion;
use super::mesh::ShellMesh;

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

/// Coulomb friction with the plate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    pub mu: f64,
    /// Tangential penalty stiffness per unit area.
    pub stiffness: f64,
}

/// Penalty contact with a plate, with adhesion and friction if given.
pub struct Plate {
    /// Tributary areas of the outer nodes (reference configuration).
    pub weights: Vec<f64>,
    /// Penalty stiffness per unit area, k_n = penalty E / h.
    pub stiffness: f64,
    pub adhesion: Option<Adhesion>,
    pub friction: Option<Friction>,
}

impl Plate {
    pub fn new(mesh: &ShellMesh, e: f64, penalty: f64) -> Plate {
        let mut weights = vec![0.0; mesh.outer.len()];
        for q in mesh.outer_edge_points() {
            for k in 0..3 {
                weights[q.outer[k]] += q.shape[k] * 2.0 * std::f64::consts::PI * q.r * q.ds * q.weight;
            }
        }
        Plate { weights, stiffness: penalty * e / mesh.thickness, adhesion: None, friction: None }
    }

    /// With Lennard-Jones adhesion of work `gamma` and range `g0` (none if gamma = 0).
    pub fn with_adhesion(mut self, gamma: f64, g0: f64) -> Plate {
        self.adhesion = (gamma > 0.0).then_some(Adhesion { gamma, g0 });
        self
    }

    /// With Coulomb friction of coefficient `mu` (none if mu = 0), tangential penalty equal
    /// to the normal one.
    pub fn with_friction(mut self, mu: f64) -> Plate {
        self.friction = (mu > 0.0).then_some(Friction { mu, stiffness: self.stiffness });
        self
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
        let adhesive = self.adhesion.map_or(0.0, |ad| {
            let n = 2 * mesh.n_nodes();
            ad.apply(mesh, u, z_plate, &mut vec![0.0; n], &mut Vec::new(), &mut vec![0.0; n], false).1
        });
        penalty + adhesive
    }

    /// Interface forces (added to `f_ext`, full dof vector), tangent entries of the residual
    /// f_int - f_ext (pushed to `triplets`), the residual's derivative with respect to the
    /// plate displacement delta (added to `q`) and the state, for the plate at z = z_plate,
    /// displacements u and the anchors `stick` of the last converged state (empty: the
    /// reference radii).
    #[allow(clippy::too_many_arguments)]
    pub fn apply(
        &self,
        mesh: &ShellMesh,
        u: &[f64],
        z_plate: f64,
        stick: &[f64],
        f_ext: &mut [f64],
        triplets: &mut Vec<(usize, usize, f64)>,
        q: &mut [f64],
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
            let (pull, _) = ad.apply(mesh, u, z_plate, &mut grad, triplets, q, false);
            f_ext.iter_mut().zip(&grad).for_each(|(f, g)| *f -= g);
            s.adhesive = pull;
            s.force += pull;
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
}
