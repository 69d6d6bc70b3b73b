//! The smaller commands: dag, kinds, schema, and a missing pipeline file.

mod common;
use common::{sleep_pipeline, Scratch};

#[test]
fn dag_prints_graphviz_with_every_stage_and_edge() {
    let s = Scratch::new("dag");
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 0, "t"));
    let out = s.repro(&["dag", "p.yaml"]);
    assert!(out.status.success());
    let dot = String::from_utf8(out.stdout).unwrap();
    assert!(dot.starts_with("digraph pipeline {"), "{dot}");
    assert!(dot.contains("\"sweep\" [label=\"sweep\\nutil.sleep (3 points)\"]"), "{dot}");
    assert!(dot.contains("\"sweep\" -> \"after\";") && dot.contains("\"sweep\" -> \"fig\";"), "{dot}");
}

#[test]
fn kinds_lists_every_kind_with_its_version() {
    let s = Scratch::new("kinds");
    let out = s.repro(&["kinds"]);
    let text = String::from_utf8(out.stdout).unwrap();
    for k in repro::stages::registry().iter() {
        assert!(text.contains(&format!("{:<28} v{}", k.name(), k.version())), "{text}");
    }
}

#[test]
fn schema_command_prints_the_committed_schema() {
    let s = Scratch::new("schema-cmd");
    let out = s.repro(&["schema"]);
    let printed: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let committed: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/pipelines/schema.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(printed, committed);
}

#[test]
fn a_missing_pipeline_file_is_invalid_input() {
    let s = Scratch::new("missing-file");
    let out = s.repro(&["run", "nope.yaml"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("nope.yaml") && err.contains("cannot read the pipeline file"), "{err}");
    assert!(!s.exists("cache"));
}
