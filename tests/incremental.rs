//! Incremental runs: what runs, read from the run report (`--report`), not only from the
//! outputs.

mod common;
use common::{sleep_pipeline, snapshot, Scratch};
use serde_json::json;

#[test]
fn no_op_rerun_computes_nothing_and_rewrites_nothing() {
    let s = Scratch::new("noop");
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 0, "t"));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(None, "computed"), 5);
    assert!(s.exists("figures/fig.svg") && s.exists("figures/fig.parquet") && s.exists("tables/sweep.parquet"));
    let before = snapshot(&s.path("figures"));
    let (code, _, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0);
    assert_eq!(r.count(None, "computed"), 0);
    assert_eq!(r.count(None, "cached"), 5);
    assert_eq!(r.0["published"].as_array().unwrap().len(), 0, "nothing is rewritten");
    assert_eq!(before, snapshot(&s.path("figures")));
}

#[test]
fn adding_a_sweep_value_computes_only_that_point() {
    let s = Scratch::new("sweep-add");
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 0, "t"));
    s.run("p.yaml", &[]);
    s.write("p.yaml", &sleep_pipeline("[1, 2, 2.5, 3]", 0, "t"));
    let (code, _, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0);
    assert_eq!(r.count(Some("sweep"), "computed"), 1);
    assert_eq!(r.count(Some("sweep"), "cached"), 3);
    let t = r.task("sweep", "x=2.5");
    assert_eq!(t["status"], "computed");
    assert_eq!(t["reason"], json!({"why": "new_point", "point": "x=2.5"}));
    // Its readers see a new table, so they rerun; the stage table has all four points.
    assert_eq!(r.count(Some("after"), "computed"), 1);
    assert_eq!(r.count(Some("fig"), "computed"), 1);
    let df = repro::pipeline::table::read_parquet(&s.path("tables/sweep.parquet")).unwrap();
    assert_eq!(df.height(), 4);
    // A logspace sweep gives the same points as the equivalent list: nothing recomputed.
    s.write("p.yaml", &sleep_pipeline("{logspace: [0, 1, 3]}", 0, "t"));
    s.write("q.yaml", &sleep_pipeline("[1, 3.16227766017, 10]", 0, "t"));
    s.run("p.yaml", &[]);
    let (_, _, r) = s.run("q.yaml", &[]);
    assert_eq!(r.count(Some("sweep"), "computed"), 0, "{:?}", r.0);
}

#[test]
fn early_cutoff_when_a_recomputed_output_is_identical() {
    let s = Scratch::new("cutoff");
    let yaml = |x: &str| {
        format!(
            "stages:\n  - name: up\n    kind: util.sleep\n    params: {{x: {x}, round: 1}}\n  - name: down\n    kind: util.sleep\n    needs: [up]\n    params: {{x: 5}}\n"
        )
    };
    s.write("p.yaml", &yaml("1.01"));
    s.run("p.yaml", &[]);
    // 1.02 rounds to the same 1.0: `up` recomputes, `down` sees identical input.
    s.write("p.yaml", &yaml("1.02"));
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(Some("up"), "computed"), 1);
    assert_eq!(r.count(Some("down"), "cached"), 1);
    // 1.2 rounds to 1.2: a different output, so `down` reruns.
    s.write("p.yaml", &yaml("1.2"));
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(Some("down"), "computed"), 1);
    assert_eq!(r.task("down", "")["reason"], json!({"why": "input_changed", "stages": ["up"]}));
}

#[test]
fn editing_only_a_figure_style_reruns_only_that_figure() {
    let s = Scratch::new("style");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "first title"));
    s.run("p.yaml", &[]);
    let svg1 = s.read("figures/fig.svg");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "second title"));
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(None, "computed"), 1);
    assert_eq!(r.task("fig", "")["status"], "computed");
    assert_eq!(
        r.task("fig", "")["reason"],
        json!({"why": "parameters_changed", "changes": [{"param": "title", "from": "\"first title\"", "to": "\"second title\"", "set_by_cli": false}]})
    );
    let svg2 = String::from_utf8(s.read("figures/fig.svg")).unwrap();
    assert!(svg2.contains("second title") && s.read("figures/fig.svg") != svg1);
}

#[test]
fn a_fixed_parameter_changed_in_a_swept_stage_is_named_with_its_values() {
    // Not "new sweep point x=1": the sweep is the same, `ms` changed at every point.
    let s = Scratch::new("fixed-param");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    s.run("p.yaml", &[]);
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 1, "t"));
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(
        r.task("sweep", "x=1")["reason"],
        json!({"why": "parameters_changed", "changes": [{"param": "ms", "from": "0", "to": "1", "set_by_cli": false}]})
    );
    // A new value of the swept parameter is a new sweep point.
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 1, "t"));
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.task("sweep", "x=3")["reason"], json!({"why": "new_point", "point": "x=3"}));
}

#[test]
fn targets_run_only_what_they_need() {
    let s = Scratch::new("targets");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    let (code, _, r) = s.run("p.yaml", &["--target", "after"]);
    assert_eq!(code, 0);
    assert_eq!(r.stages(), vec!["sweep", "after"]);
    assert!(!s.exists("figures/fig.svg"));
    let (code, err, _) = s.run("p.yaml", &["--target", "nope"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--target nope: no stage of that name"), "{err}");
    // A near miss is answered with the nearest stage, not a list of every stage.
    let (code, err, _) = s.run("p.yaml", &["--target", "afer"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--target afer: no stage of that name in p.yaml (did you mean `after`?)"), "{err}");
    assert!(err.contains("`repro dag p.yaml` shows its 3 stages") && !err.contains("sweep"), "{err}");
    // A prefix of stage names is answered with the names it begins.
    let (_, err, _) = s.run("p.yaml", &["--target", "sw"]);
    assert!(err.contains("(did you mean `sweep`?)"), "{err}");
}

#[test]
fn force_recomputes_a_stage_and_cutoff_spares_its_readers() {
    let s = Scratch::new("force");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    s.run("p.yaml", &[]);
    let (_, _, r) = s.run("p.yaml", &["--force", "sweep"]);
    assert_eq!(r.count(Some("sweep"), "computed"), 2);
    assert_eq!(r.task("sweep", "x=1")["reason"], json!({"why": "forced"}));
    assert_eq!(r.count(Some("after"), "cached"), 1, "identical outputs: readers stay cached");
}

#[test]
fn keep_going_records_failures_and_skips_dependents() {
    let s = Scratch::new("keep-going");
    s.write(
        "p.yaml",
        r#"stages:
  - name: bad
    kind: util.fail
    params: {message: "deliberate failure", x: [1, 0]}
  - name: worse
    kind: util.fail
    params: {message: "deliberate panic", panic: true}
  - name: good
    kind: util.sleep
    params: {x: [1, 2, 3]}
  - name: after_bad
    kind: util.sleep
    needs: [bad]
    params: {x: 1}
  - name: after_good
    kind: util.sleep
    needs: [good]
    params: {x: 1}
"#,
    );
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 1, "failed tasks exit with 1: {err}");
    assert_eq!(r.task("bad", "x=1")["status"], "computed");
    let failed = r.task("bad", "x=0");
    assert_eq!(failed["status"], "failed");
    assert_eq!(failed["error"], "deliberate failure");
    assert_eq!(r.task("worse", "")["status"], "failed");
    assert!(r.task("worse", "")["error"].as_str().unwrap().contains("panicked: deliberate panic"));
    assert_eq!(r.count(Some("good"), "computed"), 3);
    assert_eq!(r.count(Some("after_good"), "computed"), 1);
    let skipped = r.task("after_bad", "");
    assert_eq!(skipped["status"], "skipped");
    assert_eq!(skipped["reason"], json!({"why": "needs_incomplete", "stages": ["bad"]}));
    assert!(err.contains("FAILED x=0: deliberate failure"), "{err}");
    // The successful point of the failed stage is cached; the failure is retried.
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.task("bad", "x=1")["status"], "cached");
    assert_eq!(r.task("bad", "x=0")["status"], "failed");
}

#[test]
fn dry_run_and_status_explain_without_writing() {
    let s = Scratch::new("dry");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    let (code, err, r) = s.run("p.yaml", &["--dry-run"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(Some("sweep"), "would_run"), 2);
    assert_eq!(r.count(Some("after"), "unknown"), 1);
    assert!(!s.exists("cache/objects") && !s.exists("figures"));
    s.run("p.yaml", &[]);
    s.write("p.yaml", &sleep_pipeline("[1, 2, 4]", 0, "t"));
    let out = s.repro(&["status", "p.yaml"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("sweep") && text.contains("1 would run") && text.contains("new sweep point x=4"), "{text}");
}

#[test]
fn a_sweep_of_thousands_of_tasks_plans_runs_and_reruns_as_a_no_op() {
    // `cargo bench --bench scale` times this at 1e3..1e5 tasks (docs/reliability.md); here the counts.
    let s = Scratch::new("scale");
    s.write("p.yaml", "stages:\n  - name: many\n    kind: util.sleep\n    params: {x: {linspace: [1, 5000, 5000]}}\n  - name: all\n    kind: util.sleep\n    needs: [many]\n    params: {x: 0}\n");
    let (code, _, r) = s.run("p.yaml", &["--dry-run"]);
    assert_eq!((code, r.count(Some("many"), "would_run"), r.count(Some("all"), "unknown")), (0, 5000, 1));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!((code, r.count(None, "computed")), (0, 5001), "{err}");
    assert_eq!(common::column(&s.table("all"), "upstream_rows"), vec![5000.0]);
    let manifest_dir = std::fs::read_dir(s.path("cache/manifests")).unwrap().next().unwrap().unwrap().path();
    let modified = |f: &str| std::fs::metadata(manifest_dir.join(f)).unwrap().modified().unwrap();
    let before = modified("many.json");
    let (code, _, r) = s.run("p.yaml", &[]);
    assert_eq!((code, r.count(None, "cached"), r.count(None, "computed")), (0, 5001, 0));
    assert_eq!(modified("many.json"), before, "an unchanged manifest is not rewritten");
}

#[test]
fn stages_sharing_points_compute_each_shared_task_once() {
    let s = Scratch::new("twins");
    s.write(
        "p.yaml",
        "stages:\n  - name: a\n    kind: util.sleep\n    params: {x: [1, 2, 3]}\n  - name: b\n    kind: util.sleep\n    params: {x: [2, 3, 4]}\n",
    );
    let (_, _, r) = s.run("p.yaml", &["--dry-run"]);
    assert_eq!((r.count(None, "would_run"), r.count(None, "cached")), (4, 2));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    // x = 2 and 3 are one task each, shared by both stages: 4 computations, not 6.
    assert_eq!(r.count(None, "computed"), 4);
    let twin = r.task("b", "x=2");
    assert_eq!(twin["status"], "cached");
    assert_eq!(twin["reason"], json!({"why": "same_task_as", "stage": "a", "point": "x=2"}), "{twin}");
    assert_eq!(s.table("b").height(), 3);
    // Both tables show the one computation's wall time, so a rerun rewrites neither.
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(None, "computed"), 0);
    assert_eq!(r.0["published"].as_array().unwrap().len(), 0, "{:?}", r.0["published"]);
}

/// The manifest a stage's last run left in the cache (one pipeline per scratch cache).
fn manifest_file(s: &Scratch, stage: &str) -> std::path::PathBuf {
    let dir = std::fs::read_dir(s.path("cache/manifests")).unwrap().flatten().next().unwrap().path();
    dir.join(format!("{stage}.json"))
}

#[test]
fn every_reason_for_recomputing_is_typed_in_the_report() {
    let s = Scratch::new("typed-reasons");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.task("sweep", "x=1")["reason"], json!({"why": "never_run"}));
    // An entry removed behind the cache's back: the same point, inputs and code.
    let key = r.task("sweep", "x=1")["key"].as_str().unwrap().to_string();
    std::fs::remove_file(s.path(&format!("cache/objects/{}/{key}.entry", &key[..2]))).unwrap();
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.task("sweep", "x=1")["reason"], json!({"why": "entry_missing"}));
    assert_eq!(r.task("sweep", "x=2")["status"], "cached");
    // A damaged entry.
    let path = s.path(&format!("cache/objects/{}/{key}.entry", &key[..2]));
    let mut bytes = std::fs::read(&path).unwrap();
    let n = bytes.len();
    bytes[n - 3] ^= 1;
    std::fs::write(&path, bytes).unwrap();
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.task("sweep", "x=1")["reason"]["why"], "corrupted");
    // The code of the kind changed since the last run (its manifest says v0) and the entry
    // of the new code is not there yet.
    let m = manifest_file(&s, "sweep");
    let mut manifest: serde_json::Value = serde_json::from_slice(&std::fs::read(&m).unwrap()).unwrap();
    let version = manifest["version"].as_u64().unwrap();
    manifest["version"] = json!(0);
    std::fs::write(&m, serde_json::to_vec(&manifest).unwrap()).unwrap();
    std::fs::remove_file(&path).unwrap();
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(
        r.task("sweep", "x=1")["reason"],
        json!({"why": "code_version_changed", "kind": "util.sleep", "from": 0, "to": version})
    );
    // Another kind for the same stage name.
    let s = Scratch::new("typed-reasons-kind");
    s.write("p.yaml", "stages:\n  - name: one\n    kind: util.sleep\n    params: {x: 1}\n");
    s.run("p.yaml", &[]);
    s.write("p.yaml", "stages:\n  - name: one\n    kind: util.fail\n    params: {x: 1, message: m}\n");
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.task("one", "")["reason"], json!({"why": "kind_changed", "from": "util.sleep", "to": "util.fail"}));
    // The summary prints each reason as a sentence.
    assert!(err.contains("kind changed (util.sleep -> util.fail)"), "{err}");
}
