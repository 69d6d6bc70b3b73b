//! Computing one task, wherever it runs (in this process or in a SLURM worker): the kind's
//! computation with panics caught and held to its time limit, its table checked (no NaN or
//! infinity reaches a table), and its entry stored in the cache atomically. A task that
//! fails says how, as a [`TaskError`].

use crate::cache::{Cache, Entry};
use crate::key::Hash;
use crate::kind::{DynKind, Inputs, Interrupted, Output, Registry, TimeLimitExceeded};
use serde::{Deserialize, Serialize};
use std::time::{Duration, Instant};

/// How a task failed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, thiserror::Error)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum TaskError {
    /// The kind's computation returned an error.
    #[error("{message}")]
    Failed { message: String },
    /// The kind's computation panicked.
    #[error("panicked: {message}")]
    Panicked { message: String },
    /// The computation was stopped at its time limit.
    #[error("timed out: past its time limit of {limit_s} s (a stage's `time_limit`, or `repro run --time-limit`)")]
    TimedOut { limit_s: f64 },
    /// The process was interrupted while it ran, or before it started (Ctrl-C in the
    /// Python package); nothing of it is stored.
    #[error("interrupted before it ended")]
    Interrupted,
    /// The table it returned is not one a stage may publish (NaN, infinity, ragged columns).
    #[error("invalid output: {message}")]
    InvalidOutput { message: String },
    /// Not started: its estimated memory exceeds what is available (`Kind::memory_bytes`;
    /// the available memory is `REPRO_MEMORY_BYTES` if set, else the system's).
    #[error("not started: it may need {} of memory, {} is available (set REPRO_MEMORY_BYTES to allow more)", gigabytes(*needed_bytes), gigabytes(*available_bytes))]
    Resources { needed_bytes: u64, available_bytes: u64 },
    /// Computed, but its cache entry could not be written (a full disk, permissions).
    #[error("writing the cache entry: {message}")]
    NotStored { message: String },
    /// A SLURM worker could not run it (task specification, version, inputs), or ended
    /// without a result.
    #[error("{message}")]
    Worker { message: String },
}

/// Computes one task and stores its entry: [`guarded_run`], then its entry written to
/// the cache. Returns the output or how it failed, and the wall time. Shared by the local
/// backend and the SLURM worker.
///
/// Its arguments: the registry and the kind, the task's key, parameters and inputs, the
/// cache it writes to and its time limit.
pub fn compute_task(
    registry: &Registry,
    kind: &dyn DynKind,
    key: &Hash,
    params: &serde_json::Value,
    inputs: &Inputs,
    cache: &Cache,
    limit: Option<Duration>,
) -> (Result<Output, TaskError>, f64) {
    crate::fault::point("task.start");
    let (out, dt) = guarded_run(registry, kind, params, inputs, limit);
    let out = out.and_then(|o| {
        let entry = Entry::new(key.clone(), kind.name(), kind.version(), params.clone(), o, dt);
        cache.put(&entry).map_err(|e| TaskError::NotStored { message: format!("{e:#}") })?;
        Ok(entry.output)
    });
    (out, dt)
}

/// Computes one point of `kind` as a task is computed, without storing it: not started
/// when its estimated memory exceeds what is available, its panics caught, held to
/// `limit` (`Registry::run_limited`), its table checked (no NaN or infinity). Returns the
/// output or how it failed, and the wall time.
pub fn guarded_run(
    registry: &Registry,
    kind: &dyn DynKind,
    params: &serde_json::Value,
    inputs: &Inputs,
    limit: Option<Duration>,
) -> (Result<Output, TaskError>, f64) {
    if let (Some(needed_bytes), Some(available_bytes)) = (kind.memory_bytes(params), available_memory()) {
        if needed_bytes > available_bytes {
            return (Err(TaskError::Resources { needed_bytes, available_bytes }), 0.0);
        }
    }
    let t0 = Instant::now();
    let res =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| registry.run_limited(kind, params, inputs, limit)));
    let out = match res {
        Ok(Ok(out)) => {
            out.table.check().map(|_| out).map_err(|e| TaskError::InvalidOutput { message: format!("{e:#}") })
        }
        Ok(Err(e)) => Err(if let Some(t) = e.downcast_ref::<TimeLimitExceeded>() {
            TaskError::TimedOut { limit_s: t.0 }
        } else if e.is::<Interrupted>() {
            TaskError::Interrupted
        } else {
            TaskError::Failed { message: format!("{e:#}") }
        }),
        Err(panic) => Err(TaskError::Panicked {
            message: panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default(),
        }),
    };
    (out, t0.elapsed().as_secs_f64())
}

/// The memory a task may use, in bytes: `REPRO_MEMORY_BYTES` if set (a share of a node, or
/// a test), else the system's available memory (`MemAvailable` of `/proc/meminfo`); None
/// where neither says.
pub fn available_memory() -> Option<u64> {
    if let Some(v) = std::env::var("REPRO_MEMORY_BYTES").ok().and_then(|v| v.trim().parse::<f64>().ok()) {
        return Some(v.max(0.0) as u64);
    }
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// A size as a person reads it: "5602.3 GB", "0.8 GB", "96 MB" (below 0.1 GB).
fn gigabytes(bytes: u64) -> String {
    if bytes < 100_000_000 {
        format!("{} MB", (bytes as f64 / 1e6).round())
    } else {
        format!("{:.1} GB", bytes as f64 / 1e9)
    }
}
