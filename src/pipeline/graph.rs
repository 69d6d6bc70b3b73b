//! The stage graph: cycles, topological order, the stages a target needs, Graphviz output.

use super::spec::Pipeline;
use petgraph::graphmap::DiGraphMap;
use std::collections::BTreeSet;

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
/// edge per need, and a dashed one from a figure to each sweep that samples its range.
pub fn to_dot(p: &Pipeline) -> String {
    let mut s = String::from("digraph pipeline {\n  rankdir=LR;\n  node [shape=box, fontname=\"Helvetica\"];\n");
    for st in &p.stages {
        let shape = if st.kind.starts_with("figure") { ", style=rounded" } else { "" };
        s.push_str(&format!(
            "  \"{}\" [label=\"{}\\n{} ({} point{})\"{shape}];\n",
            st.name,
            st.name,
            st.kind,
            st.points.len(),
            if st.points.len() == 1 { "" } else { "s" }
        ));
    }
    for st in &p.stages {
        for n in &st.needs {
            s.push_str(&format!("  \"{n}\" -> \"{}\";\n", st.name));
        }
    }
    // A figure whose declared range fixes a sweep's points: dashed, against the data flow.
    for st in &p.stages {
        for f in &st.ranges_from {
            s.push_str(&format!("  \"{f}\" -> \"{}\" [style=dashed, constraint=false, label=\"range\"];\n", st.name));
        }
    }
    s.push_str("}\n");
    s
}
