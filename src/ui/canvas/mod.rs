//! The braille turntable: the page's description (`plot::page::table::Picture`, which `E`
//! writes too) painted at true aspect ratio. What is the terminal's alone stays here: the
//! bounds for the cells' aspect, where a glyph lands in a cell, the labels kept clear of one
//! another, long paths thinned, the theme's colours.

use crate::app::{App, CanvasGeom};
use crate::engine::Frame;
use crate::theme::Theme;
use glam::DVec2;
use ratatui::Frame as TuiFrame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::widgets::canvas::Canvas;

mod paint;

pub use crate::plot::page::arrows::{FORCE_SHARE, ForceArrow, arrows, force_arrows, velocity};
use paint::Painter;

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
fn title(app: &App, frame: Frame, point: bool) -> String {
    let mut title = match frame {
        Frame::Lab => " lab frame ".to_string(),
        Frame::Table => " rotating frame ".to_string(),
    };
    if app.view().zoom != 1.0 {
        title.push_str(&format!(
            "zoom ×{} (follows {}) ",
            crate::present::num(app.view().zoom, 2),
            if point { "●" } else { "the body" }
        ));
    }
    title
}

/// The two canvases of a split view (`%`): side by side, or one above the other where that
/// shows the larger table. A table fills the smaller of a canvas's width and twice its
/// height (cells are twice as tall as wide), so the arrangement whose smaller side is longer
/// wins.
pub fn split(area: Rect) -> [Rect; 2] {
    use ratatui::layout::{Constraint, Layout};
    let (w, h) = (area.width, area.height);
    let beside = (w / 2).min(2 * h);
    let stacked = w.min(h / 2 * 2);
    let halves = [Constraint::Ratio(1, 2), Constraint::Ratio(1, 2)];
    if beside >= stacked {
        Layout::horizontal(halves).areas(area)
    } else {
        Layout::vertical(halves).areas(area)
    }
}

/// Draws the canvas (both frames' in a split view, the frame chosen first) and returns the
/// geometry of each (where it is and which world it shows).
pub fn render(f: &mut TuiFrame, area: Rect, app: &App, th: &Theme) -> Vec<CanvasGeom> {
    if !app.view().split {
        return vec![render_in(f, area, app, app.view().frame, th)];
    }
    let other = match app.view().frame {
        Frame::Lab => Frame::Table,
        Frame::Table => Frame::Lab,
    };
    let [a, b] = split(area);
    vec![
        render_in(f, a, app, app.view().frame, th),
        render_in(f, b, app, other, th),
    ]
}

/// What paints `pic` on a canvas whose inside is `inner`.
fn painter(pic: crate::plot::page::table::Picture, inner: Rect, th: &Theme) -> Painter {
    let (xb, yb) = bounds(inner.width, inner.height, pic.centre, pic.half_width);
    let body_glyph = pic
        .body
        .as_ref()
        .and_then(|b| b.bar)
        .map(|(_, c)| on_cell(c, (xb, yb), (inner.width, inner.height), th.marker));
    Painter {
        inner,
        xb,
        yb,
        body_glyph,
        // One terminal cell in world units.
        cell: DVec2::new(
            (xb[1] - xb[0]) / f64::from(inner.width.max(1)),
            (yb[1] - yb[0]) / f64::from(inner.height.max(1)),
        ),
        // Words on the canvas only where there is room for them beside the drawing.
        words: inner.width >= 40 && inner.height >= 10,
        pin_style: Style::default().fg(th.muted),
        th: th.clone(),
        pic,
    }
}

/// Draws one canvas of the turntable as `frame` sees it.
fn render_in(f: &mut TuiFrame, area: Rect, app: &App, frame: Frame, th: &Theme) -> CanvasGeom {
    let pic = crate::plot::page::table::Picture::in_frame(app, frame);
    let block = super::titled(title(app, frame, pic.point.is_some()), th);
    let inner = block.inner(area);
    let (xb, yb) = bounds(inner.width, inner.height, pic.centre, pic.half_width);
    let geom = CanvasGeom {
        area: inner,
        x: xb,
        y: yb,
        arrow_scale: pic.speed_scale,
        frame: pic.frame,
        turn: pic.turn,
        page: crate::app::pages::Page::Turntable,
    };
    let painter = painter(pic, inner, th);
    let canvas = Canvas::default()
        .block(block)
        .marker(th.marker)
        .background_color(th.background)
        .x_bounds(xb)
        .y_bounds(yb)
        .paint(move |ctx| painter.paint(ctx));
    f.render_widget(canvas, area);
    geom
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::{Action, update};
    use crate::scene::Scene;

    /// Every label placed over the presets A–D, in both frames, one canvas or split, with
    /// every arrow on and the four presets pinned, at 80×24 and 60×20, through each run:
    /// none overlaps another, none touches another on its row, none covers the particle or
    /// the fixed words.
    #[test]
    fn labels_never_collide() {
        let th = Theme::builtin("dark").unwrap();
        let mut placed = 0;
        for shown in 0..4 {
            let mut app = App::new(Scene::preset("A").unwrap());
            for k in 0..4 {
                update(&mut app, Action::Preset(k));
                update(&mut app, Action::PinRun);
            }
            update(&mut app, Action::Preset(shown));
            for (on, toggle) in [
                (app.view().forces, Action::ToggleForces),
                (app.view().net_force, Action::ToggleNetForce),
                (app.view().velocity, Action::ToggleVelocity),
            ] {
                if !on {
                    update(&mut app, toggle);
                }
            }
            for tick in 0..300 {
                if tick % 15 == 0 {
                    placed += check(&app, &th);
                }
                if !app.playing() {
                    app.play(None);
                }
                app.tick();
            }
        }
        assert!(placed > 500, "{placed}");
    }

    fn check(app: &App, th: &Theme) -> usize {
        let mut placed = 0;
        for (w, h) in [(80, 24), (60, 20)] {
            let canvas = crate::ui::layout::regions(w, h).unwrap().canvas;
            for split in [false, true] {
                let areas = if split {
                    split_areas(canvas)
                } else {
                    vec![canvas]
                };
                for (area, frame) in areas.into_iter().zip([Frame::Lab, Frame::Table]) {
                    let inner = ratatui::widgets::Block::bordered().inner(area);
                    let p = painter(
                        crate::plot::page::table::Picture::in_frame(app, frame),
                        inner,
                        th,
                    );
                    let stuck = p.stuck_label();
                    let (labels, cells) = p.labels(stuck.as_ref());
                    // The fixed words: the table's sense clear of the particle, where it
                    // stuck and the ring's words.
                    if let Some(sense) = p.sense_at(stuck.as_ref()) {
                        let n = crate::plot::page::table::SENSE_LABEL.chars().count();
                        let (r, a, b) = cells.of(sense, n);
                        let mut others = Vec::new();
                        if let Some(pt) = &p.pic.point {
                            others.push(cells.of(pt.at, 1));
                        }
                        if let Some((at, text)) = &stuck {
                            others.push(cells.of(*at, text.chars().count()));
                        }
                        if let (Some(ring), Some(at)) = (&p.pic.table.ring, p.ring_at()) {
                            let n = ring.label.chars().count();
                            let (r, a, b) = cells.of(at, n);
                            assert!(a >= 0 && b <= i64::from(inner.width), "ring cut");
                            others.push((r, a, b));
                        }
                        for (tr, ta, tb) in others {
                            assert!(
                                !(tr == r && a <= tb && ta <= b),
                                "{w}×{h} {frame:?} τ={}: the sense at {r},{a} meets {:?}",
                                app.now().tau,
                                (tr, ta, tb)
                            );
                        }
                    }
                    let fixed = cells.taken.len() - labels.len();
                    for (i, l) in labels.iter().enumerate() {
                        let (r, a, b) = cells.of(l.at, l.text.chars().count());
                        for (j, &(tr, ta, tb)) in cells.taken.iter().enumerate() {
                            if j != fixed + i {
                                assert!(
                                    !(tr == r && a < tb && ta < b),
                                    "{w}×{h} {frame:?} τ={}: {:?} at {r},{a} meets {:?}",
                                    app.now().tau,
                                    l.text,
                                    (tr, ta, tb)
                                );
                            }
                        }
                        assert!(a >= 0 && b <= i64::from(inner.width));
                    }
                    placed += labels.len();
                }
            }
        }
        placed
    }

    fn split_areas(r: Rect) -> Vec<Rect> {
        split(r).to_vec()
    }
}
