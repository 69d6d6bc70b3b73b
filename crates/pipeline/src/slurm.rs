//! The SLURM executor: the coordinator (`repro run --executor slurm`) submits the ready
//! tasks of a wave as one job array (`sbatch --array`); each array element runs
//! `repro worker` on one task, which computes it and writes its entry into the shared cache
//! with the same atomic protocol as a local run. The coordinator holds the cache lock;
//! workers take none (they only add entries, each by an atomic rename).
//!
//! Files under `cache/slurm/`:
//! - `tasks/<key>.json`: what a worker needs ([`TaskSpec`]: kind, version, canonical
//!   parameters, the keys of its inputs' points, read back from the cache);
//! - `lists/<id>.txt`: the keys of one array, one per line (element i runs line i);
//! - `logs/<job>_<i>.out|err`: the workers' output;
//! - `failed/<key>.json`: a task that failed in its worker (an error, not a crash);
//! - `submissions.log`: one line per `sbatch` (job id, attempt, number of tasks).
//!
//! Polling: one `squeue --name` call per poll for all of this cache's jobs, with a
//! back-off from `poll_min` to `poll_max` while nothing changes. A task is done when its
//! entry is in the cache; failed when its failure record is; crashed when its job has
//! left the queue with neither (checked in that order, after squeue, so no race), and
//! then resubmitted at most `retries` times. Restarted after being killed, a coordinator
//! reconciles with the scheduler: every job of this cache still queued or running carries
//! its task list in its comment, and the tasks in it are waited for, not resubmitted.
//!
//! One file: submission, polling and reconciliation share the coordinator's view of the
//! queue.

use super::cache::{is_key, write_atomic, Cache, Entry};
use super::key::Hash;
use crate::backend::{Backend, Settled, Task};
use crate::kind::Registry;
use crate::task::TaskError;
use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

#[derive(Clone, Debug)]
pub struct SlurmOptions {
    pub partition: Option<String>,
    /// At most this many elements of an array run at once (`--array=...%N`).
    pub max_jobs: Option<usize>,
    /// Resubmissions of a task whose worker ended without a result.
    pub retries: u32,
    pub poll_min: Duration,
    pub poll_max: Duration,
}

impl Default for SlurmOptions {
    fn default() -> Self {
        SlurmOptions {
            partition: None,
            max_jobs: None,
            retries: 2,
            poll_min: Duration::from_millis(250),
            poll_max: Duration::from_secs(10),
        }
    }
}

/// One task as a worker sees it.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TaskSpec {
    pub key: Hash,
    pub kind: String,
    pub version: u32,
    pub params: Value,
    /// Per input stage (in `needs` order), the keys of its points in order.
    pub inputs: Vec<(String, Vec<Hash>)>,
    /// The task's time limit in seconds (none: 0); the job array asks SLURM for the largest
    /// of its tasks' (`--time`, in whole minutes, plus one for the worker's start).
    #[serde(default)]
    pub time_limit_s: f64,
}

/// A worker's failure record.
#[derive(Debug, Serialize, Deserialize)]
pub struct Failure {
    pub key: Hash,
    pub error: TaskError,
}

fn dir(cache: &Cache, sub: &str) -> PathBuf {
    cache.root.join("slurm").join(sub)
}

pub fn spec_path(cache: &Cache, key: &str) -> PathBuf {
    dir(cache, "tasks").join(format!("{key}.json"))
}

pub fn failure_path(cache: &Cache, key: &str) -> PathBuf {
    dir(cache, "failed").join(format!("{key}.json"))
}

/// Where a task is: submitted in job `job` as element `index`, at attempt `attempt`
/// (`adopted`: submitted by an earlier coordinator).
#[derive(Clone, Debug)]
struct Placement {
    job: String,
    index: usize,
    attempt: u32,
    adopted: bool,
}

impl Placement {
    /// `SLURM job 12_3`, with the attempt and adoption if any.
    fn describe(&self) -> String {
        let mut s = format!("SLURM job {}_{}", self.job, self.index);
        if self.attempt > 0 {
            s.push_str(&format!(", attempt {}", self.attempt + 1));
        }
        if self.adopted {
            s.push_str(", adopted from an earlier coordinator");
        }
        s
    }
}

/// How a task ended: its entry or its error, and where it ran (None: found in the cache).
pub struct Ran {
    pub result: Result<Entry, TaskError>,
    pub placement: Option<String>,
}

pub struct Coordinator<'a> {
    cache: &'a Cache,
    opts: SlurmOptions,
    /// `repro-<hash of the cache path>`: the name of this cache's jobs.
    job_name: String,
    exe: PathBuf,
    /// Tasks of jobs found queued or running at start-up (a previous coordinator's).
    adopted: BTreeMap<Hash, Placement>,
}

fn command_output(cmd: &mut Command) -> Result<String> {
    let out = cmd.output().with_context(|| format!("running {:?}", cmd.get_program()))?;
    if !out.status.success() {
        bail!("{:?} failed ({}): {}", cmd.get_program(), out.status, String::from_utf8_lossy(&out.stderr).trim());
    }
    Ok(String::from_utf8_lossy(&out.stdout).to_string())
}

/// A task's time limit as sbatch's `--time` in minutes: rounded up, plus one for the
/// worker's start and the loading of its inputs; None without a limit (or beyond a year).
pub fn slurm_minutes(time_limit_s: f64) -> Option<u64> {
    (time_limit_s > 0.0 && time_limit_s < 3.2e7).then(|| (time_limit_s / 60.0).ceil() as u64 + 1)
}

/// Single-quotes `s` for the shell line that sbatch runs.
fn shell_quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
}

/// The last `n` lines of a file (for failure reports).
fn tail(path: &Path, n: usize) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

impl<'a> Coordinator<'a> {
    /// Prepares the directories and reconciles with this cache's jobs still in the queue.
    pub fn new(cache: &'a Cache, opts: SlurmOptions) -> Result<Coordinator<'a>> {
        let root = std::fs::canonicalize(&cache.root)?;
        let job_name = format!("repro-{}", &blake3::hash(root.to_string_lossy().as_bytes()).to_hex()[..12]);
        for sub in ["tasks", "lists", "logs", "failed"] {
            std::fs::create_dir_all(dir(cache, sub))?;
        }
        let exe = std::env::current_exe().context("locating the repro executable for the workers")?;
        let mut c = Coordinator { cache, opts, job_name, exe, adopted: BTreeMap::new() };
        for (job, comment) in c.queued_jobs()? {
            let list = dir(cache, "lists").join(&comment);
            let Ok(text) = std::fs::read_to_string(&list) else { continue };
            for (index, key) in text.lines().enumerate() {
                c.adopted.insert(key.to_string(), Placement { job: job.clone(), index, attempt: 0, adopted: true });
            }
        }
        if !c.adopted.is_empty() {
            eprintln!(
                "repro: {} task(s) of an earlier coordinator are still queued or running on SLURM; waiting for them",
                c.adopted.len()
            );
        }
        Ok(c)
    }

    /// This cache's jobs in the queue: (job id, comment = list file name).
    fn queued_jobs(&self) -> Result<Vec<(String, String)>> {
        let out = command_output(Command::new("squeue").args(["-h", "--name", &self.job_name, "-o", "%A %k"]))
            .context("asking SLURM for this cache's jobs (the SLURM executor needs sbatch and squeue on PATH)")?;
        let mut jobs: Vec<(String, String)> = out
            .lines()
            .filter_map(|l| l.split_once(' ').map(|(a, b)| (a.trim().to_string(), b.trim().to_string())))
            .collect();
        jobs.sort();
        jobs.dedup();
        Ok(jobs)
    }

    /// Submits `keys` as one job array, each task within `time_limit_s` (0: SLURM's
    /// default); returns the job id.
    fn submit(&self, keys: &[&Hash], attempt: u32, time_limit_s: f64) -> Result<String> {
        let joined: String = keys.iter().map(|k| format!("{k}\n")).collect();
        let list_name = format!("{}-{attempt}.txt", &blake3::hash(joined.as_bytes()).to_hex()[..16]);
        let list = dir(self.cache, "lists").join(&list_name);
        write_atomic(&list, joined.as_bytes(), &self.cache.tmp_dir())?;
        let root = std::fs::canonicalize(&self.cache.root)?;
        let logs = root.join("slurm").join("logs");
        let wrap = format!(
            "exec {} worker --cache {} --list {}",
            shell_quote(&self.exe.to_string_lossy()),
            shell_quote(&root.to_string_lossy()),
            shell_quote(&root.join("slurm").join("lists").join(&list_name).to_string_lossy())
        );
        let mut array = format!("0-{}", keys.len() - 1);
        if let Some(m) = self.opts.max_jobs {
            array.push_str(&format!("%{m}"));
        }
        let mut cmd = Command::new("sbatch");
        cmd.args(["--parsable", "--job-name", &self.job_name, "--comment", &list_name, "--array", &array])
            .arg(format!("--output={}/%A_%a.out", logs.display()))
            .arg(format!("--error={}/%A_%a.err", logs.display()));
        if let Some(p) = &self.opts.partition {
            cmd.args(["--partition", p]);
        }
        if let Some(minutes) = slurm_minutes(time_limit_s) {
            cmd.arg(format!("--time={minutes}"));
        }
        cmd.arg(format!("--wrap={wrap}"));
        // sbatch can be refused while the controller is busy: a few tries with back-off.
        let mut wait = self.opts.poll_min;
        let mut last = None;
        for _ in 0..4 {
            match command_output(&mut cmd) {
                Ok(out) => {
                    let job = out.trim().split(';').next().unwrap_or("").to_string();
                    if job.is_empty() || !job.bytes().all(|b| b.is_ascii_digit()) {
                        bail!("sbatch printed no job id: `{}`", out.trim());
                    }
                    let line = format!("{job} attempt={attempt} tasks={} list={list_name}\n", keys.len());
                    let log = dir(self.cache, "submissions.log");
                    let mut f = std::fs::OpenOptions::new().create(true).append(true).open(&log)?;
                    std::io::Write::write_all(&mut f, line.as_bytes())?;
                    return Ok(job);
                }
                Err(e) => last = Some(e),
            }
            std::thread::sleep(wait);
            wait = (wait * 2).min(self.opts.poll_max);
        }
        Err(last.unwrap().context("submitting to SLURM"))
    }

    /// Runs `tasks` on SLURM and waits for them; per task its entry or its error.
    /// `done(i)` is called as task i completes (progress).
    pub fn run(&mut self, tasks: &[TaskSpec], done: &(dyn Fn(usize) + Sync)) -> Result<Vec<Ran>> {
        let mut results: Vec<Option<Result<Entry, TaskError>>> = vec![None; tasks.len()];
        // Where each settled task last ran (only tasks that ran on SLURM).
        let mut ran_on: BTreeMap<usize, String> = BTreeMap::new();
        let mut place: BTreeMap<usize, Placement> = BTreeMap::new();
        let mut fresh: Vec<usize> = Vec::new();
        for (i, t) in tasks.iter().enumerate() {
            if !is_key(&t.key) {
                bail!("task key `{}` is malformed", t.key);
            }
            if let Ok(e) = self.cache.get(&t.key) {
                results[i] = Some(Ok(e));
                done(i);
            } else if let Some(p) = self.adopted.remove(&t.key) {
                place.insert(i, p); // its specification was written before it was submitted
            } else {
                write_atomic(&spec_path(self.cache, &t.key), &serde_json::to_vec(t)?, &self.cache.tmp_dir())?;
                fresh.push(i);
            }
        }
        self.submit_batch(tasks, &fresh, 0, &mut place, &mut results, done)?;

        let mut interval = self.opts.poll_min;
        let mut squeue_failures = 0;
        while !place.is_empty() {
            std::thread::sleep(interval);
            // The queue first, then the files: a job that has left the queue has written
            // whatever it will write.
            let queued: BTreeSet<String> = match self.queued_jobs() {
                Ok(j) => {
                    squeue_failures = 0;
                    j.into_iter().map(|(id, _)| id).collect()
                }
                Err(e) => {
                    squeue_failures += 1;
                    if squeue_failures >= 8 {
                        return Err(e.context("squeue failed 8 times in a row"));
                    }
                    interval = (interval * 2).min(self.opts.poll_max);
                    continue;
                }
            };
            let mut progressed = false;
            let mut crashed: Vec<(usize, Placement)> = Vec::new();
            for (&i, p) in &place {
                let key = &tasks[i].key;
                if let Ok(e) = self.cache.get(key) {
                    results[i] = Some(Ok(e));
                } else if let Some(f) = self.read_failure(key) {
                    results[i] = Some(Err(f));
                } else if !queued.contains(&p.job) {
                    crashed.push((i, p.clone()));
                    continue;
                } else {
                    continue;
                }
                ran_on.insert(i, p.describe());
                done(i);
                progressed = true;
            }
            place.retain(|i, _| results[*i].is_none());
            let mut retry: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
            for (i, p) in crashed {
                place.remove(&i);
                progressed = true;
                let err = dir(self.cache, "logs").join(format!("{}_{}.err", p.job, p.index));
                if p.attempt < self.opts.retries {
                    eprintln!(
                        "repro: SLURM job {}_{} ended without a result (attempt {}); resubmitting",
                        p.job,
                        p.index,
                        p.attempt + 1
                    );
                    retry.entry(p.attempt + 1).or_default().push(i);
                } else {
                    results[i] = Some(Err(TaskError::Worker {
                        message: format!(
                            "SLURM job {}_{} ended without a result after {} attempt(s); its stderr ({}):\n{}",
                            p.job,
                            p.index,
                            p.attempt + 1,
                            err.display(),
                            tail(&err, 20)
                        ),
                    }));
                    ran_on.insert(i, p.describe());
                    done(i);
                }
            }
            for (attempt, idx) in retry {
                self.submit_batch(tasks, &idx, attempt, &mut place, &mut results, done)?;
            }
            interval = if progressed { self.opts.poll_min } else { (interval * 3 / 2).min(self.opts.poll_max) };
        }
        Ok(results
            .into_iter()
            .enumerate()
            .map(|(i, r)| Ran { result: r.expect("every task settled"), placement: ran_on.remove(&i) })
            .collect())
    }

    fn submit_batch(
        &self,
        tasks: &[TaskSpec],
        idx: &[usize],
        attempt: u32,
        place: &mut BTreeMap<usize, Placement>,
        results: &mut [Option<Result<Entry, TaskError>>],
        done: &(dyn Fn(usize) + Sync),
    ) -> Result<()> {
        if idx.is_empty() {
            return Ok(());
        }
        for &i in idx {
            let _ = std::fs::remove_file(failure_path(self.cache, &tasks[i].key));
        }
        let keys: Vec<&Hash> = idx.iter().map(|&i| &tasks[i].key).collect();
        let limit = idx.iter().map(|&i| tasks[i].time_limit_s).fold(0.0, f64::max);
        match self.submit(&keys, attempt, limit) {
            Ok(job) => {
                for (index, &i) in idx.iter().enumerate() {
                    place.insert(i, Placement { job: job.clone(), index, attempt, adopted: false });
                }
            }
            Err(e) => {
                for &i in idx {
                    results[i] = Some(Err(TaskError::Worker { message: format!("submitting to SLURM: {e:#}") }));
                    done(i);
                }
            }
        }
        Ok(())
    }

    fn read_failure(&self, key: &str) -> Option<TaskError> {
        let bytes = crate::cache::read_regular(&failure_path(self.cache, key)).ok()?;
        let f: Failure = serde_json::from_slice(&bytes).ok()?;
        Some(f.error)
    }
}

/// The worker: runs the task on line `index` of `list` and writes its entry, or its
/// failure record, into the cache. Returns an error only if it could not even record the
/// failure.
pub fn work(registry: &super::kind::Registry, cache_dir: &Path, list: &Path, index: usize) -> Result<bool> {
    let cache = Cache::open_worker(cache_dir)?;
    let text = std::fs::read_to_string(list).with_context(|| format!("reading the task list {}", list.display()))?;
    let Some(key) = text.lines().nth(index) else {
        bail!("{}: no line {index} (the list has {} tasks)", list.display(), text.lines().count());
    };
    if !is_key(key) {
        bail!("{}: line {} is not a task key", list.display(), index + 1);
    }
    if cache.get(key).is_ok() {
        eprintln!("repro worker: {key} is already in the cache");
        return Ok(true);
    }
    let outcome = run_spec(registry, &cache, key);
    match outcome {
        Ok(wall) => {
            eprintln!("repro worker: computed {key} in {wall:.3} s");
            Ok(true)
        }
        Err(error) => {
            eprintln!("repro worker: task {key} failed: {error}");
            let f = Failure { key: key.to_string(), error };
            write_atomic(&failure_path(&cache, key), &serde_json::to_vec(&f)?, &cache.tmp_dir())?;
            Ok(false)
        }
    }
}

fn run_spec(registry: &super::kind::Registry, cache: &Cache, key: &str) -> Result<f64, TaskError> {
    let worker = |message: String| TaskError::Worker { message };
    let bytes = crate::cache::read_regular(&spec_path(cache, key))
        .map_err(|e| worker(format!("reading its task specification: {e}")))?;
    let spec: TaskSpec = serde_json::from_slice(&bytes).map_err(|e| worker(format!("its task specification: {e}")))?;
    if spec.key != key {
        return Err(worker(format!("its task specification holds key {}", spec.key)));
    }
    let kind = registry.get(&spec.kind).ok_or_else(|| worker(format!("unknown stage kind `{}`", spec.kind)))?;
    if kind.version() != spec.version {
        return Err(worker(format!(
            "this worker's {} is v{}, the coordinator's v{}: run the same repro build on the cluster",
            spec.kind,
            kind.version(),
            spec.version
        )));
    }
    let mut tables = BTreeMap::new();
    let mut input_hashes = BTreeMap::new();
    for (name, keys) in &spec.inputs {
        let mut t = super::table::Table::new();
        let mut hashes = Vec::with_capacity(keys.len());
        for k in keys {
            let e = cache.get(k).map_err(|m| worker(format!("input `{name}`: entry {k}: {m:?}")))?;
            t.append(&e.output.table).map_err(|e| worker(format!("input `{name}`: {e:#}")))?;
            hashes.push(e.output_hash);
        }
        tables.insert(name.clone(), t);
        input_hashes.insert(name.clone(), super::key::stage_hash(&hashes));
    }
    // The specification is validated before it is used: its content must hash to the key
    // the result will be stored under (a damaged or foreign file cannot plant a result).
    let actual = super::key::task_key(&spec.kind, spec.version, &spec.params, &input_hashes);
    if actual != key {
        return Err(worker(format!(
            "its task specification does not hash to its key (hashes to {actual}): damaged or foreign"
        )));
    }
    let inputs = super::kind::Inputs { tables: tables.iter().map(|(n, t)| (n.clone(), t)).collect() };
    let limit =
        (spec.time_limit_s > 0.0).then(|| Duration::try_from_secs_f64(spec.time_limit_s).unwrap_or(Duration::MAX));
    let (out, wall) = crate::task::compute_task(registry, kind, &spec.key, &spec.params, &inputs, cache, limit);
    out.map(|_| wall)
}

impl Backend for Coordinator<'_> {
    fn compute(
        &mut self,
        tasks: &[Task],
        _registry: &Registry,
        _cache: &Cache,
        done: &(dyn Fn(usize) + Sync),
    ) -> Result<Vec<Settled>> {
        let specs: Vec<TaskSpec> = tasks
            .iter()
            .map(|t| TaskSpec {
                key: t.key.clone(),
                kind: t.kind.name().to_string(),
                version: t.kind.version(),
                params: t.params.clone(),
                inputs: t.input_keys.iter().map(|(n, k)| (n.clone(), k.clone())).collect(),
                time_limit_s: t.time_limit.as_secs_f64(),
            })
            .collect();
        Ok(self
            .run(&specs, done)?
            .into_iter()
            .map(|r| {
                let (result, wall_time_s) = match r.result {
                    Ok(e) => (Ok(e.output), e.wall_time_s),
                    Err(e) => (Err(e), 0.0),
                };
                Settled { result, wall_time_s, started_s: None, ran_on: r.placement }
            })
            .collect())
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_time_limit_becomes_whole_minutes_with_one_to_spare() {
        // sbatch's --time in minutes: 600 s -> 11, 61 s -> 3, 1 s -> 2; none without a limit.
        assert_eq!(super::slurm_minutes(600.0), Some(11));
        assert_eq!(super::slurm_minutes(61.0), Some(3));
        assert_eq!(super::slurm_minutes(1.0), Some(2));
        assert_eq!(super::slurm_minutes(0.0), None);
        assert_eq!(super::slurm_minutes(f64::INFINITY), None);
    }
}
