//! The pipeline file: parsing, sweep expansion and validation, with errors that name the
//! file, line and column.
//!
//! ```yaml
//! stages:
//!   - name: persson            # unique, [A-Za-z0-9_.-]
//!     kind: theory.persson     # a registered stage kind
//!     params:                  # checked against the kind's parameter type
//!       inv_k: [1.1, 2, 10]    # a sweep: a list,
//!       V0: {logspace: [-3, 3, 61]}   # or 10^from..10^to in n points, or {linspace: [from, to, n]}
//!       # or refined where the curve of an output column bends or peaks (`adaptive`):
//!       # V0: {adaptive: {logspace: [-3, 3, 13], y: mu_star, tol: 0.01}}
//!       # or over the range the figures that plot it show (their `x_range`), in n points:
//!       # V0: {shown: 49}   or   V0: {adaptive: {shown: 13, y: mu_star, tol: 0.01}}
//!     needs: [other_stage]     # stages whose tables this stage reads
//! ```
//! A stage with sweeps expands into one point per element of the Cartesian product.
//! Nothing is run when any error is found; all errors found are reported together.
//!
//! Ranges shown: a stage kind may declare that a stage shows a column of another stage
//! over a range ([`ShownRange`], a figure's `x_range`). A sweep of that parameter may
//! sample it (`shown`), and any sweep of it is checked against it: one that leaves part of
//! the range without points, or (when every stage that reads it shows the column over a
//! declared range) computes points outside every range shown, gets a warning.

use super::adaptive::AdaptiveAxis;
use super::kind::{FieldError, Registry, ShownRange};
use super::table::format_number;
use marked_yaml::types::{MarkedMappingNode, MarkedScalarNode, Node};
use serde_json::{Map, Number, Value};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;

/// A place in a pipeline file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    pub file: String,
    pub line: usize,
    pub column: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.column)
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
    pub needs: Vec<String>,
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

/// Reads and validates a pipeline file.
pub fn load(path: &std::path::Path, registry: &Registry) -> Result<Pipeline, InvalidPipeline> {
    load_with(path, registry, &[])
}

/// Reads a pipeline file, sets the parameters `overrides` name (each replaces the stage's
/// parameter, or adds it), and validates the result.
pub fn load_with(
    path: &std::path::Path,
    registry: &Registry,
    overrides: &[Override],
) -> Result<Pipeline, InvalidPipeline> {
    let file = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| {
        InvalidPipeline(vec![Diagnostic {
            location: Location { file: file.clone(), line: 0, column: 0 },
            message: format!("cannot read the pipeline file: {e}"),
        }])
    })?;
    let text = String::from_utf8(bytes).map_err(|e| {
        // Located at the first invalid byte.
        let at = e.utf8_error().valid_up_to();
        let before = &e.as_bytes()[..at];
        let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
        let column = at - before.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1) + 1;
        InvalidPipeline(vec![Diagnostic {
            location: Location { file: file.clone(), line, column },
            message: format!("the pipeline file is not UTF-8 (invalid byte at offset {at})"),
        }])
    })?;
    parse_with(&file, &text, registry, overrides)
}

/// A range shown by a stage (`by`), declared at `location`.
#[derive(Clone, Debug)]
struct Shown {
    by: String,
    range: ShownRange,
    location: Location,
}

struct Ctx<'a> {
    file: &'a str,
    errors: Vec<Diagnostic>,
    warnings: Vec<Warning>,
    /// The ranges shown of (stage, column), from every stage that declares one.
    shown: BTreeMap<(String, String), Vec<Shown>>,
    /// The stages whose ranges the stage being parsed samples.
    ranges_used: BTreeSet<String>,
}

impl Ctx<'_> {
    /// Where a node starts; for a block mapping, where its first key starts (marked_yaml
    /// marks block mappings at their first colon).
    fn loc(&self, node: &Node) -> Location {
        if let Node::Mapping(m) = node {
            return mapping_location(self.file, m);
        }
        span_location(self.file, node.span())
    }
    fn err(&mut self, location: Location, message: impl Into<String>) {
        self.errors.push(Diagnostic { location, message: message.into() });
    }
}

fn span_location(file: &str, span: &marked_yaml::Span) -> Location {
    let (line, column) = span.start().map_or((0, 0), |m| (m.line(), m.column()));
    Location { file: file.to_string(), line, column }
}

fn mapping_location(file: &str, m: &MarkedMappingNode) -> Location {
    match m.keys().next() {
        Some(k) if !is_flow_mapping(m) => span_location(file, k.span()),
        _ => span_location(file, m.span()),
    }
}

/// A flow mapping (`{a: 1}`) starts at its brace, which is what its span marks.
fn is_flow_mapping(m: &MarkedMappingNode) -> bool {
    match (m.span().start(), m.keys().next().and_then(|k| k.span().start())) {
        (Some(ms), Some(ks)) => ms.line() < ks.line() || (ms.line() == ks.line() && ms.column() < ks.column()),
        _ => true,
    }
}

fn marker_location(file: &str, m: &marked_yaml::Marker) -> Location {
    Location { file: file.to_string(), line: m.line(), column: m.column() }
}

fn load_error(file: &str, e: marked_yaml::LoadError) -> Diagnostic {
    use marked_yaml::LoadError::*;
    let (location, message) = match &e {
        TopLevelMustBeMapping(m) => {
            (marker_location(file, m), "the top level must be a mapping with a `stages` list".to_string())
        }
        TopLevelMustBeSequence(m) | UnexpectedAnchor(m) | MappingKeyMustBeScalar(m) | UnexpectedTag(m) => {
            (marker_location(file, m), strip_marker(&e.to_string()))
        }
        ScanError(m, _) => (marker_location(file, m), format!("invalid YAML: {}", strip_marker(&e.to_string()))),
        DuplicateKey(inner) => (
            span_location(file, inner.key.span()),
            format!(
                "duplicate key `{}` (first given at line {})",
                inner.key.as_str(),
                inner.prev_key.span().start().map_or(0, |m| m.line())
            ),
        ),
    };
    Diagnostic { location, message }
}

/// The line (1-based) where a second YAML document starts: a `---` or `...` marker after
/// the first document's content (a `---` before any content opens the first document).
fn second_document(text: &str) -> Option<usize> {
    let mut content = false;
    for (i, line) in text.lines().enumerate() {
        let marker = |m: &str| line == m || line.starts_with(&format!("{m} ")) || line.starts_with(&format!("{m}\t"));
        if marker("---") || marker("...") {
            if content {
                return Some(i + 1);
            }
            continue;
        }
        let t = line.trim_start();
        if !t.is_empty() && !t.starts_with('#') {
            content = true;
        }
    }
    None
}

fn strip_marker(s: &str) -> String {
    // marked_yaml prefixes messages with its own marker; we print ours.
    match s.split_once(": ") {
        Some((head, rest)) if head.chars().any(|c| c.is_ascii_digit()) => rest.to_string(),
        _ => s.to_string(),
    }
}

/// Parses pipeline text (exposed for tests).
pub fn parse(file: &str, text: &str, registry: &Registry) -> Result<Pipeline, InvalidPipeline> {
    parse_with(file, text, registry, &[])
}

/// Sets each override's parameter in the parsed file: a diagnostic per override that names no
/// stage, or whose value is not YAML.
fn apply_overrides(file: &str, root: &mut Node, overrides: &[Override]) -> Vec<Diagnostic> {
    let mut errors = Vec::new();
    let at = |o: &Override, message: String| Diagnostic {
        location: Location { file: format!("{file} (-S {o})"), line: 0, column: 0 },
        message,
    };
    for o in overrides {
        let options = marked_yaml::LoaderOptions::default().prevent_coercion(true);
        let value = match marked_yaml::parse_yaml_with_options(0, format!("v: {}", o.value), options) {
            Ok(Node::Mapping(m)) => m.get_node("v").cloned(),
            _ => None,
        };
        let Some(value) = value else {
            errors.push(at(o, format!("`{}` is not a YAML value", o.value)));
            continue;
        };
        let stages = match root.as_mapping_mut().and_then(|m| m.get_mut(&MarkedScalarNode::from("stages"))) {
            Some(Node::Sequence(seq)) => seq,
            _ => {
                errors.push(at(o, "the pipeline has no `stages` list".into()));
                continue;
            }
        };
        let names: Vec<String> =
            stages.iter().filter_map(|n| n.as_mapping()?.get_scalar("name").map(|s| s.as_str().to_string())).collect();
        let Some(stage) = stages
            .iter_mut()
            .filter_map(|n| n.as_mapping_mut())
            .find(|m| m.get_scalar("name").is_some_and(|s| s.as_str() == o.stage))
        else {
            let known: Vec<&str> = names.iter().map(|s| s.as_str()).collect();
            let hint = suggestion(&o.stage, &known).map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default();
            errors.push(at(o, format!("no stage `{}` in the pipeline{hint}", o.stage)));
            continue;
        };
        let key = MarkedScalarNode::from("params");
        if !matches!(stage.get(&key), Some(Node::Mapping(_))) {
            stage.insert(key.clone(), Node::Mapping(MarkedMappingNode::new_empty(marked_yaml::Span::new_blank())));
        }
        if let Some(Node::Mapping(params)) = stage.get_mut(&key) {
            params.insert(MarkedScalarNode::from(o.param.as_str()), value);
        }
    }
    errors
}

/// `parse`, with `overrides` applied to the parsed file before validation.
pub fn parse_with(
    file: &str,
    text: &str,
    registry: &Registry,
    overrides: &[Override],
) -> Result<Pipeline, InvalidPipeline> {
    if let Some(line) = second_document(text) {
        return Err(InvalidPipeline(vec![Diagnostic {
            location: Location { file: file.to_string(), line, column: 1 },
            message: "a pipeline file holds one YAML document; a second one starts here".to_string(),
        }]));
    }
    // A quoted scalar stays text (`A_max: "5.0"` is a string, as for the JSON Schema).
    let options = marked_yaml::LoaderOptions::default().error_on_duplicate_keys(true).prevent_coercion(true);
    let mut root = marked_yaml::parse_yaml_with_options(0, text, options)
        .map_err(|e| InvalidPipeline(vec![load_error(file, e)]))?;
    let errors = apply_overrides(file, &mut root, overrides);
    if !errors.is_empty() {
        return Err(InvalidPipeline(errors));
    }
    let mut cx =
        Ctx { file, errors: Vec::new(), warnings: Vec::new(), shown: BTreeMap::new(), ranges_used: BTreeSet::new() };
    let root_map = root.as_mapping().expect("marked_yaml guarantees a top-level mapping");
    check_keys(&mut cx, root_map, &["stages", "description"], "the pipeline");
    let description = root_map.get_scalar("description").map(|s| s.as_str().to_string()).unwrap_or_default();
    let mut stages = Vec::new();
    match root_map.get_node("stages") {
        None => cx.err(cx.loc(&root), "missing `stages`: a pipeline is a list of stages"),
        Some(Node::Sequence(seq)) => {
            cx.shown = ranges_shown(file, seq, registry);
            for node in seq.iter() {
                if let Some(s) = parse_stage(&mut cx, node, registry) {
                    stages.push(s);
                }
            }
        }
        Some(other) => cx.err(cx.loc(other), "`stages` must be a list of stages"),
    }
    check_graph(&mut cx, &stages);
    if cx.errors.is_empty() {
        check_ranges_shown(&mut cx, &stages);
        cx.warnings.sort_by_key(|w| (w.0.location.line, w.0.location.column));
        Ok(Pipeline {
            file: file.to_string(),
            description,
            stages: stages.into_iter().map(|s| s.stage).collect(),
            warnings: cx.warnings,
            overrides: overrides.iter().map(|o| o.to_string()).collect(),
        })
    } else {
        cx.errors.sort_by_key(|d| (d.location.line, d.location.column));
        Err(InvalidPipeline(cx.errors))
    }
}

fn check_keys(cx: &mut Ctx, map: &MarkedMappingNode, allowed: &[&str], what: &str) {
    for key in map.keys() {
        if !allowed.contains(&key.as_str()) {
            cx.err(
                span_location(cx.file, key.span()),
                format!("unknown field `{}` in {what} (expected one of: {})", key.as_str(), allowed.join(", ")),
            );
        }
    }
}

struct ParsedStage {
    stage: Stage,
    need_locations: Vec<Location>,
}

fn parse_stage(cx: &mut Ctx, node: &Node, registry: &Registry) -> Option<ParsedStage> {
    let Some(map) = node.as_mapping() else {
        cx.err(cx.loc(node), "a stage must be a mapping with `name`, `kind`, `params` and `needs`");
        return None;
    };
    check_keys(cx, map, &["name", "kind", "params", "needs", "description", "publish", "time_limit"], "a stage");
    let name = match map.get_node("name") {
        Some(Node::Scalar(s)) if is_valid_name(s.as_str()) => s.as_str().to_string(),
        Some(n) => {
            cx.err(cx.loc(n), "a stage name must be 1 to 100 letters, digits, `_`, `-` or `.`, not starting with `.` or `-` (it names the published files)");
            return None;
        }
        None => {
            cx.err(cx.loc(node), "missing field `name` in a stage");
            return None;
        }
    };
    let kind_node = match map.get_node("kind") {
        Some(n @ Node::Scalar(_)) => n,
        Some(n) => {
            cx.err(cx.loc(n), format!("stage `{name}`: `kind` must be a string"));
            return None;
        }
        None => {
            cx.err(cx.loc(node), format!("missing field `kind` in stage `{name}`"));
            return None;
        }
    };
    let kind_name = kind_node.as_scalar().unwrap().as_str().to_string();
    let publish = match map.get_node("publish") {
        None => true,
        Some(Node::Scalar(s)) if s.as_str() == "true" => true,
        Some(Node::Scalar(s)) if s.as_str() == "false" => false,
        Some(n) => {
            cx.err(cx.loc(n), format!("stage `{name}`: `publish` must be true or false"));
            true
        }
    };
    let time_limit_s = match map.get_node("time_limit") {
        None => None,
        Some(n) => match to_json(n).as_f64() {
            Some(s) if s > 0.0 => Some(s),
            _ => {
                cx.err(cx.loc(n), format!("stage `{name}`: `time_limit` must be a positive number of seconds"));
                None
            }
        },
    };
    let mut needs = Vec::new();
    let mut need_locations = Vec::new();
    match map.get_node("needs") {
        None => {}
        Some(Node::Sequence(seq)) => {
            for n in seq.iter() {
                match n {
                    Node::Scalar(s) => {
                        needs.push(s.as_str().to_string());
                        need_locations.push(cx.loc(n));
                    }
                    _ => cx.err(cx.loc(n), format!("stage `{name}`: each entry of `needs` must be a stage name")),
                }
            }
        }
        Some(n) => cx.err(cx.loc(n), format!("stage `{name}`: `needs` must be a list of stage names")),
    }
    let Some(kind) = registry.get(&kind_name) else {
        let known: Vec<_> = registry.names().collect();
        let hint = suggestion(&kind_name, &known).map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default();
        cx.err(
            cx.loc(kind_node),
            format!("stage `{name}`: unknown stage kind `{kind_name}`{hint}; known kinds: {}", known.join(", ")),
        );
        return None;
    };
    let empty;
    let params_map = match map.get_node("params") {
        None => {
            empty = MarkedMappingNode::new_empty(*node.span());
            &empty
        }
        Some(Node::Mapping(m)) => m,
        Some(n) => {
            cx.err(cx.loc(n), format!("stage `{name}`: `params` must be a mapping of parameter names to values"));
            return None;
        }
    };
    cx.ranges_used.clear();
    let (points, adaptive) = expand_points(cx, &name, params_map, kind.sweepable())?;
    let ranges_from: Vec<String> = std::mem::take(&mut cx.ranges_used).into_iter().collect();
    let mut checked = Vec::with_capacity(points.len());
    let mut referenced: BTreeSet<(String, String)> = BTreeSet::new();
    for p in points {
        match kind.check(&p.value) {
            Ok((canonical, refs)) => {
                referenced.extend(refs);
                checked.push(Point { params: canonical, label: p.label });
            }
            Err(errors) => {
                for e in errors {
                    let location = locate(cx, params_map, &p.swept_nodes, &e);
                    let point =
                        if p.label.is_empty() { String::new() } else { format!(" (at sweep point {})", p.label) };
                    cx.err(location, format!("stage `{name}` ({kind_name}){point}: {}", describe(&e)));
                }
                // One point's structural errors repeat at every point: report them once.
                return None;
            }
        }
    }
    for (path, stage) in referenced {
        if !needs.contains(&stage) {
            let location = locate(cx, params_map, &BTreeMap::new(), &FieldError::new(&path, ""));
            cx.err(
                location,
                format!("stage `{name}`: `{path}` refers to stage `{stage}`, which is not in its `needs`"),
            );
        }
    }
    Some(ParsedStage {
        stage: Stage {
            name,
            kind: kind_name,
            needs,
            points: checked,
            adaptive,
            ranges_from,
            publish,
            time_limit_s,
            location: mapping_location(cx.file, map),
        },
        need_locations,
    })
}

fn describe(e: &FieldError) -> String {
    if e.path.is_empty() {
        e.message.clone()
    } else {
        format!("parameter `{}`: {}", e.path, e.message)
    }
}

/// Stage names become file names (`tables/<name>.parquet`, `figures/<name>.svg`): letters,
/// digits, `_`, `-` and `.`, not starting with `.` or `-`, so a pipeline cannot write
/// outside the output directories (no `/`, no `..`), nor hide or shadow files there.
fn is_valid_name(s: &str) -> bool {
    !s.is_empty()
        && s.len() <= 100
        && !s.starts_with(['.', '-'])
        && s.chars().all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c))
}

/// The known name closest to `name`, if it is close (edit distance at most 3, and less
/// than the length of `name`).
fn suggestion<'a>(name: &str, known: &[&'a str]) -> Option<&'a str> {
    fn distance(a: &str, b: &str) -> usize {
        let b: Vec<char> = b.chars().collect();
        let mut prev: Vec<usize> = (0..=b.len()).collect();
        for (i, ca) in a.chars().enumerate() {
            let mut cur = vec![i + 1];
            for (j, cb) in b.iter().enumerate() {
                cur.push((prev[j] + usize::from(ca != *cb)).min(prev[j + 1] + 1).min(cur[j] + 1));
            }
            prev = cur;
        }
        prev[b.len()]
    }
    let limit = 3.min(name.chars().count().saturating_sub(1));
    known.iter().map(|k| (distance(name, k), *k)).filter(|(d, _)| *d <= limit).min().map(|(_, k)| k)
}

/// Converts a YAML node to JSON: unquoted scalars become null, booleans or numbers where
/// they read as such; quoted scalars stay strings.
pub fn to_json(node: &Node) -> Value {
    match node {
        Node::Scalar(s) => {
            let text = s.as_str();
            if !s.may_coerce() {
                return Value::String(text.to_string());
            }
            match text {
                "" | "~" | "null" | "Null" | "NULL" => Value::Null,
                "true" | "True" | "TRUE" => Value::Bool(true),
                "false" | "False" | "FALSE" => Value::Bool(false),
                _ => {
                    if let Ok(i) = text.parse::<i64>() {
                        Value::Number(i.into())
                    } else if let Some(n) = text.parse::<f64>().ok().and_then(Number::from_f64) {
                        // from_f64 refuses NaN and infinities, which stay strings (and fail type checks).
                        Value::Number(n)
                    } else {
                        Value::String(text.to_string())
                    }
                }
            }
        }
        Node::Sequence(seq) => Value::Array(seq.iter().map(to_json).collect()),
        Node::Mapping(map) => Value::Object(map.iter().map(|(k, v)| (k.as_str().to_string(), to_json(v))).collect()),
    }
}

struct RawPoint<'a> {
    value: Value,
    label: String,
    swept_nodes: BTreeMap<String, &'a Node>,
}

/// The values of a swept parameter (with the node each comes from) and, for an adaptive
/// one, its refinement.
type Axis<'a> = (Vec<(f64, &'a Node)>, Option<AdaptiveAxis>);

/// The initial values of a swept parameter and, for `{adaptive: ...}`, its refinement.
fn sweep_values<'a>(cx: &mut Ctx, stage: &str, param: &str, node: &'a Node) -> Option<Axis<'a>> {
    if let Node::Mapping(map) = node {
        if let Some(body) = map.get_node("adaptive") {
            if map.len() != 1 {
                cx.err(
                    cx.loc(node),
                    format!("stage `{stage}`: parameter `{param}`: `adaptive` stands alone in its mapping"),
                );
                return None;
            }
            return adaptive_axis(cx, stage, param, body);
        }
    }
    sweep_values_plain(cx, stage, param, node).map(|v| (v, None))
}

/// `{adaptive: {logspace|linspace: [from, to, n], y: col | [cols], tol: x, log_y, levels, max_points}}`.
fn adaptive_axis<'a>(cx: &mut Ctx, stage: &str, param: &str, body: &'a Node) -> Option<Axis<'a>> {
    let what = format!("stage `{stage}`: parameter `{param}`: adaptive");
    let Node::Mapping(m) = body else {
        cx.err(cx.loc(body), format!("{what}: expected a mapping with `logspace` or `linspace`, `y` and `tol`"));
        return None;
    };
    check_keys(
        cx,
        m,
        &["logspace", "linspace", "shown", "y", "tol", "log_y", "levels", "max_points"],
        "an adaptive sweep",
    );
    let grids: Vec<&str> = ["logspace", "linspace", "shown"].into_iter().filter(|g| m.get_node(g).is_some()).collect();
    if grids.len() != 1 {
        cx.err(
            cx.loc(body),
            format!("{what}: give exactly one of `logspace`, `linspace` and `shown` (the initial grid)"),
        );
        return None;
    }
    let grid_node = m.get_node(grids[0]).unwrap();
    let (log, from, to, n) = if grids[0] == "shown" {
        shown_grid(cx, stage, param, grid_node)?
    } else {
        let (from, to, n) = grid(cx, stage, param, grids[0], grid_node)?;
        (grids[0] == "logspace", from, to, n)
    };
    let values: Vec<(f64, &Node)> = (0..n).map(|i| (spaced(log, from, to, n, i), grid_node)).collect();
    if n < 3 {
        cx.err(cx.loc(grid_node), format!("{what}: the initial grid needs at least 3 points"));
        return None;
    }
    let y = match m.get_node("y").map(to_json) {
        Some(Value::String(s)) => vec![s],
        Some(Value::Array(a)) if !a.is_empty() && a.iter().all(Value::is_string) => {
            a.into_iter().map(|v| v.as_str().unwrap().to_string()).collect()
        }
        _ => {
            let at = m.get_node("y").map_or_else(|| cx.loc(body), |n| cx.loc(n));
            cx.err(at, format!("{what}: `y` must name the output column (or list of columns) to resolve"));
            return None;
        }
    };
    let tol = match m.get_node("tol").map(|n| (to_json(n).as_f64(), n)) {
        Some((Some(t), _)) if t > 0.0 && t < 1.0 => t,
        other => {
            let at = other.map_or_else(|| cx.loc(body), |(_, n)| cx.loc(n));
            cx.err(
                at,
                format!(
                    "{what}: `tol` must be a number in (0, 1): the allowed deviation as a fraction of the curve's span"
                ),
            );
            return None;
        }
    };
    let log_y = match m.get_node("log_y").map(|n| (to_json(n), n)) {
        None => false,
        Some((Value::Bool(b), _)) => b,
        Some((_, n)) => {
            cx.err(cx.loc(n), format!("{what}: `log_y` must be true or false"));
            return None;
        }
    };
    let int = |cx: &mut Ctx, key: &str, default: u64, max: u64| -> Option<u64> {
        match m.get_node(key).map(|n| (to_json(n).as_u64(), n)) {
            None => Some(default),
            Some((Some(v), _)) if v <= max => Some(v),
            Some((_, n)) => {
                cx.err(cx.loc(n), format!("{what}: `{key}` must be an integer from 0 to {max}"));
                None
            }
        }
    };
    let levels = int(cx, "levels", 3, 20)? as u32;
    let max_points = int(cx, "max_points", ((n as u64 - 1) << levels) + 1, 100_000)? as usize;
    if max_points < n {
        cx.err(
            cx.loc(m.get_node("max_points").unwrap()),
            format!("{what}: `max_points` is below the {n} initial points"),
        );
        return None;
    }
    let axis = AdaptiveAxis { param: param.to_string(), log, from, to, initial: n, y, log_y, tol, levels, max_points };
    Some((values, Some(axis)))
}

fn sweep_values_plain<'a>(cx: &mut Ctx, stage: &str, param: &str, node: &'a Node) -> Option<Vec<(f64, &'a Node)>> {
    match node {
        Node::Sequence(seq) => {
            if seq.is_empty() {
                cx.err(cx.loc(node), format!("stage `{stage}`: parameter `{param}`: an empty sweep"));
                return None;
            }
            let vals: Vec<_> =
                seq.iter().map(|n| number(cx, stage, param, n, "each sweep value").map(|x| (x, n))).collect();
            vals.into_iter().collect()
        }
        Node::Mapping(map) if map.len() == 1 => {
            let (key, body) = map.iter().next().unwrap();
            let form = key.as_str();
            if form == "shown" {
                let (log, a, b, n) = shown_grid(cx, stage, param, body)?;
                return Some((0..n).map(|i| (spaced(log, a, b, n, i), node)).collect());
            }
            if form != "logspace" && form != "linspace" {
                cx.err(
                    span_location(cx.file, key.span()),
                    format!("stage `{stage}`: parameter `{param}`: unknown sweep `{form}` (expected a list, `logspace`, `linspace`, `shown` or `adaptive`)"),
                );
                return None;
            }
            let (a, b, n) = grid(cx, stage, param, form, body)?;
            Some((0..n).map(|i| (spaced(form == "logspace", a, b, n, i), node)).collect())
        }
        _ => number(cx, stage, param, node, "a swept value").map(|x| vec![(x, node)]),
    }
}

fn number(cx: &mut Ctx, stage: &str, param: &str, n: &Node, what: &str) -> Option<f64> {
    match to_json(n).as_f64() {
        Some(x) => Some(x),
        None => {
            cx.err(cx.loc(n), format!("stage `{stage}`: parameter `{param}`: {what} must be a number"));
            None
        }
    }
}

/// `[from, to, n]` of a `logspace` or `linspace`.
fn grid(cx: &mut Ctx, stage: &str, param: &str, form: &str, body: &Node) -> Option<(f64, f64, usize)> {
    let items = match body {
        Node::Sequence(s) if s.len() == 3 => s,
        _ => {
            cx.err(cx.loc(body), format!("stage `{stage}`: parameter `{param}`: `{form}` takes [from, to, n]"));
            return None;
        }
    };
    let a = number(cx, stage, param, &items[0], "`from`")?;
    let b = number(cx, stage, param, &items[1], "`to`")?;
    let n = match to_json(&items[2]).as_u64() {
        Some(n) if (1..=100_000).contains(&n) => n as usize,
        _ => {
            cx.err(
                cx.loc(&items[2]),
                format!("stage `{stage}`: parameter `{param}`: `n` must be an integer from 1 to 100000"),
            );
            return None;
        }
    };
    if form == "logspace" && (a.abs() > 300.0 || b.abs() > 300.0) {
        cx.err(
            cx.loc(body),
            format!("stage `{stage}`: parameter `{param}`: logspace takes decimal exponents ([-3, 3, 61] is 1e-3..1e3), got {a} and {b}"),
        );
        return None;
    }
    Some((a, b, n))
}

/// `shown: n`: n points over the union of the ranges shown of this stage's `param`, in
/// log10 when they are shown on log axes: (log, from, to, n) in the sampling coordinate.
fn shown_grid(cx: &mut Ctx, stage: &str, param: &str, body: &Node) -> Option<(bool, f64, f64, usize)> {
    let what = format!("stage `{stage}`: parameter `{param}`: `shown`");
    let n = match to_json(body).as_u64() {
        Some(n) if (2..=100_000).contains(&n) => n as usize,
        _ => {
            cx.err(cx.loc(body), format!("{what} takes the number of points, an integer from 2 to 100000"));
            return None;
        }
    };
    let ranges = cx.shown.get(&(stage.to_string(), param.to_string())).cloned().unwrap_or_default();
    let Some(first) = ranges.first() else {
        cx.err(
            cx.loc(body),
            format!(
                "{what}: no stage declares the range it shows of `{param}` from `{stage}` (give a figure that plots `{param}` of `{stage}` on its x axis an `x_range`)"
            ),
        );
        return None;
    };
    let log = first.range.log;
    if let Some(other) = ranges.iter().find(|r| r.range.log != log) {
        let (l, s) = if log { (first, other) } else { (other, first) };
        cx.err(
            cx.loc(body),
            format!(
                "{what}: `{}` shows it on a log axis and `{}` on a linear one; sample it with `logspace` or `linspace`",
                l.by, s.by
            ),
        );
        return None;
    }
    cx.ranges_used.extend(ranges.iter().map(|r| r.by.clone()));
    let coord = |x: f64| if log { x.log10() } else { x };
    let from = ranges.iter().map(|r| coord(r.range.from)).fold(f64::INFINITY, f64::min);
    let to = ranges.iter().map(|r| coord(r.range.to)).fold(f64::NEG_INFINITY, f64::max);
    if !(from.is_finite() && to.is_finite() && to > from) {
        cx.err(cx.loc(body), format!("{what}: the ranges shown do not give an interval ({from} to {to})"));
        return None;
    }
    Some((log, from, to, n))
}

/// The ranges every stage of the file shows, by (stage shown, column). Stages whose
/// parameters do not parse declare none here (their errors come from `check`).
fn ranges_shown(
    file: &str,
    seq: &marked_yaml::types::MarkedSequenceNode,
    registry: &Registry,
) -> BTreeMap<(String, String), Vec<Shown>> {
    let mut shown: BTreeMap<(String, String), Vec<Shown>> = BTreeMap::new();
    for node in seq.iter() {
        let Some(map) = node.as_mapping() else { continue };
        let (Some(name), Some(kind)) = (map.get_scalar("name"), map.get_scalar("kind")) else { continue };
        let Some(kind) = registry.get(kind.as_str()) else { continue };
        let Some(params) = map.get_mapping("params") else { continue };
        for range in kind.shown_ranges(&to_json(&Node::Mapping(params.clone()))) {
            let location = params
                .keys()
                .find(|k| k.as_str() == range.path)
                .map_or_else(|| mapping_location(file, params), |k| span_location(file, k.span()));
            shown.entry((range.stage.clone(), range.column.clone())).or_default().push(Shown {
                by: name.as_str().to_string(),
                range,
                location,
            });
        }
    }
    shown
}

/// Warns of sweeps that leave part of a range shown without points, and of points
/// computed outside every range shown when every stage that reads the stage shows the
/// swept column over a declared range.
fn check_ranges_shown(cx: &mut Ctx, stages: &[ParsedStage]) {
    let shown = std::mem::take(&mut cx.shown);
    for ((stage_name, column), ranges) in &shown {
        let Some(stage) = stages.iter().find(|s| &s.stage.name == stage_name) else { continue };
        let values: BTreeSet<u64> = stage
            .stage
            .points
            .iter()
            .filter_map(|p| p.params.get(column).and_then(Value::as_f64))
            .map(f64::to_bits)
            .collect();
        if values.len() < 2 {
            continue; // not swept: a single value is a point in the figure, not a curve
        }
        let values: Vec<f64> = values.into_iter().map(f64::from_bits).collect();
        let (lo, hi) = (
            values.iter().copied().fold(f64::INFINITY, f64::min),
            values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
        for r in ranges {
            let (from, to) = (r.range.from, r.range.to);
            if (lo > from && !close(lo, from)) || (hi < to && !close(hi, to)) {
                cx.warnings.push(Warning(Diagnostic {
                    location: r.location.clone(),
                    message: format!(
                        "`{}` shows `{column}` of `{stage_name}` from {} to {} (its `{}`), but `{stage_name}` samples it from {} to {}: part of the range has no points",
                        r.by,
                        format_number(from),
                        format_number(to),
                        r.range.path,
                        format_number(lo),
                        format_number(hi)
                    ),
                }));
            }
        }
        let readers: Vec<&str> = stages
            .iter()
            .filter(|s| s.stage.needs.iter().any(|n| n == stage_name))
            .map(|s| s.stage.name.as_str())
            .collect();
        if readers.is_empty() || !readers.iter().all(|reader| ranges.iter().any(|r| r.by == *reader)) {
            continue; // some reader may use points outside the ranges shown
        }
        let inside = |x: f64| {
            ranges
                .iter()
                .any(|r| (x >= r.range.from || close(x, r.range.from)) && (x <= r.range.to || close(x, r.range.to)))
        };
        let outside: Vec<f64> = values.iter().copied().filter(|&x| !inside(x)).collect();
        if !outside.is_empty() {
            let by: BTreeSet<&str> = ranges.iter().map(|r| r.by.as_str()).collect();
            cx.warnings.push(Warning(Diagnostic {
                location: stage.stage.location.clone(),
                message: format!(
                    "stage `{stage_name}` computes {} of its {} values of `{column}` ({}) outside the ranges that the stages reading it show ({}): nothing shows them",
                    outside.len(),
                    values.len(),
                    outside.iter().take(4).map(|&x| format_number(x)).collect::<Vec<_>>().join(", ")
                        + if outside.len() > 4 { ", ..." } else { "" },
                    by.into_iter().collect::<Vec<_>>().join(", ")
                ),
            }));
        }
    }
    cx.shown = shown;
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

fn expand_points<'a>(
    cx: &mut Ctx,
    stage: &str,
    params: &'a MarkedMappingNode,
    sweepable: &[&str],
) -> Option<(Vec<RawPoint<'a>>, Option<AdaptiveAxis>)> {
    let mut fixed = Map::new();
    let mut axes: Vec<(String, Vec<(f64, &'a Node)>)> = Vec::new();
    let mut adaptive: Option<AdaptiveAxis> = None;
    let mut ok = true;
    for (key, node) in params.iter() {
        let name = key.as_str().to_string();
        if sweepable.contains(&name.as_str()) {
            match sweep_values(cx, stage, &name, node) {
                Some((v, None)) if v.len() == 1 && !matches!(node, Node::Sequence(_)) => {
                    fixed.insert(name, json_number(v[0].0));
                }
                Some((v, a)) => {
                    if let Some(a) = a {
                        if let Some(prev) = &adaptive {
                            cx.err(
                                cx.loc(node),
                                format!(
                                    "stage `{stage}`: parameter `{name}`: only one parameter may be adaptive (`{}` is)",
                                    prev.param
                                ),
                            );
                            ok = false;
                        }
                        adaptive = Some(a);
                    }
                    axes.push((name, v));
                }
                None => ok = false,
            }
        } else {
            fixed.insert(name, to_json(node));
        }
    }
    if !ok {
        return None;
    }
    let total = axes.iter().try_fold(1usize, |t, (_, v)| t.checked_mul(v.len())).unwrap_or(usize::MAX);
    if total > 1_000_000 {
        cx.err(
            mapping_location(cx.file, params),
            format!("stage `{stage}`: the sweep has {total} points (more than a million)"),
        );
        return None;
    }
    let mut points = Vec::with_capacity(total);
    for idx in 0..total {
        let mut value = fixed.clone();
        let mut labels = Vec::new();
        let mut swept_nodes = BTreeMap::new();
        let mut rem = idx;
        // The last axis varies fastest.
        let mut picks = vec![0; axes.len()];
        for (a, (_, vals)) in axes.iter().enumerate().rev() {
            picks[a] = rem % vals.len();
            rem /= vals.len();
        }
        for ((name, vals), &pick) in axes.iter().zip(&picks) {
            let (x, node) = vals[pick];
            value.insert(name.clone(), json_number(x));
            labels.push(label_token(name, x));
            swept_nodes.insert(name.clone(), node);
        }
        points.push(RawPoint { value: Value::Object(value), label: labels.join(" "), swept_nodes });
    }
    Some((points, adaptive))
}

fn json_number(x: f64) -> Value {
    if x.fract() == 0.0 && x.abs() < 9.0e15 {
        Value::Number((x as i64).into())
    } else {
        Number::from_f64(x).map_or(Value::Null, Value::Number)
    }
}

/// The location of the deepest node on `err.path` (a swept parameter's node for this point).
fn locate(cx: &Ctx, params: &MarkedMappingNode, swept: &BTreeMap<String, &Node>, err: &FieldError) -> Location {
    let segments = split_path(&err.path);
    let params_node_loc = mapping_location(cx.file, params);
    let Some((first, rest)) = segments.split_first() else {
        return params_node_loc;
    };
    let mut node: &Node = match swept.get(first.as_str()) {
        Some(n) => n,
        None => match params.get_node(first) {
            Some(n) => n,
            None => {
                // An unknown field is reported at its key; a missing one at the params mapping.
                return params
                    .keys()
                    .find(|k| k.as_str() == first)
                    .map_or(params_node_loc, |k| span_location(cx.file, k.span()));
            }
        },
    };
    let unknown_field = err.message.starts_with("unknown field");
    if rest.is_empty() && unknown_field {
        if let Some(k) = params.keys().find(|k| k.as_str() == first) {
            return span_location(cx.file, k.span());
        }
    }
    for (i, seg) in rest.iter().enumerate() {
        if let (Node::Mapping(m), true) = (node, unknown_field && i + 1 == rest.len()) {
            if let Some(k) = m.keys().find(|k| k.as_str() == seg) {
                return span_location(cx.file, k.span());
            }
        }
        let next = match (node, seg.parse::<usize>()) {
            (Node::Sequence(s), Ok(i)) => s.get(i),
            (Node::Mapping(m), _) => m.get_node(seg),
            _ => None,
        };
        match next {
            Some(n) => node = n,
            None => break,
        }
    }
    cx.loc(node)
}

/// `layers[0].from` -> [layers, 0, from].
fn split_path(path: &str) -> Vec<String> {
    path.split(['.', '[']).filter(|s| !s.is_empty()).map(|s| s.trim_end_matches(']').to_string()).collect()
}

fn check_graph(cx: &mut Ctx, stages: &[ParsedStage]) {
    let mut index = BTreeMap::new();
    for (i, s) in stages.iter().enumerate() {
        if let Some(&j) = index.get(s.stage.name.as_str()) {
            let first: &ParsedStage = &stages[j];
            cx.err(
                s.stage.location.clone(),
                format!(
                    "duplicate stage name `{}` (first defined at line {})",
                    s.stage.name, first.stage.location.line
                ),
            );
        } else {
            index.insert(s.stage.name.as_str(), i);
        }
    }
    let mut graph = petgraph::graphmap::DiGraphMap::<usize, ()>::new();
    for i in 0..stages.len() {
        graph.add_node(i);
    }
    for (i, s) in stages.iter().enumerate() {
        for (need, loc) in s.stage.needs.iter().zip(&s.need_locations) {
            match index.get(need.as_str()) {
                Some(&j) => {
                    graph.add_edge(j, i, ());
                }
                None => {
                    let names: Vec<&str> = index.keys().copied().collect();
                    let hint = suggestion(need, &names).map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default();
                    cx.err(loc.clone(), format!("stage `{}` needs `{need}`, which names no stage{hint}", s.stage.name));
                }
            }
        }
    }
    for cycle in super::graph::cycles(&graph) {
        let names: Vec<&str> = cycle.iter().map(|&i| stages[i].stage.name.as_str()).collect();
        let first = cycle[0];
        cx.err(
            stages[first].stage.location.clone(),
            format!("the stages form a cycle: {} -> {}", names.join(" -> "), names[0]),
        );
    }
}
