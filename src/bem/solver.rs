//! Steady sliding of a rigid cylinder on an adhesive standard-linear-solid half-plane:
//! boundary elements with Newton's method under load control (thesis Eqs. 4.4–4.16).
//!
//! Units and conventions are those of `kernel` (Eq. 4.6 corrected): X = x/beta,
//! H = (h - eps)R/beta^2, P = p/sigma0, W = w/(E0* R dgamma^2)^(1/3); the indenter slides
//! towards -X (trailing edge on the right). The speed enters as V0 = v tau/a0 with
//! a0/beta = 2 sqrt(W/pi) (ERRATA 4), so V = v tau/beta = 2 V0 sqrt(W/pi) (Eq. 4.18).
//!
//! Discretisation: n elements of width 2A on [-L, L], uniform pressure on each (Eq. 4.12:
//! U = (2 lambda/pi) G P, G Toeplitz). Unknowns: the gaps H_i and the approach Delta.
//! Equations: H_i + Delta - X_i^2/2 - U_i(P(H)) = 0 (Eq. 4.7) and lambda Int P dX = W.
//! Newton with a dense LU (faer) and a backtracking line search that keeps every
//! z = 1 + alpha lambda H positive. Unconverged points are returned as such, with their
//! residual and iteration count.
//!
//! Friction (Eq. 4.16 with the prefactor of ERRATA 3, sign for sliding towards -X):
//!   mu* = (sqrt(pi)/2) (lambda / W^(3/2)) Int P dU/dX dX,
//! evaluated exactly for piecewise-constant pressure as sum_j P_j [U(X_j + A) - U(X_j - A)],
//! with U at the element edges from the same kernel. mu_adh and mu_comp are the parts
//! from tensile and compressive elements.

use super::kernel;
use super::traction::{self, ALPHA};
use crate::numerics::gmres::gmres;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::Mat;
use std::f64::consts::PI;

/// The four governing parameters (Eq. 4.17).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// Maugis-Tabor parameter lambda (Eq. 4.9).
    pub lambda: f64,
    /// Dimensionless load W (Eq. 4.6).
    pub w: f64,
    /// Modulus ratio k = E0/E_inf.
    pub k: f64,
    /// Dimensionless speed V0 = v tau / a0 (Eq. 4.18).
    pub v0: f64,
}

impl Params {
    /// The Hertz half-width a0/beta = 2 sqrt(W/pi) (relaxed modulus).
    pub fn a0(&self) -> f64 {
        2.0 * (self.w.abs() / PI).sqrt()
    }
    /// V = v tau/beta.
    pub fn v(&self) -> f64 {
        self.v0 * self.a0()
    }
    /// The same point at speed V = v tau/beta.
    pub fn with_v(&self, v: f64) -> Params {
        Params { v0: v / self.a0(), ..*self }
    }
}

/// Mesh: n elements on [-half_length, half_length].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mesh {
    pub n: usize,
    pub half_length: f64,
}

impl Mesh {
    /// Half-width A of an element.
    pub fn a(&self) -> f64 {
        self.half_length / self.n as f64
    }
    pub fn x(&self, i: usize) -> f64 {
        -self.half_length + self.a() * (2 * i + 1) as f64
    }
}

/// The JKR half-width of the 2D line contact for load W (relaxed modulus), from
/// W = (pi/4) A^2 - sqrt(2 pi A) on its stable branch; None below the pull-off
/// -3 (pi/16)^(1/3).
pub fn jkr_half_width(w: f64) -> Option<f64> {
    let load = |a: f64| PI / 4.0 * a * a - (2.0 * PI * a).sqrt();
    let a_po = (2.0 / PI).powf(1.0 / 3.0);
    if w < load(a_po) {
        return None;
    }
    crate::numerics::roots::bisect(|a| load(a) - w, a_po, 10.0 + 4.0 * w.abs().sqrt(), 1e-13)
}

/// The 2D JKR pull-off load, -3 (pi/16)^(1/3) (load control, relaxed modulus).
pub fn jkr_pull_off() -> f64 {
    -3.0 * (PI / 16.0).powf(1.0 / 3.0)
}

/// A default mesh for the parameters: the domain spans 2.5 contact half-widths (JKR, or
/// Hertz at large loads) and at least the range where the Lennard-Jones tail still
/// carries a relative 1e-4 of the load; n elements resolve both the contact (100 per
/// half-width) and the cohesive zone, of length about pi/(8 lambda^2) (8 per zone).
pub fn default_mesh(p: &Params) -> Mesh {
    let a_ref = jkr_half_width(p.w).unwrap_or(jkr_half_width(0.0).unwrap()).max(p.a0());
    // Tail: P ~ -(3 sqrt 3/2)(alpha lambda X^2/2)^-3; its load beyond L is about
    // lambda * 2 * 2.6 * 8 / (5 (alpha lambda)^3 L^5); ask for 1e-4 max(|W|, 0.1).
    let tail = (2.0 * 2.6 * 8.0 * p.lambda / (5.0 * (ALPHA * p.lambda).powi(3) * 1e-4 * p.w.abs().max(0.1))).powf(0.2);
    let half_length = (2.5 * a_ref).max(tail);
    let zone = PI / (8.0 * p.lambda * p.lambda);
    let h = (a_ref / 100.0).min(zone / 8.0);
    let n = ((2.0 * half_length / h).ceil() as usize).clamp(64, 4000);
    Mesh { n, half_length }
}

/// A solved (or not) point with its fields.
#[derive(Clone, Debug)]
pub struct Solution {
    pub params: Params,
    pub mesh: Mesh,
    pub x: Vec<f64>,
    pub h: Vec<f64>,
    pub p: Vec<f64>,
    pub u: Vec<f64>,
    /// U at the n + 1 element edges.
    pub u_edges: Vec<f64>,
    pub delta: f64,
    pub converged: bool,
    /// Newton iterations over the whole continuation path.
    pub iterations: usize,
    /// LU factorisations of the Jacobian (the rest of the linear solves are GMRES).
    pub factorizations: usize,
    pub residual: f64,
}

/// Friction and its parts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    pub mu_star: f64,
    pub mu_adh: f64,
    pub mu_comp: f64,
}

impl Solution {
    pub fn friction(&self) -> Friction {
        let pre = PI.sqrt() / 2.0 * self.params.lambda / self.params.w.abs().powf(1.5);
        let (mut adh, mut comp) = (0.0, 0.0);
        for j in 0..self.p.len() {
            let term = self.p[j] * (self.u_edges[j + 1] - self.u_edges[j]);
            if self.p[j] < 0.0 {
                adh += term;
            } else {
                comp += term;
            }
        }
        Friction { mu_star: pre * (adh + comp), mu_adh: pre * adh, mu_comp: pre * comp }
    }

    /// Leading (left) and trailing (right) edges of the compressive zone, interpolated
    /// where P changes sign; None if no element is in compression.
    pub fn contact_edges(&self) -> Option<(f64, f64)> {
        let first = self.p.iter().position(|&p| p > 0.0)?;
        let last = self.p.iter().rposition(|&p| p > 0.0)?;
        let cross = |i: usize, j: usize| {
            let (pi, pj) = (self.p[i], self.p[j]);
            self.x[i] + (self.x[j] - self.x[i]) * pi / (pi - pj)
        };
        let lead = if first == 0 { self.x[0] } else { cross(first - 1, first) };
        let trail = if last + 1 == self.p.len() { self.x[last] } else { cross(last, last + 1) };
        Some((lead, trail))
    }

    /// Half-width of the region where the surfaces are closer than the separation of
    /// peak Lennard-Jones tension, H_c = (3^(1/6) - 1)/(alpha lambda): the contact in the
    /// JKR sense (the P > 0 width is not: in 2D the JKR pressure turns tensile inside the
    /// contact, ERRATA 19). None if no element is that close.
    pub fn adhered_half_width(&self) -> Option<f64> {
        let hc = (3f64.powf(1.0 / 6.0) - 1.0) / (ALPHA * self.params.lambda);
        let first = self.h.iter().position(|&h| h <= hc)?;
        let last = self.h.iter().rposition(|&h| h <= hc)?;
        let a = self.mesh.a();
        Some(0.5 * (self.x[last] - self.x[first]) + a)
    }

    /// lambda Int P dX: the load actually carried (equals W when converged).
    pub fn load(&self) -> f64 {
        self.params.lambda * 2.0 * self.mesh.a() * self.p.iter().sum::<f64>()
    }
}

/// The discretised operator for one (mesh, lambda, k, V).
struct Operator {
    mesh: Mesh,
    lambda: f64,
    /// Node-to-node Toeplitz coefficients, times 2 lambda/pi.
    nodes: Vec<f64>,
    /// Node-to-edge coefficients, times 2 lambda/pi: edge e, element m at offset index e - m + n - 1.
    edges: Vec<f64>,
}

impl Operator {
    fn new(mesh: Mesh, lambda: f64, k: f64, v: f64) -> Operator {
        let n = mesh.n;
        let a = mesh.a();
        let s = 2.0 * lambda / PI;
        let nodes = kernel::toeplitz_coefficients(n, a, v, k).into_iter().map(|c| c * s).collect();
        // Edge e sits at X_0 - A + 2A e; offset from element m: 2A (e - m) - A.
        let edges =
            (0..2 * n).map(|idx| s * kernel::strip(2.0 * a * (idx as f64 - (n as f64 - 1.0)) - a, a, v, k)).collect();
        Operator { mesh, lambda, nodes, edges }
    }

    fn displacement(&self, p: &[f64]) -> Vec<f64> {
        let n = self.mesh.n;
        (0..n).map(|i| (0..n).map(|j| self.nodes[i + n - 1 - j] * p[j]).sum()).collect()
    }

    fn edge_displacement(&self, p: &[f64]) -> Vec<f64> {
        let n = self.mesh.n;
        (0..=n).map(|e| (0..n).map(|m| self.edges[e + n - 1 - m] * p[m]).sum()).collect()
    }
}

/// The discrete equations of one point: residual and Jacobian in the unknowns (H, Delta).
struct System<'a> {
    op: &'a Operator,
    x: Vec<f64>,
    /// W / lambda: the required Int P dX.
    target: f64,
    /// The load equation is divided by the domain length so that it reads in H-like units.
    load_scale: f64,
}

struct Evaluation {
    p: Vec<f64>,
    dp: Vec<f64>,
    r: Vec<f64>,
    /// Max norm (the convergence test) and Euclidean norm (the line-search merit).
    norm: f64,
    merit: f64,
}

impl<'a> System<'a> {
    fn new(op: &'a Operator, params: &Params) -> Self {
        let x = (0..op.mesh.n).map(|i| op.mesh.x(i)).collect();
        System { op, x, target: params.w / op.lambda, load_scale: 1.0 / (2.0 * op.mesh.half_length) }
    }

    fn eval(&self, h: &[f64], delta: f64) -> Evaluation {
        let n = self.op.mesh.n;
        let (p, dp): (Vec<f64>, Vec<f64>) = h.iter().map(|&hi| traction::pressure(hi, self.op.lambda)).unzip();
        let u = self.op.displacement(&p);
        let mut r: Vec<f64> = (0..n).map(|i| h[i] + delta - 0.5 * self.x[i] * self.x[i] - u[i]).collect();
        r.push((2.0 * self.op.mesh.a() * p.iter().sum::<f64>() - self.target) * self.load_scale);
        let norm = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let merit = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        Evaluation { p, dp, r, norm, merit }
    }

    /// The Jacobian applied to a vector without forming it: O(n^2).
    fn apply_jacobian(&self, dp: &[f64], v: &[f64]) -> Vec<f64> {
        let n = self.op.mesh.n;
        let dv: Vec<f64> = (0..n).map(|j| dp[j] * v[j]).collect();
        let g = self.op.displacement(&dv);
        let mut out: Vec<f64> = (0..n).map(|i| v[i] - g[i] + v[n]).collect();
        out.push(2.0 * self.op.mesh.a() * dv.iter().sum::<f64>() * self.load_scale);
        out
    }

    fn jacobian(&self, dp: &[f64]) -> Mat<f64> {
        let n = self.op.mesh.n;
        let mut jac = Mat::<f64>::zeros(n + 1, n + 1);
        for i in 0..n {
            for j in 0..n {
                jac[(i, j)] = -self.op.nodes[i + n - 1 - j] * dp[j];
            }
            jac[(i, i)] += 1.0;
            jac[(i, n)] = 1.0;
        }
        for j in 0..n {
            jac[(n, j)] = 2.0 * self.op.mesh.a() * dp[j] * self.load_scale;
        }
        jac
    }
}

/// The LU factors of an earlier Jacobian, kept across Newton iterations and continuation
/// steps: the preconditioner of GMRES for the current Jacobian. Refactored only when
/// GMRES does not converge in `GMRES_ITERATIONS` (Newton-Krylov with a frozen
/// preconditioner: the Jacobian changes little from one iteration or step to the next).
#[derive(Default)]
struct Preconditioner {
    lu: Option<PartialPivLu<f64>>,
    factorizations: usize,
}

const GMRES_ITERATIONS: usize = 40;

fn lu_solve(lu: &PartialPivLu<f64>, v: &[f64]) -> Vec<f64> {
    let m = lu.solve(Mat::<f64>::from_fn(v.len(), 1, |i, _| v[i]));
    (0..v.len()).map(|i| m[(i, 0)]).collect()
}

/// Newton's method from `h0`, `delta0`. Returns the solution (converged or not).
fn newton(
    op: &Operator,
    params: &Params,
    h0: Vec<f64>,
    delta0: f64,
    tol: f64,
    max_iter: usize,
    pre: &mut Preconditioner,
) -> Solution {
    let n = op.mesh.n;
    let lambda = op.lambda;
    let sys = System::new(op, params);
    let mut h = h0;
    let mut delta = delta0;
    let mut ev = sys.eval(&h, delta);
    let mut iterations = 0;
    while ev.norm > tol && iterations < max_iter && ev.norm.is_finite() {
        iterations += 1;
        let rhs: Vec<f64> = ev.r.iter().map(|v| -v).collect();
        // Inexact Newton: solve to a relative accuracy that tightens with the residual.
        let lin_tol = (ev.merit * ev.merit.min(0.1)).max(1e-3 * tol);
        let krylov = pre.lu.as_ref().and_then(|lu| {
            let g = gmres(|v| sys.apply_jacobian(&ev.dp, v), |v| lu_solve(lu, v), &rhs, lin_tol, GMRES_ITERATIONS);
            g.converged.then_some(g.x)
        });
        let d = match krylov {
            Some(d) => d,
            None => {
                let lu = sys.jacobian(&ev.dp).partial_piv_lu();
                let d = lu_solve(&lu, &rhs);
                pre.lu = Some(lu);
                pre.factorizations += 1;
                d
            }
        };
        if d.iter().any(|v| !v.is_finite()) {
            break;
        }
        // Keep z = 1 + alpha lambda H above 30% of its current value.
        let mut step: f64 = 1.0;
        for i in 0..n {
            let di = d[i];
            if di < 0.0 {
                step = step.min(0.7 * traction::z_of(h[i], lambda) / (ALPHA * lambda * -di));
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
            break;
        }
    }
    let u = op.displacement(&ev.p);
    let u_edges = op.edge_displacement(&ev.p);
    Solution {
        params: *params,
        mesh: op.mesh,
        x: sys.x,
        h,
        p: ev.p,
        u,
        u_edges,
        delta,
        converged: ev.norm <= tol,
        iterations,
        factorizations: pre.factorizations,
        residual: ev.norm,
    }
}

/// Tolerance of the max-norm residual (in units of H).
pub const TOLERANCE: f64 = 1e-9;

/// A starting state: a Hertzian pressure carrying the load on the JKR half-width (or the
/// Hertz one at large loads); inside the contact the gap that the repulsive
/// Lennard-Jones branch needs for that pressure, outside the gap the pressure leaves.
fn initial_state(op: &Operator, params: &Params) -> (Vec<f64>, f64) {
    let n = op.mesh.n;
    let c = jkr_half_width(params.w).unwrap_or(0.5).max(params.a0());
    let x: Vec<f64> = (0..n).map(|i| op.mesh.x(i)).collect();
    let shape: Vec<f64> = x.iter().map(|&xi| (c * c - xi * xi).max(0.0).sqrt()).collect();
    let total: f64 = 2.0 * op.mesh.a() * shape.iter().sum::<f64>();
    let scale = if total > 0.0 { params.w.max(0.1) / op.lambda / total } else { 0.0 };
    let p: Vec<f64> = shape.iter().map(|s| s * scale).collect();
    let u = op.displacement(&p);
    let i0 = n / 2;
    let h_centre = traction::gap_for_pressure(p[i0], op.lambda);
    let delta = 0.5 * x[i0] * x[i0] + u[i0] - h_centre;
    let h = (0..n)
        .map(|i| {
            if p[i] > 0.0 {
                traction::gap_for_pressure(p[i], op.lambda)
            } else {
                (-delta + 0.5 * x[i] * x[i] + u[i]).max(0.0)
            }
        })
        .collect();
    (h, delta)
}

/// Geometric continuation of a parameter from `from` to `to` (either direction): each
/// step multiplies it by at most `factor`, warm-starting from the last converged state;
/// a failed step is retried with the square root of the factor, down to a factor of
/// 1.001. Returns the solution at `to` (converged or the failed last trial) and the
/// Newton iterations spent.
fn continue_geometric(
    from: f64,
    to: f64,
    mut factor: f64,
    start: Solution,
    mut step: impl FnMut(f64, &Solution) -> Solution,
) -> (Solution, usize) {
    let mut iterations = 0;
    let mut value = from;
    let mut last = start;
    let up = to > from;
    while value != to {
        let next = if up { (value * factor).min(to) } else { (value / factor).max(to) };
        let trial = step(next, &last);
        iterations += trial.iterations;
        if trial.converged {
            value = next;
            last = trial;
            factor = (factor * factor).min(4.0);
        } else {
            factor = factor.sqrt();
            if factor < 1.001 {
                return (trial, iterations);
            }
        }
    }
    (last, iterations)
}

/// The smallest lambda at which Newton starts (soft, long-range adhesion converges from a
/// Hertzian guess); larger lambda are reached by continuation.
const LAMBDA_START: f64 = 0.3;

/// Solves one point. Path: the relaxed elastic problem (V = 0) at lambda = min(lambda,
/// 0.3) from a Hertzian guess; continuation in lambda up to its value; then continuation
/// in the speed V from 1e-3 element widths up to its value. Load control throughout.
pub fn solve(params: &Params, mesh: Mesh) -> Solution {
    let lam0 = params.lambda.min(LAMBDA_START);
    let at = |lambda: f64, v: f64| Params { lambda, ..*params }.with_v(v);
    let op0 = Operator::new(mesh, lam0, params.k, 0.0);
    let (h0, d0) = initial_state(&op0, &at(lam0, 0.0));
    let mut pre = Preconditioner::default();
    let first = newton(&op0, &at(lam0, 0.0), h0, d0, TOLERANCE, 100, &mut pre);
    let mut iterations = first.iterations;
    if !first.converged {
        return first;
    }
    let (mut sol, it) = continue_geometric(lam0, params.lambda, 1.5, first, |lambda, warm| {
        let op = Operator::new(mesh, lambda, params.k, 0.0);
        newton(&op, &at(lambda, 0.0), warm.h.clone(), warm.delta, TOLERANCE, 40, &mut pre)
    });
    iterations += it;
    let v_target = params.v();
    if sol.converged && v_target > 0.0 {
        let v_start = 1e-3 * mesh.a();
        let (s, it) = if v_target <= v_start {
            let op = Operator::new(mesh, params.lambda, params.k, v_target);
            let s = newton(&op, params, sol.h.clone(), sol.delta, TOLERANCE, 40, &mut pre);
            let it = s.iterations;
            (s, it)
        } else {
            continue_geometric(v_start, v_target, 4.0, sol, |v, warm| {
                let op = Operator::new(mesh, params.lambda, params.k, v);
                newton(&op, &params.with_v(v), warm.h.clone(), warm.delta, TOLERANCE, 40, &mut pre)
            })
        };
        sol = s;
        iterations += it;
    }
    sol.params = *params;
    sol.iterations = iterations;
    sol.factorizations = pre.factorizations;
    sol
}

/// A solution with the Richardson estimate of the discretisation error of mu*: the
/// solver converges at second order in the element size (measured: successive
/// differences shrink by 3.9 per halving), so the error of the fine solution is about
/// |mu*(n) - mu*(n/2)| / 3. When the coarse solve does not converge, the estimate is
/// |mu*| (no confidence).
pub fn solve_with_estimate(params: &Params, mesh: Mesh) -> (Solution, f64) {
    solve_to_tolerance(params, mesh, f64::INFINITY, mesh.n)
}

fn richardson(fine: &Solution, coarse: &Solution) -> f64 {
    let mu = fine.friction().mu_star;
    let estimate =
        if coarse.converged && fine.converged { (mu - coarse.friction().mu_star).abs() / 3.0 } else { mu.abs() };
    if estimate.is_finite() {
        estimate
    } else {
        f64::MAX
    }
}

/// Solves on `mesh`, then doubles the number of elements (same domain) until the
/// Richardson estimate is at most `rel_tol` |mu*| or the next mesh would exceed `n_max`.
/// Each refinement reuses the previous fine solution as the coarse one.
pub fn solve_to_tolerance(params: &Params, mesh: Mesh, rel_tol: f64, n_max: usize) -> (Solution, f64) {
    let mut coarse = solve(params, Mesh { n: (mesh.n / 2).max(8), ..mesh });
    let mut fine = solve(params, mesh);
    loop {
        let estimate = richardson(&fine, &coarse);
        if estimate <= rel_tol * fine.friction().mu_star.abs() || 2 * fine.mesh.n > n_max {
            return (fine, estimate);
        }
        let n = 2 * fine.mesh.n;
        coarse = fine;
        fine = solve(params, Mesh { n, ..mesh });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jkr_line_contact_formulas() {
        // Pull-off -3 (pi/16)^(1/3) = -1.7438, at A = (2/pi)^(1/3); Hertz at large load.
        assert!((jkr_pull_off() + 1.743_671_027).abs() < 1e-8);
        // The same from the minimum of W(A) = (pi/4) A^2 - sqrt(2 pi A).
        let (_, max_neg) =
            crate::numerics::roots::maximize(|a| -(PI / 4.0 * a * a - (2.0 * PI * a).sqrt()), 0.1, 3.0, 50, 1e-12);
        assert!((-max_neg - jkr_pull_off()).abs() < 1e-10);
        assert!(jkr_half_width(-1.8).is_none());
        let a = jkr_half_width(1000.0).unwrap();
        let hertz = Params { lambda: 1.0, w: 1000.0, k: 0.1, v0: 1.0 }.a0();
        assert!((a / hertz - 1.0).abs() < 0.03, "{a} {hertz}");
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let params = Params { lambda: 1.3, w: 0.7, k: 0.1, v0: 1.0 };
        let mesh = Mesh { n: 40, half_length: 4.0 };
        let op = Operator::new(mesh, params.lambda, params.k, params.v());
        let sys = System::new(&op, &params);
        let h: Vec<f64> = (0..40).map(|i| 0.3 * ((i as f64) * 0.7).sin() + 0.2).collect();
        let delta = 0.4;
        let ev = sys.eval(&h, delta);
        let jac = sys.jacobian(&ev.dp);
        let eps = 1e-6;
        for j in [0, 7, 20, 39, 40] {
            let (mut hp, mut dpl) = (h.clone(), delta);
            if j < 40 {
                hp[j] += eps;
            } else {
                dpl += eps;
            }
            let ev2 = sys.eval(&hp, dpl);
            for i in 0..=40 {
                let fd = (ev2.r[i] - ev.r[i]) / eps;
                assert!((fd - jac[(i, j)]).abs() < 1e-4 * (1.0 + fd.abs()), "({i},{j}): {fd} vs {}", jac[(i, j)]);
            }
        }
    }

    #[test]
    fn large_load_friction_approaches_persson_hunter() {
        // Adhesion negligible at W = 100 (the thesis: the adhesionless limit is reached
        // near W = 100). Persson's approximation assumes a Hertzian pressure; the BEM
        // solves the asymmetric one: the BEM curve is Persson's shifted to slightly higher
        // speed (measured: -0.5% at V0 = 0.1, -6.1% at 0.56, +3.1% at 1.78, +0.2% at 10),
        // and the BEM maximum, about 0.483 near V0 = 1.3, is the thesis' "about 0.48"
        // at k = 0.1.
        let mesh = Mesh { n: 400, half_length: 28.0 };
        for (v0, bem_expected) in [(0.1, 0.0858), (1.3, 0.4829), (10.0, 0.1709)] {
            let params = Params { lambda: 0.5, w: 100.0, k: 0.1, v0 };
            let s = solve(&params, mesh);
            assert!(s.converged, "V0 = {v0}: residual {}", s.residual);
            let f = s.friction();
            let persson = crate::theory::persson::mu_star(0.1, v0, 1e-8).mu_star;
            assert!((f.mu_star / persson - 1.0).abs() < 0.05, "V0 = {v0}: {} vs Persson {persson}", f.mu_star);
            assert!((f.mu_star - bem_expected).abs() < 2e-3, "V0 = {v0}: {}", f.mu_star);
            // Adhesive hysteresis is small here (measured: 2% of mu* at V0 = 0.1, where
            // friction itself is small; 0.1% at V0 = 1.3).
            assert!(f.mu_adh.abs() < 0.05 * f.mu_star, "adhesion negligible: {:?}", f);
        }
    }

    #[test]
    fn elastic_point_converges_and_carries_its_load() {
        let params = Params { lambda: 1.0, w: 1.0, k: 0.1, v0: 0.0 };
        let mesh = Mesh { n: 200, half_length: 6.0 };
        let s = solve(&params, mesh);
        assert!(s.converged, "residual {} after {}", s.residual, s.iterations);
        assert!((s.load() - 1.0).abs() < 1e-6);
        // Elastic and symmetric: no friction.
        assert!(s.friction().mu_star.abs() < 1e-8, "{:?}", s.friction());
        let (lead, trail) = s.contact_edges().unwrap();
        assert!((lead + trail).abs() < 1e-6, "{lead} {trail}");
    }
}
