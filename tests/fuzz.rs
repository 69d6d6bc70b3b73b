//! Bad input never panics: property tests (proptest, a bounded number of cases) of the
//! pipeline parser on mutated and random pipeline files, and of the cache reader on
//! truncated, bit-flipped, forged and foreign entries.

use proptest::prelude::*;
use repro::pipeline::cache::{decode_entry, Cache, Entry, LockMode, Miss};
use repro::pipeline::key::content_hash;
use repro::pipeline::kind::Output;
use repro::pipeline::parse;
use repro::pipeline::table::Table;

const SMALL: &str = r#"stages:
  - name: sweep
    kind: util.sleep
    params: {x: {linspace: [1, 3, 3]}, ms: 0}
  - name: sliding
    kind: bem.sweep
    params: {lambda: [0.3, 1], W: 1, k: 0.1, V0: {logspace: [-1, 1, 3]}}
  - name: fig
    kind: figure
    needs: [sliding]
    params:
      title: "t"
      x_label: "V0"
      y_label: "mu*"
      log_x: true
      layers:
        - data: {from: sliding, x: V0, y: mu_star, label: "a"}
"#;

#[derive(Clone, Debug)]
enum Mutation {
    Truncate(usize),
    Flip(usize, u8),
    Insert(usize, u8),
    Delete(usize, usize),
    DuplicateLine(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    // Bytes that matter to YAML and to the pipeline grammar.
    let special = prop::sample::select(b":-[]{},'\"#&*!|>%@`\n\t 0123456789.eE+-_/\\".to_vec());
    prop_oneof![
        any::<usize>().prop_map(Mutation::Truncate),
        (any::<usize>(), 0u8..8).prop_map(|(p, b)| Mutation::Flip(p, b)),
        (any::<usize>(), special).prop_map(|(p, c)| Mutation::Insert(p, c)),
        (any::<usize>(), 1usize..40).prop_map(|(p, n)| Mutation::Delete(p, n)),
        any::<usize>().prop_map(Mutation::DuplicateLine),
    ]
}

fn apply(mut b: Vec<u8>, muts: &[Mutation]) -> Vec<u8> {
    for m in muts {
        let n = b.len().max(1);
        match *m {
            Mutation::Truncate(p) => b.truncate(p % n),
            Mutation::Flip(p, bit) if !b.is_empty() => b[p % n] ^= 1 << bit,
            Mutation::Insert(p, c) => b.insert(p % (b.len() + 1), c),
            Mutation::Delete(p, k) if !b.is_empty() => {
                let s = p % n;
                b.drain(s..(s + k).min(b.len()));
            }
            Mutation::DuplicateLine(p) => {
                let text = String::from_utf8_lossy(&b).to_string();
                let lines: Vec<&str> = text.lines().collect();
                if !lines.is_empty() {
                    let i = p % lines.len();
                    let mut out: Vec<&str> = lines[..=i].to_vec();
                    out.extend_from_slice(&lines[i..]);
                    b = out.join("\n").into_bytes();
                }
            }
            _ => {}
        }
    }
    b
}

/// The parser's contract: a pipeline, or diagnostics that name the file and a line.
fn check_parse(text: &str) {
    let registry = repro::stages::registry();
    match parse::parse("fuzz.yaml", text, &registry) {
        Ok(p) => assert!(p.stages.iter().all(|s| !s.points.is_empty())),
        Err(e) => {
            assert!(!e.0.is_empty());
            for d in &e.0 {
                assert!(d.location.file == "fuzz.yaml" && d.location.line >= 1, "{d}");
                assert!(!d.message.is_empty());
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn mutated_pipelines_parse_or_fail_with_located_errors(muts in prop::collection::vec(mutation(), 1..6)) {
        let bytes = apply(SMALL.as_bytes().to_vec(), &muts);
        check_parse(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn random_yaml_like_text_never_panics_the_parser(text in "[a-z_:\\-\\[\\]{}, \n0-9.'\"#&*!|>]{0,200}") {
        check_parse(&format!("stages:\n{text}"));
        check_parse(&text);
    }
}

/// A sound entry, written by the cache itself: (key, file bytes). Made once.
fn sample_entry() -> (String, Vec<u8>) {
    static SAMPLE: std::sync::OnceLock<(String, Vec<u8>)> = std::sync::OnceLock::new();
    SAMPLE
        .get_or_init(|| {
            let output =
                Output::from(Table::new().with_f64("mu_star", vec![1.5, 2.5]).with_f64("wall_time_s", vec![0.1, 0.2]));
            let key = content_hash(b"a task");
            let entry = Entry::new(key.clone(), "util.sleep", 1, serde_json::json!({"x": 1}), output, 0.3);
            let dir = std::env::temp_dir().join(format!("repro-fuzz-entry-{}", std::process::id()));
            let cache = Cache::open(&dir, LockMode::Wait).unwrap();
            cache.put(&entry).unwrap();
            let bytes = std::fs::read(cache.entry_path(&key)).unwrap();
            drop(cache);
            let _ = std::fs::remove_dir_all(&dir);
            (key, bytes)
        })
        .clone()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn damaged_entries_are_rejected_never_used(muts in prop::collection::vec(mutation(), 1..4)) {
        let (key, good) = sample_entry();
        let bad = apply(good.clone(), &muts);
        match decode_entry(&key, &bad) {
            Ok(e) => {
                // Only a mutation that restored the bytes (or touched nothing) may decode.
                prop_assert_eq!(&bad, &good);
                prop_assert_eq!(e.key, key);
            }
            Err(e) => prop_assert!(!e.to_string().is_empty()),
        }
    }

    #[test]
    fn forged_entries_with_a_valid_checksum_are_rejected(body in prop::collection::vec(any::<u8>(), 0..300)) {
        // A foreign file that carries a correct header hash of its own body.
        let (key, _) = sample_entry();
        let mut bytes = format!("repro-entry-1 {}\n", content_hash(&body)).into_bytes();
        bytes.extend_from_slice(&body);
        prop_assert!(decode_entry(&key, &bytes).is_err());
    }

    #[test]
    fn foreign_files_are_rejected(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        let (key, _) = sample_entry();
        prop_assert!(decode_entry(&key, &bytes).is_err());
    }
}

#[test]
fn an_entry_stored_under_another_key_or_a_malformed_key_is_rejected() {
    let (key, good) = sample_entry();
    let other = content_hash(b"another task");
    let err = decode_entry(&other, &good).unwrap_err().to_string();
    assert!(err.contains("is stored under"), "{err}");
    let dir = std::env::temp_dir().join(format!("repro-fuzz-keys-{}", std::process::id()));
    let cache = Cache::open(&dir, LockMode::Wait).unwrap();
    for k in ["", "a", "../../etc/passwd", &key.to_uppercase(), "é"] {
        assert!(matches!(cache.get(k), Err(Miss::Corrupted(_))), "{k}");
    }
    drop(cache);
    let _ = std::fs::remove_dir_all(&dir);
    // A valid entry still decodes (the properties above are not vacuous).
    assert_eq!(decode_entry(&key, &good).unwrap().key, key);
}

#[test]
fn a_sweep_whose_size_overflows_is_an_error_not_a_panic() {
    // 100000^4 points overflow a 64-bit count (seen in the sweep expansion while writing
    // these tests; it was an arithmetic-overflow panic in debug builds).
    let text = "stages:\n  - name: s\n    kind: bem.sweep\n    params:\n      lambda: {linspace: [0.1, 1, 100000]}\n      W: {linspace: [0.1, 1, 100000]}\n      k: {linspace: [0.1, 0.5, 100000]}\n      V0: {logspace: [-1, 1, 100000]}\n";
    let err = parse::parse("big.yaml", text, &repro::stages::registry()).unwrap_err().to_string();
    assert!(err.contains("big.yaml:5:") && err.contains("more than a million"), "{err}");
}
