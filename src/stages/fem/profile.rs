//! Stage kind `fem.profile`: the deformed meridian (outer and inner surface) and the
//! contact pressure at chosen plate displacements (Figs. 3.3-3.4, 3.8).

#![allow(non_snake_case)] // parameter names as in the thesis

use super::indent::{IndentParams, Row};
use super::prefixed;
use crate::stages::values::finite;
use anyhow::Result;
use physics::fem::mesh::ShellMesh;
use pipeline::kind::{FieldError, Inputs, Kind, Output};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// One state to draw (thesis Fig. 3.3: I Hertzian, II intermediate, III post-buckling).
#[derive(Serialize, Deserialize, JsonSchema, Clone)]
#[serde(deny_unknown_fields)]
pub struct ProfilePoint {
    /// Legend label of the state.
    pub label: String,
    /// Plate displacement delta/R on the loading leg (the nearest computed state is drawn).
    pub delta: f64,
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProfileParams {
    /// The cycle, as the parameters of `fem.indent` (only its loading leg is computed, to
    /// the largest `points` delta if that is smaller than delta_max).
    pub cycle: IndentParams,
    /// The states to draw.
    pub points: Vec<ProfilePoint>,
}

/// Deformed meridian and contact pressure of chosen states of the loading leg; on every row
/// the state's plate force with its declared resolution error, and the wall time.
pub struct FemProfile;

impl Kind for FemProfile {
    const NAME: &'static str = "fem.profile";
    const VERSION: u32 = 24;
    const DOC: &'static str =
        "Chapter 3: deformed meridian (outer and inner surface) and contact pressure at chosen plate displacements";
    const COLUMNS: &'static [&'static str] = &[
        "label",
        "point",
        "surface_id",
        "delta_over_R",
        "r_over_R",
        "z_over_R",
        "p_over_E",
        "contact",
        "inverted",
        "F_bar",
        "F_contact_bar",
        "F_error_bar",
        "lu_factorizations",
        "wall_time_s",
    ];
    type Params = ProfileParams;

    fn validate(p: &ProfileParams) -> Vec<FieldError> {
        let mut cycle = Vec::new();
        p.cycle.validate(&mut cycle);
        let mut e = prefixed("cycle", cycle);
        if p.points.is_empty() {
            e.push(FieldError::new("points", "at least one state to draw".to_string()));
        }
        for (i, q) in p.points.iter().enumerate() {
            if !(q.delta >= 0.0 && q.delta <= p.cycle.delta_max) {
                e.push(FieldError::new(
                    &format!("points[{i}].delta"),
                    format!("must lie in [0, delta_max = {}], got {}", p.cycle.delta_max, q.delta),
                ));
            }
        }
        e
    }

    fn memory_bytes(p: &ProfileParams) -> Option<u64> {
        Some(p.cycle.shell.memory_bytes(p.cycle.g0, p.cycle.steps, p.cycle.mesh_study))
    }

    fn run(p: &ProfileParams, _: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let top = p.points.iter().map(|q| q.delta).fold(0.0, f64::max);
        let (model, cycles) = p.cycle.cycles(top.min(p.cycle.delta_max), false);
        let c = &cycles.cycle;
        let sh = &p.cycle.shell;
        let m = &model.mesh;
        let mut t = ProfileRows::default();
        let inner: Vec<usize> = m.outer.iter().map(|&a| inner_of(m, a)).collect();
        let f_bar = sh.f_bar();
        for (k, q) in p.points.iter().enumerate() {
            let Some(state) =
                c.points.iter().filter(|s| s.step.converged()).min_by(|a, b| {
                    (a.step.delta / sh.R - q.delta).abs().total_cmp(&(b.step.delta / sh.R - q.delta).abs())
                })
            else {
                continue;
            };
            let s = &state.step;
            let force_error = finite(cycles.force_error(&Row::of(state)) * f_bar);
            for (surface, nodes) in [(0, &m.outer), (1, &inner)] {
                for (i, &a) in nodes.iter().enumerate() {
                    t.label.push(q.label.clone());
                    t.point.push(k as i64);
                    t.surface.push(surface);
                    t.delta.push(s.delta / sh.R);
                    t.r.push(finite((m.nodes[a][0] + s.u[2 * a]) / sh.R));
                    t.z.push(finite((m.nodes[a][1] + s.u[2 * a + 1]) / sh.R));
                    let p_a = if surface == 0 { s.contact.pressure[i] } else { 0.0 };
                    t.pressure.push(finite(p_a / sh.E));
                    t.contact.push(surface == 0 && s.contact.active[i]);
                    t.inverted.push(state.inverted);
                    t.force.push(finite(s.contact.force * f_bar));
                    t.contact_force.push(finite((s.contact.force - s.contact.adhesive) * f_bar));
                    t.force_error.push(force_error);
                }
            }
        }
        let rows = t.label.len();
        Ok(Table::new()
            .with("label", ColumnData::Str(t.label))
            .with("point", ColumnData::I64(t.point))
            .with("surface_id", ColumnData::I64(t.surface))
            .with_f64("delta_over_R", t.delta)
            .with_f64("r_over_R", t.r)
            .with_f64("z_over_R", t.z)
            .with_f64("p_over_E", t.pressure)
            .with_f64("contact", t.contact.iter().map(|&c| if c { 1.0 } else { 0.0 }).collect())
            .with("inverted", ColumnData::Bool(t.inverted))
            // The state's plate force and the mesh's share of its error (`fem.indent`'s).
            .with_f64("F_bar", t.force)
            // The compressive contact force alone (F_bar less the adhesive pull).
            .with_f64("F_contact_bar", t.contact_force)
            .with_f64("F_error_bar", t.force_error)
            .with("lu_factorizations", ColumnData::I64(vec![cycles.lu_factorizations as i64; rows]))
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64(); rows])
            .into())
    }
}

#[derive(Default)]
pub(super) struct ProfileRows {
    label: Vec<String>,
    point: Vec<i64>,
    surface: Vec<i64>,
    delta: Vec<f64>,
    r: Vec<f64>,
    z: Vec<f64>,
    pressure: Vec<f64>,
    contact: Vec<bool>,
    inverted: Vec<bool>,
    force: Vec<f64>,
    contact_force: Vec<f64>,
    force_error: Vec<f64>,
}

/// The inner-surface node on the same radial line as the outer node `a` (same meridian
/// angle in the reference configuration).
pub(super) fn inner_of(m: &ShellMesh, a: usize) -> usize {
    let angle = |x: [f64; 2]| x[0].atan2(x[1]);
    let target = angle(m.nodes[a]);
    (0..m.n_nodes())
        .filter(|&b| ((m.nodes[b][0].hypot(m.nodes[b][1])) - m.radius).abs() < 1e-9 * m.radius)
        .min_by(|&x, &y| (angle(m.nodes[x]) - target).abs().total_cmp(&(angle(m.nodes[y]) - target).abs()))
        .unwrap_or(a)
}
