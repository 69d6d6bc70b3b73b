//! Fault injection: the run is aborted (SIGABRT, no clean-up, like SIGKILL) at every
//! atomic write and every task start in turn, then rerun; a full disk and a read-only
//! cache. Each time: nothing lost, no corrupted entry used, the final outputs identical to
//! an undisturbed run.

mod common;
use common::{sleep_pipeline, snapshot, snapshot_untimed, Scratch};
use std::path::Path;
use std::process::Command;

/// How many times a run of `yaml` reaches each fault point (from a clean cache).
const POINTS: &[(&str, usize)] = &[("task.start", 5), ("atomic.before_rename", 15), ("atomic.after_rename", 15)];

/// Every published file with its bytes (figures, then tables: their contents but the task
/// wall times).
type Snapshot = Vec<(String, Vec<u8>)>;

fn outputs(s: &Scratch) -> (Snapshot, Snapshot) {
    (snapshot(&s.path("figures")), snapshot_untimed(&s.path("tables")))
}

#[test]
fn a_run_aborted_at_any_write_resumes_to_the_same_outputs() {
    let yaml = sleep_pipeline("[1, 2, 3]", 0, "t");
    let reference = Scratch::new("faults-ref");
    reference.run_pipeline(&yaml);
    let expected = outputs(&reference);
    let mut crashes = 0;
    for &(point, count) in POINTS {
        // One past the count: the run is not interrupted (checks the counts above).
        for n in 1..=count + 1 {
            let s = Scratch::new(&format!("faults-{point}-{n}"));
            s.write("p.yaml", &yaml);
            let out = s
                .command(&["run", "p.yaml", "-q", "--jobs", "1"])
                .env("REPRO_CRASH_AT", format!("{point}:{n}"))
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&out.stderr);
            if n <= count {
                assert!(out.status.code().is_none(), "{point} #{n}: aborted by a signal: {err}");
                assert!(err.contains(&format!("crashing at {point} #{n}")), "{err}");
                crashes += 1;
            } else {
                assert_eq!(out.status.code(), Some(0), "{point} is reached {count} times: {err}");
            }
            let (code, err, r) = s.run("p.yaml", &[]);
            assert_eq!(code, 0, "{point} #{n}: {err}");
            assert!(!err.contains("corrupted"), "{point} #{n}: no torn entry was ever visible: {err}");
            assert_eq!(r.count(None, "failed"), 0);
            assert_eq!(outputs(&s), expected, "{point} #{n}: outputs identical to an undisturbed run");
            assert_eq!(std::fs::read_dir(s.path("cache/tmp")).unwrap().count(), 0, "no temporaries left");
            let (_, _, r) = s.run("p.yaml", &[]);
            assert_eq!(r.count(None, "computed"), 0, "{point} #{n}: every entry sound");
        }
    }
    assert_eq!(crashes, 35);
}

/// A tmpfs of `size` mounted at `dir` (root only), unmounted when dropped.
struct Mount(std::path::PathBuf);

impl Mount {
    fn tmpfs(dir: &Path, size: &str) -> Option<Mount> {
        std::fs::create_dir_all(dir).unwrap();
        let ok = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(dir)
            .output()
            .is_ok_and(|o| o.status.success());
        if !ok {
            if std::env::var_os("REPRO_REQUIRE_SLURM").is_some() {
                panic!("CI runs as root and must be able to mount a tmpfs");
            }
            eprintln!("skipped: cannot mount a tmpfs here (needs root)");
            return None;
        }
        Some(Mount(dir.to_path_buf()))
    }

    fn remount(&self, opts: &str) {
        let st = Command::new("mount").args(["-o", &format!("remount,{opts}")]).arg(&self.0).status().unwrap();
        assert!(st.success(), "remount {opts}");
    }
}

impl Drop for Mount {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

#[test]
fn a_full_disk_fails_clearly_and_leaves_the_cache_consistent() {
    let yaml = sleep_pipeline("{linspace: [1, 40, 40]}", 0, "t");
    let reference = Scratch::new("full-ref");
    reference.run_pipeline(&yaml);
    let s = Scratch::new("full");
    s.write("p.yaml", &yaml);
    // Room for the lock and a few entries (about 1 kB each, 4 kB blocks), not for 42.
    let Some(disk) = Mount::tmpfs(&s.path("cache"), "48k") else { return };
    let (code, err, r) = s.run("p.yaml", &["--jobs", "1"]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("No space left on device"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    // The run report is written (here outside the full disk), and names every task whose
    // entry could not be stored, and what else could not be written.
    let failed: Vec<_> = r.tasks().into_iter().filter(|t| t["status"] == "failed").collect();
    assert!(!failed.is_empty(), "{err}");
    for t in &failed {
        let e = t["error"].as_str().unwrap();
        assert!(e.contains("writing the cache entry") && e.contains("No space left on device"), "{e}");
    }
    assert_eq!(failed.len() + r.count(Some("sweep"), "computed") + r.count(None, "skipped"), r.tasks().len());
    let errors: Vec<&str> =
        r.0["errors"].as_array().map_or(Vec::new(), |a| a.iter().filter_map(|e| e.as_str()).collect());
    assert!(errors.iter().all(|e| e.contains("No space left on device")), "{errors:?}");
    // Room again: the rerun uses what was written, and nothing it finds is torn.
    disk.remount("size=4m");
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("corrupted"), "{err}");
    assert!(r.count(Some("sweep"), "cached") >= 1, "entries written before the disk filled are kept");
    assert_eq!(outputs(&s), outputs(&reference));
}

#[test]
fn a_read_only_cache_is_a_clear_error_and_is_left_untouched() {
    let yaml = sleep_pipeline("[1, 2]", 0, "t");
    let s = Scratch::new("readonly");
    s.write("p.yaml", &yaml);
    let Some(disk) = Mount::tmpfs(&s.path("cache"), "1m") else { return };
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    let before = snapshot(&s.path("cache"));
    disk.remount("ro");
    s.write("p.yaml", &sleep_pipeline("[1, 2, 3]", 0, "t"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 4, "{err}");
    assert!(err.contains("Read-only file system") && err.contains("cache"), "{err}");
    // Status still reads it.
    let out = s.repro(&["status", "p.yaml"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && text.contains("1 would compute"), "{text}");
    disk.remount("rw");
    assert_eq!(snapshot(&s.path("cache")), before, "nothing in the cache changed");
}

#[test]
fn a_cache_disk_full_before_the_run_still_gives_a_run_report_and_the_report_names_its_file() {
    let yaml = sleep_pipeline("[1, 2]", 0, "t");
    let s = Scratch::new("full-start");
    s.write("p.yaml", &yaml);
    let Some(disk) = Mount::tmpfs(&s.path("cache"), "48k") else { return };
    // The disk full before the run opens the cache: it stopped at its `lock.info` with no
    // report; now each task that cannot store its entry is recorded, and the report is
    // written beside.
    // As much as fits: the write stops at the full disk.
    let _ = std::fs::write(s.path("cache/fill"), "x".repeat(64 * 1024));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("No space left on device"), "{err}");
    assert!(r.0.is_object(), "a run report is written: {err}");
    let failed: Vec<_> = r.tasks().into_iter().filter(|t| t["status"] == "failed").collect();
    assert!(!failed.is_empty(), "{err}");
    assert!(failed.iter().all(|t| t["error"].as_str().unwrap().contains("No space left on device")));
    drop(disk);
    // A report on a full disk is named, with the cause.
    let Some(_full) = Mount::tmpfs(&s.path("full"), "16k") else { return };
    let _ = std::fs::write(s.path("full/fill"), "x".repeat(64 * 1024));
    let out = s.repro(&["run", "p.yaml", "-q", "--report", "full/r.json"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_ne!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("writing the run report full/r.json: No space left on device"), "{err}");
}
