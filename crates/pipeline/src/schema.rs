//! The JSON Schema of pipeline files, generated from the parameter types of the
//! registered stage kinds (schemars), so that editors can check and complete pipelines.

use super::kind::Registry;
use serde_json::{json, Map, Value};

fn rewrite_refs(v: &mut Value, prefix: &str) {
    match v {
        Value::Object(m) => {
            for (k, x) in m.iter_mut() {
                if k == "$ref" {
                    if let Value::String(s) = x {
                        if let Some(rest) = s.strip_prefix("#/$defs/") {
                            *s = format!("#/$defs/{prefix}.{rest}");
                        }
                    }
                } else {
                    rewrite_refs(x, prefix);
                }
            }
        }
        Value::Array(a) => a.iter_mut().for_each(|x| rewrite_refs(x, prefix)),
        _ => {}
    }
}

fn sweep_of(item: Value) -> Value {
    let triple = json!({"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3});
    json!({
        "anyOf": [
            item.clone(),
            {"type": "array", "items": item, "minItems": 1, "description": "a sweep over these values"},
            {"type": "object", "properties": {"logspace": triple.clone()}, "required": ["logspace"], "additionalProperties": false,
             "description": "n values from 10^from to 10^to: [from, to, n]"},
            {"type": "object", "properties": {"linspace": triple.clone()}, "required": ["linspace"], "additionalProperties": false,
             "description": "n values from `from` to `to`: [from, to, n]"},
            {"type": "object", "properties": {"shown": {"type": "integer", "minimum": 2, "maximum": 100000}},
             "required": ["shown"], "additionalProperties": false,
             "description": "n values over the range that the figures plotting this parameter show (their x_range), in log10 on log axes"},
            {"type": "object", "additionalProperties": false, "required": ["adaptive"],
             "description": "sampled where the curve of output columns bends or peaks (see docs/pipelines.md)",
             "properties": {"adaptive": {
                "type": "object", "additionalProperties": false, "required": ["y", "tol"],
                "oneOf": [{"required": ["logspace"]}, {"required": ["linspace"]}, {"required": ["shown"]}],
                "properties": {
                    "logspace": triple.clone(),
                    "linspace": triple,
                    "shown": {"type": "integer", "minimum": 3, "maximum": 100000,
                              "description": "the initial grid: n points over the range shown (see `shown` sweeps)"},
                    "y": {"anyOf": [{"type": "string"}, {"type": "array", "items": {"type": "string"}, "minItems": 1}],
                          "description": "the output column(s) to resolve, one row per point"},
                    "tol": {"type": "number", "exclusiveMinimum": 0, "exclusiveMaximum": 1,
                            "description": "largest deviation from the chord, as a fraction of the curve's span"},
                    "log_y": {"type": "boolean"},
                    "levels": {"type": "integer", "minimum": 0, "maximum": 20,
                               "description": "halvings of the initial spacing at most (default 3)"},
                    "max_points": {"type": "integer", "minimum": 3}
                }}}}
        ]
    })
}

/// The schema of a pipeline file for the kinds in `registry`.
pub fn pipeline_schema(registry: &Registry) -> Value {
    let mut defs = Map::new();
    let mut branches = Vec::new();
    let mut kinds = Vec::new();
    for kind in registry.iter() {
        let mut schema = kind.params_schema();
        let prefix = kind.name();
        rewrite_refs(&mut schema, prefix);
        if let Some(Value::Object(d)) = schema.as_object_mut().and_then(|m| m.remove("$defs")) {
            for (k, v) in d {
                defs.insert(format!("{prefix}.{k}"), v);
            }
        }
        if let Some(Value::Object(props)) = schema.get_mut("properties") {
            for name in kind.sweepable() {
                if let Some(p) = props.remove(*name) {
                    props.insert(name.to_string(), sweep_of(p));
                }
            }
        }
        if let Some(m) = schema.as_object_mut() {
            m.remove("$schema");
            m.insert("description".into(), json!(format!("{} (code version {})", kind.doc(), kind.version())));
        }
        defs.insert(format!("params.{prefix}"), schema);
        // One branch per kind, selected by `kind`: an editor reports the errors of the
        // stage's own kind only.
        branches.push(json!({
            "if": {"properties": {"kind": {"const": prefix}}, "required": ["kind"]},
            "then": {"properties": {"params": {"$ref": format!("#/$defs/params.{prefix}")}}}
        }));
        kinds.push(json!({"const": prefix, "description": kind.doc()}));
    }
    let stage = json!({
        "type": "object",
        "properties": {
            "name": {"type": "string", "pattern": "^[A-Za-z0-9_.-]+$"},
            "kind": {"oneOf": kinds, "description": "the stage kind (`repro kinds` lists them)"},
            "description": {"type": "string"},
            "params": {"type": "object"},
            "needs": {
                "type": "array",
                "description": "the stages whose tables this stage reads; `{stage: NAME, match: [PARAM, ...]}` reads, per point, only the rows of the points of NAME whose parameters PARAM equal its own (a point's key then depends on those rows alone)",
                "items": {"oneOf": [
                    {"type": "string"},
                    {
                        "type": "object",
                        "properties": {
                            "stage": {"type": "string"},
                            "match": {"type": "array", "items": {"type": "string"}, "minItems": 1}
                        },
                        "required": ["stage", "match"],
                        "additionalProperties": false
                    }
                ]}
            },
            "publish": {"type": "boolean", "description": "write the stage's table to the tables folder (default true; false: kept in the cache for the stages that need it)"},
            "time_limit": {"type": "number", "exclusiveMinimum": 0, "description": "each task's time limit in seconds (default: the kind's, `repro kinds KIND`); a task past it is recorded as timed out"}
        },
        "required": ["name", "kind"],
        "additionalProperties": false,
        "allOf": branches
    });
    json!({
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "repro pipeline",
        "description": "A DAG of stages; see docs/pipelines.md. Generated by `repro schema`.",
        "type": "object",
        "properties": {
            "description": {"type": "string"},
            "stages": {"type": "array", "items": stage}
        },
        "required": ["stages"],
        "additionalProperties": false,
        "$defs": defs
    })
}
