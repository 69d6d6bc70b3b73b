//! The run loop: for each wave of stages, the planner's tasks ([`crate::plan`]), computed by
//! a backend ([`crate::backend`]: in this process, or on SLURM), then the stages' tables
//! assembled; at the end the manifests, the published files ([`crate::publish`]) and the
//! run report.
//!
//! Stages run in waves (a stage's wave is one more than that of the latest stage it
//! needs); within a wave, the tasks of all its stages run side by side. A stage's output
//! hash is the hash of its points' outputs, so a recomputed task that produces identical
//! bytes changes no downstream key (early cutoff). A failing task fails its stage; stages
//! that need it are skipped; independent stages carry on.
//!
//! One file: the waves, the adaptive rounds and the assembly share the run's state.

use crate::backend::{Backend, Local, Task};
use crate::cache::{Cache, LockMode, ManifestPoint, StageManifest};
use crate::graph;
use crate::key::{stage_hash, Hash};
use crate::kind::{DynKind, Inputs, Output, Registry};
use crate::plan::{plan_round, twin_reason, MatchedInput, StagePlan};
use crate::publish::{publish_stage, remove_stale_temporaries, OutputDirs};
use crate::reason::Reason;
use crate::report::{unix_ms, RunReport, Status, TaskRecord};
use crate::slurm::{Coordinator, SlurmOptions};
use crate::spec::{Pipeline, Stage};
use crate::table::Table;
use anyhow::{Context, Result};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Clone, Debug)]
pub struct RunOptions {
    pub cache_dir: PathBuf,
    pub figures_dir: PathBuf,
    pub tables_dir: PathBuf,
    pub jobs: Option<usize>,
    pub dry_run: bool,
    pub force: Vec<String>,
    pub targets: Vec<String>,
    pub lock: LockMode,
    pub progress: bool,
    pub executor: Executor,
    /// Every task's time limit in seconds (`--time-limit`), over the stages' and kinds' own.
    pub time_limit_s: Option<f64>,
    /// Counts the tasks to compute and those computed, for a caller that shows progress
    /// its own way (the Python package's tqdm bar).
    pub counter: Option<std::sync::Arc<TaskCounter>>,
}

/// Tasks to compute and computed so far in a run, read while it runs.
#[derive(Debug, Default)]
pub struct TaskCounter {
    pub total: std::sync::atomic::AtomicUsize,
    pub done: std::sync::atomic::AtomicUsize,
}

/// Where tasks are computed.
#[derive(Clone, Debug, Default)]
pub enum Executor {
    /// In this process, in parallel (rayon).
    #[default]
    Local,
    /// As SLURM job arrays whose workers write into the shared cache.
    Slurm(SlurmOptions),
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            cache_dir: "cache".into(),
            figures_dir: "figures".into(),
            tables_dir: "tables".into(),
            jobs: None,
            dry_run: false,
            force: Vec::new(),
            targets: Vec::new(),
            lock: LockMode::Wait,
            progress: true,
            executor: Executor::Local,
            time_limit_s: None,
            counter: None,
        }
    }
}

/// A task's time limit: the command line's, else its stage's `time_limit`, else its kind's.
fn time_limit(stage: &Stage, kind: &dyn DynKind, opts: &RunOptions) -> std::time::Duration {
    let s = opts.time_limit_s.or(stage.time_limit_s).unwrap_or_else(|| kind.time_limit_s());
    std::time::Duration::try_from_secs_f64(s).unwrap_or(std::time::Duration::MAX)
}

/// A command-line mistake: reported as invalid input.
#[derive(Debug, thiserror::Error)]
pub enum UsageError {
    /// `--target` or `--force` names no stage of the pipeline (the message names the
    /// nearest).
    #[error("{0}")]
    UnknownStage(String),
    /// Another argument the command cannot use (a worker without its index, a point's
    /// parameters that are no YAML).
    #[error("{0}")]
    Argument(String),
}

/// Why a run could not be carried out (failed tasks are not errors: the report records
/// them).
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The options name what the pipeline does not have (`--target`, `--force`).
    #[error(transparent)]
    Usage(#[from] UsageError),
    /// Another run holds the cache.
    #[error(transparent)]
    CacheBusy(#[from] crate::cache::CacheBusy),
    /// The cache, the backend or the file system failed.
    #[error(transparent)]
    Io(#[from] anyhow::Error),
}

impl From<crate::cache::OpenError> for RunError {
    fn from(e: crate::cache::OpenError) -> Self {
        match e {
            crate::cache::OpenError::Busy(b) => RunError::CacheBusy(b),
            crate::cache::OpenError::Io(e) => RunError::Io(e),
        }
    }
}

enum StageState {
    /// Per point: its key and output, and the wall time of its task (when it was computed).
    Done {
        hash: Hash,
        table: Table,
        points: Vec<(Hash, Output)>,
        /// Per point (in the order of `points`), its parameters.
        params: Vec<serde_json::Value>,
        times: Vec<f64>,
    },
    Failed,
    Skipped,
    Unknown,
}

/// An identifier of a pipeline file for per-pipeline records in the cache.
pub fn pipeline_id(p: &Pipeline) -> String {
    let abs = std::fs::canonicalize(&p.file).unwrap_or_else(|_| PathBuf::from(&p.file));
    blake3::hash(abs.to_string_lossy().as_bytes()).to_hex()[..16].to_string()
}

fn make_bar(multi: &indicatif::MultiProgress, stage: &str, n: usize) -> indicatif::ProgressBar {
    let bar = multi.add(indicatif::ProgressBar::new(n as u64));
    bar.set_style(
        indicatif::ProgressStyle::with_template("{prefix:>16} [{bar:30}] {pos}/{len} {elapsed_precise} eta {eta}")
            .unwrap()
            .progress_chars("=> "),
    );
    bar.set_prefix(stage.to_string());
    bar
}

/// Runs a pipeline (its targets and what they need): computes what the cache lacks,
/// publishes, records the run; returns its report.
pub fn run(p: &Pipeline, registry: &Registry, opts: &RunOptions) -> Result<RunReport, RunError> {
    run_keeping(p, registry, opts).map(|(report, _)| report)
}

/// A stage the run completed: per point its key and output, and the wall time its task
/// took (when it was computed, for a point the cache held).
pub struct Completed {
    pub stage: String,
    pub points: Vec<(Hash, Output)>,
    pub times: Vec<f64>,
}

/// [`run`], also returning the stages it completed, in the pipeline's order (for callers
/// that read the tables in memory, such as the Python package).
pub fn run_keeping(
    p: &Pipeline,
    registry: &Registry,
    opts: &RunOptions,
) -> Result<(RunReport, Vec<Completed>), RunError> {
    let start = Instant::now();
    let started_unix_ms = unix_ms();
    let selected = selected_stages(p, opts)?;
    let cache =
        if opts.dry_run { Cache::open_read_only(&opts.cache_dir) } else { Cache::open(&opts.cache_dir, opts.lock)? };
    let mut run = RunState::new(p, registry, opts, &cache, start)?;
    let order: Vec<usize> = graph::topological_order(p).into_iter().filter(|i| selected.contains(i)).collect();
    for stages_here in waves(p, &order, &run.index) {
        let mut plans = run.plan_wave(&stages_here);
        // Rounds: the stages' points, then the points adaptive stages add after each round.
        for round in 0.. {
            run.compute_round(&mut plans, round)?;
            if !run.refine_adaptive(&mut plans, round) {
                break;
            }
        }
        run.assemble_wave(plans)?;
    }
    let _ = run.multi.clear();
    run.finish(&order, started_unix_ms, start)
}

/// The stages a run selects: its targets and the stages they need (all, without targets);
/// an unknown target or stage to force is a usage error.
fn selected_stages(p: &Pipeline, opts: &RunOptions) -> Result<BTreeSet<usize>, RunError> {
    let mut target_idx = Vec::new();
    for t in &opts.targets {
        match p.stages.iter().position(|s| &s.name == t) {
            Some(i) => target_idx.push(i),
            None => return Err(UsageError::UnknownStage(crate::parse::unknown_stage("--target", t, p)).into()),
        }
    }
    for f in &opts.force {
        if p.stage(f).is_none() {
            return Err(UsageError::UnknownStage(crate::parse::unknown_stage("--force", f, p)).into());
        }
    }
    Ok(if target_idx.is_empty() { (0..p.stages.len()).collect() } else { graph::with_ancestors(p, &target_idx) })
}

/// The stages of `order` grouped in waves: a stage's wave is one more than that of the
/// latest stage it needs.
fn waves(p: &Pipeline, order: &[usize], index: &BTreeMap<&str, usize>) -> Vec<Vec<usize>> {
    let mut wave = vec![0usize; p.stages.len()];
    for &i in order {
        for n in &p.stages[i].needs {
            let j = index[n.as_str()];
            wave[i] = wave[i].max(wave[j] + 1);
        }
    }
    let n_waves = order.iter().map(|&i| wave[i] + 1).max().unwrap_or(0);
    (0..n_waves).map(|w| order.iter().copied().filter(|&i| wave[i] == w).collect()).collect()
}

/// What a run has settled so far, and what it computes with: the stages' states, the
/// tasks' records, the manifests to write, and the backends.
struct RunState<'a> {
    p: &'a Pipeline,
    registry: &'a Registry,
    opts: &'a RunOptions,
    cache: &'a Cache,
    pid: String,
    index: BTreeMap<&'a str, usize>,
    states: BTreeMap<usize, StageState>,
    records: Vec<TaskRecord>,
    manifests: Vec<(usize, StageManifest)>,
    local: Local,
    slurm: Option<Coordinator<'a>>,
    multi: indicatif::MultiProgress,
}

/// Per job, the points of each stage it needs: all of them, or for a stage read row by row,
/// those that match the job's parameters.
type JobNeeds = Vec<(String, Vec<usize>)>;

impl<'a> RunState<'a> {
    fn new(
        p: &'a Pipeline,
        registry: &'a Registry,
        opts: &'a RunOptions,
        cache: &'a Cache,
        start: Instant,
    ) -> Result<Self, RunError> {
        let multi = indicatif::MultiProgress::with_draw_target(if opts.progress {
            indicatif::ProgressDrawTarget::stderr()
        } else {
            indicatif::ProgressDrawTarget::hidden()
        });
        Ok(RunState {
            p,
            registry,
            opts,
            pid: pipeline_id(p),
            index: p.stages.iter().enumerate().map(|(i, s)| (s.name.as_str(), i)).collect(),
            cache,
            states: BTreeMap::new(),
            records: Vec::new(),
            manifests: Vec::new(),
            local: Local::new(opts.jobs, start)?,
            slurm: None,
            multi,
        })
    }

    /// The plans of a wave's stages; a stage whose needs failed or were skipped is skipped,
    /// one whose needs are unknown (a dry run) is unknown, and neither is planned.
    fn plan_wave(&mut self, stages_here: &[usize]) -> BTreeMap<usize, StagePlan> {
        let mut plans = BTreeMap::new();
        for &si in stages_here {
            let stage = &self.p.stages[si];
            let need_states: Vec<(&String, &StageState)> =
                stage.needs.iter().map(|n| (n, &self.states[&self.index[n.as_str()]])).collect();
            let blocked: Vec<&str> = need_states
                .iter()
                .filter(|(_, s)| matches!(s, StageState::Failed | StageState::Skipped))
                .map(|(n, _)| n.as_str())
                .collect();
            let unknown = need_states.iter().any(|(_, s)| matches!(s, StageState::Unknown));
            if !blocked.is_empty() || unknown {
                let (status, state, reason) = if !blocked.is_empty() {
                    (
                        Status::Skipped,
                        StageState::Skipped,
                        Reason::NeedsIncomplete { stages: blocked.iter().map(|s| s.to_string()).collect() },
                    )
                } else {
                    (Status::Unknown, StageState::Unknown, Reason::UpstreamWouldRun)
                };
                for pt in &stage.points {
                    self.records.push(TaskRecord::new(stage, &pt.label, None, status, Some(reason.clone())));
                }
                self.states.insert(si, state);
                continue;
            }
            let inputs: BTreeMap<String, Hash> = need_states
                .iter()
                .filter(|(n, _)| stage.matched(n).is_none())
                .map(|(n, s)| match s {
                    StageState::Done { hash, .. } => ((*n).clone(), hash.clone()),
                    _ => unreachable!(),
                })
                .collect();
            let matched = stage
                .matched
                .iter()
                .map(|m| match &self.states[&self.index[m.stage.as_str()]] {
                    StageState::Done { points, params, .. } => MatchedInput {
                        need: m.clone(),
                        upstream: points
                            .iter()
                            .zip(params)
                            .map(|((k, o), pa)| (pa.clone(), k.clone(), super::cache::output_hash(o)))
                            .collect(),
                    },
                    _ => unreachable!(),
                })
                .collect();
            plans.insert(
                si,
                StagePlan {
                    prev: self.cache.read_manifest(&self.pid, &stage.name),
                    inputs,
                    matched,
                    points: stage.points.clone(),
                    outs: Vec::new(),
                    failed: false,
                },
            );
        }
        plans
    }

    /// One round of a wave: the planner's answer for every point not yet settled (cached,
    /// to compute, or the same task as another), and in a real run the tasks computed and
    /// settled in their plans; a dry run records what would run.
    fn compute_round(&mut self, plans: &mut BTreeMap<usize, StagePlan>, round: usize) -> Result<()> {
        let crate::plan::Round { mut jobs, twins, cached } =
            plan_round(self.p, self.registry, self.cache, plans, &self.opts.force, round);
        self.records.extend(cached);
        if self.opts.dry_run {
            for j in &jobs {
                let stage = &self.p.stages[j.stage];
                let record =
                    TaskRecord::new(stage, &j.label, Some(j.key.clone()), Status::WouldRun, Some(j.reason.clone()));
                self.records.push(record);
            }
            for (j, first) in &twins {
                let reason = twin_reason(self.p, &jobs[*first]);
                let stage = &self.p.stages[j.stage];
                self.records.push(TaskRecord::new(stage, &j.label, Some(j.key.clone()), Status::Cached, Some(reason)));
            }
            return Ok(());
        }
        if jobs.is_empty() {
            return Ok(());
        }
        let outcomes = self.compute_jobs(plans, &jobs, round)?;
        // A twin takes its job's outcome.
        for (j, first) in &twins {
            let (out, dt) = (outcomes[*first].result.clone(), outcomes[*first].wall_time_s);
            let mut r = TaskRecord::new(
                &self.p.stages[j.stage],
                &j.label,
                Some(j.key.clone()),
                if out.is_ok() { Status::Cached } else { Status::Failed },
                Some(twin_reason(self.p, &jobs[*first])),
            );
            if let Err(e) = &out {
                r.failed_with(e.clone());
            }
            self.records.push(r);
            plans.get_mut(&j.stage).unwrap().settle(j, out, dt);
        }
        for (j, settled) in jobs.iter_mut().zip(outcomes) {
            let (out, dt) = (settled.result, settled.wall_time_s);
            j.ran_on = settled.ran_on;
            let stage = &self.p.stages[j.stage];
            let mut r = TaskRecord::new(
                stage,
                &j.label,
                Some(j.key.clone()),
                if out.is_ok() { Status::Computed } else { Status::Failed },
                Some(j.reason.clone()),
            );
            r.wall_time_s = dt;
            r.started_s = settled.started_s;
            if let Err(e) = &out {
                r.failed_with(e.clone());
            }
            r.ran_on = j.ran_on.clone();
            self.records.push(r);
            plans.get_mut(&j.stage).unwrap().settle(j, out, dt);
        }
        Ok(())
    }

    /// Computes a round's jobs on the run's backend, each with the tables it reads, a
    /// progress bar per stage; returns their outcomes in the jobs' order.
    fn compute_jobs(
        &mut self,
        plans: &BTreeMap<usize, StagePlan>,
        jobs: &[crate::plan::Job],
        round: usize,
    ) -> Result<Vec<crate::backend::Settled>> {
        let (p, states, index) = (self.p, &self.states, &self.index);
        let mut bars: BTreeMap<usize, indicatif::ProgressBar> = BTreeMap::new();
        for j in jobs {
            bars.entry(j.stage).or_insert_with(|| {
                let n = jobs.iter().filter(|k| k.stage == j.stage).count();
                let name = &p.stages[j.stage].name;
                let label = if round == 0 { name.clone() } else { format!("{name} (round {round})") };
                make_bar(&self.multi, &label, n)
            });
        }
        // The whole tables the stages need, for computing (the rows of the stages read row
        // by row are assembled per task).
        let input_tables: BTreeMap<usize, BTreeMap<String, &Table>> = plans
            .keys()
            .map(|&si| {
                let tables = p.stages[si]
                    .needs
                    .iter()
                    .filter(|n| p.stages[si].matched(n).is_none())
                    .map(|n| (n.clone(), done_table(states, index, n)))
                    .collect();
                (si, tables)
            })
            .collect();
        let job_needs: Vec<JobNeeds> = jobs.iter().map(|j| job_needs(p, states, index, &plans[&j.stage], j)).collect();
        let job_rows: Vec<BTreeMap<String, Table>> = jobs
            .iter()
            .zip(&job_needs)
            .map(|(j, needs)| matched_rows(p, states, index, j, needs))
            .collect::<Result<_>>()?;
        let job_inputs: Vec<Inputs> = jobs
            .iter()
            .zip(&job_rows)
            .map(|(j, rows)| {
                let mut tables = input_tables[&j.stage].clone();
                tables.extend(rows.iter().map(|(n, t)| (n.clone(), t)));
                Inputs { tables }
            })
            .collect();
        let tasks: Vec<Task> = jobs
            .iter()
            .zip(&job_inputs)
            .zip(&job_needs)
            .map(|((j, inputs), needs)| {
                let stage = &p.stages[j.stage];
                let kind = self.registry.get(&stage.kind).expect("validated kinds");
                Task {
                    key: &j.key,
                    kind,
                    params: &j.params,
                    inputs,
                    input_keys: needs
                        .iter()
                        .map(|(n, selected)| {
                            let points = done_points(states, index, n);
                            (n.clone(), selected.iter().map(|&i| points[i].0.clone()).collect())
                        })
                        .collect(),
                    time_limit: time_limit(stage, kind, self.opts),
                }
            })
            .collect();
        let backend: &mut dyn Backend = match &self.opts.executor {
            Executor::Local => &mut self.local,
            Executor::Slurm(so) => match &mut self.slurm {
                Some(c) => c,
                None => self.slurm.insert(Coordinator::new(self.cache, so.clone())?),
            },
        };
        if let Some(c) = &self.opts.counter {
            c.total.fetch_add(jobs.len(), std::sync::atomic::Ordering::Relaxed);
        }
        let counter = &self.opts.counter;
        let outcomes = backend.compute(&tasks, self.registry, self.cache, &|i| {
            bars[&jobs[i].stage].inc(1);
            if let Some(c) = counter {
                c.done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            }
        })?;
        for bar in bars.values() {
            bar.finish();
        }
        Ok(outcomes)
    }

    /// After a round, the adaptive stages whose points are all known choose their next
    /// points; whether any stage grew (then another round follows).
    fn refine_adaptive(&mut self, plans: &mut BTreeMap<usize, StagePlan>, round: usize) -> bool {
        let mut grew = false;
        for (&si, plan) in plans.iter_mut() {
            let stage = &self.p.stages[si];
            let Some(axis) = &stage.adaptive else { continue };
            if plan.failed {
                continue;
            }
            let label = format!("(adaptive refinement of {} after round {round})", axis.param);
            if plan.outs.iter().any(Option::is_none) {
                // Dry run: what follows depends on the points that would run.
                self.records.push(TaskRecord::new(
                    stage,
                    &label,
                    None,
                    Status::Unknown,
                    Some(Reason::AdaptiveWouldRun),
                ));
                continue;
            }
            let outputs: Vec<&Output> = plan.outs.iter().map(|o| &o.as_ref().unwrap().1).collect();
            let kind = self.registry.get(&stage.kind).unwrap();
            match super::adaptive::next_points(axis, kind, &plan.points, &outputs) {
                Ok(new) => {
                    grew |= !new.is_empty();
                    plan.points.extend(new);
                }
                Err(e) => {
                    let mut r = TaskRecord::new(stage, &label, None, Status::Failed, None);
                    r.error = Some(e.to_string());
                    self.records.push(r);
                    plan.failed = true;
                }
            }
        }
        grew
    }

    /// Each stage of a finished wave: failed, unknown (a dry run), or done, its points in
    /// publication order, its table assembled and its manifest kept for the end.
    fn assemble_wave(&mut self, plans: BTreeMap<usize, StagePlan>) -> Result<()> {
        for (si, mut plan) in plans {
            let stage = &self.p.stages[si];
            let kind = self.registry.get(&stage.kind).unwrap();
            let state = if plan.failed {
                StageState::Failed
            } else if plan.outs.iter().any(Option::is_none) {
                StageState::Unknown // dry run
            } else {
                let order: Vec<usize> = match &stage.adaptive {
                    Some(axis) => super::adaptive::publication_order(axis, &plan.points),
                    None => (0..plan.points.len()).collect(),
                };
                let mut outs = std::mem::take(&mut plan.outs);
                let params: Vec<serde_json::Value> = order.iter().map(|&i| plan.points[i].params.clone()).collect();
                let (points, times): (Vec<(Hash, Output)>, Vec<f64>) = order
                    .iter()
                    .map(|&i| {
                        let (k, o, dt) = outs[i].take().unwrap();
                        ((k, o), dt)
                    })
                    .unzip();
                let hashes: Vec<Hash> = points.iter().map(|(_, o)| super::cache::output_hash(o)).collect();
                let mut table = Table::new();
                for (_, o) in &points {
                    table
                        .append(&o.table)
                        .with_context(|| format!("assembling the table of stage `{}`", stage.name))?;
                }
                self.manifests.push((
                    si,
                    StageManifest {
                        kind: stage.kind.clone(),
                        version: kind.version(),
                        inputs: std::mem::take(&mut plan.inputs),
                        points: order
                            .iter()
                            .zip(&points)
                            .map(|(&i, (k, _))| ManifestPoint {
                                label: plan.points[i].label.clone(),
                                params: plan.points[i].params.clone(),
                                key: k.clone(),
                                inputs: plan.matched_inputs(&plan.points[i].params),
                            })
                            .collect(),
                    },
                ));
                StageState::Done { hash: stage_hash(&hashes), table, points, params, times }
            };
            self.states.insert(si, state);
        }
        Ok(())
    }

    /// The end of a run: the manifests and published files written (what cannot be is
    /// recorded and the rest still written), the stages' notes and regressions gathered,
    /// the report kept in the run history; returns it with the completed stages.
    fn finish(
        self,
        order: &[usize],
        started_unix_ms: u64,
        start: Instant,
    ) -> Result<(RunReport, Vec<Completed>), RunError> {
        let (p, opts) = (self.p, self.opts);
        let pipeline_dir = Path::new(&p.file).parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        let mut report = RunReport {
            started_unix_ms,
            pipeline: p.file.clone(),
            overrides: p.overrides.clone(),
            dry_run: opts.dry_run,
            git_commit: crate::report::git_commit(pipeline_dir).map(|(c, modified)| {
                if modified {
                    format!("{c} (modified)")
                } else {
                    c
                }
            }),
            tasks: self.records,
            ..Default::default()
        };
        if !opts.dry_run {
            remove_stale_temporaries(&[&opts.figures_dir, &opts.tables_dir]);
            let dirs = OutputDirs { figures: opts.figures_dir.clone(), tables: opts.tables_dir.clone() };
            // A manifest or a published file that cannot be written (a full disk) is recorded,
            // and the rest still written: the other stages' outputs and the report.
            for (si, m) in &self.manifests {
                if let Err(e) = self.cache.write_manifest(&self.pid, &p.stages[*si].name, m) {
                    report.errors.push(format!("stage `{}`: its manifest: {e:#}", p.stages[*si].name));
                }
            }
            for &si in order {
                if let Some(StageState::Done { points, times, .. }) =
                    self.states.get(&si).filter(|_| p.stages[si].publish)
                {
                    match publish_stage(p, &p.stages[si], self.registry, points, times, &dirs) {
                        Ok(written) => report.published.extend(written),
                        Err(e) => report.errors.push(format!("stage `{}`: publishing: {e:#}", p.stages[si].name)),
                    }
                }
            }
        }
        for &si in order {
            if let Some(StageState::Done { points, .. }) = self.states.get(&si) {
                for (_, o) in points {
                    report.notes.extend(o.notes.iter().cloned());
                    let stage = &p.stages[si].name;
                    report.regressions.extend(o.regressions.iter().map(|r| format!("{stage}: {r}")));
                }
            }
        }
        report.wall_time_s = start.elapsed().as_secs_f64();
        report.finalize_counts();
        if !opts.dry_run {
            // The run's report, kept in the history (`repro runs`, and the roots of `repro gc`),
            // and as the last run.
            let bytes = serde_json::to_vec_pretty(&report).context("serialising the run report")?;
            let runs = self.cache.root.join("runs");
            let name = format!("run-{:013}-{}.json", report.started_unix_ms, std::process::id());
            for path in [runs.join(name), runs.join("last.json")] {
                if let Err(e) = super::cache::write_atomic(&path, &bytes, &self.cache.tmp_dir()) {
                    report.errors.push(format!("the run history: {e:#}"));
                    break;
                }
            }
        }
        let mut completed = Vec::new();
        for (si, state) in self.states {
            if let StageState::Done { points, times, .. } = state {
                completed.push(Completed { stage: p.stages[si].name.clone(), points, times });
            }
        }
        Ok((report, completed))
    }
}

/// The table of a needed stage that is done.
fn done_table<'s>(states: &'s BTreeMap<usize, StageState>, index: &BTreeMap<&str, usize>, need: &str) -> &'s Table {
    match &states[&index[need]] {
        StageState::Done { table, .. } => table,
        _ => unreachable!("a stage runs after the stages it needs are done"),
    }
}

/// The points (key and output) of a needed stage that is done.
fn done_points<'s>(
    states: &'s BTreeMap<usize, StageState>,
    index: &BTreeMap<&str, usize>,
    need: &str,
) -> &'s [(Hash, Output)] {
    match &states[&index[need]] {
        StageState::Done { points, .. } => points,
        _ => unreachable!("a stage runs after the stages it needs are done"),
    }
}

/// The points of each stage a job needs: all of them, or for a stage read row by row, those
/// that match the job's parameters.
fn job_needs(
    p: &Pipeline,
    states: &BTreeMap<usize, StageState>,
    index: &BTreeMap<&str, usize>,
    plan: &StagePlan,
    j: &crate::plan::Job,
) -> JobNeeds {
    p.stages[j.stage]
        .needs
        .iter()
        .map(|n| match plan.matched.iter().find(|m| &m.need.stage == n) {
            Some(m) => (n.clone(), m.select(&j.params)),
            None => (n.clone(), (0..done_points(states, index, n).len()).collect()),
        })
        .collect()
}

/// The rows a job reads of the stages it reads row by row, assembled into a table each.
fn matched_rows(
    p: &Pipeline,
    states: &BTreeMap<usize, StageState>,
    index: &BTreeMap<&str, usize>,
    j: &crate::plan::Job,
    needs: &JobNeeds,
) -> Result<BTreeMap<String, Table>> {
    needs
        .iter()
        .filter(|(n, _)| p.stages[j.stage].matched(n).is_some())
        .map(|(n, selected)| {
            let points = done_points(states, index, n);
            let mut t = Table::new();
            for &i in selected {
                t.append(&points[i].1.table).with_context(|| format!("assembling the rows of stage `{n}`"))?;
            }
            Ok((n.clone(), t))
        })
        .collect()
}
