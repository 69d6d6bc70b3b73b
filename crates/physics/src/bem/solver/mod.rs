//! Steady sliding of a rigid cylinder on an adhesive standard-linear-solid half-plane:
//! boundary elements with Newton's method under load control (thesis Eqs. 4.4–4.16).
//!
//! Units and conventions are those of `kernel` (Eq. 4.6 corrected): X = x/beta,
//! H = (h - eps)R/beta^2, P = p/sigma0, W = w/(E0* R dgamma^2)^(1/3); the indenter slides
//! towards -X (trailing edge on the right). The speed enters as V0 = v tau/a0 with
//! a0/beta = 2 sqrt(W/pi) (ERRATA 4), so V = v tau/beta = 2 V0 sqrt(W/pi) (Eq. 4.18).
//!
//! Discretisation: n elements of width 2A on [-L, L] with their centres X_i as nodes, the
//! pressure linear between the nodes (a hat per node: `kernel::MeshKernel`; Eq. 4.12 with
//! hats instead of the thesis' uniform strips: U = (2 lambda/pi) G P, G Toeplitz, second
//! order in A at every speed). Unknowns: the gaps H_i and the approach Delta.
//! Equations: H_i + Delta - X_i^2/2 - U_i(P(H)) = 0 (Eq. 4.7) and lambda Int P dX = W.
//! Newton-Krylov: products with G by FFT (`numerics::toeplitz`), GMRES preconditioned by a
//! dense LU (faer) of the near-contact block (`ActiveLu`), and a backtracking line search
//! that keeps every z = 1 + alpha lambda H positive. Unconverged points are returned as
//! such, with their residual and iteration count.
//!
//! Friction (Eq. 4.16 with the prefactor of ERRATA 3, sign for sliding towards -X):
//!   mu* = (sqrt(pi)/2) (lambda / W^(3/2)) Int P dU/dX dX,
//! evaluated as sum_j P_j [U(X_j + A) - U(X_j - A)] (the midpoint rule of Int P dU), with
//! U at the element edges from the same kernel. mu_adh and mu_comp are the parts from
//! tensile and compressive nodes.
//!
//! One file per concern: `params` (parameters, domain and mesh choice), `system` (the
//! operator and the residual), `precondition`, `newton`, `continuation`, `solution` (the
//! friction of a solved point), `refinement` (mesh studies and error estimates), `branch`
//! (the equilibrium branch walked by pseudo-arclength: pull-off, tensile loads).

pub mod branch;
mod continuation;
mod newton;
mod params;
mod precondition;
mod refinement;
mod solution;
mod system;

pub use continuation::solve;
pub use newton::PathSolver;
pub use params::{
    cohesive_zone, domain_half_length, domain_load_error, domain_rel_error, memory_bound, starting_mesh, zone_elements,
    Mesh, Params, DEFAULT_N_MAX, DEFAULT_REL_TOL, MIN_ZONE_ELEMENTS, TOLERANCE,
};
pub use refinement::{
    refine, solve_to_tolerance, solve_to_tolerance_from, solve_to_tolerance_shares, solve_with_estimate, ErrorShares,
    DOMAIN_SAFETY, MESH_SAFETY,
};
pub use solution::{Cost, Friction, Solution, Start, Termination};
pub use system::Control;

#[cfg(test)]
mod tests;
