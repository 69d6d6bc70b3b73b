//! The SLURM executor against a real single-node cluster (`.ci/slurm/cluster.sh`, started
//! by `.ci/slurm/test.sh`, which `make test` runs when SLURM is installed and `.ci/run`
//! always). Without `SLURM_CONF` these tests say so and pass, unless
//! `REPRO_REQUIRE_SLURM` is set (as in CI), when they fail.

mod common;
use common::{column, snapshot, Scratch};
use std::time::{Duration, Instant};

fn cluster() -> bool {
    if std::env::var_os("SLURM_CONF").is_some() {
        return true;
    }
    if std::env::var_os("REPRO_REQUIRE_SLURM").is_some() {
        panic!("REPRO_REQUIRE_SLURM is set but SLURM_CONF is not: start a cluster with .ci/slurm/cluster.sh");
    }
    eprintln!("skipped: no SLURM cluster (SLURM_CONF unset); `make test` starts one when SLURM is installed");
    false
}

const SLURM: &[&str] = &["--executor", "slurm"];

/// Physics (a BEM sweep), a reader of it, an orchestrator test kind (read whole and row by
/// row) and a figure.
const PIPELINE: &str = r#"stages:
  - name: sliding
    kind: bem.sweep
    params: {lambda: 1, W: 1, k: 0.1, V0: [0.3, 1, 3], n: 80, half_length: 5}
  - name: sweep
    kind: util.sleep
    params: {x: [1, 2, 3], ms: 100}
  - name: after
    kind: util.sleep
    needs: [sweep, sliding]
    params: {x: 7}
  - name: per_x
    kind: util.sleep
    needs: [{stage: sweep, match: [x]}]
    params: {x: [1, 2]}
  - name: fig
    kind: figure
    needs: [sliding]
    params:
      title: "mu* on SLURM"
      x_label: "V0"
      y_label: "mu*"
      layers:
        - data: {from: sliding, x: V0, y: mu_star, label: "lambda = 1"}
"#;

/// A published table without its timing columns, as (name, values) pairs.
fn table_values(s: &Scratch, stage: &str) -> Vec<(String, String)> {
    let df = s.table(stage);
    df.columns()
        .iter()
        .filter(|c| !c.name().as_str().ends_with("_time_s"))
        .map(|c| (c.name().to_string(), format!("{:?}", c.as_materialized_series())))
        .collect()
}

#[test]
fn a_slurm_run_gives_the_tables_and_figures_of_a_local_run() {
    if !cluster() {
        return;
    }
    let local = Scratch::new("slurm-local");
    local.run_pipeline(PIPELINE);
    let s = Scratch::new("slurm-remote");
    s.write("p.yaml", PIPELINE);
    let (code, err, r) = s.run("p.yaml", SLURM);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(None, "computed"), 10, "{err}");
    for t in r.tasks() {
        assert!(t["ran_on"].as_str().is_some_and(|o| o.starts_with("SLURM job ")), "{t}");
    }
    for stage in ["sliding", "sweep", "after", "per_x"] {
        assert_eq!(table_values(&s, stage), table_values(&local, stage), "table {stage}");
    }
    assert!(column(&s.table("sliding"), "mu_star").iter().all(|m| m.is_finite() && *m > 0.0));
    assert_eq!(snapshot(&s.path("figures")), snapshot(&local.path("figures")), "figures identical");
    // Each `per_x` point read its own row of `sweep`.
    assert_eq!(column(&s.table("per_x"), "upstream_x"), vec![1.0, 2.0]);
    // One array per wave: the first wave's 6 tasks, then `after`, `per_x` and `fig`.
    let log = String::from_utf8(s.read("cache/slurm/submissions.log")).unwrap();
    assert_eq!(log.lines().count(), 2, "{log}");
    assert!(log.lines().next().unwrap().contains("tasks=6"), "{log}");
    // A rerun computes nothing and submits nothing.
    let (code, _, r) = s.run("p.yaml", SLURM);
    assert_eq!(code, 0);
    assert_eq!(r.count(None, "cached"), 10);
    assert_eq!(String::from_utf8(s.read("cache/slurm/submissions.log")).unwrap(), log);
}

#[test]
fn a_crashed_worker_is_resubmitted_and_a_failing_task_is_not() {
    if !cluster() {
        return;
    }
    let s = Scratch::new("slurm-crash");
    s.write(
        "p.yaml",
        r#"stages:
  - name: sweep
    kind: util.sleep
    params: {x: [1, 2, 3]}
  - name: bad
    kind: util.fail
    params: {message: "no such material"}
"#,
    );
    // Exactly one worker aborts (the first to reach task.start); its task is resubmitted.
    let mark = s.path("crashed-once");
    let mut cmd = s.command(&["run", "p.yaml", "--report", "report.json", "-q", "--executor", "slurm"]);
    cmd.env("REPRO_CRASH_AT", "task.start:1").env("REPRO_CRASH_MARK", &mark);
    let out = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "the util.fail task fails the run: {err}");
    assert!(mark.exists(), "a worker crashed");
    let r = common::Report(serde_json::from_slice(&s.read("report.json")).unwrap());
    let bad = r.task("bad", "");
    assert_eq!(bad["status"], "failed");
    assert!(bad["error"].as_str().unwrap().contains("no such material"), "{bad}");
    let computed = r.count(Some("sweep"), "computed");
    let retried: Vec<_> =
        r.tasks().into_iter().filter(|t| t["ran_on"].as_str().is_some_and(|o| o.contains("attempt 2"))).collect();
    // The crash hit either a sweep task (resubmitted, then computed) or the failing task
    // (resubmitted, then failed as a task: reported with its own error, not retried again).
    assert_eq!(computed, 3, "{err}");
    assert_eq!(retried.len(), 1, "one task ran twice: {err}");
    assert!(err.contains("ended without a result (attempt 1); resubmitting"), "{err}");
    let log = String::from_utf8(s.read("cache/slurm/submissions.log")).unwrap();
    assert_eq!(log.lines().filter(|l| l.contains("attempt=1")).count(), 1, "{log}");
    assert_eq!(log.lines().filter(|l| l.contains("attempt=2")).count(), 0, "{log}");
}

#[test]
fn a_worker_that_always_crashes_is_reported_with_its_stderr() {
    if !cluster() {
        return;
    }
    let s = Scratch::new("slurm-always");
    s.write("p.yaml", "stages:\n  - name: one\n    kind: util.sleep\n    params: {x: 1}\n");
    let mut cmd =
        s.command(&["run", "p.yaml", "--report", "report.json", "-q", "--executor", "slurm", "--retries", "1"]);
    cmd.env("REPRO_CRASH_AT", "task.start:1");
    let out = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let r = common::Report(serde_json::from_slice(&s.read("report.json")).unwrap());
    let e = r.task("one", "")["error"].as_str().unwrap().to_string();
    assert!(e.contains("ended without a result after 2 attempt(s)"), "{e}");
    assert!(e.contains("fault injection: crashing at task.start"), "the worker's stderr: {e}");
    assert!(!s.exists("cache/objects") || std::fs::read_dir(s.path("cache/objects")).unwrap().count() == 0);
}

#[test]
fn a_restarted_coordinator_waits_for_queued_work_instead_of_resubmitting_it() {
    if !cluster() {
        return;
    }
    let s = Scratch::new("slurm-restart");
    let yaml = "stages:\n  - name: sweep\n    kind: util.sleep\n    params: {x: [1, 2, 3, 4], ms: 1500}\n  - name: after\n    kind: util.sleep\n    needs: [sweep]\n    params: {x: 7}\n";
    s.write("p.yaml", yaml);
    let reference = Scratch::new("slurm-restart-ref");
    reference.run_pipeline(yaml);
    let mut first = s.spawn_run("p.yaml", &["--executor", "slurm", "--max-jobs", "2"]);
    // Killed once the first submission is logged: the log is created, then its line
    // written, so a kill between the two would hide a submission from the count below.
    let log = s.path("cache/slurm/submissions.log");
    let logged = || std::fs::read_to_string(&log).is_ok_and(|t| t.ends_with('\n'));
    let t0 = Instant::now();
    while !logged() && t0.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(logged(), "the first coordinator submitted");
    first.kill().unwrap(); // SIGKILL
    first.wait().unwrap();
    let (code, err, r) = s.run("p.yaml", SLURM);
    assert_eq!(code, 0, "{err}");
    let adopted = r
        .tasks()
        .into_iter()
        .filter(|t| t["ran_on"].as_str().is_some_and(|o| o.contains("adopted from an earlier coordinator")))
        .count();
    assert!(adopted >= 1, "the restarted coordinator waited for the queued tasks: {err}");
    assert!(err.contains("still queued or running on SLURM"), "{err}");
    let log = String::from_utf8(s.read("cache/slurm/submissions.log")).unwrap();
    let sweep_submitted: usize = log
        .lines()
        .filter(|l| !l.contains("tasks=1 "))
        .map(|l| l.split("tasks=").nth(1).unwrap().split(' ').next().unwrap().parse::<usize>().unwrap())
        .sum();
    assert_eq!(sweep_submitted, 4, "no sweep task submitted twice: {log}");
    assert_eq!(snapshot(&s.path("tables")).len(), 2);
    for stage in ["sweep", "after"] {
        assert_eq!(table_values(&s, stage), table_values(&reference, stage));
    }
}

/// The worker alone (no cluster needed): it recomputes a task from its specification, and
/// refuses a specification that does not hash to its key.
#[test]
fn the_worker_recomputes_a_task_from_its_spec_and_rejects_a_tampered_one() {
    use repro::pipeline::cache::{Cache, LockMode};
    use repro::pipeline::slurm::{failure_path, spec_path, TaskSpec};
    let s = Scratch::new("worker-alone");
    s.run_pipeline(&common::sleep_pipeline("[1, 2]", 0, "t"));
    let r = common::Report(serde_json::from_slice(&s.read("report.json")).unwrap());
    let key = r.task("after", "")["key"].as_str().unwrap().to_string();
    let inputs: Vec<String> =
        ["x=1", "x=2"].iter().map(|p| r.task("sweep", p)["key"].as_str().unwrap().to_string()).collect();
    let cache = Cache::open(&s.path("cache"), LockMode::Wait).unwrap();
    let entry = cache.get(&key).unwrap();
    let spec = TaskSpec {
        key: key.clone(),
        kind: "util.sleep".into(),
        version: entry.version,
        params: entry.params.clone(),
        inputs: vec![("sweep".into(), inputs)],
        time_limit_s: 600.0,
    };
    std::fs::create_dir_all(spec_path(&cache, &key).parent().unwrap()).unwrap();
    std::fs::create_dir_all(failure_path(&cache, &key).parent().unwrap()).unwrap();
    std::fs::write(spec_path(&cache, &key), serde_json::to_vec(&spec).unwrap()).unwrap();
    s.write("list.txt", &format!("{key}\n"));
    let entry_file = cache.entry_path(&key);
    drop(cache);
    std::fs::remove_file(&entry_file).unwrap();
    let worker = |s: &Scratch| s.repro(&["worker", "--cache", "cache", "--list", "list.txt", "--index", "0"]);
    let out = worker(&s);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let cache = Cache::open(&s.path("cache"), LockMode::Wait).unwrap();
    assert_eq!(cache.get(&key).unwrap().output, entry.output, "the worker's result is the local one");
    // Tampered parameters: the spec no longer hashes to the key; nothing is stored.
    std::fs::remove_file(&entry_file).unwrap();
    let mut bad = spec.clone();
    bad.params["x"] = serde_json::json!(8);
    std::fs::write(spec_path(&cache, &key), serde_json::to_vec(&bad).unwrap()).unwrap();
    drop(cache);
    let out = worker(&s);
    assert_eq!(out.status.code(), Some(1));
    let failure = String::from_utf8(s.read(&format!("cache/slurm/failed/{key}.json"))).unwrap();
    assert!(failure.contains("does not hash to its key"), "{failure}");
    assert!(!entry_file.exists(), "no result planted under the key");
    // A list line that is not a key, and a missing line, are errors that say so.
    s.write("list.txt", "../../etc/passwd\n");
    let out = worker(&s);
    assert!(String::from_utf8_lossy(&out.stderr).contains("line 1 is not a task key"));
    let out = s.repro(&["worker", "--cache", "cache", "--list", "list.txt", "--index", "5"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("no line 5"));
}
