//! A solved point: pressures, gaps and displacements on the mesh, how Newton ended, and the
//! friction (Eq. 4.16 with the prefactor of ERRATA 3, the midpoint rule of Int P dU over
//! the elements), split into its adhesive and compressive parts.

use super::params::{Mesh, Params};
use crate::lennard_jones::ALPHA;
use std::f64::consts::PI;

/// A state to start Newton from: the gap H at the nodes X and the approach Delta of a
/// converged solution of the same lambda, W and k (at another speed), interpolated onto the
/// mesh to be solved (`refinement::solve_to_tolerance_from`).
#[derive(Clone, Debug, PartialEq)]
pub struct Start {
    pub x: Vec<f64>,
    pub h: Vec<f64>,
    pub delta: f64,
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
    /// Why the solver stopped (`converged` derives from it).
    pub termination: Termination,
    /// What reaching it cost over the whole path, the fallbacks tried before included.
    pub cost: Cost,
    pub residual: f64,
}

/// What a solve cost: the Newton solves run, their iterations, and the LU factorisations
/// of the Jacobian (the rest of the linear solves are GMRES). A path or a fallback adds the
/// cost of each solve it runs (`+=`), so a result carries all that was spent to reach it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Cost {
    pub newton_solves: usize,
    pub iterations: usize,
    pub factorizations: usize,
}

impl std::ops::AddAssign for Cost {
    fn add_assign(&mut self, other: Cost) {
        self.newton_solves += other.newton_solves;
        self.iterations += other.iterations;
        self.factorizations += other.factorizations;
    }
}

impl std::ops::Add for Cost {
    type Output = Cost;
    fn add(mut self, other: Cost) -> Cost {
        self += other;
        self
    }
}

impl std::iter::Sum for Cost {
    fn sum<I: Iterator<Item = Cost>>(costs: I) -> Cost {
        costs.fold(Cost::default(), |a, b| a + b)
    }
}

/// Why the solver of a point stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Termination {
    /// The max-norm residual met Newton's tolerance.
    Converged,
    /// Newton's iteration limit was reached first.
    IterationLimit,
    /// Several line searches in a row cut the step to `STALL_STEP` or less (a fold of the
    /// load-controlled path, or a lattice-trapped crack front).
    Stalled,
    /// No step along the Newton direction lowered the residual (30 halvings).
    StepTooSmall,
    /// The residual or the Newton direction stopped being finite.
    Diverged,
    /// The state reached under load control left the stable branch, and the path search
    /// for it failed.
    OffBranch,
    /// The load is beyond the pull-off: the stable branch has no state there.
    BeyondPullOff,
}

impl Termination {
    /// Its name in tables: `converged`, `iteration_limit`, ...
    pub fn name(self) -> &'static str {
        match self {
            Termination::Converged => "converged",
            Termination::IterationLimit => "iteration_limit",
            Termination::Stalled => "stalled",
            Termination::StepTooSmall => "step_too_small",
            Termination::Diverged => "diverged",
            Termination::OffBranch => "off_branch",
            Termination::BeyondPullOff => "beyond_pull_off",
        }
    }
}

/// Friction and its parts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    pub mu_star: f64,
    pub mu_adh: f64,
    pub mu_comp: f64,
}

impl Solution {
    /// Whether the solver met its tolerance: the termination is `Converged`.
    pub fn converged(&self) -> bool {
        self.termination == Termination::Converged
    }

    /// Its state as a start for another solve (`Start`); None unless converged.
    pub fn start(&self) -> Option<Start> {
        self.converged().then(|| Start { x: self.x.clone(), h: self.h.clone(), delta: self.delta })
    }

    /// Marks the solution as stopped for `why` (not converged unless `why` is `Converged`).
    pub fn stop(&mut self, why: Termination) {
        self.termination = why;
    }

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
