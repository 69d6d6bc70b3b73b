//! The legend: drawn by this code (not plotters'), inside the axes where it covers the
//! fewest drawn points and lines, or outside on the right when every place covers data.

use super::Style;
use anyhow::Result;
use plotters::prelude::*;

/// The legend position (a box of the labels at 14 px plus the 30 px sample and 10 px
/// margins, 5 px from the plotting area's edges) that covers the fewest of `marks` (pixels of the plotting area of size `area`), the corners
/// first on a tie.
pub(super) fn least_covering_legend(
    labels: &[&str],
    area: (u32, u32),
    marks: &[(i32, i32)],
) -> (SeriesLabelPosition, usize) {
    use SeriesLabelPosition::*;
    let candidates = [UpperRight, UpperLeft, LowerRight, LowerLeft, MiddleRight, MiddleLeft, UpperMiddle, LowerMiddle];
    let (w, h) = legend_size(labels);
    let covered = |p: &SeriesLabelPosition| {
        let (x, y) = legend_corner(p, (w, h), area);
        marks.iter().filter(|&&(mx, my)| mx >= x && mx <= x + w && my >= y && my <= y + h).count()
    };
    candidates
        .into_iter()
        .map(|p| {
            let n = covered(&p);
            (p, n)
        })
        .min_by_key(|&(_, n)| n)
        .unwrap_or((UpperRight, 0))
}

/// The top left corner of a legend box of size `(w, h)` at position `p` of a plotting area
/// of size `area`, 5 px from its edges, in pixels of the plotting area.
pub(super) fn legend_corner(p: &SeriesLabelPosition, (w, h): (i32, i32), area: (u32, u32)) -> (i32, i32) {
    use SeriesLabelPosition::*;
    let (aw, ah) = (area.0 as i32, area.1 as i32);
    let x = match p {
        UpperLeft | MiddleLeft | LowerLeft => 5,
        UpperMiddle | MiddleMiddle | LowerMiddle => (aw - w) / 2,
        _ => aw - w - 5,
    };
    let y = match p {
        UpperLeft | UpperMiddle | UpperRight => 5,
        MiddleLeft | MiddleMiddle | MiddleRight => (ah - h) / 2,
        _ => ah - h - 5,
    };
    (x, y)
}

/// A legend below the axes, in columns (`legend: below`): as many columns of the widest
/// entry as the figure's width holds, filled row by row, centred.
pub(super) struct Grid {
    columns: usize,
    column_width: i32,
    /// The height the grid takes from the bottom of the figure (pixels).
    pub(super) height: u32,
    width: u32,
}

/// A row of the grid (pixels).
const GRID_ROW: i32 = 20;

impl Grid {
    pub(super) fn of(labels: &[&str], width: u32) -> Grid {
        let column_width = labels.iter().map(|l| legend_size(&[l]).0).max().unwrap_or(0).max(1);
        let usable = width.saturating_sub(36) as i32;
        let columns = ((usable / column_width).max(1) as usize).min(labels.len().max(1));
        let rows = labels.len().div_ceil(columns) as i32;
        Grid { columns, column_width, height: (rows * GRID_ROW + 12) as u32, width }
    }

    /// Draws `entries` in the grid, above the bottom `height` of a figure `figure_height` tall.
    pub(super) fn draw(
        &self,
        root: &DrawingArea<SVGBackend, plotters::coord::Shift>,
        entries: &[(&str, Style, RGBColor)],
        figure_height: u32,
    ) -> Result<()> {
        let left = (self.width as i32 - self.columns as i32 * self.column_width) / 2;
        let top = figure_height as i32 - self.height as i32;
        for (k, &entry) in entries.iter().enumerate() {
            let (col, row) = ((k % self.columns) as i32, (k / self.columns) as i32);
            draw_entry(root, entry, (left + col * self.column_width + 10, top + row * GRID_ROW + GRID_ROW / 2))?;
        }
        Ok(())
    }
}

/// One legend entry with its sample's left end at `(sx, sy)`: a 22 px sample of the series'
/// style and colour, then its label.
fn draw_entry(
    root: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    (label, style, color): (&str, Style, RGBColor),
    (sx, sy): (i32, i32),
) -> Result<()> {
    let err = |e| anyhow::anyhow!("{e:?}");
    let font: TextStyle = ("sans-serif", 14).into_font().into();
    let font = font.pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Left,
        plotters::style::text_anchor::VPos::Center,
    ));
    let stroke = match style {
        Style::Band => band_style(color),
        _ => ShapeStyle::from(&color).stroke_width(2),
    };
    let segments: &[(i32, i32)] = match style {
        Style::Points => &[],
        Style::Dotted => &[(0, 3), (9, 12), (18, 21)],
        Style::Dashed => &[(0, 8), (13, 22)],
        Style::Line | Style::LinePoints | Style::Area | Style::Band => &[(0, 22)],
    };
    for &(a, b) in segments {
        root.draw(&PathElement::new(vec![(sx + a, sy), (sx + b, sy)], stroke)).map_err(err)?;
    }
    if matches!(style, Style::Points | Style::LinePoints) {
        root.draw(&Circle::new((sx + 11, sy), 3, color.filled())).map_err(err)?;
    }
    root.draw(&Text::new(label, (sx + 30, sy), font)).map_err(err)?;
    Ok(())
}

/// The stroke of `Style::Band`: three times a line's width, at 40 % opacity.
pub(super) fn band_style(color: RGBColor) -> ShapeStyle {
    ShapeStyle::from(&color.mix(0.4)).stroke_width(6)
}

/// Draws the legend box with its top left corner at `at` (pixels of `root`): per entry a
/// 22 px sample of the series' style and colour, then its label.
pub(super) fn draw_legend(
    root: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    entries: &[(&str, Style, RGBColor)],
    at: (i32, i32),
) -> Result<()> {
    if entries.is_empty() {
        return Ok(());
    }
    let err = |e| anyhow::anyhow!("{e:?}");
    let labels: Vec<&str> = entries.iter().map(|e| e.0).collect();
    let (w, h) = legend_size(&labels);
    let (x, y) = at;
    root.draw(&Rectangle::new([(x, y), (x + w, y + h)], WHITE.mix(0.85).filled())).map_err(err)?;
    root.draw(&Rectangle::new([(x, y), (x + w, y + h)], RGBColor(120, 120, 120))).map_err(err)?;
    let row = (h - 20) as f64 / entries.len() as f64;
    for (k, &entry) in entries.iter().enumerate() {
        draw_entry(root, entry, (x + 10, y + 10 + (row * (k as f64 + 0.5)).round() as i32))?;
    }
    Ok(())
}

/// The legend box in pixels: the labels at 14 px plus the 30 px sample and 10 px margins.
pub(super) fn legend_size(labels: &[&str]) -> (i32, i32) {
    let font: TextStyle = ("sans-serif", 14).into_font().into();
    let mut text = MultiLineText::<_, &str>::new((0, 0), &font);
    for l in labels {
        text.push_line(*l);
    }
    let (w, h) = text.estimate_dimension().unwrap_or((0, 0));
    (w + 30 + 20, h + 20)
}
