//! The physics of `repro`: the models of a thesis on adhesion and friction in soft contact
//! mechanics and the numerics they rest on. Plain functions on plain types: no files,
//! serialisation, YAML or caches (the `repro` crate binds these functions to pipeline
//! stages).
//!
//! - [`theory`]: closed-form and quadrature theories (Hertz, JKR, DMT, Maugis-Dugdale,
//!   Persson, Persson-Brener; Chapter 2, Chapter 5, Appendix A).
//! - [`rheology`]: viscoelastic materials (standard linear solid, power-law spectra,
//!   Prony series).
//! - [`bem`]: the boundary element model of a cylinder sliding on an adhesive viscoelastic
//!   half-plane (Chapters 4-5).
//! - [`fem`]: the axisymmetric hyperelastic shell pressed by an adhesive, frictional plate
//!   (Chapter 3).
//! - [`lennard_jones`]: the 3-9 interface law both models use.
//! - [`numerics`]: quadrature, root finding, GMRES, banded and Toeplitz solvers, fits, and
//!   the time budget the long solvers check.

// `!(x > 0.0)` is how the checks say "not positive, or NaN": keep it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bem;
pub mod fem;
pub mod lennard_jones;
pub mod numerics;
pub mod rheology;
pub mod theory;
