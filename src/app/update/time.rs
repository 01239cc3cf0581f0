//! The "time" group: play, step, speed, restart.

use super::super::action::Action;
use super::super::state::{App, SPEED_RANGE, TICK_DT};
use super::step;
use crate::engine::State;

pub(super) fn apply(app: &mut App, action: Action) {
    match action {
        Action::PlayPause => {
            app.playing = !app.playing;
            app.view.step_mode &= !app.playing;
        }
        Action::IntegratorStep => {
            app.playing = false;
            app.view.step_mode = true;
            if !app.exploration.runs_mut().0.step_once() {
                app.notice = Some("no more steps: the run has ended (r restarts)".into());
            }
        }
        Action::StepForward => {
            app.playing = false;
            let dtau = TICK_DT * app.speed;
            let (sim, paper) = app.exploration.runs_mut();
            if !step_through_history(sim, dtau) {
                step(app);
            } else if let Some(p) = paper {
                step_through_history(p, dtau);
            }
        }
        Action::StepBack => {
            app.playing = false;
            let dtau = -TICK_DT * app.speed;
            let (sim, paper) = app.exploration.runs_mut();
            step_through_history(sim, dtau);
            if let Some(p) = paper {
                step_through_history(p, dtau);
            }
        }
        Action::Faster => app.speed = (app.speed * 2.0).min(SPEED_RANGE.1),
        Action::Slower => app.speed = (app.speed / 2.0).max(SPEED_RANGE.0),
        Action::Restart => app.exploration.restart(),
        // Other groups' actions: `update` never sends them here.
        _ => {}
    }
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
        match sim.status() {
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
