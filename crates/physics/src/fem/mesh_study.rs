//! The mesh study of a load-unload cycle of the shell: the errors of its snap force and
//! dissipated energy from the cycle on a mesh with twice the meridian elements, and whether
//! the two meshes agree on the cycle's discrete events (a snap, a complete cycle).

use super::cycle::{Cycle, Jump};
use crate::numerics::extrapolation;

/// The mesh's share of the errors of F_buckling and W on n meridian elements, from the
/// cycles on n and 2n (the `mesh_study` option of the `fem.*` kinds): twice the differences, Richardson's
/// bound |X(n) - X(2n)| 2^p / (2^p - 1) at first order p = 1. The elements are quadratic,
/// but the snap's force comes from a bisection on a discrete stability test, and its mesh
/// sequence is not monotone (docs/tuning.md, "Shell mesh"), so the second-order factor 4/3
/// would not be safe. The companion is the finer mesh, not the coarser: a coarse mesh is
/// often outside the asymptotic range, and then no estimate holds. When
/// the two meshes disagree on whether the shell snaps, or either cycle is incomplete,
/// nothing is known: the errors are the larger |F| and |W| of the two and `agrees` is
/// false.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshStudy {
    pub f_error: f64,
    pub w_error: f64,
    pub agrees: bool,
}

/// What a mesh study compares of one cycle.
#[derive(Clone, Copy, Debug)]
pub struct Outcome {
    pub buckled: bool,
    /// F_buckling (0 without a snap) and W.
    pub force: f64,
    pub w: f64,
    pub complete: bool,
}

impl Outcome {
    pub fn of(buckling: &Option<Jump>, w: f64, c: &Cycle) -> Outcome {
        Outcome {
            buckled: buckling.is_some(),
            force: buckling.map_or(0.0, |j| j.force_before),
            w,
            complete: c.complete,
        }
    }
}

impl MeshStudy {
    /// From the cycle on the mesh and on its companion with twice the meridian elements.
    pub fn of(mesh: Outcome, finer: Outcome) -> MeshStudy {
        let agrees = mesh.buckled == finer.buckled && mesh.complete && finer.complete;
        if agrees {
            let bound = |a: f64, b: f64| extrapolation::coarse_error(a, b, 1.0);
            MeshStudy { f_error: bound(mesh.force, finer.force), w_error: bound(mesh.w, finer.w), agrees }
        } else {
            let largest = |a: f64, b: f64| a.abs().max(b.abs());
            MeshStudy { f_error: largest(mesh.force, finer.force), w_error: largest(mesh.w, finer.w), agrees }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{MeshStudy, Outcome};

    fn outcome((buckled, force, w, complete): (bool, f64, f64, bool)) -> Outcome {
        Outcome { buckled, force, w, complete }
    }

    fn study(mesh: (bool, f64, f64, bool), finer: (bool, f64, f64, bool)) -> MeshStudy {
        MeshStudy::of(outcome(mesh), outcome(finer))
    }

    #[test]
    fn the_mesh_study_bounds_the_error_by_twice_the_difference_and_knows_when_it_knows_nothing() {
        // Agreeing meshes: twice the differences (the first-order Richardson bound).
        let st = study((true, 9.314, 0.0206, true), (true, 9.352, 0.0194, true));
        assert!((st.f_error - 0.076).abs() < 1e-12 && (st.w_error - 0.0024).abs() < 1e-12 && st.agrees, "{st:?}");
        // One mesh snaps and the other does not, or a cycle is incomplete: the larger |F|
        // and |W| of the two.
        for (mesh, finer) in
            [((true, -9.3, 0.02, true), (false, 0.0, 0.01, true)), ((false, 0.0, 0.01, true), (true, 9.3, 0.02, true))]
        {
            assert_eq!(study(mesh, finer), MeshStudy { f_error: 9.3, w_error: 0.02, agrees: false });
        }
        let st = study((true, 9.2, 0.02, true), (true, 9.3, 0.01, false));
        assert_eq!(st, MeshStudy { f_error: 9.3, w_error: 0.02, agrees: false });
        // Neither snaps: F is 0 on both, W's difference stands.
        let st = study((false, 0.0, 1.5, true), (false, 0.0, 1.4, true));
        assert!(st.f_error == 0.0 && (st.w_error - 0.2).abs() < 1e-12 && st.agrees);
    }
}
