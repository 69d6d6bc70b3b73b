//! Stage kinds of the Chapter 3 shell model: `fem.mesh` (the meridian mesh as a table of
//! nodes, for inspection and Fig. 3.1b) and `fem.indent` (indentation by the rigid plate
//! under prescribed displacement: the path from the reference state, and the inverted
//! state at the same plate displacements where it exists).

use super::{check, finite};
use crate::fem::contact::Plate;
use crate::fem::cycle::{load_unload, Cycle, CycleOptions, Jump, Leg};
use crate::fem::indent::Step;
use crate::fem::mesh::{default_mesh_rel_error, ShellMesh};
use crate::fem::system::{Base, Model};
use crate::pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use crate::pipeline::table::{ColumnData, Table};
use anyhow::Result;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

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
    pub R: f64,
    /// Thickness h (mm).
    pub h: f64,
    /// Young's modulus E (N/mm^2), default 1.3.
    #[serde(default = "default_e")]
    pub E: f64,
    /// Poisson's ratio, default 0.45.
    #[serde(default = "default_nu")]
    pub nu: f64,
    /// Elements along the meridian (default: 1.5 (R + h) / g0, so that the elements at the
    /// contact rim resolve the Lennard-Jones range g0; `fem::mesh::meridian_elements`) and
    /// through the thickness (default 2: quadratic elements carry the bending exactly).
    #[serde(default)]
    pub n_meridian: Option<usize>,
    #[serde(default = "default_n_thickness")]
    pub n_thickness: usize,
    /// Ratio of the last to the first element size along the meridian (default 3: fine enough
    /// at the apex for the first contact, and at r ~ 0.6 R for the inverted state's ring).
    #[serde(default = "default_grading")]
    pub grading: f64,
}

impl ShellParams {
    fn validate(&self, e: &mut Vec<FieldError>) {
        check::positive(e, "R", self.R);
        check::positive(e, "h", self.h);
        if self.h >= 0.5 * self.R {
            e.push(FieldError::new("h", format!("a thin shell needs h < R/2, got h = {} and R = {}", self.h, self.R)));
        }
        check::positive(e, "E", self.E);
        check::in_open(e, "nu", self.nu, -1.0, 0.5, "Poisson's ratio");
        if let Some(n) = self.n_meridian {
            check::at_least(e, "n_meridian", n, 4);
        }
        check::at_least(e, "n_thickness", self.n_thickness, 1);
        check::positive(e, "grading", self.grading);
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

    /// The mesh, its meridian resolved for the Lennard-Jones range `g0` unless given.
    fn mesh(&self, g0: f64) -> ShellMesh {
        let n = self.n_meridian.unwrap_or_else(|| crate::fem::mesh::meridian_elements(self.R, self.h, g0));
        ShellMesh::hemisphere(self.R, self.h, n, self.n_thickness, self.grading)
    }
}

pub struct FemMesh;

impl Kind for FemMesh {
    const NAME: &'static str = "fem.mesh";
    const VERSION: u32 = 2;
    const DOC: &'static str =
        "Chapter 3: the meridian mesh of a hemispherical shell (8-node elements), one row per node";
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
fn default_lift_threshold() -> f64 {
    crate::fem::stability::LIFT_THRESHOLD
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
    pub penalty: f64,
    /// Largest plate displacement delta/R.
    pub delta_max: f64,
    /// Equal load steps to delta_max (and back).
    pub steps: usize,
    /// Stability test: contact nodes pressed above this fraction of the peak pressure are
    /// held against lifting off, the others are free to (default 0.02).
    #[serde(default = "default_lift_threshold")]
    pub lift_threshold: f64,
    /// Bisections locating the snap-through in delta (default 6: to steps/64).
    #[serde(default = "default_bisections")]
    pub bisections: u32,
    /// Work of adhesion dgamma of the Lennard-Jones law, Eq. 3.3 (N/mm; default 0).
    #[serde(default)]
    pub gamma: f64,
    /// Equilibrium distance g0 of the Lennard-Jones law (mm; default 0.1 as the thesis).
    #[serde(default = "default_g0")]
    pub g0: f64,
    /// Coulomb friction coefficient (default 0).
    #[serde(default)]
    pub mu: f64,
    /// What holds touching points of an adhesive contact in the stability test: `free`
    /// (default) or `lennard_jones` (16 dgamma / g0^2).
    #[serde(default)]
    pub hold: super::fem_map::Hold,
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
        check::positive(e, "penalty", self.penalty);
        check::in_open(e, "delta_max", self.delta_max, 0.0, 1.0, "delta/R");
        check::at_least(e, "steps", self.steps, 1);
        check::in_open(e, "lift_threshold", self.lift_threshold, 0.0, 1.0, "a fraction of the peak pressure");
        check::non_negative(e, "gamma", self.gamma);
        check::positive(e, "g0", self.g0);
        check::non_negative(e, "mu", self.mu);
    }

    fn model(&self) -> (Model, Plate) {
        let base = match self.base {
            Support::Clamped => Base::Clamped,
            Support::Roller => Base::Roller,
        };
        let sh = &self.shell;
        let model = Model::new(sh.mesh(self.g0), sh.E, sh.nu, base);
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
            lift_threshold: self.lift_threshold,
            hold: self.hold.into(),
            trace_unstable: unload,
            unload,
            stop_at_buckling: false,
            snap: Default::default(),
        };
        load_unload(model, plate, self.shell.E, opt)
    }
}

/// A load-unload cycle under prescribed plate displacement (thesis Figs. 3.2-3.3): the
/// flattened branch until its interior lifts off, the snap-through to the inverted branch,
/// unloading on it to its limit point, the snap-back, and the unstable branch between.
pub struct FemIndent;

impl Kind for FemIndent {
    const NAME: &'static str = "fem.indent";
    const VERSION: u32 = 20;
    const DOC: &'static str =
        "Chapter 3: load-unload cycle of a shell pressed by a rigid plate (snap-through, snap-back, unstable branch)";
    const SWEEPABLE: &'static [&'static str] = &["gamma", "mu"];
    type Params = IndentParams;

    fn validate(p: &IndentParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        p.validate(&mut e);
        e
    }

    fn run(p: &IndentParams, _: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let (model, plate) = p.model();
        let c = p.cycle(&model, &plate, p.delta_max, true);
        let sh = &p.shell;
        let mut rows: Vec<(&str, &str, &Step)> = Vec::new();
        for q in &c.points {
            let leg = if q.leg == Leg::Loading { "loading" } else { "unloading" };
            rows.push((leg, if q.inverted { "inverted" } else { "flattened" }, &q.step));
        }
        for s in &c.unstable {
            rows.push(("unstable", "unstable", s));
        }
        let (f_bar, default_mesh) = (sh.f_bar(), sh.default_mesh());
        // W and its error for a complete cycle only (a partial one has no closed integral).
        let w_scale = sh.E * sh.h.powi(3);
        let (w_bar, w_error_bar) = if c.complete {
            (finite(c.dissipated() / w_scale), finite(c.dissipated_error() / w_scale))
        } else {
            (0.0, 0.0)
        };
        let col = |f: &dyn Fn(&Step) -> f64| rows.iter().map(|(_, _, s)| finite(f(s))).collect::<Vec<f64>>();
        let n = rows.len();
        let leg_id = |l: &str| match l {
            "loading" => 0,
            "unloading" => 1,
            _ => 2,
        };
        let t = Table::new()
            .with("leg", ColumnData::Str(rows.iter().map(|r| r.0.to_string()).collect()))
            .with("leg_id", ColumnData::I64(rows.iter().map(|r| leg_id(r.0)).collect()))
            .with("state", ColumnData::Str(rows.iter().map(|r| r.1.to_string()).collect()))
            .with_f64("gamma", vec![p.gamma; n])
            .with_f64("mu", vec![p.mu; n])
            .with_f64("delta_over_R", col(&|s| s.delta / sh.R))
            .with_f64("F_bar", col(&|s| s.contact.force * f_bar))
            // The resolution error of the default mesh (0 for others: not measured).
            .with_f64("F_error_bar", col(&|s| declared_mesh_error(s.contact.force * f_bar, default_mesh, p.mu)))
            .with_f64("F_adhesive_bar", col(&|s| s.contact.adhesive * f_bar))
            .with_f64(
                "slip_fraction",
                col(&|s| {
                    let active = s.contact.active.iter().filter(|&&a| a).count();
                    s.contact.slipping.iter().filter(|&&x| x).count() as f64 / active.max(1) as f64
                }),
            )
            .with_f64("p_max_over_E", col(&|s| s.contact.pressure.iter().copied().fold(0.0, f64::max) / sh.E))
            .with_f64("A_bar", col(&|s| 2.0 * s.contact.area / (std::f64::consts::PI * sh.R * sh.R)))
            .with_f64("contact_radius_over_R", col(&|s| s.contact.radius / sh.R))
            .with_f64("max_penetration_over_h", col(&|s| s.contact.max_penetration / sh.h))
            .with("stable", ColumnData::Bool(rows.iter().map(|r| r.2.stable).collect()))
            // Flattened states past the stability test where no inverted state is reachable
            // (`fem::cycle::invert`): the shell stays there.
            .with(
                "held",
                ColumnData::Bool(
                    rows.iter()
                        .map(|r| r.0 != "unstable" && r.1 == "flattened" && r.2.converged && !r.2.stable)
                        .collect(),
                ),
            )
            .with("converged", ColumnData::Bool(rows.iter().map(|r| r.2.converged).collect()))
            .with("iterations", ColumnData::I64(rows.iter().map(|r| r.2.iterations as i64).collect()))
            .with_f64("residual", col(&|s| s.residual))
            // The cycle's summary, repeated on every row (0 where there is no such event).
            .with("buckled", ColumnData::Bool(vec![c.buckling.is_some(); n]))
            .with_f64("F_buckling_bar", vec![finite(c.buckling.map_or(0.0, |b| b.force_before * f_bar)); n])
            .with_f64(
                "F_buckling_error_bar",
                vec![finite(c.buckling.map_or(0.0, |b| snap_force_error(&b, default_mesh, p.mu) * f_bar)); n],
            )
            .with_f64("delta_buckling_over_R", vec![finite(c.buckling.map_or(0.0, |b| b.delta / sh.R)); n])
            // Where the snap-through landed on the inverted branch (0: it did not).
            .with_f64("delta_landing_over_R", vec![finite(c.buckling.map_or(0.0, |b| b.delta_after / sh.R)); n])
            .with_f64("delta_snap_back_over_R", vec![finite(c.snap_back.map_or(0.0, |b| b.delta / sh.R)); n])
            .with_f64("W_bar", vec![w_bar; n])
            // The load path's share of W's error (`Cycle::dissipated_error`; the mesh's is not
            // estimated).
            .with_f64("W_error_bar", vec![w_error_bar; n])
            .with("complete", ColumnData::Bool(vec![c.complete; n]))
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64(); n]);
        Ok(t.into())
    }
}

/// Error estimate of a snap-through force: the bisection's bracket (the force rises from
/// the last stable state to the first unstable one) plus, on the default mesh, its measured
/// resolution error at friction `mu` (`fem::mesh::default_mesh_rel_error`; other meshes:
/// the bracket only).
pub(crate) fn snap_force_error(j: &Jump, default_mesh: bool, mu: f64) -> f64 {
    snap_bracket(j) + declared_mesh_error(j.force_before, default_mesh, mu)
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
    const VERSION: u32 = 15;
    const DOC: &'static str =
        "Chapter 3: deformed meridian (outer and inner surface) and contact pressure at chosen plate displacements";
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
        let (model, plate) = p.cycle.model();
        let top = p.points.iter().map(|q| q.delta).fold(0.0, f64::max);
        let c = p.cycle.cycle(&model, &plate, top.min(p.cycle.delta_max), false);
        let sh = &p.cycle.shell;
        let m = &model.mesh;
        let mut t = ProfileRows::default();
        let inner: Vec<usize> = m.outer.iter().map(|&a| inner_of(m, a)).collect();
        let (f_bar, default_mesh) = (sh.f_bar(), sh.default_mesh());
        for (k, q) in p.points.iter().enumerate() {
            let Some(state) =
                c.points.iter().filter(|s| s.step.converged).min_by(|a, b| {
                    (a.step.delta / sh.R - q.delta).abs().total_cmp(&(b.step.delta / sh.R - q.delta).abs())
                })
            else {
                continue;
            };
            let s = &state.step;
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
                    t.force_error.push(finite(declared_mesh_error(s.contact.force * f_bar, default_mesh, p.cycle.mu)));
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
            // The state's plate force and its declared resolution error (`fem.indent`'s).
            .with_f64("F_bar", t.force)
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
    r.add::<FemMesh>().add::<FemIndent>().add::<FemProfile>();
}
