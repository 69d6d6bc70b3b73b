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

/// A persson sweep over V0 at one 1/k and a figure whose title names `{column}`s.
fn titled_pipeline(title: &str) -> String {
    format!(
        r#"stages:
  - name: persson
    kind: theory.persson
    params: {{inv_k: 2, V0: [0.1, 1, 10]}}
  - name: fig
    kind: figure
    needs: [persson]
    params:
      title: "{title}"
      x_label: "V0"
      y_label: "mu*"
      log_x: true
      layers:
        - data: {{from: persson, x: V0, y: mu_star, label: "Persson"}}
"#
    )
}

#[test]
fn a_figure_title_says_the_parameters_of_the_data_it_draws() {
    let s = Scratch::new("titles");
    s.write("p.yaml", &titled_pipeline("μ* vs V0 at 1/k = {inv_k}"));
    assert_eq!(s.run("p.yaml", &[]).0, 0);
    let svg = String::from_utf8(s.read("figures/fig.svg")).unwrap();
    assert!(svg.contains("1/k = 2\n"), "{svg}");
    // Another 1/k on the command line: the run publishes into a folder of its own, whose
    // title follows it; the file's figure is untouched; `repro runs` names the folder.
    let file_figure = s.read("figures/fig.svg");
    let (code, err, _) = s.run("p.yaml", &["-S", "persson.inv_k=10"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(s.read("figures/fig.svg"), file_figure);
    let svg = String::from_utf8(s.read("overrides/p/persson.inv_k=10/figures/fig.svg")).unwrap();
    assert!(svg.contains("1/k = 10\n") && !svg.contains("1/k = 2\n"), "{svg}");
    assert!(s.path("overrides/p/persson.inv_k=10/tables/persson.parquet").exists());
    let runs = String::from_utf8_lossy(&s.repro(&["runs"]).stdout).to_string();
    assert!(runs.contains("-S persson.inv_k=10  -> overrides/p/persson.inv_k=10/"), "{runs}");
    // Asked to (`--publish`), it writes over the file's.
    assert_eq!(s.run("p.yaml", &["-S", "persson.inv_k=10", "--publish"]).0, 0);
    let svg = String::from_utf8(s.read("figures/fig.svg")).unwrap();
    assert!(svg.contains("1/k = 10\n"), "{svg}");
    // A column that takes several values in the drawn data: the title lists them all.
    s.write("p.yaml", &titled_pipeline("μ* at V0 = {V0}"));
    let (code, err, _) = s.run("p.yaml", &["--publish"]);
    assert_eq!(code, 0, "{err}");
    let svg = String::from_utf8(s.read("figures/fig.svg")).unwrap();
    assert!(svg.contains("μ* at V0 = 0.1, 1 and 10\n"), "{svg}");
}

#[test]
fn a_limit_line_drawn_beside_the_data_follows_an_override_of_its_parameters() {
    // The JKR limit of the friction is computed from the (W, k) of the table it bounds, so
    // an override of W moves the line and its label with the data; no value is written in
    // the figure's layers.
    let s = Scratch::new("limit-line");
    s.write(
        "p.yaml",
        r#"stages:
  - name: pts
    kind: bem.sweep
    params: {lambda: 1, W: 1, k: 0.1, V0: 1, n: 64}
  - name: limit
    kind: theory.jkr_friction_limit
    needs: [pts]
    params: {from: pts, lambda_range: [0.1, 10]}
  - name: fig
    kind: figure
    needs: [pts, limit]
    params:
      title: "max mu* vs lambda, W = {W}"
      x_label: "lambda"
      y_label: "mu*"
      log_x: true
      layers:
        - data: {from: pts, x: lambda, y: mu_star, label: "BEM", style: points}
        - data: {from: limit, x: lambda, y: mu_star_jkr, label: "JKR limit, W = {W}, k = {k}", style: dashed}
"#,
    );
    let (code, err, _) = s.run("p.yaml", &["-S", "pts.W=2"]);
    assert_eq!(code, 0, "{err}");
    let svg = String::from_utf8(s.read("overrides/p/pts.W=2/figures/fig.svg")).unwrap();
    assert!(svg.contains("JKR limit, W = 2, k = 0.1") && !svg.contains("W = 1,"), "{svg}");
    // The line's level, from the figure's own table: sqrt(pi) / (2 W^(3/2) k) at W = 2.
    let table = s.repro(&["show", &s.path("overrides/p/pts.W=2/tables/limit.parquet").to_string_lossy()]);
    let shown = String::from_utf8_lossy(&table.stdout).to_string() + &String::from_utf8_lossy(&table.stderr);
    let level = std::f64::consts::PI.sqrt() / (2.0 * 2f64.powf(1.5) * 0.1);
    assert!(shown.contains(&format!("{level:.6}")), "{shown} (expected {level})");
}

#[test]
fn a_column_that_does_not_exist_fails_the_dry_run_at_the_line_naming_it() {
    // A figure layer, a title's placeholder and a claim naming columns the kind does not
    // declare: each an error at its line before anything runs, with the nearest column.
    let s = Scratch::new("columns");
    let mut text = titled_pipeline("μ* at {inv_kk}").replace("y: mu_star", "y: mu_str");
    text.push_str(
        r#"  - name: c
    kind: claim
    needs: [persson]
    params:
      id: t.c
      source: "s"
      statement: "s"
      quantity: {from: persson, y: mu_star, x: V00, aggregate: argmax}
      thesis: {value: 1}
      expect: differs
      reason: "r"
"#,
    );
    s.write("p.yaml", &text);
    let out = s.repro(&["run", "p.yaml", "--dry-run"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("p.yaml:9:14: error: stage `fig`: `title` reads column `inv_kk`")
            && err.contains("(did you mean `inv_k`?)"),
        "{err}"
    );
    assert!(
        err.contains("p.yaml:14:43: error: stage `fig`: `layers[0].data.y` reads column `mu_str`")
            && err.contains("(did you mean `mu_star`?)"),
        "{err}"
    );
    assert!(
        err.contains("p.yaml:22:48: error: stage `c`: `quantity.x` reads column `V00`")
            && err.contains("(did you mean `V0`?)"),
        "{err}"
    );
    assert_eq!(err.matches("error:").count(), 3, "{err}");
}
