//! Where tasks are computed: a [`Backend`] takes the tasks of a round and returns each one's
//! outcome. [`Local`] computes them in this process, in parallel (rayon); the SLURM
//! backend (`crate::slurm::Coordinator`) submits them as job arrays whose workers write
//! into the shared cache. The run loop knows only the trait.

use crate::cache::Cache;
use crate::key::Hash;
use crate::kind::{DynKind, Inputs, Output, Registry};
use crate::task::{compute_task, TaskError};
use anyhow::Result;
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::time::{Duration, Instant};

/// One task to compute.
pub struct Task<'a> {
    pub key: &'a Hash,
    pub kind: &'a dyn DynKind,
    pub params: &'a serde_json::Value,
    /// The tables of the stages it needs (for computing here).
    pub inputs: &'a Inputs<'a>,
    /// The keys of those tables' tasks, per stage (for a worker, which reads them from the
    /// cache).
    pub input_keys: BTreeMap<String, Vec<Hash>>,
    pub time_limit: Duration,
}

/// A task's outcome.
pub struct Settled {
    pub result: Result<Output, TaskError>,
    pub wall_time_s: f64,
    /// When it started, in seconds from the start of the run (known for tasks computed in
    /// this process).
    pub started_s: Option<f64>,
    /// Where it ran, when not in this process (`SLURM job 12_3`).
    pub ran_on: Option<String>,
}

/// Computes tasks.
pub trait Backend {
    /// Computes `tasks` (their entries stored in `cache`), calling `done(i)` as task `i`
    /// settles; one outcome per task, in order. An error is a failure of the backend itself
    /// (SLURM unreachable), not of a task.
    fn compute(
        &mut self,
        tasks: &[Task],
        registry: &Registry,
        cache: &Cache,
        done: &(dyn Fn(usize) + Sync),
    ) -> Result<Vec<Settled>>;
}

/// Computes tasks in this process on a rayon pool.
pub struct Local {
    pool: rayon::ThreadPool,
    start: Instant,
}

impl Local {
    /// A pool of `jobs` threads (None: one per core); start times are counted from `start`.
    pub fn new(jobs: Option<usize>, start: Instant) -> Result<Local> {
        Ok(Local { pool: rayon::ThreadPoolBuilder::new().num_threads(jobs.unwrap_or(0)).build()?, start })
    }
}

impl Backend for Local {
    fn compute(
        &mut self,
        tasks: &[Task],
        registry: &Registry,
        cache: &Cache,
        done: &(dyn Fn(usize) + Sync),
    ) -> Result<Vec<Settled>> {
        let start = self.start;
        Ok(self.pool.install(|| {
            // One task per split: tasks differ in cost by orders of magnitude, and rayon's
            // default splitting can leave several expensive tasks queued behind one another
            // on one thread while the other idles.
            tasks
                .par_iter()
                .enumerate()
                .with_max_len(1)
                .map(|(i, t)| {
                    let started = start.elapsed().as_secs_f64();
                    let (result, dt) =
                        compute_task(registry, t.kind, t.key, t.params, t.inputs, cache, Some(t.time_limit));
                    done(i);
                    Settled { result, wall_time_s: dt, started_s: Some(started), ran_on: None }
                })
                .collect()
        }))
    }
}
