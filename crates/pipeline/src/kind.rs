//! The interface between the orchestrator and the code that computes: a stage kind.
//!
//! A kind declares its name, its code version, its parameters (a serde type, from which
//! the JSON Schema is generated), which parameters may be swept, and how to run one point.
//! The orchestrator knows kinds only through this trait; kinds know nothing of YAML,
//! caches or files.

use super::table::Table;
use anyhow::Result;
use schemars::JsonSchema;
use serde::{de::DeserializeOwned, Serialize};
use serde_json::Value;
use std::collections::BTreeMap;
use std::time::Duration;

/// The assembled tables of the stages a task needs, by stage name.
pub struct Inputs<'a> {
    pub tables: BTreeMap<String, &'a Table>,
}

impl<'a> Inputs<'a> {
    pub fn table(&self, stage: &str) -> Result<&'a Table> {
        self.tables.get(stage).copied().ok_or_else(|| {
            anyhow::anyhow!(
                "stage `{stage}` is not among this stage's inputs (needs: {})",
                self.tables.keys().cloned().collect::<Vec<_>>().join(", ")
            )
        })
    }
}

/// What a task produces: a table and, for figures, text artifacts keyed by file extension;
/// a task that checks something may add lines for the end of the run (`notes`) and
/// expectations that no longer hold (`regressions`: the run then exits with its own code).
/// Both are empty for most kinds and then not serialised (an output's bytes, and so its
/// hash, do not change).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Output {
    pub table: Table,
    #[serde(default)]
    pub artifacts: BTreeMap<String, String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub regressions: Vec<String>,
}

impl From<Table> for Output {
    fn from(table: Table) -> Self {
        Output { table, ..Default::default() }
    }
}

/// A problem with one parameter: its path (`k`, `layers[0].from`) and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldError {
    pub path: String,
    pub message: String,
}

impl FieldError {
    pub fn new(path: &str, message: impl Into<String>) -> Self {
        FieldError { path: path.to_string(), message: message.into() }
    }
}

/// A range of one column of another stage's table that a stage shows, e.g. a figure's
/// x axis: the stage `stage` may sample its parameter `column` over it (`{shown: n}`), and
/// the pipeline is checked for sweeps that leave part of it empty or compute outside it.
#[derive(Clone, Debug, PartialEq)]
pub struct ShownRange {
    pub stage: String,
    pub column: String,
    pub from: f64,
    pub to: f64,
    /// Shown on a log axis (sampled in log10).
    pub log: bool,
    /// The parameter that declares the range, e.g. `x_range` (for messages).
    pub path: String,
}

/// A column of another stage's table that a stage reads (a figure layer's `x`, a claim's
/// `y`, a placeholder `{column}` of a title): checked against the columns that stage's kind
/// declares before anything runs.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct ColumnRead {
    /// The parameter that names it, e.g. `layers[2].data.y` (where an error is located).
    pub path: String,
    /// The stage read; none: any of the stages the reader refers to (a title's placeholder
    /// is resolved from the data the figure draws).
    pub stage: Option<String>,
    pub column: String,
}

/// A stage kind, typed. Implement this; the registry wraps it.
pub trait Kind: Send + Sync + 'static {
    /// The name used in pipeline files, e.g. `theory.persson`.
    const NAME: &'static str;
    /// Bump when a change to the code can change this kind's outputs (docs/pipelines.md, "Code versions").
    const VERSION: u32;
    /// One line for `repro kinds` and the schema.
    const DOC: &'static str;
    /// Parameters that may be given as a sweep (list, logspace, linspace).
    const SWEEPABLE: &'static [&'static str] = &[];
    /// The wall time after which a task of this kind is stopped and recorded as timed out,
    /// in seconds: far above what a point of the thesis takes (its longest, about 30 s),
    /// far below a runaway's hours. A stage's `time_limit` and `repro run --time-limit`
    /// override it.
    const TIME_LIMIT_S: f64 = 600.0;
    /// The columns of this kind's table, in order (some only for some parameters, e.g. a
    /// material's), for `repro kinds KIND`; a test checks that every emitted column is here.
    const COLUMNS: &'static [&'static str] = &[];
    /// The table may carry columns beyond `COLUMNS`, named by the parameters (a fit's group
    /// column): columns read from it are not checked.
    const OPEN_COLUMNS: bool = false;
    type Params: DeserializeOwned + Serialize + JsonSchema + Send + Sync;

    /// Physical and logical validity of one point's parameters.
    fn validate(_p: &Self::Params) -> Vec<FieldError> {
        Vec::new()
    }
    /// Stages named inside the parameters (with the parameter path), which must be in `needs`.
    fn referenced_stages(_p: &Self::Params) -> Vec<(String, String)> {
        Vec::new()
    }
    /// Ranges of other stages' columns that this stage shows (see [`ShownRange`]).
    fn shown_ranges(_p: &Self::Params) -> Vec<ShownRange> {
        Vec::new()
    }
    /// Columns of other stages' tables that this stage reads (see [`ColumnRead`]).
    fn read_columns(_p: &Self::Params) -> Vec<ColumnRead> {
        Vec::new()
    }
    /// The most memory a task of these parameters allocates, in bytes, estimated before it
    /// runs, for the kinds whose need grows with their parameters (None: small). A task
    /// whose estimate exceeds the memory available is not started (`task::TaskError::Resources`).
    fn memory_bytes(_p: &Self::Params) -> Option<u64> {
        None
    }
    fn run(p: &Self::Params, inputs: &Inputs) -> Result<Output>;
}

/// Canonical parameters of a point, and the (parameter path, stage) pairs it refers to.
pub type Checked = (Value, Vec<(String, String)>);

/// The object-safe form of [`Kind`] that the orchestrator uses.
pub trait DynKind: Send + Sync {
    fn name(&self) -> &'static str;
    fn version(&self) -> u32;
    fn doc(&self) -> &'static str;
    fn sweepable(&self) -> &'static [&'static str];
    fn columns(&self) -> &'static [&'static str];
    /// Whether the table may carry columns beyond `columns` (`Kind::OPEN_COLUMNS`).
    fn open_columns(&self) -> bool;
    fn time_limit_s(&self) -> f64;
    fn params_schema(&self) -> Value;
    /// Parses and validates one point; returns its canonical parameters (defaults filled in)
    /// and the stages it references.
    fn check(&self, params: &Value) -> Result<Checked, Vec<FieldError>>;
    fn run(&self, params: &Value, inputs: &Inputs) -> Result<Output>;
    /// The ranges a point with these parameters shows; none when they do not parse (their
    /// errors are reported by `check`).
    fn shown_ranges(&self, params: &Value) -> Vec<ShownRange>;
    /// The columns a point with these parameters reads; none when they do not parse.
    fn read_columns(&self, params: &Value) -> Vec<ColumnRead>;
    /// [`Kind::memory_bytes`] of one point's canonical parameters.
    fn memory_bytes(&self, params: &Value) -> Option<u64>;
}

/// A kind with the JSON Schema of its parameters, whose numeric bounds (`minimum`,
/// `exclusiveMinimum`, `maximum`, `exclusiveMaximum`, declared once on the parameter types)
/// every point is checked against.
struct Typed<K: Kind> {
    schema: Value,
    kind: std::marker::PhantomData<K>,
}

/// The definition a `$ref` of `schema` points to in `root`'s `$defs`, if it has one.
fn referenced<'a>(root: &'a Value, schema: &Value) -> Option<&'a Value> {
    let name = schema.get("$ref")?.as_str()?.strip_prefix("#/$defs/")?;
    root.get("$defs")?.get(name)
}

/// The errors of `value` (at `path`) against the numeric bounds of `schema` and of the
/// schemas of its fields and items; `root` resolves `$ref`s.
pub fn bound_errors(root: &Value, schema: &Value, value: &Value, path: &str, errors: &mut Vec<FieldError>) {
    if let Some(def) = referenced(root, schema) {
        bound_errors(root, def, value, path, errors);
    }
    for key in ["anyOf", "oneOf", "allOf"] {
        for branch in schema.get(key).and_then(Value::as_array).into_iter().flatten() {
            bound_errors(root, branch, value, path, errors);
        }
    }
    let join = |field: &str| if path.is_empty() { field.to_string() } else { format!("{path}.{field}") };
    match value {
        Value::Number(n) => {
            if let Some(message) = n.as_f64().and_then(|x| out_of_bounds(schema, x)) {
                errors.push(FieldError::new(path, message));
            }
        }
        Value::Object(fields) => {
            if let Some(props) = schema.get("properties") {
                for (name, v) in fields {
                    if let Some(s) = props.get(name) {
                        bound_errors(root, s, v, &join(name), errors);
                    }
                }
            }
        }
        Value::Array(items) => {
            let prefix = schema.get("prefixItems").and_then(Value::as_array);
            for (i, v) in items.iter().enumerate() {
                let s = prefix.and_then(|p| p.get(i)).or_else(|| schema.get("items"));
                if let Some(s) = s {
                    bound_errors(root, s, v, &format!("{path}[{i}]"), errors);
                }
            }
        }
        _ => {}
    }
}

/// A bound or a value as errors and `repro kinds` show it: 0.5, 32000, 1e100, 1e-14.
fn show(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else if x != 0.0 && (x.abs() >= 1e15 || x.abs() < 1e-4) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The bounds of a numeric schema: (lower, exclusive), (upper, exclusive), and whether it
/// is an integer's.
struct Bounds {
    lo: Option<(f64, bool)>,
    hi: Option<(f64, bool)>,
    integer: bool,
}

impl Bounds {
    fn of(schema: &Value) -> Bounds {
        let get = |k: &str| schema.get(k).and_then(Value::as_f64);
        let side =
            |inclusive: &str, exclusive: &str| get(exclusive).map(|b| (b, true)).or(get(inclusive).map(|b| (b, false)));
        let integer = schema
            .get("type")
            .is_some_and(|t| t == "integer" || t.as_array().is_some_and(|a| a.iter().any(|x| x == "integer")));
        Bounds { lo: side("minimum", "exclusiveMinimum"), hi: side("maximum", "exclusiveMaximum"), integer }
    }

    fn contains(&self, x: f64) -> bool {
        self.lo.is_none_or(|(b, open)| if open { x > b } else { x >= b })
            && self.hi.is_none_or(|(b, open)| if open { x < b } else { x <= b })
    }

    /// "> 0", ">= 0", "(0, 1)", "[0, 1)", "16..=32000"; empty without bounds.
    fn text(&self) -> String {
        match (self.lo, self.hi) {
            (Some((a, open)), None) => format!("{} {}", if open { ">" } else { ">=" }, show(a)),
            (None, Some((b, open))) => format!("{} {}", if open { "<" } else { "<=" }, show(b)),
            (Some((a, false)), Some((b, false))) if self.integer => format!("{}..={}", show(a), show(b)),
            (Some((a, lo_open)), Some((b, hi_open))) => {
                format!(
                    "{}{}, {}{}",
                    if lo_open { "(" } else { "[" },
                    show(a),
                    show(b),
                    if hi_open { ")" } else { "]" }
                )
            }
            (None, None) => String::new(),
        }
    }
}

/// The valid range of a numeric schema as `repro kinds` shows it (`Bounds::text`); `$ref`s
/// are followed (`root` resolves them).
pub fn range_text(root: &Value, schema: &Value) -> String {
    match referenced(root, schema) {
        Some(def) => range_text(root, def),
        None => Bounds::of(schema).text(),
    }
}

/// What is wrong with `x` against the bounds of `schema`, if anything, in the words of the
/// errors: "must be positive", "must be zero or positive", "must lie in (-1, 0.5)".
fn out_of_bounds(schema: &Value, x: f64) -> Option<String> {
    let bounds = Bounds::of(schema);
    if bounds.contains(x) {
        return None;
    }
    let wanted = match (bounds.lo, bounds.hi) {
        (Some((0.0, true)), None) => "must be positive".to_string(),
        (Some((0.0, false)), None) => "must be zero or positive".to_string(),
        (Some(_), Some(_)) => format!("must lie in {}", bounds.text()),
        _ => format!("must be {}", bounds.text()),
    };
    Some(format!("{wanted}, got {}", show(x)))
}

fn parse<K: Kind>(params: &Value) -> Result<K::Params, FieldError> {
    serde_path_to_error::deserialize::<_, K::Params>(params).map_err(|e| {
        let path = e.path().to_string();
        let path = if path == "." { String::new() } else { path };
        FieldError { path, message: e.into_inner().to_string() }
    })
}

impl<K: Kind> DynKind for Typed<K> {
    fn name(&self) -> &'static str {
        K::NAME
    }
    fn version(&self) -> u32 {
        K::VERSION
    }
    fn doc(&self) -> &'static str {
        K::DOC
    }
    fn sweepable(&self) -> &'static [&'static str] {
        K::SWEEPABLE
    }
    fn columns(&self) -> &'static [&'static str] {
        K::COLUMNS
    }
    fn open_columns(&self) -> bool {
        K::OPEN_COLUMNS
    }
    fn time_limit_s(&self) -> f64 {
        K::TIME_LIMIT_S
    }
    fn params_schema(&self) -> Value {
        self.schema.clone()
    }
    fn check(&self, params: &Value) -> Result<Checked, Vec<FieldError>> {
        let p = parse::<K>(params).map_err(|e| vec![e])?;
        let canonical = serde_json::to_value(&p).expect("params serialise");
        let mut errors = Vec::new();
        bound_errors(&self.schema, &self.schema, &canonical, "", &mut errors);
        // Every error at once; a field out of its declared bounds is reported once.
        let out_of_bounds: Vec<String> = errors.iter().map(|e| e.path.clone()).collect();
        errors.extend(K::validate(&p).into_iter().filter(|e| !out_of_bounds.contains(&e.path)));
        if !errors.is_empty() {
            return Err(errors);
        }
        Ok((canonical, K::referenced_stages(&p)))
    }
    fn run(&self, params: &Value, inputs: &Inputs) -> Result<Output> {
        let p = parse::<K>(params).map_err(|e| anyhow::anyhow!("{}: {}", e.path, e.message))?;
        K::run(&p, inputs)
    }
    fn shown_ranges(&self, params: &Value) -> Vec<ShownRange> {
        parse::<K>(params).map(|p| K::shown_ranges(&p)).unwrap_or_default()
    }
    fn read_columns(&self, params: &Value) -> Vec<ColumnRead> {
        parse::<K>(params).map(|p| K::read_columns(&p)).unwrap_or_default()
    }
    fn memory_bytes(&self, params: &Value) -> Option<u64> {
        parse::<K>(params).ok().and_then(|p| K::memory_bytes(&p))
    }
}

/// Why a limited computation stopped before it ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stopped {
    /// Its time limit passed.
    TimeLimit,
    /// The process was interrupted (Ctrl-C in the Python package).
    Interrupted,
}

/// Runs a task's computation within a time limit, or says why it stopped first. The code
/// that binds kinds to their solvers installs it (`Registry::set_limiter`): it knows how
/// they are interrupted.
pub type Limiter = fn(Duration, &mut dyn FnMut() -> Result<Output>) -> Result<Result<Output>, Stopped>;

/// A task stopped at its time limit (seconds).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("timed out: past its time limit of {0} s (a stage's `time_limit`, or `repro run --time-limit`)")]
pub struct TimeLimitExceeded(pub f64);

/// A task stopped because the process was interrupted.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("interrupted before it ended")]
pub struct Interrupted;

/// The stage kinds a pipeline may use, by name, and what their output columns mean.
#[derive(Default)]
pub struct Registry {
    kinds: BTreeMap<&'static str, Box<dyn DynKind>>,
    columns: BTreeMap<String, ColumnDoc>,
    limiter: Option<Limiter>,
}

/// The unit (or normalisation) and meaning of an output column, written beside every
/// published table in its Parquet metadata (`repro.columns`).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct ColumnDoc {
    pub unit: String,
    pub meaning: String,
}

impl Registry {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn add<K: Kind>(&mut self) -> &mut Self {
        let schema = serde_json::to_value(schemars::schema_for!(K::Params)).expect("schema serialises");
        let prev = self.kinds.insert(K::NAME, Box::new(Typed::<K> { schema, kind: std::marker::PhantomData }));
        assert!(prev.is_none(), "stage kind {} registered twice", K::NAME);
        self
    }

    pub fn get(&self, name: &str) -> Option<&dyn DynKind> {
        self.kinds.get(name).map(|b| b.as_ref())
    }

    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.kinds.keys().copied()
    }

    pub fn iter(&self) -> impl Iterator<Item = &dyn DynKind> + '_ {
        self.kinds.values().map(|b| b.as_ref())
    }

    /// Documents output columns (the first description of a name is kept).
    pub fn document_columns(&mut self, docs: impl IntoIterator<Item = (String, ColumnDoc)>) -> &mut Self {
        for (name, doc) in docs {
            self.columns.entry(name).or_insert(doc);
        }
        self
    }

    /// Installs the way tasks are held to their time limit (without one, they run to the end).
    pub fn set_limiter(&mut self, limiter: Limiter) -> &mut Self {
        self.limiter = Some(limiter);
        self
    }

    /// Runs one point of `kind`, stopped at `limit` (if the registry has a limiter) with
    /// [`TimeLimitExceeded`], or by an interrupt with [`Interrupted`].
    pub fn run_limited(
        &self,
        kind: &dyn DynKind,
        params: &Value,
        inputs: &Inputs,
        limit: Option<Duration>,
    ) -> Result<Output> {
        match (self.limiter, limit) {
            (Some(limiter), Some(limit)) => match limiter(limit, &mut || kind.run(params, inputs)) {
                Ok(out) => out,
                Err(Stopped::TimeLimit) => Err(TimeLimitExceeded(limit.as_secs_f64()).into()),
                Err(Stopped::Interrupted) => Err(Interrupted.into()),
            },
            _ => kind.run(params, inputs),
        }
    }

    /// The unit and meaning of an output column, if documented.
    pub fn column(&self, name: &str) -> Option<&ColumnDoc> {
        self.columns.get(name)
    }
}
