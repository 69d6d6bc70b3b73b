//! Finite element model of a thin hemispherical shell pressed by a rigid plate (thesis
//! Chapter 3): axisymmetric 8-node solid elements, geometrically nonlinear.

pub mod contact;
pub mod element;
pub mod indent;
pub mod mesh;
pub mod system;
