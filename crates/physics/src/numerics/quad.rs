//! Adaptive Gauss–Kronrod (7/15) quadrature on finite panels.
#![allow(clippy::excessive_precision)] // the published nodes and weights, as published

const XGK: [f64; 8] = [
    0.991_455_371_120_812_639_206_854_697_526_329,
    0.949_107_912_342_758_524_526_189_684_047_851,
    0.864_864_423_359_769_072_789_712_788_640_926,
    0.741_531_185_599_394_439_863_864_773_280_788,
    0.586_087_235_467_691_130_294_144_845_693_013,
    0.405_845_151_377_397_166_906_606_412_076_961,
    0.207_784_955_007_898_467_600_689_403_773_245,
    0.0,
];
const WGK: [f64; 8] = [
    0.022_935_322_010_529_224_963_732_008_058_970,
    0.063_092_092_629_978_553_290_700_663_189_204,
    0.104_790_010_322_250_183_839_876_322_541_518,
    0.140_653_259_715_525_918_745_189_590_510_238,
    0.169_004_726_639_267_902_826_583_426_598_550,
    0.190_350_578_064_785_409_913_256_402_421_014,
    0.204_432_940_075_298_892_414_161_999_234_649,
    0.209_482_141_084_727_828_012_999_174_891_714,
];
const WG: [f64; 4] = [
    0.129_484_966_168_869_693_270_611_432_679_082,
    0.279_705_391_489_276_667_901_467_771_423_780,
    0.381_830_050_505_118_944_950_369_775_488_975,
    0.417_959_183_673_469_387_755_102_040_816_327,
];

/// One Gauss–Kronrod 7/15 rule on [a, b]: (Kronrod estimate, |Kronrod - Gauss|).
pub fn gk15<F: Fn(f64) -> f64>(f: &F, a: f64, b: f64) -> (f64, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut k = WGK[7] * fc;
    let mut g = WG[3] * fc;
    for i in 0..7 {
        let x = h * XGK[i];
        let s = f(c - x) + f(c + x);
        k += WGK[i] * s;
        if i % 2 == 1 {
            g += WG[i / 2] * s;
        }
    }
    (k * h, ((k - g) * h).abs())
}

/// Adaptive integration of f on [a, b] to an absolute tolerance: returns (value, error
/// estimate). Panels are bisected until their error estimate is below their share of
/// `abs_tol`, or `max_depth` is reached.
pub fn integrate<F: Fn(f64) -> f64>(f: &F, a: f64, b: f64, abs_tol: f64, max_depth: u32) -> (f64, f64) {
    let (v, e) = gk15(f, a, b);
    refine(f, a, b, v, e, abs_tol, max_depth)
}

fn refine<F: Fn(f64) -> f64>(f: &F, a: f64, b: f64, v: f64, e: f64, tol: f64, depth: u32) -> (f64, f64) {
    if e <= tol || depth == 0 {
        return (v, e);
    }
    super::budget::checkpoint();
    let m = 0.5 * (a + b);
    let (vl, el) = gk15(f, a, m);
    let (vr, er) = gk15(f, m, b);
    let (vl, el) = refine(f, a, m, vl, el, 0.5 * tol, depth - 1);
    let (vr, er) = refine(f, m, b, vr, er, 0.5 * tol, depth - 1);
    (vl + vr, el + er)
}

/// Integrates over consecutive panels [p0, p1], [p1, p2], ...: a first pass estimates the
/// total, a second refines every panel to `rel_tol` of it. Returns (value, error estimate).
pub fn integrate_panels<F: Fn(f64) -> f64>(f: &F, breaks: &[f64], rel_tol: f64) -> (f64, f64) {
    let crude: f64 = breaks.windows(2).map(|w| gk15(f, w[0], w[1]).0.abs()).sum();
    let n = (breaks.len() - 1).max(1) as f64;
    let tol = (rel_tol * crude / n).max(f64::MIN_POSITIVE);
    breaks.windows(2).map(|w| integrate(f, w[0], w[1], tol, 30)).fold((0.0, 0.0), |(v, e), (dv, de)| (v + dv, e + de))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_smooth_and_peaked_functions() {
        let (v, e) = integrate(&|x: f64| x.sin(), 0.0, std::f64::consts::PI, 1e-12, 30);
        assert!((v - 2.0).abs() < 1e-12 && e < 1e-10, "{v} {e}");
        // A narrow Lorentzian: integral over the real line is pi/eps.
        let eps = 1e-3;
        let (v, _) = integrate_panels(&|x: f64| 1.0 / (x * x + eps * eps), &[-1e3, -1.0, 0.0, 1.0, 1e3], 1e-10);
        let exact = 2.0 * (1e3f64 / eps).atan() / eps;
        assert!((v / exact - 1.0).abs() < 1e-8, "{v} {exact}");
    }
}
