//! The time plots page: its panels (`plot::page::time`) stacked on one τ axis, as many as the
//! height holds.

use super::chart;
use crate::app::App;
use crate::theme::Theme;
use ratatui::Frame as TuiFrame;
use ratatui::layout::{Constraint, Layout, Rect};

/// The time plots: ξ, θ′ (Θ′ in the rotating view), |u| and the energy identity, aligned in τ
/// with the cursor at the τ on screen, the stop and the escape certificate marked, and the
/// paper's Sec. III approximations over their window for releases at rest.
pub fn render(f: &mut TuiFrame, area: Rect, app: &App, th: &Theme) {
    let title = crate::present::alternatives(&[
        "time plots: ξ, θ, θ′, |u|, energy against τ (t/T: τ window)",
        "time plots: ξ, θ, θ′, |u|, energy",
        "time plots",
    ]);
    let room = usize::from(area.width).saturating_sub(4);
    let block = super::titled(format!(" {} ", super::fit::fit(&title, "\0", room)), th);
    let inner = block.inner(area);
    f.render_widget(block, area);
    let mut charts = crate::plot::page::time::panels(app);
    // As many plots as fit (ξ first), each at least a legend line and three rows; the τ axis
    // under the last.
    let fit = ((inner.height.saturating_sub(2)) / 4).clamp(0, charts.len() as u16) as usize;
    if fit == 0 {
        return;
    }
    let rows = Layout::vertical(
        (0..fit)
            .map(|k| Constraint::Fill(if k + 1 == fit { 2 } else { 1 }))
            .collect::<Vec<_>>(),
    )
    .split(inner);
    charts.truncate(fit);
    // The τ axis's name under the last only.
    for c in charts.iter_mut().take(fit - 1) {
        c.x_label.clear();
    }
    // One τ axis: every plot's gutter as wide as the widest, so τ = 0 is one column.
    let gutter = charts
        .iter()
        .enumerate()
        .map(|(k, c)| chart::gutter(rows[k], c, k + 1 == fit))
        .max()
        .unwrap_or(0);
    for (k, c) in charts.iter().enumerate() {
        chart::render_bare(f, rows[k], th, c, k + 1 == fit, gutter);
    }
}
