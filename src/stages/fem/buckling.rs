//! Stage kinds of the snap-through of Chapter 3 (Section 3.4, Figs. 3.6 and 3.9), one task
//! per point so that every point is cached on its own: `fem.buckling` (one load-unload
//! cycle at (h/R, gamma/(E h), mu): buckles?, F_buckling, W) and `fem.buckling_limit` (the
//! thickness above which there is no snap at all, by bisection); the model they share with
//! `fem.gamma_c` (`MapModel`).

#![allow(non_snake_case)] // parameter names as in the thesis: h_over_R, gamma_over_Eh

use super::map::{MapModel, SnapCriterion};
use super::{declared_mesh_error, declared_w_mesh_error, snap_bracket};
use crate::stages::values::finite;
use anyhow::Result;
use physics::fem::critical::probe;
use physics::fem::cycle::{load_unload, Snap};
use physics::fem::mesh_study::{MeshStudy, Outcome};
use pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

fn default_true() -> bool {
    true
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BucklingParams {
    /// Thickness over radius h/R (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 0.5))]
    pub h_over_R: f64,
    /// Work of adhesion gamma/(E h) (sweepable; default 0).
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub gamma_over_Eh: f64,
    /// Coulomb friction coefficient (sweepable; default 0).
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub mu: f64,
    /// Also unload, for the dissipated energy W (default true; false stops at the snap).
    #[serde(default = "default_true")]
    pub dissipation: bool,
    /// Estimate the mesh's share of the errors of F_buckling and W at this point by a second
    /// cycle on twice the meridian elements, run alongside (`MeshStudy`; default false: the
    /// declared errors of the default mesh, none on other meshes). Three to four times the
    /// CPU time.
    #[serde(default)]
    pub mesh_study: bool,
    /// The apex force of the imperfection in units of F_c = E h^3 / R (sweepable; default:
    /// `model.imperfection.apex_force`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub apex_force: Option<f64>,
    /// The dimple depth of the imperfection in units of h (sweepable; default:
    /// `model.imperfection.dimple`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dimple: Option<f64>,
    #[serde(default)]
    pub model: MapModel,
}

impl BucklingParams {
    /// The model with the point's imperfection.
    fn point_model(&self) -> MapModel {
        self.model.at_point(None, self.apex_force, self.dimple)
    }
}

/// One cycle of the map: does the loading snap before delta_max, at what force, and the
/// energy dissipated over the cycle.
pub struct FemBuckling;

impl Kind for FemBuckling {
    const NAME: &'static str = "fem.buckling";
    const VERSION: u32 = 35;
    const DOC: &'static str =
        "Chapter 3: F_buckling, delta at it and the dissipated energy W at one (h/R, gamma/(E h), mu)";
    const SWEEPABLE: &'static [&'static str] = &["h_over_R", "gamma_over_Eh", "mu", "apex_force", "dimple"];
    const COLUMNS: &'static [&'static str] = &[
        "h_over_R",
        "gamma_over_Eh",
        "mu",
        "apex_force",
        "dimple",
        "delta_max_over_R",
        "criterion",
        "buckled",
        "F_buckling_bar",
        "F_contact_buckling_bar",
        "F_adhesive_buckling_bar",
        "F_buckling_error_bar",
        "F_buckling_mesh_error_bar",
        "delta_buckling_over_R",
        "delta_buckling_error_over_R",
        "r_over_R",
        "delta_landing_over_R",
        "W_bar",
        "W_Nmm",
        "W_error_bar",
        "W_error_Nmm",
        "W_mesh_error_Nmm",
        "W_friction_Nmm",
        "n_meridian",
        "mesh_error_source",
        "mesh_study_agrees",
        "complete",
        "max_iterations",
        "max_residual",
        "lu_factorizations",
        "wall_time_s",
    ];
    type Params = BucklingParams;

    fn memory_bytes(p: &BucklingParams) -> Option<u64> {
        Some(p.point_model().memory_bytes(p.h_over_R, p.mesh_study))
    }

    fn validate(p: &BucklingParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        let m = p.point_model();
        m.validate(&mut e);
        m.validate_mesh(p.h_over_R, &mut e);
        if p.dissipation && matches!(m.snap, SnapCriterion::Thesis(_)) {
            e.push(FieldError::new(
                "dissipation",
                "`snap: {thesis: ...}` runs the loading leg only: set `dissipation: false`",
            ));
        }
        e
    }

    fn run(p: &BucklingParams, _: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let m = &p.point_model();
        let n = m.meridian_elements(p.h_over_R);
        // The cycle on `n` meridian elements: (buckled, F, W and its path error, complete),
        // the snap and the cycle.
        let cycle_on = |n: usize| {
            let model = m.shell_with(p.h_over_R, n);
            let plate = m.plate(&model, p.h_over_R, p.gamma_over_Eh, p.mu);
            let c = load_unload(&model, &plate, m.E, m.options(p.dissipation));
            // Under `snap: landing` a loss of stability that never lands is no snap.
            let b = c.buckling.filter(|j| Snap::from(m.snap).counts(j));
            // The loop area only for a complete cycle (a partial one has no closed integral).
            let (w, w_error) =
                if p.dissipation && c.complete { (c.dissipated(), c.dissipated_error()) } else { (0.0, 0.0) };
            let friction = if p.dissipation && c.complete { c.friction_work(&plate.weights) } else { 0.0 };
            (b, w, w_error, (c, friction, model.factorizations()))
        };
        let ((b, w, w_error, (c, friction, lus)), finer) = if p.mesh_study {
            let (this, finer) = rayon::join(|| cycle_on(n), || cycle_on(2 * n));
            (this, Some(finer))
        } else {
            (cycle_on(n), None)
        };
        let study = finer
            .as_ref()
            .map(|(fb, fw, _, (fc, _, _))| MeshStudy::of(Outcome::of(&b, w, &c), Outcome::of(fb, *fw, fc)));
        let lus = lus + finer.as_ref().map_or(0, |(_, _, _, (_, _, n))| *n);
        let fb = m.f_bar(p.h_over_R);
        let h = m.h(p.h_over_R);
        let (iterations, residual) =
            c.points.iter().fold((0usize, 0.0f64), |(i, r), q| (i.max(q.step.iterations), r.max(q.step.residual)));
        // The mesh's share: the study's if one ran, else the declared errors of the default
        // mesh, else none.
        let (f_mesh, w_mesh, source) = match study {
            Some(st) => (st.f_error, st.w_error, "study"),
            None if m.default_mesh() => (
                b.map_or(0.0, |j| declared_mesh_error(j.force_before, true, p.mu)),
                declared_w_mesh_error(w, true, m.integration),
                "declared",
            ),
            None => (0.0, 0.0, "none"),
        };
        let point = Table::new()
            .with_f64("h_over_R", vec![p.h_over_R])
            .with_f64("gamma_over_Eh", vec![p.gamma_over_Eh])
            .with_f64("mu", vec![p.mu])
            .with_f64("apex_force", vec![m.imperfection.apex_force])
            .with_f64("dimple", vec![m.imperfection.dimple]);
        Ok(m.stated(point, 1)
            .with("buckled", ColumnData::Bool(vec![b.is_some()]))
            // The net plate force (contact minus adhesion) at the snap, and its two parts.
            .with_f64("F_buckling_bar", vec![finite(b.map_or(0.0, |j| j.force_before * fb))])
            .with_f64("F_contact_buckling_bar", vec![finite(b.map_or(0.0, |j| (j.force_before - j.pull_before) * fb))])
            .with_f64("F_adhesive_buckling_bar", vec![finite(b.map_or(0.0, |j| j.pull_before * fb))])
            // The bisection's bracket plus the mesh's share.
            .with_f64("F_buckling_error_bar", vec![finite(b.map_or(0.0, |j| (snap_bracket(&j) + f_mesh) * fb))])
            .with_f64("F_buckling_mesh_error_bar", vec![finite(f_mesh * fb)])
            .with_f64("delta_buckling_over_R", vec![finite(b.map_or(0.0, |j| j.delta / m.R))])
            .with_f64("delta_buckling_error_over_R", vec![finite(b.map_or(0.0, |j| (j.delta - j.delta_stable) / m.R))])
            .with_f64("r_over_R", vec![finite(b.map_or(0.0, |j| j.radius_before / m.R))])
            // Where the snap-through landed on the inverted branch (0: it did not, or only the
            // loading up to the snap was computed).
            .with_f64("delta_landing_over_R", vec![finite(b.map_or(0.0, |j| j.delta_after / m.R))])
            .with_f64("W_bar", vec![finite(w / (m.E * h.powi(3)))])
            .with_f64("W_Nmm", vec![finite(w)])
            // The load path's share of W's error (`Cycle::dissipated_error`) plus the mesh's.
            .with_f64("W_error_bar", vec![finite((w_error + w_mesh) / (m.E * h.powi(3)))])
            .with_f64("W_error_Nmm", vec![finite(w_error + w_mesh)])
            .with_f64("W_mesh_error_Nmm", vec![finite(w_mesh)])
            // The part of W done against friction on the quasi-static pieces of the cycle
            // (`Cycle::friction_work`); the rest is lost in the jumps and the adhesive
            // hysteresis.
            .with_f64("W_friction_Nmm", vec![finite(friction)])
            .with("n_meridian", ColumnData::I64(vec![n as i64]))
            // Where the mesh's share comes from: `study` (2 n elements run too), `declared`
            // (the default mesh's measured errors) or `none`.
            .with("mesh_error_source", ColumnData::Str(vec![source.to_string()]))
            .with("mesh_study_agrees", ColumnData::Bool(vec![study.is_none_or(|st| st.agrees)]))
            .with("complete", ColumnData::Bool(vec![c.complete]))
            .with("max_iterations", ColumnData::I64(vec![iterations as i64]))
            .with_f64("max_residual", vec![finite(residual)])
            .with("lu_factorizations", ColumnData::I64(vec![lus as i64]))
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64()])
            .into())
    }
}

fn default_h_lo() -> f64 {
    0.1
}
fn default_h_hi() -> f64 {
    0.4
}
fn default_h_tol() -> f64 {
    0.005
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LimitParams {
    /// Coulomb friction coefficient (sweepable; default 0).
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub mu: f64,
    /// Work of adhesion gamma/(E h) (default 0).
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub gamma_over_Eh: f64,
    /// The search interval of h/R (default [0.1, 0.4]) and its tolerance (default 0.005).
    #[serde(default = "default_h_lo")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 0.5))]
    pub h_lo: f64,
    #[serde(default = "default_h_hi")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 0.5))]
    pub h_hi: f64,
    #[serde(default = "default_h_tol")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub tol: f64,
    #[serde(default)]
    pub model: MapModel,
}

/// The thickness above which the shell does not snap at all (thesis: h/R = 0.235).
pub struct FemBucklingLimit;

impl Kind for FemBucklingLimit {
    const NAME: &'static str = "fem.buckling_limit";
    const VERSION: u32 = 24;
    const DOC: &'static str =
        "Chapter 3: the h/R above which the shell does not snap through before delta_max, by bisection";
    const SWEEPABLE: &'static [&'static str] = &["mu", "gamma_over_Eh"];
    const COLUMNS: &'static [&'static str] = &[
        "mu",
        "gamma_over_Eh",
        "delta_max_over_R",
        "criterion",
        "h_limit_over_R",
        "h_lo_over_R",
        "h_hi_over_R",
        "error_estimate",
        "found",
        "buckles_at_h_lo",
        "buckles_at_h_hi",
        "probes",
        "lu_factorizations",
        "wall_time_s",
    ];
    type Params = LimitParams;

    /// One cycle at a time, on the default mesh of the thickest shell bisected (it grows
    /// with R + h) unless the mesh is given: the larger of the two ends.
    fn memory_bytes(p: &LimitParams) -> Option<u64> {
        Some(p.model.memory_bytes(p.h_lo, false).max(p.model.memory_bytes(p.h_hi, false)))
    }

    fn validate(p: &LimitParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        if p.h_hi <= p.h_lo {
            e.push(FieldError::new("h_hi", format!("must exceed h_lo = {}, got {}", p.h_lo, p.h_hi)));
        }
        p.model.validate(&mut e);
        p.model.validate_mesh(p.h_hi, &mut e);
        e
    }

    fn run(p: &LimitParams, _: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let m = &p.model;
        let opt = m.options(false);
        let lus = std::cell::Cell::new(0);
        let buckles = |h: f64| {
            let model = m.shell(h);
            let answer = probe(&model, &m.plate(&model, h, p.gamma_over_Eh, p.mu), m.E, h, opt).buckles();
            lus.set(lus.get() + model.factorizations());
            answer
        };
        let (mut lo, mut hi) = (p.h_lo, p.h_hi);
        let mut probes = 2;
        let (at_lo, at_hi) = (buckles(lo), buckles(hi));
        let found = at_lo && !at_hi;
        if found {
            while hi - lo > p.tol {
                let mid = 0.5 * (lo + hi);
                probes += 1;
                if buckles(mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
        }
        let point = Table::new().with_f64("mu", vec![p.mu]).with_f64("gamma_over_Eh", vec![p.gamma_over_Eh]);
        Ok(m.stated(point, 1)
            .with_f64("h_limit_over_R", vec![if found { 0.5 * (lo + hi) } else { 0.0 }])
            .with_f64("h_lo_over_R", vec![lo])
            .with_f64("h_hi_over_R", vec![hi])
            // The half-bracket; without a limit in [h_lo, h_hi] (found = false, the limit 0 a
            // placeholder) no confidence: h_hi.
            .with_f64("error_estimate", vec![if found { 0.5 * (hi - lo) } else { p.h_hi }])
            .with("found", ColumnData::Bool(vec![found]))
            .with("buckles_at_h_lo", ColumnData::Bool(vec![at_lo]))
            .with("buckles_at_h_hi", ColumnData::Bool(vec![at_hi]))
            .with("probes", ColumnData::I64(vec![probes]))
            .with("lu_factorizations", ColumnData::I64(vec![lus.get() as i64]))
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64()])
            .into())
    }
}

pub fn register(r: &mut Registry) {
    r.add::<FemBuckling>().add::<FemBucklingLimit>();
}
