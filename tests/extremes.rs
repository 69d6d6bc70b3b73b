//! Extreme parameters through `repro point`, drawn at random (seeded): every kind that reads
//! no other stage's table, from its reference parameters (tests/kind_versions.rs) with one
//! to three numbers, at any depth, set to an extreme (0, ±1e300, 1e-300, NaN, ±infinity, a
//! huge or negative count). Whatever the draw, the command ends by itself within its time
//! limit, with exit code 0 (computed), 1 (the point failed: refused its memory, timed out, a
//! contained panic) or 2 (invalid input); never an abort, a signal or an escaped panic.

use crate::common::Scratch;
use serde_json::Value;
use std::time::{Duration, Instant};

const DRAWS: usize = 300;
/// Each point's time limit (`repro point --time-limit`), and the margin allowed beyond it
/// for start-up and a checkpoint's interval.
const LIMIT_S: f64 = 2.0;
const MARGIN: Duration = Duration::from_secs(20);

const EXTREMES: &[&str] =
    &["0", "-0.0", "1e-300", "1e300", "-1e300", ".nan", ".inf", "-.inf", "1000000000", "-1", "32001"];

/// A small deterministic generator (SplitMix64).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The paths of the numbers in a value (`shell.R`, `prony.0.1`).
fn number_paths(v: &Value, path: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match v {
        Value::Number(_) => out.push(path.clone()),
        Value::Object(m) => {
            for (k, x) in m {
                path.push(k.clone());
                number_paths(x, path, out);
                path.pop();
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                path.push(i.to_string());
                number_paths(x, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

fn set(v: &mut Value, path: &[String], to: &str) {
    let mut at = v;
    for p in path {
        at = match at {
            Value::Object(m) => m.get_mut(p).unwrap(),
            Value::Array(a) => a.get_mut(p.parse::<usize>().unwrap()).unwrap(),
            _ => unreachable!(),
        };
    }
    // A marker the YAML text below replaces by the extreme itself (NaN and infinity have no
    // JSON spelling).
    *at = Value::String(format!("@@{to}@@"));
}

/// A parameter's value as `repro point` reads it (YAML flow: JSON with the markers unquoted).
fn yaml(v: &Value) -> String {
    let text = v.to_string();
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("\"@@") {
        out.push_str(&rest[..i]);
        let after = &rest[i + 3..];
        let j = after.find("@@\"").unwrap();
        out.push_str(&after[..j]);
        rest = &after[j + 3..];
    }
    out.push_str(rest);
    out
}

/// The kinds drawn: those that read no other stage's table (the others fail at once
/// without inputs), with their reference parameters.
fn drawable_kinds() -> Vec<(&'static str, Value)> {
    crate::kind_versions::reference_params()
        .into_iter()
        .filter(|(k, _)| {
            !k.starts_with("bench.")
                && !["pb.calibrate", "fem.gamma_c_map", "claim", "claims", "fit.powerlaw", "figure"].contains(k)
        })
        .collect()
}

/// One draw: a kind, its reference parameters with one to three numbers set to extremes,
/// and what was changed.
fn draw(rng: &mut Rng, kinds: &[(&'static str, Value)]) -> (&'static str, Value, String) {
    let (kind, reference) = &kinds[rng.below(kinds.len())];
    let mut params = reference.clone();
    let mut paths = Vec::new();
    number_paths(&params, &mut Vec::new(), &mut paths);
    let mut changed = Vec::new();
    for _ in 0..=rng.below(3) {
        if paths.is_empty() {
            break;
        }
        let path = paths[rng.below(paths.len())].clone();
        let to = EXTREMES[rng.below(EXTREMES.len())];
        set(&mut params, &path, to);
        changed.push(format!("{}={to}", path.join(".")));
    }
    (kind, params, changed.join(" "))
}

/// The largest resident set of any child of this test process so far, in bytes.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn largest_child_bytes() -> f64 {
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    assert_eq!(unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) }, 0);
    usage.ru_maxrss as f64 * 1024.0
}

#[test]
fn extreme_parameters_end_every_point_with_an_answer() {
    let s = Scratch::new("extremes");
    let kinds = drawable_kinds();
    let mut rng = Rng(0x5EED_2026);
    let mut outcomes = std::collections::BTreeMap::<i32, usize>::new();
    let mut bad = Vec::new();
    for _ in 0..DRAWS {
        let (kind, params, changed) = draw(&mut rng, &kinds);
        let args: Vec<String> = params
            .as_object()
            .unwrap()
            .iter()
            .map(|(k, v)| {
                format!(
                    "{k}={}",
                    if v.is_string() && !v.as_str().unwrap().starts_with("@@") {
                        v.as_str().unwrap().to_string()
                    } else {
                        yaml(v)
                    }
                )
            })
            .collect();
        let mut cmd = s.command(&["point", kind, "--time-limit", &LIMIT_S.to_string()]);
        cmd.args(&args).env("REPRO_MEMORY_BYTES", "4e9");
        let t0 = Instant::now();
        let out = cmd.output().unwrap();
        let dt = t0.elapsed();
        let code = out.status.code().unwrap_or(-1);
        *outcomes.entry(code).or_default() += 1;
        let err = String::from_utf8_lossy(&out.stderr);
        if ![0, 1, 2].contains(&code) || dt > Duration::from_secs_f64(LIMIT_S) + MARGIN {
            bad.push(format!("{kind} {changed} -> exit {code} after {dt:?}: {}", err.trim()));
        }
    }
    eprintln!("outcomes by exit code: {outcomes:?}");
    assert!(bad.is_empty(), "{} of {DRAWS} draws ended badly:\n{}", bad.len(), bad.join("\n"));
    // The draws reach the solvers, not only the validation: some compute, some fail.
    assert!(outcomes.get(&0).copied().unwrap_or(0) > 10 && outcomes.get(&2).copied().unwrap_or(0) > 10, "{outcomes:?}");
    // No point allocated past the memory the draws allowed (these points among the children).
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        let peak_bytes = largest_child_bytes();
        eprintln!("largest child resident set: {:.2} GB", peak_bytes / 1e9);
        assert!(peak_bytes < 4e9, "a child reached {:.1} GB", peak_bytes / 1e9);
    }
}

/// Draws through `repro run`, which a point's draws do not reach: the pipeline file's
/// parser and checks, the executor's guard, the cache and publishing. Each draw a file of
/// its own, beside a stage that always computes (most draws are invalid input, which
/// refuses the whole file, exit 2).
const RUN_DRAWS: usize = 300;

#[test]
fn extreme_parameters_in_a_pipeline_end_every_run_with_an_answer() {
    let s = Scratch::new("extremes-run");
    let kinds = drawable_kinds();
    let mut rng = Rng(0x5EED_2027);
    let mut outcomes = std::collections::BTreeMap::<i32, usize>::new();
    let mut bad = Vec::new();
    for run in 0..RUN_DRAWS {
        let (kind, params, what) = draw(&mut rng, &kinds);
        let changed = format!("{kind} {what}");
        s.write(
            "p.yaml",
            &format!(
                "stages:\n  - name: drawn\n    kind: {kind}\n    params: {}\n  - name: other\n    kind: util.sleep\n    params: {{x: {run}}}\n",
                yaml(&params)
            ),
        );
        let t0 = Instant::now();
        let out = s
            .command(&["run", "p.yaml", "-q", "--time-limit", &LIMIT_S.to_string(), "--report", "r.json"])
            .env("REPRO_MEMORY_BYTES", "4e9")
            .output()
            .unwrap();
        let dt = t0.elapsed();
        let code = out.status.code().unwrap_or(-1);
        *outcomes.entry(code).or_default() += 1;
        let err = String::from_utf8_lossy(&out.stderr);
        // 0: computed; 1: the drawn task failed (memory, time limit, a contained panic); 2:
        // invalid input, located in the file.
        let located = code != 2 || err.contains("p.yaml:");
        if ![0, 1, 2].contains(&code) || !located || dt > Duration::from_secs_f64(LIMIT_S) + MARGIN {
            bad.push(format!("run {run}: {changed} -> exit {code} after {dt:?}: {}", err.trim()));
        }
        if code == 0 || code == 1 {
            // The report records the drawn task's outcome (a failure with its reason), and
            // the other stage computed whatever the drawn one did.
            let report: Value = serde_json::from_slice(&std::fs::read(s.path("r.json")).unwrap()).unwrap();
            let tasks = report["tasks"].as_array().unwrap();
            let status = |stage: &str| tasks.iter().find(|t| t["stage"] == stage).map(|t| t["status"].clone());
            let drawn_ok = if code == 1 {
                tasks.iter().any(|t| t["stage"] == "drawn" && t["status"] == "failed" && t["error"].is_string())
            } else {
                status("drawn").is_some_and(|st| st == "computed" || st == "cached")
            };
            let other_ok = status("other").is_some_and(|st| st == "computed" || st == "cached");
            if !drawn_ok || !other_ok {
                bad.push(format!("run {run}: {changed} -> exit {code}, report {tasks:?}"));
            }
        }
    }
    eprintln!("outcomes by exit code: {outcomes:?}");
    assert!(bad.is_empty(), "{} runs ended badly:\n{}", bad.len(), bad.join("\n"));
    assert!(outcomes.get(&0).copied().unwrap_or(0) > 3 && outcomes.get(&2).copied().unwrap_or(0) > 3, "{outcomes:?}");
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    assert!(largest_child_bytes() < 4e9, "a run allocated past the memory allowed");
}
