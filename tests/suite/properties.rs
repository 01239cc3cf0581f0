//! Sec. II's general properties 1–4 and the energy identity dE/dτ = −|u|, over seeded random
//! initial conditions.

use std::f64::consts::TAU;
use turntable::engine::model::{Frame, Y, friction};
use turntable::engine::stepper::Dense;
use turntable::engine::{Initial, Method, Outcome, Run, Settings, Status};

use turntable::rng::SplitMix64 as Rng;

fn random_release(rng: &mut Rng) -> Initial {
    Initial::velocity(1.5 * rng.unit(), TAU * rng.unit(), 2.0 * rng.unit())
}

/// (τ, ξ, ξ′, θ′) along a run.
type Sample = (f64, f64, f64, Option<f64>);

/// Samples a run on a fine grid through its dense output.
fn sampled(i: Initial, tau_max: f64) -> Vec<Sample> {
    let mut run = Run::new(i, Settings::dp54(1e-11)).unwrap();
    let mut out = vec![];
    let mut t = 0.0;
    while t <= tau_max {
        while run.status() == Status::Slipping && run.tau() < t {
            run.step(f64::INFINITY).unwrap();
        }
        let s = run.state_at(t).unwrap();
        out.push((t, s.xi(), s.xi_dot(), s.theta_dot()));
        t += 0.01;
    }
    out
}

#[test]
fn property_1_at_rest_inside_xi_1_stays_at_rest() {
    let mut rng = Rng(1);
    for _ in 0..200 {
        let q = glam::DVec2::from_angle(TAU * rng.unit()) * rng.unit();
        // Static friction balances the centrifugal pull: no acceleration in the table frame.
        let a = Frame::Table.rhs(Y {
            p: q,
            w: glam::DVec2::ZERO,
        });
        assert_eq!(a.w, glam::DVec2::ZERO);
        assert_eq!(friction(glam::DVec2::ZERO, q), -q);
        let run = Run::new(
            Initial::at_rest(q.length(), turntable::engine::Release::TableRest),
            Settings::default(),
        )
        .unwrap();
        assert_eq!(run.outcome(), Outcome::Stuck);
        // ... and it rides the table in closed form.
        let s = run.state_at(7.0).unwrap();
        assert!((s.xi() - q.length()).abs() < 1e-15 && (s.u_lab().length()) < 1e-14);
    }
}

#[test]
fn properties_2_and_3_hold_along_random_runs() {
    let mut rng = Rng(2);
    for _ in 0..60 {
        let i = random_release(&mut rng);
        let samples = sampled(i, 8.0);
        let mut outward = false;
        let mut prograde = false;
        for &(t, _, xi_dot, theta_dot) in &samples {
            // 2: once ξ′ > 0 it never turns negative (ξ grows, or stays at a stop).
            if outward {
                assert!(xi_dot > -1e-9, "{i:?}: ξ′ = {xi_dot} at τ = {t}");
            }
            outward |= xi_dot > 1e-9;
            // 3: once θ′ > 0 it stays positive.
            if let Some(td) = theta_dot {
                if prograde {
                    assert!(td > -1e-9, "{i:?}: θ′ = {td} at τ = {t}");
                }
                prograde |= td > 1e-9;
            }
        }
    }
}

#[test]
fn property_4_escaping_runs_end_with_theta_dot_between_0_and_1() {
    let mut rng = Rng(4);
    let mut escaped = 0;
    for _ in 0..40 {
        let i = Initial::velocity(1.5 * rng.unit(), TAU * rng.unit(), 1.0 + 2.0 * rng.unit());
        let mut run = Run::new(i, Settings::dp54(1e-10)).unwrap();
        if run.run(300.0, false).unwrap() != Outcome::Escaped {
            continue;
        }
        escaped += 1;
        let td = run.state().theta_dot().unwrap();
        assert!((0.0..=1.0).contains(&td), "{i:?}: θ′ = {td}");
    }
    assert!(escaped > 20, "only {escaped} escaped");
}

/// E(τ) − E(0) = −∫|u| dτ along every dp54 and dop853 run, the integral by 5-point
/// Gauss–Legendre on each quarter of each step's dense output (dop853's steps are long).
#[test]
fn energy_identity_holds_on_every_adaptive_run() {
    const X: [f64; 5] = [
        -0.906_179_845_938_664,
        -0.538_469_310_105_683,
        0.0,
        0.538_469_310_105_683,
        0.906_179_845_938_664,
    ];
    const W: [f64; 5] = [
        0.236_926_885_056_189,
        0.478_628_670_499_366,
        0.568_888_888_888_889,
        0.478_628_670_499_366,
        0.236_926_885_056_189,
    ];
    let mut rng = Rng(5);
    for (method, tol) in [
        (Method::Dp54, 1e-10),
        (Method::Dp54, 1e-12),
        (Method::Dop853, 1e-12),
    ] {
        for _ in 0..50 {
            let i = random_release(&mut rng);
            let s = Settings {
                scheme: method.with(tol),
                ..Settings::default()
            };
            let mut run = Run::new(i, s).unwrap();
            let e0 = run.state().energy();
            let mut work = 0.0;
            while run.status() == Status::Slipping && run.tau() < 20.0 {
                run.step(20.0).unwrap();
                let seg = run.last().unwrap();
                let f = Frame::Lab;
                let state = |t: f64| f.to_state(seg.at(t), t);
                work += match seg.dense {
                    // A stop taken in closed form: a straight stretch in the table frame.
                    Dense::Hermite { .. } => (state(seg.t1()).q() - state(seg.t0).q()).length(),
                    Dense::Dp5(_) | Dense::Dop853(_) | Dense::Hermite5 { .. } => {
                        let h = 0.25 * seg.h;
                        0.5 * h
                            * (0..20)
                                .map(|j| {
                                    let (q, k) = (j / 5, j % 5);
                                    let t = seg.t0 + h * (q as f64 + 0.5 * (1.0 + X[k]));
                                    W[k] * state(t).u_lab().length()
                                })
                                .sum::<f64>()
                    }
                };
            }
            let e1 = run.state().energy();
            assert!(
                (e1 - e0 + work).abs() < 1e-9,
                "{i:?} {method} tol {tol}: ΔE = {}, −∫|u| = {}",
                e1 - e0,
                -work
            );
        }
    }
}

/// Every fixed-step method shows its order on a smooth stretch: the error at τ = 0.5 of case A
/// (before any stop) falls by ≈ 2^p as the step halves.
#[test]
fn fixed_step_methods_show_their_order() {
    let i = Initial::velocity(0.5, std::f64::consts::PI, 1.0);
    let mut exact = Run::new(i, Settings::dp54(1e-14)).unwrap();
    exact.run(0.5, false).unwrap();
    let r = exact.state().r;
    for (m, p) in [
        (Method::Rk2Raw, 2.0),
        (Method::Rk2, 2.0),
        (Method::Rk4, 4.0),
    ] {
        let err = |dt: f64| {
            let mut run = Run::new(i, Settings::fixed(m, dt)).unwrap();
            run.run(0.5, false).unwrap();
            (run.state().r - r).length()
        };
        for dt in [1e-2, 5e-3] {
            let ratio = err(dt) / err(dt / 2.0);
            assert!(
                (ratio / 2f64.powf(p) - 1.0).abs() < 0.1,
                "{m}: ratio {ratio} at dt {dt}"
            );
        }
    }
}

#[test]
fn outcomes_agree_across_frames() {
    let mut rng = Rng(6);
    for _ in 0..40 {
        let i = random_release(&mut rng);
        let lab = Run::new(i, Settings::dp54(1e-11))
            .unwrap()
            .finish(200.0)
            .unwrap();
        let table = Run::new(
            i,
            Settings {
                frame: Frame::Table,
                ..Settings::dp54(1e-11)
            },
        )
        .unwrap()
        .finish(200.0)
        .unwrap();
        assert_eq!(lab.0, table.0, "{i:?}");
        if lab.0 == Outcome::Stuck {
            assert!((lab.1.q() - table.1.q()).length() < 1e-7, "{i:?}");
        }
    }
}

#[test]
fn a_state_outside_the_dense_output_is_an_error() {
    let mut run = Run::new(Initial::velocity(0.5, 0.4, 0.3), Settings::default()).unwrap();
    for _ in 0..5 {
        run.step(f64::INFINITY).unwrap();
    }
    let seg = run.last().unwrap();
    let mid = 0.5 * (seg.t0 + seg.t1());
    assert!(run.state_at(mid).is_ok() && run.state_at(run.tau()).is_ok());
    for tau in [0.5 * seg.t0, seg.t1() + 1e-3, 1e3] {
        let e = run.state_at(tau).unwrap_err().to_string();
        assert!(
            e.contains(&format!("no state at tau = {tau}")) && e.contains("only from"),
            "{e}"
        );
    }
    // Once stuck the particle rides the table: every later τ has a state.
    run.run(100.0, false).unwrap();
    assert_eq!(run.outcome(), Outcome::Stuck);
    assert!(run.state_at(1e6).is_ok());
}

/// `Run::step` says where each step left the run: `Escaped` once, when the certificate first
/// holds (then `Stepped` while it is followed), `Stuck` from the stop on, `End` at τ-max; and
/// `goes_on` is the one loop condition.
#[test]
fn each_step_says_where_it_left_the_run() {
    use turntable::engine::Stop;
    let mut run = Run::new(Initial::velocity(0.5, 0.4, 1.5), Settings::default()).unwrap();
    let mut seen = vec![];
    while run.goes_on(50.0, false) {
        let why = run.step(50.0).unwrap();
        if seen.last() != Some(&why) {
            seen.push(why);
        }
    }
    assert_eq!(
        seen,
        [Stop::Stepped, Stop::Escaped, Stop::Stepped, Stop::End]
    );
    assert!(!run.goes_on(50.0, false) && run.goes_on(60.0, false) && !run.goes_on(60.0, true));
    let mut run = Run::new(Initial::velocity(0.5, 0.0, 0.3), Settings::default()).unwrap();
    let mut last = Stop::Stepped;
    while run.goes_on(50.0, true) {
        last = run.step(50.0).unwrap();
    }
    assert_eq!(last, Stop::Stuck);
    assert_eq!(run.step(50.0).unwrap(), Stop::Stuck);
}
