//! The headless commands as a user runs them: JSON fields and the trajectory file.

use crate::common;
use crate::reference;
use common::turntable;

fn field(json: &str, key: &str) -> String {
    let v: serde_json::Value = serde_json::from_str(json).unwrap();
    v[key].to_string()
}

#[test]
fn run_json_and_trajectory_agree() {
    let path = std::env::temp_dir().join(format!("turntable-traj-{}.csv", std::process::id()));
    let p = path.to_str().unwrap();
    let (code, out, _) = turntable(&[
        "run",
        "--xi0",
        "0.5",
        "--phi",
        "0",
        "--v0",
        "0.6",
        "--json",
        "--trajectory",
        p,
    ]);
    assert_eq!(code, 0);
    assert_eq!(field(&out, "outcome"), "\"stuck\"");
    let xi: f64 = field(&out, "xi").parse().unwrap();
    assert!((xi - reference::B_REST.0).abs() < 1e-9, "{xi}");
    let steps: usize = field(&out, "steps").parse().unwrap();
    let csv = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').take(9).map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(
        csv.lines().next().unwrap(),
        "tau,x,y,xq,yq,u,stuck,energy,work,approx_xi"
    );
    // dE/dτ = −|u|: E − E(0) and the work column agree to the run's own error (they differed
    // by up to 1.8e-4 with trapezoids between rows); a release with speed has no Sec. III
    // approximation (the column is empty).
    // README: to 1e-11 at the default tol, 1e-7 with rk2 at dt = 1e-3.
    let e0 = rows[0][7];
    for r in &rows {
        assert!((r[7] - e0 - r[8]).abs() < 1e-11, "{r:?}");
    }
    assert!(csv.lines().skip(1).all(|l| l.ends_with(',')));
    // One row per step, plus the start and the closed-form stop.
    assert!(rows.len() > steps, "{} rows for {steps} steps", rows.len());
    let last = rows.last().unwrap();
    assert_eq!((last[5], last[6]), (0.0, 1.0));
    assert!(((last[3] * last[3] + last[4] * last[4]).sqrt() - xi).abs() < 1e-12);
    assert!(
        rows[..rows.len() - 1]
            .iter()
            .all(|r| r[6] == 0.0 && r[5] > 0.0)
    );
    let tau: f64 = field(&out, "tau").parse().unwrap();
    assert_eq!(last[0], tau);
    let (code, _, err) = turntable(&[
        "run",
        "--xi0",
        "0.5",
        "--v0",
        "0.6",
        "--method",
        "rk2",
        "--dt",
        "1e-3",
        "--trajectory",
        p,
    ]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    let col = |l: &str, k: usize| l.split(',').nth(k).unwrap().parse::<f64>().unwrap();
    let e0 = col(csv.lines().nth(1).unwrap(), 7);
    for l in csv.lines().skip(1) {
        assert!((col(l, 7) - e0 - col(l, 8)).abs() < 1e-7, "{l}");
    }
    // Released at rest in the lab far out (Fig. 1), the approx_xi column is Eq. 13.
    let (code, _, err) = turntable(&[
        "run",
        "--xi0",
        "500",
        "--release",
        "lab-rest",
        "--tau-max",
        "10",
        "--follow",
        "--trajectory",
        p,
    ]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    for l in csv.lines().skip(1) {
        let r: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
        let xi = (r[1] * r[1] + r[2] * r[2]).sqrt();
        assert!((r[9] - (r[0].powi(4) / 6000.0 + 500.0)).abs() < 1e-9, "{l}");
        // Within the window τ ≲ √ξ0 the approximation holds closely.
        assert!((r[9] - xi).abs() < 0.05, "{l}");
    }
}

#[test]
fn escape_and_critical_print_their_values() {
    let (code, out, _) = turntable(&["escape", "--xi0", "0.5", "--phi", "0", "--json"]);
    assert_eq!(code, 0);
    let v: f64 = field(&out, "v_escape").parse().unwrap();
    assert!((v - reference::VE_C).abs() < 2e-8, "{v}");
    let (code, out, _) = turntable(&["critical", "--json"]);
    assert_eq!(code, 0);
    let x: f64 = field(&out, "xi0c").parse().unwrap();
    assert!((x - reference::XI0C).abs() < 1e-7, "{x}");
    let (code, out, _) = turntable(&["sweep", "fig6", "--points", "11"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "xi0,outcome,xi,angle");
    assert!(
        lines[9].starts_with("0.8,stuck,") && lines[10].starts_with("0.9,escaped,"),
        "{out}"
    );
}

/// The paper's way to measure μ (Eq. 22): from the measured Ω and critical radius r0c.
#[test]
fn critical_radius_measures_mu() {
    let (code, out, _) = turntable(&["critical", "--omega", "3.3", "--r0c", "0.12", "--json"]);
    assert_eq!(code, 0);
    let mu: f64 = field(&out, "mu").parse().unwrap();
    assert!(
        (mu - 3.3 * 3.3 * 0.12 / (reference::XI0C * 9.81)).abs() < 1e-7,
        "{mu}"
    );
    let (code, _, _) = turntable(&["critical", "--omega", "3.3"]);
    assert_eq!(code, 2);
}

#[test]
fn run_frictionless_is_a_closed_form_line() {
    let (code, out, _) = turntable(&[
        "run",
        "--xi0",
        "0.5",
        "--release",
        "table-rest",
        "--frictionless",
        "--json",
    ]);
    assert_eq!(code, 0);
    assert_eq!(field(&out, "outcome"), "\"escaped\"");
    assert_eq!(field(&out, "frictionless"), "true");
    assert_eq!(field(&out, "rhs_evals"), "0");
    let tau: f64 = field(&out, "escape_tau").parse().unwrap();
    assert!((tau - 3f64.sqrt()).abs() < 1e-12, "{tau}");
    let (_, text, _) = turntable(&["run", "--release", "lab-rest", "--frictionless"]);
    assert!(
        text.contains("running") && text.contains("closed form"),
        "{text}"
    );
}

#[test]
fn enum_flags_list_their_values_and_take_aliases() {
    let (code, _, err) = turntable(&["run", "--method", "rk3"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("[possible values: rk2-raw, rk2, rk4, dp54, dop853]"),
        "{err}"
    );
    let (code, out, err) = turntable(&["run", "--frame", "rotating", "--json"]);
    assert_eq!(
        (code, field(&out, "frame")),
        (0, "\"table\"".into()),
        "{err}"
    );
    let (code, _, err) = turntable(&["run", "--release", "rest"]);
    assert_eq!(code, 2);
    assert!(err.contains("velocity, table-rest, lab-rest"), "{err}");
}

#[test]
fn sweep_map_prints_one_row_per_cell_that_agrees_with_v_e() {
    let (code, out, err) = turntable(&[
        "sweep",
        "map",
        "--xi0",
        "0.5",
        "--phi-points",
        "12",
        "--v0-points",
        "10",
    ]);
    assert_eq!(code, 0, "{err}");
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("phi,v0,outcome,xi,angle"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 120);
    let mut checked = 0;
    // v_e once for each of the 12 angles, not once a row (`escape` as a process each).
    let mut escape: std::collections::HashMap<&str, f64> = Default::default();
    for r in &rows {
        let (phi, v0): (f64, f64) = (r[0].parse().unwrap(), r[1].parse().unwrap());
        let ve = *escape.entry(r[0]).or_insert_with(|| {
            let (_, ve, _) = turntable(&["escape", "--xi0", "0.5", "--phi", r[0], "--json"]);
            field(&ve, "v_escape").parse().unwrap()
        });
        if (v0 - ve).abs() > 1e-3 {
            let want = if v0 > ve { "escaped" } else { "stuck" };
            assert_eq!(r[2], want, "phi {phi} v0 {v0} v_e {ve}");
            assert_eq!(r[3].is_empty(), want == "escaped");
            checked += 1;
        }
        if checked > 30 {
            break;
        }
    }
    for bad in [
        &["sweep", "map", "--xi0", "0.5,0.2"][..],
        &["sweep", "map", "--xi0", "0.5", "--v0-points", "0"],
        &["sweep", "map", "--xi0", "0.5", "--v0-max", "-1"],
        &["sweep", "map", "--xi0", "0.5", "--release", "sideways"],
    ] {
        let (code, out, err) = turntable(bad);
        assert_eq!(code, 2, "{bad:?}: {err}");
        assert!(out.is_empty() && err.lines().count() <= 6, "{bad:?}: {err}");
    }
}

#[test]
fn physical_units_give_si_copies() {
    let (code, out, err) = turntable(&[
        "run", "--xi0", "0.5", "--v0", "0.6", "--mu", "0.15", "--rpm", "31.5", "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let omega = 31.5 * std::f64::consts::TAU / 60.0;
    let r_max = 0.15 * 9.81 / (omega * omega);
    let u = &v["units"];
    assert!((u["R_max_m"].as_f64().unwrap() - r_max).abs() < 1e-15);
    assert!((u["T_s"].as_f64().unwrap() - 1.0 / omega).abs() < 1e-15);
    let xi = v["xi"].as_f64().unwrap();
    assert!((u["xi_m"].as_f64().unwrap() - xi * r_max).abs() < 1e-15);
    let tau = v["tau"].as_f64().unwrap();
    assert!((u["tau_s"].as_f64().unwrap() - tau / omega).abs() < 1e-15);
    let (code, out, _) = turntable(&["run", "--xi0", "0.5", "--json"]);
    assert_eq!(code, 0);
    assert!(!out.contains("units"));
    for bad in [
        &["run", "--mu", "0.2"][..],
        &["run", "--mu", "0.2", "--rpm", "-3"],
        &["run", "--mu", "nan", "--rpm", "30"],
        &["--rpm", "30"],
    ] {
        let (code, _, err) = turntable(bad);
        assert_eq!(code, 2, "{bad:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

#[test]
fn scene_files_carry_units_and_the_explorer_shows_si() {
    let dir = std::env::temp_dir().join(format!("turntable-units-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = dir.join("table.toml");
    std::fs::write(
        &good,
        "name = \"real\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.6\n[units]\nmu = 0.15\nrpm = 31.5\n",
    )
    .unwrap();
    let scene = turntable::scene::Scene::load(good.to_str().unwrap()).unwrap();
    let u = scene.units.unwrap();
    assert_eq!((u.mu, u.rpm, u.g), (0.15, 31.5, 9.81));
    let mut app = turntable::app::App::new(scene);
    let lines: Vec<String> =
        turntable::ui::panel::lines(&app, &turntable::theme::Theme::builtin("dark").unwrap())
            .iter()
            .map(|l| l.to_string())
            .collect();
    assert!(
        lines
            .iter()
            .any(|l| l.contains("ξ") && l.contains("= 6.76 cm")),
        "{lines:?}"
    );
    assert!(
        lines
            .iter()
            .any(|l| l.contains("τ") && l.contains("= 0.00 s")),
        "{lines:?}"
    );
    app.tick();
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "name = \"real\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.6\n[units]\nmu = -1\nrpm = 31.5\n",
    )
    .unwrap();
    let e = turntable::scene::Scene::load(bad.to_str().unwrap()).unwrap_err();
    assert!(e.to_string().contains("[units] mu must lie in"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A release at rest in the lab far out escapes at once, on its release direction: the angle
/// is 0, not 2π less a rounding error (which printed as 6.283185307180, outside [0, 2π)).
#[test]
fn an_angle_a_hair_below_a_turn_is_zero() {
    let (code, out, _) = turntable(&["run", "--xi0", "500", "--release", "lab-rest", "--json"]);
    assert_eq!(code, 0);
    assert_eq!(field(&out, "angle"), "0.0");
    let (code, out, _) = turntable(&["run", "--xi0", "500", "--release", "lab-rest"]);
    assert_eq!(code, 0);
    assert!(out.contains("angle    0 in [0, 2π)"), "{out}");
    assert_eq!(turntable::engine::model::turn_angle(-1e-13), 0.0);
    assert_eq!(turntable::engine::model::turn_angle(-0.0), 0.0);
    let w = turntable::engine::model::turn_angle(-1e-3);
    assert!((w - (std::f64::consts::TAU - 1e-3)).abs() < 1e-15);
}

/// The fields docs/command-line.md's table under `heading` lists.
fn readme_fields(heading: &str) -> Vec<String> {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/command-line.md"))
            .unwrap();
    let table = readme.split(heading).nth(1).unwrap();
    table
        .lines()
        .skip_while(|l| !l.starts_with("| field"))
        .skip(2)
        .take_while(|l| l.starts_with("| `"))
        .map(|l| l.split('`').nth(1).unwrap().to_string())
        .collect()
}

/// The JSON reports are documented once, in docs/command-line.md: every field printed is listed there, and
/// nothing else is (units and check included when asked for).
#[test]
fn json_reports_are_the_fields_readme_lists() {
    for (heading, args) in [
        (
            "`run --json`:",
            &[
                "run",
                "--v0",
                "0.3",
                "--json",
                "--mu",
                "0.2",
                "--rpm",
                "30",
                "--body-length",
                "0.01",
                "--error",
                "1e-6",
            ][..],
        ),
        ("`escape --json`:", &["escape", "--xi0", "0.5", "--json"]),
        (
            "`critical --json`:",
            &["critical", "--json", "--xtol", "1e-6"],
        ),
        (
            "`spinup --json`:",
            &[
                "spinup", "--rate", "0.3", "--json", "--mu", "0.3", "--rpm", "30",
            ],
        ),
    ] {
        let (code, out, err) = turntable(args);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        // serde_json's map sorts its keys.
        let keys: Vec<String> = v.as_object().unwrap().keys().cloned().collect();
        let mut listed = readme_fields(heading);
        listed.sort();
        assert_eq!(keys, listed, "{heading}");
    }
}

/// Issue 32 item 7: with a body, `run` says how the body ends first (JSON and text); `plot
/// map`, `sweep map` and `escape` take ξ0 = 0.5 as `run` does.
#[test]
fn the_body_comes_first_and_the_map_has_a_default_radius() {
    let args = ["run", "--xi0", "0.5", "--v0", "0.6", "--body-length", "0.1"];
    let (code, out, err) = turntable(&[&args[..], &["--json"]].concat());
    assert_eq!(code, 0, "{err}");
    assert!(
        out.starts_with("{\"body_outcome\":\"stuck\","),
        "{}",
        &out[..60]
    );
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["body_outcome"], v["body"]["motion"]["outcome"]);
    let (code, out, _) = turntable(&args);
    assert_eq!(code, 0);
    assert!(
        out.starts_with("rod      the two-mass body: stuck at tau 2.75"),
        "{out}"
    );
    let (code, out, _) = turntable(&["run", "--xi0", "0.5", "--v0", "0.6", "--json"]);
    assert_eq!(code, 0);
    assert!(
        out.starts_with("{\"outcome\":"),
        "no body, no body_outcome: {out}"
    );
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("map.svg");
    let (code, _, err) = turntable(&[
        "plot",
        "map",
        "--phi-points",
        "8",
        "--v0-points",
        "6",
        "--out",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read_to_string(&svg).unwrap().contains("0.5"));
    let (code, csv, err) = turntable(&["sweep", "map", "--phi-points", "4", "--v0-points", "3"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(csv.lines().count(), 1 + 4 * 3, "{csv}");
    let (code, out, err) = turntable(&["escape", "--vtol", "1e-4", "--no-check"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("v_escape"), "{out}");
}

/// Issue 46 item 4: `--scene` completes to the presets and `--theme` to the built-in themes,
/// beside file names (bash, zsh, fish; clap's PowerShell script completes flags, not their
/// values), and a path is still taken: the names are offered, not
/// enforced, and the help does not list them twice.
#[test]
fn scene_and_theme_complete_to_their_names_and_files() {
    let presets = turntable::scene::PRESETS.join(" ");
    let themes = turntable::theme::BUILTIN.join(" ");
    let (_, bash, _) = turntable(&["completions", "bash"]);
    for words in [&presets, &themes] {
        let both = format!(
            "COMPREPLY=($(compgen -W \"{words}\" -- \"${{cur}}\") $(compgen -f -- \"${{cur}}\"))"
        );
        assert!(bash.contains(&both), "bash: no {both}");
    }
    // `plot` plays every preset but the spun-up table, which it refuses.
    assert!(
        bash.contains("compgen -W \"A B C D fig1 fig2\" --"),
        "plot's scenes"
    );
    let (_, zsh, _) = turntable(&["completions", "zsh"]);
    let zsh_scene = format!(
        ":NAME|PATH: _alternative \"names\\:name\\:({presets})\" \"files\\:file\\:_files\"'"
    );
    assert!(zsh.contains(&zsh_scene), "zsh: no {zsh_scene}");
    let (_, fish, _) = turntable(&["completions", "fish"]);
    assert!(fish.contains("-l scene -d 'Scene to open"), "fish");
    assert!(
        fish.contains("-r -F -a \"A\\t''\nB\\t''"),
        "fish: scenes with files"
    );
    assert!(
        fish.contains("-r -F -a \"dark\\t''\nlight\\t''"),
        "fish: themes with files"
    );
    // Any other value is a path, read where it is opened.
    let (code, _, err) = turntable(&["spinup", "--scene", "/nonexistent/s.toml"]);
    assert_eq!(code, 2, "{err}");
    let (code, _, err) = turntable(&["replay", "/nonexistent/x.keys", "--scene", "mine.toml"]);
    assert_eq!(code, 2);
    assert!(
        !err.contains("possible values") && !err.contains("invalid value"),
        "{err}"
    );
    let (_, help, _) = turntable(&["--help"]);
    assert!(!help.contains("[possible values: A"), "{help}");
}

/// Shell completions and the manual page come from the clap definitions, every subcommand in.
#[test]
fn completions_and_man_page() {
    for shell in ["bash", "zsh", "fish", "powershell", "elvish"] {
        let (code, out, err) = turntable(&["completions", shell]);
        assert_eq!(code, 0, "{err}");
        assert!(out.len() > 1000, "{shell}: {} bytes", out.len());
        for word in ["turntable", "escape", "critical", "vtol", "no-check"] {
            assert!(out.contains(word), "{shell}: no {word}");
        }
    }
    let (code, _, err) = turntable(&["completions", "tcsh"]);
    assert_eq!(code, 2, "{err}");
    let (code, out, _) = turntable(&["man"]);
    assert_eq!(code, 0);
    assert!(
        out.starts_with(".ie ") || out.starts_with(".TH"),
        "{}",
        &out[..40]
    );
    for section in [
        "TURNTABLE RUN",
        "TURNTABLE ESCAPE",
        "TURNTABLE REPLAY",
        "xi0",
        // Issue 32 item 3: the options of nested subcommands, and the keys.
        "TURNTABLE SWEEP FIG5",
        "TURNTABLE PLOT MAP",
        ".SH KEYS",
        "play / pause",
    ] {
        assert!(out.contains(section), "no {section}");
    }
    // Every key of the table is in the page.
    for b in turntable::app::KEYMAP {
        assert!(out.contains(b.help), "no key {:?}: {}", b.chord, b.help);
    }
    // No page that does not exist: every subcommand is in this one.
    assert!(
        !out.contains("turntable\\-"),
        "refers to a turntable-*(1) page"
    );
}

/// Issue 32 item 3: `--help` fits an 80-column terminal, `-h` is the short form, and the
/// options come under headings instead of "Explorer:" prefixes.
#[test]
fn help_fits_the_terminal_and_h_is_short() {
    let help = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_turntable"))
            .args(args)
            .env("COLUMNS", "80")
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    let subs = [
        "run", "escape", "critical", "sweep", "spinup", "plot", "bench", "replay", "serve",
        "lesson", "config",
    ];
    for sub in std::iter::once(None).chain(subs.iter().map(Some)) {
        let args = |flag| sub.map_or(vec![flag], |s| vec![*s, flag]);
        let long = help(&args("--help"));
        let short = help(&args("-h"));
        for text in [&long, &short] {
            for line in text.lines() {
                assert!(
                    line.chars().count() <= 80,
                    "{sub:?}: {} chars: {line}",
                    line.chars().count()
                );
            }
        }
        assert!(short.len() <= long.len(), "{sub:?}");
    }
    let (long, short) = (help(&["--help"]), help(&["-h"]));
    assert!(
        short.len() * 3 < long.len() * 2,
        "-h {} bytes, --help {}",
        short.len(),
        long.len()
    );
    assert!(
        long.contains("\nExplorer:\n") && long.contains("\nFriction:\n"),
        "{long}"
    );
    assert!(!long.contains("Explorer: "), "a prefix left: {long}");
}

/// Issue 32 item 5: the configuration can be found (`turntable config`) and named
/// (`--config FILE`); its template, uncommented, is read (the library's test).
#[test]
fn the_configuration_can_be_found_and_named() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_turntable"))
            .args(args)
            .env("XDG_CONFIG_HOME", dir.path())
            .output()
            .unwrap();
        let text = |b: Vec<u8>| String::from_utf8(b).unwrap();
        (
            out.status.code().unwrap_or(-1),
            text(out.stdout),
            text(out.stderr),
        )
    };
    let want = dir.path().join("turntable").join("config.toml");
    let (code, out, _) = run(&["config", "--path"]);
    assert_eq!((code, out.trim()), (0, want.to_str().unwrap()));
    let (code, out, _) = run(&["config"]);
    assert_eq!(code, 0);
    assert!(
        out.starts_with(&format!("# {} (not there yet", want.display())),
        "{out}"
    );
    for key in [
        "theme", "fps", "speed", "paused", "mouse", "marker", "[units]",
    ] {
        assert!(out.contains(&format!("# {key}")), "{key}: {out}");
    }
    // --init writes the template there, its folder made (a fresh machine has none), the file
    // the explorer then reads; a second --init keeps it.
    let (code, said, err) = run(&["config", "--init"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(said.trim(), format!("wrote {}", want.display()));
    let written = std::fs::read_to_string(&want).unwrap();
    assert!(out.ends_with(&written) && written.len() > 200, "{written}");
    std::fs::write(&want, "fps = 12\n").unwrap();
    let (code, _, err) = run(&["config", "--init"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("is there already: kept"), "{err}");
    assert_eq!(std::fs::read_to_string(&want).unwrap(), "fps = 12\n");
    let (code, out, _) = run(&["config"]);
    assert!(code == 0 && out.contains("(there;"), "{out}");
    std::fs::remove_file(&want).unwrap();
    // A named file is read, and refused as the usual one is; a missing one is said.
    let bad = dir.path().join("mine.toml");
    std::fs::write(&bad, "fps = 500\n").unwrap();
    let (code, _, err) = run(&["--config", bad.to_str().unwrap(), "--plain"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("mine.toml: key `fps`: must lie in 1..=240"),
        "{err}"
    );
    let (code, _, err) = run(&["--config", "/nonexistent/turntable.toml", "--plain"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("/nonexistent/turntable.toml"), "{err}");
}

/// Issue 18 item 22: bracket widths no run can certify are refused up front (`sweep fig5
/// --vtol 1e-308` ran on and then advised `--tau-max`, which sweep does not take); a budget
/// spent inside a solver advises the solver's own flags.
#[test]
fn solvers_refuse_unreachable_brackets_and_advise_their_own_flags() {
    for args in [
        &["sweep", "fig5", "--vtol", "1e-308"][..],
        &["escape", "--xi0", "0.5", "--vtol", "1e-20"],
        &["critical", "--xtol", "1e-300"],
    ] {
        let (code, out, err) = turntable(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty());
        assert!(err.contains("must lie in [1e-12, 1]"), "{err}");
    }
    let (code, _, err) = turntable(&[
        "escape",
        "--xi0",
        "0.5",
        "--phi",
        "1",
        "--vtol",
        "1e-12",
        "--max-steps",
        "1000",
    ]);
    assert_eq!(code, 1);
    assert!(
        err.contains("raise --max-steps, or loosen --vtol or --tol"),
        "{err}"
    );
    assert!(!err.contains("tau-max"), "{err}");
}

/// Issue 18 item 22: a write error on `--out` names the file.
#[test]
fn a_failed_out_names_its_file() {
    if !std::path::Path::new("/dev/full").exists() {
        eprintln!("skipped: no /dev/full here");
        return;
    }
    let (code, _, err) = turntable(&["sweep", "fig6", "--points", "3", "--out", "/dev/full"]);
    assert_eq!(code, 1);
    assert!(err.starts_with("error: --out /dev/full: "), "{err}");
}

/// Issue 33 item 8: `--help` or `--version` that cannot be written (stdout on /dev/full)
/// fails; clap's own exit said 0. Written, or read in part by `| head`, they still exit 0.
#[test]
fn help_and_version_that_cannot_be_written_fail() {
    if !std::path::Path::new("/dev/full").exists() {
        eprintln!("skipped: no /dev/full here");
        return;
    }
    let run = |args: &[&str], stdout: std::process::Stdio| {
        std::process::Command::new(env!("CARGO_BIN_EXE_turntable"))
            .args(args)
            .env("XDG_CONFIG_HOME", common::NO_CONFIG)
            .stdout(stdout)
            .output()
            .unwrap()
    };
    for args in [
        &["--help"][..],
        &["-h"],
        &["--version"],
        &["-V"],
        &["run", "--help"],
        &["help", "replay"],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let o = run(args, full.into());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains("writing to stdout"), "{args:?}: {err}");
        let o = run(args, std::process::Stdio::piped());
        assert_eq!(o.status.code(), Some(0), "{args:?}");
        assert!(!o.stdout.is_empty());
    }
    // A usage error is still 2, its message on stderr.
    let (code, _, err) = turntable(&["--no-such-flag"]);
    assert_eq!(code, 2, "{err}");
}

/// Issue 18 item 22: φ beyond ±1e6 rad is refused (its remainder mod 2π has no digits left);
/// CSV numbers never print as 300-digit decimals, nor as −0, and JSON gives no −0.
#[test]
fn angles_are_bounded_and_numbers_print_short() {
    let (code, _, err) = turntable(&["run", "--phi", "1e300"]);
    assert_eq!(code, 2);
    assert!(err.contains("phi must lie in [-1e6, 1e6]"), "{err}");
    let (code, out, _) = turntable(&["sweep", "fig6", "--points", "2", "--xi0-max", "1e-300"]);
    assert_eq!(code, 0);
    assert_eq!(out, "xi0,outcome,xi,angle\n0,stuck,0,0\n1e-300,stuck,0,0\n");
    let (code, out, _) = turntable(&["sweep", "fig5", "--xi0", "-0", "--points", "1"]);
    assert_eq!(code, 0);
    assert!(out.lines().nth(1).unwrap().starts_with("0,0,"), "{out}");
    let (code, out, _) = turntable(&["escape", "--xi0", "0.5", "--phi", "-0", "--json"]);
    assert_eq!(code, 0);
    assert_eq!(field(&out, "phi"), "0.0");
    let path = std::env::temp_dir().join(format!("turntable-tiny-{}.csv", std::process::id()));
    let (code, _, err) = turntable(&[
        "run",
        "--v0",
        "1e-300",
        "--tau-max",
        "1",
        "--trajectory",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    let longest = csv.split([',', '\n']).map(str::len).max().unwrap();
    assert!(longest <= 24, "{longest}: {csv}");
    assert!(!csv.contains("-0,") && !csv.contains("-0\n"), "{csv}");
}

/// `sweep fig5|fig6|map` are subcommands, each refusing a flag that means nothing to it (`sweep
/// fig6 --phi-points 7 --v0-max 9 --release lab-rest` exited 0, ignoring all three).
#[test]
fn each_sweep_takes_only_its_own_flags() {
    for args in [
        &["sweep", "fig6", "--phi-points", "7"][..],
        &["sweep", "fig6", "--v0-max", "9"],
        &["sweep", "fig6", "--release", "lab-rest"],
        &["sweep", "fig6", "--vtol", "1e-6"],
        &["sweep", "fig5", "--xi0-max", "2"],
        &["sweep", "fig5", "--release", "lab-rest"],
        &["sweep", "map", "--xi0", "0.5", "--points", "3"],
        &["sweep", "map", "--xi0", "0.5", "--xi0-max", "2"],
    ] {
        let (code, out, err) = turntable(args);
        assert_eq!(code, 2, "{args:?}: {out}");
        assert!(err.contains("unexpected argument"), "{args:?}: {err}");
    }
}

/// One angle convention on every output (issue 18): `sweep map` and `sweep fig6` give rest
/// angles in [0, 2π), as `run` does (they wrote raw atan2, some negative).
#[test]
fn sweep_angles_lie_in_zero_to_two_pi() {
    let runs = [
        vec![
            "sweep",
            "map",
            "--xi0",
            "0.5",
            "--phi-points",
            "12",
            "--v0-points",
            "6",
            "--v0-max",
            "1",
        ],
        vec!["sweep", "fig6", "--points", "12"],
    ];
    for args in runs {
        let (code, out, err) = turntable(&args);
        assert_eq!(code, 0, "{err}");
        let mut n = 0;
        for line in out.lines().skip(1) {
            let angle = line.rsplit(',').next().unwrap();
            if angle.is_empty() {
                continue;
            }
            let a: f64 = angle.parse().unwrap();
            assert!(
                (0.0..std::f64::consts::TAU).contains(&a),
                "{args:?}: {line}"
            );
            n += 1;
        }
        assert!(n >= 6, "{args:?}: {out}");
    }
}

#[test]
fn dop853_takes_tol_and_rests_where_dp54_does() {
    let args = [
        "run",
        "--xi0",
        "0.5",
        "--phi",
        "3.141592653589793",
        "--v0",
        "1",
        "--json",
    ];
    let xi = |extra: &[&str]| {
        let (code, out, err) = turntable(&[&args[..], extra].concat());
        assert_eq!(code, 0, "{err}");
        (field(&out, "method"), field(&out, "tol"), field(&out, "xi"))
    };
    let (m, tol, x8) = xi(&["--method", "dop853", "--tol", "1e-12"]);
    assert_eq!((m.as_str(), tol.as_str()), ("\"dop853\"", "1e-12"));
    let (_, _, x5) = xi(&["--method", "dp54", "--tol", "1e-12"]);
    let (x8, x5): (f64, f64) = (x8.parse().unwrap(), x5.parse().unwrap());
    assert!((x8 - x5).abs() < 1e-10, "{x8} vs {x5}");
    // Its default knob is a tolerance too; a dt is refused.
    assert_eq!(xi(&["--method", "dop853"]).1, "1e-10");
    let (code, _, err) = turntable(&["run", "--method", "dop853", "--dt", "0.01"]);
    assert_eq!(code, 2);
    assert!(err.contains("dop853 takes --tol"), "{err}");
}

/// `replay --help` documents the script grammar itself (an installed binary has no README), and
/// its example replays as printed.
#[test]
fn replay_help_carries_a_working_example() {
    let (code, help, _) = turntable(&["replay", "--help"]);
    assert_eq!(code, 0);
    assert!(!help.contains("README"), "{help}");
    let script: String = help
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("resize"))
        .take_while(|l| l.starts_with("    "))
        .map(|l| format!("{}\n", l.trim()))
        .collect();
    assert!(script.contains("mouse click"), "{script}");
    let path = std::env::temp_dir().join(format!("turntable-help-{}.keys", std::process::id()));
    std::fs::write(&path, &script).unwrap();
    let (code, out, err) = turntable(&["replay", path.to_str().unwrap()]);
    std::fs::remove_file(&path).unwrap();
    assert_eq!(code, 0, "{err}");
    assert!(
        out.starts_with("--- snapshot 1: after 80 ticks (80x24"),
        "{out}"
    );
}

/// Issue 32 item 4: the long commands draw their progress bar only where stderr is a
/// terminal; piped, stderr stays empty and the output is the same.
#[test]
fn progress_is_silent_in_a_pipe() {
    for args in [
        &[
            "sweep", "fig5", "--xi0", "0.5", "--points", "12", "--vtol", "1e-6",
        ][..],
        &["sweep", "fig6", "--points", "12"],
        &["sweep", "map", "--phi-points", "6", "--v0-points", "4"],
        &["critical", "--xtol", "1e-4"],
    ] {
        let (code, out, err) = turntable(args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert!(err.is_empty(), "{args:?}: {err}");
        assert!(!out.is_empty());
    }
}

/// An error quoting what it refuses is cut at a screen's worth (a key script's line of a
/// megabyte was echoed whole), and an output that cannot be written names its path.
#[test]
fn errors_are_cut_and_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("long.keys");
    std::fs::write(&script, format!("{}\n", "x".repeat(1_000_000))).unwrap();
    let (code, _, err) = turntable(&["replay", script.to_str().unwrap()]);
    assert_eq!(code, 2, "{}", &err[..err.len().min(400)]);
    assert!(err.len() < 2_000, "{} bytes of error", err.len());
    assert!(err.contains("characters in all"), "{err}");
    if std::path::Path::new("/dev/full").exists() {
        let (code, _, err) = turntable(&["run", "--trajectory", "/dev/full", "--force"]);
        assert_eq!(code, 1, "{err}");
        assert!(err.contains("writing --trajectory /dev/full"), "{err}");
    }
}

/// Each flag's help sits under its own group's heading: a flattened group's heading once
/// carried over to the flags declared after it (`run -h` listed --json, --tau-max and
/// --trajectory under "Friction:"). The groups' members are read from the groups themselves.
#[test]
fn every_flag_is_under_its_own_heading() {
    use clap::{Args, CommandFactory};
    use turntable::cli::{BodyArgs, Cli, CouplingArgs, UnitsArgs};
    // A group's flag: its id and its help (`sweep body` has a --body-angle of its own).
    let key = |a: &clap::Arg| (a.get_id().to_string(), a.get_help().map(|h| h.to_string()));
    let groups: Vec<(Option<String>, Vec<_>)> = [
        CouplingArgs::augment_args(clap::Command::new("g")),
        UnitsArgs::augment_args(clap::Command::new("g")),
        BodyArgs::augment_args(clap::Command::new("g")),
    ]
    .iter()
    .map(|c| {
        let ids: Vec<_> = c.get_arguments().map(key).collect();
        let heading = c.get_arguments().next().and_then(|a| a.get_help_heading());
        (heading.map(str::to_string), ids)
    })
    .collect();
    assert!(
        groups.iter().all(|(h, ids)| h.is_some() && ids.len() >= 3),
        "{groups:?}"
    );
    let mut bad = vec![];
    let mut seen = 0;
    let mut stack = vec![(String::new(), Cli::command())];
    while let Some((path, cmd)) = stack.pop() {
        for a in cmd.get_arguments() {
            let id = key(a);
            let want = groups
                .iter()
                .find(|(_, ids)| ids.contains(&id))
                .and_then(|(h, _)| h.clone());
            let got = a.get_help_heading().map(str::to_string);
            let a_groups = groups.iter().any(|(h, _)| *h == got);
            seen += 1;
            // A group's flag under its heading; any other under none of the groups' (the
            // explorer's own flags are under "Explorer").
            if (want.is_some() && got != want) || (want.is_none() && got.is_some() && a_groups) {
                bad.push(format!("{path} --{}: under {got:?}, not {want:?}", id.0));
            }
        }
        let help = cmd.clone().render_help().to_string();
        if help.contains("0.0000") {
            bad.push(format!("{path}: a default written long: {help}"));
        }
        for sub in cmd.get_subcommands() {
            stack.push((format!("{path} {}", sub.get_name()), sub.clone()));
        }
    }
    let help = Cli::command().render_help().to_string();
    for preset in turntable::scene::PRESETS {
        assert!(
            help.contains(&format!("{preset}, ")) || help.contains(&format!("{preset})")),
            "{preset}: {help}"
        );
    }
    assert!(seen > 100, "{seen}");
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
