//! The run report: one record per task (written as JSON with `--report` and always to
//! `cache/runs/last.json`), and the summary printed at the end of a run.

use crate::reason::Reason;
use crate::task::TaskError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Computed in this run.
    Computed,
    /// Taken from the cache.
    Cached,
    /// The task returned an error or panicked.
    Failed,
    /// Not run because a stage it needs failed or was skipped.
    Skipped,
    /// Dry run: would be computed.
    WouldRun,
    /// Dry run: its key depends on outputs that are not computed yet.
    Unknown,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TaskRecord {
    pub stage: String,
    pub kind: String,
    /// The sweep point (`lambda=0.1 k=0.1`), empty for an unswept stage.
    pub point: String,
    pub key: Option<String>,
    pub status: Status,
    /// Why it was computed (or would be), or why not (`crate::reason`).
    #[serde(default, deserialize_with = "crate::reason::deserialize_reason")]
    pub reason: Option<Reason>,
    pub wall_time_s: f64,
    /// When it started, in seconds from the start of the run (computed in this process;
    /// with `wall_time_s`, the run's timeline).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub started_s: Option<f64>,
    /// How it failed, as a message.
    pub error: Option<String>,
    /// How it failed, typed (`crate::task::TaskError`: failed, panicked, timed out, invalid
    /// output, not stored, worker).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failure: Option<TaskError>,
    /// Where it was computed when not in this process (`SLURM job 12_3`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ran_on: Option<String>,
}

impl TaskRecord {
    /// A record of a task of `stage` (no wall time, error or placement yet).
    pub fn new(
        stage: &super::spec::Stage,
        point: &str,
        key: Option<String>,
        status: Status,
        reason: Option<Reason>,
    ) -> Self {
        TaskRecord {
            stage: stage.name.clone(),
            kind: stage.kind.clone(),
            point: point.to_string(),
            key,
            status,
            reason,
            wall_time_s: 0.0,
            started_s: None,
            error: None,
            failure: None,
            ran_on: None,
        }
    }

    /// Records how the task failed.
    pub fn failed_with(&mut self, e: TaskError) {
        self.error = Some(e.to_string());
        self.failure = Some(e);
    }
}

#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct RunReport {
    /// When the run started, in milliseconds since the Unix epoch.
    #[serde(default)]
    pub started_unix_ms: u64,
    pub pipeline: String,
    /// The parameters set on the command line for this run (`-S STAGE.PARAM=VALUE`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub overrides: Vec<String>,
    pub dry_run: bool,
    /// The git commit of the pipeline file's checkout, when it is one; " (modified)" when
    /// tracked files differ from it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub git_commit: Option<String>,
    pub wall_time_s: f64,
    pub counts: BTreeMap<String, usize>,
    pub tasks: Vec<TaskRecord>,
    /// Files written (or rewritten) by this run.
    pub published: Vec<String>,
    /// What the tasks of the run's stages report for its end (`kind::Output::notes`), and
    /// the expectations that stopped holding (`kind::Output::regressions`), with their stage.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub regressions: Vec<String>,
    /// What the run could not write after its tasks (a stage's manifest, a published file,
    /// the run history: a full disk, a read-only folder), each with its stage and file; the
    /// rest was written.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub errors: Vec<String>,
}

impl RunReport {
    pub fn count(&self, s: Status) -> usize {
        self.tasks.iter().filter(|t| t.status == s).count()
    }

    pub fn finalize_counts(&mut self) {
        self.counts.clear();
        for t in &self.tasks {
            let name = serde_json::to_value(t.status).unwrap().as_str().unwrap().to_string();
            *self.counts.entry(name).or_default() += 1;
        }
    }

    pub fn any_failed(&self) -> bool {
        self.count(Status::Failed) + self.count(Status::Skipped) > 0
    }

    /// A human summary: totals, then per stage what ran, the task time of what it computed
    /// and why it ran, then failures.
    pub fn summary(&self, explain: bool) -> String {
        let mut s = String::new();
        let mut stages: Vec<&str> = Vec::new();
        for t in &self.tasks {
            if !stages.contains(&t.stage.as_str()) {
                stages.push(&t.stage);
            }
        }
        // The stage names in a column as wide as the longest (at least 16).
        let width = stages.iter().map(|s| s.chars().count()).max().unwrap_or(0).max(16);
        for stage in stages {
            let tasks: Vec<&TaskRecord> = self.tasks.iter().filter(|t| t.stage == stage).collect();
            let mut by_status: BTreeMap<Status, usize> = BTreeMap::new();
            for t in &tasks {
                *by_status.entry(t.status).or_default() += 1;
            }
            let parts: Vec<String> = by_status
                .iter()
                .map(|(st, n)| format!("{n} {}", serde_json::to_value(st).unwrap().as_str().unwrap().replace('_', " ")))
                .collect();
            // Reasons, grouped, for the tasks that ran or would run.
            let mut reasons: BTreeMap<String, usize> = BTreeMap::new();
            for t in &tasks {
                if let Some(r) = &t.reason {
                    if matches!(t.status, Status::Computed | Status::WouldRun | Status::Failed) {
                        *reasons.entry(r.to_string()).or_default() += 1;
                    }
                }
            }
            let why = if reasons.is_empty() {
                String::new()
            } else {
                let list: Vec<String> =
                    reasons.iter().take(3).map(|(r, n)| if *n > 1 { format!("{r} ×{n}") } else { r.clone() }).collect();
                let more =
                    if reasons.len() > 3 { format!(", … {} more reasons", reasons.len() - 3) } else { String::new() };
                format!(" ({}{more})", list.join("; "))
            };
            // What the stage's computed tasks cost, summed over workers (one core each); not
            // shown where it rounds to nothing.
            let task_time: f64 = tasks.iter().filter(|t| t.status == Status::Computed).map(|t| t.wall_time_s).sum();
            let cost = if task_time >= 0.05 { format!(", {task_time:.1} s of task time") } else { String::new() };
            s.push_str(&format!("  {stage:<width$} {}{cost}{why}\n", parts.join(", ")));
            if explain {
                for t in &tasks {
                    let label = if t.point.is_empty() { "(single point)" } else { &t.point };
                    let st = serde_json::to_value(t.status).unwrap().as_str().unwrap().to_string();
                    let key = t.key.as_deref().map(|k| &k[..12]).unwrap_or("?");
                    let why = t.reason.as_ref().map(|r| r.to_string()).unwrap_or_default();
                    let on = t.ran_on.as_deref().map(|o| format!(" [{o}]")).unwrap_or_default();
                    s.push_str(&format!("      {label:<40} {key} {st:<9} {why}{on}\n"));
                }
            }
            for t in tasks.iter().filter(|t| t.status == Status::Failed) {
                s.push_str(&format!(
                    "      FAILED {}: {}\n",
                    if t.point.is_empty() { "task" } else { &t.point },
                    t.error.as_deref().unwrap_or("")
                ));
            }
        }
        let verb = if self.dry_run { "would compute" } else { "computed" };
        let ran = if self.dry_run { self.count(Status::WouldRun) } else { self.count(Status::Computed) };
        s.push_str(&format!(
            "repro: {ran} {verb}, {} cached, {} failed, {} skipped{} in {:.2} s\n",
            self.count(Status::Cached),
            self.count(Status::Failed),
            self.count(Status::Skipped),
            if self.dry_run {
                format!(", {} unknown until upstream runs", self.count(Status::Unknown))
            } else {
                String::new()
            },
            self.wall_time_s
        ));
        s
    }
}

/// A time given in milliseconds since the Unix epoch as `YYYY-MM-DD HH:MM:SS UTC`.
pub fn utc_time(unix_ms: u64) -> String {
    let secs = unix_ms / 1000;
    let (days, rem) = (secs / 86400, secs % 86400);
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02} {:02}:{:02}:{:02} UTC", rem / 3600, rem % 3600 / 60, rem % 60)
}

/// The commit of the git checkout holding `dir`, and whether tracked files differ from it;
/// None outside a checkout (or without git).
pub fn git_commit(dir: &std::path::Path) -> Option<(String, bool)> {
    let git = |args: &[&str]| -> Option<String> {
        let out = std::process::Command::new("git").args(args).current_dir(dir).output().ok()?;
        out.status.success().then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
    };
    let commit = git(&["rev-parse", "HEAD"])?;
    let modified = git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
    Some((commit, modified))
}

/// The run reports kept in the history of a cache (`runs/run-*.json`), oldest first; a report
/// that cannot be read is skipped.
pub fn run_history(cache_dir: &Path) -> Vec<(PathBuf, RunReport)> {
    let Ok(entries) = std::fs::read_dir(cache_dir.join("runs")) else { return Vec::new() };
    let mut runs: Vec<(PathBuf, RunReport)> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let name = p.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
            name.starts_with("run-") && name.ends_with(".json")
        })
        .filter_map(|p| {
            let r: RunReport = serde_json::from_slice(&crate::cache::read_regular(&p).ok()?).ok()?;
            Some((p, r))
        })
        .collect();
    runs.sort_by(|a, b| a.1.started_unix_ms.cmp(&b.1.started_unix_ms).then(a.0.cmp(&b.0)));
    runs
}

/// Milliseconds since the Unix epoch (0 if the clock is before it).
pub fn unix_ms() -> u64 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_millis() as u64)
}

#[cfg(test)]
mod time_tests {
    #[test]
    fn utc_time_of_known_instants() {
        assert_eq!(super::utc_time(0), "1970-01-01 00:00:00 UTC");
        // 2000-02-29 12:34:56 UTC (a leap day) = 951827696 s.
        assert_eq!(super::utc_time(951_827_696_000), "2000-02-29 12:34:56 UTC");
        // 2026-11-25 00:00:00 UTC = 1795564800 s.
        assert_eq!(super::utc_time(1_795_564_800_000), "2026-11-25 00:00:00 UTC");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(stage: &str, status: Status, wall_time_s: f64) -> TaskRecord {
        TaskRecord {
            stage: stage.into(),
            kind: "k".into(),
            point: String::new(),
            key: None,
            status,
            reason: None,
            wall_time_s,
            started_s: None,
            error: None,
            failure: None,
            ran_on: None,
        }
    }

    #[test]
    fn the_summary_gives_each_stage_the_task_time_of_what_it_computed() {
        let report = RunReport {
            tasks: vec![
                record("shell", Status::Computed, 2.25),
                record("shell", Status::Computed, 1.5),
                record("shell", Status::Cached, 0.0),
                record("bem", Status::Cached, 0.0),
                record("figure", Status::Computed, 0.01),
            ],
            ..Default::default()
        };
        let summary = report.summary(false);
        let line = |stage: &str| summary.lines().find(|l| l.trim_start().starts_with(stage)).unwrap().to_string();
        // 2.25 + 1.5 s; the cached task adds nothing.
        assert!(line("shell").contains("2 computed, 1 cached, 3.8 s of task time"), "{summary}");
        assert!(!line("bem").contains("task time"), "{summary}");
        assert!(!line("figure").contains("task time"), "{summary}");
        // One column for the counts, however long a stage's name.
        let long = RunReport {
            tasks: vec![record("shell_indent_adhesive", Status::Cached, 0.0), record("bem", Status::Cached, 0.0)],
            ..Default::default()
        };
        let columns: Vec<usize> = long.summary(false).lines().filter_map(|l| l.find(" 1 cached")).collect();
        assert_eq!(columns.len(), 2);
        assert_eq!(columns[0], columns[1], "{}", long.summary(false));
    }
}
