//! The braille turntable: table edge, ξ = 1 circle, spokes, trail(s), particle, initial
//! velocity and force arrows, in the lab or the rotating frame at true aspect ratio.

use crate::app::{App, CanvasGeom};
use crate::engine::model::{coupled_forces, rotate};
use crate::engine::{Frame, State};
use glam::DVec2;
use ratatui::Frame as TuiFrame;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::Span;
use ratatui::widgets::canvas::{Canvas, Circle, Context, Line};

/// Most trail segments drawn per run (longer trails are thinned evenly).
const MAX_SEGMENTS: usize = 3000;

/// A sample's position in the frame shown: lab `r`, or `q = R(−τ) r`.
pub fn in_frame(s: &State, frame: Frame) -> DVec2 {
    match frame {
        Frame::Lab => s.r,
        Frame::Table => s.q(),
    }
}

/// The auto-framed half-width: the table, the release point and everything the run's trail
/// reached, a little beyond. The paper's run beside it may widen the view by half at most, so
/// when it escapes it is seen leaving rather than shrinking the table to a dot.
pub fn auto_extent(app: &App) -> f64 {
    let reach = |sim: &crate::sim::Sim| sim.trail().iter().fold(0.0, |m: f64, s| m.max(s.xi()));
    let own = reach(app.sim()).max(app.initial().xi0).max(1.0);
    let m = app
        .paper()
        .map_or(own, |p| own.max(reach(p).min(1.5 * own)));
    // Pins widen it as the paper's run does, so a pinned D (from ξ0 = 1.1) stays in view.
    let m = app.pins.iter().fold(m, |m, p| {
        let r = p.path.iter().fold(0.0, |m: f64, s| m.max(s.xi())) * p.scale(app.units).0;
        m.max(r.min(1.5 * own))
    });
    (m * 1.1)
        .max(1.5)
        .min(crate::app::state::view_radius(&app.initial()) * 1.1)
}

/// World bounds of a canvas of `w`×`h` cells showing a disc of radius `r` around `c`, with
/// cells twice as tall as wide: circles come out round.
pub fn bounds(w: u16, h: u16, c: DVec2, r: f64) -> ([f64; 2], [f64; 2]) {
    let (w, h) = (f64::from(w.max(1)), 2.0 * f64::from(h.max(1)));
    let (rx, ry) = if w >= h {
        (r * w / h, r)
    } else {
        (r, r * h / w)
    };
    ([c.x - rx, c.x + rx], [c.y - ry, c.y + ry])
}

fn arrow(ctx: &mut Context, from: DVec2, vec: DVec2, color: Color) {
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

/// A force arrow as drawn: its label at the head (so it reads without colour), the word the
/// legend uses, and the vector in world units of the frame shown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceArrow {
    pub label: &'static str,
    pub word: &'static str,
    pub vec: DVec2,
    pub color: Color,
}

/// Share of the visible half-width the longest force arrow takes.
pub const FORCE_SHARE: f64 = 0.2;

/// The forces on the particle in the frame shown (Sec. II). In the lab, an inertial frame,
/// only friction acts in the plane (gravity and the normal force cancel; at μ = 0 nothing
/// does). In the rotating frame the fictitious Coriolis and centrifugal forces act too. All
/// are scaled together so the longest is [`FORCE_SHARE`] of `half_width`.
pub fn force_arrows(app: &App, half_width: f64) -> Vec<ForceArrow> {
    forces(app, half_width).0
}

/// [`force_arrows`], and the net force at their scale (their sum: du/dτ in the rotating
/// frame, dv/dτ in the lab).
fn forces(app: &App, half_width: f64) -> (Vec<ForceArrow>, DVec2) {
    let th = &app.theme;
    let now = app.sim().now();
    let [fr, co, ce] = coupled_forces(&now, app.initial().frictionless, app.settings().coupling);
    let mut out = Vec::new();
    let mut push = |label, word, vec: DVec2, color| {
        if vec.length() > 0.0 {
            out.push(ForceArrow {
                label,
                word,
                vec,
                color,
            });
        }
    };
    match app.view {
        Frame::Lab => push("fr", "friction", rotate(fr, now.tau), th.friction),
        Frame::Table => {
            push("fr", "friction", fr, th.friction);
            push("co", "Coriolis", co, th.coriolis);
            push("cf", "centrifugal", ce, th.centrifugal);
        }
    }
    let mut net: DVec2 = out.iter().map(|f| f.vec).sum();
    let longest = out.iter().fold(0.0, |m: f64, f| m.max(f.vec.length()));
    if longest > 0.0 {
        let k = FORCE_SHARE * half_width / longest;
        for f in &mut out {
            f.vec *= k;
        }
        net *= k;
    }
    (out, net)
}

/// The arrows the canvas draws at the particle, each labelled at its head: the forces (`a`),
/// the net force (`A`, at the forces' scale) and the velocity (`i`: relative to the table in
/// the rotating frame, the lab velocity in the lab; `speed_scale` world units per unit speed,
/// as the initial velocity's arrow). A zero vector is not drawn.
pub fn arrows(app: &App, half_width: f64, speed_scale: f64) -> Vec<ForceArrow> {
    let th = &app.theme;
    let (mut out, net) = forces(app, half_width);
    if !app.forces {
        out.clear();
    }
    // Below this the sum is rounding: the forces balance (stuck).
    let balanced = 1e-9 * half_width;
    if app.net_force && net.length() > balanced {
        out.push(ForceArrow {
            label: "net",
            word: "net force",
            vec: net,
            color: th.foreground,
        });
    }
    if app.velocity {
        let (label, word, v) = velocity(app);
        if v.length() > 0.0 {
            out.push(ForceArrow {
                label,
                word,
                vec: v * speed_scale,
                color: th.arrow,
            });
        }
    }
    out
}

/// The velocity the frame shown sees: `u` relative to the table (rotating), `v` (lab).
pub fn velocity(app: &App) -> (&'static str, &'static str, DVec2) {
    let now = app.sim().now();
    match app.view {
        Frame::Lab => ("v", "velocity (lab)", now.v),
        Frame::Table => ("u", "velocity rel. table", now.u()),
    }
}

/// The body's centre on the canvas (`⊕`, at the middle of its bar).
pub const BODY_GLYPH: &str = "⊕";

/// The body as the canvas draws it at `tau`: its track's state, or where it left the view
/// once an escaping body's track has followed it out (kept there, as the point is).
fn body_shown(
    rod: &crate::engine::rod::RodTrack,
    tau: f64,
) -> Option<crate::engine::rod::RodState> {
    rod.at(tau).or_else(|| rod.left().filter(|s| tau >= s.tau))
}

/// Where to print a glyph so that it lands in the cell whose dots draw `p`: ratatui places a
/// line's dots on a grid of `marker`'s resolution (rounded, over the cells' dots) but a label
/// at (x − left)·(width − 1)/(right − left), truncated, so a label printed at `p` itself may
/// sit a cell off the line through `p` (the body's `⊕` beside its bar).
fn on_cell(
    p: DVec2,
    (xb, yb): ([f64; 2], [f64; 2]),
    (w, h): (u16, u16),
    marker: ratatui::symbols::Marker,
) -> DVec2 {
    use ratatui::symbols::Marker;
    let (dx, dy) = match marker {
        Marker::Braille | Marker::Octant => (2.0, 4.0),
        Marker::Sextant => (2.0, 3.0),
        Marker::Quadrant => (2.0, 2.0),
        Marker::HalfBlock => (1.0, 2.0),
        _ => (1.0, 1.0),
    };
    let axis = |v: f64, lo: f64, hi: f64, n: u16, dots: f64, down: bool| {
        let n = f64::from(n);
        let span = hi - lo;
        if n < 2.0 || span <= 0.0 {
            return v;
        }
        let from = if down { hi - v } else { v - lo };
        let dot = (from * (n * dots - 1.0) / span).round();
        let cell = (dot / dots).floor();
        let at = ((cell + 0.25) * span / (n - 1.0)).min(span);
        if down { hi - at } else { lo + at }
    };
    DVec2::new(
        axis(p.x, xb[0], xb[1], w, dx, false),
        axis(p.y, yb[0], yb[1], h, dy, true),
    )
}

/// Draws the canvas and returns its geometry (where it is and which world it shows).
pub fn render(f: &mut TuiFrame, area: Rect, app: &App) -> CanvasGeom {
    let th = app.theme.clone();
    let mut title = match app.view {
        Frame::Lab => " lab frame ".to_string(),
        Frame::Table => " rotating frame ".to_string(),
    };
    // With the point model hidden (`C`), the body's centre is what a zoom follows.
    let point = app.point_shown();
    let body_now = app
        .rod()
        .and_then(|rod| body_shown(rod, app.sim().now().tau));
    if app.zoom != 1.0 {
        title.push_str(&format!(
            "zoom ×{} (follows {}) ",
            crate::ui::panel::num(app.zoom, 2),
            if point { "●" } else { "the body" }
        ));
    }
    let block = super::titled(title, &th);
    let inner = block.inner(area);
    let r0 = auto_extent(app);
    let r = r0 / app.zoom;
    // The picture is turned by `app.turn` so a release point clicked anywhere shows there
    // (the physics is rotationally symmetric: the model keeps its release on +x). Zoomed in,
    // the view follows the particle.
    let turn = app.turn;
    let now = app.sim().now();
    let view = app.view;
    let follow = if app.zoom > 1.0 {
        match body_now.filter(|_| !point) {
            Some(b) => rotate(
                if view == Frame::Lab {
                    rotate(b.q, b.tau)
                } else {
                    b.q
                },
                turn,
            ),
            None => rotate(in_frame(&now, view), turn),
        }
    } else {
        DVec2::ZERO
    };
    let centre = follow + app.pan * r0;
    let (xb, yb) = bounds(inner.width, inner.height, centre, r);
    let arrow_scale = 0.3 * r0 / app.initial().xi0.max(1.0);
    let geom = CanvasGeom {
        area: inner,
        x: xb,
        y: yb,
        arrow_scale,
        frame: app.view,
        turn,
        page: crate::app::pages::Page::Turntable,
    };
    let table_r = 1.5f64.max(app.initial().xi0 * 1.2);
    let spin = turn + if view == Frame::Lab { now.tau } else { 0.0 };
    // Where and when it stuck: the rest point in the frame shown (in the lab, where it was at
    // the stop; it rides the table from there).
    let stuck = match app.sim().run.status() {
        crate::engine::Status::Stuck { tau, q } if now.tau >= tau && point => {
            let at = match view {
                Frame::Lab => rotate(q, tau),
                Frame::Table => q,
            };
            Some((rotate(at, turn), tau))
        }
        _ => None,
    };
    // The initial velocity as the frame shown sees it: lab v, or u relative to the table.
    let s0 = app.initial().state();
    let v_init = match view {
        Frame::Lab => s0.v,
        Frame::Table => s0.u(),
    };
    let x0 = rotate(DVec2::new(app.initial().xi0, 0.0), turn);
    let v_init = rotate(v_init, turn);
    let sim = app.sim();
    let paper = app.paper();
    let pins = &app.pins;
    let units = app.units;
    let pin_style = Style::default().fg(th.muted);
    // The finite body's centre, its path so far beside the point's (thinned as trails are),
    // and the body as a bar between its two masses, in the frame shown.
    let rod_path: Vec<DVec2> = app.rod().map_or_else(Vec::new, |rod| {
        let n = rod.states.partition_point(|s| s.tau <= now.tau);
        let stride = n / MAX_SEGMENTS + 1;
        rod.states[..n]
            .iter()
            .step_by(stride)
            .map(|s| {
                let q = if view == Frame::Lab {
                    rotate(s.q, s.tau)
                } else {
                    s.q
                };
                rotate(q, turn)
            })
            .collect()
    });
    // The bar between the two masses, and its centre's glyph.
    let bar = app.rod().and_then(|rod| {
        let s = body_shown(rod, now.tau)?;
        let spin = turn + if view == Frame::Lab { s.tau } else { 0.0 };
        let q = rotate(s.q, spin);
        let centre = on_cell(q, (xb, yb), (inner.width, inner.height), th.marker);
        Some((s.contacts(rod.l).map(|c| rotate(c, spin)), centre))
    });
    let half_width = 0.5 * (xb[1] - xb[0]).min(yb[1] - yb[0]);
    // The arrows are the point's: hidden with it.
    let forces = if point {
        arrows(app, half_width, arrow_scale)
    } else {
        Vec::new()
    };
    let ring_label = rotate(DVec2::new(-0.95, -0.72), turn);
    let tau_now = now.tau;
    let marks: Vec<State> = if app.step_mode && point {
        app.sim()
            .step_marks
            .iter()
            .filter(|m| m.tau <= tau_now)
            .copied()
            .collect()
    } else {
        Vec::new()
    };
    // One terminal cell in world units.
    let cell = DVec2::new(
        (xb[1] - xb[0]) / f64::from(inner.width.max(1)),
        (yb[1] - yb[0]) / f64::from(inner.height.max(1)),
    );
    // Words on the canvas only where there is room for them beside the drawing.
    let words = inner.width >= 40 && inner.height >= 10;
    let sense = DVec2::new(-0.8, 0.62) * table_r;
    let canvas = Canvas::default()
        .block(block)
        .marker(th.marker)
        .background_color(th.background)
        .x_bounds(xb)
        .y_bounds(yb)
        .paint(move |ctx| {
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
                let d = rotate(DVec2::X, spin + k as f64 * 2.0 * std::f64::consts::PI / 3.0);
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
            for p in pins {
                let k = p.scale(units).0;
                let at = |s: &State| rotate(in_frame(s, view), p.spec.turn) * k;
                let n = p.path.len();
                for k in 1..PIN_MARKS {
                    let s = &p.path[k * (n - 1) / PIN_MARKS];
                    let m = at(s);
                    ctx.print(m.x, m.y, Span::styled(p.marker.to_string(), pin_style));
                }
            }
            if words {
                // ξ = 1 is R_max = μg/Ω², the whole story: inside it friction can hold the
                // particle.
                ctx.print(
                    ring_label.x,
                    ring_label.y,
                    Span::styled("ξ=1 (R_max)", Style::default().fg(th.limit_circle)),
                );
                // The table's sense of rotation (counterclockwise), in both frames.
                ctx.print(
                    sense.x,
                    sense.y,
                    Span::styled("↺ table", Style::default().fg(th.table_edge)),
                );
            }
            ctx.layer();
            // The initial velocity beneath the trails: where they cross, the trail shows (in
            // the rotating frame D's whole path lies along its arrow).
            arrow(ctx, x0, v_init * arrow_scale, th.arrow);
            ctx.layer();
            for p in pins {
                let look = (view, p.spec.turn, p.scale(units).0);
                polyline(ctx, p.path.iter(), p.path.len(), look, th.muted);
            }
            if let Some(p) = paper {
                trail(ctx, p, view, turn, th.accent);
            }
            if point {
                trail(ctx, sim, view, turn, th.trail);
            }
            ctx.layer();
            let stuck_label = stuck.map(|(at, tau)| {
                let text = if words {
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
            for m in marks.iter().rev().take(500) {
                let p = rotate(in_frame(m, view), turn);
                ctx.print(p.x, p.y, Span::styled("·", Style::default().fg(th.notice)));
            }
            let at = rotate(in_frame(&now, view), turn);
            // The cells a label covers (row, first column, past the last): labels never
            // cover the particle or one another (in the lab `net` is `fr`, at one head).
            // (As ratatui's canvas places text: (x − left)·(width − 1)/(right − left).)
            let cells = |p: DVec2, n: usize| {
                let (w, h) = (
                    f64::from(inner.width.max(1) - 1),
                    f64::from(inner.height.max(1) - 1),
                );
                let col = ((p.x - xb[0]) * w / (xb[1] - xb[0])).floor() as i64;
                let row = ((yb[1] - p.y) * h / (yb[1] - yb[0])).floor() as i64;
                (row, col, col + n as i64)
            };
            let mut taken = if point {
                vec![cells(at, 1)]
            } else {
                Vec::new()
            };
            taken.extend(stuck_label.map(|(p, text)| cells(p, text.chars().count())));
            if words {
                taken.push(cells(ring_label, 11));
                taken.push(cells(sense, 7));
            }
            let free = |h: DVec2, n: usize, taken: &[(i64, i64, i64)]| {
                let (r, a, b) = cells(h, n);
                !taken
                    .iter()
                    .any(|&(tr, ta, tb)| tr == r && a < tb && ta < b)
            };
            for fa in &forces {
                let vec = rotate(fa.vec, turn);
                arrow(ctx, at, vec, fa.color);
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
                    .find(|h| free(*h, n, &taken))
                {
                    head = h;
                }
                taken.push(cells(head, n));
                ctx.print(
                    head.x,
                    head.y,
                    Span::styled(fa.label, Style::default().fg(fa.color)),
                );
            }
            // Each pin's end: its marker and label, beside the end where the run's own
            // words leave room (else the marker along the path and the panel name it). An
            // escape ends out of view: labelled where it leaves.
            let inside =
                |q: DVec2| (xb[0]..=xb[1]).contains(&q.x) && (yb[0]..=yb[1]).contains(&q.y);
            for p in pins {
                let k = p.scale(units).0;
                let place = |s: &State| rotate(in_frame(s, view), p.spec.turn) * k;
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
                    .find(|h| free(*h, n, &taken));
                if let Some(h) = spot {
                    taken.push(cells(h, n));
                    ctx.print(h.x, h.y, Span::styled(text, pin_style));
                }
            }
            // The body's centre's path in the trail's colour, as the point's; the bar in the
            // particle's, its centre a glyph of its own (it reads without colour, in `mono`).
            for w in rod_path.windows(2) {
                ctx.draw(&Line {
                    x1: w[0].x,
                    y1: w[0].y,
                    x2: w[1].x,
                    y2: w[1].y,
                    color: th.trail,
                });
            }
            if let Some(([a, b], c)) = bar {
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
            if let Some(p) = paper {
                let q = rotate(in_frame(&p.now(), view), turn);
                ctx.print(q.x, q.y, Span::styled("○", Style::default().fg(th.accent)));
            }
            // Stuck, the particle is a square: it reads without colour.
            if point {
                let glyph = if stuck.is_some() { "■" } else { "●" };
                ctx.print(
                    at.x,
                    at.y,
                    Span::styled(glyph, Style::default().fg(th.particle)),
                );
            }
        });
    f.render_widget(canvas, area);
    geom
}
