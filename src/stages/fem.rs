//! Stage kinds of the Chapter 3 shell model: `fem.mesh` (the meridian mesh as a table of
//! nodes, for inspection and Fig. 3.1b) and `fem.indent` (indentation by the rigid plate
//! under prescribed displacement: the path from the reference state, and the inverted
//! state at the same plate displacements where it exists).

use super::{check, finite};
use crate::fem::contact::Plate;
use crate::fem::indent::{dimple, load_path, solve_at, Options, Step};
use crate::fem::mesh::ShellMesh;
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
fn default_n_meridian() -> usize {
    80
}
fn default_n_thickness() -> usize {
    4
}
fn default_grading() -> f64 {
    8.0
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
    /// Elements along the meridian (default 80) and through the thickness (default 4).
    #[serde(default = "default_n_meridian")]
    pub n_meridian: usize,
    #[serde(default = "default_n_thickness")]
    pub n_thickness: usize,
    /// Ratio of the last to the first element size along the meridian (default 8).
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
        check::at_least(e, "n_meridian", self.n_meridian, 4);
        check::at_least(e, "n_thickness", self.n_thickness, 1);
        check::positive(e, "grading", self.grading);
    }

    fn mesh(&self) -> ShellMesh {
        ShellMesh::hemisphere(self.R, self.h, self.n_meridian, self.n_thickness, self.grading)
    }
}

pub struct FemMesh;

impl Kind for FemMesh {
    const NAME: &'static str = "fem.mesh";
    const VERSION: u32 = 1;
    const DOC: &'static str =
        "Chapter 3: the meridian mesh of a hemispherical shell (8-node elements), one row per node";
    type Params = ShellParams;

    fn validate(p: &ShellParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        p.validate(&mut e);
        e
    }

    fn run(p: &ShellParams, _: &Inputs) -> Result<Output> {
        let m = p.mesh();
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
    /// Equal load steps to delta_max.
    pub steps: usize,
}

#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Default)]
#[serde(rename_all = "snake_case")]
pub enum Support {
    #[default]
    Clamped,
    Roller,
}

/// The flattened path from the reference state and, at each of its plate displacements,
/// the inverted state reached from it through a central dimple (Pogorelov's mirror
/// buckling), where Newton finds one distinct from the flattened state.
pub struct FemIndent;

impl Kind for FemIndent {
    const NAME: &'static str = "fem.indent";
    const VERSION: u32 = 1;
    const DOC: &'static str =
        "Chapter 3: a shell pressed by a rigid plate under prescribed displacement; flattened and inverted branches";
    type Params = IndentParams;

    fn validate(p: &IndentParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        p.shell.validate(&mut e);
        check::positive(&mut e, "penalty", p.penalty);
        check::in_open(&mut e, "delta_max", p.delta_max, 0.0, 1.0, "delta/R");
        check::at_least(&mut e, "steps", p.steps, 1);
        e
    }

    fn run(p: &IndentParams, _: &Inputs) -> Result<Output> {
        let t0 = std::time::Instant::now();
        let base = match p.base {
            Support::Clamped => Base::Clamped,
            Support::Roller => Base::Roller,
        };
        let sh = &p.shell;
        let model = Model::new(sh.mesh(), sh.E, sh.nu, base);
        let plate = Plate::new(&model.mesh, sh.E, p.penalty);
        let path = load_path(&model, &plate, sh.E, p.delta_max * sh.R, p.steps, 8);
        let mut rows: Vec<(&str, Step)> = Vec::new();
        let r_mid = sh.R + 0.5 * sh.h;
        let apex = model.mesh.outer[0];
        for s in &path {
            rows.push(("flattened", s.clone()));
            if !s.converged {
                continue;
            }
            let a = 0.8 * s.contact.radius;
            let start = dimple(&model, &s.u, a, a * a / r_mid);
            let inv =
                solve_at(&model, &plate, sh.E, s.delta, &start, Options { max_iterations: 60, ..Options::default() });
            // Distinct: the apex has left the plate (inverted cap).
            let z_plate = sh.R + sh.h - s.delta;
            let z_apex = model.mesh.nodes[apex][1] + inv.u[2 * apex + 1];
            if inv.converged && z_apex < z_plate - 0.5 * sh.h {
                rows.push(("inverted", inv));
            }
        }
        let f_bar = sh.R / (sh.E * sh.h.powi(3));
        let col = |f: &dyn Fn(&Step) -> f64| rows.iter().map(|(_, s)| finite(f(s))).collect::<Vec<f64>>();
        let t = Table::new()
            .with("branch", ColumnData::Str(rows.iter().map(|(b, _)| b.to_string()).collect()))
            .with_f64("delta_over_R", col(&|s| s.delta / sh.R))
            .with_f64("F_bar", col(&|s| s.contact.force * f_bar))
            .with_f64("p_max_over_E", col(&|s| s.contact.pressure.iter().copied().fold(0.0, f64::max) / sh.E))
            .with_f64("A_bar", col(&|s| 2.0 * s.contact.area / (std::f64::consts::PI * sh.R * sh.R)))
            .with_f64("contact_radius_over_R", col(&|s| s.contact.radius / sh.R))
            .with_f64("max_penetration_over_h", col(&|s| s.contact.max_penetration / sh.h))
            .with("stable", ColumnData::Bool(rows.iter().map(|(_, s)| s.stable).collect()))
            .with("converged", ColumnData::Bool(rows.iter().map(|(_, s)| s.converged).collect()))
            .with("iterations", ColumnData::I64(rows.iter().map(|(_, s)| s.iterations as i64).collect()))
            .with_f64("residual", col(&|s| s.residual))
            .with_f64("wall_time_s", vec![t0.elapsed().as_secs_f64(); rows.len()]);
        Ok(t.into())
    }
}

pub fn register(r: &mut Registry) {
    r.add::<FemMesh>().add::<FemIndent>();
}
