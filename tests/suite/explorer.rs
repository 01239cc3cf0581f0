//! The explorer driven headless: keys and ticks into `App`, frames rendered on a `TestBackend`.

use crate::common;
use common::render;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use turntable::app::keymap::KEYMAP;
use turntable::app::pages::Page;
use turntable::app::testing::Testing as _;
use turntable::app::{Action, App, Chord};
use turntable::engine::{Frame, Outcome, Run, Settings, Status};
use turntable::present::num;
use turntable::scene::{PRESETS, Scene};
use turntable::session::Explorer;
use turntable::sim::testing::Testing as _;
use turntable::theme::Theme;

fn theme() -> Theme {
    Theme::builtin("dark").expect("dark theme")
}

fn app(scene: &str) -> App {
    App::new(Scene::preset(scene).unwrap())
}

/// A key pressed, and what it asks for carried out as the explorer's session does (files
/// written).
fn key(app: &mut App, c: char) {
    press(app, KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE));
}

fn press(app: &mut App, k: KeyEvent) {
    let effects = app.handle_key(k);
    turntable::session::carry_out(app, effects);
}

/// The canvas part of a screen (left of the panel at 80 columns).
fn canvas_part(screen: &str) -> String {
    screen
        .lines()
        .skip(2)
        .take(20)
        .map(|l| l.chars().take(48).collect::<String>())
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn frame_toggle_redraws_the_same_trail_in_the_other_frame() {
    let mut a = app("B");
    for _ in 0..60 {
        a.tick();
    }
    key(&mut a, ' ');
    let n = a.sim().trail().len();
    let lab = render(&mut a, 80, 24);
    assert!(lab.contains("lab frame"));
    key(&mut a, 'f');
    assert_eq!(a.view().frame, Frame::Table);
    let rot = render(&mut a, 80, 24);
    assert!(rot.contains("rotating frame"));
    assert_eq!(a.sim().trail().len(), n, "the trail is stored once");
    assert_ne!(canvas_part(&lab), canvas_part(&rot));
    key(&mut a, 'f');
    assert_eq!(canvas_part(&render(&mut a, 80, 24)), canvas_part(&lab));
}

#[test]
fn preset_b_run_to_the_end_says_stuck_at_the_engines_xi() {
    let mut a = app("C");
    key(&mut a, '2');
    assert_eq!(a.scene().name, "B");
    for _ in 0..2000 {
        if a.sim().outcome_now() == Outcome::Stuck {
            break;
        }
        a.tick();
    }
    let mut run = Run::new(a.initial(), Settings::default()).unwrap();
    let (out, _) = run.finish(100.0).unwrap();
    assert_eq!(out, Outcome::Stuck);
    let Status::Stuck { tau, q } = run.status() else {
        panic!()
    };
    let Status::Stuck { tau: t2, q: q2 } = a.sim().status() else {
        panic!("app run not stuck: {:?}", a.sim().status())
    };
    assert!((q.length() - q2.length()).abs() < 1e-12 && (tau - t2).abs() < 1e-12);
    let xi = num(q.length(), 5);
    assert!(xi.starts_with("0.945"), "{xi}");
    let screen = render(&mut a, 80, 24);
    assert!(screen.contains(&format!("stuck at ξ = {xi}")), "{screen}");
    assert!(
        screen.contains(&format!("since τ = {}", num(tau, 3))),
        "{screen}"
    );
}

#[test]
fn readouts_equal_the_engine_state() {
    let mut a = app("A");
    for _ in 0..23 {
        a.tick();
    }
    let s = a.sim().now();
    assert!((s.tau - 23.0 * turntable::app::TICK_DT).abs() < 1e-9);
    let mut run = Run::new(a.initial(), a.settings()).unwrap();
    run.run(s.tau, false).unwrap();
    let e = run.state_at(s.tau).unwrap();
    assert!((e.r - s.r).length() < 1e-8, "{e:?} vs {s:?}");
    let screen = render(&mut a, 80, 24);
    for v in [
        num(s.tau, 3),
        num(s.xi(), 5),
        num(s.xi_dot(), 4),
        num(s.u().length(), 4),
        num(s.theta_dot().unwrap(), 4),
        format!(
            "steps  {} rej {}",
            a.sim().cost().steps,
            a.sim().cost().rejected
        ),
        format!("RHS    {}", a.sim().cost().rhs_evals),
        "dp54   tol=1e-10".to_string(),
    ] {
        assert!(screen.contains(&v), "missing {v} in\n{screen}");
    }
}

#[test]
fn theta_dot_at_the_centre_shows_a_dash_not_nan() {
    let mut scene = Scene::preset("B").unwrap();
    scene.initial.xi0 = 0.0;
    let mut a = App::new(scene);
    let screen = render(&mut a, 80, 24);
    assert!(screen.contains("θ′     —"), "{screen}");
    assert!(!screen.contains("NaN"));
    a.check_invariants().unwrap();
}

/// A fresh app part-way into scene C, zoomed in (so "auto-frame" has something to undo).
fn setup(dir: &std::path::Path) -> App {
    let mut a = app("C");
    a.tell_save_path(dir.join("scene.toml"));
    for _ in 0..10 {
        a.tick();
    }
    turntable::app::update(&mut a, Action::ZoomIn);
    a
}

#[test]
fn every_key_in_the_keymap_does_what_its_help_says() {
    let dir = std::env::temp_dir().join(format!("turntable-keys-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for b in KEYMAP {
        let mut a = setup(&dir);
        if b.action == Action::Dismiss {
            turntable::app::update(&mut a, Action::ToggleHelp);
        }
        if let Action::TauWindow(narrow) = b.action {
            crate::common::turn_to(&mut a, Page::TimePlots);
            // A window narrowed twice, so that widening it leaves it narrower than the run.
            for _ in 0..if narrow { 0 } else { 2 } {
                turntable::app::update(&mut a, Action::TauWindow(true));
            }
        }
        if matches!(b.action, Action::HelpScroll(_) | Action::HelpPage(_)) {
            turntable::app::update(&mut a, Action::ToggleHelp);
            render(&mut a, 80, 24);
            turntable::app::update(&mut a, Action::HelpScroll(5));
        }
        let window = a.view().tau_window;
        // The lesson's keys are live only while it asks or waits (a wait holds time, and
        // Enter takes it up as the wait found it).
        let played = a.playing();
        match b.action {
            Action::Answer(_) => a.ask("Will it escape? (y/n)".into()),
            Action::GoOn => a.wait(),
            _ => {}
        }
        let before = render(&mut a, 80, 24);
        let (tau, init, set) = (a.sim().now().tau, a.initial(), a.settings());
        let (speed, zoom, pan) = (a.speed(), a.view().zoom, a.view().pan);
        let init_playing = a.playing();
        press(&mut a, b.chord.event());
        let after = render(&mut a, 80, 24);
        let what = format!("{} ({})", b.chord.label(), b.help);
        match b.action {
            Action::Quit => assert!(a.should_quit(), "{what}"),
            _ => assert_ne!(before, after, "{what}: screen unchanged"),
        }
        let now = a.sim().now().tau;
        let ok = match b.action {
            Action::Quit => a.should_quit(),
            Action::Dismiss => !a.view().help && !a.should_quit(),
            Action::ToggleHelp => a.view().help && after.contains("help"),
            Action::HelpScroll(d) => i32::from(a.view().help_scroll) == 5 + i32::from(d),
            Action::TauWindow(true) => a.view().tau_window.is_some_and(|w| w < now),
            Action::TauWindow(false) => a.view().tau_window == window.map(|w| 2.0 * w),
            // A page down from 5 reaches the end of the help at 80x24 (as long as the keymap).
            Action::HelpPage(d) => {
                a.view().help_scroll
                    == if d > 0 {
                        turntable::ui::help::max_scroll(80, 24)
                    } else {
                        0
                    }
            }
            Action::PlayPause => !a.is_playing() && after.contains("❚❚"),
            Action::StepForward => now > tau && !a.is_playing(),
            Action::StepBack => now < tau,
            Action::PlaceRelease(_) | Action::AimVelocity(..) | Action::EndDrag => {
                unreachable!("mouse actions have no key")
            }
            Action::IntegratorStep => {
                a.view().step_mode && !a.is_playing() && after.contains("h      ")
            }
            Action::Faster => a.speed() == 2.0 * speed && after.contains("×2"),
            Action::Slower => a.speed() == speed / 2.0 && after.contains("×1/2"),
            Action::Restart => now == 0.0 && a.initial() == init,
            Action::ToggleFrame => a.view().frame == Frame::Table,
            Action::ToggleSplit => {
                a.view().split && after.contains("lab frame") && after.contains("rotating frame")
            }
            Action::CycleMethod => a.settings().method() != set.method() && now == 0.0,
            Action::Loosen => a.settings().scheme.knob() > set.scheme.knob() && now == 0.0,
            Action::Tighten => a.settings().scheme.knob() < set.scheme.knob() && now == 0.0,
            Action::Xi0(d) => (a.initial().xi0 - (init.xi0 + d)).abs() < 1e-12 && now == 0.0,
            Action::Phi(d) => {
                let w = turntable::engine::model::wrap_angle(init.phi + d);
                (a.initial().phi - w).abs() < 1e-12 && now == 0.0
            }
            Action::V0(d) => (a.initial().v0 - (init.v0 + d)).abs() < 1e-12 && now == 0.0,
            Action::CycleRelease => a.initial().release != init.release && now == 0.0,
            Action::ToggleFriction => {
                a.initial().frictionless
                    && now == 0.0
                    && a.sim().cost().rhs_evals == 0
                    && after.contains("μ = 0  closed form")
            }
            Action::ResetScene => a.initial() == a.scene().initial && now == 0.0,
            Action::Preset(i) => a.scene().name == PRESETS[i] && now == 0.0,
            Action::ToggleCompare => a.paper().is_some() && after.contains("paper: rk2-raw"),
            // In the lab (the default view) friction is the only force.
            Action::ToggleForces => {
                a.view().forces && after.contains("friction") && !after.contains("Coriolis")
            }
            Action::EstimateError => after.contains("|Δr| ="),
            Action::ToggleNetForce => a.view().net_force && after.contains("net net force"),
            Action::ToggleVelocity => a.view().velocity && after.contains("v  velocity (lab)"),
            // This scene has no body: `C` only says so (tests/suite/body.rs tries it with one).
            Action::TogglePointModel => {
                a.view().point_model && after.contains("no body to compare")
            }
            Action::PinRun => {
                a.pins().len() == 1 && after.contains("pinned ◆C") && after.contains("pins   ◆C")
            }
            Action::ClearPins => a.pins().is_empty() && after.contains("no pins to clear"),
            // Off at first: the first press turns SI units on at a record player's.
            Action::Unit(..) => {
                a.units() == Some(turntable::app::state::record_player())
                    && after.contains("SI units: μ 0.15")
            }
            Action::UnitsOff => a.units().is_none() && after.contains("SI units off"),
            Action::ZoomIn => a.view().zoom > zoom,
            Action::ZoomOut => a.view().zoom < zoom,
            Action::Pan(dx, dy) => {
                let d = a.view().pan - pan;
                d.x * dx > 0.0 || d.y * dy > 0.0
            }
            Action::ResetView => a.view().zoom == 1.0 && a.view().pan == glam::DVec2::ZERO,
            Action::SaveAs => typed(&a) == Some("") && after.contains("save as: ▏"),
            Action::SetValues => typed(&a) == Some("") && after.contains("set: ▏"),
            Action::Type(_) => unreachable!("typed at the prompt, bound to no key"),
            Action::Save => {
                after.contains("saved \"")
                    && Scene::load(a.save_path().to_str().unwrap())
                        .unwrap()
                        .initial
                        == a.initial()
            }
            Action::ExportSvg => {
                after.contains("wrote this page to")
                    && std::fs::read_to_string(dir.join("turntable-table-1.svg"))
                        .is_ok_and(|s| s.starts_with("<?xml"))
            }
            Action::ToggleMouse => !a.mouse_capture() && after.contains("mouse off"),
            // Alone, F2 says it is a served class's key (serve's session takes it first).
            Action::Follow => after.contains("F2 steps in and out of a class"),
            // The readouts in words, on the status line: τ, ξ, |u| and how the run stands.
            Action::Readouts => {
                a.readouts_asked() == 1
                    && after.contains(&format!(
                        " τ = {}, ξ = {}, |u| = ",
                        num(a.now().tau, 3),
                        num(a.now().xi(), 5)
                    ))
            }
            Action::NextPage => a.view().page == Page::TimePlots && after.contains("time plots"),
            Action::PrevPage => {
                a.view().page == Page::WorkPrecision && after.contains("work-precision")
            }
            Action::PickPoint(_) => after.contains("j/k pick a setting on the work-precision page"),
            Action::Choose => a.view().page == Page::Turntable && after.contains("Enter runs"),
            Action::PickRelease(_) => unreachable!("mouse actions have no key"),
            Action::Answer(yes) => {
                let q = a.lesson().question.as_ref().unwrap();
                q.answer == Some(yes)
                    && after.contains(if yes {
                        "You said it escapes"
                    } else {
                        "You said it does not"
                    })
            }
            Action::GoOn => !a.lesson().waiting && !init_playing && a.playing() == played,
            Action::Omega(d) => {
                (a.mu_probe().0 - (turntable::app::MU_PROBE.0 + d)).abs() < 1e-12
                    && after.contains("Ω = ")
            }
            Action::R0c(d) => {
                (a.mu_probe().1 - (turntable::app::MU_PROBE.1 + d)).abs() < 1e-12
                    && after.contains("r0c = ")
            }
        };
        assert!(ok, "{what} did not do what it says");
        a.check_invariants().unwrap();
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn esc_closes_help_before_quitting() {
    let mut a = app("C");
    key(&mut a, '?');
    a.handle_key(KeyEvent::new(KeyCode::Esc, KeyModifiers::NONE));
    assert!(!a.view().help && !a.should_quit());
    // Esc is the reflex for closing things: it never quits. q does.
    a.handle_key(KeyEvent::new(KeyCode::Esc, KeyModifiers::NONE));
    assert!(!a.should_quit());
    key(&mut a, 'q');
    assert!(a.should_quit());
}

/// Issue 33 item 8: the README says `q` and Ctrl-C quit; with the help open they used to
/// close it instead.
#[test]
fn q_and_ctrl_c_quit_with_the_help_open() {
    let mut a = app("C");
    key(&mut a, '?');
    assert!(a.view().help);
    key(&mut a, 'q');
    assert!(a.should_quit(), "q with the help open");
    let mut a = app("C");
    key(&mut a, '?');
    a.handle_key(KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL));
    assert!(a.should_quit(), "Ctrl-C with the help open");
}

#[test]
fn tiny_and_large_sizes_render_without_panic() {
    for (w, h) in [
        (0, 0),
        (1, 1),
        (10, 5),
        (39, 11),
        (40, 12),
        (59, 20),
        (80, 24),
        (160, 48),
    ] {
        let mut a = app("C");
        a.tick();
        let s = render(&mut a, w, h);
        if w >= 10 && h >= 5 && (w < 40 || h < 12) {
            assert!(s.contains("small"), "{w}×{h}:\n{s}");
        }
        if w >= 40 && h >= 12 {
            assert!(s.contains("τ"), "{w}×{h}:\n{s}");
        }
        key(&mut a, '?');
        render(&mut a, w, h);
    }
}

#[test]
fn help_overlay_lists_every_binding() {
    let mut a = app("C");
    key(&mut a, '?');
    let screen = render(&mut a, 160, 48);
    let rows = turntable::ui::help::rows();
    for (_, rs) in &rows {
        for (label, help) in rs {
            // The label, then at least two blanks, then the help: never glued.
            assert!(
                screen.lines().any(|l| l
                    .split_once(&format!(" {label}  "))
                    .is_some_and(|(_, rest)| rest.trim_start().starts_with(help))),
                "missing '{label}  {help}' in\n{screen}"
            );
        }
    }
    for b in KEYMAP {
        assert!(
            rows.iter().any(|(g, rs)| *g == b.group
                && rs.iter().any(|(l, h)| *h == b.help
                    && l.contains(b.chord.label().rsplit('-').next().unwrap()))),
            "{} not in help",
            b.chord.label()
        );
    }
    // 80×24 shows it in three pages (the last a row).
    let small = render(&mut a, 80, 24);
    // As many rows as the keymap makes: 21 on screen, the rest a page down (the scroll goes
    // one row further, for the group heading a scrolled column repeats at its top).
    let all = 20 + turntable::ui::help::max_scroll(80, 24);
    assert!(all > 30, "{all}");
    assert!(
        small.contains("presets A B C D fig1")
            && small.contains(&format!("rows 1–21 of {all}, ↓ more")),
        "{small}"
    );
    // The two columns put the lesson and app groups on the first page, the right column
    // headed by the group it opens in (issue 46 item 6).
    assert!(
        small.contains("y/n            answer yes / no")
            && small.contains("Esc            close help / notice")
            && small.contains("│time                                   view (cont.)"),
        "{small}"
    );
    assert!(
        !small.contains("/ onM") && !small.contains("fig2q"),
        "{small}"
    );
    a.handle_key(KeyEvent::new(KeyCode::PageDown, KeyModifiers::NONE));
    a.handle_key(KeyEvent::new(KeyCode::PageDown, KeyModifiers::NONE));
    let small = render(&mut a, 80, 24);
    assert!(
        small.contains("◆▲▼◇△▽         pinned runs (b)")
            && small.contains(&format!("rows {}–{all} of {all}", all - 19)),
        "{small}"
    );
}

/// Help scrolls at every size (↓ and the wheel) until every key, the mouse and the glyphs
/// have been on screen, and it says where the reader is (issue 18).
#[test]
fn help_scrolls_to_everything_at_every_size() {
    let labels: Vec<String> = turntable::ui::help::rows()
        .into_iter()
        .flat_map(|(_, rs)| rs.into_iter().map(|(l, _)| l))
        .chain(["click", "drag", "wheel", "●", "○", "■", "×", "·", "↺"].map(String::from))
        .collect();
    for (w, h) in [(40, 12), (56, 30), (59, 24), (60, 20), (80, 24), (200, 60)] {
        let mut a = app("C");
        key(&mut a, '?');
        let mut seen = render(&mut a, w, h);
        assert!(
            seen.contains("↑ ↓ PgUp PgDn wheel scroll") || w < 60,
            "{w}×{h}\n{seen}"
        );
        let first = seen.clone();
        for i in 0..100 {
            let before = a.view().help_scroll;
            if i % 2 == 0 {
                a.handle_key(KeyEvent::new(KeyCode::Down, KeyModifiers::NONE));
            } else {
                a.handle_mouse(MouseEvent {
                    kind: MouseEventKind::ScrollDown,
                    column: w / 2,
                    row: h / 2,
                    modifiers: KeyModifiers::NONE,
                });
            }
            seen += &render(&mut a, w, h);
            if a.view().help_scroll == before {
                break;
            }
        }
        for l in &labels {
            assert!(
                seen.contains(&format!(" {l} ")),
                "{w}×{h}: '{l}' never shown"
            );
        }
        if first.contains("↓ more") {
            assert!(a.view().help_scroll > 0 && !render(&mut a, w, h).contains("↓ more"));
        }
        // Back to the top with PgUp.
        for _ in 0..20 {
            a.handle_key(KeyEvent::new(KeyCode::PageUp, KeyModifiers::NONE));
        }
        assert_eq!(render(&mut a, w, h), first, "{w}×{h}");
    }
}

#[test]
fn scene_c_shows_the_paper_escaping_where_the_converged_run_sticks() {
    let mut a = app("C");
    key(&mut a, 'c');
    for _ in 0..3 {
        key(&mut a, ']');
    }
    for _ in 0..400 {
        a.tick();
        if a.paper().unwrap().outcome_now() == Outcome::Escaped {
            break;
        }
    }
    let Status::Stuck { q, .. } = a.sim().status() else {
        panic!("converged run not stuck")
    };
    assert!((q.length() - 0.99717).abs() < 1e-4, "{}", q.length());
    let esc = a.paper().unwrap().escape().unwrap().tau;
    assert!((esc - 17.3).abs() < 0.1, "{esc}");
    let screen = render(&mut a, 80, 24);
    assert!(screen.contains(&format!("stuck at ξ = {}", num(q.length(), 5))));
    assert!(
        screen.contains("escape certified") && screen.contains(&format!("at τ = {}", num(esc, 3)))
    );
    assert!(
        screen.contains("steps over the stop and escapes"),
        "{screen}"
    );
}

#[test]
fn paused_and_idle_needs_no_redraw() {
    let mut a = app("C");
    render(&mut a, 80, 24);
    assert!(!a.needs_redraw());
    a.tick();
    assert!(a.needs_redraw(), "playing: a tick changes the picture");
    key(&mut a, ' ');
    render(&mut a, 80, 24);
    for _ in 0..5 {
        a.tick();
    }
    assert!(!a.needs_redraw());
}

#[test]
fn same_keys_give_the_same_screens() {
    let keys = "c]]x.v,,fa+R";
    let run = || {
        let mut a = app("C");
        let mut shots = Vec::new();
        for c in keys.chars() {
            key(&mut a, c);
            a.tick();
            a.tick();
            shots.push(render(&mut a, 80, 24));
        }
        shots
    };
    assert_eq!(run(), run());
}

#[test]
fn mouse_click_places_the_release_point_and_drag_sets_the_velocity() {
    let mut a = app("B");
    render(&mut a, 80, 24);
    let g = a.geom_for_tests().unwrap();
    // The cell under world point (0.8, 0).
    let (col, row) = crate::common::cell_under(&g, 0.8, 0.0);
    let ev = crate::common::mouse;
    a.handle_mouse(ev(MouseEventKind::Down(MouseButton::Left), col, row));
    assert!((a.initial().xi0 - 0.8).abs() < 0.1, "{}", a.initial().xi0);
    a.handle_mouse(ev(
        MouseEventKind::Drag(MouseButton::Left),
        col,
        row.saturating_sub(3),
    ));
    assert!(a.initial().v0 > 0.0);
    a.handle_mouse(ev(
        MouseEventKind::Up(MouseButton::Left),
        col,
        row.saturating_sub(3),
    ));
    assert_eq!(a.sim().now().tau, 0.0);
    a.check_invariants().unwrap();
    key(&mut a, 'M');
    let xi0 = a.initial().xi0;
    a.handle_mouse(ev(MouseEventKind::Down(MouseButton::Left), col + 5, row));
    assert_eq!(a.initial().xi0, xi0, "mouse off: clicks do nothing");
}

#[test]
fn random_keys_keep_the_invariants() {
    let mut a = app("C");
    // `S` then Enter, or `E`, write files: into a folder of the test's own.
    let dir = std::env::temp_dir().join(format!("turntable-random-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    a.tell_save_path(dir.join("scene.toml"));
    let mut x: u64 = 0x9E3779B97F4A7C15;
    for i in 0..1500 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let b = &KEYMAP[(x % KEYMAP.len() as u64) as usize];
        if matches!(b.action, Action::Quit | Action::Save | Action::ToggleHelp) {
            a.tick();
            continue;
        }
        a.handle_key(b.chord.event());
        a.tick();
        a.check_invariants()
            .unwrap_or_else(|e| panic!("after {i} keys ({}): {e}", b.chord.label()));
        if i % 50 == 0 {
            let s = render(&mut a, 80, 24);
            assert!(!s.contains("NaN") && !s.contains("inf"), "{s}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_scene_or_theme_exits_2_before_touching_the_terminal() {
    let bin = env!("CARGO_BIN_EXE_turntable");
    for args in [["--scene", "nope"], ["--theme", "nope"]] {
        let out = std::process::Command::new(bin)
            .env("XDG_CONFIG_HOME", "/nonexistent/turntable-tests/config")
            .args(args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(out.stdout.is_empty(), "no escape codes on stdout");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("nope"), "{err}");
    }
}

/// No key is bound twice in one mode: a lesson's bindings (y/n while it asks, Space/Enter
/// while it waits) take their keys only then.
#[test]
fn no_key_is_bound_twice() {
    use turntable::app::action::Group;
    use turntable::app::keymap::lookup_when;
    use turntable::app::lesson::Prompt;
    let mode = |a: Action| match a {
        Action::Answer(_) => Prompt::Answer,
        Action::GoOn => Prompt::GoOn,
        _ => Prompt::None,
    };
    for (i, a) in KEYMAP.iter().enumerate() {
        for b in &KEYMAP[i + 1..] {
            let lesson = |x: &turntable::app::Binding| x.action.group() == Group::Lesson;
            let apart = lesson(a) != lesson(b) || mode(a.action) != mode(b.action);
            assert!(
                a.chord != b.chord || apart,
                "{} bound twice",
                a.chord.label()
            );
        }
        let sent = turntable::app::Chord::from_event(&a.chord.event());
        assert_eq!(sent, Some(a.chord), "{} is not in normal form", a.chord);
        assert_eq!(
            lookup_when(a.chord, mode(a.action)),
            Some(a.action),
            "{} does not dispatch to its own action",
            a.chord.label()
        );
        if mode(a.action) != Prompt::None {
            assert_ne!(turntable::app::keymap::lookup(a.chord), Some(a.action));
        }
    }
}

#[test]
fn every_builtin_theme_renders_every_preset() {
    for t in ["dark", "light", "high-contrast", "mono"] {
        let theme = Theme::builtin(t).unwrap_or_else(|| panic!("theme {t}"));
        for p in PRESETS {
            let mut a = App::new(Scene::preset(p).unwrap());
            key(&mut a, 'c');
            key(&mut a, 'a');
            for _ in 0..20 {
                a.tick();
            }
            let s = common::render_with(&mut a, &theme, 80, 24);
            assert!(s.contains(&format!("scene {p}")), "{t} {p}:\n{s}");
            a.check_invariants().unwrap();
        }
    }
}

/// `e` estimates the error of the state on screen from a shadow run: tiny for the default
/// dp54, large for the paper's raw RK2 once it has crept past the stop.
#[test]
fn error_estimate_tells_converged_from_creeping() {
    let mut a = app("B");
    assert!(a.is_playing());
    for _ in 0..80 {
        a.tick();
    }
    let e = a.sim().error_estimate().unwrap();
    assert!(e.tau > 3.0 && e.error < 1e-9, "{e:?}");
    key(&mut a, 'e');
    assert!(render(&mut a, 100, 30).contains("|Δr| ="));
    let mut raw =
        turntable::sim::Sim::new(a.initial(), turntable::engine::Settings::paper(), 10.0).unwrap();
    for _ in 0..80 {
        raw.advance(0.05);
    }
    let e = raw.error_estimate().unwrap();
    assert!(e.error > 1e-4 && e.error < 1e-2, "{e:?}");
}

/// Where a world point is drawn on the last rendered canvas: the cell whose centre maps
/// nearest to it.
fn cell_of(a: &App, p: glam::DVec2) -> (u16, u16) {
    let g = a.geom_for_tests().unwrap();
    let mut best = (0, 0, f64::INFINITY);
    for row in g.area.y..g.area.y + g.area.height {
        for col in g.area.x..g.area.x + g.area.width {
            let w = g.to_world(col, row).unwrap();
            let d = (w - p).length();
            if d < best.2 {
                best = (col, row, d);
            }
        }
    }
    (best.0, best.1)
}

/// A click upper-left of the centre puts the release point there, angle included: the
/// picture turns, the model keeps its release on +x (rotational symmetry).
#[test]
fn a_click_places_the_release_where_clicked() {
    use crossterm::event::{MouseButton, MouseEvent, MouseEventKind};
    let mut a = app("C");
    key(&mut a, ' ');
    render(&mut a, 80, 24);
    let target = glam::DVec2::new(-0.4, 0.4);
    let (col, row) = cell_of(&a, target);
    let centre = cell_of(&a, glam::DVec2::ZERO);
    a.handle_mouse(MouseEvent {
        kind: MouseEventKind::Down(MouseButton::Left),
        column: col,
        row,
        modifiers: KeyModifiers::NONE,
    });
    let angle = 0.75 * std::f64::consts::PI;
    assert!(
        (a.view().turn - angle).abs() < 0.2,
        "turn {}",
        a.view().turn
    );
    assert!(
        (a.initial().xi0 - 0.4 * 2f64.sqrt()).abs() < 0.12,
        "{}",
        a.initial().xi0
    );
    assert_eq!(a.initial().phi, 0.0, "the model's release is unchanged");
    let screen = render(&mut a, 80, 24);
    let (pc, pr) = screen
        .lines()
        .enumerate()
        .find_map(|(r, l)| {
            l.chars()
                .position(|c| c == '●')
                .map(|c| (c as u16, r as u16))
        })
        .unwrap();
    assert!(
        pc < centre.0 && pr < centre.1,
        "● at {pc},{pr}, centre {centre:?}\n{screen}"
    );
    // The same cell maps back to the release point in the model.
    let back = a.geom_for_tests().unwrap().to_world(col, row).unwrap();
    assert!(
        (back - glam::DVec2::new(a.initial().xi0, 0.0)).length() < 0.1,
        "{back}"
    );
}

/// Forces in the frame shown: friction alone in the lab, three in the rotating frame, the
/// longest a fifth of the visible half-width, labelled; stuck, a square glyph and a mark.
#[test]
fn forces_marks_and_glyphs_follow_the_frame() {
    use turntable::ui::canvas::{FORCE_SHARE, force_arrows};
    let mut a = app("C");
    for _ in 0..6 {
        a.tick();
    }
    for zoom_ins in [0, 2] {
        for _ in 0..zoom_ins {
            turntable::app::update(&mut a, Action::ZoomIn);
        }
        let lab = force_arrows(&a, 2.0);
        assert_eq!(lab.iter().map(|f| f.word).collect::<Vec<_>>(), ["friction"]);
        assert!((lab[0].vec.length() - FORCE_SHARE * 2.0).abs() < 1e-12);
        key(&mut a, 'f');
        let rot = force_arrows(&a, 2.0);
        assert_eq!(
            rot.iter().map(|f| f.word).collect::<Vec<_>>(),
            ["friction", "Coriolis", "centrifugal"]
        );
        let longest = rot.iter().map(|f| f.vec.length()).fold(0.0, f64::max);
        assert!((longest - FORCE_SHARE * 2.0).abs() < 1e-12);
        key(&mut a, 'f');
    }
    turntable::app::update(&mut a, Action::ResetView);
    key(&mut a, 'F');
    assert!(
        force_arrows(&a, 2.0).is_empty(),
        "μ = 0: no force in the lab"
    );
    key(&mut a, 'F');
    key(&mut a, 'a');
    let screen = render(&mut a, 80, 24);
    assert!(
        screen.contains("fr friction") && !screen.contains("Coriolis"),
        "{screen}"
    );
    assert!(
        screen.contains("ξ=1 (R_max)") && screen.contains("↺ table"),
        "{screen}"
    );
    for _ in 0..200 {
        a.tick();
    }
    let screen = render(&mut a, 80, 24);
    assert!(screen.contains('■') && !screen.contains('●'), "{screen}");
    // In the lab the mark rides the table with the particle: where it rests on the table now.
    // C stops within 1 % of the rim: the label says where, inside ξ = 1.
    assert!(screen.contains("■ stuck ξ=0.99717<1 τ=5.60"), "{screen}");
}

/// Layout by priority: at every size down to 40×12 the status and ξ stay on screen, sliding
/// or stuck.
#[test]
fn status_and_xi_survive_every_size() {
    for ticks in [3, 200] {
        let mut a = app("C");
        for _ in 0..ticks {
            a.tick();
        }
        let word = if ticks == 3 {
            "slipping"
        } else {
            "stuck at ξ"
        };
        for w in (40..=200).step_by(7) {
            for h in (12..=60).step_by(4) {
                let s = render(&mut a, w, h);
                assert!(s.contains(word), "{w}×{h}: no '{word}'\n{s}");
                assert!(
                    s.contains("ξ      ") || s.contains("stuck at ξ = "),
                    "{w}×{h}: no ξ readout\n{s}"
                );
            }
        }
    }
}

/// The trail comes from the run's dense output on a fixed τ grid: at ×256 it is the same
/// smooth curve as at ×1 (no chords across the table), and its points are bounded.
#[test]
fn the_trail_is_the_same_at_every_speed() {
    let mut slow = app("C");
    let mut fast = app("C");
    for _ in 0..8 {
        key(&mut fast, ']');
    }
    assert_eq!(fast.speed(), 256.0);
    fast.tick();
    while slow.sim().now().tau < fast.sim().now().tau - 1e-9 {
        slow.tick();
    }
    let (a, b) = (slow.sim().trail(), fast.sim().trail());
    assert!(a.len() > 300, "{}", a.len());
    assert_eq!(a.len(), b.len());
    for (p, q) in a.iter().zip(b) {
        assert_eq!(p.tau, q.tau);
        assert!((p.r - q.r).length() < 1e-12, "{p:?} {q:?}");
    }
    // Neighbouring points are close: no chord longer than the speed allows over one step.
    for w in b.windows(2) {
        let gap = (w[1].r - w[0].r).length();
        assert!(
            gap <= 2.0 * turntable::sim::TRAIL_DT,
            "{gap} at τ = {}",
            w[0].tau
        );
    }
    // Stuck, one turn of the table is the whole circle: the path stops growing.
    for _ in 0..50 {
        fast.tick();
    }
    let n = fast.sim().path.len();
    assert!(n < 2 * (12.8 / turntable::sim::TRAIL_DT) as usize, "{n}");
}

/// Step mode: `n` takes exactly one integrator step. Toward C's stop dp54's steps shrink
/// (implicit steps where explicit ones would be held to the stability limit, then the stop
/// within the tolerance in closed form); rk2-raw steps at dt through it and never stops.
#[test]
fn integrator_steps_one_at_a_time() {
    use turntable::engine::Limit;
    let mut a = app("C");
    for _ in 0..108 {
        a.tick();
    }
    let mut hs = Vec::new();
    let mut limits = Vec::new();
    for _ in 0..200 {
        let before = a.sim().cost();
        key(&mut a, 'n');
        assert!(a.view().step_mode && !a.playing());
        let st = a.sim().last_step().unwrap();
        if hs.len() > 1 {
            let c = a.sim().cost();
            let taken = (c.steps - before.steps) + (c.rejected - before.rejected);
            assert!(
                taken <= 1 + u64::from(st.rejected),
                "{taken} steps in one key"
            );
        }
        hs.push(st.h);
        limits.push(st.limit);
        if a.sim().outcome() != Outcome::Running {
            break;
        }
    }
    assert_eq!(a.sim().outcome(), Outcome::Stuck);
    assert_eq!(*limits.last().unwrap(), Limit::ClosedForm, "{limits:?}");
    assert!(limits.contains(&Limit::Implicit), "{limits:?}");
    assert!(hs[hs.len() - 2] < 0.5 * hs[1], "{hs:?}");
    assert_eq!(a.sim().step_marks.len(), hs.len());
    let screen = render(&mut a, 100, 30);
    assert!(
        screen.contains("h      ") && screen.contains('·'),
        "{screen}"
    );

    let mut a = app("C");
    key(&mut a, 'm'); // dop853
    key(&mut a, 'm'); // rk2-raw
    for _ in 0..112 {
        a.tick();
    }
    for _ in 0..50 {
        key(&mut a, 'n');
        let st = a.sim().last_step().unwrap();
        assert_eq!((st.h, st.limit), (1e-3, Limit::FixedStep));
    }
    assert_eq!(a.sim().outcome(), Outcome::Running);
}

/// SI units from the keys: the first press turns them on at a record player's (33⅓ rpm), the next change
/// μ, rpm and g; the panel and the time plots' axes show SI values; Alt-u turns them off.
#[test]
fn unit_keys_give_si_readouts_and_axes() {
    let mut a = App::new(Scene::default_scene());
    let press = |a: &mut App, c: char, m: KeyModifiers| {
        a.handle_key(KeyEvent::new(KeyCode::Char(c), m));
    };
    press(&mut a, 'u', KeyModifiers::NONE);
    assert_eq!(a.units(), Some(turntable::app::state::record_player()));
    press(&mut a, 'u', KeyModifiers::NONE);
    press(&mut a, 'w', KeyModifiers::NONE);
    press(&mut a, 'G', KeyModifiers::NONE);
    let u = a.units().unwrap();
    let paper = turntable::app::state::record_player();
    assert!((u.mu - 0.16).abs() < 1e-12, "{u:?}");
    assert!((u.rpm - (paper.rpm + 1.0)).abs() < 1e-9, "{u:?}");
    assert!((u.g - 9.8).abs() < 1e-12, "{u:?}");
    let screen = render(&mut a, 100, 30);
    // R_max = μg/Ω² for this table, as the notice says.
    let r_max = 0.16 * 9.8 / (u.omega() * u.omega());
    let shown = turntable::present::si_length(r_max);
    assert!(screen.contains(&shown), "{shown}\n{screen}");
    // The time plots' axes carry the unit's SI value.
    crate::common::turn_to(&mut a, Page::TimePlots);
    let screen = render(&mut a, 100, 30);
    let tau = turntable::present::si_time(1.0 / u.omega());
    assert!(screen.contains(&format!("τ (1 = {tau})")), "{screen}");
    assert!(screen.contains(&format!("ξ (1 = {shown})")), "{screen}");
    press(&mut a, 'u', KeyModifiers::ALT);
    assert_eq!(a.units(), None);
    let screen = render(&mut a, 100, 30);
    assert!(!screen.contains("(1 ="), "{screen}");
}

/// A preset loads as itself: D's φ = 1.2π is held as −0.8π, the same angle, so the title keeps
/// the preset's words and `s` saves it under its own name (issue 18).
#[test]
fn every_preset_loads_unedited() {
    for name in PRESETS {
        let a = app(name);
        assert!(!a.edited(), "{name}");
        let scene = a.current_scene();
        assert_eq!(scene.name, name);
        assert_eq!(scene.about, Scene::preset(name).unwrap().about);
    }
    let mut d = app("D");
    assert!(render(&mut d, 100, 30).contains("Fig. 3 D: comes to rest on the table inside ξ = 1"));
    key(&mut d, 'p');
    assert!(d.edited() && d.current_scene().name == "D (edited)");
}

/// The initial-velocity arrow lies beneath the trail (issue 18): in the rotating frame D's
/// path runs along its arrow, and every cell the arrow shares with the trail shows the trail.
#[test]
fn the_trail_is_drawn_over_the_initial_velocity_arrow() {
    let th = theme();
    assert_ne!(th.trail, th.arrow);
    let mut a = app("D");
    key(&mut a, 'f');
    for _ in 0..40 {
        a.tick();
    }
    let mut t = ratatui::Terminal::new(ratatui::backend::TestBackend::new(80, 24)).unwrap();
    a.resize(80, 24);
    t.draw(|f| {
        turntable::ui::draw(f, &a, &turntable::theme::Theme::builtin("dark").unwrap());
    })
    .unwrap();
    let buf = t.backend().buffer().clone();
    let count = |c| buf.content.iter().filter(|x| x.fg == c).count();
    let (trail, arrow) = (count(th.trail), count(th.arrow));
    // Before, the arrow covered the whole path: 0 trail cells against the arrow's 8.
    assert!(trail >= 4 && trail >= arrow, "trail {trail} arrow {arrow}");
}

/// A step is one tick at the speed now, through history too (issue 18): after ×64 play and
/// back to ×1, `,` goes back 0.05 in τ (it went back a ×64 tick, 3.2), `.` forward again.
#[test]
fn steps_through_fast_history_are_one_tick_at_the_speed_now() {
    let mut a = app("A");
    key(&mut a, 'c');
    for _ in 0..6 {
        key(&mut a, ']');
    }
    for _ in 0..3 {
        a.tick();
    }
    for _ in 0..6 {
        key(&mut a, '[');
    }
    assert_eq!(a.speed(), 1.0);
    let t0 = a.sim().now().tau;
    assert!((t0 - 9.6).abs() < 1e-9, "{t0}");
    key(&mut a, ',');
    let t1 = a.sim().now().tau;
    assert!((t0 - t1 - 0.05).abs() < 1e-9, "{t0} → {t1}");
    assert!((a.paper().unwrap().now().tau - t1).abs() < 1e-9);
    // The state there is the run's own (at rest, riding the table), not a copy of another.
    let Status::Stuck { q, .. } = a.sim().status() else {
        panic!("A sticks")
    };
    assert_eq!(a.sim().now(), turntable::engine::State::riding(q, t1));
    key(&mut a, ',');
    assert!((a.sim().now().tau - (t0 - 0.1)).abs() < 1e-9);
    key(&mut a, '.');
    assert!((a.sim().now().tau - (t0 - 0.05)).abs() < 1e-9);
    key(&mut a, '.');
    key(&mut a, '.');
    assert!((a.sim().now().tau - (t0 + 0.05)).abs() < 1e-9);
    a.check_invariants().unwrap();
    // Still sliding, the state a tick back is the path's, on its τ grid.
    let mut c = app("C");
    key(&mut c, ']');
    key(&mut c, ']');
    for _ in 0..3 {
        c.tick();
    }
    key(&mut c, '[');
    key(&mut c, '[');
    key(&mut c, ',');
    let now = c.sim().now();
    assert!((now.tau - 0.55).abs() < 1e-9 && c.sim().status() == Status::Slipping);
    assert!(c.sim().path.contains(&now));
}

/// The title tells what is on screen at the τ on screen, in the panel's notation; `s` saves
/// how the run ends (nothing while undecided) and the view (issue 18).
#[test]
fn the_title_and_a_saved_scene_tell_what_is_on_screen() {
    let dir = std::env::temp_dir().join(format!("turntable-about-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut a = app("C");
    key(&mut a, 'V');
    a.tick();
    a.tick();
    // The integrator looks ahead of the screen; the title reads the screen's τ.
    let shown = a.sim().now().tau;
    assert!(a.sim().run_tau() > shown, "{} {shown}", a.sim().run_tau());
    let screen = render(&mut a, 100, 30);
    let title = screen.lines().next().unwrap().to_string();
    assert!(
        title.contains(&format!("C, edited: sliding at τ = {}", num(shown, 3))),
        "{title}"
    );
    assert!(!title.contains("tau") && !title.contains("xi"), "{title}");
    // Undecided: saved with the release in words, nothing about its end.
    a.tell_save_path(dir.join("undecided.toml"));
    key(&mut a, 's');
    let saved = Scene::load(dir.join("undecided.toml").to_str().unwrap()).unwrap();
    assert_eq!(
        (saved.name.as_str(), saved.about.as_str()),
        ("C (edited)", "released at ξ0 = 0.5, φ = 0, v0 = 0.6068")
    );
    // An unedited preset saved under a name of one's own keeps its words (the title too).
    let mut b = app("B");
    b.tell_save_path(dir.join("b.toml"));
    turntable::app::update(&mut b, Action::SaveAs);
    for c in "mine".chars() {
        b.press(Chord::new(KeyCode::Char(c), KeyModifiers::NONE));
    }
    let effects = b.press("enter".parse().unwrap());
    turntable::session::carry_out(&mut b, effects);
    let saved = Scene::load(dir.join("mine.toml").to_str().unwrap()).unwrap();
    assert_eq!(saved.about, Scene::preset("B").unwrap().about);
    let mut back = App::new(saved);
    let title = render(&mut back, 100, 30)
        .lines()
        .next()
        .unwrap()
        .to_string();
    assert!(
        title.contains("comes to rest on the table, thrown outward"),
        "{title}"
    );
    // Decided: how it ends, and the view it was shown in.
    for _ in 0..200 {
        a.tick();
    }
    let Status::Stuck { tau, q } = a.sim().status() else {
        panic!("C with v0 − 0.001 sticks")
    };
    key(&mut a, 'f');
    key(&mut a, 'a');
    key(&mut a, '+');
    key(&mut a, 'x');
    key(&mut a, 'X');
    a.tell_save_path(dir.join("decided.toml"));
    // x then X: the edit is undone, the run restarted; play it to its end again.
    for _ in 0..200 {
        a.tick();
    }
    key(&mut a, 's');
    let saved = Scene::load(dir.join("decided.toml").to_str().unwrap()).unwrap();
    assert_eq!(
        saved.about,
        format!("sticks at ξ = {} (τ = {})", num(q.length(), 4), num(tau, 3))
    );
    let view = saved.view.unwrap();
    assert_eq!(
        (view.frame, view.forces, view.zoom),
        (Frame::Table, true, a.view().zoom)
    );
    assert!(view.zoom > 1.0);
    let back = App::new(saved);
    assert_eq!(
        (back.view().frame, back.view().forces, back.view().zoom),
        (Frame::Table, true, a.view().zoom)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `m` goes from dp54 to dop853 keeping the tolerance (both adaptive), then to the fixed-step
/// methods at the paper's dt; the panel names the method and its knob.
#[test]
fn method_key_reaches_dop853_with_the_same_tol() {
    use turntable::engine::method::Scheme;
    let mut a = app("C");
    key(&mut a, '>');
    key(&mut a, '>');
    assert_eq!(a.settings().scheme, Scheme::Dp54 { tol: 1e-11 });
    key(&mut a, 'm');
    assert_eq!(a.settings().scheme, Scheme::Dop853 { tol: 1e-11 });
    let screen = render(&mut a, 100, 30);
    assert!(screen.contains("dop853"), "{screen}");
    for _ in 0..400 {
        a.tick();
    }
    assert_eq!(a.sim().outcome(), Outcome::Stuck);
    key(&mut a, 'm');
    assert_eq!(a.settings().scheme, Scheme::Rk2Raw { dt: 1e-3 });
}

/// `update` dispatches on the action's group: every key is listed in help under the group
/// whose module handles it, and every group is one the help shows.
#[test]
fn every_binding_is_listed_under_its_actions_group() {
    use turntable::app::action::Group;
    use turntable::app::keymap::GROUPS;
    for b in KEYMAP {
        assert_eq!(b.group, b.action.group().name(), "{}", b.chord.label());
    }
    let all = [
        Group::Time,
        Group::InitialConditions,
        Group::Integrator,
        Group::View,
        Group::App,
        Group::Lesson,
    ];
    assert_eq!(all.map(Group::name), GROUPS);
    // The mouse sets the release: its actions are initial conditions.
    let p = glam::DVec2::new(0.5, 0.1);
    for a in [
        Action::PlaceRelease(p),
        Action::AimVelocity(p, Frame::Lab),
        Action::PickRelease(p),
    ] {
        assert_eq!(a.group(), Group::InitialConditions);
    }
}

/// The footer says what Space does now: pause while playing, play while paused.
#[test]
fn footer_names_what_space_does_now() {
    for (w, h) in [(80, 24), (140, 40)] {
        let mut a = app("C");
        assert!(a.playing());
        let last = |a: &mut App| render(a, w, h).lines().last().unwrap().to_string();
        let playing = last(&mut a);
        assert!(playing.contains("Space pause"), "{playing}");
        assert!(!playing.contains("Space play"), "{playing}");
        key(&mut a, ' ');
        let paused = last(&mut a);
        assert!(paused.contains("Space play"), "{paused}");
    }
}

/// `S` names the scene before saving (issue 18 item 7): while the prompt is open keys are the
/// name's letters (`q` quits nothing, `x` edits nothing), Backspace takes one back, Enter
/// saves to a file named after it, Esc saves nothing. The prompt shows what is typed.
#[test]
fn s_names_the_scene_it_saves() {
    let dir = std::env::temp_dir().join(format!("turntable-name-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut a = app("D");
    a.tell_save_path(dir.join("turntable-scene.toml"));
    let xi0 = a.initial().xi0;
    key(&mut a, 'S');
    for c in "Case Dx, μ × 2q".chars() {
        key(&mut a, c);
    }
    press(
        &mut a,
        KeyEvent::new(KeyCode::Backspace, KeyModifiers::NONE),
    );
    assert!(!a.should_quit());
    assert_eq!(a.initial().xi0, xi0, "x typed a letter, no edit");
    assert_eq!(typed(&a), Some("Case Dx, μ × 2"));
    let screen = render(&mut a, 40, 12);
    assert!(
        screen.contains(" save as: Case Dx, μ × 2▏"),
        "the prompt shows what is typed:\n{screen}"
    );
    press(&mut a, KeyEvent::new(KeyCode::Enter, KeyModifiers::NONE));
    assert!(a.prompt().is_none());
    let path = dir.join("case-dx-μ-2.toml");
    let saved = Scene::load(path.to_str().unwrap()).unwrap();
    assert_eq!(saved.name, "Case Dx, μ × 2");
    assert_eq!(saved.initial, a.initial());
    assert!(a.notice().as_deref().unwrap().contains("case-dx-μ-2.toml"));
    // The same name again: a new file beside it, never a replaced one.
    key(&mut a, 'S');
    for c in "case dx μ 2".chars() {
        key(&mut a, c);
    }
    press(&mut a, KeyEvent::new(KeyCode::Enter, KeyModifiers::NONE));
    assert!(dir.join("case-dx-μ-2-2.toml").exists());
    // Esc: nothing saved, and keys are keys again.
    key(&mut a, 'S');
    key(&mut a, 'z');
    press(&mut a, KeyEvent::new(KeyCode::Esc, KeyModifiers::NONE));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2);
    key(&mut a, 'x');
    assert!(a.initial().xi0 > xi0);
    // A name is at most TYPED_MAX characters.
    key(&mut a, 'S');
    for _ in 0..60 {
        key(&mut a, 'n');
    }
    assert_eq!(typed(&a).unwrap().chars().count(), 40);
    // Too long for 40 columns: its end stays in sight, by the cursor.
    let screen = render(&mut a, 40, 12);
    let prompt = screen.lines().last().unwrap();
    assert!(
        prompt.starts_with(" save as: nnnn") && prompt.trim_end().ends_with("n▏"),
        "{prompt}"
    );
    // Ctrl-C still quits from the prompt.
    press(
        &mut a,
        KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL),
    );
    assert!(a.should_quit());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A paste is the name at the save prompt (one line, recorded as the keys it typed) and
/// nothing elsewhere: a `q` in it quits nothing.
#[test]
fn a_paste_types_the_name_at_the_prompt_only() {
    use turntable::session::Explorer;
    let mut s = Explorer::headless(
        app("B"),
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        true,
    );
    s.paste("q x\nstill nothing");
    assert!(!s.app.should_quit() && s.app.prompt().is_none());
    assert_eq!(s.app.initial(), app("B").initial());
    s.press("S".parse().unwrap());
    s.paste("Fig. 3 B\r\n, again");
    assert_eq!(typed(&s.app), Some("Fig. 3 B, again"));
    let script = s.take_recording().unwrap();
    assert!(script.contains("S F i g"), "{script}");
    assert!(!script.contains("still"), "{script}");
}

/// `update` is pure: `s`, `S` then Enter, and `E` write no file; they return what to write.
/// The shell carries it out (the explorer's session writes it, a replay says what it would
/// have written) and reports back as a notice.
#[test]
fn saving_and_exporting_are_effects_the_shell_carries_out() {
    use turntable::app::action::Edit;
    use turntable::app::{Effect, update};
    let dir = std::env::temp_dir().join(format!("turntable-effects-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let files = || std::fs::read_dir(&dir).unwrap().count();
    let mut a = app("C");
    a.tell_save_path(dir.join("scene.toml"));
    let save = update(&mut a, Action::Save);
    assert!(
        matches!(&save[..], [Effect::SaveScene { scene, path }]
            if *path == a.save_path() && scene.initial == a.initial()),
        "{save:?}"
    );
    let export = update(&mut a, Action::ExportSvg);
    assert_eq!(
        export,
        [Effect::ExportSvg {
            dir: dir.clone(),
            page: Page::Turntable
        }]
    );
    assert!(update(&mut a, Action::SaveAs).is_empty());
    for c in "Mine".chars() {
        assert!(update(&mut a, Action::Type(Edit::Char(c))).is_empty());
    }
    let named = update(&mut a, Action::Type(Edit::Done));
    assert!(
        matches!(&named[..], [Effect::SaveScene { scene, path }]
            if scene.name == "Mine" && *path == dir.join("mine.toml")),
        "{named:?}"
    );
    assert_eq!(files(), 0, "update wrote nothing");
    // A replay answers them: a notice each, no file.
    let mut r = a.clone();
    turntable::replay::answer(&mut r, save.clone());
    assert!(
        r.notice()
            .as_deref()
            .unwrap()
            .starts_with("replay saves nothing: \""),
        "{:?}",
        r.notice()
    );
    turntable::replay::answer(&mut r, export.clone());
    assert_eq!(
        r.notice().as_deref(),
        Some("replay saves nothing: this page → turntable-table-N.svg (the first free N)")
    );
    assert_eq!(files(), 0, "a replay wrote nothing");
    // The explorer's shell writes them, and says where.
    turntable::session::carry_out(&mut a, save);
    assert!(a.notice().as_deref().unwrap().starts_with("saved \""));
    turntable::session::carry_out(&mut a, named);
    turntable::session::carry_out(&mut a, export);
    assert!(
        a.notice()
            .as_deref()
            .unwrap()
            .starts_with("wrote this page to")
    );
    assert!(dir.join("scene.toml").exists() && dir.join("mine.toml").exists());
    assert!(dir.join("turntable-table-1.svg").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// What is typed at the prompt, while it is open.
fn typed(a: &App) -> Option<&str> {
    a.prompt().as_ref().map(|p| p.typed.as_str())
}

/// `:` takes values as typed: the run restarts from them; a bad line is refused with the
/// reason beside it and kept to mend; Esc changes nothing.
#[test]
fn values_typed_at_the_prompt() {
    let mut s = Explorer::headless(
        App::new(Scene::preset("B").unwrap()),
        theme(),
        80,
        24,
        false,
    );
    let typed_keys = |s: &mut Explorer<ratatui::backend::TestBackend>, text: &str| {
        for c in text.chars() {
            s.press(Chord::new(KeyCode::Char(c), KeyModifiers::NONE));
        }
    };
    s.press(":".parse().unwrap());
    typed_keys(&mut s, "v0 0.6078");
    let screen = turntable::ui::export::plain_text(s.screen());
    assert!(screen.contains(" set: v0 0.6078▏"), "{screen}");
    s.press("enter".parse().unwrap());
    assert!(s.app.prompt().is_none());
    assert_eq!(s.app.initial().v0, 0.6078);
    assert_eq!(s.app.sim().now().tau, 0.0, "the run restarts");
    assert_eq!(
        s.app.notice().as_deref(),
        Some("set: ξ0 = 0.5, φ = 0, v0 = 0.6078")
    );
    // Refused: the reason beside the line, which stays to mend; nothing changes.
    s.press(":".parse().unwrap());
    typed_keys(&mut s, "xi0 -1");
    s.press("enter".parse().unwrap());
    let refused = s
        .app
        .prompt()
        .as_ref()
        .and_then(|p| p.refused.clone())
        .unwrap();
    assert!(refused.contains("xi0"), "{refused}");
    let screen = turntable::ui::export::plain_text(s.screen());
    assert!(screen.contains(" set: xi0 -1▏"), "{screen}");
    assert_eq!(s.app.initial().xi0, 0.5);
    s.press("backspace".parse().unwrap());
    s.press("backspace".parse().unwrap());
    typed_keys(&mut s, "1.1 phi 1.2pi mu 0.2");
    s.press("enter".parse().unwrap());
    let i = s.app.initial();
    assert_eq!(i.xi0, 1.1);
    assert!(
        (i.phi + 0.8 * std::f64::consts::PI).abs() < 1e-12,
        "{}",
        i.phi
    );
    assert_eq!(s.app.units().map(|u| u.mu), Some(0.2));
    // Esc: nothing set; q typed is a letter, not quit.
    s.press(":".parse().unwrap());
    typed_keys(&mut s, "q");
    assert!(!s.app.should_quit());
    s.press("esc".parse().unwrap());
    assert_eq!(
        (s.app.prompt().clone(), s.app.notice().as_deref()),
        (None, Some("nothing set"))
    );
    assert_eq!(s.app.initial().xi0, 1.1);
}
