//! A figure declares the range it shows (`x_range`), and the sweeps that feed it sample
//! that range (`{shown: n}`, plain or as an adaptive sweep's initial grid) or are checked
//! against it: warnings for parts of the range without points and for points that nothing
//! shows; located errors for a `shown` sweep that no figure gives a range.

use crate::common;
use common::Scratch;
use repro::pipeline::parse;
use repro::pipeline::spec::{self, Pipeline};

fn parse(text: &str) -> Result<Pipeline, String> {
    parse::parse("p.yaml", text, &repro::stages::registry()).map_err(|e| e.to_string())
}

/// The sorted distinct values of `param` over a stage's points.
fn values(p: &Pipeline, stage: &str, param: &str) -> Vec<f64> {
    let mut v: Vec<f64> = p.stage(stage).unwrap().points.iter().map(|pt| pt.params[param].as_f64().unwrap()).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

fn persson_and_figure(sweep: &str, figure_extra: &str) -> String {
    format!(
        "stages:
  - name: mu
    kind: theory.persson
    params:
      inv_k: 10
      V0: {sweep}
  - name: fig
    kind: figure
    needs: [mu]
    params:
      title: t
      x_label: V0
      y_label: mu
{figure_extra}      layers:
        - data: {{from: mu, x: V0, y: mu_star}}
"
    )
}

#[test]
fn a_shown_sweep_samples_the_figures_range_exactly_as_the_equivalent_grid() {
    let shown = parse(&persson_and_figure("{shown: 7}", "      log_x: true\n      x_range: [0.001, 1000]\n")).unwrap();
    let grid =
        parse(&persson_and_figure("{logspace: [-3, 3, 7]}", "      log_x: true\n      x_range: [0.001, 1000]\n"))
            .unwrap();
    assert_eq!(values(&shown, "mu", "V0"), vec![0.001, 0.01, 0.1, 1.0, 10.0, 100.0, 1000.0]);
    // The same canonical parameters, hence the same cache keys.
    let a: Vec<_> = shown.stage("mu").unwrap().points.iter().map(|p| p.params.clone()).collect();
    let b: Vec<_> = grid.stage("mu").unwrap().points.iter().map(|p| p.params.clone()).collect();
    assert_eq!(a, b);
    assert!(shown.warnings.is_empty(), "{:?}", shown.warnings);
    // A linear axis is sampled linearly.
    let lin = parse(&persson_and_figure("{shown: 5}", "      x_range: [1, 3]\n")).unwrap();
    assert_eq!(values(&lin, "mu", "V0"), vec![1.0, 1.5, 2.0, 2.5, 3.0]);
}

#[test]
fn several_figures_showing_one_parameter_are_sampled_over_the_union_of_their_ranges() {
    let mut text = persson_and_figure("{shown: 4}", "      log_x: true\n      x_range: [0.01, 1]\n");
    text.push_str(
        "  - name: fig2
    kind: figure
    needs: [mu]
    params: {title: t, x_label: V0, y_label: mu, log_x: true, x_range: [0.1, 10],
             layers: [{data: {from: mu, x: V0, y: mu_star}}]}
",
    );
    let p = parse(&text).unwrap();
    assert_eq!(values(&p, "mu", "V0"), vec![0.01, 0.1, 1.0, 10.0]);
}

#[test]
fn a_shown_sweep_that_no_figure_gives_a_range_is_refused_at_its_line() {
    let e = parse(&persson_and_figure("{shown: 7}", "      log_x: true\n")).unwrap_err();
    assert!(e.starts_with("p.yaml:6:"), "{e}");
    assert!(e.contains("no stage declares the range it shows of `V0` from `mu`"), "{e}");
    assert!(e.contains("x_range"), "{e}");
    // A count that is not an integer of at least 2.
    let e = parse(&persson_and_figure("{shown: 1}", "      x_range: [1, 3]\n")).unwrap_err();
    assert!(e.starts_with("p.yaml:6:") && e.contains("integer from 2"), "{e}");
    // One log and one linear axis: which to sample is ambiguous.
    let mut text = persson_and_figure("{shown: 4}", "      log_x: true\n      x_range: [0.01, 1]\n");
    text.push_str(
        "  - name: fig_lin
    kind: figure
    needs: [mu]
    params: {title: t, x_label: V0, y_label: mu, x_range: [0.1, 10], layers: [{data: {from: mu, x: V0, y: mu_star}}]}
",
    );
    let e = parse(&text).unwrap_err();
    assert!(e.contains("`fig` shows it on a log axis and `fig_lin` on a linear one"), "{e}");
}

#[test]
fn an_adaptive_sweep_starts_from_the_range_shown() {
    let p = parse(&persson_and_figure(
        "{adaptive: {shown: 7, y: mu_star, tol: 0.01}}",
        "      log_x: true\n      x_range: [0.001, 1000]\n",
    ))
    .unwrap();
    let a = p.stage("mu").unwrap().adaptive.clone().unwrap();
    assert!(a.log && a.initial == 7);
    assert!((a.from + 3.0).abs() < 1e-12 && (a.to - 3.0).abs() < 1e-12, "{} {}", a.from, a.to);
    assert_eq!(values(&p, "mu", "V0"), vec![0.001, 0.01, 0.1, 1.0, 10.0, 100.0, 1000.0]);
}

#[test]
fn a_sweep_that_leaves_part_of_the_range_shown_empty_is_warned_of_at_the_range() {
    let p = parse(&persson_and_figure("{logspace: [-2, 2, 5]}", "      log_x: true\n      x_range: [0.001, 100]\n"))
        .unwrap();
    assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
    let w = p.warnings[0].to_string();
    // Line 15 is the figure's `x_range`.
    assert!(w.starts_with("p.yaml:15:") && w.contains(": warning: "), "{w}");
    assert!(w.contains("`fig` shows `V0` of `mu` from 0.001 to 100") && w.contains("from 0.01 to 100"), "{w}");
}

#[test]
fn points_outside_every_range_shown_are_warned_of_unless_another_stage_reads_them() {
    let text = persson_and_figure("{logspace: [-3, 3, 7]}", "      log_x: true\n      x_range: [0.01, 100]\n");
    let p = parse(&text).unwrap();
    assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
    let w = p.warnings[0].to_string();
    assert!(w.starts_with("p.yaml:2:"), "{w}");
    assert!(w.contains("computes 2 of its 7 values of `V0` (0.001, 1000) outside"), "{w}");
    // A fit over the whole sweep reads them too: no warning.
    let mut with_fit = text.clone();
    with_fit.push_str(
        "  - name: fit
    kind: fit.powerlaw
    needs: [mu]
    params: {from: mu, x: V0, y: mu_star, x_min: 0.001, x_max: 0.01}
",
    );
    let p = parse(&with_fit).unwrap();
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    // A single value is a point in the figure, not a sweep over its range.
    let p = parse(&persson_and_figure("5", "      log_x: true\n      x_range: [0.01, 100]\n")).unwrap();
    assert!(p.warnings.is_empty(), "{:?}", p.warnings);
}

#[test]
fn the_thesis_pipeline_samples_what_its_figures_show_and_nothing_else() {
    let p = parse::load(std::path::Path::new("pipelines/thesis.yaml"), &repro::stages::registry()).unwrap();
    assert!(p.warnings.is_empty(), "{}", p.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>().join("\n"));
    // The sweeps turned into `shown` kept their points (and so their cache keys).
    let grid = |a: f64, b: f64, n: usize| -> Vec<f64> { (0..n).map(|i| spec::spaced(true, a, b, n, i)).collect() };
    assert_eq!(values(&p, "persson_brener", "V_PB"), grid(-4.0, 10.0, 57));
    assert_eq!(values(&p, "bem_large_load", "V0"), grid(-2.0, 2.0, 17));
    assert_eq!(values(&p, "max_vs_load", "W"), grid(-1.0, 2.0, 10));
    assert_eq!(values(&p, "rolling", "V0"), grid(-4.0, 3.0, 29));
    assert_eq!(values(&p, "pb_power_law", "V_PB"), grid(-4.0, 12.0, 65));
    assert_eq!(values(&p, "rolling_power_law", "V0"), grid(-4.0, 6.0, 41));
    // The adaptive ones start from the range shown.
    for (stage, range, initial) in [
        ("friction_maps", (-3.0, 3.0), 13),
        ("persson", (-3.0, 3.0), 13),
        ("persson_k10", (-2.0, 2.0), 9),
        ("rolling_sls_wide", (-4.0, 6.0), 11),
    ] {
        let a = p.stage(stage).unwrap().adaptive.clone().unwrap();
        assert_eq!(((a.from, a.to), a.initial), (range, initial), "{stage}");
    }
}

#[test]
fn widening_the_range_shown_computes_only_the_new_points() {
    let s = Scratch::new("ranges-shown-widen");
    // One point per decade over 1e-2..1e2, then over 1e-3..1e3.
    s.write("p.yaml", &persson_and_figure("{shown: 5}", "      log_x: true\n      x_range: [0.01, 100]\n"));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(r.count(Some("mu"), "computed"), 5);
    s.write("p.yaml", &persson_and_figure("{shown: 7}", "      log_x: true\n      x_range: [0.001, 1000]\n"));
    let (code, err, r) = s.run("p.yaml", &["--dry-run"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!((r.count(Some("mu"), "would_run"), r.count(Some("mu"), "cached")), (2, 5));
    let (code, err, r) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!((r.count(Some("mu"), "computed"), r.count(Some("mu"), "cached")), (2, 5));
    assert_eq!(s.table("mu").height(), 7);
    // A sweep the figure does not cover is reported on the command line, and still runs.
    s.write(
        "p.yaml",
        &persson_and_figure("{logspace: [-2, 2, 5]}", "      log_x: true\n      x_range: [0.001, 1000]\n"),
    );
    let (code, err, _) = s.run("p.yaml", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning: `fig` shows `V0` of `mu` from 0.001 to 1000"), "{err}");
}

#[test]
fn every_committed_pipeline_loads_without_warnings() {
    let registry = repro::stages::registry();
    let mut files: Vec<_> = std::fs::read_dir("pipelines")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "yaml"))
        .collect();
    files.sort();
    assert!(files.len() >= 5, "{files:?}");
    for f in files {
        let p = parse::load(&f, &registry).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        assert!(p.warnings.is_empty(), "{}: {:?}", f.display(), p.warnings);
    }
}

#[test]
fn the_stage_graph_draws_the_figure_that_fixes_a_sweeps_range() {
    let p = parse(&persson_and_figure("{shown: 5}", "      log_x: true\n      x_range: [0.01, 100]\n")).unwrap();
    assert_eq!(p.stage("mu").unwrap().ranges_from, vec!["fig".to_string()]);
    assert!(p.stage("fig").unwrap().ranges_from.is_empty());
    let dot = repro::pipeline::graph::to_dot(&p);
    assert!(dot.contains("\"mu\" -> \"fig\";"), "{dot}");
    assert!(dot.contains("\"fig\" -> \"mu\" [style=dashed, constraint=false, label=\"range\"];"), "{dot}");
    // An explicit grid takes no range from the figure.
    let p = parse(&persson_and_figure("{logspace: [-2, 2, 5]}", "      log_x: true\n      x_range: [0.01, 100]\n"))
        .unwrap();
    assert!(p.stage("mu").unwrap().ranges_from.is_empty());
}
