//! YAML nodes as the parser reads them: where a node is (file, line, column), its value as
//! JSON, and the context that collects a file's errors and warnings.

use crate::kind::ShownRange;
use crate::spec::{Diagnostic, Location, Warning};
use marked_yaml::types::{MarkedMappingNode, Node};
use serde_json::{Number, Value};
use std::collections::{BTreeMap, BTreeSet};

/// A range shown by a stage (`by`), declared at `location`.
#[derive(Clone, Debug)]
pub(super) struct Shown {
    pub by: String,
    pub range: ShownRange,
    pub location: Location,
}

pub(super) struct Ctx<'a> {
    pub file: &'a str,
    /// The parameters the command line sets (`-S`): their errors are located there.
    pub overrides: &'a [crate::spec::Override],
    pub errors: Vec<Diagnostic>,
    pub warnings: Vec<Warning>,
    /// The ranges shown of (stage, column), from every stage that declares one.
    pub shown: BTreeMap<(String, String), Vec<Shown>>,
    /// The stages whose ranges the stage being parsed samples.
    pub ranges_used: BTreeSet<String>,
}

impl Ctx<'_> {
    /// Where a node starts; for a block mapping, where its first key starts (marked_yaml
    /// marks block mappings at their first colon).
    pub(super) fn loc(&self, node: &Node) -> Location {
        if let Node::Mapping(m) = node {
            return mapping_location(self.file, m);
        }
        span_location(self.file, node.span())
    }
    pub(super) fn err(&mut self, location: Location, message: impl Into<String>) {
        self.errors.push(Diagnostic { location, message: message.into() });
    }
}

pub(super) fn span_location(file: &str, span: &marked_yaml::Span) -> Location {
    let (line, column) = span.start().map_or((0, 0), |m| (m.line(), m.column()));
    Location { file: file.to_string(), line, column }
}

pub(super) fn mapping_location(file: &str, m: &MarkedMappingNode) -> Location {
    match m.keys().next() {
        Some(k) if !is_flow_mapping(m) => span_location(file, k.span()),
        _ => span_location(file, m.span()),
    }
}

/// A flow mapping (`{a: 1}`) starts at its brace, which is what its span marks.
pub(super) fn is_flow_mapping(m: &MarkedMappingNode) -> bool {
    match (m.span().start(), m.keys().next().and_then(|k| k.span().start())) {
        (Some(ms), Some(ks)) => ms.line() < ks.line() || (ms.line() == ks.line() && ms.column() < ks.column()),
        _ => true,
    }
}

pub(super) fn marker_location(file: &str, m: &marked_yaml::Marker) -> Location {
    Location { file: file.to_string(), line: m.line(), column: m.column() }
}

/// Converts a YAML node to JSON: unquoted scalars become null, booleans or numbers where
/// they read as such; quoted scalars stay strings.
pub fn to_json(node: &Node) -> Value {
    match node {
        Node::Scalar(s) => {
            let text = s.as_str();
            if !s.may_coerce() {
                return Value::String(text.to_string());
            }
            match text {
                "" | "~" | "null" | "Null" | "NULL" => Value::Null,
                "true" | "True" | "TRUE" => Value::Bool(true),
                "false" | "False" | "FALSE" => Value::Bool(false),
                _ => {
                    if let Ok(i) = text.parse::<i64>() {
                        Value::Number(i.into())
                    } else if let Some(n) = text.parse::<f64>().ok().and_then(Number::from_f64) {
                        // from_f64 refuses NaN and infinities, which stay strings (and fail type checks).
                        Value::Number(n)
                    } else {
                        Value::String(text.to_string())
                    }
                }
            }
        }
        Node::Sequence(seq) => Value::Array(seq.iter().map(to_json).collect()),
        Node::Mapping(map) => Value::Object(map.iter().map(|(k, v)| (k.as_str().to_string(), to_json(v))).collect()),
    }
}

/// An error at each key of `map` that is not in `allowed`.
pub(super) fn check_keys(cx: &mut Ctx, map: &MarkedMappingNode, allowed: &[&str], what: &str) {
    for key in map.keys() {
        if !allowed.contains(&key.as_str()) {
            cx.err(
                span_location(cx.file, key.span()),
                format!("unknown field `{}` in {what} (expected one of: {})", key.as_str(), allowed.join(", ")),
            );
        }
    }
}
