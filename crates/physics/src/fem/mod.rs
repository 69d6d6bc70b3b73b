//! Finite element model of a thin hemispherical shell pressed by a rigid plate (thesis
//! Chapter 3): axisymmetric 8-node solid elements, geometrically nonlinear.
//!
//! Model: a hemispherical shell of inner radius R and thickness h (`mesh`), clamped at its
//! equator, of a hyperelastic material with Young's modulus E and Poisson's ratio nu
//! (`material`: neo-Hookean, St Venant-Kirchhoff or Hencky), pressed by a rigid plate under
//! prescribed displacement delta through penalty contact, with Lennard-Jones adhesion
//! (Eq. 3.3) and Coulomb friction (`contact`, `adhesion`). An explicit imperfection makes
//! the snap-through a property of the structure: a point force at the inner apex pointing
//! away from the plate (`system::Model::with_apex_force`) or a Gaussian dimple of the
//! reference shape (`mesh::ShellMesh::with_dimple`). The snap is then the limit point of the
//! imperfect shell's path under prescribed delta (`stability::Criterion::Tangent`), located
//! by bisection and followed by the jump to the inverted branch (`cycle`).
//!
//! Nondimensionalisation: forces in F_c = E h^3 / R (the thesis' F R / (E h^3)),
//! displacements in R (delta / R), pressures in E, energies in E h^3; adhesion as
//! gamma / (E h) (Section 3.4, Eq. 3.7). Thesis equations: 3.1-3.2 (the shell and plate),
//! 3.3 (the Lennard-Jones law), 3.7 (the estimate of gamma_c).

pub mod adhesion;
pub mod arclength;
pub mod contact;
pub mod critical;
pub mod cycle;
pub mod element;
pub mod indent;
pub mod material;
pub mod mesh;
pub mod mesh_study;
pub mod problem;
pub mod stability;
pub mod system;
