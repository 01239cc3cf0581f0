//! The outcome map page: stuck or escaped over (φ, v0), stuck cells shaded by their rest
//! radius, the v_e curve on it.

use super::geom;
use crate::app::pages::{Charts, Map, Page, map_filled};
use crate::app::{App, CanvasGeom};
use crate::engine::model::turn_angle;
use crate::engine::units::Quantity;
use crate::engine::{Outcome, Release};
use crate::theme::Theme;
use crate::ui::chart::{self, Chart, Mark, Series};
use crate::ui::panel::num;
use ratatui::Frame as TuiFrame;
use ratatui::layout::Rect;
use std::f64::consts::TAU;

/// Stuck or escaped over (φ, v0), stuck cells shaded by their rest radius, the v_e curve on it.
pub(super) fn outcome_map(f: &mut TuiFrame, area: Rect, app: &App) -> Option<CanvasGeom> {
    let th = &app.theme;
    let i = app.initial();
    let settings = crate::analysis::settings_for(app.settings());
    let map = app.charts.map.as_ref().filter(|m| match m.job {
        crate::analysis::Job::Map { xi0, release, .. } => {
            xi0 == i.xi0 && release == i.release && m.settings == settings
        }
        _ => false,
    });
    let v0_max = match map.map(|m| m.job) {
        Some(crate::analysis::Job::Map { v0_max, .. }) => v0_max,
        _ => app
            .charts
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
    let c = map_chart(app, v0_max, progress);
    // The cells first, then the chart's braille over them.
    let plot = chart::plot_area(area, &c)?;
    if let Some(m) = map {
        paint_cells(f, plot, m, th);
    }
    let plot = chart::render(f, area, th, &c)?;
    Some(geom(plot, &c, Page::OutcomeMap, app))
}

/// The outcome map's chart (without its cells) for speeds up to `v0_max`.
fn map_chart(app: &App, v0_max: f64, progress: String) -> Chart {
    let th = &app.theme;
    let i = app.initial();
    let settings = crate::analysis::settings_for(app.settings());
    let frame_word = if i.release == Release::LabRest {
        "lab"
    } else {
        "table"
    };
    let mut series = Vec::new();
    if i.release != Release::LabRest
        && let Some(c) = app.charts.curve(i.xi0, settings)
    {
        let window = i.xi0 > 1.0;
        series.push(Series {
            name: if window { "sticking window" } else { "v_e(φ)" }.into(),
            color: th.accent,
            points: c.points(),
            joined: true,
        });
        if window {
            series.push(Series {
                name: String::new(),
                color: th.accent,
                points: c.floor(),
                joined: true,
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
        x_label: format!("φ ({frame_word} frame)  blank: escapes  ·:▒▓ stuck at ξ <¼ <½ <¾ ≤1"),
        y_label: chart::axis("v0", Quantity::Speed, app.units),
        x: [0.0, TAU],
        y: [0.0, v0_max],
        series,
        marks: vec![Mark::Point {
            x: phi,
            y: v0,
            label: "release".into(),
            color: th.particle,
        }],
    }
}

/// The outcome map's grid at the app's terminal size for speeds up to `v0_max`: one cell a
/// character of the plot the page draws (the same layout and chart) up to
/// [`crate::analysis::MAP_CELLS`], none when no plot fits.
pub fn map_grid(app: &App, v0_max: f64) -> Option<(usize, usize)> {
    let (w, h) = app.screen();
    let canvas = crate::ui::layout::regions(w, h)?.canvas;
    let plot = chart::plot_area(canvas, &map_chart(app, v0_max, String::new()))?;
    Some(crate::analysis::map_grid_for(
        usize::from(plot.width),
        usize::from(plot.height),
    ))
}

/// The map's cells under the plot, one character each: shaded by rest radius where stuck,
/// blank where escaped, `?` while unknown.
fn paint_cells(f: &mut TuiFrame, plot: Rect, m: &Map, th: &Theme) {
    let crate::analysis::Job::Map {
        size: (n, rows), ..
    } = m.job
    else {
        return;
    };
    let buf = f.buffer_mut();
    for cy in 0..plot.height {
        for cx in 0..plot.width {
            let fx = (f64::from(cx) + 0.5) / f64::from(plot.width);
            let fy = 1.0 - (f64::from(cy) + 0.5) / f64::from(plot.height);
            let ci = ((fx * n as f64) as usize).min(n - 1);
            let cj = ((fy * rows as f64) as usize).min(rows - 1);
            let Some(Some(cell)) = m.cells.get(cj * n + ci) else {
                continue;
            };
            let (ch, color) = match (cell.outcome, cell.rest) {
                (Outcome::Stuck, Some((xi, _))) => (
                    match xi {
                        x if x < 0.25 => '·',
                        x if x < 0.5 => ':',
                        x if x < 0.75 => '▒',
                        _ => '▓',
                    },
                    th.stuck,
                ),
                (Outcome::Escaped, _) => (' ', th.escaped),
                _ => ('?', th.muted),
            };
            if let Some(c) = buf.cell_mut((plot.x + cx, plot.y + cy)) {
                c.set_char(ch).set_fg(color);
            }
        }
    }
}
