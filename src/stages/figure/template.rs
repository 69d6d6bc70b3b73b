//! Parameter values in a figure's text: a `{column}` in its title or axis labels is the
//! value that column takes in the data the figure draws (the kept rows of its data layers),
//! so that a figure run with other parameters says so. A column that takes several values
//! there belongs in a layer's label (`{column}` per curve), not in the title: an error.

use super::series::kept_rows;
use super::{FigureParams, Layer};
use crate::pipeline::kind::{ColumnRead, Inputs};
use anyhow::{bail, Result};
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

/// `text` with each placeholder replaced by the one value its column takes in the kept rows
/// of the figure's data layers (`field` names the text in errors).
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
        match values.len() {
            1 => out = out.replace(&format!("{{{name}}}"), values.first().unwrap()),
            0 => bail!("`{field}` names `{{{name}}}`, which no row the figure draws has"),
            n => bail!(
                "`{field}` names `{{{name}}}`, which takes {n} values in the data the figure draws ({}): name it in a layer's label instead",
                values.into_iter().take(5).collect::<Vec<_>>().join(", ")
            ),
        }
    }
    Ok(out)
}

/// The figure's parameters with its title and axis labels filled in (`fill`).
pub(super) fn filled(p: &FigureParams, inputs: &Inputs) -> Result<FigureParams> {
    let [title, x_label, y_label] = text_fields(p).map(|(field, text)| fill(text, field, p, inputs));
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
