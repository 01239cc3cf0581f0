use super::*;
use crate::Coupling;

fn settings(hold: f64) -> Settings {
    Settings {
        coupling: Coupling::Coulomb { hold },
        ..Settings::dp54(1e-10)
    }
}

/// The slip a run locates is the closed form's, Ω_slip⁴ = (μ_s/(μ_k ξ0))² − a², to 1e-12.
#[test]
fn the_located_slip_is_the_closed_forms() {
    for (rate, omega0, xi0, hold) in [
        (0.1, 0.0, 0.5, 1.0),
        (0.01, 0.3, 0.9, 1.0),
        (1.5, 0.0, 0.5, 1.0),
        (0.2, 0.5, 0.3, 2.0),
        (1e-4, 0.0, 1.0, 1.0),
    ] {
        let ramp = Ramp { rate, omega0 };
        let Onset::At { tau, omega } = ramp.onset(xi0, hold) else {
            panic!("{rate} {xi0}")
        };
        let mut run = SpinRun::new(ramp, xi0, settings(hold)).unwrap();
        let stop = run.step(f64::INFINITY).unwrap();
        assert!(
            matches!(stop, Stop::Stepped | Stop::Escaped),
            "{rate} {xi0} {hold}"
        );
        let slip = run.slip().unwrap();
        assert!(
            (slip.tau - tau).abs() <= 1e-12 * tau.max(1.0),
            "{} {tau}",
            slip.tau
        );
        assert!(
            (slip.omega - omega).abs() <= 1e-12,
            "{} {omega}",
            slip.omega
        );
        assert!(ramp.grip(xi0, slip.tau) > hold);
        // Stepped in strides, the ride locates the same slip.
        let mut strides = SpinRun::new(ramp, xi0, settings(hold)).unwrap();
        let mut t = 0.0;
        while strides.slip().is_none() {
            t += 0.37;
            strides.step(t).unwrap();
        }
        assert!((strides.slip().unwrap().tau - tau).abs() <= 1e-12 * tau.max(1.0));
    }
}

/// A ramp as fast as μ_s g/r0 slips at once; a coin at the centre never does.
#[test]
fn fast_ramps_slip_at_once_and_the_centre_never() {
    let mut run = SpinRun::new(
        Ramp {
            rate: 2.5,
            omega0: 0.0,
        },
        0.5,
        settings(1.0),
    )
    .unwrap();
    run.step(10.0).unwrap();
    assert_eq!(run.phase(), Phase::Sliding);
    assert_eq!(run.slip().unwrap().tau, 0.0);
    let mut run = SpinRun::new(
        Ramp {
            rate: 2.0,
            omega0: 0.0,
        },
        0.0,
        settings(1.0),
    )
    .unwrap();
    run.run(100.0, true).unwrap();
    assert!(run.slip().is_none() && matches!(run.phase(), Phase::Stuck { .. }));
    assert_eq!(run.state_at(50.0).unwrap().r, DVec2::ZERO);
}

/// Once loose the coin slides out and escape is certified (ξΩ² > 1 moving out); up to the slip
/// it rides the table, turned by the ramp's angle.
#[test]
fn a_loose_coin_escapes() {
    let ramp = Ramp {
        rate: 0.1,
        omega0: 0.0,
    };
    let mut run = SpinRun::new(ramp, 0.5, settings(1.0)).unwrap();
    run.run(200.0, true).unwrap();
    let (tau, s) = run.escape().unwrap();
    let slip = run.slip().unwrap();
    assert!(tau > slip.tau, "{tau} {}", slip.tau);
    let z = Z {
        p: s.r,
        w: s.v,
        omega: ramp.omega(tau),
    };
    assert!(
        z.certificate_margin().abs() < 1e-9,
        "{}",
        z.certificate_margin()
    );
    assert_eq!(run.stops(), (0, 0));
    assert!(run.cost().steps < 2000, "{:?}", run.cost());
    let mut again = SpinRun::new(ramp, 0.5, settings(1.0)).unwrap();
    again.step(slip.tau * 0.5).unwrap();
    let s = again.state_at(slip.tau * 0.5).unwrap();
    let angle = ramp.angle(slip.tau * 0.5);
    assert!((s.r - DVec2::from_angle(angle) * 0.5).length() < 1e-15);
}

/// A budget too small, and a state asked for outside the latest step, are errors.
#[test]
fn a_run_is_bounded() {
    let s = Settings {
        max_steps: 5,
        ..settings(1.0)
    };
    let mut run = SpinRun::new(
        Ramp {
            rate: 0.1,
            omega0: 0.0,
        },
        0.5,
        s,
    )
    .unwrap();
    assert!(matches!(
        run.run(200.0, true),
        Err(RunError::Budget { steps: 5, .. })
    ));
    // The ride before the slip is a closed form: answered exactly, at rest on the table.
    let rest = run.state_at(0.0).unwrap();
    assert_eq!((rest.r, rest.v), (DVec2::new(0.5, 0.0), DVec2::ZERO));
    // Past what it has integrated, an error, never a nearby state.
    assert!(run.state_at(run.tau() + 1e-3).is_err());
    let stokes = Settings {
        coupling: Coupling::Stokes { gamma: 1.0 },
        ..settings(1.0)
    };
    assert!(
        SpinRun::new(
            Ramp {
                rate: 0.1,
                omega0: 0.0
            },
            0.5,
            stokes
        )
        .is_err()
    );
}

/// The slide converges: its launch in closed form and its steps at tol 1e-10 put the coin
/// where a run at 1e-13 does, to 1e-7 (the global error goes as the tolerance: 2.9e-6 at
/// 1e-8, 2.0e-8 at 1e-10, 2.2e-11 at 1e-12, for μ_s = μ_k), for μ_s = μ_k and above.
#[test]
fn the_slide_converges() {
    for hold in [1.0, 1.5] {
        let ramp = Ramp {
            rate: 0.1,
            omega0: 0.0,
        };
        let end = |tol: f64| {
            let s = Settings {
                coupling: Coupling::Coulomb { hold },
                ..Settings::dp54(tol)
            };
            let mut run = SpinRun::new(ramp, 0.5, s).unwrap();
            run.run(25.0, false).unwrap();
            assert!(run.slip().unwrap().tau < 20.0);
            run.state_at(25.0).unwrap()
        };
        let (a, b) = (end(1e-10), end(1e-13));
        assert!(a.xi() > 0.6, "{}", a.xi());
        assert!(
            (a.r - b.r).length() < 1e-7,
            "{hold}: {}",
            (a.r - b.r).length()
        );
        assert!(
            (a.v - b.v).length() < 1e-7,
            "{hold}: {}",
            (a.v - b.v).length()
        );
    }
}
