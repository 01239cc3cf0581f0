//! The rest radius page: Fig. 6, where a particle released at rest in the lab comes to rest,
//! and the paper's μ measurement (Eq. 22) beside it.

use crate::app::App;
use crate::present::num;
use crate::theme::Theme;
use crate::ui::chart;
use ratatui::Frame as TuiFrame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use std::f64::consts::TAU;
use unicode_width::UnicodeWidthStr;

/// Fig. 6: where a particle released at rest in the lab comes to rest, against ξ0, with ξ0c;
/// beside it Eq. 22, μ = Ω² r0c / (g ξ0c), from an Ω and r0c the user enters.
pub(super) fn rest_radius(f: &mut TuiFrame, area: Rect, app: &App, th: &Theme) {
    let [top, bottom] = Layout::vertical([Constraint::Min(6), Constraint::Length(5)]).areas(area);
    let xi0c = crate::plot::page::rest::shown(app).and_then(|r| r.critical.flatten());
    chart::render(f, top, th, &crate::plot::page::rest::chart(app));
    measure_mu(f, bottom, app, th, xi0c);
}

/// Eq. 22, μ = Ω² r0c / (g ξ0c), from the Ω and r0c the user enters and ξ0c once computed.
fn measure_mu(f: &mut TuiFrame, bottom: Rect, app: &App, th: &Theme, xi0c: Option<f64>) {
    // With SI units on, the table's Ω and g (o/O turn the table).
    let (omega, g) = app
        .units()
        .map_or((app.mu_probe().0, crate::engine::units::G_DEFAULT), |u| {
            (u.omega(), u.g)
        });
    let r0c = app.mu_probe().1;
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
                Some(mu) => format!("μ_k = {}", num(mu, 4)),
                None => "μ_k = … (ξ0c still computing)".into(),
            },
            accent,
        ),
        (
            format!(
                "Ω = {} rad/s ({} rpm{})",
                num(omega, 3),
                num(omega * 60.0 / TAU, 1),
                if app.units().is_some() {
                    ", the table's"
                } else {
                    ""
                }
            ),
            Style::default(),
        ),
        (format!("r0c = {} m", num(r0c, 4)), Style::default()),
        ("Eq. 22: μ_k = Ω² r0c / (g ξ0c)".to_string(), muted),
        // The paper's "subtly different concept": a slide that stops against a coin that
        // starts to slide.
        ("a spin-up (7) measures μ_s".to_string(), muted),
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
