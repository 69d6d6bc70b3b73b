//! Stage kinds of the Chapter 3 shell model: `fem.mesh` (the meridian mesh as a table of
//! nodes, for inspection and Fig. 3.1b) and `fem.indent` (indentation by the rigid plate
//! under prescribed displacement: the path from the reference state, and the inverted
//! state at the same plate displacements where it exists).

pub mod buckling;
pub mod gamma_c;
pub mod shell;

use crate::fem::contact::Plate;
use crate::fem::cycle::{load_unload, Cycle, CycleOptions, CyclePoint, Jump, Leg};
use crate::fem::indent::Step;
use crate::fem::mesh::{default_mesh_rel_error, ShellMesh};
use crate::fem::system::{Base, Model};
use crate::pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use crate::pipeline::table::{ColumnData, Table};
use crate::stages::{check, finite};
use anyhow::Result;
use buckling::{MeshStudy, Outcome};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use shell::{default_lift_threshold, Imperfection, MaterialLaw, Stability};

fn default_e() -> f64 {
    1.3
}
fn default_nu() -> f64 {
    0.45
}
fn default_n_thickness() -> usize {
    2
}
fn default_grading() -> f64 {
    3.0
}

/// The shell and its mesh (thesis Section 3.2: E = 1.3 N/mm^2, nu = 0.45).
#[derive(Serialize, Deserialize, JsonSchema, Clone)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct ShellParams {
    /// Inner radius R (mm).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub R: f64,
    /// Thickness h (mm).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub h: f64,
    /// Young's modulus E (N/mm^2), default 1.3.
    #[serde(default = "default_e")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub E: f64,
    /// Poisson's ratio, default 0.45.
    #[serde(default = "default_nu")]
    #[schemars(extend("exclusiveMinimum" = -1.0, "exclusiveMaximum" = 0.5))]
    pub nu: f64,
    /// Elements along the meridian (default: 1.5 (R + h) / g0, so that the elements at the
    /// contact rim resolve the Lennard-Jones range g0; `fem::mesh::meridian_elements`) and
    /// through the thickness (default 2: quadratic elements carry the bending exactly).
    #[serde(default)]
    #[schemars(range(min = 4, max = check::MAX_SHELL_ELEMENTS))]
    pub n_meridian: Option<usize>,
    #[serde(default = "default_n_thickness")]
    #[schemars(range(min = 1, max = 16))]
    pub n_thickness: usize,
    /// Ratio of the last to the first element size along the meridian (default 3: fine enough
    /// at the apex for the first contact, and at r ~ 0.6 R for the inverted state's ring).
    #[serde(default = "default_grading")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub grading: f64,
    /// Hyperelastic law: `neo_hookean` (default), `saint_venant_kirchhoff` or `hencky`.
    #[serde(default, skip_serializing_if = "MaterialLaw::is_default")]
    pub material: MaterialLaw,
    /// Imperfection: `{apex_force: F/F_c, dimple: depth/h, width: /sqrt(R h)}` (default none).
    #[serde(default, skip_serializing_if = "Imperfection::is_none")]
    pub imperfection: Imperfection,
}

impl ShellParams {
    fn validate(&self, e: &mut Vec<FieldError>) {
        if self.h >= 0.5 * self.R {
            e.push(FieldError::new("h", format!("a thin shell needs h < R/2, got h = {} and R = {}", self.h, self.R)));
        }
        self.imperfection.validate(e, "");
    }

    /// F R / (E h^3) per unit force.
    fn f_bar(&self) -> f64 {
        self.R / (self.E * self.h.powi(3))
    }

    /// The mesh is the default one, whose resolution error is declared
    /// (`fem::mesh::default_mesh_rel_error`).
    fn default_mesh(&self) -> bool {
        self.n_meridian.is_none() && self.n_thickness == 2
    }

    /// Elements along the meridian: as given, else resolving the Lennard-Jones range `g0`.
    fn meridian(&self, g0: f64) -> usize {
        self.n_meridian.unwrap_or_else(|| crate::fem::mesh::meridian_elements(self.R, self.h, g0))
    }

    /// The mesh on `n` meridian elements, before the imperfection's dimple.
    fn mesh_on(&self, n: usize) -> ShellMesh {
        ShellMesh::hemisphere(self.R, self.h, n, self.n_thickness, self.grading)
    }

    /// The mesh, its meridian resolved for the Lennard-Jones range `g0` unless given.
    fn mesh(&self, g0: f64) -> ShellMesh {
        self.imperfection.shape(self.mesh_on(self.meridian(g0)))
    }
}

pub struct FemMesh;

impl Kind for FemMesh {
    const NAME: &'static str = "fem.mesh";
    const VERSION: u32 = 2;
    const DOC: &'static str =
        "Chapter 3: the meridian mesh of a hemispherical shell (8-node elements), one row per node";
    const COLUMNS: &'static [&'static str] = &["r", "z", "axis", "base", "outer"];
    type Params = ShellParams;

    fn validate(p: &ShellParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        p.validate(&mut e);
        e
    }

    fn run(p: &ShellParams, _: &Inputs) -> Result<Output> {
        let m = p.mesh(default_g0());
        let flag = |list: &[usize]| {
            let mut v = vec![false; m.n_nodes()];
            list.iter().for_each(|&a| v[a] = true);
            v
        };
        Ok(Table::new()
            .with_f64("r", m.nodes.iter().map(|x| x[0]).collect())
            .with_f64("z", m.nodes.iter().map(|x| x[1]).collect())
            .with("axis", ColumnData::Bool(flag(&m.axis)))
            .with("base", ColumnData::Bool(flag(&m.base)))
            .with("outer", ColumnData::Bool(flag(&m.outer)))
            .into())
    }
}

fn default_penalty() -> f64 {
    1000.0
}
fn default_bisections() -> u32 {
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
    pub hold: buckling::Hold,
    /// Estimate the mesh's share of the errors of every state's force, F_buckling and W by a
    /// second cycle on twice the meridian elements, run alongside (`Cycles`; default false:
    /// the declared error of the default mesh for forces, none for W or other meshes).
    /// Three to four times the CPU time.
    #[serde(default)]
    pub mesh_study: bool,
}

fn default_g0() -> f64 {
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
    fn validate(&self, e: &mut Vec<FieldError>) {
        let mut shell = Vec::new();
        self.shell.validate(&mut shell);
        e.extend(prefixed("shell", shell));
    }

    /// The model on `n` meridian elements and the plate.
    fn model_on(&self, n: usize) -> (Model, Plate) {
        let base = match self.base {
            Support::Clamped => Base::Clamped,
            Support::Roller => Base::Roller,
        };
        let sh = &self.shell;
        let model = shell::model(sh.mesh_on(n), sh.E, sh.nu, base, sh.material, &sh.imperfection);
        let plate =
            Plate::new(&model.mesh, sh.E, self.penalty).with_adhesion(self.gamma, self.g0).with_friction(self.mu);
        (model, plate)
    }

    fn cycle(&self, model: &Model, plate: &Plate, delta_max: f64, unload: bool) -> Cycle {
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
            snap: Default::default(),
        };
        load_unload(model, plate, self.shell.E, opt)
    }

    /// The model and its cycle to `delta_max` (delta/R), and with `mesh_study` the cycle on
    /// twice the meridian elements, computed alongside.
    fn cycles(&self, delta_max: f64, unload: bool) -> (Model, Cycles) {
        let n = self.shell.meridian(self.g0);
        let on = |n: usize| {
            let (model, plate) = self.model_on(n);
            let c = self.cycle(&model, &plate, delta_max, unload);
            let friction = if c.complete { c.friction_work(&plate.weights) } else { 0.0 };
            (model, (c, friction))
        };
        let ((model, (cycle, friction)), finer) = if self.mesh_study {
            let (this, (_, (finer, _))) = rayon::join(|| on(n), || on(2 * n));
            (this, Some(finer))
        } else {
            (on(n), None)
        };
        let source = match (&finer, self.shell.default_mesh()) {
            (Some(_), _) => "study",
            (None, true) => "declared",
            (None, false) => "none",
        };
        let step = delta_max * self.shell.R / self.steps as f64;
        (model, Cycles { cycle, finer, default_mesh: self.shell.default_mesh(), mu: self.mu, source, step, friction })
    }
}

/// A state of a cycle as a table row: its leg (`loading`, `unloading`, `unstable`) and
/// branch (`flattened`, `inverted`, `unstable`).
struct Row<'a> {
    leg: &'static str,
    branch: &'static str,
    step: &'a Step,
}

impl Row<'_> {
    fn of(q: &CyclePoint) -> Row<'_> {
        Row {
            leg: if q.leg == Leg::Loading { "loading" } else { "unloading" },
            branch: if q.inverted { "inverted" } else { "flattened" },
            step: &q.step,
        }
    }

    /// Every state of `c`: the legs in order, then the unstable branch.
    fn all(c: &Cycle) -> Vec<Row<'_>> {
        let mut rows: Vec<Row> = c.points.iter().map(Row::of).collect();
        rows.extend(c.unstable.iter().map(|s| Row { leg: "unstable", branch: "unstable", step: s }));
        rows
    }
}

/// A cycle and, from `IndentParams::mesh_study`, its companion on twice the meridian
/// elements; where the mesh's share of an error comes from (`source`: `study`, `declared`
/// for the default mesh's measured error, `none`).
struct Cycles {
    cycle: Cycle,
    finer: Option<Cycle>,
    default_mesh: bool,
    mu: f64,
    source: &'static str,
    /// The load step (mesh units).
    step: f64,
    /// The work done against friction on a complete cycle (`Cycle::friction_work`), else 0.
    friction: f64,
}

impl Cycles {
    /// The mesh's share of the error of a state's plate force (units of the force). With a
    /// study: twice the difference from the finer cycle's force at the same delta, leg and
    /// branch (`branch_force`, within a load step of a branch's end; Richardson's bound at
    /// first order, as `buckling::MeshStudy`), or |F| where the finer cycle has no such state
    /// (it snapped elsewhere: whether this state exists is what the mesh decides). Without:
    /// the default mesh's declared error, or 0.
    fn force_error(&self, row: &Row) -> f64 {
        let force = row.step.contact.force;
        match &self.finer {
            Some(finer) => branch_force(&Row::all(finer), row.leg, row.branch, row.step.delta, self.step)
                .map_or(force.abs(), |f| 2.0 * (force - f).abs()),
            None => declared_mesh_error(force, self.default_mesh, self.mu),
        }
    }

    /// The mesh's shares of the errors of F_buckling and W (units of force and energy),
    /// with whether the two meshes agree on the cycle's events (`buckling::MeshStudy`); the
    /// declared error of F_buckling on the default mesh and none for W without a study.
    fn event_errors(&self, w: f64, finer_w: impl Fn(&Cycle) -> f64) -> MeshStudy {
        let c = &self.cycle;
        match &self.finer {
            Some(finer) => {
                MeshStudy::of(Outcome::of(&c.buckling, w, c), Outcome::of(&finer.buckling, finer_w(finer), finer))
            }
            None => MeshStudy {
                f_error: c.buckling.map_or(0.0, |j| declared_mesh_error(j.force_before, self.default_mesh, self.mu)),
                w_error: 0.0,
                agrees: true,
            },
        }
    }
}

/// The plate force on a leg and branch of a cycle's rows at plate displacement `delta`:
/// linear between the first two consecutive converged states of that leg and branch that
/// bracket it; else, within `reach` of delta, the force of the nearest one (a branch that
/// ends a little earlier on this mesh, at a snap); None if there is none.
fn branch_force(rows: &[Row], leg: &str, branch: &str, delta: f64, reach: f64) -> Option<f64> {
    let on: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.leg == leg && r.branch == branch && r.step.converged)
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
    const VERSION: u32 = 24;
    const DOC: &'static str =
        "Chapter 3: load-unload cycle of a shell pressed by a rigid plate (snap-through, snap-back, unstable branch)";
    const SWEEPABLE: &'static [&'static str] = &["gamma", "mu"];
    const COLUMNS: &'static [&'static str] = &[
        "leg",
        "leg_id",
        "state",
        "gamma",
        "mu",
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
        "wall_time_s",
    ];
    type Params = IndentParams;

    fn validate(p: &IndentParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        p.validate(&mut e);
        e
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
        let closed = |c: &Cycle| if c.complete { c.dissipated() } else { 0.0 };
        let path_error = if c.complete { c.dissipated_error() } else { 0.0 };
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
            .with_f64("gamma", vec![p.gamma; n])
            .with_f64("mu", vec![p.mu; n])
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
            // (`fem::cycle::invert`): the shell stays there.
            .with(
                "held",
                ColumnData::Bool(
                    rows.iter()
                        .map(|r| r.leg != "unstable" && r.branch == "flattened" && r.step.converged && !r.step.stable)
                        .collect(),
                ),
            )
            .with("converged", ColumnData::Bool(rows.iter().map(|r| r.step.converged).collect()))
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
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64(); n]);
        Ok(t.into())
    }
}

/// The declared resolution error of a force on the default mesh at friction `mu`
/// (`fem::mesh::default_mesh_rel_error`); 0 on other meshes (not measured).
pub(crate) fn declared_mesh_error(force: f64, default_mesh: bool, mu: f64) -> f64 {
    if default_mesh {
        default_mesh_rel_error(mu) * force.abs()
    } else {
        0.0
    }
}

/// The bisection's bracket of a snap-through force: from the last stable state to the
/// first unstable one.
pub(crate) fn snap_bracket(j: &Jump) -> f64 {
    (j.force_unstable - j.force_before).abs()
}

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
    const VERSION: u32 = 17;
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
                c.points.iter().filter(|s| s.step.converged).min_by(|a, b| {
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
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64(); rows])
            .into())
    }
}

/// Errors of a nested parameter block, with their paths below `prefix`.
fn prefixed(prefix: &str, errors: Vec<FieldError>) -> Vec<FieldError> {
    errors.into_iter().map(|f| FieldError::new(&format!("{prefix}.{}", f.path), f.message)).collect()
}

#[derive(Default)]
struct ProfileRows {
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
fn inner_of(m: &ShellMesh, a: usize) -> usize {
    let angle = |x: [f64; 2]| x[0].atan2(x[1]);
    let target = angle(m.nodes[a]);
    (0..m.n_nodes())
        .filter(|&b| ((m.nodes[b][0].hypot(m.nodes[b][1])) - m.radius).abs() < 1e-9 * m.radius)
        .min_by(|&x, &y| (angle(m.nodes[x]) - target).abs().total_cmp(&(angle(m.nodes[y]) - target).abs()))
        .unwrap_or(a)
}

pub fn register(r: &mut Registry) {
    buckling::register(r);
    gamma_c::register(r);
    r.add::<FemMesh>().add::<FemIndent>().add::<FemProfile>();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::contact::ContactState;

    fn step(delta: f64, force: f64, converged: bool) -> Step {
        let contact = ContactState { force, ..Default::default() };
        Step { delta, u: Vec::new(), contact, iterations: 1, residual: 0.0, converged, stable: true }
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
