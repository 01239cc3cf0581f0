//! The braille turntable: table edge, ξ = 1 circle, spokes, trail(s), particle, initial
//! velocity and force arrows, in the lab or the rotating frame at true aspect ratio.

use crate::app::{App, CanvasGeom};
use crate::engine::model::rotate;
use crate::engine::rod::{RodState, RodTrack};
use crate::engine::{Frame, State};
use crate::theme::Theme;
use glam::DVec2;
use ratatui::Frame as TuiFrame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::widgets::canvas::Canvas;

mod paint;

pub use crate::plot::page::arrows::{FORCE_SHARE, ForceArrow, arrows, force_arrows, velocity};
pub use crate::plot::page::table::{auto_extent, in_frame};
use paint::Picture;

/// Most trail segments drawn per run (longer trails are thinned evenly).
const MAX_SEGMENTS: usize = 3000;

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

/// The body's centre on the canvas (`⊕`, at the middle of its bar).
pub const BODY_GLYPH: &str = "⊕";

/// The body as the canvas draws it at `tau`: its track's state, or where it left the view
/// once an escaping body's track has followed it out (kept there, as the point is).
fn body_shown(rod: &RodTrack, tau: f64) -> Option<RodState> {
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

/// The canvas's title: the frame shown and, zoomed, what the zoom follows.
fn title(app: &App, point: bool) -> String {
    let mut title = match app.view.frame {
        Frame::Lab => " lab frame ".to_string(),
        Frame::Table => " rotating frame ".to_string(),
    };
    if app.view.zoom != 1.0 {
        title.push_str(&format!(
            "zoom ×{} (follows {}) ",
            crate::ui::panel::num(app.view.zoom, 2),
            if point { "●" } else { "the body" }
        ));
    }
    title
}

/// What a zoom follows, turned as the picture is: the particle, or with the point model
/// hidden (`C`) the body's centre; the origin when not zoomed in.
fn followed(app: &App, body_now: Option<RodState>, point: bool) -> DVec2 {
    let (turn, view) = (app.view.turn, app.view.frame);
    if app.view.zoom > 1.0 {
        match body_now.filter(|_| !point) {
            Some(b) => rotate(
                if view == Frame::Lab {
                    rotate(b.q, b.tau)
                } else {
                    b.q
                },
                turn,
            ),
            None => rotate(in_frame(&app.sim().now(), view), turn),
        }
    } else {
        DVec2::ZERO
    }
}

/// Where and when it stuck: the rest point on the table, in the frame shown (in the lab,
/// where that point of the table is now: the particle rides it), turned as the picture is.
fn stuck_at(app: &App, point: bool) -> Option<(DVec2, f64)> {
    let now = app.sim().now();
    match app.sim().run.status() {
        crate::engine::Status::Stuck { tau, q } if now.tau >= tau && point => {
            let at = match app.view.frame {
                Frame::Lab => rotate(q, now.tau),
                Frame::Table => q,
            };
            Some((rotate(at, app.view.turn), tau))
        }
        _ => None,
    }
}

/// The finite body's centre's path so far beside the point's (thinned as trails are), in
/// the frame shown.
fn rod_path(app: &App) -> Vec<DVec2> {
    let (now, view, turn) = (app.sim().now(), app.view.frame, app.view.turn);
    app.rod().map_or_else(Vec::new, |rod| {
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
    })
}

/// The bar between the body's two masses, and where its centre's glyph is printed.
fn bar(
    app: &App,
    th: &Theme,
    bounds: ([f64; 2], [f64; 2]),
    inner: Rect,
) -> Option<([DVec2; 2], DVec2)> {
    let (now, view, turn) = (app.sim().now(), app.view.frame, app.view.turn);
    app.rod().and_then(|rod| {
        let s = body_shown(rod, now.tau)?;
        let spin = turn + if view == Frame::Lab { s.tau } else { 0.0 };
        let q = rotate(s.q, spin);
        let centre = on_cell(q, bounds, (inner.width, inner.height), th.marker);
        Some((s.contacts(rod.l).map(|c| rotate(c, spin)), centre))
    })
}

/// Integrator step mode: each step's end so far.
fn step_marks(app: &App, point: bool) -> Vec<State> {
    let tau_now = app.sim().now().tau;
    if app.view.step_mode && point {
        app.sim()
            .step_marks
            .iter()
            .filter(|m| m.tau <= tau_now)
            .copied()
            .collect()
    } else {
        Vec::new()
    }
}

/// Draws the canvas and returns its geometry (where it is and which world it shows).
pub fn render(f: &mut TuiFrame, area: Rect, app: &App, th: &Theme) -> CanvasGeom {
    // With the point model hidden (`C`), the body's centre is what a zoom follows.
    let point = app.point_shown();
    let body_now = app
        .rod()
        .and_then(|rod| body_shown(rod, app.sim().now().tau));
    let block = super::titled(title(app, point), th);
    let inner = block.inner(area);
    let r0 = auto_extent(app);
    let r = r0 / app.view.zoom;
    // The picture is turned by `app.turn` so a release point clicked anywhere shows there
    // (the physics is rotationally symmetric: the model keeps its release on +x). Zoomed in,
    // the view follows the particle.
    let turn = app.view.turn;
    let now = app.sim().now();
    let view = app.view.frame;
    let centre = followed(app, body_now, point) + app.view.pan * r0;
    let (xb, yb) = bounds(inner.width, inner.height, centre, r);
    let arrow_scale = 0.3 * r0 / app.initial().xi0.max(1.0);
    let geom = CanvasGeom {
        area: inner,
        x: xb,
        y: yb,
        arrow_scale,
        frame: app.view.frame,
        turn,
        page: crate::app::pages::Page::Turntable,
    };
    let table_r = 1.5f64.max(app.initial().xi0 * 1.2);
    // The initial velocity as the frame shown sees it: lab v, or u relative to the table.
    let s0 = app.initial().state();
    let v_init = match view {
        Frame::Lab => s0.v,
        Frame::Table => s0.u(),
    };
    let half_width = 0.5 * (xb[1] - xb[0]).min(yb[1] - yb[0]);
    let picture = Picture {
        inner,
        xb,
        yb,
        view,
        turn,
        point,
        now,
        table_r,
        spin: turn + if view == Frame::Lab { now.tau } else { 0.0 },
        stuck: stuck_at(app, point),
        x0: rotate(DVec2::new(app.initial().xi0, 0.0), turn),
        v_init: rotate(v_init, turn),
        arrow_scale,
        sim: app.sim(),
        paper: app.paper(),
        pins: &app.pins,
        units: app.units,
        pin_style: Style::default().fg(th.muted),
        rod_path: rod_path(app),
        bar: bar(app, th, (xb, yb), inner),
        // The arrows are the point's: hidden with it.
        forces: if point {
            arrows(app, half_width, arrow_scale)
        } else {
            Vec::new()
        },
        ring_label: rotate(DVec2::new(-0.95, -0.72), turn),
        marks: step_marks(app, point),
        // One terminal cell in world units.
        cell: DVec2::new(
            (xb[1] - xb[0]) / f64::from(inner.width.max(1)),
            (yb[1] - yb[0]) / f64::from(inner.height.max(1)),
        ),
        // Words on the canvas only where there is room for them beside the drawing.
        words: inner.width >= 40 && inner.height >= 10,
        sense: DVec2::new(-0.8, 0.62) * table_r,
        th: th.clone(),
    };
    let canvas = Canvas::default()
        .block(block)
        .marker(th.marker)
        .background_color(th.background)
        .x_bounds(xb)
        .y_bounds(yb)
        .paint(move |ctx| picture.paint(ctx));
    f.render_widget(canvas, area);
    geom
}
