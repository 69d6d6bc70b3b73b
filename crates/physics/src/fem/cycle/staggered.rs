//! The thesis' staggered procedure (Section 3.2) as a loading leg: "first, a prescribed
//! displacement delta is applied to the top nodes without considering adhesion. Next, the
//! gap between the nodes of the interface and the rigid surface is calculated. Then, using
//! the adhesive stress given by Eq. (3.3), the adhesive force is calculated [Eq. 3.4] ...
//! applied to the interface nodes. Finally, the problem is iteratively solved for the
//! specified displacement delta with the adhesive force included." Buckling is the first
//! negative slope of the displacement-controlled F(delta) curve (Section 3.1).
//!
//! Model: at each displacement step, pass 0 solves the shell with contact and friction but
//! without adhesion (Newton from the last step's state; `FirstPass::LastLoads`: under the
//! last step's adhesive loads instead, the common reading of a staggered scheme); each
//! pass k >= 1 freezes the
//! Lennard-Jones forces at the gaps of pass k - 1 as dead loads (`contact::FrozenAdhesion`)
//! and solves the shell again (Newton from pass k - 1, the friction anchors of the last
//! step). `Passes::Fixed(n)` stops after n such passes; `Passes::Converged` when the
//! displacements change by less than `STAGGERED_TOLERANCE` h between passes. The loads are
//! the consistent nodal forces of the monolithic model's adhesive energy (Eq. 3.4's
//! annuli p(g') A_i integrated by Gauss points on the current meridian, `adhesion`), so
//! that a converged staggered state is a monolithic equilibrium and the two schemes differ
//! only where the passes stop early or the frozen loads change the path.
//!
//! F(delta) is the contact force of each state, the plate's reaction to the pressure: in
//! the thesis' scheme the adhesive forces are nodal loads on the shell, not forces of the
//! plate, so that the rigid plate's reaction is the contact force alone (Section 3.3: "the
//! contact force increases with indentation until a buckling instability occurs"). The net
//! force (contact plus the frozen adhesive pull) is what the state reports, as everywhere;
//! with strong adhesion it falls while the adhesive annulus grows, with no snap. A structural solve that fails is taken again at half the step
//! (as the monolithic leg does); one that fails at the smallest step has passed the
//! structure's limit point under its frozen loads, and the state lands where an energy
//! descent of the loaded structure leads (`ShellProblem::jump_to_inverted`), as a damped
//! solver would; the next step then starts from there. Nondimensionalisation as in `fem`.

use super::{CycleOptions, CyclePoint, Jump, Leg};
use crate::fem::contact::{FrozenAdhesion, Plate};
use crate::fem::indent::{apex_z, Options, Step};
use crate::fem::problem::ShellProblem;
use std::sync::Arc;

/// Passes of the staggered procedure at each displacement step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Passes {
    /// Until the displacements change by less than `STAGGERED_TOLERANCE` h between passes
    /// (at most `MAX_PASSES`).
    Converged,
    /// This many structural solves with the adhesive loads after the adhesionless one.
    Fixed(u32),
}

/// What the first structural solve of a displacement step carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FirstPass {
    /// No adhesion, as Section 3.2 writes it ("first, a prescribed displacement delta is
    /// applied ... without considering adhesion").
    #[default]
    WithoutAdhesion,
    /// The adhesive loads of the last step's last pass (adhesion lagging one step behind
    /// the structure: the common staggered scheme).
    LastLoads,
}

/// The thesis' staggered procedure: passes per step and what the first one carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Staggered {
    pub passes: Passes,
    pub first: FirstPass,
}

/// Largest change of any displacement between two passes, in units of h, at which
/// `Passes::Converged` stops.
pub const STAGGERED_TOLERANCE: f64 = 1e-10;

/// At most this many passes with adhesive loads per step under `Passes::Converged`.
pub const MAX_PASSES: u32 = 200;

/// A force lower than the last by more than this fraction of it is a negative slope of
/// F(delta) (a converged staggered path is smooth to about 1e-9 relative).
pub const SLOPE_TOLERANCE: f64 = 1e-7;

/// Why a staggered step stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StaggeredEnd {
    /// The passes converged (`Passes::Converged`), or there is no adhesion to iterate.
    Converged,
    /// The given number of passes was done (`Passes::Fixed`).
    PassesDone,
    /// `MAX_PASSES` passes did not converge.
    PassLimit,
    /// A structural solve did not converge.
    StructureFailed,
}

/// One displacement step of the staggered procedure.
#[derive(Clone, Debug)]
pub struct StaggeredStep {
    /// The state of the last pass (its plate force includes the frozen adhesive pull).
    pub step: Step,
    /// Passes with adhesive loads done.
    pub passes: u32,
    /// Largest change of a displacement in the last pass, over h.
    pub change: f64,
    pub end: StaggeredEnd,
    /// The adhesive loads of its last pass (none without adhesion).
    pub loads: Option<Arc<FrozenAdhesion>>,
}

/// The compressive contact force of `s` (its plate force without the adhesive pull).
fn contact_force(s: &Step) -> f64 {
    s.contact.force - s.contact.adhesive
}

impl ShellProblem<'_> {
    /// The adhesive forces of the plate's law at displacements `u`, the plate at `delta`
    /// (none if it has no adhesion).
    pub fn adhesive_loads(&self, delta: f64, u: &[f64]) -> Option<Arc<FrozenAdhesion>> {
        let z_plate = apex_z(self.model) - delta;
        self.plate.adhesion.map(|ad| Arc::new(FrozenAdhesion::at(&ad, &self.model.mesh, u, z_plate)))
    }

    /// The plate without its live adhesion, carrying `loads` as dead loads instead.
    pub fn structure_plate(&self, loads: Option<Arc<FrozenAdhesion>>) -> Plate {
        Plate { adhesion: None, frozen: loads, ..self.plate.clone() }
    }

    /// One displacement step to `delta` from the converged state `from` by the thesis'
    /// staggered passes (module doc), the first solve under `first_loads` (none: without
    /// adhesion).
    pub fn staggered_step(
        &self,
        delta: f64,
        from: &Step,
        first_loads: Option<Arc<FrozenAdhesion>>,
        passes: Passes,
    ) -> StaggeredStep {
        let h = self.model.mesh.thickness;
        let first_plate = self.structure_plate(first_loads.clone());
        let first = self.with_plate(&first_plate).solve_from(delta, from, Options::default());
        let failed = |step: Step, passes, loads| StaggeredStep {
            step,
            passes,
            change: f64::INFINITY,
            end: StaggeredEnd::StructureFailed,
            loads,
        };
        if !first.converged() {
            return failed(first, 0, first_loads);
        }
        if self.plate.adhesion.is_none() {
            return StaggeredStep { step: first, passes: 0, change: 0.0, end: StaggeredEnd::Converged, loads: None };
        }
        let limit = match passes {
            Passes::Converged => MAX_PASSES,
            Passes::Fixed(n) => n,
        };
        let mut s = first;
        let mut loads = first_loads;
        let mut change = f64::INFINITY;
        for pass in 1..=limit {
            loads = self.adhesive_loads(delta, &s.u);
            let loaded_plate = self.structure_plate(loads.clone());
            let loaded = self.with_plate(&loaded_plate);
            let mut next = loaded.solve_at(delta, &s.u, &from.contact.stick, Options::default());
            if !next.converged() {
                next = loaded.solve_from(delta, from, Options::default());
            }
            if !next.converged() {
                return failed(next, pass, loads);
            }
            change = next.u.iter().zip(&s.u).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())) / h;
            s = next;
            if passes == Passes::Converged && change <= STAGGERED_TOLERANCE {
                return StaggeredStep { step: s, passes: pass, change, end: StaggeredEnd::Converged, loads };
            }
        }
        let end = match passes {
            Passes::Converged => StaggeredEnd::PassLimit,
            Passes::Fixed(_) => StaggeredEnd::PassesDone,
        };
        StaggeredStep { step: s, passes: limit, change, end, loads }
    }

    /// The loading leg of the staggered procedure from the reference state, in the steps
    /// of `opt` (halved where a structural solve fails), to delta_max or, with
    /// `stop_at_buckling`, to the first negative slope of F(delta). Returns the states, the
    /// buckling event (the last state before the drop, and the first after it) and whether
    /// every step was solved.
    pub(super) fn staggered_loading(
        &self,
        opt: &CycleOptions,
        procedure: Staggered,
    ) -> (Vec<CyclePoint>, Option<Jump>, bool) {
        let passes = procedure.passes;
        // The loads the next step's first solve carries.
        let mut carried: Option<Arc<FrozenAdhesion>> = None;
        let first_loads = |carried: &Option<Arc<FrozenAdhesion>>| match procedure.first {
            FirstPass::WithoutAdhesion => None,
            FirstPass::LastLoads => carried.clone(),
        };
        let base = opt.delta_max / opt.steps as f64;
        let mut cur = self.reference_state();
        let mut points = vec![CyclePoint { step: cur.clone(), leg: Leg::Loading, inverted: false }];
        let mut buckling = None;
        let (mut dd, mut cuts) = (base, 0);
        while cur.delta < opt.delta_max * (1.0 - 1e-12) {
            let target = (cur.delta + dd).min(opt.delta_max);
            let mut next = self.staggered_step(target, &cur, first_loads(&carried), passes);
            if next.end == StaggeredEnd::StructureFailed {
                if cuts < opt.max_cuts {
                    cuts += 1;
                    dd *= 0.5;
                    continue;
                }
                // Past the structure's limit point under the last loads: where it comes to
                // rest, then the adhesion iterated there.
                let loaded_plate = self.structure_plate(next.loads.clone().or_else(|| carried.clone()));
                let Some(landed) =
                    self.with_plate(&loaded_plate).jump_to_inverted(&Step { delta: target, ..cur.clone() })
                else {
                    points.push(CyclePoint { step: next.step, leg: Leg::Loading, inverted: false });
                    return (points, buckling, false);
                };
                next = self.staggered_step(target, &landed, first_loads(&carried), passes);
                if next.end == StaggeredEnd::StructureFailed {
                    points.push(CyclePoint { step: next.step, leg: Leg::Loading, inverted: true });
                    return (points, buckling, false);
                }
            }
            carried = next.loads;
            let mut s = next.step;
            // The procedure has no stability test of its own: a solved state counts as one
            // on the path (the tables' `stable` column), its snap the negative slope below.
            s.stable = s.converged();
            let inverted = self.is_inverted(&s);
            let (before, after) = (contact_force(&cur), contact_force(&s));
            let drop = after < before - SLOPE_TOLERANCE * before.abs();
            if buckling.is_none() && drop && cur.delta > 0.0 {
                buckling = Some(Jump {
                    delta: s.delta,
                    force_before: cur.contact.force,
                    delta_stable: cur.delta,
                    force_unstable: s.contact.force,
                    force_after: s.contact.force,
                    radius_before: cur.contact.radius,
                    pull_before: cur.contact.adhesive,
                    delta_after: s.delta,
                });
            }
            points.push(CyclePoint { step: s.clone(), leg: Leg::Loading, inverted });
            cur = s;
            if buckling.is_some() && opt.stop_at_buckling {
                break;
            }
            if cuts > 0 {
                cuts -= 1;
                dd = (2.0 * dd).min(base);
            }
        }
        (points, buckling, true)
    }
}
