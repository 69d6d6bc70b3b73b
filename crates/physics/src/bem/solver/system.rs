//! The nonlinear system of one point: the compliance operator (Eq. 4.12, Toeplitz, applied
//! by FFT), the control (load or approach), and the residual of Eq. 4.7 with the load
//! equation, evaluated with its Jacobian's near-contact block.

use super::super::kernel::{MeshKernel, Pressure};
use super::params::Mesh;
use crate::lennard_jones;
use crate::numerics::toeplitz::Toeplitz;
use crate::rheology::Spectrum;
use std::f64::consts::PI;

/// The discretised operator for one (mesh, lambda, k, V).
pub(super) struct Operator {
    pub(super) mesh: Mesh,
    pub(super) lambda: f64,
    /// Node-to-node Toeplitz coefficients, times 2 lambda/pi.
    pub(super) nodes: Vec<f64>,
    /// The same as an FFT-based product (O(n log n)).
    pub(super) nodes_fft: Toeplitz,
    /// Node-to-edge coefficients (edge e, element m: diagonal e - m + n - 1), times
    /// 2 lambda/pi.
    pub(super) edges: Vec<f64>,
    /// The same as an FFT-based product.
    pub(super) edges_fft: Toeplitz,
}

impl Operator {
    pub(super) fn new(mesh: Mesh, lambda: f64, k: f64, spectrum: &Spectrum, v: f64, pressure: Pressure) -> Operator {
        Operator::scaled(mesh, &MeshKernel::new(mesh.n, mesh.a(), v, k, spectrum, pressure), lambda)
    }

    /// The operator at `lambda` from the kernel of its mesh and speed (which lambda only
    /// scales: a lambda continuation builds the kernel once).
    pub(super) fn scaled(mesh: Mesh, kern: &MeshKernel, lambda: f64) -> Operator {
        let n = mesh.n;
        let s = 2.0 * lambda / PI;
        let nodes: Vec<f64> = kern.nodes.iter().map(|c| c * s).collect();
        // Edge e sits at X_0 - A + 2A e; offset from element m: 2A (e - m) - A.
        let edges: Vec<f64> = kern.edges.iter().map(|c| c * s).collect();
        let nodes_fft = Toeplitz::new(&nodes, n, n);
        let edges_fft = Toeplitz::new(&edges, n, n + 1);
        Operator { mesh, lambda, nodes, nodes_fft, edges, edges_fft }
    }

    /// An operator of the mesh with half the elements (coarse element i = fine elements
    /// 2i and 2i + 1), when n is even, from this one's coefficients and without evaluating
    /// the kernel again: a coarse node's pressure acts as the same value at the two fine
    /// nodes of its element (Eq. 4.12 is linear in the pressure), observed at the fine edge
    /// between them (the coarse node) and at every other fine edge (the coarse edges). Not
    /// `Operator::new` on the coarse mesh (whose hats are twice as wide; the two differ in
    /// the near field by up to 5 % of the self-influence): a preconditioner's
    /// (`ActiveLu::restricted`).
    pub(super) fn coarsened(&self) -> Option<Operator> {
        let n = self.mesh.n;
        if n % 2 == 1 || n < 4 {
            return None;
        }
        let nc = n / 2;
        let mesh = Mesh { n: nc, ..self.mesh };
        // Fine edge e from fine element m: edges[e - m + n - 1].
        let pair = |e: usize, j: usize| self.edges[e + n - 1 - 2 * j] + self.edges[e + n - 2 - 2 * j];
        // Coarse diagonal k = I - J + nc - 1 (I: coarse node = fine edge 2I + 1): take J = nc - 1.
        let nodes: Vec<f64> = (0..2 * nc - 1).map(|k| pair(2 * k + 1, nc - 1)).collect();
        // Coarse edge E (fine edge 2E) from coarse element J: diagonal E - J + nc - 1.
        let edges: Vec<f64> = (0..2 * nc).map(|k| pair(2 * k, nc - 1)).collect();
        let nodes_fft = Toeplitz::new(&nodes, nc, nc);
        let edges_fft = Toeplitz::new(&edges, nc, nc + 1);
        Some(Operator { mesh, lambda: self.lambda, nodes, nodes_fft, edges, edges_fft })
    }

    pub(super) fn displacement(&self, p: &[f64]) -> Vec<f64> {
        self.nodes_fft.apply(p)
    }

    pub(super) fn edge_displacement(&self, p: &[f64]) -> Vec<f64> {
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
pub(super) struct System<'a> {
    pub(super) op: &'a Operator,
    pub(super) x: Vec<f64>,
    pub(super) control: Control,
    /// The load equation is divided by the domain length so that it reads in H-like units.
    pub(super) load_scale: f64,
}

pub(super) struct Evaluation {
    pub(super) p: Vec<f64>,
    pub(super) dp: Vec<f64>,
    pub(super) r: Vec<f64>,
    /// Max norm (the convergence test) and Euclidean norm (the line-search merit).
    pub(super) norm: f64,
    pub(super) merit: f64,
}

impl<'a> System<'a> {
    pub(super) fn new(op: &'a Operator, control: Control) -> Self {
        let x = (0..op.mesh.n).map(|i| op.mesh.x(i)).collect();
        System { op, x, control, load_scale: 1.0 / (2.0 * op.mesh.half_length) }
    }

    /// The coefficient of dP_j/dH_j in the last row: the load weight, or minus the mean
    /// influence of element j on the two edge nodes (path control: approach and load).
    pub(super) fn edge_row(&self, j: usize) -> f64 {
        let n = self.op.mesh.n;
        match self.control {
            Control::Load(_) => 2.0 * self.op.mesh.a() * self.load_scale,
            Control::Path { t_approach, t_load, .. } => {
                -0.5 * t_approach * (self.op.nodes[n - 1 - j] + self.op.nodes[2 * n - 2 - j])
                    + t_load * self.op.lambda * 2.0 * self.op.mesh.a()
            }
        }
    }

    pub(super) fn eval(&self, h: &[f64], delta: f64) -> Evaluation {
        let n = self.op.mesh.n;
        let (p, dp): (Vec<f64>, Vec<f64>) = h.iter().map(|&hi| lennard_jones::pressure(hi, self.op.lambda)).unzip();
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
    pub(super) fn apply_jacobian(&self, dp: &[f64], v: &[f64]) -> Vec<f64> {
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
    pub(super) fn jacobian(&self, dp: &[f64]) -> faer::Mat<f64> {
        let n = self.op.mesh.n;
        let mut jac = faer::Mat::<f64>::zeros(n + 1, n + 1);
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
