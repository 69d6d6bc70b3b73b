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
//! Newton-Krylov: products with G by FFT (`numerics::toeplitz`), GMRES preconditioned by a
//! dense LU (faer) of the near-contact block (`ActiveLu`), and a backtracking line search
//! that keeps every z = 1 + alpha lambda H positive. Unconverged points are returned as
//! such, with their residual and iteration count.
//!
//! Friction (Eq. 4.16 with the prefactor of ERRATA 3, sign for sliding towards -X):
//!   mu* = (sqrt(pi)/2) (lambda / W^(3/2)) Int P dU/dX dX,
//! evaluated exactly for piecewise-constant pressure as sum_j P_j [U(X_j + A) - U(X_j - A)],
//! with U at the element edges from the same kernel. mu_adh and mu_comp are the parts
//! from tensile and compressive elements.

use super::kernel::MeshKernel;
use super::traction::{self, ALPHA};
use crate::numerics::gmres::gmres;
use crate::numerics::toeplitz::Toeplitz;
use crate::rheology::Spectrum;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::Mat;
use std::f64::consts::PI;

/// The four governing parameters (Eq. 4.17), and the shape of the creep function.
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    /// Maugis-Tabor parameter lambda (Eq. 4.9).
    pub lambda: f64,
    /// Dimensionless load W (Eq. 4.6).
    pub w: f64,
    /// Modulus ratio k = E0/E_inf.
    pub k: f64,
    /// Dimensionless speed V0 = v tau / a0 (Eq. 4.18).
    pub v0: f64,
    /// Retardation spectrum (times in units of tau); the SLS by default.
    pub spectrum: Spectrum,
    /// Newton's tolerance on the max-norm residual, in units of H (`TOLERANCE` by default).
    pub newton_tol: f64,
}

impl Params {
    /// A point on the standard linear solid.
    pub fn sls(lambda: f64, w: f64, k: f64, v0: f64) -> Params {
        Params { lambda, w, k, v0, spectrum: Spectrum::sls(), newton_tol: TOLERANCE }
    }
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
        Params { v0: v / self.a0(), ..self.clone() }
    }
    /// The same speed V at another load (V0 is relative to the Hertz width of |W|; at
    /// W = 0 it is reported as infinite).
    pub fn with_load(&self, w: f64) -> Params {
        let v = self.v();
        let p = Params { w, ..self.clone() };
        if w == 0.0 {
            Params { v0: if v == 0.0 { 0.0 } else { f64::INFINITY }, ..p }
        } else {
            p.with_v(v)
        }
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

/// The domain half-length for a requested relative accuracy: 2.5 contact half-widths
/// (JKR, or Hertz at large loads), and at least the range beyond which the Lennard-Jones
/// tail would carry less than a fraction rel_tol of max(|W|, 0.1) (measured at lambda = 3,
/// W = 0.1: truncating at L = 5, 7 changes mu* by 5e-5, 7e-6 relative to L = 10). The tail pressure
/// is P ~ -(3 sqrt 3/2)(alpha lambda X^2/2)^-3, so its load beyond L is about
/// lambda * 2 * 2.6 * 8 / (5 (alpha lambda)^3 L^5) (`tail_over`).
pub fn domain_half_length(p: &Params, rel_tol: f64) -> f64 {
    let a_ref = contact_scale(p);
    let tail = tail_over(p, rel_tol * load_scale(p)).powf(0.2);
    (2.5 * a_ref).max(tail)
}

/// C / x, where C / L^5 = lambda * 2 * 2.6 * 8 / (5 (alpha lambda)^3 L^5) is the load the
/// Lennard-Jones tail carries beyond |X| = L (`domain_half_length`): the load for x = L^5,
/// and the L^5 that carries a given load x.
fn tail_over(p: &Params, x: f64) -> f64 {
    2.0 * 2.6 * 8.0 * p.lambda / (5.0 * (ALPHA * p.lambda).powi(3) * x)
}

/// The load the domain rule's tolerance refers to: max(|W|, 0.1).
fn load_scale(p: &Params) -> f64 {
    p.w.abs().max(0.1)
}

/// The relative error of mu* that truncating the domain at `half_length` may cause: the
/// load the Lennard-Jones tail would carry beyond it, as a fraction of max(|W|, 0.1) (the
/// inverse of `domain_half_length`'s rule). Measured against a domain 2.5 times longer at
/// lambda = 0.3, W = 1, k = 0.1, V0 = 10, where the domain's share dominates: the error of
/// mu* was 0.95-1.01 times |mu*| times this fraction plus the mesh's Richardson share, on
/// domains of 8, 10 and 16.
pub fn domain_rel_error(p: &Params, half_length: f64) -> f64 {
    domain_load_error(p, half_length) / load_scale(p)
}

/// The load the Lennard-Jones tail would carry beyond |X| = `half_length` (`tail_over`):
/// the error a domain of that half-length may cause in a load, such as the pull-off load
/// (independent of W).
pub fn domain_load_error(p: &Params, half_length: f64) -> f64 {
    tail_over(p, half_length.powi(5))
}

/// The contact half-width the mesh is built for: JKR (relaxed), at least Hertz.
fn contact_scale(p: &Params) -> f64 {
    jkr_half_width(p.w).unwrap_or(jkr_half_width(0.0).unwrap()).max(p.a0())
}

/// The first mesh of a solve to tolerance: the domain of `domain_half_length`, elements of
/// the smaller of 1/40 of the contact half-width and 1/2 of the cohesive zone, whose
/// length is about pi/(8 lambda^2) (Maugis-Dugdale in 2D); 64..=8000 elements. Coarser
/// than the answer needs at large lambda is fine: the continuation runs on it, the
/// refinement to rel_tol follows (at lambda = 10 the speed-first path converges from it).
pub fn starting_mesh(p: &Params, rel_tol: f64) -> Mesh {
    let half_length = domain_half_length(p, rel_tol);
    let h = (contact_scale(p) / 40.0).min(cohesive_zone(p.lambda) / 2.0);
    let n = ((2.0 * half_length / h).ceil() as usize).clamp(64, 8000);
    Mesh { n, half_length }
}

/// The length of the cohesive zone at a crack front, about pi/(8 lambda^2) (Maugis-Dugdale in
/// 2D, at the relaxed modulus: the shortest it gets, a stiffer material lengthening it).
pub fn cohesive_zone(lambda: f64) -> f64 {
    PI / (8.0 * lambda * lambda)
}

/// Elements of `mesh` per cohesive zone (`cohesive_zone`): a meshing diagnostic. A starting
/// mesh has at least 2 unless it is capped at 8000 elements.
pub fn zone_elements(lambda: f64, mesh: Mesh) -> f64 {
    cohesive_zone(lambda) / (2.0 * mesh.a())
}

/// Below one element per cohesive zone the crack front is not resolved, and a mesh
/// refinement's difference does not bound a pull-off's error. Measured (`pipelines/bench.yaml`,
/// `pulloff_n200`): at lambda = 3 on 200 elements (0.69 per zone) the pull-off
/// load is 90 % off at V = 1e-6 and its Richardson estimate covers 1 of 4 points; every
/// configuration with 2 or more per zone is covered (error / estimate <= 0.46). `bem.sweep`'s
/// mu* is covered at 1.39 per zone (n = 400, lambda = 3).
pub const MIN_ZONE_ELEMENTS: f64 = 1.0;

/// The default requested accuracy of mu* (relative).
pub const DEFAULT_REL_TOL: f64 = 1e-3;
/// The largest mesh a solve to tolerance refines to by default.
pub const DEFAULT_N_MAX: usize = 16_000;

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
    /// contact, ERRATA 19), with the crossings interpolated between nodes. None if no node
    /// is that close.
    pub fn adhered_half_width(&self) -> Option<f64> {
        let hc = (3f64.powf(1.0 / 6.0) - 1.0) / (ALPHA * self.params.lambda);
        let first = self.h.iter().position(|&h| h <= hc)?;
        let last = self.h.iter().rposition(|&h| h <= hc)?;
        // The crossings of H = hc, interpolated linearly between nodes (the domain edge if
        // the first or last node is already inside).
        let a = self.mesh.a();
        let cross = |i: usize, j: usize| {
            let t = (self.h[i] - hc) / (self.h[i] - self.h[j]);
            self.x[i] + t * (self.x[j] - self.x[i])
        };
        let left = if first == 0 { self.x[0] - a } else { cross(first - 1, first) };
        let right = if last + 1 == self.h.len() { self.x[last] + a } else { cross(last + 1, last) };
        Some(0.5 * (right - left))
    }

    /// The approach measured from the domain edges, Delta - (U(X_0) + U(X_n-1))/2: the
    /// quantity `Control::approach` imposes.
    pub fn approach(&self) -> f64 {
        self.delta - 0.5 * (self.u[0] + self.u[self.u.len() - 1])
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
    /// The same as an FFT-based product (O(n log n)).
    nodes_fft: Toeplitz,
    /// Node-to-edge products (edge e, element m: diagonal e - m + n - 1), by FFT.
    edges_fft: Toeplitz,
}

impl Operator {
    fn new(mesh: Mesh, lambda: f64, k: f64, spectrum: &Spectrum, v: f64) -> Operator {
        Operator::scaled(mesh, &MeshKernel::new(mesh.n, mesh.a(), v, k, spectrum), lambda)
    }

    /// The operator at `lambda` from the kernel of its mesh and speed (which lambda only
    /// scales: a lambda continuation builds the kernel once).
    fn scaled(mesh: Mesh, kern: &MeshKernel, lambda: f64) -> Operator {
        let n = mesh.n;
        let s = 2.0 * lambda / PI;
        let nodes: Vec<f64> = kern.nodes.iter().map(|c| c * s).collect();
        // Edge e sits at X_0 - A + 2A e; offset from element m: 2A (e - m) - A.
        let edges: Vec<f64> = kern.edges.iter().map(|c| c * s).collect();
        let nodes_fft = Toeplitz::new(&nodes, n, n);
        let edges_fft = Toeplitz::new(&edges, n, n + 1);
        Operator { mesh, lambda, nodes, nodes_fft, edges_fft }
    }

    fn displacement(&self, p: &[f64]) -> Vec<f64> {
        self.nodes_fft.apply(p)
    }

    fn edge_displacement(&self, p: &[f64]) -> Vec<f64> {
        self.edges_fft.apply(p)
    }
}

/// What the last of the n + 1 equations imposes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Control {
    /// The load: lambda Int P dX = W (the approach Delta is an unknown).
    Load(f64),
    /// A combination of the approach a = Delta - (U(X_0) + U(X_n-1))/2, measured from the
    /// domain edges (the grip of a finite 2D body: Delta alone is not, since at high speed
    /// the moving kernel adds a constant times the load to U), and the load carried W:
    ///   t_approach a + t_load W = value.
    /// (1, 0) is approach control, regular through the load-control fold (the pull-off);
    /// the unit tangent of the (a, W) path gives pseudo-arclength control, regular through
    /// folds in the approach as well.
    Path { t_approach: f64, t_load: f64, value: f64 },
}

impl Control {
    /// Approach control: a = value.
    pub fn approach(value: f64) -> Control {
        Control::Path { t_approach: 1.0, t_load: 0.0, value }
    }
}

/// The discrete equations of one point: residual and Jacobian in the unknowns (H, Delta).
struct System<'a> {
    op: &'a Operator,
    x: Vec<f64>,
    control: Control,
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
    fn new(op: &'a Operator, control: Control) -> Self {
        let x = (0..op.mesh.n).map(|i| op.mesh.x(i)).collect();
        System { op, x, control, load_scale: 1.0 / (2.0 * op.mesh.half_length) }
    }

    /// The coefficient of dP_j/dH_j in the last row: the load weight, or minus the mean
    /// influence of element j on the two edge nodes (path control: approach and load).
    fn edge_row(&self, j: usize) -> f64 {
        let n = self.op.mesh.n;
        match self.control {
            Control::Load(_) => 2.0 * self.op.mesh.a() * self.load_scale,
            Control::Path { t_approach, t_load, .. } => {
                -0.5 * t_approach * (self.op.nodes[n - 1 - j] + self.op.nodes[2 * n - 2 - j])
                    + t_load * self.op.lambda * 2.0 * self.op.mesh.a()
            }
        }
    }

    fn eval(&self, h: &[f64], delta: f64) -> Evaluation {
        let n = self.op.mesh.n;
        let (p, dp): (Vec<f64>, Vec<f64>) = h.iter().map(|&hi| traction::pressure(hi, self.op.lambda)).unzip();
        let u = self.op.displacement(&p);
        let mut r: Vec<f64> = (0..n).map(|i| h[i] + delta - 0.5 * self.x[i] * self.x[i] - u[i]).collect();
        r.push(match self.control {
            Control::Load(w) => (2.0 * self.op.mesh.a() * p.iter().sum::<f64>() - w / self.op.lambda) * self.load_scale,
            Control::Path { t_approach, t_load, value } => {
                let load = self.op.lambda * 2.0 * self.op.mesh.a() * p.iter().sum::<f64>();
                t_approach * (delta - 0.5 * (u[0] + u[n - 1])) + t_load * load - value
            }
        });
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
        out.push(match self.control {
            Control::Load(_) => self.edge_row(0) * dv.iter().sum::<f64>(),
            Control::Path { t_approach, t_load, .. } => {
                t_approach * (v[n] - 0.5 * (g[0] + g[n - 1]))
                    + t_load * self.op.lambda * 2.0 * self.op.mesh.a() * dv.iter().sum::<f64>()
            }
        });
        out
    }

    /// The dense Jacobian (the finite-difference test checks `apply_jacobian` against it).
    #[cfg(test)]
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
            jac[(n, j)] = self.edge_row(j) * dp[j];
        }
        if let Control::Path { t_approach, .. } = self.control {
            jac[(n, n)] = t_approach;
        }
        jac
    }
}

/// The preconditioner of GMRES: the Jacobian with the columns of the far field dropped.
/// J = I - G D + (approach column, load row), D = diag(dP/dH). Far from the contact dP/dH
/// decays like H^-4, so columns j with |dP_j/dH| (|G|_1 + load weight) below `DROP`
/// change J by at most DROP in the 1-norm; replacing them by identity columns leaves a
/// system of the active nodes only (plus the approach), factored by a dense LU (faer),
/// and an explicit update of the rest by one FFT product. It is frozen across Newton
/// iterations and continuation steps (Newton-Krylov), rebuilt when GMRES stalls.
struct ActiveLu {
    n: usize,
    idx: Vec<usize>,
    d: Vec<f64>,
    lu: PartialPivLu<f64>,
    g: Toeplitz,
}

const DROP: f64 = 1.0;

impl ActiveLu {
    fn new(sys: &System, dp: &[f64], drop: f64) -> ActiveLu {
        let n = sys.op.mesh.n;
        let load_weight = 2.0 * sys.op.mesh.a() * sys.load_scale;
        let corner = match sys.control {
            Control::Load(_) => 0.0,
            Control::Path { t_approach, .. } => t_approach,
        };
        let col_norm = sys.op.nodes.iter().map(|c| c.abs()).sum::<f64>() + load_weight;
        let idx: Vec<usize> = (0..n).filter(|&j| dp[j].abs() * col_norm > drop).collect();
        let d: Vec<f64> = idx.iter().map(|&j| dp[j]).collect();
        let m = idx.len();
        let mat = Mat::<f64>::from_fn(m + 1, m + 1, |a, b| match (a < m, b < m) {
            (true, true) => f64::from(a == b) - sys.op.nodes[idx[a] + n - 1 - idx[b]] * d[b],
            (true, false) => 1.0,
            (false, true) => sys.edge_row(idx[b]) * d[b],
            (false, false) => corner,
        });
        ActiveLu { n, lu: mat.partial_piv_lu(), idx, d, g: sys.op.nodes_fft.clone() }
    }

    fn solve(&self, b: &[f64]) -> Vec<f64> {
        let (n, m) = (self.n, self.idx.len());
        let mut small: Vec<f64> = self.idx.iter().map(|&j| b[j]).collect();
        small.push(b[n]);
        let xs = lu_solve(&self.lu, &small);
        let delta = xs[m];
        let mut t = vec![0.0; n];
        for (a, &j) in self.idx.iter().enumerate() {
            t[j] = self.d[a] * xs[a];
        }
        let g = self.g.apply(&t);
        let mut x: Vec<f64> = (0..n).map(|i| b[i] + g[i] - delta).collect();
        for (a, &j) in self.idx.iter().enumerate() {
            x[j] = xs[a];
        }
        x.push(delta);
        x
    }

    /// As a preconditioner of the Jacobian on a mesh with `r` = 2, 4, ... times the
    /// elements (nested: fine elements r i .. r i + r - 1 divide coarse element i): the
    /// group means of b are solved on this (coarse) mesh and prolonged by injection; the
    /// deviations from the group means, which the smoothing influence operator G hardly sees
    /// (J = I - G D acts on them about as the identity), are kept as they are.
    fn solve_nested(&self, b: &[f64]) -> Vec<f64> {
        let nc = self.n;
        let r = (b.len() - 1) / nc;
        if r == 2 {
            return self.solve_two_grid(b);
        }
        let inv = 1.0 / r as f64;
        let mut coarse: Vec<f64> = b[..r * nc].chunks_exact(r).map(|g| g.iter().sum::<f64>() * inv).collect();
        coarse.push(b[r * nc]);
        let xc = self.solve(&coarse);
        let mut x = Vec::with_capacity(r * nc + 1);
        for (i, g) in b[..r * nc].chunks_exact(r).enumerate() {
            x.extend(g.iter().map(|&bi| xc[i] + (bi - coarse[i])));
        }
        x.push(xc[nc]);
        x
    }

    /// `solve_nested` for r = 2, with the pair differences formed directly.
    fn solve_two_grid(&self, b: &[f64]) -> Vec<f64> {
        let nc = self.n;
        let mut coarse: Vec<f64> = (0..nc).map(|i| 0.5 * (b[2 * i] + b[2 * i + 1])).collect();
        coarse.push(b[2 * nc]);
        let xc = self.solve(&coarse);
        let mut x = Vec::with_capacity(2 * nc + 1);
        for i in 0..nc {
            let half = 0.5 * (b[2 * i] - b[2 * i + 1]);
            x.push(xc[i] + half);
            x.push(xc[i] - half);
        }
        x.push(xc[nc]);
        x
    }
}

/// The active LU in use. One of the mesh with half the elements (mesh sequencing) is
/// first tried as a two-grid preconditioner (`ActiveLu::solve_two_grid`); where GMRES
/// does not converge with it, the mesh gets its own LU. A frozen LU is also rebuilt once the
/// GMRES iterations it has cost beyond its first solve's count (`excess`) outweigh a new
/// factorization (`REBUILD_BALANCE`).
#[derive(Default)]
struct Preconditioner {
    active: Option<ActiveLu>,
    factorizations: usize,
    /// GMRES iterations of the first Newton step solved with the current LU.
    first: Option<usize>,
    /// GMRES iterations beyond `first` summed over the later steps.
    excess: usize,
}

/// A frozen active LU of m nodes is rebuilt for the next Newton step once its `excess`
/// GMRES iterations exceed REBUILD_BALANCE m / 3: a factorization costs about (2/3) m^3
/// flops and an iteration's triangular solves 2 m^2, so at 1 the iterations lost would have
/// paid for it by that count (the ski-rental balance, 2-competitive). The factorization is
/// blocked and the solves are memory-bound, and each iteration adds an FFT product and the
/// orthogonalisation, so the measured balance is lower: the 22 BEM stages of `thesis.yaml`
/// (release, empty caches, one after the other, 2 jobs) took 139.9 s of task time with no
/// such rebuild, 112.5 / 110.6 / 114.4 s at 0.1 / 0.2 / 0.3 (pull-offs 0.42-0.63 x, the
/// maxima 0.70 x, lambda24 0.93 x), 180.9 s with a rebuild whenever GMRES took more than 12
/// and twice its first count (lambda24 2.2 x). The counts, not times, decide: deterministic.
const REBUILD_BALANCE: f64 = 0.2;

/// The fewest elements of a mesh for which the two-grid preconditioner is tried instead of
/// a fresh active LU, whose cost grows as the cube of the active nodes (measured at
/// lambda = 3, W = 0.1, V0 = 1e-3, k = 0.1: 0.17 s at n = 4632 and 1.15 s at n = 9264, of a
/// whole solve to that mesh of 1.63 s; with the two-grid 0.57 s, and 12.2 -> 2.9 s at
/// n = 18528, the same mu* to 9 digits).
const TWO_GRID_MIN_N: usize = 2000;

/// The largest ratio of fine to coarse elements at which a coarse LU is used as a nested
/// preconditioner (`ActiveLu::solve_nested`): `solve_to_tolerance` carries the LU of its
/// first refinement through the next ones instead of factoring each coarse level anew,
/// whose cost grows as the cube of its active nodes. Measured (release, lambda = 2, W =
/// 0.5, k = 0.001, V0 = 4.64e-4, refined 1920 -> 3840 -> 7680 -> 15360): 3.2 s -> 0.19 s,
/// the LU at n = 7680 (m = 3760 active nodes) alone had taken 2.1-2.6 s; GMRES takes 1-4
/// iterations at r = 2 and 4, 2-5 at r = 8; the same mu* to every digit printed. The
/// Chapter 4-5 stages of `thesis.yaml` (with `LAMBDA_STEP_STALL`): 1289 G instructions
/// instead of 1917 G, the rolling stages 3-5 times faster (rolling_vs_load 11 s instead of 54 s
/// of task time), every table equal to the printed digits; no nested solve with r > 2
/// failed there (one that fails falls back, as at r = 2, to a fresh LU of the fine mesh).
const MAX_NESTED_RATIO: usize = 8;

/// r = fine / coarse when the fine mesh nests r = 2, 4, ... `MAX_NESTED_RATIO` elements in
/// each coarse one.
fn nested_ratio(coarse: usize, fine: usize) -> Option<usize> {
    (fine > coarse && fine.is_multiple_of(coarse))
        .then(|| fine / coarse)
        .filter(|r| r.is_power_of_two() && *r <= MAX_NESTED_RATIO)
}

const GMRES_ITERATIONS: usize = 30;

fn lu_solve(lu: &PartialPivLu<f64>, v: &[f64]) -> Vec<f64> {
    let m = lu.solve(Mat::<f64>::from_fn(v.len(), 1, |i, _| v[i]));
    (0..v.len()).map(|i| m[(i, 0)]).collect()
}

impl Preconditioner {
    /// The Newton step J d = rhs to `tol`: GMRES with the frozen preconditioner; if it
    /// stalls, again with a fresh one; if that stalls too, an exact LU of the whole J.
    fn newton_step(&mut self, sys: &System, dp: &[f64], rhs: &[f64], tol: f64) -> Vec<f64> {
        let apply = |v: &[f64]| sys.apply_jacobian(dp, v);
        let n = sys.op.mesh.n;
        if let Some(coarse) = self.active.as_ref().filter(|a| nested_ratio(a.n, n).is_some() && n >= TWO_GRID_MIN_N) {
            let g = gmres(apply, |v| coarse.solve_nested(v), rhs, tol, GMRES_ITERATIONS);
            if g.converged {
                return g.x;
            }
            // Not good enough here: this mesh gets its own LU from now on.
            self.active = None;
        }
        for fresh in [false, true] {
            // A preconditioner from another mesh (mesh sequencing), or one whose extra
            // iterations have outweighed a factorization, is rebuilt.
            let stale = self.active.as_ref().is_none_or(|a| {
                a.n != sys.op.mesh.n || self.excess as f64 > REBUILD_BALANCE * a.idx.len() as f64 / 3.0
            });
            if fresh || stale {
                self.active = Some(ActiveLu::new(sys, dp, DROP));
                self.factorizations += 1;
                (self.first, self.excess) = (None, 0);
            }
            let pre = self.active.as_ref().unwrap();
            let g = gmres(apply, |v| pre.solve(v), rhs, tol, GMRES_ITERATIONS);
            if g.converged {
                let first = *self.first.get_or_insert(g.iterations);
                self.excess += g.iterations.saturating_sub(first);
                return g.x;
            }
        }
        let exact = ActiveLu::new(sys, dp, 0.0);
        self.factorizations += 1;
        (self.first, self.excess) = (None, 0);
        let d = exact.solve(rhs);
        self.active = Some(exact);
        d
    }
}

/// Newton's method from `h0`, `delta0`. Returns the solution (converged or not).
/// Under path control the solution's load is the one carried, at the same speed V.
fn newton(
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
struct Limits {
    /// Newton iterations at most.
    iterations: usize,
    /// Give up after this many consecutive iterations whose line search cut the step to
    /// `STALL_STEP` or less (`LAMBDA_STEP_STALL`; `usize::MAX`: never).
    stall: usize,
}

/// A line-search step this short counts towards `Limits::stall`.
const STALL_STEP: f64 = 1.0 / 16.0;

fn newton_limited(
    op: &Operator,
    params: &Params,
    control: Control,
    h0: Vec<f64>,
    delta0: f64,
    limits: Limits,
    pre: &mut Preconditioner,
) -> Solution {
    let max_iter = limits.iterations;
    let mut stalled = 0;
    let tol = params.newton_tol;
    let n = op.mesh.n;
    let lambda = op.lambda;
    let sys = System::new(op, control);
    let mut h = h0;
    let mut delta = delta0;
    let mut ev = sys.eval(&h, delta);
    let mut iterations = 0;
    while ev.norm > tol && iterations < max_iter && ev.norm.is_finite() {
        crate::numerics::budget::checkpoint();
        iterations += 1;
        let rhs: Vec<f64> = ev.r.iter().map(|v| -v).collect();
        // Inexact Newton: solve to a relative accuracy that tightens with the residual.
        let lin_tol = (ev.merit * ev.merit.min(0.01)).max(1e-3 * tol);
        let d = pre.newton_step(&sys, &ev.dp, &rhs, lin_tol);
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
        stalled = if step <= STALL_STEP { stalled + 1 } else { 0 };
        if stalled >= limits.stall {
            break;
        }
    }
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
/// step multiplies it by at most `factor`, starting Newton from a secant predictor (linear
/// extrapolation in the logarithm of the parameter through the last two converged states)
/// or, if that fails or would bring a surface through the other, from the last state; a
/// failed step is retried with the square root of the factor, down to a factor of 1.001,
/// and the factor grows again (squared) after two successes in a row.
/// Returns the solution at `to` (converged or the failed last trial) and the Newton
/// iterations spent.
fn continue_geometric(
    from: f64,
    to: f64,
    mut factor: f64,
    start: Solution,
    mut step: impl FnMut(f64, &[f64], f64) -> Solution,
) -> (Solution, usize) {
    // Steps grow after successes (below), up to the square of the first factor (at most 4).
    let max_factor = (factor * factor).min(4.0).max(factor);
    let mut iterations = 0;
    let mut value = from;
    let mut last = start;
    let mut previous: Option<(f64, Vec<f64>, f64)> = None;
    let up = to > from;
    let lambda = last.params.lambda;
    // A factor that just failed is not grown again until two steps in a row succeed: at
    // large lambda, where the steps alternate with lattice trapping, growing at once made
    // every other step fail (15 Newton iterations each). Measured (release, W = 0.1, k =
    // 0.1): lambda = 24, V0 = 2.2 54 -> 49 s (3540 -> 2784 Newton iterations), V0 = 2.7
    // 34 -> 31 s; the lambda = 16 maximum 45 -> 33 s; the same mu* to every digit printed.
    let mut successes = 2;
    while value != to {
        let next = if up { (value * factor).min(to) } else { (value / factor).max(to) };
        let predicted = previous.as_ref().and_then(|(v_prev, h_prev, d_prev)| {
            let r = (next / value).ln() / (value / v_prev).ln();
            let h: Vec<f64> = last.h.iter().zip(h_prev).map(|(h1, h0)| h1 + r * (h1 - h0)).collect();
            let safe =
                h.iter().zip(&last.h).all(|(&hp, &h1)| traction::z_of(hp, lambda) > 0.3 * traction::z_of(h1, lambda));
            safe.then(|| (h, last.delta + r * (last.delta - d_prev)))
        });
        let mut trial = match &predicted {
            Some((h, d)) => step(next, h, *d),
            None => step(next, &last.h, last.delta),
        };
        iterations += trial.iterations;
        if !trial.converged && predicted.is_some() {
            trial = step(next, &last.h, last.delta);
            iterations += trial.iterations;
        }
        if trial.converged {
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
                return (trial, iterations);
            }
        }
    }
    (last, iterations)
}

/// The smallest lambda at which Newton starts (soft, long-range adhesion converges from a
/// Hertzian guess); larger lambda are reached by continuation.
const LAMBDA_START: f64 = 0.3;

/// Solves one point by continuation, under load control throughout. Newton starts at the
/// relaxed elastic problem (V = 0) with lambda0 = min(lambda, 0.3), from a Hertzian guess
/// (soft, long-range adhesion converges from it). The speed is then raised at lambda0 from
/// 1e-3 element widths to its value, and lambda last, at the final speed. The path is
/// walked with mesh sequencing (`mesh_levels`): on the coarsest mesh whose elements are
/// 1/40 of the contact, lambda is raised as far as that mesh resolves the cohesive zone
/// (`lambda_resolved`), then the solution is interpolated onto the next finer mesh and
/// lambda raised further, up to `mesh`. Measured at W = 0.1, k = 0.1, V0 = 3.4: lambda = 12
/// on n = 4000 in 0.9 s instead of 47 s (the same mu* to 1e-9), and lambda = 16 (2.4 s) and
/// 24 (2 min), which the single-mesh path did not reach, converge. If that path fails, the
/// same path on `mesh` alone, then the other order (lambda at V = 0, then the speed) on it,
/// are tried. On coarse meshes at large lambda the discrete crack front has folds (lattice
/// trapping): raising lambda at V = 0 can end next to one, where any change of speed snaps;
/// measured at lambda = 10, W = 0.1.
///
/// A tensile load (W < 0) is reached from the same point at load max(|W|, 0.1) by walking
/// down the branch by pseudo-arclength (`branch::descend_to_load`), so that the state
/// is the stable one; beyond the pull-off the result is marked not converged.
pub fn solve(params: &Params, mesh: Mesh) -> Solution {
    if params.w < 0.0 {
        let start = solve(&params.with_load(params.w.abs().max(0.1)), mesh);
        let mut s = if start.converged { super::branch::descend_to_load(&start, params.w) } else { start.clone() };
        s.params = params.clone();
        s.iterations += start.iterations;
        s.factorizations += start.factorizations;
        return s;
    }
    let mut pre = Preconditioner::default();
    let levels = mesh_levels(params, mesh);
    let mut s = solve_along(params, &levels, true, &mut pre);
    if !s.converged && levels.len() > 1 {
        // The same path on the final mesh alone.
        let first = s.iterations;
        s = solve_along(params, &[mesh], true, &mut pre);
        s.iterations += first;
    }
    if !s.converged {
        let first = s.iterations;
        s = solve_along(params, &[mesh], false, &mut pre);
        s.iterations += first;
    }
    s.factorizations = pre.factorizations;
    s
}

/// The meshes a solve walks through (mesh sequencing): `mesh` halved while the elements
/// stay below 1/40 of the contact half-width (and n >= 64), coarsest first. The
/// continuation runs on the coarse levels; each finer level starts from the interpolated
/// solution of the previous one.
fn mesh_levels(params: &Params, mesh: Mesh) -> Vec<Mesh> {
    let h_max = contact_scale(params) / 40.0;
    let mut levels = vec![mesh];
    loop {
        let last = levels[levels.len() - 1];
        let half = Mesh { n: last.n / 2, ..last };
        if half.n < 64 || 2.0 * half.a() > h_max {
            break;
        }
        levels.push(half);
    }
    levels.reverse();
    levels
}

/// The largest lambda a level's elements resolve for the continuation: cohesive zone
/// pi/(8 lambda^2) at least a quarter of an element (measured at W = 0.1, k = 0.1: lambda = 12
/// continues on elements of 0.011 and refines in 3-10 Newton iterations per level; lambda =
/// 24 on elements of 0.022 does not refine).
fn lambda_resolved(mesh: Mesh) -> f64 {
    (PI / (4.0 * mesh.a())).sqrt()
}

/// Newton on `mesh` from the linear interpolation of `coarse` (same parameters).
fn interpolated_newton(coarse: &Solution, mesh: Mesh, max_iter: usize, pre: &mut Preconditioner) -> Solution {
    let params = &coarse.params;
    let xs = &coarse.x;
    let m = xs.len();
    let h: Vec<f64> = (0..mesh.n)
        .map(|i| {
            let x = mesh.x(i);
            let j = xs.partition_point(|&xc| xc < x).clamp(1, m - 1);
            let t = ((x - xs[j - 1]) / (xs[j] - xs[j - 1])).clamp(0.0, 1.0);
            coarse.h[j - 1] + t * (coarse.h[j] - coarse.h[j - 1])
        })
        .collect();
    let op = Operator::new(mesh, params.lambda, params.k, &params.spectrum, params.v());
    newton(&op, params, Control::Load(params.w), h, coarse.delta, max_iter, pre)
}

/// Newton iterations allowed to one step of the lambda continuation before it counts as
/// failed and is retried with a smaller factor. Steps that converge take few; at large
/// lambda on the finest mesh most failures are lattice trapping, where more iterations do
/// not help. Measured (lambda = 24, W = 0.1, k = 0.1, V0 = 2.2, n = 8000): 137 s with 40,
/// 73 s with 15 or 10, the same mu* to the 6 digits printed; the lambda = 16 maximum 266 -> 248 s.
const LAMBDA_STEP_ITERATIONS: usize = 15;

/// A step of the lambda continuation also counts as failed (and is retried with a smaller
/// factor) after this many consecutive Newton iterations whose line search cut the step to
/// `STALL_STEP` or less. At large lambda a failing step does not diverge: it crawls, the
/// residual falling by about 1 % per iteration at steps of 1/64-1/128, to the iteration
/// limit (the crack front would have to jump an element, lattice trapping); converging
/// steps are damped at most once or twice in a row before their steps grow again.
/// Measured (release, W = 0.1, k = 0.1, the same mu* to every digit printed): lambda = 24,
/// V0 = 2.7 2475 -> 1838 Newton iterations, 68 -> 36 s; V0 = 2.2 2784 -> 2088, 69 -> 45 s;
/// the lambda = 16 maximum 61 -> 40 s. The Chapter 4-5 stages of `thesis.yaml` run side by
/// side, one core each: 1917 G instructions instead of 2080 G, 464 s of task time instead
/// of 540 s, every table equal to the digits `repro show` prints.
const LAMBDA_STEP_STALL: usize = 2;

fn solve_along(params: &Params, levels: &[Mesh], speed_first: bool, pre: &mut Preconditioner) -> Solution {
    let lam0 = params.lambda.min(LAMBDA_START);
    let at = |lambda: f64, v: f64| Params { lambda, ..params.clone() }.with_v(v);
    let coarsest = levels[0];
    let finest = levels[levels.len() - 1];
    let op0 = Operator::new(coarsest, lam0, params.k, &params.spectrum, 0.0);
    let (h0, d0) = initial_state(&op0, &at(lam0, 0.0));
    let first = newton(&op0, &at(lam0, 0.0), Control::Load(params.w), h0, d0, 100, pre);
    let mut iterations = first.iterations;
    let mut sol = first;
    let v_target = params.v();
    let stages: [bool; 2] = if speed_first { [true, false] } else { [false, true] };
    for speed in stages {
        if !sol.converged {
            break;
        }
        if speed {
            // On the current mesh: the coarsest (speed first) or the finest (speed last).
            let mesh = sol.mesh;
            let lambda = sol.params.lambda;
            let v_start = 1e-3 * mesh.a();
            let (s, it) = if v_target <= v_start {
                let op = Operator::new(mesh, lambda, params.k, &params.spectrum, v_target);
                let s = newton(&op, &at(lambda, v_target), Control::Load(params.w), sol.h.clone(), sol.delta, 40, pre);
                let it = s.iterations;
                (s, it)
            } else {
                continue_geometric(v_start, v_target, 4.0, sol, |v, h, delta| {
                    let op = Operator::new(mesh, lambda, params.k, &params.spectrum, v);
                    newton(&op, &at(lambda, v), Control::Load(params.w), h.to_vec(), delta, 40, pre)
                })
            };
            sol = s;
            iterations += it;
        } else {
            // Lambda, level by level: up to what each level resolves, then onto the next.
            let v = sol.params.v();
            for (i, &mesh) in levels.iter().enumerate() {
                if i > 0 {
                    sol = interpolated_newton(&sol, mesh, 40, pre);
                    iterations += sol.iterations;
                    if !sol.converged {
                        break;
                    }
                }
                let cap = if mesh == finest { params.lambda } else { params.lambda.min(lambda_resolved(mesh)) };
                let from = sol.params.lambda;
                if cap > from {
                    // Finer levels carry the stiff, large-lambda part of the path: smaller steps.
                    let factor = if i == 0 { 1.5 } else { 1.1 };
                    let kern = MeshKernel::new(mesh.n, mesh.a(), v, params.k, &params.spectrum);
                    let (s, it) = continue_geometric(from, cap, factor, sol, |lambda, h, delta| {
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
                    iterations += it;
                    if !sol.converged {
                        break;
                    }
                }
            }
        }
    }
    sol.params = params.clone();
    sol.iterations = iterations;
    sol
}

/// Newton solves along a path of equilibria of one (mesh, lambda, k, V) under
/// `Control::Path` or load control: the operator and the preconditioner are built once and
/// shared by every point of the path.
pub struct PathSolver {
    op: Operator,
    params: Params,
    pre: Preconditioner,
}

impl PathSolver {
    /// The solver at the mesh and parameters of `from` (its speed V is kept at every load).
    pub fn new(from: &Solution) -> PathSolver {
        let p = from.params.clone();
        PathSolver {
            op: Operator::new(from.mesh, p.lambda, p.k, &p.spectrum, p.v()),
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

/// Safety factors of the reported error estimate of mu* (`solve_to_tolerance`): on the
/// mesh's Richardson share, Roache's factor 3 for a grid convergence index from two grids
/// (the reported share is then |mu*(n) - mu*(n/2)|), and 2 on the domain's
/// (`domain_rel_error`). Measured (`pipelines/bench.yaml`: W = 1, k = 0.1,
/// lambda = 0.3 and 3, V0 = 0.1, 1, 10, against rel_tol 1e-5 on a 2.5 times longer
/// domain): without them the actual error of mu* was 0.4-1.45 times the estimate (the
/// largest at lambda = 3, V0 = 0.1, where the mesh sequence is not yet asymptotic at
/// rel_tol 3e-3); before the domain's share was counted, up to 7 times on the defaults and
/// 60-290 times on fixed meshes. The refinement itself still stops on the bare Richardson
/// share against rel_tol.
pub const MESH_SAFETY: f64 = 3.0;
pub const DOMAIN_SAFETY: f64 = 2.0;

/// A solution with the Richardson estimate of the discretisation error of mu*: the
/// solver converges at second order in the element size (measured: successive
/// differences shrink by 3.9 per halving), so the error of the fine solution is about
/// |mu*(n) - mu*(n/2)| / 3. When the coarse solve does not converge, the estimate is
/// |mu*| (no confidence). Reported with `MESH_SAFETY`, plus the domain's truncation,
/// |mu*| `domain_rel_error` times `DOMAIN_SAFETY`.
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

/// The solution on a finer `mesh` of the same domain, from Newton started at the linear
/// interpolation of `coarse` (mesh sequencing: the continuation path is walked on the
/// coarse mesh only); if that fails, by the full continuation on the fine mesh.
pub fn refine(coarse: &Solution, mesh: Mesh) -> Solution {
    refine_carrying(coarse, mesh, &mut None)
}

/// `refine`, with the active LU of an earlier refinement of the same domain (`carried`)
/// used as the nested preconditioner (`ActiveLu::solve_nested`) when the new mesh nests
/// in its mesh at most `MAX_NESTED_RATIO` to one, instead of a fresh LU of `coarse`; on
/// return `carried` holds the LU to carry to the next refinement.
fn refine_carrying(coarse: &Solution, mesh: Mesh, carried: &mut Option<ActiveLu>) -> Solution {
    let mut pre = Preconditioner::default();
    if mesh.n >= TWO_GRID_MIN_N && mesh.n == 2 * coarse.mesh.n && mesh.half_length == coarse.mesh.half_length {
        pre.active = carried.take().filter(|a| nested_ratio(a.n, mesh.n).is_some());
        if pre.active.is_none() {
            let p = &coarse.params;
            let op = Operator::new(coarse.mesh, p.lambda, p.k, &p.spectrum, p.v());
            let sys = System::new(&op, Control::Load(p.w));
            let ev = sys.eval(&coarse.h, coarse.delta);
            pre.active = Some(ActiveLu::new(&sys, &ev.dp, DROP));
            pre.factorizations += 1;
        }
    }
    let s = interpolated_newton(coarse, mesh, 40, &mut pre);
    if s.converged {
        *carried = pre.active;
        s
    } else {
        *carried = None;
        let mut full = solve(&coarse.params, mesh);
        full.iterations += s.iterations;
        full.factorizations += s.factorizations;
        full
    }
}

/// The two shares of the error of mu* that `solve_to_tolerance` reports, without their
/// safety factors: the mesh's (Richardson, `richardson`) and the domain's
/// (|mu*| `domain_rel_error`).
#[derive(Clone, Copy, Debug)]
pub struct ErrorShares {
    pub mesh: f64,
    pub domain: f64,
}

impl ErrorShares {
    /// The reported estimate: `MESH_SAFETY` mesh + `DOMAIN_SAFETY` domain (finite).
    pub fn reported(&self) -> f64 {
        (MESH_SAFETY * self.mesh + DOMAIN_SAFETY * self.domain).min(f64::MAX)
    }
}

/// Solves on `mesh` (by continuation on half its elements, then `refine`), then doubles
/// the number of elements (same domain) until the Richardson estimate is at most
/// `rel_tol` |mu*| or the next mesh would exceed `n_max`. Each refinement starts from
/// the previous solution and reuses it as the coarse one. `iterations` and
/// `factorizations` of the result count the whole path. The error estimate is
/// `ErrorShares::reported`.
pub fn solve_to_tolerance(params: &Params, mesh: Mesh, rel_tol: f64, n_max: usize) -> (Solution, f64) {
    let (s, shares) = solve_to_tolerance_shares(params, mesh, rel_tol, n_max);
    (s, shares.reported())
}

/// `solve_to_tolerance` with the error's two shares apart.
pub fn solve_to_tolerance_shares(params: &Params, mesh: Mesh, rel_tol: f64, n_max: usize) -> (Solution, ErrorShares) {
    let mut coarse = solve(params, Mesh { n: (mesh.n / 2).max(8), ..mesh });
    let (mut iterations, mut factorizations) = (coarse.iterations, coarse.factorizations);
    let mut carried = None;
    let mut next = |from: &Solution, n: usize| {
        let mut s = if from.converged {
            refine_carrying(from, Mesh { n, ..mesh }, &mut carried)
        } else {
            carried = None;
            solve(params, Mesh { n, ..mesh })
        };
        iterations += s.iterations;
        factorizations += s.factorizations;
        s.iterations = iterations;
        s.factorizations = factorizations;
        s
    };
    let mut fine = next(&coarse, mesh.n);
    loop {
        let estimate = richardson(&fine, &coarse);
        // Two levels in a row without a converged solution: refining will not rescue the
        // point (a load beyond pull-off walks to its fold on every mesh; doubling to n_max
        // took 300 s at W = -1.9, lambda = 3 before this stop). It is reported as is.
        let hopeless = !fine.converged && !coarse.converged;
        if hopeless || estimate <= rel_tol * fine.friction().mu_star.abs() || 2 * fine.mesh.n > n_max {
            // The domain's share, which refining the mesh does not change.
            let domain = fine.friction().mu_star.abs() * domain_rel_error(params, mesh.half_length);
            return (fine, ErrorShares { mesh: estimate, domain });
        }
        let n = 2 * fine.mesh.n;
        let finer = next(&fine, n);
        coarse = std::mem::replace(&mut fine, finer);
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
        let hertz = Params::sls(1.0, 1000.0, 0.1, 1.0).a0();
        assert!((a / hertz - 1.0).abs() < 0.03, "{a} {hertz}");
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let params = Params::sls(1.3, 0.7, 0.1, 1.0);
        let mesh = Mesh { n: 40, half_length: 4.0 };
        let op = Operator::new(mesh, params.lambda, params.k, &params.spectrum, params.v());
        let arc = Control::Path { t_approach: -0.6, t_load: 0.8, value: 0.1 };
        for control in [Control::Load(params.w), Control::approach(0.2), arc] {
            let sys = System::new(&op, control);
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
                    assert!(
                        (fd - jac[(i, j)]).abs() < 1e-4 * (1.0 + fd.abs()),
                        "{control:?} ({i},{j}): {fd} vs {}",
                        jac[(i, j)]
                    );
                }
            }
            // The matrix-free product and the preconditioner without dropping agree with it.
            let v: Vec<f64> = (0..=40).map(|i| ((i as f64) * 0.37).cos()).collect();
            let jv = sys.apply_jacobian(&ev.dp, &v);
            let exact = ActiveLu::new(&sys, &ev.dp, 0.0).solve(&jv);
            for i in 0..=40 {
                let dense: f64 = (0..=40).map(|j| jac[(i, j)] * v[j]).sum();
                assert!((dense - jv[i]).abs() < 1e-10, "{control:?} row {i}");
                assert!((exact[i] - v[i]).abs() < 1e-8, "{control:?} inverse, row {i}");
            }
        }
    }

    #[test]
    fn the_active_set_preconditioner_is_exact_without_dropping_and_close_with_it() {
        // A converged state at lambda = 3, W = 0.1: the far-field columns are tiny.
        let params = Params::sls(3.0, 0.1, 0.1, 1.0);
        let mesh = Mesh { n: 600, half_length: 6.0 };
        let s = solve(&params, mesh);
        assert!(s.converged);
        let op = Operator::new(mesh, params.lambda, params.k, &params.spectrum, params.v());
        let sys = System::new(&op, Control::Load(params.w));
        let ev = sys.eval(&s.h, s.delta);
        let rhs: Vec<f64> = (0..=mesh.n).map(|i| ((i as f64) * 0.37).sin()).collect();
        let resid = |d: &[f64]| {
            let jd = sys.apply_jacobian(&ev.dp, d);
            jd.iter().zip(&rhs).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
        };
        let exact = ActiveLu::new(&sys, &ev.dp, 0.0);
        assert_eq!(exact.idx.len(), mesh.n);
        assert!(resid(&exact.solve(&rhs)) < 1e-10);
        let dropped = ActiveLu::new(&sys, &ev.dp, DROP);
        assert!(dropped.idx.len() < mesh.n * 3 / 4, "active {} of {}", dropped.idx.len(), mesh.n);
        let r = resid(&dropped.solve(&rhs));
        assert!(r > 1e-12 && r < 1.0, "an approximate inverse: residual {r} (measured 0.62)");
        let g = gmres(|v| sys.apply_jacobian(&ev.dp, v), |v| dropped.solve(v), &rhs, 1e-10, GMRES_ITERATIONS);
        assert!(g.converged && g.iterations <= 12, "GMRES: {} iterations", g.iterations);
        assert!(resid(&g.x) < 1e-9);
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
            let params = Params::sls(0.5, 100.0, 0.1, v0);
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
        let params = Params::sls(1.0, 1.0, 0.1, 0.0);
        let mesh = Mesh { n: 200, half_length: 6.0 };
        let s = solve(&params, mesh);
        assert!(s.converged, "residual {} after {}", s.residual, s.iterations);
        assert!((s.load() - 1.0).abs() < 1e-6);
        // Elastic and symmetric: no friction.
        assert!(s.friction().mu_star.abs() < 1e-8, "{:?}", s.friction());
        let (lead, trail) = s.contact_edges().unwrap();
        assert!((lead + trail).abs() < 1e-6, "{lead} {trail}");
    }

    #[test]
    fn newton_stops_at_the_requested_tolerance() {
        // A sliding adhesive point: the default tolerance takes more iterations to a smaller
        // residual; a looser one stops as soon as the residual is under it, with mu* close and
        // the load balanced to that tolerance. How close depends on where Newton's path
        // crosses the tolerance, not only on the tolerance: measured relative errors of mu*
        // (no LU rebuild -> `REBUILD_BALANCE`): at newton_tol 1e-3 1.2e-5 -> 2.1e-4 (one
        // iteration fewer, residual 1.3e-4 -> 4.0e-4; the bench's points show up to 2.2e-4),
        // at 1e-5 1.1e-6 -> 3.8e-9. This test asserted 1e-4 at 1e-3 before the rebuild rule;
        // it now asserts 5e-4 there, and 1e-5 at 1e-5.
        let mesh = Mesh { n: 300, half_length: 6.0 };
        let tight = solve(&Params::sls(1.0, 1.0, 0.1, 1.0), mesh);
        assert!(tight.converged && tight.residual <= TOLERANCE, "{}", tight.residual);
        let a = tight.friction().mu_star;
        for (newton_tol, mu_tol) in [(1e-3, 5e-4), (1e-5, 1e-5)] {
            let loose = solve(&Params { newton_tol, ..Params::sls(1.0, 1.0, 0.1, 1.0) }, mesh);
            assert!(
                loose.converged && loose.residual <= newton_tol && loose.residual > TOLERANCE,
                "{}",
                loose.residual
            );
            assert!(loose.iterations < tight.iterations, "{} vs {}", loose.iterations, tight.iterations);
            let b = loose.friction().mu_star;
            assert!((a - b).abs() < mu_tol * a, "{a} vs {b} at newton_tol {newton_tol}");
            assert!((loose.load() - 1.0).abs() <= newton_tol, "load {}", loose.load());
        }
    }

    #[test]
    fn a_refinement_is_preconditioned_by_the_coarse_meshs_lu() {
        // From a converged coarse solution, Newton on the mesh with twice the elements runs on
        // the two-grid preconditioner: one LU (of the coarse Jacobian) in all, none of the
        // fine one, and the same equilibrium as Newton on the fine LU.
        let params = Params::sls(3.0, 0.1, 0.1, 1e-2);
        let coarse = solve(&params, Mesh { n: 1200, half_length: 6.0 });
        assert!(coarse.converged);
        let fine = Mesh { n: 2400, ..coarse.mesh };
        let two_grid = refine(&coarse, fine);
        assert!(two_grid.converged && two_grid.factorizations == 1, "{} LU", two_grid.factorizations);
        let direct = interpolated_newton(&coarse, fine, 40, &mut Preconditioner::default());
        assert!(direct.converged && direct.factorizations >= 1);
        let (a, b) = (two_grid.friction().mu_star, direct.friction().mu_star);
        assert!((a - b).abs() < 1e-9 * a.abs(), "{a} vs {b}");
        assert!((two_grid.delta - direct.delta).abs() < 1e-9, "{} vs {}", two_grid.delta, direct.delta);
    }

    #[test]
    fn a_carried_lu_preconditions_refinements_four_and_eight_times_finer() {
        // One LU of the 1000-element Jacobian serves the refinements to 2000, 4000 and 8000
        // elements (nested ratios 2, 4, 8), with no further factorisation, and each lands
        // on the equilibrium that a refinement with a fresh LU of its coarse mesh finds.
        let params = Params::sls(1.0, 0.1, 0.1, 0.3);
        let mut s = solve(&params, Mesh { n: 1000, half_length: 6.0 });
        assert!(s.converged);
        let mut carried = None;
        for (n, lus) in [(2000, 1), (4000, 0), (8000, 0)] {
            let prev = s.clone();
            s = refine_carrying(&prev, Mesh { n, ..prev.mesh }, &mut carried);
            assert!(s.converged && s.factorizations == lus, "n = {n}: {} LU", s.factorizations);
            assert_eq!(carried.as_ref().map(|a| a.n), Some(1000));
            let fresh = refine(&prev, s.mesh);
            assert!(fresh.converged && fresh.factorizations == 1);
            let (a, b) = (s.friction().mu_star, fresh.friction().mu_star);
            assert!((a - b).abs() < 1e-9 * a.abs(), "n = {n}: {a} vs {b}");
        }
        // Sixteen times finer is beyond MAX_NESTED_RATIO: the coarse level would be factored.
        assert_eq!(nested_ratio(1000, 16000), None);
        assert_eq!(nested_ratio(1000, 3000), None);
        assert_eq!(nested_ratio(1000, 8000), Some(8));
    }
}
