//! The four governing parameters (Eq. 4.17) with the creep function's shape, and the
//! discretisation they call for: the domain [-L, L] (wide enough for the pressure tail at
//! the load), the element count that resolves the cohesive zone, and the 2D JKR closed
//! forms that scale both.

use crate::bem::kernel::Pressure;
use crate::lennard_jones::ALPHA;
use crate::rheology::Spectrum;
use crate::theory::line_contact::jkr_half_width;
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
    /// How the pressure varies over the mesh (`Pressure::Linear` by default).
    pub pressure: Pressure,
}

impl Params {
    /// A point on the standard linear solid.
    pub fn sls(lambda: f64, w: f64, k: f64, v0: f64) -> Params {
        Params { lambda, w, k, v0, spectrum: Spectrum::sls(), newton_tol: TOLERANCE, pressure: Pressure::Linear }
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

/// The domain half-length for a requested relative accuracy: 2.5 contact half-widths
/// (JKR, or Hertz at large loads), and at least the range beyond which the Lennard-Jones
/// tail would carry less than a fraction rel_tol of max(|W|, 0.1) (what truncating changes:
/// docs/tuning.md, "BEM domain"). The tail pressure
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
pub(super) fn tail_over(p: &Params, x: f64) -> f64 {
    2.0 * 2.6 * 8.0 * p.lambda / (5.0 * (ALPHA * p.lambda).powi(3) * x)
}

/// The load the domain rule's tolerance refers to: max(|W|, 0.1).
pub(super) fn load_scale(p: &Params) -> f64 {
    p.w.abs().max(0.1)
}

/// The relative error of mu* that truncating the domain at `half_length` may cause: the
/// load the Lennard-Jones tail would carry beyond it, as a fraction of max(|W|, 0.1) (the
/// inverse of `domain_half_length`'s rule). Against domains 2.5 times longer, the reported
/// estimate covers the truncation where the domain's share dominates (docs/tuning.md, "BEM
/// domain").
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
pub(super) fn contact_scale(p: &Params) -> f64 {
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
/// refinement's difference does not bound a pull-off's error (docs/tuning.md, "BEM pull-off
/// and maxima", has the resolution study).
pub const MIN_ZONE_ELEMENTS: f64 = 1.0;

/// The default requested accuracy of mu* (relative).
pub const DEFAULT_REL_TOL: f64 = 1e-3;

/// The largest mesh a solve to tolerance refines to by default.
pub const DEFAULT_N_MAX: usize = 16_000;

/// The meshes a solve walks through (mesh sequencing): `mesh` halved while the elements
/// stay below 1/40 of the contact half-width (and n >= 64), coarsest first. The
/// continuation runs on the coarse levels; each finer level starts from the interpolated
/// solution of the previous one.
pub(super) fn mesh_levels(params: &Params, mesh: Mesh) -> Vec<Mesh> {
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

/// Tolerance of the max-norm residual (in units of H).
pub const TOLERANCE: f64 = 1e-9;

/// An upper bound of the memory a solve on `n` elements allocates, in bytes: the dense LU of
/// the near-contact block of the Jacobian (`precondition::ActiveLu`: at most n x n values of
/// 8 bytes), the nested one of the mesh before it (n/2 x n/2), and the vectors of length n
/// (GMRES's Krylov basis of `GMRES_ITERATIONS`, the FFT buffers of the Toeplitz products and
/// the fields: fewer than 100 of them).
pub fn memory_bound(n: usize) -> u64 {
    let n = n as u64;
    8 * n * n + 8 * (n / 2) * (n / 2) + 8 * 100 * n
}
