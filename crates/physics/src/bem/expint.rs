//! Exponential integrals in scaled, overflow- and cancellation-free forms.
//!
//! `exp_ei(x)` = exp(-x) Ei(x) for every real x != 0: for x < 0 it is -exp(|x|) E1(|x|).
//! Methods: the convergent series of Ei/E1 for small |x| (all terms positive for x > 0,
//! alternating but bounded by exp(|x|) <= e for |x| <= 1 for x < 0), the continued fraction
//! of exp(y) E1(y) for y = -x >= 1 (modified Lentz), and the asymptotic series
//! sum k!/x^(k+1) for x >= 40. Relative accuracy about 1e-15 throughout.

const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;

/// exp(y) E1(y) for y > 0.
pub fn exp_e1(y: f64) -> f64 {
    assert!(y > 0.0, "exp_e1 needs y > 0, got {y}");
    if y < 1.0 {
        e1_series(y)
    } else {
        e1_continued_fraction(y)
    }
}

fn e1_series(y: f64) -> f64 {
    {
        // E1(y) = -gamma - ln y - sum_{k>=1} (-y)^k / (k k!)
        let mut sum = 0.0;
        let mut term = 1.0;
        for k in 1..60 {
            term *= -y / k as f64;
            let t = term / k as f64;
            sum += t;
            if t.abs() < 1e-17 * sum.abs().max(1e-300) {
                break;
            }
        }
        (-EULER_GAMMA - y.ln() - sum) * y.exp()
    }
}

fn e1_continued_fraction(y: f64) -> f64 {
    {
        // Continued fraction (Numerical Recipes' expint for n = 1), modified Lentz.
        let tiny = 1e-300;
        let mut b = y + 1.0;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -((i * i) as f64);
            b += 2.0;
            d = 1.0 / (an * d + b);
            c = b + an / c;
            let del = c * d;
            h *= del;
            if (del - 1.0).abs() < 1e-16 {
                break;
            }
        }
        h
    }
}

/// exp(-x) Ei(x) for real x != 0.
pub fn exp_ei(x: f64) -> f64 {
    assert!(x != 0.0 && x.is_finite(), "exp_ei needs a finite x != 0, got {x}");
    if x < 0.0 {
        return -exp_e1(-x);
    }
    if x < 40.0 {
        ei_series(x)
    } else {
        ei_asymptotic(x)
    }
}

fn ei_series(x: f64) -> f64 {
    {
        // Ei(x) = gamma + ln x + sum_{k>=1} x^k / (k k!): positive terms, no cancellation.
        let mut sum = 0.0;
        let mut term = 1.0;
        for k in 1..200 {
            term *= x / k as f64;
            let t = term / k as f64;
            sum += t;
            if t < 1e-17 * sum {
                break;
            }
        }
        (EULER_GAMMA + x.ln() + sum) * (-x).exp()
    }
}

fn ei_asymptotic(x: f64) -> f64 {
    {
        // Asymptotic: exp(-x) Ei(x) ~ (1/x) sum_k k!/x^k, summed to its smallest term.
        let mut sum = 1.0;
        let mut term = 1.0;
        for k in 1..100 {
            let next = term * k as f64 / x;
            if next > term || next < 1e-17 {
                break;
            }
            term = next;
            sum += term;
        }
        sum / x
    }
}

/// g(y) = ln|y| + gamma - exp(-y) Ei(y): the moving-strip kernel's viscous part without its
/// constant. For small |y| it is y (ln|y| + gamma - 1) + O(y^2 ln|y|), computed from the
/// series so that nothing of order ln|y| cancels.
/// g(0) = 0, its limit (needed for the displacement at a strip's own edge).
pub fn g(y: f64) -> f64 {
    assert!(y.is_finite(), "g needs a finite y, got {y}");
    if y == 0.0 {
        return 0.0;
    }
    if y.abs() < 0.5 {
        // exp(-y) Ei(y) = exp(-y) (gamma + ln|y| + S(y)), S(y) = sum y^k/(k k!), so
        // g = (ln|y| + gamma)(1 - exp(-y)) - exp(-y) S(y).
        let mut s = 0.0;
        let mut term = 1.0;
        for k in 1..40 {
            term *= y / k as f64;
            let t = term / k as f64;
            s += t;
            if t.abs() < 1e-18 * s.abs() {
                break;
            }
        }
        (y.abs().ln() + EULER_GAMMA) * (-(-y).exp_m1()) - (-y).exp() * s
    } else {
        y.abs().ln() + EULER_GAMMA - exp_ei(y)
    }
}

/// G1(y) = y ln|y| - ln|y| + exp(-y) Ei(y) - gamma - (1 - gamma) y: an antiderivative of g
/// (G1' = g), with the constant and linear terms chosen so that G1 = O(y^2 ln|y|) at small
/// |y|; there it is computed from the series of Ei, without the terms of order y ln|y| and
/// ln|y| that cancel. The moving kernel's second antiderivative (`kernel::MeshKernel`).
pub fn g1(y: f64) -> f64 {
    assert!(y.is_finite(), "g1 needs a finite y, got {y}");
    if y == 0.0 {
        0.0
    } else if y.abs() < 0.5 {
        g1_series(y)
    } else {
        g1_closed(y)
    }
}

fn g1_closed(y: f64) -> f64 {
    y * y.abs().ln() - y.abs().ln() + exp_ei(y) - EULER_GAMMA - (1.0 - EULER_GAMMA) * y
}

/// With exp(-y) Ei(y) = exp(-y) (gamma + ln|y| + S(y)), S(y) = sum y^k/(k k!):
/// G1 = (y + expm1(-y)) (ln|y| + gamma) + expm1(-y) S + (S - y), each term O(y^2 ln|y|).
fn g1_series(y: f64) -> f64 {
    let (mut s, mut s_tail, mut e) = (0.0, 0.0, 0.0);
    let mut term = 1.0; // y^k / k!
    for k in 1..40 {
        term *= y / k as f64;
        s += term / k as f64;
        if k >= 2 {
            s_tail += term / k as f64;
            e += if k % 2 == 0 { term } else { -term }; // y + expm1(-y) = sum_{k>=2} (-y)^k/k!
            if term.abs() < 1e-18 * e.abs() {
                break;
            }
        }
    }
    e * (y.abs().ln() + EULER_GAMMA) + (-y).exp_m1() * s + s_tail
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    #[test]
    fn reference_values() {
        // E1 and Ei from Abramowitz & Stegun Table 5.1 / DLMF 6 (16-digit values).
        let e1_1 = 0.219_383_934_395_520_3;
        assert!(rel(exp_e1(1.0), e1_1 * 1f64.exp()) < 1e-14);
        let e1_half = 0.559_773_594_776_160_8;
        assert!(rel(exp_e1(0.5), e1_half * 0.5f64.exp()) < 1e-14);
        let e1_10 = 4.156_968_929_685_324e-6;
        assert!(rel(exp_e1(10.0), e1_10 * 10f64.exp()) < 1e-13);
        let ei_1 = 1.895_117_816_355_937;
        assert!(rel(exp_ei(1.0), ei_1 * (-1f64).exp()) < 1e-14);
        let ei_10 = 2_492.228_976_241_878;
        assert!(rel(exp_ei(10.0), ei_10 * (-10f64).exp()) < 1e-13);
        let ei_50 = 1.058_563_689_713_169e20;
        assert!(rel(exp_ei(50.0), ei_50 * (-50f64).exp()) < 1e-13);
    }

    #[test]
    fn g1_is_an_antiderivative_of_g_on_both_branches() {
        // Central differences of G1 against g (error h^2 g''/6, below 1e-8 of g here), on
        // both sides of the branch point |y| = 0.5; the two forms agree where they meet.
        for y in [-30.0f64, -3.0, -0.6, -0.4, -0.05, -1e-3, 1e-3, 0.05, 0.3, 0.49, 0.51, 0.9, 4.0, 60.0] {
            let h = 1e-4 * f64::min(y.abs(), 1.0);
            let d = (g1(y + h) - g1(y - h)) / (2.0 * h);
            assert!((d - g(y)).abs() < 1e-7 * g(y).abs(), "y = {y}: {d} vs {}", g(y));
        }
        for y in [-0.5, 0.5, -0.45, 0.45] {
            assert!((g1_series(y) - g1_closed(y)).abs() < 1e-15, "y = {y}");
        }
        // G1 = (y^2 / 2) (ln|y| + gamma - 3/2) + O(y^3 ln|y|) at small |y|.
        let y: f64 = 1e-6;
        let lead = 0.5 * y * y * (y.ln() + EULER_GAMMA - 1.5);
        assert!((g1(y) - lead).abs() < 1e-5 * lead.abs(), "{} vs {lead}", g1(y));
    }

    #[test]
    fn branches_agree_where_they_meet_and_far_arguments_are_finite() {
        // Both methods at the same arguments near where one hands over to the other.
        for y in [0.8, 1.0, 1.3] {
            assert!(rel(e1_series(y), e1_continued_fraction(y)) < 1e-14, "y = {y}");
        }
        for x in [40.0, 45.0] {
            assert!(rel(ei_series(x), ei_asymptotic(x)) < 1e-14, "x = {x}");
        }
        for x in [1e-300, 1e-12, 1e3, 1e12, 1e300] {
            for v in [exp_ei(x), exp_ei(-x), g(x), g(-x)] {
                assert!(v.is_finite(), "x = {x}");
            }
        }
        // Large arguments: exp(-x) Ei(x) ~ 1/x + 1/x^2, exp(y) E1(y) ~ 1/y - 1/y^2.
        assert!(rel(exp_ei(1e8), 1e-8 + 1e-16) < 1e-14);
        assert!(rel(exp_e1(1e8), 1e-8 - 1e-16) < 1e-14);
    }

    #[test]
    fn g_is_continuous_and_has_its_small_argument_form() {
        assert!(rel(g(0.5 - 1e-12), g(0.5 + 1e-12)) < 1e-10);
        assert!(rel(g(-0.5 + 1e-12), g(-0.5 - 1e-12)) < 1e-10);
        for y in [1e-10f64, -1e-10, 1e-6, -1e-6] {
            let lead = y * (y.abs().ln() + EULER_GAMMA - 1.0);
            assert!(rel(g(y), lead) < 1e-4, "y = {y}: {} vs {lead}", g(y));
        }
    }
}
