//! The outcome map page: its panel (`plot::page::map`) over the cells, one character each,
//! shaded by rest radius where a release sticks.

use super::geom;
use crate::app::pages::{Map, Page};
use crate::app::{App, CanvasGeom};
use crate::engine::Outcome;
use crate::plot::page::map;
use crate::theme::Theme;
use crate::ui::chart;
use ratatui::Frame as TuiFrame;
use ratatui::layout::Rect;

/// Stuck or escaped over (φ, v0), stuck cells shaded by their rest radius, the v_e curve on it.
pub(super) fn outcome_map(
    f: &mut TuiFrame,
    area: Rect,
    app: &App,
    th: &Theme,
) -> Option<CanvasGeom> {
    let c = map::chart(app);
    // The cells first, then the chart's braille over them.
    let plot = chart::plot_area(area, &c)?;
    if let Some(m) = map::shown(app) {
        paint_cells(f, plot, m, th);
    }
    let plot = chart::render(f, area, th, &c)?;
    Some(geom(plot, &c, Page::OutcomeMap, app))
}

/// The outcome map's grid at the app's terminal size for speeds up to `v0_max`: one cell a
/// character of the plot the page draws (the same layout and chart) up to
/// [`crate::analysis::MAP_CELLS`], none when no plot fits.
pub fn map_grid(app: &App, v0_max: f64) -> Option<(usize, usize)> {
    let (w, h) = app.screen();
    let canvas = crate::ui::layout::regions(w, h)?.canvas;
    let plot = chart::plot_area(canvas, &map::frame(app, v0_max, String::new()))?;
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
