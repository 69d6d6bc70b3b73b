//! What a pipeline file says, once read and validated: its stages, their sweep points and
//! where each was declared ([`Pipeline`], [`Stage`], [`Point`]), the parameters set over it
//! on the command line ([`Override`]), and what is wrong with a file ([`InvalidPipeline`],
//! [`Warning`], located by file, line and column). Reading a file is [`crate::parse`].

use crate::table::format_number;
use serde_json::Value;
use std::fmt;

/// A place in a pipeline file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    pub file: String,
    pub line: usize,
    pub column: usize,
}

impl fmt::Display for Location {
    /// `file:line:column`; the file alone where no line applies (line 0: the file could not
    /// be read, or the error is about the whole file).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}", self.file)
        } else {
            write!(f, "{}:{}:{}", self.file, self.line, self.column)
        }
    }
}

/// One error in a pipeline file.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub location: Location,
    pub message: String,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: error: {}", self.location, self.message)
    }
}

/// All the errors found in an invalid pipeline file.
#[derive(Debug)]
pub struct InvalidPipeline(pub Vec<Diagnostic>);

impl fmt::Display for InvalidPipeline {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for InvalidPipeline {}

/// Something in a valid pipeline file that is probably not what was meant (printed, not
/// fatal): e.g. a sweep that leaves part of a figure's declared range empty.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning(pub Diagnostic);

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: warning: {}", self.0.location, self.0.message)
    }
}

/// One point of a stage: its canonical parameters (sorted keys, defaults filled in).
#[derive(Clone, Debug)]
pub struct Point {
    pub params: Value,
    /// `lambda=0.1 k=0.1` for the swept parameters, empty for an unswept stage.
    pub label: String,
}

#[derive(Clone, Debug)]
pub struct Stage {
    pub name: String,
    pub kind: String,
    /// The stages it reads, in order: the whole table of each, or for those in `matched`,
    /// only the rows of the matching points.
    pub needs: Vec<String>,
    /// The stages of `needs` read row by row (`needs: [{stage: S, match: [a, b]}]`).
    pub matched: Vec<MatchedNeed>,
    pub points: Vec<Point>,
    /// The parameter whose points are refined after each round (`adaptive`), if any.
    pub adaptive: Option<AdaptiveAxis>,
    /// The stages whose declared ranges a `shown` sweep of this stage samples (not inputs:
    /// they read this stage; their ranges only fix its points).
    pub ranges_from: Vec<String>,
    /// Its table is written to the tables folder (`publish: false`: an intermediate, kept in
    /// the cache for the stages that need it).
    pub publish: bool,
    /// Its tasks' time limit in seconds (`time_limit`; default: the kind's).
    pub time_limit_s: Option<f64>,
    pub location: Location,
}

/// A needed stage read row by row: each point of the stage that needs it gets the rows of
/// the points of `stage` whose parameters named in `on` equal its own, and its task key
/// depends on those points' outputs alone (adding a point upstream recomputes only the
/// points that match it).
#[derive(Clone, Debug, PartialEq)]
pub struct MatchedNeed {
    pub stage: String,
    pub on: Vec<String>,
}

impl MatchedNeed {
    /// Whether an upstream point with parameters `upstream` matches the point `params`.
    pub fn matches(&self, upstream: &Value, params: &Value) -> bool {
        self.on.iter().all(|k| upstream.get(k).is_some_and(|v| !v.is_null() && Some(v) == params.get(k)))
    }
}

#[derive(Clone, Debug)]
pub struct Pipeline {
    pub file: String,
    pub description: String,
    pub stages: Vec<Stage>,
    /// What the checks of ranges shown found (see the module's documentation).
    pub warnings: Vec<Warning>,
    /// The parameters set over the file's (`Override`), as given.
    pub overrides: Vec<String>,
}

impl Pipeline {
    pub fn stage(&self, name: &str) -> Option<&Stage> {
        self.stages.iter().find(|s| s.name == name)
    }
}

impl Stage {
    /// How the stage reads `need` row by row, if it does.
    pub fn matched(&self, need: &str) -> Option<&MatchedNeed> {
        self.matched.iter().find(|m| m.stage == need)
    }
}

/// A parameter set from the command line for one run (`repro run -S STAGE.PARAM=VALUE`):
/// VALUE is YAML, as in the file (a number, a list, `{logspace: [...]}`, a mapping).
#[derive(Clone, Debug, PartialEq)]
pub struct Override {
    pub stage: String,
    pub param: String,
    pub value: String,
}

impl std::str::FromStr for Override {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (target, value) = s.split_once('=').ok_or_else(|| format!("`{s}`: expected STAGE.PARAM=VALUE"))?;
        let (stage, param) =
            target.split_once('.').ok_or_else(|| format!("`{target}`: expected STAGE.PARAM before `=`"))?;
        if stage.is_empty() || param.is_empty() || value.trim().is_empty() {
            return Err(format!("`{s}`: expected STAGE.PARAM=VALUE with all three given"));
        }
        Ok(Override { stage: stage.to_string(), param: param.to_string(), value: value.to_string() })
    }
}

impl std::fmt::Display for Override {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}.{}={}", self.stage, self.param, self.value)
    }
}

/// The i-th of n points from a to b, linear or in decimal exponents, rounded to 12
/// significant digits so that `{logspace: [-1, 1, 3]}` gives exactly the list [0.1, 1, 10].
pub fn spaced(log: bool, a: f64, b: f64, n: usize, i: usize) -> f64 {
    let t = if n == 1 { 0.0 } else { i as f64 / (n - 1) as f64 };
    let x = a + (b - a) * t;
    round12(if log { 10f64.powf(x) } else { x })
}

/// `x` rounded to 12 significant digits: how every swept value is stored.
pub fn round12(x: f64) -> f64 {
    format!("{x:.11e}").parse().unwrap()
}

/// The `name=value` token of a sweep point's label.
pub fn label_token(name: &str, x: f64) -> String {
    format!("{name}={}", format_number(x))
}

/// The adaptive axis of a stage (at most one per stage; refined by [`crate::adaptive`]).
#[derive(Clone, Debug, PartialEq)]
pub struct AdaptiveAxis {
    /// The swept parameter.
    pub param: String,
    /// Sample in log10 of the parameter (`logspace`) or in the parameter (`linspace`).
    pub log: bool,
    /// The range in the sampling coordinate and the number of initial points.
    pub from: f64,
    pub to: f64,
    pub initial: usize,
    /// Output columns whose curves must be resolved (one row per point).
    pub y: Vec<String>,
    /// Compare y in log10 (for curves drawn on a log axis).
    pub log_y: bool,
    /// Largest deviation from the chord, as a fraction of the curve's span of y.
    pub tol: f64,
    /// Halvings of the initial spacing at most.
    pub levels: u32,
    /// Points per curve at most.
    pub max_points: usize,
}
