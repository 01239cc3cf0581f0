//! One validation for flags, scene files and the configuration (issue 33, items 5 and 7):
//! the same value is refused or taken whichever way it comes, the error names it as the user
//! typed it and prints its number readably, and every accepted table and body shows finite
//! numbers (no `inf`, no `NaN`).

use crate::common;
use common::turntable;
use std::path::PathBuf;
use std::process::Command;

fn tmp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("turntable-valid-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// No `inf`, `NaN` (any case) as a word in `text`.
fn finite(text: &str) -> bool {
    !text
        .split(|c: char| !c.is_ascii_alphanumeric())
        .any(|w| w.eq_ignore_ascii_case("inf") || w.eq_ignore_ascii_case("nan"))
}

/// A scene file with `initial` and `more` (other tables) written out.
fn scene(dir: &std::path::Path, name: &str, initial: &str, more: &str) -> String {
    let p = dir.join(format!("{name}.toml"));
    std::fs::write(
        &p,
        format!("name = \"{name}\"\n[initial]\n{initial}\n{more}"),
    )
    .unwrap();
    p.display().to_string()
}

/// `replay` of a one-snapshot script on `scene`: exit code, stdout, stderr.
fn replay_scene(dir: &std::path::Path, scene: &str, extra: &[&str]) -> (i32, String, String) {
    let keys = dir.join("one.keys");
    std::fs::write(&keys, "tick 3\nI\nsnapshot\n").unwrap();
    let mut args = vec!["replay", keys.to_str().unwrap(), "--scene", scene];
    args.extend(extra);
    turntable(&args)
}

/// The explorer's checks with a configuration file holding `config`: exit code and stderr
/// (stdin is no terminal, so a configuration it takes ends in "needs a terminal").
fn explorer_with_config(dir: &std::path::Path, config: &str) -> (i32, String) {
    let cfg = dir.join("cfg/turntable");
    std::fs::create_dir_all(&cfg).unwrap();
    std::fs::write(cfg.join("config.toml"), config).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .env("XDG_CONFIG_HOME", dir.join("cfg"))
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// The same release and settings are refused as flags and in a scene file (and a pin), and
/// each error names the value as it was typed there.
#[test]
fn flags_and_scene_files_refuse_the_same_values_by_their_own_names() {
    let dir = tmp("same");
    let base = "xi0 = 0.5\nphi = 0.0\nv0 = 0.6";
    // (flags, the scene's [initial], its other tables, the flag's name, the file's name)
    let cases: [(&[&str], &str, &str, &str, &str); 6] = [
        (
            &["--phi", "1e300"],
            "xi0 = 0.5\nphi = 1e300\nv0 = 0.6",
            "",
            "--phi must lie in [-1e6, 1e6] rad, got 1e300",
            "[initial] phi must lie in [-1e6, 1e6] rad, got 1e300",
        ),
        (
            &["--frictionless", "--gamma", "1"],
            "xi0 = 0.5\nphi = 0.0\nv0 = 0.6\nfrictionless = true",
            "[settings]\nmethod = \"dp54\"\ncoupling = \"stokes\"\ngamma = 1.0\n",
            "--frictionless is mu = 0, no coupling to the table at all",
            "[initial] frictionless = true is mu = 0, no coupling to the table at all",
        ),
        (
            &["--v0", "1e13"],
            "xi0 = 0.5\nphi = 0.0\nv0 = 1e13",
            "",
            "--v0 must be ≤ 1e12, got 1e13",
            "[initial] v0 must be ≤ 1e12, got 1e13",
        ),
        (
            &["--tol", "1e-30"],
            base,
            "[settings]\nmethod = \"dp54\"\ntol = 1e-30\n",
            "--tol must lie in [1e-14, 1e-2], got 1e-30",
            "[settings] tol must lie in [1e-14, 1e-2], got 1e-30",
        ),
        (
            &["--mu-static-ratio", "0.5"],
            base,
            "[settings]\nmethod = \"dp54\"\nmu_static_ratio = 0.5\n",
            "--mu-static-ratio (mu_s/mu_k) must lie in [1, 1e6], got 0.5",
            "[settings] mu_static_ratio (mu_s/mu_k) must lie in [1, 1e6], got 0.5",
        ),
        (
            &["--mu", "0.1", "--rpm", "1e-300"],
            base,
            "[units]\nmu = 0.1\nrpm = 1e-300\n",
            "--rpm must lie in [1e-6, 1e6], got 1e-300",
            "[units] rpm must lie in [1e-6, 1e6], got 1e-300",
        ),
    ];
    for (k, (flags, initial, more, flag_err, file_err)) in cases.iter().enumerate() {
        let mut args = vec!["run"];
        args.extend(*flags);
        let (code, _, err) = turntable(&args);
        assert_eq!(code, 2, "{flags:?}: {err}");
        assert!(err.contains(flag_err), "{flags:?}: {err}");
        assert!(err.len() < 300, "a readable number: {err}");
        let s = scene(&dir, &format!("s{k}"), initial, more);
        let (code, _, err) = replay_scene(&dir, &s, &[]);
        assert_eq!(code, 2, "{initial} {more}: {err}");
        assert!(err.contains(file_err), "{initial} {more}: {err}");
        assert!(err.len() < 300, "a readable number: {err}");
    }
    // A pin's release and table are named as the pin's keys.
    let pin = "[[pins]]\nlabel = \"P\"\n[pins.initial]\nxi0 = 0.5\nphi = 1e300\nv0 = 0.6\n";
    let s = scene(&dir, "pin", base, pin);
    let (code, _, err) = replay_scene(&dir, &s, &[]);
    assert_eq!(code, 2);
    assert!(
        err.contains("pin 1 (\"P\"): [pins.initial] phi must lie"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The sweeps' own flags are named as typed, not as the release they stand for.
#[test]
fn sweep_errors_name_the_flag_typed() {
    for (args, want) in [
        (
            &["sweep", "map", "--xi0", "0.5", "--v0-max", "1e13"][..],
            "--v0-max must be ≤ 1e12, got 1e13",
        ),
        (
            &["sweep", "fig6", "--xi0-max", "1e300"][..],
            "--xi0-max must be ≤ 1e12, got 1e300",
        ),
        (
            &["sweep", "body", "--lengths", "1e-12"][..],
            "--lengths (units of R_max) must lie in [1e-9, 1e6], got 1e-12",
        ),
        (
            &["sweep", "fig6", "--points", "0"][..],
            "--points must lie in 1..=100000, got 0",
        ),
        (
            &["escape", "--xi0", "0.5", "--vtol", "1e-30"][..],
            "--vtol must lie in [1e-12, 1]",
        ),
        // Refused by the engine's solver, which names no flag: the command names it.
        (
            &["escape", "--xi0", "1e12"][..],
            "--xi0 must be ≤ 4e11 for an escape speed",
        ),
        (
            &["sweep", "fig5", "--xi0", "0.5,-1"][..],
            "--xi0 must be ≥ 0, got -1",
        ),
        (
            &["run", "--max-steps", "0"][..],
            "--max-steps must be ≥ 1, got 0",
        ),
        (
            &["run", "--coupling", "stokes"][..],
            "--coupling stokes needs --gamma, the drag rate in units of Omega",
        ),
    ] {
        let (code, _, err) = turntable(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
}

/// The configuration's table is checked by the same function: its key is named.
#[test]
fn the_configuration_refuses_what_the_flags_refuse() {
    let dir = tmp("config");
    for config in [
        "[units]\nmu = 0.1\nrpm = 1e-300\n",
        "units = { mu = 0.1, rpm = 1e-300 }\n",
    ] {
        let (code, err) = explorer_with_config(&dir, config);
        assert_eq!(code, 2, "{err}");
        assert!(
            err.contains("[units] rpm must lie in [1e-6, 1e6], got 1e-300"),
            "{err}"
        );
    }
    // At the bounds it is taken (and the explorer goes on to want a terminal).
    let (_, err) = explorer_with_config(&dir, "[units]\nmu = 1e-6\nrpm = 1e6\ng = 1e-6\n");
    assert!(err.contains("needs a terminal"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A tiny rpm once showed `tau = NaN s` and `R_max inf m`: the range taken is the range
/// where every SI number is finite, and at its ends (flags, a scene's [units]) nothing shows
/// `inf` or `NaN`.
#[test]
fn tables_at_the_ends_of_the_range_show_finite_numbers() {
    let dir = tmp("finite");
    for (mu, rpm, g) in [("10", "1e-6", "1e4"), ("1e-6", "1e6", "1e-6")] {
        for release in [&["--v0", "0.6"][..], &["--xi0", "1e12", "--v0", "1e12"][..]] {
            let mut args = vec!["run", "--mu", mu, "--rpm", rpm, "--g", g];
            args.extend(release);
            let (code, out, err) = turntable(&args);
            assert_eq!(code, 0, "{args:?}: {err}");
            assert!(out.contains("R_max = "), "{out}");
            assert!(finite(&out), "{args:?}: {out}");
        }
        let s = scene(
            &dir,
            &format!("u{mu}"),
            "xi0 = 0.5\nphi = 0.0\nv0 = 0.6",
            &format!("[units]\nmu = {mu}\nrpm = {rpm}\ng = {g}\n"),
        );
        for plain in [&[][..], &["--plain"][..]] {
            let (code, out, err) = replay_scene(&dir, &s, plain);
            assert_eq!(code, 0, "{err}");
            assert!(finite(&out), "{mu} {rpm} {g}: {out}");
        }
    }
    // Just outside, refused.
    for (mu, rpm) in [("0.1", "9e-7"), ("9e-7", "30")] {
        let (code, _, err) = turntable(&["run", "--mu", mu, "--rpm", rpm]);
        assert_eq!(code, 2, "{mu} {rpm}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A body: μh/L stays finite over the range taken (L ≥ 1e-9), and at the centre L/ξ is said
/// in words (`run`) or left out of the CSV with a note (`sweep body`), never `inf`.
#[test]
fn bodies_show_no_infinity() {
    let (code, out, err) = turntable(&[
        "run",
        "--body-length",
        "1e-9",
        "--body-height",
        "1e6",
        "--mu",
        "10",
        "--rpm",
        "1e-6",
        "--g",
        "1e4",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("mu h/L max = 5.000e15"), "{out}");
    assert!(finite(&out), "{out}");
    let (code, _, err) = turntable(&["run", "--body-length", "1e-300", "--body-height", "10"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--body-length (units of R_max) must lie in [1e-9, 1e6], got 1e-300"),
        "{err}"
    );
    let (code, out, _) = turntable(&["run", "--body-length", "0.1", "--xi0", "0", "--v0", "0"]);
    assert_eq!(code, 0);
    assert!(out.contains("L/xi infinite (at the centre)"), "{out}");
    let (code, out, err) = turntable(&["sweep", "body", "--xi0", "0", "--v0", "0"]);
    assert_eq!(code, 0, "{err}");
    assert!(finite(&out), "{out}");
    assert!(
        out.lines().nth(1).unwrap().starts_with("1e-6,,stuck,"),
        "{out}"
    );
    assert!(
        err.contains("L/r is unbounded: l_over_r is left empty"),
        "{err}"
    );
}
