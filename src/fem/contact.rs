//! Frictionless contact of the shell's outer surface with a rigid flat plate (thesis
//! Section 3.2; the thesis uses ANSYS' penalty-based CONTA172/TARGE169), node to plate,
//! penalty method.
//!
//! The plate is the plane z = z_p, pressing down on the shell (material below it). An outer
//! node a penetrates by d_a = z_a - z_p > 0 (z_a current), and then carries the pressure
//! p_a = k_n d_a over its tributary area w_a = Int N_a 2 pi r ds (reference outer surface,
//! quadratic edges): nodal force -p_a w_a along z, tangent k_n w_a. k_n = penalty E/h, so
//! that the penetration is p h/(penalty E): the penalty is the inverse of the tolerated
//! penetration per unit of p/E, in units of h.

use super::mesh::ShellMesh;

/// The contact state of the outer nodes at one configuration.
#[derive(Clone, Debug, Default)]
pub struct ContactState {
    /// Per outer node (apex first): pressure p_a (>= 0) and whether it is in contact.
    pub pressure: Vec<f64>,
    pub active: Vec<bool>,
    /// Total plate force (positive, pressing), contact area (sum of active tributary areas),
    /// outermost contact radius (current r), largest penetration.
    pub force: f64,
    pub area: f64,
    pub radius: f64,
    pub max_penetration: f64,
}

/// Penalty contact with a plate.
pub struct Plate {
    /// Tributary areas of the outer nodes (reference configuration).
    pub weights: Vec<f64>,
    /// Penalty stiffness per unit area, k_n = penalty E / h.
    pub stiffness: f64,
}

impl Plate {
    pub fn new(mesh: &ShellMesh, e: f64, penalty: f64) -> Plate {
        let mut weights = vec![0.0; mesh.outer.len()];
        for q in mesh.outer_edge_points() {
            for k in 0..3 {
                weights[q.outer[k]] += q.shape[k] * 2.0 * std::f64::consts::PI * q.r * q.ds * q.weight;
            }
        }
        Plate { weights, stiffness: penalty * e / mesh.thickness }
    }

    /// The penalty energy Sum k_n w_a d_a^2 / 2 of the penetrations.
    pub fn energy(&self, mesh: &ShellMesh, u: &[f64], z_plate: f64) -> f64 {
        mesh.outer
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
            .sum()
    }

    /// The derivative of the residual f_int - f_contact with respect to the plate
    /// displacement delta at fixed u: + k_n w_a on the z dof of every penetrating node
    /// (pushing the plate down by d delta raises the penetration by d delta).
    pub fn delta_derivative(&self, mesh: &ShellMesh, state: &ContactState) -> Vec<f64> {
        let mut q = vec![0.0; 2 * mesh.n_nodes()];
        for (k, &a) in mesh.outer.iter().enumerate() {
            if state.active[k] {
                q[2 * a + 1] = self.stiffness * self.weights[k];
            }
        }
        q
    }

    /// Contact forces (added to `f_ext`, full dof vector), tangent entries (pushed to
    /// `triplets`) and the state, for the plate at z = z_plate and displacements u.
    pub fn apply(
        &self,
        mesh: &ShellMesh,
        u: &[f64],
        z_plate: f64,
        f_ext: &mut [f64],
        triplets: &mut Vec<(usize, usize, f64)>,
    ) -> ContactState {
        let mut s = ContactState {
            pressure: vec![0.0; mesh.outer.len()],
            active: vec![false; mesh.outer.len()],
            ..Default::default()
        };
        for (k, &a) in mesh.outer.iter().enumerate() {
            let z = mesh.nodes[a][1] + u[2 * a + 1];
            let d = z - z_plate;
            if d > 0.0 {
                let p = self.stiffness * d;
                let w = self.weights[k];
                f_ext[2 * a + 1] -= p * w;
                triplets.push((2 * a + 1, 2 * a + 1, self.stiffness * w));
                s.pressure[k] = p;
                s.active[k] = true;
                s.force += p * w;
                s.area += w;
                s.radius = s.radius.max(mesh.nodes[a][0] + u[2 * a]);
                s.max_penetration = s.max_penetration.max(d);
            }
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
