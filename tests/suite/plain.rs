//! Plain mode for screen readers (`--plain`): the explorer's state described in lines, driven
//! headless by keys and ticks as the terminal loop drives it, the lines checked exactly and
//! their numbers against the engine's own runs.

use crate::common;
use common::turntable;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use turntable::app::keymap::KEYMAP;
use turntable::app::testing::Testing as _;
use turntable::app::{App, Chord};
use turntable::engine::{Outcome, Run, Settings, Status};
use turntable::present::num;
use turntable::scene::Scene;
use turntable::ui::plain::{Seen, opening};

/// The app and what plain mode has printed of it so far.
struct Plain {
    app: App,
    seen: Seen,
    lines: Vec<String>,
}

impl Plain {
    fn new(scene: &str) -> Plain {
        let app = App::new(Scene::preset(scene).unwrap());
        Plain {
            seen: Seen::of(&app),
            lines: opening(&app),
            app,
        }
    }

    fn say(&mut self) -> Vec<String> {
        let new = self.seen.news(&self.app);
        self.lines.extend(new.iter().cloned());
        new
    }

    fn key(&mut self, c: char) -> Vec<String> {
        self.press(Chord::new(KeyCode::Char(c), KeyModifiers::NONE))
    }

    /// A key pressed; what it asks to write is answered as a replay answers it (no file).
    fn press(&mut self, chord: Chord) -> Vec<String> {
        let effects = self.app.press(chord);
        turntable::replay::answer(&mut self.app, effects);
        self.say()
    }

    /// Ticks one at a time, as the loop does, up to `n`; the lines printed.
    fn ticks(&mut self, n: usize) -> Vec<String> {
        let mut out = vec![];
        for _ in 0..n {
            self.app.tick();
            out.extend(self.say());
        }
        out
    }
}

/// How the engine's own run of the app's release ends: the stop or the escape.
fn engine_end(app: &App) -> (Outcome, f64, f64) {
    let mut run = Run::new(app.initial(), Settings::default()).unwrap();
    let (out, _) = run.finish(100.0).unwrap();
    match (run.status(), run.escape()) {
        (Status::Stuck { tau, q }, _) => (out, tau, q.length()),
        (_, Some(e)) => (out, e.tau, f64::NAN),
        _ => panic!("undecided: {out:?}"),
    }
}

#[test]
fn opening_names_the_scene_its_release_and_its_state() {
    let p = Plain::new("C");
    assert_eq!(
        p.lines,
        [
            "turntable, plain mode: ? lists the keys, I reads the readouts, Space plays and pauses, q quits",
            "scene C: Fig. 3 C: stops inside ξ = 1, escapes in the paper",
            "release: scene C, ξ0 = 0.500, φ = 0, v0 = 0.6078 relative to the table; method dp54 tol=1e-10",
            "slipping",
        ]
    );
}

#[test]
fn preset_c_played_says_where_it_sticks_when_it_does() {
    let mut p = Plain::new("B");
    assert_eq!(
        p.key('3'),
        [
            "release: scene C, ξ0 = 0.500, φ = 0, v0 = 0.6078 relative to the table; method dp54 tol=1e-10",
            "slipping",
            "preset C: Fig. 3 C: stops inside ξ = 1, escapes in the paper",
        ]
    );
    let (out, tau, xi) = engine_end(&p.app);
    assert_eq!(out, Outcome::Stuck);
    let stuck = format!("stuck at ξ = {} (τ = {})", num(xi, 4), num(tau, 3));
    assert_eq!(stuck, "stuck at ξ = 0.9972 (τ = 5.602)");
    // Nothing while it slides; the stop on the tick that reaches it, and then nothing more.
    for t in 1..=200 {
        let said = p.ticks(1);
        if p.app.now().tau < tau {
            assert!(said.is_empty(), "tick {t}: {said:?}");
        } else {
            assert_eq!(said, std::slice::from_ref(&stuck), "tick {t}");
            assert!(p.app.now().tau - tau < turntable::app::TICK_DT);
            break;
        }
    }
    assert!(p.ticks(100).is_empty());
}

#[test]
fn fig2_escapes_and_says_when_it_was_certified() {
    let mut p = Plain::new("fig2");
    let (out, tau, _) = engine_end(&p.app);
    assert_eq!(out, Outcome::Escaped);
    p.ticks(200);
    // Released at rest outside ξ = 1 it cannot rest (E < −½): certified at once, said once.
    let escaped = format!("escaped (certified at τ = {})", num(tau, 3));
    assert_eq!(escaped, "escaped (certified at τ = 0.000)");
    assert_eq!(
        p.lines.iter().filter(|l| **l == escaped).count(),
        1,
        "{:?}",
        p.lines
    );
    assert_eq!(p.lines[3], escaped);
    // B, for contrast, sticks where the engine says.
    let mut p = Plain::new("B");
    let (_, tau, xi) = engine_end(&p.app);
    assert_eq!(
        p.ticks(200),
        [format!("stuck at ξ = {} (τ = {})", num(xi, 4), num(tau, 3))]
    );
}

#[test]
fn a_faster_throw_says_its_escape_on_the_tick_that_reaches_it() {
    let mut p = Plain::new("C");
    // v0 + 0.05 (Alt-v): above C's escape speed, 0.6078.
    p.press(Chord::new(KeyCode::Char('v'), KeyModifiers::ALT));
    let (out, tau, _) = engine_end(&p.app);
    assert_eq!(out, Outcome::Escaped);
    assert!(tau > 1.0, "certified later than the start: {tau}");
    let escaped = format!("escaped (certified at τ = {})", num(tau, 3));
    for t in 1..=400 {
        let said = p.ticks(1);
        if p.app.now().tau < tau {
            assert!(said.is_empty(), "tick {t}: {said:?}");
        } else {
            assert_eq!(said, std::slice::from_ref(&escaped), "tick {t}");
            return;
        }
    }
    panic!("never escaped: {:?}", p.lines);
}

#[test]
fn compare_says_how_the_papers_scheme_ends_too() {
    let mut p = Plain::new("C");
    assert_eq!(
        p.key('c'),
        [
            "compare on: the paper's RK2 (rk2-raw, dt = 1e-3, no stick event) from the same release",
            "paper's RK2: slipping",
        ]
    );
    let said = p.ticks(400);
    assert_eq!(said[0], "stuck at ξ = 0.9972 (τ = 5.602)");
    // The paper's fixed-step RK2 steps over C's stop and escapes (Sec. IV), as its own run.
    let mut paper = Run::new(p.app.initial(), Settings::paper()).unwrap();
    paper.finish(100.0).unwrap();
    let e = paper.escape().expect("the paper's RK2 lets C escape");
    assert!(
        said[1].starts_with(&format!(
            "paper's RK2: escaped (certified at τ = {})",
            num(e.tau, 3)
        )),
        "{said:?}"
    );
    assert_eq!(said.len(), 2, "{said:?}");
    assert_eq!(p.key('c'), ["compare off"]);
}

#[test]
fn time_keys_say_where_time_stands() {
    let mut p = Plain::new("C");
    p.ticks(10);
    assert_eq!(p.key(' '), ["paused at τ = 0.500"]);
    assert!(p.ticks(5).is_empty(), "paused: ticks say nothing");
    assert_eq!(p.key('.'), ["τ = 0.550"]);
    assert_eq!(p.key(','), ["τ = 0.500"]);
    assert_eq!(p.key(']'), ["speed ×2"]);
    assert_eq!(p.key('r'), ["restart at τ = 0", "slipping"]);
    assert_eq!(p.key(' '), ["playing from τ = 0.000"]);
    assert_eq!(
        p.key('f'),
        ["frame: rotating (readouts in the table frame)"]
    );
}

#[test]
fn edits_say_the_new_release() {
    let mut p = Plain::new("C");
    assert_eq!(
        p.key('x'),
        [
            "release: scene C (edited), ξ0 = 0.510, φ = 0, v0 = 0.6078 relative to the table; method dp54 tol=1e-10",
            "slipping"
        ]
    );
    assert_eq!(
        p.key('R')[0],
        "release: scene C (edited), ξ0 = 0.510, at rest on the table; method dp54 tol=1e-10"
    );
    assert_eq!(
        p.key('m')[0],
        "release: scene C (edited), ξ0 = 0.510, at rest on the table; method dop853 tol=1e-10"
    );
}

#[test]
fn i_reads_every_readout_as_the_panel_shows_it() {
    let mut p = Plain::new("C");
    p.ticks(150);
    let said = p.key('I');
    let s = p.app.now();
    assert_eq!(said[0], "readouts at τ = 7.500:");
    for want in [
        "ξ0 0.500 φ 0 v0 0.6078".to_string(),
        format!("τ {}", num(s.tau, 3)),
        format!("ξ {}", num(s.xi(), 5)),
        "stuck at ξ = 0.99717 since τ = 5.602".into(),
        "dp54 tol=1e-10".into(),
        "speed ×1 ▶".into(),
    ] {
        assert!(said.contains(&want), "{want} not in {said:?}");
    }
    // The explorer shows the same answer as a one-line notice; plain mode says it once.
    assert_eq!(
        p.app.notice().as_deref(),
        Some("τ = 7.500, ξ = 0.99717, |u| = 0.0000: stuck at ξ = 0.9972 (τ = 5.602)")
    );
    assert!(!said.iter().any(|l| l.starts_with("τ = 7.500,")));
}

#[test]
fn help_lists_every_key_of_the_keymap() {
    let mut p = Plain::new("C");
    let said = p.key('?');
    assert_eq!(said[0], "keys (? again closes this list):");
    for b in KEYMAP {
        assert!(
            said.iter().any(|l| l.ends_with(&format!(": {}", b.help))),
            "{} missing",
            b.help
        );
    }
    assert!(said.contains(&"  I: readouts in words".to_string()));
    assert_eq!(p.key('?'), ["help closed"]);
}

#[test]
fn the_save_prompt_is_spoken() {
    let mut p = Plain::new("C");
    assert_eq!(
        p.key('S'),
        ["save as: type a name, Enter saves, Esc cancels"]
    );
    assert_eq!(p.key('D'), ["name: D"]);
    let said = p.press(Chord::new(KeyCode::Enter, KeyModifiers::NONE));
    assert_eq!(said.len(), 1);
    assert!(
        said[0].starts_with("replay saves nothing: \"D\""),
        "{said:?}"
    );
}

/// Every key of the keymap, pressed and played on every preset: every line is plain text (no
/// control character, no escape sequence) and no number is NaN or infinite.
#[test]
fn every_key_on_every_preset_says_plain_lines_and_numbers() {
    for scene in turntable::scene::PRESETS {
        let mut p = Plain::new(scene);
        for b in KEYMAP {
            if b.action == turntable::app::Action::Quit {
                continue;
            }
            let effects = p.app.handle_key(KeyEvent::new(b.chord.code, b.chord.mods));
            turntable::replay::answer(&mut p.app, effects);
            p.say();
            p.ticks(3);
        }
        p.key('I');
        for l in &p.lines {
            assert!(!l.chars().any(char::is_control), "{scene}: {l:?}");
            for bad in ["NaN", "inf"] {
                assert!(!l.contains(bad), "{scene}: {l}");
            }
        }
    }
}

#[test]
fn replay_plain_prints_the_lines_and_the_readouts_at_a_snapshot() {
    let script = std::env::temp_dir().join(format!("turntable-plain-{}.keys", std::process::id()));
    std::fs::write(&script, "3\ntick 150\nsnapshot stopped\n6\ntick 40\n").unwrap();
    let (code, out, err) = turntable(&["replay", "--plain", script.to_str().unwrap()]);
    let (_, again, _) = turntable(&["replay", "--plain", script.to_str().unwrap()]);
    std::fs::remove_file(&script).unwrap();
    assert_eq!(out, again, "the same script, the same bytes");
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    let at = |l: &str| {
        lines
            .iter()
            .position(|x| *x == l)
            .unwrap_or_else(|| panic!("{l} not in {out}"))
    };
    assert!(at("stuck at ξ = 0.9972 (τ = 5.602)") < at("--- snapshot 1: stopped"));
    assert_eq!(
        lines[at("--- snapshot 1: stopped") + 1],
        "readouts at τ = 7.500:"
    );
    assert!(
        at("release: scene fig2, ξ0 = 1.100, at rest on the table; method dp54 tol=1e-10")
            > at("stuck at ξ = 0.99717 since τ = 5.602")
    );
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("escaped (certified at τ = "))
    );
    assert!(!out.contains('\x1b'));
    // Plain lines are not screens: --ansi and --asciicast make no sense with them.
    let (code, _, err) = turntable(&["replay", "--plain", "--ansi", "x.keys"]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn a_lesson_in_plain_mode_says_its_captions() {
    let (code, out, err) = turntable(&["lesson", "stick", "--headless", "--plain"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("\nFriction alone holds a particle on the turning table."),
        "{out}"
    );
    assert!(!out.contains('\x1b'));
    assert!(out.contains("\n--- snapshot 1: "));
}

/// A body scene says the body's events as time plays, each once, on the tick whose τ reaches
/// it, in the track's numbers: case A's body pivots about a stuck contact, then rests on the
/// table; with `6` (fig. 2's release, the body kept) it escapes at once, certified at τ = 0.
#[test]
fn a_body_scene_says_the_bodys_pivot_rest_and_escape_as_time_reaches_them() {
    use turntable::engine::rod::Phase;
    let scene = Scene::load("tests/replay/body.toml").unwrap();
    let body = scene.body.unwrap();
    let app = App::new(scene);
    let track = common::rod_track(body, 1.0, &app.initial(), 1e-10, 200.0);
    let k = track
        .phases
        .iter()
        .position(|p| matches!(p, Phase::Pivot { .. }))
        .unwrap();
    let Phase::Pivot { anchor, .. } = track.phases[k] else {
        unreachable!()
    };
    let pivot = (
        track.states[k].tau,
        format!(
            "the body pivots about a stuck contact at ξ = {}, τ = {}",
            num(anchor.length(), 5),
            num(track.states[k].tau, 3)
        ),
    );
    let rest = *track.states.last().unwrap();
    assert_eq!(track.outcome, Outcome::Stuck);
    let rest = (
        rest.tau,
        format!(
            "the body rests at ξ = {}, τ = {}",
            num(rest.q.length(), 5),
            num(rest.tau, 3)
        ),
    );
    assert_eq!(rest.1, "the body rests at ξ = 0.31442, τ = 1.027");
    let mut p = Plain {
        seen: Seen::of(&app),
        lines: opening(&app),
        app,
    };
    assert!(!p.lines.iter().any(|l| l.starts_with("the body")));
    for _ in 0..60 {
        let was = p.app.now().tau;
        let said = p.ticks(1);
        let now = p.app.now().tau;
        for (tau, line) in [&pivot, &rest] {
            assert_eq!(
                said.contains(line),
                was < *tau && *tau <= now,
                "{line} at τ {was}..{now}: {said:?}"
            );
        }
    }
    for (_, line) in [&pivot, &rest] {
        assert_eq!(p.lines.iter().filter(|l| *l == line).count(), 1, "{line}");
    }
    // Fig. 2's release outside ξ = 1: certified at once, said with the new release.
    let said = p.key('6');
    let cert = p.app.rod().unwrap().escape.unwrap();
    assert_eq!(cert, 0.0);
    assert!(
        said.contains(&"the body escapes (certified at τ = 0.000)".to_string()),
        "{said:?}"
    );
    let more = p.ticks(20);
    assert!(!more.iter().any(|l| l.starts_with("the body")), "{more:?}");
}

/// The same through `replay --plain`, as a listener hears it.
#[test]
fn replay_plain_says_the_bodys_events() {
    let script = std::env::temp_dir().join(format!("turntable-body-{}.keys", std::process::id()));
    std::fs::write(&script, "tick 40\n6\ntick 10\n").unwrap();
    let (code, out, err) = turntable(&[
        "replay",
        "--plain",
        "--scene",
        "tests/replay/body.toml",
        script.to_str().unwrap(),
    ]);
    std::fs::remove_file(&script).unwrap();
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    let at = |l: &str| {
        let n: Vec<usize> = (0..lines.len()).filter(|&k| lines[k] == l).collect();
        assert_eq!(n.len(), 1, "{l} in {out}");
        n[0]
    };
    let rest = at("the body rests at ξ = 0.31442, τ = 1.027");
    assert!(at("stuck at ξ = 0.3134 (τ = 0.997)") < rest);
    assert!(lines[at("the body escapes (certified at τ = 0.000)") - 1].starts_with("escaped"));
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("the body pivots about a stuck contact at ξ = "))
    );
}

/// A screen reader has no chart: on the escape-speed and rest-radius pages plain mode says the
/// page's numbers once computed, and the chart's verdict on the release when it changes —
/// checked against the engine's solvers (v_e's least to the 4 digits said, its angle to the
/// 0.001π said; ξ0c to the 6 digits said).
#[test]
fn plain_mode_says_the_analysis_pages_numbers() {
    use crate::common::easiest_angle;
    use turntable::engine::solve::critical_radius;
    let script = std::env::temp_dir().join(format!("turntable-pages-{}.keys", std::process::id()));
    std::fs::write(&script, "tab\ntab\nv*30\ntab\ntab\n").unwrap();
    let (code, out, err) = turntable(&["replay", "--plain", script.to_str().unwrap()]);
    std::fs::remove_file(&script).unwrap();
    assert_eq!(code, 0, "{err}");
    let line = |prefix: &str| {
        out.lines()
            .find(|l| l.starts_with(prefix))
            .unwrap_or_else(|| panic!("no {prefix:?} in {out}"))
            .to_string()
    };
    // "escape speed v_e(φ) at ξ0 = 0.500: min 0.5700 at 0.177π, max … at …π"
    let ve = line("escape speed v_e(φ) at ξ0 = 0.500: min ");
    let words: Vec<&str> = ve.split(' ').collect();
    let v: f64 = words[8].parse().unwrap();
    let phi: f64 = words[10].trim_end_matches("π,").parse().unwrap();
    let (p, v_min) = easiest_angle(0.5, 72, Settings::dp54(1e-12), 1e-10, 1e-5).unwrap();
    assert!((v - v_min).abs() <= 5e-5, "{ve}: {v_min}");
    assert!((phi - p / std::f64::consts::PI).abs() <= 1e-3, "{ve}: {p}");
    // C's release sticks below v_e; 30 × v (+0.03) takes it above.
    let stick = out
        .find("on the chart the release sticks (below v_e)")
        .unwrap();
    let escape = out
        .find("on the chart the release escapes (above v_e)")
        .unwrap();
    assert!(stick < escape, "{out}");
    assert_eq!(out.matches("on the chart the release").count(), 2, "{out}");
    let rest = line("rest radius (Fig. 6): ");
    let c: f64 = rest.rsplit(' ').next().unwrap().parse().unwrap();
    let xi0c = critical_radius(Settings::dp54(1e-12), 1e-9).unwrap().value;
    assert!((c - xi0c).abs() <= 5e-7, "{rest}: {xi0c}");
}
