//! Deterministic fault injection for the crash tests: `REPRO_CRASH_AT=point:n` aborts the
//! process (SIGABRT: no destructors, no flushing, like a SIGKILL) the n-th time it reaches
//! `point` (counting from 1). With `REPRO_CRASH_MARK=file` it crashes only if `file` does
//! not exist, and creates it first: one crash across all processes (a worker that crashes
//! once and succeeds on its retry).
//!
//! Points: `atomic.before_rename` and `atomic.after_rename` (every atomic write: cache
//! entries, manifests, published tables and figures, run reports) and `task.start` (a task
//! about to be computed, locally or by a SLURM worker). Without the variable a point costs
//! one atomic load (the initialised `OnceLock`).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::OnceLock;

struct Plan {
    point: String,
    at: u64,
    mark: Option<std::path::PathBuf>,
}

fn plan() -> Option<&'static Plan> {
    static PLAN: OnceLock<Option<Plan>> = OnceLock::new();
    PLAN.get_or_init(|| {
        let spec = std::env::var("REPRO_CRASH_AT").ok()?;
        let (point, at) = spec.rsplit_once(':')?;
        Some(Plan {
            point: point.to_string(),
            at: at.parse().ok()?,
            mark: std::env::var_os("REPRO_CRASH_MARK").map(Into::into),
        })
    })
    .as_ref()
}

/// Marks that execution reached `point`; aborts if the crash plan says so.
pub fn point(name: &str) {
    let Some(plan) = plan() else { return };
    if plan.point != name {
        return;
    }
    // Only the planned point is counted.
    static COUNT: AtomicU64 = AtomicU64::new(0);
    let n = COUNT.fetch_add(1, Ordering::Relaxed) + 1;
    if n == plan.at {
        if let Some(mark) = &plan.mark {
            if std::fs::OpenOptions::new().write(true).create_new(true).open(mark).is_err() {
                return; // already crashed once
            }
        }
        eprintln!("repro: fault injection: crashing at {name} #{n}");
        std::process::abort();
    }
}
