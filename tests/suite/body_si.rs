//! The appendix's body in SI (issue 23 item 3): `--body-length 2cm` and `[body] length =
//! "2 cm"` on a real table, held in metres in the explorer as the release is, and reported in
//! SI by `run` and the panel.

use crate::common;
use common::{render, seeded as config, turntable};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use proptest::prelude::*;
use turntable::app::App;
use turntable::app::testing::Testing as _;
use turntable::engine::body::Body;
use turntable::engine::units::{Length, Units, show_metres, show_r_max_in_metres};
use turntable::scene::Scene;

/// R_max = μg/Ω² in metres, Ω = 2π rpm/60, g = 9.81: computed here, not by the crate.
fn r_max(mu: f64, rpm: f64) -> f64 {
    let omega = 2.0 * std::f64::consts::PI * rpm / 60.0;
    mu * 9.81 / (omega * omega)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = turntable(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn a_coin_on_a_record_player_from_the_command_line() {
    let r = r_max(0.2, 33.333);
    let run = [
        "run",
        "--xi0",
        "0.5",
        "--json",
        "--no-check",
        "--mu",
        "0.2",
        "--rpm",
        "33.333",
    ];
    for (l, h) in [("2cm", "1.5mm"), ("0.02m", "0.0015 m"), ("20 mm", "0.15cm")] {
        let v = json(&[&run[..], &["--body-length", l, "--body-height", h]].concat());
        let b = &v["body"];
        assert!(
            rel(b["length"].as_f64().unwrap(), 0.02 / r) < 1e-12,
            "{l}: {b}"
        );
        assert!(
            rel(b["height"].as_f64().unwrap(), 0.0015 / r) < 1e-12,
            "{h}: {b}"
        );
        assert!(rel(b["length_m"].as_f64().unwrap(), 0.02) < 1e-12, "{b}");
        assert!(rel(b["height_m"].as_f64().unwrap(), 0.0015) < 1e-12, "{b}");
    }
    // A plain number is in R_max, as before; with units its metres are reported too, and the
    // height's is null when no height is given.
    let v = json(&[&run[..], &["--body-length", "0.1"]].concat());
    assert_eq!(v["body"]["length"].as_f64(), Some(0.1));
    assert!(rel(v["body"]["length_m"].as_f64().unwrap(), 0.1 * r) < 1e-12);
    assert_eq!(v["body"]["height_m"], serde_json::Value::Null);
    // Without units neither field is there.
    let v = json(&["run", "--json", "--no-check", "--body-length", "0.1"]);
    assert!(v["body"].get("length_m").is_none(), "{v}");
    assert!(v["body"].get("height_m").is_none(), "{v}");
    // The text names the size in SI.
    let (code, out, err) = turntable(&[
        "run",
        "--xi0",
        "0.5",
        "--no-check",
        "--mu",
        "0.2",
        "--rpm",
        "33.333",
        "--body-length",
        "2cm",
        "--body-height",
        "1.5mm",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.lines()
            .any(|l| l.starts_with("body") && l.contains("(2.00 cm)") && l.contains("(1.50 mm)")),
        "{out}"
    );
    // The angle in degrees: 90deg is π/2.
    let v = json(&[&run[..], &["--body-length", "2cm", "--body-angle", "90deg"]].concat());
    assert!(
        rel(
            v["body"]["angle"].as_f64().unwrap(),
            std::f64::consts::FRAC_PI_2
        ) < 1e-15
    );
}

#[test]
fn metres_without_a_table_are_refused_with_what_to_add() {
    for (args, says) in [
        (&["run", "--body-length", "2cm"][..], "--mu and --rpm"),
        (
            &["run", "--body-length", "0.1", "--body-height", "4 mm"],
            "--mu and --rpm",
        ),
        // The explorer refuses before it needs a terminal, and names a scene's [units] too.
        (&["--body-length", "2cm"], "[units]"),
    ] {
        let (code, out, err) = turntable(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty());
        assert!(err.contains("is a length in metres"), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(err.contains("units of R_max"), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    for bad in [
        &["run", "--mu", "0.2", "--rpm", "33", "--body-length", "-2cm"][..],
        &["run", "--mu", "0.2", "--rpm", "33", "--body-length", "0cm"],
        &[
            "run",
            "--mu",
            "0.2",
            "--rpm",
            "33",
            "--body-length",
            "nan cm",
        ],
        &[
            "run",
            "--mu",
            "0.2",
            "--rpm",
            "33",
            "--body-length",
            "inf m",
        ],
        &[
            "run",
            "--mu",
            "0.2",
            "--rpm",
            "33",
            "--body-length",
            "2cm",
            "--body-height",
            "-1mm",
        ],
        &["run", "--body-length", "2 km"],
        &["run", "--body-length", "2 inches"],
        &["run", "--body-length", "0.1", "--body-angle", "ninety deg"],
    ] {
        let (code, _, err) = turntable(bad);
        assert_eq!(code, 2, "{bad:?}: {err}");
        assert!(err.contains("body"), "{bad:?}: {err}");
    }
    // A height of 0 mm is a flat body, as 0 is.
    let v = json(&[
        "run",
        "--mu",
        "0.2",
        "--rpm",
        "33",
        "--body-length",
        "2cm",
        "--body-height",
        "0mm",
        "--json",
        "--no-check",
    ]);
    assert_eq!(v["body"]["height"].as_f64(), Some(0.0));
}

fn dir() -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("turntable-body-si-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn scene_file(name: &str, units: &str, body: &str) -> String {
    let path = dir().join(name);
    std::fs::write(
        &path,
        format!(
            "name = \"{name}\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.6\n{units}[body]\n{body}"
        ),
    )
    .unwrap();
    path.to_str().unwrap().to_string()
}

const UNITS: &str = "[units]\nmu = 0.2\nrpm = 33.333\n";

#[test]
fn scene_files_take_lengths_in_metres_with_units_and_save_them_back() {
    let r = r_max(0.2, 33.333);
    let s = Scene::load(&scene_file(
        "coin.toml",
        UNITS,
        "length = \"2 cm\"\nheight = \"1.5 mm\"\nangle = 0.25\n",
    ))
    .unwrap();
    let b = s.body.unwrap();
    assert!(rel(b.length, 0.02 / r) < 1e-12, "{b:?}");
    assert!(rel(b.height.unwrap(), 0.0015 / r) < 1e-12, "{b:?}");
    assert_eq!(b.angle, 0.25);
    // Saved in metres, as typed, and back to the same R_max.
    let text = s.to_toml();
    assert!(text.contains("length = \"2 cm\""), "{text}");
    assert!(text.contains("height = \"1.5 mm\""), "{text}");
    let path = dir().join("coin-saved.toml");
    std::fs::write(&path, &text).unwrap();
    let back = Scene::load(path.to_str().unwrap()).unwrap();
    assert_eq!(back.body, s.body);
    // A plain number still works beside [units], and a body in R_max on a table saves in
    // metres that load back to the same R_max, to 1e-12 (here exactly).
    let s = Scene::load(&scene_file("plain.toml", UNITS, "length = 0.1\n")).unwrap();
    assert_eq!(s.body.unwrap().length, 0.1);
    for l in [0.1, 1.0 / 3.0, 0.123456789, 7e-5, 2.5] {
        let mut s = s.clone();
        s.body = Some(Body {
            length: l,
            height: Some(l / 7.0),
            angle: 0.0,
        });
        let path = dir().join("held.toml");
        std::fs::write(&path, s.to_toml()).unwrap();
        let back = Scene::load(path.to_str().unwrap()).unwrap().body.unwrap();
        assert!(rel(back.length, l) < 1e-12, "{l}: {}", s.to_toml());
        assert!(rel(back.height.unwrap(), l / 7.0) < 1e-12, "{l}");
    }
    // Without [units], metres are refused, the file and the key named; a number is not.
    let bare = scene_file("bare.toml", "", "length = \"2 cm\"\n");
    let e = Scene::load(&bare).unwrap_err().to_string();
    assert!(
        e.contains("bare.toml") && e.contains("[body] length") && e.contains("[units]"),
        "{e}"
    );
    let e = Scene::load(&scene_file(
        "bare-h.toml",
        "",
        "length = 0.1\nheight = \"3mm\"\n",
    ))
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("bare-h.toml") && e.contains("[body] height"),
        "{e}"
    );
    assert!(Scene::load(&scene_file("num.toml", "", "length = 0.1\n")).is_ok());
    // What is no length is refused with its line.
    for bad in [
        "length = \"2 furlongs\"\n",
        "length = true\n",
        "length = \"-2 cm\"\n",
    ] {
        let e = Scene::load(&scene_file("bad.toml", UNITS, bad))
            .unwrap_err()
            .to_string();
        assert!(e.contains("bad.toml"), "{bad}: {e}");
    }
    // The explorer reads the scene's table for --body-length in metres: past the body, it
    // stops only for want of a terminal.
    let (code, _, err) = turntable(&[
        "--scene",
        &bare.replace("bare", "coin"),
        "--body-length",
        "3cm",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("needs a terminal"), "{err}");
}

fn key(app: &mut App, c: char) {
    app.handle_key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE));
}

fn coin() -> Scene {
    let mut s = Scene::preset("A").unwrap();
    s.body = Some(Body {
        length: 0.1,
        height: Some(0.01),
        angle: 0.0,
    });
    s
}

/// With SI units on, μ, rpm and g hold the body's metres as they hold the release's: twice μ
/// is twice R_max, so half the dimensionless L and h; the body's track restarts with it.
#[test]
fn doubling_mu_halves_the_bodys_dimensionless_size() {
    let mut a = App::new(coin());
    for _ in 0..30 {
        a.tick();
    }
    // The first press turns units on and changes nothing: the R_max size at that moment.
    key(&mut a, 'u');
    let u0 = a.units().unwrap();
    assert_eq!(a.scene().body.unwrap().length, 0.1);
    let metres = 0.1 * u0.r_max_m();
    for _ in 0..15 {
        key(&mut a, 'u');
    }
    let u = a.units().unwrap();
    assert_eq!(u.mu, 2.0 * u0.mu);
    let b = a.scene().body.unwrap();
    assert!((b.length - 0.05).abs() < 1e-12, "{b:?}");
    assert!((b.height.unwrap() - 0.005).abs() < 1e-12, "{b:?}");
    assert!(rel(b.length * u.r_max_m(), metres) < 1e-12);
    // The track was made again for the new body, from τ = 0.
    let rod = a.rod().unwrap();
    assert!((rod.l - 0.05).abs() < 1e-12);
    assert_eq!(rod.states[0].tau, 0.0);
    assert_eq!(a.sim().now().tau, 0.0);
    a.check_invariants().unwrap();
    // rpm: twice the speed is a quarter of R_max, four times L.
    let before = a.scene().body.unwrap().length;
    let r_before = a.units().unwrap().r_max_m();
    key(&mut a, 'w');
    let after = a.scene().body.unwrap().length;
    assert!(rel(after / before, r_before / a.units().unwrap().r_max_m()) < 1e-12);
    // And back: the same metres.
    key(&mut a, 'W');
    for _ in 0..15 {
        key(&mut a, 'U');
    }
    assert!((a.scene().body.unwrap().length - 0.1).abs() < 1e-9);
    // Saved with its table, it loads back at the same size.
    let text = a.current_scene().to_toml();
    assert!(text.contains("length = \""), "{text}");
    let path = dir().join("explorer.toml");
    std::fs::write(&path, &text).unwrap();
    let back = Scene::load(path.to_str().unwrap()).unwrap();
    assert!(rel(back.body.unwrap().length, a.scene().body.unwrap().length) < 1e-12);
}

/// The panel gives L and h in SI on a line of its own, whole at every size it shows at.
#[test]
fn the_panel_shows_the_body_in_si_without_cutting_it() {
    let mut a = App::new(coin());
    a.tell_units(Some(Units::new(0.2, 33.333, 9.81).unwrap()));
    let r = r_max(0.2, 33.333);
    let want = format!(
        "= {} h {}",
        turntable::present::si_length(0.1 * r),
        turntable::present::si_length(0.01 * r)
    );
    let lines: Vec<String> =
        turntable::ui::panel::lines(&a, &turntable::theme::Theme::builtin("dark").unwrap())
            .iter()
            .map(|l| l.to_string())
            .collect();
    assert!(lines.iter().any(|l| l.trim() == want), "{want}: {lines:?}");
    for (w, h) in [(80, 24), (60, 20), (100, 30), (40, 12), (50, 30)] {
        let screen = render(&mut a, w, h);
        // Where the SI line shows, it shows whole.
        if screen.contains("= ") && screen.contains(" h ") {
            let shown = screen.lines().any(|l| l.contains(&want));
            let partial = screen
                .lines()
                .any(|l| l.contains(&want[..6]) && !l.contains(&want));
            assert!(shown || !partial, "{w}×{h}:\n{screen}");
        }
    }
    let wide = render(&mut a, 80, 24);
    assert!(wide.contains(&want), "{wide}");
    // Plain mode reads it on the body's line.
    let scene = scene_file("plain-coin.toml", UNITS, "length = \"2 cm\"\n");
    let keys = dir().join("readouts.keys");
    std::fs::write(&keys, "I\n").unwrap();
    let (code, out, err) = turntable(&[
        "replay",
        "--plain",
        "--scene",
        &scene,
        keys.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.lines()
            .any(|l| l.starts_with("body L 0.1242 = 2.00 cm")),
        "{out}"
    );
}

proptest! {
    #![proptest_config(config(2000))]

    /// What is written with a unit reads back to the very same metres.
    #[test]
    fn metres_written_read_back_exactly(e in -7.0..3.0f64, k in 1.0..10.0f64) {
        let m = k * 10f64.powf(e);
        let text = show_metres(m);
        prop_assert!(text.ends_with(" m") || text.ends_with(" cm") || text.ends_with(" mm"), "{}", text);
        prop_assert_eq!(Length::parse(&text), Ok(Length::Metres(m)), "{}", text);
    }

    /// A body in R_max written in metres on a table reads back, on that table, to the same
    /// R_max to 1e-12 (exactly where a decimal does it).
    #[test]
    fn r_max_written_in_metres_reads_back(
        l in 1e-6..1e3f64,
        mu in 0.01..10.0f64,
        rpm in 1.0..1e4f64,
        g in 1.0..30.0f64,
    ) {
        let u = Units::new(mu, rpm, g).unwrap();
        let text = show_r_max_in_metres(l, &u);
        let back = Length::parse(&text).unwrap().to_r_max(Some(&u)).unwrap();
        prop_assert!(rel(back, l) < 1e-12, "{} → {} → {}", l, text, back);
    }
}
