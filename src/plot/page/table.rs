//! The turntable as a figure for `E`: what the canvas shows, in the frame shown and turned
//! as the picture is — the table's edge and the circle ξ = 1, the run's trail, the paper's RK2
//! run (`c`), the pins with their labels, the release and its velocity, the arrows at the
//! particle (forces, net force, velocity) and where it stuck.

use super::super::{Figure, Ink, Mark, Panel, Series};
use super::arrows::arrows;
use crate::app::App;
use crate::engine::model::rotate;
use crate::engine::{Frame, Outcome, State, Status};
use crate::present::num;
use glam::DVec2;
use std::f64::consts::TAU;

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
        .min(crate::app::exploration::view_radius(&app.initial()) * 1.1)
}

/// A circle of radius `r` about the centre, as a closed line.
fn circle(r: f64) -> Vec<(f64, f64)> {
    (0..=180)
        .map(|k| {
            let a = TAU * f64::from(k) / 180.0;
            (r * a.cos(), r * a.sin())
        })
        .collect()
}

/// The path of `sim` up to the τ on screen, ending exactly there.
pub fn shown_path(sim: &crate::sim::Sim) -> Vec<State> {
    let mut p = sim.trail().to_vec();
    let now = sim.now();
    if p.last().is_none_or(|s| s.tau < now.tau) {
        p.push(now);
    }
    p
}

/// The canvas as a figure titled `title`.
pub fn figure(app: &App, title: String) -> Figure {
    let (view, turn) = (app.view.frame, app.view.turn);
    let place = |s: &State, turn: f64, k: f64| {
        let p = rotate(in_frame(s, view), turn) * k;
        (p.x, p.y)
    };
    let i = app.initial();
    let table_r = 1.5f64.max(i.xi0 * 1.2);
    let mut edge = Series::line("table edge", 0, circle(table_r));
    edge.ink = Ink::TableEdge;
    let mut rim = Series::line("ξ = 1 (R_max)", 2, circle(1.0));
    rim.ink = Ink::LimitCircle;
    let mut series = vec![edge, rim];
    let mut marks = Vec::new();
    for p in &app.pins {
        let k = p.scale(app.units).0;
        let pts: Vec<_> = p.path.iter().map(|s| place(s, p.spec.turn, k)).collect();
        let name = format!("{}{}", p.marker, p.spec.label);
        if let Some(&(x, y)) = pts.last() {
            marks.push(Mark::Text {
                x,
                y,
                label: name.clone(),
                ink: Ink::Muted,
            });
        }
        series.push(Series::new(name, Ink::Muted, true, pts));
    }
    if let Some(paper) = app.paper() {
        let pts: Vec<_> = shown_path(paper)
            .iter()
            .map(|s| place(s, turn, 1.0))
            .collect();
        let (x, y) = place(&paper.now(), turn, 1.0);
        marks.push(Mark::Point {
            x,
            y,
            label: "paper's RK2".into(),
            ink: Ink::Paper,
        });
        series.push(Series::new(
            "the paper's RK2 run (c)",
            Ink::Paper,
            true,
            pts,
        ));
    }
    let r0 = auto_extent(app);
    let arrow_scale = 0.3 * r0 / i.xi0.max(1.0);
    let s0 = i.state();
    let v_init = match view {
        Frame::Lab => s0.v,
        Frame::Table => s0.u(),
    };
    let x0 = rotate(DVec2::new(i.xi0, 0.0), turn);
    let tip = x0 + rotate(v_init, turn) * arrow_scale;
    marks.push(Mark::Arrow {
        from: (x0.x, x0.y),
        to: (tip.x, tip.y),
        label: "release velocity".into(),
        ink: Ink::Arrow,
    });
    let now = app.sim().now();
    let at = rotate(in_frame(&now, view), turn);
    if app.point_shown() {
        let pts = shown_path(app.sim())
            .iter()
            .map(|s| place(s, turn, 1.0))
            .collect();
        series.push(Series::new("particle", Ink::Trail, true, pts));
        particle_marks(app, at, r0 / app.view.zoom, arrow_scale, &mut marks);
    }
    let centre = match app.view.zoom > 1.0 {
        true => at,
        false => DVec2::ZERO,
    } + app.view.pan * r0;
    let r = r0 / app.view.zoom;
    let name = match view {
        Frame::Lab => "the lab frame",
        Frame::Table => "the rotating frame (the table's)",
    };
    Figure {
        title,
        panels: vec![Panel {
            title: format!("the turntable in {name}"),
            x_label: "x (R_max)".into(),
            y_label: "y (R_max)".into(),
            x: [centre.x - r, centre.x + r],
            y: [centre.y - r, centre.y + r],
            equal_aspect: true,
            series,
            marks,
            ..Panel::default()
        }],
    }
}

/// The particle at `at` with how its run stands, where it stuck, and the arrows drawn at it
/// (forces scaled to the half-width shown, speeds by `speed_scale`).
fn particle_marks(app: &App, at: DVec2, half_width: f64, speed_scale: f64, marks: &mut Vec<Mark>) {
    let now = app.sim().now();
    if let Status::Stuck { tau, q } = app.sim().run.status()
        && now.tau >= tau
    {
        let p = rotate(
            match app.view.frame {
                Frame::Lab => rotate(q, tau),
                Frame::Table => q,
            },
            app.view.turn,
        );
        marks.push(Mark::Point {
            x: p.x,
            y: p.y,
            label: format!("× stuck τ={}", num(tau, 2)),
            ink: Ink::Stuck,
        });
    }
    for fa in arrows(app, half_width, speed_scale) {
        let tip = at + rotate(fa.vec, app.view.turn);
        marks.push(Mark::Arrow {
            from: (at.x, at.y),
            to: (tip.x, tip.y),
            label: format!("{} ({})", fa.label, fa.word),
            ink: fa.ink,
        });
    }
    let end = match app.sim().outcome_now() {
        Outcome::Stuck => format!("stuck at ξ = {}", num(now.xi(), 5)),
        Outcome::Escaped => "escaped".into(),
        Outcome::Running => format!("τ = {}", num(now.tau, 3)),
    };
    marks.push(Mark::Point {
        x: at.x,
        y: at.y,
        label: end,
        ink: Ink::Particle,
    });
}
