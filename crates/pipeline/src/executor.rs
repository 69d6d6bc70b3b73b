//! Runs a pipeline: plans each stage's tasks from their keys, takes what the cache holds,
//! computes the rest in parallel (rayon), assembles stage tables and publishes them.
//!
//! Stages run in waves (a stage's wave is one more than that of the latest stage it
//! needs); within a wave, the tasks of all its stages run side by side. A stage's output
//! hash is the hash of its points' outputs, so a recomputed task that produces identical
//! bytes changes no downstream key (early cutoff). A failing task fails its stage; stages
//! that need it are skipped; independent stages carry on.

use super::cache::{Cache, Entry, LockMode, ManifestPoint, Miss, StageManifest};
use super::graph;
use super::key::{stage_hash, task_key, Hash};
use super::kind::{DynKind, Inputs, Output, Registry};
use super::report::{RunReport, Status, TaskRecord};
use super::slurm::{SlurmOptions, TaskSpec};
use super::spec::{Pipeline, Point, Stage};
use super::table::{ColumnData, Table};
use anyhow::{bail, Context, Result};
use rayon::prelude::*;
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
        }
    }
}

/// A task's time limit: the command line's, else its stage's `time_limit`, else its kind's.
fn time_limit(stage: &Stage, kind: &dyn DynKind, opts: &RunOptions) -> std::time::Duration {
    let s = opts.time_limit_s.or(stage.time_limit_s).unwrap_or_else(|| kind.time_limit_s());
    std::time::Duration::try_from_secs_f64(s).unwrap_or(std::time::Duration::MAX)
}

/// A command-line mistake (unknown target, ...): reported as invalid input.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

enum StageState {
    /// Per point: its key and output, and the wall time of its task (when it was computed).
    Done {
        hash: Hash,
        table: Table,
        points: Vec<(Hash, Output)>,
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

fn stale_reason(
    prev: Option<&StageManifest>,
    stage: &Stage,
    version: u32,
    inputs: &BTreeMap<String, Hash>,
    point: &Point,
    key: &str,
    overrides: &[String],
) -> String {
    let Some(m) = prev else { return "never run".into() };
    // A parameter set on the command line says so.
    let set_by_cli = |k: &str| overrides.iter().any(|o| o.starts_with(&format!("{}.{k}=", stage.name)));
    if m.kind != stage.kind {
        return format!("kind changed ({} -> {})", m.kind, stage.kind);
    }
    let same = m.points.iter().find(|mp| mp.params == point.params);
    match same {
        Some(mp) => {
            if m.version != version {
                format!("code version of {} changed (v{} -> v{version})", stage.kind, m.version)
            } else if &m.inputs != inputs {
                let changed: Vec<&str> = inputs
                    .iter()
                    .filter(|(n, h)| m.inputs.get(*n) != Some(*h))
                    .map(|(n, _)| n.as_str())
                    .chain(m.inputs.keys().filter(|n| !inputs.contains_key(*n)).map(|n| n.as_str()))
                    .collect();
                format!("input changed: {}", changed.join(", "))
            } else if mp.key == key {
                "cache entry missing".into()
            } else {
                "key changed".into()
            }
        }
        None => {
            // The previous point nearest to this one (fewest parameters differing): a change
            // of swept parameters alone is a new sweep point; any other is a parameter change,
            // named with its old and new values.
            let diff = |a: &serde_json::Value| -> Vec<(String, String, String)> {
                let (Some(a), Some(b)) = (a.as_object(), point.params.as_object()) else { return Vec::new() };
                let keys: BTreeSet<&String> = a.keys().chain(b.keys()).collect();
                let show = |v: Option<&serde_json::Value>| v.map_or("(none)".to_string(), |v| short(&v.to_string()));
                keys.into_iter()
                    .filter(|k| a.get(*k) != b.get(*k))
                    .map(|k| (k.clone(), show(a.get(k)), show(b.get(k))))
                    .collect()
            };
            let nearest = m.points.iter().map(|mp| diff(&mp.params)).min_by_key(|d| d.len()).unwrap_or_default();
            let swept = |k: &str| point.label.split(' ').any(|kv| kv.split('=').next() == Some(k));
            if !point.label.is_empty() && nearest.iter().all(|(k, _, _)| swept(k)) {
                format!("new sweep point {}", point.label)
            } else {
                let changes: Vec<String> = nearest
                    .iter()
                    .map(|(k, a, b)| format!("{k}: {a} -> {b}{}", if set_by_cli(k) { " (-S)" } else { "" }))
                    .collect();
                format!("parameters changed: {}", changes.join(", "))
            }
        }
    }
}

/// A value for a message: at most 40 characters.
fn short(s: &str) -> String {
    if s.chars().count() <= 40 {
        s.to_string()
    } else {
        format!("{}…", s.chars().take(39).collect::<String>())
    }
}

/// Adds the per-row task key and the code version to a stage's table, for publishing, and
/// the task's wall time as `wall_time_s` where the kind does not report its own, and as
/// `task_time_s` on the task's first row only (0 on the others: the column sums to the
/// stage's cost); not to a figure's data: its numbers are those of the stages it draws.
fn provenance_table(points: &[(Hash, Output)], times: &[f64], code_version: &str, figure: bool) -> Result<Table> {
    let mut table = Table::new();
    for ((key, out), &dt) in points.iter().zip(times) {
        let n = out.table.n_rows();
        let mut t = out.table.clone();
        if !figure && t.column("wall_time_s").is_none() {
            t = t.with_f64("wall_time_s", vec![dt; n]);
        }
        if !figure {
            t = t.with_f64("task_time_s", (0..n).map(|i| if i == 0 { dt } else { 0.0 }).collect());
        }
        let t = t
            .with("task_key", ColumnData::Str(vec![key.clone(); n]))
            .with("code_version", ColumnData::Str(vec![code_version.to_string(); n]));
        table.append(&t)?;
    }
    Ok(table)
}

/// Writes `bytes` to `path` unless it already holds them; returns whether it wrote.
fn publish_file(path: &Path, bytes: &[u8]) -> Result<bool> {
    if std::fs::read(path).map(|b| b == bytes).unwrap_or(false) {
        return Ok(false);
    }
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    super::cache::write_atomic(path, bytes, dir)?;
    Ok(true)
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

struct Job {
    stage: usize,
    point: usize,
    key: Hash,
    reason: String,
    params: serde_json::Value,
    label: String,
    ran_on: Option<String>,
}

/// A stage of the current wave while its rounds run: its points so far (an adaptive stage
/// adds some after each round) and, per point, its output once known.
struct StagePlan {
    prev: Option<StageManifest>,
    inputs: BTreeMap<String, Hash>,
    points: Vec<Point>,
    /// Per point, once known: its key, output and the wall time of its task.
    outs: Vec<Option<(Hash, Output, f64)>>,
    failed: bool,
}

impl StagePlan {
    /// Records the outcome of a job of this stage (a failure fails the stage).
    fn settle(&mut self, j: &Job, out: Result<Output, String>, dt: f64) {
        match out {
            Ok(o) => {
                self.outs[j.point] = Some((j.key.clone(), o, dt));
            }
            Err(_) => self.failed = true,
        }
    }
}

pub fn run(p: &Pipeline, registry: &Registry, opts: &RunOptions) -> Result<RunReport> {
    let start = Instant::now();
    let started_unix_ms = unix_ms();
    let mut target_idx = Vec::new();
    for t in &opts.targets {
        match p.stages.iter().position(|s| &s.name == t) {
            Some(i) => target_idx.push(i),
            None => {
                return Err(UsageError(format!(
                    "--target {t}: no stage of that name in {} (stages: {})",
                    p.file,
                    p.stages.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", ")
                ))
                .into())
            }
        }
    }
    for f in &opts.force {
        if p.stage(f).is_none() {
            return Err(UsageError(format!("--force {f}: no stage of that name in {}", p.file)).into());
        }
    }
    let selected: BTreeSet<usize> =
        if target_idx.is_empty() { (0..p.stages.len()).collect() } else { graph::with_ancestors(p, &target_idx) };
    let cache =
        if opts.dry_run { Cache::open_read_only(&opts.cache_dir) } else { Cache::open(&opts.cache_dir, opts.lock)? };
    let pid = pipeline_id(p);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(opts.jobs.unwrap_or(0)).build()?;
    let multi = indicatif::MultiProgress::with_draw_target(if opts.progress {
        indicatif::ProgressDrawTarget::stderr()
    } else {
        indicatif::ProgressDrawTarget::hidden()
    });

    let index: BTreeMap<&str, usize> = p.stages.iter().enumerate().map(|(i, s)| (s.name.as_str(), i)).collect();
    let order: Vec<usize> = graph::topological_order(p).into_iter().filter(|i| selected.contains(i)).collect();
    let mut wave = vec![0usize; p.stages.len()];
    for &i in &order {
        for n in &p.stages[i].needs {
            let j = index[n.as_str()];
            wave[i] = wave[i].max(wave[j] + 1);
        }
    }
    let n_waves = order.iter().map(|&i| wave[i] + 1).max().unwrap_or(0);
    let mut states: BTreeMap<usize, StageState> = BTreeMap::new();
    let mut records: Vec<TaskRecord> = Vec::new();
    let mut manifests: Vec<(usize, StageManifest)> = Vec::new();
    let mut slurm: Option<super::slurm::Coordinator> = None;

    for w in 0..n_waves {
        let stages_here: Vec<usize> = order.iter().copied().filter(|&i| wave[i] == w).collect();
        let mut plans: BTreeMap<usize, StagePlan> = BTreeMap::new();
        for &si in &stages_here {
            let stage = &p.stages[si];
            let need_states: Vec<(&String, &StageState)> =
                stage.needs.iter().map(|n| (n, &states[&index[n.as_str()]])).collect();
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
                        format!("needs {} which did not complete", blocked.join(", ")),
                    )
                } else {
                    (Status::Unknown, StageState::Unknown, "upstream stages would run first".to_string())
                };
                for pt in &stage.points {
                    records.push(TaskRecord::new(stage, &pt.label, None, status, Some(reason.clone())));
                }
                states.insert(si, state);
                continue;
            }
            let inputs: BTreeMap<String, Hash> = need_states
                .iter()
                .map(|(n, s)| match s {
                    StageState::Done { hash, .. } => ((*n).clone(), hash.clone()),
                    _ => unreachable!(),
                })
                .collect();
            plans.insert(
                si,
                StagePlan {
                    prev: cache.read_manifest(&pid, &stage.name),
                    inputs,
                    points: stage.points.clone(),
                    outs: Vec::new(),
                    failed: false,
                },
            );
        }
        // The inputs' tables, for computing.
        let input_tables: BTreeMap<usize, Inputs> = plans
            .keys()
            .map(|&si| {
                let tables = p.stages[si]
                    .needs
                    .iter()
                    .map(|n| match &states[&index[n.as_str()]] {
                        StageState::Done { table, .. } => (n.clone(), table),
                        _ => unreachable!(),
                    })
                    .collect();
                (si, Inputs { tables })
            })
            .collect();

        // Rounds: the stages' points, then the points adaptive stages add after each round.
        for round in 0.. {
            let mut jobs: Vec<Job> = Vec::new();
            // Tasks of this round whose key another stage's task already has (two stages
            // sharing points): computed once, with the index of the job that computes them.
            let mut twins: Vec<(Job, usize)> = Vec::new();
            let mut job_of_key: BTreeMap<Hash, usize> = BTreeMap::new();
            for (&si, plan) in plans.iter_mut() {
                let stage = &p.stages[si];
                let kind = registry.get(&stage.kind).expect("validated kinds");
                let forced = opts.force.contains(&stage.name);
                for pi in plan.outs.len()..plan.points.len() {
                    let pt = &plan.points[pi];
                    let key = task_key(&stage.kind, kind.version(), &pt.params, &plan.inputs);
                    let lookup = if forced { Err(Miss::Absent) } else { cache.get(&key) };
                    match lookup {
                        Ok(entry) => {
                            records.push(TaskRecord::new(stage, &pt.label, Some(key.clone()), Status::Cached, None));
                            plan.outs.push(Some((key, entry.output, entry.wall_time_s)));
                        }
                        Err(miss) => {
                            let mut reason = match miss {
                                _ if forced => "forced (--force)".to_string(),
                                Miss::Corrupted(why) => {
                                    eprintln!("repro: warning: cache entry {key} of stage `{}` is corrupted ({why}); recomputing it", stage.name);
                                    format!("corrupted cache entry ({why})")
                                }
                                Miss::Absent => stale_reason(
                                    plan.prev.as_ref(),
                                    stage,
                                    kind.version(),
                                    &plan.inputs,
                                    pt,
                                    &key,
                                    &p.overrides,
                                ),
                            };
                            if round > 0 {
                                reason = format!("adaptive refinement, round {round} ({reason})");
                            }
                            let job = Job {
                                stage: si,
                                point: pi,
                                key,
                                reason,
                                params: pt.params.clone(),
                                label: pt.label.clone(),
                                ran_on: None,
                            };
                            match job_of_key.get(&job.key) {
                                Some(&first) => twins.push((job, first)),
                                None => {
                                    job_of_key.insert(job.key.clone(), jobs.len());
                                    jobs.push(job);
                                }
                            }
                            plan.outs.push(None);
                        }
                    }
                }
            }
            let twin_reason = |first: &Job| {
                format!("the same task as stage `{}` point {} (computed once)", p.stages[first.stage].name, first.label)
            };
            if opts.dry_run {
                for j in &jobs {
                    let stage = &p.stages[j.stage];
                    records.push(TaskRecord::new(
                        stage,
                        &j.label,
                        Some(j.key.clone()),
                        Status::WouldRun,
                        Some(j.reason.clone()),
                    ));
                }
                for (j, first) in &twins {
                    let reason = twin_reason(&jobs[*first]);
                    records.push(TaskRecord::new(
                        &p.stages[j.stage],
                        &j.label,
                        Some(j.key.clone()),
                        Status::Cached,
                        Some(reason),
                    ));
                }
            } else if !jobs.is_empty() {
                let mut bars: BTreeMap<usize, indicatif::ProgressBar> = BTreeMap::new();
                for j in &jobs {
                    bars.entry(j.stage).or_insert_with(|| {
                        let n = jobs.iter().filter(|k| k.stage == j.stage).count();
                        let name = &p.stages[j.stage].name;
                        let label = if round == 0 { name.clone() } else { format!("{name} (round {round})") };
                        make_bar(&multi, &label, n)
                    });
                }
                // Per job: its outcome, its wall time and when it started (seconds from the start of
                // the run; not known for jobs run elsewhere).
                let outcomes: Vec<(Result<Output, String>, f64, Option<f64>)> = match &opts.executor {
                    Executor::Local => pool.install(|| {
                        // One task per split: tasks differ in cost by orders of magnitude, and rayon's
                        // default splitting can leave several expensive tasks queued behind one
                        // another on one thread while the other idles.
                        jobs.par_iter()
                            .with_max_len(1)
                            .map(|j| {
                                let kind = registry.get(&p.stages[j.stage].kind).unwrap();
                                let started = start.elapsed().as_secs_f64();
                                let limit = time_limit(&p.stages[j.stage], kind, opts);
                                let (out, dt) = compute_task(
                                    registry,
                                    kind,
                                    &j.key,
                                    &j.params,
                                    &input_tables[&j.stage],
                                    &cache,
                                    Some(limit),
                                );
                                bars[&j.stage].inc(1);
                                (out, dt, Some(started))
                            })
                            .collect()
                    }),
                    Executor::Slurm(so) => {
                        let coordinator = match &mut slurm {
                            Some(c) => c,
                            None => slurm.insert(super::slurm::Coordinator::new(&cache, so.clone())?),
                        };
                        let specs: Vec<TaskSpec> = jobs
                            .iter()
                            .map(|j| {
                                let stage = &p.stages[j.stage];
                                TaskSpec {
                                    key: j.key.clone(),
                                    kind: stage.kind.clone(),
                                    version: registry.get(&stage.kind).unwrap().version(),
                                    params: j.params.clone(),
                                    inputs: stage
                                        .needs
                                        .iter()
                                        .map(|n| match &states[&index[n.as_str()]] {
                                            StageState::Done { points, .. } => {
                                                (n.clone(), points.iter().map(|(k, _)| k.clone()).collect())
                                            }
                                            _ => unreachable!(),
                                        })
                                        .collect(),
                                    time_limit_s: time_limit(stage, registry.get(&stage.kind).unwrap(), opts)
                                        .as_secs_f64(),
                                }
                            })
                            .collect();
                        let results = coordinator.run(&specs, &|i| bars[&jobs[i].stage].inc(1))?;
                        jobs.iter_mut()
                            .zip(results)
                            .map(|(j, s)| {
                                j.ran_on = s.placement;
                                match s.result {
                                    Ok(entry) => (Ok(entry.output), entry.wall_time_s, None),
                                    Err(e) => (Err(e), 0.0, None),
                                }
                            })
                            .collect()
                    }
                };
                for bar in bars.values() {
                    bar.finish();
                }
                // A twin takes its job's outcome.
                let twin_outcomes: Vec<(Result<Output, String>, f64)> =
                    twins.iter().map(|(_, first)| (outcomes[*first].0.clone(), outcomes[*first].1)).collect();
                for ((j, first), (out, dt)) in twins.iter().zip(twin_outcomes) {
                    let mut r = TaskRecord::new(
                        &p.stages[j.stage],
                        &j.label,
                        Some(j.key.clone()),
                        if out.is_ok() { Status::Cached } else { Status::Failed },
                        Some(twin_reason(&jobs[*first])),
                    );
                    r.error = out.as_ref().err().cloned();
                    records.push(r);
                    plans.get_mut(&j.stage).unwrap().settle(j, out, dt);
                }
                for (j, (out, dt, started)) in jobs.iter().zip(outcomes) {
                    let stage = &p.stages[j.stage];
                    let mut r = TaskRecord::new(
                        stage,
                        &j.label,
                        Some(j.key.clone()),
                        if out.is_ok() { Status::Computed } else { Status::Failed },
                        Some(j.reason.clone()),
                    );
                    r.wall_time_s = dt;
                    r.started_s = started;
                    r.error = out.as_ref().err().cloned();
                    r.ran_on = j.ran_on.clone();
                    records.push(r);
                    plans.get_mut(&j.stage).unwrap().settle(j, out, dt);
                }
            }
            // Adaptive stages whose points are all known choose their next points.
            let mut grew = false;
            for (&si, plan) in plans.iter_mut() {
                let stage = &p.stages[si];
                let Some(axis) = &stage.adaptive else { continue };
                if plan.failed {
                    continue;
                }
                if plan.outs.iter().any(Option::is_none) {
                    // Dry run: what follows depends on the points that would run.
                    records.push(TaskRecord::new(
                        stage,
                        &format!("(adaptive refinement of {} after round {round})", axis.param),
                        None,
                        Status::Unknown,
                        Some("further points depend on the results of the points that would run".into()),
                    ));
                    continue;
                }
                let outputs: Vec<&Output> = plan.outs.iter().map(|o| &o.as_ref().unwrap().1).collect();
                match super::adaptive::next_points(axis, registry.get(&stage.kind).unwrap(), &plan.points, &outputs) {
                    Ok(new) => {
                        grew |= !new.is_empty();
                        plan.points.extend(new);
                    }
                    Err(e) => {
                        let mut r = TaskRecord::new(
                            stage,
                            &format!("(adaptive refinement of {} after round {round})", axis.param),
                            None,
                            Status::Failed,
                            None,
                        );
                        r.error = Some(e);
                        records.push(r);
                        plan.failed = true;
                    }
                }
            }
            if !grew {
                break;
            }
        }
        drop(input_tables);

        // Assemble each stage of the wave.
        for (si, plan) in plans {
            let stage = &p.stages[si];
            let kind = registry.get(&stage.kind).unwrap();
            let state = if plan.failed {
                StageState::Failed
            } else if plan.outs.iter().any(Option::is_none) {
                StageState::Unknown // dry run
            } else {
                let order: Vec<usize> = match &stage.adaptive {
                    Some(axis) => super::adaptive::publication_order(axis, &plan.points),
                    None => (0..plan.points.len()).collect(),
                };
                let mut outs = plan.outs;
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
                manifests.push((
                    si,
                    StageManifest {
                        kind: stage.kind.clone(),
                        version: kind.version(),
                        inputs: plan.inputs,
                        points: order
                            .iter()
                            .zip(&points)
                            .map(|(&i, (k, _))| ManifestPoint {
                                label: plan.points[i].label.clone(),
                                params: plan.points[i].params.clone(),
                                key: k.clone(),
                            })
                            .collect(),
                    },
                ));
                StageState::Done { hash: stage_hash(&hashes), table, points, times }
            };
            states.insert(si, state);
        }
    }
    let _ = multi.clear();

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
        tasks: records,
        ..Default::default()
    };
    if !opts.dry_run {
        remove_stale_temporaries(&[&opts.figures_dir, &opts.tables_dir]);
        // A manifest or a published file that cannot be written (a full disk) is recorded,
        // and the rest still written: the other stages' outputs and the report.
        for (si, m) in &manifests {
            if let Err(e) = cache.write_manifest(&pid, &p.stages[*si].name, m) {
                report.errors.push(format!("stage `{}`: its manifest: {e:#}", p.stages[*si].name));
            }
        }
        for &si in &order {
            if let Some(StageState::Done { points, times, .. }) = states.get(&si).filter(|_| p.stages[si].publish) {
                match publish_stage(p, &p.stages[si], registry, points, times, opts) {
                    Ok(written) => report.published.extend(written),
                    Err(e) => report.errors.push(format!("stage `{}`: publishing: {e:#}", p.stages[si].name)),
                }
            }
        }
    }
    for &si in &order {
        if let Some(StageState::Done { points, .. }) = states.get(&si) {
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
        let bytes = serde_json::to_vec_pretty(&report)?;
        let runs = cache.root.join("runs");
        let name = format!("run-{:013}-{}.json", report.started_unix_ms, std::process::id());
        for path in [runs.join(name), runs.join("last.json")] {
            if let Err(e) = super::cache::write_atomic(&path, &bytes, &cache.tmp_dir()) {
                report.errors.push(format!("the run history: {e:#}"));
                break;
            }
        }
    }
    Ok(report)
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
            let r: RunReport = serde_json::from_slice(&std::fs::read(&p).ok()?).ok()?;
            Some((p, r))
        })
        .collect();
    runs.sort_by(|a, b| a.1.started_unix_ms.cmp(&b.1.started_unix_ms).then(a.0.cmp(&b.0)));
    runs
}

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
}

/// Computes one task and stores its entry (atomically): the kind's run with panics caught,
/// held to `limit` (`Registry::run_limited`), its table checked (no NaN or infinity).
/// Returns the output or the error, and the wall time. Shared by the local executor and the
/// SLURM worker.
pub fn compute_task(
    registry: &Registry,
    kind: &dyn DynKind,
    key: &Hash,
    params: &serde_json::Value,
    inputs: &Inputs,
    cache: &Cache,
    limit: Option<std::time::Duration>,
) -> (Result<Output, String>, f64) {
    super::fault::point("task.start");
    let t0 = Instant::now();
    let res =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| registry.run_limited(kind, params, inputs, limit)));
    let out = match res {
        Ok(Ok(out)) => out.table.check().map(|_| out).map_err(|e| format!("invalid output: {e:#}")),
        Ok(Err(e)) => Err(format!("{e:#}")),
        Err(panic) => Err(format!(
            "panicked: {}",
            panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default()
        )),
    };
    let dt = t0.elapsed().as_secs_f64();
    let out = out.and_then(|o| {
        let entry = Entry::new(key.clone(), kind.name(), kind.version(), params.clone(), o, dt);
        cache.put(&entry).map_err(|e| format!("writing the cache entry: {e:#}"))?;
        Ok(entry.output)
    });
    (out, dt)
}

/// Removes temporary files a killed run left while publishing (`.repro-<pid>-<n>.tmp`), and
/// only those: a temporary of a process that is still running (another run publishing into
/// the same folder) is left alone. Where the system does not say which processes run (no
/// `/proc`), only temporaries older than a day are removed.
fn remove_stale_temporaries(dirs: &[&Path]) {
    let procs = Path::new("/proc/self").exists();
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(dir) else { continue };
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().to_string();
            let Some(pid) = name.strip_prefix(".repro-").and_then(|r| r.strip_suffix(".tmp")) else { continue };
            let pid = pid.split('-').next().and_then(|p| p.parse::<u32>().ok());
            let stale = match pid {
                Some(pid) if procs => pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists(),
                _ => e
                    .metadata()
                    .and_then(|m| m.modified())
                    .is_ok_and(|t| t.elapsed().is_ok_and(|age| age > std::time::Duration::from_secs(86400))),
            };
            if stale {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
}

/// The parameters every point of `stage` shares, canonical (defaults filled in): all of
/// them for an unswept stage, all but the swept ones for a sweep.
fn fixed_params(stage: &Stage) -> serde_json::Map<String, serde_json::Value> {
    let mut points = stage.points.iter().filter_map(|p| p.params.as_object());
    let Some(first) = points.next() else { return Default::default() };
    let mut fixed = first.clone();
    for other in points {
        fixed.retain(|k, v| other.get(k) == Some(v));
    }
    fixed
}

/// Publishes a completed stage: `tables/<stage>.parquet`, or for a figure
/// `figures/<stage>.<ext>` for each artifact and `figures/<stage>.parquet` for its data.
fn publish_stage(
    p: &Pipeline,
    stage: &Stage,
    registry: &Registry,
    points: &[(Hash, Output)],
    times: &[f64],
    opts: &RunOptions,
) -> Result<Vec<String>> {
    let kind = registry.get(&stage.kind).unwrap();
    let code_version = format!("{}@v{}", stage.kind, kind.version());
    let is_figure = points.iter().any(|(_, o)| !o.artifacts.is_empty());
    let table = provenance_table(points, times, &code_version, is_figure)?;
    let keys: Vec<&str> = points.iter().map(|(k, _)| k.as_str()).collect();
    // What a reader needs beside the numbers: the stage's parameters as the pipeline gives
    // them (a figure's axis labels among them) and every column's unit and meaning.
    let columns: serde_json::Map<String, serde_json::Value> = table
        .column_names()
        .into_iter()
        .filter_map(|c| Some((c.to_string(), serde_json::to_value(registry.column(&c)?).ok()?)))
        .collect();
    let metadata = vec![
        ("repro.pipeline".to_string(), p.file.clone()),
        ("repro.stage".to_string(), stage.name.clone()),
        ("repro.code_version".to_string(), code_version),
        ("repro.version".to_string(), env!("CARGO_PKG_VERSION").to_string()),
        ("repro.task_keys".to_string(), keys.join(",")),
        ("repro.params".to_string(), serde_json::to_string(&fixed_params(stage))?),
        ("repro.columns".to_string(), serde_json::to_string(&columns)?),
    ];
    if is_figure && points.len() != 1 {
        bail!("figure stage `{}` has {} points; a figure stage takes no sweep", stage.name, points.len());
    }
    let dir = if is_figure { &opts.figures_dir } else { &opts.tables_dir };
    let mut written = Vec::new();
    let pq = dir.join(format!("{}.parquet", stage.name));
    if publish_file(&pq, &table.to_parquet_bytes(&metadata)?)? {
        written.push(pq.display().to_string());
    }
    for (_, o) in points {
        for (ext, text) in &o.artifacts {
            let path = dir.join(format!("{}.{ext}", stage.name));
            if publish_file(&path, text.as_bytes())? {
                written.push(path.display().to_string());
            }
        }
    }
    Ok(written)
}

/// Removes cache entries that nothing refers to: no task of the given pipelines, and no task
/// of a run in the cache's history (younger than `older_than`, when given). A dry run lists
/// them without removing.
pub fn gc(pipelines: &[Pipeline], registry: &Registry, cache_dir: &Path, opt: GcOptions) -> Result<GcSummary> {
    let mut live: BTreeSet<String> = BTreeSet::new();
    for p in pipelines {
        let opts =
            RunOptions { cache_dir: cache_dir.to_path_buf(), dry_run: true, progress: false, ..Default::default() };
        let report = run(p, registry, &opts)?;
        live.extend(report.tasks.into_iter().filter_map(|t| t.key));
    }
    let now_ms = unix_ms();
    let mut summary = GcSummary::default();
    for (_, r) in run_history(cache_dir) {
        let young = opt.older_than.is_none_or(|age| now_ms.saturating_sub(r.started_unix_ms) < age.as_millis() as u64);
        if young {
            summary.runs_kept += 1;
            live.extend(r.tasks.into_iter().filter_map(|t| t.key));
        }
    }
    let cache = if opt.dry_run { Cache::open_read_only(cache_dir) } else { Cache::open(cache_dir, LockMode::Wait)? };
    for key in cache.all_keys()? {
        if live.contains(&key) {
            summary.kept += 1;
        } else if opt.dry_run {
            let size = std::fs::metadata(cache.entry_path(&key)).map(|m| m.len()).unwrap_or(0);
            summary.removed.push((key, size));
        } else {
            let size = cache.remove(&key)?;
            summary.removed.push((key, size));
        }
    }
    Ok(summary)
}

/// Milliseconds since the Unix epoch (0 if the clock is before it).
pub fn unix_ms() -> u64 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_millis() as u64)
}
