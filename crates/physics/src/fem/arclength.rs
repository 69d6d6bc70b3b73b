//! Arc-length continuation of the shell's equilibrium path in (u, delta) (pseudo-arc-length,
//! Keller; the thesis' ANSYS runs use the related Riks/Crisfield scheme): the plate
//! displacement delta becomes an unknown, and each step adds the constraint that the new
//! point lies at distance ds along the previous tangent,
//!
//!   t_u . (u - u_k) / n + t_delta (delta - delta_k) = ds,
//!
//! (n the number of dofs: the u part is a mean square, comparable with delta). Newton on the
//! bordered system by block elimination: K a = -r, K b = -q with q = d r / d delta, then
//! d delta = -(g + t_u . a / n) / (t_delta + t_u . b / n), du = a + d delta b. The path
//! passes limit points in delta (where K is singular and d delta / ds changes sign) and
//! traces the unstable branches between them, which prescribed-delta Newton cannot.
//!
//! Stability: the free tangent K positive definite (`Model::is_stable`); a limit point shows
//! as a sign change of d delta / ds together with a change of that flag.

use super::contact::Plate;
use super::indent::{evaluate, Evaluation, Options, Step, StepEnd};
use super::system::{Model, Stiffness};

/// Step control of the continuation (lengths in the mesh's units).
#[derive(Clone, Copy, Debug)]
pub struct ArcOptions {
    /// First, smallest and largest arc step.
    pub ds: f64,
    pub ds_min: f64,
    pub ds_max: f64,
    /// At most this many points.
    pub max_points: usize,
    /// Newton tolerance and iteration limit of each corrector.
    pub newton: Options,
    /// Steps grow when a corrector takes fewer iterations, shrink when more.
    pub target_iterations: usize,
}

/// One point of the continued path.
#[derive(Clone, Debug)]
pub struct ArcPoint {
    pub step: Step,
    /// d delta / ds along the path (in the orientation of the continuation).
    pub d_delta: f64,
}

/// The weighted inner product of the constraint.
fn dot(a_u: &[f64], a_d: f64, b_u: &[f64], b_d: f64) -> f64 {
    let n = a_u.len() as f64;
    a_u.iter().zip(b_u).map(|(x, y)| x * y).sum::<f64>() / n + a_d * b_d
}

/// Unit tangent (t_u, t_delta) at a converged state, oriented along `orient` (previous
/// tangent) or, without one, so that delta moves with the sign of `sign`.
fn tangent(
    model: &Model,
    tangent: &Stiffness,
    q: &[f64],
    orient: Option<(&[f64], f64)>,
    sign: f64,
) -> Option<(Vec<f64>, f64)> {
    let minus_q: Vec<f64> = q.iter().map(|v| -v).collect();
    let b = model.solve(tangent, &minus_q).ok()?;
    let norm = dot(&b, 1.0, &b, 1.0).sqrt();
    let (mut t_u, mut t_d): (Vec<f64>, f64) = (b.iter().map(|v| v / norm).collect(), 1.0 / norm);
    let flip = match orient {
        Some((pu, pd)) => dot(&t_u, t_d, pu, pd) < 0.0,
        None => t_d * sign < 0.0,
    };
    if flip {
        t_u.iter_mut().for_each(|v| *v = -*v);
        t_d = -t_d;
    }
    if t_u.iter().all(|v| v.is_finite()) && t_d.is_finite() {
        Some((t_u, t_d))
    } else {
        None
    }
}

/// One corrector from the predictor (u_k, delta_k) + ds t.
/// Returns the converged state with its evaluation (tangent and contact, for the next
/// tangent).
///
/// Its arguments: the shell problem's three parts (`ShellProblem` binds them above this
/// module), the state and predictor, the step and the Newton options.
fn correct(
    model: &Model,
    plate: &Plate,
    e: f64,
    from: &Step,
    t: (&[f64], f64),
    ds: f64,
    opt: Options,
) -> Option<(Step, Evaluation)> {
    let scale = e * model.mesh.thickness.powi(2);
    let mut u: Vec<f64> = from.u.iter().zip(t.0).map(|(a, b)| a + ds * b).collect();
    let mut delta = from.delta + ds * t.1;
    let mut iterations = 0;
    loop {
        crate::numerics::budget::checkpoint();
        let ev = evaluate(model, plate, delta, &u, &from.contact.stick)?;
        let du_k: Vec<f64> = u.iter().zip(&from.u).map(|(a, b)| a - b).collect();
        let g = dot(t.0, t.1, &du_k, delta - from.delta) - ds;
        // The constraint is linear: after one Newton update it holds to rounding.
        if ev.norm <= opt.tol * scale && g.abs() <= 1e-9 * ds.abs() {
            let stable = model.is_stable(&ev.tangent);
            let step = Step {
                delta,
                u,
                contact: ev.contact.clone(),
                iterations,
                residual: ev.norm / scale,
                stable,
                termination: StepEnd::Converged,
            };
            return Some((step, ev));
        }
        if iterations >= opt.max_iterations || !ev.norm.is_finite() {
            return None;
        }
        iterations += 1;
        let minus_r: Vec<f64> = ev.residual.iter().map(|v| -v).collect();
        let minus_q: Vec<f64> = ev.q.iter().map(|v| -v).collect();
        let sol = model.solve_many(&ev.tangent, &[&minus_r, &minus_q]).ok()?;
        let (a, b) = (&sol[0], &sol[1]);
        let dd = -(g + dot(t.0, 0.0, a, 0.0)) / (t.1 + dot(t.0, 0.0, b, 0.0));
        if !dd.is_finite() {
            return None;
        }
        u.iter_mut().zip(a.iter().zip(b)).for_each(|(x, (ai, bi))| *x += ai + dd * bi);
        delta += dd;
    }
}

/// Continues the path from the converged state `start`, moving delta first in the direction
/// of `sign` (+1 or -1), until `stop` returns true for a point, `max_points` are reached or
/// the step falls below `ds_min` (the last point is then the failed attempt's start, and
/// the returned flag is false).
///
/// Its arguments: the shell problem's three parts, which `ShellProblem::continue_path`
/// binds, the start, the direction, the options and the stopping rule.
pub fn continue_path(
    model: &Model,
    plate: &Plate,
    e: f64,
    start: &Step,
    sign: f64,
    opt: ArcOptions,
    mut stop: impl FnMut(&ArcPoint) -> bool,
) -> (Vec<ArcPoint>, bool) {
    let Some(ev) = evaluate(model, plate, start.delta, &start.u, &start.contact.stick) else {
        return (Vec::new(), false);
    };
    let Some(mut t) = tangent(model, &ev.tangent, &ev.q, None, sign) else {
        return (Vec::new(), false);
    };
    let mut out = Vec::new();
    let mut current = start.clone();
    let mut ds = opt.ds;
    while out.len() < opt.max_points {
        match correct(model, plate, e, &current, (&t.0, t.1), ds, opt.newton) {
            Some((next, ev)) => {
                let Some(t_next) = tangent(model, &ev.tangent, &ev.q, Some((&t.0, t.1)), sign) else {
                    return (out, false);
                };
                let ratio = opt.target_iterations as f64 / next.iterations.max(1) as f64;
                ds = (ds * ratio.sqrt().clamp(0.5, 2.0)).clamp(opt.ds_min, opt.ds_max);
                t = t_next;
                current = next.clone();
                let point = ArcPoint { step: next, d_delta: t.1 };
                let done = stop(&point);
                out.push(point);
                if done {
                    return (out, true);
                }
            }
            None if ds > opt.ds_min => ds = (0.5 * ds).max(opt.ds_min),
            None => return (out, false),
        }
    }
    (out, true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::indent::{inverted_from, load_path};
    use crate::fem::mesh::ShellMesh;
    use crate::fem::system::Base;

    #[test]
    fn the_inverted_branch_ends_in_a_limit_point_where_stability_is_lost() {
        // From the inverted state at delta/R = 0.25 (R = 15, h = 1) backwards: delta falls to
        // a minimum (the limit point, delta/R = 0.1735) and rises again on the unstable
        // branch; the tangent's positive definiteness is lost exactly there (determinant
        // sign change), within one arc step.
        let (e, r, h) = (1.3, 15.0, 1.0);
        let model = Model::new(ShellMesh::hemisphere(r, h, 60, 3, 8.0), e, 0.45, Base::Clamped);
        let plate = Plate::new(&model.mesh, e, 1000.0);
        let flat = load_path(&model, &plate, e, 0.25 * r, 10, 4).pop().unwrap();
        let inv = inverted_from(&model, &plate, e, &flat, r, h);
        assert!(inv.converged() && inv.stable);
        let opt = ArcOptions {
            ds: 0.02,
            ds_min: 1e-5,
            ds_max: 0.03,
            max_points: 400,
            newton: Options { max_iterations: 25, ..Options::default() },
            target_iterations: 5,
        };
        let (pts, ok) =
            continue_path(&model, &plate, e, &inv, -1.0, opt, |p| p.d_delta > 0.0 && p.step.delta > 0.19 * r);
        assert!(ok);
        let fold = pts.iter().position(|p| p.d_delta > 0.0).unwrap();
        let lowest = pts.iter().map(|p| p.step.delta).fold(f64::INFINITY, f64::min);
        assert!((lowest / r - 0.1735).abs() < 1e-3, "{}", lowest / r);
        let lost = pts.iter().position(|p| !p.step.stable).unwrap();
        assert!(lost.abs_diff(fold) <= 1, "stability lost at {lost}, fold at {fold}");
        assert!(pts[..lost].iter().all(|p| p.step.stable) && pts[lost..].iter().all(|p| !p.step.stable));
        assert!(pts.iter().all(|p| p.step.converged() && p.step.iterations <= 10));
    }
}
