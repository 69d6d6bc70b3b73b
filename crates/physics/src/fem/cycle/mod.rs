//! A load-unload cycle under prescribed plate displacement, as the experiments of thesis
//! Section 3.3 see it (Figs. 3.2, 3.4-3.5: loading solid, unloading dashed): the plate goes
//! down to delta_max and back in equal steps; the state follows its branch until the branch
//! loses stability (loading: the flattened state, whose interior then lifts off and inverts,
//! `stability`) or ends (unloading: the inverted state past its limit point), and then jumps
//! at that delta to the other branch. Both events are located by bisection in delta.
//! With adhesion the loss of stability can come before the inverted branch exists: the
//! jump lands where an energy descent leads (`invert`), and until it does the flattened
//! state is *held* (given up by the stability test, kept by the energy) and the landing is
//! sought again at each step. `Snap` chooses which of the two events answers "does it
//! buckle" when the leg stops there.
//!
//! Reported: F_buckling (the largest force before the snap) and its delta, the snap-back
//! delta on unloading, and the work of the plate on each leg, whose difference is the
//! hysteresis loop area W = closed integral of F d(delta) (zero without a jump: the model is
//! elastic and frictionless).

mod jump;

use jump::{confirm_failure, invert, is_inverted, jump_in, land, land_with, walk, SNAP_BACK_STARTS};

use super::arclength::{continue_path, ArcOptions};
use super::contact::Plate;
use super::indent::{solve_at, solve_from, solve_from_extending, Options, Step, StepEnd};
use super::stability::{stability_margin, unilaterally_stable, AdhesiveHold, Criterion};
use super::system::Model;

/// Inverse iterations for a stability margin (`stability::stability_margin`): measured
/// near the fold of h/R = 0.06, mu = 0.5, 15 agree with 40 to 1e-10.
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
    /// experiment sees. States given up but held by the energy (`invert`) do not count; a
    /// leg that never lands has not snapped.
    Landing,
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
}

impl Cycle {
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
                a.step.converged && b.step.converged && a.inverted == b.inverted && a.step.delta != b.step.delta
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

/// Runs the cycle from the reference state.
pub fn load_unload(model: &Model, plate: &Plate, e: f64, opt: CycleOptions) -> Cycle {
    let base = opt.delta_max / opt.steps as f64;
    let stable = |s: &Step| unilaterally_stable(model, plate, s, opt.criterion.threshold(), opt.hold);
    // Under the tangent criterion a step that finds no state at the smallest size has
    // passed the limit point of the flattened branch (no equilibrium lies beyond it), and a
    // state that Newton finds already inverted lies past it too.
    let limit_point = opt.criterion == Criterion::Tangent;
    // Whether the fold of the flattened branch lies before `target`, as the stability
    // margins (smallest eigenvalues of the stability test's tangent) of the last two states
    // of `loading` predict: near a limit point the margin's square falls linearly to zero.
    // Margins are computed once per state (`margins`, by delta).
    let fold_predicted = |margins: &mut Vec<(f64, Option<f64>)>, loading: &[CyclePoint], target: f64| -> bool {
        let [.., p, c] = loading else { return false };
        // (The reference state carries no contact state: no margin there.)
        let on_branch =
            |q: &CyclePoint| q.step.converged && q.step.stable && !q.inverted && !q.step.contact.active.is_empty();
        if plate.friction.is_none() || !on_branch(p) || !on_branch(c) || c.step.delta <= p.step.delta {
            return false;
        }
        let mut margin = |s: &Step| -> Option<f64> {
            if let Some(&(_, m)) = margins.iter().find(|(d, _)| *d == s.delta) {
                return m;
            }
            let m = stability_margin(model, plate, s, opt.criterion.threshold(), opt.hold, MARGIN_ITERATIONS);
            margins.push((s.delta, m));
            m
        };
        let (Some(lp), Some(lc)) = (margin(&p.step), margin(&c.step)) else { return false };
        if lc >= lp {
            return false;
        }
        let fold = c.step.delta + lc * lc * (c.step.delta - p.step.delta) / (lp * lp - lc * lc);
        fold < target
    };
    let mut cycle = Cycle { complete: true, ..Default::default() };
    let zero = Step {
        delta: 0.0,
        u: vec![0.0; model.n_dofs()],
        contact: Default::default(),
        iterations: 0,
        residual: 0.0,
        converged: true,
        stable: true,
        termination: StepEnd::Converged,
    };
    // With adhesion the reference state is not in equilibrium at delta = 0: the apex jumps
    // into contact (as the plate approaches, before delta = 0). The loading starts from that
    // adhering state.
    // If no adhering state is found, the loading starts from the reference state, which is
    // then recorded as what it is: not an equilibrium (not converged).
    let zero = match plate.adhesion {
        Some(_) => {
            jump_in(model, plate, e, base).unwrap_or(Step { converged: false, termination: StepEnd::NotSolved, ..zero })
        }
        None => zero,
    };
    let mut loading = vec![CyclePoint { step: zero.clone(), leg: Leg::Loading, inverted: false }];
    // Loading.
    let mut cur = zero.clone();
    let mut inverted = false;
    let mut dd = base;
    let mut cuts = 0;
    let smallest = base / 2f64.powi(opt.max_cuts as i32);
    // While the fold of the flattened branch is sought (tangent criterion): the smallest
    // plate displacement whose step failed or left the branch since the last state reached
    // it. With friction a step grown again after a success goes no further than there: the
    // failure is tried again from the nearer state (a step that failed from one state can
    // succeed from a nearer one), but not overshot, which near a fold fails as surely;
    // without friction the bracket is bisected (below; docs/shell.md, "Cost").
    let mut failed_at: Option<f64> = None;
    // With friction: the failure ahead lies past the fold that the stability margins of
    // the last two states predict (`fold_predicted`), and is bisected as without friction.
    let mut fold_ahead = false;
    let mut margins: Vec<(f64, Option<f64>)> = Vec::new();
    while cur.delta < opt.delta_max * (1.0 - 1e-12) {
        let past_fold = limit_point && !inverted && cycle.buckling.is_none();
        let grown = (cur.delta + dd).min(opt.delta_max);
        let target = match failed_at {
            Some(f) if past_fold && f > cur.delta => grown.min(f),
            _ => grown,
        };
        // A step shortened to delta_max counts as capped too: halving it would try the
        // same failed displacement again from the same state.
        let capped = target < cur.delta + dd;
        // A capped step no longer than the smallest counts as one.
        let at_smallest = cuts >= opt.max_cuts || (capped && target - cur.delta <= smallest * (1.0 + 1e-9));
        // The next, shorter step: half of this one; for a capped step, the largest
        // base / 2^cuts at most half of it (dd stays base / 2^cuts).
        let cut = |cuts: &mut u32, dd: &mut f64| {
            if capped {
                // (Rounding aside: a step of exactly base / 2^k is halved, not quartered.)
                *cuts = (((2.0 * base / (target - cur.delta)).log2() - 1e-9).ceil().max(1.0) as u32).min(opt.max_cuts);
                *dd = base / 2f64.powi(*cuts as i32);
            } else {
                *cuts += 1;
                *dd *= 0.5;
            }
        };
        let mut s = solve_from(model, plate, e, target, &cur, Options::default());
        if !s.converged && at_smallest {
            cuts = cuts.max(opt.max_cuts);
            s = confirm_failure(model, plate, e, target, &cur, s);
        }
        if !s.converged {
            if !at_smallest {
                cut(&mut cuts, &mut dd);
                if past_fold {
                    failed_at = Some(failed_at.map_or(target, |f| f.min(target)));
                    fold_ahead = fold_ahead || fold_predicted(&mut margins, &loading, target);
                }
                continue;
            }
            if !past_fold {
                loading.push(CyclePoint { step: s, leg: Leg::Loading, inverted });
                cycle.complete = false;
                break;
            }
        }
        s.stable = s.converged && stable(&s);
        let leaves = |s: &Step| !s.stable || (limit_point && is_inverted(model, s));
        let leaves_branch = limit_point && s.converged && !inverted && cycle.buckling.is_none() && leaves(&s);
        if leaves_branch && at_smallest {
            cuts = cuts.max(opt.max_cuts);
        }
        if leaves_branch && !at_smallest {
            // Under the tangent criterion a step that lands off the flattened branch is taken
            // again shorter, as a failed one is: the loss of stability is where the shortest
            // step still leaves (the lift threshold's test is left as it was). A long
            // step can land on another equilibrium (another slip set, or the inverted branch)
            // before the branch ends (measured, h/R = 0.06, mu = 0.5, apex force 1e-3 F_c,
            // 70 steps to delta/R = 0.7: the step to delta/R = 0.44 landed on an unstable
            // state, which put the snap at 35.2 F_c; with 105, 140 or 280 steps the branch
            // runs on to 39.46 F_c at delta/R = 0.478. Solving only the step again from the
            // bisection's last stable state is not enough: with a dimple of 1e-3 h a state
            // of the bisection itself landed off the branch, at 34.1 F_c instead of 36.36).
            cut(&mut cuts, &mut dd);
            failed_at = Some(failed_at.map_or(target, |f| f.min(target)));
            fold_ahead = fold_ahead || fold_predicted(&mut margins, &loading, target);
            continue;
        }
        if !inverted && leaves(&s) {
            let retry = cycle.buckling.is_some();
            let from = if !retry {
                // Bisect for the last stable flattened state: F_buckling, located to
                // base / 2^bisections (under the tangent criterion the step is already
                // base / 2^cuts).
                let (mut lo, mut hi) = (cur.clone(), s.clone());
                let halved = if limit_point { cuts } else { 0 };
                for _ in halved..opt.bisections {
                    let at = 0.5 * (lo.delta + hi.delta);
                    let mut mid = solve_from(model, plate, e, at, &lo, Options::default());
                    if !mid.converged && !limit_point {
                        break;
                    }
                    mid.stable = mid.converged && stable(&mid);
                    if leaves(&mid) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                if lo.delta > cur.delta {
                    loading.push(CyclePoint { step: lo.clone(), leg: Leg::Loading, inverted: false });
                }
                cycle.buckling = Some(Jump {
                    delta: hi.delta,
                    force_before: lo.contact.force,
                    delta_stable: lo.delta,
                    // Past a limit point there may be no state: the force there is the
                    // last one's (the bracket is then the bisection's delta alone).
                    force_unstable: if hi.converged { hi.contact.force } else { lo.contact.force },
                    force_after: f64::NAN,
                    radius_before: lo.contact.radius,
                    pull_before: lo.contact.adhesive,
                    delta_after: f64::NAN,
                });
                if opt.stop_at_buckling && opt.snap == Snap::Instability {
                    // The question is answered.
                    break;
                }
                // The jump starts from the last state where the first past the fold has none.
                if hi.converged {
                    hi
                } else {
                    lo
                }
            } else {
                // Unstable, and no inverted state was found at the last attempt: try again.
                s.clone()
            };
            // Snap to the inverted branch (where the energy leads, `invert`; else carry on
            // along the unstable flattened branch, held, and try at the next step).
            if let Some(mut inv) = invert(model, plate, e, &from) {
                inv.stable = stable(&inv);
                if retry {
                    // The held state the jump leaves, at the same delta (the curve's drop).
                    loading.push(CyclePoint { step: s.clone(), leg: Leg::Loading, inverted: false });
                }
                if let Some(b) = cycle.buckling.as_mut() {
                    b.force_after = inv.contact.force;
                    b.delta_after = inv.delta;
                }
                inverted = true;
                s = inv;
                if opt.stop_at_buckling {
                    // Landed: the question is answered (`Snap::Landing`).
                    loading.push(CyclePoint { step: s, leg: Leg::Loading, inverted });
                    break;
                }
            } else if !s.converged {
                // Past the limit point with nowhere to land: the path ends there.
                loading.push(CyclePoint { step: s, leg: Leg::Loading, inverted });
                cycle.complete = false;
                break;
            } else if !retry && from.delta < s.delta {
                // The first unstable state, held (the bisection's end).
                loading.push(CyclePoint { step: from, leg: Leg::Loading, inverted: false });
            }
        }
        if inverted && !is_inverted(model, &s) {
            inverted = false;
        }
        loading.push(CyclePoint { step: s.clone(), leg: Leg::Loading, inverted });
        cur = s;
        if failed_at.is_some_and(|f| cur.delta >= f) {
            failed_at = None;
            fold_ahead = false;
        }
        // The prediction again with the new state: a fold predicted too early (the margins
        // of states far from it fall, but not as the square root) is withdrawn, and the
        // failure is tried again as any frictional failure.
        if let (true, Some(f)) = (fold_ahead, failed_at) {
            fold_ahead = fold_predicted(&mut margins, &loading, f + (f - cur.delta));
        }
        // Between a success and the failure still ahead, a frictionless loading bisects: the
        // next step is half this one, not the failure again. Its equilibria do not depend on
        // the path, and the last step, of the smallest size, tries the failure from the
        // nearest state anyway (on the stages of `pipelines/thesis.yaml` the fold's delta and
        // force are the retrying rule's to 1e-9; docs/shell.md, "Cost"). A frictional one
        // bisects too while the margins predict the fold before the failure.
        let bisecting =
            (plate.friction.is_none() || fold_ahead) && past_fold && failed_at.is_some_and(|f| f > cur.delta);
        if bisecting {
            if cuts < opt.max_cuts {
                cuts += 1;
                dd *= 0.5;
            }
        } else if cuts > 0 {
            cuts -= 1;
            dd = (2.0 * dd).min(base);
        }
    }
    cycle.work_loading = work(&loading);
    if !opt.unload || opt.stop_at_buckling {
        cycle.points = loading;
        return cycle;
    }
    // Unloading, warm-started from the loading states once back on the flattened branch.
    // The landing of the snap-back starts from the flattened loading state nearest in delta,
    // or, if Newton finds nothing from there (adhesion makes the basin narrow), from the next
    // nearest ones, and at last descends the energy from the nearest.
    let land_flattened = |delta: f64| -> Step {
        let mut near: Vec<&Step> =
            loading.iter().filter(|p| !p.inverted && p.step.converged).map(|p| &p.step).collect();
        near.sort_by(|a, b| (a.delta - delta).abs().total_cmp(&(b.delta - delta).abs()));
        let zero = vec![0.0; model.n_dofs()];
        let starts: Vec<&Vec<f64>> =
            near.iter().take(SNAP_BACK_STARTS).map(|s| &s.u).chain(near.is_empty().then_some(&zero)).collect();
        let landed = |s: &Step| s.converged && !is_inverted(model, s);
        starts
            .iter()
            .map(|start| land(model, plate, e, delta, start))
            .find(landed)
            .unwrap_or_else(|| land_with(model, plate, e, delta, starts[0], true))
    };
    let mut unloading = vec![CyclePoint { step: cur.clone(), leg: Leg::Unloading, inverted }];
    if cycle.complete && inverted {
        // The inverted branch by arc length down to its limit point (prescribed-delta Newton
        // stalls there, and on the ring contact's changes of status).
        let h = model.mesh.thickness;
        let arc = ArcOptions {
            ds: 0.02 * h,
            ds_min: 1e-5 * h,
            ds_max: 0.03 * h,
            max_points: 20 * opt.steps,
            newton: Options { max_iterations: 25, ..Options::default() },
            target_iterations: 5,
        };
        // Past the limit point the path is the unstable branch back towards the flattened
        // one; traced (if asked) up to the loading's snap-through.
        let until = if opt.trace_unstable { cycle.buckling.map_or(opt.delta_max, |b| b.delta) } else { 0.0 };
        let (path, ok) = continue_path(model, plate, e, &cur, -1.0, arc, |p| {
            (p.d_delta >= 0.0 && p.step.delta >= until) || (p.d_delta < 0.0 && !is_inverted(model, &p.step))
        });
        let mut last = cur.clone();
        let mut past_fold = false;
        for p in path {
            past_fold |= p.d_delta >= 0.0;
            if past_fold {
                let mut s = p.step;
                s.stable = stable(&s);
                cycle.unstable.push(s);
                continue;
            }
            if !is_inverted(model, &p.step) {
                break;
            }
            last = p.step.clone();
            let mut s = p.step;
            s.stable = stable(&s);
            unloading.push(CyclePoint { step: s, leg: Leg::Unloading, inverted: true });
        }
        if !ok && !past_fold {
            cycle.complete = false;
        }
        // Snap back at the limit point to the flattened branch.
        let mut back = land_flattened(last.delta);
        if back.converged && !is_inverted(model, &back) {
            back.stable = stable(&back);
            cycle.snap_back = Some(Jump {
                delta: last.delta,
                force_before: last.contact.force,
                delta_stable: last.delta,
                force_unstable: last.contact.force,
                force_after: back.contact.force,
                radius_before: last.contact.radius,
                pull_before: last.contact.adhesive,
                delta_after: last.delta,
            });
            unloading.push(CyclePoint { step: back.clone(), leg: Leg::Unloading, inverted: false });
            inverted = false;
            cur = back;
        } else {
            unloading.push(CyclePoint { step: back, leg: Leg::Unloading, inverted: true });
            cycle.complete = false;
        }
    }
    // The flattened branch back to delta = 0 through the loading's plate displacements,
    // each Newton started from the loading state there (the same state, the model being
    // elastic and frictionless: Newton confirms it in a few iterations) or, failing that,
    // from the previous unloading state.
    let targets: Vec<Step> = loading
        .iter()
        .rev()
        .filter(|p| !p.inverted && p.step.converged && p.step.delta < cur.delta)
        .map(|p| p.step.clone())
        .collect();
    for warm in targets {
        if !cycle.complete || inverted {
            break;
        }
        // Frictionless, the loading state is the answer (Newton confirms it), else Newton from
        // the last unloading state with an Euler predictor; with friction the state depends
        // on the path: Euler predictor from the last unloading state, its runs extended
        // where they stopped at the iteration limit.
        let more = Options { max_iterations: 60, ..Options::default() };
        let mut s = if plate.friction.is_none() {
            let s = solve_at(model, plate, e, warm.delta, &warm.u, &cur.contact.stick, Options::default());
            if s.converged {
                s
            } else {
                solve_from(model, plate, e, warm.delta, &cur, more)
            }
        } else {
            solve_from_extending(model, plate, e, warm.delta, &cur, Options::default(), more.max_iterations)
        };
        if !s.converged && plate.friction.is_some() {
            // With friction the unloading path is walked in halved steps, as the loading is
            // (measured: h/R = 0.06, gamma/(E h) = 2e-3, mu = 1 failed in one step at
            // delta/R = 0.11 for h = 0.06 x 15, not for h = 0.9).
            if let Some(t) = walk(model, plate, e, &cur, warm.delta, opt.max_cuts) {
                s = t;
            }
        }
        if !s.converged {
            unloading.push(CyclePoint { step: s, leg: Leg::Unloading, inverted });
            cycle.complete = false;
            break;
        }
        s.stable = stable(&s);
        unloading.push(CyclePoint { step: s.clone(), leg: Leg::Unloading, inverted });
        cur = s;
    }
    cycle.work_unloading = work(&unloading);
    cycle.points = loading;
    cycle.points.extend(unloading);
    cycle
}

#[cfg(test)]
mod tests;
