//! Physical controls: with SI units on the release is held in metres and m/s, so μ, rpm and g
//! change the dimensionless release and the outcome (lengths in R_max = μg/Ω², speeds in
//! μg/Ω); the table stays in the panel; the μ probe reads the table's Ω.

use crate::common;
use common::render;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use turntable::app::App;
use turntable::app::pages::Page;
use turntable::app::testing::Testing as _;
use turntable::engine::units::Units;
use turntable::engine::{Initial, Outcome, Run};
use turntable::present::{si_length, si_rate};
use turntable::scene::Scene;

fn key(app: &mut App, c: char) {
    app.handle_key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE));
}

fn outcome(a: &App) -> Outcome {
    Run::new(a.initial(), a.settings())
        .unwrap()
        .finish(1e3)
        .unwrap()
        .0
}

#[test]
fn doubling_mu_doubles_r_max_and_halves_xi0_for_the_same_metres() {
    let mut a = App::new(Scene::preset("C").unwrap());
    // Thrown outward faster than C: it escapes on this table.
    a.explore().set_initial(Initial::velocity(0.5, 0.0, 0.7));
    assert_eq!(outcome(&a), Outcome::Escaped);
    key(&mut a, 'u');
    let u0 = a.units().unwrap();
    assert_eq!(
        a.initial().xi0,
        0.5,
        "turning units on changes nothing but labels"
    );
    let (r0, v0) = (
        a.initial().xi0 * u0.r_max_m(),
        a.initial().v0 * u0.speed_m_s(),
    );
    for _ in 0..15 {
        key(&mut a, 'u');
    }
    let u = a.units().unwrap();
    assert_eq!(u.mu, 2.0 * u0.mu);
    assert!((u.r_max_m() / u0.r_max_m() - 2.0).abs() < 1e-12);
    // The same metres and m/s: ξ0 and v0 halve.
    assert!((a.initial().xi0 - 0.25).abs() < 1e-9, "{}", a.initial().xi0);
    assert!((a.initial().v0 - 0.35).abs() < 1e-9, "{}", a.initial().v0);
    assert!((a.initial().xi0 * u.r_max_m() - r0).abs() < 1e-9);
    assert!((a.initial().v0 * u.speed_m_s() - v0).abs() < 1e-9);
    assert_eq!(a.initial().phi, 0.0);
    // "What if friction were larger?": it now stops.
    assert_eq!(outcome(&a), Outcome::Stuck);
    assert_eq!(a.sim().now().tau, 0.0, "the run restarted");
    a.check_invariants().unwrap();
    // And back: the release in metres is the same one.
    for _ in 0..15 {
        key(&mut a, 'U');
    }
    assert!((a.initial().xi0 - 0.5).abs() < 1e-9 && (a.initial().v0 - 0.7).abs() < 1e-9);
    assert_eq!(outcome(&a), Outcome::Escaped);
}

#[test]
fn rpm_and_g_rescale_the_release_as_r_max_says() {
    let u = Units::new(0.2, 30.0, 9.81).unwrap();
    let i = Initial::velocity(0.4, 1.0, 0.3);
    // Twice the rpm: R_max a quarter, ξ0 four times; speeds in μg/Ω: v0 twice.
    let fast = Units::new(0.2, 60.0, 9.81).unwrap();
    let j = u.carry(i, &fast);
    assert!((fast.r_max_m() / u.r_max_m() - 0.25).abs() < 1e-12);
    assert!((j.xi0 - 1.6).abs() < 1e-12 && (j.v0 - 0.6).abs() < 1e-12 && j.phi == 1.0);
    // Twice g: as twice μ.
    let heavy = Units::new(0.2, 30.0, 19.62).unwrap();
    let k = u.carry(i, &heavy);
    assert!((k.xi0 - 0.2).abs() < 1e-12 && (k.v0 - 0.15).abs() < 1e-12);
}

#[test]
fn the_table_stays_in_the_panel_and_the_mu_probe_reads_its_omega() {
    let mut a = App::new(Scene::preset("B").unwrap());
    key(&mut a, 'u');
    key(&mut a, 'w');
    a.handle_key(KeyEvent::new(KeyCode::Esc, KeyModifiers::NONE));
    let u = a.units().unwrap();
    for (w, h) in [(40, 12), (80, 24), (200, 60)] {
        let screen = render(&mut a, w, h);
        a.check_invariants().unwrap();
        if h >= 24 {
            let r_max = format!("R_max  {}", si_length(u.r_max_m()));
            let r0 = format!("r0     {} φ 0", si_length(a.initial().xi0 * u.r_max_m()));
            let omega = format!("Ω      {} 34.3 rpm", si_rate(u.omega()));
            for want in [&r_max, &r0, "μ g    0.15, 9.81 m/s²", &omega] {
                assert!(screen.contains(want), "{w}×{h}: {want}\n{screen}");
            }
        }
    }
    // The largest table the knobs reach still fits the panel whole.
    let mut big = App::new(Scene::preset("B").unwrap());
    big.tell_units(Some(Units::new(10.0, 1e4, 1000.0).unwrap()));
    let screen = render(&mut big, 80, 24);
    for want in [
        "Ω      1047 rad/s 10000 rpm │",
        "μ g    10.00, 1000.00 m/s²",
    ] {
        assert!(screen.contains(want), "{want}\n{screen}");
    }
    // The rest page's Eq. 22 uses the table's Ω, and `o` turns the table.
    crate::common::turn_to(&mut a, Page::RestRadius);
    let screen = render(&mut a, 100, 40);
    assert!(
        screen.contains("Ω = 3.595 rad/s (34.3 rpm, the table's)"),
        "{screen}"
    );
    let xi0 = a.initial().xi0;
    key(&mut a, 'o');
    let v = a.units().unwrap();
    assert!((v.omega() - (u.omega() + 0.1)).abs() < 1e-9, "{v:?}");
    assert!(
        a.initial().xi0 > xi0,
        "a faster table: a smaller R_max, a larger ξ0"
    );
    assert_eq!(
        a.mu_probe(),
        turntable::app::MU_PROBE,
        "the probe's own Ω is left alone"
    );
}

/// A run pinned on one table and compared with the same release on another (μ doubled) is
/// drawn in the new table's units: the same metres start at the same point.
#[test]
fn a_pin_from_another_table_is_drawn_in_this_ones_units() {
    let mut a = App::new(Scene::preset("C").unwrap());
    a.explore().set_initial(Initial::velocity(0.5, 0.0, 0.7));
    key(&mut a, 'u');
    key(&mut a, 'b');
    let before = a.units();
    for _ in 0..15 {
        key(&mut a, 'u');
    }
    let pin = &a.pins()[0];
    assert_eq!(pin.spec.units, before);
    assert_eq!(pin.outcome, Outcome::Escaped);
    let (kl, kt) = pin.scale(a.units());
    assert!(
        (kl - 0.5).abs() < 1e-12 && (kt - 1.0).abs() < 1e-12,
        "{kl} {kt}"
    );
    assert!((pin.path[0].xi() * kl - a.initial().xi0).abs() < 1e-9);
    // Units off: nothing to convert by.
    assert_eq!(pin.scale(None), (1.0, 1.0));
    for page in [Page::Turntable, Page::TimePlots] {
        crate::common::turn_to(&mut a, page);
        for (w, h) in [(40, 12), (80, 24), (200, 60)] {
            render(&mut a, w, h);
            a.check_invariants().unwrap();
        }
    }
}
