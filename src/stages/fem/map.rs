//! The model every point of the Chapter 3 buckling map shares (`MapModel`: the clamped
//! shell, its mesh, the interface and the loading), with the choices of what holds touching
//! points (`Hold`) and what counts as a snap (`SnapCriterion`); used by `fem.buckling`,
//! `fem.buckling_limit` and `fem.gamma_c`.

#![allow(non_snake_case)] // parameter names as in the thesis

use super::shell::{self, Imperfection, Integration, MaterialLaw, Stability};
use crate::stages::values::check;
use physics::fem::contact::Plate;
use physics::fem::cycle::{CycleOptions, FirstPass, Passes, Snap, Staggered};
use physics::fem::mesh::ShellMesh;
use physics::fem::stability::{AdhesiveHold, LIFT_THRESHOLD};
use physics::fem::system::{Base, Model};
use pipeline::kind::FieldError;
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// What holds touching points of an adhesive contact in the stability test
/// (`fem::stability::AdhesiveHold`).
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Default, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Hold {
    /// Nothing (Eq. 3.3 acts only for g' > 0; the default).
    #[default]
    Free,
    /// The law's lifting stiffness 16 dgamma / g0^2.
    LennardJones,
}

/// What counts as a snap-through for the questions "does it buckle before delta_max"
/// (`fem.gamma_c`, `fem.buckling_limit`) and where (`fem.buckling` without dissipation)
/// (`fem::cycle::Snap`).
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Default, PartialEq, Eq, Debug)]
#[serde(rename_all = "snake_case")]
pub enum SnapCriterion {
    /// The stability test gives up the flattened state (the thesis' criterion; default).
    #[default]
    Instability,
    /// The state lands on the inverted branch: the drop a displacement-controlled experiment
    /// sees (states given up by the test but held by the energy do not count).
    Landing,
    /// The thesis' staggered procedure (Section 3.2; `fem::cycle::Staggered`): adhesion as
    /// loads from the last pass's gaps, buckling the first negative slope of the contact
    /// force F(delta). Loading leg only.
    Thesis(ThesisProcedure),
    /// The energy balance Eq. 3.7 estimates (`fem::cycle::Snap::Energy`): the inverted
    /// state stores less total potential energy than the adhered flattened one at some
    /// delta up to delta_max, or the flattened branch ends.
    Energy,
    /// The energy balance with the work friction does as the contact slides to the
    /// inverted state (`fem::cycle::ShellProblem::friction_work`): the inverted state must
    /// lie lower by that work.
    EnergyFriction,
}

/// The settings of the thesis' staggered procedure (`SnapCriterion::Thesis`).
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Default, PartialEq, Eq, Debug)]
#[serde(deny_unknown_fields, default)]
pub struct ThesisProcedure {
    /// Passes with adhesive loads per displacement step (default: until the displacements
    /// change by less than 1e-10 h, at most 200).
    pub passes: Option<u32>,
    /// What each step's first solve carries: `without_adhesion` (default, as Section 3.2
    /// writes it) or `last_loads` (the last step's adhesive loads).
    pub first_pass: FirstPassLoads,
}

/// `fem::cycle::FirstPass`.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Default, PartialEq, Eq, Debug)]
#[serde(rename_all = "snake_case")]
pub enum FirstPassLoads {
    #[default]
    WithoutAdhesion,
    LastLoads,
}

impl SnapCriterion {
    pub(super) fn is_default(&self) -> bool {
        *self == SnapCriterion::Instability
    }

    /// The criterion in a figure's words (the `criterion` column): "local", "landing",
    /// "energy" (with the friction work, the published one), "energy (no friction work)",
    /// "staggered (the thesis' procedure)".
    pub(super) fn words(&self) -> &'static str {
        match self {
            SnapCriterion::Instability => "local",
            SnapCriterion::Landing => "landing",
            SnapCriterion::Energy => "energy (no friction work)",
            SnapCriterion::EnergyFriction => "energy",
            SnapCriterion::Thesis(_) => "staggered (the thesis' procedure)",
        }
    }
}

impl From<SnapCriterion> for Snap {
    fn from(c: SnapCriterion) -> Snap {
        match c {
            SnapCriterion::Instability => Snap::Instability,
            SnapCriterion::Landing => Snap::Landing,
            SnapCriterion::Energy => Snap::Energy { friction: false },
            SnapCriterion::EnergyFriction => Snap::Energy { friction: true },
            SnapCriterion::Thesis(t) => Snap::Staggered(Staggered {
                passes: t.passes.map_or(Passes::Converged, Passes::Fixed),
                first: match t.first_pass {
                    FirstPassLoads::WithoutAdhesion => FirstPass::WithoutAdhesion,
                    FirstPassLoads::LastLoads => FirstPass::LastLoads,
                },
            }),
        }
    }
}

impl From<Hold> for AdhesiveHold {
    fn from(h: Hold) -> AdhesiveHold {
        match h {
            Hold::Free => AdhesiveHold::Free,
            Hold::LennardJones => AdhesiveHold::LennardJones,
        }
    }
}

/// The shell (clamped base), its mesh, the interface and the loading shared by the points
/// of a map. Every field has a default (the thesis' R = 15 mm, E = 1.3 N/mm^2, nu = 0.45,
/// g0 = 0.1 mm).
#[derive(Serialize, Deserialize, JsonSchema, Clone)]
#[serde(deny_unknown_fields, default)]
#[allow(non_snake_case)]
pub struct MapModel {
    /// Inner radius R (mm).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub R: f64,
    /// Young's modulus (N/mm^2) and Poisson's ratio.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub E: f64,
    #[schemars(extend("exclusiveMinimum" = -1.0, "exclusiveMaximum" = 0.5))]
    pub nu: f64,
    /// Equilibrium distance g0 of the Lennard-Jones law (mm).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub g0: f64,
    /// Mesh: elements along the meridian (default 1.5 (R + h) / g0,
    /// `fem::mesh::meridian_elements`) and through the thickness (default 2), grading.
    #[schemars(range(min = 4, max = check::MAX_SHELL_ELEMENTS))]
    pub n_meridian: Option<usize>,
    #[schemars(range(min = 1, max = 16))]
    pub n_thickness: usize,
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub grading: f64,
    /// Contact penalty in units of E/h.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub penalty: f64,
    /// Largest plate displacement delta/R, and equal load steps to it.
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub delta_max: f64,
    #[schemars(range(min = 1, max = check::MAX_STEPS))]
    pub steps: usize,
    /// Stability test: pressure fraction above which contact nodes are held.
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub lift_threshold: f64,
    /// Bisections locating a snap in delta.
    pub bisections: u32,
    /// What holds touching adhesive points in the stability test.
    pub hold: Hold,
    /// What counts as a snap-through: `instability` (default), `landing` or
    /// `{thesis: {passes: n, first_pass: ...}}` (`SnapCriterion`).
    #[serde(skip_serializing_if = "SnapCriterion::is_default")]
    pub snap: SnapCriterion,
    /// Stability test: `lift_threshold` (default) or `tangent` (`shell::Stability`).
    #[serde(skip_serializing_if = "Stability::is_default")]
    pub stability: Stability,
    /// Hyperelastic law (`shell::MaterialLaw`).
    #[serde(skip_serializing_if = "MaterialLaw::is_default")]
    pub material: MaterialLaw,
    /// Gauss rule of the elements (`shell::Integration`; default `full`, 3 x 3).
    #[serde(skip_serializing_if = "Integration::is_default")]
    pub integration: Integration,
    /// Imperfection (`shell::Imperfection`; default none).
    #[serde(skip_serializing_if = "Imperfection::is_none")]
    pub imperfection: Imperfection,
}

impl Default for MapModel {
    fn default() -> Self {
        MapModel {
            R: 15.0,
            E: 1.3,
            nu: 0.45,
            g0: 0.1,
            n_meridian: None,
            n_thickness: 2,
            grading: 3.0,
            penalty: 1000.0,
            delta_max: 0.35,
            steps: 35,
            lift_threshold: LIFT_THRESHOLD,
            bisections: 5,
            hold: Hold::Free,
            snap: SnapCriterion::Instability,
            stability: Stability::LiftThreshold,
            material: MaterialLaw::NeoHookean,
            integration: Integration::Full,
            imperfection: Imperfection::default(),
        }
    }
}

/// A snap is located to delta/R = 1 / `FOLD_RESOLUTION` at least, whatever the base step:
/// the default base step delta/R = 0.35 / 35 halved 8 times. Probes that need only the snap
/// (`fem.gamma_c`, `fem.buckling_limit`, the imperfection sweeps) take fewer, longer steps
/// on the way to it (docs/shell.md, "Cost").
const FOLD_RESOLUTION: f64 = 25_600.0;

/// Halvings of a base step of `base_over_r` (delta/R): 8, or more where the step needs them
/// to reach delta/R = 1 / `FOLD_RESOLUTION`.
fn max_cuts(base_over_r: f64) -> u32 {
    // (the tolerance keeps a base step of exactly 256 resolutions at 8)
    ((base_over_r * FOLD_RESOLUTION).log2() - 1e-9).ceil().max(8.0) as u32
}

impl MapModel {
    pub(super) fn validate(&self, e: &mut Vec<FieldError>) {
        self.imperfection.validate(e, "model.");
        if let SnapCriterion::Thesis(ThesisProcedure { passes: Some(n), .. }) = self.snap {
            if !(1..=physics::fem::cycle::MAX_PASSES).contains(&n) {
                e.push(FieldError::new(
                    "model.snap.thesis.passes",
                    format!("passes per step must lie in 1..={}, got {n}", physics::fem::cycle::MAX_PASSES),
                ));
            }
        }
    }

    /// `t` with the model's parameters a figure states, on each of its `n` rows: where the
    /// loading ends (`delta_max_over_R`) and what counts as a snap (`criterion`).
    pub(super) fn stated(&self, t: Table, n: usize) -> Table {
        t.with_f64("delta_max_over_R", vec![self.delta_max; n])
            .with("criterion", ColumnData::Str(vec![self.snap.words().to_string(); n]))
    }

    /// The model of one point of a sweep over the interface's range and the imperfection:
    /// each given value replaces the model's (`g0` in mm, `apex_force` in F_c, `dimple` in h).
    pub(super) fn at_point(&self, g0: Option<f64>, apex_force: Option<f64>, dimple: Option<f64>) -> MapModel {
        let mut m = self.clone();
        m.g0 = g0.unwrap_or(m.g0);
        m.imperfection.apex_force = apex_force.unwrap_or(m.imperfection.apex_force);
        m.imperfection.dimple = dimple.unwrap_or(m.imperfection.dimple);
        m
    }

    /// Checks the mesh of the shell at `h_over_r` (the default one resolves g0).
    pub(super) fn validate_mesh(&self, h_over_r: f64, e: &mut Vec<FieldError>) {
        if self.n_meridian.is_none() {
            e.extend(super::default_mesh_error("model.n_meridian", self.R, self.h(h_over_r), self.g0));
        }
    }

    /// The memory of one cycle at `h_over_r` (`fem::mesh::cycle_memory_bound`), with the
    /// mesh study's companion alongside.
    pub(super) fn memory_bytes(&self, h_over_r: f64, mesh_study: bool) -> u64 {
        super::cycle_memory_bytes(self.meridian_elements(h_over_r), self.n_thickness, self.steps, mesh_study)
    }

    pub(super) fn h(&self, h_over_r: f64) -> f64 {
        h_over_r * self.R
    }

    /// Elements along the meridian at `h_over_r` (given, or the default rule).
    pub(super) fn meridian_elements(&self, h_over_r: f64) -> usize {
        self.n_meridian.unwrap_or_else(|| physics::fem::mesh::meridian_elements(self.R, self.h(h_over_r), self.g0))
    }

    pub(super) fn shell(&self, h_over_r: f64) -> Model {
        self.shell_with(h_over_r, self.meridian_elements(h_over_r))
    }

    /// The shell with `n_meridian` elements along the meridian.
    pub(super) fn shell_with(&self, h_over_r: f64, n_meridian: usize) -> Model {
        let mesh = ShellMesh::hemisphere(self.R, self.h(h_over_r), n_meridian, self.n_thickness, self.grading);
        shell::model(mesh, self.E, self.nu, Base::Clamped, self.material, self.integration, &self.imperfection)
    }

    /// The mesh is the default one (whose resolution error is declared,
    /// `fem::mesh::default_mesh_rel_error`).
    pub(super) fn default_mesh(&self) -> bool {
        self.n_meridian.is_none() && self.n_thickness == 2
    }

    pub(super) fn plate(&self, model: &Model, h_over_r: f64, gamma_over_eh: f64, mu: f64) -> Plate {
        Plate::new(&model.mesh, self.E, self.penalty)
            .with_adhesion(gamma_over_eh * self.E * self.h(h_over_r), self.g0)
            .with_friction(mu)
    }

    pub(super) fn options(&self, unload: bool) -> CycleOptions {
        CycleOptions {
            delta_max: self.delta_max * self.R,
            steps: self.steps,
            max_cuts: max_cuts(self.delta_max / self.steps as f64),
            bisections: self.bisections,
            criterion: self.stability.criterion(self.lift_threshold),
            hold: self.hold.into(),
            trace_unstable: false,
            unload,
            stop_at_buckling: !unload,
            snap: self.snap.into(),
        }
    }

    /// F R / (E h^3) per unit force.
    pub(super) fn f_bar(&self, h_over_r: f64) -> f64 {
        self.R / (self.E * self.h(h_over_r).powi(3))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_snap_is_located_to_the_same_resolution_whatever_the_base_step() {
        // The default 35 steps to delta/R = 0.35, and steps of that length or shorter, keep 8
        // halvings; longer steps get as many more as reach delta/R = 1/25600 (10 steps to
        // 0.35: 10 halvings, 1/29257).
        assert_eq!(max_cuts(0.35 / 35.0), 8);
        assert_eq!(max_cuts(0.7 / 70.0), 8);
        assert_eq!(max_cuts(0.65 / 65.0), 8);
        assert_eq!(max_cuts(0.35 / 70.0), 8);
        assert_eq!(max_cuts(0.35 / 20.0), 9);
        assert_eq!(max_cuts(0.35 / 10.0), 10);
        assert_eq!(max_cuts(0.7 / 20.0), 10);
        for (delta_max, steps) in [(0.35, 1), (0.35, 3), (0.35, 7), (0.35, 10), (0.7, 20), (0.35, 34), (0.5, 36)] {
            let base = delta_max / steps as f64;
            let smallest = base / 2f64.powi(max_cuts(base) as i32);
            assert!(smallest <= 1.0 / FOLD_RESOLUTION, "{steps} steps: {smallest}");
            // and no finer than needed
            assert!(2.0 * smallest > 1.0 / FOLD_RESOLUTION, "{steps} steps");
        }
    }
}
