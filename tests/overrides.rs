//! `repro run -S STAGE.PARAM=VALUE`: a parameter set for one run, without editing the file
//! (DVC's `exp run -S`, Snakemake's `--config`), recorded in the run report and named in
//! the stale reasons.

mod common;
use common::{sleep_pipeline, Scratch};

#[test]
fn an_override_recomputes_what_it_changes_and_says_so() {
    let s = Scratch::new("override");
    let yaml = sleep_pipeline("[1, 2]", 0, "t");
    s.write("p.yaml", &yaml);
    assert_eq!(s.run("p.yaml", &[]).0, 0);
    let (code, err, r) = s.run("p.yaml", &["-S", "sweep.ms=1"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.task("sweep", "x=1")["reason"], "parameters changed: ms: 0 -> 1 (-S)");
    assert_eq!(r.0["overrides"], serde_json::json!(["sweep.ms=1"]));
    // The stage's output did not change (util.sleep returns x): nothing downstream reruns.
    assert_eq!(r.count(Some("fig"), "cached"), 1);
    // The file is untouched; the same override again is all cached.
    assert_eq!(std::fs::read_to_string(s.path("p.yaml")).unwrap(), yaml);
    let (_, _, r) = s.run("p.yaml", &["-S", "sweep.ms=1"]);
    assert_eq!(r.count(None, "computed"), 0);
    // A sweep as the value: one new point.
    let (code, err, r) = s.run("p.yaml", &["-S", "sweep.ms=1", "--set", "sweep.x=[1, 2, 3]"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(Some("sweep"), "computed"), 1);
    assert_eq!(r.task("sweep", "x=3")["reason"], "new sweep point x=3");
    // Without it, the file's parameters again: their results are still in the cache.
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(None, "computed"), 0);
    assert_eq!(r.task("sweep", "x=1")["status"], "cached");
    assert!(r.0.get("overrides").is_none());
}

#[test]
fn a_wrong_override_is_refused_before_anything_runs() {
    let s = Scratch::new("override-bad");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    let (code, err, _) = s.run("p.yaml", &["-S", "swep.ms=1"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("p.yaml (-S swep.ms=1)")
            && err.contains("no stage `swep` in the pipeline (did you mean `sweep`?)"),
        "{err}"
    );
    let (code, err, _) = s.run("p.yaml", &["-S", "sweep.msec=1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("stage `sweep` (util.sleep)") && err.contains("msec"), "{err}");
    let (code, err, _) = s.run("p.yaml", &["-S", "sweep.ms=-1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("ms"), "{err}");
    let (code, err, _) = s.run("p.yaml", &["-S", "sweep.ms=[1, 2"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("is not a YAML value"), "{err}");
    let (code, err, _) = s.run("p.yaml", &["-S", "sweep"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("expected STAGE.PARAM=VALUE"), "{err}");
    assert!(!s.path("cache/runs/last.json").exists());
}
