//! Terminals that are not a modern xterm (issue 19): `TERM=dumb`, a locale that is not UTF-8,
//! the point markers a terminal can show.

use ratatui::symbols::Marker;
use std::process::{Command, Stdio};
use turntable::app::App;
use turntable::cli::MarkerArg;
use turntable::scene::Scene;
use turntable::session::Explorer;
use turntable::theme::Theme;

#[test]
fn term_dumb_is_refused_with_a_clear_message() {
    let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .env("XDG_CONFIG_HOME", "/nonexistent/turntable-tests/config")
        .env("TERM", "dumb")
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("TERM=dumb cannot show the explorer"), "{err}");
    assert!(
        err.contains("`turntable --plain`"),
        "the mode made for it: {err}"
    );
}

#[test]
fn a_locale_that_is_not_utf8_gets_ascii_markers() {
    let with = |vars: &[(&str, &str)]| {
        MarkerArg::from_locale(|k| {
            vars.iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        })
    };
    assert_eq!(with(&[("LANG", "C")]), MarkerArg::Ascii);
    assert_eq!(with(&[("LANG", "POSIX")]), MarkerArg::Ascii);
    assert_eq!(with(&[("LANG", "en_US.UTF-8")]), MarkerArg::Braille);
    assert_eq!(with(&[("LANG", "de_DE.utf8")]), MarkerArg::Braille);
    // LC_ALL wins over LANG, LC_CTYPE too; an empty one does not count.
    assert_eq!(
        with(&[("LC_ALL", "C"), ("LANG", "en_US.UTF-8")]),
        MarkerArg::Ascii
    );
    assert_eq!(
        with(&[("LC_CTYPE", "C.UTF-8"), ("LANG", "C")]),
        MarkerArg::Braille
    );
    assert_eq!(with(&[("LC_ALL", ""), ("LANG", "C")]), MarkerArg::Ascii);
    // No locale named at all: braille (terminals are UTF-8 nearly everywhere).
    assert_eq!(with(&[]), MarkerArg::Braille);
}

/// The default scene's screen at 120×40 with `marker`, after a second of play.
fn screen(marker: Marker) -> String {
    let theme = Theme::builtin("dark").unwrap().with_marker(marker);
    let mut s = Explorer::headless(App::new(Scene::default_scene()), theme, 120, 40, false);
    for _ in 0..30 {
        s.tick();
    }
    s.screen().content.iter().map(|c| c.symbol()).collect()
}

fn braille(s: &str) -> usize {
    s.chars()
        .filter(|c| ('\u{2801}'..='\u{28ff}').contains(c))
        .count()
}

#[test]
fn the_marker_decides_the_glyphs_of_the_drawing() {
    let b = screen(MarkerArg::Braille.marker());
    assert!(braille(&b) > 50, "{}", braille(&b));
    let ascii = screen(MarkerArg::Ascii.marker());
    assert_eq!(braille(&ascii), 0);
    assert!(!ascii.contains('•'));
    assert!(ascii.matches('*').count() > 50);
    let block = screen(MarkerArg::Block.marker());
    assert_eq!(braille(&block), 0);
    assert!(block.matches(['▀', '▄', '█']).count() > 50);
}

/// A terminal that is not UTF-8 gets ASCII only, on every page and the help (box drawing,
/// glyphs and Greek letters were sent as UTF-8 to a `LANG=C` terminal), cell for cell so the
/// layout holds.
#[test]
fn an_ascii_terminal_gets_only_ascii() {
    let theme = Theme::builtin("dark")
        .unwrap()
        .with_marker(MarkerArg::Ascii.marker());
    let mut s = Explorer::headless(App::new(Scene::preset("D").unwrap()), theme, 100, 30, false);
    let mut seen = 0;
    for keys in ["", "\t", "\t", "\t", "\t", "?"] {
        for k in keys.chars() {
            let code = if k == '\t' {
                crossterm::event::KeyCode::Tab
            } else {
                crossterm::event::KeyCode::Char(k)
            };
            s.key(crossterm::event::KeyEvent::from(code));
        }
        for _ in 0..10 {
            s.tick();
        }
        s.draw().unwrap();
        let text: String = s.screen().content.iter().map(|c| c.symbol()).collect();
        let bad: String = text.chars().filter(|c| !c.is_ascii()).collect();
        assert!(bad.is_empty(), "after {keys:?}: {bad}");
        assert!(text.contains("+--") && text.contains('|'), "{text}");
        seen += 1;
    }
    assert_eq!(seen, 6);
}
