//! Cache keys: a blake3 hash of what determines a task's result.
//!
//! key = blake3("repro-task-1", kind, kind version, canonical parameters,
//!              for each input stage in name order: its name and its output hash).
//! Canonical parameters: object keys sorted, every number encoded as the bits of an f64
//! (so `1`, `1.0` and `1e0` hash alike, and -0 as 0), strings length-prefixed.

use serde_json::Value;
use std::collections::BTreeMap;

pub type Hash = String;

fn encode(v: &Value, out: &mut Vec<u8>) {
    match v {
        Value::Null => out.push(b'n'),
        Value::Bool(b) => out.push(if *b { b't' } else { b'f' }),
        Value::Number(n) => {
            let x = n.as_f64().expect("JSON numbers are finite");
            let x = if x == 0.0 { 0.0 } else { x };
            out.push(b'd');
            out.extend_from_slice(&x.to_bits().to_le_bytes());
        }
        Value::String(s) => {
            out.push(b's');
            out.extend_from_slice(&(s.len() as u64).to_le_bytes());
            out.extend_from_slice(s.as_bytes());
        }
        Value::Array(a) => {
            out.push(b'[');
            out.extend_from_slice(&(a.len() as u64).to_le_bytes());
            for x in a {
                encode(x, out);
            }
        }
        Value::Object(m) => {
            let sorted: BTreeMap<&String, &Value> = m.iter().collect();
            out.push(b'{');
            out.extend_from_slice(&(sorted.len() as u64).to_le_bytes());
            for (k, x) in sorted {
                encode(&Value::String(k.clone()), out);
                encode(x, out);
            }
        }
    }
}

/// The canonical byte encoding of parameters.
pub fn canonical_params(v: &Value) -> Vec<u8> {
    let mut out = Vec::new();
    encode(v, &mut out);
    out
}

pub fn task_key(kind: &str, version: u32, params: &Value, inputs: &BTreeMap<String, Hash>) -> Hash {
    let mut h = blake3::Hasher::new();
    h.update(b"repro-task-1\0");
    h.update(kind.as_bytes());
    h.update(b"\0");
    h.update(&version.to_le_bytes());
    h.update(&canonical_params(params));
    for (name, hash) in inputs {
        h.update(name.as_bytes());
        h.update(b"\0");
        h.update(hash.as_bytes());
    }
    h.finalize().to_hex().to_string()
}

pub fn content_hash(bytes: &[u8]) -> Hash {
    blake3::hash(bytes).to_hex().to_string()
}

/// The output hash of a stage: the hash of its points' output hashes, in point order.
pub fn stage_hash(point_hashes: &[Hash]) -> Hash {
    let mut h = blake3::Hasher::new();
    h.update(b"repro-stage-1\0");
    for p in point_hashes {
        h.update(p.as_bytes());
    }
    h.finalize().to_hex().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn key_ignores_key_order_and_number_spelling() {
        let none = BTreeMap::new();
        let a = task_key("k", 1, &json!({"a": 1, "b": 0.5}), &none);
        let b = task_key("k", 1, &json!({"b": 0.5, "a": 1.0}), &none);
        assert_eq!(a, b);
    }

    #[test]
    fn key_depends_on_every_ingredient() {
        let none = BTreeMap::new();
        let base = task_key("k", 1, &json!({"a": 1}), &none);
        assert_ne!(base, task_key("k", 2, &json!({"a": 1}), &none));
        assert_ne!(base, task_key("j", 1, &json!({"a": 1}), &none));
        assert_ne!(base, task_key("k", 1, &json!({"a": 1.0000001}), &none));
        let mut inputs = BTreeMap::new();
        inputs.insert("up".to_string(), "abc".to_string());
        assert_ne!(base, task_key("k", 1, &json!({"a": 1}), &inputs));
        // Strings are length-prefixed: no two different objects share an encoding.
        assert_ne!(canonical_params(&json!({"ab": "c"})), canonical_params(&json!({"a": "bc"})));
    }
}
