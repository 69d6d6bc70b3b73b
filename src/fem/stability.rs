//! Stability of a state pressed by the plate, with the contact treated as unilateral
//! (thesis Section 3.3: the snap-through, "buckling", of the flattened shell).
//!
//! The penalty contact of `contact` adds its stiffness k_n w_a to every penetrating node,
//! which in the tangent acts both ways: it also resists the node's *lifting off* the plate.
//! That is right where the contact pressure is large (lifting costs first-order energy
//! p_a w_a per unit lift), but not where it vanishes: in the flattened state (Pogorelov) the
//! pressure is a ring at the rim of the contact disk and the disk's interior touches the
//! plate with p ~ 0 (measured: p/E < 1e-4 inside, 1.4e-2 at the rim, R = 15, h = 1,
//! delta/R = 0.25). The interior then buckles away from the plate (the shell inverts) as
//! soon as the tangent *without* its contact stiffness has a negative direction that
//! lifts it, long after the bilateral tangent still looks positive definite.
//!
//! Test: K_int plus the penalty stiffness only on the nodes whose pressure exceeds
//! `threshold` times the largest, positive definite (sparse Cholesky). The threshold is the
//! model's one free choice here: measured on R = 15, h = 1 (60 x 3 elements and 80 x 4), the
//! first unstable delta/R is 0.175, 0.185, 0.190, 0.195, 0.200, 0.205 for thresholds 0.2,
//! 0.1, 0.05, 0.02, 0.01, 0.005, all past the limit point of the inverted branch (0.1735,
//! where the snap can first land), and insensitive to the mesh and the penalty.

use super::contact::{ContactState, Plate};
use super::system::Model;

/// Default pressure threshold (fraction of the peak pressure) above which a contact node
/// is held against lifting in the stability test.
pub const LIFT_THRESHOLD: f64 = 0.02;

/// Whether the state (displacements `u`, contact `state`) is stable under prescribed plate
/// displacement with the weakly pressed contact nodes free to lift off. `extra` adds
/// interface stiffness that acts on lifting (adhesion), as triplets.
pub fn unilaterally_stable(
    model: &Model,
    plate: &Plate,
    u: &[f64],
    state: &ContactState,
    threshold: f64,
    extra: &[(usize, usize, f64)],
) -> bool {
    let Some((_, mut k)) = model.assemble(u) else { return false };
    let peak = state.pressure.iter().copied().fold(0.0, f64::max);
    for (i, &a) in model.mesh.outer.iter().enumerate() {
        if state.active[i] && state.pressure[i] > threshold * peak {
            k.push((2 * a + 1, 2 * a + 1, plate.stiffness * plate.weights[i]));
        }
    }
    k.extend_from_slice(extra);
    model.is_stable(&k)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::indent::load_path;
    use crate::fem::mesh::ShellMesh;
    use crate::fem::system::Base;

    #[test]
    fn the_flattened_interior_is_free_to_lift() {
        // R = 15, h = 1: at delta/R = 0.15 the flattened state is stable either way; at 0.25
        // the bilateral tangent is still positive definite but the disk's interior, pressed
        // with p < 1e-4 E against 1.4e-2 E at the rim, lifts off: unstable.
        let (e, r) = (1.3, 15.0);
        let model = Model::new(ShellMesh::hemisphere(r, 1.0, 60, 3, 8.0), e, 0.45, Base::Clamped);
        let plate = Plate::new(&model.mesh, e, 1000.0);
        let path = load_path(&model, &plate, e, 0.25 * r, 10, 4);
        let at = |d: f64| path.iter().find(|s| (s.delta / r - d).abs() < 1e-9).unwrap();
        for (d, expected) in [(0.15, true), (0.25, false)] {
            let s = at(d);
            assert!(s.converged && s.stable, "bilateral at {d}");
            assert_eq!(unilaterally_stable(&model, &plate, &s.u, &s.contact, LIFT_THRESHOLD, &[]), expected, "{d}");
            // Holding every contact node restores the bilateral verdict.
            assert!(unilaterally_stable(&model, &plate, &s.u, &s.contact, 0.0, &[]));
        }
        let s = at(0.25);
        let peak = s.contact.pressure.iter().copied().fold(0.0, f64::max);
        assert!(s.contact.pressure[0] < 0.03 * peak && peak / e > 0.01);
    }
}
