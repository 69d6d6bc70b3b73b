//! Verification of published artifacts against a reference copy (`repro verify`): every
//! figure (SVG) and table (Parquet) that a run produced must equal the one of the same name
//! in the reference folder (the committed `figures/`). SVGs are compared byte for byte, or,
//! with a tolerance, token by token with their numbers within it; tables column by column
//! and value by value, the columns of timing (`*_time_s`) aside. A file of the reference
//! that the run did not produce is not checked (another pipeline publishes it); a produced
//! file missing from the reference is a difference (an artifact that was never committed).

use anyhow::{Context, Result};
use polars::prelude::{AnyValue, DataFrame};
use std::fmt;
use std::path::{Path, PathBuf};

/// What differs in one artifact.
#[derive(Clone, Debug, PartialEq)]
pub enum Difference {
    /// Produced, but there is no reference copy.
    NotInReference,
    /// The SVGs differ; the first differing line (1-based) of each.
    Svg { line: usize, produced: String, reference: String },
    /// The tables have different column sets (timing columns aside).
    Columns { produced: Vec<String>, reference: Vec<String> },
    /// The tables have different row counts.
    Rows { produced: usize, reference: usize },
    /// The first differing value of a column.
    Value { column: String, row: usize, produced: String, reference: String },
    /// The file could not be read.
    Unreadable(String),
}

impl fmt::Display for Difference {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            Difference::NotInReference => write!(f, "not in the reference (never committed)"),
            Difference::Svg { line, produced, reference } => {
                write!(f, "line {line} differs:\n    produced:  {produced}\n    reference: {reference}")
            }
            Difference::Columns { produced, reference } => {
                write!(f, "columns differ: produced {produced:?}, reference {reference:?}")
            }
            Difference::Rows { produced, reference } => write!(f, "{produced} rows, the reference has {reference}"),
            Difference::Value { column, row, produced, reference } => {
                write!(f, "column `{column}`, row {row}: produced {produced}, reference {reference}")
            }
            Difference::Unreadable(e) => write!(f, "unreadable: {e}"),
        }
    }
}

/// The verdict on one folder.
#[derive(Debug, Default)]
pub struct Verdict {
    /// Files compared and found equal.
    pub equal: Vec<PathBuf>,
    /// Files that differ, with the first difference of each.
    pub differ: Vec<(PathBuf, Difference)>,
    /// Reference files the run did not produce (not checked).
    pub unchecked: Vec<PathBuf>,
}

impl Verdict {
    /// Nothing differs, and something was compared: an empty produced folder (or one holding
    /// only subfolders) proves nothing.
    pub fn passed(&self) -> bool {
        self.differ.is_empty() && !self.compared_nothing()
    }

    /// No figure or table was compared.
    pub fn compared_nothing(&self) -> bool {
        self.equal.is_empty() && self.differ.is_empty()
    }
}

/// Whether a table column holds timings (left out of the comparison).
fn is_timing(column: &str) -> bool {
    column.ends_with("_time_s")
}

fn artifacts(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("reading {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file() && matches!(p.extension().and_then(|e| e.to_str()), Some("svg" | "parquet")))
        .collect();
    out.sort();
    Ok(out)
}

/// Compares every artifact in `produced` with its namesake in `reference`; numbers within
/// `rel_tol` (relative, with an absolute floor of rel_tol * 1e-12) count as equal, exact
/// equality when 0.
pub fn verify(produced: &Path, reference: &Path, rel_tol: f64) -> Result<Verdict> {
    let mut v = Verdict::default();
    let made = artifacts(produced)?;
    for p in &made {
        let name = p.file_name().expect("a file name");
        let r = reference.join(name);
        let diff = if !r.is_file() {
            Some(Difference::NotInReference)
        } else if p.extension().is_some_and(|e| e == "svg") {
            compare_svg(p, &r, rel_tol)
        } else {
            compare_tables(p, &r, rel_tol)
        };
        match diff {
            Some(d) => v.differ.push((PathBuf::from(name), d)),
            None => v.equal.push(PathBuf::from(name)),
        }
    }
    for r in artifacts(reference)? {
        let name = r.file_name().expect("a file name");
        if !produced.join(name).is_file() {
            v.unchecked.push(PathBuf::from(name));
        }
    }
    Ok(v)
}

fn close(a: f64, b: f64, rel_tol: f64) -> bool {
    a.to_bits() == b.to_bits()
        || (a.is_nan() && b.is_nan())
        || (rel_tol > 0.0 && (a - b).abs() <= rel_tol * a.abs().max(b.abs()).max(1e-12))
}

/// Splits a line into numbers and the text between them.
fn tokens(line: &str) -> Vec<Result<f64, &str>> {
    let mut out = Vec::new();
    let bytes = line.as_bytes();
    let (mut i, mut text_start) = (0, 0);
    while i < bytes.len() {
        let starts_number = bytes[i].is_ascii_digit()
            || ((bytes[i] == b'-' || bytes[i] == b'.') && bytes.get(i + 1).is_some_and(|c| c.is_ascii_digit()));
        if starts_number {
            let mut j = i + 1;
            while j < bytes.len() && (bytes[j].is_ascii_digit() || matches!(bytes[j], b'.' | b'e' | b'E')) {
                j += 1;
            }
            if let Ok(x) = line[i..j].parse::<f64>() {
                if text_start < i {
                    out.push(Err(&line[text_start..i]));
                }
                out.push(Ok(x));
                text_start = j;
                i = j;
                continue;
            }
        }
        i += 1;
    }
    if text_start < line.len() {
        out.push(Err(&line[text_start..]));
    }
    out
}

fn lines_match(a: &str, b: &str, rel_tol: f64) -> bool {
    if a == b {
        return true;
    }
    if rel_tol == 0.0 {
        return false;
    }
    let (ta, tb) = (tokens(a), tokens(b));
    ta.len() == tb.len()
        && ta.iter().zip(&tb).all(|(x, y)| match (x, y) {
            (Ok(x), Ok(y)) => close(*x, *y, rel_tol),
            (Err(x), Err(y)) => x == y,
            _ => false,
        })
}

fn clip(s: &str) -> String {
    if s.chars().count() > 160 {
        format!("{}...", s.chars().take(160).collect::<String>())
    } else {
        s.to_string()
    }
}

fn compare_svg(produced: &Path, reference: &Path, rel_tol: f64) -> Option<Difference> {
    let read = |p: &Path| {
        crate::cache::read_regular(p)
            .map(|b| String::from_utf8_lossy(&b).into_owned())
            .map_err(|e| Difference::Unreadable(format!("{}: {e}", p.display())))
    };
    let (a, b) = match (read(produced), read(reference)) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => return Some(e),
    };
    if a == b {
        return None;
    }
    let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    for i in 0..la.len().max(lb.len()) {
        let (x, y) = (la.get(i).copied().unwrap_or(""), lb.get(i).copied().unwrap_or(""));
        if !lines_match(x, y, rel_tol) || (i >= la.len()) != (i >= lb.len()) {
            return Some(Difference::Svg { line: i + 1, produced: clip(x), reference: clip(y) });
        }
    }
    None
}

fn compare_tables(produced: &Path, reference: &Path, rel_tol: f64) -> Option<Difference> {
    let read = |p: &Path| super::table::read_parquet(p).map_err(|e| Difference::Unreadable(format!("{e:#}")));
    let (a, b) = match (read(produced), read(reference)) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => return Some(e),
    };
    compare_frames(&a, &b, rel_tol)
}

/// The first difference of two tables (timing columns aside), or None.
pub fn compare_frames(a: &DataFrame, b: &DataFrame, rel_tol: f64) -> Option<Difference> {
    let names = |d: &DataFrame| -> Vec<String> {
        d.get_column_names().iter().map(|c| c.to_string()).filter(|c| !is_timing(c)).collect()
    };
    let (na, nb) = (names(a), names(b));
    if na != nb {
        return Some(Difference::Columns { produced: na, reference: nb });
    }
    if a.height() != b.height() {
        return Some(Difference::Rows { produced: a.height(), reference: b.height() });
    }
    for name in &na {
        let (ca, cb) = (a.column(name).ok()?, b.column(name).ok()?);
        for row in 0..a.height() {
            let (x, y) = (ca.get(row).ok()?, cb.get(row).ok()?);
            let same = match (&x, &y) {
                (AnyValue::Float64(x), AnyValue::Float64(y)) => close(*x, *y, rel_tol),
                _ => x == y,
            };
            if !same {
                let show = |v: &AnyValue| match v {
                    AnyValue::Float64(f) => format!("{f:?}"),
                    v => v.to_string(),
                };
                return Some(Difference::Value { column: name.clone(), row, produced: show(&x), reference: show(&y) });
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_lines_match_exactly_or_number_by_number_within_the_tolerance() {
        let a = r#"<path d="M 10.5 20 L 30.25 -4e-3"/>"#;
        let b = r#"<path d="M 10.5000001 20 L 30.25 -4e-3"/>"#;
        assert!(lines_match(a, a, 0.0));
        assert!(!lines_match(a, b, 0.0));
        assert!(lines_match(a, b, 1e-6));
        assert!(!lines_match(a, b, 1e-9));
        // Text must match to the letter whatever the tolerance.
        assert!(!lines_match(r#"<text>a 1</text>"#, r#"<text>b 1</text>"#, 0.1));
        assert_eq!(tokens("x=1.5e2,y"), vec![Err("x="), Ok(150.0), Err(",y")]);
    }

    #[test]
    fn close_is_bitwise_at_zero_tolerance() {
        assert!(close(0.1 + 0.2, 0.1 + 0.2, 0.0));
        assert!(!close(0.1 + 0.2, 0.3, 0.0));
        assert!(close(0.1 + 0.2, 0.3, 1e-15));
        assert!(close(f64::NAN, f64::NAN, 0.0));
    }
}
