//! DOP853 (and DOPRI5 beside it): their orders measured on the frictionless table-frame equations,
//! whose solution is known in closed form, and its stick/escape verdicts against dp54's.

use std::f64::consts::{PI, TAU};
use turntable::engine::method::Scheme;
use turntable::engine::model::Y;
use turntable::engine::stepper::{Cost, Dense, Segment, Stepper, adaptive_plain};
use turntable::engine::{Frame, Initial, Method, Outcome, Run, Settings};
use turntable::rng::SplitMix64 as Rng;

const DOP853: Scheme = Scheme::Dop853 { tol: 1e-10 };

/// A frictionless release: closed form in `Initial::free_state`.
fn free() -> Initial {
    Initial {
        frictionless: true,
        ..Initial::velocity(0.6, 1.0, 0.8)
    }
}

fn exact(i: Initial, t: f64) -> Y {
    Frame::Table.from_state(&i.free_state(t))
}

fn dist(a: Y, b: Y) -> f64 {
    ((a.p - b.p).length_squared() + (a.w - b.w).length_squared()).sqrt()
}

fn rhs(y: Y) -> Y {
    Frame::Table.rhs_free(y)
}

/// One step of exactly `h` through `scheme`'s tableau, accepted whatever its error (with its
/// dense output): what the measured orders are taken on. The engine's `retake` from where the
/// stepper is, the step an event is landed on.
fn forced(st: &mut Stepper, scheme: Scheme, h: f64) -> Segment<Y> {
    let here = *st;
    st.retake(rhs, scheme, &here, h, &mut Cost::default())
}

/// The global error at τ = 2 after `n` steps of exactly 2/n through `scheme`'s tableau.
fn global_error_of(scheme: Scheme, n: u32) -> f64 {
    let i = free();
    let mut st = Stepper::new(rhs, exact(i, 0.0), scheme, &mut Cost::default());
    let h = 2.0 / f64::from(n);
    for _ in 0..n {
        forced(&mut st, scheme, h);
    }
    dist(st.y, exact(i, 2.0))
}

fn global_error(n: u32) -> f64 {
    global_error_of(DOP853, n)
}

const DP54: Scheme = Scheme::Dp54 { tol: 1e-10 };

/// DOPRI5 beside it: fifth order, and its dense output (Hairer's contd5) fourth order, whose
/// error within a step is O(h⁵).
#[test]
fn dopri5_is_fifth_order_and_its_dense_output_fourth() {
    let errs: Vec<f64> = [4, 8, 16]
        .into_iter()
        .map(|n| global_error_of(DP54, n))
        .collect();
    for w in errs.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((4.6..5.6).contains(&order), "order {order} from {errs:?}");
    }
    let mid = |h: f64| {
        let i = free();
        let mut st = Stepper::new(rhs, exact(i, 0.3), DP54, &mut Cost::default());
        let seg = forced(&mut st, DP54, h);
        assert!(matches!(seg.dense, Dense::Dp5(_)));
        dist(seg.at(0.5 * h), exact(i, 0.3 + 0.5 * h))
    };
    let errs: Vec<f64> = [0.4, 0.2, 0.1].into_iter().map(mid).collect();
    for w in errs.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!(
            (4.6..5.6).contains(&order),
            "dense order {order} from {errs:?}"
        );
    }
}

#[test]
fn the_step_is_eighth_order() {
    let errs: Vec<f64> = [2, 4, 8].into_iter().map(global_error).collect();
    for w in errs.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((7.5..8.8).contains(&order), "order {order} from {errs:?}");
    }
}

/// One step of `h` from τ = 0.3, and the dense output's error at its midpoint.
fn midpoint_error(h: f64) -> f64 {
    let i = free();
    let mut st = Stepper::new(rhs, exact(i, 0.3), DOP853, &mut Cost::default());
    let seg = forced(&mut st, DOP853, h);
    assert!(matches!(seg.dense, Dense::Dop853(_)));
    dist(seg.at(0.5 * h), exact(i, 0.3 + 0.5 * h))
}

#[test]
fn the_dense_output_is_seventh_order() {
    // A seventh-order interpolant errs by O(h⁸) within one step.
    let errs: Vec<f64> = [0.8, 0.4, 0.2].into_iter().map(midpoint_error).collect();
    for w in errs.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((7.3..8.8).contains(&order), "order {order} from {errs:?}");
    }
    // The ends are the step's own.
    let i = free();
    let mut st = Stepper::new(rhs, exact(i, 0.0), DOP853, &mut Cost::default());
    let seg = forced(&mut st, DOP853, 0.5);
    assert_eq!(seg.at(0.0), exact(i, 0.0));
    assert_eq!(seg.at(0.5), seg.y1);
}

/// Adaptive, the error follows the tolerance (slope near one in log–log), and at tight
/// tolerances it takes fewer right-hand-side evaluations than dp54 for a smaller error.
#[test]
fn adaptive_error_follows_tol_and_beats_dp54_when_tight() {
    let i = free();
    let run = |s: Scheme| {
        let (y, evals) = adaptive_plain(rhs, exact(i, 0.0), 5.0, s).unwrap();
        (dist(y, exact(i, 5.0)), evals)
    };
    let (e6, _) = run(Scheme::Dop853 { tol: 1e-6 });
    let (e10, n8) = run(Scheme::Dop853 { tol: 1e-10 });
    let slope = (e6 / e10).log10() / 4.0;
    assert!((0.6..1.4).contains(&slope), "slope {slope}: {e6} {e10}");
    let (d10, n5) = run(Scheme::Dp54 { tol: 1e-10 });
    assert!(
        e10 < d10 && 2 * n8 < n5,
        "dop853 {e10} in {n8}, dp54 {d10} in {n5}"
    );
}

/// Closing in on a stop the error grows from step to step; DOP853's predictive control sees
/// it coming, where Hairer's plain controller had one rejected try per step (20 of 22 on A).
#[test]
fn the_approach_to_a_stop_is_not_a_string_of_rejections() {
    let a = Initial::velocity(0.5, PI, 1.0);
    let s = Settings {
        scheme: Scheme::Dop853 { tol: 1e-10 },
        ..Settings::default()
    };
    let mut run = Run::new(a, s).unwrap();
    assert_eq!(run.finish(10.0).unwrap().0, Outcome::Stuck);
    let c = run.cost();
    assert!(4 * c.rejected <= c.steps, "{c:?}");
    assert!(c.rhs_evals < 400, "{c:?}");
}

fn fate(i: Initial, m: Method) -> (Outcome, f64) {
    let s = Settings {
        scheme: m.with(1e-12),
        ..Settings::default()
    };
    let mut run = Run::new(i, s).unwrap();
    let (o, s) = run.finish(200.0).unwrap();
    (o, s.q().length())
}

#[test]
fn paper_cases_stick_where_dp54_says_at_the_same_place() {
    for (name, i) in [
        ("A", Initial::velocity(0.5, PI, 1.0)),
        ("B", Initial::velocity(0.5, 0.0, 0.6)),
        ("C", Initial::velocity(0.5, 0.0, 0.6078)),
        ("D", Initial::velocity(1.1, 1.2 * PI, 1.3)),
    ] {
        let (o8, x8) = fate(i, Method::Dop853);
        let (o5, x5) = fate(i, Method::Dp54);
        assert_eq!((o8, o5), (Outcome::Stuck, Outcome::Stuck), "{name}");
        assert!((x8 - x5).abs() < 1e-9, "{name}: ξ {x8} vs {x5}");
    }
}

#[test]
fn random_releases_share_dp54s_fate() {
    let mut rng = Rng(17);
    let mut escaped = 0;
    for _ in 0..120 {
        let i = Initial::velocity(1.5 * rng.unit(), TAU * rng.unit(), 2.0 * rng.unit());
        let (o8, x8) = fate(i, Method::Dop853);
        let (o5, x5) = fate(i, Method::Dp54);
        assert_eq!(o8, o5, "{i:?}");
        if o8 == Outcome::Stuck {
            assert!((x8 - x5).abs() < 1e-8, "{i:?}: ξ {x8} vs {x5}");
        } else {
            escaped += 1;
        }
    }
    // Both fates were tried.
    assert!((10..110).contains(&escaped), "{escaped} escaped");
}
