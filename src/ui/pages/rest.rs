//! The rest radius page: Fig. 6, where a particle released at rest in the lab comes to rest,
//! and the paper's μ measurement (Eq. 22) beside it.

use crate::analysis::{REST_POINTS, REST_XI0_MAX};
use crate::app::App;
use crate::app::pages::Rest;
use crate::engine::units::Quantity;
use crate::ui::chart::{self, Chart, Mark, Series};
use crate::ui::panel::num;
use ratatui::Frame as TuiFrame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use std::f64::consts::TAU;
use unicode_width::UnicodeWidthStr;

/// Fig. 6: where a particle released at rest in the lab comes to rest, against ξ0, with ξ0c;
/// beside it Eq. 22, μ = Ω² r0c / (g ξ0c), from an Ω and r0c the user enters.
pub(super) fn rest_radius(f: &mut TuiFrame, area: Rect, app: &App) {
    let th = &app.theme;
    let settings = crate::analysis::settings_for(app.settings());
    let rest = app.charts.rest.as_ref().filter(|r| r.settings == settings);
    let [top, bottom] = Layout::vertical([Constraint::Min(6), Constraint::Length(5)]).areas(area);
    let xi0c = rest.and_then(|r| r.critical.flatten());
    chart::render(f, top, th, &rest_chart(app, rest, xi0c));
    measure_mu(f, bottom, app, xi0c);
}

/// Fig. 6's chart: the final ξ of each release at rest in the lab against its ξ0 (those that
/// escape drawn at 1), ξ0c and the ξ0 on screen marked.
fn rest_chart(app: &App, rest: Option<&Rest>, xi0c: Option<f64>) -> Chart {
    let th = &app.theme;
    let mut points = Vec::new();
    let mut escaped = Vec::new();
    let mut marks = Vec::new();
    let mut progress = ", computing…".to_string();
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
    Chart {
        title: crate::ui::fit::alternatives(&[
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
    }
}

/// Eq. 22, μ = Ω² r0c / (g ξ0c), from the Ω and r0c the user enters and ξ0c once computed.
fn measure_mu(f: &mut TuiFrame, bottom: Rect, app: &App, xi0c: Option<f64>) {
    let th = &app.theme;
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
        let text = crate::ui::fit::fit(&text, "\0", width);
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
        Paragraph::new(lines).block(crate::ui::titled(" measure μ ".into(), th)),
        bottom,
    );
}
