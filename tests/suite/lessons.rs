//! The narrated lessons: every number a caption states is checked here against the engine;
//! every caption fits the smallest screen; an interactive lesson holds at `wait` and `ask`
//! without holding up time; the command's errors. Their screens are goldens in
//! `tests/replay` (`lesson-NAME.txt`, see tests/suite/replay.rs).

use crate::common::easiest_angle;
use std::f64::consts::PI;
use std::process::Command;
use turntable::app::{App, Chord};
use turntable::engine::solve::{critical_radius, escape_speed, sweep_escape};
use turntable::engine::{Initial, Method, Outcome, Release, Run, Settings};
use turntable::lesson::{Driver, LESSONS, find};
use turntable::scene::Scene;
use turntable::script::{Step, parse};
use turntable::session::Explorer;
use turntable::ui::fit::wrap;

/// The captions and questions of a lesson, in order.
fn captions(script: &str) -> Vec<String> {
    parse(script)
        .unwrap()
        .into_iter()
        .filter_map(|s| match s {
            Step::Say(t) => t.map(|t| t.to_string()),
            Step::Ask(t) => Some(t.to_string()),
            _ => None,
        })
        .collect()
}

/// Numbers as written in `text` (`0.60782`, `2.4e-5`, `1.2` of `1.2π`).
fn numbers(text: &str) -> Vec<String> {
    let mut out = vec![];
    let b: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < b.len() {
        if !b[i].is_ascii_digit() || (i > 0 && (b[i - 1].is_alphanumeric() || b[i - 1] == '_')) {
            i += 1;
            continue;
        }
        let start = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        if i + 1 < b.len() && b[i] == '.' && b[i + 1].is_ascii_digit() {
            i += 1;
            while i < b.len() && b[i].is_ascii_digit() {
                i += 1;
            }
        }
        if i + 2 < b.len() && b[i] == 'e' && b[i + 1] == '-' && b[i + 2].is_ascii_digit() {
            i += 2;
            while i < b.len() && b[i].is_ascii_digit() {
                i += 1;
            }
        }
        out.push(b[start..i].iter().collect());
    }
    out
}

#[test]
fn numbers_are_read_as_written() {
    assert_eq!(
        numbers("v_e = 0.60782, 2.4e-5 below; φ = 1.2π, dt = 1e-3, ξ0 = 0.5, Ω², R_max"),
        ["0.60782", "2.4e-5", "1.2", "1e-3", "0.5"]
    );
}

/// Phrases that name a figure, section, equation, key or property: references, not claims.
const REFERENCES: [&str; 22] = [
    "Fig. 1",
    "Sec. III",
    "property 3",
    "property 4",
    "key 1",
    "key 5",
    "(2ξ0)",
    "(12ξ0)",
    "Figs. 3 and 4",
    "Fig. 2",
    "Fig. 5",
    "Fig. 6",
    "Sec. II",
    "Eq. 22",
    "property 1",
    "property 2",
    "key 2",
    "key 4",
    "key 6",
    "key 7",
    "keys 1 to 4",
    "Ω²",
];

/// A converged run's states, step by step, up to its end or `tau_max`.
fn states(i: Initial, tau_max: f64) -> Vec<turntable::engine::State> {
    let mut run = Run::new(i, Settings::dp54(1e-12)).unwrap();
    let mut out = vec![run.state()];
    while run.outcome() == Outcome::Running && run.tau() < tau_max {
        run.step(tau_max).unwrap();
        out.push(run.state());
    }
    out
}

/// A converged run's state at `tau`.
fn at(i: Initial, tau: f64) -> turntable::engine::State {
    let mut run = Run::new(i, Settings::dp54(1e-12)).unwrap();
    run.run(tau, false).unwrap();
    let s = run.state();
    assert!((s.tau - tau).abs() < 1e-9, "{}", s.tau);
    s
}

/// The least escape speed over φ from `xi0` (0.2 or 0.5), each found once.
fn least_ve(xi0: f64) -> f64 {
    static LEAST: std::sync::OnceLock<[f64; 2]> = std::sync::OnceLock::new();
    let least = |x: f64| {
        easiest_angle(x, 36, Settings::dp54(1e-10), 1e-10, 1e-4)
            .unwrap()
            .1
    };
    let [at_02, at_05] = *LEAST.get_or_init(|| [least(0.2), least(0.5)]);
    match xi0 {
        0.2 => at_02,
        0.5 => at_05,
        _ => least(xi0),
    }
}

fn converged(i: Initial, tau_max: f64) -> (Outcome, f64, f64) {
    let mut run = Run::new(i, Settings::dp54(1e-12)).unwrap();
    let (o, s) = run.finish(tau_max).unwrap();
    (o, s.q().length(), s.tau)
}

/// `x` as printed to the digits of `shown`.
fn shows(x: f64, shown: &str) -> bool {
    let decimals = shown.split('.').nth(1).map_or(0, str::len);
    format!("{x:.decimals$}") == shown
}

fn preset(name: &str) -> Initial {
    Scene::preset(name).unwrap().initial
}

fn table_rest(xi0: f64) -> Outcome {
    converged(Initial::at_rest(xi0, Release::TableRest), 50.0).0
}

/// A number as a caption writes it, and its check against the engine.
type Claim = (&'static str, Box<dyn Fn()>);

/// Each number a lesson's captions state, with its check against the engine.
fn claims(lesson: &str) -> Vec<Claim> {
    let b = || -> (Outcome, f64, f64) { converged(preset("B"), 50.0) };
    let ve_c = || {
        escape_speed(0.5, 0.0, Settings::dp54(1e-11), 1e-8)
            .unwrap()
            .value
    };
    let d = || converged(preset("D"), 50.0);
    let c = |k: &'static str, f: Box<dyn Fn()>| (k, f);
    match lesson {
        "stick" => vec![
            // R_max in units of itself; Ω = 1 and μg = 1 as friction's strength while sliding.
            c(
                "1",
                Box::new(|| {
                    assert_eq!(table_rest(1.0 - 1e-9), Outcome::Stuck);
                    assert_eq!(table_rest(1.0 + 1e-3), Outcome::Escaped);
                    let f = turntable::engine::model::friction(
                        glam::DVec2::new(0.3, -0.4),
                        glam::DVec2::X,
                    );
                    assert!((f.length() - 1.0).abs() < 1e-15);
                }),
            ),
            c(
                "0.9",
                Box::new(|| {
                    let (o, xi, tau) = converged(Initial::at_rest(0.9, Release::TableRest), 50.0);
                    assert_eq!((o, tau), (Outcome::Stuck, 0.0));
                    assert!((xi - 0.9).abs() < 1e-15);
                }),
            ),
            c(
                "1.1",
                Box::new(|| {
                    assert_eq!(preset("fig2"), Initial::at_rest(1.1, Release::TableRest));
                    assert_eq!(table_rest(1.1), Outcome::Escaped);
                }),
            ),
            c(
                "0.5",
                Box::new(|| assert_eq!(preset("B"), Initial::velocity(0.5, 0.0, 0.6))),
            ),
            c("0.6", Box::new(|| assert_eq!(preset("B").v0, 0.6))),
            c(
                "0.9453",
                Box::new(move || {
                    let (o, xi, _) = b();
                    assert_eq!(o, Outcome::Stuck);
                    assert!(shows(xi, "0.9453") && xi < 1.0, "{xi}");
                }),
            ),
        ],
        "cases" => vec![
            c(
                "0.5",
                Box::new(|| {
                    assert_eq!(preset("A"), Initial::velocity(0.5, PI, 1.0));
                }),
            ),
            // A's v0, and R_max.
            c(
                "1",
                Box::new(|| {
                    assert_eq!(preset("A").v0, 1.0);
                    assert_eq!(table_rest(1.0 - 1e-9), Outcome::Stuck);
                    assert_eq!(table_rest(1.0 + 1e-3), Outcome::Escaped);
                }),
            ),
            c(
                "0.3134",
                Box::new(|| {
                    let (o, xi, _) = converged(preset("A"), 50.0);
                    assert_eq!(o, Outcome::Stuck);
                    assert!(shows(xi, "0.3134"), "{xi}");
                }),
            ),
            c("0", Box::new(|| assert_eq!(preset("B").phi, 0.0))),
            c(
                "0.6",
                Box::new(|| assert_eq!(preset("B"), Initial::velocity(0.5, 0.0, 0.6))),
            ),
            c("0.9453", Box::new(move || assert!(shows(b().1, "0.9453")))),
            c(
                "0.6078",
                Box::new(|| assert_eq!(preset("C"), Initial::velocity(0.5, 0.0, 0.6078))),
            ),
            c(
                "0.60782",
                Box::new(move || assert!(shows(ve_c(), "0.60782"), "{}", ve_c())),
            ),
            c(
                "2.4e-5",
                Box::new(move || {
                    let gap = ve_c() - 0.6078;
                    assert_eq!(format!("{gap:.1e}"), "2.4e-5");
                    // Below it: a converged run sticks, just inside ξ = 1.
                    let (o, xi, _) = converged(preset("C"), 50.0);
                    assert!(o == Outcome::Stuck && xi < 1.0 && xi > 0.99, "{xi}");
                }),
            ),
            c(
                "1e-3",
                Box::new(|| {
                    let s = Settings::paper();
                    assert_eq!(s.method(), Method::Rk2Raw);
                    assert_eq!(s.scheme.knob(), 1e-3);
                    assert!(!s.method().stick_events());
                }),
            ),
            c(
                "17.3",
                Box::new(|| {
                    let mut raw = Run::new(preset("C"), Settings::paper()).unwrap();
                    assert_eq!(raw.run(50.0, true).unwrap(), Outcome::Escaped);
                    let t = raw.escape().unwrap().tau;
                    assert!(shows(t, "17.3"), "{t}");
                }),
            ),
            c(
                "1.1",
                Box::new(|| assert_eq!(preset("D"), Initial::velocity(1.1, 1.2 * PI, 1.3))),
            ),
            c("1.2", Box::new(|| assert_eq!(preset("D").phi, 1.2 * PI))),
            c("1.3", Box::new(|| assert_eq!(preset("D").v0, 1.3))),
            c(
                "0.6750",
                Box::new(move || {
                    let (o, xi, _) = d();
                    assert_eq!(o, Outcome::Stuck);
                    assert!(shows(xi, "0.6750"), "{xi}");
                }),
            ),
        ],
        "escape" => {
            let window = |v0: f64| converged(Initial::velocity(1.1, 1.2 * PI, v0), 100.0).0;
            vec![
                // ξ0 = 0.5 (scene C), and v0 = 0.5 along D's direction escapes.
                c(
                    "0.5",
                    Box::new(move || {
                        assert_eq!(preset("C").xi0, 0.5);
                        assert_eq!(window(0.5), Outcome::Escaped);
                    }),
                ),
                c(
                    "0.5700",
                    Box::new(|| {
                        let (_, v) =
                            easiest_angle(0.5, 36, Settings::dp54(1e-10), 1e-10, 1e-4).unwrap();
                        assert!(shows(v, "0.5700"), "{v}");
                    }),
                ),
                // Where v_e is least moves with ξ0 (angles in π, as the explorer says them); the
                // paper's "≈ 0.4 for all" (rad, 0.13π) holds near 0.7 only.
                c(
                    "0.222",
                    Box::new(|| {
                        let (phi, _) =
                            easiest_angle(0.2, 36, Settings::dp54(1e-10), 1e-10, 1e-4).unwrap();
                        assert!(shows(phi / PI, "0.222"), "{phi}");
                    }),
                ),
                // Two of Fig. 5's curves.
                c(
                    "0.2",
                    Box::new(|| assert!(turntable::analysis::PAPER_XI0.contains(&0.2))),
                ),
                c(
                    "0.098",
                    Box::new(|| {
                        let (phi, _) =
                            easiest_angle(0.8, 36, Settings::dp54(1e-10), 1e-10, 1e-4).unwrap();
                        assert!(shows(phi / PI, "0.098"), "{phi}");
                    }),
                ),
                c(
                    "0.8",
                    Box::new(|| assert!(turntable::analysis::PAPER_XI0.contains(&0.8))),
                ),
                c(
                    "0.13",
                    Box::new(|| {
                        // The paper's value, 0.4 rad, is 0.13π; at ξ0 = 0.2, 0.5 and 0.8 the
                        // least v_e is off it by more than 0.09 rad.
                        assert!(shows(0.4 / PI, "0.13"));
                        for xi0 in [0.2, 0.5, 0.8] {
                            let (phi, _) =
                                easiest_angle(xi0, 36, Settings::dp54(1e-10), 1e-10, 1e-4).unwrap();
                            assert!((phi - 0.13 * PI).abs() > 0.09, "{xi0}: {phi}");
                        }
                    }),
                ),
                c(
                    "0.177",
                    Box::new(|| {
                        let (phi, _) =
                            easiest_angle(0.5, 36, Settings::dp54(1e-10), 1e-10, 1e-4).unwrap();
                        // Left of radial: counterclockwise from outward.
                        assert!(shows(phi / PI, "0.177") && phi > 0.0, "{phi}");
                    }),
                ),
                // φ = 0 straight out; and v_e = 0 beyond R_max: at rest on the table it escapes.
                c(
                    "0",
                    Box::new(|| {
                        assert_eq!(preset("C").phi, 0.0);
                        let t = escape_speed(1.1, 1.2 * PI, Settings::dp54(1e-10), 1e-6).unwrap();
                        assert_eq!((t.value, t.stuck_at), (0.0, None));
                    }),
                ),
                c(
                    "0.60782",
                    Box::new(move || assert!(shows(ve_c(), "0.60782"))),
                ),
                c(
                    "0.6078",
                    Box::new(move || {
                        assert_eq!(preset("C").v0, 0.6078);
                        assert_eq!(converged(preset("C"), 50.0).0, Outcome::Stuck);
                    }),
                ),
                // The peak on the escape page's grid of 72 angles, where it marks its max.
                c(
                    "1.28",
                    Box::new(|| {
                        let pts = sweep_escape(
                            &[0.5],
                            72,
                            Settings::dp54(1e-8),
                            1e-6,
                            &Default::default(),
                        )
                        .unwrap();
                        let max = pts
                            .iter()
                            .max_by(|a, b| a.v_escape.total_cmp(&b.v_escape))
                            .unwrap();
                        assert!(shows(max.phi / PI, "1.28"), "peak at {}", max.phi);
                    }),
                ),
                c("1.1", Box::new(|| assert_eq!(preset("D").xi0, 1.1))),
                c("1.2", Box::new(|| assert_eq!(preset("D").phi, 1.2 * PI))),
                c(
                    "1.3",
                    Box::new(move || {
                        assert_eq!(preset("D").v0, 1.3);
                        assert_eq!(window(1.3), Outcome::Stuck);
                    }),
                ),
                c(
                    "2.5",
                    Box::new(move || assert_eq!(window(2.5), Outcome::Escaped)),
                ),
                c(
                    "0.87204",
                    Box::new(|| {
                        let t = critical_radius(Settings::dp54(1e-11), 1e-8).unwrap();
                        assert!(shows(t.value, "0.87204"), "{}", t.value);
                        // "Up to ξ0c it comes to rest; from further out it escapes."
                        assert!(t.interval);
                    }),
                ),
                c(
                    "0.87",
                    Box::new(|| {
                        let t = critical_radius(Settings::dp54(1e-10), 1e-6).unwrap();
                        assert!(shows(t.value, "0.87"), "{}", t.value);
                    }),
                ),
                c(
                    "0.9",
                    Box::new(|| {
                        let (o, _, _) = converged(Initial::at_rest(0.9, Release::LabRest), 50.0);
                        assert_eq!(o, Outcome::Escaped);
                    }),
                ),
            ]
        }
        "spin" => {
            use turntable::engine::spinup::{Onset, Ramp, Slip, SpinRun};
            let scene = || Scene::preset("spin").unwrap();
            // The slip as a converged run finds it, an event located inside its step.
            let slip = move || -> Slip {
                let s = scene();
                let mut run =
                    SpinRun::new(s.spin.unwrap(), s.initial.xi0, Settings::dp54(1e-12)).unwrap();
                run.run(50.0, true).unwrap();
                run.slip().unwrap()
            };
            vec![
                c(
                    "0.5",
                    Box::new(move || assert_eq!(scene().initial.xi0, 0.5)),
                ),
                c(
                    "0.2",
                    Box::new(move || {
                        let ramp = Ramp {
                            rate: 0.2,
                            omega0: 0.0,
                        };
                        assert_eq!(scene().spin, Some(ramp));
                    }),
                ),
                c(
                    "1.4107",
                    Box::new(move || assert!(shows(slip().omega, "1.4107"), "{:?}", slip())),
                ),
                c(
                    "1.410665",
                    Box::new(move || {
                        let s = scene();
                        let Onset::At { omega, .. } = s.spin.unwrap().onset(s.initial.xi0, 1.0)
                        else {
                            panic!("the preset's coin slips on the way")
                        };
                        assert!(shows(omega, "1.410665"), "{omega}");
                        assert!((slip().omega - omega).abs() < 1e-9);
                    }),
                ),
                c(
                    "0.995",
                    Box::new(move || assert!(shows(slip().inferred_mu, "0.995"), "{:?}", slip())),
                ),
            ]
        }
        "forces" => forces_claims(),
        "slow" => slow_claims(),
        other => panic!("no claims listed for lesson {other}"),
    }
}

/// Every number in a lesson's captions is one its claims check (references aside), and every
/// claim is checked.
fn check_lesson(name: &str) {
    let lesson = find(name).unwrap();
    let claims = claims(name);
    let mut stated: Vec<String> = vec![];
    for text in captions(lesson.script) {
        let mut t = text.clone();
        for r in REFERENCES {
            t = t.replace(r, "");
        }
        for n in numbers(&t) {
            assert!(
                claims.iter().any(|(k, _)| *k == n),
                "{name}: '{n}' in {text:?} is not checked"
            );
            stated.push(n);
        }
    }
    for (k, check) in &claims {
        assert!(
            stated.iter().any(|n| n == k),
            "{name}: claim {k} is stated nowhere"
        );
        check();
    }
}

#[test]
fn every_number_in_lesson_stick_is_checked() {
    check_lesson("stick");
}

#[test]
fn every_number_in_lesson_cases_is_checked() {
    check_lesson("cases");
}

#[test]
fn every_number_in_lesson_escape_is_checked() {
    check_lesson("escape");
}

#[test]
fn every_number_in_lesson_spin_is_checked() {
    check_lesson("spin");
}

#[test]
fn every_number_in_lesson_forces_is_checked() {
    check_lesson("forces");
}

#[test]
fn every_number_in_lesson_slow_is_checked() {
    check_lesson("slow");
}

#[test]
fn every_lesson_has_claims_and_snapshots() {
    assert_eq!(LESSONS.len(), 6);
    for l in LESSONS {
        assert!(find(&l.name.to_uppercase()).is_some());
        let steps = parse(l.script).unwrap();
        assert!(
            steps.iter().any(|s| matches!(s, Step::Ask(_))),
            "{}",
            l.name
        );
        assert!(
            steps
                .iter()
                .filter(|s| matches!(s, Step::Snapshot(_)))
                .count()
                >= 4
        );
        assert!(steps.contains(&Step::Wait));
    }
}

/// At the smallest screen (40×12: a box 38 wide over the 9-row body, 7 rows of text) every
/// caption fits whole, a question with the longest verdict the run can give too.
#[test]
fn every_caption_fits_the_smallest_screen() {
    let verdict = "Not so: you said it does not escape, but it escapes (certified at τ = 17.329).";
    for l in LESSONS {
        let steps = parse(l.script).unwrap();
        for s in steps {
            let text = match s {
                Step::Say(Some(t)) => t.to_string(),
                Step::Ask(t) => format!("{t}\n{verdict}"),
                _ => continue,
            };
            let lines = wrap(&text, 38, 100);
            assert!(
                lines.len() <= 7,
                "{}: {} lines: {lines:#?}",
                l.name,
                lines.len()
            );
        }
    }
}

/// Each lesson at 40×12 and at 200×60: the caption box is there, its words whole.
#[test]
fn lessons_render_at_the_smallest_and_a_large_screen() {
    for l in LESSONS {
        for size in [(40, 12), (200, 60)] {
            let out = turntable::cli::lesson::headless(l, Some(size)).unwrap();
            let shots = out.split("--- snapshot").skip(1).count();
            assert!(shots >= 4);
            assert_eq!(
                out.matches(&format!("lesson: {}", l.name)).count(),
                shots,
                "{}",
                l.name
            );
            if size == (40, 12) {
                assert!(!out.contains('…'), "{}: a caption was cut:\n{out}", l.name);
            }
        }
    }
}

fn app() -> App {
    App::new(Scene::default_scene())
}

fn press(s: &mut Explorer<ratatui::backend::TestBackend>, key: &str) {
    let chord: Chord = key.parse().unwrap();
    s.press(chord);
}

/// Interactive: `wait` and an unanswered `ask` hold the lesson, not time; Enter and y/n are
/// the lesson's only then; Space plays and pauses at every moment and never moves the lesson
/// on; `tick N` counts the session's ticks of play.
#[test]
fn an_interactive_lesson_holds_as_state_and_time_goes_on() {
    let script = "pause\nsay one\nwait\nplay\ntick 3\nsay two\nask Will it escape? (y/n)\nplay 0.5\ntick 200\nsay three\n";
    let mut s = Explorer::headless(
        app(),
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        false,
    );
    s.start_lesson(Driver::new("t", parse(script).unwrap()));
    s.pump_lesson().unwrap();
    // Paused by the lesson's `pause`, held at its wait with the caption up.
    assert!(!s.app.playing() && s.app.lesson().waiting);
    assert_eq!(s.app.lesson().caption.as_deref(), Some("one"));
    let screen = turntable::ui::export::plain_text(s.screen());
    assert!(screen.contains("Enter: go on · Space plays"), "{screen}");
    // Space plays the scene while it waits: time goes on, the lesson holds.
    press(&mut s, "space");
    assert!(s.app.playing() && s.app.lesson().waiting);
    let tau = s.app.now().tau;
    s.tick();
    s.pump_lesson().unwrap();
    assert!(s.app.now().tau > tau);
    assert!(s.app.lesson().waiting);
    let screen = turntable::ui::export::plain_text(s.screen());
    assert!(screen.contains("Enter: go on · Space pauses"), "{screen}");
    // Space again pauses, and still the lesson waits; Enter goes on.
    press(&mut s, "space");
    s.pump_lesson().unwrap();
    assert!(!s.app.playing() && s.app.lesson().waiting);
    press(&mut s, "enter");
    assert!(!s.app.lesson().waiting);
    s.pump_lesson().unwrap();
    // The lesson's `play` set time going whatever the keys did; `tick 3` counts.
    assert!(s.app.playing());
    s.tick();
    // Enter while the lesson moves on by itself: it says so (it spoke of the pages' Enter).
    press(&mut s, "enter");
    assert_eq!(
        s.app.notice().as_deref(),
        Some("the lesson goes on by itself here: Enter at its next stop")
    );
    // A pause from the keys holds the lesson inside its `tick 3`, however long.
    press(&mut s, "space");
    for _ in 0..10 {
        s.tick();
        s.pump_lesson().unwrap();
    }
    assert_eq!(s.app.lesson().caption.as_deref(), Some("one"));
    press(&mut s, "space");
    s.tick();
    s.pump_lesson().unwrap();
    assert_eq!(
        s.app.lesson().caption.as_deref(),
        Some("one"),
        "two ticks of three"
    );
    s.tick();
    s.pump_lesson().unwrap();
    assert_eq!(s.app.lesson().caption, None);
    let q = s.app.lesson().question.clone().unwrap();
    assert_eq!((q.text.as_str(), q.answer), ("Will it escape? (y/n)", None));
    // Held at the question: Enter says what it waits for and changes nothing (on a spin-up
    // it said the page was refused); n answers and does not step.
    s.pump_lesson().unwrap();
    assert!(s.app.lesson().question.is_some());
    let (init, page) = (s.app.initial(), s.app.view().page);
    press(&mut s, "enter");
    assert_eq!((s.app.initial(), s.app.view().page), (init, page));
    assert_eq!(s.app.lesson().question.as_ref().unwrap().answer, None);
    assert_eq!(
        s.app.notice().as_deref(),
        Some("the question first: y if it escapes, n if it stays")
    );
    press(&mut s, "n");
    assert!(!s.app.view().step_mode);
    assert_eq!(
        s.app.lesson().question.as_ref().unwrap().answer,
        Some(false)
    );
    // A speed key before the lesson's `play 0.5`: the scene plays at the speed it names.
    press(&mut s, "]");
    s.pump_lesson().unwrap();
    assert!(s.app.playing());
    assert_eq!(s.app.speed(), 0.5);
    for _ in 0..199 {
        s.tick();
        s.pump_lesson().unwrap();
    }
    assert!(s.app.lesson().question.is_some(), "after 199 of 200 ticks");
    s.tick();
    s.pump_lesson().unwrap();
    assert_eq!(s.app.lesson().caption.as_deref(), Some("three"));
    assert!(s.app.lesson().done);
    // Unheld, n is the integrator step again.
    press(&mut s, "n");
    assert!(s.app.view().step_mode);
    // The last words stay until Esc says they were read, then the screen is the scene's.
    let screen = turntable::ui::export::plain_text(s.screen());
    assert!(screen.contains("three") && screen.contains("end · Esc closes · q quits"));
    press(&mut s, "esc");
    for _ in 0..3 {
        s.tick();
        s.pump_lesson().unwrap();
    }
    assert!(s.app.lesson().done && s.app.caption().is_none());
    let screen = turntable::ui::export::plain_text(s.screen());
    assert!(
        !screen.contains("three") && !screen.contains("lesson"),
        "{screen}"
    );
}

/// A `wait` holds time as well as the lesson: a preset left playing stands still while the
/// class reads (Space still plays it), and Enter takes time up as the wait found it.
#[test]
fn a_wait_holds_time_and_enter_takes_it_up() {
    let mut s = Explorer::headless(
        app(),
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        false,
    );
    let script = "2\nplay\nsay one\nwait\ntick 3\nsay two\nwait\npause\nsay three\nwait\n";
    s.start_lesson(Driver::new("t", parse(script).unwrap()));
    s.pump_lesson().unwrap();
    assert!(s.app.lesson().waiting && !s.app.playing());
    let screen = turntable::ui::export::plain_text(s.screen());
    assert!(screen.contains("Enter: go on · Space plays"), "{screen}");
    press(&mut s, "enter");
    assert!(s.app.playing(), "Enter takes time up as the wait found it");
    for _ in 0..3 {
        s.pump_lesson().unwrap();
        s.tick();
    }
    s.pump_lesson().unwrap();
    assert_eq!(s.app.lesson().caption.as_deref(), Some("two"));
    assert!(s.app.lesson().waiting && !s.app.playing());
    // Space plays the scene at a wait; Enter leaves it playing, and the lesson's `pause`
    // then holds it.
    press(&mut s, "space");
    assert!(s.app.playing() && s.app.lesson().waiting);
    press(&mut s, "enter");
    assert!(s.app.playing());
    s.pump_lesson().unwrap();
    assert_eq!(s.app.lesson().caption.as_deref(), Some("three"));
    // A wait that found time paused leaves it paused after Enter.
    assert!(!s.app.playing());
    press(&mut s, "enter");
    assert!(!s.app.playing());
}

/// The run answers the prediction: right or not by the engine's outcome, and only once time
/// has moved on from the question (scene C sticks; fig2 is decided at τ = 0).
#[test]
fn the_run_answers_the_prediction() {
    let mut s = Explorer::headless(
        app(),
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        false,
    );
    fn text(
        s: &mut Explorer<ratatui::backend::TestBackend>,
        script: &str,
    ) -> (String, Option<&'static str>) {
        for step in parse(script).unwrap() {
            s.apply(&step);
        }
        let c = s.app.caption().unwrap();
        (c.text, c.prompt)
    }
    let (t, prompt) = text(&mut s, "ask Will it escape?");
    assert_eq!(
        (t.as_str(), prompt),
        (
            "Will it escape?",
            Some("y escapes · n stays · Space pauses")
        )
    );
    let (t, prompt) = text(&mut s, "y");
    assert_eq!(t, "Will it escape?\nYou said it escapes. Watch the run.");
    assert_eq!(prompt, Some("Space pauses"));
    let (t, _) = text(&mut s, "tick 130");
    assert_eq!(
        t,
        "Will it escape?\nNot so: you said it escapes, but it sticks at ξ = 0.9972 (τ = 5.602)."
    );
    let (t, _) = text(&mut s, "3\nask Will C escape?\nn\ntick 130");
    assert_eq!(
        t,
        "Will C escape?\nRight: it sticks at ξ = 0.9972 (τ = 5.602)."
    );
    let (t, _) = text(&mut s, "6\npause\nask Will it escape?");
    assert_eq!(t, "Will it escape?", "decided at τ = 0, not yet told");
    // Nor do the title and the panel tell it (the scene's words say it escapes).
    let screen = turntable::ui::export::plain_text(s.screen());
    assert!(!screen.contains("escape certified"), "{screen}");
    assert!(
        !screen.contains("at rest on the table at ξ0 = 1.1"),
        "{screen}"
    );
    assert!(screen.contains("y or n: will it escape?"), "{screen}");
    let (t, _) = text(&mut s, "play\ntick");
    assert_eq!(
        t,
        "Will it escape?\nThe run: it escapes (certified at τ = 0.000)."
    );
    // Answered late, the answer still counts.
    let (t, _) = text(&mut s, "n");
    assert!(
        t.ends_with(
            "Not so: you said it does not escape, but it escapes (certified at τ = 0.000)."
        ),
        "{t}"
    );
    // A caption replaces the question; `say` alone clears it.
    let (t, _) = text(&mut s, "say Next.");
    assert_eq!(t, "Next.");
    assert!(text_none(&mut s, "say"));
}

fn text_none(s: &mut Explorer<ratatui::backend::TestBackend>, script: &str) -> bool {
    for step in parse(script).unwrap() {
        s.apply(&step);
    }
    s.app.caption().is_none()
}

fn turntable(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_turntable"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn the_lesson_command() {
    // `lesson` alone lists them, as --list does.
    for args in [&["lesson", "--list"][..], &["lesson"]] {
        let out = turntable(args);
        assert!(out.status.success());
        let list = String::from_utf8(out.stdout).unwrap();
        assert_eq!(list.lines().count(), LESSONS.len(), "{list}");
        for l in LESSONS {
            assert!(list.contains(l.name) && list.contains(l.about), "{list}");
        }
    }
    for bad in [&["lesson", "nope"][..], &["lesson", "nope", "--headless"]] {
        let out = turntable(bad);
        assert_eq!(out.status.code(), Some(2), "{bad:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(out.stdout.is_empty(), "{bad:?}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("stick, cases, escape"), "{err}");
        assert!(err.contains("unknown lesson 'nope'"), "{err}");
    }
    // A lesson of one's own, from its file, runs as a built-in one does (named by its stem).
    let dir = std::env::temp_dir().join(format!("turntable-own-lesson-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let own = dir.join("inertia.keys");
    std::fs::write(
        &own,
        "# replay: --size 60x20\n2\npause\nsay Newton's first law, on a table.\nsnapshot set\nplay 0.25\ntick 40\nsnapshot slid\n",
    )
    .unwrap();
    let out = turntable(&["lesson", own.to_str().unwrap(), "--headless"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("--- snapshot 1: set (60x20, tau=0.000)"),
        "{text}"
    );
    assert!(
        text.contains("--- snapshot 2: slid (60x20, tau=0.500)"),
        "{text}"
    );
    assert!(text.contains("lesson: inertia"), "{text}");
    assert!(text.contains("Newton's first law, on a"), "{text}");
    assert!(text.contains("×1/4"), "{text}");
    // A bad one says where.
    std::fs::write(&own, "play 3\n").unwrap();
    let out = turntable(&["lesson", own.to_str().unwrap(), "--headless"]);
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("line 1, column 6") && err.contains("power of two"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
    // --size without --headless is refused; headless prints the snapshots as replay does.
    let out = turntable(&["lesson", "stick", "--size", "40x12"]);
    assert_eq!(out.status.code(), Some(2));
    let out = turntable(&["lesson", "STICK", "--headless", "--size", "40x12"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("--- snapshot 1: at rest on the table at ξ0 = 0.9 (40x12"));
    // Interactive, with no terminal: refused before the screen is touched.
    let out = turntable(&["lesson", "cases"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
}

/// The caption at every size from the smallest up, with more words than fit: never a panic,
/// whole words on every row of the box, and `…` where the rest is left out.
#[test]
fn a_long_caption_at_every_size() {
    let words = "Friction alone holds a particle on the turning table; ".repeat(80);
    let whole: std::collections::HashSet<&str> = words.split_whitespace().collect();
    for (w, h) in (40..=120)
        .step_by(9)
        .flat_map(|w| (12..=40).step_by(7).map(move |h| (w, h)))
    {
        let mut s = Explorer::headless(
            app(),
            turntable::theme::Theme::builtin("dark").unwrap(),
            w,
            h,
            false,
        );
        s.app.say(Some(words.as_str().into()));
        let screen = turntable::ui::export::plain_text(s.screen());
        let rows: Vec<&str> = screen
            .lines()
            .filter_map(|l| l.strip_prefix('│'))
            .filter_map(|l| l.split('│').next())
            .filter(|l| l.starts_with("Friction") || l.starts_with("alone") || l.contains("table;"))
            .collect();
        assert!(!rows.is_empty(), "{w}×{h}:\n{screen}");
        for r in &rows {
            for word in r.split_whitespace() {
                assert!(
                    whole.contains(word) || word == "…",
                    "{w}×{h}: '{word}' cut in\n{screen}"
                );
            }
        }
        assert!(screen.contains(" …"), "{w}×{h}:\n{screen}");
    }
    // Too small for the explorer: its notice, and no caption.
    let mut s = Explorer::headless(
        app(),
        turntable::theme::Theme::builtin("dark").unwrap(),
        39,
        11,
        false,
    );
    s.app.say(Some(words.into()));
    assert!(turntable::ui::export::plain_text(s.screen()).contains("too small"));
}

/// What a lesson's scene is, where the lesson holds: what its script names (the release,
/// the settings, the page and frame, the caption and question), the same whatever the keys.
#[derive(Debug, PartialEq)]
struct Held {
    at: usize,
    initial: Initial,
    settings: Settings,
    page: turntable::app::pages::Page,
    frame: turntable::engine::Frame,
    caption: Option<String>,
    question: Option<String>,
}

fn held(s: &Explorer<ratatui::backend::TestBackend>) -> Held {
    Held {
        at: s.lesson().unwrap().taken(),
        initial: s.app.initial(),
        settings: s.app.settings(),
        page: s.app.view().page,
        frame: s.app.view().frame,
        caption: s.app.lesson().caption.as_ref().map(|c| c.to_string()),
        question: s.app.lesson().question.as_ref().map(|q| q.text.to_string()),
    }
}

/// Keys a teacher presses to pace a class: play/pause, step, speed.
const PACING: [&str; 5] = ["space", ".", ",", "[", "]"];

/// Runs lesson `name` as the terminal loop does (a tick only while time plays), pressing
/// each of `keys` (`(gap, key, times)`: `gap` loop turns after the one before) between its
/// ticks; at a wait or a question the user goes on (Enter, y), and plays when paused. Returns
/// the scene at each hold point, and checks that a pacing key never moves the lesson.
fn take_lesson(name: &str, keys: &[(u16, usize, u8)]) -> Vec<Held> {
    let steps = parse(find(name).unwrap().script).unwrap();
    let mut s = Explorer::headless(
        app(),
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        false,
    );
    s.start_lesson(Driver::new(name, steps));
    s.pump_lesson().unwrap();
    let (mut out, mut last, mut presses) = (Vec::new(), usize::MAX, keys.iter().peekable());
    let mut due = keys.first().map_or(0, |k| usize::from(k.0));
    for turn in 0..20_000 {
        if s.app.lesson().done {
            return out;
        }
        let at = s.lesson().unwrap().taken();
        if at != last {
            out.push(held(&s));
            last = at;
        }
        while turn >= due
            && let Some((_, k, n)) = presses.next()
        {
            due = turn + presses.peek().map_or(0, |k| usize::from(k.0));
            for _ in 0..*n {
                press(&mut s, PACING[*k]);
                s.pump_lesson().unwrap();
                assert_eq!(
                    s.lesson().unwrap().taken(),
                    at,
                    "{name}: `{}` moved the lesson on",
                    PACING[*k]
                );
            }
        }
        if s.app.lesson().waiting {
            press(&mut s, "enter");
        } else if s
            .app
            .lesson()
            .question
            .as_ref()
            .is_some_and(|q| q.answer.is_none())
        {
            press(&mut s, "y");
        } else if !s.app.playing() {
            press(&mut s, "space");
        } else {
            s.tick();
        }
        s.pump_lesson().unwrap();
    }
    panic!("{name}: the lesson did not end");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: crate::common::budget("TURNTABLE_FUZZ", 8) as u32 + 4,
        ..Default::default()
    })]
    /// Any pause, step and speed keys between a lesson's own steps: the lesson reaches each
    /// hold point with its scene as the script names it, and reaches its end.
    #[test]
    fn pacing_keys_never_put_a_lesson_out_of_step(
        lesson in 0..LESSONS.len(),
        keys in proptest::collection::vec((1u16..120, 0..PACING.len(), 1u8..4), 1..40),
    ) {
        let name = LESSONS[lesson].name;
        let reference = take_lesson(name, &[]);
        let taken = take_lesson(name, &keys);
        proptest::prop_assert_eq!(reference, taken);
    }
}

/// `lesson --check` says what a teacher should know before class: a lesson that never holds,
/// a caption that replaces a verdict before it is read.
#[test]
fn the_lesson_check_finds_the_authoring_traps() {
    let dir = std::env::temp_dir().join(format!("turntable-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let check = |script: &str| {
        let f = dir.join("l.keys");
        std::fs::write(&f, script).unwrap();
        let out = turntable(&["lesson", f.to_str().unwrap(), "--check"]);
        let err = String::from_utf8(out.stderr).unwrap();
        (
            out.status.code(),
            String::from_utf8(out.stdout).unwrap() + &err,
        )
    };
    let (code, text) = check("say one\nplay\ntick 60\nsay two\n");
    assert_eq!(code, Some(0));
    assert_eq!(
        text,
        "lesson l: 2 captions, 0 questions, 0 waits; 2 s of play between the holds\n\
         the lesson never holds (no wait, no ask): in the explorer it runs to its end in 2 s\n"
    );
    let (_, text) = check("say one\nwait\nask Out? (y/n)\nsay two\npause\nwait\n");
    assert!(text.contains("1 question, 2 waits"), "{text}");
    assert!(
        text.contains("line 4: this say replaces the question of line 3"),
        "{text}"
    );
    // Three seconds of play after the answer leave its verdict time to be read.
    let (_, text) = check("pause\nask Out? (y/n)\nplay\ntick 90\nsay two\npause\nwait\n");
    assert!(text.ends_with("nothing to warn of\n"), "{text}");
    // A script that does not parse is refused as replay refuses it.
    let (code, text) = check("say one\nbogus\n");
    assert_eq!(code, Some(2));
    assert!(text.contains("line 2, column 1"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
    // The shipped lessons hold and no caption hides a verdict.
    for l in LESSONS {
        let out = turntable(&["lesson", l.name, "--check"]);
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(out.status.success() && !text.contains("replaces"), "{text}");
    }
}

/// Lesson forces: friction against the slip, the forces of each frame, the finite stop and
/// its bound, Stokes drag, the energy bound on escape.
fn forces_claims() -> Vec<Claim> {
    use turntable::engine::stokes::{Stokes, growth_rate};
    let c = |k: &'static str, f: Box<dyn Fn()>| -> Claim { (k, f) };
    let b = || converged(preset("B"), 50.0);
    vec![
        // Friction is −û, against u = v − ẑ×r, not v: at B's throw 40° off −v.
        c(
            "40",
            Box::new(|| {
                let s = preset("B").state();
                let u = s.v - turntable::engine::model::zcross(s.r);
                assert_eq!(u, s.u());
                let fr = turntable::engine::model::friction(u, glam::DVec2::X);
                assert!((fr + u.normalize()).length() < 1e-15);
                assert!(shows(fr.angle_to(-s.v).abs().to_degrees(), "40"));
            }),
        ),
        // Friction's strength 1; γ = 1; and along B's run the slip falls at least at 1 − ξ
        // (d|u|/dτ ≤ ξ − 1 over every step, ξ growing), and E = ½|u|² − ½ξ² falls by the
        // path's length (dE/dτ = −|u|).
        c(
            "1",
            Box::new(|| {
                let f =
                    turntable::engine::model::friction(glam::DVec2::new(0.3, -0.4), glam::DVec2::X);
                assert!((f.length() - 1.0).abs() < 1e-15);
                let run = states(preset("B"), 50.0);
                let mut path = 0.0;
                for w in run.windows(2) {
                    let (a, z) = (&w[0], &w[1]);
                    let dt = z.tau - a.tau;
                    assert!(z.xi() >= a.xi());
                    if dt > 0.0 {
                        let rate = (z.u().length() - a.u().length()) / dt;
                        assert!(rate <= z.xi() - 1.0 + 1e-9, "{rate} at ξ = {}", z.xi());
                    }
                    path += (z.q() - a.q()).length();
                }
                let (e0, e1) = (run[0].energy(), run.last().unwrap().energy());
                assert!(
                    e0 - e1 >= path - 1e-9 && (e0 - e1 - path) < 1e-3 * path,
                    "{e0} {e1} {path}"
                );
            }),
        ),
        // Stokes drag is 0 at u = 0: at rest on the table inside ξ = 1 it is not held.
        c(
            "0",
            Box::new(|| {
                let s = Stokes::new(1.0, Initial::at_rest(0.5, Release::TableRest));
                assert!(s.escape().is_some());
            }),
        ),
        c(
            "2.7001",
            Box::new(move || {
                let (o, _, tau) = b();
                assert_eq!(o, Outcome::Stuck);
                assert!(shows(tau, "2.7001"), "{tau}");
            }),
        ),
        c("0.9453", Box::new(move || assert!(shows(b().1, "0.9453")))),
        c("0.6", Box::new(|| assert_eq!(preset("B").v0, 0.6))),
        c(
            "10.96",
            Box::new(move || {
                let (_, xi, tau) = b();
                let bound = 0.6 / (1.0 - xi);
                assert!(shows(bound, "10.96") && tau <= bound, "{bound}");
            }),
        ),
        c(
            "1.0409",
            Box::new(|| {
                let t = Stokes::new(1.0, preset("B")).escape().unwrap();
                assert!(shows(t, "1.0409"), "{t}");
            }),
        ),
        c(
            "0.300",
            Box::new(|| {
                let s = Stokes::new(1.0, preset("B"));
                assert!(shows(growth_rate(1.0), "0.300") && s.growth() == growth_rate(1.0));
                // Far out, ξ grows at that rate.
                let (x20, x30) = (s.at(20.0).0.length(), s.at(30.0).0.length());
                assert!(shows((x30 / x20).ln() / 10.0, "0.300"));
            }),
        ),
        // ξ0 of A and B, and the bound 1 − ξ0 there.
        c(
            "0.5",
            Box::new(|| {
                assert_eq!((preset("A").xi0, preset("B").xi0), (0.5, 0.5));
                assert!(least_ve(0.5) >= 1.0 - 0.5);
            }),
        ),
        c(
            "0.3134",
            Box::new(|| {
                assert_eq!(preset("A"), Initial::velocity(0.5, PI, 1.0));
                let (o, xi, _) = converged(preset("A"), 50.0);
                assert_eq!(o, Outcome::Stuck);
                assert!(shows(xi, "0.3134"));
            }),
        ),
        c(
            "0.5700",
            Box::new(|| assert!(shows(least_ve(0.5), "0.5700"))),
        ),
        c("0.2", Box::new(|| assert!(least_ve(0.2) >= 1.0 - 0.2))),
        c(
            "0.9274",
            Box::new(|| assert!(shows(least_ve(0.2), "0.9274"), "{}", least_ve(0.2))),
        ),
        c("0.8", Box::new(|| assert!(shows(1.0 - 0.2, "0.8")))),
    ]
}

/// Lesson slow: Sec. III's closed forms against converged runs, and properties 3-4.
fn slow_claims() -> Vec<Claim> {
    let c = |k: &'static str, f: Box<dyn Fn()>| -> Claim { (k, f) };
    let fig2 = || Initial::at_rest(1.1, Release::TableRest);
    let fig1 = || Initial::at_rest(500.0, Release::LabRest);
    let cosh = |tau: f64| (1.1 - 1.0) * f64::cosh(tau) + 1.0;
    let theta_dot = move |tau: f64| at(fig2(), tau).theta_dot().unwrap();
    vec![
        c("1.1", Box::new(move || assert_eq!(preset("fig2"), fig2()))),
        // At rest on the table θ′ = 1; friction's strength 1 (ξ″ − ξ = −1); the snapshot's τ.
        c(
            "1",
            Box::new(move || {
                assert!((fig2().state().theta_dot().unwrap() - 1.0).abs() < 1e-15);
                let f =
                    turntable::engine::model::friction(glam::DVec2::new(0.3, -0.4), glam::DVec2::X);
                assert!((f.length() - 1.0).abs() < 1e-15);
            }),
        ),
        c(
            "1.1525",
            Box::new(move || assert!(shows(at(fig2(), 1.0).xi(), "1.1525"))),
        ),
        c(
            "1.1543",
            Box::new(move || assert!(shows(cosh(1.0), "1.1543"))),
        ),
        c(
            "3",
            Box::new(move || assert!(shows(at(fig2(), 3.0).tau, "3"))),
        ),
        c(
            "1.7228",
            Box::new(move || assert!(shows(at(fig2(), 3.0).xi(), "1.7228"))),
        ),
        c(
            "2.0068",
            Box::new(move || assert!(shows(cosh(3.0), "2.0068"))),
        ),
        // θ′ > 0 all along (property 3), and between 0 and 1 as it leaves (property 4).
        c(
            "0",
            Box::new(move || {
                let run = states(fig2(), 12.0);
                assert!(run.iter().all(|s| s.theta_dot().unwrap() > 0.0));
                assert!(run.iter().all(|s| s.theta_dot().unwrap() <= 1.0 + 1e-12));
                assert_eq!(converged(fig2(), 50.0).0, Outcome::Escaped);
            }),
        ),
        c("5", Box::new(move || assert!(theta_dot(5.0) < 1.0))),
        c(
            "0.5258",
            Box::new(move || assert!(shows(theta_dot(5.0), "0.5258"))),
        ),
        c(
            "10",
            Box::new(move || assert!(theta_dot(10.0) < theta_dot(5.0))),
        ),
        c(
            "0.2237",
            Box::new(move || assert!(shows(theta_dot(10.0), "0.2237"))),
        ),
        c(
            "500",
            Box::new(move || {
                assert_eq!(preset("fig1"), fig1());
                assert_eq!(converged(fig1(), 50.0).0, Outcome::Escaped);
            }),
        ),
        c(
            "0.1",
            Box::new(|| assert!(shows(10f64.powi(2) / (2.0 * 500.0), "0.1"))),
        ),
        c(
            "501.67",
            Box::new(|| assert!(shows(500.0 + 10f64.powi(4) / (12.0 * 500.0), "501.67"))),
        ),
        c(
            "0.0998",
            Box::new(move || {
                let s = at(fig1(), 10.0);
                assert!(shows(s.r.y.atan2(s.r.x), "0.0998"));
            }),
        ),
        c(
            "501.66",
            Box::new(move || assert!(shows(at(fig1(), 10.0).xi(), "501.66"))),
        ),
    ]
}
