//! Beyond the paper's coupling (issue 23): static friction above kinetic (`--mu-static-ratio`)
//! and Stokes drag (`--coupling stokes`), each against a closed form, a limit, or plain runs.

use crate::common;
use crate::reference;
use common::{render, seeded as config, turntable};
use glam::DVec2;
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};
use turntable::app::App;
use turntable::app::testing::Testing as _;
use turntable::engine::doubt::{doubt, second_opinion};
use turntable::engine::solve::{critical_radius, escape_speed};
use turntable::engine::stokes::{Stokes, growth_rate, roots};
use turntable::engine::{
    Certificate, Coupling, Frame, Initial, Outcome, Release, Run, Settings, Status,
};
use turntable::scene::Scene;

fn held(hold: f64) -> Settings {
    Settings {
        coupling: Coupling::Coulomb { hold },
        ..Settings::default()
    }
}

fn stokes(gamma: f64) -> Settings {
    Settings {
        coupling: Coupling::Stokes { gamma },
        ..Settings::default()
    }
}

// ---- static friction above kinetic ----

/// At rest on the table the particle holds while ξ0 ≤ μ_s/μ_k, and a hair beyond it slides
/// off at μ_k and escapes (Sec. II, property 1, with μ_s > μ_k).
#[test]
fn a_release_at_table_rest_holds_out_to_the_static_ratio() {
    for r in [1.0, 1.3, 2.5] {
        for (xi0, holds) in [(r - 1e-9, true), (r, true), (r + 1e-9, false)] {
            let mut run = Run::new(Initial::at_rest(xi0, Release::TableRest), held(r)).unwrap();
            let (o, end) = run.finish(200.0).unwrap();
            if holds {
                assert_eq!(o, Outcome::Stuck, "R {r}, ξ0 {xi0}");
                assert_eq!(end.tau, 0.0);
                assert!((run.state_at(7.0).unwrap().xi() - xi0).abs() < 1e-14);
            } else {
                assert_eq!(o, Outcome::Escaped, "R {r}, ξ0 {xi0}");
            }
        }
    }
}

/// A particle that starts inside ξ = 1 reaches ξ > 1 only moving out, and from then on it never
/// stops (the radial certificate's proof, `engine::run::outcome`): so μ_s/μ_k changes nothing
/// inside the rim. The escape speed and the critical radius are the paper's for any ratio.
#[test]
fn static_friction_changes_nothing_for_releases_inside_the_rim() {
    for (xi0, phi) in [(0.5, 0.0), (0.8, 1.0), (0.2, 4.0)] {
        let base = escape_speed(xi0, phi, Settings::default(), 1e-8).unwrap();
        let more = escape_speed(xi0, phi, held(1.7), 1e-8).unwrap();
        assert!(
            (base.value - more.value).abs() < 1e-8,
            "({xi0}, {phi}): {} vs {}",
            base.value,
            more.value
        );
    }
    let base = critical_radius(Settings::default(), 1e-7).unwrap();
    let more = critical_radius(held(3.0), 1e-7).unwrap();
    assert!((base.value - more.value).abs() < 1e-7);
    assert!((base.value - reference::XI0C).abs() < 1e-6);
}

/// Thrown inward from outside ξ = 1, the particle slows, but Coriolis turns it before it stops
/// (a stop outside ξ = 1 is approached only exactly along −q̂, which Coriolis leaves): it
/// escapes whatever μ_s/μ_k, and the second opinion agrees.
#[test]
fn thrown_inward_from_outside_it_turns_before_it_stops() {
    for v0 in [0.1, 0.3, 0.5, 1.0] {
        let i = Initial::velocity(1.5, PI, v0);
        let mut run = Run::new(i, held(2.0)).unwrap();
        let (o, _) = run.finish(200.0).unwrap();
        assert_eq!(o, Outcome::Escaped, "v0 {v0}");
        let d = doubt(&run, 200.0);
        assert!(d.certain, "v0 {v0}");
    }
}

/// The energy certificate is E < −½(μ_s/μ_k)²: a release at table rest just beyond the rim has
/// E = −½ξ0², below −½ but above −½R², and the paper's certificate would call it escaped at
/// once; with R = 1.5 it is certified only once it is below −½R².
#[test]
fn the_energy_certificate_moves_with_the_static_ratio() {
    let i = Initial::at_rest(1.3, Release::TableRest);
    let mut paper = Run::new(i, Settings::default()).unwrap();
    paper.finish(100.0).unwrap();
    let e = paper.escape().unwrap();
    assert_eq!((e.tau, e.by), (0.0, Certificate::Energy));
    let i = Initial::at_rest(1.6, Release::TableRest);
    let mut run = Run::new(i, held(1.5)).unwrap();
    run.finish(100.0).unwrap();
    let e = run.escape().unwrap();
    assert_eq!((e.tau, e.by), (0.0, Certificate::Energy));
    assert!(e.state.energy() < -0.5 * 1.5 * 1.5);
    let i = Initial::velocity(1.2, 0.3, 0.4);
    let mut run = Run::new(i, held(1.5)).unwrap();
    run.finish(100.0).unwrap();
    let e = run.escape().unwrap();
    assert_eq!(e.by, Certificate::Radial);
    assert!(e.state.energy() >= -0.5 * 1.5 * 1.5);
}

/// The second opinion runs with the run's own coupling.
#[test]
fn the_second_opinion_shares_the_coupling() {
    for c in [
        Coupling::PAPER,
        Coupling::Coulomb { hold: 1.8 },
        Coupling::Stokes { gamma: 0.4 },
    ] {
        let s = Settings {
            coupling: c,
            ..Settings::default()
        };
        let run = Run::new(Initial::velocity(0.5, 0.0, 0.6), s).unwrap();
        assert_eq!(second_opinion(&run).coupling, c);
    }
}

proptest! {
    #![proptest_config(config(40))]

    /// The escape certificates, for any μ_s/μ_k, against plain runs that ignore them: a run
    /// stopped at its certificate (dp54 1e-10, lab frame) and the same release followed on at
    /// tol 1e-12 in the table frame with no certificate stopping it. A certified escape never
    /// sticks afterwards; a stuck run sticks at the same place in both.
    #[test]
    fn certificates_hold_against_plain_runs(
        xi0 in 0.0..2.5f64, phi in 0.0..TAU, v0 in 0.0..2.0f64, r in 1.0..3.0f64,
    ) {
        let i = Initial::velocity(xi0, phi, v0);
        let mut run = Run::new(i, held(r)).unwrap();
        let (o, end) = run.finish(200.0).unwrap();
        let plain_settings = Settings {
            frame: Frame::Table,
            max_steps: 2_000_000,
            ..Settings::dp54(1e-12)
        };
        let plain_settings = Settings { coupling: Coupling::Coulomb { hold: r }, ..plain_settings };
        let mut plain = Run::new(i, plain_settings).unwrap();
        let horizon = match o {
            Outcome::Escaped => end.tau + 40.0,
            _ => 200.0,
        };
        while plain.status() == Status::Slipping && plain.tau() < horizon && plain.state().xi() < 60.0 {
            plain.step(horizon).unwrap();
        }
        match o {
            Outcome::Escaped => prop_assert_eq!(plain.status(), Status::Slipping,
                "certified at τ {} ({:?}), stuck later", end.tau, run.escape().map(|e| e.by)),
            Outcome::Stuck => {
                let Status::Stuck { q, .. } = plain.status() else {
                    return Err(TestCaseError::fail("stuck, but the plain run is not"));
                };
                prop_assert!((q - end.q()).length() < 1e-6, "{:?} vs {:?}", q, end.q());
                prop_assert!(q.length() <= r);
            }
            Outcome::Running => {}
        }
    }

    /// dE/dτ = −|u| ≤ 0 whatever μ_s/μ_k: E never rises from one step to the next.
    #[test]
    fn energy_never_rises_with_static_friction(
        xi0 in 0.0..2.0f64, phi in 0.0..TAU, v0 in 0.0..2.0f64, r in 1.0..3.0f64,
        frame in prop_oneof![Just(Frame::Lab), Just(Frame::Table)],
    ) {
        let s = Settings { frame, ..held(r) };
        let mut run = Run::new(Initial::velocity(xi0, phi, v0), s).unwrap();
        let mut prev = run.state();
        while run.outcome() == Outcome::Running && run.tau() < 30.0 {
            run.step(30.0).unwrap();
            let now = run.state();
            prop_assert!(now.energy() <= prev.energy() + 1e-8,
                "E rose {:e} at τ {}", now.energy() - prev.energy(), now.tau);
            prev = now;
        }
    }

    /// Stokes drag: along the closed form, the Jacobi energy E = ½|u|² − ½|q|² obeys
    /// dE/dτ = −γ|u|² (central differences), so it never rises, and E(τ1) − E(τ0) is
    /// −γ∫|u|² (Gauss–Legendre, 8 points on 16 panels).
    #[test]
    fn stokes_loses_jacobi_energy_at_gamma_u_squared(
        xi0 in 0.0..2.0f64, phi in 0.0..TAU, v0 in 0.0..2.0f64,
        gamma in 0.0..5.0f64, t0 in 0.0..3.0f64,
    ) {
        let st = Stokes::new(gamma, Initial::velocity(xi0, phi, v0));
        let e = |t: f64| {
            let (q, u) = st.at(t);
            0.5 * (u.length_squared() - q.length_squared())
        };
        let h = 1e-4;
        let (_, u) = st.at(t0 + h);
        let slope = (e(t0 + 2.0 * h) - e(t0)) / (2.0 * h);
        let scale = 1.0 + e(t0).abs() + u.length_squared();
        prop_assert!((slope + gamma * u.length_squared()).abs() < 1e-6 * scale,
            "dE/dτ {} vs −γ|u|² {}", slope, -gamma * u.length_squared());
        let t1 = t0 + 1.0;
        let (x, w) = gauss8();
        let panels = 16;
        let mut loss = 0.0;
        for k in 0..panels {
            let (a, b) = (t0 + k as f64 / panels as f64, t0 + (k + 1) as f64 / panels as f64);
            for (xi, wi) in x.iter().zip(w) {
                let t = 0.5 * (a + b) + 0.5 * (b - a) * xi;
                loss += 0.5 * (b - a) * wi * gamma * st.at(t).1.length_squared();
            }
        }
        prop_assert!(e(t1) <= e(t0) + 1e-12 * scale);
        prop_assert!((e(t1) - e(t0) + loss).abs() < 1e-9 * scale,
            "ΔE {} vs −γ∫|u|² {}", e(t1) - e(t0), -loss);
    }
}

/// Gauss–Legendre nodes and weights, 8 points on [−1, 1].
fn gauss8() -> ([f64; 8], [f64; 8]) {
    let x = [
        -0.9602898564975363,
        -0.7966664774136267,
        -0.525532409916329,
        -0.1834346424956498,
        0.1834346424956498,
        0.525532409916329,
        0.7966664774136267,
        0.9602898564975363,
    ];
    let w = [
        0.1012285362903763,
        0.2223810344533745,
        0.3137066458778873,
        0.362683783378362,
        0.362683783378362,
        0.3137066458778873,
        0.2223810344533745,
        0.1012285362903763,
    ];
    (x, w)
}

// ---- Stokes drag ----

/// e^{Aτ} y0 for the 4×4 real rotating-frame system y = (qx, qy, ux, uy),
/// q′ = u, u′ = −2ẑ×u + q − γu: Taylor series with scaling and squaring, independent of the
/// engine's complex eigen-decomposition.
fn expm_apply(gamma: f64, tau: f64, y0: [f64; 4]) -> [f64; 4] {
    let a = [
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
        [1.0, 0.0, -gamma, 2.0],
        [0.0, 1.0, -2.0, -gamma],
    ];
    let norm: f64 = a
        .iter()
        .map(|r| r.iter().map(|x: &f64| x.abs()).sum::<f64>())
        .fold(0.0, f64::max)
        * tau.abs();
    let squarings = if norm > 0.5 {
        (norm / 0.5).log2().ceil() as i32
    } else {
        0
    };
    let h = tau / 2f64.powi(squarings);
    let mul = |x: &[[f64; 4]; 4], y: &[[f64; 4]; 4]| {
        let mut z = [[0.0; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                z[i][j] = (0..4).map(|k| x[i][k] * y[k][j]).sum();
            }
        }
        z
    };
    let mut e = [[0.0; 4]; 4];
    let mut term = [[0.0; 4]; 4];
    for i in 0..4 {
        e[i][i] = 1.0;
        term[i][i] = 1.0;
    }
    let ah = a.map(|r| r.map(|x| x * h));
    for k in 1..30 {
        term = mul(&term, &ah).map(|r| r.map(|x| x / k as f64));
        for i in 0..4 {
            for j in 0..4 {
                e[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..squarings {
        e = mul(&e, &e);
    }
    let mut y = [0.0; 4];
    for i in 0..4 {
        y[i] = (0..4).map(|k| e[i][k] * y0[k]).sum();
    }
    y
}

#[test]
fn stokes_closed_form_is_the_matrix_exponential() {
    let releases = [
        Initial::velocity(0.5, 0.0, 0.6078),
        Initial::velocity(1.1, 1.2 * PI, 1.3),
        Initial::velocity(0.0, 2.0, 0.7),
        Initial::at_rest(0.8, Release::LabRest),
        Initial::at_rest(0.3, Release::TableRest),
    ];
    for gamma in [1e-9, 1e-3, 0.1, 0.5, 1.0, 3.0, 20.0] {
        for i in releases {
            let st = Stokes::new(gamma, i);
            let s0 = i.state();
            let (q0, u0) = (s0.q(), s0.u());
            for tau in [0.01, 0.3, 1.0, 4.0, 12.0] {
                let y = expm_apply(gamma, tau, [q0.x, q0.y, u0.x, u0.y]);
                let (q, u) = st.at(tau);
                let size = 1.0 + y.iter().map(|x| x.abs()).fold(0.0, f64::max);
                let err = (q - DVec2::new(y[0], y[1]))
                    .length()
                    .max((u - DVec2::new(y[2], y[3])).length());
                assert!(
                    err < 1e-11 * size,
                    "γ {gamma}, {i:?}, τ {tau}: off by {err:e} at size {size:e}"
                );
            }
        }
    }
}

/// γ = 0 is the straight line in the lab (`Initial::frictionless`), and γ → 0 tends to it.
#[test]
fn stokes_without_drag_is_the_frictionless_line() {
    let i = Initial::velocity(0.5, 2.0, 0.8);
    let free = Initial {
        frictionless: true,
        ..i
    };
    for tau in [0.0, 0.5, 3.0, 10.0] {
        let line = free.free_state(tau);
        let s = Stokes::new(0.0, i).state(tau);
        assert!(
            (s.r - line.r).length() < 1e-13 * (1.0 + line.xi()),
            "τ {tau}"
        );
        assert!(
            (s.v - line.v).length() < 1e-13 * (1.0 + line.xi()),
            "τ {tau}"
        );
        let near = Stokes::new(1e-12, i).state(tau);
        assert!((near.r - line.r).length() < 1e-9, "τ {tau}");
    }
    let mut a = Run::new(i, stokes(0.0)).unwrap();
    let mut b = Run::new(free, Settings::default()).unwrap();
    let (oa, ea) = a.finish(100.0).unwrap();
    let (ob, eb) = b.finish(100.0).unwrap();
    assert_eq!((oa, a.escape().unwrap().by), (ob, Certificate::Radial));
    assert!((ea.tau - eb.tau).abs() < 1e-12 && (ea.r - eb.r).length() < 1e-12);
    assert_eq!(a.cost().rhs_evals, 0);
    // A little drag: certified where the line would be, to first order in γ.
    let mut c = Run::new(i, stokes(1e-9)).unwrap();
    let (oc, ec) = c.finish(100.0).unwrap();
    assert_eq!(oc, Outcome::Escaped);
    assert!((ec.tau - eb.tau).abs() < 1e-7, "{} vs {}", ec.tau, eb.tau);
}

/// The roots solve λ² + (2i + γ)λ − 1 = 0; Re λ+ is the rate at which |q| grows, ≈ √(γ/2) for
/// small γ and ≈ 1/γ for large (the slow creep of an overdamped particle).
#[test]
fn stokes_leaves_at_the_growth_rate() {
    for gamma in [1e-6, 0.01, 0.5, 2.0, 50.0, 1e4] {
        let (p, m, g) = roots(gamma);
        for l in [p, m] {
            let c = DVec2::new(gamma, 2.0);
            let sq = DVec2::new(l.x * l.x - l.y * l.y, 2.0 * l.x * l.y);
            let cl = DVec2::new(c.x * l.x - c.y * l.y, c.x * l.y + c.y * l.x);
            let res = sq + cl - DVec2::X;
            assert!(
                res.length() < 1e-12 * (1.0 + l.length_squared()),
                "γ {gamma}: {res:?}"
            );
        }
        assert!((g - p.x).abs() <= 1e-9 * g, "γ {gamma}");
        assert!(g > 0.0 && m.x < 0.0);
        assert_eq!(growth_rate(gamma), g);
    }
    assert!((growth_rate(1e-8) / (0.5e-8f64).sqrt() - 1.0).abs() < 1e-3);
    assert!((growth_rate(1e4) * 1e4 - 1.0).abs() < 1e-3);
    // Measured on the closed form: d ln|q|/dτ late on.
    for gamma in [0.2, 1.0, 5.0] {
        let st = Stokes::new(gamma, Initial::velocity(0.5, 1.0, 0.3));
        let (t1, t2) = (40.0 / growth_rate(gamma), 50.0 / growth_rate(gamma));
        let rate = (st.at(t2).0.length() / st.at(t1).0.length()).ln() / (t2 - t1);
        assert!(
            (rate - growth_rate(gamma)).abs() < 1e-6,
            "γ {gamma}: {rate}"
        );
    }
}

/// A subnormal drag is a little drag: its roots solve the equation, Re λ+ is √(γ/2), and a
/// run leaves where the straight line does. (At γ = 4.9e-324, γ(√(γ² + 16) + γ)/2 underflowed
/// to 0: Re d was 0, Im λ+ −∞, and `run --gamma 4.9e-324` reported an overflow where 1e-320
/// and 0 escape.)
#[test]
fn a_subnormal_drag_leaves_as_the_line_does() {
    let i = Initial::velocity(0.5, 2.0, 0.8);
    let mut line = Run::new(i, stokes(0.0)).unwrap();
    let (_, end) = line.finish(100.0).unwrap();
    for gamma in [4.9e-324, 1e-322, 1e-320, 1e-310, f64::MIN_POSITIVE, 1e-300] {
        let (p, m, g) = roots(gamma);
        for l in [p, m] {
            let c = DVec2::new(gamma, 2.0);
            let sq = DVec2::new(l.x * l.x - l.y * l.y, 2.0 * l.x * l.y);
            let cl = DVec2::new(c.x * l.x - c.y * l.y, c.x * l.y + c.y * l.x);
            let res = sq + cl - DVec2::X;
            assert!(res.length() < 1e-15, "γ {gamma:e}: {res:?}");
        }
        let expected = gamma.sqrt() * 0.5f64.sqrt();
        assert!((g / expected - 1.0).abs() < 1e-12, "γ {gamma:e}: {g:e}");
        let mut run = Run::new(i, stokes(gamma)).unwrap();
        let (o, e) = run.finish(100.0).unwrap();
        assert_eq!(o, Outcome::Escaped, "γ {gamma:e}");
        assert!((e.tau - end.tau).abs() < 1e-12, "γ {gamma:e}: τ {}", e.tau);
    }
}

/// Only releases with no growing part stay: the centre at rest, and u0 = λ− q0 (here at
/// ξ0 = 0.5, speed |λ−|/2 in direction arg λ−), which spirals into the centre.
#[test]
fn only_the_stable_manifold_stays() {
    let gamma = 0.7;
    let (_, m, _) = roots(gamma);
    let i = Initial::velocity(0.5, m.y.atan2(m.x), 0.5 * m.length());
    let st = Stokes::new(gamma, i);
    assert!(st.at(20.0).0.length() < 1e-3 * 0.5, "{:?}", st.at(20.0));
    let centre = Initial::at_rest(0.0, Release::TableRest);
    let mut run = Run::new(centre, stokes(gamma)).unwrap();
    assert_eq!(run.finish(50.0).unwrap().0, Outcome::Running);
    assert_eq!(run.state().xi(), 0.0);
}

/// The Stokes certificate: from the τ it gives on, ξ > 1 and ξ only grows (checked on a fine
/// grid of the closed form out to where |q| is 1e6 times larger), and just before it, it did
/// not yet hold (ξ ≤ 1 or ξ′ ≤ 0).
#[test]
fn stokes_escape_certificate_holds() {
    for gamma in [0.05, 0.5, 3.0] {
        for i in [
            Initial::velocity(0.5, 0.0, 0.3),
            Initial::velocity(0.2, PI, 1.5),
            Initial::at_rest(0.9, Release::LabRest),
            Initial::velocity(1.5, 0.5 * PI, 2.0),
        ] {
            let mut run = Run::new(i, stokes(gamma)).unwrap();
            let (o, end) = run.finish(1e4).unwrap();
            assert_eq!(o, Outcome::Escaped);
            assert_eq!(run.escape().unwrap().by, Certificate::Radial);
            assert!(end.xi() >= 1.0 - 1e-12, "γ {gamma}: {}", end.xi());
            let st = Stokes::new(gamma, i);
            if end.tau > 0.0 {
                let (q, u) = st.at(end.tau - 1e-9);
                assert!(
                    q.length() <= 1.0 || q.dot(u) <= 0.0,
                    "γ {gamma}, {i:?}: held earlier"
                );
            }
            let span = (1e6f64).ln() / growth_rate(gamma);
            let mut prev = end.xi();
            for k in 1..=4000 {
                let xi = st.at(end.tau + span * k as f64 / 4000.0).0.length();
                assert!(xi > prev && xi > 1.0, "γ {gamma}, {i:?}: at step {k}");
                prev = xi;
            }
        }
    }
}

// ---- the scene file, the command line, the explorer ----

#[test]
fn scene_files_carry_the_coupling() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, settings: &str| {
        let p = dir.path().join(name);
        std::fs::write(
            &p,
            format!(
                "name = \"x\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.3\n[settings]\nmethod = \"dp54\"\n{settings}"
            ),
        )
        .unwrap();
        p.display().to_string()
    };
    let s = Scene::load(&write("a.toml", "mu_static_ratio = 1.5\n")).unwrap();
    assert_eq!(s.settings.coupling, Coupling::Coulomb { hold: 1.5 });
    let s = Scene::load(&write("b.toml", "coupling = \"stokes\"\ngamma = 0.3\n")).unwrap();
    assert_eq!(s.settings.coupling, Coupling::Stokes { gamma: 0.3 });
    let back: Scene = toml::from_str(&s.to_toml()).unwrap();
    assert_eq!(back.settings, s.settings);
    let plain = Scene::preset("B").unwrap().to_toml();
    assert!(!plain.contains("coupling") && !plain.contains("mu_static_ratio"));
    for (name, bad, says) in [
        (
            "c.toml",
            "mu_static_ratio = 0.5\n",
            "[settings] mu_static_ratio",
        ),
        ("d.toml", "mu_static_ratio = nan\n", "NaN"),
        ("e.toml", "coupling = \"stokes\"\n", "needs gamma"),
        ("f.toml", "gamma = 0.2\n", "needs coupling stokes"),
        ("g.toml", "coupling = \"stokes\"\ngamma = -1.0\n", "gamma"),
        (
            "h.toml",
            "coupling = \"viscous\"\n",
            "expected `coulomb` or `stokes`",
        ),
    ] {
        let e = Scene::load(&write(name, bad)).unwrap_err().to_string();
        assert!(e.contains(says), "{bad}: {e}");
    }
}

#[test]
fn the_command_line_refuses_bad_couplings() {
    for args in [
        &["run", "--mu-static-ratio", "0.5"][..],
        &["run", "--mu-static-ratio", "nan"],
        &["run", "--mu-static-ratio", "inf"],
        &["run", "--mu-static-ratio", "-1"],
        &["run", "--coupling", "stokes"],
        &["run", "--gamma", "nan"],
        &["run", "--gamma", "-0.5"],
        &["run", "--gamma", "1", "--mu-static-ratio", "2"],
        &["run", "--coupling", "coulomb", "--gamma", "1"],
        &["run", "--method", "rk2-raw", "--mu-static-ratio", "2"],
        &["escape", "--xi0", "0.5", "--gamma", "1"],
        &["critical", "--coupling", "stokes", "--gamma", "1"],
        &["sweep", "map", "--xi0", "0.5", "--gamma", "1"],
        &["escape", "--xi0", "0.5", "--mu-static-ratio", "0.9"],
        &["run", "--frictionless", "--gamma", "1"],
        &["run", "--frictionless", "--mu-static-ratio", "2"],
        // The explorer refuses them before it needs a terminal.
        &["--mu-static-ratio", "0.5"],
        &["--coupling", "stokes"],
        &["--gamma", "1", "--record", "session.keys"],
    ] {
        let (code, _, err) = turntable(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            err.starts_with("error: ") && err.lines().count() == 1,
            "{args:?}: {err}"
        );
    }
}

#[test]
fn run_reports_the_coupling() {
    let (code, out, err) = turntable(&[
        "run",
        "--coupling",
        "stokes",
        "--gamma",
        "0.5",
        "--xi0",
        "0.5",
        "--v0",
        "0.3",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["coupling"], "stokes");
    assert_eq!(v["gamma"], 0.5);
    assert_eq!(v["mu_static_ratio"], serde_json::Value::Null);
    assert_eq!(v["growth_rate"].as_f64().unwrap(), growth_rate(0.5));
    assert_eq!(v["certificate"], "radial");
    assert_eq!(v["rhs_evals"], 0);
    let (code, out, err) = turntable(&[
        "run",
        "--release",
        "table-rest",
        "--xi0",
        "1.3",
        "--mu-static-ratio",
        "1.5",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        (&v["outcome"], &v["coupling"], &v["mu_static_ratio"]),
        (
            &serde_json::json!("stuck"),
            &serde_json::json!("coulomb"),
            &serde_json::json!(1.5)
        )
    );
    let (code, out, _) = turntable(&["escape", "--xi0", "0.5", "--mu-static-ratio", "1.5"]);
    assert_eq!(code, 0);
    assert!(out.contains("mu_s/mu_k = 1.5"), "{out}");
}

/// The explorer draws a Stokes scene in closed form and says how it ends; a μ_s/μ_k scene
/// shows its ratio.
#[test]
fn the_explorer_shows_the_coupling() {
    let mut scene = Scene::preset("B").unwrap();
    scene.settings.coupling = Coupling::Stokes { gamma: 0.5 };
    let mut app = App::new(scene);
    for _ in 0..40 {
        app.tick();
    }
    let screen = render(&mut app, 100, 32);
    assert!(screen.contains("Stokes γ"), "{screen}");
    assert!(screen.contains("e^0.2822τ"), "{screen}");
    assert_eq!(app.sim().cost().rhs_evals, 0);
    assert!(app.sim().now().tau > 1.0);
    let tab = crossterm::event::KeyEvent::new(
        crossterm::event::KeyCode::Tab,
        crossterm::event::KeyModifiers::NONE,
    );
    app.handle_key(tab);
    let screen = render(&mut app, 100, 32);
    assert!(screen.contains("dE/dτ = −γ|u|²"), "{screen}");
    for _ in 0..3 {
        app.handle_key(tab);
        let screen = render(&mut app, 100, 32);
        assert!(screen.contains("no threshold"), "{screen}");
        assert!(screen.contains("0.282161"), "{screen}");
    }
    let mut scene = Scene::preset("fig2").unwrap();
    scene.settings.coupling = Coupling::Coulomb { hold: 1.2 };
    let mut app = App::new(scene);
    for _ in 0..40 {
        app.tick();
    }
    let screen = render(&mut app, 100, 32);
    assert!(screen.contains("μs/μk"), "{screen}");
    assert!(screen.contains("stuck at ξ = 1.1"), "{screen}");
    // `m` cycles the methods but passes the paper's raw scheme by (μs = μk there).
    let m = crossterm::event::KeyEvent::new(
        crossterm::event::KeyCode::Char('m'),
        crossterm::event::KeyModifiers::NONE,
    );
    let mut seen = Vec::new();
    for _ in 0..5 {
        app.handle_key(m);
        seen.push(app.settings().method());
        assert_eq!(app.sim().settings(), app.settings());
        assert_eq!(app.settings().hold(), 1.2);
    }
    assert!(
        !seen.contains(&turntable::engine::Method::Rk2Raw),
        "{seen:?}"
    );
    assert_eq!(seen.len(), 5);
}

/// A stop outside ξ = 1 does happen, on the thin set of releases that approach it straight in:
/// built by integrating back in time from rest at ξ = 1.3 (backward, the approach along −q̂
/// is stable; RK4, 3000 steps). Forward, that release stops at ξ = 1.3: with μ_s/μ_k ≥ 1.3
/// it sticks there, with the paper's 1, or 1.29, it slips on and escapes.
#[test]
fn a_stop_outside_the_rim_sticks_when_static_friction_can_hold_it() {
    let zc = |a: DVec2| DVec2::new(-a.y, a.x);
    // Backward in time: dq/ds = −u, du/ds = 2ẑ×u − q + û.
    let f = |q: DVec2, u: DVec2| (-u, 2.0 * zc(u) - q + u.normalize());
    let qs = DVec2::new(1.3, 0.0);
    let (q, u) = common::rk4(f, (qs, -1e-12 * qs.normalize()), 1e-4, 3000);
    let turn = q.y.atan2(q.x);
    let i = Initial::velocity(q.length(), u.y.atan2(u.x) - turn, u.length());
    let rest = DVec2::from_angle(-turn).rotate(qs);
    for (r, sticks) in [(1.5, true), (1.3 + 1e-6, true), (1.29, false), (1.0, false)] {
        let mut run = Run::new(i, held(r)).unwrap();
        let (o, end) = run.finish(200.0).unwrap();
        if sticks {
            assert_eq!(o, Outcome::Stuck, "R {r}");
            assert!(
                (end.q() - rest).length() < 1e-6,
                "R {r}: {:?} vs {rest:?}",
                end.q()
            );
            assert!((end.tau - 0.3).abs() < 1e-6, "R {r}: τ {}", end.tau);
            // The second opinion (dop853, tighter, other frame) stops there too; the margin is
            // the room left to the static cone, R − ξ.
            let d = doubt(&run, 200.0);
            assert_eq!(d.shadow, Some(Outcome::Stuck), "R {r}");
            assert!(
                (d.margin - (r - end.xi())).abs() < 1e-12,
                "R {r}: {}",
                d.margin
            );
            assert!(d.error < 1e-6, "R {r}: {}", d.error);
            assert!(d.certain && d.error < 0.25 * d.margin, "R {r}: {d:?}");
        } else {
            // Certified (by energy) before the stop; followed on, it stops and slips on.
            assert_eq!(o, Outcome::Escaped, "R {r}");
            assert!(end.tau < 0.3, "R {r}: certified at {}", end.tau);
            run.run(10.0, false).unwrap();
            assert_eq!(run.status(), Status::Slipping, "R {r}");
            assert!(run.slip_restarts() >= 1, "R {r}");
            assert!(run.state().xi() > 3.0, "R {r}");
        }
    }
}

/// The outcome map outside the rim: releases at ξ0 = 1.5 that stick with μ_s/μ_k = 2 all come
/// to rest inside ξ = 1 (there are some: thrown inward), none outside.
#[test]
fn no_release_of_a_map_sticks_outside_the_rim() {
    let (code, out, err) = turntable(&[
        "sweep",
        "map",
        "--xi0",
        "1.5",
        "--mu-static-ratio",
        "2",
        "--phi-points",
        "36",
        "--v0-points",
        "30",
        "--v0-max",
        "4",
    ]);
    assert_eq!(code, 0, "{err}");
    let stuck: Vec<f64> = out
        .lines()
        .skip(1)
        .filter_map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            (c[2] == "stuck").then(|| c[3].parse().unwrap())
        })
        .collect();
    assert!(stuck.len() > 10, "{}", stuck.len());
    assert!(stuck.iter().all(|&xi| xi < 1.0), "{stuck:?}");
}

/// `run --trajectory` under Stokes drag samples the closed form, and its `work` column,
/// −γ∫|u|²dτ by Gauss–Legendre, is E − E(0) (dE/dτ = −γ|u|²).
#[test]
fn the_trajectory_of_stokes_drag_balances_its_energy() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.csv");
    let (code, _, err) = turntable(&[
        "run",
        "--coupling",
        "stokes",
        "--gamma",
        "0.8",
        "--xi0",
        "0.4",
        "--phi",
        "2",
        "--v0",
        "0.9",
        "--trajectory",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&path).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').take(9).map(|x| x.parse().unwrap()).collect())
        .collect();
    assert!(rows.len() > 100, "{}", rows.len());
    let e0 = rows[0][7];
    for r in &rows {
        assert!(
            (r[7] - e0 - r[8]).abs() < 1e-9,
            "τ {}: E − E0 {} vs work {}",
            r[0],
            r[7] - e0,
            r[8]
        );
    }
    assert!(rows.last().unwrap()[8] < -0.01);
}

proptest! {
    #![proptest_config(config(16))]

    /// Near the escape threshold, where runs crawl up to the saddle and its end games act, a
    /// run with μ_s/μ_k > 1 (any method, frame, tolerance) that says `certain` ends as the
    /// paper's tight reference does — the threshold does not move with μ_s/μ_k (above).
    #[test]
    fn certain_is_never_wrong_near_the_threshold_with_static_friction(
        xi0 in 0.0..0.999f64,
        phi in 0.0..TAU,
        e in -8.0..-4.0f64,
        above in any::<bool>(),
        r in 1.0..2.0f64,
        knob in prop_oneof![
            (-12.0..-6.0f64).prop_map(|e| Settings::dp54(10f64.powf(e))),
            (-3.5..-2.5f64).prop_map(|e| Settings::fixed(turntable::engine::Method::Rk4, 10f64.powf(e))),
        ],
        frame in prop_oneof![Just(Frame::Lab), Just(Frame::Table)],
    ) {
        let ve = escape_speed(xi0, phi, Settings::dp54(1e-12), 1e-10).unwrap();
        prop_assume!(ve.interval && ve.stuck_at.is_some());
        let dv = if above { 10f64.powf(e) } else { -(10f64.powf(e)) };
        let i = Initial::velocity(xi0, phi, (ve.value + dv).max(0.0));
        let s = Settings {
            frame,
            max_steps: 2_000_000,
            coupling: Coupling::Coulomb { hold: r },
            ..knob
        };
        let mut run = Run::new(i, s).unwrap();
        prop_assume!(run.run(1e4, true).is_ok());
        let d = doubt(&run, 1e4);
        // Only a certain run claims its outcome: the reference is run for those alone.
        if d.certain {
            let reference = Settings { frame: Frame::Table, ..Settings::dp54(1e-12) };
            let mut reference = Run::new(i, reference).unwrap();
            let want = reference.run(1e4, true).unwrap();
            prop_assert_eq!(run.outcome() == Outcome::Stuck, want == Outcome::Stuck,
                "certain and wrong at v_e {:+e}, R {}", dv, r);
        }
    }
}
