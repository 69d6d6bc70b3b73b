//! Small numerical building blocks shared by the physics modules.

pub mod banded;
pub mod fit;
pub mod gmres;
pub mod quad;
pub mod roots;
pub mod toeplitz;
