//! Stability of a state pressed by the plate, with the contact treated as unilateral
//! (thesis Section 3.3: the snap-through, "buckling", of the flattened shell).
//!
//! Two criteria (`Criterion`):
//!
//! `Tangent`, the physical one: the tangent of the converged state, with the penalty
//! stiffness of every pressed node (the unilateral contact's own tangent at its active
//! set), positive definite. On an imperfect shell (an apex force or a dimple) the weakly
//! pressed interior lifts off in the equilibrium itself, and the path under prescribed
//! delta ends at a limit point where the tangent turns singular: the snap. On the perfect
//! shell of R = 15, h = 0.9 (default mesh) the flattened interior keeps a pressure of about
//! 4e-5 E and the tangent stays positive definite to delta/R = 0.4245 (F = 32.1 F_c); an
//! imperfection lowers the snap from there (Koiter-type sensitivity: apex force 1e-4, 1e-3,
//! 1e-2, 1e-1 F_c: 31.7, 28.3, 12.7, 7.2 F_c).
//!
//! `LiftThreshold`, a numerical stand-in for an imperfection of the perfect shell: the
//! penalty contact adds its stiffness k_n w_a to every penetrating node, which in the tangent
//! also resists the node's *lifting off* the plate. That is right where the contact
//! pressure is large, but in the flattened state (Pogorelov) the pressure is a ring at the
//! rim of the contact disk and the interior touches the plate with p ~ 0 (p/E < 1e-4
//! inside, 1.4e-2 at the rim, R = 15, h = 1, delta/R = 0.25). The test holds only the
//! nodes pressed above `threshold` times the peak pressure. The threshold is a free
//! choice: the first unstable delta moves with it by a fifth over thresholds from 0.2 to
//! 0.005 (docs/tuning.md, "Shell snap search").
//!
//! With adhesion (Eq. 3.3) the test adds the adhesive tangent of the state. A touching point
//! (g' <= 0) sits on the kink of the law: lifting it is resisted by 16 dgamma / g0^2 per area
//! on the g' > 0 side, by nothing on its own side. `AdhesiveHold` chooses: holding with
//! 16 dgamma / g0^2 (with g0 = 0.1 mm of the order of E/h already at dgamma ~ 1e-3 N/mm)
//! suppresses every snap; letting touching points lift freely (the default), F_buckling
//! rises with dgamma until the snap disappears (docs/tuning.md, "Shell snap search", has
//! both). The thesis (staggered adhesion, ANSYS) finds gamma_c/(E h) ~ 5e-2 there: its
//! adhesion holds the shell even less.

use super::adhesion::Tangent;
use super::contact::Plate;
use super::indent::{apex_z, Step};
use super::system::{Model, Stiffness, TangentSink};

/// Default pressure threshold (fraction of the peak pressure) above which a contact node
/// is held against lifting in the stability test.
pub const LIFT_THRESHOLD: f64 = 0.02;

/// Which states of a path under prescribed plate displacement count as stable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Criterion {
    /// The tangent of the converged state with every pressed node held (the unilateral
    /// contact's own tangent at its active set) is positive definite. On an imperfect shell
    /// (an apex force or a dimple) the weakly pressed interior lifts off in the equilibrium
    /// itself, and the path loses stability at its limit point in delta, where no
    /// equilibrium lies beyond: the physical snap-through, with no free parameter. On a
    /// perfect shell it does not snap before the interior's pressure vanishes.
    Tangent,
    /// Only nodes pressed above this fraction of the peak pressure are held, the others
    /// free to lift (`unilaterally_stable`): a numerical stand-in for the imperfection of a
    /// perfect shell, whose verdict moves with the threshold.
    LiftThreshold(f64),
}

impl Criterion {
    /// The pressure threshold of `unilaterally_stable`.
    pub fn threshold(self) -> f64 {
        match self {
            Criterion::Tangent => 0.0,
            Criterion::LiftThreshold(t) => t,
        }
    }
}

/// What resists the lifting of a touching point (g' <= 0) of an adhesive contact in the
/// stability test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum AdhesiveHold {
    /// Nothing: Eq. 3.3 acts "only for g' > 0", and a touching point takes the tangent of
    /// that side (zero); adhesion stabilises through the points near, not on, the plate.
    #[default]
    Free,
    /// The law's lifting-side stiffness 16 dgamma / g0^2 (the one-sided linear stability of
    /// the Lennard-Jones model, which holds the weakly pressed interior down).
    LennardJones,
}

/// Whether the converged state `s` is stable under prescribed plate displacement with the
/// weakly pressed contact nodes free to lift off (against the adhesive lift stiffness, if
/// the plate adheres). The held nodes also keep their frictional stick stiffness; slipping
/// ones contribute none (the symmetric part of the slip tangent is dropped).
pub fn unilaterally_stable(model: &Model, plate: &Plate, s: &Step, threshold: f64, hold: AdhesiveHold) -> bool {
    stability_tangent(model, plate, s, threshold, hold).is_some_and(|k| model.is_stable(&k))
}

/// The smallest eigenvalue of the tangent of `unilaterally_stable` (`iterations` steps of
/// inverse iteration), None if it is not positive definite: how far the state is from
/// losing stability.
pub fn stability_margin(
    model: &Model,
    plate: &Plate,
    s: &Step,
    threshold: f64,
    hold: AdhesiveHold,
    iterations: usize,
) -> Option<f64> {
    model.smallest_eigenvalue(&stability_tangent(model, plate, s, threshold, hold)?, iterations)
}

/// The tangent whose positive definiteness `unilaterally_stable` tests.
fn stability_tangent(model: &Model, plate: &Plate, s: &Step, threshold: f64, hold: AdhesiveHold) -> Option<Stiffness> {
    let (_, mut k) = model.assemble(&s.u)?;
    let state = &s.contact;
    let peak = state.pressure.iter().copied().fold(0.0, f64::max);
    for (i, &a) in model.mesh.outer.iter().enumerate() {
        if state.active[i] && state.pressure[i] > threshold * peak {
            k.push((2 * a + 1, 2 * a + 1, plate.stiffness * plate.weights[i]));
            if let Some(fr) = plate.friction {
                if !state.slipping[i] {
                    k.push((2 * a, 2 * a, fr.stiffness * plate.weights[i]));
                }
            }
        }
    }
    // The whole adhesive tangent, with the lifting side's curvature where the surface
    // touches the plate.
    if let Some(ad) = plate.adhesion {
        let tangent = if hold == AdhesiveHold::LennardJones { Tangent::Lifting } else { Tangent::Exact };
        let n = model.n_dofs();
        ad.apply(&model.mesh, &s.u, apex_z(model) - s.delta, &mut vec![0.0; n], &mut k, &mut vec![0.0; n], tangent);
    }
    Some(k)
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
            assert!(s.converged() && s.stable, "bilateral at {d}");
            assert_eq!(unilaterally_stable(&model, &plate, s, LIFT_THRESHOLD, AdhesiveHold::Free), expected, "{d}");
            // Holding every contact node restores the bilateral verdict.
            assert!(unilaterally_stable(&model, &plate, s, 0.0, AdhesiveHold::Free));
        }
        let s = at(0.25);
        let peak = s.contact.pressure.iter().copied().fold(0.0, f64::max);
        assert!(s.contact.pressure[0] < 0.03 * peak && peak / e > 0.01);
    }
}
