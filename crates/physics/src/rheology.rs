//! Linear viscoelastic materials beyond the standard linear solid: a discrete spectrum of
//! retardation (creep) times, built directly, from a Maxwell-Wiechert relaxation Prony series
//! (thesis Section 2, the Prony series after Eq. 2.28, converted with Eq. 2.27), or by
//! discretising the power-law spectrum of Eq. 5.24.
//!
//! Model: the creep function, in units of the relaxed compliance 1/E0,
//!   E0 J(t) = 1 - (1 - k) Sum_j w_j exp(-t / t_j),   Sum_j w_j = 1,   k = E0/E_inf,
//! i.e. the compliance spectrum of Eq. 5.25, 1/E(omega) = 1/E_inf + Int S(tau)/(1 - i omega tau)
//! dtau, with S(tau) = (1/E0 - 1/E_inf) Sum_j w_j delta(tau - t_j). Times t_j are in units of
//! a reference time tau: for the standard linear solid (one term, w = 1, t = 1) tau is its
//! creep time, the tau of Chapters 4-5; for the power law it is the longest time tau2.
//! A spectrum is a shape (weights and times); k is kept apart, as in the rest of the crate.
//!
//! Relaxation Prony series (Maxwell-Wiechert), in units of E_inf:
//!   Psi(t)/E_inf = k + (1 - k) Sum_i r_i exp(-t / rho_i),   Sum_i r_i = 1.
//! With f(s) = s Psi^(s)/E_inf = k + (1 - k) Sum_i r_i s/(s + 1/rho_i), Eq. 2.27 gives
//! s J^(s) E_inf = 1/f(s): the retardation rates q_j = 1/t_j are the zeros of f at s = -q_j,
//! one between each pair of consecutive relaxation rates (and one in (0, 1/rho_max)), and
//! the residues 1/f'(-q_j) give the weights: E_inf J(t) = 1 + Sum_j (1 - e^(-q_j t))/(q_j f'(-q_j)).
//! One relaxation time rho gives the SLS with creep time rho/k, exactly.
//!
//! Power law (Eq. 5.24): S(tau) = S0 tau^-s on (tau1, tau2), zero elsewhere, 0 <= s < 1.
//! Discretised on m bins per decade of ln tau: each bin carries its exact weight
//! Int_bin tau^-s dtau / Int tau^-s dtau and sits at its weight centroid in ln tau (second
//! order in the bin width for any smooth functional of the spectrum; tested on the moving
//! kernel).

use rustfft::num_complex::Complex64;
use std::sync::Arc;

/// Why a spectrum cannot be built from the values given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpectrumError {
    #[error("a spectrum needs at least one term")]
    NoTerms,
    #[error("term ({weight}, {time}): weights and times must be finite and positive")]
    Term { weight: f64, time: f64 },
    #[error("k = {0}: the modulus ratio must lie in (0, 1)")]
    ModulusRatio(f64),
    #[error("s = {0}: the power-law exponent must lie in [0, 1)")]
    Exponent(f64),
    #[error("t_min = {0}: tau1/tau2 must lie in (0, 1)")]
    TimeRatio(f64),
    #[error("per_decade must be at least 1")]
    NoBins,
}

/// A normalised retardation spectrum: weights w_j > 0 (summing to 1) at times t_j > 0,
/// sorted by time. Cheap to clone (shared).
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    terms: Arc<[(f64, f64)]>,
}

impl Default for Spectrum {
    fn default() -> Self {
        Spectrum::sls()
    }
}

impl Spectrum {
    /// The standard linear solid: one retardation time, the reference time.
    pub fn sls() -> Spectrum {
        Spectrum { terms: Arc::from(vec![(1.0, 1.0)]) }
    }

    /// A retardation spectrum from (weight, time) pairs; the weights are normalised.
    pub fn retardation(terms: &[(f64, f64)]) -> Result<Spectrum, SpectrumError> {
        if terms.is_empty() {
            return Err(SpectrumError::NoTerms);
        }
        for &(w, t) in terms {
            if !(w.is_finite() && w > 0.0 && t.is_finite() && t > 0.0) {
                return Err(SpectrumError::Term { weight: w, time: t });
            }
        }
        let total: f64 = terms.iter().map(|t| t.0).sum();
        let mut v: Vec<(f64, f64)> = terms.iter().map(|&(w, t)| (w / total, t)).collect();
        v.sort_by(|a, b| a.1.total_cmp(&b.1));
        Ok(Spectrum { terms: Arc::from(v) })
    }

    /// The retardation spectrum of a Maxwell-Wiechert relaxation Prony series with
    /// (weight r_i, relaxation time rho_i) pairs (weights normalised) and modulus ratio k.
    pub fn from_relaxation(k: f64, terms: &[(f64, f64)]) -> Result<Spectrum, SpectrumError> {
        if !(k > 0.0 && k < 1.0) {
            return Err(SpectrumError::ModulusRatio(k));
        }
        let relax = Spectrum::retardation(terms)?; // validated, normalised, sorted by time
                                                   // Rates p_i = 1/rho_i, ascending.
        let rates: Vec<(f64, f64)> = relax.terms.iter().rev().map(|&(r, rho)| (r, 1.0 / rho)).collect();
        let f = |s: f64| k + (1.0 - k) * rates.iter().map(|&(r, p)| r * s / (s + p)).sum::<f64>();
        let df = |s: f64| (1.0 - k) * rates.iter().map(|&(r, p)| r * p / ((s + p) * (s + p))).sum::<f64>();
        let mut out = Vec::with_capacity(rates.len());
        let mut lo = 0.0;
        for &(_, p) in &rates {
            // f(-q) = 0 with q in (lo, p): f(-lo) > 0 (or = k at lo = 0), f -> -inf as q -> p.
            // Bisection in q (f is monotone in s between its poles).
            let (mut a, mut b) = (lo, p);
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if m <= a || m >= b {
                    break;
                }
                if f(-m) > 0.0 {
                    a = m;
                } else {
                    b = m;
                }
            }
            let q = 0.5 * (a + b);
            // E_inf J(t) = 1 + Sum d_j (1 - e^(-q t)), d_j = 1/(q f'(-q)).
            let d = 1.0 / (q * df(-q));
            out.push((d, 1.0 / q));
            lo = p;
        }
        // Sum d_j = 1/k - 1 exactly; normalising by it keeps E0 J(inf) = 1 to rounding.
        Spectrum::retardation(&out)
    }

    /// The power-law spectrum of Eq. 5.24 on (t_min, 1) (times in units of tau2), exponent
    /// s in [0, 1), `per_decade` bins per decade (rounded up to cover the range).
    pub fn power_law(s: f64, t_min: f64, per_decade: usize) -> Result<Spectrum, SpectrumError> {
        if !(0.0..1.0).contains(&s) {
            return Err(SpectrumError::Exponent(s));
        }
        if !(t_min > 0.0 && t_min < 1.0) {
            return Err(SpectrumError::TimeRatio(t_min));
        }
        if per_decade == 0 {
            return Err(SpectrumError::NoBins);
        }
        let decades = -t_min.log10();
        let bins = (decades * per_decade as f64).ceil().max(1.0) as usize;
        let h = -t_min.ln() / bins as f64;
        // Int tau^-s dtau = tau^(1-s)/(1-s) (s < 1).
        let prim = |ln_t: f64| ((1.0 - s) * ln_t).exp() / (1.0 - s);
        // Each bin's node sits at its weight centroid in ln tau, lo + h c(h), with
        // c = 1/(1 - e^(-(1-s)h)) - 1/((1-s)h) (-> 1/2 as s -> 1): exact for any functional
        // linear in ln tau over the bin.
        let q = (1.0 - s) * h;
        let centroid = if q < 1e-6 { 0.5 } else { 1.0 / (-(-q).exp_m1()) - 1.0 / q };
        let terms: Vec<(f64, f64)> = (0..bins)
            .map(|b| {
                let lo = t_min.ln() + h * b as f64;
                (prim(lo + h) - prim(lo), (lo + h * centroid).exp())
            })
            .collect();
        Spectrum::retardation(&terms)
    }

    /// (weight, time) pairs, sorted by time, weights summing to 1.
    pub fn terms(&self) -> &[(f64, f64)] {
        &self.terms
    }

    /// Whether this is the one-term spectrum at the reference time (the SLS).
    pub fn is_sls(&self) -> bool {
        self.terms.len() == 1 && self.terms[0].1 == 1.0
    }

    /// E0 J(t), t in units of the reference time.
    pub fn creep(&self, k: f64, t: f64) -> f64 {
        1.0 - (1.0 - k) * self.terms.iter().map(|&(w, tj)| w * (-t / tj).exp()).sum::<f64>()
    }

    /// E0 / E(omega) (Eq. 5.25), omega in units of 1/tau, with the thesis' sign convention
    /// 1/(1 - i omega t): the imaginary part is positive (loss).
    pub fn compliance(&self, k: f64, omega: f64) -> Complex64 {
        let one = Complex64::new(1.0, 0.0);
        let sum: Complex64 = self.terms.iter().map(|&(w, t)| w * one / Complex64::new(1.0, -omega * t)).sum();
        Complex64::new(k, 0.0) + (1.0 - k) * sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::quad::integrate_panels;

    #[test]
    fn one_relaxation_time_is_the_standard_linear_solid() {
        // Psi = E0 + (E_inf - E0) e^(-t/rho) creeps with the time rho/k (Zener).
        for k in [1e-4, 0.1, 0.5, 0.99] {
            let rho = 0.37;
            let s = Spectrum::from_relaxation(k, &[(1.0, rho)]).unwrap();
            assert_eq!(s.terms().len(), 1);
            let (w, t) = s.terms()[0];
            assert!((w - 1.0).abs() < 1e-15 && (t / (rho / k) - 1.0).abs() < 1e-12, "k={k}: {w} {t}");
        }
        assert!(Spectrum::from_relaxation(0.1, &[(1.0, 0.1)]).unwrap().terms()[0].1 - 1.0 < 1e-12);
    }

    #[test]
    fn relaxation_and_creep_satisfy_eq_2_27() {
        // Check Int_0^t J(t - s) dPsi(s) + J(t) Psi(0) = 1 (the convolution form of Eq. 2.27)
        // by quadrature, for a three-term series, in units E_inf = 1.
        let k = 0.02;
        let relax = [(0.5, 0.01), (0.3, 1.0), (0.2, 40.0)];
        let spec = Spectrum::from_relaxation(k, &relax).unwrap();
        assert_eq!(spec.terms().len(), 3);
        let j = |t: f64| spec.creep(k, t) / k; // E_inf J
        let psi_rate = |t: f64| -(1.0 - k) * relax.iter().map(|&(r, rho)| r / rho * (-t / rho).exp()).sum::<f64>();
        for t in [0.003, 0.5, 7.0, 300.0] {
            let f = |s: f64| j(t - s) * psi_rate(s);
            let breaks: Vec<f64> =
                [0.0, 0.01, 0.1, 1.0, 10.0, 100.0, 1e3].iter().copied().filter(|&b| b < t).chain([t]).collect();
            let (conv, _) = integrate_panels(&f, &breaks, 1e-12);
            let lhs = j(t) * 1.0 + conv;
            assert!((lhs - 1.0).abs() < 1e-9, "t={t}: {lhs}");
        }
        // Relaxed and glassy limits.
        assert!((spec.creep(k, 0.0) - k).abs() < 1e-15 && (spec.creep(k, 1e9) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn power_law_bins_carry_the_exact_weights() {
        let s = 0.5;
        let spec = Spectrum::power_law(s, 1e-6, 4).unwrap();
        assert_eq!(spec.terms().len(), 24);
        // Weight below tau = 1e-3: (1e-3^(1/2) - 1e-3)/(1 - 1e-3) of the total.
        let below: f64 = spec.terms().iter().filter(|t| t.1 < 1e-3).map(|t| t.0).sum();
        let exact = (1e-3f64.sqrt() - 1e-6f64.sqrt()) / (1.0 - 1e-6f64.sqrt());
        assert!((below / exact - 1.0).abs() < 1e-12, "{below} {exact}");
        // s = 0: equal weight per unit tau, so the longest decade carries 90%.
        let flat = Spectrum::power_law(0.0, 1e-6, 1).unwrap();
        assert!((flat.terms()[5].0 - 0.9 / (1.0 - 1e-6)).abs() < 1e-12);
    }

    #[test]
    fn power_law_compliance_matches_eq_5_25_and_its_slope() {
        // The discretised 1/E(omega) against the integral of Eq. 5.25 by quadrature in ln tau.
        let (s, t1, k): (f64, f64, f64) = (0.6, 1e-6, 1e-3);
        let norm = (1.0 - t1.powf(1.0 - s)) / (1.0 - s);
        let exact = |omega: f64| {
            let f_re = |u: f64| {
                let t = u.exp();
                t.powf(1.0 - s) / norm / (1.0 + (omega * t).powi(2))
            };
            let f_im = |u: f64| {
                let t = u.exp();
                t.powf(1.0 - s) / norm * omega * t / (1.0 + (omega * t).powi(2))
            };
            let br: Vec<f64> = (0..=24).map(|i| t1.ln() * (1.0 - i as f64 / 24.0)).collect();
            let re = integrate_panels(&f_re, &br, 1e-12).0;
            let im = integrate_panels(&f_im, &br, 1e-12).0;
            Complex64::new(k + (1.0 - k) * re, (1.0 - k) * im)
        };
        for per_decade in [4, 16] {
            let spec = Spectrum::power_law(s, t1, per_decade).unwrap();
            let tol = if per_decade == 4 { 2e-2 } else { 2e-3 };
            for omega in [1e-2, 1.0, 1e2, 1e4] {
                let (a, b) = (spec.compliance(k, omega), exact(omega));
                assert!(((a - b).norm() / b.norm()) < tol, "m={per_decade} omega={omega}: {a} {b}");
            }
        }
        // Deep inside the spectrum |E(omega)| grows as omega^(1-s) (Section 5.4.1).
        let spec = Spectrum::power_law(s, 1e-9, 8).unwrap();
        let modulus = |w: f64| 1.0 / spec.compliance(1e-6, w).norm();
        let slope = (modulus(1e5) / modulus(1e3)).ln() / 100f64.ln();
        assert!((slope - (1.0 - s)).abs() < 0.02, "{slope}");
    }

    #[test]
    fn bad_spectra_are_rejected() {
        assert!(Spectrum::retardation(&[]).is_err());
        assert!(Spectrum::retardation(&[(1.0, 0.0)]).is_err());
        assert!(Spectrum::retardation(&[(-1.0, 1.0)]).is_err());
        assert!(Spectrum::power_law(1.0, 1e-6, 4).is_err());
        assert!(Spectrum::power_law(0.5, 2.0, 4).is_err());
        assert!(Spectrum::from_relaxation(1.0, &[(1.0, 1.0)]).is_err());
    }
}
