//! The pipeline file's YAML read into marked nodes, each keeping the line and column it
//! was written at, with anchors, aliases and merge keys resolved: `&name` marks a node,
//! `*name` repeats it (PyYAML writes them for values it dumps twice), and `<<: *name` (or
//! a list of such) merges a mapping's entries under those written beside it, which take
//! precedence. A repeated node keeps the location of its anchor, so an error inside it
//! points at its definition. Tags, keys that are not scalars and keys given twice are
//! refused; only the first document is read (the caller refuses a second one).

use marked_yaml::types::{MarkedMappingNode, MarkedScalarNode, MarkedSequenceNode, Marker, Node, Span};
use std::collections::HashMap;
use yaml_rust2::parser::{Event, MarkedEventReceiver, Parser};
use yaml_rust2::scanner::{Marker as YamlMarker, TScalarStyle};

/// Why the YAML could not be read, located.
#[derive(Debug)]
pub(super) enum LoadError {
    /// Not YAML: the scanner's message.
    Scan(Marker, String),
    TopLevelMustBeMapping(Marker),
    MappingKeyMustBeScalar(Marker),
    UnexpectedTag(Marker),
    /// `*name` before (or inside) the node `&name` marks.
    UnknownAlias(Marker),
    /// `<<` given something other than a mapping or a list of mappings.
    MergeNotMapping(Marker),
    /// A key given twice in one mapping, and the line of its first.
    DuplicateKey {
        key: MarkedScalarNode,
        first_line: usize,
    },
}

impl LoadError {
    /// Where it is, and what to say there.
    pub(super) fn located(&self) -> (Marker, String) {
        match self {
            LoadError::Scan(m, info) => (*m, format!("invalid YAML: {info}")),
            LoadError::TopLevelMustBeMapping(m) => (*m, "the top level must be a mapping with a `stages` list".into()),
            LoadError::MappingKeyMustBeScalar(m) => (*m, "a mapping's key must be a scalar".into()),
            LoadError::UnexpectedTag(m) => (*m, "YAML tags (`!name`) are not read".into()),
            LoadError::UnknownAlias(m) => (*m, "an alias (`*name`) names no anchor (`&name`) defined before it".into()),
            LoadError::MergeNotMapping(m) => (*m, "a merge key (`<<`) takes a mapping or a list of mappings".into()),
            LoadError::DuplicateKey { key, first_line } => (
                key.span().start().copied().unwrap_or_else(|| Marker::new(0, 0, 0, 0)),
                format!("duplicate key `{}` (first given at line {first_line})", key.as_str()),
            ),
        }
    }
}

/// A collection being read: where it starts, its anchor (0: none), what it holds so far.
/// One per nesting level is open at a time, so the variants' sizes do not matter.
#[allow(clippy::large_enum_variant)]
enum Open {
    Mapping { start: Marker, anchor: usize, map: MarkedMappingNode, key: Option<MarkedScalarNode>, merged: Vec<Node> },
    Sequence { start: Marker, anchor: usize, items: Vec<Node> },
}

#[derive(Default)]
struct Loader {
    open: Vec<Open>,
    anchors: HashMap<usize, Node>,
    root: Option<Node>,
    error: Option<LoadError>,
    /// Where the last event was: an empty document's empty mapping is placed there.
    last: Option<Marker>,
}

fn marker(m: YamlMarker) -> Marker {
    Marker::new(0, m.index(), m.line(), m.col() + 1)
}

impl Loader {
    /// A complete node where the open collection (or the document) expects one.
    fn place(&mut self, node: Node, anchor: usize, at: Marker) -> Result<(), LoadError> {
        if anchor != 0 {
            self.anchors.insert(anchor, node.clone());
        }
        match self.open.last_mut() {
            None => match node {
                Node::Mapping(_) => self.root = Some(node),
                _ => return Err(LoadError::TopLevelMustBeMapping(at)),
            },
            Some(Open::Sequence { items, .. }) => items.push(node),
            Some(Open::Mapping { map, key, merged, .. }) => match key.take() {
                None => match node {
                    Node::Scalar(s) => *key = Some(s),
                    _ => return Err(LoadError::MappingKeyMustBeScalar(at)),
                },
                Some(k) if k.as_str() == "<<" => match &node {
                    Node::Mapping(_) => merged.push(node),
                    Node::Sequence(s) if s.iter().all(|n| matches!(n, Node::Mapping(_))) => {
                        merged.extend(s.iter().cloned())
                    }
                    _ => return Err(LoadError::MergeNotMapping(at)),
                },
                Some(k) => {
                    if let Some((first, _)) = map.get_key_value(&k) {
                        let first_line = first.span().start().map_or(0, |m| m.line());
                        return Err(LoadError::DuplicateKey { key: k, first_line });
                    }
                    map.insert(k, node);
                }
            },
        }
        Ok(())
    }

    fn event(&mut self, ev: Event, at: Marker) -> Result<(), LoadError> {
        match ev {
            Event::MappingStart(_, Some(_)) | Event::SequenceStart(_, Some(_)) | Event::Scalar(_, _, _, Some(_)) => {
                Err(LoadError::UnexpectedTag(at))
            }
            Event::MappingStart(anchor, None) => {
                let map = MarkedMappingNode::new_empty(Span::new_start(at));
                self.open.push(Open::Mapping { start: at, anchor, map, key: None, merged: Vec::new() });
                Ok(())
            }
            Event::SequenceStart(anchor, None) => {
                self.open.push(Open::Sequence { start: at, anchor, items: Vec::new() });
                Ok(())
            }
            Event::MappingEnd => {
                let Some(Open::Mapping { start, anchor, mut map, merged, .. }) = self.open.pop() else {
                    unreachable!("the parser closes the mapping it opened")
                };
                // The merged mappings' entries under the explicit ones, the first merged first.
                for m in merged.iter().filter_map(Node::as_mapping) {
                    for (k, v) in m.iter() {
                        if !map.contains_key(k) {
                            map.insert(k.clone(), v.clone());
                        }
                    }
                }
                *map.span_mut() = Span::new_with_marks(start, at);
                self.place(Node::from(map), anchor, start)
            }
            Event::SequenceEnd => {
                let Some(Open::Sequence { start, anchor, items }) = self.open.pop() else {
                    unreachable!("the parser closes the sequence it opened")
                };
                self.place(Node::from(MarkedSequenceNode::new(Span::new_with_marks(start, at), items)), anchor, start)
            }
            Event::Scalar(value, style, anchor, None) => {
                let mut node = MarkedScalarNode::new(Span::new_start(at), value);
                // A quoted scalar stays text (`A_max: "5.0"` is a string).
                node.set_coerce(matches!(style, TScalarStyle::Plain));
                self.place(Node::from(node), anchor, at)
            }
            Event::Alias(id) => match self.anchors.get(&id) {
                Some(node) => self.place(node.clone(), 0, at),
                None => Err(LoadError::UnknownAlias(at)),
            },
            Event::StreamStart | Event::StreamEnd | Event::DocumentStart | Event::DocumentEnd | Event::Nothing => {
                Ok(())
            }
        }
    }
}

impl MarkedEventReceiver for Loader {
    fn on_event(&mut self, ev: Event, mark: YamlMarker) {
        self.last = Some(marker(mark));
        if self.error.is_none() {
            if let Err(e) = self.event(ev, marker(mark)) {
                self.error = Some(e);
            }
        }
    }
}

/// Reads `text`'s first YAML document, whose top level must be a mapping (an empty
/// document is an empty mapping).
pub(super) fn parse(text: &str) -> Result<Node, LoadError> {
    let mut loader = Loader::default();
    Parser::new_from_str(text).load(&mut loader, false).map_err(|e| match e.info() {
        // The parser knows the anchors defined so far.
        info if info.contains("unknown anchor") => LoadError::UnknownAlias(marker(*e.marker())),
        info => LoadError::Scan(marker(*e.marker()), info.to_string()),
    })?;
    if let Some(e) = loader.error {
        return Err(e);
    }
    let end = loader.last.unwrap_or_else(|| Marker::new(0, 0, 1, 1));
    Ok(loader.root.unwrap_or_else(|| Node::from(MarkedMappingNode::new_empty(Span::new_with_marks(end, end)))))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(n: &Node) -> (usize, usize) {
        let m = n.span().start().unwrap();
        (m.line(), m.column())
    }

    #[test]
    fn anchors_aliases_and_merge_keys_are_resolved_with_their_locations() {
        let text = "base: &model {R: 15, h: 0.9}\n\
                    a: *model\n\
                    b:\n  <<: *model\n  h: 1.2\n\
                    list: &l [1, 2]\n\
                    c: *l\n";
        let root = parse(text).unwrap();
        let m = root.as_mapping().unwrap();
        let a = m.get_mapping("a").unwrap();
        assert_eq!(a.get_scalar("R").unwrap().as_str(), "15");
        // The repeated node keeps the location of the node its anchor marks (line 1).
        assert_eq!(at(m.get_node("a").unwrap()), (1, 14));
        let b = m.get_mapping("b").unwrap();
        assert_eq!((b.get_scalar("R").unwrap().as_str(), b.get_scalar("h").unwrap().as_str()), ("15", "1.2"));
        assert!(b.get_node("<<").is_none());
        assert_eq!(m.get_sequence("c").unwrap().len(), 2);
    }

    #[test]
    fn what_the_pipeline_refuses_is_refused_where_it_is() {
        let err = |t: &str| {
            let (m, msg) = parse(t).unwrap_err().located();
            (m.line(), msg)
        };
        assert_eq!(
            err("a: 1\nb: *nope\n"),
            (2, "an alias (`*name`) names no anchor (`&name`) defined before it".into())
        );
        assert_eq!(err("a: 1\na: 2\n"), (2, "duplicate key `a` (first given at line 1)".into()));
        assert_eq!(err("a: !tag 1\n").0, 1);
        assert_eq!(err("- 1\n").1, "the top level must be a mapping with a `stages` list");
        assert!(err("a: [1\n").1.starts_with("invalid YAML"));
        // An empty document is an empty mapping, placed at its end (a line to point at).
        let empty = parse("# nothing\n\n").unwrap();
        assert!(empty.as_mapping().unwrap().is_empty() && empty.span().start().unwrap().line() >= 1);
        assert_eq!(err("a:\n  <<: 3\n"), (2, "a merge key (`<<`) takes a mapping or a list of mappings".into()));
        // Quoted scalars stay text; plain ones may be read as numbers.
        let root = parse("a: \"5.0\"\nb: 5.0\n").unwrap();
        let m = root.as_mapping().unwrap();
        assert!(!m.get_scalar("a").unwrap().may_coerce() && m.get_scalar("b").unwrap().may_coerce());
    }
}
