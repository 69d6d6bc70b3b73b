//! Sweeps: a swept parameter's values (a list, `logspace`, `linspace`, `shown`, `adaptive`),
//! the Cartesian product of a stage's axes as its points, and the checks of sweeps against
//! the ranges that figures show (see [`crate::parse`]).

use super::yaml::{check_keys, mapping_location, span_location, to_json, Ctx, Shown};
use crate::kind::Registry;
use crate::spec::AdaptiveAxis;
use crate::spec::{label_token, spaced, Diagnostic, Stage, Warning};
use crate::table::format_number;
use marked_yaml::types::{MarkedMappingNode, Node};
use serde_json::{Map, Number, Value};
use std::collections::{BTreeMap, BTreeSet};

pub(super) struct RawPoint<'a> {
    pub value: Value,
    pub label: String,
    pub swept_nodes: BTreeMap<String, &'a Node>,
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
pub(super) fn ranges_shown(
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
pub(super) fn check_ranges_shown(cx: &mut Ctx, stages: &[Stage]) {
    let shown = std::mem::take(&mut cx.shown);
    for ((stage_name, column), ranges) in &shown {
        let Some(stage) = stages.iter().find(|s| &s.name == stage_name) else { continue };
        let values: BTreeSet<u64> = stage
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
        let readers: Vec<&str> =
            stages.iter().filter(|s| s.needs.iter().any(|n| n == stage_name)).map(|s| s.name.as_str()).collect();
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
                location: stage.location.clone(),
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

pub(super) fn expand_points<'a>(
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
