//! Painting the canvas: the table, the trails, the arrows and the labels placed so that none
//! covers the particle or another, in the layers ratatui's canvas draws them.

use super::{BODY_GLYPH, ForceArrow, MAX_SEGMENTS, in_frame};
use crate::engine::model::rotate;
use crate::engine::{Frame, State};
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

/// Markers along a pin's path: at its quarters (and its end, with the label).
const PIN_MARKS: usize = 4;

/// The `n` states of `path` as a line in the frame shown, turned and scaled, thinned to at
/// most [`MAX_SEGMENTS`] segments.
fn polyline<'a>(
    ctx: &mut Context,
    path: impl Iterator<Item = &'a State>,
    n: usize,
    (frame, turn, scale): (Frame, f64, f64),
    color: Color,
) {
    let stride = n.div_ceil(MAX_SEGMENTS).max(1);
    let mut prev: Option<DVec2> = None;
    for (i, s) in path.enumerate() {
        if i % stride != 0 && i + 1 != n {
            continue;
        }
        let p = rotate(in_frame(s, frame), turn) * scale;
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

/// The trail of `sim` up to the τ on screen, from its path (a fixed τ grid, see
/// [`crate::sim::TRAIL_DT`]), joined to the particle where the path is still growing.
fn trail(ctx: &mut Context, sim: &crate::sim::Sim, frame: Frame, turn: f64, color: Color) {
    let path = sim.trail();
    let now = sim.now();
    let tail = path
        .last()
        .filter(|l| now.tau > l.tau && now.tau - l.tau <= crate::sim::TRAIL_DT)
        .map(|_| now);
    let n = path.len() + usize::from(tail.is_some());
    polyline(
        ctx,
        path.iter().chain(tail.as_ref()),
        n,
        (frame, turn, 1.0),
        color,
    );
}

/// Everything the canvas paints, worked out before painting: in world units of the frame
/// shown, turned as the picture is.
pub(super) struct Picture<'a> {
    pub th: Theme,
    pub inner: Rect,
    pub xb: [f64; 2],
    pub yb: [f64; 2],
    pub view: Frame,
    pub turn: f64,
    /// The point model is shown (`C` hides it).
    pub point: bool,
    pub now: State,
    pub table_r: f64,
    /// The table's angle in the picture (its rim marks).
    pub spin: f64,
    pub stuck: Option<(DVec2, f64)>,
    /// The release point and the initial velocity.
    pub x0: DVec2,
    pub v_init: DVec2,
    pub arrow_scale: f64,
    pub sim: &'a crate::sim::Sim,
    pub paper: Option<&'a crate::sim::Sim>,
    pub pins: &'a [crate::pin::Pin],
    pub units: Option<crate::engine::units::Units>,
    pub pin_style: Style,
    pub rod_path: Vec<DVec2>,
    pub bar: Option<([DVec2; 2], DVec2)>,
    pub forces: Vec<ForceArrow>,
    pub ring_label: DVec2,
    pub marks: Vec<State>,
    /// One terminal cell in world units.
    pub cell: DVec2,
    /// Words on the canvas only where there is room for them beside the drawing.
    pub words: bool,
    pub sense: DVec2,
}

/// The cells labels cover (row, first column, past the last): labels never cover the
/// particle or one another (in the lab `net` is `fr`, at one head).
struct Cells {
    inner: Rect,
    xb: [f64; 2],
    yb: [f64; 2],
    taken: Vec<(i64, i64, i64)>,
}

impl Cells {
    /// (As ratatui's canvas places text: (x − left)·(width − 1)/(right − left).)
    fn of(&self, p: DVec2, n: usize) -> (i64, i64, i64) {
        let (xb, yb) = (self.xb, self.yb);
        let (w, h) = (
            f64::from(self.inner.width.max(1) - 1),
            f64::from(self.inner.height.max(1) - 1),
        );
        let col = ((p.x - xb[0]) * w / (xb[1] - xb[0])).floor() as i64;
        let row = ((yb[1] - p.y) * h / (yb[1] - yb[0])).floor() as i64;
        (row, col, col + n as i64)
    }

    fn take(&mut self, p: DVec2, n: usize) {
        let c = self.of(p, n);
        self.taken.push(c);
    }

    fn free(&self, h: DVec2, n: usize) -> bool {
        let (r, a, b) = self.of(h, n);
        !self
            .taken
            .iter()
            .any(|&(tr, ta, tb)| tr == r && a < tb && ta < b)
    }
}

impl Picture<'_> {
    pub fn paint(&self, ctx: &mut Context) {
        self.table(ctx);
        ctx.layer();
        // The initial velocity beneath the trails: where they cross, the trail shows (in
        // the rotating frame D's whole path lies along its arrow).
        arrow(ctx, self.x0, self.v_init * self.arrow_scale, self.th.arrow);
        ctx.layer();
        self.trails(ctx);
        ctx.layer();
        self.labelled(ctx);
    }

    /// The table: its edge, three marks on its rim, the ξ = 1 circle, the pins' markers
    /// along their paths and, where there is room, the words for the circle and the sense.
    fn table(&self, ctx: &mut Context) {
        let th = &self.th;
        let table_r = self.table_r;
        ctx.draw(&Circle {
            x: 0.0,
            y: 0.0,
            radius: table_r,
            color: th.table_edge,
        });
        // Three short marks on the rim show the table turning: in the lab they move
        // every frame, so they are kept short (each changed cell costs bytes on a slow
        // link; six long spokes were 85 % of what a playing frame wrote).
        for k in 0..3 {
            let d = rotate(
                DVec2::X,
                self.spin + k as f64 * 2.0 * std::f64::consts::PI / 3.0,
            );
            let (a, b) = (d * 0.9 * table_r, d * table_r);
            ctx.draw(&Line {
                x1: a.x,
                y1: a.y,
                x2: b.x,
                y2: b.y,
                color: th.spokes,
            });
        }
        ctx.draw(&Circle {
            x: 0.0,
            y: 0.0,
            radius: 1.0,
            color: th.limit_circle,
        });
        // Each pin: its marker along its path (printed first: words printed later win),
        // and at its end (below) the marker and its label, so pins read without colour.
        for p in self.pins {
            let k = p.scale(self.units).0;
            let at = |s: &State| rotate(in_frame(s, self.view), p.spec.turn) * k;
            let n = p.path.len();
            for k in 1..PIN_MARKS {
                let s = &p.path[k * (n - 1) / PIN_MARKS];
                let m = at(s);
                ctx.print(m.x, m.y, Span::styled(p.marker.to_string(), self.pin_style));
            }
        }
        if self.words {
            // ξ = 1 is R_max = μg/Ω², the whole story: inside it friction can hold the
            // particle.
            ctx.print(
                self.ring_label.x,
                self.ring_label.y,
                Span::styled("ξ=1 (R_max)", Style::default().fg(th.limit_circle)),
            );
            // The table's sense of rotation (counterclockwise), in both frames.
            ctx.print(
                self.sense.x,
                self.sense.y,
                Span::styled("↺ table", Style::default().fg(th.table_edge)),
            );
        }
    }

    /// The pins' paths, the paper's run and the run's own trail.
    fn trails(&self, ctx: &mut Context) {
        let (view, turn) = (self.view, self.turn);
        for p in self.pins {
            let look = (view, p.spec.turn, p.scale(self.units).0);
            polyline(ctx, p.path.iter(), p.path.len(), look, self.th.muted);
        }
        if let Some(p) = self.paper {
            trail(ctx, p, view, turn, self.th.accent);
        }
        if self.point {
            trail(ctx, self.sim, view, turn, self.th.trail);
        }
    }

    /// The top layer: where it stuck, the step marks, the arrows and the pins' ends with
    /// their labels placed clear of one another, the body, the paper's run and the particle.
    fn labelled(&self, ctx: &mut Context) {
        let th = &self.th;
        let stuck_label = self.stuck.map(|(at, tau)| {
            let text = if self.words {
                format!("× stuck τ={}", crate::ui::panel::num(tau, 2))
            } else {
                "×".into()
            };
            (at, text)
        });
        if let Some((at, text)) = &stuck_label {
            ctx.print(
                at.x,
                at.y,
                Span::styled(text.clone(), Style::default().fg(th.stuck)),
            );
        }
        // Integrator step mode: each step's end on the trail (the latest 500).
        for m in self.marks.iter().rev().take(500) {
            let p = rotate(in_frame(m, self.view), self.turn);
            ctx.print(p.x, p.y, Span::styled("·", Style::default().fg(th.notice)));
        }
        let at = rotate(in_frame(&self.now, self.view), self.turn);
        let mut cells = Cells {
            inner: self.inner,
            xb: self.xb,
            yb: self.yb,
            taken: Vec::new(),
        };
        if self.point {
            cells.take(at, 1);
        }
        if let Some((p, text)) = stuck_label {
            cells.take(p, text.chars().count());
        }
        if self.words {
            cells.take(self.ring_label, 11);
            cells.take(self.sense, 7);
        }
        self.arrows(ctx, at, &mut cells);
        self.pin_ends(ctx, &mut cells);
        self.body_and_particle(ctx, at);
    }

    /// The arrows at the particle `at`, each labelled at its head where the label is free.
    fn arrows(&self, ctx: &mut Context, at: DVec2, cells: &mut Cells) {
        let cell = self.cell;
        for fa in &self.forces {
            let vec = rotate(fa.vec, self.turn);
            let color = crate::ui::chart::ink(&self.th, fa.ink);
            arrow(ctx, at, vec, color);
            let mut head = at + vec * 1.15;
            // Never under the particle's glyph (`co` read `●o`): right of it instead.
            let n = fa.label.chars().count();
            let len = n as f64 * cell.x;
            if (head.y - at.y).abs() < cell.y && head.x - cell.x < at.x && at.x < head.x + len {
                head.x = at.x + cell.x;
            }
            // Else a row off, above or below.
            if let Some(h) = [0.0, 1.0, -1.0, 2.0, -2.0]
                .into_iter()
                .map(|k| head + DVec2::Y * (k * cell.y))
                .find(|h| cells.free(*h, n))
            {
                head = h;
            }
            cells.take(head, n);
            ctx.print(
                head.x,
                head.y,
                Span::styled(fa.label, Style::default().fg(color)),
            );
        }
    }

    /// Each pin's end: its marker and label, beside the end where the run's own words leave
    /// room (else the marker along the path and the panel name it). An escape ends out of
    /// view: labelled where it leaves.
    fn pin_ends(&self, ctx: &mut Context, cells: &mut Cells) {
        let (xb, yb, cell) = (self.xb, self.yb, self.cell);
        let inside = |q: DVec2| (xb[0]..=xb[1]).contains(&q.x) && (yb[0]..=yb[1]).contains(&q.y);
        for p in self.pins {
            let k = p.scale(self.units).0;
            let place = |s: &State| rotate(in_frame(s, self.view), p.spec.turn) * k;
            let Some(e) = p.path.iter().rev().map(place).find(|q| inside(*q)) else {
                continue;
            };
            let text = format!("{}{}", p.marker, p.spec.label);
            let n = text.chars().count();
            let back = n as f64 - 1.0;
            let spot = [(0.0, 0.0), (0.0, 1.0), (0.0, -1.0), (-back, 0.0)]
                .into_iter()
                .chain([(-back, 1.0), (-back, -1.0), (0.0, 2.0), (0.0, -2.0)])
                .map(|(dx, dy)| e + DVec2::new(dx * cell.x, dy * cell.y))
                .find(|h| cells.free(*h, n));
            if let Some(h) = spot {
                cells.take(h, n);
                ctx.print(h.x, h.y, Span::styled(text, self.pin_style));
            }
        }
    }

    /// The body's centre's path in the trail's colour, as the point's; the bar in the
    /// particle's, its centre a glyph of its own (it reads without colour, in `mono`); the
    /// paper's run's head; the particle at `at` (stuck, a square: it reads without colour).
    fn body_and_particle(&self, ctx: &mut Context, at: DVec2) {
        let th = &self.th;
        for w in self.rod_path.windows(2) {
            ctx.draw(&Line {
                x1: w[0].x,
                y1: w[0].y,
                x2: w[1].x,
                y2: w[1].y,
                color: th.trail,
            });
        }
        if let Some(([a, b], c)) = self.bar {
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
        if let Some(p) = self.paper {
            let q = rotate(in_frame(&p.now(), self.view), self.turn);
            ctx.print(q.x, q.y, Span::styled("○", Style::default().fg(th.accent)));
        }
        if self.point {
            let glyph = if self.stuck.is_some() { "■" } else { "●" };
            ctx.print(
                at.x,
                at.y,
                Span::styled(glyph, Style::default().fg(th.particle)),
            );
        }
    }
}
