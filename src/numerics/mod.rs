//! Small numerical building blocks shared by the physics modules.

pub mod quad;
pub mod roots;
