//! A stage's `needs`, read from its mapping, and the graph they make: every name a stage,
//! no name twice, no cycle, and the entries matched row by row on parameters both stages
//! have.

use super::yaml::{check_keys, mapping_location, Ctx};
use super::{suggestion, ParsedStage};
use crate::spec::{Diagnostic, Location, MatchedNeed, Warning};
use marked_yaml::types::{MarkedMappingNode, Node};
use std::collections::{BTreeMap, BTreeSet};

/// A stage's `needs`: the stage names (a matched entry's too), where each is, and the
/// entries matched row by row with where their `match` is.
pub(super) struct StageNeeds {
    pub(super) needs: Vec<String>,
    pub(super) need_locations: Vec<Location>,
    pub(super) matched: Vec<MatchedNeed>,
    pub(super) match_locations: Vec<Location>,
}

/// Reads the `needs` of stage `name` from its mapping `map`, reporting malformed entries
/// and names given twice.
pub(super) fn parse_needs(cx: &mut Ctx, name: &str, map: &MarkedMappingNode) -> StageNeeds {
    let mut needs = Vec::new();
    let mut need_locations = Vec::new();
    let mut matched = Vec::new();
    let mut match_locations = Vec::new();
    match map.get_node("needs") {
        None => {}
        Some(Node::Sequence(seq)) => {
            for n in seq.iter() {
                match n {
                    Node::Scalar(s) => {
                        needs.push(s.as_str().to_string());
                        need_locations.push(cx.loc(n));
                    }
                    Node::Mapping(m) => {
                        if let Some((need, location)) = parse_matched_need(cx, name, m) {
                            needs.push(need.stage.clone());
                            need_locations.push(cx.loc(n));
                            matched.push(need);
                            match_locations.push(location);
                        }
                    }
                    _ => cx.err(
                        cx.loc(n),
                        format!("stage `{name}`: each entry of `needs` must be a stage name or `{{stage: NAME, match: [PARAM, ...]}}`"),
                    ),
                }
            }
        }
        Some(n) => cx.err(cx.loc(n), format!("stage `{name}`: `needs` must be a list of stage names")),
    }
    for (i, n) in needs.iter().enumerate() {
        if needs[..i].contains(n) {
            cx.err(need_locations[i].clone(), format!("stage `{name}`: `needs` names `{n}` twice"));
        }
    }
    StageNeeds { needs, need_locations, matched, match_locations }
}

/// A `needs` entry read row by row: `{stage: NAME, match: [PARAM, ...]}`, and where its
/// `match` is.
fn parse_matched_need(cx: &mut Ctx, name: &str, m: &MarkedMappingNode) -> Option<(MatchedNeed, Location)> {
    check_keys(cx, m, &["stage", "match"], "a `needs` entry");
    let stage = match m.get_node("stage") {
        Some(Node::Scalar(s)) => s.as_str().to_string(),
        Some(n) => {
            cx.err(cx.loc(n), format!("stage `{name}`: `stage` of a `needs` entry must be a stage name"));
            return None;
        }
        None => {
            cx.err(mapping_location(cx.file, m), format!("stage `{name}`: a `needs` entry with `match` needs `stage`"));
            return None;
        }
    };
    let on: Vec<String> = match m.get_node("match") {
        Some(Node::Sequence(seq)) if !seq.is_empty() && seq.iter().all(|p| p.as_scalar().is_some()) => {
            seq.iter().map(|p| p.as_scalar().unwrap().as_str().to_string()).collect()
        }
        Some(n) => {
            cx.err(
                cx.loc(n),
                format!("stage `{name}`: `match` of need `{stage}` must be a non-empty list of parameter names"),
            );
            return None;
        }
        None => {
            cx.err(
                mapping_location(cx.file, m),
                format!("stage `{name}`: need `{stage}` as a mapping needs `match` (else name the stage alone)"),
            );
            return None;
        }
    };
    let location = m.get_node("match").map_or_else(|| mapping_location(cx.file, m), |n| cx.loc(n));
    Some((MatchedNeed { stage, on }, location))
}

/// The stages' graph checked: names unique, every need a stage (with the nearest name
/// when not), no cycle, and the matched needs' parameters on both sides.
pub(super) fn check_graph(cx: &mut Ctx, stages: &[ParsedStage], declared: &BTreeSet<String>) {
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
                // Declared, but invalid: its own errors say why.
                None if declared.contains(need) => {}
                None => {
                    let names: Vec<&str> = index.keys().copied().collect();
                    let hint = suggestion(need, &names).map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default();
                    cx.err(loc.clone(), format!("stage `{}` needs `{need}`, which names no stage{hint}", s.stage.name));
                }
            }
        }
    }
    // A need read row by row matches on parameters that both stages have; a point that
    // matches no point of it gets no rows (a warning: probably not what was meant).
    for s in stages {
        for (m, loc) in s.stage.matched.iter().zip(&s.match_locations) {
            let Some(&j) = index.get(m.stage.as_str()) else { continue };
            let upstream = &stages[j].stage;
            let mut missing = false;
            for p in &m.on {
                for (st, what) in [(&s.stage, "this stage"), (upstream, "the stage it needs")] {
                    if st.points.iter().any(|pt| pt.params.get(p).is_none_or(|v| v.is_null())) {
                        missing = true;
                        cx.err(
                            loc.clone(),
                            format!(
                                "stage `{}`: `match` names `{p}`, which is not a parameter of every point of {what} (`{}`)",
                                s.stage.name, st.name
                            ),
                        );
                    }
                }
            }
            if missing {
                continue;
            }
            let lonely: Vec<&str> = s
                .stage
                .points
                .iter()
                .filter(|pt| !upstream.points.iter().any(|up| m.matches(&up.params, &pt.params)))
                .map(|pt| if pt.label.is_empty() { "(the point)" } else { pt.label.as_str() })
                .collect();
            if !lonely.is_empty() && upstream.adaptive.is_none() {
                cx.warnings.push(Warning(Diagnostic {
                    location: loc.clone(),
                    message: format!(
                        "stage `{}`: {} of its {} points match no point of `{}` on {} (they get no rows of it), e.g. {}",
                        s.stage.name,
                        lonely.len(),
                        s.stage.points.len(),
                        m.stage,
                        m.on.join(", "),
                        lonely[0]
                    ),
                }));
            }
        }
    }
    for cycle in crate::graph::cycles(&graph) {
        let names: Vec<&str> = cycle.iter().map(|&i| stages[i].stage.name.as_str()).collect();
        let first = cycle[0];
        cx.err(
            stages[first].stage.location.clone(),
            format!("the stages form a cycle: {} -> {}", names.join(" -> "), names[0]),
        );
    }
}
