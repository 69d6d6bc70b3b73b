//! Boundary element model of a rigid cylinder sliding on an adhesive standard-linear-solid
//! half-plane (thesis Chapter 4).

pub mod expint;
pub mod kernel;
pub mod maxima;
pub mod solver;
