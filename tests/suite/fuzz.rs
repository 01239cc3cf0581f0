//! Random keys (the keymap's, plus random characters and modifiers), random ticks, mouse
//! events and resizes (down to 1×1 and 0×0) through `App` and `ui::draw`, from fixed seeds:
//! no panic, `check_invariants()` after every step, and no NaN or infinity on any screen.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use turntable::app::testing::Testing as _;
use turntable::app::{Action, App, KEYMAP};
use turntable::scene::{PRESETS, Scene};
use turntable::session::Explorer;
use turntable::theme::{BUILTIN, Theme};
use turntable::ui::export::plain_text;

use crate::common;
use turntable::rng::SplitMix64 as Rng;

/// "NaN" or "inf" as a word (Rust's spelling of non-finite floats), anywhere on screen.
fn non_finite(screen: &str) -> Option<&str> {
    screen.lines().find(|line| {
        line.contains("NaN")
            || line.match_indices("inf").any(|(i, _)| {
                let before = line[..i].chars().next_back();
                let after = line[i + 3..].chars().next();
                !before.is_some_and(char::is_alphabetic) && !after.is_some_and(char::is_alphabetic)
            })
    })
}

fn random_key(rng: &mut Rng) -> KeyEvent {
    match rng.below(10) {
        0..=6 => KEYMAP[rng.below(KEYMAP.len() as u64) as usize]
            .chord
            .event(),
        7 => {
            let c = char::from_u32(rng.below(0x250) as u32).unwrap_or('?');
            let m = rng.pick(&[
                KeyModifiers::NONE,
                KeyModifiers::SHIFT,
                KeyModifiers::ALT,
                KeyModifiers::CONTROL,
            ]);
            KeyEvent::new(KeyCode::Char(c), m)
        }
        8 => KeyEvent::new(
            rng.pick(&[
                KeyCode::Up,
                KeyCode::Down,
                KeyCode::Left,
                KeyCode::Right,
                KeyCode::Enter,
                KeyCode::Tab,
                KeyCode::Backspace,
                KeyCode::F(1),
                KeyCode::Home,
            ]),
            rng.pick(&[KeyModifiers::NONE, KeyModifiers::SHIFT]),
        ),
        // Bursts of the value editors, to push ξ0, φ and v0 to extremes.
        _ => {
            let c = rng.pick(&['x', 'X', 'v', 'V', 'p', 'P', '<', '>', ']', '[', '+', '-']);
            KeyEvent::new(
                KeyCode::Char(c),
                rng.pick(&[KeyModifiers::NONE, KeyModifiers::ALT]),
            )
        }
    }
}

fn fuzz(seed: u64, steps: usize) {
    let mut rng = Rng(seed);
    let scene = Scene::preset(rng.pick(&PRESETS)).unwrap();
    let theme = Theme::builtin(rng.pick(&BUILTIN)).unwrap();
    let mut app = App::new(scene);
    let dir = std::env::temp_dir().join(format!("turntable-fuzz-{}", std::process::id()));
    app.tell_save_path(dir.join("scene.toml"));
    let mut s = Explorer::headless(app, theme, 80, 24, false);
    let sizes = [
        (0, 0),
        (1, 1),
        (0, 5),
        (7, 0),
        (39, 11),
        (40, 12),
        (59, 20),
        (80, 24),
    ];
    for i in 0..steps {
        let what = rng.below(100);
        match what {
            0..=4 => {
                let (w, h) = if rng.below(2) == 0 {
                    rng.pick(&sizes)
                } else {
                    (rng.below(140) as u16, rng.below(50) as u16)
                };
                s.resize(w, h);
            }
            5..=9 => {
                let kind = rng.pick(&[
                    MouseEventKind::Down(MouseButton::Left),
                    MouseEventKind::Drag(MouseButton::Left),
                    MouseEventKind::Up(MouseButton::Left),
                    MouseEventKind::ScrollUp,
                    MouseEventKind::ScrollDown,
                ]);
                let ev = MouseEvent {
                    kind,
                    column: rng.below(150) as u16,
                    row: rng.below(60) as u16,
                    modifiers: KeyModifiers::NONE,
                };
                s.mouse(ev).unwrap();
            }
            10..=24 => {
                for _ in 0..rng.below(10) {
                    s.tick();
                }
            }
            _ => {
                let k = random_key(&mut rng);
                // Quitting ends a session: a key that quits is left out, and it carries on.
                let before = s.app.clone();
                s.key(k);
                if s.app.should_quit() {
                    s.app = before;
                }
            }
        }
        if let Err(e) = s.app.check_invariants() {
            panic!("seed {seed}, step {i}: {e}");
        }
        let screen = plain_text(s.screen());
        if let Some(line) = non_finite(&screen) {
            panic!("seed {seed}, step {i}: non-finite readout: {line}\n{screen}");
        }
    }
}

/// Seeds × steps of the key fuzzer: `TURNTABLE_FUZZ=SEEDS` (each 1500 steps) runs more, or
/// fewer; the default, 4, is what CI runs (~3 s of CPU; a seed costs ~0.7 s, and the suite's
/// time is its tests' CPU time over two cores).
#[test]
fn random_keys_and_resizes_keep_the_app_valid() {
    let seeds = common::budget("TURNTABLE_FUZZ", 4);
    for seed in 0..seeds {
        fuzz(seed, 1500);
    }
}

#[test]
fn non_finite_detector() {
    assert!(non_finite("ξ = NaN").is_some());
    assert!(non_finite("v = -inf").is_some());
    assert!(non_finite("τ inf").is_some());
    assert!(non_finite("information infinity").is_none());
    assert!(non_finite("ξ = 0.5").is_none());
}

/// From scenes at the bounds (ξ0 and v0 at 0 and at `Initial::MAX`, every release mode, with
/// and without friction), every key of the keymap twice (plain and with Alt) and clicks and
/// drags far out: edits clamp to the valid range, nothing panics.
#[test]
fn edits_at_the_bounds_clamp() {
    use turntable::engine::{Initial, Release};
    let max = Initial::MAX;
    for (xi0, v0) in [(max, 0.0), (0.0, max), (max, max), (0.0, 0.0)] {
        for release in [Release::Velocity, Release::TableRest, Release::LabRest] {
            for frictionless in [false, true] {
                let mut scene = Scene::default_scene();
                scene.initial = Initial {
                    xi0,
                    v0,
                    release,
                    frictionless,
                    ..scene.initial
                };
                let mut s = Explorer::headless(
                    App::new(scene),
                    Theme::builtin("mono").unwrap(),
                    80,
                    24,
                    false,
                );
                s.app
                    .tell_save_path(std::env::temp_dir().join("turntable-never-written.toml"));
                for b in KEYMAP {
                    let mut k = b.chord.event();
                    // Not the keys that write files or open the name prompt (whose letters
                    // would then be typed, not pressed).
                    if matches!(
                        b.action,
                        Action::Save | Action::SaveAs | Action::ExportSvg | Action::Quit
                    ) {
                        continue;
                    }
                    for alt in [false, true] {
                        if alt {
                            k.modifiers |= KeyModifiers::ALT;
                        }
                        let before = s.app.clone();
                        s.key(k);
                        if s.app.should_quit() {
                            s.app = before;
                        }
                        s.tick();
                        let i = s.app.initial();
                        assert!(
                            (0.0..=max).contains(&i.xi0) && (0.0..=max).contains(&i.v0),
                            "{xi0} {v0} {release:?}: {:?} gave {i:?}",
                            b.help
                        );
                    }
                }
                for (col, row) in [(0, 0), (79, 23), (40, 12), (2, 20)] {
                    for kind in [
                        MouseEventKind::Down(MouseButton::Left),
                        MouseEventKind::Drag(MouseButton::Left),
                        MouseEventKind::Up(MouseButton::Left),
                    ] {
                        let ev = MouseEvent {
                            kind,
                            column: col,
                            row,
                            modifiers: KeyModifiers::NONE,
                        };
                        s.mouse(ev).unwrap();
                        s.app.check_invariants().unwrap();
                    }
                }
            }
        }
    }
}
