//! Stage kinds of the Chapter 3 shell model, one file per kind: `fem.mesh` here (the
//! meridian mesh as a table of nodes, for inspection and Fig. 3.1b) with the shell
//! parameters every kind shares (`ShellParams`); `fem.indent` (`indent`), `fem.profile`
//! (`profile`), `fem.buckling` and `fem.buckling_limit` (`buckling`), `fem.gamma_c` and
//! `fem.gamma_c_map` (`gamma_c`); the shell's law, imperfection and stability test in
//! `shell`.

pub mod buckling;
pub mod gamma_c;
pub mod indent;
pub mod map;
pub mod profile;
pub mod shell;

use crate::stages::values::check;
use anyhow::Result;
use indent::{default_g0, FemIndent};
use physics::fem::cycle::Jump;
use physics::fem::mesh::{default_mesh_rel_error, default_mesh_w_rel_error, ShellMesh};
use pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::{format_number, ColumnData, Table};
use profile::FemProfile;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use shell::{Imperfection, Integration, MaterialLaw};

pub(super) fn default_e() -> f64 {
    1.3
}

pub(super) fn default_nu() -> f64 {
    0.45
}

pub(super) fn default_n_thickness() -> usize {
    2
}

pub(super) fn default_grading() -> f64 {
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
    /// Gauss rule of the elements: `full` (3 x 3, default) or `reduced` (2 x 2, ANSYS
    /// PLANE183's).
    #[serde(default, skip_serializing_if = "Integration::is_default")]
    pub integration: Integration,
    /// Imperfection: `{apex_force: F/F_c, dimple: depth/h, width: /sqrt(R h)}` (default none).
    #[serde(default, skip_serializing_if = "Imperfection::is_none")]
    pub imperfection: Imperfection,
}

impl ShellParams {
    /// Checks the shell, its mesh sized for the Lennard-Jones range `g0`.
    pub(super) fn validate(&self, g0: f64, e: &mut Vec<FieldError>) {
        if self.h >= 0.5 * self.R {
            e.push(FieldError::new("h", format!("a thin shell needs h < R/2, got h = {} and R = {}", self.h, self.R)));
        }
        if self.n_meridian.is_none() {
            e.extend(default_mesh_error("n_meridian", self.R, self.h, g0));
        }
        self.imperfection.validate(e, "");
    }

    /// F R / (E h^3) per unit force.
    pub(super) fn f_bar(&self) -> f64 {
        self.R / (self.E * self.h.powi(3))
    }

    /// The mesh is the default one, whose resolution error is declared
    /// (`fem::mesh::default_mesh_rel_error`).
    pub(super) fn default_mesh(&self) -> bool {
        self.n_meridian.is_none() && self.n_thickness == 2
    }

    /// Elements along the meridian: as given, else resolving the Lennard-Jones range `g0`.
    pub(super) fn meridian(&self, g0: f64) -> usize {
        self.n_meridian.unwrap_or_else(|| physics::fem::mesh::meridian_elements(self.R, self.h, g0))
    }

    /// The memory a cycle of `steps` load steps allocates on this shell's mesh at the
    /// Lennard-Jones range `g0` (`fem::mesh::cycle_memory_bound`), with the mesh study's
    /// companion on twice the meridian elements alongside.
    pub(super) fn memory_bytes(&self, g0: f64, steps: usize, mesh_study: bool) -> u64 {
        cycle_memory_bytes(self.meridian(g0), self.n_thickness, steps, mesh_study)
    }

    /// The mesh on `n` meridian elements, before the imperfection's dimple.
    pub(super) fn mesh_on(&self, n: usize) -> ShellMesh {
        ShellMesh::hemisphere(self.R, self.h, n, self.n_thickness, self.grading)
    }

    /// The mesh, its meridian resolved for the Lennard-Jones range `g0` unless given.
    pub(super) fn mesh(&self, g0: f64) -> ShellMesh {
        self.imperfection.shape(self.mesh_on(self.meridian(g0)))
    }
}

/// The memory of a cycle of `steps` load steps on `n_meridian` x `n_thickness` elements
/// (the path's states: three per step are counted, which the peak resident sets of
/// docs/reliability.md, "Resources", bear out), with the mesh
/// study's companion on twice the meridian elements alongside.
pub(super) fn cycle_memory_bytes(n_meridian: usize, n_thickness: usize, steps: usize, mesh_study: bool) -> u64 {
    let states = steps.saturating_mul(3).saturating_add(64);
    let one = |n: usize| physics::fem::mesh::cycle_memory_bound(n, n_thickness, states);
    let companion = if mesh_study { one(n_meridian.saturating_mul(2)) } else { 0 };
    one(n_meridian).saturating_add(companion)
}

/// The default meridian mesh of a shell of radius `r` and thickness `h` resolves the
/// Lennard-Jones range `g0` (`fem::mesh::meridian_elements`); an error at `path` when that
/// takes more elements than the shell solver is given (`check::MAX_SHELL_ELEMENTS`), so
/// that a valid radius cannot ask for a mesh no memory holds (R = 1e6 mm at g0 = 0.1 mm:
/// 1.5e7 elements, 6 GB before it failed).
pub(super) fn default_mesh_error(path: &str, r: f64, h: f64, g0: f64) -> Option<FieldError> {
    let n = 1.5 * (r + h) / g0;
    (!(n <= check::MAX_SHELL_ELEMENTS as f64)).then(|| {
        FieldError::new(
            path,
            format!(
                "the default mesh of R = {} mm, h = {} mm at g0 = {} mm has about {n:.1e} meridian elements (1.5 (R + h) / g0), \
                 more than the {} the shell solver takes: give `n_meridian`, or a larger g0",
                format_number(r),
                format_number(h),
                format_number(g0),
                check::MAX_SHELL_ELEMENTS
            ),
        )
    })
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
        p.validate(default_g0(), &mut e);
        e
    }

    /// The mesh and its table: a few hundred bytes a node.
    fn memory_bytes(p: &ShellParams) -> Option<u64> {
        let nodes = physics::fem::mesh::node_count(p.meridian(default_g0()), p.n_thickness);
        Some((64u64 << 20).saturating_add(nodes.saturating_mul(256)))
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

/// The declared resolution error of a force on the default mesh at friction `mu`
/// (`fem::mesh::default_mesh_rel_error`); 0 on other meshes (not measured).
pub(crate) fn declared_mesh_error(force: f64, default_mesh: bool, mu: f64) -> f64 {
    if default_mesh {
        default_mesh_rel_error(mu) * force.abs()
    } else {
        0.0
    }
}

/// The declared resolution error of a cycle's dissipated energy `w` on the default mesh
/// under the Gauss rule `integration` (`fem::mesh::default_mesh_w_rel_error`); 0 on other
/// meshes (not measured).
pub(crate) fn declared_w_mesh_error(w: f64, default_mesh: bool, integration: Integration) -> f64 {
    if default_mesh {
        default_mesh_w_rel_error(integration.into()) * w.abs()
    } else {
        0.0
    }
}

/// The bisection's bracket of a snap-through force: from the last stable state to the
/// first unstable one.
pub(crate) fn snap_bracket(j: &Jump) -> f64 {
    (j.force_unstable - j.force_before).abs()
}

/// Errors of a nested parameter block, with their paths below `prefix`.
pub(super) fn prefixed(prefix: &str, errors: Vec<FieldError>) -> Vec<FieldError> {
    errors.into_iter().map(|f| FieldError::new(&format!("{prefix}.{}", f.path), f.message)).collect()
}

pub fn register(r: &mut Registry) {
    buckling::register(r);
    gamma_c::register(r);
    r.add::<FemMesh>().add::<FemIndent>().add::<FemProfile>();
}
