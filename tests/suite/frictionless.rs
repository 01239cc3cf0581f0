//! μ = 0 (issue #5, "model only what a scene requires"): a straight line in the lab in closed
//! form, checked against integrating the frictionless equations in the rotating frame.

use glam::DVec2;
use turntable::engine::method::Scheme;
use turntable::engine::stepper::adaptive_plain;
use turntable::engine::{Frame, Initial, Outcome, Release, Run, Settings};

fn free(i: Initial) -> Initial {
    Initial {
        frictionless: true,
        ..i
    }
}

#[test]
fn the_closed_form_is_what_the_rotating_frame_equations_give() {
    for i in [
        Initial::velocity(0.5, 0.0, 0.6078),
        Initial::velocity(0.2, 2.5, 1.3),
        Initial::at_rest(0.7, Release::TableRest),
        Initial::at_rest(0.7, Release::LabRest),
    ] {
        let i = free(i);
        let tau = 5.0;
        let (y, _) = adaptive_plain(
            |y| Frame::Table.rhs_free(y),
            Frame::Table.from_state(&i.state()),
            tau,
            Scheme::Dp54 { tol: 1e-12 },
        )
        .unwrap();
        let integrated = Frame::Table.to_state(y, tau);
        let closed = i.free_state(tau);
        assert!((integrated.r - closed.r).length() < 1e-9, "{i:?}");
        assert!((integrated.v - closed.v).length() < 1e-9, "{i:?}");
    }
}

#[test]
fn a_free_particle_escapes_where_its_line_leaves_the_unit_circle() {
    // At rest on the table at ξ0 = 0.5 it leaves tangentially at speed 0.5: ξ² = ¼ + ¼τ².
    let mut run = Run::new(
        free(Initial::at_rest(0.5, Release::TableRest)),
        Settings::default(),
    )
    .unwrap();
    let (outcome, s) = run.finish(100.0).unwrap();
    assert_eq!(outcome, Outcome::Escaped);
    assert!((s.tau - 3f64.sqrt()).abs() < 1e-12, "{}", s.tau);
    assert!((s.xi() - 1.0).abs() < 1e-12);
    assert_eq!(run.cost().rhs_evals, 0);
    // Already outside and moving out: certified at once.
    let mut run = Run::new(free(Initial::velocity(1.5, 0.0, 0.1)), Settings::default()).unwrap();
    assert_eq!(run.finish(100.0).unwrap().1.tau, 0.0);
    // Thrown inward across the centre: it escapes on the far side, after closest approach.
    let i = free(Initial::velocity(0.8, std::f64::consts::PI, 2.0));
    let te = i.free_escape().unwrap();
    let s = i.free_state(te);
    assert!(
        (s.xi() - 1.0).abs() < 1e-12 && s.xi_dot() > 0.0 && s.r.x < 0.0,
        "{s:?}"
    );
}

#[test]
fn at_rest_in_the_lab_it_stays_put_while_the_table_turns_beneath() {
    for xi0 in [0.0, 0.7, 3.0] {
        let i = free(Initial::at_rest(xi0, Release::LabRest));
        assert_eq!(i.free_escape(), None);
        let mut run = Run::new(i, Settings::default()).unwrap();
        assert_eq!(run.run(100.0, true).unwrap(), Outcome::Running);
        let s = run.state();
        assert_eq!(
            (s.tau, s.r, s.v),
            (100.0, DVec2::new(xi0, 0.0), DVec2::ZERO)
        );
        // Seen from the table it circles backwards at ξ0, at relative speed ξ0.
        assert!((s.u().length() - xi0).abs() < 1e-12);
        assert_eq!(run.cost().rhs_evals, 0);
    }
}

#[test]
fn any_method_gives_the_same_closed_form() {
    let i = free(Initial::velocity(0.3, 1.0, 0.4));
    let ends: Vec<_> = [
        Settings::paper(),
        Settings::fixed(turntable::engine::Method::Rk4, 0.1),
    ]
    .into_iter()
    .chain([Settings::default()])
    .map(|s| Run::new(i, s).unwrap().finish(50.0).unwrap().1)
    .collect();
    assert!(ends.windows(2).all(|w| w[0] == w[1]), "{ends:?}");
}

#[test]
fn a_scene_file_says_frictionless_only_when_it_is() {
    use turntable::scene::Scene;
    let dir = std::env::temp_dir().join(format!("turntable-free-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut scene = Scene::default_scene();
    assert!(!scene.to_toml().contains("frictionless"));
    scene.initial.frictionless = true;
    assert!(scene.to_toml().contains("frictionless = true"));
    let path = dir.join("free.toml");
    let _ = std::fs::remove_file(&path);
    assert_eq!(scene.save_new(&path).unwrap(), path);
    let back = Scene::load(path.to_str().unwrap()).unwrap();
    assert!(back.initial.frictionless);
    assert_eq!(back.initial, scene.initial);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn without_friction_only_coriolis_and_centrifugal_act_on_the_table() {
    use turntable::engine::model::table_forces;
    let s = Initial::velocity(0.6, 1.0, 0.3).state();
    let [fr, co, ce] = table_forces(&s, true);
    assert_eq!(fr, DVec2::ZERO);
    let [fr1, co1, ce1] = table_forces(&s, false);
    assert!((fr1.length() - 1.0).abs() < 1e-15);
    assert_eq!((co, ce), (co1, ce1));
}

/// At μ = 0 nothing sticks: the threshold pages say so instead of drawing the paper's
/// friction figures beside a release that leaves, ask the worker for nothing, and export
/// nothing (the twin of Stokes drag's "no threshold").
#[test]
fn without_friction_the_threshold_pages_say_there_is_none() {
    use turntable::app::pages::Page;
    let mut app = turntable::app::App::new(turntable::scene::Scene::preset("C").unwrap());
    turntable::app::update(&mut app, turntable::app::Action::ToggleFriction);
    assert!(app.initial().frictionless);
    for page in [
        Page::EscapeSpeed,
        Page::OutcomeMap,
        Page::RestRadius,
        Page::WorkPrecision,
    ] {
        super::common::turn_to(&mut app, page);
        let screen = super::common::render(&mut app, 80, 24);
        let said = if page == Page::WorkPrecision {
            "closed form"
        } else {
            "μ = 0: no threshold"
        };
        assert!(screen.contains(said), "{page:?}\n{screen}");
        assert!(!screen.contains("release sticks"), "{page:?}\n{screen}");
        assert!(app.wanted_job(|_| Some((10, 10))).is_none(), "{page:?}");
        let dir = tempfile::tempdir().unwrap();
        let said = turntable::session::export_svg(&app, dir.path(), page, None);
        assert!(said.starts_with("not exported"), "{said}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
    // Friction back on: the pages draw and compute again.
    turntable::app::update(&mut app, turntable::app::Action::ToggleFriction);
    super::common::turn_to(&mut app, Page::EscapeSpeed);
    assert!(app.wanted_job(|_| Some((10, 10))).is_some());
}
