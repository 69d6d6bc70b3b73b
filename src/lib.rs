//! `repro`: a reproduction engine for a thesis on adhesion and friction in soft contact
//! mechanics. Three crates, one per layer: `repro-pipeline` (the orchestrator, free of
//! physics; `pipeline::` in this crate's code), `repro-physics` (the models and numerics,
//! free of files, serialisation and YAML; `physics::`), and this crate: the stage kinds
//! that bind the two ([`stages`]; the value policies every kind follows in
//! [`stages::values`]), the reproduction report and the command line. The two crates are
//! re-exported here ([`pipeline`], [`theory`], [`rheology`], [`bem`], [`fem`],
//! [`numerics`]) for the library's users, the tests and the Python package; this crate's
//! own code names them by their crates (`tests/architecture.rs`).

// `!(x > 0.0)` is how the checks say "not positive, or NaN": keep it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub use physics::{bem, fem, lennard_jones, numerics, rheology, theory};
pub use pipeline;

pub mod description;
pub mod point;
pub mod reproduction_report;
pub mod stage_graph;
pub mod stages;
