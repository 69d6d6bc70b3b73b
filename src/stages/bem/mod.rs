//! Stage kinds for the Chapter 4 boundary element model: one sliding point per task
//! (`bem.sweep`), the fields of one point (`bem.profile`), the maximum over V0
//! (`bem.maxima`) and, in `pulloff`, the pull-off load (`bem.pulloff`).

pub mod pulloff;

use super::material::with_material_fields;
use crate::stages::values::{bound, finite};
use anyhow::Result;
use physics::bem::kernel::Pressure;
use physics::bem::solver::{self, Mesh, Params, Solution, Start};
use pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A point whose solver stopped before convergence: the task fails with the solver's own
/// reason for stopping (`bem::solver::Termination`), not a table of an unconverged state.
#[derive(Debug, thiserror::Error)]
#[error("the point did not converge ({}: residual {residual:e} after {iterations} iterations)", termination.name())]
pub struct NotConverged {
    pub termination: physics::bem::solver::Termination,
    pub residual: f64,
    pub iterations: usize,
}

with_material_fields! {
#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct BemParams {
    /// Maugis-Tabor parameter lambda (Eq. 4.9), > 0 (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub lambda: f64,
    /// Dimensionless load W (Eq. 4.6), nonzero (sweepable). Negative: a tensile load (the
    /// cylinder beneath the substrate, Chapter 5), reached on the stable branch by walking
    /// down from |W| by pseudo-arclength continuation; beyond the pull-off the point is
    /// reported as not converged.
    pub W: f64,
    /// Modulus ratio k = E0/E_inf in (0, 1) (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub k: f64,
    /// Dimensionless speed V0 = v tau / a0 (Eq. 4.18; a0 the Hertz half-width of |W|), >= 0
    /// (sweepable).
    #[schemars(range(min = 0))]
    pub V0: f64,
    /// A fixed number of elements (the error is then estimated against n/2); default: the
    /// mesh is chosen from `rel_tol`.
    #[serde(default)]
    #[schemars(range(min = 16, max = 32_000))]
    pub n: Option<usize>,
    /// Half-length of the domain in units of beta; default: chosen from lambda, W and rel_tol
    /// (`bem::solver::domain_half_length`).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub half_length: Option<f64>,
    /// Requested relative accuracy of mu* (default 1e-3): starting from
    /// `bem::solver::starting_mesh`, the number of elements is doubled until the Richardson
    /// error estimate meets it, up to `n_max`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub rel_tol: Option<f64>,
    /// The largest mesh of the refinement (default 16000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 16, max = 32_000))]
    pub n_max: Option<usize>,
    /// Newton's tolerance on the max-norm residual in units of H (default 1e-9,
    /// `bem::solver::TOLERANCE`); for the accuracy-cost bench.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub newton_tol: Option<f64>,
    /// A stage of `needs` whose rows hold converged states (a `bem.profile`'s: `X`, `H`,
    /// `approach`), best read row by row (`needs: [{stage: S, match: [lambda, W, k]}]`): the
    /// refinement's first mesh starts by Newton from the state, among those of this
    /// lambda, W, k and material, at the speed nearest V0 (in log V0), instead of the
    /// continuation from the relaxed state (the continuation if that fails). mu* changes
    /// within Newton's tolerance only; without such rows the point is solved from scratch.
    /// Not with a fixed `n`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<String>,
    /// How the pressure varies over the mesh: `linear` between the element centres (the
    /// default: second order at every speed) or `uniform` on each element (the thesis'
    /// strips, Eq. 4.12: first order where the elements are longer than the creep length,
    /// as at low speed; docs/bem.md, "Discretisation").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<PressureParam>,
}
}

/// `pressure` of `bem.sweep`, `bem.profile` and `bem.pulloff`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum PressureParam {
    Linear,
    Uniform,
}

impl PressureParam {
    /// The solver's `Pressure` (`Linear` when not given).
    pub fn physics(p: Option<PressureParam>) -> Pressure {
        match p {
            Some(PressureParam::Uniform) => Pressure::Uniform,
            Some(PressureParam::Linear) | None => Pressure::Linear,
        }
    }
}

impl BemParams {
    fn physics(&self) -> Params {
        Params {
            spectrum: self.material().spectrum(),
            newton_tol: self.newton_tol.unwrap_or(solver::TOLERANCE),
            pressure: PressureParam::physics(self.pressure),
            ..Params::sls(self.lambda, self.W, self.k, self.V0)
        }
    }

    fn rel_tol(&self) -> f64 {
        self.rel_tol.unwrap_or(solver::DEFAULT_REL_TOL)
    }

    /// The mesh of a fixed-n solve, or the first mesh of a solve to tolerance.
    fn mesh(&self) -> Mesh {
        let p = self.physics();
        let start = solver::starting_mesh(&p, self.rel_tol());
        let half_length = self.half_length.unwrap_or(start.half_length);
        let n = self.n.unwrap_or_else(|| (start.n as f64 * half_length / start.half_length).ceil() as usize);
        Mesh { n, half_length }
    }

    /// The memory its solves may allocate: on its fixed mesh, or on the finest the
    /// refinement may reach (`n_max`).
    fn memory_bytes(&self) -> u64 {
        let n = self.n.unwrap_or_else(|| self.n_max.unwrap_or(solver::DEFAULT_N_MAX).max(self.mesh().n));
        solver::memory_bound(n)
    }

    /// Solves the point at `physics` (this point's mesh rules) with its error estimate.
    fn solve_at(&self, physics: &Params) -> (Solution, f64) {
        let mesh = self.mesh();
        match self.n {
            Some(_) => solver::solve_with_estimate(physics, mesh),
            None => {
                solver::solve_to_tolerance(physics, mesh, self.rel_tol(), self.n_max.unwrap_or(solver::DEFAULT_N_MAX))
            }
        }
    }

    /// The stage `start` names (which must be in `needs`).
    fn referenced_stages(&self) -> Vec<(String, String)> {
        self.start.iter().map(|s| ("start".to_string(), s.clone())).collect()
    }

    /// The point solved, from the state its `start` rows give if any (`start_state`); the
    /// speed of that state, if one was used.
    fn solve(&self, inputs: &Inputs) -> Result<(Solution, f64, Option<f64>)> {
        let physics = self.physics();
        Ok(match self.start_state(inputs)? {
            Some((v0, start)) => {
                let (s, estimate) = self.solve_near(&physics, Some(&start));
                (s, estimate, Some(v0))
            }
            None => {
                let (s, estimate) = self.solve_at(&physics);
                (s, estimate, None)
            }
        })
    }

    /// The state named by `start`: of the rows of that stage with this point's lambda, W, k
    /// and material, those of the speed nearest V0 in log V0 (the lower of two equally
    /// near), with that speed. None without `start` or without such rows.
    fn start_state(&self, inputs: &Inputs) -> Result<Option<(f64, Start)>> {
        let Some(stage) = &self.start else { return Ok(None) };
        let t = inputs.table(stage)?;
        if t.n_rows() == 0 {
            return Ok(None);
        }
        let column = |c: &str| match t.column(c) {
            Some(ColumnData::F64(v)) => Ok(v.as_slice()),
            _ => Err(anyhow::anyhow!(
                "`start`: stage `{stage}` has no numeric column `{c}` (a `bem.profile`'s rows hold the states)"
            )),
        };
        let (lambda, w, k, v0) = (column("lambda")?, column("W")?, column("k")?, column("V0")?);
        let (x, h, approach) = (column("X")?, column("H")?, column("approach")?);
        // (The SLS has no `material` column.)
        let materials = |t: &Table| match t.column("material") {
            Some(ColumnData::Str(v)) => Some(v.clone()),
            _ => None,
        };
        let own = materials(&self.parameter_columns(1)).map(|v| v[0].clone());
        let theirs = materials(t);
        let material = |i: usize| theirs.as_ref().map(|v| &v[i]);
        let rows: Vec<usize> = (0..t.n_rows())
            .filter(|&i| lambda[i] == self.lambda && w[i] == self.W && k[i] == self.k && material(i) == own.as_ref())
            .collect();
        let mut speeds: Vec<f64> = rows.iter().map(|&i| v0[i]).collect();
        speeds.sort_by(f64::total_cmp);
        speeds.dedup();
        let distance = |v: f64| (v.max(f64::MIN_POSITIVE).ln() - self.V0.max(f64::MIN_POSITIVE).ln()).abs();
        let Some(nearest) =
            speeds.into_iter().min_by(|a, b| distance(*a).total_cmp(&distance(*b)).then(a.total_cmp(b)))
        else {
            return Ok(None);
        };
        let rows: Vec<usize> = rows.into_iter().filter(|&i| v0[i] == nearest).collect();
        let start = Start {
            x: rows.iter().map(|&i| x[i]).collect(),
            h: rows.iter().map(|&i| h[i]).collect(),
            delta: approach[rows[0]],
        };
        if start.x.len() < 2 || start.x.windows(2).any(|p| p[1] <= p[0]) {
            anyhow::bail!("`start`: the rows of stage `{stage}` at V0 = {nearest} are not one profile (X must rise)");
        }
        Ok(Some((nearest, start)))
    }

    /// `solve_at`, the refinement's first level started from `near` (the state of a
    /// converged solve of the same point at another speed) when there is one and the mesh
    /// is not fixed.
    fn solve_near(&self, physics: &Params, near: Option<&Start>) -> (Solution, f64) {
        let n_max = self.n_max.unwrap_or(solver::DEFAULT_N_MAX);
        match self.n {
            Some(_) => self.solve_at(physics),
            None => solver::solve_to_tolerance_from(physics, self.mesh(), self.rel_tol(), n_max, near),
        }
    }

    fn validate(&self) -> Vec<FieldError> {
        let mut e = Vec::new();
        if !(self.W != 0.0 && self.W.is_finite()) {
            e.push(FieldError::new("W", format!("must be nonzero and finite, got {}", self.W)));
        }
        self.material().validate(&mut e);
        if self.start.is_some() && self.n.is_some() {
            e.push(FieldError::new("start", "starts the refinement's first mesh: not with a fixed `n`"));
        }
        e
    }

    /// The parameters as columns; a material other than the SLS adds `s` (power law, -1
    /// otherwise) and a `material` description.
    fn parameter_columns(&self, rows: usize) -> Table {
        let t = Table::new()
            .with_f64("lambda", vec![self.lambda; rows])
            .with_f64("W", vec![self.W; rows])
            .with_f64("k", vec![self.k; rows])
            .with_f64("V0", vec![self.V0; rows]);
        let m = self.material();
        if m.is_sls() {
            t
        } else {
            t.with_f64("s", vec![self.s.unwrap_or(-1.0); rows])
                .with("material", ColumnData::Str(vec![m.describe(); rows]))
        }
    }
}

fn extremes(s: &Solution) -> (f64, f64) {
    let max = s.p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let min = s.p.iter().copied().fold(f64::INFINITY, f64::min);
    (finite(max), finite(min))
}

/// One sliding (or rolling) point: friction and its parts, the rolling friction force
/// F_T* = mu* |W| (Eq. 5.6), contact edges, approach, extreme pressures, solver diagnostics
/// and the Richardson error estimate of mu*.
pub struct BemSweep;

impl Kind for BemSweep {
    const NAME: &'static str = "bem.sweep";
    const VERSION: u32 = 20;
    const DOC: &'static str = "Chapter 4 BEM: friction mu* (Eq. 4.16) of a cylinder sliding on an adhesive SLS half-plane, one point per task";
    const SWEEPABLE: &'static [&'static str] = &["lambda", "W", "k", "V0", "s"];
    const COLUMNS: &'static [&'static str] = &[
        "lambda",
        "W",
        "k",
        "V0",
        "s",
        "material",
        "mu_star",
        "mu_adh",
        "mu_comp",
        "F_T",
        "x_lead",
        "x_trail",
        "approach",
        "p_max_bar",
        "p_min_bar",
        "converged",
        "termination",
        "iterations",
        "residual",
        "error_estimate",
        "n",
        "half_length",
        "zone_elements",
        "start_V0",
        "wall_time_s",
    ];
    type Params = BemParams;

    fn validate(p: &BemParams) -> Vec<FieldError> {
        p.validate()
    }

    fn memory_bytes(p: &Self::Params) -> Option<u64> {
        Some(p.memory_bytes())
    }

    fn referenced_stages(p: &BemParams) -> Vec<(String, String)> {
        p.referenced_stages()
    }

    fn run(p: &BemParams, inputs: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let (s, estimate, started) = p.solve(inputs)?;
        let f = s.friction();
        let (lead, trail) = s.contact_edges().unwrap_or((0.0, 0.0));
        let (p_max, p_min) = extremes(&s);
        let ok = s.converged() && f.mu_star.is_finite();
        // Why the solver stopped; a converged state whose friction is not finite is not one.
        let termination = if s.converged() && !ok { "non_finite_friction" } else { s.termination.name() };
        let t = p
            .parameter_columns(1)
            .with_f64("mu_star", vec![finite(f.mu_star)])
            .with_f64("mu_adh", vec![finite(f.mu_adh)])
            .with_f64("mu_comp", vec![finite(f.mu_comp)])
            .with_f64("F_T", vec![finite(f.mu_star * p.W.abs())])
            .with_f64("x_lead", vec![finite(lead)])
            .with_f64("x_trail", vec![finite(trail)])
            .with_f64("approach", vec![finite(s.delta)])
            .with_f64("p_max_bar", vec![p_max])
            .with_f64("p_min_bar", vec![p_min])
            .with("converged", ColumnData::Bool(vec![ok]))
            .with("termination", ColumnData::Str(vec![termination.to_string()]))
            .with("iterations", ColumnData::I64(vec![s.cost.iterations as i64]))
            .with_f64("residual", vec![bound(s.residual)])
            .with_f64("error_estimate", vec![bound(estimate)])
            .with("n", ColumnData::I64(vec![s.mesh.n as i64]))
            .with_f64("half_length", vec![s.mesh.half_length])
            // Elements per cohesive zone (`solver::zone_elements`), a meshing diagnostic.
            .with_f64("zone_elements", vec![finite(solver::zone_elements(p.lambda, s.mesh))]);
        // With `start`: the speed of the state it started from (-1: none matched).
        let t = match &p.start {
            Some(_) => t.with_f64("start_V0", vec![started.unwrap_or(-1.0)]),
            None => t,
        };
        Ok(t.with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64()]).into())
    }
}

/// The fields of one point: P(X), U(X), H(X), the friction integrand P dU/dX and its
/// multiple whose integral is mu* (Eq. 4.16), the deformed surface Z = -U and the
/// indenter Z = X^2/2 - Delta (Z towards the indenter; the gap is their difference); on
/// every row the point's mu*, its error estimate (as `bem.sweep`'s), the elements and the
/// wall time.
pub struct BemProfile;

impl Kind for BemProfile {
    const NAME: &'static str = "bem.profile";
    const VERSION: u32 = 18;
    const DOC: &'static str =
        "Chapter 4 BEM: pressure P(X), displacement U(X), gap H(X) and friction integrand P dU/dX of one point";
    const SWEEPABLE: &'static [&'static str] = &["lambda", "W", "k", "V0", "s"];
    const COLUMNS: &'static [&'static str] = &[
        "lambda",
        "W",
        "k",
        "V0",
        "s",
        "material",
        "X",
        "P",
        "U",
        "H",
        "P_dU_dX",
        "mu_integrand",
        "surface",
        "indenter",
        "mu_star",
        "error_estimate",
        "n",
        "zone_elements",
        "approach",
        "wall_time_s",
    ];
    type Params = BemParams;

    fn validate(p: &BemParams) -> Vec<FieldError> {
        p.validate()
    }

    fn memory_bytes(p: &Self::Params) -> Option<u64> {
        Some(p.memory_bytes())
    }

    fn referenced_stages(p: &BemParams) -> Vec<(String, String)> {
        p.referenced_stages()
    }

    fn run(p: &BemParams, inputs: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let (s, estimate, _) = p.solve(inputs)?;
        if !s.converged() {
            return Err(NotConverged {
                termination: s.termination,
                residual: s.residual,
                iterations: s.cost.iterations,
            }
            .into());
        }
        let two_a = 2.0 * s.mesh.a();
        let integrand: Vec<f64> = (0..s.p.len()).map(|j| s.p[j] * (s.u_edges[j + 1] - s.u_edges[j]) / two_a).collect();
        // Eq. 4.16: mu* = (sqrt(pi)/2) lambda W^(-3/2) Int P dU/dX dX (ERRATA 3).
        let pre = std::f64::consts::PI.sqrt() / 2.0 * p.lambda / p.W.abs().powf(1.5);
        let n = s.x.len();
        let t = p
            .parameter_columns(n)
            .with_f64("X", s.x.clone())
            .with_f64("P", s.p.clone())
            .with_f64("U", s.u.clone())
            .with_f64("H", s.h.clone())
            .with_f64("P_dU_dX", integrand.clone())
            .with_f64("mu_integrand", integrand.iter().map(|v| pre * v).collect())
            .with_f64("surface", s.u.iter().map(|u| -u).collect())
            .with_f64("indenter", s.x.iter().map(|x| 0.5 * x * x - s.delta).collect())
            // The point's friction and its error estimate, as `bem.sweep` reports them.
            .with_f64("mu_star", vec![finite(s.friction().mu_star); n])
            .with_f64("error_estimate", vec![estimate.min(f64::MAX); n])
            .with("n", ColumnData::I64(vec![s.mesh.n as i64; n]))
            .with_f64("zone_elements", vec![finite(solver::zone_elements(p.lambda, s.mesh)); n])
            // The approach Delta: with X and H, the state a `start` reads.
            .with_f64("approach", vec![finite(s.delta); n])
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64(); n]);
        Ok(t.into())
    }
}

fn default_v0_range() -> [f64; 2] {
    [1e-3, 1e3]
}
fn default_grid() -> usize {
    13
}
fn default_log_tol() -> f64 {
    0.01
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct MaximaParams {
    /// Maugis-Tabor parameter (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub lambda: f64,
    /// Dimensionless load (sweepable).
    pub W: f64,
    /// Modulus ratio k = E0/E_inf (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub k: f64,
    /// Speeds searched, [from, to].
    #[serde(default = "default_v0_range")]
    pub V0_range: [f64; 2],
    /// Log-spaced bracketing points over the range.
    #[serde(default = "default_grid")]
    #[schemars(range(min = 3, max = 1000))]
    pub grid: usize,
    /// Golden-section tolerance in log10 V0.
    #[serde(default = "default_log_tol")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub log_tol: f64,
    /// Mesh rules of each solve, as in `bem.sweep`.
    #[serde(default)]
    #[schemars(range(min = 16, max = 32_000))]
    pub n: Option<usize>,
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub half_length: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub rel_tol: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 16, max = 32_000))]
    pub n_max: Option<usize>,
}

impl MaximaParams {
    fn point(&self) -> BemParams {
        BemParams {
            lambda: self.lambda,
            W: self.W,
            k: self.k,
            V0: 1.0,
            n: self.n,
            half_length: self.half_length,
            rel_tol: self.rel_tol,
            n_max: self.n_max,
            newton_tol: None,
            start: None,
            pressure: None,
            s: None,
            tau_ratio: None,
            per_decade: None,
            prony: None,
        }
    }
}

/// The maximum over V0 of mu* for one (lambda, W, k) (Figs. 4.6-4.7).
pub struct BemMaxima;

impl Kind for BemMaxima {
    const NAME: &'static str = "bem.maxima";
    const VERSION: u32 = 20;
    const DOC: &'static str =
        "Chapter 4 BEM: maximum over V0 of mu* for one (lambda, W, k), by bracketing and golden-section search";
    const SWEEPABLE: &'static [&'static str] = &["lambda", "W", "k"];
    const COLUMNS: &'static [&'static str] = &[
        "lambda",
        "W",
        "k",
        "mu_star_max",
        "V0_at_max",
        "mu_adh",
        "mu_comp",
        "error_estimate",
        "evaluations",
        "iterations",
        "converged",
        "wall_time_s",
    ];
    type Params = MaximaParams;

    fn validate(p: &MaximaParams) -> Vec<FieldError> {
        let mut e = p.point().validate();
        let [a, b] = p.V0_range;
        if !(a > 0.0 && b > a) {
            e.push(FieldError::new("V0_range", format!("needs 0 < from < to, got [{a}, {b}]")));
        }
        e
    }

    fn memory_bytes(p: &Self::Params) -> Option<u64> {
        Some(p.point().memory_bytes())
    }

    fn run(p: &MaximaParams, _: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let point = p.point();
        let m = physics::bem::maxima::max_over_speed(
            &point.physics(),
            p.V0_range[0],
            p.V0_range[1],
            p.grid,
            p.log_tol,
            |physics, near| point.solve_near(physics, near.and_then(Solution::start).as_ref()),
        );
        let t = Table::new()
            .with_f64("lambda", vec![p.lambda])
            .with_f64("W", vec![p.W])
            .with_f64("k", vec![p.k])
            .with_f64("mu_star_max", vec![finite(m.friction.mu_star)])
            .with_f64("V0_at_max", vec![m.v0])
            .with_f64("mu_adh", vec![finite(m.friction.mu_adh)])
            .with_f64("mu_comp", vec![finite(m.friction.mu_comp)])
            .with_f64("error_estimate", vec![m.error_estimate.min(f64::MAX)])
            .with("evaluations", ColumnData::I64(vec![m.evaluations as i64]))
            .with("iterations", ColumnData::I64(vec![m.iterations as i64]))
            .with("converged", ColumnData::Bool(vec![m.all_converged]))
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64()]);
        Ok(t.into())
    }
}

pub fn register(r: &mut Registry) {
    r.add::<BemSweep>().add::<BemProfile>().add::<BemMaxima>();
    pulloff::register(r);
}
