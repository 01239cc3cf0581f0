//! The outcome map page's panel: how a throw from the ξ0 on screen ends over (φ, v0), stuck
//! cells shaded by their rest radius, the v_e curve (or the sticking window) over them.

use super::super::build::cells_by_rest;
use super::super::{Chart, Ink, Mark, Scale, Series, Style};
use crate::analysis::map_cell;
use crate::app::App;
use crate::app::pages::{Charts, Map, map_filled};
use crate::engine::Release;
use crate::engine::model::turn_angle;
use crate::present::{Quantity, num};
use std::f64::consts::TAU;

/// The map computed for the release and settings on screen, if any.
pub fn shown(app: &App) -> Option<&Map> {
    let i = app.initial();
    let settings = crate::analysis::settings_for(app.settings());
    app.charts().map.as_ref().filter(|m| match m.job {
        crate::analysis::Job::Map { xi0, release, .. } => {
            xi0 == i.xi0 && release == i.release && m.settings == settings
        }
        _ => false,
    })
}

/// The page's panel: [`frame`] with the cells computed so far.
pub fn chart(app: &App) -> Chart {
    let i = app.initial();
    let settings = crate::analysis::settings_for(app.settings());
    let map = shown(app);
    let v0_max = match map.map(|m| m.job) {
        Some(crate::analysis::Job::Map { v0_max, .. }) => v0_max,
        _ => app
            .charts()
            .curve(i.xi0, settings)
            .map_or(1.0, |c| Charts::map_v0_max(c, i.release, i.xi0)),
    };
    let progress = match map {
        Some(m) => {
            let (done, all) = map_filled(m);
            if done < all {
                format!(", {done}/{all} cells")
            } else {
                String::new()
            }
        }
        None => ", computing…".into(),
    };
    let mut c = frame(app, v0_max, progress);
    if let Some(m) = map
        && let crate::analysis::Job::Map { size, .. } = m.job
    {
        let cells: Vec<_> = m
            .cells
            .iter()
            .enumerate()
            .filter_map(|(k, c)| {
                let (phi, v0) = map_cell(k, size, v0_max);
                c.map(|c| (phi, v0, c.rest.map(|r| r.0)))
            })
            .collect();
        let mut series = cells_by_rest(&cells, size, v0_max);
        series.append(&mut c.series);
        c.series = series;
    }
    c
}

/// The outcome map's chart (without its cells) for speeds up to `v0_max`.
pub fn frame(app: &App, v0_max: f64, progress: String) -> Chart {
    let i = app.initial();
    let settings = crate::analysis::settings_for(app.settings());
    let frame_word = if i.release == Release::LabRest {
        "lab"
    } else {
        "table"
    };
    let mut series = Vec::new();
    if i.release != Release::LabRest
        && let Some(c) = app.charts().curve(i.xi0, settings)
    {
        let window = i.xi0 > 1.0;
        series.push(Series {
            name: if window { "sticking window" } else { "v_e(φ)" }.into(),
            ink: Ink::Accent,
            points: c.points(),
            style: Style::Line { dash: 0 },
        });
        if window {
            series.push(Series {
                name: String::new(),
                ink: Ink::Accent,
                points: c.floor(),
                style: Style::Line { dash: 0 },
            });
        }
    }
    let (phi, v0) = match i.release {
        Release::Velocity => (turn_angle(i.phi), i.v0),
        _ => (0.0, 0.0),
    };
    Chart {
        title: format!(
            "outcome map, ξ0 = {}, {} release{progress}",
            num(i.xi0, 3),
            i.release
        ),
        note: String::new(),
        x_label: format!("φ (rad, {frame_word} frame)  blank: escapes  ·:▒▓ stuck, ξ <¼ <½ <¾ ≤1"),
        y_label: crate::plot::axis("v0", Quantity::Speed, app.units()),
        x: [0.0, TAU],
        y: [0.0, v0_max],
        x_scale: Scale::Angle,
        series,
        marks: vec![Mark::Point {
            x: phi,
            y: v0,
            label: "release".into(),
            ink: Ink::Particle,
        }],
        ..Chart::default()
    }
}
