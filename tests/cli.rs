//! The smaller commands: dag, kinds, schema, point, and a missing pipeline file.

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
fn a_column_meaning_with_a_pipe_is_shown_whole() {
    // docs/outputs.md escapes the pipes of |W| inside its cells; `repro kinds` shows the
    // meanings whole, where a plain split had cut them at the first pipe.
    let s = Scratch::new("kinds-pipe");
    let out = s.repro(&["kinds", "bem.sweep"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)"), "{text}");
    assert!(text.contains("rolling friction force F_T* = μ* |W| (Eq. 5.6)"), "{text}");
}

#[test]
fn messages_name_a_missing_file_without_a_line_and_large_numbers_compactly() {
    // A pipeline file that does not exist has no line to point at: the file alone, not
    // `file:0:0`. A parameter of 1e300 in a message reads 1e300, not 301 digits.
    let s = Scratch::new("messages");
    let out = s.repro(&["run", "missing.yaml"]);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("missing.yaml: error: cannot read the pipeline file") && !err.contains(":0:0"), "{err}");
    let out = s.repro(&["point", "theory.line_pulloff", "lambda=1e300"]);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(err.contains("lambda = 1e300") && !err.contains("10000000000"), "{err}");
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

#[test]
fn show_stops_quietly_when_its_reader_closes_the_pipe() {
    let s = Scratch::new("show-pipe");
    s.run_pipeline(
        "stages:\n  - name: mu\n    kind: theory.persson\n    params: {inv_k: 10, V0: {logspace: [-3, 3, 3000]}}\n",
    );
    // Far more than a pipe holds (3000 rows with their 64-character task keys).
    let mut child = s
        .command(&["show", "tables/mu.parquet"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    std::io::Read::read_exact(child.stdout.as_mut().unwrap(), &mut first).unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !err.contains("panicked"), "{:?}: {err}", out.status);
}

#[test]
fn show_csv_prints_every_digit_and_quotes_what_needs_it() {
    let s = Scratch::new("show-csv");
    s.run_pipeline(
        "stages:\n  - name: mu\n    kind: theory.persson\n    params: {inv_k: [1.1, 1000], V0: {logspace: [-3, 3, 7]}}\n",
    );
    let df = s.table("mu");
    let out = s.repro(&["show", "tables/mu.parquet", "--columns", "inv_k,V0,mu_star,code_version", "--csv"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("inv_k,V0,mu_star,code_version"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), df.height());
    // The floats parse back to the very same bits (the aligned table rounds them: Persson's
    // mu* at V0 = 1e-3 and 1/k = 1.1 prints as 0.000091 there).
    for (name, j) in [("inv_k", 0), ("V0", 1), ("mu_star", 2)] {
        let parsed: Vec<f64> = rows.iter().map(|r| r[j].parse().unwrap()).collect();
        assert_eq!(parsed, common::column(&df, name), "{name}");
    }
    assert!(rows.iter().all(|r| r[3].starts_with("theory.persson@v")), "{text}");
    let aligned = String::from_utf8(s.repro(&["show", "tables/mu.parquet", "--columns", "mu_star"]).stdout).unwrap();
    assert!(!aligned.contains(','), "{aligned}");
}

#[test]
fn point_rejects_a_repeated_parameter_and_names_the_kind_of_a_missing_one() {
    let s = Scratch::new("point-args");
    let out = s.repro(&["point", "util.sleep", "x=1", "x=2"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("parameter `x` is given twice"), "{err}");
    let out = s.repro(&["point", "bem.sweep"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bem.sweep: missing field `lambda`") && !err.contains("parameter ``"), "{err}");
    // A parameter without a name is refused as such, not passed on as the field ``.
    let out = s.repro(&["point", "util.sleep", "=2"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("`=2`: parameters are NAME=VALUE") && !err.contains("``"), "{err}");
    // A well-formed call still runs.
    let out = s.repro(&["point", "util.sleep", "x=1"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn point_is_guarded_as_a_task_of_a_run() {
    let s = Scratch::new("point-guard");
    // Held to a time limit (its kind's, or --time-limit): stopped, exit 1 as a failed task.
    let t0 = std::time::Instant::now();
    let out = s.repro(&["point", "util.sleep", "x=1", "ms=60000", "--time-limit", "0.3"]);
    assert!(t0.elapsed().as_secs_f64() < 30.0);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("the point was not computed: timed out: past its time limit of 0.3 s"), "{err}");
    // A panic is contained and reported, exit 1 (it aborted the command before).
    let out = s.repro(&["point", "util.fail", "message=boom", "panic=true"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("the point was not computed: panicked: boom"), "{err}");
    // A solver's own panic on an absurd domain: contained as in a run.
    let out = s.repro(&["point", "bem.sweep", "lambda=1", "W=1", "k=0.1", "V0=1", "half_length=1e300"]);
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    // A failure the kind returns is a failed task too.
    let out = s.repro(&["point", "util.fail", "message=no"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("the point was not computed: no"));
}

#[test]
fn kinds_describes_a_kind_s_parameters() {
    let s = Scratch::new("kinds-describe");
    let out = s.repro(&["kinds", "bem.sweep"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let lambda = text.lines().find(|l| l.starts_with("lambda ")).unwrap_or_else(|| panic!("{text}"));
    assert!(lambda.contains("number") && lambda.contains("(required)") && lambda.contains("sweepable"), "{lambda}");
    assert!(lambda.contains("Maugis-Tabor parameter"), "{lambda}");
    // Bounds and output columns, from the same declarations as the schema and the checks.
    let k = text.lines().find(|l| l.starts_with("k ")).unwrap_or_else(|| panic!("{text}"));
    assert!(k.contains("(0, 1)"), "{k}");
    let n = text.lines().find(|l| l.starts_with("n ")).unwrap_or_else(|| panic!("{text}"));
    assert!(n.contains("16..=32000"), "{n}");
    let mu = text.lines().find(|l| l.starts_with("mu_star ")).unwrap_or_else(|| panic!("{text}"));
    assert!(mu.contains("R/a0") || mu.contains("friction"), "{mu}");
    let out = s.repro(&["kinds", "theory.lennard_jones"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.lines().any(|l| l.starts_with("z_min") && l.contains("0.85")), "{text}");
    let out = s.repro(&["kinds", "bem.swep"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown stage kind `bem.swep`"));
}

#[test]
fn sizes_and_tolerances_that_would_abort_or_hang_are_refused() {
    // Each passed validation once: n = 1e11 then aborted the process allocating 800 GB,
    // V0 = 1e300 panicked (an overflow in |c|) and now would underflow the quadrature's
    // tolerance, rel_tol = 1e-16 refined for a minute.
    let s = Scratch::new("bounds");
    for (args, field) in [
        (
            &["theory.maugis_dugdale", "lambda=1", "A_min=0.01", "A_max=2", "n=100000000000"][..],
            "parameter `n`: must lie in 2..=1000000",
        ),
        (&["theory.persson", "inv_k=2", "V0=1e300"][..], "parameter `V0`: must lie in (0, 1e100], got 1e300"),
        (
            &["theory.persson", "inv_k=2", "V0=1", "rel_tol=1e-16"][..],
            "parameter `rel_tol`: must lie in [1e-14, 0.01), got 1e-16",
        ),
        // A valid radius whose default mesh (resolving g0) no memory holds: R = 1e6 mm used
        // 6 GB before it failed, R = 1e9 aborted the process.
        (&["fem.mesh", "R=1000000", "h=1"][..], "parameter `n_meridian`: the default mesh of R = 1e6 mm"),
        (
            &["fem.indent", "shell={R: 1000000000, h: 1}", "delta_max=0.1", "steps=2"][..],
            "parameter `shell.n_meridian`: the default mesh of R = 1e9 mm, h = 1 mm at g0 = 0.1 mm has about 1.5e10",
        ),
        (&["fem.gamma_c", "h_over_R=0.06", "model={R: 1000000}"][..], "parameter `model.n_meridian`: the default mesh"),
    ] {
        let mut a = vec!["point"];
        a.extend_from_slice(args);
        let out = s.repro(&a);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(field), "{args:?}: {err}");
    }
    // In a pipeline: located, nothing runs.
    s.write("p.yaml", "stages:\n  - name: md\n    kind: theory.maugis_dugdale\n    params: {lambda: 1, A_min: 0.01, A_max: 2, n: 100000000000}\n");
    let out = s.repro(&["run", "p.yaml", "--dry-run"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("p.yaml:4:") && err.contains("must lie in 2..=1000000"), "{err}");
    // A mesh given within the solver's range is taken at any radius.
    let out = s.repro(&["point", "fem.mesh", "R=1000000", "h=1", "n_meridian=8"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // Persson's friction at the largest speed allowed is finite, about 1/V0.
    let out = s.repro(&["point", "theory.persson", "inv_k=2", "V0=1e100"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn a_dry_run_prints_its_plan_per_stage_and_show_prints_a_head() {
    let s = Scratch::new("dry-plan");
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3, 4, 5, 6]", 0, "t"));
    let out = s.repro(&["run", "p.yaml", "--dry-run"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    // One line per stage (and the totals), not one per task.
    let sweep: Vec<&str> = stdout.lines().filter(|l| l.trim_start().starts_with("sweep")).collect();
    assert_eq!(sweep.len(), 1, "{stdout}");
    assert!(sweep[0].contains("6 would run"), "{stdout}");
    let out = s.repro(&["run", "p.yaml", "--dry-run", "--explain"]);
    assert!(String::from_utf8_lossy(&out.stdout).lines().filter(|l| l.contains("x=")).count() >= 6);
    // status --target: that stage and what it needs, as run --target selects them.
    let out = s.repro(&["status", "p.yaml", "--target", "after"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stages: Vec<&str> = stdout.lines().filter_map(|l| l.split_whitespace().next()).collect();
    assert_eq!(&stages[..2], ["sweep", "after"], "{stdout}");
    assert!(!stdout.contains("fig"), "{stdout}");
    let out = s.repro(&["status", "p.yaml", "--target", "aftr"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("did you mean `after`?"));
    // show: the first rows, provenance columns hidden unless asked.
    s.run("p.yaml", &[]);
    let out = s.repro(&["show", "tables/sweep.parquet", "--head", "2"]);
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 4, "{text}");
    assert!(!lines[0].contains("task_key") && lines[0].contains("x"), "{text}");
    assert_eq!(lines[3], "... 2 of 6 rows shown");
    let out = s.repro(&["show", "tables/sweep.parquet", "--all"]);
    assert!(String::from_utf8_lossy(&out.stdout).lines().next().unwrap().contains("task_key"));
}

#[test]
fn dag_shows_a_target_s_stages_coloured_by_their_state() {
    let s = Scratch::new("dag-status");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    let dot = |args: &[&str]| {
        let mut a = vec!["dag", "p.yaml"];
        a.extend_from_slice(args);
        let out = s.repro(&a);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stdout).to_string()
    };
    // `fig` needs `sweep` only: `after` is not drawn.
    let g = dot(&["--target", "fig"]);
    assert!(g.contains("\"sweep\" [") && g.contains("\"fig\" [") && !g.contains("\"after\""), "{g}");
    // Nothing run yet: stale (orange); after a run: cached (green); a changed sweep: stale again.
    let node =
        |g: &str, n: &str| g.lines().find(|l| l.trim_start().starts_with(&format!("\"{n}\" ["))).unwrap().to_string();
    assert!(node(&dot(&["--status"]), "sweep").contains("#fde2b5"));
    s.run("p.yaml", &[]);
    assert!(node(&dot(&["--status"]), "sweep").contains("#d5f0d5"));
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 0, "t"));
    let g = dot(&["--status"]);
    assert!(node(&g, "sweep").contains("#fde2b5") && node(&g, "after").contains("#fde2b5"), "{g}");
    let out = s.repro(&["dag", "p.yaml", "--target", "nope"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn published_tables_carry_their_units_and_fixed_parameters() {
    // Every published Parquet file says, in its key/value metadata, the unit and meaning of
    // each column (from docs/outputs.md) and the parameters its points share (a figure's
    // axis labels among them), for a reader who has only the file.
    let s = Scratch::new("metadata");
    s.run_pipeline(
        r#"stages:
  - name: pulloff
    kind: theory.maugis_pulloff
    params: {lambda: [0.5, 1]}
  - name: fig
    kind: figure
    needs: [pulloff]
    params:
      title: "pull-off"
      x_label: "λ"
      y_label: "P̄ pull-off"
      layers:
        - data: {from: pulloff, x: lambda, y: P_bar_pulloff, label: "Maugis"}
"#,
    );
    let meta = |rel: &str| -> std::collections::BTreeMap<String, serde_json::Value> {
        repro::pipeline::table::read_parquet_metadata(&s.path(rel))
            .unwrap()
            .into_iter()
            .filter(|(k, _)| k == "repro.columns" || k == "repro.params")
            .map(|(k, v)| (k, serde_json::from_str(&v).unwrap()))
            .collect()
    };
    let raw = repro::pipeline::table::read_parquet_metadata(&s.path("tables/pulloff.parquet")).unwrap();
    assert!(raw.iter().any(|(k, v)| k == "repro.version" && v == env!("CARGO_PKG_VERSION")), "{raw:?}");
    let table = meta("tables/pulloff.parquet");
    let columns = &table["repro.columns"];
    assert_eq!(columns["lambda"]["unit"], "1");
    assert_eq!(columns["P_bar_pulloff"]["unit"], "F/(π w R)");
    assert!(columns["P_bar_pulloff"]["meaning"].as_str().unwrap().contains("pull-off"), "{columns}");
    assert_eq!(columns["wall_time_s"]["unit"], "s");
    // The swept parameter is not a fixed one.
    assert!(table["repro.params"].get("lambda").is_none(), "{}", table["repro.params"]);
    let figure = meta("figures/fig.parquet");
    assert_eq!(figure["repro.params"]["x_label"], "λ");
    assert_eq!(figure["repro.params"]["y_label"], "P̄ pull-off");
    // A figure's x and y carry their units per point (`x_unit`, `y_unit`).
    assert_eq!(figure["repro.columns"]["x"]["unit"], "`x_unit`");
    assert_eq!(figure["repro.columns"]["x_unit"]["unit"], "text");
    assert_eq!(figure["repro.columns"]["series"]["unit"], "text");
}

#[test]
fn the_task_time_column_sums_to_the_cost_of_a_stage() {
    // A stage of three tasks of many rows each: `wall_time_s` repeats each task's time on
    // its rows, `task_time_s` holds it once, so that its sum is the stage's cost.
    let s = Scratch::new("task-time");
    s.run_pipeline(
        "stages:
  - name: curves
    kind: theory.maugis_dugdale
    params: {lambda: [0.5, 1, 2]}
",
    );
    let t = s.table("curves");
    let keys = common::strings(&t, "task_key");
    let (wall, task) = (common::column(&t, "wall_time_s"), common::column(&t, "task_time_s"));
    assert!(t.height() > 3 * 10, "{}", t.height());
    let mut per_task = std::collections::BTreeMap::new();
    for (i, k) in keys.iter().enumerate() {
        let first = !per_task.contains_key(k);
        per_task.entry(k.clone()).or_insert(wall[i]);
        assert_eq!(task[i], if first { wall[i] } else { 0.0 }, "row {i}");
    }
    assert_eq!(per_task.len(), 3);
    let total: f64 = per_task.values().sum();
    assert!((task.iter().sum::<f64>() - total).abs() <= 1e-12 * total.max(1e-300));
}

#[test]
fn anchors_aliases_and_merge_keys_are_read_and_errors_in_them_point_at_the_anchor() {
    // PyYAML writes `&id001` / `*id001` for a value it dumps twice; people write `<<:` to
    // share settings. Stage b repeats a's parameters (the same tasks), c merges them under
    // its own 1/k.
    let s = Scratch::new("anchors");
    let yaml = |inv_k: &str| {
        format!(
            "stages:\n  - name: a\n    kind: theory.persson\n    params: &shared {{inv_k: {inv_k}, V0: [0.1, 1]}}\n  \
             - name: b\n    kind: theory.persson\n    params: *shared\n  \
             - name: c\n    kind: theory.persson\n    params:\n      <<: *shared\n      inv_k: 10\n"
        )
    };
    s.write("p.yaml", &yaml("2"));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(Some("a"), "computed"), 2);
    assert_eq!(r.count(Some("c"), "computed"), 2);
    let shown = |stage: &str| {
        String::from_utf8_lossy(&s.repro(&["show", &format!("tables/{stage}.parquet")]).stdout).to_string()
    };
    assert_eq!(shown("a"), shown("b"));
    assert!(shown("c").contains("10.0") && !shown("c").contains(" 2.0 "), "{}", shown("c"));
    // A wrong value in the anchored mapping: one error per stage that uses it, each at the
    // anchor's line (4), where it is written.
    s.write("p.yaml", &yaml("0.5"));
    let (code, err, _) = s.run("p.yaml", &["--dry-run"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("p.yaml:4:") && err.contains("inv_k"), "{err}");
    // An alias before its anchor is refused where it stands.
    s.write("p.yaml", "stages:\n  - name: a\n    kind: theory.persson\n    params: *later\n");
    let (code, err, _) = s.run("p.yaml", &["--dry-run"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("p.yaml:4:") && err.contains("names no anchor"), "{err}");
}
