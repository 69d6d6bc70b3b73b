//! The `repro` command line.

mod exit;

use anyhow::Context;
use clap::{Parser, Subcommand};
use exit::{CliError, Exit};
use repro::pipeline::cache::LockMode;
use repro::pipeline::executor::{self, Executor, RunOptions, UsageError};
use repro::pipeline::parse;
use repro::pipeline::slurm::SlurmOptions;
use repro::pipeline::spec::{self, InvalidPipeline, Pipeline};
use repro::pipeline::{gc, graph, report, schema};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const DEFAULT_PIPELINE: &str = "pipelines/thesis.yaml";

#[derive(Parser)]
#[command(name = "repro", version, about = "Reproduce the thesis' tables and figures from a pipeline of cached tasks")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(clap::Args, Clone)]
struct CacheArg {
    /// Cache directory.
    #[arg(long, default_value = "cache")]
    cache: PathBuf,
}

#[derive(clap::ValueEnum, Clone, Copy, PartialEq)]
enum ExecutorArg {
    Local,
    Slurm,
}

#[derive(Subcommand)]
enum Command {
    /// Run a pipeline (computing only what is not cached) and publish its tables and figures.
    Run {
        /// Pipeline file.
        #[arg(default_value = DEFAULT_PIPELINE)]
        pipeline: PathBuf,
        /// Run only these stages and what they need (repeatable).
        #[arg(long = "target")]
        targets: Vec<String>,
        /// Set a stage's parameter for this run, e.g. `-S max_vs_lambda.W=1` or
        /// `-S persson.V0='{logspace: [-2, 2, 9]}'` (YAML, as in the file; repeatable). The file
        /// is not changed; the run report records the overrides.
        #[arg(short = 'S', long = "set", value_name = "STAGE.PARAM=VALUE")]
        set: Vec<spec::Override>,
        /// Worker threads (default: one per core).
        #[arg(long)]
        jobs: Option<usize>,
        /// Show what would run, and why, without running or writing anything.
        #[arg(long)]
        dry_run: bool,
        /// List every task with its key, status and the reason it ran.
        #[arg(long)]
        explain: bool,
        /// Recompute this stage's tasks even if cached (repeatable).
        #[arg(long)]
        force: Vec<String>,
        #[command(flatten)]
        cache: CacheArg,
        /// Write a JSON run report (one record per task) to this file.
        #[arg(long)]
        report: Option<PathBuf>,
        /// Refuse (exit 3) instead of waiting when another repro holds the cache.
        #[arg(long)]
        no_wait: bool,
        /// Where figures are published.
        #[arg(long, default_value = "figures")]
        figures: PathBuf,
        /// Where stage tables are published.
        #[arg(long, default_value = "tables")]
        tables: PathBuf,
        /// No progress bars.
        #[arg(long, short)]
        quiet: bool,
        /// Where tasks run: `local` (threads here) or `slurm` (job arrays; the cache must be
        /// on a file system the compute nodes share).
        #[arg(long, value_enum, default_value = "local")]
        executor: ExecutorArg,
        /// SLURM partition (default: the cluster's default partition).
        #[arg(long)]
        partition: Option<String>,
        /// SLURM: at most this many tasks of an array run at once.
        #[arg(long)]
        max_jobs: Option<usize>,
        /// SLURM: resubmissions of a task whose worker ended without a result.
        #[arg(long, default_value_t = 2)]
        retries: u32,
        /// Every task's time limit in seconds, over the stages' `time_limit` and the kinds'
        /// defaults (`repro kinds KIND`): a task past it is recorded as timed out and the
        /// others carry on; SLURM jobs ask for it as `--time`.
        #[arg(long, value_parser = positive_seconds)]
        time_limit: Option<f64>,
    },
    /// Compute one task of a SLURM job array (run by the SLURM executor, not by hand).
    Worker {
        #[command(flatten)]
        cache: CacheArg,
        /// The array's task list (cache/slurm/lists/...).
        #[arg(long)]
        list: PathBuf,
        /// Line of the list to run (default: $SLURM_ARRAY_TASK_ID).
        #[arg(long)]
        index: Option<usize>,
    },
    /// Which tasks are stale, and why (nothing is run).
    Status {
        #[arg(default_value = DEFAULT_PIPELINE)]
        pipeline: PathBuf,
        /// Set a stage's parameter, as `repro run -S`.
        #[arg(short = 'S', long = "set", value_name = "STAGE.PARAM=VALUE")]
        set: Vec<spec::Override>,
        #[command(flatten)]
        cache: CacheArg,
        /// List every task.
        #[arg(long)]
        explain: bool,
    },
    /// Print the stage graph in Graphviz dot (`repro dag | dot -Tsvg > dag.svg`).
    Dag {
        #[arg(default_value = DEFAULT_PIPELINE)]
        pipeline: PathBuf,
        /// Only these stages and what they need (repeatable).
        #[arg(long = "target")]
        targets: Vec<String>,
        /// Fill each stage by its state against the cache: green every task cached, orange
        /// some would run.
        #[arg(long)]
        status: bool,
        #[command(flatten)]
        cache: CacheArg,
    },
    /// Remove cache entries that nothing refers to: no task of the pipelines (default: every
    /// pipelines/*.yaml and the pipelines of the recorded runs) and no task of a recorded run
    /// (`repro runs`). `--dry-run` lists what would go.
    Gc {
        pipelines: Vec<PathBuf>,
        #[command(flatten)]
        cache: CacheArg,
        /// List the entries that would be removed, and their size; remove nothing.
        #[arg(long)]
        dry_run: bool,
        /// Keep the entries of recorded runs only if they are younger than this many days
        /// (default: keep those of every recorded run).
        #[arg(long, value_name = "DAYS")]
        older_than: Option<f64>,
    },
    /// List the recorded runs of a cache (newest last): when, which pipeline, the parameters
    /// set with -S, what was computed.
    Runs {
        #[command(flatten)]
        cache: CacheArg,
    },
    /// What changed between two recorded runs (default: the last two): the pipeline and the
    /// parameters set with -S, the tasks computed and why, and the table values and figures
    /// whose results differ.
    Diff {
        /// The earlier run (a name from `repro runs`, or its file); default: the second last.
        a: Option<String>,
        /// The later run; default: the last.
        b: Option<String>,
        #[command(flatten)]
        cache: CacheArg,
        /// Relative changes up to this are not reported.
        #[arg(long, default_value_t = 1e-12)]
        rel_tol: f64,
    },
    /// Run one point of a stage kind and print its output, e.g.
    /// `repro point bem.sweep lambda=1 W=1 k=0.1 V0=1`.
    Point {
        /// The stage kind (`repro kinds`).
        kind: String,
        /// Parameters as NAME=VALUE (values read as YAML scalars).
        params: Vec<String>,
    },
    /// Print the JSON Schema of pipeline files.
    Schema,
    /// List the stage kinds with their code versions.
    Kinds {
        /// A kind to describe: its parameters (type, default, whether sweepable, meaning).
        kind: Option<String>,
    },
    /// Check that the figures and tables of a run equal the reference ones (default: the
    /// committed `figures/`): SVGs byte for byte, Parquet tables value by value (timing
    /// columns aside). Exit 0 if all equal, 1 if any differs (each named, with its first
    /// difference).
    Verify {
        /// The folder the run published into (`repro run --figures DIR`).
        produced: PathBuf,
        /// The reference folder.
        #[arg(default_value = "figures")]
        reference: PathBuf,
        /// Relative tolerance for numbers (in tables and in SVG coordinates), for
        /// floating-point differences across platforms; 0 (the default): exact.
        #[arg(long, default_value_t = 0.0)]
        rel_tol: f64,
    },
    /// Write the reproduction report: one self-contained HTML page with the claims and their
    /// verdicts, every figure by chapter, the last run's cost and timeline, and provenance
    /// (open it from disk; it makes no request).
    Report {
        /// The pipeline file.
        #[arg(default_value = "pipelines/thesis.yaml")]
        pipeline: PathBuf,
        #[command(flatten)]
        cache: CacheArg,
        /// Where the run published its figures and tables.
        #[arg(long, default_value = "figures")]
        figures: PathBuf,
        #[arg(long, default_value = "tables")]
        tables: PathBuf,
        /// The HTML file written.
        #[arg(long, short, default_value = "report/index.html")]
        out: PathBuf,
    },
    /// Print a published Parquet table (or some of its columns) as text.
    Show {
        /// The Parquet file (tables/<stage>.parquet or figures/<figure>.parquet).
        file: PathBuf,
        /// Only these columns, comma-separated.
        #[arg(long, value_delimiter = ',')]
        columns: Vec<String>,
        /// Comma-separated values with every digit (floats round-trip exactly), for other
        /// tools; the default is an aligned table with polars' rounding.
        #[arg(long)]
        csv: bool,
        /// Only the first N rows (with a line saying how many there are in all).
        #[arg(long, value_name = "N")]
        head: Option<usize>,
        /// Show the provenance columns too (`task_key`, `code_version`), hidden by default
        /// unless named in --columns or with --csv.
        #[arg(long)]
        all: bool,
    },
}

/// A CSV field: quoted (with doubled quotes) when it holds a comma, a quote or a newline.
fn csv_field(t: &str) -> String {
    if t.contains([',', '"', '\n']) {
        format!("\"{}\"", t.replace('"', "\"\""))
    } else {
        t.to_string()
    }
}

fn load(path: &Path, registry: &repro::pipeline::kind::Registry) -> Result<Pipeline, InvalidPipeline> {
    load_with(path, registry, &[])
}

fn load_with(
    path: &Path,
    registry: &repro::pipeline::kind::Registry,
    overrides: &[spec::Override],
) -> Result<Pipeline, InvalidPipeline> {
    let p = parse::load_with(path, registry, overrides)?;
    for w in &p.warnings {
        eprintln!("{w}");
    }
    Ok(p)
}

/// A kind's parameters from its schema: name, type, default, sweepable, meaning.
fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x > 0.0 && x.is_finite() => Ok(x),
        _ => Err(format!("a positive number of seconds, got `{s}`")),
    }
}

fn describe_kind(k: &dyn repro::pipeline::kind::DynKind, registry: &repro::pipeline::kind::Registry) -> String {
    use serde_json::Value;
    let schema = k.params_schema();
    let defs = schema.get("$defs").cloned().unwrap_or(Value::Null);
    let resolve = |v: &Value| -> Value {
        match v.get("$ref").and_then(Value::as_str).and_then(|r| r.rsplit('/').next()) {
            Some(name) => defs.get(name).cloned().unwrap_or(Value::Null),
            None => v.clone(),
        }
    };
    let type_of = |v: &Value| -> String {
        if let Some(r) = v.get("$ref").and_then(Value::as_str) {
            return r.rsplit('/').next().unwrap_or(r).to_string();
        }
        match v.get("type") {
            Some(Value::String(t)) => t.clone(),
            Some(Value::Array(ts)) => ts.iter().filter_map(Value::as_str).collect::<Vec<_>>().join(" or "),
            _ => match v.get("anyOf").or_else(|| v.get("oneOf")).and_then(Value::as_array) {
                Some(alts) => alts
                    .iter()
                    .map(|a| {
                        a.get("$ref")
                            .and_then(Value::as_str)
                            .map(|r| r.rsplit('/').next().unwrap_or(r).to_string())
                            .or_else(|| a.get("type").and_then(Value::as_str).map(str::to_string))
                            .or_else(|| a.get("const").map(|c| c.to_string()))
                            .unwrap_or_else(|| "value".into())
                    })
                    .collect::<Vec<_>>()
                    .join(" or "),
                None => v.get("enum").map_or("value".into(), |e| format!("one of {e}")),
            },
        }
    };
    let mut out = format!(
        "{} (code version {}): {}\ntime limit per task: {} s (a stage's `time_limit`, `repro run --time-limit`)\n\n",
        k.name(),
        k.version(),
        k.doc(),
        k.time_limit_s()
    );
    let required: Vec<&str> = schema
        .get("required")
        .and_then(Value::as_array)
        .map_or(Vec::new(), |r| r.iter().filter_map(Value::as_str).collect());
    let Some(props) = schema.get("properties").and_then(Value::as_object) else {
        out.push_str("no parameters\n");
        return out;
    };
    out.push_str(&format!(
        "{:<18} {:<22} {:<14} {:<14} {:<9} meaning\n",
        "parameter", "type", "default", "valid range", "sweep"
    ));
    for (name, v) in props {
        let doc = v
            .get("description")
            .and_then(Value::as_str)
            .map(str::to_string)
            .or_else(|| resolve(v).get("description").and_then(Value::as_str).map(str::to_string))
            .unwrap_or_default();
        let default = match v.get("default") {
            Some(d) => d.to_string(),
            None if required.contains(&name.as_str()) => "(required)".into(),
            None => "(none)".into(),
        };
        let default = if default.chars().count() > 14 {
            format!("{}…", default.chars().take(13).collect::<String>())
        } else {
            default
        };
        let sweep = if k.sweepable().contains(&name.as_str()) { "sweepable" } else { "" };
        let doc = doc.split_whitespace().collect::<Vec<_>>().join(" ");
        let range = repro::pipeline::kind::range_text(&schema, v);
        out.push_str(&format!("{name:<18} {:<22} {default:<14} {range:<14} {sweep:<9} {doc}\n", type_of(v)));
    }
    if !k.columns().is_empty() {
        out.push_str(&format!("\n{:<24} {:<26} meaning\n", "output column", "unit"));
        for c in k.columns() {
            let (unit, meaning) =
                registry.column(c).map_or(("", "(see docs/outputs.md)"), |d| (d.unit.as_str(), d.meaning.as_str()));
            out.push_str(&format!("{c:<24} {unit:<26} {meaning}\n"));
        }
    }
    out
}

fn main() -> ExitCode {
    // Tasks run in parallel (rayon); a sparse factorisation inside one task gains nothing
    // from threads of its own on 2 cores, only contention.
    faer::set_global_parallelism(faer::Par::Seq);
    let cli = Cli::parse();
    let registry = repro::stages::registry();
    let result: Result<Exit, CliError> = (|| match cli.command {
        Command::Run {
            pipeline,
            targets,
            set,
            jobs,
            dry_run,
            explain,
            force,
            cache,
            report,
            no_wait,
            figures,
            tables,
            quiet,
            executor,
            partition,
            max_jobs,
            retries,
            time_limit,
        } => {
            let p = load_with(&pipeline, &registry, &set)?;
            let executor = match executor {
                ExecutorArg::Local => Executor::Local,
                ExecutorArg::Slurm => {
                    Executor::Slurm(SlurmOptions { partition, max_jobs, retries, ..Default::default() })
                }
            };
            let opts = RunOptions {
                cache_dir: cache.cache,
                figures_dir: figures,
                tables_dir: tables,
                jobs,
                dry_run,
                force,
                targets,
                lock: if no_wait { LockMode::Refuse } else { LockMode::Wait },
                progress: !quiet,
                executor,
                time_limit_s: time_limit,
            };
            let rep = executor::run(&p, &registry, &opts)?;
            if let Some(path) = report {
                std::fs::write(&path, serde_json::to_vec_pretty(&rep)?)?;
            }
            // A dry run's plan goes to stdout (per stage; per task with --explain).
            if dry_run {
                print!("{}", rep.summary(explain));
            } else {
                eprint!("{}", rep.summary(explain));
            }
            for f in &rep.published {
                eprintln!("  wrote {f}");
            }
            for n in &rep.notes {
                eprintln!("{n}");
            }
            for r in &rep.regressions {
                eprintln!("repro: regression: {r}");
            }
            for e in &rep.errors {
                eprintln!("repro: error: {e}");
            }
            Ok(if !rep.errors.is_empty() {
                Exit::Error
            } else if rep.any_failed() {
                Exit::FailedTasks
            } else if !rep.regressions.is_empty() {
                Exit::Regression
            } else {
                Exit::Success
            })
        }
        Command::Worker { cache, list, index } => {
            let index = match index {
                Some(i) => i,
                None => std::env::var("SLURM_ARRAY_TASK_ID")
                    .ok()
                    .and_then(|v| v.parse().ok())
                    .ok_or_else(|| UsageError("worker: give --index or run inside a SLURM array".into()))?,
            };
            let ok = repro::pipeline::slurm::work(&registry, &cache.cache, &list, index)?;
            Ok(if ok { Exit::Success } else { Exit::FailedTasks })
        }
        Command::Status { pipeline, set, cache, explain } => {
            let p = load_with(&pipeline, &registry, &set)?;
            let opts = RunOptions { cache_dir: cache.cache, dry_run: true, progress: false, ..Default::default() };
            let rep = executor::run(&p, &registry, &opts)?;
            print!("{}", rep.summary(explain));
            Ok(Exit::Success)
        }
        Command::Dag { pipeline, targets, status, cache } => {
            let p = load(&pipeline, &registry)?;
            let mut idx = Vec::new();
            for t in &targets {
                match p.stages.iter().position(|s| &s.name == t) {
                    Some(i) => idx.push(i),
                    None => return Err(CliError::usage(format!("--target {t}: no stage of that name in {}", p.file))),
                }
            }
            let only = (!idx.is_empty()).then(|| graph::with_ancestors(&p, &idx));
            let mut states = std::collections::BTreeMap::new();
            if status {
                let opts = RunOptions {
                    cache_dir: cache.cache,
                    dry_run: true,
                    progress: false,
                    targets,
                    ..Default::default()
                };
                let rep = executor::run(&p, &registry, &opts)?;
                for t in &rep.tasks {
                    use repro::pipeline::report::Status as S;
                    let s = match t.status {
                        S::Cached | S::Computed => graph::StageStatus::Cached,
                        S::Failed | S::Skipped => graph::StageStatus::Failed,
                        S::WouldRun | S::Unknown => graph::StageStatus::Stale,
                    };
                    let e = states.entry(t.stage.clone()).or_insert(s);
                    if s != graph::StageStatus::Cached {
                        *e = s;
                    }
                }
            }
            print!("{}", graph::to_dot_with(&p, only.as_ref(), &states));
            Ok(Exit::Success)
        }
        Command::Gc { pipelines, cache, dry_run, older_than } => {
            let files = if pipelines.is_empty() {
                let mut v: Vec<PathBuf> = std::fs::read_dir("pipelines")
                    .map(|d| {
                        d.filter_map(|e| e.ok().map(|e| e.path()))
                            .filter(|p| p.extension().is_some_and(|x| x == "yaml" || x == "yml"))
                            .collect()
                    })
                    .unwrap_or_default();
                // The pipelines of the recorded runs (a user's own file outside pipelines/).
                for (_, r) in report::run_history(&cache.cache) {
                    let f = PathBuf::from(&r.pipeline);
                    if f.exists() && !v.contains(&f) {
                        v.push(f);
                    }
                }
                v.sort();
                v.dedup();
                v
            } else {
                pipelines
            };
            if let Some(d) = older_than {
                if !(d >= 0.0 && d.is_finite()) {
                    return Err(CliError::usage(format!("--older-than {d}: expected a number of days >= 0")));
                }
            }
            let opt = gc::GcOptions {
                dry_run,
                older_than: older_than.map(|d| std::time::Duration::from_secs_f64(d * 86400.0)),
            };
            let ps = files.iter().map(|f| load(f, &registry)).collect::<Result<Vec<_>, _>>()?;
            let g = gc::gc(&ps, &registry, &cache.cache, opt)?;
            let bytes: u64 = g.removed.iter().map(|(_, b)| b).sum();
            if dry_run {
                for (key, size) in &g.removed {
                    println!("would remove {key} ({size} bytes)");
                }
            }
            eprintln!(
                "repro gc: kept {} entries (referred to by {} pipeline(s) and {} recorded run(s)), {} {} ({:.1} kB)",
                g.kept,
                ps.len(),
                g.runs_kept,
                if dry_run { "would remove" } else { "removed" },
                g.removed.len(),
                bytes as f64 / 1e3
            );
            Ok(Exit::Success)
        }
        Command::Diff { a, b, cache, rel_tol } => {
            let runs = report::run_history(&cache.cache);
            let pick =
                |name: &Option<String>,
                 default_from_end: usize|
                 -> Result<repro::pipeline::report::RunReport, CliError> {
                    match name {
                        Some(n) => runs
                            .iter()
                            .find(|(p, _)| {
                                p.file_stem().is_some_and(|s| s.to_string_lossy() == n.as_str())
                                    || p.to_string_lossy() == n.as_str()
                            })
                            .map(|(_, r)| r.clone())
                            .ok_or_else(|| CliError::usage(format!("no recorded run `{n}` (`repro runs` lists them)"))),
                        None => runs.len().checked_sub(default_from_end).map(|i| runs[i].1.clone()).ok_or_else(|| {
                            CliError::usage(format!("{} recorded run(s): a diff needs two", runs.len()))
                        }),
                    }
                };
            let (ra, rb) = (pick(&a, 2)?, pick(&b, 1)?);
            let store = repro::pipeline::cache::Cache::open_read_only(&cache.cache);
            print!("{}", repro::pipeline::diff::diff(&ra, &rb, &store, rel_tol).render());
            Ok(Exit::Success)
        }
        Command::Runs { cache } => {
            let runs = report::run_history(&cache.cache);
            if runs.is_empty() {
                println!("no recorded runs in {}", cache.cache.display());
            }
            for (path, r) in &runs {
                let name = path.file_stem().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
                let set =
                    if r.overrides.is_empty() { String::new() } else { format!(" -S {}", r.overrides.join(" -S ")) };
                let commit = r.git_commit.as_deref().map_or(String::new(), |c| {
                    format!(
                        "  at {}{}",
                        &c[..c.len().min(12)],
                        if c.ends_with("(modified)") { " (modified)" } else { "" }
                    )
                });
                println!(
                    "{name}  {}  {}{set}{commit}  {} computed, {} cached, {} failed, {:.1} s",
                    repro::pipeline::report::utc_time(r.started_unix_ms),
                    r.pipeline,
                    r.count(repro::pipeline::report::Status::Computed),
                    r.count(repro::pipeline::report::Status::Cached),
                    r.count(repro::pipeline::report::Status::Failed),
                    r.wall_time_s
                );
            }
            Ok(Exit::Success)
        }
        Command::Point { kind, params } => {
            let Some(k) = registry.get(&kind) else {
                let known: Vec<_> = registry.names().collect();
                return Err(CliError::usage(format!("unknown stage kind `{kind}`; known kinds: {}", known.join(", "))));
            };
            let mut yaml = String::new();
            let mut seen = std::collections::BTreeSet::new();
            for p in &params {
                let Some((name, value)) = p.split_once('=').filter(|(name, _)| !name.trim().is_empty()) else {
                    return Err(CliError::usage(format!("`{p}`: parameters are NAME=VALUE")));
                };
                if !seen.insert(name) {
                    return Err(CliError::usage(format!("parameter `{name}` is given twice")));
                }
                yaml.push_str(&format!("{name}: {value}\n"));
            }
            let node = marked_yaml::parse_yaml(0, if yaml.is_empty() { "{}" } else { &yaml })
                .map_err(|e| UsageError(format!("parameters: {e}")))?;
            let (canonical, _) = k.check(&parse::to_json(&node)).map_err(|errors| {
                UsageError(
                    errors
                        .iter()
                        .map(|e| match e.path.as_str() {
                            // A missing field is reported at the root: name the kind instead.
                            "" => format!("{kind}: {} (`repro kinds` lists the kinds)", e.message),
                            path => format!("parameter `{path}`: {}", e.message),
                        })
                        .collect::<Vec<_>>()
                        .join("; "),
                )
            })?;
            let out = k.run(&canonical, &repro::pipeline::kind::Inputs { tables: Default::default() })?;
            let t = &out.table;
            for row in 0..t.n_rows().min(50) {
                for (name, col) in &t.columns {
                    println!("{name:>16} = {}", col.display_at(row));
                }
                if t.n_rows() > 1 {
                    println!();
                }
            }
            if t.n_rows() > 50 {
                println!("({} more rows)", t.n_rows() - 50);
            }
            Ok(Exit::Success)
        }
        Command::Schema => {
            println!("{}", serde_json::to_string_pretty(&schema::pipeline_schema(&registry))?);
            Ok(Exit::Success)
        }
        Command::Show { file, columns, csv, head, all } => {
            let df = repro::pipeline::table::read_parquet(&file)?;
            let names: Vec<String> = if columns.is_empty() {
                df.get_column_names()
                    .iter()
                    .map(|c| c.to_string())
                    .filter(|c| all || csv || !matches!(c.as_str(), "task_key" | "code_version"))
                    .collect()
            } else {
                columns
            };
            let shown_rows = head.unwrap_or(usize::MAX).min(df.height());
            let cols = names
                .iter()
                .map(|c| df.column(c).with_context(|| format!("{}: no column `{c}`", file.display())))
                .collect::<anyhow::Result<Vec<_>>>()?;
            let cell = |v: polars::prelude::AnyValue| match v {
                polars::prelude::AnyValue::Float64(x) if csv => format!("{x:?}"),
                polars::prelude::AnyValue::String(t) if csv => csv_field(t),
                polars::prelude::AnyValue::StringOwned(t) if csv => csv_field(&t),
                v => v.to_string(),
            };
            let cells: Vec<Vec<String>> = (0..shown_rows)
                .map(|i| cols.iter().map(|c| c.get(i).map(&cell).unwrap_or_default()).collect())
                .collect();
            let widths: Vec<usize> = (0..names.len())
                .map(|j| cells.iter().map(|r| r[j].chars().count()).chain([names[j].len()]).max().unwrap_or(0))
                .collect();
            let line = |r: &[String]| {
                if csv {
                    r.join(",")
                } else {
                    r.iter().zip(&widths).map(|(c, w)| format!("{c:>w$}")).collect::<Vec<_>>().join("  ")
                }
            };
            // A reader that stops early (`| head`) closes the pipe: stop quietly.
            use std::io::Write;
            let mut out = std::io::stdout().lock();
            for r in std::iter::once(&names).chain(&cells) {
                if writeln!(out, "{}", line(r)).is_err() {
                    break;
                }
            }
            if shown_rows < df.height() && !csv {
                let _ = writeln!(out, "... {} of {} rows shown", shown_rows, df.height());
            }
            Ok(Exit::Success)
        }
        Command::Report { pipeline, cache, figures, tables, out } => {
            let p = load(&pipeline, &registry)?;
            let versions = registry.iter().map(|k| (k.name().to_string(), k.version())).collect();
            let sources = repro::reproduction_report::Sources {
                pipeline_file: pipeline,
                figures_dir: figures,
                tables_dir: tables,
                run_report: Some(cache.cache.join("runs").join("last.json")),
            };
            let (figures, claims) = repro::reproduction_report::write(&p, &versions, &sources, &out)?;
            println!("wrote {} ({figures} figures, {claims} claims)", out.display());
            Ok(Exit::Success)
        }
        Command::Verify { produced, reference, rel_tol } => {
            let v = repro::pipeline::verify::verify(&produced, &reference, rel_tol)?;
            for (file, d) in &v.differ {
                println!("DIFFERS {}: {d}", file.display());
            }
            println!(
                "repro verify: {} equal, {} differ, {} in {} not produced (not checked)",
                v.equal.len(),
                v.differ.len(),
                v.unchecked.len(),
                reference.display()
            );
            Ok(if v.passed() { Exit::Success } else { Exit::FailedTasks })
        }
        Command::Kinds { kind: None } => {
            for k in registry.iter() {
                println!("{:<28} v{:<3} {}", k.name(), k.version(), k.doc());
            }
            Ok(Exit::Success)
        }
        Command::Kinds { kind: Some(name) } => {
            let Some(k) = registry.get(&name) else {
                let known: Vec<_> = registry.names().collect();
                return Err(CliError::usage(format!("unknown stage kind `{name}`; known kinds: {}", known.join(", "))));
            };
            print!("{}", describe_kind(k, &registry));
            Ok(Exit::Success)
        }
    })();
    match result {
        Ok(exit) => exit.into(),
        Err(e) => e.report(),
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn csv_fields_are_quoted_only_when_they_must_be() {
        assert_eq!(super::csv_field("λ = 1"), "λ = 1");
        assert_eq!(super::csv_field("λ = 1, W = 0.1"), "\"λ = 1, W = 0.1\"");
        assert_eq!(super::csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(super::csv_field("two\nlines"), "\"two\nlines\"");
    }
}
