//! The table spun up in the explorer (`7`, or a scene with `[spin]`): the coin rides the
//! table, held still in its frame, the table turning by Ω0 τ + ½ a τ²; it slips where the
//! closed form says; what the spin-up does not model is refused with a notice, never run as
//! something else.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use glam::DVec2;
use turntable::app::App;
use turntable::app::pages::Page;
use turntable::app::testing::Testing as _;
use turntable::engine::spinup::Onset;
use turntable::engine::{Frame, Method, Release};
use turntable::plot::page::table::Picture;
use turntable::scene::Scene;
use turntable::sim::Motion;

fn spin() -> App {
    App::new(Scene::preset("spin").unwrap())
}

fn key(app: &mut App, k: KeyCode) {
    let effects = app.handle_key(KeyEvent::new(k, KeyModifiers::NONE));
    turntable::session::carry_out(app, effects);
}

/// The closed-form slip of the app's scene.
fn onset(app: &App) -> (f64, f64) {
    let Onset::At { tau, omega } = app
        .scene()
        .spin
        .unwrap()
        .onset(app.initial().xi0, app.settings().hold())
    else {
        panic!("the coin slips on the way")
    };
    (tau, omega)
}

#[test]
fn the_coin_rides_still_on_the_table_then_slips_where_the_closed_form_says() {
    let mut a = spin();
    let (tau_slip, omega_slip) = onset(&a);
    let mut riding = 0;
    while a.sim().now().tau < tau_slip + 1.0 {
        a.tick();
        let now = a.sim().now();
        let m = a.sim().motion();
        let on_table = m.in_frame(&now, Frame::Table);
        if now.tau < tau_slip {
            // Held: still on the table, its lab velocity the table's there.
            assert!(m.riding(&now), "τ = {}", now.tau);
            // Riding, ξ′ is exactly 0 (not the rounding of r·v, 1e-17 on screen).
            assert_eq!(m.xi_dot(&now), 0.0, "τ = {}", now.tau);
            assert!((on_table - DVec2::new(0.5, 0.0)).length() < 1e-14);
            let pic = Picture::in_frame(&a, Frame::Lab);
            assert_eq!(pic.table.spin, 0.1 * now.tau * now.tau);
            riding += 1;
        } else {
            assert!(!m.riding(&now), "τ = {}: slid", now.tau);
        }
    }
    assert!(riding > 100, "{riding} ticks riding");
    let Motion::Spin(run) = a.sim().motion() else {
        panic!("a spin-up scene runs the spin-up")
    };
    let slip = run.slip().unwrap();
    assert!((slip.tau - tau_slip).abs() < 1e-9, "{slip:?}");
    assert!((slip.omega - omega_slip).abs() < 1e-9, "{slip:?}");
    // Out and backwards on the table: behind the table's turn (Θ < 0) and beyond ξ0.
    let s = a.sim().now();
    let q = a.sim().motion().in_frame(&s, Frame::Table);
    assert!(q.length() > 0.5 && q.y < 0.0, "{q}");
    let screen = common_render(&mut a);
    assert!(
        screen.contains("riding") || screen.contains("escape certified"),
        "{screen}"
    );
    assert!(screen.contains("μ read 0.9950 μs"), "{screen}");
    assert!(screen.contains("closed Ω 1.410665"), "{screen}");
}

fn common_render(a: &mut App) -> String {
    crate::common::render(a, 100, 30)
}

#[test]
fn before_the_slip_the_panel_does_not_say_where_it_comes() {
    let mut a = spin();
    for _ in 0..60 {
        a.tick();
    }
    let screen = common_render(&mut a);
    assert!(screen.contains("riding the table"), "{screen}");
    assert!(screen.contains("slip   not yet"), "{screen}");
    assert!(!screen.contains("1.41"), "{screen}");
}

#[test]
fn what_the_spin_up_does_not_model_is_refused_with_a_notice() {
    let mut a = spin();
    for _ in 0..10 {
        a.tick();
    }
    let (initial, settings, tau) = (a.initial(), a.settings(), a.sim().now().tau);
    for k in [
        KeyCode::Char('v'),
        KeyCode::Char('p'),
        KeyCode::Char('R'),
        KeyCode::Char('F'),
        KeyCode::Char('c'),
        KeyCode::Char('b'),
        KeyCode::Tab,
    ] {
        key(&mut a, k);
        assert!(a.notice().is_some(), "{k:?} says why");
        assert_eq!(
            (a.initial(), a.settings(), a.sim().now().tau, a.view().page),
            (initial, settings, tau, Page::Turntable),
            "{k:?} changed nothing"
        );
        assert!(a.paper().is_none() && a.pins().is_empty());
    }
    assert_eq!(a.initial().release, Release::TableRest);
    // The method cycles, passing the paper's raw scheme by: the spin-up needs its events.
    for _ in 0..8 {
        key(&mut a, KeyCode::Char('m'));
        assert_ne!(a.settings().method(), Method::Rk2Raw);
        assert!(matches!(a.sim().motion(), Motion::Spin(_)));
    }
    // ξ0 moves, and the slip moves with it.
    key(&mut a, KeyCode::Char('x'));
    assert_eq!(a.initial().xi0, 0.51);
    assert!(matches!(a.sim().motion(), Motion::Spin(r) if r.xi0() == 0.51));
}

#[test]
fn the_error_estimate_shadows_the_spin_up() {
    let mut a = spin();
    let (tau_slip, _) = onset(&a);
    while a.sim().now().tau < tau_slip + 0.5 {
        a.tick();
    }
    let e = a.sim().error_estimate().unwrap();
    assert!(e.error > 0.0 && e.error < 1e-6, "{e:?}");
    key(&mut a, KeyCode::Char('e'));
    assert!(
        a.notice().as_deref().unwrap().contains("|Δr|"),
        "{:?}",
        a.notice()
    );
}

#[test]
fn another_preset_leaves_the_spin_up_for_the_paper_table() {
    let mut a = spin();
    key(&mut a, KeyCode::Char('3'));
    assert!(a.scene().spin.is_none());
    assert!(matches!(a.sim().motion(), Motion::Steady(_)));
    key(&mut a, KeyCode::Char('7'));
    assert!(matches!(a.sim().motion(), Motion::Spin(_)));
}

#[test]
fn a_saved_spin_scene_loads_as_it_was_saved() {
    let dir = std::env::temp_dir().join(format!("turntable-spin-save-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("mine.toml");
    let scene = Scene::preset("spin").unwrap();
    std::fs::write(&path, scene.to_toml()).unwrap();
    let back = Scene::load(path.to_str().unwrap()).unwrap();
    assert_eq!(back.spin, scene.spin);
    assert_eq!(back.initial, scene.initial);
    // A spin-up scene opens on the turntable page: another page is refused.
    let page = format!(
        "{}\n[view]\npage = \"time-plots\"\nframe = \"lab\"\nforces = false\nzoom = 1.0\n",
        scene.to_toml()
    );
    std::fs::write(&path, page).unwrap();
    let err = Scene::load(path.to_str().unwrap()).unwrap_err().to_string();
    assert!(err.contains("and the turntable page"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The arrows' forces are the motion's: on the table, friction, Coriolis, centrifugal and the
/// Euler force sum to the relative acceleration du/dτ (a central difference of the run's own
/// dense output); riding, they balance.
#[test]
fn the_forces_on_a_table_speeding_up_are_those_that_move_the_coin() {
    use turntable::engine::Settings;
    use turntable::engine::spinup::{Ramp, SpinRun};
    let ramp = Ramp {
        rate: 0.2,
        omega0: 0.0,
    };
    let mut run = SpinRun::new(ramp, 0.5, Settings::dp54(1e-12)).unwrap();
    run.run(3.0, false).unwrap();
    let m = Motion::Spin(run.clone());
    let s = m.state_at(3.0).unwrap();
    let [fr, co, cf, eu] = m.forces(&s, false);
    assert!((fr + co + cf + eu).length() < 1e-15, "riding: balanced");
    assert_eq!(co, DVec2::ZERO);
    assert!((cf - 0.36 * DVec2::new(0.5, 0.0)).length() < 1e-15, "{cf}");
    assert!((eu - DVec2::new(0.0, -0.1)).length() < 1e-15, "{eu}");
    // Sliding: friction at full strength against u, and the sum is du/dτ on the table.
    run.run(7.3, false).unwrap();
    let m = Motion::Spin(run.clone());
    let (t, h) = (run.tau(), 1e-4);
    let at = |tau: f64| m.state_at(tau).unwrap();
    let u = |tau: f64| m.u(&at(tau));
    let dudt = (u(t) - u(t - 2.0 * h)) / (2.0 * h);
    let [fr, co, cf, eu] = m.forces(&at(t - h), false);
    assert!((fr.length() - 1.0).abs() < 1e-12, "{fr}");
    assert!(fr.dot(u(t - h)) < 0.0);
    assert!(
        (dudt - (fr + co + cf + eu)).length() < 1e-6,
        "{dudt} against {}",
        fr + co + cf + eu
    );
}

/// `E` writes what the screen shows of a spun-up table: the Euler force's arrow in the
/// rotating frame, and the slip's readouts' run (the particle's mark, its status).
#[test]
fn the_exported_page_is_the_spun_up_table_on_screen() {
    let mut a = spin();
    for k in ['f', 'a'] {
        key(&mut a, KeyCode::Char(k));
    }
    for _ in 0..60 {
        a.tick();
    }
    let fig = turntable::plot::page::table::figure(&a, "spin".into());
    let svg = turntable::plot::to_svg(&fig);
    assert!(
        svg.contains("eu (Euler)"),
        "the Euler force's arrow is exported"
    );
    assert!(svg.contains("cf (centrifugal)") && svg.contains("fr (friction)"));
    let on_screen = Picture::in_frame(&a, Frame::Table);
    let p = on_screen.point.unwrap();
    assert!(
        (p.at - DVec2::new(0.5, 0.0)).length() < 1e-14,
        "held still on the table"
    );
    assert_eq!(
        p.arrows.len(),
        3,
        "fr, cf, eu while riding (no Coriolis at u = 0)"
    );
}

/// Whatever a constant-Ω scene left behind (the paper's RK2 beside it, pins, another page,
/// another release), `7` opens the spin-up as a fresh one opens: every piece of per-scene state
/// is reset or refused, as the scene file's check demands of a `[spin]` scene.
#[test]
fn the_spin_preset_opens_the_same_whatever_came_before() {
    use proptest::prelude::*;
    let keys = prop::collection::vec(
        prop::sample::select(vec!['c', 'b', '\t', 'x', 'X', '1', '2', '3', '4', '5', '6']),
        0..12,
    );
    let mut fresh = spin();
    let expected = without_last_line(&common_render(&mut fresh));
    let config = ProptestConfig {
        cases: 48,
        rng_seed: proptest::test_runner::RngSeed::Fixed(7),
        failure_persistence: None,
        ..ProptestConfig::default()
    };
    proptest!(config, |(keys in keys)| {
        let mut a = App::new(Scene::preset("C").unwrap());
        for k in keys {
            key(&mut a, if k == '\t' { KeyCode::Tab } else { KeyCode::Char(k) });
            a.tick();
        }
        key(&mut a, KeyCode::Char('7'));
        prop_assert!(a.paper().is_none() && a.pins().is_empty());
        prop_assert_eq!(a.view().page, Page::Turntable);
        prop_assert_eq!(without_last_line(&common_render(&mut a)), expected.clone());
    });
}

/// A screen without its notice line (what the key said differs, what it shows must not).
fn without_last_line(screen: &str) -> String {
    let lines: Vec<&str> = screen.lines().collect();
    lines[..lines.len() - 1].join("\n")
}
