//! Stage kind `bem.pulloff`: the pull-off load of the Chapter 4/5 model at one speed
//! (`bem::solver::branch::pull_off`), with the contact at pull-off (thesis Fig. 5.8).

use super::PressureParam;
use crate::stages::values::finite;
use anyhow::Result;
use physics::bem::solver::branch::{pull_off, PullOff};
use physics::bem::solver::{self, ErrorShares, Mesh, Params};
use pipeline::kind::{Inputs, Kind, Output, Registry};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct PullOffParams {
    /// Maugis-Tabor parameter lambda (Eq. 4.9), > 0 (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub lambda: f64,
    /// Modulus ratio k = E0/E_inf in (0, 1) (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub k: f64,
    /// Speed V = v tau/beta >= 0 (sweepable): independent of the load, which is the unknown
    /// here; the table also gives V0 = V/a0 with a0 the Hertz half-width of the pull-off load.
    #[schemars(range(min = 0))]
    pub V: f64,
    /// A fixed number of elements (default: from `bem::solver::starting_mesh`, doubled until
    /// the Richardson estimate of the pull-off load meets rel_tol).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 16, max = 32_000))]
    pub n: Option<usize>,
    /// Requested relative accuracy of the pull-off load (default 1e-3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub rel_tol: Option<f64>,
    /// How the pressure varies over the mesh, as in `bem.sweep` (default `linear`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<PressureParam>,
}

/// The load the walk starts from.
const W_START: f64 = 0.1;
/// Bracket of the golden-section search in the approach, relative to the first step.
const APPROACH_TOL: f64 = 1e-3;

/// The pull-off load at one (lambda, k, V), with its error estimate: the Richardson
/// estimate of the same search on half the elements, and the domain's truncation. Not
/// converged on a mesh with less than one element per cohesive zone (`zone_elements`,
/// `bem::solver::MIN_ZONE_ELEMENTS`).
pub struct BemPullOff;

impl Kind for BemPullOff {
    const NAME: &'static str = "bem.pulloff";
    const VERSION: u32 = 15;
    const DOC: &'static str =
        "Chapters 4-5 BEM: pull-off load (minimum W on the equilibrium branch, walked by pseudo-arclength in approach and load) at speed V";
    const SWEEPABLE: &'static [&'static str] = &["lambda", "k", "V"];
    const COLUMNS: &'static [&'static str] = &[
        "lambda",
        "k",
        "V",
        "V0",
        "W_pulloff",
        "A",
        "two_A",
        "x_lead",
        "x_trail",
        "mu_star",
        "F_T",
        "converged",
        "evaluations",
        "iterations",
        "error_estimate",
        "n",
        "half_length",
        "zone_elements",
        "wall_time_s",
    ];
    type Params = PullOffParams;

    fn memory_bytes(p: &Self::Params) -> Option<u64> {
        Some(solver::memory_bound(p.n.unwrap_or(solver::DEFAULT_N_MAX)))
    }

    fn run(p: &PullOffParams, _: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let start = Params { pressure: PressureParam::physics(p.pressure), ..Params::sls(p.lambda, W_START, p.k, 0.0) }
            .with_v(p.V);
        let rel_tol = p.rel_tol.unwrap_or(solver::DEFAULT_REL_TOL);
        let first = solver::starting_mesh(&start, rel_tol);
        // The search on a mesh of n elements (None if the starting solve fails).
        let search = |n: usize| -> (Option<PullOff>, usize) {
            let s = solver::solve(&start, Mesh { n, ..first });
            (s.converged().then(|| pull_off(&s, APPROACH_TOL)), s.cost.iterations)
        };
        // The mesh's share: Richardson at second order (the refinement stops on it).
        let estimate_of = |f: &Option<PullOff>, c: &Option<PullOff>| match (f, c) {
            (Some(f), Some(c)) if f.converged && c.converged => (f.load - c.load).abs() / 3.0,
            _ => f64::MAX,
        };
        // Richardson on the pull-off load itself: n doubles until the estimate meets rel_tol.
        let mut n = p.n.unwrap_or(first.n);
        let (mut coarse, _) = search(n / 2);
        let (mut po, mut start_iterations) = search(n);
        let mut estimate = estimate_of(&po, &coarse);
        while p.n.is_none()
            && estimate > rel_tol * po.as_ref().map_or(0.0, |r| r.load.abs())
            && 2 * n <= solver::DEFAULT_N_MAX
            && po.as_ref().is_some_and(|r| r.converged)
        {
            n *= 2;
            coarse = po;
            (po, start_iterations) = search(n);
            estimate = estimate_of(&po, &coarse);
        }
        let converged = po.as_ref().is_some_and(|r| r.converged);
        let fine_mesh = Mesh { n, ..first };
        // The reported error, as `bem.sweep`'s (`solver::ErrorShares::reported`): the mesh's
        // share with Roache's safety factor, plus twice the load the Lennard-Jones tail
        // carries beyond the domain.
        let reported =
            ErrorShares { mesh: estimate, domain: solver::domain_load_error(&start, first.half_length) }.reported();
        // A cohesive zone shorter than an element: the refinement's difference bounds nothing
        // (`solver::MIN_ZONE_ELEMENTS`), so the mesh has not converged the pull-off whatever
        // the search did.
        let zone_elements = solver::zone_elements(p.lambda, Mesh { n, ..first });
        let resolved = zone_elements >= solver::MIN_ZONE_ELEMENTS;
        let (load, width, edges, mu, evaluations, iterations) = match &po {
            Some(r) => (
                r.load,
                r.solution.adhered_half_width().unwrap_or(0.0),
                r.solution.contact_edges().unwrap_or((0.0, 0.0)),
                r.solution.friction().mu_star,
                r.cost.newton_solves,
                r.cost.iterations,
            ),
            None => (0.0, 0.0, (0.0, 0.0), 0.0, 0, start_iterations),
        };
        let v0 = if load != 0.0 { p.V / Params { w: load, ..start.clone() }.a0() } else { 0.0 };
        let t = Table::new()
            .with_f64("lambda", vec![p.lambda])
            .with_f64("k", vec![p.k])
            .with_f64("V", vec![p.V])
            .with_f64("V0", vec![finite(v0)])
            .with_f64("W_pulloff", vec![finite(load)])
            .with_f64("A", vec![finite(width)])
            .with_f64("two_A", vec![finite(2.0 * width)])
            .with_f64("x_lead", vec![finite(edges.0)])
            .with_f64("x_trail", vec![finite(edges.1)])
            .with_f64("mu_star", vec![finite(mu)])
            .with_f64("F_T", vec![finite(mu * load.abs())])
            .with("converged", ColumnData::Bool(vec![converged && resolved && load.is_finite()]))
            .with("evaluations", ColumnData::I64(vec![evaluations as i64]))
            .with("iterations", ColumnData::I64(vec![iterations as i64]))
            .with_f64("error_estimate", vec![reported])
            .with("n", ColumnData::I64(vec![fine_mesh.n as i64]))
            .with_f64("half_length", vec![fine_mesh.half_length])
            .with_f64("zone_elements", vec![finite(zone_elements)])
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64()]);
        Ok(t.into())
    }
}

pub fn register(r: &mut Registry) {
    r.add::<BemPullOff>();
}
