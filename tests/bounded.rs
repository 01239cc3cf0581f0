//! Every key answers within a frame's budget (issue 11): work is counted, not timed.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use turntable::app::App;
use turntable::engine::{Initial, Release};
use turntable::scene::Scene;
use turntable::session::Session;
use turntable::sim::STEPS_PER_TICK;
use turntable::theme::Theme;

fn key(c: char) -> KeyEvent {
    KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE)
}

fn session(scene: &str) -> Session<ratatui::backend::TestBackend> {
    let app = App::new(
        Scene::preset(scene).unwrap(),
        Theme::builtin("mono").unwrap(),
    );
    Session::headless(app, 80, 24, false)
}

/// `c` after a long frictionless session used to catch up 1e-3 τ at a time inside the key
/// (20 s). Now the key does no integration; the paper's run catches up over the following
/// ticks, even while paused, within each tick's step budget.
#[test]
fn compare_after_a_long_session_catches_up_over_ticks() {
    for friction in [false, true] {
        let mut scene = Scene::preset("A").unwrap();
        if !friction {
            // At rest in the lab with no friction: it stays there forever.
            scene.initial = Initial {
                frictionless: true,
                ..Initial::at_rest(0.5, Release::LabRest)
            };
        }
        let app = App::new(scene, Theme::builtin("mono").unwrap());
        let mut s = Session::headless(app, 80, 24, false);
        for _ in 0..8 {
            s.key(key(']'));
        }
        for _ in 0..2000 {
            s.tick();
        }
        s.key(key(' '));
        let tau = s.app.now().tau;
        assert!(tau > 1000.0, "{tau}");
        s.key(key('c'));
        let p = s.app.paper.as_ref().unwrap();
        assert!(p.samples.len() <= 2, "{}", p.samples.len());
        // In closed form (μ = 0) it is there at once; else, paused, it ticks until it is.
        assert_eq!(s.app.paper_lags(), friction);
        assert_eq!(s.app.is_playing(), friction);
        let mut ticks = 0;
        while s.app.paper_lags() {
            let before = s.app.paper.as_ref().unwrap().run.cost.steps;
            s.tick();
            let p = s.app.paper.as_ref().unwrap();
            assert!(p.run.cost.steps - before <= STEPS_PER_TICK);
            ticks += 1;
            assert!(ticks < 1000, "never caught up");
        }
        let p = s.app.paper.as_ref().unwrap();
        assert!(
            (p.now().tau - tau).abs() < 1e-9 || !p.live(),
            "{} {tau}",
            p.now().tau
        );
        assert!(!s.app.is_playing());
    }
}

/// Restarting does not buy more work per tick: `r` then a tick costs at most one tick's
/// budget, however often it is repeated.
#[test]
fn restart_work_is_bounded_per_tick() {
    let mut s = session("C");
    // dp54 → dop853 → rk2-raw → rk2 → rk4
    for _ in 0..4 {
        s.key(key('m'));
    }
    for _ in 0..200 {
        s.key(key('r'));
        s.tick();
        let c = s.app.sim.run.cost;
        assert!(c.steps + c.rejected <= STEPS_PER_TICK + 1, "{c:?}");
    }
}

/// `e` on a long run: the shadow run is held to one tick's budget and says so.
#[test]
fn error_estimate_is_bounded() {
    let mut s = session("fig1");
    for _ in 0..8 {
        s.key(key(']'));
    }
    for _ in 0..1000 {
        s.tick();
    }
    let est = s.app.sim.error_estimate();
    match est {
        Ok(e) => assert!(e.rhs_evals <= 13 * STEPS_PER_TICK, "{e:?}"),
        Err(e) => assert!(
            matches!(
                e,
                turntable::error::Error::Run(turntable::engine::RunError::Budget { .. })
            ),
            "{e}"
        ),
    }
}
