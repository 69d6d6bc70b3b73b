//! Garbage collection of the cache: an entry is kept while a task of a given pipeline, or
//! of a run in the cache's history (younger than a given age), refers to it; the rest is
//! removed, or listed in a dry run. Nothing outside `objects/` is touched.

use crate::cache::{Cache, LockMode};
use crate::executor::{run, RunOptions};
use crate::key::Hash;
use crate::kind::Registry;
use crate::report::{run_history, unix_ms};
use crate::spec::Pipeline;
use anyhow::Result;
use std::collections::BTreeSet;
use std::path::Path;

/// What `gc` keeps and removes.
#[derive(Clone, Copy, Debug, Default)]
pub struct GcOptions {
    /// List what would go, remove nothing.
    pub dry_run: bool,
    /// Keep the entries of recorded runs younger than this only (None: of every recorded run).
    pub older_than: Option<std::time::Duration>,
}

/// What `gc` found.
#[derive(Clone, Debug, Default)]
pub struct GcSummary {
    pub kept: usize,
    /// The entries removed (or, in a dry run, that would be), with their sizes.
    pub removed: Vec<(Hash, u64)>,
    /// The recorded runs whose entries were kept.
    pub runs_kept: usize,
    /// In a dry run, what each entry to remove was: the stage, point and pipeline of the
    /// latest recorded run that computed or read it, else its kind and parameters.
    pub described: std::collections::BTreeMap<Hash, String>,
}

/// Removes cache entries that nothing refers to: no task of the given pipelines, and no task
/// of a run in the cache's history (younger than `older_than`, when given). A dry run lists
/// them without removing.
pub fn gc(pipelines: &[Pipeline], registry: &Registry, cache_dir: &Path, opt: GcOptions) -> Result<GcSummary> {
    // The lock first: a run holding it is still storing entries and has not yet recorded
    // itself in the history; what to keep is read once it is done.
    let cache = if opt.dry_run { Cache::open_read_only(cache_dir) } else { Cache::open(cache_dir, LockMode::Wait)? };
    let mut live: BTreeSet<String> = BTreeSet::new();
    for p in pipelines {
        let opts =
            RunOptions { cache_dir: cache_dir.to_path_buf(), dry_run: true, progress: false, ..Default::default() };
        let report = run(p, registry, &opts)?;
        live.extend(report.tasks.into_iter().filter_map(|t| t.key));
    }
    let now_ms = unix_ms();
    let mut summary = GcSummary::default();
    let history = run_history(cache_dir);
    // Per key, the latest recorded task that had it (for a dry run's list).
    let mut last_seen: std::collections::BTreeMap<String, String> = std::collections::BTreeMap::new();
    if opt.dry_run {
        for (_, r) in &history {
            for t in &r.tasks {
                if let Some(k) = &t.key {
                    let point = if t.point.is_empty() { String::new() } else { format!(" [{}]", t.point) };
                    last_seen.insert(k.clone(), format!("stage `{}`{point} of {}", t.stage, r.pipeline));
                }
            }
        }
    }
    for (_, r) in history {
        let young = opt.older_than.is_none_or(|age| now_ms.saturating_sub(r.started_unix_ms) < age.as_millis() as u64);
        if young {
            summary.runs_kept += 1;
            live.extend(r.tasks.into_iter().filter_map(|t| t.key));
        }
    }
    for key in cache.all_keys()? {
        if live.contains(&key) {
            summary.kept += 1;
        } else if opt.dry_run {
            let size = std::fs::metadata(cache.entry_path(&key)).map(|m| m.len()).unwrap_or(0);
            let what = last_seen.remove(&key).unwrap_or_else(|| match cache.get(&key) {
                Ok(e) => format!("{}@v{} {}", e.kind, e.version, e.params),
                Err(_) => "an unreadable entry".to_string(),
            });
            summary.described.insert(key.clone(), what);
            summary.removed.push((key, size));
        } else {
            let size = cache.remove(&key)?;
            summary.removed.push((key, size));
        }
    }
    Ok(summary)
}
