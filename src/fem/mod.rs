//! Finite element model of a thin hemispherical shell pressed by a rigid plate (thesis
//! Chapter 3): axisymmetric 8-node solid elements, geometrically nonlinear.

pub mod adhesion;
pub mod arclength;
pub mod contact;
pub mod critical;
pub mod cycle;
pub mod element;
pub mod indent;
pub mod material;
pub mod mesh;
pub mod stability;
pub mod system;
