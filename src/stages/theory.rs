//! Stage kinds for the closed-form theories: classical sphere contact (Hertz, JKR, DMT,
//! Maugis–Dugdale), Persson's adhesionless friction, and Persson–Brener.

use super::material::{with_material_fields, DEFAULT_TAU_RATIO};
use super::values::{bound, check};
use anyhow::{bail, Result};
use physics::theory::{classical, line_contact, persson, persson_brener};
use pipeline::kind::{FieldError, Inputs, Kind, Output, Registry};
use pipeline::table::{ColumnData, Table};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

fn default_a_min() -> f64 {
    0.02
}
fn default_a_max() -> f64 {
    2.5
}
fn default_n() -> usize {
    200
}
fn default_rel_tol() -> f64 {
    1e-8
}

/// Log-spaced contact radii from a_min to a_max.
fn radii(a_min: f64, a_max: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| a_min * (a_max / a_min).powf(i as f64 / (n - 1) as f64)).collect()
}

fn check_radii(e: &mut Vec<FieldError>, a_min: f64, a_max: f64) {
    if !(a_max > a_min) {
        e.push(FieldError::new("A_max", format!("must exceed A_min ({a_min}), got {a_max}")));
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct MaugisParams {
    /// Maugis' transition parameter lambda = 2 sigma0 (R / (pi w K^2))^(1/3) (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub lambda: f64,
    /// Smallest dimensionless contact radius A.
    #[serde(default = "default_a_min")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub A_min: f64,
    /// Largest dimensionless contact radius A.
    #[serde(default = "default_a_max")]
    pub A_max: f64,
    /// Number of radii (log-spaced).
    #[serde(default = "default_n")]
    #[schemars(range(min = 2, max = check::MAX_POINTS))]
    pub n: usize,
}

/// The Maugis–Dugdale load–radius curve for one lambda.
pub struct MaugisDugdale;

impl Kind for MaugisDugdale {
    const NAME: &'static str = "theory.maugis_dugdale";
    const VERSION: u32 = 2;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "Maugis-Dugdale sphere contact: load P_bar and approach vs contact radius A_bar (thesis 2.4.2.4)";
    const SWEEPABLE: &'static [&'static str] = &["lambda"];
    const COLUMNS: &'static [&'static str] = &["lambda", "A_bar", "P_bar", "approach_bar", "m", "error_estimate"];
    type Params = MaugisParams;

    fn validate(p: &MaugisParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        check_radii(&mut e, p.A_min, p.A_max);
        e
    }

    fn run(p: &MaugisParams, _: &Inputs) -> Result<Output> {
        let mut cols: [Vec<f64>; 5] = Default::default();
        for a in radii(p.A_min, p.A_max, p.n) {
            let Some(pt) = classical::maugis_dugdale(a, p.lambda) else {
                bail!("no Maugis-Dugdale solution at A = {a}, lambda = {}", p.lambda)
            };
            for (c, v) in cols.iter_mut().zip([a, pt.load, pt.approach, pt.m, bound(pt.load_error)]) {
                c.push(v);
            }
        }
        let [a, load, approach, m, error] = cols;
        Ok(Table::new()
            .with_f64("lambda", vec![p.lambda; a.len()])
            .with_f64("A_bar", a)
            .with_f64("P_bar", load)
            .with_f64("approach_bar", approach)
            .with_f64("m", m)
            .with_f64("error_estimate", error)
            .into())
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PullOffParams {
    /// Maugis' transition parameter (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub lambda: f64,
}

/// Pull-off load of the Maugis–Dugdale sphere under load control.
pub struct MaugisPullOff;

impl Kind for MaugisPullOff {
    const NAME: &'static str = "theory.maugis_pulloff";
    const VERSION: u32 = 2;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str = "Maugis-Dugdale pull-off load (minimum of P_bar over A_bar); JKR -3/2, DMT -2";
    const SWEEPABLE: &'static [&'static str] = &["lambda"];
    const COLUMNS: &'static [&'static str] =
        &["lambda", "P_bar_pulloff", "A_bar_pulloff", "error_estimate", "P_bar_jkr", "P_bar_dmt"];
    type Params = PullOffParams;

    fn run(p: &PullOffParams, _: &Inputs) -> Result<Output> {
        let Some(po) = classical::maugis_pull_off(p.lambda) else {
            bail!("no pull-off found for lambda = {}", p.lambda)
        };
        Ok(Table::new()
            .with_f64("lambda", vec![p.lambda])
            .with_f64("P_bar_pulloff", vec![po.load])
            .with_f64("A_bar_pulloff", vec![po.radius])
            .with_f64("error_estimate", vec![bound(po.error)])
            .with_f64("P_bar_jkr", vec![classical::JKR_PULL_OFF])
            .with_f64("P_bar_dmt", vec![classical::DMT_PULL_OFF])
            .into())
    }
}

/// Line-contact pull-off (2D, Chapter 4 units): Maugis-Dugdale, JKR and the rigid
/// cylinder with the Lennard-Jones law, the limits of `bem.pulloff` at low speed.
pub struct LinePullOff;

impl Kind for LinePullOff {
    const NAME: &'static str = "theory.line_pulloff";
    const VERSION: u32 = 2;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "2D line-contact pull-off W: Maugis-Dugdale, JKR -3(pi/16)^(1/3), rigid Lennard-Jones -2.434 sqrt(lambda)";
    const SWEEPABLE: &'static [&'static str] = &["lambda"];
    const COLUMNS: &'static [&'static str] = &["lambda", "W_md", "A_md", "error_estimate", "W_jkr", "W_rigid_lj"];
    type Params = PullOffParams;

    fn run(p: &PullOffParams, _: &Inputs) -> Result<Output> {
        let Some(po) = line_contact::maugis_dugdale_line_pull_off(p.lambda) else {
            bail!("no line-contact pull-off found for lambda = {}", pipeline::table::format_number(p.lambda))
        };
        Ok(Table::new()
            .with_f64("lambda", vec![p.lambda])
            .with_f64("W_md", vec![po.load])
            .with_f64("A_md", vec![po.radius])
            .with_f64("error_estimate", vec![bound(po.error)])
            .with_f64("W_jkr", vec![physics::theory::line_contact::jkr_pull_off()])
            .with_f64("W_rigid_lj", vec![-line_contact::lj_rigid_pull_off_coefficient() * p.lambda.sqrt()])
            .into())
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct LimitsParams {
    #[serde(default = "default_a_min")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub A_min: f64,
    #[serde(default = "default_a_max")]
    pub A_max: f64,
    #[serde(default = "default_n")]
    #[schemars(range(min = 2, max = check::MAX_POINTS))]
    pub n: usize,
}

/// Hertz, JKR and DMT load–radius curves in Maugis' units.
pub struct SphereLimits;

impl Kind for SphereLimits {
    const NAME: &'static str = "theory.sphere_limits";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str = "Hertz (P = A^3), JKR (A^3 - sqrt(6 A^3)) and DMT (A^3 - 2) curves in Maugis' units";
    const COLUMNS: &'static [&'static str] = &["model", "A_bar", "P_bar"];
    type Params = LimitsParams;

    fn validate(p: &LimitsParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        check_radii(&mut e, p.A_min, p.A_max);
        e
    }

    fn run(p: &LimitsParams, _: &Inputs) -> Result<Output> {
        let a = radii(p.A_min, p.A_max, p.n);
        let mut t = Table::new();
        type LoadOfRadius = fn(f64) -> f64;
        let models: [(&str, LoadOfRadius); 3] =
            [("hertz", classical::hertz_load), ("jkr", classical::jkr_load), ("dmt", classical::dmt_load)];
        for (name, f) in models {
            t.append(
                &Table::new()
                    .with("model", ColumnData::Str(vec![name.to_string(); a.len()]))
                    .with_f64("A_bar", a.clone())
                    .with_f64("P_bar", a.iter().map(|&x| f(x)).collect()),
            )?;
        }
        Ok(t.into())
    }
}

fn default_load() -> f64 {
    1.0
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct PressureParams {
    /// Load in Maugis' units, P = F / (pi w R); must exceed the JKR pull-off -3/2.
    #[serde(default = "default_load")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub P_bar: f64,
    /// Number of radial points per model.
    #[serde(default = "default_n")]
    #[schemars(range(min = 10, max = check::MAX_POINTS))]
    pub n: usize,
}

/// Hertz and JKR pressure profiles at the same load (thesis Fig. 2.4).
pub struct HertzJkrPressure;

impl Kind for HertzJkrPressure {
    const NAME: &'static str = "theory.hertz_jkr_pressure";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str = "Hertz and JKR pressure p/p0_Hertz vs r/a_Hertz at the same load (Fig. 2.4)";
    const COLUMNS: &'static [&'static str] = &["model", "P_bar", "r_over_aH", "p_over_p0H"];
    type Params = PressureParams;

    fn run(p: &PressureParams, _: &Inputs) -> Result<Output> {
        let a_h = p.P_bar.cbrt();
        let Some(a_j) = classical::jkr_radius(p.P_bar) else { bail!("load below the JKR pull-off") };
        let rho_max = 1.3 * a_j / a_h;
        let mut t = Table::new();
        // Hertz on a uniform grid; JKR on r = a sin(theta), which clusters points at the
        // singular edge; stop where sqrt(1 - r^2/a^2) = 0.02.
        let hertz_rho: Vec<f64> = (0..p.n).map(|i| rho_max * i as f64 / (p.n - 1) as f64).collect();
        let th_max = (1.0f64 - 0.02f64.powi(2)).sqrt().asin();
        let mut jkr_rho: Vec<f64> =
            (0..p.n).map(|i| (a_j / a_h) * (th_max * i as f64 / (p.n - 1) as f64).sin()).collect();
        jkr_rho.extend([a_j / a_h, rho_max]);
        let mut jkr_p: Vec<f64> =
            jkr_rho[..p.n].iter().map(|&r| classical::jkr_pressure(r, p.P_bar).unwrap()).collect();
        jkr_p.extend([0.0, 0.0]);
        for (name, rho, pr) in [
            ("hertz", hertz_rho.clone(), hertz_rho.iter().map(|&r| classical::hertz_pressure(r)).collect::<Vec<_>>()),
            ("jkr", jkr_rho, jkr_p),
        ] {
            let n = rho.len();
            t.append(
                &Table::new()
                    .with("model", ColumnData::Str(vec![name.to_string(); n]))
                    .with_f64("P_bar", vec![p.P_bar; n])
                    .with_f64("r_over_aH", rho)
                    .with_f64("p_over_p0H", pr),
            )?;
        }
        Ok(t.into())
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct PerssonParams {
    /// 1/k = E_inf / E0 (sweepable), > 1.
    #[schemars(extend("exclusiveMinimum" = 1.0))]
    pub inv_k: f64,
    /// V0 = v tau / a0 (sweepable), in (0, 1e100]: beyond 1e100 mu* (about 1/V0 there)
    /// underflows the quadrature's relative tolerance.
    #[schemars(extend("exclusiveMinimum" = 0), range(max = 1e100))]
    pub V0: f64,
    /// Relative tolerance of the quadrature, in [1e-14, 0.01): below 1e-14 double precision
    /// cannot meet it (at 1e-16 the quadrature refines for a minute and returns the same digits).
    #[serde(default = "default_rel_tol")]
    #[schemars(range(min = 1e-14), extend("exclusiveMaximum" = 0.01))]
    pub rel_tol: f64,
}

/// Persson's adhesionless friction mu* at one (1/k, V0) (Appendix A).
pub struct Persson;

impl Kind for Persson {
    const NAME: &'static str = "theory.persson";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "Persson's adhesionless friction mu* = mu R/a0 vs V0 = v tau/a0 for a standard linear solid (Eqs. 7.1-7.2)";
    const SWEEPABLE: &'static [&'static str] = &["inv_k", "V0"];
    const COLUMNS: &'static [&'static str] = &["inv_k", "k", "V0", "mu_star", "error_estimate"];
    type Params = PerssonParams;

    fn run(p: &PerssonParams, _: &Inputs) -> Result<Output> {
        let f = persson::mu_star(1.0 / p.inv_k, p.V0, p.rel_tol);
        Ok(Table::new()
            .with_f64("inv_k", vec![p.inv_k])
            .with_f64("k", vec![1.0 / p.inv_k])
            .with_f64("V0", vec![p.V0])
            .with_f64("mu_star", vec![f.mu_star])
            .with_f64("error_estimate", vec![f.error_estimate])
            .into())
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PerssonMaxParams {
    /// 1/k = E_inf / E0 (sweepable), > 1.
    #[schemars(extend("exclusiveMinimum" = 1.0))]
    pub inv_k: f64,
    #[serde(default = "default_rel_tol")]
    #[schemars(range(min = 1e-14), extend("exclusiveMaximum" = 0.01))]
    pub rel_tol: f64,
}

/// The maximum over V0 of Persson's mu* for one 1/k (Fig. 7.4).
pub struct PerssonMax;

impl Kind for PerssonMax {
    const NAME: &'static str = "theory.persson_max";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str = "Maximum over V0 of Persson's adhesionless mu*, and where it occurs";
    const SWEEPABLE: &'static [&'static str] = &["inv_k"];
    const COLUMNS: &'static [&'static str] = &["inv_k", "k", "mu_star_max", "V0_at_max", "error_estimate"];
    type Params = PerssonMaxParams;

    fn run(p: &PerssonMaxParams, _: &Inputs) -> Result<Output> {
        let (v, f) = persson::max_mu_star(1.0 / p.inv_k, p.rel_tol);
        Ok(Table::new()
            .with_f64("inv_k", vec![p.inv_k])
            .with_f64("k", vec![1.0 / p.inv_k])
            .with_f64("mu_star_max", vec![f.mu_star])
            .with_f64("V0_at_max", vec![v])
            .with_f64("error_estimate", vec![f.error_estimate])
            .into())
    }
}

with_material_fields! {
#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct PbParams {
    /// Modulus ratio k = E0 / E_inf in (0, 1) (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0.0, "exclusiveMaximum" = 1.0))]
    pub k: f64,
    /// V_PB = v / v0, v0 = c0 / (2 pi tau) (sweepable).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub V_PB: f64,
}
}

/// Persson–Brener trailing-edge energy release and friction (Eqs. 5.10–5.13), for the SLS
/// or a retardation spectrum (Eq. 5.27).
pub struct PerssonBrener;

impl Kind for PerssonBrener {
    const NAME: &'static str = "theory.persson_brener";
    const VERSION: u32 = 4;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str = "Persson-Brener G_trail/dgamma (Eq. 5.12, or Eq. 5.27 for a spectrum) and f_T/dgamma = G - 1/G (Eq. 5.13) vs v/v0";
    const SWEEPABLE: &'static [&'static str] = &["k", "V_PB", "s"];
    const COLUMNS: &'static [&'static str] =
        &["k", "V_PB", "G_trail_over_dgamma", "F_T_PB", "error_estimate", "s", "tau_ratio", "n_eq_5_28", "material"];
    type Params = PbParams;

    fn validate(p: &PbParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        p.material().validate(&mut e);
        e
    }

    fn run(p: &PbParams, _: &Inputs) -> Result<Output> {
        let m = p.material();
        let spectrum = m.spectrum();
        let g = persson_brener::g_trailing_spectrum(p.V_PB, p.k, &spectrum);
        let (f, f_error) = persson_brener::friction_spectrum_bounded(p.V_PB, p.k, &spectrum);
        let t = Table::new()
            .with_f64("k", vec![p.k])
            .with_f64("V_PB", vec![p.V_PB])
            .with_f64("G_trail_over_dgamma", vec![g])
            .with_f64("F_T_PB", vec![f])
            .with_f64("error_estimate", vec![bound(f_error)]);
        let t = match p.s {
            _ if m.is_sls() => t,
            Some(s) => t
                .with_f64("s", vec![s])
                .with_f64("tau_ratio", vec![m.tau_ratio.unwrap_or(DEFAULT_TAU_RATIO)])
                .with_f64("n_eq_5_28", vec![persson_brener::power_law_exponent(s)])
                .with("material", ColumnData::Str(vec![m.describe()])),
            None => t.with("material", ColumnData::Str(vec![m.describe()])),
        };
        Ok(t.into())
    }
}

#[derive(Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LennardJonesParams {
    /// Separations h/eps from `z_min` to `z_max` (eps the equilibrium separation), `n` points.
    #[serde(default = "default_z_min")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub z_min: f64,
    #[serde(default = "default_z_max")]
    pub z_max: f64,
    #[serde(default = "default_n")]
    #[schemars(range(min = 2, max = check::MAX_POINTS))]
    pub n: usize,
}

fn default_z_min() -> f64 {
    0.85
}
fn default_z_max() -> f64 {
    4.0
}

/// The Lennard-Jones 3-9 law the BEM solves with (`lennard_jones`; the shell's is the same law
/// shifted by g0, `fem::adhesion`): energy and disjoining pressure against separation.
pub struct LennardJones;

impl Kind for LennardJones {
    const NAME: &'static str = "theory.lennard_jones";
    const VERSION: u32 = 1;
    const TIME_LIMIT_S: f64 = 60.0;
    const DOC: &'static str =
        "The Lennard-Jones 3-9 law of the solvers: energy/dgamma and pressure/sigma0 vs separation h/eps (Fig. 2.3)";
    const COLUMNS: &'static [&'static str] = &["h_over_eps", "energy_over_dgamma", "pressure_over_sigma0"];
    type Params = LennardJonesParams;

    fn validate(p: &LennardJonesParams) -> Vec<FieldError> {
        let mut e = Vec::new();
        if !(p.z_max > p.z_min) {
            e.push(FieldError::new("z_max", format!("must exceed z_min ({}), got {}", p.z_min, p.z_max)));
        }
        e
    }

    fn run(p: &LennardJonesParams, _: &Inputs) -> Result<Output> {
        use physics::lennard_jones::{energy, pressure, ALPHA};
        let z: Vec<f64> = (0..p.n).map(|i| p.z_min + (p.z_max - p.z_min) * i as f64 / (p.n - 1) as f64).collect();
        // The solver's pressure at lambda = 1: h/eps = 1 + alpha H.
        let sigma: Vec<f64> = z.iter().map(|&z| pressure((z - 1.0) / ALPHA, 1.0).0).collect();
        Ok(Table::new()
            .with_f64("h_over_eps", z.clone())
            .with_f64("energy_over_dgamma", z.iter().map(|&z| energy(z)).collect())
            .with_f64("pressure_over_sigma0", sigma)
            .into())
    }
}

pub fn register(r: &mut Registry) {
    r.add::<MaugisDugdale>()
        .add::<LennardJones>()
        .add::<MaugisPullOff>()
        .add::<LinePullOff>()
        .add::<SphereLimits>()
        .add::<HertzJkrPressure>()
        .add::<Persson>()
        .add::<PerssonMax>()
        .add::<PerssonBrener>();
}
