//! `repro report`: the HTML page lists every figure of the pipeline (inlined SVG) and every
//! claim with its verdict, the last run's timeline, and provenance, and makes no request
//! (a Content-Security-Policy of `default-src 'none'`, no external reference). The browser
//! check of the same page is `make report-check` (.ci/report_check.mjs), run by CI.

use crate::common;
use common::Scratch;

const PIPELINE: &str = r#"
stages:
  - name: pulloff
    kind: theory.maugis_pulloff
    params:
      lambda: [0.1, 1, 10]

  - name: fig2_x
    kind: figure
    needs: [pulloff]
    params:
      title: "Fig. 2.9: pull-off vs λ"
      x_label: "λ"
      y_label: "P"
      log_x: true
      layers:
        - data: {from: pulloff, x: lambda, y: P_bar_pulloff, label: "Maugis"}

  - name: extra
    kind: figure
    needs: [pulloff]
    params:
      title: "A check of our own at λ = {lambda}"
      x_label: "λ"
      y_label: "P"
      layers:
        - data: {from: pulloff, x: lambda, y: P_bar_pulloff, label: "Maugis", filter: {lambda: 1}}

  - name: c_jkr
    kind: claim
    publish: false
    needs: [pulloff]
    params:
      id: jkr
      source: "Fig. 2.9"
      statement: "JKR limit <at large λ>"
      quantity: {from: pulloff, y: P_bar_pulloff, x: lambda, x_min: 9, aggregate: value}
      thesis: {value: -1.5, rel_tol: 0.01}
      expect: reproduced

  - name: c_dmt
    kind: claim
    publish: false
    needs: [pulloff]
    params:
      id: dmt
      source: "Fig. 2.9"
      statement: "DMT at λ = 0.1"
      quantity: {from: pulloff, y: P_bar_pulloff, x: lambda, x_max: 0.11, aggregate: value}
      thesis: {value: -2, rel_tol: 0.001}
      expect: differs
      reason: "not yet the limit"
      docs: docs/claims.md

  - name: claims
    kind: claims
    needs: [c_jkr, c_dmt]
    params:
      claims: [c_jkr, c_dmt]
"#;

#[test]
fn the_report_shows_every_figure_and_claim_and_makes_no_request() {
    let s = Scratch::new("report");
    s.write("p.yaml", PIPELINE);
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    // Another pipeline file and a run with settings use the cache since: the report's cost
    // is still that of p.yaml's run, which produced what it shows.
    s.write(
        "other.yaml",
        "stages:\n  - name: lj\n    kind: theory.lennard_jones\n    params: {z_min: 0.9, z_max: 3.0, n: 7}\n",
    );
    assert_eq!(s.run("other.yaml", &[]).0, 0);
    assert_eq!(s.run("p.yaml", &["-S", "fig2_x.y_label=Q"]).0, 0);
    let out = s.repro(&["report", "p.yaml", "--out", "rep/index.html"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("(2 figures, 2 claims)"), "{stdout}");
    let html = std::fs::read_to_string(s.path("rep/index.html")).unwrap();
    assert!(html.contains("content=\"default-src 'none'; style-src 'unsafe-inline'; img-src data:\""));
    assert!(!html.contains("src=\"http") && !html.contains("href=\"http"), "an external reference");
    assert!(html.contains("1 of 2 thesis claims reproduced, 1 differ (explained)"));
    // Figures by chapter, inlined, with their claims; a figure outside the thesis apart.
    let ch2 = html.find("id=\"chapter-2\"").unwrap();
    let other = html.find("id=\"chapter-other\"").unwrap();
    let fig = html.find("id=\"figure-fig2_x\"").unwrap();
    let extra = html.find("id=\"figure-extra\"").unwrap();
    assert!(ch2 < fig && fig < other && other < extra);
    assert!(html[fig..extra].contains("<svg") && html[fig..extra].contains("<code>jkr</code>"));
    // A caption reads the title as drawn, its `{column}` filled in.
    assert!(html[extra..].contains("<b>A check of our own at λ = 1</b>"), "{}", &html[extra..extra + 400]);
    assert!(html[fig..extra].contains("computed from pulloff (theory.maugis_pulloff@v2)"));
    let key_at = html[fig..extra].find("task key <code>").unwrap() + fig + "task key <code>".len();
    assert!(html[key_at..key_at + 64].bytes().all(|b| b.is_ascii_hexdigit()), "the figure's task key");
    // Text is escaped, the claims table has one row per claim (and again under the figures).
    assert!(html.contains("JKR limit &lt;at large λ&gt;"));
    // Ids are unique: the rows repeated under the figures carry none.
    assert_eq!(html.matches("<tr id=\"claim-dmt\">").count(), 1);
    assert_eq!(html.matches("<code>dmt</code>").count(), 3);
    // Each claim says what it compared.
    assert!(html.contains("value of pulloff.P_bar_pulloff against lambda for lambda in [-∞, 0.11]"), "the quantity");
    assert!(html.contains("class=\"differs\">differs</td>") && html.contains("not yet the limit"));
    // The last run computed everything: its timeline has a bar per computed task.
    assert!(html.contains("class=\"timeline\""));
    assert!(html.contains("The latest run of <code>p.yaml</code> without settings"), "the cost's run");
    let cost = &html[html.find("id=\"cost\"").unwrap()..];
    assert!(cost.contains(" computed, 0 from the cache"), "the cost of p.yaml's first run: {}", &cost[..400]);
    assert!(html.matches("<rect ").count() >= 3 + 2, "timeline bars");
    assert!(html.contains("blake3 ") && html.contains("git commit"));
    // The stage graph: a panel per chapter, a box per stage but the claims, an arrow per
    // dependency within a panel. pulloff belongs to Chapter 2, whose figure reads it first;
    // `extra` (no thesis number) to the further panel, its need on pulloff named in its
    // tooltip.
    let panels: Vec<&str> = html.split("<h3 id=\"graph-").skip(1).collect();
    assert_eq!(panels.iter().map(|p| &p[..p.find('"').unwrap()]).collect::<Vec<_>>(), ["2", "other"]);
    let graph = |p: &str| p[p.find("class=\"graph\"").unwrap()..p.find("</svg>").unwrap()].to_string();
    let (two, other) = (graph(panels[0]), graph(panels[1]));
    assert_eq!((two.matches("<rect ").count(), other.matches("<rect ").count()), (2, 1));
    assert!(two.contains("data-edges=\"1\"") && two.matches("class=\"edge\"").count() == 1, "{two}");
    assert!(two.contains("marker-end=\"url(#arrow-2)\""), "{two}");
    assert!(other.contains("reads pulloff (2)") && other.matches("class=\"edge\"").count() == 0, "{other}");
}

#[test]
fn the_report_of_a_partial_run_marks_what_it_did_not_reach() {
    // A run of one figure: the report still shows it, and says which figure and which
    // claims the run did not reach, instead of refusing.
    let s = Scratch::new("report-partial");
    s.write("p.yaml", PIPELINE);
    let (code, err, _) = s.run("p.yaml", &["--target", "fig2_x"]);
    assert_eq!(code, 0, "{err}");
    let out = s.repro(&["report", "p.yaml", "--out", "rep/index.html"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let html = std::fs::read_to_string(s.path("rep/index.html")).unwrap();
    assert!(html.contains(
        "0 of 2 thesis claims reproduced, 0 differ (explained), 2 not run (the last run did not reach them)"
    ));
    assert_eq!(
        html.matches("class=\"notrun\">not run</td>").count(),
        2 + 2,
        "both claims, in the table and under fig2_x"
    );
    let extra = html.find("id=\"figure-extra\"").unwrap();
    assert!(html[extra..].contains("not produced: the last run did not reach it"));
    assert!(html[html.find("id=\"figure-fig2_x\"").unwrap()..extra].contains("<svg"));
}

#[test]
fn the_report_of_a_pipeline_not_yet_run_says_what_to_do() {
    let s = Scratch::new("report-not-run");
    s.write("p.yaml", PIPELINE);
    let out = s.repro(&["report", "p.yaml", "--out", "rep/index.html"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("run the pipeline first"), "{err}");
    assert!(!s.path("rep/index.html").exists());
}
