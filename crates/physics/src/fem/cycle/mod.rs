//! A load-unload cycle under prescribed plate displacement, as the experiments of thesis
//! Section 3.3 see it (Figs. 3.2, 3.4-3.5: loading solid, unloading dashed): the plate goes
//! down to delta_max and back in equal steps; the state follows its branch until the branch
//! loses stability (loading: the flattened state, whose interior then lifts off and inverts,
//! `stability`) or ends (unloading: the inverted state past its limit point), and then jumps
//! at that delta to the other branch. Both events are located by bisection in delta.
//! With adhesion the loss of stability can come before the inverted branch exists: the
//! jump lands where an energy descent leads (`ShellProblem::jump_to_inverted`), and until it does the flattened
//! state is *held* (given up by the stability test, kept by the energy) and the landing is
//! sought again at each step. `Snap` chooses which of the two events answers "does it
//! buckle" when the leg stops there.
//!
//! Reported: F_buckling (the largest force before the snap) and its delta, the snap-back
//! delta on unloading, and the work of the plate on each leg, whose difference is the
//! hysteresis loop area W = closed integral of F d(delta) (zero without a jump: the model is
//! elastic and frictionless).

mod energy;
mod jump;
mod loading;
mod staggered;
mod unloading;

pub use staggered::{
    FirstPass, Passes, Staggered, StaggeredEnd, StaggeredStep, MAX_PASSES, SLOPE_TOLERANCE, STAGGERED_TOLERANCE,
};

use loading::Loading;
use unloading::Unloading;

use super::contact::Plate;
use super::indent::{Step, StepEnd};
use super::problem::ShellProblem;
use super::stability::{AdhesiveHold, Criterion};
use super::system::Model;

/// Inverse iterations for a stability margin (`stability::stability_margin`): as many as
/// the margin needs to settle next to the fold, where it is smallest (tested:
/// `the_stability_margins_inverse_iterations_have_converged_near_the_fold`).
const MARGIN_ITERATIONS: usize = 15;

/// Settings of the cycle (lengths in the mesh's units).
#[derive(Clone, Copy, Debug)]
pub struct CycleOptions {
    pub delta_max: f64,
    /// Equal steps on each leg.
    pub steps: usize,
    /// Halvings of a step that fails to converge.
    pub max_cuts: u32,
    /// Bisections locating each event (the event's delta is then known to
    /// delta_max / steps / 2^bisections).
    pub bisections: u32,
    /// Which states count as stable (`stability::Criterion`).
    pub criterion: Criterion,
    /// What holds touching points of an adhesive contact in the stability test.
    pub hold: AdhesiveHold,
    /// Also trace the unstable branch past the inverted branch's limit point (arc length).
    pub trace_unstable: bool,
    /// Run the unloading leg (false: loading only).
    pub unload: bool,
    /// End the loading leg at the snap-through (the question "does it buckle, and at what
    /// force" is then answered; implies no unloading).
    pub stop_at_buckling: bool,
    /// What answers that question when the leg stops there (`Snap`).
    pub snap: Snap,
}

/// When a loading leg that stops at the snap-through has its answer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Snap {
    /// At the first state the stability test gives up (the thesis' criterion, its
    /// structural solve seeing the adhesion as loads): F_buckling is known.
    #[default]
    Instability,
    /// At the landing on the inverted branch: the drop a displacement-controlled
    /// experiment sees. States given up but held by the energy (`ShellProblem::jump_to_inverted`) do not count; a
    /// leg that never lands has not snapped.
    Landing,
    /// The thesis' own procedure (Section 3.2, `staggered`): adhesion applied as loads
    /// from the last pass's gaps, the passes per step as given, and the snap the first
    /// negative slope of F(delta). Runs the loading leg only.
    Staggered(Staggered),
    /// The energy balance (`energy`): the snap where the inverted state lies lower in total
    /// potential energy than the adhered flattened one, or where the flattened branch ends.
    /// A cycle that unloads jumps there and comes back as under `Instability`. With
    /// `friction`, the inverted state must lie lower by the work friction does on the way
    /// (`ShellProblem::friction_work`): the energetic criterion of a rate-independent
    /// dissipative system.
    Energy { friction: bool },
}

impl Snap {
    /// Whether the loss of stability `j` is a snap-through under this criterion.
    pub fn counts(self, j: &Jump) -> bool {
        self == Snap::Instability || j.delta_after.is_finite()
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Leg {
    Loading,
    Unloading,
}

/// One state of the cycle.
#[derive(Clone, Debug)]
pub struct CyclePoint {
    pub step: Step,
    pub leg: Leg,
    /// The apex has left the plate by more than half a thickness (inverted cap).
    pub inverted: bool,
}

/// A jump between branches at fixed delta.
#[derive(Clone, Copy, Debug)]
pub struct Jump {
    pub delta: f64,
    pub force_before: f64,
    /// The bracket of the event: the last state before it (delta_stable, force_before) and
    /// the first after it, still on the old branch (delta, force_unstable). The snap-through
    /// lies between (bisected to delta - delta_stable); the snap-back is a limit point found
    /// by arc length, where both are the same state.
    pub delta_stable: f64,
    pub force_unstable: f64,
    pub force_after: f64,
    /// Outermost contact radius (current) of the state before the jump.
    pub radius_before: f64,
    /// The adhesive part (<= 0) of `force_before`.
    pub pull_before: f64,
    /// Where the state after the jump was found (= delta, unless Newton found no state to
    /// land on at first; NaN if it never did).
    pub delta_after: f64,
}

#[derive(Clone, Debug, Default)]
pub struct Cycle {
    pub points: Vec<CyclePoint>,
    /// Loading snap-through: delta and force F_buckling just before, force just after.
    pub buckling: Option<Jump>,
    /// Unloading snap-back from the inverted to the flattened branch.
    pub snap_back: Option<Jump>,
    /// Int F d(delta) on the loading and on the unloading leg (trapezoids; jumps are
    /// vertical). Their difference is the dissipated energy.
    pub work_loading: f64,
    pub work_unloading: f64,
    /// Every step converged.
    pub complete: bool,
    /// The unstable branch from the limit point of the inverted branch (if traced), in the
    /// order of the arc length.
    pub unstable: Vec<Step>,
    /// Under `Snap::Energy`, the balance at the last loaded state, when the flattened
    /// branch reached it and an inverted state was found there.
    pub balance: Option<Balance>,
}

/// The energy criterion's comparison at one plate displacement (`Snap::Energy`): the total
/// potential energy Pi of the inverted state less the flattened one's, plus the friction
/// work of the way between them where the criterion counts it (> 0: the flattened state
/// holds, no snap there), that friction work, and the adhesive energies of both (<= 0).
#[derive(Clone, Copy, Debug)]
pub struct Balance {
    pub delta: f64,
    pub inverted_less_flat: f64,
    pub friction_work: f64,
    pub adhesive_flat: f64,
    pub adhesive_inverted: f64,
}

impl Cycle {
    /// Every step converged and the cycle came back (an unloading leg): its work is a
    /// closed integral. (The staggered procedure runs the loading leg only.)
    pub fn is_closed(&self) -> bool {
        self.complete && self.points.iter().any(|p| p.leg == Leg::Unloading)
    }

    pub fn dissipated(&self) -> f64 {
        self.work_loading - self.work_unloading
    }

    /// Error estimate of `dissipated`, from the discretisation of the load path (not of the
    /// mesh): per leg `path_work_error` (the trapezoids on the smooth pieces and where the
    /// vertical jumps lie between computed states), plus, for a snap-through that landed at
    /// once, its bisection bracket times the force drop.
    pub fn dissipated_error(&self) -> f64 {
        let leg = |leg: Leg| -> Vec<[f64; 2]> {
            self.points.iter().filter(|p| p.leg == leg).map(|p| [p.step.delta, p.step.contact.force]).collect()
        };
        let snap = self
            .buckling
            .filter(|b| b.delta_after == b.delta)
            .map_or(0.0, |b| (b.delta - b.delta_stable).abs() * (b.force_before - b.force_after).abs());
        path_work_error(&leg(Leg::Loading)) + path_work_error(&leg(Leg::Unloading)) + snap
    }
}

impl Cycle {
    /// The work done against friction on the quasi-static pieces of the cycle, by the outer
    /// nodes of tributary areas `weights` (`contact::Plate::weights`): between consecutive
    /// converged states of the path on the same branch at different delta, Sum_a |tau_a| w_a
    /// |xi_a' - xi_a| over the nodes slipping in the later state (tau its shear per reference
    /// area, xi its anchor, whose motion is the slip of the return mapping; backward Euler,
    /// as the solve). Not across the jumps, whose landings re-anchor the contact: the
    /// friction during a snap belongs to the snap's loss. Part of `dissipated`; the rest is
    /// lost in the jumps and in the adhesive hysteresis (without either, all of it).
    pub fn friction_work(&self, weights: &[f64]) -> f64 {
        self.points
            .windows(2)
            .filter(|w| {
                let (a, b) = (&w[0], &w[1]);
                a.step.converged() && b.step.converged() && a.inverted == b.inverted && a.step.delta != b.step.delta
            })
            .map(|w| {
                let (a, b) = (&w[0].step.contact, &w[1].step.contact);
                (0..weights.len())
                    .filter(|&k| b.slipping.get(k).copied().unwrap_or(false) && k < a.stick.len())
                    .map(|k| b.shear[k].abs() * weights[k] * (b.stick[k] - a.stick[k]).abs())
                    .sum::<f64>()
            })
            .sum()
    }
}

/// The trapezoid rule's Int F d(delta) along `path` ((delta, F) in path order).
fn trapezoid(path: &[[f64; 2]]) -> f64 {
    path.windows(2).map(|w| 0.5 * (w[0][1] + w[1][1]) * (w[1][0] - w[0][0]).abs()).sum()
}

/// Error estimate of `trapezoid(path)`. The path is split at its vertical jumps (two states
/// at the same delta). On each smooth piece of at least three states, Richardson's
/// |T - T_2| / 3 (T_2 the rule on every other state, the last one kept). Each jump may lie
/// anywhere since the state before it: |force jump| times that delta step.
fn path_work_error(path: &[[f64; 2]]) -> f64 {
    let mut error = 0.0;
    let mut start = 0;
    for i in 1..=path.len() {
        let jump = i < path.len() && path[i][0] == path[i - 1][0];
        if jump && i >= 2 {
            error += (path[i][1] - path[i - 1][1]).abs() * (path[i - 1][0] - path[i - 2][0]).abs();
        }
        if jump || i == path.len() {
            let piece = &path[start..i];
            if piece.len() >= 3 {
                let mut every_other: Vec<[f64; 2]> = piece.iter().step_by(2).copied().collect();
                if piece.len().is_multiple_of(2) {
                    every_other.push(piece[piece.len() - 1]);
                }
                error += (trapezoid(piece) - trapezoid(&every_other)).abs() / 3.0;
            }
            start = i;
        }
    }
    error
}

fn work(points: &[CyclePoint]) -> f64 {
    trapezoid(&points.iter().map(|p| [p.step.delta, p.step.contact.force]).collect::<Vec<_>>())
}

impl ShellProblem<'_> {
    /// The load-unload cycle from the reference state: the start (the adhering state of
    /// the jump-in, with adhesion), the loading leg with its snap (`loading`), and unless
    /// the options end the cycle there, the unloading leg with its snap-back
    /// (`unloading`).
    pub fn load_unload(&self, opt: CycleOptions) -> Cycle {
        if let Snap::Energy { .. } = opt.snap {
            return if opt.unload && !opt.stop_at_buckling { self.energy_cycle(opt) } else { self.energy_loading(opt) };
        }
        if let Snap::Staggered(procedure) = opt.snap {
            let (points, buckling, complete) = self.staggered_loading(&opt, procedure);
            return Cycle { work_loading: work(&points), points, buckling, complete, ..Default::default() };
        }
        let loading = self.local_loading(opt);
        self.with_unloading(opt, loading)
    }

    /// The loading leg from the cycle's start, run.
    fn local_loading(&self, opt: CycleOptions) -> Loading<'_, '_> {
        let mut loading = Loading::new(self, opt, self.cycle_start(opt.delta_max / opt.steps as f64));
        loading.run();
        loading
    }

    /// The cycle of a loading leg that has run: with its unloading leg unless the options
    /// end the cycle at the snap or on loading.
    fn with_unloading(&self, opt: CycleOptions, loading: Loading) -> Cycle {
        let mut cycle = Cycle {
            complete: loading.complete,
            buckling: loading.buckling,
            work_loading: work(&loading.points),
            ..Default::default()
        };
        if !opt.unload || opt.stop_at_buckling {
            cycle.points = loading.points;
            return cycle;
        }
        let mut unloading = Unloading::new(self, opt, &loading.points, loading.cur.clone(), loading.inverted);
        unloading.run(&mut cycle);
        cycle.work_unloading = work(&unloading.points);
        let unloading = unloading.points;
        cycle.points = loading.points;
        cycle.points.extend(unloading);
        cycle
    }

    /// The state the loading starts from. With adhesion the reference state is not in
    /// equilibrium at delta = 0: the apex jumps into contact (as the plate approaches,
    /// before delta = 0), and the loading starts from that adhering state (`jump_in`, with
    /// load step `step`). If no adhering state is found, the loading starts from the
    /// reference state, then recorded as what it is: not an equilibrium (not converged).
    fn cycle_start(&self, step: f64) -> Step {
        let zero = self.reference_state();
        match self.plate.adhesion {
            Some(_) => self.jump_in(step).unwrap_or(Step { termination: StepEnd::NotSolved, ..zero }),
            None => zero,
        }
    }
}

/// Runs the cycle from the reference state (`ShellProblem::load_unload`).
pub fn load_unload(model: &Model, plate: &Plate, e: f64, opt: CycleOptions) -> Cycle {
    ShellProblem::new(model, plate, e).load_unload(opt)
}

#[cfg(test)]
mod tests;
