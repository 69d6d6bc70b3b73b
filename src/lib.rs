//! `repro`: a reproduction engine for a thesis on adhesion and friction in soft contact
//! mechanics. `pipeline` is the orchestrator (physics-free), `theory` and `numerics` are
//! the physics (free of files and YAML), `stages` binds the two.

pub mod numerics;
pub mod pipeline;
pub mod stages;
pub mod theory;
