//! `repro`: a reproduction engine for a thesis on adhesion and friction in soft contact
//! mechanics. Three crates, one per layer: `repro-pipeline` (the orchestrator, free of
//! physics, re-exported as [`pipeline`]), `repro-physics` (the models and numerics, free of
//! files, serialisation and YAML, re-exported as [`theory`], [`rheology`], [`bem`], [`fem`]
//! and [`numerics`]), and this crate: the stage kinds that bind the two ([`stages`]), the
//! reproduction report and the command line.

// `!(x > 0.0)` is how the checks say "not positive, or NaN": keep it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub use physics::{bem, fem, lennard_jones, numerics, rheology, theory};
pub use pipeline;

pub mod description;
pub mod point;
pub mod reproduction_report;
pub mod stages;
