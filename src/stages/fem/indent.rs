//! Stage kind `fem.indent`: the shell indented by the rigid plate under prescribed
//! displacement, loading and unloading (snap-through, snap-back, the unstable branch), with
//! the mesh study that bounds its error.

#![allow(non_snake_case)] // parameter names as in the thesis

use super::shell::{default_lift_threshold, Stability};
use super::{declared_mesh_error, declared_w_mesh_error, map, prefixed, shell, snap_bracket, ShellParams};
use crate::stages::values::{check, finite};
use anyhow::Result;
use physics::fem::contact::Plate;
use physics::fem::cycle::{load_unload, Cycle, CycleOptions, CyclePoint, Leg};
use physics::fem::indent::Step;
use physics::fem::mesh_study::{MeshStudy, Outcome};
use physics::fem::system::{Base, Model};
use pipeline::kind::{FieldError, Inputs, Kind, Output};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub(super) fn default_penalty() -> f64 {
    1000.0
}

pub(super) fn default_bisections() -> u32 {
    6
}

/// The shell, its support, the contact and the loading of one indentation cycle.
#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct IndentParams {
    /// The shell and its mesh, as for `fem.mesh`.
    pub shell: ShellParams,
    /// Base support: `clamped` (default, as the experiments) or `roller`.
    #[serde(default)]
    pub base: Support,
    /// Contact penalty in units of E/h: the penetration is about p h/(penalty E).
    #[serde(default = "default_penalty")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub penalty: f64,
    /// Largest plate displacement delta/R.
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub delta_max: f64,
    /// Equal load steps to delta_max (and back).
    #[schemars(range(min = 1, max = check::MAX_STEPS))]
    pub steps: usize,
    /// Stability test: `lift_threshold` (default) or `tangent` (`shell::Stability`).
    #[serde(default, skip_serializing_if = "Stability::is_default")]
    pub stability: Stability,
    /// With `stability: lift_threshold`: contact nodes pressed above this fraction of the
    /// peak pressure are held against lifting off, the others are free to (default 0.02).
    #[serde(default = "default_lift_threshold")]
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub lift_threshold: f64,
    /// Bisections locating the snap-through in delta (default 6: to steps/64).
    #[serde(default = "default_bisections")]
    pub bisections: u32,
    /// Work of adhesion dgamma of the Lennard-Jones law, Eq. 3.3 (N/mm; default 0).
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub gamma: f64,
    /// Equilibrium distance g0 of the Lennard-Jones law (mm; default 0.1 as the thesis).
    #[serde(default = "default_g0")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub g0: f64,
    /// Coulomb friction coefficient (default 0).
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub mu: f64,
    /// What holds touching points of an adhesive contact in the stability test: `free`
    /// (default) or `lennard_jones` (16 dgamma / g0^2).
    #[serde(default)]
    pub hold: map::Hold,
    /// What counts as the snap-through: `instability` (default, the stability test),
    /// `energy` (the inverted state stores less total potential energy; the whole cycle,
    /// `fem::cycle::energy`) or the thesis' staggered procedure, `{thesis: {passes: n,
    /// first_pass: ...}}` (`map::SnapCriterion`), which runs the loading leg only (W is then
    /// 0: no loop).
    #[serde(default, skip_serializing_if = "map::SnapCriterion::is_default")]
    pub snap: map::SnapCriterion,
    /// Estimate the mesh's share of the errors of every state's force, F_buckling and W by a
    /// second cycle on twice the meridian elements, run alongside (`Cycles`; default false:
    /// the declared errors of the default mesh, none on other meshes).
    /// Three to four times the CPU time.
    #[serde(default)]
    pub mesh_study: bool,
}

pub(super) fn default_g0() -> f64 {
    0.1
}

#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Default)]
#[serde(rename_all = "snake_case")]
pub enum Support {
    #[default]
    Clamped,
    Roller,
}

impl IndentParams {
    pub(super) fn validate(&self, e: &mut Vec<FieldError>) {
        let mut shell = Vec::new();
        self.shell.validate(self.g0, &mut shell);
        e.extend(prefixed("shell", shell));
    }

    /// The model on `n` meridian elements and the plate.
    pub(super) fn model_on(&self, n: usize) -> (Model, Plate) {
        let base = match self.base {
            Support::Clamped => Base::Clamped,
            Support::Roller => Base::Roller,
        };
        let sh = &self.shell;
        let model = shell::model(sh.mesh_on(n), sh.E, sh.nu, base, sh.material, sh.integration, &sh.imperfection);
        let plate =
            Plate::new(&model.mesh, sh.E, self.penalty).with_adhesion(self.gamma, self.g0).with_friction(self.mu);
        (model, plate)
    }

    pub(super) fn cycle(&self, model: &Model, plate: &Plate, delta_max: f64, unload: bool) -> Cycle {
        let opt = CycleOptions {
            delta_max: delta_max * self.shell.R,
            steps: self.steps,
            max_cuts: 8,
            bisections: self.bisections,
            criterion: self.stability.criterion(self.lift_threshold),
            hold: self.hold.into(),
            trace_unstable: unload,
            unload,
            stop_at_buckling: false,
            snap: self.snap.into(),
        };
        load_unload(model, plate, self.shell.E, opt)
    }

    /// The model and its cycle to `delta_max` (delta/R), and with `mesh_study` the cycle on
    /// twice the meridian elements, computed alongside.
    pub(super) fn cycles(&self, delta_max: f64, unload: bool) -> (Model, Cycles) {
        let n = self.shell.meridian(self.g0);
        let on = |n: usize| {
            let (model, plate) = self.model_on(n);
            let c = self.cycle(&model, &plate, delta_max, unload);
            let friction = if c.complete { c.friction_work(&plate.weights) } else { 0.0 };
            (model, (c, friction))
        };
        let ((model, (cycle, friction)), finer) = if self.mesh_study {
            let (this, (finer_model, (finer, _))) = rayon::join(|| on(n), || on(2 * n));
            (this, Some((finer, finer_model.factorizations())))
        } else {
            (on(n), None)
        };
        let lu_factorizations = model.factorizations() + finer.as_ref().map_or(0, |(_, lus)| *lus);
        let finer = finer.map(|(c, _)| c);
        let source = match (&finer, self.shell.default_mesh()) {
            (Some(_), _) => "study",
            (None, true) => "declared",
            (None, false) => "none",
        };
        let step = delta_max * self.shell.R / self.steps as f64;
        let cycles = Cycles {
            cycle,
            finer,
            default_mesh: self.shell.default_mesh(),
            mu: self.mu,
            integration: self.shell.integration,
            source,
            step,
            friction,
            lu_factorizations,
        };
        (model, cycles)
    }
}

/// A state of a cycle as a table row: its leg (`loading`, `unloading`, `unstable`) and
/// branch (`flattened`, `inverted`, `unstable`).
pub(super) struct Row<'a> {
    leg: &'static str,
    branch: &'static str,
    step: &'a Step,
}

impl Row<'_> {
    pub(super) fn of(q: &CyclePoint) -> Row<'_> {
        Row {
            leg: if q.leg == Leg::Loading { "loading" } else { "unloading" },
            branch: if q.inverted { "inverted" } else { "flattened" },
            step: &q.step,
        }
    }

    /// Every state of `c`: the legs in order, then the unstable branch.
    pub(super) fn all(c: &Cycle) -> Vec<Row<'_>> {
        let mut rows: Vec<Row> = c.points.iter().map(Row::of).collect();
        rows.extend(c.unstable.iter().map(|s| Row { leg: "unstable", branch: "unstable", step: s }));
        rows
    }
}

/// A cycle and, from `IndentParams::mesh_study`, its companion on twice the meridian
/// elements; where the mesh's share of an error comes from (`source`: `study`, `declared`
/// for the default mesh's measured error, `none`).
pub(super) struct Cycles {
    pub(super) cycle: Cycle,
    finer: Option<Cycle>,
    default_mesh: bool,
    mu: f64,
    integration: shell::Integration,
    source: &'static str,
    /// The load step (mesh units).
    step: f64,
    /// The work done against friction on a complete cycle (`Cycle::friction_work`), else 0.
    friction: f64,
    /// LU factorisations of the tangent over the cycles (the mesh study's included).
    pub(super) lu_factorizations: usize,
}

impl Cycles {
    /// The mesh's share of the error of a state's plate force (units of the force). With a
    /// study: twice the difference from the finer cycle's force at the same delta, leg and
    /// branch (`branch_force`, within a load step of a branch's end; Richardson's bound at
    /// first order, as `buckling::MeshStudy`), or |F| where the finer cycle has no such state
    /// (it snapped elsewhere: whether this state exists is what the mesh decides). Without:
    /// the default mesh's declared error, or 0.
    pub(super) fn force_error(&self, row: &Row) -> f64 {
        let force = row.step.contact.force;
        match &self.finer {
            Some(finer) => branch_force(&Row::all(finer), row.leg, row.branch, row.step.delta, self.step)
                .map_or(force.abs(), |f| 2.0 * (force - f).abs()),
            None => declared_mesh_error(force, self.default_mesh, self.mu),
        }
    }

    /// The mesh's shares of the errors of F_buckling and W (units of force and energy),
    /// with whether the two meshes agree on the cycle's events (`buckling::MeshStudy`); the
    /// declared errors of the default mesh without a study.
    pub(super) fn event_errors(&self, w: f64, finer_w: impl Fn(&Cycle) -> f64) -> MeshStudy {
        let c = &self.cycle;
        match &self.finer {
            Some(finer) => {
                MeshStudy::of(Outcome::of(&c.buckling, w, c), Outcome::of(&finer.buckling, finer_w(finer), finer))
            }
            None => MeshStudy {
                f_error: c.buckling.map_or(0.0, |j| declared_mesh_error(j.force_before, self.default_mesh, self.mu)),
                w_error: declared_w_mesh_error(w, self.default_mesh, self.integration),
                agrees: true,
            },
        }
    }
}

/// The plate force on a leg and branch of a cycle's rows at plate displacement `delta`:
/// linear between the first two consecutive converged states of that leg and branch that
/// bracket it; else, within `reach` of delta, the force of the nearest one (a branch that
/// ends a little earlier on this mesh, at a snap); None if there is none.
pub(super) fn branch_force(rows: &[Row], leg: &str, branch: &str, delta: f64, reach: f64) -> Option<f64> {
    let on: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.leg == leg && r.branch == branch && r.step.converged())
        .map(|r| (r.step.delta, r.step.contact.force))
        .collect();
    let bracketed = on.windows(2).find_map(|w| {
        let ((d0, f0), (d1, f1)) = (w[0], w[1]);
        if (d0 - delta) * (d1 - delta) > 0.0 {
            return None;
        }
        Some(if d1 == d0 { f0 } else { f0 + (f1 - f0) * (delta - d0) / (d1 - d0) })
    });
    bracketed.or_else(|| {
        on.iter()
            .filter(|(d, _)| (d - delta).abs() <= reach)
            .min_by(|a, b| (a.0 - delta).abs().total_cmp(&(b.0 - delta).abs()))
            .map(|&(_, f)| f)
    })
}

/// A load-unload cycle under prescribed plate displacement (thesis Figs. 3.2-3.3): the
/// flattened branch until its interior lifts off, the snap-through to the inverted branch,
/// unloading on it to its limit point, the snap-back, and the unstable branch between.
pub struct FemIndent;

impl Kind for FemIndent {
    const NAME: &'static str = "fem.indent";
    const VERSION: u32 = 38;
    const DOC: &'static str =
        "Chapter 3: load-unload cycle of a shell pressed by a rigid plate (snap-through, snap-back, unstable branch)";
    const SWEEPABLE: &'static [&'static str] = &["gamma", "mu"];
    const COLUMNS: &'static [&'static str] = &[
        "leg",
        "leg_id",
        "state",
        "R_mm",
        "h_mm",
        "h_over_R",
        "gamma",
        "mu",
        "apex_force",
        "dimple",
        "criterion",
        "delta_over_R",
        "F_bar",
        "F_error_bar",
        "F_contact_bar",
        "F_adhesive_bar",
        "slip_fraction",
        "p_max_over_E",
        "p_apex_over_E",
        "A_bar",
        "contact_radius_over_R",
        "max_penetration_over_h",
        "stable",
        "held",
        "converged",
        "termination",
        "iterations",
        "residual",
        "buckled",
        "F_buckling_bar",
        "F_buckling_error_bar",
        "F_buckling_mesh_error_bar",
        "delta_buckling_over_R",
        "delta_landing_over_R",
        "delta_snap_back_over_R",
        "W_bar",
        "W_error_bar",
        "W_mesh_error_bar",
        "W_friction_bar",
        "n_meridian",
        "mesh_error_source",
        "mesh_study_agrees",
        "complete",
        "lu_factorizations",
        "wall_time_s",
    ];
    type Params = IndentParams;

    fn validate(p: &IndentParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        p.validate(&mut e);
        e
    }

    fn memory_bytes(p: &IndentParams) -> Option<u64> {
        Some(p.shell.memory_bytes(p.g0, p.steps, p.mesh_study))
    }

    fn run(p: &IndentParams, _: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let (model, cycles) = p.cycles(p.delta_max, true);
        let c = &cycles.cycle;
        let rows = Row::all(c);
        let sh = &p.shell;
        let f_bar = sh.f_bar();
        // W and its error for a complete cycle only (a partial one has no closed integral).
        let w_scale = sh.E * sh.h.powi(3);
        let closed = |c: &Cycle| if c.is_closed() { c.dissipated() } else { 0.0 };
        let path_error = if c.is_closed() { c.dissipated_error() } else { 0.0 };
        let events = cycles.event_errors(closed(c), closed);
        let col = |f: &dyn Fn(&Step) -> f64| rows.iter().map(|r| finite(f(r.step))).collect::<Vec<f64>>();
        let n = rows.len();
        let leg_id = |l: &str| match l {
            "loading" => 0,
            "unloading" => 1,
            _ => 2,
        };
        let t = Table::new()
            .with("leg", ColumnData::Str(rows.iter().map(|r| r.leg.to_string()).collect()))
            .with("leg_id", ColumnData::I64(rows.iter().map(|r| leg_id(r.leg)).collect()))
            .with("state", ColumnData::Str(rows.iter().map(|r| r.branch.to_string()).collect()))
            // The shell's size, on every row: what a figure's title states.
            .with_f64("R_mm", vec![sh.R; n])
            .with_f64("h_mm", vec![sh.h; n])
            .with_f64("h_over_R", vec![sh.h / sh.R; n])
            .with_f64("gamma", vec![p.gamma; n])
            .with_f64("mu", vec![p.mu; n])
            .with_f64("apex_force", vec![sh.imperfection.apex_force; n])
            .with_f64("dimple", vec![sh.imperfection.dimple; n])
            .with("criterion", ColumnData::Str(vec![p.snap.words().to_string(); n]))
            .with_f64("delta_over_R", col(&|s| s.delta / sh.R))
            .with_f64("F_bar", col(&|s| s.contact.force * f_bar))
            // The mesh's share of the force's error (`Cycles::force_error`).
            .with_f64("F_error_bar", rows.iter().map(|r| finite(cycles.force_error(r) * f_bar)).collect())
            // The compressive contact force alone (F_bar = F_contact_bar + F_adhesive_bar).
            .with_f64("F_contact_bar", col(&|s| (s.contact.force - s.contact.adhesive) * f_bar))
            .with_f64("F_adhesive_bar", col(&|s| s.contact.adhesive * f_bar))
            .with_f64(
                "slip_fraction",
                col(&|s| {
                    let active = s.contact.active.iter().filter(|&&a| a).count();
                    s.contact.slipping.iter().filter(|&&x| x).count() as f64 / active.max(1) as f64
                }),
            )
            .with_f64("p_max_over_E", col(&|s| s.contact.pressure.iter().copied().fold(0.0, f64::max) / sh.E))
            // The pressure at the apex: zero once the contact disk has become a ring.
            .with_f64("p_apex_over_E", col(&|s| s.contact.pressure.first().copied().unwrap_or(0.0) / sh.E))
            .with_f64("A_bar", col(&|s| 2.0 * s.contact.area / (std::f64::consts::PI * sh.R * sh.R)))
            .with_f64("contact_radius_over_R", col(&|s| s.contact.radius / sh.R))
            .with_f64("max_penetration_over_h", col(&|s| s.contact.max_penetration / sh.h))
            .with("stable", ColumnData::Bool(rows.iter().map(|r| r.step.stable).collect()))
            // Flattened states past the stability test where no inverted state is reachable
            // (`ShellProblem::jump_to_inverted`): the shell stays there.
            .with(
                "held",
                ColumnData::Bool(
                    rows.iter()
                        .map(|r| r.leg != "unstable" && r.branch == "flattened" && r.step.converged() && !r.step.stable)
                        .collect(),
                ),
            )
            .with("converged", ColumnData::Bool(rows.iter().map(|r| r.step.converged()).collect()))
            .with("termination", ColumnData::Str(rows.iter().map(|r| r.step.termination.name().to_string()).collect()))
            .with("iterations", ColumnData::I64(rows.iter().map(|r| r.step.iterations as i64).collect()))
            .with_f64("residual", col(&|s| s.residual))
            // The cycle's summary, repeated on every row (0 where there is no such event).
            .with("buckled", ColumnData::Bool(vec![c.buckling.is_some(); n]))
            .with_f64("F_buckling_bar", vec![finite(c.buckling.map_or(0.0, |b| b.force_before * f_bar)); n])
            // The bisection's bracket plus the mesh's share.
            .with_f64(
                "F_buckling_error_bar",
                vec![finite(c.buckling.map_or(0.0, |b| (snap_bracket(&b) + events.f_error) * f_bar)); n],
            )
            .with_f64("F_buckling_mesh_error_bar", vec![finite(events.f_error * f_bar); n])
            .with_f64("delta_buckling_over_R", vec![finite(c.buckling.map_or(0.0, |b| b.delta / sh.R)); n])
            // Where the snap-through landed on the inverted branch (0: it did not).
            .with_f64("delta_landing_over_R", vec![finite(c.buckling.map_or(0.0, |b| b.delta_after / sh.R)); n])
            .with_f64("delta_snap_back_over_R", vec![finite(c.snap_back.map_or(0.0, |b| b.delta / sh.R)); n])
            .with_f64("W_bar", vec![finite(closed(c) / w_scale); n])
            // The load path's share of W's error (`Cycle::dissipated_error`) plus the mesh's
            // (with a study; else not estimated).
            .with_f64("W_error_bar", vec![finite((path_error + events.w_error) / w_scale); n])
            .with_f64("W_mesh_error_bar", vec![finite(events.w_error / w_scale); n])
            // The part of W done against friction on the quasi-static pieces of the cycle
            // (`Cycle::friction_work`); the rest is lost in the jumps and the adhesive
            // hysteresis.
            .with_f64("W_friction_bar", vec![finite(cycles.friction / w_scale); n])
            .with("n_meridian", ColumnData::I64(vec![(model.mesh.elements.len() / sh.n_thickness) as i64; n]))
            // Where the mesh's shares come from: `study` (2 n elements run too), `declared`
            // (the default mesh's measured error, forces only) or `none`.
            .with("mesh_error_source", ColumnData::Str(vec![cycles.source.to_string(); n]))
            .with("mesh_study_agrees", ColumnData::Bool(vec![events.agrees; n]))
            .with("complete", ColumnData::Bool(vec![c.complete; n]))
            .with("lu_factorizations", ColumnData::I64(vec![cycles.lu_factorizations as i64; n]))
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64(); n]);
        Ok(t.into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use physics::fem::contact::ContactState;
    use physics::fem::indent::{Step, StepEnd};

    fn step(delta: f64, force: f64, converged: bool) -> Step {
        let contact = ContactState { force, ..Default::default() };
        let termination = if converged { StepEnd::Converged } else { StepEnd::IterationLimit };
        Step { delta, u: Vec::new(), contact, iterations: 1, residual: 0.0, stable: true, termination }
    }

    #[test]
    fn a_branch_force_is_interpolated_on_its_own_leg_and_branch_or_taken_near_its_end() {
        let steps = [step(0.1, 1.0, true), step(0.2, 3.0, true), step(0.3, 2.0, false), step(0.4, 10.0, true)];
        let other = step(0.15, 100.0, true);
        let mut rows: Vec<Row> = steps.iter().map(|s| Row { leg: "loading", branch: "flattened", step: s }).collect();
        rows.push(Row { leg: "loading", branch: "inverted", step: &other });
        let at = |d: f64, reach: f64| branch_force(&rows, "loading", "flattened", d, reach);
        // Linear between the bracketing states; the unconverged one at 0.3 is not a state.
        assert!((at(0.15, 0.0).unwrap() - 2.0).abs() < 1e-12);
        assert!((at(0.3, 0.0).unwrap() - 6.5).abs() < 1e-12);
        assert_eq!(at(0.1, 0.0), Some(1.0));
        // Past the ends: the nearest state within reach, else nothing.
        assert_eq!(at(0.45, 0.06), Some(10.0));
        assert_eq!(at(0.05, 0.06), Some(1.0));
        assert_eq!(at(0.45, 0.04), None);
        assert_eq!(branch_force(&rows, "unloading", "flattened", 0.15, 1.0), None);
        assert_eq!(branch_force(&rows, "loading", "inverted", 0.15, 0.0), Some(100.0));
    }
}
