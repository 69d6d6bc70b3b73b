//! The command line's arguments (clap): the commands, their options and their help.

use clap::{Parser, Subcommand};
use pipeline::spec;
use std::path::PathBuf;

pub(crate) const DEFAULT_PIPELINE: &str = "pipelines/thesis.yaml";

#[derive(Parser)]
#[command(name = "repro", version, about = "Reproduce the thesis' tables and figures from a pipeline of cached tasks")]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(clap::Args, Clone)]
pub(crate) struct CacheArg {
    /// Cache directory.
    #[arg(long, default_value = "cache")]
    pub(crate) cache: PathBuf,
}

#[derive(clap::ValueEnum, Clone, Copy, PartialEq)]
pub(crate) enum ExecutorArg {
    Local,
    Slurm,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Run a pipeline (computing only what is not cached) and publish its tables and figures.
    Run(RunArgs),
    /// Compute one task of a SLURM job array (run by the SLURM executor, not by hand).
    Worker(WorkerArgs),
    /// Which tasks are stale, and why (nothing is run).
    Status(StatusArgs),
    /// Print the stage graph in Graphviz dot (`repro dag | dot -Tsvg > dag.svg`).
    Dag(DagArgs),
    /// Remove cache entries that nothing refers to: no task of the pipelines (default: every
    /// pipelines/*.yaml and the pipelines of the recorded runs) and no task of a recorded run
    /// (`repro runs`). `--dry-run` lists what would go.
    Gc(GcArgs),
    /// List the recorded runs of a cache (newest last): when, which pipeline, the parameters
    /// set with -S, what was computed.
    Runs(RunsArgs),
    /// What changed between two recorded runs (default: the last two): the pipeline and the
    /// parameters set with -S, the tasks computed and why, and the table values and figures
    /// whose results differ.
    Diff(DiffArgs),
    /// Run one point of a stage kind and print its output, e.g.
    /// `repro point bem.sweep lambda=1 W=1 k=0.1 V0=1`.
    Point(PointArgs),
    /// Print the JSON Schema of pipeline files.
    Schema,
    /// List the stage kinds with their code versions.
    Kinds(KindsArgs),
    /// Check that the figures and tables of a run equal the reference ones (default: the
    /// committed `figures/`): SVGs byte for byte, Parquet tables value by value (timing
    /// columns aside). Exit 0 if all equal, 1 if any differs (each named, with its first
    /// difference).
    Verify(VerifyArgs),
    /// Write the reproduction report: one self-contained HTML page with the claims and their
    /// verdicts, every figure by chapter, the last run's cost and timeline, and provenance
    /// (open it from disk; it makes no request).
    Report(ReportArgs),
    /// Print a published Parquet table (or some of its columns) as text.
    Show(ShowArgs),
}

/// The arguments of `repro run` (`Command::Run`).
#[derive(clap::Args)]
pub(crate) struct RunArgs {
    /// Pipeline file.
    #[arg(default_value = DEFAULT_PIPELINE)]
    pub(crate) pipeline: PathBuf,
    /// Run only these stages and what they need (repeatable).
    #[arg(long = "target")]
    pub(crate) targets: Vec<String>,
    /// Set a stage's parameter for this run, e.g. `-S max_vs_lambda.W=1` or
    /// `-S persson.V0='{logspace: [-2, 2, 9]}'` (YAML, as in the file; repeatable). The file
    /// is not changed; the run report records the overrides.
    #[arg(short = 'S', long = "set", value_name = "STAGE.PARAM=VALUE")]
    pub(crate) set: Vec<spec::Override>,
    /// Worker threads (default: one per core).
    #[arg(long)]
    pub(crate) jobs: Option<usize>,
    /// Show what would run, and why, without running or writing anything.
    #[arg(long)]
    pub(crate) dry_run: bool,
    /// List every task with its key, status and the reason it ran.
    #[arg(long)]
    pub(crate) explain: bool,
    /// Recompute this stage's tasks even if cached (repeatable).
    #[arg(long)]
    pub(crate) force: Vec<String>,
    #[command(flatten)]
    pub(crate) cache: CacheArg,
    /// Write a JSON run report (one record per task) to this file.
    #[arg(long)]
    pub(crate) report: Option<PathBuf>,
    /// Refuse (exit 3) instead of waiting when another repro holds the cache.
    #[arg(long)]
    pub(crate) no_wait: bool,
    /// Where figures are published (default `figures`; with `-S` and without `--publish`,
    /// `overrides/<pipeline>/<settings>/figures`).
    #[arg(long)]
    pub(crate) figures: Option<PathBuf>,
    /// Where stage tables are published (default `tables`; with `-S` and without
    /// `--publish`, `overrides/<pipeline>/<settings>/tables`).
    #[arg(long)]
    pub(crate) tables: Option<PathBuf>,
    /// With `-S`, publish into `figures/` and `tables/` (or `--figures`, `--tables`) as a run
    /// of the file alone does, over what the pipeline file produces.
    #[arg(long)]
    pub(crate) publish: bool,
    /// No progress bars.
    #[arg(long, short)]
    pub(crate) quiet: bool,
    /// Where tasks run: `local` (threads here) or `slurm` (job arrays; the cache must be
    /// on a file system the compute nodes share).
    #[arg(long, value_enum, default_value = "local")]
    pub(crate) executor: ExecutorArg,
    /// SLURM partition (default: the cluster's default partition).
    #[arg(long)]
    pub(crate) partition: Option<String>,
    /// SLURM: at most this many tasks of an array run at once.
    #[arg(long)]
    pub(crate) max_jobs: Option<usize>,
    /// SLURM: resubmissions of a task whose worker ended without a result.
    #[arg(long, default_value_t = 2)]
    pub(crate) retries: u32,
    /// Every task's time limit in seconds, over the stages' `time_limit` and the kinds'
    /// defaults (`repro kinds KIND`): a task past it is recorded as timed out and the
    /// others carry on; SLURM jobs ask for it as `--time`.
    #[arg(long, value_parser = positive_seconds)]
    pub(crate) time_limit: Option<f64>,
}

/// The arguments of `repro worker` (`Command::Worker`).
#[derive(clap::Args)]
pub(crate) struct WorkerArgs {
    #[command(flatten)]
    pub(crate) cache: CacheArg,
    /// The array's task list (cache/slurm/lists/...).
    #[arg(long)]
    pub(crate) list: PathBuf,
    /// Line of the list to run (default: $SLURM_ARRAY_TASK_ID).
    #[arg(long)]
    pub(crate) index: Option<usize>,
}

/// The arguments of `repro status` (`Command::Status`).
#[derive(clap::Args)]
pub(crate) struct StatusArgs {
    #[arg(default_value = DEFAULT_PIPELINE)]
    pub(crate) pipeline: PathBuf,
    /// Set a stage's parameter, as `repro run -S`.
    #[arg(short = 'S', long = "set", value_name = "STAGE.PARAM=VALUE")]
    pub(crate) set: Vec<spec::Override>,
    #[command(flatten)]
    pub(crate) cache: CacheArg,
    /// List every task.
    #[arg(long)]
    pub(crate) explain: bool,
    /// Only this stage and what it needs (repeatable), as `repro run --target`.
    #[arg(long = "target", value_name = "STAGE")]
    pub(crate) targets: Vec<String>,
}

/// The arguments of `repro dag` (`Command::Dag`).
#[derive(clap::Args)]
pub(crate) struct DagArgs {
    #[arg(default_value = DEFAULT_PIPELINE)]
    pub(crate) pipeline: PathBuf,
    /// Only these stages and what they need (repeatable).
    #[arg(long = "target")]
    pub(crate) targets: Vec<String>,
    /// Fill each stage by its state against the cache: green every task cached, orange
    /// some would run.
    #[arg(long)]
    pub(crate) status: bool,
    #[command(flatten)]
    pub(crate) cache: CacheArg,
}

/// The arguments of `repro gc` (`Command::Gc`).
#[derive(clap::Args)]
pub(crate) struct GcArgs {
    pub(crate) pipelines: Vec<PathBuf>,
    #[command(flatten)]
    pub(crate) cache: CacheArg,
    /// List the entries that would be removed, and their size; remove nothing.
    #[arg(long)]
    pub(crate) dry_run: bool,
    /// Keep the entries of recorded runs only if they are younger than this many days
    /// (default: keep those of every recorded run).
    #[arg(long, value_name = "DAYS")]
    pub(crate) older_than: Option<f64>,
}

/// The arguments of `repro runs` (`Command::Runs`).
#[derive(clap::Args)]
pub(crate) struct RunsArgs {
    #[command(flatten)]
    pub(crate) cache: CacheArg,
}

/// The arguments of `repro diff` (`Command::Diff`).
#[derive(clap::Args)]
pub(crate) struct DiffArgs {
    /// The earlier run (a name from `repro runs`, or its file); default: the second last.
    pub(crate) a: Option<String>,
    /// The later run; default: the last.
    pub(crate) b: Option<String>,
    #[command(flatten)]
    pub(crate) cache: CacheArg,
    /// Relative changes up to this are not reported.
    #[arg(long, default_value_t = 1e-12)]
    pub(crate) rel_tol: f64,
}

/// The arguments of `repro point` (`Command::Point`).
#[derive(clap::Args)]
pub(crate) struct PointArgs {
    /// The stage kind (`repro kinds`).
    pub(crate) kind: String,
    /// Parameters as NAME=VALUE (values read as YAML scalars).
    pub(crate) params: Vec<String>,
    /// Print the table as JSON, `{"column": [values]}`, every number to the bits it has
    /// (for scripts; the text shows six digits).
    #[arg(long)]
    pub(crate) json: bool,
    /// Stop the point after this many seconds (default: its kind's time limit, `repro kinds
    /// KIND`), as a task of a run is stopped.
    #[arg(long, value_name = "SECONDS")]
    pub(crate) time_limit: Option<f64>,
}

/// The arguments of `repro kinds` (`Command::Kinds`).
#[derive(clap::Args)]
pub(crate) struct KindsArgs {
    /// A kind to describe: its parameters (type, default, whether sweepable, meaning).
    pub(crate) kind: Option<String>,
}

/// The arguments of `repro verify` (`Command::Verify`).
#[derive(clap::Args)]
pub(crate) struct VerifyArgs {
    /// The folder the run published into (`repro run --figures DIR`).
    pub(crate) produced: PathBuf,
    /// The reference folder.
    #[arg(default_value = "figures")]
    pub(crate) reference: PathBuf,
    /// Relative tolerance for numbers (in tables and in SVG coordinates), for
    /// floating-point differences across platforms; 0 (the default): exact.
    #[arg(long, default_value_t = 0.0)]
    pub(crate) rel_tol: f64,
}

/// The arguments of `repro report` (`Command::Report`).
#[derive(clap::Args)]
pub(crate) struct ReportArgs {
    /// The pipeline file.
    #[arg(default_value = "pipelines/thesis.yaml")]
    pub(crate) pipeline: PathBuf,
    #[command(flatten)]
    pub(crate) cache: CacheArg,
    /// Where the run published its figures and tables.
    #[arg(long, default_value = "figures")]
    pub(crate) figures: PathBuf,
    #[arg(long, default_value = "tables")]
    pub(crate) tables: PathBuf,
    /// The HTML file written.
    #[arg(long, short, default_value = "report/index.html")]
    pub(crate) out: PathBuf,
}

/// The arguments of `repro show` (`Command::Show`).
#[derive(clap::Args)]
pub(crate) struct ShowArgs {
    /// The Parquet file (tables/<stage>.parquet or figures/<figure>.parquet).
    pub(crate) file: PathBuf,
    /// Only these columns, comma-separated.
    #[arg(long, value_delimiter = ',')]
    pub(crate) columns: Vec<String>,
    /// Comma-separated values with every digit (floats round-trip exactly), for other
    /// tools; the default is an aligned table with polars' rounding.
    #[arg(long)]
    pub(crate) csv: bool,
    /// Only the first N rows (with a line saying how many there are in all).
    #[arg(long, value_name = "N")]
    pub(crate) head: Option<usize>,
    /// Show the provenance columns too (`task_key`, `code_version`), hidden by default
    /// unless named in --columns or with --csv.
    #[arg(long)]
    pub(crate) all: bool,
}

/// A kind's parameters from its schema: name, type, default, sweepable, meaning.
pub(crate) fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x > 0.0 && x.is_finite() => Ok(x),
        _ => Err(format!("a positive number of seconds, got `{s}`")),
    }
}
