//! The `repro` command line.

mod cli;
mod describe;
mod exit;
mod heap;

use anyhow::Context;
use clap::Parser;
use cli::{Cli, Command, ExecutorArg};
use describe::{csv_field, describe_kind};
use exit::{CliError, Exit};
use pipeline::cache::LockMode;
use pipeline::executor::{self, Executor, RunOptions, UsageError};
use pipeline::kind::Registry;
use pipeline::parse;
use pipeline::slurm::SlurmOptions;
use pipeline::spec::{self, InvalidPipeline, Pipeline};
use pipeline::table::ColumnData;
use pipeline::{gc, graph, report, schema};
use repro::point::PointError;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn load(path: &Path, registry: &pipeline::kind::Registry) -> Result<Pipeline, InvalidPipeline> {
    load_with(path, registry, &[])
}

fn load_with(
    path: &Path,
    registry: &pipeline::kind::Registry,
    overrides: &[spec::Override],
) -> Result<Pipeline, InvalidPipeline> {
    let p = parse::load_with(path, registry, overrides)?;
    for w in &p.warnings {
        eprintln!("{w}");
    }
    Ok(p)
}

fn main() -> ExitCode {
    heap::keep_freed_blocks();
    // Tasks run in parallel (rayon); a sparse factorisation inside one task gains nothing
    // from threads of its own on 2 cores, only contention.
    faer::set_global_parallelism(faer::Par::Seq);
    let cli = Cli::parse();
    let registry = repro::stages::registry();
    let result: Result<Exit, CliError> = match cli.command {
        Command::Run(args) => run_command(args, &registry),
        Command::Worker(args) => worker_command(args, &registry),
        Command::Status(args) => status_command(args, &registry),
        Command::Dag(args) => dag_command(args, &registry),
        Command::Gc(args) => gc_command(args, &registry),
        Command::Diff(args) => diff_command(args),
        Command::Runs(args) => runs_command(args),
        Command::Point(args) => point_command(args, &registry),
        Command::Schema => schema_command(&registry),
        Command::Show(args) => show_command(args),
        Command::Report(args) => report_command(args, &registry),
        Command::Verify(args) => verify_command(args),
        Command::Kinds(args) => kinds_command(args, &registry),
    };
    match result {
        Ok(exit) => exit.into(),
        Err(e) => e.report(),
    }
}

/// `repro run`.
fn run_command(args: cli::RunArgs, registry: &Registry) -> Result<Exit, CliError> {
    let cli::RunArgs {
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
        publish,
        quiet,
        executor,
        partition,
        max_jobs,
        retries,
        time_limit,
    } = args;
    let p = load_with(&pipeline, registry, &set)?;
    // A run with parameters set on the command line publishes apart from the file's outputs.
    let settings: Vec<String> = set.iter().map(ToString::to_string).collect();
    let (figures, tables, apart) = pipeline::publish::publish_dirs(&pipeline, &settings, figures, tables, publish);
    if let (Some(dir), false, false) = (&apart, dry_run, quiet) {
        eprintln!(
            "repro: parameters set with -S: this run publishes into {}/ (figures/ and tables/ stay the pipeline file's; --publish writes there)",
            dir.display()
        );
    }
    let executor = match executor {
        ExecutorArg::Local => Executor::Local,
        ExecutorArg::Slurm => Executor::Slurm(SlurmOptions { partition, max_jobs, retries, ..Default::default() }),
    };
    let cache_dir = cache.cache.clone();
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
        counter: None,
    };
    let rep = match executor::run(&p, registry, &opts) {
        Ok(rep) => rep,
        Err(e) => {
            // The run stopped before its tasks (the cache not writable, a full disk): the
            // report still says so, wherever it can be written.
            if let (Some(path), executor::RunError::Io(why)) = (&report, &e) {
                let failed = report::RunReport {
                    pipeline: pipeline.display().to_string(),
                    dry_run,
                    errors: vec![format!("{why:#}")],
                    ..Default::default()
                };
                if let Err(w) = write_run_report(path, &failed) {
                    eprintln!("repro: error: {w:#}");
                }
            }
            return Err(e.into());
        }
    };
    if let Some(path) = report {
        write_run_report(&path, &rep)?;
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
    if !dry_run {
        if let Some(line) = partial_verdict(&p, &rep, &cache_dir) {
            eprintln!("{line}");
        }
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

/// The verdict line of a run that reached some of the pipeline's claims but not the
/// `claims` stage that prints it (a `--target` run): from the claim tasks' cached tables.
fn partial_verdict(p: &Pipeline, rep: &report::RunReport, cache_dir: &Path) -> Option<String> {
    use pipeline::report::Status;
    if rep.tasks.iter().any(|t| t.kind == "claims") {
        return None;
    }
    let of_all = p.stages.iter().filter(|s| s.kind == "claim").count();
    let store = pipeline::cache::Cache::open_read_only(cache_dir);
    let entries: Vec<_> = rep
        .tasks
        .iter()
        .filter(|t| t.kind == "claim" && matches!(t.status, Status::Computed | Status::Cached))
        .filter_map(|t| store.get(t.key.as_deref()?).ok())
        .collect();
    let tables: Vec<&pipeline::table::Table> = entries.iter().map(|e| &e.output.table).collect();
    repro::stages::claim::partial_verdict_line(&tables, of_all)
}

/// Writes the run report (`--report FILE`), naming the file if it cannot.
fn write_run_report(path: &std::path::Path, run: &report::RunReport) -> anyhow::Result<()> {
    std::fs::write(path, serde_json::to_vec_pretty(run)?)
        .with_context(|| format!("writing the run report {}", path.display()))
}

/// `repro worker`.
fn worker_command(args: cli::WorkerArgs, registry: &Registry) -> Result<Exit, CliError> {
    let cli::WorkerArgs { cache, list, index } = args;
    let index = match index {
        Some(i) => i,
        None => std::env::var("SLURM_ARRAY_TASK_ID")
            .ok()
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| UsageError::Argument("worker: give --index or run inside a SLURM array".into()))?,
    };
    let ok = pipeline::slurm::work(registry, &cache.cache, &list, index)?;
    Ok(if ok { Exit::Success } else { Exit::FailedTasks })
}

/// `repro status`.
fn status_command(args: cli::StatusArgs, registry: &Registry) -> Result<Exit, CliError> {
    let cli::StatusArgs { pipeline, set, cache, explain, targets } = args;
    let p = load_with(&pipeline, registry, &set)?;
    let opts = RunOptions { cache_dir: cache.cache, dry_run: true, progress: false, targets, ..Default::default() };
    let rep = executor::run(&p, registry, &opts)?;
    print!("{}", rep.summary(explain));
    Ok(Exit::Success)
}

/// `repro dag`.
fn dag_command(args: cli::DagArgs, registry: &Registry) -> Result<Exit, CliError> {
    let cli::DagArgs { pipeline, targets, status, cache } = args;
    let p = load(&pipeline, registry)?;
    let mut idx = Vec::new();
    for t in &targets {
        match p.stages.iter().position(|s| &s.name == t) {
            Some(i) => idx.push(i),
            None => return Err(CliError::usage(parse::unknown_stage("--target", t, &p))),
        }
    }
    let only = (!idx.is_empty()).then(|| graph::with_ancestors(&p, &idx));
    let mut states = std::collections::BTreeMap::new();
    if status {
        let opts = RunOptions { cache_dir: cache.cache, dry_run: true, progress: false, targets, ..Default::default() };
        let rep = executor::run(&p, registry, &opts)?;
        for t in &rep.tasks {
            use pipeline::report::Status as S;
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

/// `repro gc`.
fn gc_command(args: cli::GcArgs, registry: &Registry) -> Result<Exit, CliError> {
    let cli::GcArgs { pipelines, cache, dry_run, older_than } = args;
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
    let opt =
        gc::GcOptions { dry_run, older_than: older_than.map(|d| std::time::Duration::from_secs_f64(d * 86400.0)) };
    let ps = files.iter().map(|f| load(f, registry)).collect::<Result<Vec<_>, _>>()?;
    let g = gc::gc(&ps, registry, &cache.cache, opt)?;
    let bytes: u64 = g.removed.iter().map(|(_, b)| b).sum();
    if dry_run {
        for (key, size) in &g.removed {
            let what = g.described.get(key).map_or("", String::as_str);
            println!("would remove {key} ({size} bytes): {what}");
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

/// `repro diff`.
fn diff_command(args: cli::DiffArgs) -> Result<Exit, CliError> {
    let cli::DiffArgs { a, b, cache, rel_tol } = args;
    let runs = report::run_history(&cache.cache);
    let pick = |name: &Option<String>, default_from_end: usize| -> Result<pipeline::report::RunReport, CliError> {
        match name {
            Some(n) => runs
                .iter()
                .find(|(p, _)| {
                    p.file_stem().is_some_and(|s| s.to_string_lossy() == n.as_str())
                        || p.to_string_lossy() == n.as_str()
                })
                .map(|(_, r)| r.clone())
                .ok_or_else(|| CliError::usage(format!("no recorded run `{n}` (`repro runs` lists them)"))),
            None => runs
                .len()
                .checked_sub(default_from_end)
                .map(|i| runs[i].1.clone())
                .ok_or_else(|| CliError::usage(format!("{} recorded run(s): a diff needs two", runs.len()))),
        }
    };
    let (ra, rb) = (pick(&a, 2)?, pick(&b, 1)?);
    let store = pipeline::cache::Cache::open_read_only(&cache.cache);
    print!("{}", pipeline::diff::diff(&ra, &rb, &store, rel_tol).render());
    Ok(Exit::Success)
}

/// `repro runs`.
fn runs_command(args: cli::RunsArgs) -> Result<Exit, CliError> {
    let cli::RunsArgs { cache } = args;
    let runs = report::run_history(&cache.cache);
    if runs.is_empty() {
        println!("no recorded runs in {}", cache.cache.display());
    }
    for (path, r) in &runs {
        let name = path.file_stem().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
        let set = if r.overrides.is_empty() { String::new() } else { format!(" -S {}", r.overrides.join(" -S ")) };
        // Where a run with settings published, when apart from the file's outputs.
        let folder: std::collections::BTreeSet<String> = r
            .published
            .iter()
            .filter(|f| f.starts_with("overrides/"))
            .filter_map(|f| Some(std::path::Path::new(f).parent()?.parent()?.display().to_string()))
            .collect();
        let set = match folder.first() {
            Some(dir) => format!("{set}  -> {dir}/"),
            None => set,
        };
        let commit = r.git_commit.as_deref().map_or(String::new(), |c| {
            format!("  at {}{}", &c[..c.len().min(12)], if c.ends_with("(modified)") { " (modified)" } else { "" })
        });
        println!(
            "{name}  {}  {}{set}{commit}  {} computed, {} cached, {} failed, {:.1} s",
            pipeline::report::utc_time(r.started_unix_ms),
            r.pipeline,
            r.count(pipeline::report::Status::Computed),
            r.count(pipeline::report::Status::Cached),
            r.count(pipeline::report::Status::Failed),
            r.wall_time_s
        );
    }
    Ok(Exit::Success)
}

/// `repro point`.
fn point_command(args: cli::PointArgs, registry: &Registry) -> Result<Exit, CliError> {
    let cli::PointArgs { kind, params, json, time_limit } = args;
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
        .map_err(|e| UsageError::Argument(format!("parameters: {e}")))?;
    let out = repro::point::compute(registry, &kind, &parse::to_json(&node), time_limit).map_err(|e| match e {
        PointError::Failed(failed) => CliError::TaskFailed(failed),
        invalid => CliError::usage(invalid.to_string()),
    })?;
    let t = &out.table;
    if json {
        let columns: serde_json::Map<String, serde_json::Value> = t
            .columns
            .iter()
            .map(|(name, col)| {
                let values = match col {
                    ColumnData::F64(v) => serde_json::json!(v),
                    ColumnData::I64(v) => serde_json::json!(v),
                    ColumnData::Bool(v) => serde_json::json!(v),
                    ColumnData::Str(v) => serde_json::json!(v),
                };
                (name.clone(), values)
            })
            .collect();
        println!("{}", serde_json::Value::Object(columns));
        return Ok(Exit::Success);
    }
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

/// `repro schema`.
fn schema_command(registry: &Registry) -> Result<Exit, CliError> {
    println!("{}", serde_json::to_string_pretty(&schema::pipeline_schema(registry))?);
    Ok(Exit::Success)
}

/// `repro show`.
fn show_command(args: cli::ShowArgs) -> Result<Exit, CliError> {
    let cli::ShowArgs { file, columns, csv, head, all } = args;
    let df = pipeline::table::read_parquet(&file)?;
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
    let cells: Vec<Vec<String>> =
        (0..shown_rows).map(|i| cols.iter().map(|c| c.get(i).map(&cell).unwrap_or_default()).collect()).collect();
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

/// `repro report`.
fn report_command(args: cli::ReportArgs, registry: &Registry) -> Result<Exit, CliError> {
    let cli::ReportArgs { pipeline, cache, figures, tables, out } = args;
    let p = load(&pipeline, registry)?;
    let versions = registry.iter().map(|k| (k.name().to_string(), k.version())).collect();
    // The cost and timeline of the run that produced these outputs: the latest recorded
    // run of this pipeline file without settings (a run with `-S` publishes apart), not
    // whatever ran last in the cache.
    let same_file = |recorded: &str| {
        let (a, b) = (std::path::Path::new(recorded), pipeline.as_path());
        a == b || matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
    };
    let own_run = pipeline::report::run_history(&cache.cache)
        .into_iter()
        .rev()
        .find(|(_, r)| !r.dry_run && r.overrides.is_empty() && same_file(&r.pipeline))
        .map(|(path, _)| path);
    let sources = repro::reproduction_report::Sources {
        pipeline_file: pipeline,
        figures_dir: figures,
        tables_dir: tables,
        run_report: own_run,
    };
    let (figures, claims) = repro::reproduction_report::write(&p, &versions, &sources, &out)?;
    println!("wrote {} ({figures} figures, {claims} claims)", out.display());
    Ok(Exit::Success)
}

/// `repro verify`.
fn verify_command(args: cli::VerifyArgs) -> Result<Exit, CliError> {
    let cli::VerifyArgs { produced, reference, rel_tol } = args;
    let v = pipeline::verify::verify(&produced, &reference, rel_tol)?;
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
    if v.compared_nothing() {
        println!(
            "repro verify: nothing was compared: {} holds no figure (.svg) or table (.parquet)",
            produced.display()
        );
    }
    Ok(if v.passed() { Exit::Success } else { Exit::FailedTasks })
}

/// `repro kinds` and `repro kinds <kind>`.
fn kinds_command(args: cli::KindsArgs, registry: &Registry) -> Result<Exit, CliError> {
    match args.kind {
        None => {
            for k in registry.iter() {
                println!("{:<28} v{:<3} {}", k.name(), k.version(), k.doc());
            }
            Ok(Exit::Success)
        }
        Some(name) => {
            let k = repro::point::kind(registry, &name).map_err(|e| CliError::usage(e.to_string()))?;
            print!("{}", describe_kind(k, registry));
            Ok(Exit::Success)
        }
    }
}
