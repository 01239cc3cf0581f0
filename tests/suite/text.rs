//! Text from outside — a scene's name and about, a pin's label, a script's `say`, `ask` and
//! `snapshot` labels, a theme's name, the configuration's strings — reaches no output with a
//! control character or an escape sequence in it (issue 33, item 2): it is cleaned once where
//! it is read (`turntable::text`). Each hostile string goes through each input, and each
//! output is checked: replay's text, ANSI and plain snapshots, its asciicast, the CLI's
//! errors. A property test feeds random control-laden strings through the cleaner and through
//! scene and script loading, and counts the cases by class.

use crate::common;
use std::path::{Path, PathBuf};
use std::process::Command;
use turntable::text::{MARK, clean, needs_escape};

/// Injections a crafted file might carry: each clears the screen, retitles the window, writes
/// the clipboard, queries the terminal, or moves the cursor, were it printed raw.
const HOSTILE: [&str; 12] = [
    "a\x1b]0;PWNED\x07b",
    "c\x1b]52;c;SGVsbG8=\x1b\\d",
    "e\x1b[2J\x1b[Hf",
    "g\x1bP1$qm\x1b\\h",
    "i\u{9b}2Jj",
    "k\u{9d}0;t\u{9c}l",
    "bell\x07ring",
    "car\rriage",
    "null\0byte",
    "\u{feff}bom",
    "bidi\u{202e}txt",
    "esc\x1bc reset",
];

fn tmp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("turntable-text-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A TOML string holding `s` exactly (escapes and all).
fn toml_str(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// A scene file whose name and about are `s`, with a pin labelled `pin` (a label is short).
fn scene_text(s: &str, pin: Option<&str>) -> String {
    let q = toml_str(s);
    let mut t = format!("name = {q}\nabout = {q}\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.6\n");
    if let Some(label) = pin {
        let l = toml_str(label);
        t += &format!("\n[[pins]]\nlabel = {l}\n[pins.initial]\nxi0 = 0.5\nphi = 1.0\nv0 = 0.6\n");
    }
    t
}

/// A pin label that retitles the window and rings the bell (two characters once cleaned).
const LABEL: &str = "\x1b]0;PWNED\x07P\x07";

/// A key script that says, asks and labels snapshots with `s` (one line each).
fn script_text(s: &str) -> String {
    format!("resize 100x30\nsay {s}\nsnapshot {s}\ntick 3\nask {s}\nsnapshot\n")
}

/// `out` as a terminal would take it: Ok if nothing but text, line breaks and (with `csi`,
/// for a screen's bytes) the program's own CSI sequences (parameters, then a final letter)
/// and CR LF line ends are in it — no other control character, no OSC, DCS, C1 or invisible
/// mark.
fn clean_output(out: &str, csi: bool) -> Result<(), String> {
    let mut chars = out.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\r' && csi && chars.peek() == Some(&'\n') {
            continue;
        }
        if c == '\x1b' && csi && chars.peek() == Some(&'[') {
            chars.next();
            let mut ok = false;
            for p in chars.by_ref() {
                match p {
                    '0'..='9' | ';' | '?' | ':' => {}
                    'A'..='Z' | 'a'..='z' => {
                        ok = true;
                        break;
                    }
                    _ => break,
                }
            }
            if !ok {
                return Err(format!("a malformed CSI in {out:?}"));
            }
            continue;
        }
        if c != '\n' && needs_escape(c) {
            let at = out.find(c).unwrap_or(0);
            let from = out[..at].char_indices().rev().nth(20).map_or(0, |(i, _)| i);
            return Err(format!(
                "{c:?} reached the output near {:?}",
                &out[from..(at + 8).min(out.len())]
            ));
        }
    }
    Ok(())
}

fn run(args: &[&str], dir: &Path) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .args(args)
        .env("XDG_CONFIG_HOME", common::NO_CONFIG)
        .current_dir(dir)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn the_cleaner_keeps_text_and_marks_what_it_removes() {
    assert_eq!(clean("Fig. 3 C: ξ = 1, φ 0.5π"), "Fig. 3 C: ξ = 1, φ 0.5π");
    for h in HOSTILE {
        let c = clean(h);
        assert!(c.contains(MARK), "{h:?} → {c:?}");
        assert!(!c.chars().any(needs_escape), "{h:?} → {c:?}");
        assert!(
            !c.contains("PWNED") && !c.contains("SGVsbG8") && !c.contains("2J"),
            "a sequence goes whole: {h:?} → {c:?}"
        );
    }
}

/// Every hostile string in a scene's name, about and pin label and in a script's say, ask and
/// snapshot label: replay's text, ANSI, plain and asciicast outputs carry none of it raw.
#[test]
fn scene_and_script_text_reaches_every_output_clean() {
    let dir = tmp("outputs");
    for (k, h) in HOSTILE.iter().enumerate() {
        let scene = dir.join(format!("s{k}.toml"));
        std::fs::write(&scene, scene_text(h, Some(LABEL))).unwrap();
        // A script is lines: a carriage return or NUL stays inside its line.
        let script = dir.join(format!("s{k}.keys"));
        std::fs::write(&script, script_text(h)).unwrap();
        let (s, p) = (scene.to_str().unwrap(), script.to_str().unwrap());
        let cast = dir.join(format!("s{k}.cast"));
        for (how, extra) in [
            ("text", &[][..]),
            ("ansi", &["--ansi"][..]),
            ("plain", &["--plain"][..]),
            ("cast", &["--asciicast", cast.to_str().unwrap()][..]),
        ] {
            let mut args = vec!["replay", p, "--scene", s];
            args.extend(extra);
            let (code, out, err) = run(&args, &dir);
            assert_eq!(code, 0, "{h:?} {how}: {err}");
            clean_output(&out, how == "ansi").unwrap_or_else(|e| panic!("{h:?} {how}: {e}"));
            clean_output(&err, false).unwrap_or_else(|e| panic!("{h:?} {how} stderr: {e}"));
            assert!(
                out.contains(MARK),
                "{h:?} {how}: the mark shows where text was removed"
            );
        }
        let text = std::fs::read_to_string(&cast).unwrap();
        for line in text.lines() {
            let v: serde_json::Value = serde_json::from_str(line).unwrap();
            let frame = v
                .get(2)
                .and_then(|f| f.as_str())
                .or_else(|| v["title"].as_str())
                .unwrap_or("");
            clean_output(frame, true).unwrap_or_else(|e| panic!("{h:?} cast: {e}"));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A theme's name is cleaned as it is read; the configuration's strings and a script's
/// unknown keys reach the CLI's errors escaped (`\u{1b}`), a BOM too.
#[test]
fn theme_names_configuration_strings_and_errors_are_clean() {
    let dir = tmp("errors");
    let dark = include_str!("../../themes/dark.toml");
    for (k, h) in HOSTILE.iter().enumerate() {
        let path = dir.join(format!("t{k}.toml"));
        let text = dark.replacen("name = \"dark\"", &format!("name = {}", toml_str(h)), 1);
        assert_ne!(text, dark, "the theme names itself");
        std::fs::write(&path, text).unwrap();
        let theme = turntable::theme::Theme::load(path.to_str().unwrap()).unwrap();
        assert_eq!(theme.name.as_str(), clean(h), "{h:?}");
        // The configuration names a theme (and a key) that is not there.
        let cfg = dir.join(format!("c{k}/turntable"));
        std::fs::create_dir_all(&cfg).unwrap();
        std::fs::write(
            cfg.join("config.toml"),
            format!("theme = {}\n", toml_str(h)),
        )
        .unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
            .env("XDG_CONFIG_HOME", dir.join(format!("c{k}")))
            .arg("--plain")
            .current_dir(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{h:?}: {err}");
        clean_output(&err, false).unwrap_or_else(|e| panic!("{h:?} config: {e}"));
        // A script's unknown key, and an unknown scene.
        let script = dir.join(format!("k{k}.keys"));
        std::fs::write(&script, format!("{}\n", h.replace(' ', "_"))).unwrap();
        let mut cases = vec![vec!["replay", script.to_str().unwrap()]];
        // (An argument cannot hold a NUL.)
        if !h.contains('\0') {
            cases.push(vec!["replay", script.to_str().unwrap(), "--scene", h]);
        }
        for args in cases {
            let (code, _, err) = run(&args, &dir);
            assert_eq!(code, 2, "{h:?}: {err}");
            clean_output(&err, false).unwrap_or_else(|e| panic!("{h:?} {args:?}: {e}"));
        }
    }
    // A BOM that begins a script is named, not shown as nothing.
    let bom = dir.join("bom.keys");
    std::fs::write(&bom, "\u{feff}tick 3\nsnapshot\n").unwrap();
    let (code, _, err) = run(&["replay", bom.to_str().unwrap()], &dir);
    assert_eq!(code, 2);
    assert!(err.contains("byte-order mark (U+FEFF"), "{err}");
    // Mid-script, it is an escape.
    std::fs::write(&bom, "tick 3\n\u{feff}snapshot\n").unwrap();
    let (_, _, err) = run(&["replay", bom.to_str().unwrap()], &dir);
    assert!(err.contains("\\u{feff}snapshot"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Random strings heavy in controls, escape sequences' pieces and invisible marks, through
/// the cleaner and through a scene file and a key script into replay's outputs: each case is
/// refused with a clean error or runs with every output clean. The counts by class are
/// printed (`cargo test --release --test suite text:: -- --nocapture`).
#[test]
fn random_control_laden_text_never_reaches_an_output() {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};
    use turntable::app::App;
    use turntable::replay::{Options, replay};
    use turntable::scene::Scene;

    let piece = prop_oneof![
        Just("\x1b".to_string()),
        Just("\x1b[".to_string()),
        Just("\x1b]".to_string()),
        Just("\x1bP".to_string()),
        Just("\x1b\\".to_string()),
        Just("\x07".to_string()),
        Just("\r".to_string()),
        Just("\n".to_string()),
        Just("\t".to_string()),
        Just("\0".to_string()),
        Just("\x7f".to_string()),
        Just("\u{9b}".to_string()),
        Just("\u{9c}".to_string()),
        Just("\u{9d}".to_string()),
        Just("\u{90}".to_string()),
        Just("\u{feff}".to_string()),
        Just("\u{202e}".to_string()),
        Just("2J".to_string()),
        Just("0;title".to_string()),
        "[ -~]{0,6}",
        "[ξφτ≪]{0,2}",
        any::<char>().prop_map(String::from),
    ];
    let text = prop::collection::vec(piece, 0..24).prop_map(|v| v.concat());
    let dir = tmp("prop");
    let counts: [std::cell::Cell<usize>; 4] = Default::default();
    let bump = |k: usize| counts[k].set(counts[k].get() + 1);
    const NAMES: [&str; 4] = [
        "clean error",
        "sanitised",
        "plain text, unchanged",
        "cleaner only",
    ];
    // A fixed seed: the same cases, and the same counts, on every run.
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 300,
            failure_persistence: None,
            ..Config::default()
        },
        proptest::test_runner::TestRng::deterministic_rng(
            proptest::test_runner::RngAlgorithm::ChaCha,
        ),
    );
    let cases = std::cell::Cell::new(0usize);
    let result = runner.run(&text, |s| {
        cases.set(cases.get() + 1);
        let n = cases.get();
        // The cleaner: nothing unsafe left, and cleaning twice changes nothing.
        let c = clean(&s);
        prop_assert!(!c.chars().any(needs_escape), "{s:?} → {c:?}");
        prop_assert_eq!(clean(&c), c.clone());
        if n.is_multiple_of(3) {
            bump(3);
            return Ok(());
        }
        // Through a scene file and a script.
        let path = dir.join(format!("p{n}.toml"));
        std::fs::write(&path, scene_text(&s, None)).unwrap();
        let scene = Scene::load(path.to_str().unwrap());
        let steps = turntable::script::parse(&script_text(&s));
        let (scene, steps) = match (scene, steps) {
            (Ok(scene), Ok(steps)) => (scene, steps),
            (Err(e), _) => {
                let shown = turntable::files::escape_controls(&e.to_string());
                prop_assert!(clean_output(&shown, false).is_ok(), "{shown:?}");
                bump(0);
                return Ok(());
            }
            (_, Err(e)) => {
                let shown = turntable::files::escape_controls(&e.to_string());
                prop_assert!(clean_output(&shown, false).is_ok(), "{shown:?}");
                bump(0);
                return Ok(());
            }
        };
        prop_assert!(!scene.name.chars().any(needs_escape));
        for plain in [false, true] {
            let opts = Options {
                plain,
                ..Options::default()
            };
            let out = replay(App::new(scene.clone()), &steps, &opts);
            if let Err(e) = clean_output(&out, false) {
                return Err(TestCaseError::fail(format!("{s:?}: {e}")));
            }
        }
        bump(if c == s { 2 } else { 1 });
        Ok(())
    });
    let _ = std::fs::remove_dir_all(&dir);
    if let Err(e) = result {
        panic!("{e}");
    }
    let counts = counts.map(|c| c.get());
    let total: usize = counts.iter().sum();
    eprintln!("random control-laden text: {total} cases");
    for (name, k) in NAMES.iter().zip(counts) {
        eprintln!("  {name}: {k}");
    }
    assert!(counts[0] > 0 && counts[1] > 0, "both classes are exercised");
}
