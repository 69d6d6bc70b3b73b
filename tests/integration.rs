//! The integration tests that assert no timings, in one binary (`Cargo.toml`: each test
//! binary links the whole engine). One module per concern, named as its file.

mod common;

mod adaptive;
mod architecture;
mod bem_convergence;
mod bem_elastic_limits;
mod bem_starts;
mod claims;
mod error_coverage;
mod extremes;
mod figure_texts;
mod fuzz;
mod kind_versions;
mod matched_needs;
mod pipeline_errors;
mod power_law_materials;
mod ranges_shown;
mod report;
mod rolling;
mod schema;
mod shell_imperfection;
mod shell_stages;
mod solver_properties;
mod stress;
mod thesis_pipeline;
mod verify;
