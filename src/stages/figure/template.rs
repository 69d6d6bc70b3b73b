//! Parameter values in a figure's text: a `{column}` in its title or axis labels is the
//! value that column takes in the data the figure draws (the kept rows of its data layers),
//! so that a figure run with other parameters says so. Where the column takes several
//! values there, the text lists them all ("W = 0.1 and 1"): a title never claims one value
//! for data drawn at several (per curve, a layer's label says which).

use super::series::{kept_rows, listed};
use super::{FigureParams, Layer};
use anyhow::{bail, Result};
use pipeline::kind::{ColumnRead, Inputs};
use std::collections::BTreeSet;

/// The `{name}` placeholders of `text` (names of letters, digits and `_`), in order.
pub(super) fn placeholders(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(open) = rest.find('{') {
        let after = &rest[open + 1..];
        match after.find('}') {
            Some(close) => {
                let name = &after[..close];
                if !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
                    out.push(name.to_string());
                }
                rest = &after[close + 1..];
            }
            None => break,
        }
    }
    out
}

/// The figure's own text fields that may name columns: (parameter, text).
fn text_fields(p: &FigureParams) -> [(&'static str, &str); 3] {
    [("title", &p.title), ("x_label", &p.x_label), ("y_label", &p.y_label)]
}

/// The columns the figure's text names, to be found in the data it draws.
pub(super) fn text_reads(p: &FigureParams) -> Vec<ColumnRead> {
    text_fields(p)
        .into_iter()
        .flat_map(|(path, text)| {
            placeholders(text).into_iter().map(move |column| ColumnRead { path: path.into(), stage: None, column })
        })
        .collect()
}

/// `text` with each placeholder replaced by the values its column takes in the kept rows of
/// the figure's data layers: one value where they agree, all of them where they do not (a
/// figure drawing data at W = 0.1 and at W = 1 says so, not one of them) (`field` names the
/// text in errors).
fn fill(text: &str, field: &str, p: &FigureParams, inputs: &Inputs) -> Result<String> {
    let mut out = text.to_string();
    for name in placeholders(text) {
        let mut values: BTreeSet<String> = BTreeSet::new();
        for layer in &p.layers {
            let Layer::Data(d) = layer else { continue };
            let t = inputs.table(&d.from)?;
            let Some(column) = t.column(&name) else { continue };
            let keep = kept_rows(d, t)?;
            values.extend((0..t.n_rows()).filter(|&r| keep[r]).map(|r| column.display_at(r)));
        }
        if values.is_empty() {
            bail!("`{field}` names `{{{name}}}`, which no row the figure draws has");
        }
        out = out.replace(&format!("{{{name}}}"), &listed(&values));
    }
    Ok(out)
}

/// The figure's parameters with its title and axis labels filled in (`fill`).
/// Its exponents set as superscripts (`superscripts`).
pub(super) fn filled(p: &FigureParams, inputs: &Inputs) -> Result<FigureParams> {
    let [title, x_label, y_label] =
        text_fields(p).map(|(field, text)| fill(text, field, p, inputs).map(|t| superscripts(&t)));
    Ok(FigureParams { title: title?, x_label: x_label?, y_label: y_label?, ..p.clone() })
}

#[cfg(test)]
mod tests {
    use super::placeholders;

    #[test]
    fn placeholders_are_names_in_braces() {
        assert_eq!(placeholders("W = {W}, k = {k} ({x_1})"), vec!["W", "k", "x_1"]);
        // Not names: left alone.
        assert!(placeholders("a {b c} {} {").is_empty());
        assert_eq!(placeholders("{a}{b}"), vec!["a", "b"]);
    }
}

/// The exponents of `text` set as superscripts, as a paper prints them: `λ^1.28` -> `λ¹·²⁸`,
/// `W^3/2` -> `W³ᐟ²`, `(π/16)^(1/3)` -> `(π/16)⁽¹ᐟ³⁾`, `(v/v0)^n` -> `(v/v0)ⁿ`. An exponent is a
/// parenthesised group or a run of digits, `.`, `/`, signs and the letters n, s, i after a
/// `^`; one with a character that has no superscript form keeps its caret.
pub(super) fn superscripts(text: &str) -> String {
    fn sup(c: char) -> Option<char> {
        Some(match c {
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            '9' => '⁹',
            '+' => '⁺',
            '-' => '⁻',
            '/' => 'ᐟ',
            '.' => '·',
            '(' => '⁽',
            ')' => '⁾',
            'n' => 'ⁿ',
            's' => 'ˢ',
            'i' => 'ⁱ',
            _ => return None,
        })
    }
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        if chars[i] != '^' || i + 1 == chars.len() {
            out.push(chars[i]);
            i += 1;
            continue;
        }
        // The exponent: a balanced group, or a run of the characters above (but a sign or a
        // point only where a digit follows, so that "x^2." ends a sentence).
        let start = i + 1;
        let end = if chars[start] == '(' {
            let mut depth = 0;
            let mut j = start;
            loop {
                match chars.get(j) {
                    Some('(') => depth += 1,
                    Some(')') => {
                        depth -= 1;
                        if depth == 0 {
                            break j + 1;
                        }
                    }
                    Some(_) => {}
                    None => break start,
                }
                j += 1;
            }
        } else {
            let mut j = start;
            while j < chars.len() && sup(chars[j]).is_some() && chars[j] != '(' && chars[j] != ')' {
                let needs_digit = matches!(chars[j], '.' | '/' | '+' | '-');
                if needs_digit && !chars.get(j + 1).is_some_and(|c| c.is_ascii_digit()) {
                    break;
                }
                j += 1;
            }
            j
        };
        let exponent: Option<String> =
            if end > start { chars[start..end].iter().map(|&c| sup(c)).collect() } else { None };
        match exponent {
            Some(e) => {
                out.push_str(&e);
                i = end;
            }
            None => {
                out.push('^');
                i += 1;
            }
        }
    }
    out
}

#[cfg(test)]
mod superscript_tests {
    use super::superscripts;

    #[test]
    fn exponents_are_set_as_superscripts() {
        assert_eq!(superscripts("fit λ^1.2823 ± 0.0123"), "fit λ¹·²⁸²³ ± 0.0123");
        assert_eq!(superscripts("JKR limit √π / (2 W^3/2 k)"), "JKR limit √π / (2 W³ᐟ² k)");
        assert_eq!(superscripts("-3 (π/16)^1/3"), "-3 (π/16)¹ᐟ³");
        assert_eq!(superscripts("(K / (π w R²))^(1/3)"), "(K / (π w R²))⁽¹ᐟ³⁾");
        assert_eq!(superscripts("G/Δγ fit (v/v0)^-0.5, s = 0.5"), "G/Δγ fit (v/v0)⁻⁰·⁵, s = 0.5");
        assert_eq!(superscripts("(v/v0)^n"), "(v/v0)ⁿ");
        // Nothing to set: the caret stays.
        assert_eq!(superscripts("a^b and x^"), "a^b and x^");
        assert_eq!(superscripts("up to x^2."), "up to x².");
        assert_eq!(superscripts("no caret"), "no caret");
    }
}
