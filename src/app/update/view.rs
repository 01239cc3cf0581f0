//! The "view" group: frame, forces, zoom and pan, the τ window, pages, the μ probe and the
//! SI units.

use super::super::action::{Action, UnitKnob};
use super::super::pages::{Page, trade_picked, trade_schemes};
use super::super::state::{App, ZOOM_RANGE, record_player};
use super::round_sig;
use crate::engine::units::Units;
use crate::engine::{Frame, Settings};
use std::f64::consts::TAU;

pub(super) fn apply(app: &mut App, action: Action) {
    match action {
        Action::ToggleFrame => {
            app.view.frame = match app.view.frame {
                Frame::Lab => Frame::Table,
                Frame::Table => Frame::Lab,
            }
        }
        Action::ToggleSplit => app.view.split = !app.view.split,
        Action::ToggleForces => app.view.forces = !app.view.forces,
        Action::ToggleNetForce => app.view.net_force = !app.view.net_force,
        Action::ToggleVelocity => app.view.velocity = !app.view.velocity,
        Action::TogglePointModel if app.scene().body.is_none() => {
            app.notice = Some(
                "no body to compare with the point model (--body-length, or [body] in a scene)"
                    .into(),
            );
        }
        Action::TogglePointModel => {
            app.view.point_model = !app.view.point_model;
            app.notice = Some(
                match (app.rod().is_some(), app.view.point_model) {
                    (true, true) => "point model beside the body (C)",
                    (true, false) => "the body alone, point model hidden (C)",
                    // Nothing of the body is drawn to stand alone: the point stays.
                    (false, true) => "point model shown; the body is not run here (μ = 0, Stokes)",
                    (false, false) => "point model kept: the body is not run here (μ = 0, Stokes)",
                }
                .into(),
            );
        }
        Action::ZoomIn => app.view.zoom = (app.view.zoom * 1.5).min(ZOOM_RANGE.1),
        Action::ZoomOut => app.view.zoom = (app.view.zoom / 1.5).max(ZOOM_RANGE.0),
        Action::Pan(dx, dy) => app.view.pan += glam::DVec2::new(dx, dy) / app.view.zoom,
        Action::ResetView => {
            app.view.zoom = 1.0;
            app.view.pan = glam::DVec2::ZERO;
        }
        Action::TauWindow(narrow) => {
            let now = app.plot_span().max(1e-3);
            let span = app.view.tau_window.unwrap_or(now);
            app.view.tau_window = if narrow {
                Some((0.5 * span).max(1e-3))
            } else {
                Some(2.0 * span).filter(|s| *s < now)
            };
        }
        Action::NextPage => app.view.page = app.view.page.next(),
        Action::PrevPage => app.view.page = app.view.page.prev(),
        Action::PickPoint(step) if app.view.page == Page::WorkPrecision => pick(app, step),
        Action::PickPoint(_) => {
            app.notice = Some("j/k pick a setting on the work-precision page (Tab)".into());
        }
        Action::Choose => choose(app),
        // With SI units on, the μ probe's Ω is the table's: `o`/`O` turn the table.
        Action::Omega(d) if app.units.is_some() => {
            if let Some(u) = app.units {
                // Within the rpm knob's range (1 to 10⁴ rpm).
                let omega = (u.omega() + d).clamp(TAU / 60.0, 1e4 * TAU / 60.0);
                set_units(
                    app,
                    Units {
                        rpm: round_sig(omega * 60.0 / TAU),
                        ..u
                    },
                );
            }
        }
        Action::Omega(d) | Action::R0c(d) => {
            let (omega, r0c) = &mut app.mu_probe;
            if matches!(action, Action::Omega(_)) {
                *omega = round_sig((*omega + d).clamp(0.1, 100.0));
            } else {
                *r0c = round_sig((*r0c + d).clamp(0.001, 10.0));
            }
            if app.view.page != Page::RestRadius {
                app.notice = Some(format!(
                    "μ probe: Ω = {} rad/s, r0c = {} m (the rest-radius page reads μ)",
                    app.mu_probe.0, app.mu_probe.1
                ));
            }
        }
        Action::Unit(knob, d) => match app.units {
            // The first press turns units on at the record player, changing nothing else.
            None => set_units(app, record_player()),
            Some(mut u) => {
                let (x, lo, hi) = match knob {
                    UnitKnob::Mu => (&mut u.mu, 0.01, 10.0),
                    UnitKnob::Rpm => (&mut u.rpm, 1.0, 1e4),
                    UnitKnob::G => (&mut u.g, 0.01, 1e3),
                };
                *x = round_sig((*x + d).clamp(lo, hi));
                set_units(app, u);
            }
        },
        Action::PinRun => app.pin_run(),
        Action::ClearPins => {
            app.notice = Some(match app.pins.len() {
                0 => "no pins to clear (b pins the run on screen)".into(),
                n => format!("{n} pins cleared"),
            });
            app.pins.clear();
        }
        Action::UnitsOff => {
            app.units = None;
            app.notice = Some("SI units off: dimensionless readouts only".into());
        }
        // Other groups' actions: `update` never sends them here.
        _ => {}
    }
}

/// The work–precision page's point `step` on from the one picked, in the page's order,
/// wrapping round.
fn pick(app: &mut App, step: i8) {
    let (initial, settings) = (app.initial(), app.settings());
    let all = trade_schemes(&initial, settings);
    let now = trade_picked(app.view.trade_pick, &initial, settings);
    let at = all.iter().position(|s| *s == now).unwrap_or(0) as i64;
    let n = all.len().max(1) as i64;
    app.view.trade_pick = all
        .get((at + i64::from(step)).rem_euclid(n) as usize)
        .copied();
}

/// Enter: the release chosen on the escape-speed or outcome-map page run on the turntable, or
/// the run switched to the setting picked on the work–precision page.
fn choose(app: &mut App) {
    match app.view.page {
        Page::EscapeSpeed | Page::OutcomeMap => {
            app.view.page = Page::Turntable;
            app.playing = true;
            app.exploration.restart();
        }
        Page::WorkPrecision => switch_to_picked(app),
        // A lesson that goes on by itself: a teacher's Enter is for its next stop.
        _ if app.lesson.name.is_some() && !app.lesson.done => {
            app.notice = Some("the lesson goes on by itself here: Enter at its next stop".into())
        }
        _ => {
            app.notice = Some(
                "Enter runs the release chosen on the escape-speed or outcome-map page, or the setting picked on the work-precision page (Tab)"
                    .into(),
            )
        }
    }
}

/// The run switched to the setting picked on the work–precision page (the page stays, its mark
/// of the run's setting moving there).
fn switch_to_picked(app: &mut App) {
    let (initial, settings) = (app.initial(), app.settings());
    let picked = trade_picked(app.view.trade_pick, &initial, settings);
    app.view.trade_pick = None;
    let to = Settings {
        scheme: picked,
        ..settings
    };
    let name = format!("{} {}", picked.method(), crate::present::accuracy(&to));
    app.notice = Some(if picked == settings.scheme {
        format!("the run is already at {name}: j/k pick another")
    } else {
        app.exploration.set_settings(to);
        format!("the run is now at {name} (Tab to the turntable to watch it)")
    });
}

/// Sets the table's μ, rpm and g. With units on already, the release is held in metres and
/// m/s, and the body (if any) in metres: its dimensionless ξ0, v0, L and h are recomputed
/// for the new table, and the run and the body's track restart (a larger μ changes the
/// outcome, not only the labels).
pub(super) fn set_units(app: &mut App, to: Units) {
    let Ok(to) = Units::new(to.mu, to.rpm, to.g) else {
        return;
    };
    if let Some(from) = app.units
        && from != to
    {
        app.exploration.carry(&from, &to);
    }
    app.units = Some(to);
    app.notice = Some(format!("SI units: {}", crate::present::table(&to)));
}
