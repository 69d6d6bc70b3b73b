//! `repro`: a reproduction engine for a thesis on adhesion and friction in soft contact
//! mechanics. `pipeline` is the orchestrator (physics-free), `theory` and `numerics` are
//! the physics (free of files and YAML), `stages` binds the two.

// `!(x > 0.0)` is how the checks say "not positive, or NaN": keep it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bem;
pub mod fem;
pub mod numerics;
pub mod pipeline;
pub mod reproduction_report;
pub mod rheology;
pub mod stages;
pub mod theory;
