//! Closed-form and quadrature theories that serve as limits and references.

pub mod classical;
pub mod line_contact;
pub mod persson;
pub mod persson_brener;
