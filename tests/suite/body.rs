//! The appendix's body (issue 23 item 3): its size from flags and scene files, and the
//! appendix's two conditions for treating it as a point, in `run --json` and on the panel.

use crate::common;
use common::turntable;
use turntable::app::exploration::testing::Testing as _;
use turntable::engine::Outcome;

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = turntable(args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

fn close(a: &serde_json::Value, b: f64) -> bool {
    (a.as_f64().unwrap() - b).abs() <= 1e-12 * b.abs().max(1e-300)
}

/// μh/L is μ_k f h/L, f the friction in units of μ_k m g: at rest on the table the centripetal
/// ξ it supplies, sliding 1; L/ξ at the end. μ_k from `--mu`, else the bound 1.
#[test]
fn run_json_reports_the_appendixs_conditions_at_the_end() {
    let body = ["--body-length", "0.02", "--body-height", "0.004"];
    // Case A comes to rest: f = ξ_rest.
    let mut a = vec![
        "run",
        "--xi0",
        "0.5",
        "--phi",
        "3.141592653589793",
        "--v0",
        "1",
    ];
    a.extend(body);
    a.extend(["--json", "--no-check", "--mu", "0.5", "--rpm", "30"]);
    let v = json(&a);
    assert_eq!(v["outcome"], "stuck");
    let xi = v["xi"].as_f64().unwrap();
    assert!(xi > 0.2 && xi < 0.5, "{xi}");
    let b = &v["body"];
    // μh/L is the run's largest, while sliding (f = 1), not the static friction at rest (ξ).
    assert!(close(&b["mu_h_over_l"], 0.5 * 0.004 / 0.02), "{b}");
    assert!(close(&b["l_over_xi"], 0.02 / xi), "{b}");
    assert_eq!(b["mu_assumed"], false);
    assert_eq!(b["point_ok"], true);
    assert_eq!(
        (b["length"].as_f64(), b["angle"].as_f64()),
        (Some(0.02), Some(0.0))
    );
    // Thrown out fast it escapes, sliding (f = 1); without --mu the bound μ_k = 1: h/L.
    let mut e = vec!["run", "--v0", "1"];
    e.extend(body);
    e.extend(["--json", "--no-check"]);
    let v = json(&e);
    assert_eq!(v["outcome"], "escaped");
    let b = &v["body"];
    assert!(close(&b["mu_h_over_l"], 0.2), "{b}");
    assert_eq!(b["mu_assumed"], true);
    // h/L = 0.2 is not ≪ 1 (> 0.1): out of its depth.
    assert_eq!(b["point_ok"], false);
    // No height: toppling is not judged; a point-sized body is fine.
    let v = json(&[
        "run",
        "--v0",
        "1",
        "--body-length",
        "1e-6",
        "--json",
        "--no-check",
    ]);
    assert_eq!(v["body"]["mu_h_over_l"], serde_json::Value::Null);
    assert_eq!(v["body"]["point_ok"], true);
    // The two-mass body integrated from the same release: a tiny one rests where the point does
    // (case A), a longer one measurably elsewhere.
    let a = [
        "run",
        "--xi0",
        "0.5",
        "--phi",
        "3.141592653589793",
        "--v0",
        "1",
        "--json",
        "--no-check",
    ];
    let v = json(&[&a[..], &["--body-length", "1e-6"]].concat());
    let m = &v["body"]["motion"];
    assert_eq!(m["outcome"], "stuck");
    assert!(
        close(&m["xi"], v["xi"].as_f64().unwrap())
            || (m["xi"].as_f64().unwrap() - v["xi"].as_f64().unwrap()).abs() < 1e-9,
        "{v}"
    );
    let v = json(&[&a[..], &["--body-length", "0.05"]].concat());
    let m = &v["body"]["motion"];
    let d = m["xi"].as_f64().unwrap() - v["xi"].as_f64().unwrap();
    assert!(d.abs() > 1e-5 && d.abs() < 1e-2, "{d}");
    // Stokes drag has no stick to model.
    let v = json(&[
        "run",
        "--coupling",
        "stokes",
        "--gamma",
        "1",
        "--body-length",
        "0.1",
        "--json",
        "--no-check",
    ]);
    assert_eq!(v["body"]["motion"], serde_json::Value::Null);
    // Without a body, no `body` field.
    let v = json(&["run", "--json", "--no-check"]);
    assert!(v.get("body").is_none(), "{v}");
}

#[test]
fn bad_body_sizes_exit_2() {
    for bad in [
        &["run", "--body-length", "0"][..],
        &["run", "--body-length", "-0.1"],
        &["run", "--body-length", "nan"],
        &["run", "--body-length", "inf"],
        &["run", "--body-length", "0.1", "--body-height", "-1"],
        &["run", "--body-length", "0.1", "--body-angle", "nan"],
        &["run", "--body-height", "0.1"],
        &["run", "--body-angle", "1"],
        // The explorer refuses before it opens a terminal.
        &["--body-length", "-1"],
        &["--body-angle", "1"],
    ] {
        let (code, _, err) = turntable(bad);
        assert_eq!(code, 2, "{bad:?}: {err}");
        assert!(err.contains("body"), "{bad:?}: {err}");
    }
}

fn scene_file(name: &str, body: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("turntable-body-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(
        &path,
        format!("name = \"{name}\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.6\n[body]\n{body}"),
    )
    .unwrap();
    path
}

fn panel(scene: turntable::scene::Scene, ticks: usize) -> Vec<String> {
    let mut app = turntable::app::App::new(scene);
    for _ in 0..ticks {
        app.tick();
    }
    turntable::ui::panel::lines(&app, &turntable::theme::Theme::builtin("dark").unwrap())
        .iter()
        .map(|l| l.to_string())
        .collect()
}

/// A scene's `[body]` reaches the panel: the two numbers and their verdicts, live, and the
/// warning once either is not ≪ 1; the scene saves it back; bad values are refused.
#[test]
fn scene_body_shows_the_conditions_on_the_panel() {
    let small = scene_file(
        "small.toml",
        "length = 0.01\nheight = 0.0005\nangle = 0.25\n",
    );
    let scene = turntable::scene::Scene::load(small.to_str().unwrap()).unwrap();
    let body = scene.body.unwrap();
    assert_eq!(
        (body.length, body.height, body.angle),
        (0.01, Some(0.0005), 0.25)
    );
    let lines = panel(scene.clone(), 0);
    let has =
        |lines: &[String], a: &str, b: &str| lines.iter().any(|l| l.contains(a) && l.contains(b));
    // At release, sliding: μh/L ≤ 1 · 0.05; L/ξ = 0.01/0.5.
    assert!(has(&lines, "μh/L", "≤ 0.0500 ≪ 1 ok"), "{lines:?}");
    assert!(has(&lines, "L/ξ", "0.0200 ≪ 1 ok"), "{lines:?}");
    assert!(
        !lines.iter().any(|l| l.contains("out of its depth")),
        "{lines:?}"
    );
    // Saved with the scene.
    assert!(scene.to_toml().contains("[body]"), "{}", scene.to_toml());
    // A long body: L/ξ = 0.5 at release, not ≪ 1, and the warning.
    let long = scene_file("long.toml", "length = 0.25\n");
    let scene = turntable::scene::Scene::load(long.to_str().unwrap()).unwrap();
    let lines = panel(scene.clone(), 0);
    assert!(has(&lines, "L/ξ", "0.5000 not ≪ 1"), "{lines:?}");
    assert!(has(&lines, "μh/L", "no height given"), "{lines:?}");
    assert!(
        lines
            .iter()
            .any(|l| l.contains("point model out of its depth")),
        "{lines:?}"
    );
    // The body itself is drawn, a bar between its masses: the picture differs from the point's.
    let mut with = turntable::app::App::new(scene.clone());
    assert!(with.rod().is_some());
    let mut bare = scene;
    bare.body = None;
    let mut without = turntable::app::App::new(bare);
    assert!(without.rod().is_none());
    let (a, b) = (
        common::render(&mut with, 100, 30),
        common::render(&mut without, 100, 30),
    );
    let canvas = |s: &str| {
        s.lines()
            .map(|l| l.chars().take(70).collect::<String>())
            .collect::<Vec<_>>()
    };
    assert_ne!(canvas(&a), canvas(&b));
    for bad in [
        "length = 0\n",
        "length = -1\n",
        "length = 0.1\nheight = -0.1\n",
        "height = 0.1\n",
        "length = 0.1\nwidth = 1\n",
    ] {
        let path = scene_file("bad.toml", bad);
        let e = turntable::scene::Scene::load(path.to_str().unwrap()).unwrap_err();
        assert!(e.to_string().contains("bad.toml"), "{bad}: {e}");
    }
}

/// `sweep body` makes the appendix's "L ≪ r" a number: the rest radius of the two-mass body
/// departs from the point's as (L/r)², not L/r (cases A and B: a tenth of L, a hundredth of the
/// error), and not at all at L = 1e-6.
#[test]
fn sweep_body_measures_the_rest_radius_error_against_l_over_r() {
    for release in [
        &["--xi0", "0.5", "--phi", "3.141592653589793", "--v0", "1"][..],
        &["--xi0", "0.5", "--phi", "0", "--v0", "0.6"],
    ] {
        let args = [
            &["sweep", "body"][..],
            release,
            &["--lengths", "1e-6,1e-3,1e-2"],
        ]
        .concat();
        let (code, out, err) = turntable(&args);
        assert_eq!(code, 0, "{err}");
        let mut lines = out.lines();
        assert_eq!(
            lines.next(),
            Some("length,l_over_r,outcome,xi,xi_point,xi_error,tau,tau_point")
        );
        let errs: Vec<f64> = lines
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                assert_eq!(f[2], "stuck", "{l}");
                f[5].parse().unwrap()
            })
            .collect();
        assert!(errs[0].abs() < 1e-9, "{errs:?}");
        let ratio = errs[2] / errs[1];
        assert!((50.0..200.0).contains(&ratio), "{errs:?}");
    }
    for bad in [
        &["sweep", "body", "--lengths", "0"][..],
        &["sweep", "body", "--lengths", "nan"],
        &["sweep", "body", "--coupling", "stokes", "--gamma", "1"],
        &["sweep", "body", "--tau-max", "-1"],
    ] {
        let (code, _, err) = turntable(bad);
        assert_eq!(code, 2, "{bad:?}: {err}");
    }
}

/// A body scene as the explorer loads it: case A's release (thrown inward, rests at
/// ξ ≈ 0.313), a rod of `length` at angle 0.4.
fn body_app(length: f64) -> turntable::app::App {
    let mut scene = turntable::scene::Scene::preset("A").unwrap();
    scene.body = Some(turntable::engine::body::Body {
        length,
        height: Some(0.01),
        angle: 0.4,
    });
    turntable::app::App::new(scene)
}

fn key(app: &mut turntable::app::App, c: char) {
    app.press(turntable::app::Chord::new(
        crossterm::event::KeyCode::Char(c),
        crossterm::event::KeyModifiers::NONE,
    ));
}

fn panel_of(app: &turntable::app::App) -> Vec<String> {
    turntable::ui::panel::lines(app, &turntable::theme::Theme::builtin("dark").unwrap())
        .iter()
        .map(|l| l.to_string())
        .collect()
}

/// The line starting with `key` (then blanks): its value.
fn value(lines: &[String], key: &str) -> String {
    lines
        .iter()
        .find_map(|l| {
            l.strip_prefix(key)
                .filter(|r| r.starts_with(' '))
                .map(|r| r.trim().to_string())
        })
        .unwrap_or_else(|| panic!("no {key} in {lines:?}"))
}

/// The panel judges the appendix's conditions at the body's state, not the point's: L/ξ with
/// the body's centre from its track at the τ on screen, and "rests" when the body does; and it
/// shows the body's own phase, centre and angle, and how it ends once τ gets there.
#[test]
fn the_panel_judges_at_the_bodys_state() {
    let mut app = body_app(0.25);
    for _ in 0..10 {
        app.tick();
    }
    let tau = app.now().tau;
    let rod = app.rod().cloned().unwrap();
    let (st, phase) = rod.at_with_phase(tau).unwrap();
    let lines = panel_of(&app);
    let body_xi = st.q.length();
    let point_xi = app.now().xi();
    let expect = format!("{:.4}", 0.25 / body_xi);
    assert_ne!(expect, format!("{:.4}", 0.25 / point_xi));
    assert!(
        value(&lines, "L/ξ").starts_with(&expect),
        "{expect} {lines:?}"
    );
    assert_eq!(
        value(&lines, "rod"),
        turntable::ui::panel::phase_word(phase)
    );
    assert_eq!(
        value(&lines, "rod ξ"),
        format!("{:.5} ψ {}", body_xi, turntable::present::angle(st.psi))
    );
    // The end is not told before τ reaches it.
    assert!(!lines.iter().any(|l| l.starts_with("ends")), "{lines:?}");
    // Past the body's rest: riding the table, its rest radius, and friction judged at rest
    // (μh/L = μ f h/L with f = ξ of the body, ≤ since μ is the bound 1).
    for _ in 0..100 {
        app.tick();
    }
    let lines = panel_of(&app);
    let rest = rod.states.last().unwrap().q.length();
    assert_eq!(value(&lines, "rod"), "riding the table");
    assert_eq!(value(&lines, "ends"), format!("rests at ξ = {rest:.5}"));
    // The toppling risk is the run's largest, while sliding (f = 1); at rest it is "now".
    assert_eq!(
        value(&lines, "μh/L max"),
        format!("≤ {:.4} ≪ 1 ok", 0.01 / 0.25)
    );
    assert_eq!(
        value(&lines, "  now"),
        format!("≤ {:.4}", rest * 0.01 / 0.25),
        "{lines:?}"
    );
    assert!(value(&lines, "L/ξ").starts_with(&format!("{:.4}", 0.25 / rest)));
    // Readouts in words (`I`, plain mode) say the body's phase and centre.
    let words = turntable::ui::plain::summary(&app);
    assert!(
        words.ends_with(&format!("; body\u{a0}ξ\u{a0}=\u{a0}{rest:.5} at rest")),
        "{words}"
    );
}

/// `C` hides and shows the point model beside the body: its marker leaves the canvas, the
/// body stays; a saved scene keeps the choice. Without a body `C` changes nothing and says so.
#[test]
fn c_compares_the_body_with_the_point_model() {
    let mut app = body_app(0.1);
    for _ in 0..60 {
        app.tick();
    }
    // The picture's rows (not the status line's notice).
    let canvas = |s: &str| {
        s.lines()
            .take(28)
            .map(|l| l.chars().take(70).collect::<String>())
            .collect::<Vec<_>>()
            .join("\n")
    };
    let shown = canvas(&common::render(&mut app, 100, 30));
    assert!(shown.contains('■'), "{shown}");
    key(&mut app, 'C');
    assert!(!app.view().point_model);
    assert!(
        app.notice()
            .as_deref()
            .unwrap()
            .contains("point model hidden")
    );
    let hidden = canvas(&common::render(&mut app, 100, 30));
    assert!(!hidden.contains('■') && !hidden.contains('●'), "{hidden}");
    assert!(!hidden.contains("stuck τ"), "{hidden}");
    // The body's bar and path are still drawn: the canvas is not the bare table.
    let mut bare = body_app(0.1);
    turntable::app::update(&mut bare, turntable::app::Action::TogglePointModel);
    bare.explore().set_body(None);
    for _ in 0..60 {
        bare.tick();
    }
    assert_ne!(hidden, canvas(&common::render(&mut bare, 100, 30)));
    let saved = app.current_scene().to_toml();
    assert!(saved.contains("point = false"), "{saved}");
    key(&mut app, 'C');
    assert!(app.view().point_model);
    assert!(!app.current_scene().to_toml().contains("point ="));
    assert_eq!(canvas(&common::render(&mut app, 100, 30)), shown);
    // No body: nothing changes but the notice.
    let mut point = turntable::app::App::new(turntable::scene::Scene::preset("A").unwrap());
    let before = canvas(&common::render(&mut point, 100, 30));
    key(&mut point, 'C');
    assert!(point.view().point_model);
    assert!(
        point
            .notice()
            .as_deref()
            .unwrap()
            .starts_with("no body to compare"),
        "{:?}",
        point.notice()
    );
    assert_eq!(canvas(&common::render(&mut point, 100, 30)), before);
    // `C` is in the help, from the keymap.
    assert!(
        turntable::app::KEYMAP
            .iter()
            .any(|b| b.help == "body: point model beside it")
    );
}

/// The body is the object and a preset its release: keys 1–6 keep it (and compute its run
/// from the new release); `0` goes back to the scene, body and all.
#[test]
fn presets_keep_the_body() {
    let mut app = body_app(0.1);
    let body = app.scene().body;
    key(&mut app, '2');
    assert_eq!(app.scene().name, "B");
    assert_eq!(app.scene().body, body);
    let rod = app.rod().cloned().unwrap();
    assert_eq!(rod.states[0].q.x, 0.5);
    assert!(app.notice().as_deref().unwrap().contains("the body stays"));
    key(&mut app, 'x');
    key(&mut app, '0');
    assert_eq!(app.scene().body, body);
    assert_eq!(app.rod().cloned().unwrap().states, rod.states);
}

/// A track cut short (here by a budget of 30 steps) is drawn as far as it goes; past its end
/// the panel says where and why it stopped, and nothing on screen is NaN.
#[test]
fn a_cut_track_says_where_it_stopped() {
    let mut app = body_app(0.1);
    let b = app.scene().body.unwrap();
    let cut = common::rod_track_within(b, 1.0, &app.initial(), 1e-10, 200.0, 30, usize::MAX);
    let end = cut.end_tau();
    assert!(
        turntable::app::exploration::rod_cut_notice(&cut)
            .unwrap()
            .contains("30-step budget")
    );
    app.explore().limit_body_steps(30);
    assert_eq!(app.rod().unwrap().end_tau(), end);
    while app.now().tau <= end {
        app.tick();
    }
    let lines = panel_of(&app);
    assert_eq!(value(&lines, "rod"), "not computed here");
    assert_eq!(value(&lines, "ends"), format!("cut at τ = {end:.2}"));
    assert_eq!(value(&lines, "  by"), "30-step budget");
    let screen = common::render(&mut app, 80, 24);
    assert!(
        !screen.contains("NaN") && !screen.contains("inf"),
        "{screen}"
    );
    assert!(screen.contains("cut at τ"), "{screen}");
}

/// `body.motion.check` is the body run again at tol/1000 and says how far its end lies: the
/// numbers are those of two runs made here, it is null with `--no-check` and at tol 1e-14
/// (nothing tighter to ask), and it never says `certain` (the same integrator twice).
#[test]
fn the_body_s_end_is_checked_against_a_tighter_run() {
    use turntable::engine::rod::RodRun;
    let a = [
        "run",
        "--xi0",
        "0.5",
        "--phi",
        "3",
        "--v0",
        "1",
        "--body-length",
        "0.1",
        "--json",
    ];
    let v = json(&a);
    let c = &v["body"]["motion"]["check"];
    let initial = turntable::engine::Initial::velocity(0.5, 3.0, 1.0);
    let b = turntable::engine::body::Body {
        length: 0.1,
        height: None,
        angle: 0.0,
    };
    let end = |tol: f64| {
        let mut r = RodRun::new(b, 1.0, &initial, tol).unwrap();
        r.finish(100.0, |_| {}).unwrap();
        r.state
    };
    let (own, tight) = (end(1e-10), end(1e-13));
    assert_eq!(c["tol"].as_f64(), Some(1e-13));
    assert_eq!(
        (c["outcome"].as_str(), c["agrees"].as_bool()),
        (Some("stuck"), Some(true))
    );
    let q = c["q_error"].as_f64().unwrap();
    assert!((q - (own.q - tight.q).length()).abs() < 1e-15, "{c}");
    assert!(q > 0.0 && q < 1e-10, "{c}");
    assert!(c["tau_error"].as_f64().unwrap() < 1e-6, "{c}");
    assert!(v["body"]["motion"].get("certain").is_none(), "{v}");
    assert!(c.get("certain").is_none(), "{c}");
    let v = json(&[&a[..], &["--no-check"]].concat());
    assert_eq!(v["body"]["motion"]["check"], serde_json::Value::Null);
    let v = json(&[&a[..], &["--tol", "1e-14"]].concat());
    assert_eq!(v["body"]["motion"]["check"], serde_json::Value::Null);
}

/// Fig. 2 with a body (`6` keeps it): its track escapes at the certificate, τ = 0, as
/// `RodRun::finish` says, and is followed out to the point's view radius, so past the
/// certificate the canvas still draws the bar (its centre `⊕`), to where it leaves and there
/// after, and the panel says how it ends.
#[test]
fn fig2s_body_is_drawn_leaving_past_its_certificate() {
    let mut app = body_app(0.1);
    app.explore().set_body(Some(turntable::engine::body::Body {
        length: 0.1,
        height: Some(0.01),
        angle: 0.0,
    }));
    key(&mut app, '6');
    let rod = app.rod().cloned().unwrap();
    let mut run = turntable::engine::rod::RodRun::new(
        app.scene().body.unwrap(),
        app.settings().hold(),
        &app.initial(),
        1e-10,
    )
    .unwrap();
    assert_eq!(run.finish(200.0, |_| {}).unwrap(), Outcome::Escaped);
    assert_eq!(rod.escape, Some(run.state.tau));
    assert_eq!(rod.escape, Some(0.0));
    assert_eq!((rod.outcome, rod.cut.clone()), (Outcome::Escaped, None));
    let radius = turntable::app::exploration::view_radius(&app.initial());
    let last = *rod.states.last().unwrap();
    assert!(last.q.length() >= radius, "{} < {radius}", last.q.length());
    assert!(rod.steps <= turntable::engine::rod::TRACK_STEPS);
    assert!(rod.states.len() <= turntable::engine::rod::TRACK_STATES);
    // C hides the point: what is drawn is the body's.
    key(&mut app, 'C');
    for _ in 0..20 {
        app.tick();
    }
    let tau = app.now().tau;
    assert!(tau > 0.9 && rod.at(tau).is_some(), "{tau}");
    let screen = common::render(&mut app, 100, 30);
    assert!(screen.contains('⊕'), "{screen}");
    assert!(!screen.contains('●'), "{screen}");
    let lines = panel_of(&app);
    assert_eq!(value(&lines, "ends"), "escapes (τ = 0.000)");
    assert_eq!(value(&lines, "rod"), "sliding");
    // Past where the body leaves (τ ≈ 5.92): kept at its last place, as the point is.
    for _ in 0..200 {
        app.tick();
    }
    assert!(app.now().tau > last.tau, "{}", app.now().tau);
    let screen = common::render(&mut app, 100, 30);
    assert!(screen.contains('⊕'), "{screen}");
    assert_eq!(value(&panel_of(&app), "rod"), "escaped");
}

/// A body's size reads as its size at any scale: a body 1e-9 long is not "L 0.0000" (a length
/// the flags refuse), nor a height of 1e-7 "h 0.0000"; a large one keeps its digits.
#[test]
fn the_bodys_size_reads_at_any_scale() {
    let lines = panel_of(&body_app(1e-9));
    assert_eq!(value(&lines, "body"), "L 1.00e-9 h 0.0100", "{lines:?}");
    let lines = panel_of(&body_app(5.0));
    assert_eq!(value(&lines, "body"), "L 5.0000 h 0.0100", "{lines:?}");
    let mut scene = turntable::scene::Scene::preset("A").unwrap();
    scene.body = Some(turntable::engine::body::Body {
        length: 0.1,
        height: Some(1e-7),
        angle: 0.0,
    });
    let app = turntable::app::App::new(scene);
    let lines = panel_of(&app);
    assert_eq!(value(&lines, "body"), "L 0.1000 h 1.00e-7", "{lines:?}");
    assert!(!lines.iter().any(|l| l.contains("NaN")), "{lines:?}");
}

/// With μ = 0 there is no friction to tip the body: μh/L is 0 exactly, not "≤ 0" (the bound
/// taken without a real table is μ_k = 1, and 1 · 0 is no bound).
#[test]
fn without_friction_the_toppling_number_is_exactly_zero() {
    let mut app = body_app(0.1);
    assert!(value(&panel_of(&app), "μh/L max").starts_with("≤ "));
    key(&mut app, 'F');
    assert_eq!(value(&panel_of(&app), "μh/L"), "0.0000 ≪ 1 ok");
}
