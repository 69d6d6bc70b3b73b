//! Following the equilibrium branch of the adhesive cylinder of Chapter 4 towards
//! detachment: the pull-off load and states under negative (tensile) loads (thesis
//! Sections 4.3 and 5.3; the model and units of `solver`, Eqs. 4.4-4.18).
//!
//! Under load control the branch ends in a fold: the pull-off load is the minimum of W over
//! the branch, where the load-control Jacobian is singular, and Newton started at a
//! negative load can land on the unstable branch (small contact) or on another equilibrium
//! of the finite domain. The branch is therefore walked by pseudo-arclength continuation in
//! the plane of (approach a, load W) (`Control::Path`: t_a a + t_W W = value, with (t_a, t_W)
//! the unit secant of the last two states), regular through the load minimum and through
//! folds in the approach (at k = 0.001, lambda = 3, V = 2 the approach turns before the load
//! does: fixed-grip instability precedes the pull-off, and pure approach control stalls
//! there). The first step lowers the approach; a step is accepted only if the adhered width
//! changes by less than 20% (the guard against jumping branches).
//! - `pull_off`: walk until W has risen well above its lowest local minimum (`RISE`), then
//!   golden-section search along the path around that minimum
//!   (arclength from the middle state, its central secant as the direction).
//! - `descend_to_load`: walk until W passes a target above the pull-off, then Newton under
//!   load control from the interpolation of the two bracketing states: a stable state.
//!
//! The speed V = v tau/beta is held fixed along the walk.

use super::newton::PathSolver;
use super::params::TOLERANCE;
use super::solution::{Cost, Solution, Termination};
use super::system::Control;
use crate::lennard_jones;
use crate::numerics::roots::golden_section_max;

/// Largest relative change of the adhered half-width between accepted neighbours.
const BRANCH_JUMP: f64 = 0.2;
/// Steps of a walk before giving up.
const MAX_STEPS: usize = 400;

fn on_branch(from: &Solution, to: &Solution) -> bool {
    match (from.adhered_half_width(), to.adhered_half_width()) {
        (Some(a), Some(b)) => (b - a).abs() <= BRANCH_JUMP * a,
        _ => false,
    }
}

/// A walk down the branch by pseudo-arclength in (approach, load).
struct Walk {
    solver: PathSolver,
    /// The last three accepted states, newest last.
    states: Vec<Solution>,
    step0: f64,
    step: f64,
    /// The cost of the walk's solves (of `start` not included).
    cost: Cost,
    path: Vec<[f64; 2]>,
}

/// A point of the (approach, load) plane.
fn point(s: &Solution) -> [f64; 2] {
    [s.approach(), s.load()]
}

/// The unit vector from p to q, and the distance.
fn direction(p: [f64; 2], q: [f64; 2]) -> ([f64; 2], f64) {
    let d = [q[0] - p[0], q[1] - p[1]];
    let len = d[0].hypot(d[1]);
    ([d[0] / len, d[1] / len], len)
}

/// The control fixing the arclength `s` from `at` along the unit direction `t`.
fn arc(t: [f64; 2], at: [f64; 2], s: f64) -> Control {
    Control::Path { t_approach: t[0], t_load: t[1], value: t[0] * at[0] + t[1] * at[1] + s }
}

impl Walk {
    fn new(start: &Solution) -> Walk {
        assert!(start.converged(), "a walk starts from an equilibrium");
        let width = start.adhered_half_width().unwrap_or(1.0);
        let step0 = 0.02 * width * width;
        Walk {
            solver: PathSolver::new(start),
            states: vec![start.clone()],
            step0,
            step: step0,
            cost: Cost::default(),
            path: vec![point(start)],
        }
    }

    fn current(&self) -> &Solution {
        self.states.last().unwrap()
    }

    fn solve(&mut self, control: Control, guess: &[f64], delta0: f64) -> Solution {
        let s = self.solver.solve(control, guess, delta0);
        self.cost += s.cost;
        s
    }

    /// One accepted step along the branch (false when the steps shrink below 1e-6 of the
    /// first without one being accepted: the branch ends).
    fn advance(&mut self) -> bool {
        let lambda = self.current().params.lambda;
        while self.step >= 1e-6 * self.step0 {
            let cur = self.current().clone();
            // Direction: the secant of the last two states, or down in the approach.
            let (t, predicted, delta0) = match self.states.len() {
                1 => ([-1.0, 0.0], None, cur.delta - self.step),
                m => {
                    let prev = &self.states[m - 2];
                    let (t, len) = direction(point(prev), point(&cur));
                    let r = self.step / len;
                    let h: Vec<f64> = cur.h.iter().zip(&prev.h).map(|(h1, h0)| h1 + r * (h1 - h0)).collect();
                    let safe = h
                        .iter()
                        .zip(&cur.h)
                        .all(|(&hp, &h1)| lennard_jones::z_of(hp, lambda) > 0.3 * lennard_jones::z_of(h1, lambda));
                    (t, safe.then_some(h), cur.delta + r * (cur.delta - prev.delta))
                }
            };
            let control = arc(t, point(&cur), self.step);
            let mut trial = self.solve(control, predicted.as_deref().unwrap_or(&cur.h), delta0);
            if !(trial.converged() && on_branch(&cur, &trial)) && predicted.is_some() {
                trial = self.solve(control, &cur.h, cur.delta);
            }
            if trial.converged() && on_branch(&cur, &trial) {
                self.path.push(point(&trial));
                self.states.push(trial);
                if self.states.len() > 3 {
                    self.states.remove(0);
                }
                self.step = (self.step * 1.5).min(8.0 * self.step0);
                return true;
            }
            self.step *= 0.5;
        }
        false
    }
}

/// The result of a pull-off search.
#[derive(Clone, Debug)]
pub struct PullOff {
    /// The pull-off load: the smallest W on the branch (negative with adhesion).
    pub load: f64,
    /// The equilibrium at that load.
    pub solution: Solution,
    /// True if the minimum was bracketed and refined; false if the branch ended first (a
    /// fold in the approach, or no step could stay on the branch: `load` is then the
    /// smallest load reached) or if no state inside the bracket converged (`load` is then
    /// the bracket's centre).
    pub converged: bool,
    /// What the walk and the search cost (the start's not included).
    pub cost: Cost,
    /// The accepted states of the walk: [approach, W], the approach of `Solution::approach`.
    pub path: Vec<[f64; 2]>,
}

/// How far the load must rise above the lowest local minimum of a walk before `pull_off`
/// stops walking, as a fraction of that load (negative): a rise ends the search only if it
/// continues. Under load control the state at a shallower first minimum jumps to the
/// branch's next descending part at the same load, so the pull-off is the deeper minimum.
/// A small rise on the way to the deeper minimum is real (fig5_8's sweep at lambda = 3;
/// docs/bem.md, Chapter 5, the pull-off, has the numbers). Stopping at 2 % costs little
/// more than at the first rise, at 10 % a third more (docs/tuning.md).
const RISE: f64 = 0.02;

/// Walks down the branch from the converged state `start` (any load above the pull-off) and
/// returns its minimum load, refined until the bracket along the path is below `tol` times
/// the first step. The walk goes on past a rise until the load is `RISE` |W| above the
/// lowest local minimum (negative) met so far, which is the one refined.
pub fn pull_off(start: &Solution, tol: f64) -> PullOff {
    let mut walk = Walk::new(start);
    // The lowest local minimum so far, with its neighbours on the path.
    let mut bracket: Option<(Solution, Solution, Solution)> = None;
    for _ in 0..MAX_STEPS {
        if !walk.advance() {
            break;
        }
        let n = walk.states.len();
        if n < 3 {
            continue;
        }
        let (before, centre, after) = (&walk.states[n - 3], &walk.states[n - 2], &walk.states[n - 1]);
        if after.load() > centre.load()
            && centre.load() <= before.load()
            && bracket.as_ref().is_none_or(|(_, low, _)| centre.load() < low.load())
        {
            bracket = Some((before.clone(), centre.clone(), after.clone()));
        }
        if let Some((_, low, _)) = &bracket {
            if low.load() < 0.0 && after.load() - low.load() > RISE * low.load().abs() {
                break;
            }
        }
    }
    // A walk that ended below its lowest local minimum has not bracketed the pull-off.
    let bracket = bracket.filter(|(_, low, _)| walk.current().load() >= low.load());
    let Some((before, centre, after)) = bracket else {
        let last = walk.current().clone();
        return PullOff { load: last.load(), solution: last, converged: false, cost: walk.cost, path: walk.path };
    };
    // Golden-section search for the minimum load along the path: arclength s from the
    // centre along its central secant, between the two neighbours.
    let (t, _) = direction(point(&before), point(&after));
    let c = point(&centre);
    let along = |q: [f64; 2]| t[0] * (q[0] - c[0]) + t[1] * (q[1] - c[1]);
    let (lo, hi) = (along(point(&before)), along(point(&after)));
    let mut best = centre.clone();
    let mut refined = false;
    let step0 = walk.step0;
    // Maximise -W; unconverged or off-branch solves count as -inf.
    golden_section_max(
        |s| {
            // Newton from the path's linear interpolation between the centre and the
            // neighbour on that side (as the walk's predictor): from the centre's state
            // itself the crack front must move element by element, which took more than
            // Newton's 40 iterations on 9264 elements (lambda = 3) and left the bracket's
            // centre as the answer. The centre's state is the fallback.
            let (other, fraction) = if s < 0.0 { (&before, s / lo) } else { (&after, s / hi) };
            let fraction = if fraction.is_finite() { fraction.clamp(0.0, 1.0) } else { 0.0 };
            let h: Vec<f64> = centre.h.iter().zip(&other.h).map(|(a, b)| a + fraction * (b - a)).collect();
            let delta = centre.delta + fraction * (other.delta - centre.delta);
            let mut r = walk.solve(arc(t, c, s), &h, delta);
            if !(r.converged() && on_branch(&centre, &r)) {
                r = walk.solve(arc(t, c, s), &centre.h, centre.delta);
            }
            if !(r.converged() && on_branch(&centre, &r)) {
                return f64::NEG_INFINITY;
            }
            refined = true;
            let w = r.load();
            if w < best.load() {
                best = r;
            }
            -w
        },
        lo,
        hi,
        tol * step0,
    );
    PullOff { load: best.load(), solution: best, converged: refined, cost: walk.cost, path: walk.path }
}

/// Regula falsi iterations of `along_the_path`.
const PATH_ROOT_ITERATIONS: usize = 60;

/// The state at load `w` between the neighbours `above` and `below` of a walk (their loads
/// bracket `w`), found along the path between them: the arclength from `above` along their
/// secant is the unknown, each trial solved under path control (regular, also where the
/// lattice of the crack front makes load control stall), until the load is `w` to
/// `TOLERANCE`; then polished by Newton under load control from there. Load control from
/// the interpolated guess fails near some pull-offs (the case of
/// `tests/solver_properties.rs`, lambda = 2.19, k = 0.5). None if the bracket cannot be
/// narrowed (a trial off the branch or not converged).
fn along_the_path(walk: &mut Walk, above: &Solution, below: &Solution, w: f64) -> Option<Solution> {
    let (t, len) = direction(point(above), point(below));
    let origin = point(above);
    // Illinois regula falsi on g(s) = W(s) - w, g(0) > 0 >= g(len).
    let (mut a, mut ga, mut sa) = (0.0, above.load() - w, above.clone());
    let (mut b, mut gb, mut sb) = (len, below.load() - w, below.clone());
    let mut side = 0;
    for _ in 0..PATH_ROOT_ITERATIONS {
        let s = (a * gb - b * ga) / (gb - ga);
        let near = if s - a < b - s { &sa } else { &sb };
        let r = walk.solve(arc(t, origin, s), &near.h, near.delta);
        if !(r.converged() && on_branch(above, &r)) {
            return None;
        }
        let g = r.load() - w;
        if g.abs() <= TOLERANCE {
            // Its cost is its own: the path's trials are the walk's.
            let polished = walk.solver.solve_load(w, &r);
            if polished.converged() && on_branch(above, &polished) {
                return Some(polished);
            }
            // Load control stalls even here: the path state, whose load is w to TOLERANCE
            // (its cost the failed polish's: the path state's is the walk's).
            let residual = r.residual.max(g.abs());
            return Some(Solution { params: r.params.with_load(w), residual, cost: polished.cost, ..r });
        }
        if g > 0.0 {
            (a, ga, sa) = (s, g, r);
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        } else {
            (b, gb, sb) = (s, g, r);
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        }
    }
    None
}

/// The stable equilibrium at load `w`, below the load of `start` and above the pull-off:
/// walks down the branch until the load passes `w`, then solves under load control from the
/// linear interpolation of the two bracketing states. If the branch reaches its minimum (or
/// ends) first, `w` is beyond the pull-off: the result is the last state reached, marked
/// not converged, its residual the missing load.
pub fn descend_to_load(start: &Solution, w: f64) -> Solution {
    let mut walk = Walk::new(start);
    if start.load() <= w {
        return start.clone();
    }
    for _ in 0..MAX_STEPS {
        if !walk.advance() {
            break;
        }
        let n = walk.states.len();
        let (above, below) = (walk.states[n - 2].clone(), walk.states[n - 1].clone());
        if below.load() > above.load() {
            break;
        }
        if below.load() <= w {
            let t = (above.load() - w) / (above.load() - below.load());
            let mut guess = above.clone();
            guess.h = above.h.iter().zip(&below.h).map(|(a, b)| a + t * (b - a)).collect();
            guess.delta = above.delta + t * (below.delta - above.delta);
            let mut s = walk.solver.solve_load(w, &guess);
            if !(s.converged() && on_branch(&above, &s)) {
                let failed = s.cost;
                s = match along_the_path(&mut walk, &above, &below, w) {
                    Some(mut found) => {
                        found.cost += failed;
                        found
                    }
                    None => {
                        s.stop(Termination::OffBranch);
                        s
                    }
                };
            }
            s.cost += walk.cost;
            return s;
        }
    }
    let mut last = walk.current().clone();
    last.cost = walk.cost;
    last.stop(Termination::BeyondPullOff);
    last.residual = (last.load() - w).abs();
    last
}
