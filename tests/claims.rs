//! The thesis' claims as data (`claim`, `claims`): a claim that holds, one that differs as
//! recorded, a qualitative one, and a regression (recorded as reproduced, no longer so: exit
//! code 5 and a message naming it), through the command line on Maugis' pull-off (cheap:
//! a few closed-form-limit points). The numbers: Maugis-Dugdale pull-off -1.9506 at
//! lambda = 0.1 and -1.5016 at lambda = 10 (`tables/maugis_pulloff.parquet`), DMT -2 and
//! JKR -1.5.

use crate::common;
use common::{column, strings, Scratch};

/// A pipeline with Maugis' pull-off at three lambdas and four claims on it; `jkr_tol` is the
/// relative tolerance of the JKR-limit claim and `jkr_expect` its recorded verdict.
fn pipeline(jkr_tol: f64, jkr_expect: &str) -> String {
    format!(
        r#"
stages:
  - name: pulloff
    kind: theory.maugis_pulloff
    params:
      lambda: [0.1, 1, 10]

  - name: c_jkr
    kind: claim
    publish: false
    needs: [pulloff]
    params:
      id: jkr
      source: "Fig. 2.5"
      statement: "JKR limit at large lambda"
      quantity: {{from: pulloff, y: P_bar_pulloff, x: lambda, x_min: 9, aggregate: value}}
      thesis: {{value: -1.5, rel_tol: {jkr_tol}}}
      independent: {{value: -1.5, source: "JKR closed form"}}
      expect: {jkr_expect}
      reason: "the tolerance is tighter than the distance to the limit at lambda = 10"

  - name: c_dmt
    kind: claim
    publish: false
    needs: [pulloff]
    params:
      id: dmt
      source: "Fig. 2.5"
      statement: "DMT's -2 already at lambda = 0.1"
      quantity: {{from: pulloff, y: P_bar_pulloff, filter: {{lambda: 0.1}}, aggregate: value}}
      thesis: {{value: -2, rel_tol: 0.001}}
      expect: differs
      reason: "lambda = 0.1 is not yet the DMT limit"

  - name: c_monotone
    kind: claim
    publish: false
    needs: [pulloff]
    params:
      id: monotone
      source: "Fig. 2.6"
      statement: "the pull-off rises from DMT to JKR"
      quantity: {{from: pulloff, y: P_bar_pulloff, x: lambda, aggregate: increasing}}
      thesis: {{value: 1}}
      expect: reproduced

  - name: claims
    kind: claims
    needs: [c_jkr, c_dmt, c_monotone]
    params:
      claims: [c_jkr, c_dmt, c_monotone]
"#
    )
}

#[test]
fn verdicts_are_counted_and_tabled() {
    let s = Scratch::new("claims-verdicts");
    s.write("p.yaml", &pipeline(0.01, "reproduced"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("2 of 3 thesis claims reproduced, 1 differ (explained)"), "{err}");
    // The claim stages are not published on their own; their summary is.
    assert!(!s.path("tables/c_jkr.parquet").exists());
    let df = repro::pipeline::table::read_parquet(&s.path("tables/claims.parquet")).unwrap();
    assert_eq!(strings(&df, "id"), ["jkr", "dmt", "monotone"]);
    assert_eq!(strings(&df, "verdict"), ["reproduced", "differs", "reproduced"]);
    let value = column(&df, "value");
    assert!((value[0] + 1.5016).abs() < 1e-3, "{value:?}");
    assert!((value[1] + 1.9506).abs() < 1e-3, "{value:?}");
    assert_eq!(value[2], 1.0);
    assert_eq!(strings(&df, "thesis")[0], "-1.5 ± 1 %");
    assert_eq!(column(&df, "has_independent"), [1.0, 0.0, 0.0]);
    assert_eq!(column(&df, "regression"), [0.0, 0.0, 0.0]);
}

#[test]
fn a_run_of_some_targets_gives_the_verdict_of_the_claims_it_reached() {
    // `--target` short of the `claims` stage: the line counts the claims the run reached and
    // says how many it did not run. Before, such a run printed no verdict at all.
    let s = Scratch::new("claims-targets");
    s.write("p.yaml", &pipeline(0.01, "reproduced"));
    let (code, err, _) = s.run("p.yaml", &["--target", "c_jkr", "--target", "c_dmt"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("1 of 2 claims in scope reproduced, 1 differ (explained), 1 not run"), "{err}");
    // A run of no claim prints none; a whole run the pipeline's own line.
    let (_, err, _) = s.run("p.yaml", &["--target", "pulloff"]);
    assert!(!err.contains("claims in scope"), "{err}");
    let (_, err, _) = s.run("p.yaml", &[]);
    assert!(err.contains("2 of 3 thesis claims reproduced") && !err.contains("in scope"), "{err}");
}

#[test]
fn a_calibrated_claim_is_counted_apart_and_regresses_if_its_calibration_breaks() {
    // Recorded as calibrated (the model tuned to it), a claim that holds reads `calibrated`,
    // not `reproduced`, in the table and the verdict line; one that stops holding is a
    // regression, as a reproduced one is.
    let s = Scratch::new("claims-calibrated");
    s.write("p.yaml", &pipeline(0.01, "calibrated"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("1 of 3 thesis claims reproduced, 1 calibrated (the model tuned to them), 1 differ (explained)"),
        "{err}"
    );
    let df = repro::pipeline::table::read_parquet(&s.path("tables/claims.parquet")).unwrap();
    assert_eq!(strings(&df, "verdict"), ["calibrated", "differs", "reproduced"]);
    s.write("p.yaml", &pipeline(0.0001, "calibrated"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 5, "{err}");
    assert!(err.contains("1 regressed"), "{err}");
}

#[test]
fn a_claim_that_stops_holding_is_a_regression() {
    let s = Scratch::new("claims-regression");
    s.write("p.yaml", &pipeline(0.01, "reproduced"));
    assert_eq!(s.run("p.yaml", &[]).0, 0);
    // Tighten the JKR claim below its distance (1.1e-3 relative): recorded as reproduced, it
    // now differs.
    s.write("p.yaml", &pipeline(0.0001, "reproduced"));
    let (code, err, report) = s.run("p.yaml", &[]);
    assert_eq!(code, 5, "{err}");
    assert!(err.contains("1 of 3 thesis claims reproduced, 1 differ (explained), 1 regressed"), "{err}");
    assert!(
        err.contains("repro: regression: c_jkr: claim jkr (Fig. 2.5: JKR limit at large lambda) was reproduced"),
        "{err}"
    );
    let regressions = report.0["regressions"].as_array().unwrap();
    assert_eq!(regressions.len(), 1);
    // Recorded as differing, the same result is no regression.
    s.write("p.yaml", &pipeline(0.0001, "differs"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("1 of 3 thesis claims reproduced, 2 differ (explained)"), "{err}");
}

#[test]
fn a_claim_expected_to_differ_needs_a_reason_and_a_tolerance_needs_a_value() {
    let s = Scratch::new("claims-invalid");
    let yaml = pipeline(0.01, "reproduced").replace("      reason: \"lambda = 0.1 is not yet the DMT limit\"\n", "");
    s.write("p.yaml", &yaml);
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("stage `c_dmt` (claim): parameter `reason`: a claim expected to differ needs its reason"),
        "{err}"
    );
    s.write("p.yaml", &pipeline(0.01, "reproduced").replace("thesis: {value: 1}", "thesis: {rel_tol: 0.1}"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("a tolerance needs a `value`"), "{err}");
}

#[test]
fn the_thesis_pipeline_records_every_claim_with_a_reason_where_it_differs() {
    // At least 40 claims, every chapter covered, and each one recorded as differing carries
    // its reason and a docs link.
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/pipelines/thesis.yaml")).unwrap();
    let p = repro::pipeline::parse::load(
        std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/pipelines/thesis.yaml")),
        &repro::stages::registry(),
    )
    .unwrap();
    let claims: Vec<_> = p.stages.iter().filter(|s| s.kind == "claim").collect();
    assert!(claims.len() >= 40, "{} claims", claims.len());
    for chapter in ["ch2.", "appA.", "ch3.", "ch4.", "ch5."] {
        assert!(claims.iter().any(|c| c.points[0].params["id"].as_str().unwrap().starts_with(chapter)), "{chapter}");
    }
    for c in &claims {
        let params = &c.points[0].params;
        if params["expect"] == "differs" {
            assert!(params["docs"].as_str().is_some_and(|d| d.starts_with("docs/")), "{}", c.name);
        }
    }
    // docs/claims.md lists every claim.
    let docs = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/claims.md")).unwrap();
    for c in &claims {
        let id = c.points[0].params["id"].as_str().unwrap();
        assert!(docs.contains(&format!("`{id}`")), "docs/claims.md does not list {id}");
    }
    let summary = p.stages.iter().find(|s| s.kind == "claims").unwrap();
    assert_eq!(summary.points[0].params["claims"].as_array().unwrap().len(), claims.len());
    assert!(text.contains("kind: claims"));
}
