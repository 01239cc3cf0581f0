//! The pure update: an action applied to the state. No I/O, no clock: what must happen
//! outside (a file saved or exported) is returned as [`Effects`] for the shell to carry out.
//! One module per help group (as the keymap lists them); `update` dispatches on the action's
//! group.

mod app;
mod initial;
mod integrator;
mod lesson;
mod time;
mod view;

use super::action::{Action, Group};
use super::effect::Effects;
use super::state::App;

/// Applies `action` to `app`; returns what the shell must do outside the model.
pub fn update(app: &mut App, action: Action) -> Effects {
    if action == Action::EndDrag {
        // Letting go of the mouse changes nothing on screen (the notice stays).
        app.dragging = false;
        return Effects::new();
    }
    app.dirty = true;
    app.notice = None;
    let mut effects = Effects::new();
    if app.scene().spin.is_some()
        && let Some(why) = spin_refuses(action)
    {
        app.notice = Some(why.into());
        return effects;
    }
    match action.group() {
        Group::Time => time::apply(app, action),
        Group::InitialConditions => initial::apply(app, action),
        Group::Integrator => integrator::apply(app, action),
        Group::View => view::apply(app, action),
        Group::App => effects = app::apply(app, action),
        Group::Lesson => lesson::apply(app, action),
    }
    // A body's track cut short by the key just pressed says so, beside what the key said.
    if let Some(cut) = app.exploration.take_rod_notice() {
        app.notice = Some(match app.notice.take() {
            Some(n) => format!("{n}; {cut}"),
            None => cut,
        });
    }
    effects
}

/// What a spin-up scene does not take, and why: its coin starts at rest on the table, and it
/// is shown on the turntable page (the other pages, pins and the paper's run are the
/// constant-Ω table's).
fn spin_refuses(action: Action) -> Option<&'static str> {
    use Action::*;
    Some(match action {
        Phi(_) | V0(_) | CycleRelease | AimVelocity(..) => {
            "the spin-up starts the coin at rest on the table: only ξ0 changes (x/X, or a click)"
        }
        ToggleFriction => "the spin-up needs friction: the slip is how it measures μ",
        ToggleCompare => "the paper's RK2 runs a table at constant Ω: it has no spin-up to compare",
        PinRun => "pins run the table at constant Ω, not the spin-up",
        NextPage | PrevPage | Choose | PickRelease(_) | Omega(_) | R0c(_) => {
            "a spin-up scene has the turntable page only: the other pages are the constant-Ω table's"
        }
        _ => return None,
    })
}

/// One tick of sim time (× speed) for both runs. Marks the screen dirty only if time moved.
pub fn step(app: &mut App) -> bool {
    let dtau = super::state::TICK_DT * app.speed;
    let (sim, _) = app.exploration.runs_mut();
    let before = (sim.cursor, sim.samples.len());
    sim.advance(dtau);
    let moved = before != (sim.cursor, sim.samples.len());
    let mut moved = moved;
    moved |= app.catch_up();
    app.dirty |= moved;
    moved
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
