//! A published figure states no parameter value by hand: every number in a
//! title, an axis label or a layer's label is a `{column}` of the data it draws (so that an
//! override changes it), a reference to the thesis (Fig. 3.6a, Eq. 5.20), part of a symbol
//! (σ0, τ2, W^3/2) or one of the formulas' constants declared below with why.

use repro::pipeline::parse;
use serde_json::Value;

/// Text that holds numbers that are not parameters of the data drawn: formulas' constants,
/// a publication year, the thesis' own value, names of surfaces. Each with the figure it is in.
const CONSTANTS: &[(&str, &str)] = &[
    // The law's exponents and coefficients (Eqs. 2.x), not parameters.
    ("fig2_3a", "3-9"),
    ("fig2_3a", "z⁻⁸/3 − 4 z⁻²/3"),
    ("fig2_3b", "(3√3/2)"),
    // Coefficients of the scaled quantities' definitions.
    ("fig2_5", "^(1/3)"),
    ("fig4_4", "(√π λ / 2W"),
    ("fig4_6a", "√π / (2 W"),
    ("fig5_9", "2π"),
    ("fig3_4c", "2A / (π R²)"),
    ("fig3_5c", "2A / (π R²)"),
    ("fig5_8", "2A at pull-off"),
    // The reciprocal of k (E∞ / E0), a symbol.
    ("fig7_3", "1/k"),
    ("fig7_4", "1/k"),
    // The publication and the thesis' value beside the computed one.
    ("fig7_4", "Persson (2010)"),
    ("fig_bem_vs_persson_large_load", "Persson (2010)"),
    ("fig4_6a", "(thesis at λ = 24: about 215)"),
    // The closed forms of the line contact's pull-off (Section 2.x, `theory.line_pulloff`).
    ("fig_line_pulloff_vs_lambda", "-2.434 √λ"),
    ("fig_line_pulloff_vs_lambda", "-3 (π/16)"),
    // The roughness each surface of Fig. 3.8 names (the thesis' experiments).
    ("fig3_8", "27 µm"),
    ("fig3_8", "15 µm"),
    ("fig3_8", "3 µm"),
    // The morphology's value where the surface touches.
    ("fig3_3b", "(1 where"),
];

/// `text` without its `{column}`s, its references to the thesis, its symbols' digits
/// (a letter's subscript, an exponent) and the figure's declared constants.
fn stripped(figure: &str, text: &str) -> String {
    let mut s = text.to_string();
    for (f, c) in CONSTANTS {
        if *f == figure {
            s = s.replace(c, "");
        }
    }
    // Placeholders.
    while let (Some(a), Some(b)) = (s.find('{'), s.find('}')) {
        if b < a {
            break;
        }
        s.replace_range(a..=b, "");
    }
    // References: "Fig. 3.6a", "Eqs. 5.10–5.13", "Eq. 4.16".
    for prefix in ["Figs. ", "Fig. ", "Eqs. ", "Eq. "] {
        while let Some(at) = s.find(prefix) {
            let rest = &s[at + prefix.len()..];
            let end = rest
                .char_indices()
                .find(|&(i, c)| {
                    let after_digit = i > 0 && rest[..i].ends_with(|p: char| p.is_ascii_digit());
                    !(c.is_ascii_digit() || c == '.' || c == '-' || c == '–' || (c.is_ascii_lowercase() && after_digit))
                })
                .map_or(rest.len(), |(i, _)| i);
            s.replace_range(at..at + prefix.len() + end, "");
        }
    }
    // A symbol's subscript (σ0, τ2, V0, p0_Hertz) and an exponent (W^3/2, (v/v0)^1/2).
    let mut out = String::new();
    let mut prev: Option<char> = None;
    let mut in_exponent = false;
    for c in s.chars() {
        let subscript = c.is_ascii_digit() && prev.is_some_and(|p| p.is_alphabetic() || p == '_');
        in_exponent = (in_exponent && (c.is_ascii_digit() || c == '/' || c == '.')) || c == '^';
        if !(subscript || in_exponent) {
            out.push(c);
        }
        if !subscript {
            prev = Some(c);
        }
    }
    out
}

/// The texts of a figure stage's parameters: title, axis labels, every layer's label.
fn texts(params: &Value) -> Vec<String> {
    let mut t: Vec<String> =
        ["title", "x_label", "y_label"].iter().filter_map(|k| params[*k].as_str().map(String::from)).collect();
    for layer in params["layers"].as_array().into_iter().flatten() {
        for (_, l) in layer.as_object().into_iter().flatten() {
            if let Some(label) = l["label"].as_str() {
                t.push(label.to_string());
            }
        }
    }
    t
}

/// The pipelines whose figures are published in figures/ (bench.yaml's titles describe its
/// solver configurations, which its tables do not carry).
const PUBLISHED: &[&str] = &["pipelines/thesis.yaml", "pipelines/snap_criteria.yaml", "pipelines/gamma_c_landing.yaml"];

#[test]
fn a_published_figure_states_no_parameter_value_by_hand() {
    let mut found = Vec::new();
    for file in PUBLISHED {
        let p = parse::load(std::path::Path::new(file), &repro::stages::registry()).unwrap();
        for s in p.stages.iter().filter(|s| s.kind == "figure") {
            for text in texts(&s.points[0].params) {
                let rest = stripped(&s.name, &text);
                if rest.chars().any(|c| c.is_ascii_digit()) {
                    found.push(format!("{file}: {}: \"{text}\" (left: \"{rest}\")", s.name));
                }
            }
        }
    }
    assert!(found.is_empty(), "numbers written by hand in figure texts:\n{}", found.join("\n"));
}

#[test]
fn the_check_catches_a_written_value_and_passes_its_template() {
    // What the test above would miss if its stripping were too eager.
    assert_eq!(stripped("f", "W = 0.1, k = {k}").trim(), "W = 0.1, k =");
    assert!(stripped("f", "δ_max/R = 0.35").contains("0.35"));
    assert!(stripped("f", "λ = 3, V0 = 2.73").contains('3'));
    assert!(stripped("f", "(V = 1e-6)").contains('1'));
    // What it lets through.
    assert!(
        !stripped("f", "Fig. 3.6a: F vs μ, Eqs. 5.10–5.13, σ0, τ1/τ2 = {tau_ratio}, W^3/2").contains(char::is_numeric)
    );
}
