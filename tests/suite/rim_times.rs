//! Stop times (issues 35 and 42): every certified stop time lies within its stated error of an
//! independent reference (the Cartesian Sundman-time form of `common::sundman`, which shares
//! nothing with the engine: neither the runs' Cartesian τ-time steps nor the second opinion's
//! polar rim-distance form), on every method and tolerance, rim included, and the stated error
//! is a bar, not a blanket: within 10× of the actual one in the median. Before the closed-form
//! end games were replaced by implicit steps, a release at ξ0 = 0.9999 stopped at τ = 5.5008
//! "with an error of 0" where the truth is 4.9518; before the second opinion had its own form,
//! 15–35 % of certified stops were further off than stated (issue 42's audit; the old test, at
//! twice the stated error, failed at seeds 7, 8 and 13, and this one, with the Cartesian check
//! as the only second opinion, failed at seed 7 against the reference's RK4 form, before its
//! Kutta–Merson one).

use crate::common;
use common::sundman::{self, Fate};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};
use std::f64::consts::PI;
use std::sync::Mutex;
use turntable::engine::doubt::doubt;
use turntable::engine::method::Scheme;
use turntable::engine::{Initial, Outcome, Run, Settings};

const TAU_MAX: f64 = 200.0;

/// The reference, with its own error measured against itself at a tenth of the tolerance.
fn reference(xi0: f64, phi: f64, v0: f64) -> Option<(Fate, f64)> {
    let a = sundman::fate(xi0, phi, v0, 1e-12, 20_000_000);
    let b = sundman::fate(xi0, phi, v0, 1e-13, 20_000_000);
    match (a, b) {
        (Fate::Stuck { tau: ta, .. }, Fate::Stuck { tau: tb, .. }) => Some((b, (ta - tb).abs())),
        (Fate::Escaped, Fate::Escaped) => Some((b, 0.0)),
        _ => None,
    }
}

/// A run's stop time, its stated error and whether it is certified, against the reference.
struct Case {
    tau: f64,
    stated: f64,
    certain: bool,
    outcome: Outcome,
}

fn case(xi0: f64, phi: f64, v0: f64, s: Settings) -> Case {
    let mut run = Run::new(Initial::velocity(xi0, phi, v0), s).unwrap();
    let outcome = run.run(TAU_MAX, true).unwrap();
    let d = doubt(&run, TAU_MAX);
    Case {
        tau: run.tau(),
        stated: d.tau_error,
        certain: d.certain,
        outcome,
    }
}

/// Checks one release at one setting: `Ok(Some((stated, actual)))` for a certified stop the
/// reference resolves, `Err` says how it failed. A run that is not certain claims nothing: the
/// reference (two runs, most of a case's time) is run only for a certain one.
fn check(xi0: f64, phi: f64, v0: f64, s: Settings) -> Result<Option<(f64, f64)>, String> {
    let c = case(xi0, phi, v0, s);
    if !c.certain {
        return Ok(None);
    }
    let Some((fate, own)) = reference(xi0, phi, v0) else {
        return Ok(None);
    };
    let at = format!(
        "ξ0 {xi0} φ {phi} v0 {v0:e} {}",
        turntable::present::accuracy(&s)
    );
    match fate {
        Fate::Stuck { tau, .. } => {
            if c.outcome != Outcome::Stuck {
                return Err(format!("{at}: certified {:?}, reference sticks", c.outcome));
            }
            let actual = (c.tau - tau).abs();
            // No better than the reference resolves: its own error, and τ's rounding.
            let resolution = 4.0 * own + 4.0 * f64::EPSILON * tau;
            if actual > c.stated + resolution {
                return Err(format!(
                    "{at}: τ {} against {tau}: actual {actual:e}, stated {:e}",
                    c.tau, c.stated
                ));
            }
            Ok((actual > resolution).then_some((c.stated, actual)))
        }
        Fate::Escaped if c.outcome != Outcome::Escaped => Err(format!(
            "{at}: certified {:?}, reference escapes",
            c.outcome
        )),
        _ => Ok(None),
    }
}

/// Every method: dp54 and dop853 at tol 1e-4 … 1e-13, rk4 and rk2 at dt 1e-2 … 1e-4.
fn settings() -> impl Strategy<Value = Settings> {
    let with = |scheme| Settings {
        scheme,
        ..Settings::default()
    };
    prop_oneof![
        (-13.0..-4.0f64).prop_map(move |e| with(Scheme::Dp54 { tol: 10f64.powf(e) })),
        (-13.0..-4.0f64).prop_map(move |e| with(Scheme::Dop853 { tol: 10f64.powf(e) })),
        (-4.0..-2.0f64).prop_map(move |e| with(Scheme::Rk4 { dt: 10f64.powf(e) })),
        (-4.0..-2.0f64).prop_map(move |e| with(Scheme::Rk2 { dt: 10f64.powf(e) })),
    ]
}

fn angle() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(1e-9),
        Just(1e-4),
        Just(PI),
        Just(PI - 1e-4),
        0.0..2.0 * PI,
    ]
}

/// The seeds the property test runs under, each its own random cases.
const SEEDS: [u64; 6] = [7, 8, 13, 23, 42, 1042];
const CASES: u32 = 40;

/// ξ0 ∈ [0.9, 1.01] (and [0.999, 1.001], and mid-table releases from 0.3), v0 a fraction up to
/// 0.999 of |1 − ξ0| near the rim (up to 1.2 mid-table), φ near 0, near π and between, every
/// method and setting: each certified stop within its stated error of the reference, and the
/// stated error within 10× of the actual one in the median.
#[test]
fn certified_stop_times_are_within_their_stated_error() {
    let pairs = Mutex::new(Vec::new());
    let release = prop_oneof![
        (
            prop_oneof![0.9..1.01f64, 0.999..1.001f64],
            prop_oneof![0.0..0.999f64, 0.99..0.999f64]
        )
            .prop_map(|(xi0, frac)| (xi0, frac * (1.0 - xi0).abs())),
        (0.3..0.9f64, 0.05..1.2f64),
    ];
    for seed in SEEDS {
        let mut runner = TestRunner::new(Config {
            rng_seed: RngSeed::Fixed(seed),
            ..common::seeded(CASES)
        });
        let result = runner.run(
            &(release.clone(), angle(), settings()),
            |((xi0, v0), phi, s)| {
                prop_assume!(v0 > 0.0);
                match check(xi0, phi, v0, s) {
                    Ok(Some(p)) => pairs.lock().unwrap().push(p),
                    Ok(None) => {}
                    Err(e) => prop_assert!(false, "seed {}: {}", seed, e),
                }
                Ok(())
            },
        );
        if let Err(e) = result {
            panic!("{e}");
        }
    }
    let mut ratios: Vec<f64> = pairs.lock().unwrap().iter().map(|(s, a)| s / a).collect();
    ratios.sort_by(f64::total_cmp);
    let median = ratios[ratios.len() / 2];
    eprintln!(
        "{} certified stops resolved by the reference over seeds {SEEDS:?}: stated/actual median {median:.2}, least {:.2}, most {:.1}",
        ratios.len(),
        ratios[0],
        ratios[ratios.len() - 1]
    );
    assert!(ratios.len() >= 100, "only {} resolved stops", ratios.len());
    assert!(
        median <= 10.0,
        "the stated error is a blanket: median {median}"
    );
}

/// The cases, and the table the closing note quotes: stated against actual error.
#[test]
fn the_reported_rim_cases_are_right_and_say_so() {
    let rows = [
        (
            0.9999,
            0.0,
            9.999666511839613e-05,
            Settings::default(),
            4.9517692,
        ),
        (0.9999, 0.0, 9.9e-05, Settings::default(), 2.6434131511),
        (0.99, 0.0, 0.0099, dop853(1e-10), 2.400982626),
    ];
    for (xi0, phi, v0, s, truth) in rows {
        let c = case(xi0, phi, v0, s);
        let Some((Fate::Stuck { tau, .. }, own)) = reference(xi0, phi, v0) else {
            panic!("({xi0}, {phi}, {v0:e}): the reference does not stick");
        };
        eprintln!(
            "ξ0 {xi0} φ {phi} v0 {v0:e} {}: τ {:.10} stated {:.1e} actual {:.1e} (reference {tau:.10} ± {own:.0e})",
            turntable::present::accuracy(&s),
            c.tau,
            c.stated,
            (c.tau - tau).abs()
        );
        assert!(
            (tau - truth).abs() < 1e-7,
            "reference {tau} against the issue's {truth}"
        );
        assert!(c.certain && c.outcome == Outcome::Stuck);
        assert!((c.tau - tau).abs() <= c.stated + 4.0 * own + 1e-12);
        assert!(c.stated > 0.0, "a stated error of exactly 0");
    }
}

fn dop853(tol: f64) -> Settings {
    Settings {
        scheme: turntable::engine::method::Scheme::Dop853 { tol },
        ..Settings::default()
    }
}

/// On the saddle itself (ξ0 = 1 thrown straight in at 1e-6) the particle slows to a halt inside
/// at τ ≈ 5e-7, but before it stops û swings outward (Coriolis turns it off the radial line, and
/// near a stop û turns without bound) and it crawls on at a deceleration of 2.5e-13 (1 − ξ, ξ
/// having moved in by s²/4) until τ = 9.444444e-7, as the second opinion's rim-distance form
/// finds at every tolerance from 1e-10 to 1e-14. Cartesian forms cannot follow the crawl (it
/// starts at |u| ~ 1e-19, below their rounding of u; the test's own reference gives no answer):
/// runs stop at 5.0e-7 or near 9.44e-7. Every setting's stated bar contains the crawl's end, so
/// the bars have a point in common. It used to fail with "step size underflow", then to state
/// 4.4e-7 for every setting, the crawl taken as what τ cannot resolve.
#[test]
fn on_the_saddle_the_stop_time_states_what_it_cannot_resolve() {
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for s in [
        Settings::dp54(1e-6),
        Settings::dp54(1e-10),
        Settings::dp54(1e-13),
        dop853(1e-12),
    ] {
        let c = case(1.0, PI, 1e-6, s);
        assert!(c.certain && c.outcome == Outcome::Stuck, "{s:?}");
        assert!((4.9e-7..9.5e-7).contains(&c.tau), "{s:?}: {}", c.tau);
        assert!(
            (c.tau - 9.444444e-7).abs() <= c.stated,
            "{s:?}: {} ±{:e}",
            c.tau,
            c.stated
        );
        (lo, hi) = (lo.max(c.tau - c.stated), hi.min(c.tau + c.stated));
    }
    assert!(lo <= hi, "the stated bars share no point: {lo:e} > {hi:e}");
}

/// A run says what its end game contributed (`Run::end_game`): near the rim rk4 at dt 1e-3
/// reaches the stop in implicit steps and a closed-form stop, bounded by dt²; far from any stop
/// dp54 takes neither.
#[test]
fn a_run_says_what_its_end_game_set() {
    let rk4 = Settings {
        scheme: Scheme::Rk4 { dt: 1e-3 },
        ..Settings::default()
    };
    let mut run = Run::new(Initial::velocity(0.9999, 0.0, 9.9e-5), rk4).unwrap();
    assert_eq!(run.run(TAU_MAX, true).unwrap(), Outcome::Stuck);
    let e = run.end_game();
    assert!(
        e.used() && e.implicit_steps > 0 && e.closed_steps == 1,
        "{e:?}"
    );
    assert!(e.implicit_tau > 1.0 && e.implicit_tau < run.tau(), "{e:?}");
    assert!(e.closed_bound > 0.0 && e.closed_bound <= 1e-6, "{e:?}");
    assert!(e.implicit_error > 0.0 && e.implicit_error < 1e-4, "{e:?}");
    let mut far = Run::new(Initial::velocity(0.5, 0.0, 0.6), Settings::dp54(1e-10)).unwrap();
    far.run(1.0, false).unwrap();
    assert!(!far.end_game().used(), "{:?}", far.end_game());
}
