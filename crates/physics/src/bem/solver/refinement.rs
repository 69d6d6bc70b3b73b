//! Mesh refinement and error estimates: solutions on successively finer meshes of the same
//! domain (mesh sequencing from the coarser solution), a Richardson-type estimate of the
//! discretisation error with a safety factor, the domain's truncation error, and refinement
//! until the estimate meets a relative tolerance (`solve_to_tolerance`).

use super::continuation::{interpolated_newton, solve, started_newton};
use super::params::{domain_rel_error, Mesh, Params};
use super::precondition::{nested_ratio, ActiveLu, Preconditioner, DROP, TWO_GRID_MIN_N};
use super::solution::{Cost, Solution, Start};
use super::system::{Control, Operator, System};
use crate::numerics::extrapolation;

/// Safety factors of the reported error estimate of mu* (`solve_to_tolerance`): on the
/// mesh's Richardson share, Roache's factor 3 for a grid convergence index from two grids
/// (the reported share is then |mu*(n) - mu*(n/2)|), and 2 on the domain's
/// (`domain_rel_error`): with them every point of the bench's configurations is covered
/// (`pipelines/bench.yaml`; docs/bem.md, Chapter 4's model, has the ratios of actual error to
/// estimate). The refinement itself stops on the bare shares against rel_tol (`refine_to`).
pub const MESH_SAFETY: f64 = 3.0;

pub const DOMAIN_SAFETY: f64 = 2.0;

/// A solution on a fixed `mesh` with its error estimate: the two-level `richardson` share
/// against the mesh with half its elements (when that solve does not converge, |mu*|: no
/// confidence), reported with `MESH_SAFETY`, plus the domain's truncation, |mu*|
/// `domain_rel_error` times `DOMAIN_SAFETY`. (A fixed mesh may be coarse enough that a
/// quarter of it is far from the asymptotic regime; the three-level estimate of
/// `solve_to_tolerance` is then needlessly large.)
pub fn solve_with_estimate(params: &Params, mesh: Mesh) -> (Solution, f64) {
    let (s, shares) = refine_to(params, mesh, f64::INFINITY, mesh.n, false, None);
    (s, shares.reported())
}

/// The Richardson estimate of the error of `fine` from `coarse` (half its elements),
/// assuming the second order the solver reaches asymptotically: successive differences
/// shrink by 4 per halving, so the error of the fine solution is about
/// |mu*(n) - mu*(n/2)| / 3. What the refinement stops on.
pub(super) fn richardson(fine: &Solution, coarse: &Solution) -> f64 {
    let mu = fine.friction().mu_star;
    let estimate = if coarse.converged() && fine.converged() {
        extrapolation::richardson(mu, coarse.friction().mu_star, 2.0)
    } else {
        mu.abs()
    };
    if estimate.is_finite() {
        estimate
    } else {
        f64::MAX
    }
}

/// The estimate of the error of `fine` from three levels (n/4, n/2, n): the three-level
/// bound of `numerics::extrapolation::three_level` for second order (the largest of the
/// two-level Richardson share, one more halving of the previous difference, and the
/// geometric tail at the observed ratio). The two-level estimate alone misses the error where
/// the sequence is not yet asymptotic: at lambda = 3, W = 1, k = 0.1, V0 = 0.01 the
/// differences are -1.7e-2, -9.1e-5, +5.4e-4, +2.0e-4 (n = 288 to 4616), and |d2|/3 at n =
/// 1154 under-states the error (8.1e-4) by 6 times; |d1|/12 bounds it. Where the
/// differences shrink slowly (by 1.2 per halving) the tail covers it. Without a converged
/// `coarser`, the two-level estimate.
pub(super) fn observed_estimate(fine: &Solution, coarse: &Solution, coarser: Option<&Solution>) -> f64 {
    let two_level = richardson(fine, coarse);
    let Some(coarser) = coarser.filter(|c| c.converged() && coarse.converged() && fine.converged()) else {
        return two_level;
    };
    let mu = |s: &Solution| s.friction().mu_star;
    let estimate = extrapolation::three_level(mu(coarser), mu(coarse), mu(fine), 2.0, MIN_RATIO);
    if estimate.is_finite() {
        estimate.max(two_level)
    } else if [mu(coarser), mu(coarse), mu(fine)].iter().all(|m| m.is_finite()) {
        f64::MAX
    } else {
        two_level
    }
}

/// The smallest ratio of successive differences `observed_estimate` trusts (a tail of at
/// most 10 times the last difference).
const MIN_RATIO: f64 = 1.1;

/// The solution on a finer `mesh` of the same domain, from Newton started at the linear
/// interpolation of `coarse` (mesh sequencing: the continuation path is walked on the
/// coarse mesh only); if that fails, by the full continuation on the fine mesh.
pub fn refine(coarse: &Solution, mesh: Mesh) -> Solution {
    refine_carrying(coarse, mesh, &mut None)
}

/// `refine`, with the active LU of an earlier refinement of the same domain (`carried`)
/// used as the nested preconditioner (`ActiveLu::solve_nested`) when the new mesh nests
/// in its mesh at most `MAX_NESTED_RATIO` to one, instead of a fresh LU of `coarse`; on
/// return `carried` holds the LU to carry to the next refinement.
pub(super) fn refine_carrying(coarse: &Solution, mesh: Mesh, carried: &mut Option<ActiveLu>) -> Solution {
    let mut pre = Preconditioner::default();
    if mesh.n >= TWO_GRID_MIN_N && mesh.n == 2 * coarse.mesh.n && mesh.half_length == coarse.mesh.half_length {
        pre.active = carried.take().filter(|a| nested_ratio(a.n, mesh.n).is_some());
        if pre.active.is_none() {
            let p = &coarse.params;
            let op = Operator::new(coarse.mesh, p.lambda, p.k, &p.spectrum, p.v(), p.pressure);
            let sys = System::new(&op, Control::Load(p.w));
            let ev = sys.eval(&coarse.h, coarse.delta);
            pre.active = Some(ActiveLu::new(&sys, &ev.dp, DROP));
            pre.factorizations += 1;
        }
    }
    // The coarse LU factored here is part of the refinement's cost.
    let coarse_lu = pre.factorizations;
    let mut s = interpolated_newton(coarse, mesh, 40, &mut pre);
    s.cost.factorizations += coarse_lu;
    *carried = if s.converged() { pre.active } else { None };
    or_continuation(s, mesh)
}

/// The solution on a coarser `mesh` of the same domain, from Newton started at the
/// restriction (linear interpolation) of `fine`: the continuation path is not walked again
/// for the third level of `observed_estimate`.
fn coarsen(fine: &Solution, mesh: Mesh) -> Solution {
    or_continuation(interpolated_newton(fine, mesh, 40, &mut Preconditioner::default()), mesh)
}

/// `s` if it converged, else the full continuation on `mesh` (its cost counting that of
/// `s`).
fn or_continuation(s: Solution, mesh: Mesh) -> Solution {
    if s.converged() {
        return s;
    }
    let mut full = solve(&s.params, mesh);
    full.cost += s.cost;
    full
}

/// The two shares of the error of mu* that `solve_to_tolerance` reports, without their
/// safety factors: the mesh's (from three levels, `observed_estimate`) and the domain's
/// (|mu*| `domain_rel_error`).
#[derive(Clone, Copy, Debug)]
pub struct ErrorShares {
    pub mesh: f64,
    pub domain: f64,
}

impl ErrorShares {
    /// The reported estimate: `MESH_SAFETY` mesh + `DOMAIN_SAFETY` domain (finite).
    pub fn reported(&self) -> f64 {
        (MESH_SAFETY * self.mesh + DOMAIN_SAFETY * self.domain).min(f64::MAX)
    }
}

/// Solves on `mesh` (by continuation on half its elements, then `refine`), then doubles
/// the number of elements (same domain) until the Richardson estimate is at most
/// `rel_tol` |mu*|, from two levels and then from three (`observed_estimate`), or the next
/// mesh would exceed `n_max`. Each refinement starts from
/// the previous solution and reuses it as the coarse one. The result's `cost` counts the
/// whole path (with the quarter-size solve the
/// three-level estimate needs when the refinement stopped at its first two levels). The
/// error estimate is `ErrorShares::reported`.
pub fn solve_to_tolerance(params: &Params, mesh: Mesh, rel_tol: f64, n_max: usize) -> (Solution, f64) {
    let (s, shares) = solve_to_tolerance_shares(params, mesh, rel_tol, n_max);
    (s, shares.reported())
}

/// `solve_to_tolerance` with the error's two shares apart.
pub fn solve_to_tolerance_shares(params: &Params, mesh: Mesh, rel_tol: f64, n_max: usize) -> (Solution, ErrorShares) {
    refine_to(params, mesh, rel_tol, n_max, true, None)
}

/// `solve_to_tolerance`, its first level started by Newton from `neighbour` (if any), the
/// state of a converged solution of the same lambda, W and k at another speed (interpolated
/// onto the mesh), instead of the continuation from the relaxed state; the continuation if
/// that fails (its iterations counted too). What a search over V0 uses, from its nearest
/// solve so far, and a sweep point given a start (`bem.sweep`'s `start`).
pub fn solve_to_tolerance_from(
    params: &Params,
    mesh: Mesh,
    rel_tol: f64,
    n_max: usize,
    neighbour: Option<&Start>,
) -> (Solution, f64) {
    let (s, shares) = refine_to(params, mesh, rel_tol, n_max, true, neighbour);
    (s, shares.reported())
}

/// The refinement of `solve_to_tolerance`; `three_levels`: the mesh's share from three
/// levels (`observed_estimate`), else the two-level `richardson`; `neighbour`: the first
/// level from it (`solve_to_tolerance_from`).
fn refine_to(
    params: &Params,
    mesh: Mesh,
    rel_tol: f64,
    n_max: usize,
    three_levels: bool,
    neighbour: Option<&Start>,
) -> (Solution, ErrorShares) {
    let first = Mesh { n: (mesh.n / 2).max(8), ..mesh };
    let mut coarse = match neighbour.filter(|s| s.x.len() >= 2 && s.x.len() == s.h.len()) {
        Some(s) => or_continuation(
            started_newton(params, &s.x, &s.h, s.delta, first, 40, &mut Preconditioner::default()),
            first,
        ),
        None => solve(params, first),
    };
    let mut spent = coarse.cost;
    let mut carried = None;
    let mut next = |from: &Solution, n: usize| {
        let mut s = if from.converged() {
            refine_carrying(from, Mesh { n, ..mesh }, &mut carried)
        } else {
            carried = None;
            solve(params, Mesh { n, ..mesh })
        };
        spent += s.cost;
        s.cost = spent;
        s
    };
    let mut fine = next(&coarse, mesh.n);
    // The level before `coarse`, once the refinement has made one, or restricted from
    // `coarse` when it stopped at its first two; the latter's Newton counts.
    let mut coarser: Option<Solution> = None;
    let mut restricted = Cost::default();
    loop {
        let mu = fine.friction().mu_star.abs();
        let two_level = richardson(&fine, &coarse);
        // Two levels in a row without a converged solution: refining will not rescue the
        // point (a load beyond pull-off walks to its fold on every mesh, and doubling to
        // n_max costs minutes: docs/tuning.md). It is reported as is.
        let hopeless = !fine.converged() && !coarse.converged();
        let capped = 2 * fine.mesh.n > n_max;
        if hopeless || capped || two_level <= rel_tol * mu {
            // The domain's share, which refining the mesh does not change.
            let domain = mu * domain_rel_error(params, mesh.half_length);
            if !three_levels {
                return (fine, ErrorShares { mesh: two_level, domain });
            }
            if coarser.is_none() && !hopeless && fine.converged() && coarse.mesh.n / 2 >= 8 {
                let c = coarsen(&coarse, Mesh { n: coarse.mesh.n / 2, ..mesh });
                restricted += c.cost;
                coarser = Some(c);
            }
            // The mesh's share from three levels. Where they show the sequence not yet
            // asymptotic (the share above the tolerance that two levels met), the mesh is
            // refined further while n_max allows.
            let estimate = observed_estimate(&fine, &coarse, coarser.as_ref());
            if hopeless || capped || estimate <= rel_tol * mu {
                fine.cost += restricted;
                return (fine, ErrorShares { mesh: estimate, domain });
            }
        }
        let n = 2 * fine.mesh.n;
        let finer = next(&fine, n);
        coarser = Some(std::mem::replace(&mut coarse, std::mem::replace(&mut fine, finer)));
    }
}
