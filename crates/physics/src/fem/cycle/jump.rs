//! Jumping between the branches of the cycle: whether a state is inverted, landing on the
//! other branch at a fixed delta (Newton from a trial state, an energy descent where Newton
//! finds no stable state), the adhesive jump-in at first touch, and the walk to a target
//! delta that halves its steps where they fail.

use crate::fem::adhesion::Tangent;
use crate::fem::contact::Plate;
use crate::fem::indent::{
    apex_z, descend, descend_loaded, dimple, solve_at, solve_from, solve_from_extending, Options, Step,
};
use crate::fem::system::Model;

pub(super) fn is_inverted(model: &Model, s: &Step) -> bool {
    let apex = model.mesh.outer[0];
    let z = model.mesh.nodes[apex][1] + s.u[2 * apex + 1];
    z < apex_z(model) - s.delta - 0.5 * model.mesh.thickness
}

/// The friction anchors of a fresh contact at displacements `u` (the outer nodes' current
/// radii).
pub(super) fn fresh_stick(model: &Model, u: &[f64]) -> Vec<f64> {
    model.mesh.outer.iter().map(|&a| model.mesh.nodes[a][0] + u[2 * a]).collect()
}

/// Newton for the state a jump lands on, at `delta` from the guess `start`. With friction
/// the contact is re-established where it lands, without shear: the frictionless state,
/// whose own positions then become the anchors (so that it is an equilibrium with friction
/// too, and the shear builds up again from there).
pub(super) fn land(model: &Model, plate: &Plate, e: f64, delta: f64, start: &[f64]) -> Step {
    land_with(model, plate, e, delta, start, false)
}

/// `land`; with `descent`, if Newton finds no equilibrium near the guess, the energy is
/// descended from it instead (`indent::descend`: where a damped jump comes to rest).
pub(super) fn land_with(model: &Model, plate: &Plate, e: f64, delta: f64, start: &[f64], descent: bool) -> Step {
    let opt = Options { max_iterations: 60, ..Options::default() };
    let bare = plate.frictionless();
    let mut s = solve_at(model, &bare, e, delta, start, &[], opt);
    if !s.converged && descent {
        s = descend(model, &bare, e, delta, start, LANDING_DESCENT_ITERATIONS);
    }
    anchor(model, plate, e, s)
}

/// A frictionless landing `s` re-established with the plate's friction (anchors where it
/// landed, no shear); `s` itself without friction or if it did not converge.
pub(super) fn anchor(model: &Model, plate: &Plate, e: f64, s: Step) -> Step {
    if plate.friction.is_none() || !s.converged {
        return s;
    }
    let opt = Options { max_iterations: 60, ..Options::default() };
    let stick = fresh_stick(model, &s.u);
    solve_at(model, plate, e, s.delta, &s.u, &stick, opt)
}

/// The inverted state the snap-through from the flattened state `s` lands on at its delta,
/// if the energy leads there, found as a damped jump would find it. The structure first
/// collapses from a central dimple (radius 0.8, 0.6 or 1.0 times the contact radius, the
/// first whose collapse converges) under the adhesive forces of `s` held fixed: the
/// structural solve of the thesis' staggered scheme (Section 3.2, adhesion applied as
/// loads), here an energy descent (`indent::descend_loaded`). The energy is then descended
/// with the adhesion live (`indent::descend`). Without adhesion the two are one descent.
///
/// Why descents and not Newton from the dimple: with adhesion the flattened state stays a
/// minimum of the model's energy past the stability test's verdict (touching points free to
/// lift, `stability`), and the inverted state appears only later (measured at h/R = 0.06,
/// gamma/(E h) = 2e-3: unstable from delta/R = 0.190, no inverted state reachable before
/// 0.255; Fig. 3.2's case: 0.189 and 0.209). In between, Newton from a dimple converged to
/// an inverted equilibrium or not depending on the rounding of the build, and so did W
/// (-0.03 and 0.59 for a change of h by one ulp). A descent ends where the energy leads.
pub(super) fn invert(model: &Model, plate: &Plate, e: f64, s: &Step) -> Option<Step> {
    let r_mid = model.mesh.radius + 0.5 * model.mesh.thickness;
    let bare = plate.frictionless();
    let structure = Plate { adhesion: None, ..bare.clone() };
    let dead = bare.adhesion.map_or(Vec::new(), |ad| {
        let n = model.n_dofs();
        let mut g = vec![0.0; n];
        let z_plate = apex_z(model) - s.delta;
        ad.apply(&model.mesh, &s.u, z_plate, &mut g, &mut Vec::new(), &mut vec![0.0; n], Tangent::Exact);
        g
    });
    let collapsed = [0.8, 0.6, 1.0].iter().find_map(|&f| {
        let a = f * s.contact.radius;
        let start = dimple(model, &s.u, a, a * a / r_mid);
        let c = descend_loaded(model, &structure, e, s.delta, &start, &dead, LANDING_DESCENT_ITERATIONS);
        c.converged.then_some(c)
    })?;
    let rest = match bare.adhesion {
        Some(_) => descend(model, &bare, e, s.delta, &collapsed.u, LANDING_DESCENT_ITERATIONS),
        None => collapsed,
    };
    if !(rest.converged && is_inverted(model, &rest)) {
        return None;
    }
    let inv = anchor(model, plate, e, rest);
    (inv.converged && is_inverted(model, &inv)).then_some(inv)
}

/// The adhering state at delta = 0, as the plate brought to the apex finds it: released
/// there (the apex at the law's equilibrium gap g' = 0, everything else attracted), the
/// shell comes to rest where the energy descends to (`indent::descend`, frictionless),
/// the advancing-contact state of the jump-in. Friction joins only at the end: the
/// jump-in is a jump like the others, and lands without shear (`anchor`: the frictionless
/// state, its own positions the anchors).
///
/// Why a descent: an adhering shell has several stable states at delta = 0 (the contact
/// edge recedes at a larger radius than it advances), and which one a Newton path reaches
/// depended on the rounding. The former construction (pressed in by four load steps,
/// adhesion ramped on, withdrawn in adaptive steps) ended, at h/R = 0.1, gamma/(E h) =
/// 0.0283, mu = 0, at r/R = 0.410 with faer's sparse LU and at 0.447 with the band LU
/// (different step halvings on the way back): the one loading snapped before delta_max and
/// the other did not, and gamma_c moved from 0.038 to 0.027. The descent ends at r/R =
/// 0.410165 with both, and at the same r/R and force with both wherever it was tried
/// (docs/tuning.md). Should it not converge, the press-and-withdraw path is the fallback,
/// each of its states a minimum (`stable_or_descend`); with friction that path's withdrawal
/// costs thousands of Newton iterations in stick-slip cycles.
pub(super) fn jump_in(model: &Model, plate: &Plate, e: f64, step: f64) -> Option<Step> {
    let bare = plate.frictionless();
    let zero = vec![0.0; model.n_dofs()];
    let released = descend(model, &bare, e, 0.0, &zero, JUMP_IN_DESCENT_ITERATIONS);
    let s = if released.converged { released } else { press_and_withdraw(model, &bare, e, step)? };
    let s = anchor(model, plate, e, s);
    s.converged.then_some(Step { iterations: 0, ..s })
}

/// Shifted-Newton iterations of the jump-in's descent: about three times the most it takes
/// up to gamma/(E h) = 0.08 (docs/tuning.md).
pub(super) const JUMP_IN_DESCENT_ITERATIONS: usize = 400;

/// The adhering state at delta = 0 by continuation (`jump_in`'s fallback; frictionless
/// `plate`). Pressed in by four load steps without adhesion, the adhesion is switched on
/// by continuation in gamma (adaptive increments, each Newton from the last: strong
/// adhesion pulls a wide annulus onto the plate, too far for one Newton; eight fixed
/// increments failed from gamma/(E h) ~ 1e-2 on, at h/R = 0.06), and the plate is withdrawn
/// to delta = 0 in adaptive steps. If it cannot be withdrawn all the way (the contact would
/// be torn off), the state at the smallest delta reached starts the loading.
pub(super) fn press_and_withdraw(model: &Model, plate: &Plate, e: f64, step: f64) -> Option<Step> {
    let ad = plate.adhesion?;
    let opt = Options { max_iterations: 60, ..Options::default() };
    let zero = vec![0.0; model.n_dofs()];
    let bare = Plate { adhesion: None, ..plate.clone() };
    // Pressed in by four load steps: a contact disk wide enough that the adhesive zone
    // around it grows from its rim rather than snapping on.
    let press = 4.0 * step;
    let mut s = solve_at(model, &bare, e, press, &zero, &[], opt);
    if !s.converged {
        return None;
    }
    // Continuation in the work of adhesion, adaptive: an increment Newton cannot follow is
    // halved (strong adhesion pulls the surface onto the plate over a widening annulus).
    let (mut t, mut dt) = (0.0f64, 1.0 / 8.0);
    while t < 1.0 {
        let next = (t + dt).min(1.0);
        let partial =
            Plate { adhesion: Some(crate::fem::adhesion::Adhesion { gamma: ad.gamma * next, ..ad }), ..plate.clone() };
        let trial = solve_at(model, &partial, e, press, &s.u, &s.contact.stick, opt);
        if let Some(trial) = stable_or_descend(model, &partial, e, trial, &s.u) {
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
        let next = solve_from(model, plate, e, (s.delta - dd).max(0.0), &s, opt);
        if let Some(next) = stable_or_descend(model, plate, e, next, &s.u) {
            s = next;
            dd = (1.5 * dd).min(max_dd);
        } else {
            dd *= 0.5;
        }
    }
    s.iterations = 0;
    Some(s)
}

/// A state of the jump-in: the converged Newton state `trial` if it is stable; if it is an
/// unstable equilibrium (Newton converges to whichever equilibrium is near, and past a fold
/// of the adhering branch that is the saddle beyond it), the minimum the energy descends to
/// from the previous state `from`, as a damped shell would come to rest (a frictionless
/// `plate`: the descent needs a potential). None if neither converges.
///
/// Measured: without this, the start of h/R = 0.1, mu = 0, gamma/(E h) = 0.03 was a saddle
/// (r/R 0.430, unstable even with every contact node held) with a sparse LU
/// and a minimum (r/R 0.419) with the band LU; the loading from the saddle
/// "snapped" at delta/R = 3e-4, which decided gamma_c, so the map moved with the rounding.
pub(super) fn stable_or_descend(model: &Model, plate: &Plate, e: f64, trial: Step, from: &[f64]) -> Option<Step> {
    if !trial.converged {
        return None;
    }
    if trial.stable {
        return Some(trial);
    }
    let s = descend(model, plate, e, trial.delta, from, LANDING_DESCENT_ITERATIONS);
    s.converged.then_some(s)
}

/// Shifted-Newton iterations of an energy descent that lands a jump.
pub(super) const LANDING_DESCENT_ITERATIONS: usize = 150;

/// How many flattened loading states (nearest in delta first) the snap-back's landing
/// starts from before it gives up.
pub(super) const SNAP_BACK_STARTS: usize = 4;

/// A failed Newton solve at `delta` from `from` (`failed`), tried again with the monotone
/// line search before the failure is taken as an answer (past the limit point, no state
/// there): one more solve, only where a failure decides the result, in case the nonmonotone
/// search (`indent::NONMONOTONE_WINDOW`) missed a state the monotone one finds.
pub(super) fn confirm_failure(model: &Model, plate: &Plate, e: f64, delta: f64, from: &Step, failed: Step) -> Step {
    let retry = solve_from(model, plate, e, delta, from, Options { window: 1, ..Options::default() });
    if retry.converged {
        retry
    } else {
        failed
    }
}

/// From the converged state `from` to plate displacement `target` in steps halved on
/// failure (at most `max_cuts` halvings below half the distance); the state at `target`,
/// or None if a step fails at the smallest size. Each step's Newton runs are extended to
/// 60 iterations where they stop at the limit, as the unloading's full step is: near a
/// stick-slip transition of the frictional unloading (Fig. 3.8's shells at delta/R
/// 0.22-0.28) converging steps take 40-57 iterations, and with 30 a walk failed at every
/// size, which ended the unloading leg at a state where the path goes on smoothly.
pub(super) fn walk(model: &Model, plate: &Plate, e: f64, from: &Step, target: f64, max_cuts: u32) -> Option<Step> {
    halving_walk(
        from.clone(),
        |s| s.delta,
        target,
        max_cuts,
        |next, cur| {
            let s = solve_from_extending(model, plate, e, next, cur, Options::default(), 60);
            s.converged.then_some(s)
        },
    )
}

/// The walk of `walk` for any state with a plate displacement `delta_of`: `solve(next,
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
