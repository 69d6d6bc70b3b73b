//! `repro._repro`: the native half of the Python package `repro` (crates/python/python/repro
//! is the other). It binds the library's own entry points, so that a point, a sweep or a run
//! from Python is computed by the same code as from the command line, under the same cache
//! keys:
//! - a point: `repro::point::compute` (as `repro point`);
//! - a sweep: a pipeline of one stage, parsed as a pipeline file is and run by the executor
//!   (as `repro run`), its table returned as Parquet bytes with the published metadata;
//! - a run: `pipeline::executor::run_keeping` over a pipeline file, with `-S` overrides.
//!
//! Parameters cross the boundary as JSON text (Python's `json.dumps` writes every float so
//! that it reads back to the same bits, and `serde_json` reads it so). Errors become the
//! package's exceptions (`repro.errors`), with the command line's messages. The
//! computation runs on a thread of its own while the calling thread, without the GIL,
//! watches for signals: Ctrl-C cancels the solvers at their next checkpoint
//! (`numerics::budget::cancel`) and raises `KeyboardInterrupt`.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use repro::numerics::budget;
use repro::pipeline::cache::LockMode;
use repro::pipeline::executor::{self, RunError, RunOptions, TaskCounter};
use repro::pipeline::kind::Registry;
use repro::pipeline::report::{RunReport, Status};
use repro::pipeline::spec::{InvalidPipeline, Override, Pipeline};
use repro::pipeline::table::ColumnData;
use repro::point::PointError;
use std::path::PathBuf;
use std::sync::atomic::Ordering;
use std::sync::{Arc, OnceLock};
use std::time::Duration;

/// The stage kinds, built once per process.
fn registry() -> &'static Registry {
    static REGISTRY: OnceLock<Registry> = OnceLock::new();
    REGISTRY.get_or_init(repro::stages::registry)
}

/// An exception of `repro.errors`, by class name, with `args`.
fn error<'py>(py: Python<'py>, class: &str, args: impl pyo3::call::PyCallArgs<'py>) -> PyErr {
    match py.import("repro.errors").and_then(|m| m.getattr(class)).and_then(|c| c.call1(args)) {
        Ok(e) => PyErr::from_value(e),
        Err(e) => e,
    }
}

fn invalid_pipeline(py: Python<'_>, inv: &InvalidPipeline) -> PyErr {
    let diagnostics: Vec<(String, usize, usize, String)> = inv
        .0
        .iter()
        .map(|d| (d.location.file.clone(), d.location.line, d.location.column, d.message.clone()))
        .collect();
    error(py, "InvalidPipeline", (inv.to_string(), diagnostics))
}

fn point_error(py: Python<'_>, e: PointError) -> PyErr {
    match e {
        PointError::UnknownKind { .. } => error(py, "UnknownKind", (e.to_string(),)),
        PointError::InvalidParameters { .. } => error(py, "InvalidParameter", (e.to_string(),)),
        PointError::Failed(repro::pipeline::task::TaskError::Interrupted) => {
            pyo3::exceptions::PyKeyboardInterrupt::new_err("interrupted")
        }
        PointError::Failed(failed) => error(py, "TaskFailed", (failed.to_string(), Vec::<String>::new())),
    }
}

fn run_error(py: Python<'_>, e: RunError) -> PyErr {
    match e {
        RunError::Usage(u) => error(py, "UsageError", (u.to_string(),)),
        RunError::CacheBusy(b) => error(py, "CacheBusy", (b.to_string(),)),
        RunError::Io(e) => error(py, "CacheError", (format!("{e:#}"),)),
    }
}

/// Runs `work` on a thread of its own while this thread, without the GIL, waits for it:
/// every 50 ms it reports the task counter to `on_progress` (with the GIL) and checks for
/// signals. On a signal's exception (Ctrl-C's `KeyboardInterrupt`) the solvers are
/// cancelled at their next checkpoint, the work is waited for (what it finished stays in
/// the cache, written atomically), and the exception is raised.
fn interruptible<T: Send>(
    py: Python<'_>,
    counter: Option<&TaskCounter>,
    on_progress: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    budget::resume();
    std::thread::scope(|scope| {
        let handle = scope.spawn(work);
        let mut shown = (usize::MAX, usize::MAX);
        loop {
            py.detach(|| {
                for _ in 0..10 {
                    if handle.is_finished() {
                        break;
                    }
                    std::thread::sleep(Duration::from_millis(5));
                }
            });
            if let (Some(c), Some(f)) = (counter, on_progress) {
                let now = (c.done.load(Ordering::Relaxed), c.total.load(Ordering::Relaxed));
                if now != shown {
                    shown = now;
                    f.call1(now)?;
                }
            }
            if handle.is_finished() {
                return match handle.join() {
                    Ok(v) => Ok(v),
                    Err(panic) => std::panic::resume_unwind(panic),
                };
            }
            if let Err(interrupt) = py.check_signals() {
                budget::cancel();
                let _ = py.detach(|| handle.join());
                budget::resume();
                return Err(interrupt);
            }
        }
    })
}

/// The names of the stage kinds.
#[pyfunction]
fn kinds() -> Vec<&'static str> {
    registry().names().collect()
}

/// A kind's description (`repro kinds KIND`) as JSON.
#[pyfunction]
fn describe_json(py: Python<'_>, kind: &str) -> PyResult<String> {
    let r = registry();
    let k = repro::point::kind(r, kind).map_err(|e| point_error(py, e))?;
    serde_json::to_string(&repro::description::describe(k, r)).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// The columns of a table as a dict of lists (floats, ints, bools or strings).
fn columns<'py>(py: Python<'py>, t: &repro::pipeline::table::Table) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, col) in &t.columns {
        match col {
            ColumnData::F64(v) => d.set_item(name, PyList::new(py, v)?)?,
            ColumnData::I64(v) => d.set_item(name, PyList::new(py, v)?)?,
            ColumnData::Bool(v) => d.set_item(name, PyList::new(py, v)?)?,
            ColumnData::Str(v) => d.set_item(name, PyList::new(py, v)?)?,
        }
    }
    Ok(d)
}

/// One point of a kind: its table's columns as lists.
#[pyfunction]
fn point<'py>(py: Python<'py>, kind: &str, params_json: &str) -> PyResult<Bound<'py, PyDict>> {
    let params: serde_json::Value =
        serde_json::from_str(params_json).map_err(|e| error(py, "InvalidParameter", (format!("parameters: {e}"),)))?;
    let out = interruptible(py, None, None, || repro::point::compute(registry(), kind, &params, None))?
        .map_err(|e| point_error(py, e))?;
    columns(py, &out.table)
}

/// The failed tasks of a run, as "stage [label]: error" lines.
fn failures(report: &RunReport) -> Vec<String> {
    report
        .tasks
        .iter()
        .filter(|t| t.status == Status::Failed)
        .map(|t| format!("{} [{}]: {}", t.stage, t.point, t.error.as_deref().unwrap_or_default()))
        .collect()
}

/// Runs a parsed pipeline; returns its report as JSON and its completed stages' tables as
/// Parquet bytes (with the metadata of a published table), by stage name.
fn run_pipeline<'py>(
    py: Python<'py>,
    p: &Pipeline,
    opts: RunOptions,
    on_progress: Option<&Bound<'py, PyAny>>,
) -> PyResult<(String, Bound<'py, PyDict>, Vec<String>)> {
    let counter = Arc::new(TaskCounter::default());
    let opts = RunOptions { counter: Some(counter.clone()), ..opts };
    let r = registry();
    let (report, completed) = interruptible(py, Some(&counter), on_progress, || executor::run_keeping(p, r, &opts))?
        .map_err(|e| run_error(py, e))?;
    if report.tasks.iter().any(|t| t.failure == Some(repro::pipeline::task::TaskError::Interrupted)) {
        return Err(pyo3::exceptions::PyKeyboardInterrupt::new_err("interrupted"));
    }
    let tables = PyDict::new(py);
    for c in &completed {
        let stage = p.stage(&c.stage).expect("a completed stage is the pipeline's");
        let (bytes, _) = repro::pipeline::publish::stage_parquet(p, stage, r, &c.points, &c.times)
            .map_err(|e| error(py, "CacheError", (format!("{e:#}"),)))?;
        tables.set_item(&c.stage, PyBytes::new(py, &bytes))?;
    }
    let json = serde_json::to_string(&report).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok((json, tables, failures(&report)))
}

/// The options every call shares: the cache, the threads, the command line's progress
/// bars, and whether to wait for another process holding the cache (else `CacheBusy`).
fn cache_options(cache: PathBuf, jobs: Option<usize>, progress: bool, wait: bool) -> RunOptions {
    let lock = if wait { LockMode::Wait } else { LockMode::Refuse };
    RunOptions { cache_dir: cache, jobs, progress, lock, ..Default::default() }
}

/// A sweep of one kind: a pipeline of one stage, named after the kind, whose parameters
/// `params_json` gives as a pipeline file does (a list sweeps a sweepable parameter).
///
/// Its arguments are the Python keyword arguments of `repro.sweep`.
#[pyfunction]
#[pyo3(signature = (kind, params_json, cache, jobs=None, progress=false, on_progress=None, wait=true))]
#[allow(clippy::too_many_arguments)]
fn sweep<'py>(
    py: Python<'py>,
    kind: &str,
    params_json: &str,
    cache: PathBuf,
    jobs: Option<usize>,
    progress: bool,
    on_progress: Option<Bound<'py, PyAny>>,
    wait: bool,
) -> PyResult<(String, Bound<'py, PyDict>, Vec<String>)> {
    let r = registry();
    repro::point::kind(r, kind).map_err(|e| point_error(py, e))?;
    let params: serde_json::Value =
        serde_json::from_str(params_json).map_err(|e| error(py, "InvalidParameter", (format!("parameters: {e}"),)))?;
    let text = serde_json::json!({"stages": [{"name": kind, "kind": kind, "params": params}]}).to_string();
    // The pipeline's text is this call's: its errors are the parameters', without a line.
    let p = repro::pipeline::parse::parse(&format!("<repro.sweep({kind})>"), &text, r).map_err(|inv| {
        let messages: Vec<String> = inv.0.iter().map(|d| d.message.clone()).collect();
        error(py, "InvalidParameter", (messages.join("; "),))
    })?;
    run_pipeline(py, &p, cache_options(cache, jobs, progress, wait), on_progress.as_ref())
}

/// A run of a pipeline file: its targets (all stages if none) and what they need, with
/// `overrides` ("stage.param=value", the value YAML) set as `repro run -S` sets them.
///
/// Its arguments are the Python keyword arguments, one per option of `repro run`.
#[pyfunction]
#[pyo3(signature = (pipeline, targets, overrides, cache, figures=None, tables=None, jobs=None, progress=false, dry_run=false, force=Vec::new(), on_progress=None, wait=true, publish=false))]
#[allow(clippy::too_many_arguments)]
fn run<'py>(
    py: Python<'py>,
    pipeline: PathBuf,
    targets: Vec<String>,
    overrides: Vec<String>,
    cache: PathBuf,
    figures: Option<PathBuf>,
    tables: Option<PathBuf>,
    jobs: Option<usize>,
    progress: bool,
    dry_run: bool,
    force: Vec<String>,
    on_progress: Option<Bound<'py, PyAny>>,
    wait: bool,
    publish: bool,
) -> PyResult<(String, Bound<'py, PyDict>, Vec<String>)> {
    // With settings, apart from the file's outputs unless told (as `repro run -S`).
    let (figures, tables, _) = repro::pipeline::publish::publish_dirs(&pipeline, &overrides, figures, tables, publish);
    let overrides = overrides
        .iter()
        .map(|o| o.parse::<Override>().map_err(|m| error(py, "UsageError", (m,))))
        .collect::<PyResult<Vec<_>>>()?;
    let p = repro::pipeline::parse::load_with(&pipeline, registry(), &overrides)
        .map_err(|inv| invalid_pipeline(py, &inv))?;
    let opts = RunOptions {
        figures_dir: figures,
        tables_dir: tables,
        dry_run,
        force,
        targets,
        ..cache_options(cache, jobs, progress, wait)
    };
    run_pipeline(py, &p, opts, on_progress.as_ref())
}

#[pymodule]
fn _repro(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // Tasks run in parallel (rayon); a factorisation inside one task gains nothing from
    // threads of its own (as in the command line).
    faer::set_global_parallelism(faer::Par::Seq);
    m.add_function(wrap_pyfunction!(kinds, m)?)?;
    m.add_function(wrap_pyfunction!(describe_json, m)?)?;
    m.add_function(wrap_pyfunction!(point, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
