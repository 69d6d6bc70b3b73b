//! The material fields shared by the kinds that take a viscoelastic material (`bem.sweep`,
//! `theory.persson_brener`): the standard linear solid by default, the power-law spectrum
//! of Eq. 5.24 when `s` is given, or a Maxwell-Wiechert relaxation Prony series.

use pipeline::kind::FieldError;

/// Declares a kind's parameter struct with the material fields appended (`s`, `tau_ratio`,
/// `per_decade`, `prony`; serde cannot flatten into a struct that denies unknown fields) and
/// its `material()` view. The struct must have a field `k`.
macro_rules! with_material_fields {
    ($(#[$meta:meta])* pub struct $name:ident { $($(#[$fmeta:meta])* pub $field:ident : $ty:ty),* $(,)? }) => {
        $(#[$meta])*
        pub struct $name {
            $($(#[$fmeta])* pub $field: $ty,)*
            /// Material: the exponent s in [0, 1) of the power-law retardation spectrum
            /// S(tau) ~ tau^-s on (tau1, tau2) (Eq. 5.24), sweepable; then tau = tau2 (in V0 or
            /// v0). Default: the standard linear solid.
            #[serde(default, skip_serializing_if = "Option::is_none")]
            #[schemars(range(min = 0), extend("exclusiveMaximum" = 1.0))]
            pub s: Option<f64>,
            /// Power-law spectrum: tau1/tau2 (default 1e-6).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
            pub tau_ratio: Option<f64>,
            /// Power-law spectrum: bins per decade of its discretisation (default 8).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            #[schemars(range(min = 1, max = 64))]
            pub per_decade: Option<usize>,
            /// Material: a Maxwell-Wiechert relaxation Prony series, [[weight, relaxation time /
            /// tau], ...] (weights normalised; with k it fixes the creep function, Eq. 2.27).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub prony: Option<Vec<[f64; 2]>>,
        }

        impl $name {
            fn material(&self) -> $crate::stages::material::Material<'_> {
                $crate::stages::material::Material {
                    k: self.k,
                    s: self.s,
                    tau_ratio: self.tau_ratio,
                    per_decade: self.per_decade,
                    prony: self.prony.as_deref(),
                }
            }
        }
    };
}
use physics::rheology::Spectrum;
pub(crate) use with_material_fields;

/// A view of a kind's material fields.
pub struct Material<'a> {
    pub k: f64,
    pub s: Option<f64>,
    pub tau_ratio: Option<f64>,
    pub per_decade: Option<usize>,
    pub prony: Option<&'a [[f64; 2]]>,
}

/// Default tau1/tau2 of the power-law spectrum (Fig. 5.9: 1e-6 s to 1 s).
pub const DEFAULT_TAU_RATIO: f64 = 1e-6;
/// Default bins per decade of the discretised power law (kernel error < 1e-3 of the
/// strip's own displacement at 8; see `bem::kernel` tests).
pub const DEFAULT_PER_DECADE: usize = 8;

impl Material<'_> {
    pub fn validate(&self, errs: &mut Vec<FieldError>) {
        if self.s.is_some() && self.prony.is_some() {
            errs.push(FieldError::new("prony", "give either `s` (a power-law spectrum) or `prony`, not both"));
        }
        if self.s.is_none() && (self.tau_ratio.is_some() || self.per_decade.is_some()) {
            let name = if self.tau_ratio.is_some() { "tau_ratio" } else { "per_decade" };
            errs.push(FieldError::new(name, "only meaningful with `s` (the power-law spectrum)"));
        }
        if let Some(p) = self.prony {
            if p.is_empty() || p.len() > 200 {
                errs.push(FieldError::new("prony", format!("needs 1 to 200 [weight, time] terms, got {}", p.len())));
            } else if let Err(m) = Spectrum::retardation(&pairs(p)) {
                errs.push(FieldError::new("prony", m.to_string()));
            }
        }
    }

    /// The retardation spectrum (validated parameters).
    pub fn spectrum(&self) -> Spectrum {
        if let Some(s) = self.s {
            let t = self.tau_ratio.unwrap_or(DEFAULT_TAU_RATIO);
            Spectrum::power_law(s, t, self.per_decade.unwrap_or(DEFAULT_PER_DECADE)).expect("validated")
        } else if let Some(p) = self.prony {
            Spectrum::from_relaxation(self.k, &pairs(p)).expect("validated")
        } else {
            Spectrum::sls()
        }
    }

    /// The material in words, for a table's `material` column.
    pub fn describe(&self) -> String {
        if let Some(s) = self.s {
            format!(
                "power law s={s} tau1/tau2={} per_decade={}",
                self.tau_ratio.unwrap_or(DEFAULT_TAU_RATIO),
                self.per_decade.unwrap_or(DEFAULT_PER_DECADE)
            )
        } else if let Some(p) = self.prony {
            format!("Prony series, {} relaxation times", p.len())
        } else {
            "SLS".into()
        }
    }

    /// Whether the material is the default standard linear solid.
    pub fn is_sls(&self) -> bool {
        self.s.is_none() && self.prony.is_none()
    }
}

fn pairs(p: &[[f64; 2]]) -> Vec<(f64, f64)> {
    p.iter().map(|&[w, t]| (w, t)).collect()
}
