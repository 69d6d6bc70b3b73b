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

mod loader;
mod needs;
mod sweep;
mod yaml;

pub use yaml::to_json;

use crate::kind::{ColumnRead, FieldError, Registry};
use crate::spec::{Diagnostic, InvalidPipeline, Location, Override, Pipeline, Point, Stage};
use marked_yaml::types::{MarkedMappingNode, MarkedScalarNode, Node};
use needs::{check_graph, parse_needs, StageNeeds};
use std::collections::{BTreeMap, BTreeSet};
use sweep::{check_ranges_shown, expand_points, ranges_shown};
use yaml::{check_keys, mapping_location, marker_location, span_location, Ctx};

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
    let bytes = crate::cache::read_regular(path).map_err(|e| {
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

fn load_error(file: &str, e: loader::LoadError) -> Diagnostic {
    let (m, message) = e.located();
    Diagnostic { location: marker_location(file, &m), message }
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
        let value = match loader::parse(&format!("v: {}", o.value)) {
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
    // Anchors and aliases resolved; a quoted scalar stays text (`A_max: "5.0"` is a string,
    // as for the JSON Schema).
    let mut root = loader::parse(text).map_err(|e| InvalidPipeline(vec![load_error(file, e)]))?;
    let errors = apply_overrides(file, &mut root, overrides);
    if !errors.is_empty() {
        return Err(InvalidPipeline(errors));
    }
    let mut cx = Ctx {
        file,
        overrides,
        errors: Vec::new(),
        warnings: Vec::new(),
        shown: BTreeMap::new(),
        ranges_used: BTreeSet::new(),
    };
    let root_map = root.as_mapping().expect("marked_yaml guarantees a top-level mapping");
    check_keys(&mut cx, root_map, &["stages", "description"], "the pipeline");
    let description = root_map.get_scalar("description").map(|s| s.as_str().to_string()).unwrap_or_default();
    let mut stages = Vec::new();
    let mut declared = BTreeSet::new();
    match root_map.get_node("stages") {
        None => cx.err(cx.loc(&root), "missing `stages`: a pipeline is a list of stages"),
        Some(Node::Sequence(seq)) => {
            cx.shown = ranges_shown(file, seq, registry);
            for node in seq.iter() {
                if let Some(s) = parse_stage(&mut cx, node, registry) {
                    stages.push(s);
                }
            }
            // Every stage the file declares, valid or not: a need of one that failed is not
            // an error of its own (its errors are reported), so one mistake gives one error.
            declared =
                seq.iter().filter_map(|n| n.as_mapping()?.get_scalar("name").map(|s| s.as_str().to_string())).collect();
        }
        Some(other) => cx.err(cx.loc(other), "`stages` must be a list of stages"),
    }
    check_graph(&mut cx, &stages, &declared);
    check_columns_read(&mut cx, &stages, registry);
    if cx.errors.is_empty() {
        let stages: Vec<Stage> = stages.into_iter().map(|s| s.stage).collect();
        check_ranges_shown(&mut cx, &stages);
        cx.warnings.sort_by_key(|w| (w.0.location.line, w.0.location.column));
        Ok(Pipeline {
            file: file.to_string(),
            description,
            stages,
            warnings: cx.warnings,
            overrides: overrides.iter().map(|o| o.to_string()).collect(),
        })
    } else {
        cx.errors.sort_by_key(|d| (d.location.line, d.location.column));
        Err(InvalidPipeline(cx.errors))
    }
}

struct ParsedStage {
    stage: Stage,
    need_locations: Vec<Location>,
    /// Where the `match` of each of `stage.matched` is.
    match_locations: Vec<Location>,
    /// The columns of other stages this one reads, and where each is named.
    column_reads: Vec<(ColumnRead, Location)>,
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
    let StageNeeds { needs, need_locations, matched, match_locations } = parse_needs(cx, &name, map);
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
                    let location = override_location(cx, &name, &e.path)
                        .unwrap_or_else(|| locate(cx, params_map, &p.swept_nodes, &e));
                    let point =
                        if p.label.is_empty() { String::new() } else { format!(" (at sweep point {})", p.label) };
                    cx.err(location, format!("stage `{name}` ({kind_name}){point}: {}", describe(&e)));
                }
                // One point's structural errors repeat at every point: report them once.
                return None;
            }
        }
    }
    let reads: BTreeSet<ColumnRead> = checked.iter().flat_map(|p| kind.read_columns(&p.params)).collect();
    let column_reads = reads
        .into_iter()
        .map(|r| {
            let location = locate(cx, params_map, &BTreeMap::new(), &FieldError::new(&r.path, ""));
            (r, location)
        })
        .collect();
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
            matched,
            points: checked,
            adaptive,
            ranges_from,
            publish,
            time_limit_s,
            location: mapping_location(cx.file, map),
        },
        need_locations,
        match_locations,
        column_reads,
    })
}

/// Every column a stage reads from another (`Kind::read_columns`) must be one that the other
/// stage's kind declares, unless its table is open (`Kind::OPEN_COLUMNS`): a figure layer or
/// a claim naming a column that does not exist fails here, before any work, at the line
/// that names it. A read without a stage (a title's placeholder) must be a column of one of
/// the stages the reader needs.
fn check_columns_read(cx: &mut Ctx, stages: &[ParsedStage], registry: &Registry) {
    let kind_of = |name: &str| {
        let stage = stages.iter().find(|s| s.stage.name == name)?;
        registry.get(&stage.stage.kind).map(|k| (name.to_string(), stage.stage.kind.clone(), k))
    };
    for s in stages {
        for (read, location) in &s.column_reads {
            let candidates: Vec<&String> = match &read.stage {
                Some(stage) => vec![stage],
                None => s.stage.needs.iter().collect(),
            };
            let kinds: Vec<_> = candidates.iter().filter_map(|c| kind_of(c)).collect();
            let open = kinds.iter().any(|(_, _, k)| k.open_columns() || k.columns().is_empty());
            if kinds.is_empty() || open || kinds.iter().any(|(_, _, k)| k.columns().contains(&read.column.as_str())) {
                continue;
            }
            let mut declared: Vec<&str> = kinds.iter().flat_map(|(_, _, k)| k.columns().iter().copied()).collect();
            declared.sort_unstable();
            declared.dedup();
            let hint =
                suggestion(&read.column, &declared).map(|c| format!(" (did you mean `{c}`?)")).unwrap_or_default();
            let of = kinds.iter().map(|(n, k, _)| format!("`{n}` ({k})")).collect::<Vec<_>>().join(" or ");
            cx.err(
                location.clone(),
                format!(
                    "stage `{}`: `{}` reads column `{}`, which {of} does not have{hint}; its columns: {}",
                    s.stage.name,
                    read.path,
                    read.column,
                    declared.join(", ")
                ),
            );
        }
    }
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

/// The message for a command-line flag (`--target`, `--force`) naming a stage `name` that
/// `p` does not have: the nearest stage name if one is close, and where to see them all.
pub fn unknown_stage(flag: &str, name: &str, p: &Pipeline) -> String {
    let names: Vec<&str> = p.stages.iter().map(|s| s.name.as_str()).collect();
    // The stages whose names extend it (a figure's panels: fig4_6 -> fig4_6a, fig4_6b), else
    // the nearest name.
    let extending: Vec<String> =
        names.iter().filter(|n| n.starts_with(name)).take(4).map(|n| format!("`{n}`")).collect();
    let hint = if !extending.is_empty() {
        format!(" (did you mean {}?)", extending.join(" or "))
    } else {
        suggestion(name, &names).map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default()
    };
    format!(
        "{flag} {name}: no stage of that name in {}{hint}; `repro dag {}` shows its {} stages",
        p.file,
        p.file,
        names.len()
    )
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

/// Where an error of parameter `path` of stage `stage` is, when the command line set that
/// parameter (`-S stage.param=value`): on that argument, not in the file.
fn override_location(cx: &Ctx, stage: &str, path: &str) -> Option<Location> {
    let first = split_path(path).into_iter().next()?;
    let o = cx.overrides.iter().rev().find(|o| o.stage == stage && o.param == first)?;
    Some(Location { file: format!("{} (-S {o})", cx.file), line: 0, column: 0 })
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
