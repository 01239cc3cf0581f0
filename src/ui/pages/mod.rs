//! The analysis pages: the escape speed v_e(φ) (Fig. 5), the outcome map over (φ, v0), and the
//! rest radius against ξ0 (Fig. 6) with the paper's μ measurement (Eq. 22); the time plots are
//! in `time_plots`. Pure: they draw what the app holds and never compute a run.

use crate::app::pages::Page;
use crate::app::{App, CanvasGeom};
use crate::plot::Chart;
use crate::present::num;
use crate::theme::Theme;
use ratatui::Frame as TuiFrame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::widgets::{Paragraph, Wrap};

mod map;
mod rest;
mod trade;

use crate::plot::page::escape::{curve_note, release_verdict};
pub use map::map_grid;
use map::outcome_map;
use rest::rest_radius;

/// Draws `app.page` in `area`; returns the plot's geometry where a click means a release.
pub fn render(f: &mut TuiFrame, area: Rect, app: &App, th: &Theme) -> Option<CanvasGeom> {
    if crate::engine::closed_form(&app.initial(), app.settings())
        && matches!(
            app.view().page,
            Page::EscapeSpeed | Page::OutcomeMap | Page::RestRadius
        )
    {
        no_threshold(f, area, th, app.settings().stokes());
        return None;
    }
    match app.view().page {
        Page::Turntable => None,
        Page::TimePlots => {
            super::time_plots::render(f, area, app, th);
            None
        }
        Page::EscapeSpeed => {
            let c = crate::plot::page::escape::chart(app);
            let plot = super::chart::render(f, area, th, &c)?;
            Some(geom(plot, &c, Page::EscapeSpeed, app))
        }
        Page::OutcomeMap => outcome_map(f, area, app, th),
        Page::RestRadius => {
            rest_radius(f, area, app, th);
            None
        }
        Page::WorkPrecision => {
            trade::work_precision(f, area, app, th);
            None
        }
    }
}

/// Under Stokes drag (extends the paper) or at μ = 0 the threshold pages have nothing to draw:
/// nothing sticks. Said instead: under drag with the rate every release leaves at.
fn no_threshold(f: &mut TuiFrame, area: Rect, th: &Theme, stokes: Option<f64>) {
    let (title, text) = match stokes {
        Some(gamma) => (
            " Stokes drag: no threshold ",
            format!(
                "Under Stokes drag γ = {gamma} there is no escape speed, outcome map or rest \
                 radius: every release leaves, exponentially at the rate Re λ+ = {}, except \
                 those with u0 = λ− q0 (the centre at rest, and one speed and direction at each \
                 radius), which spiral into the centre.",
                num(crate::engine::stokes::growth_rate(gamma), 6)
            ),
        ),
        None => (
            " μ = 0: no threshold ",
            "With no friction (μ = 0) there is no escape speed, outcome map or rest radius: \
             the particle keeps its lab velocity, a straight line that leaves ξ = 1, unless it \
             is released at rest in the lab, where it stays. These pages are the paper's, with \
             friction: F turns it back on."
                .to_string(),
        ),
    };
    let block = super::titled(title.to_string(), th);
    f.render_widget(
        Paragraph::new(text)
            .wrap(Wrap { trim: true })
            .style(Style::default().fg(th.foreground))
            .block(block),
        area,
    );
}

fn geom(plot: Rect, c: &Chart, page: Page, app: &App) -> CanvasGeom {
    CanvasGeom {
        area: plot,
        x: crate::plot::sane(c.x),
        y: crate::plot::sane(c.y),
        arrow_scale: 1.0,
        frame: app.view().frame,
        turn: 0.0,
        page,
    }
}

/// Whether `page` has numbers of its own to say in words ([`summary`]).
pub fn summarized(page: Page) -> bool {
    matches!(
        page,
        Page::EscapeSpeed | Page::RestRadius | Page::WorkPrecision
    )
}

/// The analysis page on screen in words, for plain mode (a screen reader has no chart): what
/// the chart shows once its data are in, and what it says of the release on screen, from the
/// same pieces the chart is drawn from. None while they compute, and on the pages without a
/// summary of their own (the turntable's and the time plots' readouts are spoken already).
pub fn summary(app: &App) -> Option<(String, Option<String>)> {
    let settings = crate::analysis::settings_for(app.settings());
    let i = app.initial();
    if app.settings().stokes().is_some() {
        return None;
    }
    match app.view().page {
        Page::EscapeSpeed => {
            let window = i.xi0 > 1.0;
            // Inside ξ = 1, once the least v_e is refined too: said once, not grid then refined.
            let c = app
                .charts()
                .curve(i.xi0, settings)
                .filter(|c| c.complete() && (window || c.least.is_some()))?;
            let what = if window {
                "sticking window"
            } else {
                "escape speed v_e(φ)"
            };
            let note = curve_note(c, window);
            let note = note.split(crate::present::OR).next().unwrap_or_default();
            let (verdict, _) = release_verdict(app, Some(c));
            Some((
                format!("{what} at ξ0 = {}: {note}", num(i.xi0, 3)),
                Some(format!(
                    "on the chart the release{}",
                    if verdict.is_empty() {
                        " is not judged"
                    } else {
                        verdict
                    }
                )),
            ))
        }
        Page::RestRadius => {
            let rest = app
                .charts()
                .rest
                .as_ref()
                .filter(|r| r.settings == settings)?;
            let c = rest.critical??;
            Some((
                format!(
                    "rest radius (Fig. 6): released at rest in the lab, it stays on the table up to ξ0c = {}",
                    num(c, 6)
                ),
                None,
            ))
        }
        Page::WorkPrecision => {
            use crate::plot::page::trade::{measured, said, shown, whole};
            let first = |s: String| {
                s.split(crate::present::OR)
                    .next()
                    .unwrap_or_default()
                    .to_string()
            };
            if !whole(app) {
                return None;
            }
            let t = shown(app);
            let picked = crate::app::pages::trade_picked(app.view().trade_pick, &i, app.settings());
            let lead = if picked == app.settings().scheme {
                "now"
            } else {
                "picked (Enter runs it)"
            };
            Some((
                format!("work-precision, {}", first(measured(t))),
                Some(first(said(t, picked, lead))),
            ))
        }
        _ => None,
    }
}
