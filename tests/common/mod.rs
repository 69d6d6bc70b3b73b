//! Helpers for the integration tests: a scratch directory per test, pipeline files, and
//! runs of the `repro` binary whose JSON run report the tests read.
#![allow(dead_code)]

use polars::prelude::{DataFrame, DataType};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};

pub struct Scratch {
    pub dir: PathBuf,
}

/// A numeric column (integers cast to f64) of a published table.
pub fn column(df: &DataFrame, name: &str) -> Vec<f64> {
    let c = df.column(name).unwrap().cast(&DataType::Float64).unwrap();
    c.f64().unwrap().into_no_null_iter().collect()
}

/// A string column of a published table.
pub fn strings(df: &DataFrame, name: &str) -> Vec<String> {
    df.column(name).unwrap().str().unwrap().iter().map(|s| s.unwrap_or_default().to_string()).collect()
}

impl Scratch {
    pub fn new(name: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("repro-test-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch { dir }
    }

    pub fn path(&self, rel: &str) -> PathBuf {
        self.dir.join(rel)
    }

    pub fn write(&self, rel: &str, text: &str) -> PathBuf {
        let p = self.path(rel);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(&p, text).unwrap();
        p
    }

    pub fn command(&self, args: &[&str]) -> Command {
        let mut c = Command::new(env!("CARGO_BIN_EXE_repro"));
        c.current_dir(&self.dir).args(args);
        c
    }

    /// Runs `repro` with `args` and returns its output.
    pub fn repro(&self, args: &[&str]) -> Output {
        self.command(args).output().unwrap()
    }

    /// `repro run PIPELINE --report report.json -q ARGS`; returns (exit code, stderr, report).
    pub fn run(&self, pipeline: &str, extra: &[&str]) -> (i32, String, Report) {
        let _ = std::fs::remove_file(self.path("report.json"));
        let mut args = vec!["run", pipeline, "--report", "report.json", "-q"];
        args.extend_from_slice(extra);
        let out = self.repro(&args);
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        let report = std::fs::read(self.path("report.json"))
            .map(|b| Report(serde_json::from_slice(&b).unwrap()))
            .unwrap_or(Report(Value::Null));
        (out.status.code().unwrap_or(-1), stderr, report)
    }

    pub fn spawn_run(&self, pipeline: &str, extra: &[&str]) -> Child {
        let mut args = vec!["run", pipeline, "-q"];
        args.extend_from_slice(extra);
        self.command(&args).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().unwrap()
    }

    /// Writes `yaml` as p.yaml and runs it, which must succeed.
    pub fn run_pipeline(&self, yaml: &str) {
        self.write("p.yaml", yaml);
        let (code, err, _) = self.run("p.yaml", &[]);
        assert_eq!(code, 0, "{err}");
    }

    /// A stage's published table.
    pub fn table(&self, stage: &str) -> DataFrame {
        repro::pipeline::table::read_parquet(&self.path(&format!("tables/{stage}.parquet"))).unwrap()
    }

    pub fn read(&self, rel: &str) -> Vec<u8> {
        std::fs::read(self.path(rel)).unwrap_or_else(|e| panic!("reading {rel}: {e}"))
    }

    pub fn exists(&self, rel: &str) -> bool {
        self.path(rel).exists()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.dir);
        }
    }
}

/// The JSON run report written by `--report`.
pub struct Report(pub Value);

impl Report {
    pub fn tasks(&self) -> Vec<&Value> {
        self.0["tasks"].as_array().map(|a| a.iter().collect()).unwrap_or_default()
    }

    /// How many tasks of `stage` (or of all stages, if None) have `status`.
    pub fn count(&self, stage: Option<&str>, status: &str) -> usize {
        self.tasks().iter().filter(|t| stage.is_none_or(|s| t["stage"] == s) && t["status"] == status).count()
    }

    pub fn stages(&self) -> Vec<String> {
        let mut v: Vec<String> = self.tasks().iter().map(|t| t["stage"].as_str().unwrap().to_string()).collect();
        v.dedup();
        v
    }

    pub fn task(&self, stage: &str, point: &str) -> &Value {
        self.tasks()
            .into_iter()
            .find(|t| t["stage"] == stage && t["point"] == point)
            .unwrap_or_else(|| panic!("no task {stage} {point}"))
    }
}

/// Every file under `dir`, with its bytes, sorted by path (for comparing outputs); damage
/// that a run moved aside (`*.damaged-*`) is not an output.
pub fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    if let Ok(rd) = std::fs::read_dir(dir) {
        for e in rd.flatten() {
            let p = e.path();
            if e.file_name().to_string_lossy().contains(".damaged-") {
                continue;
            }
            if p.is_dir() {
                out.extend(snapshot(&p));
            } else {
                out.push((p.file_name().unwrap().to_string_lossy().to_string(), std::fs::read(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// Like `snapshot`, but a table (`.parquet`) is its contents without the timing columns
/// (`*_time_s`, as `repro verify` leaves them out: they differ between two computations of
/// the same task).
pub fn snapshot_untimed(dir: &Path) -> Vec<(String, Vec<u8>)> {
    snapshot(dir)
        .into_iter()
        .map(|(name, bytes)| {
            if !name.ends_with(".parquet") {
                return (name, bytes);
            }
            let df = repro::pipeline::table::read_parquet(&dir.join(&name)).unwrap();
            let mut text = String::new();
            for name in df.get_column_names() {
                if name.as_str().ends_with("_time_s") {
                    continue;
                }
                let c = df.column(name).unwrap();
                text.push_str(&format!("{name}:"));
                for i in 0..df.height() {
                    text.push_str(&format!(" {:?}", c.get(i).unwrap()));
                }
                text.push('\n');
            }
            (name, text.into_bytes())
        })
        .collect()
}

/// A small pipeline of `util.sleep` tasks: a sweep, a stage that reads it, and a figure.
pub fn sleep_pipeline(xs: &str, ms: u64, title: &str) -> String {
    format!(
        r#"stages:
  - name: sweep
    kind: util.sleep
    params: {{x: {xs}, ms: {ms}}}
  - name: after
    kind: util.sleep
    needs: [sweep]
    params: {{x: 7}}
  - name: fig
    kind: figure
    needs: [sweep]
    params:
      title: "{title}"
      x_label: "x"
      y_label: "upstream rows"
      layers:
        - data: {{from: sweep, x: x, y: upstream_rows, label: "sweep"}}
"#
    )
}

/// Runs an invalid pipeline; asserts exit code 2, no cache and no outputs; returns stderr.
pub fn rejected(name: &str, yaml: &str) -> String {
    let s = Scratch::new(name);
    s.write("p.yaml", yaml);
    let out = s.repro(&["run", "p.yaml", "-q"]);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(!s.exists("cache"), "an invalid pipeline must not touch the cache");
    assert!(!s.exists("figures") && !s.exists("tables"), "an invalid pipeline must not write outputs");
    assert!(stderr.contains("nothing was run"), "{stderr}");
    stderr
}
