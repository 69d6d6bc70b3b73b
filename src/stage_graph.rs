//! The pipeline's stage graph as a reader follows it: one panel per chapter of the thesis,
//! a box per stage (a sweep is one box, its point count in it; the claim stages, which the
//! claims table lists, are left out), and an arrow per `needs`, drawn in a layered layout.
//!
//! A stage belongs to the first chapter, in the thesis' order, of the figures that read it
//! (directly or through other stages); one that no figure reads, to the further panel. A
//! panel's layers are the longest chains of its stages before each one, and the stages of a
//! layer are ordered by the mean place of their neighbours in the layers before and after
//! (the barycenter heuristic of Sugiyama's layered drawing, four sweeps each way), which
//! keeps most arrows short and uncrossed. A need on another chapter's stage is named in the
//! box's tooltip.

use pipeline::spec::{Pipeline, Stage};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// Sweeps of the barycenter ordering (down then up each).
const SWEEPS: usize = 4;

/// The panels' HTML: a heading and an SVG per chapter that has stages, in `order` (chapter
/// keys as `chapter_of_figure` gives them; the key `other` collects the rest), headed by
/// `heading`.
pub fn panels(
    p: &Pipeline,
    order: &[&str],
    chapter_of_figure: impl Fn(&Stage) -> String,
    heading: impl Fn(&str) -> &'static str,
) -> String {
    let shown: Vec<&Stage> = p.stages.iter().filter(|s| s.kind != "claim" && s.kind != "claims").collect();
    let chapter = chapters(&shown, order, chapter_of_figure);
    let mut h = String::new();
    let _ = writeln!(
        h,
        "<p>{} stages ({} figures; the {} claim stages are in the claims table), a panel per chapter: \
         each arrow goes from a stage to one that reads its table.</p>",
        shown.len(),
        shown.iter().filter(|s| s.kind == "figure").count(),
        p.stages.len() - shown.len()
    );
    for ch in order.iter().copied().chain(std::iter::once("other")) {
        let members: Vec<&Stage> = shown.iter().copied().filter(|s| chapter[s.name.as_str()] == ch).collect();
        if members.is_empty() {
            continue;
        }
        let _ = writeln!(h, "<h3 id=\"graph-{ch}\">{}</h3>", heading(ch));
        h.push_str(&panel(ch, &members, &chapter));
    }
    h
}

/// Each stage's chapter: the first in `order` among the figures that read it (itself, for a
/// figure), else `other`.
fn chapters<'a>(
    shown: &[&'a Stage],
    order: &[&str],
    chapter_of_figure: impl Fn(&Stage) -> String,
) -> BTreeMap<&'a str, String> {
    let rank = |c: &str| order.iter().position(|o| *o == c).unwrap_or(order.len());
    let mut readers: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for s in shown {
        for n in &s.needs {
            readers.entry(n.as_str()).or_default().push(s.name.as_str());
        }
    }
    let by_name: BTreeMap<&str, &Stage> = shown.iter().map(|s| (s.name.as_str(), *s)).collect();
    let mut out = BTreeMap::new();
    for s in shown {
        // The figures downstream of s (s itself if a figure), by a walk over its readers.
        let mut seen = BTreeSet::from([s.name.as_str()]);
        let mut stack = vec![s.name.as_str()];
        let mut best: Option<String> = None;
        while let Some(name) = stack.pop() {
            let stage = by_name[name];
            if stage.kind == "figure" {
                let c = chapter_of_figure(stage);
                if best.as_deref().is_none_or(|b| rank(&c) < rank(b)) {
                    best = Some(c);
                }
            }
            for r in readers.get(name).into_iter().flatten() {
                if seen.insert(r) {
                    stack.push(r);
                }
            }
        }
        let c = best.filter(|c| rank(c) < order.len()).unwrap_or_else(|| "other".into());
        out.insert(s.name.as_str(), c);
    }
    out
}

/// One chapter's panel: the layered drawing of `members` and the arrows between them.
fn panel(ch: &str, members: &[&Stage], chapter: &BTreeMap<&str, String>) -> String {
    let index: BTreeMap<&str, usize> = members.iter().enumerate().map(|(i, s)| (s.name.as_str(), i)).collect();
    let needs: Vec<Vec<usize>> =
        members.iter().map(|s| s.needs.iter().filter_map(|n| index.get(n.as_str()).copied()).collect()).collect();
    let layers = layered(&needs);
    let (row_h, box_h, gap) = (22.0, 16.0, 48.0);
    // Each layer as wide as its longest label (about 6 px a character at 10 px).
    let label =
        |s: &Stage| if s.points.len() > 1 { format!("{} ×{}", s.name, s.points.len()) } else { s.name.clone() };
    let widths: Vec<f64> = layers
        .iter()
        .map(|l| l.iter().map(|&i| label(members[i]).chars().count() as f64 * 6.0 + 10.0).fold(60.0, f64::max))
        .collect();
    let mut x = vec![10.0; layers.len()];
    for k in 1..layers.len() {
        x[k] = x[k - 1] + widths[k - 1] + gap;
    }
    let mut at = vec![(0.0, 0.0, 0.0); members.len()];
    for (k, layer) in layers.iter().enumerate() {
        for (row, &i) in layer.iter().enumerate() {
            at[i] = (x[k], 10.0 + row as f64 * row_h, widths[k]);
        }
    }
    let width = x.last().copied().unwrap_or(10.0) + widths.last().copied().unwrap_or(60.0) + 10.0;
    let height = 20.0 + layers.iter().map(Vec::len).max().unwrap_or(1) as f64 * row_h;
    let edges: usize = needs.iter().map(Vec::len).sum();
    let mut g = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"graph\" data-edges=\"{edges}\" width=\"{width:.0}\" \
         height=\"{height:.0}\" viewBox=\"0 0 {width:.0} {height:.0}\" font-size=\"10\">\n\
         <defs><marker id=\"arrow-{ch}\" viewBox=\"0 0 8 8\" refX=\"8\" refY=\"4\" markerWidth=\"7\" \
         markerHeight=\"7\" orient=\"auto\"><path d=\"M0,0 L8,4 L0,8 z\" fill=\"#555\"/></marker></defs>\n"
    );
    for (i, ns) in needs.iter().enumerate() {
        let (x1, y1, _) = at[i];
        for &j in ns {
            let (x0, y0, w0) = at[j];
            let (sx, sy, tx, ty) = (x0 + w0, y0 + box_h / 2.0, x1, y1 + box_h / 2.0);
            let bend = (tx - sx) / 2.0;
            let _ = writeln!(
                g,
                "<path class=\"edge\" d=\"M{sx:.1},{sy:.1} C{:.1},{sy:.1} {:.1},{ty:.1} {tx:.1},{ty:.1}\" \
                 fill=\"none\" stroke=\"#555\" stroke-width=\"1\" marker-end=\"url(#arrow-{ch})\"/>",
                sx + bend,
                tx - bend
            );
        }
    }
    for (i, s) in members.iter().enumerate() {
        let (bx, by, w) = at[i];
        let fill = if s.kind == "figure" { "#e8f0fb" } else { "#f3f3f3" };
        let elsewhere: Vec<String> = s
            .needs
            .iter()
            .filter(|n| !index.contains_key(n.as_str()))
            .map(|n| format!("{n} ({})", chapter.get(n.as_str()).map_or("?", |c| c.as_str())))
            .collect();
        let reads = if elsewhere.is_empty() { String::new() } else { format!("; reads {}", elsewhere.join(", ")) };
        let _ = writeln!(
            g,
            "<g><title>{} ({}, {} point{}){}</title><rect x=\"{bx:.1}\" y=\"{by:.1}\" width=\"{w:.1}\" \
             height=\"{box_h}\" rx=\"3\" fill=\"{fill}\" stroke=\"#888\" stroke-width=\"0.6\"/>\
             <text x=\"{:.1}\" y=\"{:.1}\">{}</text></g>",
            esc(&s.name),
            esc(&s.kind),
            s.points.len(),
            if s.points.len() == 1 { "" } else { "s" },
            esc(&reads),
            bx + 5.0,
            by + 12.0,
            esc(&label(s))
        );
    }
    g.push_str("</svg>\n");
    format!("<div style=\"overflow-x:auto\">{g}</div>\n")
}

/// The layers of a graph given as each node's predecessors (`needs`, acyclic): a node's
/// layer is the length of the longest chain before it; within a layer the nodes are
/// ordered by the barycenter of their neighbours' places, sweeping down (predecessors) and
/// up (successors) `SWEEPS` times, ties kept in the input order.
fn layered(needs: &[Vec<usize>]) -> Vec<Vec<usize>> {
    let n = needs.len();
    let mut depth = vec![0usize; n];
    // Longest path by relaxation (at most n rounds; the pipeline is acyclic).
    for _ in 0..n {
        let mut changed = false;
        for i in 0..n {
            let d = needs[i].iter().map(|&j| depth[j] + 1).max().unwrap_or(0);
            if d > depth[i] {
                depth[i] = d;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let mut layers = vec![Vec::new(); depth.iter().max().map_or(0, |d| d + 1)];
    for i in 0..n {
        layers[depth[i]].push(i);
    }
    let mut readers = vec![Vec::new(); n];
    for (i, ns) in needs.iter().enumerate() {
        for &j in ns {
            readers[j].push(i);
        }
    }
    let mut place = vec![0.0; n];
    let set_places = |layers: &[Vec<usize>], place: &mut Vec<f64>| {
        for layer in layers {
            for (row, &i) in layer.iter().enumerate() {
                place[i] = row as f64;
            }
        }
    };
    set_places(&layers, &mut place);
    let reorder = |layer: &mut Vec<usize>, neighbours: &[Vec<usize>], place: &[f64]| {
        let key = |i: usize| {
            let ns = &neighbours[i];
            if ns.is_empty() {
                place[i]
            } else {
                ns.iter().map(|&j| place[j]).sum::<f64>() / ns.len() as f64
            }
        };
        layer.sort_by(|&a, &b| key(a).total_cmp(&key(b)));
    };
    for _ in 0..SWEEPS {
        for k in 1..layers.len() {
            reorder(&mut layers[k], needs, &place);
            set_places(&layers, &mut place);
        }
        for k in (0..layers.len().saturating_sub(1)).rev() {
            reorder(&mut layers[k], &readers, &place);
            set_places(&layers, &mut place);
        }
    }
    layers
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The number of pairs of arrows between two layers that cross.
    fn crossings(layers: &[Vec<usize>], needs: &[Vec<usize>]) -> usize {
        let mut place = BTreeMap::new();
        for layer in layers {
            for (row, &i) in layer.iter().enumerate() {
                place.insert(i, row);
            }
        }
        let edges: Vec<(usize, usize)> =
            needs.iter().enumerate().flat_map(|(i, ns)| ns.iter().map(move |&j| (j, i))).collect();
        let mut count = 0;
        for (a, &(s1, t1)) in edges.iter().enumerate() {
            for &(s2, t2) in &edges[a + 1..] {
                let same_layers = layers.iter().position(|l| l.contains(&s1))
                    == layers.iter().position(|l| l.contains(&s2))
                    && layers.iter().position(|l| l.contains(&t1)) == layers.iter().position(|l| l.contains(&t2));
                if same_layers && (place[&s1] < place[&s2]) != (place[&t1] < place[&t2]) && s1 != s2 && t1 != t2 {
                    count += 1;
                }
            }
        }
        count
    }

    #[test]
    fn layers_follow_the_longest_chain_and_the_ordering_uncrosses_arrows() {
        // Sources 0, 1 read crosswise by 3 (reads 1) and 2 (reads 0), listed so that the input
        // order crosses them; 4 reads 2 and 3, 5 reads 4 and 0 (a chain of three before it).
        let needs = vec![vec![], vec![], vec![0], vec![1], vec![2, 3], vec![4, 0]];
        let layers = layered(&needs);
        assert_eq!(layers.len(), 4);
        assert_eq!(layers[0].len(), 2);
        assert_eq!(layers[3], vec![5]);
        // Listed as 3 then 2 the arrows 1->3 and 0->2 would cross; ordered, none do.
        let crossed = vec![vec![0, 1], vec![3, 2], vec![4], vec![5]];
        assert_eq!(crossings(&crossed, &needs), 1);
        assert_eq!(crossings(&layers, &needs), 0, "{layers:?}");
    }
}
