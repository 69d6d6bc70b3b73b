//! The planner: what a run computes and why, as data. For each point of a stage, its task
//! key (from the kind, its code version, the point's parameters and the hashes of the
//! tables it needs), the cache's answer, and for a task to compute the reason
//! ([`Reason`]), found by comparing the point with the stage's previous run (its manifest).
//! Points of two stages with the same key are one task, computed once.

use crate::cache::{Cache, Miss, StageManifest};
use crate::key::{stage_hash, task_key, Hash};
use crate::kind::{Output, Registry};
use crate::reason::{ParamChange, Reason};
use crate::report::{Status, TaskRecord};
use crate::spec::{MatchedNeed, Pipeline, Point, Stage};
use crate::task::TaskError;
use std::collections::{BTreeMap, BTreeSet};

pub struct Job {
    pub stage: usize,
    pub point: usize,
    pub key: Hash,
    pub reason: Reason,
    pub params: serde_json::Value,
    pub label: String,
    pub ran_on: Option<String>,
}

/// A needed stage read row by row (`MatchedNeed`), as a stage's plan sees it: per upstream
/// point, its parameters, its task key and the hash of its output.
pub struct MatchedInput {
    pub need: MatchedNeed,
    pub upstream: Vec<(serde_json::Value, Hash, Hash)>,
}

impl MatchedInput {
    /// The upstream points that a point with parameters `params` reads (in the upstream
    /// table's order).
    pub fn select(&self, params: &serde_json::Value) -> Vec<usize> {
        (0..self.upstream.len()).filter(|&i| self.need.matches(&self.upstream[i].0, params)).collect()
    }

    /// The hash of what a point with parameters `params` reads: its upstream points' outputs.
    pub fn hash(&self, params: &serde_json::Value) -> Hash {
        let hashes: Vec<Hash> = self.select(params).into_iter().map(|i| self.upstream[i].2.clone()).collect();
        stage_hash(&hashes)
    }
}

/// A stage of the current wave while its rounds run: its points so far (an adaptive stage
/// adds some after each round) and, per point, its output once known.
pub struct StagePlan {
    pub prev: Option<StageManifest>,
    /// The hashes of the whole tables it needs, by stage.
    pub inputs: BTreeMap<String, Hash>,
    /// The stages it reads row by row.
    pub matched: Vec<MatchedInput>,
    pub points: Vec<Point>,
    /// Per point, once known: its key, output and the wall time of its task.
    pub outs: Vec<Option<(Hash, Output, f64)>>,
    pub failed: bool,
}

impl StagePlan {
    /// The hashes of the rows that the point `params` reads row by row, by stage.
    pub fn matched_inputs(&self, params: &serde_json::Value) -> BTreeMap<String, Hash> {
        self.matched.iter().map(|m| (m.need.stage.clone(), m.hash(params))).collect()
    }

    /// The hashes of everything the point `params` reads, by stage: what its key depends on.
    pub fn point_inputs(&self, params: &serde_json::Value) -> BTreeMap<String, Hash> {
        let mut all = self.inputs.clone();
        all.extend(self.matched_inputs(params));
        all
    }

    /// Records the outcome of a job of this stage (a failure fails the stage).
    pub fn settle(&mut self, j: &Job, out: Result<Output, TaskError>, dt: f64) {
        match out {
            Ok(o) => {
                self.outs[j.point] = Some((j.key.clone(), o, dt));
            }
            Err(_) => self.failed = true,
        }
    }
}

/// The tasks of one round, planned: those to compute, and those that are the same task as
/// one of them (`twins`, with the index of that job); what the cache holds is settled in
/// the stages' plans, and recorded as cached.
#[derive(Default)]
pub struct Round {
    pub jobs: Vec<Job>,
    pub twins: Vec<(Job, usize)>,
    pub cached: Vec<TaskRecord>,
}

/// Plans the points of `plans` not planned yet (the stages' points in round 0, then the
/// points adaptive sweeps add): each task's key, the cache's answer, and for a task to
/// compute, why (`Reason`).
pub fn plan_round(
    p: &Pipeline,
    registry: &Registry,
    cache: &Cache,
    plans: &mut BTreeMap<usize, StagePlan>,
    force: &[String],
    round: usize,
) -> Round {
    let mut r = Round::default();
    let mut job_of_key: BTreeMap<Hash, usize> = BTreeMap::new();
    for (&si, plan) in plans.iter_mut() {
        let stage = &p.stages[si];
        let kind = registry.get(&stage.kind).expect("validated kinds");
        let forced = force.contains(&stage.name);
        for pi in plan.outs.len()..plan.points.len() {
            let pt = &plan.points[pi];
            let key = task_key(&stage.kind, kind.version(), &pt.params, &plan.point_inputs(&pt.params));
            let lookup = if forced { Err(Miss::Absent) } else { cache.get(&key) };
            match lookup {
                Ok(entry) => {
                    r.cached.push(TaskRecord::new(stage, &pt.label, Some(key.clone()), Status::Cached, None));
                    plan.outs.push(Some((key, entry.output, entry.wall_time_s)));
                }
                Err(miss) => {
                    let mut reason = match miss {
                        _ if forced => Reason::Forced,
                        Miss::Corrupted(detail) => {
                            eprintln!("repro: warning: cache entry {key} of stage `{}` is corrupted ({detail}); recomputing it", stage.name);
                            Reason::Corrupted { detail }
                        }
                        Miss::Absent => stale_reason(
                            plan.prev.as_ref(),
                            stage,
                            kind.version(),
                            &plan.inputs,
                            &plan.matched_inputs(&pt.params),
                            pt,
                            &key,
                            &p.overrides,
                        ),
                    };
                    if round > 0 {
                        reason = Reason::AdaptiveRound { round, cause: Box::new(reason) };
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
                        Some(&first) => r.twins.push((job, first)),
                        None => {
                            job_of_key.insert(job.key.clone(), r.jobs.len());
                            r.jobs.push(job);
                        }
                    }
                    plan.outs.push(None);
                }
            }
        }
    }
    r
}

/// Why a twin is not computed on its own.
pub fn twin_reason(p: &Pipeline, first: &Job) -> Reason {
    Reason::SameTaskAs { stage: p.stages[first.stage].name.clone(), point: first.label.clone() }
}

/// Why a task is stale against the manifest of its stage's last run (`prev`). Its
/// arguments are the task's identity as the planner holds it (stage, code version, input
/// hashes whole and matched row by row, point, key, the run's overrides), compared one by one.
#[allow(clippy::too_many_arguments)]
pub fn stale_reason(
    prev: Option<&StageManifest>,
    stage: &Stage,
    version: u32,
    inputs: &BTreeMap<String, Hash>,
    matched: &BTreeMap<String, Hash>,
    point: &Point,
    key: &str,
    overrides: &[String],
) -> Reason {
    let Some(m) = prev else { return Reason::NeverRun };
    // A parameter set on the command line says so.
    let set_by_cli = |k: &str| overrides.iter().any(|o| o.starts_with(&format!("{}.{k}=", stage.name)));
    if m.kind != stage.kind {
        return Reason::KindChanged { from: m.kind.clone(), to: stage.kind.clone() };
    }
    let same = m.points.iter().find(|mp| mp.params == point.params);
    match same {
        Some(mp) => {
            if m.version != version {
                Reason::CodeVersionChanged { kind: stage.kind.clone(), from: m.version, to: version }
            } else if &m.inputs != inputs {
                Reason::InputChanged { stages: changed_inputs(&m.inputs, inputs) }
            } else if &mp.inputs != matched {
                // The rows it reads of a stage it needs row by row.
                Reason::InputChanged { stages: changed_inputs(&mp.inputs, matched) }
            } else if mp.key == key {
                Reason::EntryMissing
            } else {
                Reason::KeyChanged
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
                Reason::NewPoint { point: point.label.clone() }
            } else {
                let changes = nearest
                    .into_iter()
                    .map(|(param, from, to)| ParamChange { set_by_cli: set_by_cli(&param), param, from, to })
                    .collect();
                Reason::ParametersChanged { changes }
            }
        }
    }
}

/// The stages whose input hash differs between `before` and `now` (or is in only one).
fn changed_inputs(before: &BTreeMap<String, Hash>, now: &BTreeMap<String, Hash>) -> Vec<String> {
    now.iter()
        .filter(|(n, h)| before.get(*n) != Some(*h))
        .map(|(n, _)| n.clone())
        .chain(before.keys().filter(|n| !now.contains_key(*n)).cloned())
        .collect()
}

/// A value for a message: at most 40 characters.
fn short(s: &str) -> String {
    if s.chars().count() <= 40 {
        s.to_string()
    } else {
        format!("{}…", s.chars().take(39).collect::<String>())
    }
}
