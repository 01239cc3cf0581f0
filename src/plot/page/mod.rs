//! The explorer's pages described once, from what the explorer already holds (the run's path
//! on its τ grid, the pins, the charts the analysis sent), never computed anew: the terminal
//! draws these panels (`ui`), and `E` writes the page on screen as a figure of them.

pub mod arrows;
pub mod escape;
pub mod map;
pub mod rest;
pub mod table;
pub mod time;
pub mod trade;

use super::Figure;
use crate::analysis::{PAPER_XI0, settings_for};
use crate::app::App;
use crate::app::pages::Page;
use crate::engine::Release;
use crate::present::{angle, num};

/// The page on screen as a figure, and whether it is whole (false while it still computes).
pub fn figure(app: &App) -> (Figure, bool) {
    let one = |panel| Figure {
        title: title(app),
        panels: vec![panel],
    };
    match app.view().page {
        Page::Turntable => (table::figure(app, title(app)), true),
        Page::TimePlots => {
            let panels = time::panels(app);
            (
                Figure {
                    title: title(app),
                    panels,
                },
                true,
            )
        }
        Page::EscapeSpeed => (one(escape::chart(app)), curves_whole(app)),
        Page::OutcomeMap => {
            let whole = map::shown(app).is_some_and(|m| m.cells.iter().all(Option::is_some));
            (one(map::chart(app)), whole)
        }
        Page::RestRadius => {
            let whole = rest::shown(app)
                .is_some_and(|r| r.xi.iter().all(Option::is_some) && r.critical.is_some());
            (one(rest::chart(app)), whole)
        }
        Page::WorkPrecision => (one(trade::chart(app)), trade::whole(app)),
    }
}

/// Whether the escape-speed page's curves are all in: the ξ0 on screen's and, inside ξ = 1,
/// the paper's four beside it.
fn curves_whole(app: &App) -> bool {
    let (i, settings) = (app.initial(), settings_for(app.settings()));
    let mut xi0s = vec![i.xi0];
    if i.xi0 <= 1.0 {
        xi0s.extend(PAPER_XI0.iter().filter(|x| **x != i.xi0));
    }
    xi0s.iter().all(|&x| {
        app.charts()
            .curve(x, settings)
            .is_some_and(|c| c.complete())
    })
}

/// The figure's title: the release on screen and its τ.
fn title(app: &App) -> String {
    let i = app.initial();
    let release = match i.release {
        Release::Velocity => format!("ξ0 = {}, φ = {}, v0 = {}", i.xi0, angle(i.phi), i.v0),
        Release::TableRest => format!("ξ0 = {}, at rest on the table", i.xi0),
        Release::LabRest => format!("ξ0 = {}, at rest in the lab", i.xi0),
    };
    format!("Released at {release}, τ = {}", num(app.sim().now().tau, 3))
}

/// The page's name in a file name after `turntable-`: `time-plots`, `table` (not
/// `turntable-turntable`, said twice).
pub fn slug(page: Page) -> String {
    match page {
        Page::Turntable => "table".to_string(),
        _ => page.title().replace(' ', "-"),
    }
}
