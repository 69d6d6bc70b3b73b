//! The stage graph: cycles, topological order, the stages a target needs, Graphviz output.

use super::spec::Pipeline;
use petgraph::graphmap::DiGraphMap;
use std::collections::{BTreeMap, BTreeSet};

/// Every cycle of the graph (one per strongly connected component), as a list of nodes in
/// the order of the cycle.
pub fn cycles(graph: &DiGraphMap<usize, ()>) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    for scc in petgraph::algo::tarjan_scc(graph) {
        let is_cycle = scc.len() > 1 || graph.contains_edge(scc[0], scc[0]);
        if !is_cycle {
            continue;
        }
        let members: BTreeSet<usize> = scc.iter().copied().collect();
        let start = *members.iter().next().unwrap();
        // Walk within the component until a node repeats: that closes a cycle.
        let mut path = vec![start];
        let mut node = start;
        loop {
            let next = graph
                .neighbors(node)
                .filter(|n| members.contains(n))
                .min()
                .expect("a node of a cycle has a successor in it");
            if let Some(pos) = path.iter().position(|&p| p == next) {
                out.push(path[pos..].to_vec());
                break;
            }
            path.push(next);
            node = next;
        }
    }
    out
}

fn stage_graph(p: &Pipeline) -> DiGraphMap<usize, ()> {
    let mut g = DiGraphMap::new();
    for i in 0..p.stages.len() {
        g.add_node(i);
    }
    for (i, s) in p.stages.iter().enumerate() {
        for n in &s.needs {
            let j = p.stages.iter().position(|t| &t.name == n).expect("validated needs");
            g.add_edge(j, i, ());
        }
    }
    g
}

/// Stage indices in an order where every stage comes after the stages it needs
/// (file order among independent stages).
pub fn topological_order(p: &Pipeline) -> Vec<usize> {
    let g = stage_graph(p);
    let mut done = vec![false; p.stages.len()];
    let mut order = Vec::new();
    while order.len() < p.stages.len() {
        let before = order.len();
        for i in 0..p.stages.len() {
            if !done[i] && g.neighbors_directed(i, petgraph::Incoming).all(|j| done[j]) {
                done[i] = true;
                order.push(i);
            }
        }
        assert!(order.len() > before, "validated pipelines have no cycle");
    }
    order
}

/// The targets and every stage they need, directly or not.
pub fn with_ancestors(p: &Pipeline, targets: &[usize]) -> BTreeSet<usize> {
    let g = stage_graph(p);
    let mut seen = BTreeSet::new();
    let mut stack: Vec<usize> = targets.to_vec();
    while let Some(i) = stack.pop() {
        if seen.insert(i) {
            stack.extend(g.neighbors_directed(i, petgraph::Incoming));
        }
    }
    seen
}

/// The pipeline as a Graphviz digraph: one node per stage (kind and number of points), an
/// edge per need (labelled `by PARAM, ...` when read row by row), and a dashed one from a
/// figure to each sweep that samples its range.
pub fn to_dot(p: &Pipeline) -> String {
    to_dot_with(p, None, &BTreeMap::new())
}

/// The state of a stage's tasks against the cache, for colouring the graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StageStatus {
    /// Every task is in the cache.
    Cached,
    /// Some task would run (new, changed, or its inputs are not computed yet).
    Stale,
    /// Some task failed in the last attempt.
    Failed,
}

/// `to_dot` restricted to the stages `only` (all when None), each node filled by its status
/// (green cached, orange stale, red failed) when `status` gives one.
pub fn to_dot_with(p: &Pipeline, only: Option<&BTreeSet<usize>>, status: &BTreeMap<String, StageStatus>) -> String {
    let shown = |i: usize| only.is_none_or(|o| o.contains(&i));
    let mut s = String::from("digraph pipeline {\n  rankdir=LR;\n  node [shape=box, fontname=\"Helvetica\"];\n");
    for (_, st) in p.stages.iter().enumerate().filter(|(i, _)| shown(*i)) {
        let mut style: Vec<&str> = Vec::new();
        if st.kind.starts_with("figure") {
            style.push("rounded");
        }
        let fill = match status.get(&st.name) {
            Some(StageStatus::Cached) => Some("#d5f0d5"),
            Some(StageStatus::Stale) => Some("#fde2b5"),
            Some(StageStatus::Failed) => Some("#f6c6c6"),
            None => None,
        };
        if fill.is_some() {
            style.push("filled");
        }
        let attrs = format!(
            "{}{}",
            if style.is_empty() { String::new() } else { format!(", style=\"{}\"", style.join(",")) },
            fill.map_or(String::new(), |c| format!(", fillcolor=\"{c}\""))
        );
        s.push_str(&format!(
            "  \"{}\" [label=\"{}\\n{} ({} point{})\"{attrs}];\n",
            st.name,
            st.name,
            st.kind,
            st.points.len(),
            if st.points.len() == 1 { "" } else { "s" }
        ));
    }
    let index: BTreeMap<&str, usize> = p.stages.iter().enumerate().map(|(i, st)| (st.name.as_str(), i)).collect();
    let visible = |n: &str| index.get(n).is_some_and(|&i| shown(i));
    for st in p.stages.iter().filter(|st| visible(&st.name)) {
        for n in st.needs.iter().filter(|n| visible(n)) {
            // A need read row by row is labelled with the parameters it matches on.
            let label = st.matched(n).map_or(String::new(), |m| format!(" [label=\"by {}\"]", m.on.join(", ")));
            s.push_str(&format!("  \"{n}\" -> \"{}\"{label};\n", st.name));
        }
    }
    // A figure whose declared range fixes a sweep's points: dashed, against the data flow.
    for st in p.stages.iter().filter(|st| visible(&st.name)) {
        for f in st.ranges_from.iter().filter(|f| visible(f)) {
            s.push_str(&format!("  \"{f}\" -> \"{}\" [style=dashed, constraint=false, label=\"range\"];\n", st.name));
        }
    }
    s.push_str("}\n");
    s
}
