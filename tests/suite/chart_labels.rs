//! A chart's labels never cover a curve or one another, at any size (issue 44 item 6): each
//! page's charts (the time plots, Fig. 5's escape speed, the outcome map, Fig. 6's rest radius)
//! over presets and times, drawn with and without their labels at random sizes; every cell a
//! label takes is empty in the drawing without labels, and every run of label cells is part of
//! one label (none overwrote another).

use super::common::sync;
use proptest::prelude::*;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use std::sync::OnceLock;
use turntable::app::App;
use turntable::app::pages::Page;
use turntable::plot::{Chart, Mark};
use turntable::scene::Scene;
use turntable::theme::Theme;

/// A page's chart, described from the app.
type MakeChart = fn(&App) -> Chart;

/// The charts of every page over presets and a few times (computed once: the analysis pages
/// take seconds).
fn charts() -> &'static [(String, Chart)] {
    static CHARTS: OnceLock<Vec<(String, Chart)>> = OnceLock::new();
    CHARTS.get_or_init(|| {
        let mut out = Vec::new();
        for preset in ["A", "C", "D", "fig2"] {
            let mut app = App::new(Scene::preset(preset).unwrap());
            // Each page's chart once its page has computed it (a page's pieces go when
            // another page is shown).
            let pages: [(&str, Page, MakeChart); 3] = [
                (
                    "escape",
                    Page::EscapeSpeed,
                    turntable::plot::page::escape::chart,
                ),
                ("map", Page::OutcomeMap, turntable::plot::page::map::chart),
                ("rest", Page::RestRadius, turntable::plot::page::rest::chart),
            ];
            for (n, page, chart) in pages {
                super::common::turn_to(&mut app, page);
                sync(&mut app);
                let c = chart(&app);
                assert!(!c.series.is_empty() || !c.marks.is_empty(), "{preset} {n}");
                out.push((format!("{preset} {n}"), c));
            }
            super::common::turn_to(&mut app, Page::TimePlots);
            let mut done = 0;
            for ticks in [40, 200, 400] {
                for _ in done..ticks {
                    if !app.playing() {
                        let _ = turntable::app::update(&mut app, turntable::app::Action::PlayPause);
                    }
                    app.tick();
                }
                done = ticks;
                for (k, c) in turntable::plot::page::time::panels(&app)
                    .into_iter()
                    .enumerate()
                {
                    out.push((format!("{preset} time {k} at {ticks}"), c));
                }
            }
        }
        out
    })
}

fn unlabelled(chart: &Chart) -> Chart {
    let mut c = chart.clone();
    for m in &mut c.marks {
        match m {
            Mark::VLine { label, .. }
            | Mark::Text { label, .. }
            | Mark::Point { label, .. }
            | Mark::Arrow { label, .. } => label.clear(),
        }
    }
    c
}

fn labels(chart: &Chart) -> Vec<String> {
    chart
        .marks
        .iter()
        .map(|m| match m {
            Mark::VLine { label, .. }
            | Mark::Text { label, .. }
            | Mark::Point { label, .. }
            | Mark::Arrow { label, .. } => label.clone(),
        })
        .filter(|l| !l.is_empty())
        .collect()
}

fn draw(chart: &Chart, w: u16, h: u16) -> Vec<Vec<String>> {
    let th = Theme::builtin("dark").unwrap();
    let mut t = Terminal::new(TestBackend::new(w, h)).unwrap();
    t.draw(|f| {
        turntable::ui::chart::render(f, f.area(), &th, chart);
    })
    .unwrap();
    let buf = t.backend().buffer();
    (0..h)
        .map(|y| (0..w).map(|x| buf[(x, y)].symbol().to_string()).collect())
        .collect()
}

/// Checks `chart` at `w` × `h`; returns how many label cells it saw.
fn check(name: &str, chart: &Chart, w: u16, h: u16) -> usize {
    let with = draw(chart, w, h);
    let without = draw(&unlabelled(chart), w, h);
    let texts = labels(chart);
    let mut cells = 0;
    for (y, (a, b)) in with.iter().zip(&without).enumerate() {
        let mut run = String::new();
        for x in 0..=a.len() {
            let differs = x < a.len() && a[x] != b[x];
            if differs {
                assert!(
                    matches!(b[x].as_str(), " " | "\u{2800}"),
                    "{name} at {w}×{h}: a label covers {:?} at row {y} col {x}\n{}",
                    b[x],
                    with.iter()
                        .map(|r| r.concat())
                        .collect::<Vec<_>>()
                        .join("\n")
                );
                run.push_str(&a[x]);
                cells += 1;
            } else if !run.is_empty() {
                assert!(
                    texts.iter().any(|t| t.contains(run.as_str())),
                    "{name} at {w}×{h}: {run:?} at row {y} is no label's: {texts:?}\n{}",
                    with.iter()
                        .map(|r| r.concat())
                        .collect::<Vec<_>>()
                        .join("\n")
                );
                run.clear();
            }
        }
    }
    cells
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn labels_never_cover_a_curve_or_one_another(k in 0usize..1000, w in 16u16..170, h in 6u16..56) {
        let all = charts();
        let (name, chart) = &all[k % all.len()];
        check(name, chart, w, h);
    }
}

/// Every chart at the sizes a class has (a projector, 80×24, 60×20 and their pages' areas):
/// and labels are drawn at all (the check is not passed by drawing none).
#[test]
fn labels_are_drawn_clear_at_a_classs_sizes() {
    let mut cells = 0;
    for (name, chart) in charts() {
        for (w, h) in [
            (118, 36),
            (90, 38),
            (50, 22),
            (30, 18),
            (48, 20),
            (28, 16),
            (88, 10),
            // A dot on a column's edge (π on 105 columns), which the canvas and the
            // placement once rounded apart.
            (109, 11),
        ] {
            cells += check(name, chart, w, h);
        }
    }
    assert!(cells > 1000, "{cells}");
}
