//! Golden screens: every `tests/replay/NAME.keys` is replayed and compared with
//! `tests/replay/NAME.txt`. A `# replay: OPTIONS` comment in a script gives the options
//! (`--size WxH`, `--ansi`, `--theme T`, `--scene S`), so that
//! `turntable replay OPTIONS tests/replay/NAME.keys` prints exactly the golden.
//!
//! The cost counters are masked except in `integrator-step` (see `mask_costs`).
//!
//! Refresh the goldens after an intended change to the screen with
//! `UPDATE_GOLDENS=1 cargo test --release --test suite replay::`, and review the diff.

use crossterm::event::{KeyEvent, MouseButton, MouseEvent, MouseEventKind};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use turntable::app::{App, KEYMAP};
use turntable::cli::replay::{ReplayArgs, prepare};
use turntable::replay::{Options, replay};
use turntable::scene::Scene;
use turntable::script::parse;
use turntable::session::Explorer;
use turntable::ui::export::plain_text;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/replay")
}

/// What `turntable replay` prints for `script` (the same preparation as the command's).
fn run_script(script: &str) -> String {
    let Ok((app, opts, steps)) = prepare(script, &ReplayArgs::default()) else {
        panic!("script does not prepare")
    };
    replay(app, &steps, &opts)
}

/// The first few differing lines, numbered, expected against actual.
fn line_diff(expected: &str, actual: &str) -> String {
    let (e, a): (Vec<_>, Vec<_>) = (expected.lines().collect(), actual.lines().collect());
    let mut out = String::new();
    let mut shown = 0;
    for i in 0..e.len().max(a.len()) {
        let (x, y) = (e.get(i), a.get(i));
        if x == y {
            continue;
        }
        let show = |l: Option<&&str>| l.map_or("<missing>".to_string(), |l| format!("{l:?}"));
        out.push_str(&format!(
            "  line {}:\n    expected {}\n    actual   {}\n",
            i + 1,
            show(x),
            show(y)
        ));
        shown += 1;
        if shown == 8 {
            out.push_str("  ...\n");
            break;
        }
    }
    if out.is_empty() && expected != actual {
        out.push_str("  (the texts differ only in line endings)\n");
    }
    out
}

/// The golden that pins the cost counters on purpose: it is about step control.
const PINS_COSTS: &str = "integrator-step";

/// `text` with the cost counters (`steps N rej N`, `RHS N`) masked, and the padding after
/// them, so a change to step control does not rewrite every golden (as insta's filters do).
fn mask_costs(text: &str) -> String {
    let mut out = String::new();
    for line in text.split_inclusive('\n') {
        let mut rest = line;
        while let Some((at, label)) = ["steps ", "rej ", "RHS "]
            .iter()
            .filter_map(|l| rest.find(l).map(|at| (at, *l)))
            .min()
        {
            out.push_str(&rest[..at + label.len()]);
            let after = rest[at + label.len()..].trim_start_matches(' ');
            let digits = after.trim_start_matches(|c: char| c.is_ascii_digit());
            if digits.len() < after.len() {
                out.push('#');
                let spaces = digits.trim_start_matches(' ');
                if spaces.len() < digits.len() {
                    out.push(' ');
                }
                rest = spaces;
            } else {
                rest = after;
            }
        }
        out.push_str(rest);
    }
    out
}

#[test]
fn masking_hides_only_the_cost_counters() {
    let a = "│steps  1014 rej 1     │\n│RHS    6093   │ τ 1.5\n";
    let b = "│steps  998 rej 12     │\n│RHS    61     │ τ 1.5\n";
    assert_eq!(mask_costs(a), "│steps # rej # │\n│RHS # │ τ 1.5\n");
    assert_eq!(mask_costs(a), mask_costs(b));
    assert_ne!(
        mask_costs(a),
        mask_costs("│steps  1014 rej 1     │\n│RHS    6093   │ τ 1.6\n")
    );
}

#[test]
fn goldens() {
    let update = std::env::var_os("UPDATE_GOLDENS").is_some_and(|v| !v.is_empty());
    let mut scripts: Vec<PathBuf> = std::fs::read_dir(dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "keys"))
        .collect();
    scripts.sort();
    assert!(scripts.len() >= 15, "only {} scripts", scripts.len());
    let mut failures = Vec::new();
    // Each script's screens, and each lesson's as `turntable lesson NAME --headless` prints them.
    let mut runs: Vec<(PathBuf, String)> = scripts
        .iter()
        .map(|path| {
            (
                path.clone(),
                run_script(&std::fs::read_to_string(path).unwrap()),
            )
        })
        .collect();
    for l in turntable::lesson::LESSONS {
        let out = turntable::cli::lesson::headless(l, None).unwrap();
        runs.push((dir().join(format!("lesson-{}.keys", l.name)), out));
    }
    for (path, actual) in &runs {
        let actual = actual.clone();
        let golden = path.with_extension("txt");
        if update {
            std::fs::write(&golden, &actual).unwrap();
            continue;
        }
        let mut expected = std::fs::read_to_string(&golden).unwrap_or_default();
        let mut actual = actual;
        if !path.ends_with(format!("{PINS_COSTS}.keys")) {
            (expected, actual) = (mask_costs(&expected), mask_costs(&actual));
        }
        if expected != actual {
            failures.push(format!(
                "{} differs from {}:\n{}",
                path.display(),
                golden.display(),
                line_diff(&expected, &actual)
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{}\nIf the change is intended: UPDATE_GOLDENS=1 cargo test --release --test suite replay::",
        failures.join("\n")
    );
    // No stale goldens.
    for e in std::fs::read_dir(dir()).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "txt") {
            assert!(
                p.with_extension("keys").exists()
                    || runs.iter().any(|(k, _)| k.with_extension("txt") == p),
                "{} has no script",
                p.display()
            );
        }
    }
}

#[test]
fn line_diff_names_lines() {
    let d = line_diff("a\nb\nc\n", "a\nB\nc\nd\n");
    assert!(
        d.contains("line 2:\n    expected \"b\"\n    actual   \"B\""),
        "{d}"
    );
    assert!(
        d.contains("line 4:\n    expected <missing>\n    actual   \"d\""),
        "{d}"
    );
    assert!(!d.contains("line 1:"));
}

#[test]
fn the_same_script_gives_the_same_bytes() {
    let script = std::fs::read_to_string(dir().join("theme-light.keys")).unwrap();
    assert_eq!(run_script(&script), run_script(&script));
}

use turntable::rng::SplitMix64 as Rng;

/// A live session is recorded through the same `Explorer` the interactive loop uses (ticks
/// only while playing, as the loop calls them); replaying the recording gives the same
/// final screen.
#[test]
fn record_then_replay_gives_the_same_screen() {
    for seed in 1..=4u64 {
        let mut rng = Rng(seed);
        let mut app = App::new(Scene::default_scene());
        let tmp = std::env::temp_dir().join(format!("turntable-record-{}", std::process::id()));
        app.tell_save_path(tmp.join("scene.toml"));
        let mut s = Explorer::headless(
            app,
            turntable::theme::Theme::builtin("dark").unwrap(),
            80,
            24,
            true,
        );
        let keys: Vec<KeyEvent> = KEYMAP
            .iter()
            .filter(|b| !matches!(b.action, turntable::app::Action::Quit))
            // Saving and exporting write files (the replay's fresh app would write into the
            // working folder, the live one into a folder that is not there): not replayed.
            .filter(|b| {
                !matches!(
                    b.action,
                    turntable::app::Action::Save
                        | turntable::app::Action::SaveAs
                        | turntable::app::Action::ExportSvg
                )
            })
            .map(|b| b.chord.event())
            .collect();
        for _ in 0..400 {
            match rng.below(20) {
                0 => {
                    let (w, h) = [(80, 24), (60, 16), (100, 30), (30, 8)][rng.below(4) as usize];
                    s.term.backend_mut().resize(w, h);
                    s.resized(w, h);
                }
                1..=3 => {
                    let kind = [
                        MouseEventKind::Down(MouseButton::Left),
                        MouseEventKind::Drag(MouseButton::Left),
                        MouseEventKind::Up(MouseButton::Left),
                        MouseEventKind::ScrollUp,
                    ][rng.below(4) as usize];
                    let ev = MouseEvent {
                        kind,
                        column: rng.below(80) as u16,
                        row: rng.below(24) as u16,
                        modifiers: crossterm::event::KeyModifiers::NONE,
                    };
                    s.mouse(ev).unwrap();
                }
                4..=9 => s.key(keys[rng.below(keys.len() as u64) as usize]),
                _ => {
                    for _ in 0..rng.below(8) {
                        if s.app.is_playing() {
                            s.tick();
                        }
                    }
                }
            }
            // The loop draws whenever something changed.
            if rng.below(2) == 0 {
                s.draw_if_needed().unwrap();
            }
        }
        let live = plain_text(s.screen());
        let tau = s.app.now().tau;
        let script = s.take_recording().unwrap();
        let steps = parse(&script).expect("a recording parses");
        let fresh = App::new(Scene::default_scene());
        let out = replay(fresh, &steps, &Options::default());
        let (head, screen) = out.split_once('\n').unwrap();
        assert!(head.contains(&format!("tau={tau:.3}")), "{head}");
        assert_eq!(screen, live, "seed {seed}:\n{}", line_diff(&live, screen));
    }
}

fn binary() -> Command {
    Command::new(env!("CARGO_BIN_EXE_turntable"))
}

#[test]
fn cli_reads_stdin_and_reports_parse_errors() {
    use std::io::Write;
    let mut child = binary()
        .args(["replay", "--size", "40x12", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"tick 3\nsnapshot a b\n")
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.starts_with("--- snapshot 1: a b (40x12, tau=0.150)\n"),
        "{text}"
    );

    let bad = std::env::temp_dir().join(format!("turntable-bad-{}.keys", std::process::id()));
    std::fs::write(&bad, "tick 3\n\n  Right*0\n").unwrap();
    let out = binary().arg("replay").arg(&bad).output().unwrap();
    let _ = std::fs::remove_file(&bad);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(
        err,
        format!(
            "error: {}: line 3, column 3: repeat count 0 is out of range 1..=100000\n",
            bad.display()
        )
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn cli_output_matches_the_golden_and_ignores_no_color() {
    let path = dir().join("theme-mono.keys");
    let golden = std::fs::read_to_string(path.with_extension("txt")).unwrap();
    for no_color in ["", "1"] {
        let out = binary()
            .args(["replay", "--ansi", "--theme", "mono", "--size", "60x16"])
            .arg(&path)
            .env("NO_COLOR", no_color)
            .output()
            .unwrap();
        assert!(out.status.success());
        assert_eq!(String::from_utf8(out.stdout).unwrap(), golden);
    }
    // Plain text does not depend on the theme.
    let plain = |theme: &str| {
        let out = binary()
            .args(["replay", "--theme", theme])
            .arg(dir().join("preset-B.keys"))
            .env("NO_COLOR", "1")
            .output()
            .unwrap();
        String::from_utf8(out.stdout).unwrap()
    };
    let golden = std::fs::read_to_string(dir().join("preset-B.txt")).unwrap();
    assert_eq!(plain("light"), golden);
    assert_eq!(plain("mono"), golden);
}

/// The screen a terminal of `w` × `h` shows after `frames`: the moves (`ESC[row;colH`, `ESC[H`),
/// clears (`ESC[2J`) and text a cast's frames hold, styles and modes ignored.
fn play(frames: &[&str], w: usize, h: usize) -> Vec<String> {
    use unicode_width::UnicodeWidthChar;
    let mut screen = vec![vec![" ".to_string(); w]; h];
    let (mut row, mut col) = (0usize, 0usize);
    for f in frames {
        let mut chars = f.chars().peekable();
        while let Some(c) = chars.next() {
            if c == '\x1b' {
                assert_eq!(chars.next(), Some('['), "{f}");
                let mut params = String::new();
                let end = loop {
                    let c = chars.next().unwrap();
                    if c.is_ascii_alphabetic() {
                        break c;
                    }
                    params.push(c);
                };
                match (end, params.as_str()) {
                    ('H', "") => (row, col) = (0, 0),
                    ('H', p) => {
                        let (r, c) = p.split_once(';').unwrap();
                        (row, col) = (
                            r.parse::<usize>().unwrap() - 1,
                            c.parse::<usize>().unwrap() - 1,
                        );
                    }
                    ('J', "2") => screen = vec![vec![" ".to_string(); w]; h],
                    ('m', _) | ('l', "?25") => {}
                    other => panic!("unexpected sequence {other:?}"),
                }
            } else if c == '\r' {
                col = 0;
            } else if c == '\n' {
                row += 1;
            } else {
                let width = c.width().unwrap_or(1).max(1);
                screen[row][col] = c.to_string();
                for k in 1..width {
                    screen[row][col + k] = String::new();
                }
                col += width;
            }
        }
    }
    screen.into_iter().map(|r| r.concat()).collect()
}

/// `replay --asciicast`: a header line (version 2, the size), then events whose times never go
/// back, each a tick at 30 a second; the last frame shows what the last snapshot shows; the
/// same script gives the same bytes.
#[test]
fn asciicast_records_the_replay_at_the_pace_of_its_ticks() {
    let tmp = std::env::temp_dir().join(format!("turntable-cast-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let script = tmp.join("s.keys");
    std::fs::write(
        &script,
        "resize 60x16\n3\ntick 40\nc\ntick 20\nsnapshot end\n",
    )
    .unwrap();
    let cast = tmp.join("s.cast");
    let out = binary()
        .arg("replay")
        .arg(&script)
        .arg("--asciicast")
        .arg(&cast)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let text = std::fs::read_to_string(&cast).unwrap();
    let mut lines = text.lines();
    let header: serde_json::Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    assert_eq!(header["version"], 2);
    assert_eq!(
        (header["width"].as_u64(), header["height"].as_u64()),
        (Some(80), Some(24))
    );
    let events: Vec<serde_json::Value> = lines.map(|l| serde_json::from_str(l).unwrap()).collect();
    let mut last_time = 0.0;
    let mut frames = vec![];
    for e in &events {
        let t = e[0].as_f64().unwrap();
        assert!(t >= last_time, "time went back: {e}");
        last_time = t;
        match e[1].as_str().unwrap() {
            "o" => frames.push((t, e[2].as_str().unwrap().to_string())),
            "r" => {
                assert_eq!(e[2], "60x16");
                // The screen starts again at the new size.
                frames.clear();
            }
            "m" => assert_eq!(e[2], "end"),
            k => panic!("event kind {k}"),
        }
    }
    // 60 ticks at 30 a second: 2 s, and half a second after each of the two keys for the
    // class to see what it did; a frame for (nearly) every tick while it plays.
    assert!((last_time - 3.0).abs() < 1e-6, "{last_time}");
    assert!(frames.len() > 50, "{} frames", frames.len());
    // Every frame played on a screen as a terminal plays it, the last is the snapshot's: the
    // frames after the first carry only the cells that changed.
    let last = play(
        &frames.iter().map(|f| f.1.as_str()).collect::<Vec<_>>(),
        60,
        16,
    );
    let shot = stdout.split_once('\n').unwrap().1;
    let last: Vec<&str> = last.iter().map(|l| l.trim_end()).collect();
    let shot: Vec<&str> = shot.lines().collect();
    assert_eq!(last, shot);
    // Only what changed: the frames after the first are far smaller than a screen.
    let later: usize = frames[1..].iter().map(|f| f.1.len()).sum::<usize>() / (frames.len() - 1);
    assert!(
        later * 4 < frames[0].1.len(),
        "{later} bytes a frame against {}",
        frames[0].1.len()
    );
    assert!(
        shot.iter().any(|l| l.contains("paper's RK2 (○)")),
        "{shot:?}"
    );
    // Deterministic: no clock.
    let again = tmp.join("again.cast");
    binary()
        .arg("replay")
        .arg(&script)
        .arg("--asciicast")
        .arg(&again)
        .output()
        .unwrap();
    assert_eq!(std::fs::read(&again).unwrap(), text.as_bytes());
    // A bad path fails before any work, exit 2, and leaves nothing behind.
    let out = binary()
        .arg("replay")
        .arg(&script)
        .arg("--asciicast")
        .arg(&tmp)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    std::fs::remove_dir_all(&tmp).unwrap();
}

/// A cast a teacher shows gives a caption time to be read: 0.3 s a word, 3 s at least.
#[test]
fn asciicast_holds_a_caption_for_its_words() {
    let tmp = std::env::temp_dir().join(format!("turntable-cast-say-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let script = tmp.join("s.keys");
    let words = vec!["word"; 20].join(" ");
    std::fs::write(&script, format!("pause\nsay short\nsay {words}\nsay\n")).unwrap();
    let cast = tmp.join("s.cast");
    let out = binary()
        .args(["replay", "--asciicast"])
        .arg(&cast)
        .arg(&script)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let times: Vec<f64> = std::fs::read_to_string(&cast)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            serde_json::from_str::<serde_json::Value>(l).unwrap()[0]
                .as_f64()
                .unwrap()
        })
        .collect();
    // The opening frame and the pause's at 0; "short" held 3 s; twenty words 6 s.
    assert_eq!(times.first(), Some(&0.0));
    assert!((times.last().unwrap() - 9.0).abs() < 1e-6, "{times:?}");
    std::fs::remove_dir_all(&tmp).unwrap();
}
