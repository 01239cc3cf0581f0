//! The pure update: an action applied to the state. No I/O but `Save`, no clock.

use super::action::{Action, UnitKnob};
use super::pages::Page;
use super::state::{App, SPEED_RANGE, ZOOM_RANGE, make_sim};
use crate::engine::method::{DT_RANGE, TOL_RANGE};
use crate::engine::{Frame, Method, Release, Settings, State};
use crate::scene::{PRESETS, Scene};
use strum::VariantArray;

/// Moves the help by `rows` (no further than its end at this size); nothing when it is shut.
fn scroll_help(app: &mut App, rows: i32) {
    if app.help {
        let (w, h) = app.screen();
        let end = i32::from(crate::ui::help::max_scroll(w, h, &app.theme));
        let to = (i32::from(app.help_scroll) + rows).clamp(0, end);
        app.help_scroll = u16::try_from(to).unwrap_or(0);
    }
}

pub fn update(app: &mut App, action: Action) {
    if action == Action::EndDrag {
        // Letting go of the mouse changes nothing on screen (the notice stays).
        app.dragging = false;
        return;
    }
    app.dirty = true;
    app.notice = None;
    match action {
        Action::Quit => {
            if app.help {
                app.help = false;
            } else {
                app.quit = true;
            }
        }
        // The notice is already cleared above.
        Action::Dismiss => app.help = false,
        Action::ToggleHelp => {
            app.help = !app.help;
            app.help_scroll = 0;
        }
        Action::TauWindow(narrow) => {
            let now = app.sim.now().tau.max(1e-3);
            let span = app.tau_window.unwrap_or(now);
            app.tau_window = if narrow {
                Some((0.5 * span).max(1e-3))
            } else {
                Some(2.0 * span).filter(|s| *s < now)
            };
        }
        Action::HelpScroll(rows) => scroll_help(app, i32::from(rows)),
        Action::HelpPage(pages) => {
            let page = crate::ui::help::page(app.screen().1);
            scroll_help(app, i32::from(pages) * i32::from(page));
        }
        Action::PlayPause => {
            app.playing = !app.playing;
            app.step_mode &= !app.playing;
        }
        Action::IntegratorStep => {
            app.playing = false;
            app.step_mode = true;
            if !app.sim.step_once() {
                app.notice = Some("no more steps: the run has ended (r restarts)".into());
            }
        }
        Action::StepForward => {
            app.playing = false;
            let dtau = super::state::TICK_DT * app.speed;
            if !step_through_history(&mut app.sim, dtau) {
                step(app);
            } else if let Some(p) = app.paper.as_mut() {
                step_through_history(p, dtau);
            }
        }
        Action::StepBack => {
            app.playing = false;
            let dtau = -super::state::TICK_DT * app.speed;
            step_through_history(&mut app.sim, dtau);
            if let Some(p) = app.paper.as_mut() {
                step_through_history(p, dtau);
            }
        }
        Action::Faster => app.speed = (app.speed * 2.0).min(SPEED_RANGE.1),
        Action::Slower => app.speed = (app.speed / 2.0).max(SPEED_RANGE.0),
        Action::Restart => app.restart(),
        Action::ToggleFrame => {
            app.view = match app.view {
                Frame::Lab => Frame::Table,
                Frame::Table => Frame::Lab,
            }
        }
        Action::CycleMethod => {
            let (now, next) = (
                app.settings.scheme,
                next_of(Method::VARIANTS, app.settings.method()),
            );
            // A fixed step carries over between the fixed-step methods, a tolerance between
            // the adaptive ones; else the default.
            let knob = match now.tol() {
                Some(tol) if next.adaptive() => tol,
                None if !next.adaptive() => now.knob(),
                _ => next.default_knob(),
            };
            app.settings.scheme = next.with(knob);
            app.restart();
        }
        Action::Loosen | Action::Tighten => {
            let k = if action == Action::Loosen {
                10f64.sqrt()
            } else {
                1.0 / 10f64.sqrt()
            };
            let s = &mut app.settings.scheme;
            let range = if s.method().adaptive() {
                TOL_RANGE
            } else {
                DT_RANGE
            };
            *s = s.with_knob(round_sig(s.knob() * k).clamp(range.0, range.1));
            app.restart();
        }
        Action::Xi0(d) => {
            app.initial.xi0 += d;
            app.restart();
        }
        Action::Phi(d) => {
            app.initial.phi += d;
            app.initial.release = Release::Velocity;
            app.restart();
        }
        Action::V0(d) => {
            app.initial.v0 += d;
            app.initial.release = Release::Velocity;
            app.restart();
        }
        Action::CycleRelease => {
            app.initial.release = next_of(Release::VARIANTS, app.initial.release);
            app.restart();
        }
        Action::ToggleFriction => {
            app.initial.frictionless = !app.initial.frictionless;
            app.notice = Some(if app.initial.frictionless {
                "μ = 0: no friction, so no force at all in the lab (closed form, no steps)".into()
            } else {
                "friction on: μg = 1".into()
            });
            app.restart();
        }
        Action::ResetScene => {
            app.initial = app.scene.initial;
            app.settings = if app.scene.settings.validate().is_ok() {
                app.scene.settings
            } else {
                Settings::default()
            };
            app.restart();
        }
        Action::Preset(i) => {
            if let Some(scene) = PRESETS.get(i).and_then(|n| Scene::preset(n)) {
                app.initial = scene.initial;
                app.settings = scene.settings;
                app.notice = Some(format!("preset {}: {}", scene.name, scene.about));
                app.scene = scene;
                app.zoom = 1.0;
                app.turn = 0.0;
                app.pan = glam::DVec2::ZERO;
                app.restart();
            }
        }
        Action::ToggleCompare => {
            app.paper = match app.paper {
                Some(_) => None,
                None => {
                    // It catches up with the run on screen over the next ticks, within each
                    // tick's step budget: the key itself does no integration.
                    Some(make_sim(app.initial, Settings::paper()))
                }
            };
            app.catch_up();
        }
        Action::ToggleForces => app.forces = !app.forces,
        Action::EstimateError if app.initial.frictionless => {
            app.notice =
                Some("μ = 0 is computed in closed form: exact, no error to estimate".into());
        }
        Action::EstimateError => {
            app.notice = Some(match app.sim.error_estimate() {
                Ok(e) => format!(
                    "error at τ = {:.3}: |Δr| = {:.1e} against dp54 tol={:.0e} ({} RHS)",
                    e.tau, e.error, e.tol, e.rhs_evals
                ),
                Err(e) => format!("no estimate: {e}"),
            });
        }
        Action::ZoomIn => app.zoom = (app.zoom * 1.5).min(ZOOM_RANGE.1),
        Action::ZoomOut => app.zoom = (app.zoom / 1.5).max(ZOOM_RANGE.0),
        Action::Pan(dx, dy) => app.pan += glam::DVec2::new(dx, dy) / app.zoom,
        Action::ResetView => {
            app.zoom = 1.0;
            app.pan = glam::DVec2::ZERO;
        }
        Action::Save if !app.writes_files => {
            app.notice = Some(format!(
                "replay writes no files: s would save this scene to {} (or the next free name)",
                app.save_path.display()
            ));
        }
        Action::Save => {
            let scene = app.current_scene();
            app.notice = Some(match scene.save_new(&app.save_path) {
                Ok(p) => format!("saved scene to {}", p.display()),
                Err(e) => format!("could not save {}: {e}", app.save_path.display()),
            });
        }
        Action::PlaceRelease(p) => {
            // Clicked at an angle: the picture turns there (p is in model coordinates, so its
            // angle adds to the turn already shown).
            if p.length() > 0.0 {
                app.turn = crate::engine::model::wrap_angle(app.turn + p.y.atan2(p.x));
            }
            app.initial.xi0 = p.length();
            app.dragging = true;
            app.restart();
            app.notice = Some(format!(
                "release point ξ0 = {:.3}; drag to set the velocity",
                app.initial.xi0
            ));
        }
        Action::AimVelocity(p) => {
            let scale = app.geom.map_or(1.0, |g| g.arrow_scale);
            let r0 = glam::DVec2::new(app.initial.xi0, 0.0);
            // The arrow shows the lab velocity in the lab view and u0 in the rotating view.
            let drawn = (p - r0) / scale;
            let u0 = match app.view {
                Frame::Lab => drawn - crate::engine::model::zcross(r0),
                Frame::Table => drawn,
            };
            app.initial.release = Release::Velocity;
            app.initial.v0 = u0.length();
            app.initial.phi = if u0.length() > 0.0 {
                u0.y.atan2(u0.x)
            } else {
                0.0
            };
            app.restart();
            app.notice = Some(format!(
                "v0 = {:.3}, φ = {:.3}π",
                app.initial.v0,
                crate::engine::model::turn_angle(app.initial.phi) / std::f64::consts::PI
            ));
        }
        // Handled before anything else, above.
        Action::EndDrag => {}
        Action::ToggleMouse => {
            app.mouse = !app.mouse;
            app.notice = Some(
                if app.mouse {
                    "mouse on: click = release point, drag = initial velocity"
                } else {
                    "mouse off: select text with the mouse; M turns it back on"
                }
                .into(),
            );
        }
        Action::NextPage => app.page = app.page.next(),
        Action::PrevPage => app.page = app.page.prev(),
        Action::Choose => {
            if matches!(app.page, Page::EscapeSpeed | Page::OutcomeMap) {
                app.page = Page::Turntable;
                app.playing = true;
                app.restart();
            } else {
                app.notice = Some(
                    "Enter runs the release chosen on the escape-speed or outcome-map page (Tab)"
                        .into(),
                );
            }
        }
        Action::PickRelease(p) => {
            let release = match app.page {
                Page::OutcomeMap => app.initial.release,
                _ => Release::Velocity,
            };
            let chosen = crate::analysis::map_release(app.initial.xi0, release, p.x, p.y.max(0.0));
            app.initial = chosen;
            app.restart();
            app.notice = Some(format!(
                "release v0 = {:.4} at φ = {:.3}π: Enter runs it on the turntable",
                app.initial.v0,
                crate::engine::model::turn_angle(app.initial.phi) / std::f64::consts::PI
            ));
        }
        Action::Unit(knob, d) => {
            use crate::engine::units::Units;
            let was = app.units;
            let mut u = was.unwrap_or_else(super::state::record_player);
            if was.is_some() {
                let (x, lo, hi) = match knob {
                    UnitKnob::Mu => (&mut u.mu, 0.01, 10.0),
                    UnitKnob::Rpm => (&mut u.rpm, 1.0, 1e4),
                    UnitKnob::G => (&mut u.g, 0.01, 1e3),
                };
                *x = round_sig((*x + d).clamp(lo, hi));
            }
            if let Ok(u) = Units::new(u.mu, u.rpm, u.g) {
                app.units = Some(u);
                app.notice = Some(format!("SI units: {}", u.describe()));
            }
        }
        Action::UnitsOff => {
            app.units = None;
            app.notice = Some("SI units off: dimensionless readouts only".into());
        }
        Action::Omega(d) | Action::R0c(d) => {
            let (omega, r0c) = &mut app.mu_probe;
            if matches!(action, Action::Omega(_)) {
                *omega = round_sig((*omega + d).clamp(0.1, 100.0));
            } else {
                *r0c = round_sig((*r0c + d).clamp(0.001, 10.0));
            }
            if app.page != Page::RestRadius {
                app.notice = Some(format!(
                    "μ probe: Ω = {} rad/s, r0c = {} m (the rest-radius page reads μ)",
                    app.mu_probe.0, app.mu_probe.1
                ));
            }
        }
    }
    app.sync_analysis();
}

/// One tick of sim time (× speed) for both runs. Marks the screen dirty only if time moved.
pub fn step(app: &mut App) -> bool {
    let dtau = super::state::TICK_DT * app.speed;
    let before = (app.sim.cursor, app.sim.samples.len());
    app.sim.advance(dtau);
    let mut moved = before != (app.sim.cursor, app.sim.samples.len());
    moved |= app.catch_up();
    app.dirty |= moved;
    moved
}

/// One tick at today's speed through the history (`dtau` < 0 back): history kept at a faster
/// speed has samples further apart, so the state a tick away comes from the path (the run's
/// dense output on its τ grid) and joins the history. False at the latest sample going
/// forward (time then advances by integrating).
fn step_through_history(sim: &mut crate::sim::Sim, dtau: f64) -> bool {
    let (now, k) = (sim.now().tau, sim.cursor);
    let next = if dtau < 0.0 {
        k.checked_sub(1)
    } else {
        Some(k + 1).filter(|&n| n < sim.samples.len())
    };
    let Some(n) = next else {
        return false;
    };
    let target = now + dtau;
    let neighbour = sim.samples[n].tau;
    // Further than a tick: the path's state nearest the target, if strictly between.
    let between = if (neighbour - now).abs() > dtau.abs() + 1e-9 {
        match sim.run.status {
            // At rest it rides the table: the path keeps one turn of it, the closed form all.
            crate::engine::Status::Stuck { tau, q } if target >= tau => {
                Some(State::riding(q, target))
            }
            _ => {
                let i = sim.path.partition_point(|s| s.tau < target - 1e-9);
                sim.path
                    .get(i)
                    .filter(|s| (s.tau - target).abs() < 1e-9)
                    .copied()
            }
        }
    } else {
        None
    };
    match between {
        Some(s) if dtau < 0.0 => sim.samples.insert(k, s),
        Some(s) => {
            sim.samples.insert(n, s);
            sim.cursor = n;
        }
        None => sim.cursor = n,
    }
    true
}

/// Rounds to 12 significant digits so that ×√10 twice gives exactly ×10 on screen.
fn round_sig(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let e = x.abs().log10().floor() as i32;
    let m = 10f64.powi(11 - e);
    (x * m).round() / m
}

/// The item after `x` in `all`, wrapping round.
fn next_of<T: Copy + PartialEq>(all: &[T], x: T) -> T {
    let i = all.iter().position(|a| *a == x).unwrap_or(0);
    all[(i + 1) % all.len()]
}
