//! Elastic limits of the Chapter 4 model. At very low speed the substrate is the relaxed
//! half-plane: the adhered half-width tends to the 2D JKR one as lambda grows (measured
//! deviation -5.6% at lambda = 1, -2.3% at lambda = 3, W = 1). At very high speed it is the
//! instantaneous half-plane, modulus E0/k: in its own units (beta' = k^(1/3) beta) that is
//! the relaxed problem with lambda' = lambda k^(2/3) and W' = W k^(1/3), an exact identity
//! checked here (and the reason the high-speed limit is far from JKR at moderate lambda:
//! lambda' = 0.65 for lambda = 3, k = 0.1).

use repro::bem::solver::{jkr_half_width, solve, Mesh, Params, Solution};

fn solved(lambda: f64, w: f64, k: f64, v0: f64, mesh: Mesh) -> Solution {
    let s = solve(&Params { lambda, w, k, v0 }, mesh);
    assert!(s.converged, "lambda {lambda} W {w} V0 {v0}: residual {}", s.residual);
    s
}

#[test]
fn low_speed_tends_to_the_relaxed_jkr_line_contact() {
    let mesh = Mesh { n: 1000, half_length: 6.0 };
    let jkr = jkr_half_width(1.0).unwrap();
    let dev = |lambda: f64| solved(lambda, 1.0, 0.1, 1e-6, mesh).adhered_half_width().unwrap() / jkr - 1.0;
    let (d1, d3) = (dev(1.0), dev(3.0));
    assert!(d3.abs() < 0.03 && d3.abs() < 0.6 * d1.abs(), "deviation from JKR: lambda 1 {d1:+.4}, lambda 3 {d3:+.4}");
}

#[test]
fn high_speed_is_the_instantaneous_half_plane() {
    let (lambda, w, k): (f64, f64, f64) = (3.0, 1.0, 0.1);
    let k3 = k.cbrt();
    let fast = solved(lambda, w, k, 1e6, Mesh { n: 1000, half_length: 6.0 });
    // The same physical mesh in the instantaneous units.
    let scaled = solved(lambda * k3 * k3, w * k3, k, 1e-6, Mesh { n: 1000, half_length: 6.0 / k3 });
    let (a_fast, a_scaled) = (fast.adhered_half_width().unwrap(), k3 * scaled.adhered_half_width().unwrap());
    // Measured: equal to 5 digits (1.00800), max |dP| 4e-5 of 0.95 (V0 = 1e6 is not infinity).
    assert!((a_fast / a_scaled - 1.0).abs() < 1e-4, "{a_fast} vs {a_scaled}");
    // Pressures agree point by point (P is in units of sigma0 in both).
    let dp = fast.p.iter().zip(&scaled.p).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    let pmax = fast.p.iter().copied().fold(0.0, f64::max);
    assert!(dp < 5e-4 * pmax, "max |dP| {dp} of {pmax}");
    // And at this speed the friction has vanished again.
    assert!(fast.friction().mu_star.abs() < 1e-3, "{:?}", fast.friction());
}
