//! The escape speed page: v_e(φ) (Fig. 5) or, outside ξ = 1, the sticking window, and what
//! the curve says of the release on screen.

use super::super::{Chart, Ink, Mark, Scale, Series, Style};
use crate::analysis::PAPER_XI0;
use crate::analysis::verdict::{Verdict, judge, widest_window};
use crate::app::App;
use crate::app::pages::Curve;
use crate::engine::model::turn_angle;
use crate::engine::{Outcome, Release, Settings};
use crate::present::{Quantity, angle_to, curve_speed, num, speed};
use std::f64::consts::TAU;

/// v_e(φ) for the current ξ0 beside the paper's four, the release as a point, min and max.
pub fn chart(app: &App) -> Chart {
    let i = app.initial();
    let settings = crate::analysis::settings_for(app.settings());
    let mine = app.charts().curve(i.xi0, settings);
    // Outside ξ = 1 a throw too slow escapes too: the sticking speeds are a window, and the
    // paper's v_e curves (Fig. 5, inside ξ = 1) are another quantity.
    let window = i.xi0 > 1.0;
    let (mut series, mut marks) = paper_curves(app, settings, window);
    let (note, progress) = match mine {
        Some(c) => own_curve(app, c, window, &mut series, &mut marks),
        None => (String::new(), ", computing…".into()),
    };
    let phi = turn_angle(i.phi);
    let (verdict, tone) = release_verdict(app, mine);
    let color = match tone {
        Some(Outcome::Escaped) => Ink::Escaped,
        Some(Outcome::Stuck) => Ink::Stuck,
        Some(Outcome::Running) => Ink::Notice,
        None => Ink::Particle,
    };
    let v_now = if i.release == Release::Velocity {
        i.v0
    } else {
        0.0
    };
    marks.push(Mark::Point {
        x: phi,
        y: v_now,
        label: format!("release{verdict}"),
        ink: color,
    });
    let top = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .fold(v_now, f64::max);
    let title = if window {
        "sticking window (Fig. 3 D)"
    } else {
        "escape speed v_e(φ)"
    };
    Chart {
        title: format!("{title}, ξ0 = {}{progress}", num(i.xi0, 3)),
        note,
        x_label: "φ (rad)".into(),
        y_label: crate::plot::axis(
            if window { "v0" } else { "v_e" },
            Quantity::Speed,
            app.units(),
        ),
        x: [0.0, TAU],
        y: [0.0, (1.1 * top).max(0.1)],
        x_scale: Scale::Angle,
        series,
        marks,
        ..Chart::default()
    }
}

/// The paper's four v_e curves (Fig. 5) but the current ξ0's, faint, each named at its peak;
/// none outside ξ = 1 (`window`).
fn paper_curves(app: &App, settings: Settings, window: bool) -> (Vec<Series>, Vec<Mark>) {
    let mut series = Vec::new();
    let mut marks = Vec::new();
    let others = if window { &[][..] } else { &PAPER_XI0[..] };
    for &xi0 in others.iter().filter(|x| **x != app.initial().xi0) {
        if let Some(c) = app.charts().curve(xi0, settings) {
            let points = c.points();
            // Named at its peak rather than in the legend (their faint colours are all one),
            // which keeps the legend's room for the current curve.
            if let Some(&(x, y)) = points.iter().max_by(|a, b| a.1.total_cmp(&b.1)) {
                marks.push(Mark::Text {
                    x,
                    y,
                    label: xi0.to_string(),
                    ink: Ink::Muted,
                });
            }
            series.push(Series {
                name: String::new(),
                ink: Ink::Muted,
                points,
                style: Style::Line { dash: 0 },
            });
        }
    }
    (series, marks)
}

/// The current ξ0's curve (and the window's floor, or its min and max marked), with the
/// chart's note and how far its computation has come.
fn own_curve(
    app: &App,
    c: &Curve,
    window: bool,
    series: &mut Vec<Series>,
    marks: &mut Vec<Mark>,
) -> (String, String) {
    let i = app.initial();
    let name = if window {
        format!("ξ0={}: sticks between", num(i.xi0, 3))
    } else {
        format!("ξ0={} (now)", num(i.xi0, 3))
    };
    series.push(Series {
        name,
        ink: Ink::Trail,
        points: c.points(),
        style: Style::Line { dash: 0 },
    });
    if window {
        series.push(Series {
            name: String::new(),
            ink: Ink::Trail,
            points: c.floor(),
            style: Style::Line { dash: 0 },
        });
    } else if let Some(((p0, v0), (p1, v1))) = extremes(c) {
        marks.push(Mark::Point {
            x: p0,
            y: v0,
            label: "min".into(),
            ink: Ink::Stuck,
        });
        marks.push(Mark::Point {
            x: p1,
            y: v1,
            label: "max".into(),
            ink: Ink::Escaped,
        });
    }
    let note = curve_note(c, window);
    let done = c.ve.iter().filter(|v| v.is_some()).count();
    let progress = if done < c.ve.len() {
        format!(", {done}/{} angles", c.ve.len())
    } else if !window && c.least.is_none() {
        ", refining min…".into()
    } else {
        String::new()
    };
    (note, progress)
}

/// The least and greatest v_e of a curve as (φ, v_e): the least refined between the angles
/// once it arrives, the grid's until then.
fn extremes(c: &Curve) -> Option<((f64, f64), (f64, f64))> {
    let (least, most) = c.extremes()?;
    Some((c.least.flatten().unwrap_or(least), most))
}

/// The curve's note: the widest sticking window outside ξ = 1; inside, v_e's least (π to three
/// decimals once refined, to two from the grid, only good to its 0.03π) and greatest, each
/// speed to the digits it is known to.
pub fn curve_note(c: &Curve, window: bool) -> String {
    if window {
        return widest(c);
    }
    let Some(((p0, v0), (p1, v1))) = extremes(c) else {
        return String::new();
    };
    // The refined least is sought to 1e-8; the grid's points are known to the curve's 1e-4.
    let (least, digits) = if matches!(c.least, Some(Some(_))) {
        (speed(v0), 3)
    } else {
        (curve_speed(v0), 2)
    };
    format!(
        "min {least} at {}, max {} at {}",
        angle_to(p0, digits),
        curve_speed(v1),
        angle_to(p1, 2)
    )
}

/// What the curve says of the release on screen, in words, and its tone: the outcome it
/// foretells (Running: too near an edge to tell), or None where it says nothing.
pub fn release_verdict(app: &App, mine: Option<&Curve>) -> (&'static str, Option<Outcome>) {
    let i = app.initial();
    let window = i.xi0 > 1.0;
    let judged = match i.release {
        Release::Velocity => mine.and_then(|c| judge(&c.ve, turn_angle(i.phi), i.v0)),
        _ => None,
    };
    let (esc, stk, near) = (
        Some(Outcome::Escaped),
        Some(Outcome::Stuck),
        Some(Outcome::Running),
    );
    match (judged, window) {
        (Some(Verdict::Above), false) => (" escapes (above v_e)", esc),
        (Some(Verdict::Inside), false) => (" sticks (below v_e)", stk),
        // Between the computed angles' values: the chart cannot tell; the run can.
        (Some(Verdict::Near), false) => (" ≈ v_e: Enter runs it to see", near),
        (Some(Verdict::Above), true) => (" escapes (above the window)", esc),
        (Some(Verdict::Below), _) => (" escapes (below the window)", esc),
        (Some(Verdict::Inside), true) => (" sticks (in the window)", stk),
        (Some(Verdict::Never), _) => (" escapes (no window at this φ)", esc),
        (Some(Verdict::Near), true) => (" ≈ window's edge: Enter runs it", near),
        (None, _) if i.release == Release::Velocity => ("", None),
        (None, _) => (" (release at rest: v0 = 0)", None),
    }
}

/// The widest sticking window of a curve outside ξ = 1, in words.
fn widest(c: &Curve) -> String {
    let best = widest_window(&c.ve);
    match best {
        Some((p, lo, hi)) => {
            // A grid angle: good to its spacing, so to two decimals of π.
            let (lo, hi, p) = (curve_speed(lo), curve_speed(hi), angle_to(p, 2));
            crate::present::alternatives(&[
                format!("widest window: sticks for v0 {lo}–{hi}, at φ = {p}"),
                format!("widest: v0 {lo}–{hi} at φ = {p}"),
                format!("widest: v0 {lo}–{hi}"),
                format!("v0 {lo}–{hi}"),
            ])
        }
        None if c.complete() => "escapes at every speed and angle".into(),
        None => String::new(),
    }
}
