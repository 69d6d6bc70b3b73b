//! What a stage kind takes and gives, as data: its parameters (type, default, valid range,
//! whether it may be swept, meaning) from the JSON Schema of its parameter type, and its
//! output columns with their units and meanings from `docs/outputs.md`. One source for
//! `repro kinds KIND` and the Python package's `describe` and type stubs.

use pipeline::kind::{range_text, DynKind, Registry};
use serde::Serialize;
use serde_json::Value;

/// A stage kind, described.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct KindDescription {
    pub name: String,
    pub version: u32,
    pub doc: String,
    /// The wall time after which a task is stopped, in seconds.
    pub time_limit_s: f64,
    pub params: Vec<ParamDescription>,
    pub columns: Vec<ColumnDescription>,
}

/// One parameter of a kind.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ParamDescription {
    pub name: String,
    /// The schema's type: `number`, `integer`, `boolean`, `string`, a named type (`Material`,
    /// `SnapCriterion`), or alternatives joined by " or ".
    pub r#type: String,
    /// Whether a point must give it (it has no default).
    pub required: bool,
    /// Its default, if it has one (null for an optional parameter without one).
    pub default: Option<Value>,
    /// The valid range of a number (`> 1`, `(0, 1e100]`), empty where there is none.
    pub range: String,
    /// Whether it may be given as a sweep (a list or an array of values).
    pub sweepable: bool,
    /// Its meaning, units and limits, as one line.
    pub meaning: String,
}

/// One output column of a kind.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ColumnDescription {
    pub name: String,
    /// Its unit or normalisation (`1` for a dimensionless number); empty when undocumented.
    pub unit: String,
    pub meaning: String,
}

/// The name a `$ref` points to.
fn ref_name(v: &Value) -> Option<&str> {
    v.get("$ref").and_then(Value::as_str).map(|r| r.rsplit('/').next().unwrap_or(r))
}

/// The type of a parameter's schema, as `repro kinds` shows it.
fn type_of(v: &Value) -> String {
    if let Some(name) = ref_name(v) {
        return name.to_string();
    }
    match v.get("type") {
        Some(Value::String(t)) => t.clone(),
        Some(Value::Array(ts)) => ts.iter().filter_map(Value::as_str).collect::<Vec<_>>().join(" or "),
        _ => match v.get("anyOf").or_else(|| v.get("oneOf")).and_then(Value::as_array) {
            Some(alts) => alts
                .iter()
                .map(|a| {
                    ref_name(a)
                        .map(str::to_string)
                        .or_else(|| a.get("type").and_then(Value::as_str).map(str::to_string))
                        .or_else(|| a.get("const").map(|c| c.to_string()))
                        .unwrap_or_else(|| "value".into())
                })
                .collect::<Vec<_>>()
                .join(" or "),
            None => v.get("enum").map_or("value".into(), |e| format!("one of {e}")),
        },
    }
}

/// Describes a kind from its declarations.
pub fn describe(k: &dyn DynKind, registry: &Registry) -> KindDescription {
    let schema = k.params_schema();
    let defs = schema.get("$defs").cloned().unwrap_or(Value::Null);
    let required: Vec<&str> = schema
        .get("required")
        .and_then(Value::as_array)
        .map_or(Vec::new(), |r| r.iter().filter_map(Value::as_str).collect());
    let params = schema
        .get("properties")
        .and_then(Value::as_object)
        .into_iter()
        .flatten()
        .map(|(name, v)| {
            let meaning = v
                .get("description")
                .or_else(|| ref_name(v).and_then(|n| defs.get(n)).and_then(|d| d.get("description")))
                .and_then(Value::as_str)
                .unwrap_or_default();
            ParamDescription {
                name: name.clone(),
                r#type: type_of(v),
                required: required.contains(&name.as_str()),
                default: v.get("default").cloned(),
                range: range_text(&schema, v),
                sweepable: k.sweepable().contains(&name.as_str()),
                meaning: meaning.split_whitespace().collect::<Vec<_>>().join(" "),
            }
        })
        .collect();
    let columns = k
        .columns()
        .iter()
        .map(|c| {
            let (unit, meaning) =
                registry.column(c).map_or(("", "(see docs/outputs.md)"), |d| (d.unit.as_str(), d.meaning.as_str()));
            ColumnDescription { name: c.to_string(), unit: unit.to_string(), meaning: meaning.to_string() }
        })
        .collect();
    KindDescription {
        name: k.name().to_string(),
        version: k.version(),
        doc: k.doc().to_string(),
        time_limit_s: k.time_limit_s(),
        params,
        columns,
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_kind_is_described_from_its_declarations() {
        let registry = crate::stages::registry();
        let d = super::describe(registry.get("theory.persson").unwrap(), &registry);
        assert_eq!(d.name, "theory.persson");
        let names: Vec<&str> = d.params.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["V0", "inv_k", "rel_tol"]);
        let inv_k = &d.params[1];
        assert!(inv_k.required && inv_k.sweepable && inv_k.default.is_none());
        assert_eq!((inv_k.r#type.as_str(), inv_k.range.as_str()), ("number", "> 1"));
        let rel_tol = &d.params[2];
        assert!(!rel_tol.required && !rel_tol.sweepable);
        assert_eq!(rel_tol.default, Some(serde_json::json!(1e-8)));
        let mu = d.columns.iter().find(|c| c.name == "mu_star").unwrap();
        assert_eq!(mu.unit, "1");
        assert!(mu.meaning.starts_with("friction μ*"), "{}", mu.meaning);
    }
}
