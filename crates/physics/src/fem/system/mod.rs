//! Global equilibrium of the axisymmetric shell model: assembly of the element forces and
//! tangents (rayon over elements), the supports (axis, clamped or roller base), and the
//! direct solve of the tangent system: the tangent is stored on a sparse pattern built once
//! per model, into which the elements' blocks are added through precomputed slots, and
//! factorised as a band (`numerics::banded`: Cholesky when the tangent is symmetric
//! positive definite, LU with partial pivoting otherwise). The dofs are numbered along the
//! meridian, so the band's half-width is that of one element's dofs (about 21).
//!
//! Unknowns: nodal displacements (u_r, u_z), dof 2a and 2a + 1 of node a, in the units of the
//! mesh (lengths) and of E (stresses); forces are then in E x length^2.

// Index loops over local dofs read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::element::{energy_of, forces_and_tangent_into, forces_of, ForcesAndTangent, Geometry, Integration};
use super::material::{Law, Material};
use super::mesh::ShellMesh;
use crate::numerics::banded::{Band, BandCholesky, BandLu};
use faer::sparse::SymbolicSparseColMat;
use rayon::prelude::*;
use std::sync::Arc;

/// A tangent stiffness with no LU factorisation (a zero pivot on the free dofs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("band LU: the tangent is singular")]
pub struct SingularTangent;

/// Where tangent entries (i, j, v) on the full dof numbering go; duplicates are summed.
/// A `Vec` collects them as triplets (the interface laws' unit tests); a `Stiffness` adds
/// them into the model's sparse matrix.
pub trait TangentSink {
    fn push(&mut self, entry: (usize, usize, f64));
}

/// Drops every entry: the interface laws' forces without their tangent.
pub struct NoTangent;

impl TangentSink for NoTangent {
    fn push(&mut self, _: (usize, usize, f64)) {}
}

impl TangentSink for Vec<(usize, usize, f64)> {
    fn push(&mut self, entry: (usize, usize, f64)) {
        Vec::push(self, entry);
    }
}

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
    pub material: Material,
    /// A dead load (nodal forces, constant in magnitude and direction) on the shell: the
    /// apex force of an imperfect shell (`apex_force`). Empty: none. Internal forces are
    /// reported net of it, and the strain energy with its potential -load . u, so that every
    /// solver sees it.
    pub dead_load: Vec<f64>,
    /// Constrained dofs (u = prescribed value there; zero for the supports).
    pub fixed: Vec<bool>,
    /// Each element's Gauss-point geometry (it depends only on the mesh).
    geometry: Vec<Geometry>,
    /// The sparsity pattern of every tangent of this model.
    pattern: Arc<Pattern>,
    /// How many LU factorisations were made (for tests and profiles).
    lu_count: std::sync::atomic::AtomicUsize,
    /// The last assembly (displacements, forces, tangent): a converged step's stability test
    /// and the next step's predictor assemble at the displacements of its last Newton
    /// evaluation again, and get the same result from here.
    last: std::sync::Mutex<Option<Assembly>>,
    /// The elements' forces and tangents of an assembly, kept for the next one: each is
    /// written whole, so the 1 MB need not be allocated and cleared every time.
    blocks: std::sync::Mutex<Vec<ForcesAndTangent>>,
}

/// Each element's Gauss-point geometry under `integration`.
fn element_geometry(mesh: &ShellMesh, integration: Integration) -> Vec<Geometry> {
    mesh.elements.iter().map(|el| Geometry::new(&std::array::from_fn(|a| mesh.nodes[el[a]]), integration)).collect()
}

/// Displacements with their internal forces and tangent.
type Assembly = (Vec<f64>, Vec<f64>, Stiffness);

/// The sparsity pattern of the free-free block of the tangent: every pair of dofs of one
/// element. The interface terms lie inside it (contact and friction couple the two dofs of
/// a node, adhesion the three outer nodes of an element's edge), so it is the same for every
/// tangent of a model; it is built once, with each element's 16 x 16 block mapped to its
/// value slots, and its band's half-width is found. The values are stored row by row (the
/// pattern is symmetric, so `symbolic`'s column lists are the rows' too): the band LU's
/// rows are then copied from contiguous values.
struct Pattern {
    /// Free numbering of the dofs (usize::MAX for fixed ones) and the number of free dofs.
    index: Vec<usize>,
    symbolic: SymbolicSparseColMat<usize>,
    /// Per element, the value slot of local entry (q, r) (u32::MAX: a fixed dof).
    slots: Vec<[u32; 256]>,
    /// The slot of the transposed entry of each slot (the pattern is symmetric).
    transposed: Vec<u32>,
    /// The slot of each free dof's diagonal entry.
    diagonal: Vec<u32>,
    /// The largest |i - j| of an entry (i, j) (free numbering).
    half_band: usize,
}

impl Pattern {
    fn new(mesh: &ShellMesh, fixed: &[bool]) -> Pattern {
        let mut index = vec![usize::MAX; fixed.len()];
        let mut m = 0;
        for (i, slot) in index.iter_mut().enumerate() {
            if !fixed[i] {
                *slot = m;
                m += 1;
            }
        }
        let local_dofs = |el: &[usize; 8]| -> [usize; 16] { std::array::from_fn(|q| 2 * el[q / 2] + q % 2) };
        let mut columns: Vec<Vec<usize>> = vec![Vec::new(); m];
        for el in &mesh.elements {
            let dofs = local_dofs(el);
            for &j in &dofs {
                if index[j] == usize::MAX {
                    continue;
                }
                columns[index[j]].extend(dofs.iter().map(|&i| index[i]).filter(|&i| i != usize::MAX));
            }
        }
        let mut col_ptr = Vec::with_capacity(m + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for col in &mut columns {
            col.sort_unstable();
            col.dedup();
            row_idx.extend_from_slice(col);
            col_ptr.push(row_idx.len());
        }
        assert!(row_idx.len() < u32::MAX as usize, "tangent pattern too large");
        let symbolic = SymbolicSparseColMat::new_checked(m, m, col_ptr, None, row_idx);
        // Every entry looked up below lies in the pattern by construction.
        let at = |row: usize, col: usize| position(&symbolic, row, col).expect("in the pattern") as u32;
        let slots = mesh
            .elements
            .iter()
            .map(|el| {
                let dofs = local_dofs(el);
                std::array::from_fn(|qr| {
                    let (i, j) = (index[dofs[qr / 16]], index[dofs[qr % 16]]);
                    if i == usize::MAX || j == usize::MAX {
                        u32::MAX
                    } else {
                        at(i, j)
                    }
                })
            })
            .collect();
        let (row_ptr, col_idx) = (symbolic.col_ptr(), symbolic.row_idx());
        // Entry (i, j) of row i has its transpose at column i of row j.
        let mut transposed = Vec::with_capacity(col_idx.len());
        for i in 0..m {
            for &j in &col_idx[row_ptr[i]..row_ptr[i + 1]] {
                transposed.push(at(j, i));
            }
        }
        let diagonal = (0..m).map(|j| at(j, j)).collect();
        let half_band =
            (0..m).flat_map(|i| col_idx[row_ptr[i]..row_ptr[i + 1]].iter().map(move |&j| j.abs_diff(i))).max();
        Pattern { index, symbolic, slots, transposed, diagonal, half_band: half_band.unwrap_or(0) }
    }

    fn n_free(&self) -> usize {
        self.symbolic.ncols()
    }

    /// The value slot of entry (i, j) of the full numbering; None for a fixed dof.
    fn slot(&self, i: usize, j: usize) -> Option<usize> {
        let (fi, fj) = (self.index[i], self.index[j]);
        if fi == usize::MAX || fj == usize::MAX {
            return None;
        }
        Some(position(&self.symbolic, fi, fj).unwrap_or_else(|| {
            panic!("tangent entry ({i}, {j}) couples dofs of no common element: outside the model's pattern")
        }))
    }
}

/// The value slot of entry (row, col) of a symmetric pattern whose values are stored row by
/// row (each row's columns sorted), if present.
fn position(pattern: &SymbolicSparseColMat<usize>, row: usize, col: usize) -> Option<usize> {
    let (row_ptr, col_idx) = (pattern.col_ptr(), pattern.row_idx());
    let cols = &col_idx[row_ptr[row]..row_ptr[row + 1]];
    cols.binary_search(&col).ok().map(|k| row_ptr[row] + k)
}

/// A tangent matrix of a model: the values of its free-free block on the model's pattern
/// (entries on fixed dofs are dropped: du = 0 there).
#[derive(Clone)]
pub struct Stiffness {
    pattern: Arc<Pattern>,
    values: Vec<f64>,
}

impl TangentSink for Stiffness {
    fn push(&mut self, (i, j, v): (usize, usize, f64)) {
        if let Some(k) = self.pattern.slot(i, j) {
            self.values[k] += v;
        }
    }
}

impl Stiffness {
    /// The Cholesky factorisation of the free-free block's lower triangle, written straight
    /// into the factor's rows (row j of U holds column j's entries on and below the
    /// diagonal) instead of through a full `Band` with the LU's room for fill (3 x the
    /// storage to clear and fill); None if it is not positive definite.
    fn lower_band_cholesky(&self) -> Option<BandCholesky> {
        let p = &self.pattern;
        let (n, kl) = (p.n_free(), p.half_band);
        let w = kl + 1;
        let mut u = vec![0.0; n * w];
        let mut end: Vec<usize> = (0..n).collect();
        let (row_ptr, col_idx) = (p.symbolic.col_ptr(), p.symbolic.row_idx());
        // Column j's entries (i, j) below the diagonal sit at the transposed slots of row
        // j's (j, i).
        for j in 0..n {
            for k in row_ptr[j]..row_ptr[j + 1] {
                let i = col_idx[k];
                if i >= j {
                    u[j * w + i - j] = self.values[p.transposed[k] as usize];
                    end[j] = end[j].max(i);
                }
            }
        }
        BandCholesky::factor(n, kl, u, end)
    }

    /// The free-free block as a band matrix, with room for the LU's fill.
    fn band(&self) -> Band {
        let p = &self.pattern;
        let hb = p.half_band;
        let (row_ptr, col_idx) = (p.symbolic.col_ptr(), p.symbolic.row_idx());
        Band::from_rows(p.n_free(), hb, hb, |i, w| {
            for k in row_ptr[i]..row_ptr[i + 1] {
                w[col_idx[k] + hb - i] = self.values[k];
            }
        })
    }

    /// The mean of the free diagonal's magnitudes (a stiffness scale).
    pub fn mean_diagonal(&self) -> f64 {
        let d = &self.pattern.diagonal;
        d.iter().map(|&k| self.values[k as usize].abs()).sum::<f64>() / d.len().max(1) as f64
    }

    /// K + shift I (on the free dofs).
    pub fn shifted(&self, shift: f64) -> Stiffness {
        let mut k = self.clone();
        for &slot in &self.pattern.diagonal {
            k.values[slot as usize] += shift;
        }
        k
    }

    /// Symmetric to rounding (no slipping friction node, whose tangent is not).
    fn is_symmetric(&self) -> bool {
        self.values.iter().zip(&self.pattern.transposed).all(|(&v, &t)| {
            let w = self.values[t as usize];
            (v - w).abs() <= 1e-12 * v.abs().max(w.abs())
        })
    }
}

impl Model {
    pub fn new(mesh: ShellMesh, e: f64, nu: f64, base: Base) -> Model {
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
        let geometry = element_geometry(&mesh, Integration::default());
        let pattern = Arc::new(Pattern::new(&mesh, &fixed));
        Model {
            mesh,
            material: Material::new(Law::NeoHookean, e, nu),
            dead_load: Vec::new(),
            fixed,
            geometry,
            pattern,
            lu_count: Default::default(),
            last: std::sync::Mutex::new(None),
            blocks: Default::default(),
        }
    }

    /// The model with another Gauss rule for its elements (`Integration::default()`, 3 x 3,
    /// unless given).
    pub fn with_integration(mut self, integration: Integration) -> Model {
        self.geometry = element_geometry(&self.mesh, integration);
        self
    }

    /// The model with another hyperelastic law (same E and nu).
    pub fn with_law(mut self, law: Law) -> Model {
        self.material.law = law;
        self
    }

    /// The model with a point force at the apex of the inner surface, of magnitude `force`
    /// (units of force, the whole ring), pointing away from the plate (towards -z): the
    /// perturbing load of commercial FE practice that lets a perfect shell leave its
    /// flattened branch. A non-positive force leaves the model as it is.
    pub fn with_apex_force(mut self, force: f64) -> Model {
        if force > 0.0 {
            let apex = self.mesh.inner_apex();
            let mut load = vec![0.0; self.n_dofs()];
            load[2 * apex + 1] = -force;
            self.dead_load = load;
        }
        self
    }

    /// Subtracts the dead load from internal forces `f`.
    fn net_of_load(&self, f: &mut [f64]) {
        f.iter_mut().zip(&self.dead_load).for_each(|(f, l)| *f -= l);
    }

    pub fn n_dofs(&self) -> usize {
        2 * self.mesh.n_nodes()
    }

    /// A zero tangent on this model's pattern.
    pub fn zero_stiffness(&self) -> Stiffness {
        Stiffness { pattern: self.pattern.clone(), values: vec![0.0; self.pattern.symbolic.row_idx().len()] }
    }

    /// Internal forces and the tangent, or None if an element is inverted.
    pub fn assemble(&self, u: &[f64]) -> Option<(Vec<f64>, Stiffness)> {
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((lu, f, k)) = last.as_ref() {
            // Bitwise the same displacements: the same forces and tangent.
            if lu.len() == u.len() && lu.iter().zip(u).all(|(a, b)| a.to_bits() == b.to_bits()) {
                return Some((f.clone(), k.clone()));
            }
        }
        let (f, k) = self.assemble_anew(u)?;
        *last = Some((u.to_vec(), f.clone(), k.clone()));
        Some((f, k))
    }

    /// `local` of every element at displacements `u`, computed in parallel, each written in
    /// place into `out` (collecting them would copy the 2 kB tangent blocks around); false
    /// if any element gives false (inverted).
    fn per_element<T: Send>(
        &self,
        u: &[f64],
        out: &mut [T],
        local: impl Fn(&Geometry, &[[f64; 2]; 8], &mut T) -> bool + Sync,
    ) -> bool {
        out.par_iter_mut()
            .zip(&self.mesh.elements)
            .zip(&self.geometry)
            .all(|((out, el), geometry)| local(geometry, &self.element_displacements(u, el), out))
    }

    /// The displacements of element `el`'s nodes.
    fn element_displacements(&self, u: &[f64], el: &[usize; 8]) -> [[f64; 2]; 8] {
        std::array::from_fn(|a| [u[2 * el[a]], u[2 * el[a] + 1]])
    }

    /// Adds element `el`'s forces into the global vector.
    fn scatter_forces(f: &mut [f64], el: &[usize; 8], fe: &[f64; 16]) {
        for q in 0..16 {
            f[2 * el[q / 2] + q % 2] += fe[q];
        }
    }

    fn assemble_anew(&self, u: &[f64]) -> Option<(Vec<f64>, Stiffness)> {
        let mut local = self.blocks.lock().unwrap_or_else(|e| e.into_inner());
        local.resize(self.mesh.elements.len(), ([0.0; 16], [[0.0; 16]; 16]));
        if !self
            .per_element(u, &mut local, |geometry, ue, out| forces_and_tangent_into(geometry, ue, self.material, out))
        {
            return None;
        }
        let mut f = vec![0.0; self.n_dofs()];
        let mut k = self.zero_stiffness();
        for ((el, slots), (fe, ke)) in self.mesh.elements.iter().zip(&self.pattern.slots).zip(local.iter()) {
            Model::scatter_forces(&mut f, el, fe);
            for q in 0..16 {
                for r in 0..16 {
                    let slot = slots[16 * q + r];
                    if slot != u32::MAX {
                        k.values[slot as usize] += ke[q][r];
                    }
                }
            }
        }
        self.net_of_load(&mut f);
        Some((f, k))
    }

    /// The internal forces alone (bitwise those of `assemble`), or None if an element is
    /// inverted: a line search's trial steps, most of them rejected, need no tangent.
    pub fn internal_forces(&self, u: &[f64]) -> Option<Vec<f64>> {
        let mut local = vec![[0.0; 16]; self.mesh.elements.len()];
        let forces = |geometry: &Geometry, ue: &[[f64; 2]; 8], out: &mut [f64; 16]| {
            forces_of(geometry, ue, self.material).map(|f| *out = f).is_some()
        };
        if !self.per_element(u, &mut local, forces) {
            return None;
        }
        let mut f = vec![0.0; self.n_dofs()];
        for (el, fe) in self.mesh.elements.iter().zip(&local) {
            Model::scatter_forces(&mut f, el, fe);
        }
        self.net_of_load(&mut f);
        Some(f)
    }

    /// The stored strain energy plus the dead load's potential -load . u (None if an
    /// element is inverted).
    pub fn strain_energy(&self, u: &[f64]) -> Option<f64> {
        let load: f64 = self.dead_load.iter().zip(u).map(|(l, u)| l * u).sum();
        let stored: Option<f64> = self
            .mesh
            .elements
            .iter()
            .zip(&self.geometry)
            .map(|(el, geometry)| energy_of(geometry, &self.element_displacements(u, el), self.material))
            .sum();
        Some(stored? - load)
    }

    /// Solves K du = rhs on the free dofs (du = 0 on the fixed ones).
    pub fn solve(&self, k: &Stiffness, rhs: &[f64]) -> Result<Vec<f64>, SingularTangent> {
        Ok(self.solve_many(k, &[rhs])?.remove(0))
    }

    /// Solves K x = b for several right-hand sides with one factorisation: Cholesky when K
    /// is symmetric and positive definite (the stable branches without slip), else LU with
    /// partial pivoting.
    pub fn solve_many(&self, k: &Stiffness, rhs: &[&[f64]]) -> Result<Vec<Vec<f64>>, SingularTangent> {
        let mut b = self.to_free(rhs);
        match self.definite(k) {
            Some(llt) => b.iter_mut().for_each(|x| llt.solve_in_place(x)),
            None => {
                let lu = self.factorize(k)?;
                b.iter_mut().for_each(|x| lu.solve_in_place(x));
            }
        }
        Ok(self.full_vectors(&b))
    }

    /// The free dofs of full-numbering vectors.
    fn to_free(&self, rhs: &[&[f64]]) -> Vec<Vec<f64>> {
        let index = &self.pattern.index;
        rhs.iter()
            .map(|col| col.iter().zip(index).filter(|(_, &j)| j != usize::MAX).map(|(&v, _)| v).collect())
            .collect()
    }

    /// Free-dof vectors as full-numbering vectors, zero on the fixed dofs.
    fn full_vectors(&self, x: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let index = &self.pattern.index;
        x.iter().map(|x| index.iter().map(|&j| if j == usize::MAX { 0.0 } else { x[j] }).collect()).collect()
    }

    /// Solves K x = b by Cholesky if K is symmetric positive definite; None otherwise.
    pub fn solve_definite(&self, k: &Stiffness, rhs: &[f64]) -> Option<Vec<f64>> {
        let mut b = self.to_free(&[rhs]);
        self.definite(k)?.solve_in_place(&mut b[0]);
        self.full_vectors(&b).pop()
    }

    /// LU factorisations made so far.
    pub fn factorizations(&self) -> usize {
        self.lu_count.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// The band LU factorisation of `k`.
    fn factorize(&self, k: &Stiffness) -> Result<BandLu, SingularTangent> {
        self.lu_count.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        k.band().lu().ok_or(SingularTangent)
    }

    /// The Cholesky factorisation of `k` if it is symmetric (to rounding) and positive
    /// definite.
    fn definite(&self, k: &Stiffness) -> Option<BandCholesky> {
        if k.is_symmetric() {
            self.cholesky(k)
        } else {
            None
        }
    }

    /// The Cholesky factorisation of the lower triangle of `k`, if it is positive definite.
    fn cholesky(&self, k: &Stiffness) -> Option<BandCholesky> {
        k.lower_band_cholesky()
    }

    /// The smallest eigenvalue of the free tangent if it is positive definite (None
    /// otherwise), by inverse iteration on its Cholesky factorisation: `iterations` solves
    /// from a fixed start. Converges fastest where it matters, near a loss of stability,
    /// where the smallest eigenvalue is far below the next.
    pub fn smallest_eigenvalue(&self, k: &Stiffness, iterations: usize) -> Option<f64> {
        let c = self.cholesky(k)?;
        let m = self.pattern.index.iter().filter(|&&j| j != usize::MAX).count();
        // A start with a part along every mode (no symmetry to miss one).
        let mut x: Vec<f64> = (0..m).map(|i| 1.0 + 0.5 * ((i as f64) * 0.618_033_988_75).fract()).collect();
        let mut mu = 0.0;
        for _ in 0..iterations.max(1) {
            let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
            x.iter_mut().for_each(|v| *v /= norm);
            let mut y = x.clone();
            c.solve_in_place(&mut y);
            mu = x.iter().zip(&y).map(|(a, b)| a * b).sum::<f64>();
            x = y;
        }
        (mu > 0.0 && mu.is_finite()).then(|| 1.0 / mu)
    }

    /// Whether the free tangent is positive definite (its Cholesky factorisation exists):
    /// the equilibrium is stable under prescribed plate displacement. A sign change of the
    /// tangent's determinant along the path shows as a change of this flag.
    pub fn is_stable(&self, k: &Stiffness) -> bool {
        self.cholesky(k).is_some()
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
mod tests;
