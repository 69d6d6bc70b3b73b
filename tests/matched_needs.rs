//! A stage that needs another row by row (`needs: [{stage: S, match: [PARAM, ...]}]`): each
//! point reads only the rows of the points of S whose parameters match its own, and its key
//! depends on those rows alone (read from the run report and the tables, not assumed).

use crate::common;
use common::{column, rejected, Scratch};
use serde_json::json;

/// `up` sweeps x (rounded to `round` decimals); `down` reads, per point, the rows of `up`
/// with the same x; `whole` reads all of `up`.
fn pipeline(up_xs: &str, round: i32, down_xs: &str) -> String {
    format!(
        "stages:\n  - name: up\n    kind: util.sleep\n    params: {{x: {up_xs}, round: {round}}}\n  \
         - name: down\n    kind: util.sleep\n    needs: [{{stage: up, match: [x]}}]\n    params: {{x: {down_xs}}}\n  \
         - name: whole\n    kind: util.sleep\n    needs: [up]\n    params: {{x: 7}}\n"
    )
}

#[test]
fn each_point_reads_only_the_rows_that_match_it() {
    let s = Scratch::new("matched-rows");
    s.write("p.yaml", &pipeline("[1, 2, 3]", 3, "[1, 2, 3]"));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(None, "computed"), 7);
    let down = s.table("down");
    assert_eq!(column(&down, "x"), vec![1.0, 2.0, 3.0]);
    // One row each, the one with its own x (util.sleep sums the x of what it reads).
    assert_eq!(column(&down, "upstream_rows"), vec![1.0, 1.0, 1.0]);
    assert_eq!(column(&down, "upstream_x"), vec![1.0, 2.0, 3.0]);
    // A stage that needs `up` whole reads all of it.
    assert_eq!(column(&s.table("whole"), "upstream_x"), vec![6.0]);
}

#[test]
fn a_new_upstream_point_recomputes_only_the_points_that_match_it() {
    let s = Scratch::new("matched-new-point");
    s.write("p.yaml", &pipeline("[1, 2, 3]", 3, "[1, 2, 3, 5]"));
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    // x = 5 matches nothing upstream yet: it read no rows.
    assert_eq!(column(&s.table("down"), "upstream_rows"), vec![1.0, 1.0, 1.0, 0.0]);
    s.write("p.yaml", &pipeline("[1, 2, 3, 5]", 3, "[1, 2, 3, 5]"));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(Some("up"), "computed"), 1);
    assert_eq!(r.count(Some("down"), "computed"), 1, "{:?}", r.0);
    assert_eq!(r.count(Some("down"), "cached"), 3);
    assert_eq!(r.task("down", "x=5")["reason"], json!({"why": "input_changed", "stages": ["up"]}));
    assert_eq!(column(&s.table("down"), "upstream_x"), vec![1.0, 2.0, 3.0, 5.0]);
    // The stage that reads all of `up` sees a new table.
    assert_eq!(r.count(Some("whole"), "computed"), 1);
}

#[test]
fn a_changed_upstream_row_recomputes_only_the_points_that_read_it() {
    let s = Scratch::new("matched-changed-row");
    s.write("p.yaml", &pipeline("[1.44, 2, 3]", 3, "[1.44, 2, 3]"));
    s.run("p.yaml", &[]);
    // Rounding to one decimal changes the output of x = 1.44 alone (1.4); every point of
    // `up` is recomputed (its parameters changed), but only x = 1.44 of `down` reads a
    // changed row.
    s.write("p.yaml", &pipeline("[1.44, 2, 3]", 1, "[1.44, 2, 3]"));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(Some("up"), "computed"), 3);
    assert_eq!(r.count(Some("down"), "computed"), 1, "{:?}", r.0);
    assert_eq!(r.task("down", "x=1.44")["reason"], json!({"why": "input_changed", "stages": ["up"]}));
    assert_eq!(column(&s.table("down"), "upstream_x"), vec![1.4, 2.0, 3.0]);
    // A rerun computes nothing.
    let (_, _, r) = s.run("p.yaml", &[]);
    assert_eq!(r.count(None, "computed"), 0);
}

#[test]
fn a_point_that_matches_nothing_is_warned_of() {
    let s = Scratch::new("matched-warning");
    s.write("p.yaml", &pipeline("[1, 2]", 3, "[1, 2, 4]"));
    let out = s.repro(&["run", "p.yaml", "-q", "--dry-run"]);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("p.yaml:7:32: warning:"), "{err}");
    assert!(err.contains("1 of its 3 points match no point of `up` on x"), "{err}");
}

#[test]
fn a_wrong_matched_need_is_located_and_explained() {
    let up = "stages:\n  - name: up\n    kind: util.sleep\n    params: {x: [1, 2]}\n";
    // A parameter that the needed stage's points do not have.
    let err = rejected(
        "matched-no-param",
        &format!("{up}  - name: down\n    kind: util.sleep\n    needs: [{{stage: up, match: [x, round]}}]\n    params: {{x: 1}}\n"),
    );
    assert!(err.contains("p.yaml:7:32: error:"), "{err}");
    assert!(err.contains("`match` names `round`, which is not a parameter of every point"), "{err}");
    // A stage that does not exist, with a suggestion.
    let err = rejected(
        "matched-no-stage",
        &format!(
            "{up}  - name: down\n    kind: util.sleep\n    needs: [{{stage: upp, match: [x]}}]\n    params: {{x: 1}}\n"
        ),
    );
    assert!(err.contains("needs `upp`, which names no stage (did you mean `up`?)"), "{err}");
    // A mapping without `match`, and an unknown key.
    let err = rejected(
        "matched-no-match",
        &format!(
            "{up}  - name: down\n    kind: util.sleep\n    needs: [{{stage: up, on: [x]}}]\n    params: {{x: 1}}\n"
        ),
    );
    assert!(err.contains("unknown field `on` in a `needs` entry (expected one of: stage, match)"), "{err}");
    assert!(err.contains("need `up` as a mapping needs `match`"), "{err}");
    // The same stage twice.
    let err = rejected(
        "matched-twice",
        &format!("{up}  - name: down\n    kind: util.sleep\n    needs: [up, {{stage: up, match: [x]}}]\n    params: {{x: 1}}\n"),
    );
    assert!(err.contains("`needs` names `up` twice"), "{err}");
}

#[test]
fn the_graph_labels_a_need_read_row_by_row() {
    let s = Scratch::new("matched-dag");
    s.write("p.yaml", &pipeline("[1, 2]", 3, "[1, 2]"));
    let out = s.repro(&["dag", "p.yaml"]);
    let dot = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(dot.contains("\"up\" -> \"down\" [label=\"by x\"];"), "{dot}");
    assert!(dot.contains("\"up\" -> \"whole\";"), "{dot}");
}
