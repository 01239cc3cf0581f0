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
            let before = s.app.paper.as_ref().unwrap().run.cost().steps;
            s.tick();
            let p = s.app.paper.as_ref().unwrap();
            assert!(p.run.cost().steps - before <= STEPS_PER_TICK);
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
        let c = s.app.sim.run.cost();
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

fn keys(s: &mut Session<ratatui::backend::TestBackend>, keys: &str) {
    for c in keys.chars() {
        s.key(key(c));
    }
}

/// Issue 18 item 16: a frictionless step strides 1000 τ (40,000 trail points); a long μ = 0
/// session and `c` after it (the paper's run catching up 100,000 τ) used to build millions of
/// points (26 s, 499 MB). Now the trail never holds more than TRAIL_MAX points nor allocates
/// for more, and no tick or key evaluates more than TRAIL_MAX of them.
#[test]
fn frictionless_trail_is_bounded_per_point_and_per_tick() {
    use turntable::sim::{Sim, TRAIL_MAX};
    let bounded = |sim: &Sim, before: u64| {
        assert!(sim.path.len() <= TRAIL_MAX, "{}", sim.path.len());
        assert!(
            sim.path.capacity() <= TRAIL_MAX.next_power_of_two(),
            "{}",
            sim.path.capacity()
        );
        assert!(
            sim.work.points - before <= TRAIL_MAX as u64,
            "{:?}",
            sim.work
        );
    };
    let mut s = session("A");
    keys(&mut s, "FRR]]]]]]]]");
    assert!(s.app.initial.frictionless);
    for _ in 0..40_000 {
        let before = s.app.sim.work.points;
        s.tick();
        bounded(&s.app.sim, before);
    }
    assert!(s.app.now().tau > 100_000.0, "{}", s.app.now().tau);
    keys(&mut s, "[[[[[[[[[[[[[[");
    s.key(key('c'));
    let p = s.app.paper.as_ref().unwrap();
    bounded(p, 0);
    assert!((p.now().tau - s.app.now().tau).abs() < 1e-9);
    for _ in 0..100 {
        let before = s.app.paper.as_ref().unwrap().work.points;
        s.tick();
        bounded(s.app.paper.as_ref().unwrap(), before);
    }
    // `n` strides on 1000 τ at a time: 40,000 points each, never more kept.
    let mut s = session("A");
    keys(&mut s, "FRR");
    for _ in 0..500 {
        let before = s.app.sim.work.points;
        s.key(key('n'));
        bounded(&s.app.sim, before);
    }
    assert!(s.app.now().tau >= 400_000.0, "{}", s.app.now().tau);
}

/// Issue 18 item 17: `n` with the run integrated past the screen showed the step holding the
/// τ on screen by integrating the whole run again from τ = 0 (1.5 s at τ = 150 with rk2). Now
/// the run's latest step is that step: the key steps nothing, and the next one steps once.
#[test]
fn integrator_step_steps_from_the_current_state() {
    // dp54 → dop853 → the paper's raw rk2: no stick event, so A's stop chatters on, slipping.
    let mut s = session("A");
    s.key(key('m'));
    s.key(key('m'));
    assert_eq!(
        s.app.sim.run.settings().method(),
        turntable::engine::Method::Rk2Raw
    );
    for _ in 0..8 {
        s.key(key(']'));
    }
    let mut ticks = 0;
    while s.app.now().tau < 150.0 && s.app.sim.live() {
        s.tick();
        ticks += 1;
        assert!(ticks < 10_000);
    }
    s.key(key(' '));
    let tau = s.app.now().tau;
    let steps = s.app.sim.work.steps;
    assert!(tau >= 150.0 && s.app.sim.run.tau() > tau, "{tau}");
    s.key(key('n'));
    // The step holding the screen's τ is the run's latest: nothing to integrate.
    assert_eq!(s.app.sim.work.steps, steps);
    s.key(key('n'));
    let sim = &s.app.sim;
    assert_eq!(sim.work.steps - steps, 1, "{:?}", sim.work);
    assert!(sim.now().tau > tau, "{} {tau}", sim.now().tau);
    assert_eq!(sim.now(), sim.run.state());
}

/// Issue 18 item 18: the pages' runs are held to PIECE_STEPS steps each, whatever the
/// scene's step: rk2 at dt 1e-7 needed 1e11 steps a run and `Tab Tab` never finished. Now a
/// run stops at the budget, its piece is unknown, and the page is complete.
#[test]
fn page_pieces_are_bounded_whatever_the_step() {
    use turntable::analysis::{PIECE_STEPS, settings_for};
    use turntable::engine::method::Method;
    use turntable::engine::{Run, RunError, Settings};
    let tiny = Settings::fixed(Method::Rk2, 1e-7);
    let s = settings_for(tiny);
    assert_eq!(s.max_steps, PIECE_STEPS);
    let mut run = Run::new(Initial::velocity(0.5, 0.0, 0.3), s).unwrap();
    let r = run.run(turntable::engine::solve::CLASSIFY_TAU, true);
    assert!(matches!(r, Err(RunError::Budget { .. })), "{r:?}");
    assert!(run.cost().steps + run.cost().rejected <= PIECE_STEPS);
    let mut scene = Scene::preset("C").unwrap();
    scene.settings = tiny;
    let app = App::new(scene, Theme::builtin("mono").unwrap());
    let mut s = Session::headless(app, 80, 24, false);
    s.key(KeyEvent::new(KeyCode::Char(' '), KeyModifiers::NONE));
    s.key(KeyEvent::new(KeyCode::Tab, KeyModifiers::NONE));
    s.key(KeyEvent::new(KeyCode::Tab, KeyModifiers::NONE));
    assert!(!s.app.analysis.busy());
    assert_eq!(s.app.settings, tiny);
}
