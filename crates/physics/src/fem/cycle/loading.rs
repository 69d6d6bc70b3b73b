//! The loading leg of the cycle: equal steps in delta from the adhering start, halved where
//! they fail; the fold of the flattened branch located by bisection (`locate_fold`); the
//! jump to the inverted branch (`snap`); and the inverted branch followed to delta_max.
//!
//! Under the tangent criterion the fold is the limit point of the flattened branch: a step
//! that finds no state at the smallest size, or lands off the branch, has passed it. The
//! step control then brackets it (`StepPlan`, `note_failure`) and, where the stability
//! margins predict it (`fold_predicted`), bisects towards it (docs/shell.md, "Cost").

use super::{CycleOptions, CyclePoint, Jump, Leg, Snap, MARGIN_ITERATIONS};
use crate::fem::indent::{Options, Step};
use crate::fem::problem::ShellProblem;
use crate::fem::stability::Criterion;

/// Whether the leg goes on after a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Flow {
    Continue,
    Stop,
}

/// The next step of the leg: where it goes and what a failure there would mean.
#[derive(Clone, Copy, Debug)]
struct StepPlan {
    target: f64,
    /// The step is shorter than the current step size (cut short by delta_max or by a
    /// failure ahead).
    capped: bool,
    /// The step is of the smallest size: a failure is an answer, not a reason to halve.
    at_smallest: bool,
    /// The fold of the flattened branch is still ahead and sought (tangent criterion).
    past_fold: bool,
}

/// The state of the loading leg.
pub(super) struct Loading<'p, 'a> {
    problem: &'p ShellProblem<'a>,
    opt: CycleOptions,
    /// The full step, delta_max / steps, and the smallest, after `max_cuts` halvings.
    base: f64,
    smallest: f64,
    /// The snap is the flattened branch's limit point (`Criterion::Tangent`): a step that
    /// finds no state at the smallest size, or a state already inverted, has passed it.
    limit_point: bool,
    pub points: Vec<CyclePoint>,
    pub cur: Step,
    pub inverted: bool,
    /// The current step size, base / 2^cuts.
    dd: f64,
    cuts: u32,
    /// While the fold is sought: the smallest delta whose step failed or left the branch
    /// since the last state reached it. With friction a step grown again after a success
    /// goes no further than there: the failure is tried again from the nearer state, but
    /// not overshot, which near a fold fails as surely; without friction the bracket is
    /// bisected (docs/shell.md, "Cost").
    failed_at: Option<f64>,
    /// With friction: the failure ahead lies past the fold that the stability margins of
    /// the last two states predict (`fold_predicted`), and is bisected as without friction.
    fold_ahead: bool,
    /// Stability margins computed so far, by delta.
    margins: Vec<(f64, Option<f64>)>,
    pub buckling: Option<Jump>,
    pub complete: bool,
}

impl<'p, 'a> Loading<'p, 'a> {
    pub(super) fn new(problem: &'p ShellProblem<'a>, opt: CycleOptions, start: Step) -> Loading<'p, 'a> {
        let base = opt.delta_max / opt.steps as f64;
        Loading {
            problem,
            opt,
            base,
            smallest: base / 2f64.powi(opt.max_cuts as i32),
            limit_point: opt.criterion == Criterion::Tangent,
            points: vec![CyclePoint { step: start.clone(), leg: Leg::Loading, inverted: false }],
            cur: start,
            inverted: false,
            dd: base,
            cuts: 0,
            failed_at: None,
            fold_ahead: false,
            margins: Vec::new(),
            buckling: None,
            complete: true,
        }
    }

    /// The leg resumed after a snap found by other means (the energy criterion): the states
    /// `points` up to the snap, then the inverted state `inv` it jumps to at the same delta.
    pub(super) fn resumed(
        problem: &'p ShellProblem<'a>,
        opt: CycleOptions,
        mut points: Vec<CyclePoint>,
        inv: Step,
        jump: Jump,
    ) -> Loading<'p, 'a> {
        let mut leg = Loading::new(problem, opt, inv.clone());
        points.push(CyclePoint { step: inv, leg: Leg::Loading, inverted: true });
        leg.points = points;
        leg.inverted = true;
        leg.buckling = Some(jump);
        leg
    }

    /// Steps to delta_max, or to the end the options ask for.
    pub(super) fn run(&mut self) {
        while self.cur.delta < self.opt.delta_max * (1.0 - 1e-12) {
            if self.step() == Flow::Stop {
                break;
            }
        }
    }

    fn stable(&self, s: &Step) -> bool {
        self.problem.is_stable(s, self.opt.criterion, self.opt.hold)
    }

    /// The state leaves the flattened branch: unstable, or (limit point) already inverted.
    fn leaves(&self, s: &Step) -> bool {
        !s.stable || (self.limit_point && self.problem.is_inverted(s))
    }

    fn plan(&self) -> StepPlan {
        let past_fold = self.limit_point && !self.inverted && self.buckling.is_none();
        let cur = self.cur.delta;
        let grown = (cur + self.dd).min(self.opt.delta_max);
        let target = match self.failed_at {
            Some(f) if past_fold && f > cur => grown.min(f),
            _ => grown,
        };
        // A step shortened to delta_max counts as capped too: halving it would try the
        // same failed displacement again from the same state.
        let capped = target < cur + self.dd;
        // A capped step no longer than the smallest counts as one.
        let at_smallest = self.cuts >= self.opt.max_cuts || (capped && target - cur <= self.smallest * (1.0 + 1e-9));
        StepPlan { target, capped, at_smallest, past_fold }
    }

    /// The next, shorter step: half of this one; for a capped step, the largest
    /// base / 2^cuts at most half of it (dd stays base / 2^cuts).
    fn shorten(&mut self, plan: &StepPlan) {
        if plan.capped {
            // (Rounding aside: a step of exactly base / 2^k is halved, not quartered.)
            let halvings = ((2.0 * self.base / (plan.target - self.cur.delta)).log2() - 1e-9).ceil().max(1.0);
            self.cuts = (halvings as u32).min(self.opt.max_cuts);
            self.dd = self.base / 2f64.powi(self.cuts as i32);
        } else {
            self.cuts += 1;
            self.dd *= 0.5;
        }
    }

    /// A step to `target` failed or left the branch while the fold is sought.
    fn note_failure(&mut self, target: f64) {
        self.failed_at = Some(self.failed_at.map_or(target, |f| f.min(target)));
        self.fold_ahead = self.fold_ahead || self.fold_predicted(target);
    }

    /// Whether the fold of the flattened branch lies before `target`, as the stability
    /// margins (smallest eigenvalues of the stability test's tangent) of the last two
    /// states predict: near a limit point the margin's square falls linearly to zero.
    fn fold_predicted(&mut self, target: f64) -> bool {
        let [.., p, c] = self.points.as_slice() else { return false };
        // (The reference state carries no contact state: no margin there.)
        let on_branch =
            |q: &CyclePoint| q.step.converged() && q.step.stable && !q.inverted && !q.step.contact.active.is_empty();
        if self.problem.plate.friction.is_none() || !on_branch(p) || !on_branch(c) || c.step.delta <= p.step.delta {
            return false;
        }
        let (dp, dc) = (p.step.delta, c.step.delta);
        let n = self.points.len();
        let (Some(lp), Some(lc)) = (self.margin(n - 2), self.margin(n - 1)) else { return false };
        if lc >= lp {
            return false;
        }
        let fold = dc + lc * lc * (dc - dp) / (lp * lp - lc * lc);
        fold < target
    }

    /// The stability margin of the leg's state `index`, computed once per state.
    fn margin(&mut self, index: usize) -> Option<f64> {
        let s = &self.points[index].step;
        if let Some(&(_, m)) = self.margins.iter().find(|(d, _)| *d == s.delta) {
            return m;
        }
        let m = self.problem.stability_margin(s, self.opt.criterion, self.opt.hold, MARGIN_ITERATIONS);
        self.margins.push((s.delta, m));
        m
    }

    fn push(&mut self, step: Step, inverted: bool) {
        self.points.push(CyclePoint { step, leg: Leg::Loading, inverted });
    }

    /// One step of the leg: solved, shortened and tried again, or accepted (after the snap
    /// if the state leaves the flattened branch).
    fn step(&mut self) -> Flow {
        let plan = self.plan();
        let problem = self.problem;
        let mut s = problem.solve_from(plan.target, &self.cur, Options::default());
        if !s.converged() && plan.at_smallest {
            self.cuts = self.cuts.max(self.opt.max_cuts);
            s = problem.confirm_failure(plan.target, &self.cur, s);
        }
        if !s.converged() {
            if !plan.at_smallest {
                self.shorten(&plan);
                if plan.past_fold {
                    self.note_failure(plan.target);
                }
                return Flow::Continue;
            }
            if !plan.past_fold {
                self.push(s, self.inverted);
                self.complete = false;
                return Flow::Stop;
            }
        }
        s.stable = s.converged() && self.stable(&s);
        let leaves_branch =
            self.limit_point && s.converged() && !self.inverted && self.buckling.is_none() && self.leaves(&s);
        if leaves_branch {
            if !plan.at_smallest {
                // Under the tangent criterion a step that lands off the flattened branch is
                // taken again shorter, as a failed one is: the loss of stability is where
                // the shortest step still leaves. A long step can land on another
                // equilibrium (another slip set, or the inverted branch) before the branch
                // ends (docs/shell.md, "Model").
                self.shorten(&plan);
                self.note_failure(plan.target);
                return Flow::Continue;
            }
            self.cuts = self.cuts.max(self.opt.max_cuts);
        }
        if !self.inverted && self.leaves(&s) {
            match self.snap(s) {
                Some(next) => s = next,
                None => return Flow::Stop,
            }
        }
        self.accept(s, plan.past_fold);
        Flow::Continue
    }

    /// The state `s` has left the flattened branch: the fold located (the first time) and
    /// the jump to the inverted branch tried. The state to accept, or None where the leg
    /// ends (the question answered, or no state to go on from).
    fn snap(&mut self, s: Step) -> Option<Step> {
        let retry = self.buckling.is_some();
        let from = if retry {
            // Unstable, and no inverted state was found at the last attempt: try again.
            s.clone()
        } else {
            let from = self.locate_fold(&s);
            if self.opt.stop_at_buckling && self.opt.snap == Snap::Instability {
                // The question is answered.
                return None;
            }
            from
        };
        // Snap to the inverted branch (where the energy leads, `jump_to_inverted`; else carry
        // on along the unstable flattened branch, held, and try at the next step).
        if let Some(mut inv) = self.problem.jump_to_inverted(&from) {
            inv.stable = self.stable(&inv);
            if retry {
                // The held state the jump leaves, at the same delta (the curve's drop).
                self.push(s, false);
            }
            if let Some(b) = self.buckling.as_mut() {
                b.force_after = inv.contact.force;
                b.delta_after = inv.delta;
            }
            self.inverted = true;
            if self.opt.stop_at_buckling {
                // Landed: the question is answered (`Snap::Landing`).
                self.push(inv, true);
                return None;
            }
            Some(inv)
        } else if !s.converged() {
            // Past the limit point with nowhere to land: the path ends there.
            self.push(s, self.inverted);
            self.complete = false;
            None
        } else {
            if !retry && from.delta < s.delta {
                // The first unstable state, held (the bisection's end).
                self.push(from, false);
            }
            Some(s)
        }
    }

    /// Bisects between the current state and `s` (which leaves the branch) for the last
    /// stable flattened state, F_buckling, located to base / 2^bisections (under the
    /// tangent criterion the step is already base / 2^cuts), and records the snap there.
    /// The state the jump starts from: the first past the fold, or the last before it
    /// where the first has none.
    fn locate_fold(&mut self, s: &Step) -> Step {
        let problem = self.problem;
        let (mut lo, mut hi) = (self.cur.clone(), s.clone());
        let halved = if self.limit_point { self.cuts } else { 0 };
        for _ in halved..self.opt.bisections {
            let at = 0.5 * (lo.delta + hi.delta);
            let mut mid = problem.solve_from(at, &lo, Options::default());
            if !mid.converged() && !self.limit_point {
                break;
            }
            mid.stable = mid.converged() && self.stable(&mid);
            if self.leaves(&mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        if lo.delta > self.cur.delta {
            self.push(lo.clone(), false);
        }
        self.buckling = Some(Jump {
            delta: hi.delta,
            force_before: lo.contact.force,
            delta_stable: lo.delta,
            // Past a limit point there may be no state: the force there is the last one's
            // (the bracket is then the bisection's delta alone).
            force_unstable: if hi.converged() { hi.contact.force } else { lo.contact.force },
            force_after: f64::NAN,
            radius_before: lo.contact.radius,
            pull_before: lo.contact.adhesive,
            delta_after: f64::NAN,
        });
        if hi.converged() {
            hi
        } else {
            lo
        }
    }

    /// Takes `s` as the leg's next state and sets the next step's size.
    fn accept(&mut self, s: Step, past_fold: bool) {
        if self.inverted && !self.problem.is_inverted(&s) {
            self.inverted = false;
        }
        self.push(s.clone(), self.inverted);
        self.cur = s;
        if self.failed_at.is_some_and(|f| self.cur.delta >= f) {
            self.failed_at = None;
            self.fold_ahead = false;
        }
        // The prediction again with the new state: a fold predicted too early (the margins
        // of states far from it fall, but not as the square root) is withdrawn, and the
        // failure is tried again as any frictional failure.
        if let (true, Some(f)) = (self.fold_ahead, self.failed_at) {
            self.fold_ahead = self.fold_predicted(f + (f - self.cur.delta));
        }
        // Between a success and the failure still ahead, a frictionless loading bisects: the
        // next step is half this one, not the failure again. Its equilibria do not depend on
        // the path, and the last step, of the smallest size, tries the failure from the
        // nearest state anyway (docs/shell.md, "Cost"). A frictional one bisects too while
        // the margins predict the fold before the failure.
        let failure_ahead = self.failed_at.is_some_and(|f| f > self.cur.delta);
        let bisecting = (self.problem.plate.friction.is_none() || self.fold_ahead) && past_fold && failure_ahead;
        if bisecting {
            if self.cuts < self.opt.max_cuts {
                self.cuts += 1;
                self.dd *= 0.5;
            }
        } else if self.cuts > 0 {
            self.cuts -= 1;
            self.dd = (2.0 * self.dd).min(self.base);
        }
    }
}
