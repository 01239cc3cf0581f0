//! The table spun up until the coin slides (issue 29 item 9): `turntable spinup` locates the
//! slip where the closed form puts it, infers μ as a student would and says how far off that
//! is, and refuses a bad ramp with exit code 2, naming the flag.

use crate::common::turntable;
use turntable::engine::Settings;
use turntable::engine::spinup::{Onset, Ramp, SpinRun, inferred_mu};

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = turntable(args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

/// The slip the command prints is the closed form's to 1e-12; the student's μ is
/// Ω_slip² ξ0, below μ_s by √(1 − (a ξ0 μ_k/μ_s)²); on a real table the slip rpm is Ω_slip
/// times the reference rpm.
#[test]
fn the_command_locates_the_closed_form_slip() {
    for (rate, ratio) in [("0.1", "1"), ("1", "1"), ("0.5", "1.5")] {
        let v = json(&[
            "spinup",
            "--rate",
            rate,
            "--mu-static-ratio",
            ratio,
            "--json",
            "--mu",
            "0.3",
            "--rpm",
            "30",
        ]);
        let (a, hold): (f64, f64) = (rate.parse().unwrap(), ratio.parse().unwrap());
        let Onset::At { tau, omega } = Ramp {
            rate: a,
            omega0: 0.0,
        }
        .onset(0.5, hold) else {
            panic!()
        };
        let slip = v["slip_tau"].as_f64().unwrap();
        assert!((slip - tau).abs() < 1e-12 * tau, "{slip} {tau}");
        assert!((v["closed_form_omega"].as_f64().unwrap() - omega).abs() < 1e-15);
        let mu = v["mu_inferred"].as_f64().unwrap();
        let bias = (1.0 - (a * 0.5 / hold).powi(2)).sqrt();
        assert!((mu - hold * bias).abs() < 1e-12, "{mu} {bias}");
        assert_eq!(v["outcome"], "escaped");
        let u = &v["units"];
        assert!((u["slip_rpm"].as_f64().unwrap() - 30.0 * omega).abs() < 1e-9);
        assert!((u["mu_inferred"].as_f64().unwrap() - 0.3 * mu).abs() < 1e-12);
        assert!((u["mu_s"].as_f64().unwrap() - 0.3 * hold).abs() < 1e-15);
    }
    // A ramp of a = 1 on a coin at ξ0 = 0.5: a student reads μ 13% low.
    let v = json(&["spinup", "--rate", "1", "--json"]);
    assert_eq!(
        format!("{:.4}", v["mu_inferred"].as_f64().unwrap()),
        "0.8660"
    );
    let (code, out, _) = turntable(&["spinup", "--rate", "1"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("0.866025 mu_k, true mu_s = 1 mu_k (-13.397%)"),
        "{out}"
    );
}

/// Bad values exit 2, each named by its flag; a ramp as fast as μ_s g/r0 slips at once.
#[test]
fn bad_ramps_are_refused_by_their_flags() {
    for (args, says) in [
        (
            &["--rate", "0"][..],
            "--rate (dOmega/dtau, units of Omega_ref^2) must be > 0",
        ),
        (
            &["--rate", "nan"][..],
            "--rate (dOmega/dtau, units of Omega_ref^2) must be a finite",
        ),
        (
            &["--rate", "1", "--omega0", "-1"][..],
            "--omega0 (units of Omega_ref) must lie in [0, 1e6]",
        ),
        (&["--rate", "1", "--xi0", "-1"][..], "--xi0 must be ≥ 0"),
        (
            &["--rate", "1", "--tau-max", "0"][..],
            "--tau-max must lie in",
        ),
        (
            &["--rate", "1", "--coupling", "stokes", "--gamma", "1"][..],
            "dry friction",
        ),
        (&[][..], "--rate"),
    ] {
        let mut all = vec!["spinup"];
        all.extend_from_slice(args);
        let (code, _, err) = turntable(&all);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
    let v = json(&["spinup", "--rate", "2.5", "--json"]);
    assert_eq!(v["slip_tau"], 0.0);
    assert_eq!(v["closed_form_tau"], 0.0);
}

/// Ramped ever more slowly, the slip comes where the constant-Ω model puts it: ξ0Ω² = μ_s/μ_k,
/// and the student's μ is right in the limit.
#[test]
fn a_slow_ramp_is_the_constant_tables_stick_condition() {
    let mut last = 0.0;
    for a in [1e-1, 1e-2, 1e-3] {
        let mut run = SpinRun::new(
            Ramp {
                rate: a,
                omega0: 0.0,
            },
            0.8,
            Settings::dp54(1e-10),
        )
        .unwrap();
        run.step(1e5).unwrap();
        let s = run.slip().unwrap();
        let err = (0.8 * s.omega * s.omega - 1.0).abs();
        assert!(err < (a * 0.8).powi(2) + 1e-15, "{a}: {err}");
        assert!(err < last || last == 0.0);
        last = err;
        assert_eq!(s.inferred_mu, inferred_mu(s.omega, 0.8));
    }
}

/// A scene with `[spin]` is run by `spinup --scene`, its values checked as typed there (exit
/// 2); the explorer and replay show it (the table spun up); plot draws the constant-Ω table,
/// so it refuses it (exit 2) rather than draw another run.
#[test]
fn a_spin_scene_is_run_by_spinup_shown_by_the_explorer_and_refused_by_plot() {
    let dir = std::env::temp_dir().join(format!("turntable-spin-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = |name: &str, spin: &str, release: &str| {
        let path = dir.join(name);
        std::fs::write(
            &path,
            format!(
                "name = \"spin\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.0\nrelease = \"{release}\"\n[units]\nmu = 0.3\nrpm = 30\n[spin]\n{spin}\n"
            ),
        )
        .unwrap();
        path.to_str().unwrap().to_string()
    };
    let good = scene("good.toml", "rate = 1.0", "table-rest");
    let v = json(&["spinup", "--scene", &good, "--json"]);
    assert_eq!(
        format!("{:.4}", v["mu_inferred"].as_f64().unwrap()),
        "0.8660"
    );
    assert_eq!(v["units"]["rpm"], 30.0);
    for (path, says) in [
        (
            scene("zero.toml", "rate = 0.0", "table-rest"),
            "[spin] rate (dOmega/dtau, units of Omega_ref^2) must be > 0, got 0",
        ),
        (
            scene("neg.toml", "rate = 1.0\nomega0 = -1.0", "table-rest"),
            "[spin] omega0 (units of Omega_ref) must lie in [0, 1e6], got -1",
        ),
        (
            scene("typo.toml", "rat = 1.0", "table-rest"),
            "unknown field `rat`",
        ),
        (
            scene("thrown.toml", "rate = 1.0", "velocity"),
            "it needs [initial] release = \"table-rest\"",
        ),
    ] {
        let (code, _, err) = turntable(&["spinup", "--scene", &path]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains(says), "{err}");
    }
    let (code, _, err) = turntable(&["spinup", "--scene", &good, "--rate", "1"]);
    assert_eq!(code, 2, "{err}");
    // The explorer opens it: a real table's rpm (the reference rate) and μ in the readouts.
    let script = dir.join("s.keys");
    std::fs::write(&script, "resize 100x30\ntick 100\n").unwrap();
    let (code, out, err) = turntable(&["replay", script.to_str().unwrap(), "--scene", &good]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("scene spin") && out.contains("rpm"), "{out}");
    assert!(out.contains("μ read 0.2598 (μs 0.3000)"), "{out}");
    let (code, _, err) = turntable(&[
        "plot",
        "trajectory",
        "--scene",
        good.as_str(),
        "--out",
        "x.svg",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("[spin] spins the table up; `plot` draws the constant-Ω table"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
