//! Painting the canvas from the turntable's description (`plot::page::table::Picture`): the
//! terminal's own part is where text lands in cells (labels placed so that none covers the
//! particle or another), thinning long paths, the theme's colours, and the layers ratatui's
//! canvas draws them in.

use super::MAX_SEGMENTS;
use crate::engine::model::rotate;
use crate::plot::page::table::{BODY_GLYPH, Picture, Point, SENSE_LABEL, STUCK_GLYPH};
use crate::theme::Theme;
use glam::DVec2;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::Span;
use ratatui::widgets::canvas::{Circle, Context, Line};

pub(super) fn arrow(ctx: &mut Context, from: DVec2, vec: DVec2, color: Color) {
    let to = from + vec;
    ctx.draw(&Line {
        x1: from.x,
        y1: from.y,
        x2: to.x,
        y2: to.y,
        color,
    });
    let len = vec.length();
    if len > 0.0 {
        let back = -vec / len * (len * 0.25);
        for a in [0.45, -0.45] {
            let h = to + rotate(back, a);
            ctx.draw(&Line {
                x1: to.x,
                y1: to.y,
                x2: h.x,
                y2: h.y,
                color,
            });
        }
    }
}

/// `path` as a line, thinned evenly to at most [`MAX_SEGMENTS`] segments (its end kept).
fn polyline(ctx: &mut Context, path: &[DVec2], color: Color) {
    let n = path.len();
    let stride = n.div_ceil(MAX_SEGMENTS).max(1);
    let mut prev: Option<DVec2> = None;
    for (i, &p) in path.iter().enumerate() {
        if i % stride != 0 && i + 1 != n {
            continue;
        }
        if let Some(a) = prev {
            ctx.draw(&Line {
                x1: a.x,
                y1: a.y,
                x2: p.x,
                y2: p.y,
                color,
            });
        }
        prev = Some(p);
    }
}

/// The turntable's description and what the terminal adds to paint it.
pub(super) struct Painter {
    pub pic: Picture,
    pub th: Theme,
    pub inner: Rect,
    pub xb: [f64; 2],
    pub yb: [f64; 2],
    /// Where the body's centre glyph is printed: in the cell its bar's dots pass through.
    pub body_glyph: Option<DVec2>,
    pub pin_style: Style,
    /// One terminal cell in world units.
    pub cell: DVec2,
    /// Words on the canvas only where there is room for them beside the drawing.
    pub words: bool,
}

/// The cells labels cover (row, first column, past the last): labels never cover the
/// particle or one another, and keep a blank cell between them (`co` and `cf` glued read
/// `cocf`; in the lab `net` is `fr`, at one head).
pub(super) struct Cells {
    inner: Rect,
    xb: [f64; 2],
    yb: [f64; 2],
    pub(super) taken: Vec<(i64, i64, i64)>,
}

impl Cells {
    /// (As ratatui's canvas places text: (x − left)·(width − 1)/(right − left).)
    pub(super) fn of(&self, p: DVec2, n: usize) -> (i64, i64, i64) {
        let (xb, yb) = (self.xb, self.yb);
        let (w, h) = (
            f64::from(self.inner.width.max(1) - 1),
            f64::from(self.inner.height.max(1) - 1),
        );
        let col = ((p.x - xb[0]) * w / (xb[1] - xb[0])).floor() as i64;
        let row = ((yb[1] - p.y) * h / (yb[1] - yb[0])).floor() as i64;
        (row, col, col + n as i64)
    }

    /// A glyph's cell (the particle): a label may touch it.
    fn take(&mut self, p: DVec2, n: usize) {
        let c = self.of(p, n);
        self.taken.push(c);
    }

    /// Words: kept a cell clear of the next words on their row.
    fn take_words(&mut self, p: DVec2, n: usize) {
        let (r, a, b) = self.of(p, n);
        self.taken.push((r, a - 1, b + 1));
    }

    /// Whether `n` cells from `h` are on the canvas and clear of everything taken.
    fn free(&self, h: DVec2, n: usize) -> bool {
        let (r, a, b) = self.of(h, n);
        let (w, rows) = (i64::from(self.inner.width), i64::from(self.inner.height));
        (0..rows).contains(&r)
            && a >= 0
            && b <= w
            && !self
                .taken
                .iter()
                .any(|&(tr, ta, tb)| tr == r && a < tb && ta < b)
    }
}

/// A label placed on the canvas.
pub(super) struct Label {
    pub at: DVec2,
    pub text: String,
    pub color: Color,
}

impl Painter {
    pub fn paint(&self, ctx: &mut Context) {
        self.table(ctx);
        ctx.layer();
        // The initial velocity beneath the trails: where they cross, the trail shows (in
        // the rotating frame D's whole path lies along its arrow).
        let (x0, v0) = self.pic.release;
        arrow(ctx, x0, v0, self.th.arrow);
        ctx.layer();
        self.trails(ctx);
        ctx.layer();
        self.labelled(ctx);
    }

    /// The table: its edge, three marks on its rim, the circle inside which friction holds, the pins' markers
    /// along their paths and, where there is room, the words for the circle and the sense.
    fn table(&self, ctx: &mut Context) {
        let (th, table) = (&self.th, &self.pic.table);
        ctx.draw(&Circle {
            x: 0.0,
            y: 0.0,
            radius: table.r,
            color: th.table_edge,
        });
        // The marks on the rim are short: in the lab they move every frame, and each changed
        // cell costs bytes on a slow link (six long spokes were 85 % of what a frame wrote).
        for [a, b] in table.rim_marks() {
            ctx.draw(&Line {
                x1: a.x,
                y1: a.y,
                x2: b.x,
                y2: b.y,
                color: th.spokes,
            });
        }
        if let Some(ring) = &table.ring {
            ctx.draw(&Circle {
                x: 0.0,
                y: 0.0,
                radius: ring.r,
                color: th.limit_circle,
            });
        }
        // Each pin's marker along its path (printed first: words printed later win); at its
        // end (below) the marker and its label, so pins read without colour.
        for p in &self.pic.pins {
            for m in &p.marks {
                ctx.print(m.x, m.y, Span::styled(p.marker.to_string(), self.pin_style));
            }
        }
        if self.words {
            if let (Some(ring), Some(at)) = (&table.ring, self.ring_at()) {
                let ring_style = Style::default().fg(th.limit_circle);
                ctx.print(at.x, at.y, Span::styled(ring.label.clone(), ring_style));
            }
            if let Some(sense) = self.sense_at(self.stuck_label().as_ref()) {
                let sense_style = Style::default().fg(th.table_edge);
                ctx.print(sense.x, sense.y, Span::styled(SENSE_LABEL, sense_style));
            }
        }
    }

    /// The pins' paths, the paper's run and the run's own trail.
    fn trails(&self, ctx: &mut Context) {
        for p in &self.pic.pins {
            polyline(ctx, &p.path, self.th.muted);
        }
        if let Some(p) = &self.pic.paper {
            polyline(ctx, &p.path, self.th.accent);
        }
        if let Some(p) = &self.pic.point {
            polyline(ctx, &p.trail, self.th.trail);
        }
    }

    /// The top layer: where it stuck, the step marks, the arrows and the pins' ends with
    /// their labels placed clear of one another, the body, the paper's run and the particle.
    fn labelled(&self, ctx: &mut Context) {
        let th = &self.th;
        let point = self.pic.point.as_ref();
        let stuck_label = self.stuck_label();
        if let Some((at, text)) = &stuck_label {
            ctx.print(
                at.x,
                at.y,
                Span::styled(text.clone(), Style::default().fg(th.stuck)),
            );
        }
        for m in point.iter().flat_map(|p| p.steps.iter().rev()) {
            ctx.print(m.x, m.y, Span::styled("·", Style::default().fg(th.notice)));
        }
        if let Some(p) = point {
            for fa in &p.arrows {
                arrow(ctx, p.at, fa.vec, crate::ui::chart::ink(th, fa.ink));
            }
        }
        for l in self.labels(stuck_label.as_ref()).0 {
            ctx.print(
                l.at.x,
                l.at.y,
                Span::styled(l.text, Style::default().fg(l.color)),
            );
        }
        self.body_and_particle(ctx);
    }

    /// Where it stuck, in words where there is room for them, else its glyph. Words that
    /// would run past the canvas's right edge read leftwards, ending in the glyph at the point
    /// (a number cut at the edge, `ξ=0.997`, would say another radius); where neither fits,
    /// the glyph alone.
    pub(super) fn stuck_label(&self) -> Option<(DVec2, String)> {
        let stuck = self.pic.point.as_ref().and_then(|p| p.stuck)?;
        let glyph = Some((stuck.at, STUCK_GLYPH.to_string()));
        if !self.words {
            return glyph;
        }
        let text = stuck.label();
        let n = text.chars().count() as i64;
        let cells = Cells {
            inner: self.inner,
            xb: self.xb,
            yb: self.yb,
            taken: Vec::new(),
        };
        let (_, col, _) = cells.of(stuck.at, 0);
        let w = i64::from(self.inner.width);
        if col + n <= w {
            return Some((stuck.at, text));
        }
        let start = col - (n - 1);
        let words = text.trim_start_matches(STUCK_GLYPH).trim_start();
        if start < 0 || w < 2 {
            return glyph;
        }
        // The x ratatui prints column `start` at (see `Cells::of`).
        let x = self.xb[0] + (start as f64 + 0.25) * (self.xb[1] - self.xb[0]) / (w - 1) as f64;
        Some((DVec2::new(x, stuck.at.y), format!("{words} {STUCK_GLYPH}")))
    }

    /// Where the ring's words go: its place, moved left to end at the canvas's edge rather
    /// than be cut there (`friction holds ξ≤0.` would say another radius).
    pub(super) fn ring_at(&self) -> Option<DVec2> {
        let ring = self.pic.table.ring.as_ref()?;
        let n = ring.label.chars().count() as i64;
        let w = i64::from(self.inner.width);
        let cells = Cells {
            inner: self.inner,
            xb: self.xb,
            yb: self.yb,
            taken: Vec::new(),
        };
        let (_, col, _) = cells.of(ring.at, 0);
        if col + n <= w || w < 2 {
            return Some(ring.at);
        }
        let start = (w - n).max(0);
        let x = self.xb[0] + (start as f64 + 0.25) * (self.xb[1] - self.xb[0]) / (w - 1) as f64;
        Some(DVec2::new(x, ring.at.y))
    }

    /// Where the words for the table's sense go: the picture's place, or the first corner of
    /// the table (upper right, lower left, lower right) clear of the particle, where it stuck
    /// and the ring's words (`↺ tab■ stuck…` clobbered the sense); None where no corner is.
    pub(super) fn sense_at(&self, stuck: Option<&(DVec2, String)>) -> Option<DVec2> {
        let mut cells = Cells {
            inner: self.inner,
            xb: self.xb,
            yb: self.yb,
            taken: Vec::new(),
        };
        if let Some(p) = &self.pic.point {
            cells.take_words(p.at, 1);
        }
        if let Some((p, text)) = stuck {
            cells.take_words(*p, text.chars().count());
        }
        if let (Some(ring), Some(at)) = (&self.pic.table.ring, self.ring_at()) {
            cells.take_words(at, ring.label.chars().count());
        }
        let n = SENSE_LABEL.chars().count();
        let s = self.pic.table.sense;
        let mirror = -s.x - n as f64 * self.cell.x;
        [
            s,
            DVec2::new(mirror, s.y),
            DVec2::new(s.x, -s.y),
            DVec2::new(mirror, -s.y),
        ]
        .into_iter()
        .find(|&p| cells.free(p, n))
    }

    /// The arrows' labels and the pins' ends, each placed clear of the particle, of the fixed
    /// words (where it stuck, the ξ = 1 circle, the sense) and of one another; a label with no
    /// free place is left out (the panel's legend names the arrows, the pins' markers mark
    /// their paths). Also the cells taken, for the tests.
    pub(super) fn labels(&self, stuck: Option<&(DVec2, String)>) -> (Vec<Label>, Cells) {
        let mut cells = Cells {
            inner: self.inner,
            xb: self.xb,
            yb: self.yb,
            taken: Vec::new(),
        };
        let point = self.pic.point.as_ref();
        if let Some(p) = point {
            cells.take(p.at, 1);
        }
        if let Some((p, text)) = stuck {
            cells.take_words(*p, text.chars().count());
        }
        if self.words {
            if let (Some(ring), Some(at)) = (&self.pic.table.ring, self.ring_at()) {
                cells.take_words(at, ring.label.chars().count());
            }
            if let Some(sense) = self.sense_at(stuck) {
                cells.take_words(sense, SENSE_LABEL.chars().count());
            }
        }
        let mut out = Vec::new();
        if let Some(p) = point {
            self.arrow_labels(p, &mut cells, &mut out);
        }
        self.pin_ends(&mut cells, &mut out);
        (out, cells)
    }

    /// Each arrow's label at its head, or the nearest free place beside it.
    fn arrow_labels(&self, point: &Point, cells: &mut Cells, out: &mut Vec<Label>) {
        let (at, cell) = (point.at, self.cell);
        for fa in &point.arrows {
            let mut head = at + fa.vec * 1.15;
            // Never under the particle's glyph (`co` read `●o`): right of it instead.
            let n = fa.label.chars().count();
            let len = n as f64 * cell.x;
            if (head.y - at.y).abs() < cell.y && head.x - cell.x < at.x && at.x < head.x + len {
                head.x = at.x + cell.x;
            }
            // Else a row off, above or below, or ending at the head.
            let rows = [0.0, 1.0, -1.0, 2.0, -2.0];
            let spot = [0.0, -(n as f64)]
                .into_iter()
                .flat_map(|dx| rows.map(|k| head + DVec2::new(dx * cell.x, k * cell.y)))
                .find(|h| cells.free(*h, n));
            if let Some(h) = spot {
                cells.take_words(h, n);
                out.push(Label {
                    at: h,
                    text: fa.label.into(),
                    color: crate::ui::chart::ink(&self.th, fa.ink),
                });
            }
        }
    }

    /// Each pin's end: its marker and label, beside the end where the run's own words leave
    /// room (else the marker along the path and the panel name it). An escape ends out of
    /// view: labelled where it leaves.
    fn pin_ends(&self, cells: &mut Cells, out: &mut Vec<Label>) {
        let cell = self.cell;
        for p in &self.pic.pins {
            let Some(e) = p.end_in(self.xb, self.yb) else {
                continue;
            };
            let n = p.name.chars().count();
            let back = n as f64 - 1.0;
            let spot = [(0.0, 0.0), (0.0, 1.0), (0.0, -1.0), (-back, 0.0)]
                .into_iter()
                .chain([(-back, 1.0), (-back, -1.0), (0.0, 2.0), (0.0, -2.0)])
                .map(|(dx, dy)| e + DVec2::new(dx * cell.x, dy * cell.y))
                .find(|h| cells.free(*h, n));
            if let Some(h) = spot {
                cells.take_words(h, n);
                out.push(Label {
                    at: h,
                    text: p.name.clone(),
                    color: self.pin_style.fg.unwrap_or(self.th.muted),
                });
            }
        }
    }

    /// The body's centre's path in the trail's colour, as the point's (thinned as trails
    /// are); the bar in the particle's, its centre a glyph of its own (it reads without
    /// colour, in `mono`); the paper's run's head; the particle (stuck, a square: it reads
    /// without colour).
    fn body_and_particle(&self, ctx: &mut Context) {
        let th = &self.th;
        if let Some(body) = &self.pic.body {
            let stride = body.path.len() / MAX_SEGMENTS + 1;
            let path: Vec<DVec2> = body.path.iter().step_by(stride).copied().collect();
            for w in path.windows(2) {
                ctx.draw(&Line {
                    x1: w[0].x,
                    y1: w[0].y,
                    x2: w[1].x,
                    y2: w[1].y,
                    color: th.trail,
                });
            }
            if let (Some(([a, b], _)), Some(c)) = (body.bar, self.body_glyph) {
                ctx.draw(&Line {
                    x1: a.x,
                    y1: a.y,
                    x2: b.x,
                    y2: b.y,
                    color: th.particle,
                });
                ctx.print(
                    c.x,
                    c.y,
                    Span::styled(BODY_GLYPH, Style::default().fg(th.particle)),
                );
            }
        }
        if let Some(p) = &self.pic.paper {
            let q = p.head;
            ctx.print(q.x, q.y, Span::styled("○", Style::default().fg(th.accent)));
        }
        if let Some(p) = &self.pic.point {
            let glyph = if p.stuck.is_some() { "■" } else { "●" };
            ctx.print(
                p.at.x,
                p.at.y,
                Span::styled(glyph, Style::default().fg(th.particle)),
            );
        }
    }
}
