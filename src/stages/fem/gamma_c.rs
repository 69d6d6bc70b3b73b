//! Stage kinds of the buckling-suppression map of Chapter 3 (Section 3.4, Fig. 3.9):
//! `fem.gamma_c` (the critical adhesion at (h/R, mu) by a safeguarded secant on where the
//! snap lies, `fem::critical::bracket`, one task per point so
//! that every point is cached on its own) and `fem.gamma_c_map` (the map: gamma_c(h/R) per
//! mu closed at the thickness of `fem.buckling_limit`, with Eq. 3.7).

#![allow(non_snake_case)] // parameter names as in the thesis: h_over_R, gamma_over_Eh

use super::map::MapModel;
use crate::stages::values::finite;
use anyhow::{bail, Result};
use physics::fem::critical::{bracket, probe, retrying};
use pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

fn default_guess() -> f64 {
    2e-2
}
fn default_growth() -> f64 {
    2.0
}
fn default_gamma_max() -> f64 {
    0.1
}
fn default_rel_tol() -> f64 {
    0.1
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GammaCParams {
    /// Thickness over radius h/R (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 0.5))]
    pub h_over_R: f64,
    /// Coulomb friction coefficient (sweepable; default 0).
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub mu: f64,
    /// The first gamma/(E h) tried per unit of the adhesionless snap's distance from
    /// delta_max: the first trial is guess (1 - delta_snap(0) / delta_max) (default 2e-2;
    /// `fem::critical::bracket`), the factor of the steps taken without a secant estimate
    /// (default 2), the largest gamma/(E h) tried (default 0.1).
    #[serde(default = "default_guess")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub guess: f64,
    #[serde(default = "default_growth")]
    #[schemars(extend("exclusiveMinimum" = 1.0))]
    pub growth: f64,
    #[serde(default = "default_gamma_max")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub gamma_max: f64,
    /// Bracketing tolerance: the search stops when gamma_hi / gamma_lo - 1 < rel_tol.
    #[serde(default = "default_rel_tol")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 10.0))]
    pub rel_tol: f64,
    /// The Lennard-Jones range g0 in mm (sweepable; default: `model.g0`; the default mesh
    /// follows it), for studies of gamma_c's limit as the regularisation goes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub g0: Option<f64>,
    /// The apex force of the imperfection in units of F_c = E h^3 / R (sweepable; default:
    /// `model.imperfection.apex_force`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0))]
    pub apex_force: Option<f64>,
    /// The dimple depth of the imperfection in units of h (sweepable; default:
    /// `model.imperfection.dimple`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dimple: Option<f64>,
    #[serde(default)]
    pub model: MapModel,
}

impl GammaCParams {
    /// The model with the point's range g0 and imperfection.
    fn point_model(&self) -> MapModel {
        self.model.at_point(self.g0, self.apex_force, self.dimple)
    }
}

/// The critical adhesion at one (h/R, mu).
pub struct FemGammaC;

impl Kind for FemGammaC {
    const NAME: &'static str = "fem.gamma_c";
    const VERSION: u32 = 29;
    const DOC: &'static str =
        "Chapter 3: critical adhesion gamma_c/(E h) above which the shell does not snap, by bracketing, with Eq. 3.7";
    const SWEEPABLE: &'static [&'static str] = &["h_over_R", "mu", "g0", "apex_force", "dimple"];
    const COLUMNS: &'static [&'static str] = &[
        "h_over_R",
        "mu",
        "g0",
        "apex_force",
        "dimple",
        "delta_max_over_R",
        "criterion",
        "gamma_max_over_Eh",
        "n_meridian",
        "gamma_c_over_Eh",
        "gamma_lo_over_Eh",
        "gamma_hi_over_Eh",
        "error_estimate",
        "rel_tol",
        "found",
        "reliable",
        "buckles_without_adhesion",
        "gamma_c_N_per_mm",
        "r_over_R",
        "eq3_7_over_Eh",
        "F_buckling_bar",
        "probes",
        "unconverged_probes",
        "lu_factorizations",
        "wall_time_s",
    ];
    type Params = GammaCParams;

    fn validate(p: &GammaCParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        let m = p.point_model();
        m.validate(&mut e);
        m.validate_mesh(p.h_over_R, &mut e);
        e
    }

    fn memory_bytes(p: &GammaCParams) -> Option<u64> {
        Some(p.point_model().memory_bytes(p.h_over_R, false))
    }

    fn run(p: &GammaCParams, _: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let m = &p.point_model();
        let model = m.shell(p.h_over_R);
        let scale = m.E * m.h(p.h_over_R);
        let opt = m.options(false);
        let b = bracket(
            retrying(|g| probe(&model, &m.plate(&model, p.h_over_R, g / scale, p.mu), m.E, g, opt)),
            p.guess * scale,
            p.growth,
            p.gamma_max * scale,
            p.rel_tol,
        );
        let mid = b.mid() / scale;
        let unconverged = b.probes.iter().filter(|q| !q.complete).count();
        let last = b.last_buckled().and_then(|q| q.buckling);
        let r = last.map_or(0.0, |j| j.radius_before / m.R);
        let buckles_at_zero = b.probes.first().is_some_and(|q| q.buckles());
        let point = Table::new()
            .with_f64("h_over_R", vec![p.h_over_R])
            .with_f64("mu", vec![p.mu])
            .with_f64("g0", vec![m.g0])
            .with_f64("apex_force", vec![m.imperfection.apex_force])
            .with_f64("dimple", vec![m.imperfection.dimple]);
        Ok(m.stated(point, 1)
            .with_f64("gamma_max_over_Eh", vec![p.gamma_max])
            .with("n_meridian", ColumnData::I64(vec![m.meridian_elements(p.h_over_R) as i64]))
            .with_f64("gamma_c_over_Eh", vec![finite(mid)])
            .with_f64("gamma_lo_over_Eh", vec![finite(b.lo / scale)])
            .with_f64("gamma_hi_over_Eh", vec![finite(b.hi / scale)])
            // The half-bracket; not found, gamma_c_over_Eh is only the bound gamma_max, and
            // the estimate is the value itself (no confidence).
            .with_f64("error_estimate", vec![finite(if b.found { 0.5 * (b.hi - b.lo) / scale } else { mid })])
            .with_f64("rel_tol", vec![p.rel_tol])
            .with("found", ColumnData::Bool(vec![b.found]))
            .with("reliable", ColumnData::Bool(vec![b.reliable()]))
            .with("buckles_without_adhesion", ColumnData::Bool(vec![buckles_at_zero]))
            .with_f64("gamma_c_N_per_mm", vec![finite(mid * scale)])
            .with_f64("r_over_R", vec![finite(r)])
            .with_f64("eq3_7_over_Eh", vec![finite(r.powi(4))])
            .with_f64("F_buckling_bar", vec![finite(last.map_or(0.0, |j| j.force_before * m.f_bar(p.h_over_R)))])
            .with("probes", ColumnData::I64(vec![b.probes.len() as i64]))
            .with("unconverged_probes", ColumnData::I64(vec![unconverged as i64]))
            .with("lu_factorizations", ColumnData::I64(vec![model.factorizations() as i64]))
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64()])
            .into())
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MapParams {
    /// The `fem.gamma_c` stage swept over h_over_R and mu.
    pub gamma_c: String,
    /// The `fem.buckling_limit` stage swept over mu (optional): each mu's boundary is closed
    /// at gamma_c = 0 there.
    #[serde(default)]
    pub limit: Option<String>,
}

/// The map of Fig. 3.9: gamma_c/(E h) against h/R for each mu, sorted, closed at the
/// no-buckling thickness, with the estimate of Eq. 3.7.
pub struct FemGammaCMap;

impl Kind for FemGammaCMap {
    const NAME: &'static str = "fem.gamma_c_map";
    const VERSION: u32 = 5;
    const DOC: &'static str =
        "Chapter 3: the buckling map gamma_c/(E h) vs h/R per mu (Fig. 3.9), from fem.gamma_c points";
    const COLUMNS: &'static [&'static str] = &[
        "mu",
        "h_over_R",
        "gamma_c_over_Eh",
        "gamma_lo_over_Eh",
        "gamma_hi_over_Eh",
        "error_estimate",
        "h_error_over_R",
        "eq3_7_over_Eh",
        "found",
        "reliable",
        "delta_max_over_R",
        "criterion",
        "gamma_max_over_Eh",
    ];
    type Params = MapParams;

    fn referenced_stages(p: &MapParams) -> Vec<(String, String)> {
        let mut v = vec![("gamma_c".to_string(), p.gamma_c.clone())];
        if let Some(l) = &p.limit {
            v.push(("limit".to_string(), l.clone()));
        }
        v
    }

    fn run(p: &MapParams, inputs: &Inputs) -> Result<Output> {
        let t = inputs.table(&p.gamma_c)?;
        let col = |name: &str| t.f64_column(name);
        let (h, mu, g, lo, hi, eq) = (
            col("h_over_R")?,
            col("mu")?,
            col("gamma_c_over_Eh")?,
            col("gamma_lo_over_Eh")?,
            col("gamma_hi_over_Eh")?,
            col("eq3_7_over_Eh")?,
        );
        let (reliable, found, err) = (col("reliable")?, col("found")?, col("error_estimate")?);
        let (delta_max, gamma_max, criterion) =
            (col("delta_max_over_R")?, col("gamma_max_over_Eh")?, t.str_column("criterion")?);
        let mut rows: Vec<MapRow> = (0..h.len())
            .map(|i| MapRow {
                mu: mu[i],
                h: h[i],
                gamma_c: g[i],
                lo: lo[i],
                hi: hi[i],
                error: err[i],
                h_error: 0.0,
                eq3_7: eq[i],
                found: found[i] > 0.5,
                reliable: reliable[i] > 0.5,
                delta_max: delta_max[i],
                criterion: criterion[i].clone(),
                gamma_max: gamma_max[i],
            })
            .collect();
        if let Some(l) = &p.limit {
            let lt = inputs.table(l)?;
            let (lmu, lh, found) = (lt.f64_column("mu")?, lt.f64_column("h_limit_over_R")?, lt.f64_column("found")?);
            let (llo, lhi) = (lt.f64_column("h_lo_over_R")?, lt.f64_column("h_hi_over_R")?);
            let (ldelta, lcriterion) = (lt.f64_column("delta_max_over_R")?, lt.str_column("criterion")?);
            for i in (0..lmu.len()).filter(|&i| found[i] > 0.5) {
                rows.push(MapRow {
                    mu: lmu[i],
                    h: lh[i],
                    gamma_c: 0.0,
                    lo: 0.0,
                    hi: 0.0,
                    error: 0.0,
                    h_error: 0.5 * (lhi[i] - llo[i]),
                    eq3_7: 0.0,
                    found: true,
                    reliable: true,
                    delta_max: ldelta[i],
                    criterion: lcriterion[i].clone(),
                    gamma_max: 0.0,
                });
            }
        }
        if rows.is_empty() {
            bail!("stage `{}` has no points", p.gamma_c);
        }
        rows.sort_by(|a, b| a.mu.total_cmp(&b.mu).then(a.h.total_cmp(&b.h)));
        let c = |f: fn(&MapRow) -> f64| rows.iter().map(|r| finite(f(r))).collect::<Vec<f64>>();
        Ok(Table::new()
            .with_f64("mu", c(|r| r.mu))
            .with_f64("h_over_R", c(|r| r.h))
            .with_f64("gamma_c_over_Eh", c(|r| r.gamma_c))
            .with_f64("gamma_lo_over_Eh", c(|r| r.lo))
            .with_f64("gamma_hi_over_Eh", c(|r| r.hi))
            .with_f64("error_estimate", c(|r| r.error))
            .with_f64("h_error_over_R", c(|r| r.h_error))
            .with_f64("eq3_7_over_Eh", c(|r| r.eq3_7))
            .with("found", ColumnData::Bool(rows.iter().map(|r| r.found).collect()))
            .with("reliable", ColumnData::Bool(rows.iter().map(|r| r.reliable).collect()))
            .with_f64("delta_max_over_R", c(|r| r.delta_max))
            .with("criterion", ColumnData::Str(rows.iter().map(|r| r.criterion.clone()).collect()))
            .with_f64("gamma_max_over_Eh", c(|r| r.gamma_max))
            .into())
    }
}

/// One row of the map, a gamma_c point or a limit (where gamma_c is 0, found and reliable).
/// The error of h/R is none on a gamma_c point (h/R is given), the bisection's half-bracket
/// on a limit row; gamma_max is 0 on a limit row (no gamma was bracketed there).
struct MapRow {
    mu: f64,
    h: f64,
    gamma_c: f64,
    lo: f64,
    hi: f64,
    error: f64,
    h_error: f64,
    eq3_7: f64,
    found: bool,
    reliable: bool,
    delta_max: f64,
    criterion: String,
    gamma_max: f64,
}

pub fn register(r: &mut Registry) {
    r.add::<FemGammaC>().add::<FemGammaCMap>();
}
