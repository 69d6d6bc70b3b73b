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
    let variants = schema["properties"]["stages"]["items"]["oneOf"].as_array().unwrap();
    let kinds: Vec<&str> = variants.iter().map(|v| v["properties"]["kind"]["const"].as_str().unwrap()).collect();
    assert_eq!(kinds, registry.names().collect::<Vec<_>>());
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
    let pipeline = repro::pipeline::spec::to_json(&root);
    for stage in pipeline["stages"].as_array().unwrap() {
        let kind = stage["kind"].as_str().unwrap();
        let props = &schema["$defs"][format!("params.{kind}")]["properties"];
        assert!(props.is_object(), "kind {kind} not in schema");
        for key in stage["params"].as_object().unwrap().keys() {
            assert!(props.get(key).is_some(), "{kind}: `{key}` not in the schema");
        }
    }
}
