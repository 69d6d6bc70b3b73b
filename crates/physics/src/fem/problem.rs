//! The shell problem: one model (mesh, material, imperfection), one plate (penalty contact,
//! adhesion, friction) and the Young's modulus that scales Newton's tolerance (residuals in
//! E h^2). Every solve of the cycle (`cycle`) is a method of it, so that the clump (model,
//! plate, modulus) travels as one value.
//!
//! The solvers themselves live in `indent` (Newton at a prescribed plate displacement, the
//! energy descents) and `stability` (the tests of a state); this type only binds them to
//! one problem. Thesis equations: those of the model (`fem`).

use super::contact::Plate;
use super::indent::{self, Options, Step};
use super::stability::{self, AdhesiveHold, Criterion};
use super::system::Model;

/// The model, the plate and Young's modulus E of one shell problem.
#[derive(Clone, Copy)]
pub struct ShellProblem<'a> {
    pub model: &'a Model,
    pub plate: &'a Plate,
    /// Young's modulus E (Newton's residual tolerance is relative to E h^2).
    pub young: f64,
}

impl<'a> ShellProblem<'a> {
    pub fn new(model: &'a Model, plate: &'a Plate, young: f64) -> ShellProblem<'a> {
        ShellProblem { model, plate, young }
    }

    /// The same model and modulus against another plate (the frictionless or
    /// adhesionless variant of this one, or a partial work of adhesion).
    pub fn with_plate<'b>(&self, plate: &'b Plate) -> ShellProblem<'b>
    where
        'a: 'b,
    {
        ShellProblem { model: self.model, plate, young: self.young }
    }

    /// Newton at plate displacement `delta` from displacements `u0` with the friction
    /// anchors `stick` (`indent::solve_at`).
    pub fn solve_at(&self, delta: f64, u0: &[f64], stick: &[f64], opt: Options) -> Step {
        indent::solve_at(self.model, self.plate, self.young, delta, u0, stick, opt)
    }

    /// Newton at `delta` from the converged state `from`, Euler predictor first
    /// (`indent::solve_from`).
    pub fn solve_from(&self, delta: f64, from: &Step, opt: Options) -> Step {
        indent::solve_from(self.model, self.plate, self.young, delta, from, opt)
    }

    /// `solve_from`, its runs that stop at the iteration limit resumed up to
    /// `max_iterations` (`indent::solve_from_extending`).
    pub fn solve_from_extending(&self, delta: f64, from: &Step, opt: Options, max_iterations: usize) -> Step {
        indent::solve_from_extending(self.model, self.plate, self.young, delta, from, opt, max_iterations)
    }

    /// Energy descent to a stable state at `delta` from `u0` (`indent::descend`;
    /// frictionless plate).
    pub fn descend(&self, delta: f64, u0: &[f64], max_iterations: usize) -> Step {
        indent::descend(self.model, self.plate, self.young, delta, u0, max_iterations)
    }

    /// Energy descent under the extra dead load `-dead` (`indent::descend_loaded`).
    pub fn descend_loaded(&self, delta: f64, u0: &[f64], dead: &[f64], max_iterations: usize) -> Step {
        indent::descend_loaded(self.model, self.plate, self.young, delta, u0, dead, max_iterations)
    }

    /// Whether the converged state `s` is stable under `criterion`, touching adhesive
    /// points held as `hold` says (`stability::unilaterally_stable`).
    pub fn is_stable(&self, s: &Step, criterion: Criterion, hold: AdhesiveHold) -> bool {
        stability::unilaterally_stable(self.model, self.plate, s, criterion.threshold(), hold)
    }

    /// The smallest eigenvalue of the stability test's tangent at `s`
    /// (`stability::stability_margin`), by `iterations` inverse iterations.
    pub fn stability_margin(
        &self,
        s: &Step,
        criterion: Criterion,
        hold: AdhesiveHold,
        iterations: usize,
    ) -> Option<f64> {
        stability::stability_margin(self.model, self.plate, s, criterion.threshold(), hold, iterations)
    }

    /// The reference state: zero displacement at delta = 0, no contact (not yet an
    /// equilibrium with adhesion).
    pub fn reference_state(&self) -> Step {
        Step {
            delta: 0.0,
            u: vec![0.0; self.model.n_dofs()],
            contact: Default::default(),
            iterations: 0,
            residual: 0.0,
            stable: true,
            termination: indent::StepEnd::Converged,
        }
    }
}

impl ShellProblem<'_> {
    /// The path by arc length from the converged state `start`, delta moving first in the
    /// direction of `sign`, until `stop` holds (`arclength::continue_path`).
    pub fn continue_path(
        &self,
        start: &Step,
        sign: f64,
        opt: super::arclength::ArcOptions,
        stop: impl FnMut(&super::arclength::ArcPoint) -> bool,
    ) -> (Vec<super::arclength::ArcPoint>, bool) {
        super::arclength::continue_path(self.model, self.plate, self.young, start, sign, opt, stop)
    }
}
