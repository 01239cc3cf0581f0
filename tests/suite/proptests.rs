//! Property tests (proptest) over random releases, methods, frames and tolerances: what must hold
//! of every run, not only of the cases picked by hand. Shrinking reports the simplest release
//! that breaks one. The seed is fixed so that CI is reproducible; more cases or another
//! [`SEED`] search further (six seeds were run when these were written).

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use std::f64::consts::TAU;
use turntable::app::exploration::testing::Testing as _;
use turntable::engine::doubt::doubt;
use turntable::engine::model::rotate;
use turntable::engine::saddle::saddle_h;
use turntable::engine::solve::{
    CLASSIFY_TAU, always, escape_bracket_near, escape_speed, solve_certified,
};
use turntable::engine::{Frame, Initial, Method, Outcome, Run, Settings, State, Status};

const SEED: u64 = 17;

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: RngSeed::Fixed(SEED),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

fn frame() -> impl Strategy<Value = Frame> {
    prop_oneof![Just(Frame::Lab), Just(Frame::Table)]
}

/// Every method with stick events, over its knob's useful range.
fn settings() -> impl Strategy<Value = Settings> {
    let scheme = prop_oneof![
        (-12.0..-5.0f64).prop_map(|e| Settings::dp54(10f64.powf(e))),
        (-4.0..-2.5f64).prop_map(|e| Settings::fixed(Method::Rk4, 10f64.powf(e))),
        (-4.0..-3.0f64).prop_map(|e| Settings::fixed(Method::Rk2, 10f64.powf(e))),
    ];
    (scheme, frame()).prop_map(|(s, frame)| Settings { frame, ..s })
}

/// A release anywhere a user goes: the centre to beyond the rim, any direction, at rest to fast.
fn release() -> impl Strategy<Value = Initial> {
    (0.0..1.6f64, 0.0..TAU, 0.0..2.0f64).prop_map(|(x, p, v)| Initial::velocity(x, p, v))
}

/// Each accepted step's error may raise a monotone quantity by this much: dp54's tolerance
/// with room; for the fixed-step methods dt³, as near a stop their steps are held to the
/// stability limit |u|/ξ and the stiff turn of û costs them their order (rk4 at dt = 3e-3
/// raises H by 3e-10 there).
fn slack(s: &Settings) -> f64 {
    match s.scheme.tol() {
        Some(tol) => 100.0 * tol,
        None => s.scheme.knob().powi(3),
    }
}

proptest! {
    #![proptest_config(config(48))]

    /// dE/dτ = −|u| ≤ 0 and dH/dτ = −|u| + ξ′ ≤ 0 (Sec. II; H = ½(|u|² − (1 − ξ)²)): neither E
    /// nor H rises from one step to the next on a run with stick events, stops and closed-form
    /// stretches included.
    #[test]
    fn energy_and_h_never_rise(i in release(), s in settings()) {
        let mut run = Run::new(i, s).unwrap();
        let mut prev = run.state();
        let eps = slack(&s);
        while run.outcome() == Outcome::Running && run.tau() < 30.0 {
            run.step(30.0).unwrap();
            let now = run.state();
            prop_assert!(now.energy() <= prev.energy() + eps,
                "E rose {:e} at τ {}", now.energy() - prev.energy(), now.tau);
            if prev.xi() < 1.0 && now.xi() < 1.0 {
                prop_assert!(saddle_h(&now) <= saddle_h(&prev) + eps,
                    "H rose {:e} at τ {}", saddle_h(&now) - saddle_h(&prev), now.tau);
            }
            prev = now;
        }
    }

    /// The table turns the same way everywhere and the equations do not depend on τ: a run's
    /// state at τ1, taken as a new release (turned back onto the x axis), ends as the run
    /// does: same outcome, and a rest point turned by the same angle, τ1 later.
    #[test]
    fn turning_a_release_turns_its_end(i in release(), t1 in 0.01..0.5f64, f in frame()) {
        let s = Settings { frame: f, ..Settings::dp54(1e-12) };
        let mut run = Run::new(i, s).unwrap();
        run.run(t1, false).unwrap();
        prop_assume!(run.status() == Status::Slipping && run.escape().is_none());
        let mid: State = run.state_at(t1).unwrap();
        let (q, u) = (mid.q(), mid.u());
        let turn = q.y.atan2(q.x);
        let again = Initial::velocity(q.length(), u.y.atan2(u.x) - turn, u.length());
        let mut rest = Run::new(again, s).unwrap();
        let (o1, e1) = run.finish(200.0).unwrap();
        let (o2, e2) = rest.finish(200.0 - t1).unwrap();
        prop_assert_eq!(o1, o2);
        if o1 == Outcome::Stuck {
            let back = rotate(e2.q(), turn);
            prop_assert!((back - e1.q()).length() < 1e-7, "{:?} vs {:?}", back, e1.q());
            prop_assert!((e2.tau + t1 - e1.tau).abs() < 1e-5 * (1.0 + e1.tau),
                "{} vs {}", e2.tau + t1, e1.tau);
        }
    }
}

/// A whole run with no shortcut, in the table frame at tol 1e-12: the reference the solver's
/// shortcuts (lab frame, slow manifold, secant on H) must agree with.
fn reference(i: Initial) -> Outcome {
    let s = Settings {
        frame: Frame::Table,
        ..Settings::dp54(1e-12)
    };
    let mut run = Run::new(i, s).unwrap();
    run.run(CLASSIFY_TAU, true).unwrap()
}

proptest! {
    #![proptest_config(config(24))]

    /// The escape speed's bracket, once certified: its stuck end sticks and its escaping end
    /// escapes when run in full in the other frame, rim included. (At tol 1e-10 an end can lie
    /// 1e-11 on the wrong side of the threshold: the check catches it and the solver runs
    /// tighter.)
    #[test]
    fn certified_escape_brackets_hold_without_shortcuts(xi0 in 0.0..0.999f64, phi in 0.0..TAU) {
        let at = |v0| Initial::velocity(xi0, phi, v0);
        let (t, certified) =
            solve_certified(Settings::default(), |s| escape_speed(xi0, phi, s, 1e-8), at).unwrap();
        prop_assume!(t.interval);
        prop_assert!(certified, "not certified at ({}, {})", xi0, phi);
        if let Some(lo) = t.stuck_at {
            prop_assert_eq!(reference(at(lo)), Outcome::Stuck);
        }
        prop_assert_ne!(reference(at(t.escapes_at)), Outcome::Stuck);
    }

    /// No certain claim is false: releases 1e-8 to 1e-4 either side of the escape speed, the
    /// rim included, at any method, frame and tolerance. A run that says `certain` ends as the
    /// reference does.
    #[test]
    fn certain_is_never_wrong_near_the_threshold(
        xi0 in 0.0..0.999f64,
        phi in 0.0..TAU,
        e in -8.0..-4.0f64,
        above in any::<bool>(),
        s in settings(),
    ) {
        let ve = escape_speed(xi0, phi, Settings::dp54(1e-12), 1e-10).unwrap();
        prop_assume!(ve.interval && ve.stuck_at.is_some());
        let dv = if above { 10f64.powf(e) } else { -(10f64.powf(e)) };
        let i = Initial::velocity(xi0, phi, (ve.value + dv).max(0.0));
        let mut run = Run::new(i, Settings { max_steps: 2_000_000, ..s }).unwrap();
        prop_assume!(run.run(CLASSIFY_TAU, true).is_ok());
        let d = doubt(&run, CLASSIFY_TAU);
        if d.certain {
            prop_assert_eq!(run.outcome() == Outcome::Stuck, reference(i) == Outcome::Stuck,
                "certain and wrong at v_e {:+e}", dv);
        }
    }
}

proptest! {
    #![proptest_config(config(24))]

    /// The escape-speed page's bracket from a nearby curve's speed (`escape_bracket_near`, no
    /// scan, as a held key computes it) holds v_e, rim included, from a guess up to 0.3 off
    /// either way: its width is at most the curve's, and a tight v_e lies in it (to the 1e-6
    /// its runs at 1e-7 may place the threshold off).
    #[test]
    fn a_bracket_from_a_nearby_speed_holds_v_e(
        xi0 in 0.0..0.999f64,
        phi in 0.0..TAU,
        off in -0.3..0.3f64,
    ) {
        use turntable::analysis::{CURVE_VTOL, curve_settings, settings_for};
        let ve = escape_speed(xi0, phi, Settings::dp54(1e-12), 1e-9).unwrap();
        prop_assume!(ve.interval);
        let s = curve_settings(settings_for(Settings::default()));
        let (lo, hi, _) = escape_bracket_near(xi0, phi, s, CURVE_VTOL, ve.value + off, &always)
            .unwrap();
        prop_assert!(hi - lo <= CURVE_VTOL);
        prop_assert!(lo - 1e-6 <= ve.value && ve.value <= hi + 1e-6,
            "v_e {} outside [{}, {}] from {:+}", ve.value, lo, hi, off);
    }
}

/// The cheap second opinion behind `certain` (dop853 at 0.3× the run's tolerance in the other
/// frame, integrating what the run takes in closed form in explicit steps where they are stable)
/// never certifies a wrong outcome where outcomes are hardest to tell: releases 1e-11 to 1e-6
/// either side of the escape speed, one in two a hair inside the rim (ξ0 in 0.99 … 0.9999), at
/// either adaptive method, frame and tolerance from 1e-12 to 1e-6. The truth is two converged
/// runs that agree (dp54 tol 1e-12 in the table frame, dop853 tol 1e-13 in the lab frame); where
/// they do not the release is too close to call and is skipped. The check is not silent either:
/// at least a third of these runs are certain (46 of 80; 96 of 160 when it ran twice the cases,
/// at ~70 ms a case), and some of the others ended wrong (9): had the second opinion certified
/// them, this fails.
#[test]
fn the_second_opinion_never_certifies_a_wrong_outcome() {
    use proptest::test_runner::TestRunner;
    use std::cell::Cell;
    let adaptive = prop_oneof![
        (-12.0..-6.0f64).prop_map(|e| Settings::dp54(10f64.powf(e))),
        (-12.0..-6.0f64).prop_map(|e| Settings::fixed(Method::Dop853, 10f64.powf(e))),
    ];
    let cases = (
        prop_oneof![0.0..0.95f64, 0.99..0.9999f64],
        0.0..TAU,
        -11.0..-6.0f64,
        any::<bool>(),
        (adaptive, frame()).prop_map(|(s, frame)| Settings { frame, ..s }),
    );
    let (certain, judged, wrong) = (Cell::new(0), Cell::new(0), Cell::new(0));
    TestRunner::new(config(80))
        .run(&cases, |(xi0, phi, e, above, s)| {
            let Ok(ve) = escape_speed(xi0, phi, Settings::dp54(1e-12), 1e-11) else {
                return Ok(());
            };
            prop_assume!(ve.interval && ve.stuck_at.is_some());
            let dv = if above {
                10f64.powf(e)
            } else {
                -(10f64.powf(e))
            };
            let i = Initial::velocity(xi0, phi, (ve.value + dv).max(0.0));
            let tight = Settings {
                scheme: Method::Dop853.with(1e-13),
                ..Settings::default()
            };
            let mut other = Run::new(i, tight).unwrap();
            let truth = reference(i) == Outcome::Stuck;
            prop_assume!((other.run(CLASSIFY_TAU, true).unwrap() == Outcome::Stuck) == truth);
            let mut run = Run::new(
                i,
                Settings {
                    max_steps: 2_000_000,
                    ..s
                },
            )
            .unwrap();
            prop_assume!(run.run(CLASSIFY_TAU, true).is_ok());
            let d = doubt(&run, CLASSIFY_TAU);
            judged.set(judged.get() + 1);
            wrong.set(wrong.get() + usize::from((run.outcome() == Outcome::Stuck) != truth));
            if d.certain {
                certain.set(certain.get() + 1);
                prop_assert_eq!(
                    run.outcome() == Outcome::Stuck,
                    truth,
                    "certain and wrong at v_e {:+e}: {:?}",
                    dv,
                    d
                );
            }
            Ok(())
        })
        .unwrap();
    let (certain, judged, wrong) = (certain.get(), judged.get(), wrong.get());
    eprintln!("{certain} of {judged} certain, {wrong} wrong");
    assert!(
        3 * certain >= judged && wrong > 0,
        "{certain} of {judged} certain, {wrong} wrong"
    );
}

/// The exploration's setters restart the runs: after any sequence of edits, scenes loaded,
/// methods changed, bodies set and comparisons toggled, the run on screen (and the paper's) is
/// that of the initial conditions and settings shown, and those are kept valid. Nothing checks
/// it at run time: the type holds it, since its fields are private.
#[test]
fn the_explorations_runs_always_match_its_initial_conditions() {
    use strum::VariantArray;
    use turntable::app::Exploration;
    use turntable::app::exploration::sanitize;
    use turntable::engine::Release;
    use turntable::engine::body::Body;
    use turntable::scene::{PRESETS, Scene};
    let op = (0u8..10, -3.0f64..3.0, 0usize..64);
    proptest!(config(48), |(ops in prop::collection::vec(op, 1..10))| {
        let mut e = Exploration::new(Scene::preset("B").unwrap());
        for (op, x, k) in ops {
            match op {
                0 => e.edit_initial(|i| i.xi0 += x),
                1 => e.edit_initial(|i| {
                    i.phi += x;
                    i.release = Release::Velocity;
                }),
                2 => e.edit_initial(|i| i.v0 += x),
                3 => e.set_initial(Initial::velocity(x.abs(), x, 0.3 * x.abs())),
                4 => {
                    let m = Method::VARIANTS[k % Method::VARIANTS.len()];
                    e.set_settings(Settings {
                        scheme: m.with(m.default_knob()),
                        ..e.settings()
                    });
                }
                5 => e.load(Scene::preset(PRESETS[k % PRESETS.len()]).unwrap()),
                6 => e.reset(),
                7 => e.compare(x > 0.0),
                8 => e.set_body((x > 0.0).then_some(Body {
                    length: 0.05 + 0.1 * x.abs(),
                    height: None,
                    angle: 0.0,
                })),
                _ => e.edit_initial(|i| i.frictionless = !i.frictionless),
            }
            let (i, s) = (e.initial(), e.settings());
            prop_assert_eq!(i, sanitize(i));
            prop_assert!(s.validate().is_ok());
            prop_assert_eq!(e.sim().initial(), i);
            prop_assert_eq!(e.sim().settings(), s);
            prop_assert_eq!(e.sim().now().tau, 0.0);
            if let Some(p) = e.paper() {
                prop_assert_eq!(p.initial(), i);
                prop_assert_eq!(p.settings(), Settings::paper());
            }
        }
    });
}
