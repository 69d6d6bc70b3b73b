//! Preconditioning GMRES: a dense LU (faer) of the near-contact block of the Jacobian
//! (`ActiveLu`), rebuilt when Newton's steps lose their balance, with a two-grid variant
//! for large meshes: the LU of a coarser mesh, carried from mesh sequencing or factored
//! from the state restricted to half the elements.

use super::system::{Control, System};
use crate::numerics::gmres::{gmres, Gmres};
use crate::numerics::toeplitz::Toeplitz;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::Mat;

/// The preconditioner of GMRES: the Jacobian with the columns of the far field dropped.
/// J = I - G D + (approach column, load row), D = diag(dP/dH). Far from the contact dP/dH
/// decays like H^-4, so columns j with |dP_j/dH| (|G|_1 + load weight) below `DROP`
/// change J by at most DROP in the 1-norm; replacing them by identity columns leaves a
/// system of the active nodes only (plus the approach), factored by a dense LU (faer),
/// and an explicit update of the rest by one FFT product. It is frozen across Newton
/// iterations and continuation steps (Newton-Krylov), rebuilt when GMRES stalls.
pub(super) struct ActiveLu {
    pub(super) n: usize,
    pub(super) idx: Vec<usize>,
    pub(super) d: Vec<f64>,
    pub(super) lu: PartialPivLu<f64>,
    pub(super) g: Toeplitz,
}

pub(super) const DROP: f64 = 1.0;

impl ActiveLu {
    pub(super) fn new(sys: &System, dp: &[f64], drop: f64) -> ActiveLu {
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

    /// The active LU of the mesh with half the elements at the state restricted from
    /// `sys`'s (dP/dH averaged over each pair of elements), as a two-grid preconditioner
    /// of `sys` (`solve_two_grid`): a factorization of about an eighth of the cost of the
    /// fine mesh's own. None when the mesh does not halve.
    pub(super) fn restricted(sys: &System, dp: &[f64]) -> Option<ActiveLu> {
        let op = sys.op.coarsened()?;
        let coarse = System::new(&op, sys.control);
        let dp: Vec<f64> = dp.chunks_exact(2).map(|p| 0.5 * (p[0] + p[1])).collect();
        Some(ActiveLu::new(&coarse, &dp, DROP))
    }

    pub(super) fn solve(&self, b: &[f64]) -> Vec<f64> {
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
    pub(super) fn solve_nested(&self, b: &[f64]) -> Vec<f64> {
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
    pub(super) fn solve_two_grid(&self, b: &[f64]) -> Vec<f64> {
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
pub(super) struct Preconditioner {
    pub(super) active: Option<ActiveLu>,
    pub(super) factorizations: usize,
    /// GMRES iterations of the first Newton step solved with the current LU.
    pub(super) first: Option<usize>,
    /// GMRES iterations beyond `first` summed over the later steps.
    pub(super) excess: usize,
    /// Every mesh on its own LU, never a coarse one (the reference the two-grid
    /// preconditioners are tested against).
    pub(super) single_grid: bool,
}

/// A frozen active LU of m nodes is rebuilt for the next Newton step once its `excess`
/// GMRES iterations exceed REBUILD_BALANCE m / 3: a factorization costs about (2/3) m^3
/// flops and an iteration's triangular solves 2 m^2, so at 1 the iterations lost would have
/// paid for it by that count (the ski-rental balance, 2-competitive). The factorization is
/// blocked and the solves are memory-bound, and each iteration adds an FFT product and the
/// orthogonalisation, so the best balance is lower (0.1-0.3 are equally good on the BEM
/// stages of `thesis.yaml`: docs/tuning.md). The counts, not times, decide: deterministic.
pub(super) const REBUILD_BALANCE: f64 = 0.2;

/// The fewest elements of a mesh for which a coarse mesh's LU is tried (nested) before a
/// fresh active LU of its own, whose cost grows as the cube of the active nodes. Below
/// about 500 elements the LU is cheap and the extra GMRES iterations are not; above, a
/// solve's own LUs dominate its time (docs/tuning.md).
pub(super) const TWO_GRID_MIN_N: usize = 500;

/// The largest ratio of fine to coarse elements at which a coarse LU is used as a nested
/// preconditioner (`ActiveLu::solve_nested`): `solve_to_tolerance` carries the LU of its
/// first refinement through the next ones instead of factoring each coarse level anew.
/// GMRES converges in 1-5 iterations up to r = 32 on the refinements of `thesis.yaml`
/// (docs/tuning.md); a carried LU that stalls is replaced by a fresh one of the state
/// restricted to half the elements (`ActiveLu::restricted`).
pub(super) const MAX_NESTED_RATIO: usize = 64;

/// r = fine / coarse when the fine mesh nests r = 2, 4, ... `MAX_NESTED_RATIO` elements in
/// each coarse one.
pub(super) fn nested_ratio(coarse: usize, fine: usize) -> Option<usize> {
    (fine > coarse && fine.is_multiple_of(coarse))
        .then(|| fine / coarse)
        .filter(|r| r.is_power_of_two() && *r <= MAX_NESTED_RATIO)
}

pub(super) const GMRES_ITERATIONS: usize = 30;

pub(super) fn lu_solve(lu: &PartialPivLu<f64>, v: &[f64]) -> Vec<f64> {
    let m = lu.solve(Mat::<f64>::from_fn(v.len(), 1, |i, _| v[i]));
    (0..v.len()).map(|i| m[(i, 0)]).collect()
}

impl Preconditioner {
    /// The Newton step J d = rhs to `tol`: GMRES with the frozen preconditioner; if it
    /// stalls, again with a fresh one; if that stalls too, an exact LU of the whole J. On
    /// meshes of at least `TWO_GRID_MIN_N` elements the preconditioner is first a coarse
    /// mesh's LU (nested): the one carried or, when that stalls or has cost more than a
    /// factorization, a fresh one of the state restricted to half the elements
    /// (`ActiveLu::restricted`); where that does not converge either, the mesh gets its own.
    pub(super) fn newton_step(&mut self, sys: &System, dp: &[f64], rhs: &[f64], tol: f64) -> Vec<f64> {
        let apply = |v: &[f64]| sys.apply_jacobian(dp, v);
        let n = sys.op.mesh.n;
        let own = self.active.as_ref().is_some_and(|a| a.n == n);
        if n >= TWO_GRID_MIN_N && !own && !self.single_grid {
            let mut rebuilt = false;
            for fresh in [false, true] {
                let stale = self.stale(|a| nested_ratio(a.n, n).is_none());
                if (fresh || stale) && !rebuilt {
                    let Some(coarse) = ActiveLu::restricted(sys, dp) else { break };
                    self.install(coarse);
                    rebuilt = true;
                } else if fresh {
                    break;
                }
                let coarse = self.active.as_ref().unwrap();
                if let Some(x) = self.settle(gmres(apply, |v| coarse.solve_nested(v), rhs, tol, GMRES_ITERATIONS)) {
                    return x;
                }
            }
            // Not good enough here: this mesh gets its own LU from now on.
            self.active = None;
        }
        for fresh in [false, true] {
            // A preconditioner from another mesh (mesh sequencing), or one whose extra
            // iterations have outweighed a factorization, is rebuilt.
            if fresh || self.stale(|a| a.n != n) {
                self.install(ActiveLu::new(sys, dp, DROP));
            }
            let pre = self.active.as_ref().unwrap();
            if let Some(x) = self.settle(gmres(apply, |v| pre.solve(v), rhs, tol, GMRES_ITERATIONS)) {
                return x;
            }
        }
        self.install(ActiveLu::new(sys, dp, 0.0));
        self.active.as_ref().unwrap().solve(rhs)
    }

    /// No LU, one that `other` rules out (another mesh), or one whose extra GMRES iterations
    /// have outweighed a factorization (`REBUILD_BALANCE`).
    fn stale(&self, other: impl Fn(&ActiveLu) -> bool) -> bool {
        self.active.as_ref().is_none_or(|a| other(a) || self.excess as f64 > REBUILD_BALANCE * a.idx.len() as f64 / 3.0)
    }

    /// A fresh LU in use, its counts started.
    fn install(&mut self, lu: ActiveLu) {
        self.active = Some(lu);
        self.factorizations += 1;
        (self.first, self.excess) = (None, 0);
    }

    /// A converged GMRES solve's step, its iterations counted against the current LU's
    /// first; None if it stalled.
    fn settle(&mut self, g: Gmres) -> Option<Vec<f64>> {
        if !g.converged {
            return None;
        }
        let first = *self.first.get_or_insert(g.iterations);
        self.excess += g.iterations.saturating_sub(first);
        Some(g.x)
    }
}
