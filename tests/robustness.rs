//! Faults: corrupted cache entries, a killed run, two runs on one cache, garbage
//! collection.

mod common;
use common::{sleep_pipeline, snapshot, snapshot_untimed, Scratch};
use std::time::{Duration, Instant};

fn entry_files(s: &Scratch) -> Vec<std::path::PathBuf> {
    let mut v = Vec::new();
    for d in std::fs::read_dir(s.path("cache/objects")).unwrap().flatten() {
        for f in std::fs::read_dir(d.path()).unwrap().flatten() {
            v.push(f.path());
        }
    }
    v.sort();
    v
}

#[test]
fn corrupted_or_truncated_entries_are_reported_and_recomputed() {
    let s = Scratch::new("corrupt");
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 0, "t"));
    s.run("p.yaml", &[]);
    let figures = snapshot(&s.path("figures"));
    let files = entry_files(&s);
    assert_eq!(files.len(), 5);
    // Truncate one entry, flip a byte in another's body, empty a third.
    let bytes = std::fs::read(&files[0]).unwrap();
    std::fs::write(&files[0], &bytes[..bytes.len() / 2]).unwrap();
    let mut bytes = std::fs::read(&files[1]).unwrap();
    let n = bytes.len();
    bytes[n - 10] ^= 0x01;
    std::fs::write(&files[1], &bytes).unwrap();
    std::fs::write(&files[2], b"").unwrap();
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    let corrupted: Vec<_> = r.tasks().into_iter().filter(|t| t["reason"]["why"] == "corrupted").collect();
    assert_eq!(corrupted.len(), 3, "{:?}", r.0);
    assert_eq!(err.matches("is corrupted").count(), 3, "{err}");
    assert_eq!(snapshot(&s.path("figures")), figures, "same outputs after recomputation");
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(None, "computed"), 0, "the recomputed entries are sound");
}

/// `cmd` run to its end, or killed (and the test failed) after `limit`.
fn bounded(mut cmd: std::process::Command, limit: Duration) -> std::process::Output {
    let child = cmd.stdout(std::process::Stdio::piped()).stderr(std::process::Stdio::piped()).spawn().unwrap();
    let pid = child.id();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(child.wait_with_output());
    });
    match rx.recv_timeout(limit) {
        Ok(out) => out.unwrap(),
        Err(_) => {
            let _ = std::process::Command::new("kill").args(["-9", &pid.to_string()]).status();
            panic!("still running after {limit:?}: blocked on a special file");
        }
    }
}

#[test]
fn a_fifo_standing_for_an_entry_a_manifest_or_an_output_blocks_nothing() {
    // A FIFO's `open` for reading waits for a writer: in place of a cache entry, a stage's
    // manifest or a published table it blocked `repro run`, `status` and `gc --dry-run`
    // forever. Now each is read as what it is not (a regular file), and the run recomputes,
    // rewrites and republishes, moving the FIFO aside.
    let s = Scratch::new("fifo");
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 0, "t"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    let figures = snapshot(&s.path("figures"));
    let tables = snapshot_untimed(&s.path("tables"));
    let entry = entry_files(&s)[0].clone();
    let manifest =
        std::fs::read_dir(s.path("cache/manifests")).unwrap().next().unwrap().unwrap().path().join("sweep.json");
    let table = s.path("tables/sweep.parquet");
    for path in [&entry, &manifest, &table] {
        std::fs::remove_file(path).unwrap();
        let ok = std::process::Command::new("mkfifo").arg(path).status().unwrap().success();
        assert!(ok, "mkfifo {}", path.display());
    }
    let limit = Duration::from_secs(60);
    let out = bounded(s.command(&["status", "p.yaml"]), limit);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = bounded(s.command(&["gc", "--dry-run"]), limit);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = bounded(s.command(&["run", "p.yaml", "-q"]), limit);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("moved aside"), "{err}");
    assert_eq!(snapshot(&s.path("figures")), figures);
    assert_eq!(snapshot_untimed(&s.path("tables")), tables);
    for path in [&entry, &manifest, &table] {
        assert!(std::fs::metadata(path).unwrap().is_file(), "{} is a file again", path.display());
    }
}

#[test]
fn a_directory_standing_for_an_entry_or_an_output_is_moved_aside_and_the_damage_heals() {
    // A directory where a cache entry and where a published table belong (with a file in
    // each, which must survive): the next run recomputes the entry, publishes the table, says
    // where it moved each, and exits 0; the run after it is all cached.
    let s = Scratch::new("dir-damage");
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 0, "t"));
    s.run("p.yaml", &[]);
    let figures = snapshot(&s.path("figures"));
    let entry = entry_files(&s)[0].clone();
    let table = s.path("tables/sweep.parquet");
    for path in [&entry, &table] {
        std::fs::remove_file(path).unwrap();
        std::fs::create_dir(path).unwrap();
        std::fs::write(path.join("keep"), b"user data").unwrap();
    }
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(err.matches("was a directory; moved aside to").count(), 2, "{err}");
    assert!(entry.is_file() && table.is_file());
    assert_eq!(r.count(None, "failed"), 0);
    assert_eq!(snapshot(&s.path("figures")), figures);
    let dir = |p: &std::path::Path| -> Vec<std::path::PathBuf> {
        std::fs::read_dir(p.parent().unwrap()).unwrap().flatten().map(|e| e.path()).collect()
    };
    for path in [&entry, &table] {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let aside: Vec<_> = dir(path)
            .into_iter()
            .filter(|p| p.file_name().unwrap().to_string_lossy().starts_with(&format!("{name}.damaged-")))
            .collect();
        assert_eq!(aside.len(), 1, "{aside:?}");
        assert_eq!(std::fs::read(aside[0].join("keep")).unwrap(), b"user data");
    }
    let (code, _, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0);
    assert_eq!(r.count(None, "computed"), 0, "healed: nothing to recompute");
}

#[test]
fn a_killed_run_resumes_and_ends_with_the_same_outputs() {
    let s = Scratch::new("killed");
    let yaml = sleep_pipeline("{linspace: [1, 24, 24]}", 150, "t");
    s.write("p.yaml", &yaml);
    // Reference: an uninterrupted run in another directory.
    let reference = Scratch::new("killed-ref");
    reference.write("p.yaml", &yaml);
    assert_eq!(reference.run("p.yaml", &["--jobs", "2"]).0, 0);
    // Kill once some tasks are done (24 tasks x 150 ms on 2 workers take about 1.8 s).
    let mut child = s.spawn_run("p.yaml", &["--jobs", "2"]);
    let t0 = Instant::now();
    loop {
        std::thread::sleep(Duration::from_millis(50));
        let done = s.path("cache/objects").exists() && entry_files(&s).len() >= 4;
        if done || t0.elapsed() > Duration::from_secs(20) {
            break;
        }
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let partial = entry_files(&s).len();
    assert!((1..24).contains(&partial), "killed mid-run: {partial} entries");
    let (code, err, r) = s.run("p.yaml", &["--jobs", "2"]);
    assert_eq!(code, 0, "{err}");
    let cached = r.count(Some("sweep"), "cached");
    assert!(cached >= partial - 1 && cached < 24, "resumed: {cached} cached of 24");
    assert_eq!(r.count(Some("sweep"), "cached") + r.count(Some("sweep"), "computed"), 24);
    assert_eq!(snapshot(&s.path("figures")), snapshot(&reference.path("figures")));
    assert_eq!(snapshot_untimed(&s.path("tables")), snapshot_untimed(&reference.path("tables")));
    let leftovers = std::fs::read_dir(s.path("cache/tmp")).unwrap().count();
    assert_eq!(leftovers, 0, "no temporary files remain");
}

#[test]
fn a_second_repro_on_the_same_cache_refuses_or_waits() {
    let s = Scratch::new("concurrent");
    s.write("slow.yaml", &sleep_pipeline("[1, 2, 3, 4]", 400, "t"));
    s.write("fast.yaml", &sleep_pipeline("[5]", 0, "u"));
    let mut first = s.spawn_run("slow.yaml", &["--jobs", "1"]);
    // Wait until the first run holds the lock (it writes lock.info when it has it).
    let t0 = Instant::now();
    while !s.path("cache/lock.info").exists() && t0.elapsed() < Duration::from_secs(10) {
        std::thread::sleep(Duration::from_millis(20));
    }
    let (code, err, _) = s.run("fast.yaml", &["--no-wait"]);
    assert_eq!(code, 3, "{err}");
    assert!(err.contains("is in use by another repro (pid"), "{err}");
    // Deleting the lock file from under the first run does not let a second one in: the
    // cache directory itself is locked too.
    std::fs::remove_file(s.path("cache/lock")).unwrap();
    let (code, err, _) = s.run("fast.yaml", &["--no-wait"]);
    assert_eq!(code, 3, "{err}");
    // Without --no-wait the second run waits for the first, then runs.
    let t1 = Instant::now();
    let (code, err, r) = s.run("fast.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("waiting for it to finish"), "{err}");
    assert!(t1.elapsed() > Duration::from_millis(300), "it waited");
    assert_eq!(r.count(Some("sweep"), "computed"), 1);
    assert!(first.wait().unwrap().success());
}

#[test]
fn gc_removes_only_entries_nothing_refers_to() {
    let s = Scratch::new("gc");
    s.write("pipelines/a.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    s.run("pipelines/a.yaml", &[]);
    s.write("pipelines/a.yaml", &sleep_pipeline("[1, 3]", 0, "t"));
    s.run("pipelines/a.yaml", &[]);
    // 4 entries from the first run, 3 new ones from the second (x=3, after, fig).
    // The pipeline needs x=1, x=3 and the new after and fig; the first run's x=2, after and
    // fig are referred to by the recorded first run only.
    let before = entry_files(&s).len();
    assert_eq!(before, 7);
    let out = s.repro(&["gc"]);
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{text}");
    assert!(
        text.contains("kept 7 entries") && text.contains("2 recorded run(s)") && text.contains("removed 0"),
        "{text}"
    );
    // A dry run with an age: lists the three, removes nothing.
    let out = s.repro(&["gc", "--older-than", "0", "--dry-run"]);
    let (stdout, text) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{text}");
    assert_eq!(stdout.lines().filter(|l| l.starts_with("would remove ")).count(), 3, "{stdout}");
    // Each named by the stage, point and pipeline of the run that had it (x=2 of the sweep,
    // the first run's `after` and `fig`).
    assert!(stdout.contains("stage `sweep` [x=2] of pipelines/a.yaml"), "{stdout}");
    assert!(stdout.contains("stage `after`") && stdout.contains("stage `fig`"), "{stdout}");
    assert!(text.contains("kept 4 entries") && text.contains("would remove 3"), "{text}");
    assert_eq!(entry_files(&s).len(), 7);
    // Told to forget the recorded runs: the three go.
    let out = s.repro(&["gc", "--older-than", "0"]);
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(text.contains("kept 4 entries") && text.contains("removed 3"), "{text}");
    let (_, _, r) = s.run("pipelines/a.yaml", &[]);
    assert_eq!(r.count(None, "computed"), 0, "gc kept everything the pipeline needs");
}

#[test]
fn gc_waits_for_a_running_run_and_keeps_its_work() {
    // A run of a pipeline outside pipelines/ is storing its entries when gc starts: gc takes
    // the cache lock before it reads what to keep, so it waits for the run, whose record
    // then keeps every entry it stored.
    let s = Scratch::new("gc-race");
    s.write("elsewhere/d.yaml", &sleep_pipeline("[1, 2, 3, 4]", 300, "d"));
    let mut run = s.spawn_run("elsewhere/d.yaml", &["--jobs", "1"]);
    let t0 = Instant::now();
    while !s.path("cache/lock.info").exists() && t0.elapsed() < Duration::from_secs(10) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(400));
    let out = s.repro(&["gc"]);
    let text = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(run.wait().unwrap().success());
    assert!(out.status.success() && text.contains("removed 0") && text.contains("1 recorded run(s)"), "{text}");
    let (code, err, r) = s.run("elsewhere/d.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(None, "computed"), 0, "the run's entries survived gc");
}

#[test]
fn gc_keeps_the_work_of_a_pipeline_outside_pipelines() {
    // A user's own pipeline file elsewhere filled the cache; `repro gc` run where
    // pipelines/ holds another file must not remove that work without being told.
    let s = Scratch::new("gc-outside");
    s.write("mine/study.yaml", &sleep_pipeline("[5, 6, 7]", 0, "mine"));
    s.run("mine/study.yaml", &[]);
    s.write("pipelines/a.yaml", &sleep_pipeline("[1]", 0, "t"));
    s.run("pipelines/a.yaml", &[]);
    let before = entry_files(&s).len();
    let out = s.repro(&["gc"]);
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && text.contains("removed 0"), "{text}");
    assert_eq!(entry_files(&s).len(), before);
    // Even when the file is gone: the recorded run keeps its entries.
    std::fs::remove_file(s.path("mine/study.yaml")).unwrap();
    let out = s.repro(&["gc"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("removed 0"));
    assert_eq!(entry_files(&s).len(), before);
    // The history lists both runs, oldest first.
    let out = s.repro(&["runs"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 2, "{stdout}");
    assert!(lines[0].contains("mine/study.yaml") && lines[0].contains("5 computed"), "{stdout}");
    assert!(lines[1].contains("pipelines/a.yaml") && lines[1].contains(" UTC "), "{stdout}");
}

#[test]
fn temporaries_left_in_output_directories_are_removed() {
    let s = Scratch::new("tmp-outputs");
    s.write("p.yaml", &sleep_pipeline("[1]", 0, "t"));
    // A process id above Linux's limit (2^22) is of no running process: provably stale.
    s.write("figures/.repro-4999999-0.tmp", "half a figure");
    s.write("tables/.repro-4999999-1.tmp", "half a table");
    // This test's own process runs: its temporary is another run's, in flight.
    let live = format!("tables/.repro-{}-7.tmp", std::process::id());
    s.write(&live, "another run publishing");
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(!s.exists("figures/.repro-4999999-0.tmp") && !s.exists("tables/.repro-4999999-1.tmp"));
    assert!(s.exists(&live), "a running process's temporary is left alone");
}

#[test]
fn the_cache_never_writes_through_a_link_it_did_not_create() {
    // runs/, manifests/, an object shard and lock.info replaced by links to a folder (or file)
    // outside the cache: the run writes nothing there and leaves the link's target as it was.
    let s = Scratch::new("cache-links");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    assert_eq!(s.run("p.yaml", &[]).0, 0);
    let outside = s.path("outside");
    std::fs::create_dir_all(&outside).unwrap();
    s.write("outside/precious.txt", "mine");
    let shard = std::fs::read_dir(s.path("cache/objects")).unwrap().next().unwrap().unwrap().path();
    for p in [s.path("cache/runs"), s.path("cache/manifests"), shard.clone()] {
        std::fs::remove_dir_all(&p).unwrap();
        std::os::unix::fs::symlink(&outside, &p).unwrap();
    }
    std::fs::remove_file(s.path("cache/lock.info")).unwrap();
    std::os::unix::fs::symlink(s.path("outside/precious.txt"), s.path("cache/lock.info")).unwrap();
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 0, "t"));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("is a symbolic link the cache did not create"), "{err}");
    let names: Vec<String> =
        std::fs::read_dir(&outside).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().to_string()).collect();
    assert_eq!(names, ["precious.txt"], "nothing written outside the cache");
    assert_eq!(std::fs::read_to_string(s.path("outside/precious.txt")).unwrap(), "mine");
    for p in [s.path("cache/runs"), s.path("cache/manifests"), s.path("cache/lock.info")] {
        assert!(!std::fs::symlink_metadata(&p).unwrap().file_type().is_symlink(), "{}", p.display());
    }
    // The entries that were behind the shard's link are recomputed; the rest come from the cache.
    assert!(r.count(None, "computed") >= 1);
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(None, "computed"), 0);
}

#[test]
fn a_task_past_its_time_limit_is_recorded_as_timed_out_and_the_others_carry_on() {
    // A stage's `time_limit` stops its task at the next checkpoint (util.sleep checks every
    // 10 ms, the solvers at each Newton iteration); the run goes on and writes its report.
    let s = Scratch::new("time-limit");
    let pipeline = |limit: &str| {
        format!(
            "stages:\n  - name: slow\n    kind: util.sleep\n{limit}    params: {{x: 1, ms: 600000}}\n  - name: quick\n    kind: util.sleep\n    params: {{x: [1, 2], ms: 10}}\n"
        )
    };
    s.write("p.yaml", &pipeline("    time_limit: 0.5\n"));
    let t0 = Instant::now();
    let (code, err, report) = s.run("p.yaml", &[]);
    assert!(t0.elapsed() < Duration::from_secs(60), "{:?}", t0.elapsed());
    assert_eq!(code, 1, "{err}");
    let tasks = report.tasks();
    let slow: Vec<_> = tasks.iter().filter(|t| t["stage"] == "slow").collect();
    assert_eq!(slow.len(), 1);
    assert_eq!(slow[0]["status"], "failed");
    let error = slow[0]["error"].as_str().unwrap();
    assert!(error.starts_with("timed out: past its time limit of 0.5 s"), "{error}");
    assert!(slow[0]["wall_time_s"].as_f64().unwrap() < 30.0);
    assert_eq!(tasks.iter().filter(|t| t["stage"] == "quick" && t["status"] == "computed").count(), 2);
    // The command line's limit is over the stage's and the kind's.
    s.write("p.yaml", &pipeline(""));
    let (code, _, report) = s.run("p.yaml", &["--time-limit", "0.5"]);
    assert_eq!(code, 1);
    let slow = report.tasks().into_iter().find(|t| t["stage"] == "slow").unwrap().clone();
    assert!(slow["error"].as_str().unwrap().starts_with("timed out"), "{slow}");
    let out = s.repro(&["run", "p.yaml", "--time-limit", "0"]);
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    // A wrong `time_limit` is a located error.
    s.write("p.yaml", &pipeline("    time_limit: -3\n"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 2);
    assert!(err.contains("p.yaml:4:") && err.contains("`time_limit` must be a positive number of seconds"), "{err}");
}

#[test]
fn a_boundary_element_point_that_would_run_for_minutes_stops_at_its_time_limit() {
    // lambda = 1e6 runs for about 256 s; its Newton iterations are checkpoints.
    let s = Scratch::new("time-limit-bem");
    s.write(
        "p.yaml",
        "stages:\n  - name: hard\n    kind: bem.sweep\n    time_limit: 2\n    params: {lambda: 1000000, W: 1, k: 0.1, V0: 1}\n",
    );
    let t0 = Instant::now();
    let (code, _, report) = s.run("p.yaml", &[]);
    assert!(t0.elapsed() < Duration::from_secs(30), "{:?}", t0.elapsed());
    assert_eq!(code, 1);
    let hard = report.tasks()[0].clone();
    assert!(hard["error"].as_str().unwrap().starts_with("timed out: past its time limit of 2 s"), "{hard}");
}

#[test]
fn a_task_that_would_need_more_memory_than_there_is_is_not_started_and_the_others_run() {
    // bem.sweep on 32000 elements may hold a dense LU of 32000^2 values (8.2 GB, with the
    // nested one 10.3 GB): refused before it allocates when 1 GB is available; the small
    // point runs.
    let s = Scratch::new("memory");
    let big = refused_beside_a_small_stage(&s, "bem.sweep", "{lambda: 1, W: 1, k: 0.1, V0: 1, n: 32000}", "1e9");
    let needed = big["failure"]["needed_bytes"].as_u64().unwrap();
    assert!((10.2e9..10.3e9).contains(&(needed as f64)), "{needed}");
    let error = big["error"].as_str().unwrap();
    assert!(error.starts_with("not started: it may need 10.3 GB of memory, 1.0 GB is available"), "{error}");
}

/// Runs a pipeline of the stage `big` (`kind`, `params`) beside a small one with
/// `REPRO_MEMORY_BYTES` = `memory`: the run exits 1, `big` is refused as `resources` before
/// it runs, the small one computes. `big`'s record.
fn refused_beside_a_small_stage(s: &Scratch, kind: &str, params: &str, memory: &str) -> serde_json::Value {
    s.write(
        "p.yaml",
        &format!(
            "stages:\n  - name: big\n    kind: {kind}\n    params: {params}\n  - name: small\n    kind: util.sleep\n    params: {{x: 1}}\n"
        ),
    );
    let out = s
        .command(&["run", "p.yaml", "-q", "--report", "report.json"])
        .env("REPRO_MEMORY_BYTES", memory)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value = serde_json::from_slice(&s.read("report.json")).unwrap();
    let tasks = report["tasks"].as_array().unwrap();
    let big = tasks.iter().find(|t| t["stage"] == "big").unwrap().clone();
    assert_eq!(big["failure"]["kind"], "resources", "{big}");
    assert!(big["wall_time_s"].as_f64().unwrap() < 0.1, "refused before it ran: {big}");
    let small = tasks.iter().find(|t| t["stage"] == "small").unwrap();
    assert_eq!(small["status"], "computed");
    big
}

#[test]
fn a_shell_cycle_that_no_memory_holds_is_refused_before_it_allocates() {
    // Every parameter within its range (20000 x 16 elements, 1e5 steps), the cycle's kept
    // states and band factors need about 5.6 TB (`fem::mesh::cycle_memory_bound`: 2e6
    // dofs, 3e5 states of 18.6 MB): refused by `repro point` and by `repro run`, where the
    // other stage runs. Before the shell kinds had an estimate, both started and allocated.
    let s = Scratch::new("shell-memory");
    let shell = "{R: 15, h: 1, n_meridian: 20000, n_thickness: 16}";
    let shell_arg = format!("shell={shell}");
    let out = s
        .command(&["point", "fem.indent", &shell_arg, "delta_max=0.5", "steps=100000"])
        .env("REPRO_MEMORY_BYTES", "4e9")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("not started: it may need 5590.8 GB of memory, 4.0 GB is available"), "{err}");
    let big = refused_beside_a_small_stage(
        &s,
        "fem.indent",
        &format!("{{shell: {shell}, delta_max: 0.5, steps: 100000}}"),
        "4e9",
    );
    let needed = big["failure"]["needed_bytes"].as_u64().unwrap() as f64;
    assert!((5.5e12..5.7e12).contains(&needed), "{needed}");
}

#[test]
fn a_directory_in_place_of_the_lock_is_moved_aside_and_a_file_in_place_of_the_figures_folder_is_named() {
    // The lock replaced by a directory failed every run as "the cache is not writable";
    // now it is moved aside (kept) and the run goes on.
    let s = Scratch::new("lock-dir");
    s.write("p.yaml", &sleep_pipeline("[1, 2]", 0, "t"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    std::fs::remove_file(s.path("cache/lock")).unwrap();
    std::fs::create_dir(s.path("cache/lock")).unwrap();
    std::fs::write(s.path("cache/lock/keep"), "a user's file").unwrap();
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("cache/lock was a directory; moved aside to cache/lock.damaged-"), "{err}");
    assert_eq!(r.count(None, "cached"), r.tasks().len(), "every entry still used");
    let aside = std::fs::read_dir(s.path("cache"))
        .unwrap()
        .flatten()
        .find(|e| e.file_name().to_string_lossy().starts_with("lock.damaged-"));
    assert!(aside.is_some_and(|e| e.path().join("keep").is_file()), "nothing deleted");
    // A file where the figures folder should be: the error names both, the run goes on to
    // publish the tables, and the file is left alone (outputs are the user's).
    s.write("figs", "a user's file");
    let (code, err, _) = s.run("p.yaml", &["--figures", "figs/sub"]);
    assert_eq!(code, 4, "{err}");
    assert!(err.contains("publishing: cannot write figs/sub/fig.parquet: figs is a file, not a folder"), "{err}");
    assert_eq!(std::fs::read_to_string(s.path("figs")).unwrap(), "a user's file");
    assert!(s.path("tables/sweep.parquet").is_file());
}
