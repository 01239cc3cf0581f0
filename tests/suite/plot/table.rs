//! `E` on the turntable: the figure is made from the description the canvas paints, so the SVG
//! carries what the screen shows — the body's bar and path, the table's rim marks, the stuck
//! mark where the particle rides, each pin's name, the paper's run, the step marks.

use super::{Tag, axis, named, parse, points, with_class};
use crate::common;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use glam::DVec2;
use turntable::app::App;
use turntable::app::testing::Testing as _;
use turntable::engine::Status;
use turntable::engine::model::rotate;
use turntable::scene::Scene;

/// Presses `keys`, one character each, and carries out their effects as the terminal does.
fn press(app: &mut App, keys: &str) {
    for k in keys.chars().filter(|k| !k.is_whitespace()) {
        let effects = app.handle_key(KeyEvent::new(KeyCode::Char(k), KeyModifiers::NONE));
        turntable::session::carry_out(app, effects);
    }
}

fn ticks(app: &mut App, n: usize) {
    for _ in 0..n {
        app.tick();
    }
}

/// The turntable as `E` writes it after drawing it at 120×40, parsed.
fn export(app: &mut App, tag: &str) -> Vec<Tag> {
    let dir = std::env::temp_dir().join(format!("turntable-table-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    app.tell_save_path(dir.join("turntable-scene.toml"));
    common::render(app, 120, 40);
    press(app, "E");
    let svg = std::fs::read_to_string(dir.join("turntable-table-1.svg")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    parse(&svg)
}

/// The labels written beside marks.
fn labels(tags: &[Tag]) -> Vec<&str> {
    with_class(tags, "mark-label")
        .iter()
        .map(|t| t.text.as_str())
        .collect()
}

/// In data units: the point mark whose label starts with `label`.
fn mark_at(tags: &[Tag], label: &str) -> DVec2 {
    let (x, y) = (axis(tags, "x-tick"), axis(tags, "y-tick"));
    let k = tags
        .iter()
        .position(|t| t.attr("class") == Some("mark-label") && t.text.starts_with(label))
        .unwrap_or_else(|| panic!("no mark {label}: {:?}", labels(tags)));
    let c = &tags[k - 1];
    assert_eq!(c.name, "circle", "{label}");
    DVec2::new(x(c.num("cx")), y(c.num("cy")))
}

/// In data units: the points of the one line named `name`.
fn line(tags: &[Tag], name: &str) -> Vec<DVec2> {
    let (x, y) = (axis(tags, "x-tick"), axis(tags, "y-tick"));
    points(named(tags, name))
        .into_iter()
        .map(|(px, py)| DVec2::new(x(px), y(py)))
        .collect()
}

fn near(a: DVec2, b: DVec2) -> bool {
    a.distance(b) < 1e-4
}

/// A body scene: the bar between its two masses where they are, its centre (⊕) and its path,
/// and the table's three rim marks at its angle (the lab: τ).
#[test]
fn a_body_scene_exports_its_bar_its_path_and_the_tables_turn() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/replay/body.toml");
    let mut app = App::new(Scene::load(scene).unwrap());
    ticks(&mut app, 12);
    let tags = export(&mut app, "body");
    let rod = app.rod().unwrap();
    let s = rod.at(app.sim().now().tau).unwrap();
    let bar = line(&tags, "the body");
    let ends = s.contacts(rod.l).map(|c| rotate(c, s.tau));
    assert!(
        bar.len() == 2 && near(bar[0], ends[0]) && near(bar[1], ends[1]),
        "{bar:?} {ends:?}"
    );
    assert!(near(mark_at(&tags, "⊕ body"), rotate(s.q, s.tau)));
    let path = line(&tags, "the body's centre");
    assert!(path.len() > 1 && near(path[0], rod.states[0].q));
    let rim: Vec<&Tag> = with_class(&tags, "series")
        .into_iter()
        .filter(|t| t.attr("data-name") == Some("the table's turn"))
        .collect();
    assert_eq!(rim.len(), 3, "three marks, each its own line");
    let (x, y) = (axis(&tags, "x-tick"), axis(&tags, "y-tick"));
    let (px, py) = *points(rim[0]).last().unwrap();
    let r = 1.5f64.max(app.initial().xi0 * 1.2);
    assert!(near(DVec2::new(x(px), y(py)), rotate(DVec2::X * r, s.tau)));
    assert!(labels(&tags).contains(&"↺ table"));
}

/// Stuck, in the lab: the particle rides the table, and so does the mark where it stuck — at
/// the particle, not where the table's point was when it stuck.
#[test]
fn a_stuck_run_in_the_lab_marks_where_the_particle_rides() {
    let mut app = App::new(Scene::preset("B").unwrap());
    ticks(&mut app, 200);
    let Status::Stuck { tau, q } = app.sim().status() else {
        panic!("B sticks")
    };
    let now = app.sim().now();
    assert!(now.tau > tau + 1.0);
    let tags = export(&mut app, "stuck");
    let at = mark_at(&tags, "× stuck τ=");
    assert!(near(at, now.r), "{at} {}", now.r);
    assert!(at.distance(rotate(q, tau)) > 0.1);
    assert!(near(mark_at(&tags, "stuck at ξ ="), now.r));
}

/// Pins carry their names (marker and label) at their ends and their markers along their
/// paths; with `c`, the paper's run to its head.
#[test]
fn pins_carry_their_names_and_c_the_papers_run() {
    let mut app = App::new(Scene::default_scene());
    press(&mut app, "1 b 2 b 3 b 4 b c");
    ticks(&mut app, 20);
    assert_eq!(app.pins().len(), 4);
    let tags = export(&mut app, "pins");
    let said = labels(&tags);
    for p in app.pins() {
        let name = format!("{}{}", p.marker, p.spec.label.as_str());
        assert!(said.contains(&name.as_str()), "{name}: {said:?}");
        assert!(!line(&tags, &name).is_empty());
        let along = said.iter().filter(|l| **l == p.marker.to_string()).count();
        assert!((1..=3).contains(&along), "{name}: markers along its path");
    }
    let paper = app.paper().unwrap().now();
    let run = line(&tags, "the paper's RK2 run (c)");
    assert!(near(*run.last().unwrap(), paper.r));
    assert!(near(mark_at(&tags, "paper's RK2"), paper.r));
}

/// Step mode (`n`): each step's end so far, as the canvas marks them.
#[test]
fn step_mode_exports_the_step_marks() {
    let mut app = App::new(Scene::preset("C").unwrap());
    ticks(&mut app, 108);
    press(&mut app, "nnnnnnnn");
    let tags = export(&mut app, "steps");
    let (x, y) = (axis(&tags, "x-tick"), axis(&tags, "y-tick"));
    let k = tags
        .iter()
        .position(|t| t.attr("data-name") == Some("integrator steps"))
        .unwrap();
    let dots: Vec<DVec2> = tags[k + 1..]
        .iter()
        .take_while(|t| t.name == "circle")
        .map(|t| DVec2::new(x(t.num("cx")), y(t.num("cy"))))
        .collect();
    let marks = &app.sim().step_marks;
    assert!(
        !marks.is_empty() && dots.len() == marks.len(),
        "{}",
        dots.len()
    );
    assert!(dots.iter().zip(marks).all(|(d, m)| near(*d, m.r)));
}
