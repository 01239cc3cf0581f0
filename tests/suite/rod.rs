//! The appendix's body integrated (issue 23 item 3): as L → 0 it is the point; its energy
//! never rises.

use crate::common;
use turntable::engine::body::Body;
use turntable::engine::rod::{Phase, RodRun};
use turntable::engine::{Initial, Outcome, Release, Run, Settings};

fn body(length: f64, angle: f64) -> Body {
    Body {
        length,
        height: None,
        angle,
    }
}

/// The point's end: outcome and rest radius.
fn point(initial: Initial) -> (Outcome, f64) {
    let mut run = Run::new(initial, Settings::dp54(1e-12)).unwrap();
    let (o, s) = run.finish(100.0).unwrap();
    (o, s.q().length())
}

fn rod(initial: Initial, l: f64, angle: f64) -> (Outcome, RodRun) {
    let mut run = RodRun::new(body(l, angle), 1.0, &initial, 1e-12).unwrap();
    let end = run.finish(100.0, |_| {}).unwrap();
    (end, run)
}

#[test]
fn a_tiny_body_rests_where_the_point_does() {
    for (name, initial) in [
        ("A", Initial::velocity(0.5, std::f64::consts::PI, 1.0)),
        ("B", Initial::velocity(0.5, 0.0, 0.6)),
        ("D", Initial::velocity(1.1, 1.2 * std::f64::consts::PI, 1.3)),
        ("lab-rest 0.5", Initial::at_rest(0.5, Release::LabRest)),
    ] {
        let (o, xi) = point(initial);
        assert_eq!(o, Outcome::Stuck, "{name}");
        for angle in [0.0, 1.0, 2.5] {
            let (end, run) = rod(initial, 1e-6, angle);
            assert_eq!(end, Outcome::Stuck, "{name} {angle}");
            let got = run.state.q.length();
            eprintln!(
                "{name} psi0 {angle}: point {xi} body {got} diff {:e} steps {}",
                got - xi,
                run.steps()
            );
            assert!((got - xi).abs() < 1e-5, "{name} {angle}: {got} vs {xi}");
        }
    }
}

#[test]
fn a_tiny_body_escapes_where_the_point_does() {
    let initial = Initial::velocity(0.5, 0.0, 1.0);
    assert_eq!(point(initial).0, Outcome::Escaped);
    let (end, run) = rod(initial, 1e-6, 0.7);
    eprintln!(
        "escape at tau {} xi {}",
        run.state.tau,
        run.state.q.length()
    );
    assert_eq!(end, Outcome::Escaped);
}

#[test]
fn energy_never_rises() {
    for (l, initial) in [
        (0.05, Initial::velocity(0.5, std::f64::consts::PI, 1.0)),
        (0.2, Initial::at_rest(0.6, Release::LabRest)),
        (0.3, Initial::velocity(0.4, 2.0, 0.8)),
    ] {
        let mut run = RodRun::new(body(l, 0.3), 1.0, &initial, 1e-11).unwrap();
        let mut last = f64::INFINITY;
        let mut worst: f64 = 0.0;
        let end = run
            .finish(100.0, |s| {
                let e = s.energy(l);
                worst = worst.max(e - last);
                last = e;
            })
            .unwrap();
        eprintln!(
            "L {l}: {end:?} xi {} worst rise {worst:e} phase {:?} steps {}",
            run.state.q.length(),
            run.phase,
            run.steps()
        );
        assert!(worst <= 1e-9, "L {l}: energy rose by {worst:e}");
        assert_ne!(run.phase, Phase::Slip);
    }
}

/// The property test's two counterexamples (throws, μ_s = μ_k): a contact stopping with a
/// residual slip u_k below the floor had u_k dropped from the centre's velocity at fixed ψ′,
/// which raised the energy by ½|u_k|² − u·u_k, 1.6e-8 and 1.3e-8 here. The stop is now a
/// plastic impulse at that contact, which never adds energy.
#[test]
fn a_contacts_stop_takes_out_its_slip_without_adding_energy() {
    for (l, angle, xi0, phi, v0) in [
        (
            0.39831302616876335,
            1.5936601444069711,
            0.356507602888581,
            3.328427365917105,
            0.34545127288935756,
        ),
        (
            0.5098494369729082,
            2.169126636414347,
            0.9776794089108267,
            4.076146823614127,
            1.21049169046518,
        ),
    ] {
        let initial = Initial::velocity(xi0, phi, v0);
        let mut run = RodRun::new(body(l, angle), 1.0, &initial, 1e-10).unwrap();
        let mut last = f64::INFINITY;
        let mut worst: f64 = f64::NEG_INFINITY;
        let mut pivoted = false;
        let end = run
            .finish(20.0, |s| {
                let e = s.energy(l);
                worst = worst.max(e - last);
                last = e;
            })
            .unwrap();
        // Both cases pivot about a stopped contact before they rest, the path that rose.
        let mut again = RodRun::new(body(l, angle), 1.0, &initial, 1e-10).unwrap();
        while again.step(20.0).unwrap() == Outcome::Running {
            pivoted |= matches!(again.phase, Phase::Pivot { .. });
        }
        eprintln!("L {l}: {end:?} worst rise {worst:e}");
        assert_eq!(end, Outcome::Stuck);
        assert!(pivoted, "L {l}: no pivot");
        assert!(worst <= 100.0 * 1e-10, "L {l}: energy rose by {worst:e}");
    }
}

/// Cases the property test found (released at rest in the lab, μ_s/μ_k just above 1): a pivot's
/// stuck contact breaks loose at |need| = ½μ_s/μ_k > ½, where its slip grows only as λτ with
/// λ ~ 0.005, and every explicit step from zero slip turned it back (each stage's direction
/// error grows ~1/λ): 5 000 000 steps at slips of ~1e-10, the step budget, without reaching
/// τ = 0.66. Now each rests in under 1000 steps at tol 1e-10, where a run at 1e-13 does to
/// 1e-10 in ξ and ψ.
#[test]
fn a_contact_breaking_loose_above_kinetic_friction_does_not_stall() {
    for (l, angle, xi0, hold) in [
        (
            0.2898121123953464,
            0.22821047287117915,
            0.5530275670084983,
            1.0096843989099453,
        ),
        (
            0.5493706551599195,
            3.161549900630259,
            0.6097309546362448,
            1.0116492750557295,
        ),
        (
            0.5769103278856975,
            3.1159612859173382,
            0.5763229277807487,
            1.0213877229296202,
        ),
        (
            0.3378333179094115,
            3.5428028916869163,
            0.5352340128368036,
            1.0240279060037802,
        ),
    ] {
        let initial = Initial::at_rest(xi0, Release::LabRest);
        let end = |tol: f64| {
            let mut run = RodRun::new(body(l, angle), hold, &initial, tol).unwrap();
            let o = run.finish(100.0, |_| {}).unwrap();
            (o, run.state, run.steps())
        };
        let (o, s, steps) = end(1e-10);
        let (o_ref, r, _) = end(1e-13);
        eprintln!(
            "L {l}: {o:?} ξ {} ψ {} in {steps} steps",
            s.q.length(),
            s.psi
        );
        assert_eq!((o, o_ref), (Outcome::Stuck, Outcome::Stuck));
        assert!(steps < 1000, "L {l}: {steps} steps");
        assert!(
            (s.q - r.q).length() < 1e-10,
            "L {l}: {:e}",
            (s.q - r.q).length()
        );
        assert!((s.psi - r.psi).abs() < 1e-10, "L {l}: {:e}", s.psi - r.psi);
    }
}

/// At a loose tolerance both contacts of a short body, slowing together, crept at a slip of
/// 1.03e-5 just above the stop floor (1.00e-5 at tol 1e-6), DOPRI5's stages flipping the
/// friction within every accepted step: 700 000 steps to τ = 20 and never at rest. The floor
/// is now at least 100 tol: it rests in 81 steps (99 on the body's own stepper before issue
/// 30), within 2e-7 of the converged rest point.
#[test]
fn a_loose_tolerance_does_not_creep() {
    let initial = Initial::at_rest(0.8570948530415503, Release::LabRest);
    let b = body(0.023876767819223953, 0.10050434106907823);
    let end = |tol: f64| {
        let mut run = RodRun::new(b, 1.0698435025146684, &initial, tol).unwrap();
        let o = run.finish(100.0, |_| {}).unwrap();
        (o, run.state, run.steps())
    };
    let (o, s, steps) = end(1e-6);
    let (_, r, _) = end(1e-12);
    eprintln!(
        "{o:?} ξ {} (converged {}) in {steps} steps",
        s.q.length(),
        r.q.length()
    );
    assert_eq!(o, Outcome::Stuck);
    assert!(steps < 200, "{steps} steps");
    assert!((s.q - r.q).length() < 1e-6, "{:e}", (s.q - r.q).length());
}

/// Both contacts stuck, the rod's axial force can share the load exactly when the centre
/// could hold as a point, |q| ≤ μ_s/μ_k, whatever the length and angle.
#[test]
fn a_body_at_rest_on_the_table_rides_iff_its_centre_could() {
    for (xi0, hold, rides) in [(0.9, 1.0, true), (1.1, 1.0, false), (1.2, 1.5, true)] {
        for (l, angle) in [(0.5, 0.0), (0.5, 1.3), (1.5, 2.0)] {
            let mut run = RodRun::new(
                body(l, angle),
                hold,
                &Initial::at_rest(xi0, Release::TableRest),
                1e-10,
            )
            .unwrap();
            let end = run.finish(5.0, |_| {}).unwrap();
            assert_eq!(
                end == Outcome::Stuck && run.state.tau == 0.0,
                rides,
                "{xi0} {hold} {l}"
            );
        }
    }
}

mod prop {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        // A fixed seed, as in proptests.rs: CI sees the same 256 cases every run. (Unseeded,
        // it once found rises of 1.3e-8 to 1.6e-8 at a contact's stop, now fixed: see
        // `a_contacts_stop_takes_out_its_slip_without_adding_energy`; and one run in forty
        // exhausted the step budget, a contact breaking loose above kinetic friction: see
        // `a_contact_breaking_loose_above_kinetic_friction_does_not_stall`.)
        #![proptest_config(ProptestConfig {
            cases: 256,
            failure_persistence: None,
            rng_seed: proptest::test_runner::RngSeed::Fixed(17),
            ..ProptestConfig::default()
        })]
        /// The hidden-state invariant: the body's Jacobi energy never rises, step by step,
        /// whatever it does (slides, pivots, rides), beyond the integrator's own error (the
        /// point's slack in `proptests.rs`: 100 tol a step).
        #[test]
        fn the_bodys_energy_never_rises(
            l in 1e-4f64..0.6,
            angle in 0.0f64..6.3,
            xi0 in 0.0f64..1.5,
            phi in 0.0f64..6.3,
            v0 in 0.0f64..1.5,
            release in 0usize..3,
            hold in 1.0f64..1.5,
            tol_exp in -12i32..-4,
        ) {
            let tol = 10f64.powi(tol_exp);
            let initial = match release {
                0 => Initial::velocity(xi0, phi, v0),
                1 => Initial::at_rest(xi0, Release::TableRest),
                _ => Initial::at_rest(xi0, Release::LabRest),
            };
            let mut run = RodRun::new(body(l, angle), hold, &initial, tol).unwrap();
            let mut last = f64::INFINITY;
            let mut worst: f64 = f64::NEG_INFINITY;
            run.finish(20.0, |s| {
                let e = s.energy(l);
                worst = worst.max(e - last);
                last = e;
            })
            .unwrap();
            prop_assert!(worst <= 100.0 * tol, "energy rose by {worst:e}");
            // Work is bounded: 100 000 random cases from tol 1e-14 to 1e-4 took at most 3662
            // steps to τ = 20 (it was 5 000 000, the budget, for one in 14 000 before).
            prop_assert!(run.steps() <= 20_000, "{} steps", run.steps());
        }
    }
}

/// The explorer's track: the body at any τ, at rest for ever once stuck, nothing past an
/// escape's end.
#[test]
fn the_track_gives_the_body_at_any_tau() {
    let a = Initial::velocity(0.5, std::f64::consts::PI, 1.0);
    let t = common::rod_track(body(0.1, 0.4), 1.0, &a, 1e-10, 50.0);
    assert_eq!(t.outcome, Outcome::Stuck);
    for s in &t.states {
        let got = t.at(s.tau).unwrap();
        assert!((got.q - s.q).length() < 1e-15 && (got.psi - s.psi).abs() < 1e-15);
    }
    let rest = *t.states.last().unwrap();
    let later = t.at(rest.tau + 10.0).unwrap();
    assert_eq!((later.q, later.psi), (rest.q, rest.psi));
    // Between two step ends: on the chord.
    let (p, n) = (t.states[3], t.states[4]);
    let mid = t.at(0.5 * (p.tau + n.tau)).unwrap();
    assert!((mid.q - (p.q + n.q) * 0.5).length() < 1e-12);
    let e = common::rod_track(
        body(0.1, 0.4),
        1.0,
        &Initial::velocity(0.5, 0.0, 1.0),
        1e-10,
        50.0,
    );
    assert_eq!(e.outcome, Outcome::Escaped);
    assert!(e.at(e.states.last().unwrap().tau + 1.0).is_none());
}

/// A finite body's rest point converges with the tolerance through its pivots and stops: at
/// tol 1e-10 within 1e-8 of tol 1e-12 (case A and a release at rest in the lab, L up to 0.3).
/// Its stop time is known less well, to about 10⁻²√tol over the deceleration (the snap floor).
#[test]
fn a_finite_bodys_rest_converges_with_the_tolerance() {
    for (initial, angle) in [
        (Initial::velocity(0.5, std::f64::consts::PI, 1.0), 0.0),
        (Initial::at_rest(0.8, Release::LabRest), 1.0),
    ] {
        for l in [0.1, 0.3] {
            let end = |tol: f64| {
                let mut run = RodRun::new(body(l, angle), 1.0, &initial, tol).unwrap();
                assert_eq!(run.finish(100.0, |_| {}).unwrap(), Outcome::Stuck);
                run.state
            };
            let (a, b) = (end(1e-10), end(1e-12));
            assert!(
                (a.q - b.q).length() < 1e-8,
                "L {l}: {:e}",
                (a.q - b.q).length()
            );
            assert!((a.psi - b.psi).abs() < 1e-7, "L {l}: ψ {:e}", a.psi - b.psi);
            assert!((a.tau - b.tau).abs() < 1e-5, "L {l}: τ {:e}", a.tau - b.tau);
        }
    }
}

/// The explorer's track is bounded whatever the release: a step budget (checked between
/// steps, so a last step's own rejections may pass it by a few) and a cap on the states kept,
/// which thins them (keeping the phase changes and the end). Cut short, it keeps what it
/// computed and says where and why; nothing past its end is made up.
#[test]
fn a_tracks_steps_and_states_are_bounded() {
    use turntable::engine::rod::{Cut, RodTrack, TRACK_STATES, TRACK_STEPS};
    let b = Initial::velocity(0.5, 0.0, 0.6);
    let full =
        common::rod_track_within(body(0.1, 0.4), 1.0, &b, 1e-12, 200.0, u64::MAX, usize::MAX);
    assert_eq!((full.outcome, full.cut.clone()), (Outcome::Stuck, None));
    assert!(full.states.len() > 400, "{}", full.states.len());
    assert_eq!(full.states.len(), full.phases.len());
    // The explorer's bounds leave this run whole.
    let whole = common::rod_track(body(0.1, 0.4), 1.0, &b, 1e-12, 200.0);
    assert_eq!(whole.states, full.states);
    assert!(whole.steps < TRACK_STEPS && whole.states.len() <= TRACK_STATES);
    // At most 64 states: thinned, the same end, phase changes where the run had them.
    let thin = common::rod_track_within(body(0.1, 0.4), 1.0, &b, 1e-12, 200.0, u64::MAX, 64);
    assert!(
        thin.states.len() <= 64 && thin.states.len() >= 16,
        "{}",
        thin.states.len()
    );
    assert_eq!(thin.states.len(), thin.phases.len());
    assert_eq!(thin.outcome, Outcome::Stuck);
    assert_eq!(thin.states.last(), full.states.last());
    assert_eq!(thin.states[0], full.states[0]);
    assert!(thin.states.windows(2).all(|w| w[0].tau <= w[1].tau));
    let changes = |t: &RodTrack| {
        t.phases
            .windows(2)
            .zip(&t.states[1..])
            .filter(|(p, _)| p[0] != p[1])
            .map(|(p, s)| (s.tau, p[1]))
            .collect::<Vec<_>>()
    };
    assert_eq!(changes(&thin), changes(&full));
    assert_eq!(phase_at(&thin, full.end_tau() + 1.0), Some(Phase::Rest));
    // A budget of 40 steps: cut, what was computed kept, nothing past it.
    let cut = common::rod_track_within(body(0.1, 0.4), 1.0, &b, 1e-12, 200.0, 40, usize::MAX);
    assert_eq!(cut.cut, Some(Cut::Budget(40)));
    assert_eq!(cut.outcome, Outcome::Running);
    assert!(cut.steps >= 40 && cut.steps < 60, "{}", cut.steps);
    let end = cut.end_tau();
    assert!(end > 0.0 && end < full.end_tau());
    assert_eq!(cut.states[..], full.states[..cut.states.len()]);
    assert!(cut.at(end).is_some() && cut.at(end + 1e-9).is_none());
    assert!(cut.at(f64::NAN).is_none());
    for s in &cut.states {
        assert!(s.q.is_finite() && s.u.is_finite() && s.psi.is_finite() && s.w.is_finite());
    }
}

/// Each state carries its phase: a body thrown as case A slides, pivots about a contact on
/// the way, and ends riding the table.
#[test]
fn a_track_knows_the_phase_at_any_tau() {
    let a = Initial::velocity(0.5, std::f64::consts::PI, 1.0);
    let t = common::rod_track(body(0.2, 0.0), 1.0, &a, 1e-10, 200.0);
    assert_eq!(phase_at(&t, 0.0), Some(Phase::Slip));
    assert_eq!(phase_at(&t, t.end_tau()), Some(Phase::Rest));
    assert_eq!(phase_at(&t, t.end_tau() + 50.0), Some(Phase::Rest));
    let pivots = t
        .phases
        .iter()
        .filter(|p| matches!(p, Phase::Pivot { .. }))
        .count();
    let tau_pivot = t
        .states
        .iter()
        .zip(&t.phases)
        .find(|(_, p)| matches!(p, Phase::Pivot { .. }))
        .map(|(s, _)| s.tau);
    assert!(pivots > 0, "{:?}", t.phases);
    let tp = tau_pivot.unwrap();
    assert!(matches!(phase_at(&t, tp), Some(Phase::Pivot { .. })));
    assert_eq!(phase_at(&t, 0.5 * tp), Some(Phase::Slip));
}

/// Followed past its certificate (the explorer's track), an escaping body is stepped on out to
/// the radius asked for, within the same budgets; the escape's τ is still the certificate's,
/// where `RodRun::finish` (and `run`'s `body.motion`) stops, and up to it the track is the
/// unfollowed one. Fig. 2's release (at rest on the table at ξ0 = 1.1, E < −½ at once) and a
/// body thrown out as fast as case A (certified at τ ≈ 0.5).
#[test]
fn an_escaping_body_is_followed_out_past_its_certificate() {
    use turntable::engine::rod::{RodTrack, TRACK_STATES, TRACK_STEPS};
    for (initial, radius) in [
        (Initial::at_rest(1.1, Release::TableRest), 4.5),
        (Initial::velocity(0.5, 0.0, 1.0), 4.5),
    ] {
        let b = body(0.1, 0.0);
        let mut plain = RodRun::new(b, 1.0, &initial, 1e-10).unwrap();
        assert_eq!(plain.finish(200.0, |_| {}).unwrap(), Outcome::Escaped);
        // The certificate is located inside the step that first finds it; the run stops at
        // that step's end.
        let (cert, end) = (plain.certificate().unwrap(), plain.state.tau);
        assert!(cert <= end, "{cert} {end}");
        let ends = common::rod_track(b, 1.0, &initial, 1e-10, 200.0);
        assert_eq!((ends.outcome, ends.escape), (Outcome::Escaped, Some(cert)));
        assert_eq!(ends.end_tau(), end);
        assert!(ends.left().is_none());
        let run = RodRun::new(b, 1.0, &initial, 1e-10)
            .unwrap()
            .following(radius);
        let t = RodTrack::from_run(run, 200.0, TRACK_STEPS, TRACK_STATES);
        assert_eq!(
            (t.outcome, t.escape, t.cut.clone()),
            (Outcome::Escaped, Some(cert), None)
        );
        let last = *t.states.last().unwrap();
        assert!(last.q.length() >= radius, "{}", last.q.length());
        // Only the last step crosses the radius.
        let before = t.states[t.states.len() - 2].q.length();
        assert!(before < radius, "{before}");
        assert!(t.end_tau() > cert + 1.0, "{} vs {cert}", t.end_tau());
        assert_eq!(t.left(), Some(last));
        assert!(t.at(cert + 1.0).is_some() && t.at(t.end_tau() + 1.0).is_none());
        assert_eq!(t.states[..ends.states.len()], ends.states[..]);
        assert!(
            t.steps < 1000 && t.states.len() < 1000,
            "{} {}",
            t.steps,
            t.states.len()
        );
        // Its energy still never rises past the certificate.
        let e: Vec<f64> = t.states.iter().map(|s| s.energy(0.1)).collect();
        assert!(e.windows(2).all(|w| w[1] <= w[0] + 1e-8), "{e:?}");
    }
}

/// A followed track is bounded as any: a budget that runs out past the certificate cuts the
/// drawing, not the escape (here 50 steps of the 298 that fig2's body takes to leave).
#[test]
fn a_followed_track_cut_past_its_certificate_still_escapes() {
    use turntable::engine::rod::{Cut, RodTrack};
    let fig2 = Initial::at_rest(1.1, Release::TableRest);
    let run = RodRun::new(body(0.1, 0.4), 1.0, &fig2, 1e-10)
        .unwrap()
        .following(4.5);
    let t = RodTrack::from_run(run, 200.0, 50, 500);
    assert_eq!(t.cut, Some(Cut::Budget(50)));
    assert_eq!((t.outcome, t.escape), (Outcome::Escaped, Some(0.0)));
    assert!(t.left().is_none() && t.states.len() <= 500);
    assert!(t.end_tau() > 0.0 && t.end_tau() < 5.9, "{}", t.end_tau());
}

/// Both contacts breaking loose from rest (released at rest on the table outside R, or both
/// stopped there) slip along q̂, the one consistent start (`RodRun::both_loose`): the body
/// then slides out as the point does, without turning. Each contact along its own radius
/// turned both slips back step after step when the rod lay across the radius: fig2's body at
/// ψ0 = 0.4 spent 200 000 steps within τ = 2e-5. Now, for any ψ0 and L, it is followed out to
/// the view radius in the same steps as with the rod along the radius (298; 406 since issue 35).
#[test]
fn a_body_at_rest_outside_r_slides_out_without_turning() {
    use turntable::engine::rod::RodTrack;
    let fig2 = Initial::at_rest(1.1, Release::TableRest);
    for psi in [0.0, 0.4, 1.0, std::f64::consts::FRAC_PI_2, 2.5] {
        for l in [0.01, 0.1, 0.5] {
            let run = RodRun::new(body(l, psi), 1.0, &fig2, 1e-10)
                .unwrap()
                .following(4.5);
            let t = RodTrack::from_run(run, 200.0, 200_000, 20_000);
            assert!(
                t.cut.is_none() && t.outcome == Outcome::Escaped,
                "ψ0 {psi} L {l}"
            );
            // 406 since the stretch after the launch takes implicit steps (issue 35).
            assert!(t.steps < 500, "ψ0 {psi} L {l}: {} steps", t.steps);
            let left = t.left().unwrap();
            assert!(left.q.length() >= 4.5, "ψ0 {psi} L {l}");
            for s in &t.states {
                assert_eq!((s.psi, s.w), (psi, 0.0), "ψ0 {psi} L {l} at τ {}", s.tau);
            }
        }
    }
}

/// Sliding without turning, the body is the point released at rest on the table where its
/// centre is, and is carried by the point's run (which launches from rest in closed form): at
/// ξ0 = 1.001 its own steps took 50 000 to τ = 1.2; now it leaves the view radius at τ = 10.65
/// in 810, where the point's own run puts it.
#[test]
fn a_body_loose_from_rest_just_outside_r_leaves_as_the_point_does() {
    use turntable::engine::rod::RodTrack;
    let at_rest = Initial::at_rest(1.001, Release::TableRest);
    let run = RodRun::new(body(0.1, 1.0), 1.0, &at_rest, 1e-10)
        .unwrap()
        .following(4.5);
    let t = RodTrack::from_run(run, 200.0, 50_000, 20_000);
    let left = t.left().expect("followed out");
    eprintln!(
        "{} steps, left at τ {} ξ {}",
        t.steps,
        left.tau,
        left.q.length()
    );
    assert!(t.cut.is_none() && t.steps < 3000, "{} steps", t.steps);
    assert!(left.q.length() >= 4.5 && (left.psi, left.w) == (1.0, 0.0));
    // Stepped as the body's carrier is, towards τ 200 (a run to τ-max `left.tau` would
    // take its way there in equal steps, not these).
    let mut point = Run::new(at_rest, Settings::dp54(1e-10)).unwrap();
    while point.tau() < left.tau {
        point.step(200.0).unwrap();
    }
    let p = point.state();
    assert!((p.tau - left.tau).abs() < 1e-12, "{} {}", p.tau, left.tau);
    assert!(
        (p.q() - left.q).length() < 1e-12,
        "{:?} {:?}",
        p.q(),
        left.q
    );
}

/// The phase of `t` at `tau`.
fn phase_at(t: &turntable::engine::rod::RodTrack, tau: f64) -> Option<Phase> {
    t.at_with_phase(tau).map(|(_, p)| p)
}

/// The body's escape certificate, E < −½, is located inside the step as the point's run locates
/// its own: as L → 0 its τ tends to the τ at which the point's E crosses −½ (issue 35: it was
/// the end of a step, 1e-2 late whatever L). Case C thrown harder, and a throw at another angle.
/// (A body loose from rest outside R has E < −½R² at once: nothing to locate.)
#[test]
fn a_small_bodys_escape_time_tends_to_the_points() {
    for initial in [
        Initial::velocity(0.5, 0.0, 1.0),
        Initial::velocity(0.8, 2.0, 1.5),
    ] {
        // The point's crossing of E = −½, on its dense output.
        let mut run = Run::new(initial, Settings::dp54(1e-12)).unwrap();
        let crossing = loop {
            let before = run.state();
            run.step(100.0).unwrap();
            let after = run.state();
            assert!(after.tau < 100.0, "{initial:?}: E never below −½");
            if before.energy() >= -0.5 && after.energy() < -0.5 {
                let g = |t: f64| -0.5 - run.state_at(t).unwrap().energy();
                break turntable::engine::roots::illinois(g, before.tau, after.tau, 1e-14);
            }
        };
        for l in [1e-3, 1e-5] {
            let mut rod = RodRun::new(body(l, 0.3), 1.0, &initial, 1e-12).unwrap();
            assert_eq!(rod.finish(100.0, |_| {}).unwrap(), Outcome::Escaped);
            let at = rod.certificate().unwrap();
            assert!(
                (at - crossing).abs() < 10.0 * l,
                "{initial:?} L {l}: certificate at {at}, the point's E = −½ at {crossing}"
            );
        }
    }
}
