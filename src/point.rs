//! One point of a stage kind, computed outside a pipeline (`repro point`, the Python
//! package's `point`): its parameters checked as a pipeline's are (defaults filled in, the
//! same canonical form, so the same numbers as a task of a run), and its computation
//! guarded as a task's is (`pipeline::task::guarded_run`: the kind's time limit, memory
//! estimate, panics, non-finite tables).

use pipeline::kind::{DynKind, FieldError, Inputs, Output, Registry};
use pipeline::task::{guarded_run, TaskError};
use serde_json::Value;
use std::time::Duration;

/// Why a point was not computed.
#[derive(Debug, thiserror::Error)]
pub enum PointError {
    /// No kind has this name.
    #[error("unknown stage kind `{kind}`; known kinds: {}", known.join(", "))]
    UnknownKind { kind: String, known: Vec<String> },
    /// The parameters do not make a valid point of the kind.
    #[error("{}", invalid_text(kind, errors))]
    InvalidParameters { kind: String, errors: Vec<FieldError> },
    /// The computation failed, panicked, ran out of time or was interrupted.
    #[error(transparent)]
    Failed(#[from] TaskError),
}

fn invalid_text(kind: &str, errors: &[FieldError]) -> String {
    errors
        .iter()
        .map(|e| match e.path.as_str() {
            // A missing field is reported at the root: name the kind instead.
            "" => format!("{kind}: {} (`repro kinds` lists the kinds)", e.message),
            path => format!("parameter `{path}`: {}", e.message),
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The kind named `kind`, or the error that lists the known ones.
pub fn kind<'r>(registry: &'r Registry, kind: &str) -> Result<&'r dyn DynKind, PointError> {
    registry.get(kind).ok_or_else(|| PointError::UnknownKind {
        kind: kind.to_string(),
        known: registry.names().map(String::from).collect(),
    })
}

/// The kind named `kind` and the canonical parameters of the point `params` gives.
pub fn check<'r>(registry: &'r Registry, kind: &str, params: &Value) -> Result<(&'r dyn DynKind, Value), PointError> {
    let k = self::kind(registry, kind)?;
    let (canonical, _) =
        k.check(params).map_err(|errors| PointError::InvalidParameters { kind: kind.to_string(), errors })?;
    Ok((k, canonical))
}

/// Computes one point of `kind` (a kind that reads no other stage's table), held to
/// `time_limit_s`, else to the kind's time limit.
pub fn compute(
    registry: &Registry,
    kind: &str,
    params: &Value,
    time_limit_s: Option<f64>,
) -> Result<Output, PointError> {
    let (k, canonical) = check(registry, kind, params)?;
    let limit = Duration::try_from_secs_f64(time_limit_s.unwrap_or_else(|| k.time_limit_s())).ok();
    let (out, _) = guarded_run(registry, k, &canonical, &Inputs { tables: Default::default() }, limit);
    Ok(out?)
}
