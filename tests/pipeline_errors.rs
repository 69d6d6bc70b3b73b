//! Invalid pipeline files: every error names the file, line and column and says what is
//! wrong; nothing is run or written; the exit code says "invalid input" (2).

use crate::common;
use common::{rejected, Scratch};

#[test]
fn unknown_stage_kind_is_located_and_suggests_a_name() {
    let err =
        rejected("unknown-kind", "stages:\n  - name: a\n    kind: theory.persone\n    params: {inv_k: 10, V0: 1}\n");
    assert!(err.contains("p.yaml:3:11: error:"), "{err}");
    assert!(err.contains("unknown stage kind `theory.persone`"), "{err}");
    assert!(err.contains("did you mean `theory.persson`?"), "{err}");
}

#[test]
fn unknown_parameter_is_located_at_its_key() {
    let err = rejected(
        "unknown-param",
        "stages:\n  - name: a\n    kind: theory.persson\n    params:\n      inv_k: 10\n      V0: 1\n      speed: 3\n",
    );
    assert!(err.contains("p.yaml:7:7: error:"), "{err}");
    assert!(err.contains("unknown field `speed`"), "{err}");
}

#[test]
fn missing_parameter_is_reported_at_the_params() {
    let err =
        rejected("missing-param", "stages:\n  - name: a\n    kind: theory.persson\n    params:\n      inv_k: 10\n");
    assert!(err.contains("p.yaml:5:7: error:"), "{err}");
    assert!(err.contains("missing field `V0`"), "{err}");
}

#[test]
fn wrong_type_is_located_at_the_value() {
    let err = rejected(
        "wrong-type",
        "stages:\n  - name: a\n    kind: theory.hertz_jkr_pressure\n    params:\n      P_bar: 1.0\n      n: lots\n",
    );
    assert!(err.contains("p.yaml:6:10: error:"), "{err}");
    assert!(err.contains("parameter `n`") && err.contains("invalid type"), "{err}");
}

#[test]
fn wrong_type_inside_a_sweep_is_located_at_the_element() {
    let err = rejected(
        "wrong-type-sweep",
        "stages:\n  - name: a\n    kind: theory.persson\n    params:\n      inv_k: [2, ten]\n      V0: 1\n",
    );
    assert!(err.contains("p.yaml:5:18: error:"), "{err}");
    assert!(err.contains("must be a number"), "{err}");
}

#[test]
fn modulus_ratio_outside_zero_one_is_refused_at_the_sweep_point() {
    let err = rejected(
        "bad-k",
        "stages:\n  - name: pb\n    kind: theory.persson_brener\n    params:\n      k: [0.1, 1.5]\n      V_PB: 1\n",
    );
    assert!(err.contains("p.yaml:5:16: error:"), "{err}");
    assert!(err.contains("parameter `k`: must lie in (0, 1), got 1.5"), "{err}");
    assert!(err.contains("at sweep point k=1.5"), "{err}");
}

#[test]
fn negative_length_is_refused() {
    let err = rejected(
        "negative-length",
        "stages:\n  - name: m\n    kind: theory.maugis_dugdale\n    params: {lambda: 1, A_min: -0.5}\n",
    );
    assert!(err.contains("p.yaml:4:"), "{err}");
    assert!(err.contains("parameter `A_min`: must be positive, got -0.5"), "{err}");
}

#[test]
fn a_newton_tolerance_outside_zero_one_is_refused() {
    let err = rejected(
        "newton-tol",
        "stages:\n  - name: b\n    kind: bem.sweep\n    params: {lambda: 1, W: 1, k: 0.1, V0: 1, newton_tol: 0}\n",
    );
    assert!(err.contains("p.yaml:4:"), "{err}");
    assert!(err.contains("parameter `newton_tol`"), "{err}");
}

#[test]
fn needs_naming_no_stage_is_located() {
    let err = rejected(
        "bad-needs",
        "stages:\n  - name: a\n    kind: util.sleep\n    params: {x: 1}\n  - name: b\n    kind: util.sleep\n    needs: [a, aa, zzz]\n    params: {x: 1}\n",
    );
    assert!(
        err.contains("p.yaml:7:16: error: stage `b` needs `aa`, which names no stage (did you mean `a`?)"),
        "{err}"
    );
    assert!(err.contains("p.yaml:7:20: error: stage `b` needs `zzz`, which names no stage"), "{err}");
}

#[test]
fn a_cycle_is_printed() {
    let err = rejected(
        "cycle",
        "stages:\n  - name: a\n    kind: util.sleep\n    needs: [c]\n    params: {x: 1}\n  - name: b\n    kind: util.sleep\n    needs: [a]\n    params: {x: 1}\n  - name: c\n    kind: util.sleep\n    needs: [b]\n    params: {x: 1}\n",
    );
    assert!(err.contains("the stages form a cycle: a -> b -> c -> a"), "{err}");
    assert!(err.contains("p.yaml:2:5: error:"), "{err}");
}

#[test]
fn figure_layer_must_read_a_needed_stage() {
    let err = rejected(
        "figure-needs",
        "stages:\n  - name: a\n    kind: util.sleep\n    params: {x: 1}\n  - name: f\n    kind: figure\n    params:\n      title: t\n      x_label: x\n      y_label: y\n      layers:\n        - data: {from: a, x: x, y: x, label: l}\n",
    );
    assert!(err.contains("p.yaml:12:24: error:"), "{err}");
    assert!(err.contains("refers to stage `a`, which is not in its `needs`"), "{err}");
}

#[test]
fn yaml_syntax_errors_duplicates_and_bad_sweeps_are_located() {
    let err = rejected("syntax", "stages:\n  - name: a\n    kind: [unclosed\n");
    assert!(err.contains("p.yaml:"), "{err}");
    let err = rejected(
        "duplicate",
        "stages:\n  - name: a\n    kind: util.sleep\n    params: {x: 1}\n  - name: a\n    kind: util.sleep\n    params: {x: 2}\n",
    );
    assert!(err.contains("p.yaml:5:5: error: duplicate stage name `a` (first defined at line 2)"), "{err}");
    let err =
        rejected("bad-sweep", "stages:\n  - name: a\n    kind: util.sleep\n    params: {x: {logspace: [1, 2]}}\n");
    assert!(err.contains("p.yaml:4:28: error:") && err.contains("takes [from, to, n]"), "{err}");
    let err = rejected("unknown-top", "stage:\n  - name: a\n");
    assert!(err.contains("p.yaml:1:1: error: unknown field `stage`"), "{err}");
}

#[test]
fn all_errors_are_reported_together() {
    let err = rejected(
        "many",
        "stages:\n  - name: a\n    kind: nope\n  - name: b\n    kind: util.sleep\n    needs: [q]\n    params: {x: 1}\n",
    );
    assert!(err.contains("p.yaml:3:11") && err.contains("p.yaml:6:13"), "{err}");
}

#[test]
fn a_pipeline_cannot_name_files_outside_the_output_directories() {
    // Stage names become published file names; paths, parent directories, hidden names
    // and absolute paths are rejected where they are written.
    for (i, name) in ["../escape", "/etc/passwd", "..", ".hidden", "a/b", "-rf", "x\\\\y"].iter().enumerate() {
        let yaml = format!("stages:\n  - name: \"{name}\"\n    kind: util.sleep\n    params: {{x: 1}}\n");
        let err = rejected(&format!("confine-{i}"), &yaml);
        assert!(err.contains("p.yaml:2:11: error: a stage name must be"), "{name}: {err}");
    }
    let s = Scratch::new("confine-parent");
    assert!(!s.dir.parent().unwrap().join("escape.parquet").exists());
}

#[test]
fn a_second_yaml_document_is_rejected_where_it_starts() {
    let stage = "stages:\n  - name: a\n    kind: util.sleep\n    params: {x: 1}\n";
    let err = rejected("two-docs", &format!("---\n# one\n{stage}---\nstages:\n  - name: b\n    kind: nope\n"));
    assert!(err.contains("p.yaml:7:1: error:") && err.contains("one YAML document"), "{err}");
    let err = rejected("two-docs-end", &format!("{stage}...\n{stage}"));
    assert!(err.contains("p.yaml:5:1: error:"), "{err}");
}

#[test]
fn input_that_is_not_utf8_is_located_at_its_first_bad_byte() {
    let s = Scratch::new("not-utf8");
    let mut bytes = b"stages:\n  - name: a\n    kind: util.sl".to_vec();
    bytes.push(0xff);
    bytes.extend_from_slice(b"eep\n");
    std::fs::write(s.path("p.yaml"), bytes).unwrap();
    let out = s.repro(&["run", "p.yaml", "-q"]);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("p.yaml:3:18: error:") && err.contains("not UTF-8 (invalid byte at offset 37)"), "{err}");
}
