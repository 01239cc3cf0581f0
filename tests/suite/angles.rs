//! One angle convention for people (issue 29 item 10): an angle a person reads (φ, θ, Θ, ψ) is
//! a multiple of π in [0, 2π), said by `present::angle` to four decimals, on screen, in plain
//! mode, in notices, figure titles and on the axes of angles; JSON and CSV keep radians.

use crate::common::seeded;
use crossterm::event::{KeyCode, KeyModifiers};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};
use turntable::app::{App, Chord};
use turntable::plot::Scale;
use turntable::present::{ANGLE_DECIMALS, angle};
use turntable::scene::Scene;
use turntable::session::Explorer;
use turntable::theme::Theme;

/// An angle's text read back, in units of π.
fn read(text: &str) -> f64 {
    match text {
        "0" => 0.0,
        "π" => 1.0,
        _ => text
            .strip_suffix('π')
            .and_then(|x| x.parse().ok())
            .unwrap_or_else(|| panic!("not a multiple of π: {text:?}")),
    }
}

/// How far apart two directions are (radians, in [0, π]).
fn apart(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

proptest! {
    #![proptest_config(seeded(2000))]

    /// Read back, an angle is the direction it was to within half its last decimal of π,
    /// in [0, 2π); a whole turn more or less, or the angle's negative, reads as the direction
    /// it is. Over the whole range φ may take (|φ| ≤ 1e6 rad).
    #[test]
    fn an_angle_reads_back_as_its_direction(rad in -1e6f64..1e6) {
        let half = 0.5 * 10f64.powi(-(ANGLE_DECIMALS as i32)) * PI;
        // The remainder of 1e6 rad mod 2π keeps all but ~1e-10 of its digits.
        let slack = 1e-9;
        let text = angle(rad);
        prop_assert!(!text.contains("NaN") && !text.contains("inf") && !text.is_empty());
        prop_assert!(text == "0" || text.ends_with('π'), "{}", text);
        let x = read(&text);
        prop_assert!((0.0..2.0).contains(&x), "{} for {}", text, rad);
        prop_assert!(apart(x * PI, rad) <= half + slack, "{} for {}", text, rad);
        for turned in [rad + TAU, rad - TAU] {
            prop_assert!(apart(read(&angle(turned)) * PI, rad) <= half + slack);
        }
        prop_assert!(apart(read(&angle(-rad)) * PI, -rad) <= half + slack);
    }
}

#[test]
fn nothing_but_a_finite_angle_is_said_as_one() {
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(angle(x), "—");
    }
}

fn session(scene: &str, w: u16, h: u16) -> Explorer<ratatui::backend::TestBackend> {
    let app = App::new(Scene::preset(scene).unwrap());
    Explorer::headless(app, Theme::builtin("dark").unwrap(), w, h, false)
}

fn screen(s: &mut Explorer<ratatui::backend::TestBackend>) -> String {
    turntable::ui::export::plain_text(s.screen())
}

/// The escape-speed page and the outcome map put φ on a radian axis ticked in π, on screen
/// and in the SVG `E` writes, and the axis says its unit.
#[test]
fn the_phi_axes_tick_in_pi() {
    let mut s = session("C", 100, 30);
    for (tabs, page) in [(2, "escape speed"), (1, "outcome map")] {
        for _ in 0..tabs {
            s.press("tab".parse().unwrap());
        }
        let text = screen(&mut s);
        assert!(text.contains(page), "{text}");
        // The tick row: 0, 0.5π, π, 1.5π, 2π, left to right, nothing else.
        let ticks = text
            .lines()
            .find(|l| l.contains("0.5π"))
            .unwrap_or_else(|| panic!("no ticks in π:\n{text}"));
        let labels: Vec<&str> = ticks
            .trim_matches(|c| c == '│' || c == ' ')
            .split('│')
            .next()
            .unwrap()
            .split_whitespace()
            .collect();
        assert_eq!(labels, ["0", "0.5π", "π", "1.5π", "2π"], "{text}");
        assert!(text.contains("φ (rad"), "{text}");
        let (fig, _) = turntable::plot::page::figure(&s.app);
        let panel = &fig.panels[0];
        assert_eq!(panel.x_scale, Scale::Angle);
        assert!(panel.x_label.starts_with("φ (rad"), "{}", panel.x_label);
        let svg = turntable::plot::to_svg(&fig);
        let x_ticks: Vec<&str> = svg
            .lines()
            .filter(|l| l.contains("class=\"x-tick\""))
            .filter_map(text_of)
            .collect();
        assert_eq!(x_ticks, ["0", "0.5π", "π", "1.5π", "2π"], "{svg}");
    }
}

/// The text of an SVG line's `<text>` or `<title>` element, if it has one.
fn text_of(line: &str) -> Option<&str> {
    let end = line.find("</text>").or_else(|| line.find("</title>"))?;
    let start = line[..end].rfind('>')? + 1;
    Some(&line[start..end])
}

/// Every text an SVG shows a person (its title, labels, ticks), one a line.
fn svg_texts(svg: &str) -> String {
    svg.lines()
        .filter_map(text_of)
        .collect::<Vec<_>>()
        .join("\n")
}

/// Case D's φ = 1.2π in radians (3.7699…, or −0.8π = −2.513… as the app holds it), as it
/// was in the SVG's title, or in degrees, as it was in the SI readouts.
const RADIANS_OF_D: [&str; 5] = ["3.77", "3.769", "-0.8π", "-2.513", "216°"];

fn no_radians(what: &str, text: &str) {
    for raw in RADIANS_OF_D {
        assert!(!text.contains(raw), "{what} shows {raw}:\n{text}");
    }
}

/// Case D (φ = 1.2π) shows its φ as 1.2π wherever a person reads it, never in radians: the
/// panel at 80×24 and 120×40 (SI units on too), a notice after φ is set, the SVG an export
/// writes, plain mode's lines.
#[test]
fn no_person_facing_text_of_case_d_shows_radians() {
    for (w, h) in [(80, 24), (120, 40)] {
        let mut s = session("D", w, h);
        let text = screen(&mut s);
        assert!(text.contains("φ 1.2π"), "{text}");
        no_radians("the panel", &text);
        s.press(Chord::new(KeyCode::Char('u'), KeyModifiers::NONE));
        let text = screen(&mut s);
        assert!(text.contains("r0"), "SI units on:\n{text}");
        no_radians("the panel in SI", &text);
        s.press(":".parse().unwrap());
        for c in "phi 1.2pi".chars() {
            s.press(Chord::new(KeyCode::Char(c), KeyModifiers::NONE));
        }
        s.press("enter".parse().unwrap());
        let notice = s.app.notice().clone().unwrap_or_default();
        assert!(notice.contains("φ = 1.2π"), "{notice}");
        no_radians("the notice", &notice);
        no_radians("the screen with the notice", &screen(&mut s));
        // Every page's SVG, as `E` writes it: its title and every text in it, the page's
        // numbers computed.
        for _ in 0..5 {
            no_radians("a page", &screen(&mut s));
            let (fig, _) = turntable::plot::page::figure(&s.app);
            assert!(fig.title.contains("φ = 1.2π"), "{}", fig.title);
            no_radians("an SVG", &svg_texts(&turntable::plot::to_svg(&fig)));
            s.press("tab".parse().unwrap());
        }
    }
    let app = App::new(Scene::preset("D").unwrap());
    let th = Theme::builtin("mono").unwrap();
    let mut said = turntable::ui::plain::opening(&app);
    said.extend(turntable::ui::panel::lines(&app, &th).iter().map(|l| {
        l.spans
            .iter()
            .map(|s| s.content.as_ref())
            .collect::<String>()
    }));
    let said = said.join("\n");
    assert!(said.contains("φ = 1.2π"), "{said}");
    no_radians("plain mode", &said);
}
