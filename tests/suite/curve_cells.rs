//! The escape-speed curve as the page computes it (brackets of `CURVE_VTOL`, from no nearby
//! curve and from the one a held key left at ξ0 − 0.01) against a tight curve, drawn: the same
//! terminal cells everywhere but beside a point whose tight value lies within the coarse
//! bracket of a braille dot's edge, and even there within a dot.

use ratatui::backend::TestBackend;
use turntable::analysis::{CURVE_VTOL, Job, Piece, Speeds, angle, piece_with, settings_for};
use turntable::engine::Settings;
use turntable::engine::par::par_map;
use turntable::engine::solve::{always, escape_speed};
use turntable::plot::{Chart, Ink, Series, Style};

/// The page's escape speeds at `xi0`, each started from `near`'s when given.
fn page_curve(xi0: f64, near: Option<&[Option<Speeds>]>) -> Vec<f64> {
    let s = settings_for(Settings::default());
    let ks: Vec<usize> = (0..turntable::analysis::CURVE_POINTS).collect();
    par_map(&ks, |&k| {
        match piece_with(&Job::Curve { xi0 }, k, s, near, &always) {
            Some(Piece::Escape {
                v: Speeds::Stick { hi, .. },
                ..
            }) => hi,
            p => panic!("ξ0 {xi0} angle {k}: {p:?}"),
        }
    })
}

/// The chart's cells with only `ve` drawn over [0, `top`], at 120×40 (at least as fine as the
/// page draws its curve at that size).
fn drawn(ve: &[f64], top: f64) -> Vec<String> {
    let n = ve.len();
    let chart = Chart {
        x: [0.0, std::f64::consts::TAU],
        y: [0.0, top],
        series: vec![Series {
            name: String::new(),
            points: (0..n).map(|k| (angle(k, n), ve[k])).collect(),
            style: Style::Line { dash: 0 },
            ink: Ink::Trail,
        }],
        ..Chart::default()
    };
    let theme = turntable::theme::Theme::builtin("dark").expect("dark");
    let mut t = ratatui::Terminal::new(TestBackend::new(120, 40)).expect("terminal");
    t.draw(|f| {
        turntable::ui::chart::render(f, f.area(), &theme, &chart);
    })
    .expect("drawn");
    let buffer = t.backend().buffer().clone();
    buffer
        .content()
        .iter()
        .map(|c| c.symbol().to_string())
        .collect()
}

#[test]
fn the_curve_drawn_is_the_tight_curve_cell_by_cell() {
    let area = ratatui::layout::Rect::new(0, 0, 120, 40);
    let mut near_edges = 0;
    for xi0 in [0.001, 0.2, 0.5, 0.8, 0.95] {
        let n = turntable::analysis::CURVE_POINTS;
        let phis: Vec<f64> = (0..n).map(|k| angle(k, n)).collect();
        // To 1e-7 at tol 1e-10: within 5e-8 of v_e to 1e-9 at 1e-12 on these 360 angles,
        // 1000× finer than the 5e-5 the page's speeds are held to (and a dot's edge with them).
        let tight = par_map(&phis, |&phi| {
            escape_speed(xi0, phi, Settings::dp54(1e-10), 1e-7)
                .expect("tight")
                .value
        });
        let held_from = if xi0 > 0.01 { xi0 - 0.01 } else { xi0 + 0.01 };
        let before: Vec<Option<Speeds>> = page_curve(held_from, None)
            .into_iter()
            .map(|hi| Some(Speeds::Stick { lo: 0.0, hi }))
            .collect();
        let top = 1.1 * tight.iter().copied().fold(0.0, f64::max);
        let chart = Chart {
            y: [0.0, top],
            ..Chart::default()
        };
        let plot = turntable::ui::chart::plot_area(area, &chart).expect("a plot");
        // A value's dot row, as a real number: the canvas truncates it.
        let dots = 4.0 * f64::from(plot.height) - 1.0;
        let row = |v: f64| (top - v) / top * dots;
        for (how, page) in [
            ("from no curve", page_curve(xi0, None)),
            ("from ξ0 − 0.01's", page_curve(xi0, Some(&before))),
        ] {
            let mut near = 0;
            for k in 0..n {
                let (got, want) = (page[k], tight[k]);
                // The bracket's half-width, and the threshold as its runs at 1e-6 place it
                // (2.4e-6 off at ξ0 = 0.95).
                assert!(
                    (got - want).abs() <= 0.5 * CURVE_VTOL + 1e-5,
                    "ξ0 {xi0} {how} φ {}: {got} against {want}",
                    phis[k]
                );
                // Within the bracket of an edge, the dot may be the next one, never farther.
                let (a, b) = (row(got), row(want));
                let edge =
                    (b - b.floor()).min(b.ceil() - b) <= (0.5 * CURVE_VTOL + 1e-5) / top * dots;
                assert!(
                    a.floor() == b.floor() || (edge && (a.floor() - b.floor()).abs() <= 1.0),
                    "ξ0 {xi0} {how} φ {}: dot row {a} against {b}",
                    phis[k]
                );
                near += usize::from(edge);
            }
            let cells = drawn(&page, top)
                .iter()
                .zip(drawn(&tight, top))
                .filter(|(a, b)| **a != *b)
                .count();
            // A point's dot moves at most the cells of the two segments that meet there.
            assert!(
                cells <= 4 * near,
                "ξ0 {xi0} {how}: {cells} cells differ, {near} points near an edge"
            );
            eprintln!(
                "ξ0 {xi0} {how}: {near} of {n} points near a dot's edge, {cells} cells differ (a dot {:.1e})",
                top / dots
            );
            near_edges += near;
        }
    }
    assert!(near_edges < 40, "{near_edges}");
}
