//! Stability at the extremes (issue 5): never NaN or inf, never a hang, and outcomes that agree
//! across methods wherever each is accurate.

use std::f64::consts::{PI, TAU};
use strum::VariantArray;
use turntable::engine::method::{DT_RANGE, TOL_RANGE};
use turntable::engine::{Initial, Method, Outcome, Release, Run, RunError, Settings, State};

fn finite(s: &State) -> bool {
    [s.tau, s.r.x, s.r.y, s.v.x, s.v.y]
        .iter()
        .all(|x| x.is_finite())
}

fn finish(i: Initial, s: Settings, tau_max: f64) -> (Outcome, State) {
    let (o, st) = Run::new(i, s).unwrap().finish(tau_max).unwrap();
    assert!(finite(&st), "{i:?} {s:?}: {st:?}");
    (o, st)
}

#[test]
fn release_at_the_centre() {
    // At rest at ξ0 = 0: stuck at once.
    let (o, s) = finish(
        Initial::at_rest(0.0, Release::LabRest),
        Settings::default(),
        10.0,
    );
    assert_eq!((o, s.tau, s.xi()), (Outcome::Stuck, 0.0, 0.0));
    // Thrown from the exact centre, or from 1e-9 off it: the same stop to 1e-8.
    let (o0, s0) = finish(Initial::velocity(0.0, 0.0, 1.0), Settings::default(), 10.0);
    let (o1, s1) = finish(Initial::velocity(1e-9, 0.0, 1.0), Settings::default(), 10.0);
    assert_eq!((o0, o1), (Outcome::Stuck, Outcome::Stuck));
    assert!((s0.q().length() - s1.q().length()).abs() < 1e-8);
    assert!(
        s0.theta_dot().is_some() && State::riding(glam::DVec2::ZERO, 1.0).theta_dot().is_none()
    );
}

#[test]
fn release_at_rest_on_either_side_of_xi_1() {
    let (o, s) = finish(
        Initial::at_rest(1.0 - 1e-12, Release::TableRest),
        Settings::default(),
        10.0,
    );
    assert_eq!((o, s.tau), (Outcome::Stuck, 0.0));
    let (o, _) = finish(
        Initial::at_rest(1.0, Release::TableRest),
        Settings::default(),
        10.0,
    );
    assert_eq!(o, Outcome::Stuck);
    let (o, _) = finish(
        Initial::at_rest(1.0 + 1e-12, Release::TableRest),
        Settings::default(),
        10.0,
    );
    assert_eq!(o, Outcome::Escaped);
}

#[test]
fn far_from_the_centre_and_very_fast() {
    for xi0 in [500.0, 1e6, Initial::MAX] {
        let (o, s) = finish(
            Initial::at_rest(xi0, Release::LabRest),
            Settings::default(),
            10.0,
        );
        assert_eq!(o, Outcome::Escaped);
        assert!(s.xi() >= xi0);
    }
    let (o, _) = finish(Initial::velocity(0.5, 0.0, 1e6), Settings::default(), 10.0);
    assert_eq!(o, Outcome::Escaped);
    // Thrown inward at 1e6 it crosses the centre and escapes on the far side.
    let (o, _) = finish(Initial::velocity(0.5, PI, 1e6), Settings::default(), 10.0);
    assert_eq!(o, Outcome::Escaped);
}

/// Friction's push is unit, so |v| ≤ |v0| + τ and ξ ≤ ξ0 + |v0|τ + τ²/2 whatever happens:
/// followed to τ = 1e6 after escape, the run stays inside that bound and agrees across tolerances.
#[test]
fn followed_to_tau_1e6_the_run_stays_physical() {
    let i = Initial::velocity(1.5, 3.0, 0.5);
    let xi = |tol: f64| {
        let mut run = Run::new(i, Settings::dp54(tol)).unwrap();
        assert_eq!(run.run(1e6, false).unwrap(), Outcome::Escaped);
        let s = run.state();
        assert!(finite(&s) && s.tau == 1e6);
        assert!(s.v.length() <= i.state().v.length() + 1e6);
        s.xi()
    };
    let (a, b) = (xi(1e-10), xi(1e-12));
    assert!(a <= 1.5 + 1.6e6 + 0.5e12, "ξ = {a}");
    assert!((a - b).abs() < 1e-9 * b, "{a} vs {b}");
}

#[test]
fn phi_is_periodic_and_may_be_negative() {
    let base = finish(Initial::velocity(0.5, 0.3, 0.6), Settings::default(), 50.0).1;
    for phi in [0.3 + TAU, 0.3 - TAU, 0.3 - 2.0 * TAU] {
        let s = finish(Initial::velocity(0.5, phi, 0.6), Settings::default(), 50.0).1;
        assert!((s.q() - base.q()).length() < 1e-9, "φ = {phi}");
    }
}

#[test]
fn a_stop_inside_the_first_step() {
    for &m in Method::VARIANTS.iter().filter(|m| m.stick_events()) {
        let s = Settings {
            scheme: m.with(if m.adaptive() { m.default_knob() } else { 0.1 }),
            ..Settings::default()
        };
        let (o, st) = finish(Initial::velocity(0.5, 1.0, 1e-6), s, 1.0);
        assert_eq!(o, Outcome::Stuck, "{m}");
        assert!(st.tau < 1e-5 && (st.xi() - 0.5).abs() < 1e-6, "{m}: {st:?}");
    }
}

/// Thrown inward from just outside ξ = 1: slowly, it turns round outside (|u| dips towards 0
/// without reaching it, û swinging onto q̂) and escapes; a little faster, it crosses in and
/// stops just inside, near the saddle. Every accurate method agrees.
#[test]
fn grazing_just_outside_xi_1() {
    let accurate = [
        Settings::dp54(1e-10),
        Settings::dp54(1e-14),
        Settings::fixed(Method::Rk4, 1e-5),
    ];
    for s in accurate {
        let (o, st) = finish(Initial::velocity(1.001, PI, 0.05), s, 100.0);
        assert_eq!(o, Outcome::Escaped, "{s:?}");
        assert!(st.tau > 0.005, "{s:?}: certified at {}", st.tau);
        let (o, st) = finish(Initial::velocity(1.001, PI, 0.08), s, 100.0);
        assert_eq!(o, Outcome::Stuck, "{s:?}");
        assert!(
            (st.xi() - 0.99940390769).abs() < 5e-11,
            "{s:?}: {}",
            st.xi()
        );
    }
}

#[test]
fn tolerances_and_steps_at_their_limits() {
    let b = Initial::velocity(0.5, 0.0, 0.6);
    let exact = finish(b, Settings::dp54(1e-13), 50.0).1.q();
    for tol in [TOL_RANGE.0, 1e-12, 1e-8] {
        let (o, s) = finish(b, Settings::dp54(tol), 50.0);
        assert_eq!(o, Outcome::Stuck, "tol {tol}");
        assert!((s.q() - exact).length() < 1e-5, "tol {tol}");
    }
    // The loosest tolerance and largest step are allowed but inaccurate: finite, and they end.
    for s in [
        Settings::dp54(TOL_RANGE.1),
        Settings::fixed(Method::Rk4, DT_RANGE.1),
        Settings::fixed(Method::Rk2Raw, DT_RANGE.1),
    ] {
        let mut run = Run::new(b, s).unwrap();
        run.run(1e6, true).unwrap();
        assert!(finite(&run.state()));
    }
    // The smallest step with a long horizon runs out of budget with a clear error, not a hang.
    let mut run = Run::new(
        b,
        Settings {
            max_steps: 100_000,
            ..Settings::fixed(Method::Rk2Raw, DT_RANGE.0)
        },
    )
    .unwrap();
    match run.run(1e6, true) {
        Err(e @ RunError::Budget { .. }) => assert!(e.to_string().contains("step budget")),
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_values_are_refused() {
    for i in [
        Initial::velocity(f64::NAN, 0.0, 1.0),
        Initial::velocity(-1.0, 0.0, 1.0),
        Initial::velocity(0.5, f64::INFINITY, 1.0),
        Initial::velocity(0.5, 0.0, -1.0),
        Initial::velocity(1e300, 0.0, 1.0),
        Initial::velocity(0.5, 0.0, 1e300),
    ] {
        assert!(Run::new(i, Settings::default()).is_err(), "{i:?}");
    }
    for s in [
        Settings::dp54(0.0),
        Settings::dp54(f64::NAN),
        Settings::fixed(Method::Rk4, 0.0),
        Settings::fixed(Method::Rk4, 10.0),
    ] {
        assert!(
            Run::new(Initial::velocity(0.5, 0.0, 1.0), s).is_err(),
            "{s:?}"
        );
    }
}

/// Outcomes agree across methods wherever each is accurate: rk4 at dt = 1e-3 and dp54 at 1e-10
/// on 100 seeded releases away from the escape threshold.
#[test]
fn outcomes_agree_across_methods() {
    let mut rng = turntable::rng::SplitMix64(7);
    let mut next = || rng.unit();
    for _ in 0..100 {
        let i = Initial::velocity(1.2 * next(), TAU * next(), 1.5 * next());
        let (a, sa) = finish(i, Settings::dp54(1e-10), 1e3);
        let (b, sb) = finish(i, Settings::fixed(Method::Rk4, 1e-3), 1e3);
        assert_eq!(a, b, "{i:?}");
        if a == Outcome::Stuck {
            assert!((sa.q() - sb.q()).length() < 1e-5, "{i:?}");
        }
    }
}

/// The command line refuses bad input with one line on stderr and exit code 2.
#[test]
fn the_cli_refuses_bad_input_with_exit_code_2() {
    let bin = env!("CARGO_BIN_EXE_turntable");
    for args in [
        &["run", "--xi0", "nan"][..],
        &["run", "--v0", "-1"],
        &["run", "--tol", "0"],
        &["run", "--method", "rk4", "--dt", "1e9"],
        &["run", "--method", "dp54", "--dt", "1e-3"],
        &["run", "--tau-max", "inf"],
        &["escape", "--xi0", "0.5", "--method", "rk2-raw"],
        &["critical", "--xtol", "0"],
        &["sweep", "fig5", "--points", "0"],
    ] {
        let out = std::process::Command::new(bin).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.starts_with("error: ") && err.lines().count() == 1,
            "{args:?}: {err}"
        );
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    // A run that cannot finish within its budget says so and exits 1.
    let out = std::process::Command::new(bin)
        .args([
            "run",
            "--v0",
            "0.6",
            "--method",
            "rk2",
            "--dt",
            "1e-7",
            "--max-steps",
            "1000",
            "--tau-max",
            "10",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("step budget"));
}

#[test]
fn frictionless_at_the_extremes() {
    for xi0 in [0.0, 1e-9, 1.0, 1e6, Initial::MAX] {
        for v0 in [0.0, 1e-9, 1e6, Initial::MAX] {
            for &release in Release::VARIANTS {
                let i = Initial {
                    frictionless: true,
                    ..Initial {
                        release,
                        ..Initial::velocity(xi0, -2.0, v0)
                    }
                };
                let mut run = Run::new(i, Settings::default()).unwrap();
                let o = run.run(1e6, false).unwrap();
                let s = run.state();
                assert!(finite(&s) && s.tau == 1e6, "{i:?}: {s:?}");
                // Only a particle at rest in the lab never leaves; a slow one may take longer.
                let at_rest = i.state().v == glam::DVec2::ZERO;
                assert_eq!(at_rest, i.free_escape().is_none(), "{i:?}");
                let leaves = i.free_escape().is_some_and(|t| t <= 1e6);
                assert_eq!(o == Outcome::Escaped, leaves, "{i:?}");
                if let Some(e) = run.escape() {
                    let at = e.state;
                    assert!(finite(&at) && at.xi() >= 1.0 - 1e-9 * xi0.max(1.0), "{i:?}");
                }
            }
        }
    }
}

/// Speeds whose squares underflow stop at once (issue 11): they used to hover at |u| = 0
/// and report `running` at τ-max, or exhaust the step budget next to ξ = 1.
#[test]
fn underflowing_speeds_stop() {
    let cases = [
        Initial::velocity(0.5, 0.0, 1e-300),
        Initial::velocity(0.5, 2.0, 1e-170),
        Initial::at_rest(1e-300, Release::LabRest),
        Initial::velocity(1.0 - 1e-12, 0.0, 1e-300),
    ];
    for method in [Method::Dp54, Method::Rk4, Method::Rk2] {
        for i in cases {
            let s = Settings {
                scheme: method.with(method.default_knob()),
                ..Settings::default()
            };
            let mut run = Run::new(i, s).unwrap();
            let (o, st) = run.finish(100.0).unwrap();
            assert_eq!(o, Outcome::Stuck, "{method:?} {i:?}");
            assert!(st.tau < 1e-149, "{method:?} {i:?}: stopped at {}", st.tau);
            assert!((st.xi() - i.xi0).abs() < 1e-15, "{i:?}: {}", st.xi());
            assert!(run.cost().steps <= 1, "{i:?}: {:?}", run.cost());
        }
    }
}
