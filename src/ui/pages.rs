//! The analysis pages: the escape speed v_e(φ) (Fig. 5), the outcome map over (φ, v0), and the
//! rest radius against ξ0 (Fig. 6) with the paper's μ measurement (Eq. 22); the time plots are
//! in `time_plots`. Pure: they draw what the app holds and never compute a run.

use super::chart::{self, Chart, Mark, Series};
use crate::analysis::{PAPER_XI0, REST_POINTS, REST_XI0_MAX, Speeds};
use crate::app::pages::{Charts, Page, map_filled};
use crate::app::{App, CanvasGeom};
use crate::engine::model::turn_angle;
use crate::engine::units::Quantity;
use crate::engine::{Outcome, Release};
use crate::ui::panel::{num, speed};
use ratatui::Frame as TuiFrame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Wrap};
use std::f64::consts::{PI, TAU};
use unicode_width::UnicodeWidthStr;

/// Draws `app.page` in `area`; returns the plot's geometry where a click means a release.
pub fn render(f: &mut TuiFrame, area: Rect, app: &App) -> Option<CanvasGeom> {
    if let Some(gamma) = app.settings().stokes()
        && !app.initial().frictionless
        && matches!(
            app.page,
            Page::EscapeSpeed | Page::OutcomeMap | Page::RestRadius
        )
    {
        no_threshold(f, area, app, gamma);
        return None;
    }
    match app.page {
        Page::Turntable => None,
        Page::TimePlots => {
            super::time_plots::render(f, area, app);
            None
        }
        Page::EscapeSpeed => escape_speed(f, area, app),
        Page::OutcomeMap => outcome_map(f, area, app),
        Page::RestRadius => {
            rest_radius(f, area, app);
            None
        }
    }
}

/// Under Stokes drag (extends the paper) the threshold pages have nothing to draw: every release
/// leaves. Said instead, with the rate.
fn no_threshold(f: &mut TuiFrame, area: Rect, app: &App, gamma: f64) {
    let th = &app.theme;
    let block = super::titled(" Stokes drag: no threshold ".to_string(), th);
    let text = format!(
        "Under Stokes drag γ = {gamma} there is no escape speed, outcome map or rest radius: \
         every release leaves, exponentially at the rate Re λ+ = {:.6}, except those with \
         u0 = λ− q0 (the centre at rest, and one speed and direction at each radius), which \
         spiral into the centre.",
        crate::engine::stokes::growth_rate(gamma)
    );
    f.render_widget(
        Paragraph::new(text)
            .wrap(Wrap { trim: true })
            .style(Style::default().fg(th.foreground))
            .block(block),
        area,
    );
}

fn geom(plot: Rect, c: &Chart, page: Page, app: &App) -> CanvasGeom {
    CanvasGeom {
        area: plot,
        x: chart::sane(c.x),
        y: chart::sane(c.y),
        arrow_scale: 1.0,
        frame: app.view,
        turn: 0.0,
        page,
    }
}

/// v_e(φ) for the current ξ0 beside the paper's four, the release as a point, min and max.
fn escape_speed(f: &mut TuiFrame, area: Rect, app: &App) -> Option<CanvasGeom> {
    let th = &app.theme;
    let i = app.initial();
    let settings = crate::analysis::settings_for(app.settings());
    let charts = &app.charts;
    let mine = charts.curve(i.xi0, settings);
    let mut series = Vec::new();
    let mut marks = Vec::new();
    // Outside ξ = 1 a throw too slow escapes too: the sticking speeds are a window, and the
    // paper's v_e curves (Fig. 5, inside ξ = 1) are another quantity.
    let window = i.xi0 > 1.0;
    let others = if window { &[][..] } else { &PAPER_XI0[..] };
    for &xi0 in others.iter().filter(|x| **x != i.xi0) {
        if let Some(c) = charts.curve(xi0, settings) {
            let points = c.points();
            // Named at its peak rather than in the legend (their faint colours are all one),
            // which keeps the legend's room for the current curve.
            if let Some(&(x, y)) = points.iter().max_by(|a, b| a.1.total_cmp(&b.1)) {
                marks.push(Mark::Text {
                    x,
                    y,
                    label: xi0.to_string(),
                    color: th.muted,
                });
            }
            series.push(Series {
                name: String::new(),
                color: th.muted,
                points,
                joined: true,
            });
        }
    }
    let mut progress = String::new();
    let mut note = String::new();
    if let Some(c) = mine {
        let name = if window {
            format!("ξ0={}: sticks between", num(i.xi0, 3))
        } else {
            format!("ξ0={} (now)", num(i.xi0, 3))
        };
        series.push(Series {
            name,
            color: th.trail,
            points: c.points(),
            joined: true,
        });
        if window {
            series.push(Series {
                name: String::new(),
                color: th.trail,
                points: c.floor(),
                joined: true,
            });
        } else if let Some(((p0, v0), (p1, v1))) = extremes(c) {
            marks.push(Mark::Point {
                x: p0,
                y: v0,
                label: "min".into(),
                color: th.stuck,
            });
            marks.push(Mark::Point {
                x: p1,
                y: v1,
                label: "max".into(),
                color: th.escaped,
            });
        }
        note = curve_note(c, window);
        let done = c.ve.iter().filter(|v| v.is_some()).count();
        if done < c.ve.len() {
            progress = format!(", {done}/{} angles", c.ve.len());
        } else if !window && c.least.is_none() {
            progress = ", refining min…".into();
        }
    } else {
        progress = ", computing…".into();
    }
    let phi = turn_angle(i.phi);
    let (verdict, tone) = release_verdict(app, mine);
    let color = match tone {
        Some(Outcome::Escaped) => th.escaped,
        Some(Outcome::Stuck) => th.stuck,
        Some(Outcome::Running) => th.notice,
        None => th.particle,
    };
    let v_now = if i.release == Release::Velocity {
        i.v0
    } else {
        0.0
    };
    marks.push(Mark::Point {
        x: phi,
        y: v_now,
        label: format!("release{verdict}"),
        color,
    });
    let top = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .fold(v_now, f64::max);
    let title = if window {
        "sticking window (Fig. 3 D)"
    } else {
        "escape speed v_e(φ)"
    };
    let c = Chart {
        title: format!("{title}, ξ0 = {}{progress}", num(i.xi0, 3)),
        note,
        x_label: "φ".into(),
        y_label: chart::axis(
            if window { "v0" } else { "v_e" },
            Quantity::Speed,
            app.units,
        ),
        x: [0.0, TAU],
        y: [0.0, (1.1 * top).max(0.1)],
        series,
        marks,
    };
    let plot = chart::render(f, area, th, &c)?;
    Some(geom(plot, &c, Page::EscapeSpeed, app))
}

/// The least and greatest v_e of a curve as (φ, v_e): the least refined between the angles
/// once it arrives, the grid's until then.
fn extremes(c: &crate::app::pages::Curve) -> Option<((f64, f64), (f64, f64))> {
    let (least, most) = c.extremes()?;
    Some((c.least.flatten().unwrap_or(least), most))
}

/// The curve's note: the widest sticking window outside ξ = 1; inside, v_e's least (π to three
/// decimals once refined, to two from the grid, only good to its 0.03π) and greatest.
fn curve_note(c: &crate::app::pages::Curve, window: bool) -> String {
    if window {
        return widest(c);
    }
    let Some(((p0, v0), (p1, v1))) = extremes(c) else {
        return String::new();
    };
    let digits = if matches!(c.least, Some(Some(_))) {
        3
    } else {
        2
    };
    format!(
        "min {} at {}π, max {} at {}π",
        speed(v0),
        num(p0 / PI, digits),
        speed(v1),
        num(p1 / PI, 2)
    )
}

/// What the curve says of the release on screen, in words, and its tone: the outcome it
/// foretells (Running: too near an edge to tell), or None where it says nothing.
fn release_verdict(
    app: &App,
    mine: Option<&crate::app::pages::Curve>,
) -> (&'static str, Option<Outcome>) {
    let i = app.initial();
    let window = i.xi0 > 1.0;
    let judged = match i.release {
        Release::Velocity => mine.and_then(|c| judge(c, turn_angle(i.phi), i.v0)),
        _ => None,
    };
    let (esc, stk, near) = (
        Some(Outcome::Escaped),
        Some(Outcome::Stuck),
        Some(Outcome::Running),
    );
    match (judged, window) {
        (Some(Verdict::Above), false) => (" escapes (above v_e)", esc),
        (Some(Verdict::Inside), false) => (" sticks (below v_e)", stk),
        // Between the computed angles' values: the chart cannot tell; the run can.
        (Some(Verdict::Near), false) => (" ≈ v_e: Enter runs it to see", near),
        (Some(Verdict::Above), true) => (" escapes (above the window)", esc),
        (Some(Verdict::Below), _) => (" escapes (below the window)", esc),
        (Some(Verdict::Inside), true) => (" sticks (in the window)", stk),
        (Some(Verdict::Never), _) => (" escapes (no window at this φ)", esc),
        (Some(Verdict::Near), true) => (" ≈ window's edge: Enter runs it", near),
        (None, _) if i.release == Release::Velocity => ("", None),
        (None, _) => (" (release at rest: v0 = 0)", None),
    }
}

/// Whether `page` has numbers of its own to say in words ([`summary`]).
pub fn summarized(page: Page) -> bool {
    matches!(page, Page::EscapeSpeed | Page::RestRadius)
}

/// The analysis page on screen in words, for plain mode (a screen reader has no chart): what
/// the chart shows once its data are in, and what it says of the release on screen, from the
/// same pieces the chart is drawn from. None while they compute, and on the pages without a
/// summary of their own (the turntable's and the time plots' readouts are spoken already).
pub fn summary(app: &App) -> Option<(String, Option<String>)> {
    let settings = crate::analysis::settings_for(app.settings());
    let i = app.initial();
    if app.settings().stokes().is_some() {
        return None;
    }
    match app.page {
        Page::EscapeSpeed => {
            let window = i.xi0 > 1.0;
            // Inside ξ = 1, once the least v_e is refined too: said once, not grid then refined.
            let c = app
                .charts
                .curve(i.xi0, settings)
                .filter(|c| c.complete() && (window || c.least.is_some()))?;
            let what = if window {
                "sticking window"
            } else {
                "escape speed v_e(φ)"
            };
            let note = curve_note(c, window);
            let note = note.split(super::fit::OR).next().unwrap_or_default();
            let (verdict, _) = release_verdict(app, Some(c));
            Some((
                format!("{what} at ξ0 = {}: {note}", num(i.xi0, 3)),
                Some(format!(
                    "on the chart the release{}",
                    if verdict.is_empty() {
                        " is not judged"
                    } else {
                        verdict
                    }
                )),
            ))
        }
        Page::RestRadius => {
            let rest = app
                .charts
                .rest
                .as_ref()
                .filter(|r| r.settings == settings)?;
            let c = rest.critical??;
            Some((
                format!(
                    "rest radius (Fig. 6): released at rest in the lab, it stays on the table up to ξ0c = {}",
                    num(c, 6)
                ),
                None,
            ))
        }
        _ => None,
    }
}

/// The widest sticking window of a curve outside ξ = 1, in words.
fn widest(c: &crate::app::pages::Curve) -> String {
    let n = c.ve.len();
    let best = (0..n)
        .filter_map(|k| match c.ve[k]? {
            Speeds::Stick { lo, hi } => Some((crate::analysis::angle(k, n), lo, hi)),
            _ => None,
        })
        .max_by(|a, b| (a.2 - a.1).total_cmp(&(b.2 - b.1)));
    match best {
        Some((p, lo, hi)) => {
            let (lo, hi, p) = (speed(lo), speed(hi), num(p / PI, 2));
            super::fit::alternatives(&[
                format!("widest window: sticks for v0 {lo}–{hi}, at φ = {p}π"),
                format!("widest: v0 {lo}–{hi} at φ = {p}π"),
                format!("widest: v0 {lo}–{hi}"),
                format!("v0 {lo}–{hi}"),
            ])
        }
        None if c.complete() => "escapes at every speed and angle".into(),
        None => String::new(),
    }
}

/// How a release at (φ, v0) ends, read off the curve.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Verdict {
    /// Below the window (outside ξ = 1): escapes.
    Below,
    /// Sticks.
    Inside,
    /// Above v_e or the window: escapes.
    Above,
    /// No speed sticks at this angle.
    Never,
    /// Too close to an edge for the chart to tell.
    Near,
}

/// The verdict at φ from the curve: at a computed angle its own window, between two the span
/// of their edges (v_e is monotone between neighbours but at its extremes, where it is flat),
/// each widened by its bracket's half-width. `None` until both neighbours are known.
fn judge(c: &crate::app::pages::Curve, phi: f64, v0: f64) -> Option<Verdict> {
    let n = c.ve.len();
    let x = phi / TAU * n as f64;
    let on_grid = (x - x.round()).abs() < 1e-9;
    let (a, b) = if on_grid {
        let k = x.round() as usize % n;
        (c.ve[k]?, c.ve[k]?)
    } else {
        let k = x.floor() as usize % n;
        (c.ve[k]?, c.ve[(k + 1) % n]?)
    };
    let pad = 0.5 * crate::analysis::CURVE_VTOL;
    match (a, b) {
        (Speeds::Escapes, Speeds::Escapes) => Some(Verdict::Never),
        (Speeds::Stick { lo: l1, hi: h1 }, Speeds::Stick { lo: l2, hi: h2 }) => {
            // A floor of 0 (inside ξ = 1) is exact: no speed is below it.
            let lo = |x: f64| if x > 0.0 { x + pad } else { 0.0 };
            Some(if v0 > h1.max(h2) + pad {
                Verdict::Above
            } else if l1.min(l2) > 0.0 && v0 < l1.min(l2) - pad {
                Verdict::Below
            } else if v0 >= lo(l1.max(l2)) && v0 < h1.min(h2) - pad {
                Verdict::Inside
            } else {
                Verdict::Near
            })
        }
        (Speeds::Unknown, _) | (_, Speeds::Unknown) => None,
        _ => Some(Verdict::Near),
    }
}

/// Stuck or escaped over (φ, v0), stuck cells shaded by their rest radius, the v_e curve on it.
fn outcome_map(f: &mut TuiFrame, area: Rect, app: &App) -> Option<CanvasGeom> {
    let th = &app.theme;
    let i = app.initial();
    let settings = crate::analysis::settings_for(app.settings());
    let map = app.charts.map.as_ref().filter(|m| match m.job {
        crate::analysis::Job::Map { xi0, release, .. } => {
            xi0 == i.xi0 && release == i.release && m.settings == settings
        }
        _ => false,
    });
    let v0_max = match map.map(|m| m.job) {
        Some(crate::analysis::Job::Map { v0_max, .. }) => v0_max,
        _ => app
            .charts
            .curve(i.xi0, settings)
            .map_or(1.0, |c| Charts::map_v0_max(c, i.release, i.xi0)),
    };
    let progress = match map {
        Some(m) => {
            let (done, all) = map_filled(m);
            if done < all {
                format!(", {done}/{all} cells")
            } else {
                String::new()
            }
        }
        None => ", computing…".into(),
    };
    let c = map_chart(app, v0_max, progress);
    // The cells first, then the chart's braille over them.
    let plot = chart::plot_area(area, &c)?;
    if let Some(m) = map
        && let crate::analysis::Job::Map {
            size: (n, rows), ..
        } = m.job
    {
        let buf = f.buffer_mut();
        for cy in 0..plot.height {
            for cx in 0..plot.width {
                let fx = (f64::from(cx) + 0.5) / f64::from(plot.width);
                let fy = 1.0 - (f64::from(cy) + 0.5) / f64::from(plot.height);
                let ci = ((fx * n as f64) as usize).min(n - 1);
                let cj = ((fy * rows as f64) as usize).min(rows - 1);
                let Some(Some(cell)) = m.cells.get(cj * n + ci) else {
                    continue;
                };
                let (ch, color) = match (cell.outcome, cell.rest) {
                    (Outcome::Stuck, Some((xi, _))) => (
                        match xi {
                            x if x < 0.25 => '·',
                            x if x < 0.5 => ':',
                            x if x < 0.75 => '▒',
                            _ => '▓',
                        },
                        th.stuck,
                    ),
                    (Outcome::Escaped, _) => (' ', th.escaped),
                    _ => ('?', th.muted),
                };
                if let Some(c) = buf.cell_mut((plot.x + cx, plot.y + cy)) {
                    c.set_char(ch).set_fg(color);
                }
            }
        }
    }
    let plot = chart::render(f, area, th, &c)?;
    Some(geom(plot, &c, Page::OutcomeMap, app))
}

/// The outcome map's chart (without its cells) for speeds up to `v0_max`.
fn map_chart(app: &App, v0_max: f64, progress: String) -> Chart {
    let th = &app.theme;
    let i = app.initial();
    let settings = crate::analysis::settings_for(app.settings());
    let frame_word = if i.release == Release::LabRest {
        "lab"
    } else {
        "table"
    };
    let mut series = Vec::new();
    if i.release != Release::LabRest
        && let Some(c) = app.charts.curve(i.xi0, settings)
    {
        let window = i.xi0 > 1.0;
        series.push(Series {
            name: if window { "sticking window" } else { "v_e(φ)" }.into(),
            color: th.accent,
            points: c.points(),
            joined: true,
        });
        if window {
            series.push(Series {
                name: String::new(),
                color: th.accent,
                points: c.floor(),
                joined: true,
            });
        }
    }
    let (phi, v0) = match i.release {
        Release::Velocity => (turn_angle(i.phi), i.v0),
        _ => (0.0, 0.0),
    };
    Chart {
        title: format!(
            "outcome map, ξ0 = {}, {} release{progress}",
            num(i.xi0, 3),
            i.release
        ),
        note: String::new(),
        x_label: format!("φ ({frame_word} frame)  blank: escapes  ·:▒▓ stuck at ξ <¼ <½ <¾ ≤1"),
        y_label: chart::axis("v0", Quantity::Speed, app.units),
        x: [0.0, TAU],
        y: [0.0, v0_max],
        series,
        marks: vec![Mark::Point {
            x: phi,
            y: v0,
            label: "release".into(),
            color: th.particle,
        }],
    }
}

/// The outcome map's grid at the app's terminal size for speeds up to `v0_max`: one cell a
/// character of the plot the page draws (the same layout and chart) up to
/// [`crate::analysis::MAP_CELLS`], none when no plot fits.
pub fn map_grid(app: &App, v0_max: f64) -> Option<(usize, usize)> {
    let (w, h) = app.screen();
    let canvas = super::layout::regions(w, h)?.canvas;
    let plot = chart::plot_area(canvas, &map_chart(app, v0_max, String::new()))?;
    Some(crate::analysis::map_grid_for(
        usize::from(plot.width),
        usize::from(plot.height),
    ))
}

/// Fig. 6: where a particle released at rest in the lab comes to rest, against ξ0, with ξ0c;
/// beside it Eq. 22, μ = Ω² r0c / (g ξ0c), from an Ω and r0c the user enters.
fn rest_radius(f: &mut TuiFrame, area: Rect, app: &App) {
    let th = &app.theme;
    let settings = crate::analysis::settings_for(app.settings());
    let rest = app.charts.rest.as_ref().filter(|r| r.settings == settings);
    let [top, bottom] = Layout::vertical([Constraint::Min(6), Constraint::Length(5)]).areas(area);
    let mut points = Vec::new();
    let mut escaped = Vec::new();
    let mut marks = Vec::new();
    let mut progress = ", computing…".to_string();
    let xi0c = rest.and_then(|r| r.critical.flatten());
    if let Some(r) = rest {
        for (k, v) in r.xi.iter().enumerate() {
            let xi0 = REST_XI0_MAX * k as f64 / (REST_POINTS - 1) as f64;
            match v {
                Some(Some(xi)) => points.push((xi0, *xi)),
                Some(None) => escaped.push((xi0, 1.0)),
                None => {}
            }
        }
        let done = r.xi.iter().filter(|v| v.is_some()).count();
        progress = if done < r.xi.len() || r.critical.is_none() {
            format!(", {done}/{} radii", r.xi.len())
        } else {
            String::new()
        };
        if let Some(c) = xi0c {
            marks.push(Mark::VLine {
                x: c,
                label: format!("ξ0c={}", num(c, 4)),
                color: th.escaped,
            });
        }
    }
    marks.push(Mark::VLine {
        x: app.initial().xi0.min(REST_XI0_MAX),
        label: "now".into(),
        color: th.particle,
    });
    let c = Chart {
        title: super::fit::alternatives(&[
            format!("rest radius (Fig. 6): at rest in the lab at ξ0{progress}"),
            format!("rest radius (Fig. 6){progress}"),
            "rest radius".to_string(),
        ]),
        note: xi0c.map_or(String::new(), |c| format!("ξ0c = {}", num(c, 6))),
        x_label: chart::axis("ξ0", Quantity::Length, app.units),
        y_label: chart::axis("final ξ", Quantity::Length, app.units),
        x: [0.0, REST_XI0_MAX],
        y: [0.0, 1.05],
        series: vec![
            Series {
                name: "stuck".into(),
                color: th.trail,
                points,
                joined: false,
            },
            Series {
                name: "escapes (drawn at 1)".into(),
                color: th.escaped,
                points: escaped,
                joined: false,
            },
        ],
        marks,
    };
    chart::render(f, top, th, &c);
    // With SI units on, the table's Ω and g (o/O turn the table).
    let (omega, g) = app
        .units
        .map_or((app.mu_probe.0, crate::engine::units::G_DEFAULT), |u| {
            (u.omega(), u.g)
        });
    let r0c = app.mu_probe.1;
    let mu = xi0c.map(|c| omega * omega * r0c / (g * c));
    let (accent, muted) = (
        Style::default().fg(th.accent),
        Style::default().fg(th.muted),
    );
    // Most telling first; each whole on a line of its own or beside others, never wrapped
    // inside (a narrow box keeps μ, Ω and r0c, and drops the rest whole).
    let fields = [
        (
            match mu {
                Some(mu) => format!("μ = {}", num(mu, 4)),
                None => "μ = … (ξ0c still computing)".into(),
            },
            accent,
        ),
        (
            format!(
                "Ω = {} rad/s ({} rpm{})",
                num(omega, 3),
                num(omega * 60.0 / TAU, 1),
                if app.units.is_some() {
                    ", the table's"
                } else {
                    ""
                }
            ),
            Style::default(),
        ),
        (format!("r0c = {} m", num(r0c, 4)), Style::default()),
        ("Eq. 22: μ = Ω² r0c / (g ξ0c)".to_string(), muted),
        (format!("g = {g} m/s²"), muted),
        ("o/O: Ω ±0.1   d/D: r0c ±1 mm".to_string(), muted),
    ];
    let width = usize::from(bottom.width.saturating_sub(2));
    let mut lines: Vec<Line> = Vec::new();
    let mut line: Vec<Span> = Vec::new();
    let mut used = 0;
    for (text, style) in fields {
        let text = super::fit::fit(&text, "\0", width);
        if text.is_empty() {
            continue;
        }
        if used > 0 && used + 3 + text.width() > width {
            lines.push(Line::from(std::mem::take(&mut line)));
            used = 0;
        }
        if used > 0 {
            line.push(Span::raw("   "));
            used += 3;
        }
        used += text.width();
        line.push(Span::styled(text, style));
    }
    lines.push(Line::from(line));
    f.render_widget(
        Paragraph::new(lines).block(super::titled(" measure μ ".into(), th)),
        bottom,
    );
}
