//! The work–precision page: the chart (`plot::page::trade`) and under it the picked point and
//! the explorer's own setting in words, with the bound each stated beside its error.

use crate::app::App;
use crate::app::pages::trade_picked;
use crate::plot::page::trade::{chart, said, shown};
use crate::theme::Theme;
use ratatui::Frame as TuiFrame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

/// Draws the page in `area`: the chart, and a box of two lines (the picked point, the
/// explorer's setting) with what the keys do.
pub(super) fn work_precision(f: &mut TuiFrame, area: Rect, app: &App, th: &Theme) {
    if crate::engine::closed_form(&app.initial(), app.settings()) {
        closed_form(f, area, th);
        return;
    }
    let [top, bottom] = Layout::vertical([Constraint::Min(6), Constraint::Length(4)]).areas(area);
    super::super::chart::render(f, top, th, &chart(app));
    let (initial, settings) = (app.initial(), app.settings());
    let picked = trade_picked(app.view().trade_pick, &initial, settings);
    let t = shown(app);
    let width = usize::from(bottom.width.saturating_sub(2));
    let fit = |s: String| crate::ui::fit::fit(&s, ", ", width);
    let lines = if picked == settings.scheme {
        vec![
            Line::from(Span::styled(
                fit(said(t, picked, "now")),
                Style::default().fg(th.particle),
            )),
            Line::from(Span::styled(
                fit("j/k: pick another setting, Enter: run it, E: export".into()),
                Style::default().fg(th.muted),
            )),
        ]
    } else {
        vec![
            Line::from(Span::styled(
                fit(said(t, picked, "picked")),
                Style::default().fg(th.notice),
            )),
            Line::from(Span::styled(
                fit(said(t, settings.scheme, "now")),
                Style::default().fg(th.particle),
            )),
        ]
    };
    f.render_widget(
        Paragraph::new(lines).block(crate::ui::titled(" j/k pick · Enter run it ".into(), th)),
        bottom,
    );
}

/// μ = 0 and Stokes drag are run in closed form: every method gives the same exact run.
fn closed_form(f: &mut TuiFrame, area: Rect, th: &Theme) {
    let text = "This release is computed in closed form (μ = 0, or Stokes drag): every method \
                and tolerance gives the same exact run, so there is no trade of work against \
                error to show.";
    f.render_widget(
        Paragraph::new(text)
            .wrap(ratatui::widgets::Wrap { trim: true })
            .style(Style::default().fg(th.foreground))
            .block(crate::ui::titled(
                " work-precision: closed form ".into(),
                th,
            )),
        area,
    );
}
