//! Honest numbers (issue 11): outcomes that say when the run's own error could flip them,
//! bad solver input refused up front, and words that say what the numbers are.

use crate::common;
use crate::reference;
use common::turntable;
use turntable::engine::doubt::doubt;
use turntable::engine::{Initial, Outcome, Run, Settings};

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = turntable(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

fn outcome(i: Initial, s: Settings) -> (Outcome, Run) {
    let mut run = Run::new(i, s).unwrap();
    let o = run.run(100.0, true).unwrap();
    (o, run)
}

/// The escape speed at ξ0 = 0.5, φ = 0 (docs/numerics.md; `escape --vtol 1e-10`).
const VE: f64 = 0.607_823_64;

/// Never wrong and certain: around the escape speed, a loose run whose outcome differs from a
/// converged one (tol 1e-12) must say it is not certain.
#[test]
fn a_loose_run_near_the_threshold_is_never_wrong_and_certain() {
    let mut flagged = 0;
    let mut wrong = 0;
    for tol in [1e-6, 1e-8] {
        for k in -12..=12 {
            let v0 = VE + f64::from(k) * 2e-8;
            let i = Initial::velocity(0.5, 0.0, v0);
            let (loose, run) = outcome(i, Settings::dp54(tol));
            let (truth, _) = outcome(i, Settings::dp54(1e-12));
            let d = doubt(&run, 100.0);
            if loose != truth {
                wrong += 1;
                assert!(
                    !d.certain,
                    "tol {tol}, v0 {v0}: {loose:?} but {truth:?}: {d:?}"
                );
            }
            flagged += usize::from(!d.certain);
        }
    }
    // The loose runs do get some of these wrong, and the doubt covers them.
    assert!(
        wrong > 0 && flagged >= wrong,
        "{wrong} wrong, {flagged} flagged"
    );
}

#[test]
fn ordinary_runs_are_certain() {
    let cases = [
        Initial::velocity(0.5, std::f64::consts::PI, 1.0),
        Initial::velocity(0.5, 0.0, 0.6),
        Initial::velocity(0.5, 0.0, 0.6078),
        Initial::velocity(1.1, 1.2 * std::f64::consts::PI, 1.3),
        Initial::velocity(0.5, 0.4, 1.5),
    ];
    for i in cases {
        for s in [Settings::default(), Settings::dp54(1e-6)] {
            let (_, run) = outcome(i, s);
            let d = doubt(&run, 100.0);
            assert!(d.certain, "{i:?} {s:?}: {d:?}");
        }
    }
    // The paper's scheme on case C escapes where the converged run sticks: in doubt.
    let (o, run) = outcome(Initial::velocity(0.5, 0.0, 0.6078), Settings::paper());
    assert_eq!(o, Outcome::Escaped);
    assert!(!doubt(&run, 100.0).certain);
}

#[test]
fn run_json_says_whether_it_is_certain() {
    let v = json(&["run", "--v0", "0.6078", "--json"]);
    assert_eq!(v["certain"], true);
    let v = json(&["run", "--v0", "0.6078236", "--tol", "1e-6", "--json"]);
    assert_eq!(v["certain"], false);
    let (_, text, _) = turntable(&["run", "--v0", "0.6078236", "--tol", "1e-6"]);
    assert!(text.contains("certain  no:"), "{text}");
}

#[test]
fn solver_bounds_are_refused_up_front() {
    for args in [
        &["escape", "--xi0", "5e11"][..],
        &["sweep", "fig5", "--xi0", "1e12", "--points", "2"],
        &["sweep", "fig6", "--xi0-max", "1e13", "--points", "2"],
        &["critical", "--omega", "1e200", "--r0c", "1e200"],
    ] {
        let (code, out, err) = turntable(args);
        assert_eq!(code, 2, "{args:?}: {out}{err}");
        assert!(
            err.starts_with("error: ") && err.len() < 200,
            "{args:?}: {err}"
        );
    }
    let (code, _, err) = turntable(&["run", "--xi0", "-inf"]);
    assert_eq!(code, 2);
    assert!(err.contains("xi0 must be a finite number"), "{err}");
    let (code, _, err) = turntable(&["--fps", "5", "run"]);
    assert_eq!(code, 2, "explorer flags before a subcommand: {err}");
    let (code, _, err) = turntable(&["run", "--tau-max", "1e300"]);
    assert_eq!(code, 2);
    assert!(err.contains("got 1e300"), "{err}");
}

/// At ξ0 = 1.2, φ = 3.5 a release at rest on the table already escapes and some faster ones
/// stick: no speed is named as sticking unless a run at it sticks.
#[test]
fn escaping_speeds_that_are_not_one_interval() {
    let v = json(&["escape", "--xi0", "1.2", "--phi", "3.5", "--json"]);
    assert_eq!(v["v_escape"], 0.0);
    assert_eq!(v["stuck_at"], serde_json::Value::Null);
    assert_eq!(v["interval"], false);
    let scan = v["scan"].as_array().unwrap();
    let stuck: Vec<f64> = scan
        .iter()
        .filter(|p| p["outcome"] == "stuck")
        .map(|p| p["v0"].as_f64().unwrap())
        .collect();
    assert!(!stuck.is_empty());
    for v0 in [stuck[0], stuck[stuck.len() - 1]] {
        let r = json(&[
            "run",
            "--xi0",
            "1.2",
            "--phi",
            "3.5",
            "--v0",
            &v0.to_string(),
            "--json",
        ]);
        assert_eq!(r["outcome"], "stuck", "v0 {v0}");
    }
    let (_, text, _) = turntable(&["escape", "--xi0", "1.2", "--phi", "3.5"]);
    assert!(!text.contains("stuck at 0"), "{text}");
    assert!(text.contains("stick;") && text.contains("escape"), "{text}");
}

#[test]
fn words_that_say_what_the_numbers_are() {
    let (_, text, _) = turntable(&["run", "--v0", "1.5", "--phi", "0.4"]);
    assert!(text.starts_with("outcome  escaped: certified at tau (radial: xi = 1 crossed"));
    assert!(!text.contains("escaped: escaped"), "{text}");
    let v = json(&["run", "--frictionless", "--v0", "1", "--json"]);
    assert_eq!(
        (v["steps"].as_u64(), v["rhs_evals"].as_u64()),
        (Some(0), Some(0))
    );
    // Stops clockwise of the release (case A): the angle reads in [0, 2π), as the paper's.
    let v = json(&["run", "--phi", "-0.5", "--v0", "0.3", "--json"]);
    let a = v["angle"].as_f64().unwrap();
    assert!(
        (std::f64::consts::PI..std::f64::consts::TAU).contains(&a),
        "{a}"
    );
    let (_, help, _) = turntable(&["run", "--help"]);
    assert!(help.contains("lab-rest (at rest in the lab)"), "{help}");
    assert!(help.contains("Print one JSON object"), "{help}");
    let (_, help, _) = turntable(&["bench", "--help"]);
    assert!(!help.contains("issue"), "{help}");
}

/// The explorer shows the same doubt in its status, and none where the outcome is sure.
#[test]
fn the_explorer_says_when_an_outcome_is_in_doubt() {
    use turntable::app::App;
    use turntable::scene::Scene;
    use turntable::session::Explorer;

    use turntable::ui::export::plain_text;
    for (v0, tol, doubtful) in [(0.6078236, 1e-6, true), (0.6078, 1e-10, false)] {
        let mut scene = Scene::default_scene();
        scene.initial.v0 = v0;
        scene.settings = Settings::dp54(tol);
        let app = App::new(scene);
        let mut s = Explorer::headless(
            app,
            turntable::theme::Theme::builtin("dark").unwrap(),
            80,
            24,
            false,
        );
        for _ in 0..200 {
            s.tick();
        }
        let screen = plain_text(s.screen());
        assert!(screen.contains("stuck at ξ"), "{screen}");
        assert_eq!(screen.contains("in doubt"), doubtful, "{screen}");
    }
    // The paper's RK2 beside C: its escape is certified for its own path, and the panel says
    // in the same breath which outcome holds (it read "escape certified … in doubt").
    let mut s = Explorer::headless(
        App::new(Scene::default_scene()),
        turntable::theme::Theme::builtin("dark").unwrap(),
        100,
        40,
        false,
    );
    s.press("c".parse().unwrap());
    s.press("]".parse().unwrap());
    s.press("]".parse().unwrap());
    s.press("]".parse().unwrap());
    for _ in 0..200 {
        s.tick();
    }
    let screen = plain_text(s.screen());
    assert!(
        screen.contains("escape certified")
            && screen.contains("but its error flips it:")
            && screen.contains("a converged run sticks")
            && !screen.contains("in doubt"),
        "{screen}"
    );
}

/// The paper writes case D's angle as 1.2π: so does the explorer ([0, 2π), not −0.8π).
#[test]
fn the_explorer_shows_phi_as_the_paper_does() {
    use turntable::app::App;
    use turntable::scene::Scene;
    use turntable::session::Explorer;

    use turntable::ui::export::plain_text;
    let app = App::new(Scene::preset("D").unwrap());
    let mut s = Explorer::headless(
        app,
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        false,
    );
    let screen = plain_text(s.screen());
    assert!(screen.contains("φ 1.2π"), "{screen}");
}

/// The second opinion is another formulation, even at the tightest tolerance (where a tighter
/// run in the same form would be the run itself): Sundman time in rim distance wherever that
/// holds, else dop853 in the other frame; `--no-check` skips it and then claims nothing.
#[test]
fn the_second_opinion_is_independent_and_can_be_skipped() {
    for frame in ["lab", "table"] {
        let v = json(&[
            "run", "--v0", "0.6", "--tol", "1e-14", "--frame", frame, "--json",
        ]);
        assert_eq!(v["certain"], true);
        assert_eq!(v["check"]["method"], "sundman-radau", "{v}");
        assert_eq!(v["check"]["tol"], 1e-14);
    }
    // At rest on the table outside ξ = 1 (|u| = 0: no Sundman time): the Cartesian check.
    let v = json(&["run", "--xi0", "1.2", "--release", "table-rest", "--json"]);
    assert_eq!(v["check"]["method"], "dop853", "{v}");
    assert_eq!(v["check"]["frame"], "table");
    let v = json(&["run", "--v0", "0.6", "--json", "--no-check"]);
    assert!(
        v.get("certain").is_none() && v.get("check").is_none(),
        "{v}"
    );
    let (_, text, _) = turntable(&["run", "--v0", "0.6", "--no-check"]);
    assert!(!text.contains("certain"), "{text}");
}

/// `certain` covers the outcome; the time and place of the end come with their measured
/// differences from the second opinion. Near a threshold the stop time is ill-conditioned
/// (v0 = v_e − 3e-9 at ξ0 = 0.5): the run is certain to stick, and says its τ is uncertain by
/// far more than its tolerance.
#[test]
fn stop_times_come_with_their_measured_error() {
    let v = json(&["run", "--v0", "0.60782364", "--tau-max", "1e4", "--json"]);
    assert_eq!(v["outcome"], "stuck");
    assert_eq!(v["certain"], true);
    let dt = v["check"]["tau_error"].as_f64().unwrap();
    // Far more than the tolerance (1e-10).
    assert!(dt > 1e-6, "{v}");
    // And it is an honest measure: the converged stop time lies within it.
    let tight = json(&[
        "run",
        "--v0",
        "0.60782364",
        "--tau-max",
        "1e4",
        "--tol",
        "1e-14",
        "--json",
    ]);
    let (t, t_ref) = (v["tau"].as_f64().unwrap(), tight["tau"].as_f64().unwrap());
    assert!((t - t_ref).abs() <= 2.0 * dt, "{t} vs {t_ref}, said ±{dt}");
    // Far from any threshold the difference is at the tolerance's scale.
    let v = json(&["run", "--v0", "0.3", "--json"]);
    assert!(v["check"]["tau_error"].as_f64().unwrap() < 1e-8, "{v}");
}

/// A solver asked for a bracket narrower than its runs can place (tol looser than the
/// bracket) runs them tighter, and only a bracket whose ends, run in full, end as they say in
/// both the run and its second opinion is called certified.
#[test]
fn solver_brackets_are_certified_only_when_checked() {
    let v = json(&["critical", "--tol", "1e-6", "--json"]);
    assert_eq!(v["run_tol"], 1e-10);
    assert_eq!(v["certified"], true, "{v}");
    // ξ0c from a converged reference (tol 1e-13, xtol 1e-10).
    let x = v["xi0c"].as_f64().unwrap();
    assert!((x - reference::XI0C).abs() < 2e-8, "{x}");
    let v = json(&[
        "escape", "--xi0", "0.99", "--phi", "1", "--vtol", "1e-9", "--json",
    ]);
    assert_eq!(v["certified"], true, "{v}");
    assert_eq!(v["run_tol"], 1e-11);
    let v = json(&["escape", "--xi0", "0.5", "--json", "--no-check"]);
    assert!(v["certified"].is_null(), "{v}");
}

/// A bracket that is not certified says what was tried and no more: a fixed-step method is not
/// run tighter, so its text claims no tighter runs (issue 35: it said "even with runs 10^4x
/// tighter" where none were made).
#[test]
fn an_uncertified_bracket_claims_no_runs_it_did_not_make() {
    let (code, text, _) = turntable(&[
        "escape", "--xi0", "0.5", "--phi", "0", "--method", "rk2", "--dt", "0.1", "--vtol", "1e-8",
    ]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("NOT certified"), "{text}");
    assert!(!text.contains("tighter"), "{text}");
}

/// Followed past its escape certificate (`--follow`), `run` prints the end at τ-max but its
/// measured differences are the certificate's: it says so (issue 35).
#[test]
fn a_followed_run_says_its_errors_are_the_certificates() {
    let (code, text, _) = turntable(&[
        "run",
        "--xi0",
        "0.5",
        "--v0",
        "0.7",
        "--follow",
        "--tau-max",
        "10",
    ]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("tau      10.000000000"), "{text}");
    assert!(
        text.contains("agrees; at the escape certificate (tau "),
        "{text}"
    );
    let (_, text, _) = turntable(&["run", "--xi0", "0.5", "--v0", "0.7"]);
    assert!(!text.contains("at the escape certificate"), "{text}");
}
