//! The page on screen as a figure for `E`: drawn from what the explorer already holds — the
//! run's path on its τ grid and the charts the analysis sent — never computed anew.

use crate::analysis::{PAPER_XI0, REST_POINTS, REST_XI0_MAX, map_cell, settings_for};
use crate::app::App;
use crate::app::pages::Page;
use crate::engine::{Outcome, Release, State, Status};
use crate::plot::{Figure, build};

/// The page's figure, and whether it is whole (false while the page is still computing).
pub fn page(app: &App) -> (Figure, bool) {
    let i = app.initial();
    match app.page {
        Page::Turntable => {
            let end = match app.sim().outcome_now() {
                Outcome::Stuck => format!("stuck at ξ = {:.5}", app.sim().now().xi()),
                Outcome::Escaped => "escaped".into(),
                Outcome::Running => format!("τ = {:.3}", app.sim().now().tau),
            };
            let fig = build::trajectory(&title(app), &path(app), app.view, &end);
            (fig, true)
        }
        Page::TimePlots => {
            let now = app.sim().now().tau;
            let stop = match app.sim().run.status() {
                Status::Stuck { tau, .. } if tau <= now => Some(tau),
                _ => None,
            };
            (build::time(&title(app), &path(app), stop), true)
        }
        Page::EscapeSpeed => {
            let settings = settings_for(app.settings());
            let mut xi0s = vec![i.xi0];
            // The paper's four beside it, inside ξ = 1 where they are the same quantity.
            if i.xi0 <= 1.0 {
                xi0s.extend(PAPER_XI0.iter().filter(|x| **x != i.xi0));
            }
            let mut whole = true;
            let mut curves = Vec::new();
            for xi0 in xi0s {
                match app.charts.curve(xi0, settings) {
                    Some(c) => {
                        whole &= c.complete();
                        curves.push((xi0, c.points()));
                    }
                    None => whole = false,
                }
            }
            let release = (i.release == Release::Velocity).then(|| {
                let phi = crate::engine::model::turn_angle(i.phi);
                (phi, i.v0, "release".to_string())
            });
            let t = format!("Escape speed v_e(φ) at ξ0 = {}", i.xi0);
            (build::escape_speed(&t, &curves, release), whole)
        }
        Page::OutcomeMap => match &app.charts.map {
            Some(m) => {
                let crate::analysis::Job::Map {
                    xi0,
                    release,
                    v0_max,
                    size,
                } = m.job
                else {
                    return (empty_map(), false);
                };
                let cells: Vec<_> = m
                    .cells
                    .iter()
                    .enumerate()
                    .filter_map(|(k, c)| {
                        let (phi, v0) = map_cell(k, size, v0_max);
                        c.map(|c| (phi, v0, c.rest.map(|r| r.0)))
                    })
                    .collect();
                let whole = m.cells.iter().all(Option::is_some);
                let curve = (release != Release::LabRest)
                    .then(|| app.charts.curve(xi0, settings_for(app.settings())))
                    .flatten()
                    .map(|c| c.points());
                let v_axis = match release {
                    Release::LabRest => "v0, lab speed of the throw (μg/Ω)",
                    _ => "v0, speed relative to the table (μg/Ω)",
                };
                let t = format!("Outcome map at ξ0 = {xi0}");
                let fig = build::outcome_map(&t, &cells, size, v0_max, curve, v_axis);
                (fig, whole)
            }
            None => (empty_map(), false),
        },
        Page::RestRadius => match &app.charts.rest {
            Some(r) => {
                let points: Vec<(f64, Option<f64>)> =
                    r.xi.iter()
                        .enumerate()
                        .filter_map(|(k, xi)| {
                            let xi0 = REST_XI0_MAX * k as f64 / (REST_POINTS - 1) as f64;
                            xi.map(|xi| (xi0, xi))
                        })
                        .collect();
                let whole = r.xi.iter().all(Option::is_some) && r.critical.is_some();
                let t = "Released at rest in the lab: the final rest radius";
                let xi0c = r.critical.flatten();
                (build::rest_radius(t, &points, xi0c), whole)
            }
            None => {
                let t = "Rest radius (nothing computed yet)";
                (build::rest_radius(t, &[], None), false)
            }
        },
    }
}

/// The run's path up to the τ on screen, ending exactly there.
fn path(app: &App) -> Vec<State> {
    let mut p = app.sim().trail().to_vec();
    let now = app.sim().now();
    if p.last().is_none_or(|s| s.tau < now.tau) {
        p.push(now);
    }
    p
}

fn title(app: &App) -> String {
    let i = app.initial();
    let release = match i.release {
        Release::Velocity => format!("ξ0 = {}, φ = {:.4}, v0 = {}", i.xi0, i.phi, i.v0),
        Release::TableRest => format!("ξ0 = {}, at rest on the table", i.xi0),
        Release::LabRest => format!("ξ0 = {}, at rest in the lab", i.xi0),
    };
    format!("Released at {release}, τ = {:.3}", app.sim().now().tau)
}

/// The outcome map with nothing computed yet: its axes alone.
fn empty_map() -> Figure {
    let t = "Outcome map (nothing computed yet)";
    build::outcome_map(t, &[], (1, 1), 1.0, None, "v0 (μg/Ω)")
}

/// The page's name in a file name: `time-plots`.
pub fn slug(page: Page) -> String {
    page.title().replace(' ', "-")
}
