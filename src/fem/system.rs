//! Global equilibrium of the axisymmetric shell model: assembly of the element forces and
//! tangents (rayon over elements), the supports (axis, clamped or roller base), and the
//! sparse direct solve of the tangent system (faer's sparse LU).
//!
//! Unknowns: nodal displacements (u_r, u_z), dof 2a and 2a + 1 of node a, in the units of the
//! mesh (lengths) and of E (stresses); forces are then in E x length^2.

// Index loops over local dofs read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::element::{forces_and_tangent, lame};
use super::mesh::ShellMesh;
use anyhow::{anyhow, Result};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;
use rayon::prelude::*;

/// A sparse matrix as (row, column, value) entries; duplicates are summed.
pub type Triplets = Vec<(usize, usize, f64)>;

/// Support of the shell's base (the equator section, z = 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Base {
    /// Bonded to a base plate (the experiments): u_r = u_z = 0.
    Clamped,
    /// Free to slide radially on the base: u_z = 0.
    Roller,
}

/// A hyperelastic shell section with its supports.
pub struct Model {
    pub mesh: ShellMesh,
    pub mu: f64,
    pub lambda: f64,
    /// Constrained dofs (u = prescribed value there; zero for the supports).
    pub fixed: Vec<bool>,
    /// The symbolic LU factorisation of the last tangent's sparsity pattern, reused while
    /// the pattern stays the same (it does along a Newton solve: contact, friction and
    /// adhesion add entries only inside the elements' blocks).
    symbolic: std::sync::Mutex<Option<Pattern>>,
    /// How many symbolic / numeric LU factorisations were made (for tests and profiles).
    counts: [std::sync::atomic::AtomicUsize; 2],
}

/// A sparsity pattern (column pointers, row indices) and its symbolic LU factorisation.
struct Pattern {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    lu: SymbolicLu<usize>,
}

impl Model {
    pub fn new(mesh: ShellMesh, e: f64, nu: f64, base: Base) -> Model {
        let (mu, lambda) = lame(e, nu);
        let mut fixed = vec![false; 2 * mesh.n_nodes()];
        for &a in &mesh.axis {
            fixed[2 * a] = true;
        }
        for &a in &mesh.base {
            fixed[2 * a + 1] = true;
            if base == Base::Clamped {
                fixed[2 * a] = true;
            }
        }
        Model { mesh, mu, lambda, fixed, symbolic: std::sync::Mutex::new(None), counts: Default::default() }
    }

    pub fn n_dofs(&self) -> usize {
        2 * self.mesh.n_nodes()
    }

    /// Internal forces and the tangent as triplets (duplicates to be summed), or None if an
    /// element is inverted.
    pub fn assemble(&self, u: &[f64]) -> Option<(Vec<f64>, Triplets)> {
        let local: Option<Vec<_>> = self
            .mesh
            .elements
            .par_iter()
            .map(|el| {
                let x: [[f64; 2]; 8] = std::array::from_fn(|a| self.mesh.nodes[el[a]]);
                let ue: [[f64; 2]; 8] = std::array::from_fn(|a| [u[2 * el[a]], u[2 * el[a] + 1]]);
                forces_and_tangent(&x, &ue, self.mu, self.lambda).map(|fk| (el, fk))
            })
            .collect();
        let local = local?;
        let mut f = vec![0.0; self.n_dofs()];
        let mut triplets = Vec::with_capacity(local.len() * 256);
        for (el, (fe, ke)) in local {
            let dof = |q: usize| 2 * el[q / 2] + q % 2;
            for q in 0..16 {
                f[dof(q)] += fe[q];
                for r in 0..16 {
                    triplets.push((dof(q), dof(r), ke[q][r]));
                }
            }
        }
        Some((f, triplets))
    }

    /// The stored strain energy (None if an element is inverted).
    pub fn strain_energy(&self, u: &[f64]) -> Option<f64> {
        self.mesh
            .elements
            .iter()
            .map(|el| {
                let x: [[f64; 2]; 8] = std::array::from_fn(|a| self.mesh.nodes[el[a]]);
                let ue: [[f64; 2]; 8] = std::array::from_fn(|a| [u[2 * el[a]], u[2 * el[a] + 1]]);
                super::element::energy(&x, &ue, self.mu, self.lambda)
            })
            .sum()
    }

    /// Numbering of the free dofs (usize::MAX for fixed ones) and their count.
    fn free_index(&self) -> (Vec<usize>, usize) {
        let mut index = vec![usize::MAX; self.n_dofs()];
        let mut m = 0;
        for (i, slot) in index.iter_mut().enumerate() {
            if !self.fixed[i] {
                *slot = m;
                m += 1;
            }
        }
        (index, m)
    }

    /// The free-free block of a matrix given as triplets.
    fn free_matrix(
        &self,
        triplets: &[(usize, usize, f64)],
        index: &[usize],
        m: usize,
    ) -> Result<SparseColMat<usize, f64>> {
        let entries: Vec<Triplet<usize, usize, f64>> = triplets
            .iter()
            .filter(|&&(i, j, _)| index[i] != usize::MAX && index[j] != usize::MAX)
            .map(|&(i, j, v)| Triplet::new(index[i], index[j], v))
            .collect();
        SparseColMat::<usize, f64>::try_new_from_triplets(m, m, &entries).map_err(|e| anyhow!("sparse tangent: {e:?}"))
    }

    /// Solves K du = rhs on the free dofs (du = 0 on the fixed ones), K given as triplets.
    pub fn solve(&self, triplets: &[(usize, usize, f64)], rhs: &[f64]) -> Result<Vec<f64>> {
        Ok(self.solve_many(triplets, &[rhs])?.remove(0))
    }

    /// Solves K x = b for several right-hand sides with one factorisation.
    pub fn solve_many(&self, triplets: &[(usize, usize, f64)], rhs: &[&[f64]]) -> Result<Vec<Vec<f64>>> {
        let (index, m) = self.free_index();
        let k = self.free_matrix(triplets, &index, m)?;
        let lu = self.factorize(&k)?;
        let mut b = Mat::<f64>::zeros(m, rhs.len());
        for (c, col) in rhs.iter().enumerate() {
            for (i, &j) in index.iter().enumerate() {
                if j != usize::MAX {
                    b[(j, c)] = col[i];
                }
            }
        }
        let x = lu.solve(&b);
        Ok((0..rhs.len())
            .map(|c| index.iter().map(|&j| if j == usize::MAX { 0.0 } else { x[(j, c)] }).collect())
            .collect())
    }

    /// (symbolic, numeric) LU factorisations made so far.
    pub fn factorizations(&self) -> (usize, usize) {
        use std::sync::atomic::Ordering::Relaxed;
        (self.counts[0].load(Relaxed), self.counts[1].load(Relaxed))
    }

    /// The LU factorisation of `k`, reusing the symbolic factorisation of the previous
    /// matrix when the sparsity pattern is the same.
    fn factorize(&self, k: &SparseColMat<usize, f64>) -> Result<Lu<usize, f64>> {
        let sym = k.symbolic();
        let mut cached = self.symbolic.lock().unwrap_or_else(|e| e.into_inner());
        let same = cached.as_ref().is_some_and(|p| p.col_ptr == sym.col_ptr() && p.row_idx == sym.row_idx());
        use std::sync::atomic::Ordering::Relaxed;
        self.counts[1].fetch_add(1, Relaxed);
        if !same {
            self.counts[0].fetch_add(1, Relaxed);
            let lu = SymbolicLu::try_new(sym).map_err(|e| anyhow!("sparse LU (symbolic): {e:?}"))?;
            *cached = Some(Pattern { col_ptr: sym.col_ptr().to_vec(), row_idx: sym.row_idx().to_vec(), lu });
        }
        let symbolic = cached.as_ref().expect("set above").lu.clone();
        drop(cached);
        Lu::try_new_with_symbolic(symbolic, k.as_ref()).map_err(|e| anyhow!("sparse LU: {e:?}"))
    }

    /// Whether the free tangent is positive definite (its Cholesky factorisation exists):
    /// the equilibrium is stable under prescribed plate displacement. A sign change of the
    /// tangent's determinant along the path shows as a change of this flag.
    pub fn is_stable(&self, triplets: &[(usize, usize, f64)]) -> bool {
        let (index, m) = self.free_index();
        match self.free_matrix(triplets, &index, m) {
            Ok(k) => k.sp_cholesky(faer::Side::Lower).is_ok(),
            Err(_) => false,
        }
    }
}

/// Consistent nodal forces of a vertical (dead) pressure `p(r)` acting downward on the
/// outer surface, per unit projected area: F_z = -Int N p 2 pi r dr along each outer edge.
pub fn outer_pressure_forces(mesh: &ShellMesh, p: impl Fn(f64) -> f64) -> Vec<f64> {
    let mut f = vec![0.0; 2 * mesh.n_nodes()];
    for q in mesh.outer_edge_points() {
        let load = p(q.r) * 2.0 * std::f64::consts::PI * q.r * q.dr * q.weight;
        for k in 0..3 {
            f[2 * mesh.outer[q.outer[k]] + 1] -= q.shape[k] * load;
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Linear response (one Newton step from the reference state) to a downward load on the
    /// outer surface within r <= c ~ h, much less than the bending length sqrt(R h): the
    /// apex stiffness F / delta (delta of the mid-surface) over Reissner's shallow-shell
    /// point-load value 4 E h^2 / (R sqrt(3 (1 - nu^2))), R the mid-surface radius.
    fn reissner_ratio(h: f64, n_meridian: usize, grading: f64) -> f64 {
        let (e, nu, r) = (1.3, 0.45, 1.0);
        let mesh = ShellMesh::hemisphere(r, h, n_meridian, 4, grading);
        let idx = mesh.outer.iter().position(|&a| mesh.nodes[a][0] >= h).unwrap();
        let c = mesh.nodes[mesh.outer[idx + idx % 2]][0]; // an element corner
        let model = Model::new(mesh, e, nu, Base::Clamped);
        let f_ext = outer_pressure_forces(&model.mesh, |rr| if rr <= c { 1.0 } else { 0.0 });
        let total: f64 = -f_ext.iter().skip(1).step_by(2).sum::<f64>();
        assert!((total / (std::f64::consts::PI * c * c) - 1.0).abs() < 1e-3, "{total}");
        let (_, k) = model.assemble(&vec![0.0; model.n_dofs()]).unwrap();
        let du = model.solve(&k, &f_ext).unwrap();
        let mid = model.mesh.axis[model.mesh.axis.len() / 2];
        let delta = -du[2 * mid + 1];
        total / delta / (4.0 * e * h * h / ((r + 0.5 * h) * (3.0 * (1.0 - nu * nu)).sqrt()))
    }

    #[test]
    fn thin_shell_apex_stiffness_tends_to_reissners() {
        // Measured (c ~ h): 0.964, 0.980, 0.987 at h/R = 0.02, 0.01, 0.005, the same to 3
        // digits with twice the elements along the meridian or through the thickness; the
        // ratio grows with c/h (1.02 at c = 2h, 1.13 at 4h for h/R = 0.01): a load spread
        // over a cap is no longer a point load.
        let (r1, r2) = (reissner_ratio(0.01, 120, 40.0), reissner_ratio(0.005, 200, 60.0));
        assert!((r1 - 1.0).abs() < 0.025 && (r2 - 1.0).abs() < 0.015, "{r1} {r2}");
        assert!((r2 - 1.0).abs() < 0.75 * (r1 - 1.0).abs(), "not converging to the thin limit: {r1} {r2}");
    }

    #[test]
    fn the_symbolic_factorisation_is_reused_along_a_load_path() {
        // Pressing the shell into contact (12 load steps, many Newton iterations, contact
        // status changing) keeps one sparsity pattern: one symbolic factorisation in all.
        let (e, r) = (1.3, 15.0);
        let model = Model::new(ShellMesh::hemisphere(r, 1.0, 40, 2, 3.0), e, 0.45, Base::Clamped);
        let plate = crate::fem::contact::Plate::new(&model.mesh, e, 1000.0).with_friction(0.5);
        let path = crate::fem::indent::load_path(&model, &plate, e, 0.12 * r, 12, 4);
        assert!(path.iter().all(|s| s.converged) && path.last().unwrap().contact.force > 0.0);
        let (symbolic, numeric) = model.factorizations();
        assert_eq!(symbolic, 1, "{numeric} numeric factorisations");
        assert!(numeric > 24, "{numeric}");
    }
}
