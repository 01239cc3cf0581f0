//! Pinned runs (`b`, `B`): a pin is the whole run, computed when pinned at bounded cost, ends
//! where the engine's run ends, shows in both frames and on the time plots, and is saved with
//! the scene.

use crate::common;
use common::render;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use turntable::app::App;
use turntable::app::pages::Page;
use turntable::app::testing::Testing as _;
use turntable::engine::{Initial, Outcome, Run, Settings, Status};
use turntable::pin::{MARKERS, MAX_PINS, PIN_POINTS};
use turntable::scene::Scene;

fn app(scene: &str) -> App {
    App::new(Scene::preset(scene).unwrap())
}

fn key(app: &mut App, c: char) {
    app.handle_key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE));
}

/// Figs. 3–4's four cases pinned, as a class would: 1 b 2 b 3 b 4 b.
fn four_cases() -> App {
    let mut a = app("C");
    for c in ['1', 'b', '2', 'b', '3', 'b', '4', 'b'] {
        key(&mut a, c);
    }
    a
}

#[test]
fn a_pin_ends_where_the_engines_run_stops() {
    let a = four_cases();
    assert_eq!(a.pins().len(), 4);
    for (pin, name) in a.pins().iter().zip(["A", "B", "C", "D"]) {
        assert_eq!(pin.spec.label, name);
        let mut run = Run::new(pin.spec.initial, Settings::default()).unwrap();
        let (out, _) = run.finish(1e3).unwrap();
        assert_eq!(
            (out, pin.outcome),
            (Outcome::Stuck, Outcome::Stuck),
            "{name}"
        );
        let Status::Stuck { tau, q } = run.status() else {
            panic!("{name} not stuck")
        };
        let end = pin.end();
        assert_eq!(end.tau, tau, "{name}");
        assert!(
            (end.q() - q).length() < 1e-12,
            "{name}: {:?} vs {q:?}",
            end.q()
        );
        // The path starts at the release and runs on its grid to the stop.
        assert_eq!(pin.path[0], pin.spec.initial.state());
        assert!(pin.path.windows(2).all(|w| w[0].tau < w[1].tau), "{name}");
        assert!(
            pin.path.len() > 10 && pin.path.len() <= 2 * PIN_POINTS,
            "{name}"
        );
    }
    // C: a converged run stops just inside ξ = 1 (docs/numerics.md).
    let c = a.pins()[2].end().xi();
    assert!(c > 0.99 && c < 1.0, "{c}");
    // Each pin its own marker.
    let markers: Vec<char> = a.pins().iter().map(|p| p.marker).collect();
    assert_eq!(markers, MARKERS[..4]);
}

#[test]
fn an_escaping_pin_is_followed_out_of_view_and_a_long_one_is_bounded() {
    let mut a = app("C");
    a.explore().set_initial(Initial::velocity(0.5, 0.0, 1.2));
    key(&mut a, 'b');
    let p = &a.pins()[0];
    assert_eq!(p.outcome, Outcome::Escaped);
    assert!(p.end().xi() > turntable::app::exploration::view_radius(&p.spec.initial));
    assert_eq!(p.spec.label, "A", "an edited run is lettered");
    // Its end is out of view: labelled where it leaves (on the canvas, left of the panel).
    let screen = render(&mut a, 80, 24);
    let canvas: String = screen
        .lines()
        .map(|l| l.chars().take(50).collect::<String>())
        .collect();
    assert!(canvas.contains("◆A"), "{screen}");
    // μ = 0 at rest in the lab never moves: followed to τ = 200, still bounded.
    key(&mut a, '5');
    key(&mut a, 'F');
    key(&mut a, 'b');
    let p = &a.pins()[1];
    assert_eq!(p.end().tau, turntable::pin::PIN_TAU_MAX);
    assert!(p.path.len() <= 2 * PIN_POINTS, "{}", p.path.len());
    assert_eq!(p.spec.label, "B");
    // The paper's raw RK2 never stops at C: bounded in steps and τ all the same.
    key(&mut a, '3');
    while a.settings().method() != turntable::engine::Method::Rk2Raw {
        key(&mut a, 'm');
    }
    key(&mut a, 'b');
    let p = &a.pins()[2];
    assert!(p.path.len() <= 2 * PIN_POINTS, "{}", p.path.len());
    assert!(p.end().tau <= turntable::pin::PIN_TAU_MAX);
    // At dt = 1e-6 the step budget ends it first, and the notice says so.
    for _ in 0..6 {
        key(&mut a, '>');
    }
    key(&mut a, 'b');
    let p = &a.pins()[3];
    assert_eq!(p.outcome, Outcome::Running);
    assert!(p.end().tau < 1.0, "{}", p.end().tau);
    let n = a.notice().clone().unwrap();
    assert!(n.contains("where a pin's 200000 steps ran out"), "{n}");
}

#[test]
fn a_seventh_pin_replaces_the_oldest_and_b_clears() {
    let mut a = four_cases();
    for c in ['5', 'b', '6', 'b'] {
        key(&mut a, c);
    }
    assert_eq!(a.pins().len(), MAX_PINS);
    key(&mut a, '3');
    key(&mut a, 'x');
    key(&mut a, 'b');
    assert_eq!(a.pins().len(), MAX_PINS);
    let labels: Vec<&str> = a.pins().iter().map(|p| p.spec.label.as_str()).collect();
    // A went, its marker passed on to the newest, which is lettered (an edited C): the first
    // letter no pin holds.
    assert_eq!(labels, ["B", "C", "D", "fig1", "fig2", "A"]);
    assert_eq!(a.pins()[5].marker, MARKERS[0]);
    let n = a.notice().clone().unwrap();
    assert!(n.contains("the oldest, ◆A, unpinned"), "{n}");
    let screen = render(&mut a, 100, 30);
    assert!(screen.contains("unpinned"), "{screen}");
    key(&mut a, 'B');
    assert!(a.pins().is_empty());
    assert!(render(&mut a, 100, 30).contains("6 pins cleared"));
}

#[test]
fn pins_show_in_both_frames_and_on_the_time_plots_at_every_size() {
    let mut a = four_cases();
    for _ in 0..30 {
        a.tick();
    }
    for (w, h) in [(40, 12), (80, 24), (200, 60)] {
        for page in [Page::Turntable, Page::TimePlots] {
            for frame in ['f', 'f'] {
                crate::common::turn_to(&mut a, page);
                key(&mut a, frame);
                let screen = render(&mut a, w, h);
                a.check_invariants().unwrap();
                if w >= 80 {
                    assert!(screen.contains("pins   ◆A ▲B ▼C ◇D"), "{screen}");
                }
                if w >= 200 {
                    // Every pin labelled at its end, left of the panel.
                    let body: String = screen
                        .lines()
                        .map(|l| l.chars().take(usize::from(w) - 30).collect::<String>() + "\n")
                        .collect();
                    for l in ["◆A", "▲B", "▼C", "◇D"] {
                        assert!(body.contains(l), "{w}×{h} {page:?}: {l}\n{screen}");
                    }
                }
            }
        }
    }
    // The time plots span the longest pin (C stops at τ ≈ 5.6), not only the τ on screen.
    crate::common::turn_to(&mut a, Page::TimePlots);
    assert!(a.plot_span() > 5.5 && a.sim().now().tau < 2.0);
    let screen = render(&mut a, 200, 60);
    assert!(screen.contains(" 5 "), "{screen}");
}

#[test]
fn pins_are_saved_with_the_scene_and_load_back() {
    let a = four_cases();
    let dir = std::env::temp_dir().join(format!("turntable-pins-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = a.current_scene().save_new(&dir.join("pins.toml")).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.matches("[[pins]]").count(), 4, "{text}");
    let back = App::new(Scene::load(path.to_str().unwrap()).unwrap());
    assert_eq!(back.pins(), a.pins(), "the same paths, recomputed");
    // Too many pins are refused with the file's name.
    let eight = text.clone() + &text[text.find("[[pins]]").unwrap()..];
    std::fs::write(dir.join("eight.toml"), &eight).unwrap();
    let e = Scene::load(dir.join("eight.toml").to_str().unwrap()).unwrap_err();
    assert!(e.to_string().contains("8 pins, at most 6"), "{e}");
    // A label's controls are cleaned as it is read (`turntable::text`), as any text's.
    let bad = text.replacen("label = \"A\"", "label = \"A\\u0007\"", 1);
    std::fs::write(dir.join("bad.toml"), &bad).unwrap();
    let s = Scene::load(dir.join("bad.toml").to_str().unwrap()).unwrap();
    assert_eq!(s.pins[0].label, "A\u{FFFD}");
    // The second pin's table, with μ = 0.
    let second = text.match_indices("[[pins]]").nth(1).unwrap().0;
    let bad = text[..second].to_string()
        + &text[second..].replacen(
            "[pins.initial]",
            "[pins.units]\nmu = 0.0\nrpm = 33.0\n\n[pins.initial]",
            1,
        );
    std::fs::write(dir.join("units.toml"), &bad).unwrap();
    let e = Scene::load(dir.join("units.toml").to_str().unwrap()).unwrap_err();
    assert!(
        e.to_string()
            .contains("pin 2 (\"B\"): [pins.units] mu must lie in [1e-6, 10], got 0"),
        "{e}\n{bad}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Figs. 3–4 at 80×24: the four presets pinned read apart on the canvas, each by its marker
/// and name at its end (◆A ▲B ▼C ◇D), without colour.
#[test]
fn four_pinned_presets_read_apart_at_80x24() {
    let mut a = App::new(Scene::preset("A").unwrap());
    for k in ['1', 'b', '2', 'b', '3', 'b', '4', 'b'] {
        a.handle_key(KeyEvent::new(KeyCode::Char(k), KeyModifiers::NONE));
    }
    let screen = render(&mut a, 80, 24);
    let canvas: String = screen
        .lines()
        .map(|l| l.chars().take(50).collect::<String>())
        .collect();
    for name in ["◆A", "▲B", "▼C", "◇D"] {
        assert!(canvas.contains(name), "{name}\n{screen}");
    }
}
