//! The work–precision bench: rows with finite errors, errors that shrink as the step or the
//! tolerance tightens, the fixed-step methods' orders, and the fast escape speed against pure
//! bisection. No test here depends on timing.
use crate::reference;

use turntable::bench::{self, Config, Task};
use turntable::engine::Method as M;
use turntable::engine::solve::escape_speed;
use turntable::engine::{Initial, Method, Outcome, Run, Settings};

fn tiny() -> Config {
    Config {
        quick: true,
        cases: 3,
        seed: 7,
        reps: 0,
        python: None,
        goals: false,
    }
}

#[test]
fn quick_bench_rows_are_finite_and_converge() {
    let report = bench::run(&tiny(), |_| {}).expect("bench runs");
    assert!(!report.rows.is_empty());
    for &task in <Task as strum::VariantArray>::VARIANTS {
        assert!(
            report.rows.iter().any(|r| r.task == task),
            "task {task} missing"
        );
    }
    for r in &report.rows {
        assert!(
            r.err_median.is_finite() && r.err_worst.is_finite() && r.err_median >= 0.0,
            "{} {} {}: error {} / {}",
            r.task,
            r.method,
            r.setting,
            r.err_median,
            r.err_worst
        );
        assert!(r.rhs_evals > 0);
    }
    // Errors shrink as dt / tol tighten (over two decades; single steps may wobble).
    for m in [M::Rk2, M::Rk4, M::Dp54] {
        let rows: Vec<_> = report
            .rows
            .iter()
            .filter(|r| r.task == Task::Rest && r.method == m)
            .collect();
        let first = rows.first().unwrap();
        let last = rows.last().unwrap();
        assert!(
            last.err_median < 1e-2 * first.err_median,
            "{m}: {} -> {}",
            first.err_median,
            last.err_median
        );
    }
    // Stick events: no drift after the stop; the paper's raw scheme creeps.
    let drift = |m: M, s: &str| {
        report
            .rows
            .iter()
            .find(|r| r.task == Task::Drift && r.method == m && r.setting == s)
            .unwrap()
            .err_median
    };
    assert!(drift(M::Rk2Raw, "dt=1e-3") > 1e3 * drift(M::Rk2, "dt=1e-3"));
    // The reference agrees with its cross-check.
    for c in &report.reference {
        assert!(c.agreement < 1e-6, "{}: {}", c.task, c.agreement);
    }
    // Every method gets the outcome right once accurate: dt ≤ 1e-2, or tol ≤ 1e-6 (looser
    // dp54 tolerances misjudge releases near the escape threshold).
    for r in report.rows.iter().filter(|r| r.task == Task::Rest) {
        if r.knob <= if r.method.adaptive() { 1e-6 } else { 1e-2 } {
            assert_eq!(r.wrong, 0, "{} {}", r.method, r.setting);
        }
        // The raw scheme has no stop of its own (`run --method rk2-raw` never stops): the
        // row names the rule the bench stops it by.
        assert_eq!(
            r.method == M::Rk2Raw,
            r.setting.ends_with("|u|≤dt"),
            "{}",
            r.setting
        );
    }
    // Task by task against rk2 at dt = 1e-3: dp54 is at least as accurate wherever it is
    // listed, and on the smooth stretch (no stop to close in on) far cheaper.
    for t in &report.ratios {
        assert!(t.dp54_err <= t.rk2_err && t.ratio > 1.0, "{t:?}");
    }
    let smooth = report
        .ratios
        .iter()
        .find(|t| t.task == Task::Smooth)
        .unwrap();
    assert!(smooth.ratio > 20.0, "{smooth:?}");
    assert!(bench::table(&report).contains("rest"));
    // dop853 has its rows, and at tight tolerances on the rest task it needs fewer RHS
    // evaluations than dp54 at the same error: the bench names where that starts.
    let rest = report
        .crossovers
        .iter()
        .find(|c| c.task == Task::Rest)
        .unwrap();
    let tight = rest.points.last().unwrap();
    assert!(tight.tol <= 1e-10 && tight.ratio > 1.3, "{rest:?}");
    let (tol, _) = rest.from.unwrap();
    assert!(tol >= 1e-8, "{rest:?}");
    assert!(bench::table(&report).contains("dop853 cheaper from tol="));
    // The chart marks each method's points and names its axes.
    let plot = bench::plot(&report, Task::Rest, 72, 20).unwrap();
    for want in [
        "r rk2-raw",
        "d dp54",
        "8 dop853",
        "log10 RHS evaluations per case",
        "rest",
    ] {
        assert!(plot.contains(want), "{want} not in\n{plot}");
    }
    // Issue 34: the price of each model (closed forms take no step, the body more than the
    // point), and the pages' rows (most map cells answered by their first run).
    let rhs = |m: &str| {
        report
            .models
            .iter()
            .find(|r| r.model.starts_with(m))
            .unwrap()
    };
    assert_eq!(report.models.len(), 6);
    assert!(rhs("spin-up").frame_ms > 0.0 && rhs("spin-up").run_rhs > 0.0);
    assert_eq!(rhs("μ = 0").run_rhs, 0.0);
    assert_eq!(rhs("Stokes").run_rhs, 0.0);
    assert!(rhs("the appendix's body").run_rhs > rhs("point").run_rhs);
    assert!(rhs("μ = 0").page_ms.is_none() && rhs("point").page_ms.is_some());
    let p = &report.pages;
    assert!(p.refined * 5 < p.grid.0 * p.grid.1, "{p:?}");
    // The second opinion's price, on the bracket ends, the rest cases and stops at the rim.
    assert_eq!(report.checks.len(), 3);
    assert!(
        report
            .checks
            .iter()
            .all(|c| c.runs > 0 && c.evals_ratio() > 0.0)
    );
    for want in [
        "the price of each model",
        "`x` → outcome map complete",
        "the second opinion behind `certain`",
    ] {
        assert!(bench::table(&report).contains(want), "{want}");
    }
    let json = serde_json::to_string(&report).unwrap();
    assert!(
        json.contains("\"task\":\"drift τ=20\",\"method\":\"rk2-raw\""),
        "{json}"
    );
    honest_rows(&report);
}

/// Issue 42: errors only down to the reference's resolution; a row per setting of what its runs
/// stated against what they were off by; a fixed-step row that the end game decides says so.
fn honest_rows(report: &bench::Report) {
    let table = bench::table(report);
    for r in &report.rows {
        assert!(r.resolution > 0.0, "{} {}", r.task, r.setting);
        let line = table
            .lines()
            .find(|l| {
                l.starts_with(&r.task.to_string())
                    && l.contains(&format!(" {} ", r.method))
                    && l.contains(&format!(" {} ", r.setting))
            })
            .unwrap_or_else(|| panic!("{} {} {}", r.task, r.method, r.setting));
        let below = format!("<{:.1e}", r.resolution);
        assert_eq!(
            line.contains(&below),
            r.err_median < r.resolution || r.time_median.is_some_and(|t| t < r.resolution),
            "{line}"
        );
        // Stops are stated on by every method with stick events, and by no other.
        let stops = r.task == Task::Rest || r.task == Task::Rim;
        assert_eq!(
            r.stated.is_some(),
            stops && r.method.stick_events(),
            "{line}"
        );
    }
    // At the rim rk2 at dt = 0.1 takes no step of its own: the implicit end game starts at the
    // release and takes every stop, and the row says so instead of crediting rk2.
    let rim = report
        .rows
        .iter()
        .find(|r| r.task == Task::Rim && r.method == M::Rk2 && r.setting == "dt=1e-1")
        .unwrap();
    let end = rim.end_game.as_ref().unwrap();
    assert_eq!(end.took_stop, end.cases);
    assert!(end.evals_share > 0.99, "{end:?}");
    assert!(rim.err_median < rim.resolution);
    assert!(table.contains("the row measures the end game, not the method"));
    assert!(table.contains("stated vs actual: τ "));
}

#[test]
fn fixed_methods_show_their_order() {
    // Case A before any stop (it stops near τ ≈ 1.4): a smooth stretch.
    let a = Initial::velocity(0.5, std::f64::consts::PI, 1.0);
    let mut run = Run::new(a, Settings::default()).unwrap();
    let (outcome, end) = run.finish(100.0).unwrap();
    assert_eq!(outcome, Outcome::Stuck);
    assert!(end.tau > 0.6, "A stops at {}", end.tau);
    for (m, p) in [(Method::Rk2, 2), (Method::Rk2Raw, 2), (Method::Rk4, 4)] {
        let e1 = bench::position_error(a, m, 0.01, 0.5).unwrap();
        let e2 = bench::position_error(a, m, 0.005, 0.5).unwrap();
        let ratio = e1 / e2;
        let want = 2f64.powi(p);
        assert!(
            (ratio / want - 1.0).abs() < 0.15,
            "{m}: error ratio {ratio} (errors {e1:e}, {e2:e}), want ≈ {want}"
        );
    }
}

#[test]
fn fast_escape_speed_matches_bisection_and_is_certified() {
    let s = Settings::default();
    for (xi0, phi) in [(0.5, 0.0), (0.8, 0.4), (0.2, 4.0), (0.001, 2.0), (0.8, 5.5)] {
        let t = escape_speed(xi0, phi, s, 1e-8).unwrap();
        assert!(t.stuck_at.unwrap() < t.escapes_at, "{t:?}");
        assert!(t.escapes_at - t.stuck_at.unwrap() <= 1e-8, "{t:?}");
        assert!(t.interval);
        // The certificate itself: a run at each end, with the outcome claimed.
        let end = |v0: f64| {
            let mut run = Run::new(Initial::velocity(xi0, phi, v0), s).unwrap();
            run.run(1e4, true).unwrap()
        };
        assert_eq!(end(t.stuck_at.unwrap()), Outcome::Stuck);
        assert_eq!(end(t.escapes_at), Outcome::Escaped);
        // Pure bisection on the outcome from the certified bracket's neighbourhood.
        let (mut lo, mut hi) = (t.value - 1e-5, t.value + 1e-5);
        assert_eq!(end(lo), Outcome::Stuck);
        assert_eq!(end(hi), Outcome::Escaped);
        while hi - lo > 1e-9 {
            let mid = 0.5 * (lo + hi);
            if end(mid) == Outcome::Escaped {
                hi = mid
            } else {
                lo = mid
            }
        }
        let v_bisect = 0.5 * (lo + hi);
        assert!(
            (t.value - v_bisect).abs() <= 1e-8,
            "({xi0}, {phi}): fast {} against bisection {v_bisect}",
            t.value
        );
    }
    let t = escape_speed(0.5, 0.0, s, 1e-8).unwrap();
    assert!((t.value - reference::VE_C).abs() < 1e-8, "{}", t.value);
}

#[test]
fn splitmix_is_deterministic() {
    let a = bench::cases(5, 42);
    let b = bench::cases(5, 42);
    assert_eq!(a.len(), 8);
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x, y);
    }
    for x in &a[3..] {
        assert!((0.0..=0.9).contains(&x.xi0) && (0.0..=0.5).contains(&x.v0));
    }
}

/// What a playing frame writes through the real crossterm backend: every theme within the
/// slow-link budget (a byte count, deterministic: no clock), and 256 colours cheaper than 24-bit.
#[test]
fn terminal_bytes_fit_a_slow_link() {
    use turntable::bench::bytes::{GOAL_KB_PER_S, all};
    let rows = all(60).unwrap();
    assert_eq!(rows.len(), 8);
    for r in &rows {
        assert!(r.kb_per_s <= GOAL_KB_PER_S, "{r:?}");
        assert!(r.bytes_per_frame > 50.0, "something is drawn: {r:?}");
    }
    let dark = |d: &str| {
        rows.iter()
            .find(|r| r.theme == "dark" && r.depth == d)
            .unwrap()
    };
    assert!(dark("256").bytes_per_frame < 0.9 * dark("24-bit").bytes_per_frame);
}

/// Over a 4 and a 16 KB/s link (simulated in link time, frames measured through the real
/// backend): one frame in flight where drawing every tick leaves dozens queued, keys within
/// the bounds, and sim time kept.
#[test]
fn over_a_slow_link_one_frame_is_in_flight() {
    use turntable::bench::link::simulate_scene;
    let default = turntable::scene::Scene::default_scene();
    let slow = simulate_scene(&default, 4096.0, 10.0).unwrap();
    let fast = simulate_scene(&default, 16384.0, 10.0).unwrap();
    for l in [&slow, &fast] {
        assert_eq!(l.in_flight, 1, "{l:?}");
        assert!(l.time_kept > 0.95 && l.time_kept <= 1.0, "{l:?}");
        assert!(l.bytes_per_frame > 50.0, "{l:?}");
    }
    assert!(slow.unpaced_in_flight > 30, "{slow:?}");
    // The first screen alone takes ~3.6 s at 4 KB/s; after it a key waits for two frames.
    assert!(
        slow.frames_per_s > 2.0 && fast.frames_per_s > 10.0,
        "{slow:?} {fast:?}"
    );
    assert!(
        slow.worst_key_s < 1.5 && fast.worst_key_s < 0.5,
        "{slow:?} {fast:?}"
    );
}

/// A body scene over the same links (its bar, its centre's path and the panel's body lines
/// change as it plays): still one frame in flight, keys within the same bounds, and a frame
/// about as large as without the body (measured 540 against 529 bytes at 4 KB/s).
#[test]
fn over_a_slow_link_a_body_costs_about_what_the_point_does() {
    use turntable::bench::link::{body_scene, simulate_scene};
    let default = turntable::scene::Scene::default_scene();
    for rate in [4096.0, 16384.0] {
        let point = simulate_scene(&default, rate, 10.0).unwrap();
        let body = simulate_scene(&body_scene(), rate, 10.0).unwrap();
        assert!(body.scene.contains("body"), "{body:?}");
        assert_eq!(body.in_flight, 1, "{body:?}");
        assert!(body.time_kept > 0.95, "{body:?}");
        assert!(
            body.bytes_per_frame < 1.25 * point.bytes_per_frame,
            "{body:?} {point:?}"
        );
        let bound = if rate < 8192.0 { 1.5 } else { 0.5 };
        assert!(body.worst_key_s < bound, "{body:?}");
    }
}

/// Issue 33 item 4: the bench states a recording's worst bytes per tick (a whole-screen
/// frame every tick): at 80×24 and at the largest screen a script may ask for, with the ticks
/// until the recording's bound, which the 3-line script now reaches.
#[test]
fn a_recordings_worst_tick_and_its_bound() {
    use turntable::bench::bytes::cast_worst;
    let small = cast_worst((80, 24), 30).unwrap();
    let large = cast_worst((1000, 1000), 1).unwrap();
    eprintln!("{small:?}\n{large:?}");
    // A whole screen: at least a byte a cell.
    assert!(small.worst_bytes_per_tick >= 80 * 24, "{small:?}");
    assert!(large.worst_bytes_per_tick >= 1_000_000, "{large:?}");
    for c in [&small, &large] {
        assert_eq!(c.bound_bytes, turntable::replay::CAST_BYTES_MAX);
        assert_eq!(c.bound_frames, turntable::asciicast::MAX_FRAMES);
        let by_bytes = c.bound_bytes / c.worst_bytes_per_tick as u64;
        assert_eq!(c.ticks_to_bound, by_bytes.min(c.bound_frames), "{c:?}");
    }
    // 1000×1000 reaches the bound within seconds of play, not after gigabytes.
    assert!(large.ticks_to_bound < 30 * 10, "{large:?}");
}
