use super::draw::*;
use super::legend::*;
use super::series::*;
use super::*;
use plotters::prelude::*;

#[test]
fn linear_tick_labels_carry_no_rounding_noise() {
    assert_eq!(axis_label(3.0 * 5e-6, false, 2e-5), "1.5e-5");
    assert_eq!(axis_label(0.1 + 0.2, false, 1.0), "0.3");
    assert_eq!(axis_label(-2.2e-17, false, 1.0), "0");
    assert_eq!(axis_label(250.0, false, 1000.0), "250");
}

fn layer(y: &str, color: Option<usize>) -> DataLayer {
    DataLayer {
        from: "t".into(),
        x: "x".into(),
        y: y.into(),
        group_by: Some("g".into()),
        label: "g = {g}".into(),
        style: Style::Line,
        filter: BTreeMap::new(),
        gaps: false,
        y_scale: 1.0,
        y_error: None,
        color,
    }
}

/// A 400 x 300 figure of `layers` with placeholder labels.
fn test_figure(layers: Vec<Layer>) -> FigureParams {
    FigureParams {
        title: "t".into(),
        x_label: "x".into(),
        y_label: "y".into(),
        log_x: false,
        log_y: false,
        x_range: None,
        y_range: None,
        width: 400,
        height: 300,
        legend: LegendPosition::UpperRight,
        layers,
    }
}

#[test]
fn a_filtered_group_keeps_its_colour_and_gaps_break_the_line() {
    // Group 0 has a row the filter drops between two kept ones; group 1 has only dropped
    // rows, group 2 kept ones: group 2 is still the third colour, and with `gaps` group 0
    // is drawn as two lines.
    let t = Table::new()
        .with_f64("x", vec![1.0, 2.0, 3.0, 1.0, 2.0, 1.0, 2.0])
        .with_f64("a", vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0])
        .with_f64("keep", vec![1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0])
        .with_f64("g", vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0]);
    let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
    let mut l = layer("a", Some(1));
    l.filter = BTreeMap::from([("keep".to_string(), 1.0)]);
    let joined = data_series(&l, &inputs).unwrap();
    assert_eq!(joined.iter().map(|s| s.color).collect::<Vec<_>>(), vec![Some(1), Some(3)]);
    assert!(joined.iter().all(|s| s.breaks.is_empty()));
    l.gaps = true;
    let broken = data_series(&l, &inputs).unwrap();
    assert_eq!(broken[0].points, vec![(1.0, 1.0), (3.0, 3.0)]);
    assert_eq!((broken[0].breaks.clone(), broken[1].breaks.clone()), (vec![1], vec![]));
    let fig = test_figure(vec![Layer::Data(l.clone())]);
    let lines = |series: &[Series]| render(&fig, series).unwrap().matches("<polyline").count();
    assert_eq!(lines(&broken), lines(&joined) + 1);
}

#[test]
fn each_point_carries_its_group_as_text_and_number() {
    // Two numeric groups (g = 0.25 and 1.5) and a guide without a group: the table has
    // the grouping column's name, the group as shown and as a number, empty and 0 for the
    // guide's points.
    let t = Table::new()
        .with_f64("x", vec![1.0, 2.0, 1.0])
        .with_f64("a", vec![1.0, 2.0, 3.0])
        .with_f64("g", vec![0.25, 0.25, 1.5]);
    let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
    let guide = GuideLayer {
        slope: 1.0,
        through: [1.0, 1.0],
        x_from: 1.0,
        x_to: 2.0,
        label: "guide".into(),
        style: Style::Dashed,
    };
    let fig = test_figure(vec![Layer::Data(layer("a", None)), Layer::Guide(guide)]);
    let out = Figure::run(&fig, &inputs).unwrap();
    let n = out.table.n_rows();
    assert_eq!(n, 3 + 50);
    let text = |c: &str| match out.table.column(c).unwrap() {
        ColumnData::Str(v) => v.clone(),
        _ => panic!("{c} is not text"),
    };
    assert_eq!(&text("group_by")[..4], ["g", "g", "g", ""]);
    assert_eq!(&text("group")[..4], ["0.25", "0.25", "1.5", ""]);
    assert_eq!(&out.table.f64_column("group_value").unwrap()[..4], [0.25, 0.25, 1.5, 0.0]);
    // Without a grouped layer there are no group columns.
    let mut plain = layer("a", None);
    plain.group_by = None;
    let out = Figure::run(&test_figure(vec![Layer::Data(plain)]), &inputs).unwrap();
    assert!(out.table.column("group_by").is_none());
}

#[test]
fn the_automatic_legend_goes_where_it_covers_nothing() {
    // A 700 x 400 plotting area: marks filling the upper half push the legend to a lower
    // corner; marks everywhere but the middle of the right side put it there.
    use SeriesLabelPosition as P;
    let labels = ["a curve", "another curve"];
    let area = (700u32, 400u32);
    let grid = |keep: &dyn Fn(i32, i32) -> bool| -> Vec<(i32, i32)> {
        (0..700)
            .step_by(7)
            .flat_map(|x| (0..400).step_by(7).map(move |y| (x, y)))
            .filter(|&(x, y)| keep(x, y))
            .collect()
    };
    let upper = grid(&|_, y| y < 200);
    assert!(matches!(least_covering_legend(&labels, area, &upper).0, P::LowerRight));
    let all_but_middle_right = grid(&|x, y| !(x > 450 && (150..250).contains(&y)));
    assert!(matches!(least_covering_legend(&labels, area, &all_but_middle_right).0, P::MiddleRight));
    // Nothing drawn: the first corner.
    assert!(matches!(least_covering_legend(&labels, area, &[]).0, P::UpperRight));
}

/// Ten horizontal lines across x in [0, 1] at a = 0 .. 9, group g the line's number.
fn ten_horizontal_lines() -> Table {
    let x: Vec<f64> = (0..10).flat_map(|_| [0.0, 1.0]).collect();
    let y: Vec<f64> = (0..10).flat_map(|i| [i as f64, i as f64]).collect();
    Table::new().with_f64("x", x).with_f64("a", y.clone()).with_f64("g", y)
}

#[test]
fn a_legend_that_covers_data_everywhere_inside_goes_outside_the_axes() {
    // Ten horizontal lines across the whole 400 x 300 figure leave no place inside the
    // axes for a legend of ten labels: the automatic legend is drawn right of the axes
    // (its labels start past the last x tick label), a pinned one stays inside.
    let t = ten_horizontal_lines();
    let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
    let mut l = layer("a", None);
    l.label = "curve number {g}".into();
    let mut fig = test_figure(vec![Layer::Data(l)]);
    fig.legend = LegendPosition::Auto;
    let series = data_series(
        match &fig.layers[0] {
            Layer::Data(d) => d,
            _ => unreachable!(),
        },
        &inputs,
    )
    .unwrap();
    let (_, covered) = draw(&fig, &series, false).unwrap();
    assert!(covered > 0);
    let label_x = |svg: &str| -> f64 {
        let at = svg.find(">\ncurve number 0\n<").expect("label drawn");
        let tag = &svg[svg[..at].rfind("<text").unwrap()..at];
        let x = tag.split("x=\"").nth(1).unwrap();
        x[..x.find('"').unwrap()].parse().unwrap()
    };
    // The rightmost point of the data's lines (those longer than a legend's 22 px sample).
    let line_end = |svg: &str| -> f64 {
        svg.split("<polyline")
            .skip(1)
            .map(|p| {
                let pts = p.split("points=\"").nth(1).unwrap();
                let xs: Vec<f64> = pts[..pts.find('"').unwrap()]
                    .split_whitespace()
                    .map(|xy| xy.split(',').next().unwrap().parse::<f64>().unwrap())
                    .collect();
                let (lo, hi) = xs.iter().fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
                if hi - lo > 30.0 {
                    hi
                } else {
                    f64::MIN
                }
            })
            .fold(f64::MIN, f64::max)
    };
    let outside = render(&fig, &series).unwrap();
    assert!(line_end(&outside) < label_x(&outside) - 30.0, "{} {}", line_end(&outside), label_x(&outside));
    fig.legend = LegendPosition::UpperRight;
    let inside = render(&fig, &series).unwrap();
    assert!(line_end(&inside) > label_x(&inside), "{} {}", line_end(&inside), label_x(&inside));
}

#[test]
fn a_legend_below_leaves_the_axes_the_figure_width_and_sits_under_them() {
    // Ten labels below a 400 x 300 figure: the data's lines span the axes' whole width
    // (the legend takes none of it), and every label is drawn under the x axis, in two
    // columns or more.
    let t = ten_horizontal_lines();
    let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
    let mut l = layer("a", None);
    l.label = "c{g}".into();
    let mut fig = test_figure(vec![Layer::Data(l)]);
    fig.legend = LegendPosition::Below;
    let Layer::Data(d) = &fig.layers[0] else { unreachable!() };
    let series = data_series(d, &inputs).unwrap();
    let svg = render(&fig, &series).unwrap();
    let attr = |tag: &str, name: &str| -> f64 {
        let v = tag.split(&format!("{name}=\"")).nth(1).unwrap();
        v[..v.find('"').unwrap()].parse().unwrap()
    };
    let label_at = |label: &str| -> (f64, f64) {
        let at = svg.find(&format!(">\n{label}\n<")).expect("label drawn");
        let tag = &svg[svg[..at].rfind("<text").unwrap()..at];
        (attr(tag, "x"), attr(tag, "y"))
    };
    // The data: polylines with two points at the same height, the longest.
    let lines: Vec<(f64, f64, f64)> = svg
        .split("<polyline")
        .skip(1)
        .filter_map(|p| {
            let pts = p.split("points=\"").nth(1)?;
            let xy: Vec<(f64, f64)> = pts[..pts.find('"')?]
                .split_whitespace()
                .map(|q| {
                    let (a, b) = q.split_once(',').unwrap();
                    (a.parse().unwrap(), b.parse().unwrap())
                })
                .collect();
            (xy.len() == 2 && xy[0].1 == xy[1].1).then(|| (xy[0].0, xy[1].0, xy[0].1))
        })
        .filter(|(a, b, _)| b - a > 200.0)
        .collect();
    // The ten curves and the x axis (the lowest); a legend on the right would leave the
    // curves about 200 px of the 400.
    assert_eq!(lines.len(), 11, "{lines:?}");
    let lowest = lines.iter().map(|l| l.2).fold(f64::MIN, f64::max);
    assert!(lines.iter().all(|(a, b, _)| b - a > 0.6 * 400.0), "{lines:?}");
    let labels: Vec<(f64, f64)> = (0..10).map(|i| label_at(&format!("c{i}"))).collect();
    assert!(labels.iter().all(|&(_, y)| y > lowest + 20.0), "{labels:?} under {lowest}");
    let columns: std::collections::BTreeSet<i64> = labels.iter().map(|&(x, _)| x as i64).collect();
    assert!(columns.len() >= 2, "{labels:?}");
}

#[test]
fn a_long_title_is_wrapped_to_the_figure_width() {
    let font: TextStyle = ("sans-serif", 22).into_font().into();
    let title =
        "Fig. 3.9: critical surface energy against thickness, loading to δ/R = 0.35, four friction coefficients";
    let lines = title_lines(title, &font, 764);
    assert!(lines.len() >= 2, "{lines:?}");
    assert_eq!(lines.join(" "), title);
    assert_eq!(title_lines("short", &font, 764), vec!["short".to_string()]);
}

#[test]
fn fit_labels_carry_the_error_to_two_significant_digits() {
    assert_eq!(with_uncertainty(0.666_712, 0.001_234), ("0.6667".into(), "0.0012".into()));
    assert_eq!(with_uncertainty(1.5049, 0.0871), ("1.505".into(), "0.087".into()));
    assert_eq!(with_uncertainty(12.34, 3.2), ("12.3".into(), "3.2".into()));
    assert_eq!(with_uncertainty(120.0, 31.0), ("120".into(), "31".into()));
    assert_eq!(with_uncertainty(0.5, 0.0), ("0.5".into(), "0".into()));
}

#[test]
fn error_bars_are_drawn_and_tabulated_with_their_points() {
    // Two groups, errors in column `e` (scaled with y); on a log y axis the point at
    // y <= 0 is dropped together with its error, and a bar reaching below zero runs to
    // the bottom of the axes.
    let t = Table::new()
        .with_f64("x", vec![1.0, 2.0, 3.0, 1.0, 2.0])
        .with_f64("a", vec![1.0, 2.0, -1.0, 4.0, 5.0])
        .with_f64("e", vec![0.1, 3.0, 0.1, 0.0, 0.5])
        .with_f64("g", vec![0.0, 0.0, 0.0, 1.0, 1.0]);
    let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
    let mut l = layer("a", None);
    (l.y_error, l.y_scale) = (Some("e".into()), 2.0);
    let series = data_series(&l, &inputs).unwrap();
    assert_eq!(series[0].errors, vec![0.2, 6.0, 0.2]);
    assert_eq!(series[1].errors, vec![0.0, 1.0]);
    let mut fig = test_figure(vec![Layer::Data(l.clone())]);
    fig.log_y = true;
    let out = Figure::run(&fig, &inputs).unwrap();
    assert_eq!(out.table.f64_column("y_error").unwrap(), vec![0.2, 6.0, 0.0, 1.0]);
    // Three bars (a zero error draws none), each a stem and two caps, more than without.
    let strokes = |svg: &str| svg.matches("<line").count() + svg.matches("<polyline").count();
    l.y_error = None;
    let plain = Figure::run(&test_figure(vec![Layer::Data(l.clone())]), &inputs).unwrap();
    let mut plain_fig = test_figure(vec![Layer::Data(l.clone())]);
    plain_fig.log_y = true;
    let plain_log = Figure::run(&plain_fig, &inputs).unwrap();
    assert!(plain.table.f64_column("y_error").is_err());
    assert_eq!(strokes(&out.artifacts["svg"]) - strokes(&plain_log.artifacts["svg"]), 3 * 3);
    l.y_error = Some("missing".into());
    let e = data_series(&l, &inputs).err().unwrap();
    assert!(format!("{e:#}").contains("y_error"), "{e:#}");
}

#[test]
fn layers_with_the_same_color_pair_their_curves() {
    let t = Table::new()
        .with_f64("x", vec![1.0, 2.0, 1.0, 2.0])
        .with_f64("a", vec![1.0, 2.0, 3.0, 4.0])
        .with_f64("b", vec![1.5, 2.5, 3.5, 4.5])
        .with_f64("g", vec![0.0, 0.0, 1.0, 1.0]);
    let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
    let colors =
        |l: &DataLayer| -> Vec<Option<usize>> { data_series(l, &inputs).unwrap().iter().map(|s| s.color).collect() };
    assert_eq!(colors(&layer("a", None)), vec![None, None]);
    assert_eq!(colors(&layer("b", Some(2))), vec![Some(2), Some(3)]);
    // Rendered: the first layer is blue and red (color 1); without `color` the second
    // layer takes the palette by position (red, green), with color 1 it repeats blue, red.
    let fig = |c: Option<usize>| test_figure(vec![Layer::Data(layer("a", Some(1))), Layer::Data(layer("b", c))]);
    let svg = |c| {
        let series: Vec<Series> =
            [layer("a", Some(1)), layer("b", c)].iter().flat_map(|l| data_series(l, &inputs).unwrap()).collect();
        render(&fig(c), &series).unwrap()
    };
    let count = |s: &str, rgb: &str| s.matches(&format!("stroke=\"#{rgb}\"")).count();
    let (free, paired) = (svg(None), svg(Some(1)));
    assert!(count(&free, "2CA02C") > 0);
    assert_eq!(count(&paired, "2CA02C"), 0);
    assert_eq!(count(&paired, "1F77B4"), 2 * count(&free, "1F77B4"));
}

#[test]
fn a_figure_table_carries_the_units_of_what_it_plots() {
    // A data layer of δ/R against F_bar (units R and F_c in docs/outputs.md) and a guide
    // line: the data's rows carry their columns' units, the guide's the axes'.
    let t = Table::new().with_f64("delta_over_R", vec![0.1, 0.2]).with_f64("F_bar", vec![1.0, 2.0]);
    let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
    let mut l = layer("F_bar", None);
    (l.x, l.group_by, l.label) = ("delta_over_R".into(), None, "data".into());
    let guide = GuideLayer {
        slope: 1.0,
        through: [0.1, 1.0],
        x_from: 0.1,
        x_to: 0.2,
        label: "guide".into(),
        style: Style::Dashed,
    };
    let fig = test_figure(vec![Layer::Data(l), Layer::Guide(guide)]);
    let out = <Figure as Kind>::run(&fig, &inputs).unwrap();
    let text = |name: &str| match out.table.column(name).unwrap() {
        ColumnData::Str(v) => v.clone(),
        _ => panic!("{name} is not text"),
    };
    let (names, xu, yu) = (text("y_name"), text("x_unit"), text("y_unit"));
    for i in 0..names.len() {
        assert_eq!((xu[i].as_str(), yu[i].as_str()), ("R", "F_c"), "row {i} ({})", names[i]);
    }
    assert!(names.iter().any(|n| n == "guide") && names.iter().any(|n| n == "F_bar"));
}

#[test]
fn a_grouped_figure_table_carries_the_unit_of_its_group_column() {
    // Curves of F_bar grouped by mu (unit 1) and by gamma (N/mm in docs/outputs.md): each
    // point carries its group column's unit; an ungrouped series an empty one.
    let t = Table::new()
        .with_f64("delta_over_R", vec![0.1, 0.2, 0.1, 0.2])
        .with_f64("F_bar", vec![1.0, 2.0, 1.5, 2.5])
        .with_f64("gamma", vec![0.0, 0.0, 1e-3, 1e-3])
        .with_f64("mu", vec![0.5, 0.5, 0.5, 0.5]);
    let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
    let grouped = |by: &str| {
        let mut l = layer("F_bar", None);
        (l.x, l.group_by, l.label) = ("delta_over_R".into(), Some(by.into()), format!("{by} = {{{by}}}"));
        Layer::Data(l)
    };
    let mut plain = layer("F_bar", None);
    (plain.x, plain.group_by, plain.label) = ("delta_over_R".into(), None, "all".into());
    let fig = test_figure(vec![grouped("gamma"), grouped("mu"), Layer::Data(plain)]);
    let out = <Figure as Kind>::run(&fig, &inputs).unwrap();
    let text = |name: &str| match out.table.column(name).unwrap() {
        ColumnData::Str(v) => v.clone(),
        _ => panic!("{name} is not text"),
    };
    let (by, unit) = (text("group_by"), text("group_unit"));
    let pairs: std::collections::BTreeSet<(&str, &str)> =
        by.iter().zip(&unit).map(|(b, u)| (b.as_str(), u.as_str())).collect();
    assert_eq!(pairs, std::collections::BTreeSet::from([("gamma", "N/mm"), ("mu", "1"), ("", "")]));
}

#[test]
fn a_label_lists_every_value_its_column_takes_on_the_curve() {
    // Group g = 0 is drawn at V0 = 2.2 and 2.7, group g = 1 at 3 only: the first label
    // names both speeds, not the first row's; the second names its one.
    let t = Table::new()
        .with_f64("x", vec![1.0, 2.0, 1.0])
        .with_f64("a", vec![1.0, 2.0, 3.0])
        .with_f64("V0", vec![2.7, 2.2, 3.0])
        .with_f64("g", vec![0.0, 0.0, 1.0]);
    let inputs = Inputs { tables: BTreeMap::from([("t".to_string(), &t)]) };
    let mut l = layer("a", None);
    l.label = "g = {g}, V0 = {V0}".into();
    let labels: Vec<String> = data_series(&l, &inputs).unwrap().into_iter().map(|s| s.label).collect();
    assert_eq!(labels, vec!["g = 0, V0 = 2.2 and 2.7", "g = 1, V0 = 3"]);
}
