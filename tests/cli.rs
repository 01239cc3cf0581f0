//! The headless commands as a user runs them: JSON fields and the trajectory file.

mod common;
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
    assert!((xi - 0.9452679655).abs() < 1e-9, "{xi}");
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
    // dE/dτ = −|u|: E − E(0) and the work column agree to the trapezoid rule's error; a
    // release with speed has no Sec. III approximation (the column is empty).
    let e0 = rows[0][7];
    for r in &rows {
        assert!((r[7] - e0 - r[8]).abs() < 1e-4, "{r:?}");
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
    // Released at rest in the lab far out (Fig. 1), the approx_xi column is Eq. 17.
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
    assert!((v - 0.60782364).abs() < 2e-8, "{v}");
    let (code, out, _) = turntable(&["critical", "--json"]);
    assert_eq!(code, 0);
    let x: f64 = field(&out, "xi0c").parse().unwrap();
    assert!((x - 0.87204386).abs() < 1e-7, "{x}");
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
        (mu - 3.3 * 3.3 * 0.12 / (0.87204386 * 9.81)).abs() < 1e-7,
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
    for r in &rows {
        let (phi, v0): (f64, f64) = (r[0].parse().unwrap(), r[1].parse().unwrap());
        let (_, ve, _) = turntable(&["escape", "--xi0", "0.5", "--phi", r[0], "--json"]);
        let ve: f64 = field(&ve, "v_escape").parse().unwrap();
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
        &["sweep", "map"][..],
        &["sweep", "map", "--xi0", "0.5,0.2"],
        &["sweep", "map", "--xi0", "0.5", "--v0-points", "0"],
        &["sweep", "map", "--xi0", "0.5", "--v0-max", "-1"],
        &["sweep", "map", "--xi0", "0.5", "--release", "sideways"],
    ] {
        let (code, out, err) = turntable(bad);
        assert_eq!(code, 2, "{bad:?}: {err}");
        assert!(out.is_empty() && err.lines().count() <= 4, "{bad:?}: {err}");
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
    let mut app =
        turntable::app::App::new(scene, turntable::theme::Theme::builtin("dark").unwrap());
    let lines: Vec<String> = turntable::ui::panel::lines(&app)
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
    assert!(out.contains("angle    0.000000000000 rad"), "{out}");
    assert_eq!(turntable::engine::model::turn_angle(-1e-13), 0.0);
    assert_eq!(turntable::engine::model::turn_angle(-0.0), 0.0);
    let w = turntable::engine::model::turn_angle(-1e-3);
    assert!((w - (std::f64::consts::TAU - 1e-3)).abs() < 1e-15);
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
