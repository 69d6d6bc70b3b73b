//! Surface displacement of a uniform pressure strip moving steadily over a standard
//! linear solid half-plane (thesis Eq. 4.10, corrected: ERRATA items 2, 9, 10).
//!
//! Model: plane strain, creep function J(t) = (1/E0)[1 - (1 - k) exp(-t/tau)], k = E0/E_inf.
//! Units (Eq. 4.6 corrected, ERRATA 1): X = x/beta, U = u_z R/beta^2, P = p/sigma0, with
//! beta = (R^2 dgamma/E0*)^(1/3); V = v tau/beta (ERRATA 9); the strip has half-width A.
//! Convention (fixed for the whole crate, ERRATA 17): the indenter slides towards -X, so
//! in its frame the material flows towards +X; the leading edge is on the left, the
//! trailing edge on the right (as in Section 4.3.1 and Fig. 4.3). U is the displacement
//! into the substrate (it opens the gap H = -Delta + X^2/2 + U of Eq. 4.7).
//!
//! Derivation (hereditary integral): a material point now at X felt the relaxed elastic
//! displacement field U_el at X - V s a time s ago, so
//!   U(X) = U_el(X) - (1 - k) Int_0^inf exp(-s) dU_el/dX(X - V s) V ds,
//! with, for unit pressure and without the factor 2 lambda/pi of Eq. 4.12,
//!   U_el(X) = -[(X+A) ln|X+A| - (X-A) ln|X-A| - 2A].
//! Integrating by parts, with exp(-y)Ei(y) from `expint`, gives (dropping a constant,
//! which the approach Delta absorbs):
//!   K(X) = U_el(X) + (1 - k) V [g((X+A)/V) - g((X-A)/V)],  g(y) = ln|y| + gamma - exp(-y)Ei(y).
//! This is the printed Eq. 4.10 with its overall sign reversed and X -> -X (the printed
//! form slides towards +X); the tests check both that and the hereditary integral itself.
//! Limits: V -> 0 gives the relaxed half-plane, V -> inf k times it (the instantaneous one).
//! ERRATA 2's sign test U(0) - U(+-5A) > 0 holds in both elastic limits and upstream at
//! every speed; downstream it fails for V ~ 5A, where creep after the strip has passed
//! outgrows the displacement under it (see the test).
//!
//! General creep functions (`rheology::Spectrum`, E0 J(t) = 1 - (1-k) Sum w_j exp(-t/t_j)):
//! the hereditary integral is linear in J, so the kernel is the elastic part plus the sum of
//! one-time terms, each at its own speed V_j = V t_j:
//!   K(X) = U_el(X) + (1 - k) Sum_j w_j V_j [g((X+A)/V_j) - g((X-A)/V_j)].
//! One term at t = 1 is the SLS kernel above, term for term.
//!
//! The solver's meshes (`MeshKernel`) take the pressure linear between nodes by default
//! (`Pressure`): the displacement of a hat of pressure is the strip averaged over one
//! element, a second difference of the kernel's second antiderivative (`expint::g1` for the
//! creep part).

use super::expint::{g, g1};
use crate::rheology::Spectrum;

fn xlogx(t: f64) -> f64 {
    if t == 0.0 {
        0.0
    } else {
        t * t.abs().ln()
    }
}

/// The relaxed elastic displacement of a unit strip (without 2 lambda/pi).
pub fn elastic_strip(x: f64, a: f64) -> f64 {
    -(xlogx(x + a) - xlogx(x - a) - 2.0 * a)
}

/// The moving viscoelastic strip of half-width `a` at offset `x` from its centre, speed
/// `v` = V tau/beta >= 0, modulus ratio `k` in (0, 1]. At x = +-a (the strip's own edges)
/// the displacement is finite and continuous.
pub fn strip(x: f64, a: f64, v: f64, k: f64) -> f64 {
    let el = elastic_strip(x, a);
    if v == 0.0 || k == 1.0 {
        return el;
    }
    el + (1.0 - k) * v * (g((x + a) / v) - g((x - a) / v))
}

/// The delayed (creep) part of one retardation time at speed `v`, per unit of 1 - k.
fn delayed(x: f64, a: f64, v: f64) -> f64 {
    if v == 0.0 {
        return 0.0;
    }
    v * (g((x + a) / v) - g((x - a) / v))
}

/// The moving strip on a material with retardation spectrum `spectrum` (times in units of
/// the reference time of V = v tau/beta).
pub fn strip_spectrum(x: f64, a: f64, v: f64, k: f64, spectrum: &Spectrum) -> f64 {
    if spectrum.is_sls() {
        return strip(x, a, v, k); // the same value, to the last bit
    }
    let creep: f64 = spectrum.terms().iter().map(|&(w, t)| w * delayed(x, a, v * t)).sum();
    elastic_strip(x, a) + (1.0 - k) * creep
}

/// How the pressure varies over the mesh: `Linear` between nodes (a hat per node, the
/// default: second order at every speed), or `Uniform` on each element (the thesis' strips,
/// Eq. 4.12: first order where the elements are longer than the creep length; for
/// comparisons with it, docs/bem.md, "Discretisation").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Pressure {
    #[default]
    Linear,
    Uniform,
}

/// Influence coefficients on a uniform grid of n elements of width 2a: c[m + n - 1] is the
/// displacement at node i from unit nodal pressure at node j, m = i - j (`MeshKernel`). The
/// matrix G_ij = c[i - j + n - 1] is Toeplitz.
pub fn toeplitz_coefficients(n: usize, a: f64, v: f64, k: f64, spectrum: &Spectrum) -> Vec<f64> {
    MeshKernel::new(n, a, v, k, spectrum, Pressure::Linear).nodes
}

/// The strip's displacement as a difference, strip(x) = Q(x + a) - Q(x - a) + 2a, with
///   Q(s) = -s ln|s| + (1 - k) Sum_j w_j V_j g(s / V_j)
/// (`strip_spectrum`; one term w = 1 at V for the SLS).
fn q(s: f64, v: f64, k: f64, spectrum: &Spectrum) -> f64 {
    -xlogx(s) + creep(v, k, spectrum, |w, t| w * v * t * g(s / (v * t)))
}

/// (1 - k) Sum_j term(w_j, t_j) over the retardation times (a term at V t_j = 0 is zero),
/// 0 without creep (V = 0 or k = 1): the creep parts of `q` and `f2`.
fn creep(v: f64, k: f64, spectrum: &Spectrum, term: impl Fn(f64, f64) -> f64) -> f64 {
    if v == 0.0 || k == 1.0 {
        return 0.0;
    }
    let sum: f64 = spectrum.terms().iter().map(|&(w, t)| if v * t == 0.0 { 0.0 } else { term(w, t) }).sum();
    (1.0 - k) * sum
}

/// The second antiderivative of the point-load kernel, F2'' = K, with (per unit load,
/// without 2 lambda/pi, up to terms linear in s, which no coefficient sees)
///   K(s) = -ln|s| + (1 - k) Sum_j w_j exp(-s/V_j) Ei(s/V_j)
/// (the strip is strip(x) = F1(x + a) - F1(x - a), F1' = K):
///   F2(s) = -(s^2/2) ln|s| + (3/4) s^2 + (1 - k) Sum_j w_j V_j^2 G1(s/V_j)
/// (`expint::g1`).
fn f2(s: f64, v: f64, k: f64, spectrum: &Spectrum) -> f64 {
    let elastic = if s == 0.0 { 0.0 } else { -0.5 * s * s * s.abs().ln() + 0.75 * s * s };
    elastic
        + creep(v, k, spectrum, |w, t| {
            let vt = v * t;
            w * vt * vt * g1(s / vt)
        })
}

/// The displacement at offset `x` from a hat of pressure: 1 at its node, falling linearly
/// to 0 at the neighbouring nodes +-2a (`strip_spectrum` averaged over [x - a, x + a]):
///   hat(x) = [F2(x + 2a) - 2 F2(x) + F2(x - 2a)] / (2a).
pub fn hat_spectrum(x: f64, a: f64, v: f64, k: f64, spectrum: &Spectrum) -> f64 {
    let h = 2.0 * a;
    (f2(x + h, v, k, spectrum) - 2.0 * f2(x, v, k, spectrum) + f2(x - h, v, k, spectrum)) / h
}

/// Every influence coefficient of a uniform mesh of n elements of half-width a: the
/// node-to-node Toeplitz coefficients (`toeplitz_coefficients`) and the node-to-edge ones
/// (edge e = X_0 - a + 2a e from node m: `edges[e - m + n - 1]`), the nodes being the
/// element centres. With `Pressure::Linear` the pressure is the piecewise-linear
/// interpolant of its nodal values, a hat per node (`hat_spectrum`), and the coefficients
/// are second differences of `f2` at the multiples of a (4n + 3 evaluations of the
/// exponential integrals per retardation time); with `Pressure::Uniform` a strip per
/// element (`strip_spectrum`), first differences of `q` (4n + 1). Each is evaluated once,
/// not twice per coefficient, and the kernel is built once per lambda continuation
/// (`solver::Operator::scaled`): the exponential integrals had been most of the time of a
/// power-law point (docs/tuning.md).
///
/// Why hats by default: the creep part of K is log-singular on the scale V = v tau/beta;
/// where the elements are longer than V, the strips' pressure steps between elements give
/// the creep displacement, and with it the friction, an error of first order in the element
/// size (mu* 6.6 % off on 400 elements at V0 = 1e-3, lambda = 1, W = 1, k = 0.1). With
/// hats the error is of second order at every speed (docs/bem.md, "Discretisation").
pub struct MeshKernel {
    pub nodes: Vec<f64>,
    pub edges: Vec<f64>,
}

impl MeshKernel {
    pub fn new(n: usize, a: f64, v: f64, k: f64, spectrum: &Spectrum, pressure: Pressure) -> MeshKernel {
        match pressure {
            Pressure::Linear => MeshKernel::hats(n, a, v, k, spectrum),
            Pressure::Uniform => MeshKernel::strips(n, a, v, k, spectrum),
        }
    }

    fn hats(n: usize, a: f64, v: f64, k: f64, spectrum: &Spectrum) -> MeshKernel {
        // F2 at t a, t = -(2n + 1) ..= 2n + 1.
        let top = 2 * n as i64 + 1;
        let values: Vec<f64> = (-top..=top).map(|t| f2(a * t as f64, v, k, spectrum)).collect();
        let at = |t: i64| values[(t + top) as usize];
        let hat = |t: i64| (at(t + 2) - 2.0 * at(t) + at(t - 2)) / (2.0 * a);
        let first = n as i64 - 1;
        // Node i from node j at 2a (i - j); edge e from node m at a (2 (e - m) - 1).
        let nodes = (0..2 * n as i64 - 1).map(|d| hat(2 * (d - first))).collect();
        let edges = (0..2 * n as i64).map(|d| hat(2 * (d - first) - 1)).collect();
        MeshKernel { nodes, edges }
    }

    fn strips(n: usize, a: f64, v: f64, k: f64, spectrum: &Spectrum) -> MeshKernel {
        let nf = n as f64;
        // At a (2i - 2n + 1), i = 0 .. 2n - 1, and at 2a (p - n), p = 0 ..= 2n.
        let odd: Vec<f64> = (0..2 * n).map(|i| q(a * (2.0 * (i as f64 - nf) + 1.0), v, k, spectrum)).collect();
        let even: Vec<f64> = (0..=2 * n).map(|p| q(2.0 * a * (p as f64 - nf), v, k, spectrum)).collect();
        let diff = |t: &[f64]| t.windows(2).map(|w| w[1] - w[0] + 2.0 * a).collect::<Vec<f64>>();
        MeshKernel { nodes: diff(&odd), edges: diff(&even) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bem::expint::exp_ei;
    use crate::numerics::quad::integrate_panels;

    /// The hereditary integral evaluated by quadrature (independent of the closed form).
    fn by_quadrature(x: f64, a: f64, v: f64, k: f64) -> f64 {
        // dU_el/dX at xi = -ln|(xi + a)/(xi - a)|; the integrand in eta = V s has log
        // singularities at eta = x + a and x - a.
        let f = |eta: f64| -(-((x - eta + a).abs().ln() - (x - eta - a).abs().ln())) * (-eta / v).exp();
        let mut breaks = vec![0.0];
        for s in [x - a, x + a] {
            if s > 0.0 {
                breaks.push(s);
            }
        }
        let mut top = breaks[breaks.len() - 1].max(1e-3 * v);
        while top < 80.0 * v {
            top *= 1.5;
            breaks.push(top);
        }
        let (integral, _) = integrate_panels(&f, &breaks, 1e-12);
        elastic_strip(x, a) + (1.0 - k) * integral
    }

    #[test]
    fn closed_form_matches_the_hereditary_integral() {
        let a = 0.05;
        for (v, k) in [(0.3, 0.1), (2.0, 0.01), (0.02, 0.5)] {
            let xs = [-0.7, -0.12, -0.01, 0.03, 0.08, 0.4, 1.5];
            // The closed form drops a constant: compare differences from x = xs[0].
            let c0 = strip(xs[0], a, v, k) - by_quadrature(xs[0], a, v, k);
            for x in xs {
                let d = strip(x, a, v, k) - by_quadrature(x, a, v, k) - c0;
                assert!(d.abs() < 1e-7, "v={v} k={k} x={x}: {d}");
            }
        }
    }

    #[test]
    fn printed_eq_4_10_with_corrected_sign_is_the_mirror_image() {
        // Eq. 4.10 with +2 lambda P/pi (ERRATA 2), D = 0, describes sliding towards +X:
        // compare it at -X with this kernel at X, up to a constant.
        let printed = |x: f64, a: f64, v: f64, k: f64| {
            let l = |t: f64| (t / a).powi(2).ln();
            -(k / 2.0) * ((x + a) * l(x + a) - (x - a) * l(x - a))
                + ((1.0 - k) / 2.0) * (2.0 * v * exp_ei(-(x + a) / v) - (x + v + a) * l(x + a))
                - ((1.0 - k) / 2.0) * (2.0 * v * exp_ei(-(x - a) / v) - (x + v - a) * l(x - a))
        };
        let (a, v, k) = (0.1, 0.7, 0.1);
        let c = strip(0.35, a, v, k) - printed(-0.35, a, v, k);
        for x in [-2.0, -0.5, -0.15, 0.0, 0.05, 0.3, 1.0, 3.0] {
            let d = strip(x, a, v, k) - printed(-x, a, v, k) - c;
            assert!(d.abs() < 1e-9, "x={x}: {d}");
        }
    }

    #[test]
    fn elastic_limits() {
        let a = 0.05;
        let xs = [-1.0, -0.2, 0.0, 0.3, 2.0];
        for k in [0.1, 0.001] {
            // V -> 0: relaxed half-plane.
            for &x in &xs {
                assert!((strip(x, a, 1e-9, k) - elastic_strip(x, a)).abs() < 1e-7, "x={x}");
            }
            // V -> inf: k times the relaxed displacement, up to a constant.
            let vel = 1e9;
            for &x in &xs {
                let d =
                    (strip(x, a, vel, k) - strip(0.0, a, vel, k)) - k * (elastic_strip(x, a) - elastic_strip(0.0, a));
                assert!(d.abs() < 1e-6, "k={k} x={x}: {d}");
            }
        }
    }

    #[test]
    fn a_compressive_strip_pushes_the_surface_in_and_trails_downstream() {
        // ERRATA 2: U(0) - U(+-5A) > 0 for a compressive strip. It holds on both sides in
        // the elastic limits (V << A, V >> 5A) and upstream at every speed; downstream it
        // fails when V ~ 5A, because the material keeps creeping after it has passed the
        // strip (U(0) - U(5A) = -0.019 at V = 1, A = 0.1, k = 0.1): physics, not a sign error.
        let (a, k) = (0.1, 0.1);
        for v in [0.0, 1e-3, 1e3, 1e6] {
            assert!(strip(0.0, a, v, k) - strip(5.0 * a, a, v, k) > 0.04, "v={v}");
            assert!(strip(0.0, a, v, k) - strip(-5.0 * a, a, v, k) > 0.04, "v={v}");
        }
        for v in [0.01, 0.1, 1.0, 10.0] {
            assert!(strip(0.0, a, v, k) > strip(-5.0 * a, a, v, k), "v={v}");
            // Delayed recovery: more displacement downstream than upstream.
            assert!(strip(5.0 * a, a, v, k) > strip(-5.0 * a, a, v, k), "v={v}");
        }
        assert!(strip(0.0, a, 1.0, k) - strip(5.0 * a, a, 1.0, k) < 0.0);
    }

    #[test]
    fn a_one_term_prony_series_is_the_sls_kernel() {
        // A Maxwell-Wiechert series with one relaxation time rho creeps with time rho/k: the
        // SLS kernel at speed V rho/k, to rounding, at every speed (rho/k = 0.37 here, so the
        // general spectral sum is exercised, not the SLS shortcut).
        for k in [1e-3, 0.1, 0.7] {
            let one = Spectrum::from_relaxation(k, &[(1.0, 0.37 * k)]).unwrap();
            assert!(!one.is_sls());
            for v in [1e-6, 0.03, 1.0, 40.0, 1e6] {
                for x in [-3.0, -0.1, 0.0, 0.05, 0.1, 2.0] {
                    let (a, b) = (strip_spectrum(x, 0.05, v, k, &one), strip(x, 0.05, 0.37 * v, k));
                    assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "k={k} v={v} x={x}: {a} {b}");
                }
            }
        }
    }

    /// The power-law kernel with the continuous spectrum of Eq. 5.24, by quadrature in ln t.
    fn power_law_by_quadrature(x: f64, a: f64, v: f64, k: f64, s: f64, t1: f64) -> f64 {
        let norm = (1.0 - t1.powf(1.0 - s)) / (1.0 - s);
        let f = |u: f64| {
            let t = u.exp();
            t.powf(1.0 - s) / norm * delayed(x, a, v * t)
        };
        let breaks: Vec<f64> = (0..=48).map(|i| t1.ln() * (1.0 - i as f64 / 48.0)).collect();
        elastic_strip(x, a) + (1.0 - k) * integrate_panels(&f, &breaks, 1e-11).0
    }

    #[test]
    fn the_power_law_kernel_converges_with_the_discretisation() {
        // Error of the discretised spectrum (m bins per decade) against the continuous one,
        // over offsets and speeds spanning the spectrum; second order: /4 per doubling of m.
        let (a, k, t1) = (0.02, 1e-3, 1e-6);
        for s in [0.0, 0.5, 0.75] {
            let err = |m: usize| {
                let spec = Spectrum::power_law(s, t1, m).unwrap();
                let mut worst: f64 = 0.0;
                for v in [1e-3, 0.1, 10.0, 1e3, 1e5] {
                    // Differences from x = 0 (the kernel's constant is absorbed by the approach).
                    let r0 = power_law_by_quadrature(0.0, a, v, k, s, t1);
                    let d0 = strip_spectrum(0.0, a, v, k, &spec);
                    for x in [-1.0, -0.1, 0.04, 0.3, 2.0] {
                        let r = power_law_by_quadrature(x, a, v, k, s, t1) - r0;
                        let d = strip_spectrum(x, a, v, k, &spec) - d0;
                        worst = worst.max((d - r).abs() / elastic_strip(0.0, a));
                    }
                }
                worst
            };
            let (e2, e4, e8) = (err(2), err(4), err(8));
            // The errors this code gives: s = 0: 4.7e-3, 1.1e-3, 2.8e-4; s = 0.75: 3.0e-3, 7.1e-4, 1.8e-4.
            assert!(e4 < 1.5e-3 && e8 < 4e-4, "s={s}: {e2:.2e} {e4:.2e} {e8:.2e}");
            assert!(e2 / e4 > 3.5 && e4 / e8 > 3.5, "s={s}: not second order: {e2:.2e} {e4:.2e} {e8:.2e}");
        }
    }

    #[test]
    fn coefficients_are_finite_over_twelve_decades_of_speed() {
        for v in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
            for k in [1e-4, 0.1, 0.99] {
                let c = toeplitz_coefficients(101, 0.02, v, k, &Spectrum::power_law(0.5, 1e-6, 4).unwrap());
                assert!(c.iter().all(|x| x.is_finite()), "v={v} k={k}");
            }
        }
    }

    /// A hat by quadrature: the strip averaged over [x - a, x + a] (a hat is a strip
    /// convolved with a strip), independent of `f2` and `expint::g1`.
    fn hat_by_quadrature(x: f64, a: f64, v: f64, k: f64, spectrum: &Spectrum) -> f64 {
        let f = |t: f64| strip_spectrum(x - t, a, v, k, spectrum);
        let mut breaks = vec![-a, a];
        // strip(x - t) has logarithmic kinks at x - t = +-a.
        breaks.extend([x - a, x + a].into_iter().filter(|t| t.abs() < a));
        breaks.sort_by(f64::total_cmp);
        integrate_panels(&f, &breaks, 1e-12).0 / (2.0 * a)
    }

    #[test]
    fn the_mesh_kernel_is_the_hat_or_the_strip_at_every_offset() {
        // Second differences of F2 (hats) and differences of Q (strips) at shared points give
        // every coefficient, nodes and edges, SLS and a spectrum, elastic and moving (slow,
        // where the creep kernel varies within an element, and fast): the hat against its
        // quadrature and `hat_spectrum`, the strip against `strip_spectrum`.
        let (n, a) = (37, 0.03);
        for spectrum in [Spectrum::sls(), Spectrum::power_law(0.5, 1e-4, 2).unwrap()] {
            for (v, k) in [(0.0, 0.1), (1e-3, 0.1), (0.7, 0.01), (30.0, 0.5), (2.0, 1.0)] {
                let scale = elastic_strip(0.0, a);
                for pressure in [Pressure::Linear, Pressure::Uniform] {
                    let kern = MeshKernel::new(n, a, v, k, &spectrum, pressure);
                    assert_eq!((kern.nodes.len(), kern.edges.len()), (2 * n - 1, 2 * n));
                    for (coefficients, shift) in [(&kern.nodes, 0.0), (&kern.edges, a)] {
                        for (idx, c) in coefficients.iter().enumerate() {
                            let x = 2.0 * a * (idx as f64 - (n as f64 - 1.0)) - shift;
                            let (reference, tol) = match pressure {
                                Pressure::Linear => {
                                    let direct = hat_spectrum(x, a, v, k, &spectrum);
                                    assert!((c - direct).abs() < 1e-12 * scale, "{idx} v={v} k={k}");
                                    (hat_by_quadrature(x, a, v, k, &spectrum), 1e-10)
                                }
                                Pressure::Uniform => (strip_spectrum(x, a, v, k, &spectrum), 1e-13),
                            };
                            let d = (c - reference).abs();
                            assert!(d < tol * scale, "{pressure:?} {idx} at {x} v={v} k={k}: {d:e}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn far_from_the_node_a_hat_is_the_strip_to_second_order() {
        // A hat and a strip carry the same load; at distance x they differ by
        // (a^2/3) strip''(x) ~ a^2/(3 x^2) strip-scale: the hats change the near field only.
        let a = 0.01;
        for (v, k) in [(0.0, 0.1), (1e-3, 0.1), (1.0, 0.1)] {
            for x in [0.5, 1.0, 3.0] {
                let (hat, strip) = (hat_spectrum(x, a, v, k, &Spectrum::sls()), strip(x, a, v, k));
                let bound = 2.0 * a * a * a / (x * x);
                assert!((hat - strip).abs() < bound, "v={v} x={x}: {hat} {strip}");
            }
        }
    }
}
