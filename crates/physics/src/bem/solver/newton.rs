//! Newton-Krylov on one point: GMRES steps preconditioned by `precondition`, a
//! backtracking line search that keeps every z = 1 + alpha lambda H positive, and the
//! limits (iterations, stall, time budget) that end it; the starting state.

use super::params::Params;
use super::precondition::Preconditioner;
use super::solution::{Cost, Solution, Termination};
use super::system::{Control, Operator, System};
use crate::lennard_jones;
use crate::lennard_jones::ALPHA;
use crate::theory::line_contact::jkr_half_width;

/// Newton's method from `h0`, `delta0`. Returns the solution (converged or not).
/// Under path control the solution's load is the one carried, at the same speed V.
///
/// Its arguments: the operator and the point's parameters, the control, the start (h0,
/// delta0), the limit and the preconditioner the path shares across its solves.
pub(super) fn newton(
    op: &Operator,
    params: &Params,
    control: Control,
    h0: Vec<f64>,
    delta0: f64,
    max_iter: usize,
    pre: &mut Preconditioner,
) -> Solution {
    newton_limited(op, params, control, h0, delta0, Limits { iterations: max_iter, stall: usize::MAX }, pre)
}

/// Iteration limits of one Newton solve.
#[derive(Clone, Copy, Debug)]
pub(super) struct Limits {
    /// Newton iterations at most.
    pub(super) iterations: usize,
    /// Give up after this many consecutive iterations whose line search cut the step to
    /// `STALL_STEP` or less (`LAMBDA_STEP_STALL`; `usize::MAX`: never).
    pub(super) stall: usize,
}

/// A line-search step this short counts towards `Limits::stall`.
pub(super) const STALL_STEP: f64 = 1.0 / 16.0;

/// `newton` with the stall limit too. Its arguments: the operator and the point's
/// parameters, the control, the start (h0, delta0), the limits and the preconditioner the
/// path shares across its solves.
pub(super) fn newton_limited(
    op: &Operator,
    params: &Params,
    control: Control,
    h0: Vec<f64>,
    delta0: f64,
    limits: Limits,
    pre: &mut Preconditioner,
) -> Solution {
    let max_iter = limits.iterations;
    let factorizations_before = pre.factorizations;
    let mut stalled = 0;
    let tol = params.newton_tol;
    let n = op.mesh.n;
    let lambda = op.lambda;
    let sys = System::new(op, control);
    let mut h = h0;
    let mut delta = delta0;
    let mut ev = sys.eval(&h, delta);
    let mut iterations = 0;
    let mut why = None;
    while ev.norm > tol && iterations < max_iter && ev.norm.is_finite() {
        crate::numerics::budget::checkpoint();
        iterations += 1;
        let rhs: Vec<f64> = ev.r.iter().map(|v| -v).collect();
        // Inexact Newton: solve to a relative accuracy that tightens with the residual.
        let lin_tol = (ev.merit * ev.merit.min(0.01)).max(1e-3 * tol);
        let d = pre.newton_step(&sys, &ev.dp, &rhs, lin_tol);
        if d.iter().any(|v| !v.is_finite()) {
            why = Some(Termination::Diverged);
            break;
        }
        // Keep z = 1 + alpha lambda H above 30% of its current value.
        let mut step: f64 = 1.0;
        for i in 0..n {
            let di = d[i];
            if di < 0.0 {
                step = step.min(0.7 * lennard_jones::z_of(h[i], lambda) / (ALPHA * lambda * -di));
            }
        }
        // Backtracking on the Euclidean norm of the residual.
        let mut accepted = false;
        for _ in 0..30 {
            let h_new: Vec<f64> = (0..n).map(|i| h[i] + step * d[i]).collect();
            let delta_new = delta + step * d[n];
            let trial = sys.eval(&h_new, delta_new);
            if trial.merit.is_finite() && trial.merit < (1.0 - 1e-4 * step) * ev.merit {
                (h, delta, ev) = (h_new, delta_new, trial);
                accepted = true;
                break;
            }
            step *= 0.5;
        }
        if !accepted {
            why = Some(Termination::StepTooSmall);
            break;
        }
        stalled = if step <= STALL_STEP { stalled + 1 } else { 0 };
        if stalled >= limits.stall {
            why = Some(Termination::Stalled);
            break;
        }
    }
    let termination = if ev.norm <= tol {
        Termination::Converged
    } else if !ev.norm.is_finite() {
        Termination::Diverged
    } else {
        why.unwrap_or(Termination::IterationLimit)
    };
    let u = op.displacement(&ev.p);
    let u_edges = op.edge_displacement(&ev.p);
    let params = match control {
        Control::Load(_) => params.clone(),
        Control::Path { .. } => params.with_load(lambda * 2.0 * op.mesh.a() * ev.p.iter().sum::<f64>()),
    };
    Solution {
        params,
        mesh: op.mesh,
        x: sys.x,
        h,
        p: ev.p,
        u,
        u_edges,
        delta,
        termination,
        cost: Cost { newton_solves: 1, iterations, factorizations: pre.factorizations - factorizations_before },
        residual: ev.norm,
    }
}

/// A starting state: a Hertzian pressure carrying the load on the JKR half-width (or the
/// Hertz one at large loads); inside the contact the gap that the repulsive
/// Lennard-Jones branch needs for that pressure, outside the gap the pressure leaves.
pub(super) fn initial_state(op: &Operator, params: &Params) -> (Vec<f64>, f64) {
    let n = op.mesh.n;
    let c = jkr_half_width(params.w).unwrap_or(0.5).max(params.a0());
    let x: Vec<f64> = (0..n).map(|i| op.mesh.x(i)).collect();
    let shape: Vec<f64> = x.iter().map(|&xi| (c * c - xi * xi).max(0.0).sqrt()).collect();
    let total: f64 = 2.0 * op.mesh.a() * shape.iter().sum::<f64>();
    let scale = if total > 0.0 { params.w.max(0.1) / op.lambda / total } else { 0.0 };
    let p: Vec<f64> = shape.iter().map(|s| s * scale).collect();
    let u = op.displacement(&p);
    let i0 = n / 2;
    let h_centre = lennard_jones::gap_for_pressure(p[i0], op.lambda);
    let delta = 0.5 * x[i0] * x[i0] + u[i0] - h_centre;
    let h = (0..n)
        .map(|i| {
            if p[i] > 0.0 {
                lennard_jones::gap_for_pressure(p[i], op.lambda)
            } else {
                (-delta + 0.5 * x[i] * x[i] + u[i]).max(0.0)
            }
        })
        .collect();
    (h, delta)
}

/// Newton solves along a path of equilibria of one (mesh, lambda, k, V) under
/// `Control::Path` or load control: the operator and the preconditioner are built once and
/// shared by every point of the path.
pub struct PathSolver {
    pub(super) op: Operator,
    pub(super) params: Params,
    pub(super) pre: Preconditioner,
}

impl PathSolver {
    /// The solver at the mesh and parameters of `from` (its speed V is kept at every load).
    pub fn new(from: &Solution) -> PathSolver {
        let p = from.params.clone();
        PathSolver {
            op: Operator::new(from.mesh, p.lambda, p.k, &p.spectrum, p.v(), p.pressure),
            params: p,
            pre: Preconditioner::default(),
        }
    }

    /// The equilibrium under `control` (`Control::Path`), by Newton from the gaps `h0` and
    /// approach `delta0`.
    pub fn solve(&mut self, control: Control, h0: &[f64], delta0: f64) -> Solution {
        newton(&self.op, &self.params, control, h0.to_vec(), delta0, 40, &mut self.pre)
    }

    /// The equilibrium at load `w` from the gaps and approach of `guess` (load control).
    pub fn solve_load(&mut self, w: f64, guess: &Solution) -> Solution {
        let params = self.params.with_load(w);
        newton(&self.op, &params, Control::Load(w), guess.h.clone(), guess.delta, 40, &mut self.pre)
    }
}
