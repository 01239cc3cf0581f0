//! Both frames at once (`%`, issue 29 item 8): the same run at the same τ in a lab canvas and
//! a rotating canvas, each titled by its frame, each with the particle, and a click mapped
//! through the canvas it lands in.

use crate::common::render;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEventKind};
use turntable::app::App;
use turntable::app::testing::Testing as _;
use turntable::engine::Frame;
use turntable::scene::Scene;

fn split_app() -> App {
    let mut a = App::new(Scene::preset("C").unwrap());
    for _ in 0..60 {
        a.tick();
    }
    a.handle_key(KeyEvent::new(KeyCode::Char('%'), KeyModifiers::NONE));
    a
}

/// The text of `area` on `screen`.
fn cells(screen: &str, area: ratatui::layout::Rect) -> String {
    screen
        .lines()
        .skip(usize::from(area.y))
        .take(usize::from(area.height))
        .map(|l| {
            l.chars()
                .skip(usize::from(area.x))
                .take(usize::from(area.width))
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn both_frames_are_drawn_titled_with_the_particle_in_each() {
    for (w, h) in [(80, 24), (120, 40), (60, 20), (40, 12)] {
        let mut a = split_app();
        let screen = render(&mut a, w, h);
        let g = a.geoms_for_tests();
        assert_eq!(g.len(), 2, "{w}×{h}");
        assert_eq!((g[0].frame, g[1].frame), (Frame::Lab, Frame::Table));
        assert!(screen.contains("lab frame"), "{w}×{h}\n{screen}");
        assert!(screen.contains("rotating frame"), "{w}×{h}\n{screen}");
        for k in g {
            let inside = cells(&screen, k.area);
            assert!(inside.contains('●'), "{w}×{h} {:?}\n{screen}", k.frame);
        }
    }
}

#[test]
fn the_split_is_side_by_side_where_that_shows_the_larger_table() {
    use ratatui::layout::Rect;
    use turntable::ui::canvas::split;
    // 80×24 and 120×40: beside; the 30-column canvas beside the panel at 60×20: stacked.
    let [a, b] = split(Rect::new(0, 1, 50, 21));
    assert_eq!((a.y, b.y, a.width), (1, 1, 25));
    let [a, b] = split(Rect::new(0, 1, 30, 17));
    assert_eq!((a.x, b.x, a.width), (0, 0, 30));
    assert!(b.y > a.y);
}

#[test]
fn a_click_in_the_second_canvas_places_the_release_there() {
    let mut a = split_app();
    render(&mut a, 80, 24);
    let g = a.geoms_for_tests()[1];
    assert_eq!(g.frame, Frame::Table);
    // The cell under world point (0.8, 0) of the rotating canvas.
    let (col, row) = crate::common::cell_under(&g, 0.8, 0.0);
    let ev = crate::common::mouse;
    a.handle_mouse(ev(MouseEventKind::Down(MouseButton::Left), col, row));
    assert!((a.initial().xi0 - 0.8).abs() < 0.1, "{}", a.initial().xi0);
    // A drag straight up in the rotating canvas: u0 along +y, whatever the lab makes of it.
    a.handle_mouse(ev(MouseEventKind::Drag(MouseButton::Left), col, row - 3));
    a.handle_mouse(ev(MouseEventKind::Up(MouseButton::Left), col, row - 3));
    let phi = a.initial().phi;
    assert!(
        (phi - std::f64::consts::FRAC_PI_2).abs() < 0.3,
        "φ = {phi}: the drag read in the rotating frame"
    );
    // Both canvases show the release after the click.
    let screen = render(&mut a, 80, 24);
    assert_eq!(a.geoms_for_tests().len(), 2, "{screen}");
}

#[test]
fn the_export_has_a_panel_per_frame_and_a_saved_scene_keeps_the_split() {
    let a = split_app();
    let (fig, _) = turntable::plot::page::figure(&a);
    let titles: Vec<_> = fig.panels.iter().map(|p| p.title.as_str()).collect();
    assert_eq!(
        titles,
        [
            "the turntable in the lab frame",
            "the turntable in the rotating frame (the table's)"
        ]
    );
    let saved = a.view().saved(a.speed());
    assert!(saved.split);
    assert!(turntable::app::view::View::of(Some(saved)).split);
}
