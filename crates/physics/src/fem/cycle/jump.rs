//! Jumping between the branches of the cycle: whether a state is inverted, landing on the
//! other branch at a fixed delta (Newton from a trial state, an energy descent where Newton
//! finds no stable state), the adhesive jump-in at first touch, and the walk to a target
//! delta that halves its steps where they fail. Each is a method of the shell problem.

use crate::fem::adhesion::Adhesion;
use crate::fem::contact::{FrozenAdhesion, Plate};
use crate::fem::indent::{apex_z, dimple, Options, Step};
use crate::fem::problem::ShellProblem;

/// Newton's iteration limit for a landing (the state after a jump lies far from its guess).
const LANDING_ITERATIONS: usize = 60;

impl ShellProblem<'_> {
    /// Whether the apex of `s` has left the plate by more than half a thickness (an
    /// inverted cap).
    pub fn is_inverted(&self, s: &Step) -> bool {
        let model = self.model;
        let apex = model.mesh.outer[0];
        let z = model.mesh.nodes[apex][1] + s.u[2 * apex + 1];
        z < apex_z(model) - s.delta - 0.5 * model.mesh.thickness
    }

    /// The friction anchors of a fresh contact at displacements `u` (the outer nodes'
    /// current radii).
    pub fn fresh_anchors(&self, u: &[f64]) -> Vec<f64> {
        let mesh = &self.model.mesh;
        mesh.outer.iter().map(|&a| mesh.nodes[a][0] + u[2 * a]).collect()
    }

    /// Newton for the state a jump lands on, at `delta` from the guess `start`. With
    /// friction the contact is re-established where it lands, without shear: the
    /// frictionless state, whose own positions then become the anchors (so that it is an
    /// equilibrium with friction too, and the shear builds up again from there).
    pub fn landing(&self, delta: f64, start: &[f64]) -> Step {
        self.landing_or_rest(delta, start, false)
    }

    /// `landing`; with `descent`, if Newton finds no equilibrium near the guess, the energy
    /// is descended from it instead (`indent::descend`: where a damped jump comes to rest).
    pub fn landing_or_rest(&self, delta: f64, start: &[f64], descent: bool) -> Step {
        let opt = Options { max_iterations: LANDING_ITERATIONS, ..Options::default() };
        let bare_plate = self.plate.frictionless();
        let bare = self.with_plate(&bare_plate);
        let mut s = bare.solve_at(delta, start, &[], opt);
        if !s.converged() && descent {
            s = bare.descend(delta, start, LANDING_DESCENT_ITERATIONS);
        }
        self.anchored(s)
    }

    /// A frictionless landing `s` re-established with the plate's friction (anchors where
    /// it landed, no shear); `s` itself without friction or if it did not converge.
    pub fn anchored(&self, s: Step) -> Step {
        if self.plate.friction.is_none() || !s.converged() {
            return s;
        }
        let opt = Options { max_iterations: LANDING_ITERATIONS, ..Options::default() };
        let stick = self.fresh_anchors(&s.u);
        self.solve_at(s.delta, &s.u, &stick, opt)
    }

    /// The inverted state the snap-through from the flattened state `s` lands on at its
    /// delta, if the energy leads there, found as a damped jump would find it. The
    /// structure first collapses from a central dimple (radius 0.8, 0.6 or 1.0 times the
    /// contact radius, the first whose collapse converges) under the adhesive forces of `s`
    /// held fixed: the structural solve of the thesis' staggered scheme (Section 3.2,
    /// adhesion applied as loads), here an energy descent (`indent::descend_loaded`). The
    /// energy is then descended with the adhesion live (`indent::descend`). Without
    /// adhesion the two are one descent.
    ///
    /// Why descents and not Newton from the dimple: with adhesion the flattened state stays
    /// a minimum of the model's energy past the stability test's verdict (touching points
    /// free to lift, `stability`), and the inverted state appears only later
    /// (docs/tuning.md, "Shell"). In between, Newton from a dimple
    /// converged to an inverted equilibrium or not depending on the rounding of the build,
    /// and so did W. A descent ends where the energy leads.
    pub fn jump_to_inverted(&self, s: &Step) -> Option<Step> {
        let model = self.model;
        let r_mid = model.mesh.radius + 0.5 * model.mesh.thickness;
        let bare_plate = self.plate.frictionless();
        let structure_plate = Plate { adhesion: None, ..bare_plate.clone() };
        let (bare, structure) = (self.with_plate(&bare_plate), self.with_plate(&structure_plate));
        // The adhesive forces of `s`, frozen (the staggered scheme's loads, `FrozenAdhesion`).
        let dead = bare_plate
            .adhesion
            .map_or(Vec::new(), |ad| FrozenAdhesion::at(&ad, &model.mesh, &s.u, apex_z(model) - s.delta).gradient);
        let collapsed = [0.8, 0.6, 1.0].iter().find_map(|&f| {
            let a = f * s.contact.radius;
            let start = dimple(model, &s.u, a, a * a / r_mid);
            let c = structure.descend_loaded(s.delta, &start, &dead, LANDING_DESCENT_ITERATIONS);
            c.converged().then_some(c)
        })?;
        let rest = match bare_plate.adhesion {
            Some(_) => bare.descend(s.delta, &collapsed.u, LANDING_DESCENT_ITERATIONS),
            None => collapsed,
        };
        if !(rest.converged() && self.is_inverted(&rest)) {
            return None;
        }
        let inv = self.anchored(rest);
        (inv.converged() && self.is_inverted(&inv)).then_some(inv)
    }

    /// The adhering state at delta = 0, as the plate brought to the apex finds it: released
    /// there (the apex at the law's equilibrium gap g' = 0, everything else attracted), the
    /// shell comes to rest where the energy descends to (`indent::descend`, frictionless),
    /// the advancing-contact state of the jump-in. Friction joins only at the end: the
    /// jump-in is a jump like the others, and lands without shear (`anchored`: the
    /// frictionless state, its own positions the anchors).
    ///
    /// Why a descent: an adhering shell has several stable states at delta = 0 (the contact
    /// edge recedes at a larger radius than it advances), and which one a Newton path
    /// reaches depended on the rounding (docs/tuning.md, "Shell"). Should it
    /// not converge, the press-and-withdraw path is the fallback, each of its states a
    /// minimum (`stable_or_rest`); with friction that path's withdrawal costs thousands of
    /// Newton iterations in stick-slip cycles.
    pub fn jump_in(&self, step: f64) -> Option<Step> {
        let bare_plate = self.plate.frictionless();
        let bare = self.with_plate(&bare_plate);
        let zero = vec![0.0; self.model.n_dofs()];
        let released = bare.descend(0.0, &zero, JUMP_IN_DESCENT_ITERATIONS);
        let s = if released.converged() { released } else { bare.press_and_withdraw(step)? };
        let s = self.anchored(s);
        s.converged().then_some(Step { iterations: 0, ..s })
    }

    /// The adhering state at delta = 0 by continuation (`jump_in`'s fallback; frictionless
    /// plate). Pressed in by four load steps without adhesion, the adhesion is switched on
    /// by continuation in gamma (adaptive increments, each Newton from the last: strong
    /// adhesion pulls a wide annulus onto the plate, too far for one Newton; eight fixed
    /// increments failed from gamma/(E h) ~ 1e-2 on, at h/R = 0.06), and the plate is
    /// withdrawn to delta = 0 in adaptive steps. If it cannot be withdrawn all the way (the
    /// contact would be torn off), the state at the smallest delta reached starts the
    /// loading.
    pub fn press_and_withdraw(&self, step: f64) -> Option<Step> {
        let ad = self.plate.adhesion?;
        let opt = Options { max_iterations: LANDING_ITERATIONS, ..Options::default() };
        let zero = vec![0.0; self.model.n_dofs()];
        let bare_plate = Plate { adhesion: None, ..self.plate.clone() };
        // Pressed in by four load steps: a contact disk wide enough that the adhesive zone
        // around it grows from its rim rather than snapping on.
        let press = 4.0 * step;
        let mut s = self.with_plate(&bare_plate).solve_at(press, &zero, &[], opt);
        if !s.converged() {
            return None;
        }
        // Continuation in the work of adhesion, adaptive: an increment Newton cannot follow
        // is halved (strong adhesion pulls the surface onto the plate over a widening
        // annulus).
        let (mut t, mut dt) = (0.0f64, 1.0 / 8.0);
        while t < 1.0 {
            let next = (t + dt).min(1.0);
            let partial_plate =
                Plate { adhesion: Some(Adhesion { gamma: ad.gamma * next, ..ad }), ..self.plate.clone() };
            let partial = self.with_plate(&partial_plate);
            let trial = partial.solve_at(press, &s.u, &s.contact.stick, opt);
            if let Some(trial) = partial.stable_or_rest(trial, &s.u) {
                s = trial;
                t = next;
                dt = (1.5 * dt).min(0.25);
            } else {
                dt *= 0.5;
                if dt < 1.0 / 4096.0 {
                    return None;
                }
            }
        }
        let max_dd = 0.25 * step;
        let mut dd = max_dd;
        while s.delta > 0.0 && dd > step / 1024.0 {
            let next = self.solve_from((s.delta - dd).max(0.0), &s, opt);
            if let Some(next) = self.stable_or_rest(next, &s.u) {
                s = next;
                dd = (1.5 * dd).min(max_dd);
            } else {
                dd *= 0.5;
            }
        }
        s.iterations = 0;
        Some(s)
    }

    /// A state of the jump-in: the converged Newton state `trial` if it is stable; if it is
    /// an unstable equilibrium (Newton converges to whichever equilibrium is near, and past
    /// a fold of the adhering branch that is the saddle beyond it), the minimum the energy
    /// descends to from the previous state `from`, as a damped shell would come to rest (a
    /// frictionless plate: the descent needs a potential). None if neither converges.
    ///
    /// Without this, the start of h/R = 0.1, mu = 0, gamma/(E h) = 0.03 was a saddle with
    /// one LU and a minimum with another, and the map moved with the rounding
    /// (docs/tuning.md, "Shell").
    pub fn stable_or_rest(&self, trial: Step, from: &[f64]) -> Option<Step> {
        if !trial.converged() {
            return None;
        }
        if trial.stable {
            return Some(trial);
        }
        let s = self.descend(trial.delta, from, LANDING_DESCENT_ITERATIONS);
        s.converged().then_some(s)
    }

    /// A failed Newton solve at `delta` from `from` (`failed`), tried again with the
    /// monotone line search before the failure is taken as an answer (past the limit point,
    /// no state there): one more solve, only where a failure decides the result, in case
    /// the nonmonotone search (`indent::NONMONOTONE_WINDOW`) missed a state the monotone one
    /// finds.
    pub fn confirm_failure(&self, delta: f64, from: &Step, failed: Step) -> Step {
        let retry = self.solve_from(delta, from, Options { window: 1, ..Options::default() });
        if retry.converged() {
            retry
        } else {
            failed
        }
    }

    /// From the converged state `from` to plate displacement `target` in steps halved on
    /// failure (`halving_walk`, at most `max_cuts` halvings below half the distance); the
    /// state at `target`, or None if a step fails at the smallest size. Each step's Newton
    /// runs are extended to 60 iterations where they stop at the limit, as the unloading's
    /// full step is: near a stick-slip transition of the frictional unloading (Fig. 3.8's
    /// shells at delta/R 0.22-0.28) converging steps take 40-57 iterations, and with 30 a
    /// walk failed at every size, which ended the unloading leg where the path goes on
    /// smoothly.
    pub fn walk_to(&self, from: &Step, target: f64, max_cuts: u32) -> Option<Step> {
        halving_walk(
            from.clone(),
            |s| s.delta,
            target,
            max_cuts,
            |next, cur| {
                let s = self.solve_from_extending(next, cur, Options::default(), LANDING_ITERATIONS);
                s.converged().then_some(s)
            },
        )
    }
}

/// Shifted-Newton iterations of the jump-in's descent: about three times the most it takes
/// up to gamma/(E h) = 0.08 (docs/tuning.md).
pub(super) const JUMP_IN_DESCENT_ITERATIONS: usize = 400;

/// Shifted-Newton iterations of an energy descent that lands a jump.
pub(super) const LANDING_DESCENT_ITERATIONS: usize = 150;

/// How many flattened loading states (nearest in delta first) the snap-back's landing
/// starts from before it gives up.
pub(super) const SNAP_BACK_STARTS: usize = 4;

/// The walk of `ShellProblem::walk_to` for any state with a plate displacement `delta_of`: `solve(next,
/// cur)` gives the state at `next` from `cur`, or None. The first step is half the
/// distance; a failed step is halved (at most `max_cuts` halvings in all) and the size
/// reached is kept for the rest of the walk. The last step lands on `target` exactly.
pub(super) fn halving_walk<S>(
    from: S,
    delta_of: impl Fn(&S) -> f64,
    target: f64,
    max_cuts: u32,
    mut solve: impl FnMut(f64, &S) -> Option<S>,
) -> Option<S> {
    let mut cur = from;
    let mut dd = 0.5 * (target - delta_of(&cur));
    let mut cuts = 1;
    while delta_of(&cur) != target {
        let at = delta_of(&cur);
        let next = if (target - at).abs() <= dd.abs() { target } else { at + dd };
        match solve(next, &cur) {
            Some(s) => cur = s,
            None if cuts < max_cuts => {
                cuts += 1;
                dd *= 0.5;
            }
            None => return None,
        }
    }
    Some(cur)
}
