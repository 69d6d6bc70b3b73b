//! Why a task runs, or would, or does not: the planner's answer as data. The run report
//! serialises it (`{"why": "parameters_changed", "changes": [...]}`), tests assert on it,
//! and its `Display` is the sentence the run's summary prints ("parameters changed: ms:
//! 0 -> 1").
//!
//! The reasons a task is computed are found by comparing it with the stage's previous run
//! (its manifest in the cache): the first difference in the order kind, code version,
//! inputs, parameters decides; with none, the entry itself is missing or damaged.

use serde::{Deserialize, Deserializer, Serialize};
use std::fmt;

/// Why a task is computed (or would be, in a dry run), or why it is not.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "why", rename_all = "snake_case")]
pub enum Reason {
    /// No previous run of the stage is recorded in this cache.
    NeverRun,
    /// A point the stage's previous run did not have, differing from its nearest point in
    /// swept parameters only.
    NewPoint { point: String },
    /// Parameters differ from the nearest point of the previous run, with their old and
    /// new values.
    ParametersChanged { changes: Vec<ParamChange> },
    /// The tables of the stages it needs changed.
    InputChanged { stages: Vec<String> },
    /// The kind's code version changed (its outputs may differ).
    CodeVersionChanged { kind: String, from: u32, to: u32 },
    /// The stage now has another kind.
    KindChanged { from: String, to: String },
    /// Same point, inputs and code as the previous run, but its cache entry is gone
    /// (removed by `repro gc` or by hand).
    EntryMissing,
    /// Same point, inputs and code version, yet another key (the keying changed).
    KeyChanged,
    /// Its cache entry exists but fails its check (truncated, altered, unreadable).
    Corrupted { detail: String },
    /// Its stage was named by `--force`.
    Forced,
    /// A point an adaptive sweep added after `round` (`cause`: why it is computed).
    AdaptiveRound { round: usize, cause: Box<Reason> },
    /// The same task (same key) as a point of another stage: computed once, for that one.
    SameTaskAs { stage: String, point: String },
    /// Not run: stages it needs failed or were skipped.
    NeedsIncomplete { stages: Vec<String> },
    /// Dry run: its key depends on the outputs of stages that would run first.
    UpstreamWouldRun,
    /// Dry run: the points an adaptive sweep adds depend on points that would run.
    AdaptiveWouldRun,
    /// A reason recorded as text (run reports of earlier versions of `repro`).
    Text { text: String },
}

/// A parameter whose value differs from the previous run's (values as JSON, shortened to
/// 40 characters).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ParamChange {
    pub param: String,
    /// `(none)` when the parameter was not set.
    pub from: String,
    pub to: String,
    /// Set on the command line (`repro run -S`).
    #[serde(default)]
    pub set_by_cli: bool,
}

impl fmt::Display for Reason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Reason::NeverRun => write!(f, "never run"),
            Reason::NewPoint { point } => write!(f, "new sweep point {point}"),
            Reason::ParametersChanged { changes } => {
                write!(f, "parameters changed: ")?;
                for (i, c) in changes.iter().enumerate() {
                    let cli = if c.set_by_cli { " (-S)" } else { "" };
                    write!(f, "{}{}: {} -> {}{cli}", if i > 0 { ", " } else { "" }, c.param, c.from, c.to)?;
                }
                Ok(())
            }
            Reason::InputChanged { stages } => write!(f, "input changed: {}", stages.join(", ")),
            Reason::CodeVersionChanged { kind, from, to } => {
                write!(f, "code version of {kind} changed (v{from} -> v{to})")
            }
            Reason::KindChanged { from, to } => write!(f, "kind changed ({from} -> {to})"),
            Reason::EntryMissing => write!(f, "cache entry missing"),
            Reason::KeyChanged => write!(f, "key changed"),
            Reason::Corrupted { detail } => write!(f, "corrupted cache entry ({detail})"),
            Reason::Forced => write!(f, "forced (--force)"),
            Reason::AdaptiveRound { round, cause } => write!(f, "adaptive refinement, round {round} ({cause})"),
            Reason::SameTaskAs { stage, point } => {
                write!(f, "the same task as stage `{stage}` point {point} (computed once)")
            }
            Reason::NeedsIncomplete { stages } => write!(f, "needs {} which did not complete", stages.join(", ")),
            Reason::UpstreamWouldRun => write!(f, "upstream stages would run first"),
            Reason::AdaptiveWouldRun => {
                write!(f, "further points depend on the results of the points that would run")
            }
            Reason::Text { text } => write!(f, "{text}"),
        }
    }
}

/// Reads a reason as this version writes it, or as text (reports of earlier versions), so
/// that the run history stays readable (and `repro gc` keeps what old runs used).
pub fn deserialize_reason<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Reason>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Stored {
        Typed(Reason),
        Text(String),
    }
    Ok(Option::<Stored>::deserialize(d)?.map(|s| match s {
        Stored::Typed(r) => r,
        Stored::Text(text) => Reason::Text { text },
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reason_round_trips_through_json_and_old_text_reasons_still_read() {
        let r = Reason::AdaptiveRound {
            round: 2,
            cause: Box::new(Reason::ParametersChanged {
                changes: vec![ParamChange { param: "ms".into(), from: "0".into(), to: "1".into(), set_by_cli: true }],
            }),
        };
        let json = serde_json::to_value(&r).unwrap();
        assert_eq!(json["why"], "adaptive_round");
        assert_eq!(json["cause"]["changes"][0]["param"], "ms");
        assert_eq!(r.to_string(), "adaptive refinement, round 2 (parameters changed: ms: 0 -> 1 (-S))");
        #[derive(Deserialize)]
        struct Record {
            #[serde(deserialize_with = "deserialize_reason", default)]
            reason: Option<Reason>,
        }
        let back: Record = serde_json::from_value(serde_json::json!({ "reason": json })).unwrap();
        assert_eq!(back.reason, Some(r));
        let old: Record = serde_json::from_str(r#"{"reason": "new sweep point x=2"}"#).unwrap();
        assert_eq!(old.reason, Some(Reason::Text { text: "new sweep point x=2".into() }));
        let none: Record = serde_json::from_str(r#"{"reason": null}"#).unwrap();
        assert_eq!(none.reason, None);
    }
}
