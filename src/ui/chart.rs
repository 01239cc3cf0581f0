//! A panel described in `plot` drawn as a braille chart with labelled axes, tick values and a
//! legend: what every analysis page draws with (the same panel an export writes as SVG; its
//! cells the page paints beneath). The plot area it returns maps mouse cells back to data
//! (see `CanvasGeom`).

use super::fit::{fit, fit_label};
use crate::plot::{Chart, Ink, Mark, Series, sane};
use crate::theme::Theme;
use ratatui::Frame as TuiFrame;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Context, Line as Seg, Points};
use ratatui::widgets::{Block, Borders, Paragraph};
use unicode_width::UnicodeWidthStr;

/// The theme's colour for what a thing drawn is.
pub fn ink(th: &Theme, ink: Ink) -> Color {
    match ink {
        Ink::Trail => th.trail,
        Ink::Muted => th.muted,
        Ink::Accent => th.accent,
        Ink::Paper => th.spokes,
        Ink::Particle => th.particle,
        Ink::Foreground => th.foreground,
        Ink::Stuck => th.stuck,
        Ink::Escaped => th.escaped,
        Ink::Notice => th.notice,
        Ink::Arrow => th.arrow,
        Ink::Friction => th.friction,
        Ink::Coriolis => th.coriolis,
        Ink::Centrifugal => th.centrifugal,
        Ink::TableEdge => th.table_edge,
        Ink::LimitCircle => th.limit_circle,
    }
}

/// Draws `chart` in `area`: a titled block around [`render_bare`] with its τ axis. Returns
/// the plot area (None when `area` is too small to hold one).
pub fn render(f: &mut TuiFrame, area: Rect, th: &Theme, chart: &Chart) -> Option<Rect> {
    // Fields of the title (", ") drop whole when the box is narrow: never part of a number.
    let room = usize::from(area.width).saturating_sub(4);
    let block = super::titled(format!(" {} ", fit(&chart.title, ", ", room)), th);
    let inner = block.inner(area);
    f.render_widget(block, area);
    render_bare(f, inner, th, chart, true, 0)
}

/// Where [`render`] puts the plot in `area`, to draw beneath it first.
pub fn plot_area(area: Rect, chart: &Chart) -> Option<Rect> {
    let inner = Block::default().borders(Borders::ALL).inner(area);
    layout(inner, chart, true, 0).map(|l| l.0)
}

/// The width of the y-tick gutter [`render_bare`] gives `chart` in `inner` (charts stacked on
/// one x axis take the widest, so that their x values line up).
pub fn gutter(inner: Rect, chart: &Chart, x_axis: bool) -> u16 {
    layout(inner, chart, x_axis, 0).map_or(0, |l| l.1)
}

/// Tick values with their labels.
type Ticks = Vec<(f64, String)>;

/// The plot rectangle, the y-tick gutter's width (at least `min_gutter`), and the y ticks.
fn layout(inner: Rect, chart: &Chart, x_axis: bool, min_gutter: u16) -> Option<(Rect, u16, Ticks)> {
    let y = sane(chart.y);
    let below = if x_axis { 2 } else { 0 };
    let rows = inner.height.checked_sub(1 + below).filter(|r| *r >= 2)?;
    let yt = chart
        .y_scale
        .ticks(y[0], y[1], (rows as usize / 3).clamp(2, 5));
    // Too short for round ticks: label the ends.
    let yt = if yt.len() < 2 { vec![y[0], y[1]] } else { yt };
    let yt: Ticks = yt
        .into_iter()
        .map(|v| (v, chart.y_scale.label(v)))
        .collect();
    let gutter = yt.iter().map(|(_, l)| l.chars().count()).max().unwrap_or(1) as u16 + 1;
    let gutter = gutter.max(min_gutter);
    if inner.width < gutter + 8 {
        return None;
    }
    let plot = Rect {
        x: inner.x + gutter,
        y: inner.y + 1,
        width: inner.width - gutter,
        height: rows,
    };
    Some((plot, gutter, yt))
}

/// Draws `chart` in `area` with no border: the legend line, the y ticks in a left gutter (at
/// least `min_gutter` wide), the plot, and (with `x_axis`) the x ticks and the x axis name
/// below. Returns the plot area.
pub fn render_bare(
    f: &mut TuiFrame,
    inner: Rect,
    th: &Theme,
    chart: &Chart,
    x_axis: bool,
    min_gutter: u16,
) -> Option<Rect> {
    let (x, y) = (sane(chart.x), sane(chart.y));
    let (plot, gutter, yt) = layout(inner, chart, x_axis, min_gutter)?;
    legend(f, inner, th, chart);
    let rows = Rows { y, h: plot.height };
    y_ticks(f, inner, plot, gutter, th, &yt, rows);
    if x_axis {
        x_ticks(f, inner, plot, th, chart, x);
    }
    let labels = place_labels(th, &chart.marks, x, rows, Taken::of(plot, th, chart, x, y));
    let canvas = Canvas::default()
        .marker(th.marker)
        .x_bounds(x)
        .y_bounds(y)
        .paint(|ctx| {
            lines(ctx, th, chart, y);
            ctx.layer();
            paint_series(ctx, th, &chart.series);
        });
    f.render_widget(canvas, plot);
    // Written in the cells they were placed in: the canvas's own text placement rounds by
    // another path and can land a column or a row off (π on 105 columns, y0 on 4 rows).
    for (c, r, text, color) in labels {
        f.buffer_mut()
            .set_string(plot.x + c, plot.y + r, text, Style::default().fg(color));
    }
    Some(plot)
}

/// The legend: every series and mark by name, in its colour, after the y axis name. A name
/// that does not fit is left out whole.
fn legend(f: &mut TuiFrame, inner: Rect, th: &Theme, chart: &Chart) {
    let muted = Style::default().fg(th.muted);
    let mut legend = vec![Span::styled(format!("{} ", chart.y_label), muted)];
    let mut used = legend[0].width();
    for s in chart
        .series
        .iter()
        .filter(|s| !s.name.is_empty() && !is_cells(s))
    {
        // Lines and dots named by their own mark, not by colour alone (mono, NO_COLOR).
        let text = format!("{} {}  ", if s.joined() { "━" } else { "··" }, s.name);
        if used + text.trim_end().width() > usize::from(inner.width) {
            break;
        }
        used += text.width();
        legend.push(Span::styled(text, Style::default().fg(ink(th, s.ink))));
    }
    f.render_widget(
        Paragraph::new(Line::from(legend)),
        Rect { height: 1, ..inner },
    );
}

/// The plot's rows for y values over `y` on `h` rows.
#[derive(Clone, Copy)]
struct Rows {
    y: [f64; 2],
    h: u16,
}

impl Rows {
    /// The row a value's braille dot falls in (the canvas maps y to dot rows 0..4h − 1, top
    /// down, by truncation): tick labels and text marks go on it, so that they sit beside
    /// their curve rather than a row off.
    fn dot_row(self, v: f64) -> u16 {
        let (y, h) = (self.y, self.h);
        let d = ((y[1] - v) / (y[1] - y[0]) * (4.0 * f64::from(h) - 1.0)).max(0.0);
        ((d as u32 / 4) as u16).min(h - 1)
    }
}

/// The y ticks' labels, right-aligned in the gutter on their values' rows.
fn y_ticks(
    f: &mut TuiFrame,
    inner: Rect,
    plot: Rect,
    gutter: u16,
    th: &Theme,
    yt: &[(f64, String)],
    rows: Rows,
) {
    let muted = Style::default().fg(th.muted);
    for (v, l) in yt {
        let r = Rect::new(inner.x, plot.y + rows.dot_row(*v), gutter - 1, 1);
        f.render_widget(
            Paragraph::new(Span::styled(l.clone(), muted)).right_aligned(),
            r,
        );
    }
}

/// The x ticks under the plot (none overlapping), and below them the note and the x axis
/// name.
fn x_ticks(f: &mut TuiFrame, inner: Rect, plot: Rect, th: &Theme, chart: &Chart, x: [f64; 2]) {
    let muted = Style::default().fg(th.muted);
    let xt = chart
        .x_scale
        .ticks(x[0], x[1], (plot.width as usize / 10).clamp(1, 8));
    let axis_row = plot.y + plot.height;
    let mut taken = 0u16;
    for v in xt {
        let fx = (v - x[0]) / (x[1] - x[0]);
        let col = plot.x + ((fx * f64::from(plot.width - 1)).round() as u16).min(plot.width - 1);
        let l = chart.x_scale.label(v);
        let w = l.chars().count() as u16;
        let start = col
            .saturating_sub(w / 2)
            .max(plot.x)
            .min(plot.right().saturating_sub(w));
        if start < taken {
            continue;
        }
        taken = start + w + 1;
        f.render_widget(
            Paragraph::new(Span::styled(l, muted)),
            Rect::new(start, axis_row, w.min(plot.right() - start), 1),
        );
    }
    let row = Rect::new(inner.x, axis_row + 1, inner.width, 1);
    // The axis name's fields first, then the note's that still fit beside it.
    let x_label = fit(&chart.x_label, "  ", usize::from(plot.width));
    let room = usize::from(inner.width).saturating_sub(x_label.width() + 1);
    let note = fit(&chart.note, ", ", room);
    f.render_widget(
        Paragraph::new(Line::from(vec![Span::styled(
            note,
            Style::default().fg(th.foreground),
        )])),
        row,
    );
    f.render_widget(
        Paragraph::new(Span::styled(x_label, muted)).right_aligned(),
        Rect::new(plot.x, axis_row + 1, plot.width, 1),
    );
}

/// Cells are the page's to paint, a character each, beneath the braille.
fn is_cells(s: &Series) -> bool {
    matches!(s.style, crate::plot::Style::Cells { .. })
}

/// The series: lines (a gap where a value is not finite) or dots.
fn paint_series(ctx: &mut Context, th: &Theme, series: &[Series]) {
    for s in series.iter().filter(|s| !is_cells(s)) {
        let color = ink(th, s.ink);
        if s.joined() {
            for w in s.points.windows(2) {
                let ((x1, y1), (x2, y2)) = (w[0], w[1]);
                if [x1, y1, x2, y2].iter().all(|v| v.is_finite()) {
                    ctx.draw(&Seg::new(x1, y1, x2, y2, color));
                }
            }
        } else {
            ctx.draw(&Points {
                coords: &s.points,
                color,
            });
        }
    }
}

/// What the plot's braille holds, cell by cell (the series, the lines and arrows, drawn once
/// more off screen), and the cells labels take: a label goes only where neither is.
struct Taken {
    cols: i64,
    rows: i64,
    /// Cells the drawing's braille covers, row by row.
    drawn: Vec<bool>,
    /// (row, first column, past the last) of each label (with its blanks) and dot placed.
    spans: Vec<(i64, i64, i64)>,
    /// x of the plot's left edge and braille dots per x unit.
    x0: f64,
    per_x: f64,
}

impl Taken {
    /// The plot's drawing without its labels: which cells hold braille.
    fn of(plot: Rect, th: &Theme, chart: &Chart, x: [f64; 2], y: [f64; 2]) -> Taken {
        let area = Rect::new(0, 0, plot.width, plot.height);
        let mut buf = ratatui::buffer::Buffer::empty(area);
        use ratatui::widgets::Widget;
        Canvas::default()
            .marker(th.marker)
            .x_bounds(x)
            .y_bounds(y)
            .paint(|ctx| {
                lines(ctx, th, chart, y);
                paint_series(ctx, th, &chart.series);
            })
            .render(area, &mut buf);
        let drawn = buf
            .content()
            .iter()
            .map(|c| !matches!(c.symbol(), " " | "\u{2800}" | ""))
            .collect();
        Taken {
            cols: i64::from(plot.width),
            rows: i64::from(plot.height),
            drawn,
            spans: Vec::new(),
            x0: x[0],
            per_x: (2.0 * f64::from(plot.width) - 1.0) / (x[1] - x[0]),
        }
    }

    /// The column the braille of `a` falls in (the canvas maps x to dot columns
    /// 0..2w − 1 by truncation, two to a cell), so that a dot sits on its curve.
    fn col(&self, a: f64) -> i64 {
        ((a - self.x0) * self.per_x).floor() as i64 / 2
    }

    /// Whether `n` cells from column `c` on row `r` are on the plot, clear of the drawing and
    /// of every label placed.
    fn free(&self, c: i64, n: usize, r: i64) -> bool {
        let end = c + n as i64;
        (0..self.rows).contains(&r)
            && c >= 0
            && end <= self.cols
            && (c..end).all(|k| !self.drawn[(r * self.cols + k) as usize])
            && !self
                .spans
                .iter()
                .any(|&(tr, ta, tb)| tr == r && c < tb && ta < end)
    }

    /// Takes `n` cells from x `a` on row `r`, and a blank cell either side: two labels
    /// glued read as one (`0.2max`). A point's dot takes its cell alone: its words may touch it.
    fn take(&mut self, c: i64, n: usize, r: i64) {
        self.spans.push((r, c - 1, c + n as i64 + 1));
    }

    /// The first of `tries` (column, row) where `n` cells are free, taken; None if none is.
    fn place(
        &mut self,
        n: usize,
        tries: impl IntoIterator<Item = (i64, i64)>,
    ) -> Option<(i64, i64)> {
        let (c, r) = tries.into_iter().find(|&(c, r)| self.free(c, n, r))?;
        self.take(c, n, r);
        Some((c, r))
    }
}

/// The vertical lines and arrows the marks draw.
fn lines(ctx: &mut Context, th: &Theme, chart: &Chart, y: [f64; 2]) {
    for m in &chart.marks {
        match m {
            Mark::VLine { x: mx, ink: i, .. } => {
                ctx.draw(&Seg::new(*mx, y[0], *mx, y[1], ink(th, *i)));
            }
            Mark::Arrow {
                from, to, ink: i, ..
            } => {
                ctx.draw(&Seg::new(from.0, from.1, to.0, to.1, ink(th, *i)));
            }
            _ => {}
        }
    }
}

/// Rows nearest `r0` first: r0, r0 − 1, r0 + 1, r0 − 2, … over the plot's rows.
fn near(r0: i64, rows: i64) -> impl Iterator<Item = i64> {
    std::iter::once(r0).chain((1..rows).flat_map(move |k| [r0 - k, r0 + k]))
}

/// The marks' dots and labels. A label covers neither a curve (the drawing's braille) nor
/// another label: line labels go along the top, lower where the row is taken; a point keeps
/// its dot and its words go beside it, on the nearest row where they are clear; a label with
/// no clear place is left out (the legend names the series). The last marks (the release)
/// are placed first.
fn place_labels(
    th: &Theme,
    marks: &[Mark],
    x: [f64; 2],
    rows: Rows,
    mut taken: Taken,
) -> Vec<(u16, u16, String, Color)> {
    let mut out = Vec::new();
    let (n_cols, n_rows) = (taken.cols, taken.rows);
    // Cells placed are on the plot (`free` saw to it).
    let mut put = |c: i64, r: i64, text: String, color| {
        if let (Ok(c), Ok(r)) = (u16::try_from(c), u16::try_from(r)) {
            out.push((c, r, text, color));
        }
    };
    // The points' dots first: words go around them (a dot sits on its curve by design).
    for m in marks {
        if let Mark::Point {
            x: px,
            y: py,
            ink: i,
            ..
        } = *m
        {
            let r0 = i64::from(rows.dot_row(py));
            let c = taken.col(px);
            if (0..n_cols).contains(&c) {
                taken.spans.push((r0, c, c + 1));
                put(c, r0, "●".to_string(), ink(th, i));
            }
        }
    }
    for m in marks.iter().rev() {
        let (label, color) = match m {
            Mark::VLine { label, ink: i, .. }
            | Mark::Text { label, ink: i, .. }
            | Mark::Point { label, ink: i, .. }
            | Mark::Arrow { label, ink: i, .. } => (label, ink(th, *i)),
        };
        // Whole words only, as many as the wider side of a point has room for.
        let label = match *m {
            Mark::Point { x: px, .. } => {
                let c = taken.col(px);
                let side = (n_cols - c - 1).max(c).max(0) as usize;
                fit_label(label, side.saturating_sub(1))
            }
            _ => label.clone(),
        };
        let n = label.width();
        if n == 0 {
            continue;
        }
        let k = n as i64;
        // Right of a column or ending left of it (never on it), as the mark prefers; then a
        // cell or two further right, past a line beside it, before another row.
        let beside = |c: i64, left_first: bool| {
            let (right, left) = (c + 1, c - k);
            let (a, b) = if left_first {
                (left, right)
            } else {
                (right, left)
            };
            [a, b, c + 2, c + 3]
        };
        let spot = match *m {
            Mark::VLine { x: mx, .. } => {
                // Right of the line, or left of it in the right half; the other side next.
                let sides = beside(taken.col(mx), mx > 0.5 * (x[0] + x[1]));
                taken.place(n, (0..n_rows).flat_map(|r| sides.map(|a| (a, r))))
            }
            Mark::Point { x: px, y: py, .. } => {
                let (r0, c) = (i64::from(rows.dot_row(py)), taken.col(px));
                // Right of its dot, or left of it when they would run past the plot's edge
                // (never cut); a row off before the other side.
                let sides = beside(c, c + 1 + k > n_cols);
                let rows = near(r0, n_rows).filter(|_| (0..n_cols).contains(&c));
                taken.place(n, rows.flat_map(|r| sides.map(|a| (a, r))))
            }
            Mark::Text { x: px, y: py, .. } | Mark::Arrow { to: (px, py), .. } => {
                let r0 = i64::from(rows.dot_row(py));
                // Text that would run past the plot's right edge ends there.
                let c = taken.col(px).min(n_cols - k).max(0);
                let shifts = [0, -k / 2, k / 2, -k, k].map(|d| c + d);
                taken.place(
                    n,
                    near(r0, n_rows.min(4)).flat_map(|r| shifts.map(|a| (a, r))),
                )
            }
        };
        if let Some((c, r)) = spot {
            put(c, r, label, color);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two points side by side and a line label over them: every dot and every word shows,
    /// and each dot sits on the row of its value's braille.
    #[test]
    fn labels_never_cover_one_another() {
        use ratatui::{Terminal, backend::TestBackend};
        let th = Theme::builtin("mono").unwrap();
        let c = Ink::Foreground;
        let chart = Chart {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            x: [0.0, 10.0],
            y: [0.0, 1.0],
            marks: vec![
                Mark::Point {
                    x: 0.5,
                    y: 0.5,
                    label: "min".into(),
                    ink: c,
                },
                Mark::Point {
                    x: 0.2,
                    y: 0.5,
                    label: "release sticks".into(),
                    ink: c,
                },
                Mark::VLine {
                    x: 0.3,
                    label: "stop".into(),
                    ink: c,
                },
                Mark::VLine {
                    x: 0.4,
                    label: "τ=6".into(),
                    ink: c,
                },
            ],
            ..Chart::default()
        };
        let mut t = Terminal::new(TestBackend::new(40, 14)).unwrap();
        let mut plot = None;
        t.draw(|f| plot = render(f, f.area(), &th, &chart)).unwrap();
        let text = crate::ui::export::plain_text(t.backend().buffer());
        for w in ["min", "release sticks", "stop", "τ=6"] {
            assert!(text.contains(w), "{w} missing:\n{text}");
        }
        assert_eq!(text.matches('●').count(), 2, "{text}");
        // y = 0.5 falls in dot row ⌊0.5·(4h − 1)⌋ of the plot, so in text row that / 4.
        let plot = plot.unwrap();
        let row = (0.5 * (4.0 * f64::from(plot.height) - 1.0)) as u16 / 4;
        let line = text.lines().nth(usize::from(plot.y + row)).unwrap();
        assert_eq!(line.matches('●').count(), 2, "{text}");
    }
}
