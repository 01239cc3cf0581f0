//! The analysis pages (issue 10): Tab order and titles, and the data each page shows checked
//! against the engine's solvers, not only that a chart renders.

use crate::common;
use common::render;
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use std::f64::consts::TAU;
use turntable::analysis::{self, CURVE_VTOL, PAPER_XI0, map_cell, settings_for};
use turntable::app::App;
use turntable::app::pages::Page;
use turntable::app::testing::Testing as _;
use turntable::engine::solve::{critical_radius, escape_speed};
use turntable::engine::{Outcome, Release, Settings};
use turntable::scene::Scene;
use turntable::theme::Theme;

fn app(scene: &str) -> App {
    App::new(Scene::preset(scene).unwrap())
}

fn press(app: &mut App, code: KeyCode) {
    app.handle_key(KeyEvent::new(code, KeyModifiers::NONE));
}

#[test]
fn tab_cycles_the_pages_and_each_title_names_its_page() {
    let mut a = app("C");
    assert!(render(&mut a, 100, 30).contains("lab frame"));
    for (page, words) in [
        (Page::TimePlots, "time plots"),
        (Page::EscapeSpeed, "escape speed"),
        (Page::OutcomeMap, "outcome map"),
        (Page::RestRadius, "rest radius"),
        (Page::WorkPrecision, "work-precision"),
        (Page::Turntable, "lab frame"),
    ] {
        press(&mut a, KeyCode::Tab);
        assert_eq!(a.view().page, page);
        let screen = render(&mut a, 100, 30);
        assert!(screen.contains(words), "{words}:\n{screen}");
        assert!(!screen.contains("NaN"), "{screen}");
    }
    press(&mut a, KeyCode::BackTab);
    assert_eq!(a.view().page, Page::WorkPrecision);
    // As crossterm reports Shift-Tab: BackTab with Shift.
    a.handle_key(KeyEvent::new(KeyCode::BackTab, KeyModifiers::SHIFT));
    assert_eq!(a.view().page, Page::RestRadius);
}

#[test]
fn nothing_is_computed_for_a_page_not_on_screen() {
    let mut s = turntable::session::Explorer::headless(
        app("C"),
        turntable::theme::Theme::builtin("dark").unwrap(),
        80,
        24,
        false,
    );
    s.tick();
    assert_eq!(s.analysis.current(), None);
    let c = &s.app.charts();
    assert!(c.curves.is_empty() && c.map.is_none() && c.rest.is_none());
    s.key(KeyEvent::new(KeyCode::Tab, KeyModifiers::NONE)); // time plots: from the run itself
    assert_eq!(s.analysis.current(), None);
}

#[test]
fn the_escape_speed_page_holds_the_solver_s_curves() {
    let mut a = app("C");
    crate::common::turn_to(&mut a, Page::EscapeSpeed);
    common::sync(&mut a);
    let s = settings_for(a.settings());
    for xi0 in std::iter::once(0.5).chain(PAPER_XI0) {
        let c = a.charts().curve(xi0, s).expect("curve");
        assert!(c.complete(), "{xi0}");
    }
    let c = a.charts().curve(0.5, s).unwrap().clone();
    // Each value is the middle of a certified bracket of width ≤ vtol around v_e (its runs at
    // dp54 tol vtol/1000, see `curve_settings`): within vtol/2 of a converged v_e.
    for i in [0, 5, 23, 40, 71] {
        let phi = analysis::angle(i, c.ve.len());
        let v = escape_speed(0.5, phi, Settings::dp54(1e-12), 1e-10)
            .unwrap()
            .value;
        let got = c.ve[i].unwrap().hi().unwrap();
        assert!(
            (got - v).abs() <= 0.5 * CURVE_VTOL + 1e-10,
            "φ {phi}: {got} vs {v}"
        );
    }
    let ((_, vmin), (pmax, vmax)) = c.extremes().unwrap();
    assert!(c.points().iter().all(|p| p.1 >= vmin && p.1 <= vmax));
    // Fig. 5's minimum is refined between the angles (issue 18 item 10): the engine's own
    // search at a tighter tolerance agrees to the page's third decimal in π.
    let (pmin, vleast) = c.least.expect("refined").expect("found");
    let (phi, v) =
        crate::common::easiest_angle(0.5, 72, Settings::dp54(1e-12), 1e-10, 1e-5).unwrap();
    assert!((pmin - phi).abs() < 1e-3, "{pmin} vs {phi}");
    assert!(
        (vleast - v).abs() < 1e-7 && vleast <= vmin,
        "{vleast} vs {v}, grid {vmin}"
    );
    let screen = render(&mut a, 100, 30);
    let label =
        |v: String, p: f64, digits| format!("{v} at {}", turntable::present::angle_to(p, digits));
    // The least refined to 1e-8, the greatest a grid point's, known to the curve's 1e-4.
    let note = format!(
        "min {}, max {}",
        label(turntable::present::speed(vleast), pmin, 3),
        label(turntable::present::curve_speed(vmax), pmax, 2)
    );
    assert!(screen.contains(&note), "{note}\n{screen}");
    // C's v0 = 0.6078 at φ = 0 is below v_e(0) there: the page says it sticks.
    assert!(c.ve[0].unwrap().hi().unwrap() > a.initial().v0);
    assert!(screen.contains("release sticks (below v_e)"), "{screen}");
}

#[test]
fn the_outcome_map_agrees_with_the_escape_speeds() {
    let mut a = app("C");
    crate::common::turn_to(&mut a, Page::OutcomeMap);
    common::sync(&mut a);
    let s = settings_for(a.settings());
    let curve = a.charts().curve(0.5, s).unwrap().clone();
    let map = a.charts().map.clone().expect("map");
    let turntable::analysis::Job::Map {
        v0_max,
        size: (n, m),
        ..
    } = map.job
    else {
        panic!("{:?}", map.job)
    };
    // One cell a character of the plot at 80×24 (the app's size until told otherwise).
    assert_eq!((n, m), (44, 16));
    let c = curve.ve.len();
    let (mut stuck, mut escaped) = (0, 0);
    for j in 0..m {
        for i in 0..n {
            let cell = map.cells[j * n + i].expect("filled");
            let (phi, v0) = map_cell(j * n + i, (n, m), v0_max);
            assert!((phi - analysis::angle(i, n) - 0.5 * TAU / n as f64).abs() < 1e-12);
            // v_e at the cell's angle lies between the curve's neighbours there.
            let k = (phi / TAU * c as f64) as usize;
            let (a, b) = (curve.ve[k], curve.ve[(k + 1) % c]);
            let (a, b) = (a.unwrap().hi().unwrap(), b.unwrap().hi().unwrap());
            let (ve_lo, ve_hi) = (a.min(b), a.max(b));
            if v0 < ve_lo - 1e-3 {
                assert_eq!(cell.outcome, Outcome::Stuck, "φ_{i} v0 {v0} < {ve_lo}");
                let (xi, _) = cell.rest.unwrap();
                assert!(xi <= 1.0);
                stuck += 1;
            } else if v0 > ve_hi + 1e-3 {
                assert_eq!(cell.outcome, Outcome::Escaped, "φ_{i} v0 {v0} > {ve_hi}");
                escaped += 1;
            }
        }
    }
    assert!(stuck > 200 && escaped > 200, "{stuck} {escaped}");
    assert!(v0_max > curve.extremes().unwrap().1.1);
    let screen = render(&mut a, 100, 30);
    assert!(screen.contains('▓') && screen.contains('·'), "{screen}");
}

#[test]
fn a_click_on_the_map_picks_that_release_and_enter_runs_it() {
    let mut a = app("C");
    crate::common::turn_to(&mut a, Page::OutcomeMap);
    common::sync(&mut a);
    render(&mut a, 100, 30);
    let g = a.geom_for_tests().expect("plot geometry");
    assert_eq!(g.page, Page::OutcomeMap);
    let (col, row) = (g.area.x + g.area.width / 4, g.area.y + g.area.height / 3);
    let want = g.to_world(col, row).unwrap();
    a.handle_mouse(MouseEvent {
        kind: MouseEventKind::Down(MouseButton::Left),
        column: col,
        row,
        modifiers: KeyModifiers::NONE,
    });
    assert!((a.initial().phi.rem_euclid(TAU) - want.x).abs() < 1e-9);
    assert!((a.initial().v0 - want.y).abs() < 1e-9);
    assert_eq!(a.initial().release, Release::Velocity);
    press(&mut a, KeyCode::Enter);
    assert_eq!(a.view().page, Page::Turntable);
    assert!(a.playing() && a.sim().now().tau == 0.0);
}

#[test]
fn the_rest_radius_page_has_fig6_and_reads_mu_from_eq22() {
    let mut a = app("C");
    crate::common::turn_to(&mut a, Page::RestRadius);
    common::sync(&mut a);
    let rest = a.charts().rest.clone().expect("rest");
    let c = rest.critical.unwrap().unwrap();
    let want = critical_radius(settings_for(Settings::default()), 1e-6)
        .unwrap()
        .value;
    assert!((c - want).abs() < 1e-6, "{c} {want}");
    // Below ξ0c every release at rest in the lab sticks, and further out the farther in;
    // above it every one escapes (Fig. 6).
    let xs: Vec<(f64, Option<f64>)> = rest
        .xi
        .iter()
        .enumerate()
        .map(|(k, v)| (1.5 * k as f64 / 100.0, v.unwrap()))
        .collect();
    for w in xs.windows(2) {
        if w[1].0 < c {
            assert!(w[1].1.unwrap() >= w[0].1.unwrap() - 1e-9, "{w:?}");
        }
    }
    assert!(xs.iter().filter(|x| x.0 > c + 1e-3).all(|x| x.1.is_none()));
    let screen = render(&mut a, 100, 30);
    let mu = 3.3f64 * 3.3 * 0.12 / (9.81 * c);
    assert!(
        screen.contains(&format!("μ_k = {}", turntable::present::num(mu, 4))),
        "{screen}"
    );
    press(&mut a, KeyCode::Char('o'));
    let mu2 = 3.4f64 * 3.4 * 0.12 / (9.81 * c);
    let screen = render(&mut a, 100, 30);
    assert!(screen.contains(&format!("μ_k = {}", turntable::present::num(mu2, 4))));
}

#[test]
fn the_time_plots_show_the_energy_identity() {
    let mut a = app("C");
    for _ in 0..60 {
        a.tick();
    }
    // The work tally (Gauss–Legendre on each step's dense output) against E − E(0) at every
    // point of the trail: dE/dτ = −|u| to the run's own error (trapezoids on the 0.025 grid
    // were off by up to 1.8e-4).
    let (path, work) = (a.sim().trail(), a.sim().trail_work());
    assert_eq!(path.len(), work.len());
    let e0 = path[0].energy();
    let worst = path
        .iter()
        .zip(work)
        .map(|(s, w)| (s.energy() - e0 - w).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-10, "{worst}");
    assert!(work.last().unwrap() < &-0.1);
    press(&mut a, KeyCode::Tab);
    let screen = render(&mut a, 100, 30);
    for words in ["ξ", "θ′", "|u|", "E − E(0)", "−∫|u|dτ", "stop"] {
        assert!(screen.contains(words), "{words}:\n{screen}");
    }
}

/// The work the energy plot shows at the stop is the work `run --trajectory` writes there:
/// one tally (`engine::work`) for both.
#[test]
fn the_screens_work_is_the_clis() {
    let mut a = app("C");
    for _ in 0..400 {
        a.tick();
    }
    let turntable::engine::Status::Stuck { tau, .. } = a.sim().status() else {
        panic!("C stops inside ξ = 1");
    };
    let (path, work) = (a.sim().trail(), a.sim().trail_work());
    let at = path.iter().position(|s| s.tau == tau).unwrap();
    let csv = std::env::temp_dir().join(format!("turntable-work-{}.csv", std::process::id()));
    let i = a.initial();
    let (code, _, err) = common::turntable(&[
        "run",
        "--xi0",
        &i.xi0.to_string(),
        "--phi",
        &i.phi.to_string(),
        "--v0",
        &i.v0.to_string(),
        "--trajectory",
        csv.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(code, 0, "{err}");
    let rows = std::fs::read_to_string(&csv).unwrap();
    std::fs::remove_file(&csv).unwrap();
    let last: Vec<f64> = rows
        .lines()
        .last()
        .unwrap()
        .split(',')
        .take(9)
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(last[0], tau);
    assert!(
        (last[8] - work[at]).abs() < 1e-12,
        "{} vs {}",
        last[8],
        work[at]
    );
}

#[test]
fn pages_survive_every_size() {
    let mut a = app("fig1");
    for page in [
        Page::TimePlots,
        Page::EscapeSpeed,
        Page::OutcomeMap,
        Page::RestRadius,
        Page::WorkPrecision,
    ] {
        crate::common::turn_to(&mut a, page);
        common::sync(&mut a);
        for (w, h) in [(40, 12), (60, 20), (80, 24), (200, 60), (1, 1)] {
            let s = render(&mut a, w, h);
            assert!(!s.contains("NaN"), "{page:?} {w}x{h}");
        }
    }
}

/// The map is computed at the plot's size once drawn (one character, one release), again after
/// a resize; and a job asked for again computes only the pieces still missing.
#[test]
fn the_map_fills_the_plot_and_a_return_computes_only_what_is_missing() {
    use turntable::analysis::{Analysis, Job, Piece};
    let mut a = app("C");
    crate::common::turn_to(&mut a, Page::OutcomeMap);
    common::sync(&mut a);
    render(&mut a, 90, 26);
    common::sync(&mut a);
    let size = |a: &App| match a.charts().map.as_ref().map(|m| m.job) {
        Some(Job::Map { size, .. }) => size,
        other => panic!("{other:?}"),
    };
    let plot = a.geom_for_tests().expect("drawn").area;
    assert_eq!(
        size(&a),
        (usize::from(plot.width), usize::from(plot.height))
    );
    render(&mut a, 120, 40);
    common::sync(&mut a);
    render(&mut a, 120, 40);
    let plot = a.geom_for_tests().unwrap().area;
    assert_eq!(
        size(&a),
        (usize::from(plot.width), usize::from(plot.height))
    );
    let map = a.charts().map.clone().unwrap();
    assert!(map.cells.iter().all(Option::is_some));
    // Two cells lost: those two are what is missing, and all a new request computes.
    let mut charts = a.charts().clone();
    let cells = &mut charts.map.as_mut().unwrap().cells;
    cells[3] = None;
    cells[17] = None;
    let s = settings_for(a.settings());
    assert_eq!(charts.missing(&map.job, s), vec![3, 17]);
    let mut an = Analysis::inline();
    let curve = a.charts().curve(0.5, s).map(|c| c.ve.clone());
    an.request(map.job, s, charts.missing(&map.job, s), curve);
    assert!(an.take().is_empty(), "inline, a request waits for compute");
    an.compute();
    let got = an.take();
    assert_eq!(got.len(), 2);
    for (p, k) in got.into_iter().zip([3, 17]) {
        assert_eq!(
            p,
            Piece::Cell {
                i: k,
                cell: map.cells[k].unwrap()
            }
        );
    }
}

/// Between two computed angles the chart knows v_e only to the range of its neighbours: a
/// release inside that range is not called either way.
#[test]
fn the_escape_page_does_not_guess_between_its_angles() {
    let mut a = app("C");
    crate::common::turn_to(&mut a, Page::EscapeSpeed);
    common::sync(&mut a);
    let s = settings_for(a.settings());
    let c = a.charts().curve(0.5, s).unwrap().clone();
    let n = c.ve.len();
    let (v1, v2) = (
        c.ve[1].unwrap().hi().unwrap(),
        c.ve[2].unwrap().hi().unwrap(),
    );
    a.explore().edit_initial(|i| i.phi = 1.5 * TAU / n as f64);
    for (v0, words) in [
        (0.5 * (v1 + v2), "release ≈ v_e: Enter runs it to see"),
        (v1.max(v2) + 1e-3, "release escapes (above v_e)"),
        (v1.min(v2) - 1e-3, "release sticks (below v_e)"),
    ] {
        a.explore().edit_initial(|i| i.v0 = v0);
        let screen = render(&mut a, 100, 30);
        assert!(screen.contains(words), "{v0}: {words}\n{screen}");
    }
}

/// Outside ξ = 1 a throw too slow escapes as well as one too fast (Fig. 3 D): the escape page
/// draws the sticking window's two edges, each a certified bracket of outcomes, judges the
/// release against it, and the outcome map's speeds cover it.
#[test]
fn outside_xi_1_the_pages_show_the_sticking_window() {
    let s = settings_for(Settings::default());
    let ends = |xi0: f64, phi: f64, v0: f64| {
        turntable::analysis::classify(turntable::engine::Initial::velocity(xi0, phi, v0), s)
            .unwrap()
            .outcome
    };
    let mut a = app("D");
    for xi0 in [1.1, 1.05, 1.3, 2.0] {
        a.explore().edit_initial(|i| i.xi0 = xi0);
        crate::common::turn_to(&mut a, Page::EscapeSpeed);
        common::sync(&mut a);
        let c = a.charts().curve(xi0, s).expect("curve").clone();
        assert!(c.complete(), "{xi0}");
        let windows: Vec<(usize, f64, f64)> = (0..c.ve.len())
            .filter_map(|k| match c.ve[k].unwrap() {
                analysis::Speeds::Stick { lo, hi } => Some((k, lo, hi)),
                _ => None,
            })
            .collect();
        // Inward throws only: about a quarter of the angles at most, and some at every ξ0.
        assert!(
            !windows.is_empty() && windows.len() < 24,
            "{xi0}: {windows:?}"
        );
        for &(k, lo, hi) in windows.iter().step_by(3) {
            let phi = analysis::angle(k, c.ve.len());
            assert!(lo > 0.0 && hi > lo + 0.05, "{xi0} φ {phi}: {lo} {hi}");
            let d = CURVE_VTOL;
            assert_eq!(
                ends(xi0, phi, lo - d),
                Outcome::Escaped,
                "{xi0} φ {phi} {lo}"
            );
            assert_eq!(ends(xi0, phi, lo + d), Outcome::Stuck, "{xi0} φ {phi} {lo}");
            assert_eq!(ends(xi0, phi, hi - d), Outcome::Stuck, "{xi0} φ {phi} {hi}");
            assert_eq!(
                ends(xi0, phi, hi + d),
                Outcome::Escaped,
                "{xi0} φ {phi} {hi}"
            );
        }
        let screen = render(&mut a, 100, 30);
        assert!(screen.contains("sticking window (Fig. 3 D)"), "{screen}");
        assert!(screen.contains("widest window: sticks for v0 "), "{screen}");
        assert!(
            !screen.contains("min 0.0000") && !screen.contains("(above v_e)"),
            "{screen}"
        );
        // The map's speeds reach past the window's top, and it has stuck cells.
        crate::common::turn_to(&mut a, Page::OutcomeMap);
        common::sync(&mut a);
        let top = windows.iter().map(|w| w.2).fold(0.0, f64::max);
        let map = a.charts().map.clone().expect("map");
        let analysis::Job::Map { v0_max, .. } = map.job else {
            panic!()
        };
        assert!(v0_max > top, "{xi0}: {v0_max} {top}");
        let stuck = map
            .cells
            .iter()
            .flatten()
            .filter(|c| c.outcome == Outcome::Stuck);
        assert!(stuck.count() > 5, "{xi0}");
    }
    // D itself: thrown at 1.3 at 1.2π from ξ0 = 1.1 it sticks (at ξ = 0.67495); slower than
    // the window's floor it escapes.
    let mut d = app("D");
    crate::common::turn_to(&mut d, Page::EscapeSpeed);
    let screen = render(&mut d, 100, 30);
    assert!(
        screen.contains("release sticks (in the window)"),
        "{screen}"
    );
    d.explore().edit_initial(|i| i.v0 = 0.3);
    let screen = render(&mut d, 100, 30);
    assert!(
        screen.contains("release escapes (below the window)"),
        "{screen}"
    );
    d.explore().edit_initial(|i| i.v0 = 3.0);
    let screen = render(&mut d, 100, 30);
    assert!(
        screen.contains("release escapes (above the window)"),
        "{screen}"
    );
    d.explore().edit_initial(|i| i.phi = 0.0);
    let screen = render(&mut d, 100, 30);
    assert!(
        screen.contains("release escapes (no window at this φ)"),
        "{screen}"
    );
}

/// One layout for drawing, the map's grid and the mouse (issue 18): at every size the map has
/// a cell per character of the plot drawn, and a click on a character picks that cell's
/// release; where no plot fits, no map is computed and a click does nothing.
#[test]
fn the_map_grid_is_the_drawn_plot_at_every_size() {
    use turntable::analysis::Job;
    for (w, h) in [(40, 12), (56, 30), (59, 24), (60, 20), (80, 24), (200, 60)] {
        let mut a = app("C");
        crate::common::turn_to(&mut a, Page::OutcomeMap);
        a.resize(w, h);
        render(&mut a, w, h);
        let job = a.charts().map.as_ref().map(|m| m.job);
        let Some(g) = a.geom_for_tests() else {
            assert_eq!((w, h), (40, 12), "no plot at {w}×{h}");
            assert_eq!(job, None, "a map no one sees at {w}×{h}");
            continue;
        };
        let Some(Job::Map { size, v0_max, .. }) = job else {
            panic!("{w}×{h}: {job:?}")
        };
        assert_eq!(
            size,
            (usize::from(g.area.width), usize::from(g.area.height)),
            "{w}×{h}"
        );
        assert!(
            a.charts()
                .map
                .as_ref()
                .unwrap()
                .cells
                .iter()
                .all(Option::is_some)
        );
        // A click on the plot's character (3, 2) picks the release of cell (3, rows − 3).
        let (n, m) = size;
        let k = (m - 3) * n + 3;
        let (phi, v0) = map_cell(k, size, v0_max);
        a.handle_mouse(MouseEvent {
            kind: MouseEventKind::Down(MouseButton::Left),
            column: g.area.x + 3,
            row: g.area.y + 2,
            modifiers: KeyModifiers::NONE,
        });
        assert!(
            (a.initial().phi.rem_euclid(TAU) - phi).abs() < 1e-6
                && (a.initial().v0 - v0).abs() < 1e-6,
            "{w}×{h}: {} {} vs {phi} {v0}",
            a.initial().phi,
            a.initial().v0
        );
    }
}

/// Narrow screens drop whole fields, never digits (issue 18): the escape page's ξ0 and its
/// min/max, the status hint at every width (the long one only where it fits, measured).
#[test]
fn no_number_is_cut_at_any_width() {
    let mut a = app("C");
    crate::common::turn_to(&mut a, Page::EscapeSpeed);
    common::sync(&mut a);
    let s = settings_for(a.settings());
    let c = a.charts().curve(0.5, s).unwrap();
    let ((_, _), (_, vmax)) = c.extremes().unwrap();
    let (_, vmin) = c.least.unwrap().unwrap();
    // The greatest is a grid point's, known to the curve's bracket: four decimals.
    let (min, max) = (
        turntable::present::speed(vmin),
        turntable::present::curve_speed(vmax),
    );
    let long = " ? help  Space pause  .,  step  [] speed  f frame  m method  c compare  a forces  1-7 presets  x/p/v edit  q quit";
    let short = " ? help  q quit  Space pause  ., step  f frame  m method  c compare  1-7 presets";
    for w in 40..=130u16 {
        let screen = render(&mut a, w, 20);
        let lines: Vec<&str> = screen.lines().collect();
        let title = lines[1];
        assert!(
            title.contains("ξ0 = 0.500") || !title.contains("ξ0 ="),
            "{w}: {title}"
        );
        let note = lines
            .iter()
            .rev()
            .find(|l| l.contains("min"))
            .copied()
            .unwrap_or("");
        assert!(
            note.is_empty() || note.contains(&format!("min {min} at")),
            "{w}: {note}"
        );
        assert!(
            !note.contains("max") || note.contains(&format!("max {max} at")),
            "{w}: {note}"
        );
        // The hint: whole hints of one of the two, ending where a hint ends.
        let hint = lines[19].trim_end();
        let whole = |full: &str| {
            full.starts_with(hint)
                && (full.len() == hint.len() || full[hint.len()..].starts_with("  "))
        };
        assert!(whole(long) || whole(short), "{w}: '{hint}'");
        assert_eq!(hint == long, usize::from(w) >= long.chars().count(), "{w}");
        assert!(hint.contains("q quit"), "{w}: {hint}");
    }
    // A notice too long for the line loses whole words.
    press(&mut a, KeyCode::Char('3'));
    let notice = render(&mut a, 60, 20)
        .lines()
        .nth(19)
        .unwrap()
        .trim_end()
        .to_string();
    // Whole clauses go, and what is left reads true (it read "escapes in the paper; a
    // converged run", the opposite of the whole).
    assert_eq!(notice, " preset C: Fig. 3 C: stops inside ξ = 1");
}

/// The time plots share one τ axis (τ = 0 in one column in every plot, whatever its tick
/// labels' width), plot θ as Figs. 1–2 do, and `t`/`T` fix the τ window (issue 18).
#[test]
fn the_time_plots_share_one_tau_axis_and_a_fixed_window() {
    let mut a = App::new(Scene::preset("fig2").unwrap());
    for _ in 0..60 {
        a.tick();
    }
    crate::common::turn_to(&mut a, Page::TimePlots);
    let screen = render(&mut a, 100, 34);
    // fig2 is certified to escape at τ = 0: its line's label starts one column right of τ = 0.
    let cols: Vec<usize> = screen
        .lines()
        .filter_map(|l| l.find("escape cert.").map(|b| l[..b].chars().count()))
        .collect();
    assert_eq!(cols.len(), 5, "{screen}");
    assert!(cols.iter().all(|c| *c == cols[0]), "{cols:?}\n{screen}");
    assert!(
        screen.contains("θ (rad) ━ run  ·· Eq. 20, friction dropped"),
        "{screen}"
    );
    // The approximation's window is marked on ξ alone: on the table Eq. 20's Θ′ drops the
    // friction term (6× the run's at ξ0 = 1.1), and |u| and E have none.
    assert_eq!(screen.matches("approx. valid").count(), 1, "{screen}");
    let ticks = |s: &str| s.lines().rev().nth(4).unwrap_or("").to_string();
    assert!(ticks(&screen).contains("2.5"), "{screen}");
    press(&mut a, KeyCode::Char('t'));
    press(&mut a, KeyCode::Char('t'));
    assert!((a.view().tau_window.unwrap() - 0.75).abs() < 1e-12);
    let narrow = render(&mut a, 100, 34);
    assert!(
        ticks(&narrow).contains("0.6") && !ticks(&narrow).contains("2.5"),
        "{narrow}"
    );
    press(&mut a, KeyCode::Char('T'));
    press(&mut a, KeyCode::Char('T'));
    assert_eq!(a.view().tau_window, None);
    assert_eq!(render(&mut a, 100, 34), screen);
}

/// A theme that sets a background sets it on every cell of every page, help open or not
/// (issue 18): chart interiors kept the terminal's own. The pages do not depend on the theme:
/// computed once, each is drawn in every theme.
#[test]
fn a_theme_s_background_covers_every_cell() {
    let themes = ["dark", "light", "high-contrast"].map(|t| (t, Theme::builtin(t).unwrap()));
    let mut a = App::new(Scene::preset("C").unwrap());
    for help in [false, true] {
        if a.view().help != help {
            turntable::app::update(&mut a, turntable::app::Action::ToggleHelp);
        }
        for page in Page::ORDER {
            crate::common::turn_to(&mut a, page);
            common::sync(&mut a);
            a.resize(80, 24);
            for (theme, th) in &themes {
                let mut t =
                    ratatui::Terminal::new(ratatui::backend::TestBackend::new(80, 24)).unwrap();
                t.draw(|f| {
                    turntable::ui::draw(f, &a, th);
                })
                .unwrap();
                let bad = t
                    .backend()
                    .buffer()
                    .content
                    .iter()
                    .filter(|c| c.bg != th.background);
                assert_eq!(bad.count(), 0, "{theme} {page:?} help {help}");
            }
        }
    }
}

/// Told apart without colour (issue 18): a release speed shows the decimals that tell C's
/// v0 from its escape speed, and the time plots' dotted series (the approximation, −∫|u|dτ)
/// are named with dots in their legend.
#[test]
fn speeds_and_legends_read_without_colour() {
    use turntable::present::speed;
    assert_eq!(speed(0.6078), "0.6078");
    assert_eq!(speed(1.3), "1.3000");
    assert_eq!(speed(0.6077971), "0.607797");
    assert_eq!(speed(f64::NAN), "—");
    let mut a = App::new(Scene::preset("fig2").unwrap());
    for _ in 0..20 {
        a.tick();
    }
    crate::common::turn_to(&mut a, Page::TimePlots);
    let screen = render(&mut a, 100, 34);
    for words in ["ξ ━ run  ·· Sec. III approx.", "━ E − E(0)  ·· −∫|u|dτ"] {
        assert!(screen.contains(words), "{words}\n{screen}");
    }
}

/// The lesson line under the picture is said whole at every width: one of its wordings, never
/// a long one cut after "dt =" (issue 18: text cut at 60×20). Every width from 40 to 120, with
/// and without the paper's run, at μ = 0 too.
#[test]
fn the_lesson_line_is_a_whole_sentence_at_every_width() {
    use turntable::present::OR;
    for keys in [
        &[][..],
        &[KeyCode::Char('c')][..],
        &[KeyCode::Char('F')][..],
        &[KeyCode::Char('c'), KeyCode::Char('3')][..],
    ] {
        let mut a = app("D");
        for k in keys {
            press(&mut a, *k);
        }
        a.tick();
        let line = turntable::ui::lesson_line(&a);
        let wordings: Vec<&str> = line.split(OR).map(str::trim).collect();
        assert!(wordings.len() >= 2, "{line:?}");
        for w in 40..=120u16 {
            let screen = render(&mut a, w, 24);
            let row = screen.lines().nth(22).unwrap().trim();
            assert!(
                wordings.contains(&row),
                "{w}: {row:?} is none of {wordings:?}"
            );
            if usize::from(w) > wordings[0].chars().count() {
                assert_eq!(row, wordings[0], "{w}");
            }
        }
    }
}

/// The paper's RK2 escape of case C, where a student sees it (issue 29 item 4): ξ = 1 drawn on
/// the ξ plot, zoomed on the stop so that 0.99717 is told from the rim, and the paper's run
/// crossing it and leaving through the top.
#[test]
fn the_xi_plot_zooms_on_a_stop_at_the_rim_beside_the_papers_escape() {
    let mut a = App::new(Scene::preset("C").unwrap());
    turntable::app::update(&mut a, turntable::app::Action::ToggleCompare);
    a.tell_speed(2.0);
    for _ in 0..300 {
        a.tick();
        a.catch_up();
    }
    let xi = &turntable::plot::page::time::panels(&a)[0];
    let rim = xi
        .series
        .iter()
        .find(|s| s.name == "ξ = 1 (R_max)")
        .unwrap();
    assert!(rim.points.iter().all(|p| p.1 == 1.0));
    let stop = 0.99717;
    // A stop 0.0028 inside the rim is a fifth of the plot's height below it.
    assert!(
        xi.y[0] < stop && xi.y[1] > 1.0 && xi.y[1] - xi.y[0] < 0.03,
        "{:?}",
        xi.y
    );
    assert!(xi.y_label.contains("zoom on the stop"), "{}", xi.y_label);
    let paper = xi.series.iter().find(|s| s.name == "paper RK2").unwrap();
    let top = paper.points.iter().map(|p| p.1).fold(0.0, f64::max);
    assert!(
        top > xi.y[1],
        "the paper's run leaves through the top: {top}"
    );
    // Without the paper's run beside it, the whole run is in view.
    turntable::app::update(&mut a, turntable::app::Action::ToggleCompare);
    let xi = &turntable::plot::page::time::panels(&a)[0];
    assert!(xi.y[0] <= 0.5 && xi.y[1] >= 1.0, "{:?}", xi.y);
}
