//! Issue 42 item 6: ask for an accuracy, not a tolerance — `run --error E` and `error E` at the
//! explorer's `:` prompt run the cheapest setting whose stated error is at most E.

use crate::common::turntable;
use crossterm::event::{KeyCode, KeyModifiers};
use turntable::app::{App, Chord};
use turntable::engine::{Initial, Run, Settings};
use turntable::scene::Scene;
use turntable::session::Explorer;
use turntable::sim::accuracy::cheapest;

/// Case B's neighbour: ξ0 = 0.5 thrown out at v0 = 0.3, a stop at τ ≈ 0.65.
fn release() -> Initial {
    Initial::velocity(0.5, 0.0, 0.3)
}

/// The converged stop (dp54 at tol 1e-13): time and table-frame place.
fn converged() -> (f64, glam::DVec2) {
    let mut run = Run::new(release(), Settings::dp54(1e-13)).unwrap();
    let (_, s) = run.finish(100.0).unwrap();
    (s.tau, s.q())
}

#[test]
fn run_error_runs_a_setting_within_the_error_asked() {
    let (tau, q) = converged();
    for e in [1e-5, 1e-8, 1e-11] {
        let (code, out, err) =
            turntable(&["run", "--v0", "0.3", "--error", &e.to_string(), "--json"]);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let chosen = &v["chosen"];
        assert_eq!(chosen["error"].as_f64(), Some(e));
        assert!(chosen["stated"].as_f64().unwrap() <= e, "{chosen}");
        assert!(v["check"]["tau_error"].as_f64().unwrap() <= e, "{v}");
        assert!(chosen["rhs_evals"].as_u64() == v["rhs_evals"].as_u64());
        assert!(chosen["search_rhs_evals"].as_u64().unwrap() > v["rhs_evals"].as_u64().unwrap());
        assert!(["dp54", "dop853"].contains(&v["method"].as_str().unwrap()));
        // Within the error asked against the converged stop, in time and place.
        let off_tau = (v["tau"].as_f64().unwrap() - tau).abs();
        let xi = v["xi"].as_f64().unwrap();
        assert!(off_tau <= e, "{e}: τ off by {off_tau:e}");
        assert!(
            (xi - q.length()).abs() <= e,
            "{e}: ξ {xi} against {}",
            q.length()
        );
    }
    let (code, out, _) = turntable(&["run", "--v0", "0.3", "--error", "1e-8"]);
    assert_eq!(code, 0);
    assert!(out.starts_with("chosen   error ≤ 1e-8: chose "), "{out}");
    assert!(
        out.contains("RHS evaluations") && out.contains(" ms"),
        "{out}"
    );
}

#[test]
fn the_choice_is_the_cheapest_that_states_the_error() {
    let mut last = 0;
    for e in [1e-4, 1e-7, 1e-10, 1e-12] {
        let c = cheapest(release(), Settings::default(), 100.0, true, e).unwrap();
        let chosen = c.chosen.unwrap();
        assert!(chosen.stated <= e);
        for t in &c.tried {
            if t.stated <= e {
                assert!(t.rhs >= chosen.rhs, "{t:?} is cheaper than {chosen:?}");
            }
        }
        // Both methods were asked, and a tighter error costs more.
        assert!(
            c.tried
                .iter()
                .any(|t| t.settings.method().to_string() == "dop853")
        );
        assert!(chosen.rhs > last, "{e}: {} after {last}", chosen.rhs);
        last = chosen.rhs;
    }
}

#[test]
fn a_bad_error_is_refused_by_name() {
    for bad in ["0", "-1e-6", "nan", "inf", "1e300", "1e-20"] {
        let (code, _, err) = turntable(&["run", "--error", bad]);
        assert_eq!(code, 2, "{bad}: {err}");
        assert!(err.contains("--error must lie in [1e-13, 0.1]"), "{err}");
    }
    for other in [["--tol", "1e-6"], ["--method", "dop853"], ["--dt", "1e-3"]] {
        let (code, _, err) = turntable(&["run", "--error", "1e-6", other[0], other[1]]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("cannot be used with"), "{err}");
    }
    let (code, _, err) = turntable(&["run", "--error", "1e-6", "--frictionless"]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn error_at_the_prompt_switches_the_run() {
    let mut s = Explorer::headless(
        App::new(Scene::preset("B").unwrap()),
        theme(),
        80,
        24,
        false,
    );
    let typed = |s: &mut Explorer<ratatui::backend::TestBackend>, text: &str| {
        s.press(":".parse().unwrap());
        for c in text.chars() {
            s.press(Chord::new(KeyCode::Char(c), KeyModifiers::NONE));
        }
        s.press("enter".parse().unwrap());
    };
    let before = s.app.settings();
    for _ in 0..20 {
        s.app.tick();
    }
    typed(&mut s, "error 1e-6");
    assert!(s.app.prompt().is_none());
    let notice = s.app.notice().clone().unwrap();
    assert!(notice.starts_with("error ≤ 1e-6: chose "), "{notice}");
    let now = s.app.settings();
    assert_ne!(now, before, "dp54 tol 1e-10 is not the cheapest for 1e-6");
    assert!(now.scheme.tol().unwrap() >= 1e-7, "{now:?}");
    assert_eq!(s.app.sim().now().tau, 0.0, "the run restarts");
    let c = cheapest(s.app.initial(), before, 100.0, true, 1e-6).unwrap();
    assert_eq!(c.chosen.unwrap().settings, now);
    // Refused: the reason beside the line, nothing changed.
    typed(&mut s, "error 0");
    let refused = s
        .app
        .prompt()
        .as_ref()
        .and_then(|p| p.refused.clone())
        .unwrap();
    assert!(refused.starts_with("error must lie in"), "{refused}");
    // Short enough to stand beside the line at 80×24.
    let screen = turntable::ui::export::plain_text(s.screen());
    assert!(
        screen.contains(" set: error 0▏  error must lie in [1e-13, 0.1], got 0"),
        "{screen}"
    );
    assert_eq!(s.app.settings(), now);
}

fn theme() -> turntable::theme::Theme {
    turntable::theme::Theme::builtin("dark").unwrap()
}
