//! The unloading leg of the cycle: the inverted branch by arc length down to its limit
//! point (`unload_inverted`), the snap back to the flattened branch there
//! (`land_flattened`), and the flattened branch back to delta = 0 through the loading's
//! plate displacements (`unload_flattened`).

use super::jump::SNAP_BACK_STARTS;
use super::{Cycle, CycleOptions, CyclePoint, Jump, Leg};
use crate::fem::arclength::ArcOptions;
use crate::fem::indent::{Options, Step};
use crate::fem::problem::ShellProblem;

/// Newton's iteration limit where an unloading step is tried again.
const UNLOADING_RETRY_ITERATIONS: usize = 60;

/// The state of the unloading leg.
pub(super) struct Unloading<'p, 'a> {
    problem: &'p ShellProblem<'a>,
    opt: CycleOptions,
    /// The loading leg's states (warm starts, and the displacements walked back through).
    loading: &'p [CyclePoint],
    pub points: Vec<CyclePoint>,
    cur: Step,
    inverted: bool,
}

impl<'p, 'a> Unloading<'p, 'a> {
    /// The leg from the loading's last state `cur`.
    pub(super) fn new(
        problem: &'p ShellProblem<'a>,
        opt: CycleOptions,
        loading: &'p [CyclePoint],
        cur: Step,
        inverted: bool,
    ) -> Unloading<'p, 'a> {
        let points = vec![CyclePoint { step: cur.clone(), leg: Leg::Unloading, inverted }];
        Unloading { problem, opt, loading, points, cur, inverted }
    }

    fn stable(&self, s: &Step) -> bool {
        self.problem.is_stable(s, self.opt.criterion, self.opt.hold)
    }

    fn push(&mut self, step: Step, inverted: bool) {
        self.points.push(CyclePoint { step, leg: Leg::Unloading, inverted });
    }

    /// Runs the leg, recording its snap-back, its unstable branch and whether it completed
    /// in `cycle`.
    pub(super) fn run(&mut self, cycle: &mut Cycle) {
        if cycle.complete && self.inverted {
            self.unload_inverted(cycle);
        }
        self.unload_flattened(cycle);
    }

    /// The landing of the snap-back at `delta`: Newton from the flattened loading state
    /// nearest in delta, or, if Newton finds nothing from there (adhesion makes the basin
    /// narrow), from the next nearest ones, and at last an energy descent from the nearest.
    fn land_flattened(&self, delta: f64) -> Step {
        let problem = self.problem;
        let mut near: Vec<&Step> =
            self.loading.iter().filter(|p| !p.inverted && p.step.converged()).map(|p| &p.step).collect();
        near.sort_by(|a, b| (a.delta - delta).abs().total_cmp(&(b.delta - delta).abs()));
        let zero = vec![0.0; problem.model.n_dofs()];
        let starts: Vec<&Vec<f64>> =
            near.iter().take(SNAP_BACK_STARTS).map(|s| &s.u).chain(near.is_empty().then_some(&zero)).collect();
        let landed = |s: &Step| s.converged() && !problem.is_inverted(s);
        starts
            .iter()
            .map(|start| problem.landing(delta, start))
            .find(landed)
            .unwrap_or_else(|| problem.landing_or_rest(delta, starts[0], true))
    }

    /// The inverted branch by arc length down to its limit point (prescribed-delta Newton
    /// stalls there, and on the ring contact's changes of status), past it (if asked) the
    /// unstable branch up to the loading's snap-through, and the snap back to the
    /// flattened branch at the limit point.
    fn unload_inverted(&mut self, cycle: &mut Cycle) {
        let problem = self.problem;
        let h = problem.model.mesh.thickness;
        let arc = ArcOptions {
            ds: 0.02 * h,
            ds_min: 1e-5 * h,
            ds_max: 0.03 * h,
            max_points: 20 * self.opt.steps,
            newton: Options { max_iterations: 25, ..Options::default() },
            target_iterations: 5,
        };
        let until = if self.opt.trace_unstable { cycle.buckling.map_or(self.opt.delta_max, |b| b.delta) } else { 0.0 };
        let (path, ok) = problem.continue_path(&self.cur, -1.0, arc, |p| {
            (p.d_delta >= 0.0 && p.step.delta >= until) || (p.d_delta < 0.0 && !problem.is_inverted(&p.step))
        });
        let mut last = self.cur.clone();
        let mut past_fold = false;
        for p in path {
            past_fold |= p.d_delta >= 0.0;
            if past_fold {
                let mut s = p.step;
                s.stable = self.stable(&s);
                cycle.unstable.push(s);
                continue;
            }
            if !problem.is_inverted(&p.step) {
                break;
            }
            last = p.step.clone();
            let mut s = p.step;
            s.stable = self.stable(&s);
            self.push(s, true);
        }
        if !ok && !past_fold {
            cycle.complete = false;
        }
        // Snap back at the limit point to the flattened branch.
        let mut back = self.land_flattened(last.delta);
        if back.converged() && !problem.is_inverted(&back) {
            back.stable = self.stable(&back);
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
            self.push(back.clone(), false);
            self.inverted = false;
            self.cur = back;
        } else {
            self.push(back, true);
            cycle.complete = false;
        }
    }

    /// The flattened branch back to delta = 0 through the loading's plate displacements.
    /// Frictionless, the loading state there is the answer (Newton confirms it in a few
    /// iterations: the model is elastic), else Newton from the last unloading state with an
    /// Euler predictor; with friction the state depends on the path: Euler predictor from
    /// the last unloading state, its runs extended where they stopped at the iteration
    /// limit, and where that fails the path is walked in halved steps, as the loading is
    /// (h/R = 0.06, gamma/(E h) = 2e-3, mu = 1 failed in one step at delta/R = 0.11 for
    /// h = 0.06 x 15, not for h = 0.9).
    fn unload_flattened(&mut self, cycle: &mut Cycle) {
        let problem = self.problem;
        let frictionless = problem.plate.friction.is_none();
        let targets: Vec<&Step> = self
            .loading
            .iter()
            .rev()
            .filter(|p| !p.inverted && p.step.converged() && p.step.delta < self.cur.delta)
            .map(|p| &p.step)
            .collect();
        let more = Options { max_iterations: UNLOADING_RETRY_ITERATIONS, ..Options::default() };
        for warm in targets {
            if !cycle.complete || self.inverted {
                break;
            }
            let cur = &self.cur;
            let mut s = if frictionless {
                let s = problem.solve_at(warm.delta, &warm.u, &cur.contact.stick, Options::default());
                if s.converged() {
                    s
                } else {
                    problem.solve_from(warm.delta, cur, more)
                }
            } else {
                problem.solve_from_extending(warm.delta, cur, Options::default(), more.max_iterations)
            };
            if !s.converged() && !frictionless {
                if let Some(t) = problem.walk_to(cur, warm.delta, self.opt.max_cuts) {
                    s = t;
                }
            }
            if !s.converged() {
                self.push(s, self.inverted);
                cycle.complete = false;
                break;
            }
            s.stable = self.stable(&s);
            self.push(s.clone(), self.inverted);
            self.cur = s;
        }
    }
}
