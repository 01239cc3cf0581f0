//! The work–precision page (issue 42, item 5): each setting's error against the converged
//! reference, floored at the reference's resolution, the run's own setting marked, a point
//! picked with j/k and run with Enter, computed only while the page is shown, exported by `E`.

use crate::common::{self, render};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use turntable::analysis::trade::{Ending, TRADE_TAU, trade_base};
use turntable::app::App;
use turntable::app::pages::{Page, Trade, trade_schemes};
use turntable::app::testing::Testing as _;
use turntable::engine::method::Scheme;
use turntable::engine::{Initial, Method, Outcome, Run};
use turntable::plot::{Chart, Mark};
use turntable::scene::Scene;

fn app(scene: &str) -> App {
    let mut a = App::new(Scene::preset(scene).unwrap());
    super::common::turn_to(&mut a, Page::WorkPrecision);
    a
}

fn press(app: &mut App, c: char) {
    app.handle_key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE));
}

/// The page's runs for the release and settings on screen, all computed.
fn trade(a: &mut App) -> Trade {
    common::sync(a);
    let t = a
        .charts()
        .trade(&a.initial(), trade_base(a.settings()))
        .expect("the page's runs")
        .clone();
    for s in trade_schemes(&a.initial(), a.settings()) {
        assert!(t.point(s).is_some(), "{s:?} not computed");
    }
    t
}

fn end(t: &Trade, s: Scheme) -> Ending {
    t.point(s)
        .unwrap()
        .unwrap_or_else(|| panic!("{s:?} failed"))
}

fn err(t: &Trade, s: Scheme) -> f64 {
    end(t, s).error(&t.reference.unwrap().unwrap()).unwrap()
}

/// Case A stops inside ξ = 1: the reference agrees with its cross-check, and each method's
/// error falls as its knob tightens, down to the reference's resolution: second order for
/// rk2 (dt 1e-2 → 1e-4: at least 1000×), the adaptive methods' tightest well below their
/// loosest. The paper's raw RK2 states no error; every other point that is certain states a
/// bound its actual error does not exceed (beyond the resolution).
#[test]
fn each_setting_is_measured_against_the_converged_reference() {
    let mut a = app("A");
    let t = trade(&mut a);
    let r = t.reference.unwrap().unwrap();
    assert_eq!(r.outcome, Outcome::Stuck);
    let res = t.resolution().unwrap();
    assert!(res < 1e-8, "resolution {res}");
    // The reference is the bench's and its own run: dp54 at 1e-13 to the stop.
    let mut run = Run::new(a.initial(), turntable::bench::reference()).unwrap();
    let (_, s) = run.finish(TRADE_TAU).unwrap();
    assert_eq!((r.tau, r.q), (s.tau, s.q()));
    let rk2 = |dt| err(&t, Method::Rk2.with(dt));
    assert!(
        rk2(1e-2) > 1e3 * rk2(1e-4).max(res),
        "{} {}",
        rk2(1e-2),
        rk2(1e-4)
    );
    for m in [Method::Dp54, Method::Dop853] {
        let (loose, tight) = (err(&t, m.with(1e-3)), err(&t, m.with(1e-12)));
        assert!(tight.max(res) < 1e-3 * loose, "{m}: {loose} {tight}");
        assert!(
            tight < 10.0 * res,
            "{m} at 1e-12: {tight} (resolution {res})"
        );
    }
    let paper = end(&t, Method::Rk2Raw.with(1e-3));
    assert_eq!(paper.stated, None);
    for s in trade_schemes(&a.initial(), a.settings()) {
        let e = end(&t, s);
        assert!(e.rhs > 0, "{s:?}");
        if let Some(b) = e.stated.filter(|b| b.is_finite()) {
            assert!(
                err(&t, s) <= b.max(res) * 1.0001,
                "{s:?}: {} > {b}",
                err(&t, s)
            );
        }
    }
}

/// Nothing is drawn below the reference's resolution: such a point sits on its line and is
/// said "< res."; the chart's data are finite, on decades.
#[test]
fn no_error_is_drawn_or_said_below_the_resolution() {
    let mut a = app("A");
    let t = trade(&mut a);
    let floor = t.resolution().unwrap().log10();
    let c: Chart = turntable::plot::page::trade::chart(&a);
    let drawn: Vec<(f64, f64)> = c
        .series
        .iter()
        .filter(|s| s.name != "stated bound")
        .flat_map(|s| s.points.clone())
        .collect();
    assert!(drawn.len() >= 20, "{drawn:?}");
    for (x, y) in &drawn {
        assert!(x.is_finite() && y.is_finite(), "{x} {y}");
        assert!(*y >= floor - 1e-12, "{y} below {floor}");
    }
    // dp54 at 1e-13 is the reference itself: its error is 0, said as below the resolution.
    let below = Method::Dp54.with(1e-13);
    assert_eq!(err(&t, below), 0.0);
    let said = turntable::plot::page::trade::said(Some(&t), below, "picked");
    assert!(
        said.contains("< resolution") && !said.contains("error 0"),
        "{said}"
    );
}

/// The run's own setting is marked "now"; off the page's ladder (tol 10^-10.5 after `>`) it
/// is a point of its own, computed and marked too.
#[test]
fn the_runs_setting_is_marked_and_an_off_ladder_one_is_computed() {
    let mut a = app("A");
    let now = |a: &App| -> Vec<(f64, String)> {
        turntable::plot::page::trade::chart(a)
            .marks
            .iter()
            .filter_map(|m| match m {
                Mark::Point { x, label, .. } => Some((*x, label.clone())),
                _ => None,
            })
            .collect()
    };
    let t = trade(&mut a);
    let x = (end(&t, a.settings().scheme).rhs as f64).log10();
    assert_eq!(now(&a), [(x, "now".to_string())]);
    press(&mut a, '>');
    let s = a.settings().scheme;
    assert!((s.knob() - 10f64.powf(-10.5)).abs() < 1e-20, "{s:?}");
    assert_eq!(trade_schemes(&a.initial(), a.settings()).last(), Some(&s));
    let t = trade(&mut a);
    let x = (end(&t, s).rhs as f64).log10();
    assert_eq!(now(&a), [(x, "now".to_string())]);
    assert!(render(&mut a, 120, 40).contains("now dp54 tol=3e-11"));
}

/// `j`/`k` walk the points in the page's order, wrapping; Enter switches the run to the one
/// picked and the page stays, its mark of the run's setting moved there.
#[test]
fn j_and_k_pick_a_point_and_enter_runs_it() {
    let mut a = app("A");
    let all = trade_schemes(&a.initial(), a.settings());
    let at = all.iter().position(|s| *s == a.settings().scheme).unwrap();
    press(&mut a, 'j');
    press(&mut a, 'j');
    assert_eq!(a.view().trade_pick, Some(all[at + 2]));
    press(&mut a, 'k');
    assert_eq!(a.view().trade_pick, Some(all[at + 1]));
    let screen = render(&mut a, 120, 40);
    assert!(screen.contains("picked dp54 1e-11: "), "{screen}");
    a.handle_key(KeyEvent::new(KeyCode::Enter, KeyModifiers::NONE));
    assert_eq!(a.settings().scheme, all[at + 1]);
    assert_eq!(a.view().page, Page::WorkPrecision);
    assert_eq!(
        a.notice().as_deref(),
        Some("the run is now at dp54 tol=1e-11 (Tab to the turntable to watch it)")
    );
    // The first point back from the start wraps to the last: the paper's RK2 at dt 1e-4.
    while a.view().trade_pick != Some(all[0]) {
        press(&mut a, 'j');
    }
    press(&mut a, 'k');
    assert_eq!(a.view().trade_pick, Some(Method::Rk2Raw.with(1e-4)));
    a.handle_key(KeyEvent::new(KeyCode::Enter, KeyModifiers::NONE));
    assert_eq!(a.settings().scheme, Method::Rk2Raw.with(1e-4));
    // Elsewhere j says where it works.
    super::common::turn_to(&mut a, Page::Turntable);
    press(&mut a, 'j');
    assert!(
        a.notice()
            .as_deref()
            .unwrap()
            .contains("work-precision page")
    );
}

/// The page computes only while shown: asked for on the Tab that shows it, dropped by the Tab
/// that leaves before a frame computed it. Its job asks for no more after a switch of method:
/// the points are those of the release, not of the run's setting.
#[test]
fn it_computes_only_while_shown_and_a_switch_recomputes_nothing() {
    let mut s = turntable::session::Explorer::headless(
        App::new(Scene::preset("A").unwrap()),
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        false,
    );
    let tab = |s: &mut turntable::session::Explorer<_>| {
        s.key(KeyEvent::new(KeyCode::Tab, KeyModifiers::NONE))
    };
    for _ in 0..5 {
        tab(&mut s);
    }
    assert_eq!(s.app.view().page, Page::WorkPrecision);
    assert!(matches!(
        s.analysis.current(),
        Some((turntable::analysis::Job::Trade { .. }, _))
    ));
    tab(&mut s);
    s.draw().unwrap();
    assert_eq!(s.analysis.computed(), 0, "computed for a page not shown");
    for _ in 0..5 {
        tab(&mut s);
    }
    s.draw().unwrap();
    assert!(turntable::plot::page::trade::whole(&s.app));
    let before = s.analysis.computed();
    assert!(before > 20, "{before}");
    s.key(KeyEvent::new(KeyCode::Char('j'), KeyModifiers::NONE));
    s.key(KeyEvent::new(KeyCode::Enter, KeyModifiers::NONE));
    s.draw().unwrap();
    assert_eq!(s.analysis.computed(), before, "a switch recomputed");
    assert!(turntable::plot::page::trade::whole(&s.app));
}

/// Every size draws without a panic or a NaN, the words whole; μ = 0 says why there is no
/// trade; an escape (case C thrown 0.1 faster) is measured at its certificate.
#[test]
fn the_page_survives_every_size_and_says_what_it_measures() {
    let mut a = app("A");
    for (w, h) in [(120, 40), (80, 24), (60, 20), (40, 12), (1, 1)] {
        let s = render(&mut a, w, h);
        assert!(!s.contains("NaN"), "{w}x{h}:\n{s}");
        if w >= 80 {
            assert!(
                s.contains("now dp54") && s.contains("vs dp54 1e-13 (res"),
                "{s}"
            );
        }
        if w >= 120 {
            assert!(s.contains("error: when and where it stops"), "{s}");
        }
    }
    let mut d = app("C");
    turntable::app::update(&mut d, turntable::app::Action::V0(0.1));
    let t = trade(&mut d);
    assert_eq!(t.reference.unwrap().unwrap().outcome, Outcome::Escaped);
    assert!(render(&mut d, 120, 40).contains("when and where its escape is certified"));
    press(&mut a, 'F');
    assert!(a.initial().frictionless);
    let s = render(&mut a, 80, 24);
    assert!(s.contains("closed form"), "{s}");
    assert!(
        a.charts()
            .trade(&a.initial(), trade_base(a.settings()))
            .is_none()
    );
}

/// `E` on the page writes it as SVG (through `files`, a new file), whole once computed.
#[test]
fn e_exports_the_page() {
    let dir = std::env::temp_dir().join(format!("turntable-trade-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut a = app("A");
    a.tell_save_path(dir.join("scene.toml"));
    trade(&mut a);
    let export = turntable::app::update(&mut a, turntable::app::Action::ExportSvg);
    turntable::session::carry_out(&mut a, export);
    let path = dir.join("turntable-work-precision-1.svg");
    assert_eq!(
        a.notice().as_deref(),
        Some(format!("wrote this page to {}", path.display()).as_str())
    );
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(
        svg.contains("RHS evaluations") && svg.contains("dop853"),
        "{svg}"
    );
    let _ = std::fs::remove_dir_all(&dir);
    // The release's initial conditions are what the page ran.
    assert_eq!(
        a.initial(),
        Initial::velocity(0.5, std::f64::consts::PI, 1.0)
    );
}

/// Plain mode says the page in words once its runs are in, and each point picked.
#[test]
fn plain_mode_says_what_is_measured_and_each_pick() {
    let path = std::env::temp_dir().join(format!("turntable-wp-{}.keys", std::process::id()));
    std::fs::write(&path, "# replay: --scene A\nbacktab\nj\nenter\n").unwrap();
    let (code, out, err) = common::turntable(&["replay", "--plain", path.to_str().unwrap()]);
    let _ = std::fs::remove_file(&path);
    assert_eq!(code, 0, "{err}");
    for words in [
        "page: work-precision",
        "work-precision, error: when and where it stops, max(|Δτ|, |Δr|), against dp54 1e-13; resolution",
        "now dp54 tol=1e-10: error ",
        "picked (Enter runs it) dp54 tol=1e-11: error ",
        "the run is now at dp54 tol=1e-11",
    ] {
        assert!(out.contains(words), "{words} not in\n{out}");
    }
}

/// Names on the chart's last row land there, not on the row above over another's: on C at
/// 60×20 dop853's name stays whole beside the resolution's line (dp54's, with no room left,
/// is left out). The canvas rounded text at the bottom edge one row up.
#[test]
fn names_on_the_last_row_cover_no_other() {
    let mut a = app("C");
    let s = render(&mut a, 60, 20);
    assert!(s.contains("dop853") && !s.contains("ddp54"), "{s}");
}
