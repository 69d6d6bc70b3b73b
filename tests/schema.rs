//! The JSON Schema of pipeline files: generated from the kinds' parameter types, kept in
//! `pipelines/schema.json` (regenerate with `make schema`), and consistent with the
//! default pipeline.

use serde_json::Value;

fn generated() -> Value {
    repro::pipeline::schema::pipeline_schema(&repro::stages::registry())
}

#[test]
fn committed_schema_is_current() {
    let committed: Value = serde_json::from_str(
        &std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/pipelines/schema.json")).unwrap(),
    )
    .unwrap();
    assert!(committed == generated(), "pipelines/schema.json is stale: run `make schema`");
}

#[test]
fn schema_covers_every_kind_and_wraps_exactly_the_sweepable_parameters() {
    let schema = generated();
    let registry = repro::stages::registry();
    // One branch per kind, selected by `kind` (if/then): an editor reports a stage's errors
    // against its own kind only.
    let stage = &schema["properties"]["stages"]["items"];
    let kinds: Vec<&str> =
        stage["properties"]["kind"]["oneOf"].as_array().unwrap().iter().map(|v| v["const"].as_str().unwrap()).collect();
    assert_eq!(kinds, registry.names().collect::<Vec<_>>());
    let branches = stage["allOf"].as_array().unwrap();
    for (kind, branch) in kinds.iter().zip(branches) {
        assert_eq!(branch["if"]["properties"]["kind"]["const"], *kind);
        assert_eq!(branch["then"]["properties"]["params"]["$ref"], format!("#/$defs/params.{kind}"));
    }
    assert_eq!(branches.len(), kinds.len());
    for kind in registry.iter() {
        let props = &schema["$defs"][format!("params.{}", kind.name())]["properties"];
        for (name, p) in props.as_object().unwrap() {
            let wrapped = p["anyOf"].as_array().is_some_and(|a| a.iter().any(|x| x["required"][0] == "logspace"));
            assert_eq!(wrapped, kind.sweepable().contains(&name.as_str()), "{}.{name}", kind.name());
        }
    }
}

#[test]
fn default_pipeline_uses_only_what_the_schema_declares() {
    let schema = generated();
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/pipelines/thesis.yaml")).unwrap();
    let root = marked_yaml::parse_yaml(0, &text).unwrap();
    let pipeline = repro::pipeline::parse::to_json(&root);
    for stage in pipeline["stages"].as_array().unwrap() {
        let kind = stage["kind"].as_str().unwrap();
        let props = &schema["$defs"][format!("params.{kind}")]["properties"];
        assert!(props.is_object(), "kind {kind} not in schema");
        for key in stage["params"].as_object().unwrap().keys() {
            assert!(props.get(key).is_some(), "{kind}: `{key}` not in the schema");
        }
    }
}

#[test]
fn bounds_declared_on_the_parameters_reach_the_schema() {
    // The bounds the checks enforce (pipeline::kind::bound_errors) are the schema's own.
    let schema = generated();
    let k = &schema["$defs"]["params.bem.sweep"]["properties"]["k"]["anyOf"][0];
    assert_eq!((k["exclusiveMinimum"].as_f64(), k["exclusiveMaximum"].as_f64()), (Some(0.0), Some(1.0)));
    let nu = &schema["$defs"]["fem.gamma_c.MapModel"]["properties"]["nu"];
    assert_eq!((nu["exclusiveMinimum"].as_f64(), nu["exclusiveMaximum"].as_f64()), (Some(-1.0), Some(0.5)));
    let n = &schema["$defs"]["params.theory.maugis_dugdale"]["properties"]["n"];
    assert_eq!((n["minimum"].as_u64(), n["maximum"].as_u64()), (Some(2), Some(1_000_000)));
}
