//! Indentation of the shell by the rigid plate under prescribed plate displacement delta
//! (thesis Section 3.2, Figs. 3.2-3.3): load steps in delta, each solved by Newton's method
//! on the free dofs with the penalty contact of `contact`, from the previous state; a step
//! that does not converge is halved (down to a minimum), and the path stops there, recorded
//! as not converged.
//!
//! Units: lengths of the mesh, stresses in units of E (E = 1 here is fine: the outputs are
//! the dimensionless F R/(E h^3), delta/R, p/E).
//!
//! One file with its tests apart (`tests.rs`): Newton at a plate displacement, its line
//! search and its starts are one algorithm, read together.

use super::adhesion::Tangent;
use super::contact::{ContactState, Plate};
use super::system::{Model, NoTangent, Stiffness};

/// One converged (or the last failed) state of the path.
#[derive(Clone, Debug)]
pub struct Step {
    pub delta: f64,
    pub u: Vec<f64>,
    pub contact: ContactState,
    pub iterations: usize,
    pub residual: f64,
    /// The free tangent is positive definite (stable under prescribed delta).
    pub stable: bool,
    /// Why its solver stopped.
    pub termination: StepEnd,
}

/// Why the solver of a state stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepEnd {
    /// The residual met the tolerance (for an energy descent: at a positive-definite
    /// tangent, a stable state).
    Converged,
    /// The iteration limit was reached first.
    IterationLimit,
    /// No step along the Newton direction (nor the convexified one) was admissible: every
    /// trial inverted an element or the tangent was singular.
    NoStep,
    /// The energy descent found no shift that lowers the potential (`SHIFT_MAX`).
    NoDescent,
    /// The residual met the tolerance at a tangent that is not positive definite: an
    /// equilibrium, but not a stable one (an energy descent's verdict).
    Unstable,
    /// The state could not be evaluated (an inverted element).
    Inverted,
    /// Not solved: the reference state taken as the start when no adhering state was found.
    NotSolved,
}

impl StepEnd {
    /// Its name in tables: `converged`, `iteration_limit`, ...
    pub fn name(self) -> &'static str {
        match self {
            StepEnd::Converged => "converged",
            StepEnd::IterationLimit => "iteration_limit",
            StepEnd::NoStep => "no_step",
            StepEnd::NoDescent => "no_descent",
            StepEnd::Unstable => "unstable",
            StepEnd::Inverted => "inverted",
            StepEnd::NotSolved => "not_solved",
        }
    }
}

impl Step {
    /// Its solver met the tolerance (`termination`; an energy descent also at a stable state).
    pub fn converged(&self) -> bool {
        self.termination == StepEnd::Converged
    }

    /// A state at `delta` that could not even be evaluated (an inverted element): not
    /// converged, infinite residual.
    fn failed(delta: f64, u: Vec<f64>) -> Step {
        Step {
            delta,
            u,
            contact: ContactState::default(),
            iterations: 0,
            residual: f64::INFINITY,
            stable: false,
            termination: StepEnd::Inverted,
        }
    }
}

/// Newton options.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    pub max_iterations: usize,
    /// Convergence: max-norm of the free residual below tol * E h^2.
    pub tol: f64,
    /// The line search's nonmonotone window (`NONMONOTONE_WINDOW`; 1: monotone).
    pub window: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options { max_iterations: 30, tol: 1e-9, window: NONMONOTONE_WINDOW }
    }
}

/// The z of the undeformed apex of the outer surface (R + h on a perfect shell): the plate
/// touches it at delta = 0.
pub fn apex_z(model: &Model) -> f64 {
    model.mesh.nodes[model.mesh.outer[0]][1]
}

/// The free residual at one configuration, with the tangent and the contact state.
#[derive(Clone)]
pub(crate) struct Evaluation {
    pub residual: Vec<f64>,
    pub tangent: Stiffness,
    pub contact: ContactState,
    /// Max-norm of the residual.
    pub norm: f64,
    /// d residual / d delta at fixed u (the arc length's border).
    pub q: Vec<f64>,
}

/// Residual f_int - f_contact on the free dofs (zero on the fixed ones), its tangent and the
/// contact state, for displacements `u`, the plate at `delta` and the friction anchors
/// `stick` of the last converged state; None if an element is inverted.
pub(crate) fn evaluate(model: &Model, plate: &Plate, delta: f64, u: &[f64], stick: &[f64]) -> Option<Evaluation> {
    evaluate_with(model, plate, delta, u, stick, Tangent::Exact)
}

/// `evaluate` with a choice of adhesive tangent.
fn evaluate_with(
    model: &Model,
    plate: &Plate,
    delta: f64,
    u: &[f64],
    stick: &[f64],
    tangent: Tangent,
) -> Option<Evaluation> {
    let (fint, mut trip) = model.assemble(u)?;
    let mut fext = vec![0.0; model.n_dofs()];
    let mut q = vec![0.0; model.n_dofs()];
    let state = plate.apply(&model.mesh, u, apex_z(model) - delta, stick, &mut fext, &mut trip, &mut q, tangent);
    let (r, norm) = free_residual(model, &fint, &fext);
    q.iter_mut().zip(&model.fixed).for_each(|(v, &f)| {
        if f {
            *v = 0.0
        }
    });
    if !norm.is_finite() {
        return None;
    }
    Some(Evaluation { residual: r, tangent: trip, contact: state, norm, q })
}

/// The residual f_int - f_ext on the free dofs (zero on the fixed ones) and its max-norm.
fn free_residual(model: &Model, fint: &[f64], fext: &[f64]) -> (Vec<f64>, f64) {
    let r: Vec<f64> = (0..model.n_dofs()).map(|i| if model.fixed[i] { 0.0 } else { fint[i] - fext[i] }).collect();
    let norm = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    (r, norm)
}

/// The residual's max-norm at displacements `u` (`evaluate`'s, bitwise) without the tangent:
/// a line search's trial point. None if an element is inverted or the residual not finite.
fn trial_norm(model: &Model, plate: &Plate, delta: f64, u: &[f64], stick: &[f64]) -> Option<f64> {
    let fint = model.internal_forces(u)?;
    let mut fext = vec![0.0; model.n_dofs()];
    let mut q = vec![0.0; model.n_dofs()];
    plate.apply(&model.mesh, u, apex_z(model) - delta, stick, &mut fext, &mut NoTangent, &mut q, Tangent::Exact);
    let (_, norm) = free_residual(model, &fint, &fext);
    norm.is_finite().then_some(norm)
}

/// Newton's line search accepts a step that lowers the residual's max-norm below the
/// largest of the last `NONMONOTONE_WINDOW` norms (Grippo, Lampariello and Lucidi, SIAM J.
/// Numer. Anal. 23, 1986), not below the last one. With friction and contact the residual is
/// piecewise smooth: a monotone search damps the steps that change the stick/slip and
/// contact sets, and those sets then change by one node per iteration: most Newton runs
/// of a frictional probe of the gamma_c map then end at their iteration limit
/// (docs/tuning.md).
pub const NONMONOTONE_WINDOW: usize = 5;

/// Iterations without a new lowest residual after which Newton returns to the lowest and
/// continues with the monotone search (Chamberlain et al.'s watchdog, Math. Prog. Study 16,
/// 1982): the nonmonotone acceptance can cycle across the kinks of the interface laws, the
/// residual returning to the same few values.
pub const WATCHDOG: usize = 5;

/// Newton at plate displacement `delta` from displacements `u0`, with the friction anchors
/// `stick` of the last converged state (`ContactState::stick`; empty: the reference state).
///
/// Its arguments: the shell problem's three parts (model, plate, modulus), which
/// `ShellProblem::solve_at` binds (the solvers lie below that type), the state and the options.
pub fn solve_at(model: &Model, plate: &Plate, e: f64, delta: f64, u0: &[f64], stick: &[f64], opt: Options) -> Step {
    let scale = e * model.mesh.thickness.powi(2);
    let mut u = u0.to_vec();
    let Some(mut cur) = evaluate(model, plate, delta, &u, stick) else {
        return Step::failed(delta, u);
    };
    // Backtracking along `du` (and away from inverted elements) until the residual falls
    // below `norm`, the trial points without their tangent (`trial_norm`: most of a
    // frictional solve's trials are rejected). If no step down to 1/128 lowers it, the
    // longest admissible step is taken: at the kinks of the interface laws (contact status,
    // stick/slip) a tiny step only sends Newton back where it came from, a 2-cycle; the long
    // step lets it change the status set.
    let line_search = |u: &[f64], norm: f64, du: &[f64]| -> Option<Vec<f64>> {
        let mut step = 1.0;
        let mut longest: Option<Vec<f64>> = None;
        for _ in 0..8 {
            let trial: Vec<f64> = u.iter().zip(du).map(|(a, b)| a + step * b).collect();
            if let Some(next) = trial_norm(model, plate, delta, &trial, stick) {
                if next < norm {
                    return Some(trial);
                }
                longest.get_or_insert(trial);
            }
            step *= 0.5;
        }
        longest
    };
    // Nonmonotone acceptance with a watchdog (see `NONMONOTONE_WINDOW`): the reference is
    // the largest of the last norms; after `WATCHDOG` iterations without a new lowest
    // norm, Newton goes back to the lowest and carries on monotone.
    let mut window = opt.window.max(1);
    let mut recent: Vec<f64> = Vec::with_capacity(opt.max_iterations);
    let mut best: Option<(Vec<f64>, Evaluation)> = None;
    let mut since_best = 0;
    let mut iterations = 0;
    let mut no_step = false;
    while cur.norm > opt.tol * scale && iterations < opt.max_iterations {
        crate::numerics::budget::checkpoint();
        iterations += 1;
        if best.as_ref().is_none_or(|(_, b)| cur.norm < b.norm) {
            best = Some((u.clone(), cur.clone()));
            since_best = 0;
        } else {
            since_best += 1;
            if window > 1 && since_best >= WATCHDOG {
                if let Some((bu, bev)) = best.clone() {
                    (u, cur) = (bu, bev);
                }
                window = 1;
                recent.clear();
            }
        }
        recent.push(cur.norm);
        let reference = recent.iter().rev().take(window).fold(0.0f64, |m, &v| m.max(v));
        let rhs: Vec<f64> = cur.residual.iter().map(|v| -v).collect();
        let mut next = model.solve(&cur.tangent, &rhs).ok().and_then(|du| line_search(&u, reference, &du));
        if next.is_none() && plate.adhesion.is_some() {
            // Every step along the exact direction inverts elements: strong adhesion makes
            // the tangent indefinite where the law softens. Take the direction of the
            // convexified tangent instead (`adhesion::Tangent::Convex`).
            next = evaluate_with(model, plate, delta, &u, stick, Tangent::Convex)
                .and_then(|convex| model.solve(&convex.tangent, &rhs).ok())
                .and_then(|du| line_search(&u, cur.norm, &du));
        }
        // The accepted point's tangent (its residual is the trial's, bitwise).
        let Some((trial, ev)) = next.and_then(|t| evaluate(model, plate, delta, &t, stick).map(|ev| (t, ev))) else {
            no_step = true;
            break;
        };
        u = trial;
        cur = ev;
    }
    let converged = cur.norm <= opt.tol * scale;
    let stable = converged && model.is_stable(&cur.tangent);
    let termination = if converged {
        StepEnd::Converged
    } else if no_step {
        StepEnd::NoStep
    } else {
        StepEnd::IterationLimit
    };
    Step { delta, u, contact: cur.contact, iterations, residual: cur.norm / scale, stable, termination }
}

/// Newton at plate displacement `delta` from the converged state `from`, started from the
/// Euler predictor u + (du/d delta) (delta - from.delta), du/d delta = -K^-1 q at `from`:
/// touching points then move with the plate instead of leaving it (which, across the kink
/// of the adhesive law, costs Newton dozens of damped iterations).
pub fn solve_from(model: &Model, plate: &Plate, e: f64, delta: f64, from: &Step, opt: Options) -> Step {
    solve_from_extending(model, plate, e, delta, from, opt, opt.max_iterations)
}

/// `solve_from` with `opt`, then, if it fails, each of its Newton runs that stopped at the
/// iteration limit resumed up to `max_iterations` in all: the result of `solve_from` with
/// `opt` followed by `solve_from` with `max_iterations`, without repeating the runs that
/// stopped for another reason (no admissible step along the Newton direction), which would
/// fail again in the same way and only spend assemblies.
///
/// Its arguments: the shell problem's three parts, which `ShellProblem` binds, the
/// state, the options and the extended limit.
pub fn solve_from_extending(
    model: &Model,
    plate: &Plate,
    e: f64,
    delta: f64,
    from: &Step,
    opt: Options,
    max_iterations: usize,
) -> Step {
    let predicted = evaluate(model, plate, from.delta, &from.u, &from.contact.stick).and_then(|ev| {
        let minus_q: Vec<f64> = ev.q.iter().map(|v| -v).collect();
        let b = model.solve(&ev.tangent, &minus_q).ok()?;
        let u: Vec<f64> = from.u.iter().zip(&b).map(|(x, y)| x + y * (delta - from.delta)).collect();
        u.iter().all(|v| v.is_finite()).then_some(u)
    });
    // The predictor first, then the last state itself.
    let starts: Vec<&[f64]> = predicted.as_deref().into_iter().chain([from.u.as_slice()]).collect();
    let run = |start: &[f64], opt: Options| solve_at(model, plate, e, delta, start, &from.contact.stick, opt);
    let mut first = Vec::with_capacity(starts.len());
    for &start in &starts {
        let s = run(start, opt);
        if s.converged() {
            return s;
        }
        first.push(s);
    }
    // A Newton run depends only on its current iterate: one resumed where it stopped is the
    // run with the longer limit.
    let more = Options { max_iterations: max_iterations.saturating_sub(opt.max_iterations), ..opt };
    let mut last = None;
    for s in first {
        let s = if more.max_iterations > 0 && s.iterations >= opt.max_iterations {
            let resumed = run(&s.u, more);
            Step { iterations: s.iterations + resumed.iterations, ..resumed }
        } else {
            s
        };
        if s.converged() {
            return s;
        }
        last = Some(s);
    }
    last.expect("at least one start")
}

/// Energy descent to a stable state at plate displacement `delta` from the guess `u0`, for
/// a plate whose interface forces have a potential (no friction). The total potential
/// Pi = strain energy + penalty and adhesive energy (`Plate::energy`) is lowered by shifted
/// Newton steps (K + sigma I) du = -r with backtracking on Pi: sigma (relative to K's mean
/// diagonal) is raised tenfold until the shifted tangent is positive definite and a step
/// along it lowers Pi, and lowered tenfold after each success, to zero, so that near a
/// minimum the steps are Newton's and converge quadratically; a descent that stalls there
/// (Pi flat to its rounding) is finished by Newton (`POLISH_REACH`). This is where a quasi-statically damped shell that
/// has lost stability comes to rest; plain Newton from a guess converges to whichever
/// equilibrium is near, stable or not, or to none. Converged means a residual below
/// tolerance at a positive-definite tangent (a stable state); otherwise the last iterate is
/// returned as not converged.
pub fn descend(model: &Model, plate: &Plate, e: f64, delta: f64, u0: &[f64], max_iterations: usize) -> Step {
    descend_loaded(model, plate, e, delta, u0, &[], max_iterations)
}

/// How near its tolerance (a multiple of it) a descent that stalls is polished by Newton:
/// near a minimum of Pi, where Pi is flat to rounding and cannot tell the backtracking's
/// trials apart, a full step that crosses a contact node's kink is refused, and the shifted
/// steps that follow creep (the adhering state at delta = 0 of h/R = 0.06, gamma/(E h) =
/// 1e-4 stalled at 53 times the tolerance and spent its 400 iterations; Newton from there
/// converges in one iteration to the state the continuation reaches, to 1.4e-15 mm:
/// docs/tuning.md, "Shell").
const POLISH_REACH: f64 = 1e3;

/// The rise of Pi (relative) a polish may bring: the rounding of Pi summed over the mesh
/// (that Newton step raised it by 1.2e-12 of itself), far below the difference between two
/// distinct states.
const POLISH_RISE: f64 = 1e-9;

/// `descend` with the dead load `-dead` added to the plate's forces (`dead`: a fixed
/// gradient, full dof vector, as `Adhesion::apply` writes it; empty: none), whose potential
/// dead . u joins Pi. With the adhesive forces of a state frozen this is the structural
/// solve of the thesis' staggered scheme (Section 3.2: adhesive forces applied as loads).
///
/// Its arguments: the shell problem's three parts, which `ShellProblem` binds, the
/// state, the dead load and the limit.
pub fn descend_loaded(
    model: &Model,
    plate: &Plate,
    e: f64,
    delta: f64,
    u0: &[f64],
    dead: &[f64],
    max_iterations: usize,
) -> Step {
    assert!(plate.friction.is_none(), "energy descent needs a potential: no friction");
    const SHIFT_MIN: f64 = 1e-8;
    const SHIFT_MAX: f64 = 1e4;
    const BACKTRACKS: usize = 12;
    let scale = e * model.mesh.thickness.powi(2);
    let tol = Options::default().tol * scale;
    let z_plate = apex_z(model) - delta;
    let dead_work = |u: &[f64]| dead.iter().zip(u).map(|(g, x)| g * x).sum::<f64>();
    let potential = |u: &[f64]| Some(model.strain_energy(u)? + plate.energy(&model.mesh, u, z_plate) + dead_work(u));
    let evaluate_loaded = |u: &[f64]| {
        let mut ev = evaluate(model, plate, delta, u, &[])?;
        if !dead.is_empty() {
            for (i, r) in ev.residual.iter_mut().enumerate() {
                if !model.fixed[i] {
                    *r += dead[i];
                }
            }
            ev.norm = ev.residual.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        }
        Some(ev)
    };
    let state = |u: &[f64]| Some((evaluate_loaded(u)?, potential(u)?));
    let mut u = u0.to_vec();
    let Some((mut cur, mut pi)) = state(&u) else {
        return Step::failed(delta, u);
    };
    let mut shift = 0.0;
    let mut iterations = 0;
    let mut no_descent = false;
    let raise = |s: f64| if s == 0.0 { SHIFT_MIN } else { 10.0 * s };
    let stable = loop {
        let rhs: Vec<f64> = cur.residual.iter().map(|v| -v).collect();
        // The unshifted Newton step exists (by Cholesky) exactly when the state is stable. It
        // is needed as the step (no shift) or for the verdict (residual within tolerance):
        // under a shift, far from a minimum, its factorisation would be wasted.
        let mut newton = if shift == 0.0 || cur.norm <= tol { model.solve_definite(&cur.tangent, &rhs) } else { None };
        let stable = newton.is_some();
        if (cur.norm <= tol && stable) || iterations >= max_iterations {
            break stable;
        }
        iterations += 1;
        let d0 = cur.tangent.mean_diagonal();
        let mut du = None;
        while du.is_none() && shift <= SHIFT_MAX {
            du =
                if shift == 0.0 { newton.take() } else { model.solve_definite(&cur.tangent.shifted(shift * d0), &rhs) };
            if du.is_none() {
                shift = raise(shift);
            }
        }
        let Some(du) = du else {
            no_descent = true;
            break stable;
        };
        // Backtracking on Pi along the step (the penalty makes Pi stiff where the contact set
        // changes); at rounding level of Pi (near the minimum) a lower residual will do.
        let mut t = 1.0;
        let mut accepted = None;
        for _ in 0..BACKTRACKS {
            let trial: Vec<f64> = u.iter().zip(&du).map(|(a, b)| a + t * b).collect();
            // Pi alone decides most trials; the tangent is assembled only for a trial that
            // lowers it (or ties it at rounding level, where the residual decides).
            if let Some(p) = potential(&trial).filter(|&p| p <= pi + 1e-13 * pi.abs()) {
                if let Some(ev) = evaluate_loaded(&trial).filter(|ev| p < pi || ev.norm < cur.norm) {
                    accepted = Some((trial, ev, p));
                    break;
                }
            }
            t *= 0.5;
        }
        match accepted {
            Some(next) => {
                (u, cur, pi) = next;
                shift = if shift <= SHIFT_MIN { 0.0 } else { 0.1 * shift };
            }
            None => {
                // Stalled at a stable state within reach of the tolerance: Newton from here
                // (`polish`), kept if it lowers the residual to tolerance at a stable state
                // without raising Pi.
                if shift == 0.0 && dead.is_empty() && cur.norm <= POLISH_REACH * tol {
                    let q = solve_at(model, plate, e, delta, &u, &[], Options::default());
                    let next = q.converged().then(|| state(&q.u)).flatten();
                    if let Some((ev, p)) = next.filter(|(ev, p)| ev.norm <= tol && *p <= pi + POLISH_RISE * pi.abs()) {
                        iterations += q.iterations;
                        (u, cur, pi) = (q.u, ev, p);
                        continue;
                    }
                }
                shift = raise(shift);
                if shift > SHIFT_MAX {
                    no_descent = true;
                    break stable;
                }
            }
        }
    };
    let converged = cur.norm <= tol && stable;
    let termination = if converged {
        StepEnd::Converged
    } else if cur.norm <= tol {
        StepEnd::Unstable
    } else if no_descent {
        StepEnd::NoDescent
    } else {
        StepEnd::IterationLimit
    };
    Step { delta, u, contact: cur.contact, iterations, residual: cur.norm / scale, stable: converged, termination }
}

/// Loads from delta = 0 to `delta_max` in `steps` equal steps (halved on failure, at most
/// `max_cuts` times per step). Returns the converged states; the last entry is the failed
/// one if the path stopped early.
pub fn load_path(model: &Model, plate: &Plate, e: f64, delta_max: f64, steps: usize, max_cuts: u32) -> Vec<Step> {
    let mut out: Vec<Step> = Vec::new();
    let mut u = vec![0.0; model.n_dofs()];
    let mut stick = Vec::new();
    let mut delta = 0.0;
    let base = delta_max / steps as f64;
    let mut dd = base;
    let mut cuts = 0;
    while delta < delta_max * (1.0 - 1e-12) {
        let target = (delta + dd).min(delta_max);
        let s = solve_at(model, plate, e, target, &u, &stick, Options::default());
        if s.converged() {
            delta = target;
            u = s.u.clone();
            stick = s.contact.stick.clone();
            out.push(s);
            if cuts > 0 {
                cuts -= 1;
                dd = (2.0 * dd).min(base);
            }
        } else if cuts < max_cuts {
            cuts += 1;
            dd *= 0.5;
        } else {
            out.push(s);
            break;
        }
    }
    out
}

/// The inverted state at the plate displacement of the flattened state `flat` of a shell of
/// radius `r` and thickness `h`: Newton from `flat` with a dimple of 0.8 times its contact
/// radius pushed in (tests of the inverted branch).
#[cfg(test)]
pub(crate) fn inverted_from(model: &Model, plate: &Plate, e: f64, flat: &Step, r: f64, h: f64) -> Step {
    let a = 0.8 * flat.contact.radius;
    let start = dimple(model, &flat.u, a, a * a / (r + 0.5 * h));
    let opt = Options { max_iterations: 60, ..Options::default() };
    solve_at(model, plate, e, flat.delta, &start, &flat.contact.stick, opt)
}

/// Pushes the central part (r < radius) of a state down by a smooth dimple of depth `depth`
/// (through the whole thickness): the perturbation that leads Newton from the flattened
/// state to the inverted one.
pub fn dimple(model: &Model, u: &[f64], radius: f64, depth: f64) -> Vec<f64> {
    let mut out = u.to_vec();
    for (i, x) in model.mesh.nodes.iter().enumerate() {
        if x[0] < radius {
            let q = 1.0 - (x[0] / radius).powi(2);
            out[2 * i + 1] -= depth * q * q;
        }
    }
    out
}

#[cfg(test)]
mod tests;
