//! Every key answers within a frame's budget (issue 11): work is counted, not timed.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use turntable::app::App;
use turntable::app::testing::Testing as _;
use turntable::engine::{Initial, Release};
use turntable::scene::Scene;
use turntable::session::Explorer;
use turntable::sim::STEPS_PER_TICK;
use turntable::sim::testing::Testing as _;

fn key(c: char) -> KeyEvent {
    KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE)
}

fn session(scene: &str) -> Explorer<ratatui::backend::TestBackend> {
    let app = App::new(Scene::preset(scene).unwrap());
    Explorer::headless(
        app,
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        false,
    )
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
        let app = App::new(scene);
        let mut s = Explorer::headless(
            app,
            turntable::theme::Theme::builtin("dark").unwrap(),
            80,
            24,
            false,
        );
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
        let p = s.app.paper().unwrap();
        assert!(p.samples.len() <= 2, "{}", p.samples.len());
        // In closed form (μ = 0) it is there at once; else, paused, it ticks until it is.
        assert_eq!(s.app.paper_lags(), friction);
        assert_eq!(s.app.is_playing(), friction);
        let mut ticks = 0;
        while s.app.paper_lags() {
            let before = s.app.paper().unwrap().cost().steps;
            s.tick();
            let p = s.app.paper().unwrap();
            assert!(p.cost().steps - before <= STEPS_PER_TICK);
            ticks += 1;
            assert!(ticks < 1000, "never caught up");
        }
        let p = s.app.paper().unwrap();
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
        let c = s.app.sim().cost();
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
    let est = s.app.sim().error_estimate();
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

fn keys(s: &mut Explorer<ratatui::backend::TestBackend>, keys: &str) {
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
    assert!(s.app.initial().frictionless);
    for _ in 0..40_000 {
        let before = s.app.sim().work.points;
        s.tick();
        bounded(s.app.sim(), before);
    }
    assert!(s.app.now().tau > 100_000.0, "{}", s.app.now().tau);
    keys(&mut s, "[[[[[[[[[[[[[[");
    s.key(key('c'));
    let p = s.app.paper().unwrap();
    bounded(p, 0);
    assert!((p.now().tau - s.app.now().tau).abs() < 1e-9);
    for _ in 0..100 {
        let before = s.app.paper().unwrap().work.points;
        s.tick();
        bounded(s.app.paper().unwrap(), before);
    }
    // `n` strides on 1000 τ at a time: 40,000 points each, never more kept.
    let mut s = session("A");
    keys(&mut s, "FRR");
    for _ in 0..500 {
        let before = s.app.sim().work.points;
        s.key(key('n'));
        bounded(s.app.sim(), before);
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
        s.app.sim().settings().method(),
        turntable::engine::Method::Rk2Raw
    );
    for _ in 0..8 {
        s.key(key(']'));
    }
    let mut ticks = 0;
    while s.app.now().tau < 150.0 && s.app.sim().live() {
        s.tick();
        ticks += 1;
        assert!(ticks < 10_000);
    }
    s.key(key(' '));
    let tau = s.app.now().tau;
    let steps = s.app.sim().work.steps;
    assert!(tau >= 150.0 && s.app.sim().run_tau() > tau, "{tau}");
    s.key(key('n'));
    // The step holding the screen's τ is the run's latest: nothing to integrate.
    assert_eq!(s.app.sim().work.steps, steps);
    s.key(key('n'));
    let sim = s.app.sim();
    assert_eq!(sim.work.steps - steps, 1, "{:?}", sim.work);
    assert!(sim.now().tau > tau, "{} {tau}", sim.now().tau);
    assert_eq!(sim.now(), sim.motion().state());
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
    let app = App::new(scene);
    let mut s = Explorer::headless(
        app,
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        false,
    );
    s.key(KeyEvent::new(KeyCode::Char(' '), KeyModifiers::NONE));
    s.key(KeyEvent::new(KeyCode::Tab, KeyModifiers::NONE));
    s.key(KeyEvent::new(KeyCode::Tab, KeyModifiers::NONE));
    s.screen();
    assert!(!s.analysis.busy());
    assert_eq!(s.app.settings(), tiny);
    // The page is complete: every curve's every piece arrived (unknown where over budget).
    let curve = s
        .app
        .charts()
        .curve(0.5, settings_for(tiny))
        .expect("C's curve");
    assert!(curve.complete());
}

fn tab(s: &mut Explorer<ratatui::backend::TestBackend>, n: usize) {
    for _ in 0..n {
        s.key(KeyEvent::new(KeyCode::Tab, KeyModifiers::NONE));
    }
}

/// Issue 18 item 18: headless, a page is computed for a frame, not for each key. Twenty edits
/// of ξ0 on the outcome map and one snapshot compute one curve and one map (they computed
/// twenty of each, 3.4 s an edit at 1000×1000).
#[test]
fn headless_pages_are_computed_for_frames_not_for_keys() {
    use turntable::analysis::{CURVE_POINTS, MAP_CELLS};
    let mut s = session("A");
    tab(&mut s, 3);
    s.screen();
    let cells = s.app.charts().map.as_ref().expect("map").cells.len() as u64;
    assert!(cells > 500, "{cells}");
    let first = s.analysis.computed();
    assert_eq!(first, CURVE_POINTS as u64 + cells);
    for _ in 0..20 {
        s.key(key('x'));
    }
    assert_eq!(s.analysis.computed(), first, "keys compute nothing");
    s.screen();
    let map = s.app.charts().map.as_ref().expect("map");
    assert!(map.cells.iter().all(Option::is_some));
    assert_eq!(
        s.analysis.computed() - first,
        CURVE_POINTS as u64 + map.cells.len() as u64
    );
    // However large the terminal, a map has at most MAP_CELLS cells, in the plot's shape.
    s.resize(1000, 1000);
    let v0_max = 1.0;
    let (n, m) = turntable::ui::pages::map_grid(&s.app, v0_max).expect("a plot fits");
    assert!(n * m <= MAP_CELLS && n * m > MAP_CELLS * 9 / 10, "{n}×{m}");
    // Nearly square, as the plot of a square terminal is.
    assert!(n.abs_diff(m) < n / 5, "{n}×{m}");
}

/// A coarser grid than the plot is drawn over every character of the plot: no holes.
#[test]
fn a_map_coarser_than_its_plot_covers_it() {
    use turntable::analysis::MAP_CELLS;
    let mut s = session("A");
    s.resize(320, 120);
    tab(&mut s, 3);
    let screen = turntable::ui::export::plain_text(s.screen());
    let map = s.app.charts().map.as_ref().expect("map");
    let turntable::analysis::Job::Map { size: (n, m), .. } = map.job else {
        panic!("{:?}", map.job)
    };
    let plot = s.app.geom_for_tests().expect("drawn").area;
    assert!(
        n * m <= MAP_CELLS && usize::from(plot.width) > n,
        "{n}×{m} for {plot:?}"
    );
    // The plot shows cells: nothing unknown, and stuck glyphs all along its lowest speeds.
    let rows: Vec<String> = screen
        .lines()
        .skip(usize::from(plot.y))
        .take(usize::from(plot.height))
        .map(|l| {
            l.chars()
                .skip(usize::from(plot.x))
                .take(usize::from(plot.width))
                .collect()
        })
        .collect();
    assert!(rows.iter().all(|r| !r.contains('?')), "{rows:#?}");
    let bottom = rows.last().unwrap();
    let stuck = bottom
        .chars()
        .filter(|c| matches!(c, '·' | ':' | '▒' | '▓'))
        .count();
    assert!(stuck > usize::from(plot.width) / 2, "{bottom}");
}

/// A running piece stops at its next run once its caller says stop (the explorer's worker
/// so waits at most one bounded run for a newer request), and its answer is dropped.
#[test]
fn a_running_piece_stops_at_its_next_run_once_cancelled() {
    use std::cell::Cell;
    use turntable::analysis::{Job, REST_POINTS, piece_until, settings_for};
    use turntable::engine::Settings;
    let s = settings_for(Settings::default());
    for (job, k) in [
        (Job::Curve { xi0: 0.5 }, 0),
        (Job::Curve { xi0: 1.3 }, 40),
        (Job::Rest, REST_POINTS),
    ] {
        let runs = Cell::new(0u32);
        let all = piece_until(&job, k, s, &|| {
            runs.set(runs.get() + 1);
            true
        });
        assert!(all.is_some());
        let n = runs.get();
        assert!(n > 20, "{job:?}: {n} runs");
        for stop_at in [1, n / 2, n - 1] {
            let asked = Cell::new(0u32);
            let got = piece_until(&job, k, s, &|| {
                asked.set(asked.get() + 1);
                asked.get() < stop_at
            });
            assert_eq!(got, None, "{job:?}");
            // Asked once more at the end, and at most once by a second bisection: no run
            // starts after the first no.
            assert!(
                asked.get() <= stop_at + 2,
                "{job:?}: {} > {stop_at} + 2",
                asked.get()
            );
        }
    }
}
