//! The arrows that explain (`a`, `A`, `i`): friction opposes the slip velocity, the net force
//! is the forces' sum (the equations' acceleration), and each reads without colour.

use crate::common;
use common::render;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use turntable::app::App;
use turntable::app::testing::Testing as _;
use turntable::engine::{Frame, Outcome};
use turntable::scene::Scene;
use turntable::ui::canvas::{ForceArrow, arrows};

fn key(app: &mut App, c: char) {
    app.handle_key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE));
}

fn find<'a>(all: &'a [ForceArrow], label: &str) -> &'a ForceArrow {
    all.iter()
        .find(|a| a.label == label)
        .unwrap_or_else(|| panic!("no {label} in {all:?}"))
}

#[test]
fn friction_opposes_the_slip_velocity_and_the_net_force_is_the_acceleration() {
    let mut a = App::new(Scene::preset("C").unwrap());
    for _ in 0..30 {
        a.tick();
    }
    for c in ['a', 'A', 'i', 'f'] {
        key(&mut a, c);
    }
    assert_eq!(a.view().frame, Frame::Table);
    let s = a.sim().now();
    let all = arrows(&a, 2.0, 0.5);
    let (fr, u, net) = (find(&all, "fr"), find(&all, "u"), find(&all, "net"));
    // Slipping: friction is −û (Eq. 2), exactly against the velocity relative to the table.
    let cos = fr.vec.normalize().dot(u.vec.normalize());
    assert!((cos + 1.0).abs() < 1e-12, "{cos}");
    assert!((u.vec - s.u() * 0.5).length() < 1e-15);
    // The net force is du/dτ of the rotating frame's equations, at the forces' scale.
    let y = Frame::Table.from_state(&s);
    let accel = Frame::Table.rhs(y).w;
    let k = fr.vec.length(); // |friction| = 1 while slipping
    assert!(
        (net.vec - accel * k).length() < 1e-12,
        "{:?} vs {:?}",
        net.vec,
        accel * k
    );
    let sum: glam::DVec2 = ["fr", "co", "cf"].iter().map(|l| find(&all, l).vec).sum();
    assert!((sum - net.vec).length() < 1e-12);
    // Labelled on screen and named in the legend, colour aside (the mono theme).
    let screen = render(&mut a, 100, 30);
    for w in ["net net force", "u  velocity rel. table", "fr friction"] {
        assert!(screen.contains(w), "{w}\n{screen}");
    }
    // In the lab: the lab velocity, and the net force is friction alone.
    key(&mut a, 'f');
    let all = arrows(&a, 2.0, 0.5);
    assert!((find(&all, "v").vec - a.sim().now().v * 0.5).length() < 1e-15);
    assert!((find(&all, "net").vec - find(&all, "fr").vec).length() < 1e-15);
    let screen = render(&mut a, 100, 30);
    assert!(screen.contains("v  velocity (lab)"), "{screen}");
    // Both labels at one head: neither covers the other.
    let canvas: String = screen
        .lines()
        .map(|l| l.chars().take(70).collect::<String>())
        .collect();
    assert!(canvas.contains("net") && canvas.contains("fr"), "{screen}");
}

#[test]
fn stuck_the_forces_balance_and_nothing_moves_on_the_table() {
    let mut a = App::new(Scene::preset("B").unwrap());
    for _ in 0..400 {
        a.tick();
    }
    assert_eq!(a.sim().outcome_now(), Outcome::Stuck);
    for c in ['a', 'A', 'i', 'f'] {
        key(&mut a, c);
    }
    let all = arrows(&a, 2.0, 0.5);
    let labels: Vec<&str> = all.iter().map(|a| a.label).collect();
    // Static friction holds the centrifugal pull: no Coriolis, no net force, no u.
    assert_eq!(labels, ["fr", "cf"]);
    let screen = render(&mut a, 80, 24);
    assert!(
        screen.contains("net force 0: balanced") && screen.contains("u = 0"),
        "{screen}"
    );
    // The lab sees it ride the table: v = Ω × r, net force centripetal (friction).
    key(&mut a, 'f');
    let all = arrows(&a, 2.0, 0.5);
    let (v, net) = (find(&all, "v").vec, find(&all, "net").vec);
    assert!(v.normalize().dot(net.normalize()).abs() < 1e-9);
    assert!(net.normalize().dot(a.sim().now().r.normalize()) < -1.0 + 1e-9);
    for (w, h) in [(40, 12), (80, 24), (200, 60)] {
        render(&mut a, w, h);
        a.check_invariants().unwrap();
    }
    // The arrows shown are saved with the scene's view.
    let text = a.current_scene().to_toml();
    assert!(
        text.contains("net_force = true") && text.contains("velocity = true"),
        "{text}"
    );
    let back: Scene = toml::from_str(&text).unwrap();
    let b = App::new(back);
    assert!(b.view().forces && b.view().net_force && b.view().velocity);
    assert!(!text.contains("speed"), "×1 is not saved: {text}");
    // So is the speed (slow motion for a class), and a bad one in a file is refused.
    a.tell_speed(0.25);
    let text = a.current_scene().to_toml();
    assert!(text.contains("speed = 0.25"), "{text}");
    let path = std::env::temp_dir().join(format!("turntable-speed-{}.toml", std::process::id()));
    std::fs::write(&path, &text).unwrap();
    let back = Scene::load(path.to_str().unwrap()).unwrap();
    assert_eq!(App::new(back).speed(), 0.25);
    std::fs::write(&path, text.replace("speed = 0.25", "speed = 0.3")).unwrap();
    let err = Scene::load(path.to_str().unwrap()).unwrap_err().to_string();
    assert!(
        err.ends_with("[view] speed must be a power of two from 1/64 to 256, got 0.3"),
        "{err}"
    );
    std::fs::remove_file(&path).unwrap();
}
