//! Drawing a figure with plotters (SVG): the axes (log axes as log10 values labelled in
//! powers of ten), their extent, the title, the series with their error bars.

use super::legend::{band_style, draw_legend, least_covering_legend, legend_corner, legend_size, Grid};
use super::series::Series;
use super::{FigureParams, LegendPosition, Style};
use anyhow::{bail, Result};
use pipeline::table::format_number;
use plotters::prelude::*;

/// Sixteen colours: black, the ten of matplotlib's tab10, navy, maroon, dark green, olive
/// and teal (so that a figure of up to fifteen families repeats none: the bench's BEM
/// figure has fifteen, its FEM figure twelve).
pub(super) const PALETTE: [RGBColor; 16] = [
    RGBColor(0, 0, 0),
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
    RGBColor(188, 189, 34),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(0, 0, 128),
    RGBColor(128, 0, 0),
    RGBColor(0, 100, 0),
    RGBColor(128, 128, 0),
    RGBColor(0, 128, 128),
];

/// "10⁻³" for an integer exponent.
pub(super) fn power_of_ten(e: i32) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits: String = e.unsigned_abs().to_string().chars().map(|c| SUP[c.to_digit(10).unwrap() as usize]).collect();
    format!("10{}{digits}", if e < 0 { "⁻" } else { "" })
}

/// A tick label; on linear axes values within 1e-9 of the span of zero are 0 (plotters'
/// tick positions carry rounding: -2.2e-17 was printed on Fig. 5.2d).
pub(super) fn axis_label(v: f64, log: bool, span: f64) -> String {
    if log {
        let r = v.round();
        if (v - r).abs() < 1e-6 {
            power_of_ten(r as i32)
        } else {
            String::new()
        }
    } else if v.abs() < 1e-9 * span {
        "0".into()
    } else {
        // Rounded to 12 significant digits first: a tick at 3 x 5e-6 is 1.5000000000000002e-5.
        format_number(format!("{v:.11e}").parse().unwrap_or(v))
    }
}

/// The range of the transformed values, padded by 3% on linear axes.
pub(super) fn extent(given: Option<[f64; 2]>, log: bool, values: impl Iterator<Item = f64>) -> Result<(f64, f64)> {
    let (lo, hi) = match given {
        Some([a, b]) => {
            if log && (a <= 0.0 || b <= 0.0) {
                bail!("a log axis needs a positive range, got [{a}, {b}]");
            }
            if log {
                (a.log10(), b.log10())
            } else {
                (a, b)
            }
        }
        None => {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for v in values {
                lo = lo.min(v);
                hi = hi.max(v);
            }
            if !lo.is_finite() {
                bail!("nothing to plot");
            }
            if log {
                (lo.floor(), hi.ceil().max(lo.floor() + 1.0))
            } else {
                let pad = 0.03 * (hi - lo).max(1e-12);
                (lo - pad, hi + pad)
            }
        }
    };
    if !(hi > lo) {
        bail!("empty axis range [{lo}, {hi}]");
    }
    Ok((lo, hi))
}

/// The SVG of a figure. An automatic legend that would cover a drawn mark wherever it goes
/// inside the axes is drawn outside them, on the right.
pub(super) fn render(p: &FigureParams, series: &[Series]) -> Result<String> {
    let (svg, covered) = draw(p, series, false)?;
    let svg = if covered == 0 || p.legend != LegendPosition::Auto { svg } else { draw(p, series, true)?.0 };
    Ok(with_title_element(&svg, &p.title))
}

/// The SVG with a `<title>` element (its accessible name, and what the report's caption
/// reads) holding the figure's title as drawn, right after the opening `<svg>` tag.
fn with_title_element(svg: &str, title: &str) -> String {
    let escaped = title.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;");
    match svg.find("<svg").and_then(|i| svg[i..].find('>').map(|j| i + j + 1)) {
        Some(at) => format!("{}\n<title>{escaped}</title>{}", &svg[..at], &svg[at..]),
        None => svg.to_string(),
    }
}

/// The title's lines: words wrapped so that each line fits in `width` pixels at `font`.
pub(super) fn title_lines(title: &str, font: &TextStyle, width: u32) -> Vec<String> {
    let fits = |line: &str| {
        let mut t = MultiLineText::<_, &str>::new((0, 0), font);
        t.push_line(line);
        t.estimate_dimension().map(|(w, _)| w as u32 <= width).unwrap_or(true)
    };
    let mut lines: Vec<String> = Vec::new();
    for word in title.split(' ') {
        match lines.last_mut() {
            Some(line) if fits(&format!("{line} {word}")) => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Draws the figure, the legend outside the axes if `legend_outside`; returns the SVG and
/// how many drawn marks the legend covers.
/// The runs of a series' points (mapped to the axes' coordinates by `to_axes`) that lie in
/// view: a run ends at a point out of view (of those that are `finite`; the others are
/// skipped) and at the series' breaks, so that no line is clamped to the axes' border.
fn visible_runs(
    s: &Series,
    to_axes: impl Fn(&(f64, f64)) -> (f64, f64),
    in_view: impl Fn(&(f64, f64)) -> bool,
    finite: impl Fn(&(f64, f64)) -> bool,
) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for (k, point) in s.points.iter().enumerate() {
        if s.breaks.contains(&k) && !runs.last().unwrap().is_empty() {
            runs.push(Vec::new());
        }
        let q = to_axes(point);
        if !finite(&q) {
            continue;
        }
        if in_view(&q) {
            runs.last_mut().unwrap().push(q);
        } else if !runs.last().unwrap().is_empty() {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// The drawn marks of the series (in plot coordinates, inside the axes) in pixels of the
/// plotting area (`px`): points, lines sampled between them every 2 pixels or so (no line
/// crosses a legend box unseen), and the shaded region under an area's line down to `y0`.
fn drawn_marks(series: &[(Style, Vec<(f64, f64)>)], y0: f64, px: impl Fn((f64, f64)) -> (i32, i32)) -> Vec<(i32, i32)> {
    let mut marks = Vec::new();
    for (style, q) in series {
        for (k, &a) in q.iter().enumerate() {
            marks.push(px(a));
            if *style == Style::Area {
                marks.extend((1..=12).map(|j| px((a.0, a.1 - (a.1 - y0) * j as f64 / 12.0))));
            }
            if *style != Style::Points {
                if let Some(&b) = q.get(k + 1) {
                    let (pa, pb) = (px(a), px(b));
                    let n = ((pb.0 - pa.0).abs().max((pb.1 - pa.1).abs()) / 2).clamp(1, 2000);
                    marks.extend((1..n).map(|j| {
                        let t = j as f64 / n as f64;
                        px((a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t))
                    }));
                }
            }
        }
    }
    marks
}

pub(super) fn draw(p: &FigureParams, series: &[Series], legend_outside: bool) -> Result<(String, usize)> {
    let tx = |x: f64| if p.log_x { x.log10() } else { x };
    let ty = |y: f64| if p.log_y { y.log10() } else { y };
    let xs = series.iter().flat_map(|s| s.points.iter().map(|q| tx(q.0)));
    let (x0, x1) = extent(p.x_range, p.log_x, xs)?;
    // The automatic y range covers the points inside the x range only.
    let ys = series.iter().flat_map(|s| s.points.iter().filter(|q| tx(q.0) >= x0 && tx(q.0) <= x1).map(|q| ty(q.1)));
    let (y0, y1) = extent(p.y_range, p.log_y, ys)?;
    let mut svg = String::new();
    let covered = {
        let root = SVGBackend::with_string(&mut svg, (p.width, p.height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let title_font: TextStyle = ("sans-serif", 22).into_font().into();
        let mut area = root.clone();
        for line in title_lines(&p.title, &title_font, p.width.saturating_sub(36)) {
            area = area.titled(&line, title_font.clone()).map_err(|e| anyhow::anyhow!("{e:?}"))?;
        }
        let labels: Vec<&str> = series.iter().filter(|s| !s.label.is_empty()).map(|s| s.label.as_str()).collect();
        let (legend_w, _) = legend_size(&labels);
        let below = (p.legend == LegendPosition::Below && !labels.is_empty()).then(|| Grid::of(&labels, p.width));
        let mut chart = ChartBuilder::on(&area)
            .margin(18)
            .margin_right(if legend_outside { 18 + legend_w as u32 + 10 } else { 18 })
            .margin_bottom(18 + below.as_ref().map_or(0, |g| g.height))
            .x_label_area_size(52)
            .y_label_area_size(72)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let fx = |v: &f64| axis_label(*v, p.log_x, x1 - x0);
        let fy = |v: &f64| axis_label(*v, p.log_y, y1 - y0);
        let n_x = if p.log_x { ((x1 - x0).round() as usize + 1).clamp(2, 13) } else { 8 };
        let n_y = if p.log_y { ((y1 - y0).round() as usize + 1).clamp(2, 13) } else { 8 };
        chart
            .configure_mesh()
            .x_desc(p.x_label.as_str())
            .y_desc(p.y_label.as_str())
            .x_labels(n_x)
            .y_labels(n_y)
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .axis_desc_style(("sans-serif", 18))
            .label_style(("sans-serif", 14))
            .light_line_style(RGBColor(244, 244, 244))
            .bold_line_style(RGBColor(215, 215, 215))
            .draw()
            .map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let inside = |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite();
        for (i, s) in series.iter().enumerate() {
            let color = PALETTE[s.color.unwrap_or(i) % PALETTE.len()];
            let style = ShapeStyle::from(&color).stroke_width(2);
            let err = |e| anyhow::anyhow!("{e:?}");
            // Lines are drawn as the runs of points inside the axes: a curve that leaves
            // the plotted range is not clamped to its border. A run also ends at the
            // series' breaks.
            let in_view = |&(x, y): &(f64, f64)| x >= x0 && x <= x1 && y >= y0 && y <= y1;
            let runs = visible_runs(s, |&(x, y)| (tx(x), ty(y)), |q| inside(q) && in_view(q), inside);
            // Error bars, clipped to the axes (on a log axis a bar reaching zero or below
            // runs to the bottom).
            let bars: Vec<_> = s
                .points
                .iter()
                .zip(&s.errors)
                .filter(|&(&(x, y), &e)| e > 0.0 && in_view(&(tx(x), ty(y))))
                .map(|(&(x, y), &e)| {
                    let lo = if p.log_y && y - e <= 0.0 { y0 } else { ty(y - e).max(y0) };
                    ErrorBar::new_vertical(tx(x), lo, ty(y), ty(y + e).min(y1), style.stroke_width(1), 6)
                })
                .collect();
            chart.draw_series(bars).map_err(err)?;
            for run in runs {
                match s.style {
                    Style::Line => chart.draw_series(LineSeries::new(run, style)).map_err(err)?,
                    Style::Band => chart.draw_series(LineSeries::new(run, band_style(color))).map_err(err)?,
                    Style::Dashed => chart.draw_series(DashedLineSeries::new(run, 8, 5, style)).map_err(err)?,
                    Style::Dotted => chart.draw_series(DashedLineSeries::new(run, 2, 4, style)).map_err(err)?,
                    Style::Points => {
                        chart.draw_series(run.into_iter().map(|q| Circle::new(q, 3, color.filled()))).map_err(err)?
                    }
                    Style::LinePoints => {
                        chart.draw_series(run.iter().map(|&q| Circle::new(q, 3, color.filled()))).map_err(err)?;
                        chart.draw_series(LineSeries::new(run, style)).map_err(err)?
                    }
                    Style::Area => chart
                        .draw_series(AreaSeries::new(run, y0, color.mix(0.18).filled()).border_style(style))
                        .map_err(err)?,
                };
            }
        }
        let area = chart.plotting_area().dim_in_pixel();
        let base = chart.plotting_area().get_base_pixel();
        let pinned = |p: SeriesLabelPosition| (legend_corner(&p, legend_size(&labels), area), 0);
        let (corner, covered) = match p.legend {
            LegendPosition::UpperRight => pinned(SeriesLabelPosition::UpperRight),
            LegendPosition::UpperLeft => pinned(SeriesLabelPosition::UpperLeft),
            LegendPosition::LowerRight => pinned(SeriesLabelPosition::LowerRight),
            LegendPosition::LowerLeft => pinned(SeriesLabelPosition::LowerLeft),
            LegendPosition::Auto if legend_outside => ((area.0 as i32 + 10, 0), 0),
            LegendPosition::Auto if labels.is_empty() => ((0, 0), 0),
            LegendPosition::Below => ((0, 0), 0),
            LegendPosition::Auto => {
                let px = |q: (f64, f64)| {
                    let (x, y) = chart.backend_coord(&q);
                    (x - base.0, y - base.1)
                };
                let shown: Vec<(Style, Vec<(f64, f64)>)> = series
                    .iter()
                    .map(|s| {
                        let q = s.points.iter().map(|&(x, y)| (tx(x), ty(y)));
                        (s.style, q.filter(|&(x, y)| x >= x0 && x <= x1 && y >= y0 && y <= y1).collect())
                    })
                    .collect();
                let (best, covered) = least_covering_legend(&labels, area, &drawn_marks(&shown, y0, px));
                (legend_corner(&best, legend_size(&labels), area), covered)
            }
        };
        let entries: Vec<(&str, Style, RGBColor)> = series
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.label.is_empty())
            .map(|(i, s)| (s.label.as_str(), s.style, PALETTE[s.color.unwrap_or(i) % PALETTE.len()]))
            .collect();
        match below {
            Some(grid) => grid.draw(&root, &entries, p.height)?,
            None => draw_legend(&root, &entries, (base.0 + corner.0, base.1 + corner.1))?,
        }
        root.present().map_err(|e| anyhow::anyhow!("{e:?}"))?;
        covered
    };
    Ok((svg, covered))
}
