//! Parameters of the Chapter 3 shell shared by every `fem.*` kind: its hyperelastic law,
//! its imperfection and the stability test that decides the snap-through, with the
//! conversion to the physics' types (`fem::material::Law`, `fem::stability::Criterion`).

use physics::fem::element;
use physics::fem::material::Law;
use physics::fem::mesh::ShellMesh;
use physics::fem::stability::{Criterion, LIFT_THRESHOLD};
use physics::fem::system::Model;
use pipeline::kind::FieldError;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The hyperelastic law of the shell (`fem::material`): all three reduce to E and nu at
/// small strain.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Default, PartialEq, Eq, Debug)]
#[serde(rename_all = "snake_case")]
pub enum MaterialLaw {
    /// Compressible neo-Hookean (the default).
    #[default]
    NeoHookean,
    /// St Venant-Kirchhoff (CalculiX's `*ELASTIC` with NLGEOM).
    SaintVenantKirchhoff,
    /// Hencky: linear in the logarithmic strain.
    Hencky,
}

impl MaterialLaw {
    pub fn is_default(&self) -> bool {
        *self == MaterialLaw::NeoHookean
    }
}

impl From<MaterialLaw> for Law {
    fn from(m: MaterialLaw) -> Law {
        match m {
            MaterialLaw::NeoHookean => Law::NeoHookean,
            MaterialLaw::SaintVenantKirchhoff => Law::SaintVenantKirchhoff,
            MaterialLaw::Hencky => Law::Hencky,
        }
    }
}

/// The Gauss rule of the shell's elements (`fem::element::Integration`).
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Default, PartialEq, Eq, Debug)]
#[serde(rename_all = "snake_case")]
pub enum Integration {
    /// 3 x 3 points (the default): CalculiX's CAX8.
    #[default]
    Full,
    /// 2 x 2 points: ANSYS PLANE183's rule (the thesis' element), CalculiX's CAX8R; free of
    /// the 3 x 3 rule's excess stiffness under adhesion and friction with two elements
    /// through the thickness, but its spurious mode spoils the pressure under an apex
    /// force, and thick shells give way under it (docs/shell.md, "The element's Gauss
    /// rule").
    Reduced,
}

impl Integration {
    pub fn is_default(&self) -> bool {
        *self == Integration::Full
    }
}

impl From<Integration> for element::Integration {
    fn from(i: Integration) -> element::Integration {
        match i {
            Integration::Reduced => element::Integration::Reduced,
            Integration::Full => element::Integration::Full,
        }
    }
}

fn default_width() -> f64 {
    1.0
}

/// An explicit imperfection of the shell: a perturbing point force at the inner apex,
/// pointing away from the plate, and a Gaussian dimple of the reference shape at the apex
/// (`fem::mesh::ShellMesh::with_dimple`). Both zero: the perfect shell.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, PartialEq, Debug)]
#[serde(deny_unknown_fields)]
pub struct Imperfection {
    /// Apex force in units of F_c = E h^3 / R (default 0).
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub apex_force: f64,
    /// Depth of the dimple in units of h (default 0).
    #[serde(default)]
    pub dimple: f64,
    /// Gaussian radius of the dimple along the meridian, in units of sqrt(R h) (default 1).
    #[serde(default = "default_width")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub width: f64,
}

impl Default for Imperfection {
    fn default() -> Self {
        Imperfection { apex_force: 0.0, dimple: 0.0, width: default_width() }
    }
}

impl Imperfection {
    pub fn is_none(&self) -> bool {
        *self == Imperfection::default()
    }

    pub fn validate(&self, e: &mut Vec<FieldError>, prefix: &str) {
        if !(self.dimple.abs() < 0.5) {
            e.push(FieldError::new(
                &format!("{prefix}imperfection.dimple"),
                format!("a dimple deeper than h/2 is not an imperfection, got {} h", self.dimple),
            ));
        }
    }

    /// `mesh` with the dimple (R and h are the mesh's).
    pub fn shape(&self, mesh: ShellMesh) -> ShellMesh {
        let (r, h) = (mesh.radius, mesh.thickness);
        mesh.with_dimple(self.dimple * h, self.width * (r * h).sqrt())
    }

    /// `model` with the apex force, for Young's modulus `e`.
    pub fn load(&self, model: Model, e: f64) -> Model {
        let (r, h) = (model.mesh.radius, model.mesh.thickness);
        model.with_apex_force(self.apex_force * e * h.powi(3) / r)
    }
}

/// The stability test that decides the snap-through (`fem::stability::Criterion`).
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Default, PartialEq, Eq, Debug)]
#[serde(rename_all = "snake_case")]
pub enum Stability {
    /// Contact nodes pressed below `lift_threshold` of the peak pressure are free to lift
    /// (the default: a numerical knob standing in for an imperfection).
    #[default]
    LiftThreshold,
    /// The tangent of the unilateral contact at its active set: the snap is the limit point
    /// of the (imperfect) shell's path, no free parameter.
    Tangent,
}

impl Stability {
    pub fn is_default(&self) -> bool {
        *self == Stability::LiftThreshold
    }

    pub fn criterion(self, lift_threshold: f64) -> Criterion {
        match self {
            Stability::LiftThreshold => Criterion::LiftThreshold(lift_threshold),
            Stability::Tangent => Criterion::Tangent,
        }
    }
}

pub fn default_lift_threshold() -> f64 {
    LIFT_THRESHOLD
}

/// The shell model: mesh shaped by the imperfection, law, Gauss rule, supports, apex force.
///
/// Its arguments are the fields of the stages' shell settings (`MapModel`, `ShellParams`)
/// that the model needs, read by each kind from its own parameters.
#[allow(clippy::too_many_arguments)]
pub fn model(
    mesh: ShellMesh,
    e: f64,
    nu: f64,
    base: physics::fem::system::Base,
    law: MaterialLaw,
    integration: Integration,
    imperfection: &Imperfection,
) -> Model {
    let model =
        Model::new(imperfection.shape(mesh), e, nu, base).with_law(law.into()).with_integration(integration.into());
    imperfection.load(model, e)
}
