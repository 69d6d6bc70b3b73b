//! Reaching a point from where Newton converges: continuation in lambda from a small value
//! (`solve`), geometric continuation in the load, and path following along a sequence of
//! states (`solve_along`, `PathSolver`).

use super::super::kernel::MeshKernel;
use super::newton::{initial_state, newton, newton_limited, Limits};
use super::params::{mesh_levels, Mesh, Params};
use super::precondition::Preconditioner;
use super::solution::{Cost, Solution};
use super::system::{Control, Operator};
use crate::lennard_jones;
use std::f64::consts::PI;

/// Geometric continuation of a parameter from `from` to `to` (either direction): each
/// step multiplies it by at most `factor`, starting Newton from a secant predictor (linear
/// extrapolation in the logarithm of the parameter through the last two converged states)
/// or, if that fails or would bring a surface through the other, from the last state; a
/// failed step is retried with the square root of the factor, down to a factor of 1.001,
/// and the factor grows again (squared, up to `max_factor`) after two successes in a row.
/// Returns the solution at `to` (converged or the failed last trial) and the cost of the
/// steps taken (that of `start` not included).
pub(super) fn continue_geometric(
    from: f64,
    to: f64,
    mut factor: f64,
    max_factor: f64,
    start: Solution,
    mut step: impl FnMut(f64, &[f64], f64) -> Solution,
) -> (Solution, Cost) {
    let max_factor = max_factor.max(factor);
    let mut spent = Cost::default();
    let mut value = from;
    let mut last = start;
    let mut previous: Option<(f64, Vec<f64>, f64)> = None;
    let up = to > from;
    let lambda = last.params.lambda;
    // A factor that just failed is not grown again until two steps in a row succeed: at
    // large lambda, where the steps alternate with lattice trapping, growing at once made
    // every other step fail (15 Newton iterations each; docs/tuning.md).
    let mut successes = 2;
    while value != to {
        let next = if up { (value * factor).min(to) } else { (value / factor).max(to) };
        let predicted = previous.as_ref().and_then(|(v_prev, h_prev, d_prev)| {
            let r = (next / value).ln() / (value / v_prev).ln();
            let h: Vec<f64> = last.h.iter().zip(h_prev).map(|(h1, h0)| h1 + r * (h1 - h0)).collect();
            let safe = h
                .iter()
                .zip(&last.h)
                .all(|(&hp, &h1)| lennard_jones::z_of(hp, lambda) > 0.3 * lennard_jones::z_of(h1, lambda));
            safe.then(|| (h, last.delta + r * (last.delta - d_prev)))
        });
        let mut trial = match &predicted {
            Some((h, d)) => step(next, h, *d),
            None => step(next, &last.h, last.delta),
        };
        spent += trial.cost;
        if !trial.converged() && predicted.is_some() {
            trial = step(next, &last.h, last.delta);
            spent += trial.cost;
        }
        if trial.converged() {
            previous = Some((value, std::mem::take(&mut last.h), last.delta));
            value = next;
            last = trial;
            successes += 1;
            if successes >= 2 {
                factor = (factor * factor).min(max_factor);
            }
        } else {
            successes = 0;
            factor = factor.sqrt();
            if factor < 1.001 {
                return (trial, spent);
            }
        }
    }
    (last, spent)
}

/// The largest factor of one step of the speed continuation at lambda up to `LAMBDA_START`
/// (4 above it). Far below and far above the
/// relaxation speeds the state hardly changes over a decade of V, and the secant predictor
/// in log V lands within Newton's basin; steps of 4 spent most of a point's iterations there.
pub(super) const SPEED_MAX_FACTOR: f64 = 64.0;

/// The smallest lambda at which Newton starts (soft, long-range adhesion converges from a
/// Hertzian guess); larger lambda are reached by continuation.
pub(super) const LAMBDA_START: f64 = 0.3;

/// Solves one point by continuation, under load control throughout. Newton starts at the
/// relaxed elastic problem (V = 0) with lambda0 = min(lambda, 0.3), from a Hertzian guess
/// (soft, long-range adhesion converges from it). The speed is then raised at lambda0 from
/// 1e-3 element widths to its value, and lambda last, at the final speed. The path is
/// walked with mesh sequencing (`mesh_levels`): on the coarsest mesh whose elements are
/// 1/40 of the contact, lambda is raised as far as that mesh resolves the cohesive zone
/// (`lambda_resolved`), then the solution is interpolated onto the next finer mesh and
/// lambda raised further, up to `mesh`: many times cheaper than the single mesh, and it
/// reaches lambda that the single mesh does not (docs/tuning.md). If that path fails, the
/// same path on `mesh` alone, then the other order (lambda at V = 0, then the speed) on it,
/// are tried. On coarse meshes at large lambda the discrete crack front has folds (lattice
/// trapping): raising lambda at V = 0 can end next to one, where any change of speed snaps.
///
/// A tensile load (W < 0) is reached from the same point at load max(|W|, 0.1) by walking
/// down the branch by pseudo-arclength (`branch::descend_to_load`), so that the state
/// is the stable one; beyond the pull-off the result is marked not converged.
pub fn solve(params: &Params, mesh: Mesh) -> Solution {
    if params.w < 0.0 {
        let start = solve(&params.with_load(params.w.abs().max(0.1)), mesh);
        let mut s = if start.converged() { super::branch::descend_to_load(&start, params.w) } else { start.clone() };
        s.params = params.clone();
        s.cost += start.cost;
        return s;
    }
    let mut pre = Preconditioner::default();
    let levels = mesh_levels(params, mesh);
    let mut s = solve_along(params, &levels, true, &mut pre);
    if !s.converged() && levels.len() > 1 {
        // The same path on the final mesh alone.
        let failed = s.cost;
        s = solve_along(params, &[mesh], true, &mut pre);
        s.cost += failed;
    }
    if !s.converged() {
        let failed = s.cost;
        s = solve_along(params, &[mesh], false, &mut pre);
        s.cost += failed;
    }
    s
}

/// The largest lambda a level's elements resolve for the continuation: cohesive zone
/// pi/(8 lambda^2) at least a quarter of an element: coarser, the refinement from that level
/// fails (docs/tuning.md, "BEM continuation").
pub(super) fn lambda_resolved(mesh: Mesh) -> f64 {
    (PI / (4.0 * mesh.a())).sqrt()
}

/// Newton on `mesh` from the linear interpolation of `coarse` (same parameters; `mesh` may
/// also be coarser than `coarse.mesh`).
pub(super) fn interpolated_newton(
    coarse: &Solution,
    mesh: Mesh,
    max_iter: usize,
    pre: &mut Preconditioner,
) -> Solution {
    started_newton(&coarse.params, &coarse.x, &coarse.h, coarse.delta, mesh, max_iter, pre)
}

/// Newton for `params` on `mesh` from the linear interpolation of the gap `h` at the nodes
/// `xs` (constant beyond them) and the approach `delta`.
///
/// Its arguments: the point, the start (nodes, gaps, approach), the mesh, the limit and
/// the preconditioner the path shares.
pub(super) fn started_newton(
    params: &Params,
    xs: &[f64],
    h: &[f64],
    delta: f64,
    mesh: Mesh,
    max_iter: usize,
    pre: &mut Preconditioner,
) -> Solution {
    let m = xs.len();
    let h: Vec<f64> = (0..mesh.n)
        .map(|i| {
            let x = mesh.x(i);
            let j = xs.partition_point(|&xc| xc < x).clamp(1, m - 1);
            let t = ((x - xs[j - 1]) / (xs[j] - xs[j - 1])).clamp(0.0, 1.0);
            h[j - 1] + t * (h[j] - h[j - 1])
        })
        .collect();
    let op = Operator::new(mesh, params.lambda, params.k, &params.spectrum, params.v(), params.pressure);
    newton(&op, params, Control::Load(params.w), h, delta, max_iter, pre)
}

/// Newton iterations allowed to one step of the lambda continuation before it counts as
/// failed and is retried with a smaller factor. Steps that converge take few; at large
/// lambda on the finest mesh most failures are lattice trapping, where more iterations do
/// not help (the limit of 40 took twice as long for the same mu*: docs/tuning.md).
pub(super) const LAMBDA_STEP_ITERATIONS: usize = 15;

/// A step of the lambda continuation also counts as failed (and is retried with a smaller
/// factor) after this many consecutive Newton iterations whose line search cut the step to
/// `STALL_STEP` or less. At large lambda a failing step does not diverge: it crawls, the
/// residual falling by about 1 % per iteration at steps of 1/64-1/128, to the iteration
/// limit (the crack front would have to jump an element, lattice trapping); converging
/// steps are damped at most once or twice in a row before their steps grow again
/// (docs/tuning.md: the same answers, a quarter fewer Newton iterations).
pub(super) const LAMBDA_STEP_STALL: usize = 2;

pub(super) fn solve_along(params: &Params, levels: &[Mesh], speed_first: bool, pre: &mut Preconditioner) -> Solution {
    let lam0 = params.lambda.min(LAMBDA_START);
    let at = |lambda: f64, v: f64| Params { lambda, ..params.clone() }.with_v(v);
    let coarsest = levels[0];
    let finest = levels[levels.len() - 1];
    let op0 = Operator::new(coarsest, lam0, params.k, &params.spectrum, 0.0, params.pressure);
    let (h0, d0) = initial_state(&op0, &at(lam0, 0.0));
    let first = newton(&op0, &at(lam0, 0.0), Control::Load(params.w), h0, d0, 100, pre);
    let mut spent = first.cost;
    let mut sol = first;
    let v_target = params.v();
    let stages: [bool; 2] = if speed_first { [true, false] } else { [false, true] };
    for speed in stages {
        if !sol.converged() {
            break;
        }
        if speed {
            // On the current mesh: the coarsest (speed first) or the finest (speed last).
            let mesh = sol.mesh;
            let lambda = sol.params.lambda;
            let v_start = 1e-3 * mesh.a();
            let (s, it) = if v_target <= v_start {
                let op = Operator::new(mesh, lambda, params.k, &params.spectrum, v_target, params.pressure);
                let s = newton(&op, &at(lambda, v_target), Control::Load(params.w), sol.h.clone(), sol.delta, 40, pre);
                let cost = s.cost;
                (s, cost)
            } else {
                // Long steps only at the soft start's lambda: at large lambda a change of speed
                // can snap the crack front across a lattice fold.
                let max_factor = if lambda <= LAMBDA_START { SPEED_MAX_FACTOR } else { 4.0 };
                continue_geometric(v_start, v_target, 4.0, max_factor, sol, |v, h, delta| {
                    let op = Operator::new(mesh, lambda, params.k, &params.spectrum, v, params.pressure);
                    newton(&op, &at(lambda, v), Control::Load(params.w), h.to_vec(), delta, 40, pre)
                })
            };
            sol = s;
            spent += it;
        } else {
            // Lambda, level by level: up to what each level resolves, then onto the next.
            let v = sol.params.v();
            for (i, &mesh) in levels.iter().enumerate() {
                if i > 0 {
                    sol = interpolated_newton(&sol, mesh, 40, pre);
                    spent += sol.cost;
                    if !sol.converged() {
                        break;
                    }
                }
                let cap = if mesh == finest { params.lambda } else { params.lambda.min(lambda_resolved(mesh)) };
                let from = sol.params.lambda;
                if cap > from {
                    // Finer levels carry the stiff, large-lambda part of the path: smaller steps.
                    let factor = if i == 0 { 1.5 } else { 1.1 };
                    let kern = MeshKernel::new(mesh.n, mesh.a(), v, params.k, &params.spectrum, params.pressure);
                    let (s, it) =
                        continue_geometric(from, cap, factor, (factor * factor).min(4.0), sol, |lambda, h, delta| {
                            let op = Operator::scaled(mesh, &kern, lambda);
                            newton_limited(
                                &op,
                                &at(lambda, v),
                                Control::Load(params.w),
                                h.to_vec(),
                                delta,
                                Limits { iterations: LAMBDA_STEP_ITERATIONS, stall: LAMBDA_STEP_STALL },
                                pre,
                            )
                        });
                    sol = s;
                    spent += it;
                    if !sol.converged() {
                        break;
                    }
                }
            }
        }
    }
    sol.params = params.clone();
    sol.cost = spent;
    sol
}
