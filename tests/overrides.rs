//! `repro run -S STAGE.PARAM=VALUE`: a parameter set for one run, without editing the file
//! (DVC's `exp run -S`, Snakemake's `--config`), recorded in the run report and named in
//! the stale reasons.

mod common;
use common::{sleep_pipeline, Scratch};
use serde_json::json;

#[test]
fn an_override_recomputes_what_it_changes_and_says_so() {
    let s = Scratch::new("override");
    let yaml = sleep_pipeline("[1, 2]", 0, "t");
    s.write("p.yaml", &yaml);
    assert_eq!(s.run("p.yaml", &[]).0, 0);
    let (code, err, r) = s.run("p.yaml", &["-S", "sweep.ms=1"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        r.task("sweep", "x=1")["reason"],
        json!({"why": "parameters_changed", "changes": [{"param": "ms", "from": "0", "to": "1", "set_by_cli": true}]})
    );
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
    assert_eq!(r.task("sweep", "x=3")["reason"], json!({"why": "new_point", "point": "x=3"}));
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
    // A parameter the command line set is wrong: the error is located on that argument, and
    // it is the only one (the stages that need `sweep` add none: it is declared, only invalid).
    let (code, err, _) = s.run("p.yaml", &["-S", "sweep.msec=1"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("p.yaml (-S sweep.msec=1): error: stage `sweep` (util.sleep)") && err.contains("msec"),
        "{err}"
    );
    assert_eq!(err.matches("error:").count(), 1, "{err}");
    assert!(!err.contains("names no stage"), "{err}");
    let (code, err, _) = s.run("p.yaml", &["-S", "sweep.ms=-1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("p.yaml (-S sweep.ms=-1): error:") && err.contains("ms"), "{err}");
    assert_eq!(err.matches("error:").count(), 1, "{err}");
    let (code, err, _) = s.run("p.yaml", &["-S", "sweep.ms=[1, 2"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("is not a YAML value"), "{err}");
    let (code, err, _) = s.run("p.yaml", &["-S", "sweep"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("expected STAGE.PARAM=VALUE"), "{err}");
    assert!(!s.path("cache/runs/last.json").exists());
}

#[test]
fn diff_names_the_parameter_set_and_the_results_it_moved() {
    let s = Scratch::new("diff");
    s.write(
        "p.yaml",
        r#"stages:
  - name: persson
    kind: theory.persson
    params: {inv_k: 2, V0: [0.1, 1, 10]}
  - name: fig
    kind: figure
    needs: [persson]
    params:
      title: "mu*"
      x_label: "V0"
      y_label: "mu*"
      log_x: true
      layers:
        - data: {from: persson, x: V0, y: mu_star, label: "Persson"}
"#,
    );
    assert_eq!(s.run("p.yaml", &[]).0, 0);
    let out = s.repro(&["diff"]);
    assert_eq!(out.status.code(), Some(2), "one run: nothing to compare");
    assert_eq!(s.run("p.yaml", &["-S", "persson.inv_k=10"]).0, 0);
    let out = s.repro(&["diff"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(text.contains("parameters set with -S: (none) -> persson.inv_k=10"), "{text}");
    assert!(text.contains("persson: 3 (parameters changed: inv_k: 2.0 -> 10.0 (-S))"), "{text}");
    // mu* at k = 0.1 against k = 0.5: far more than the tolerance, at all three speeds.
    let line =
        text.lines().find(|l| l.trim_start().starts_with("persson.mu_star:")).unwrap_or_else(|| panic!("{text}"));
    assert!(line.ends_with("at 3 point(s)"), "{line}");
    assert!(text.contains("figure fig changed"), "{text}");
    assert!(!text.contains("wall_time_s"), "{text}");
    // The same run again: nothing computed, nothing changed.
    assert_eq!(s.run("p.yaml", &["-S", "persson.inv_k=10"]).0, 0);
    let text = String::from_utf8_lossy(&s.repro(&["diff"]).stdout).to_string();
    assert!(text.contains("computed: 0 task(s)") && text.contains("no table value or figure changed"), "{text}");
}

#[test]
fn a_run_records_the_git_commit_of_its_pipeline() {
    // A pipeline in a git checkout: the run report (and `repro runs`) carries the commit, and
    // says when tracked files differ from it; outside a checkout there is none.
    let s = Scratch::new("git-commit");
    let git = |args: &[&str]| {
        let out = std::process::Command::new("git")
            .args(["-c", "user.name=t", "-c", "user.email=t@t", "-c", "commit.gpgsign=false"])
            .args(args)
            .current_dir(s.path(""))
            .output()
            .expect("git runs");
        assert!(out.status.success(), "git {args:?}: {}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stdout).trim().to_string()
    };
    s.write("p.yaml", &sleep_pipeline("[1]", 0, "x"));
    let (code, err, report) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(report.0.get("git_commit").is_none(), "{:?}", report.0);
    git(&["init", "-q"]);
    git(&["add", "p.yaml"]);
    git(&["commit", "-q", "-m", "pipeline"]);
    let head = git(&["rev-parse", "HEAD"]);
    let (_, _, report) = s.run("p.yaml", &[]);
    assert_eq!(report.0["git_commit"], head.as_str());
    let runs = String::from_utf8_lossy(&s.repro(&["runs"]).stdout).to_string();
    assert!(runs.contains(&format!("at {}", &head[..12])), "{runs}");
    s.write("p.yaml", &sleep_pipeline("[2]", 0, "x"));
    let (_, _, report) = s.run("p.yaml", &[]);
    assert_eq!(report.0["git_commit"], format!("{head} (modified)").as_str());
}
