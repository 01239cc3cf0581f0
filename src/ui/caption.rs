//! A lesson's caption: a box over the lower part of the picture (over the whole body on a
//! narrow screen, where the picture is short), its words wrapped between words and its lower
//! edge saying what the keys do now.

use super::fit::{fit, wrap};
use super::layout::Regions;
use crate::app::App;
use crate::theme::Theme;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Clear, Paragraph};

/// Where the caption goes and how many text rows it may take: beside a panel, over the
/// picture; above one, over the whole body.
pub fn area(r: &Regions) -> Rect {
    if r.canvas.width < r.body.width {
        r.canvas
    } else {
        r.body
    }
}

/// The caption's text rows, wrapped to its box, and the box; None without a caption or room.
fn placed(r: &Regions, app: &App) -> Option<(Vec<String>, Rect)> {
    let c = app.caption()?;
    let room = area(r);
    if room.width < 3 || room.height < 3 {
        return None;
    }
    let lines = wrap(
        &c.text,
        usize::from(room.width - 2),
        usize::from(room.height - 2),
    );
    let height = u16::try_from(lines.len())
        .unwrap_or(room.height)
        .saturating_add(2);
    let height = height.min(room.height);
    let at = Rect {
        y: room.y + room.height - height,
        height,
        ..room
    };
    Some((lines, at))
}

/// The picture's area with a caption shown: above the caption, so that the caption never
/// covers a chart's axes, its ticks or its lines (nor the table's lower part). Where less
/// than [`MIN_ROWS`] would be left, the caption goes over the picture as before.
pub fn picture(r: &Regions, app: &App) -> Rect {
    const MIN_ROWS: u16 = 6;
    let Some((_, at)) = placed(r, app) else {
        return r.canvas;
    };
    let rows = at.y.saturating_sub(r.canvas.y).min(r.canvas.height);
    if rows < MIN_ROWS {
        return r.canvas;
    }
    Rect {
        height: rows,
        ..r.canvas
    }
}

pub fn render(frame: &mut Frame, r: &Regions, app: &App, th: &Theme) {
    let Some(c) = app.caption() else { return };
    let Some((lines, at)) = placed(r, app) else {
        return;
    };
    let room = area(r);
    let inner = usize::from(room.width).saturating_sub(4);
    let mut block = super::titled(format!(" {} ", fit(&c.title, "\0", inner)), th)
        .border_style(Style::default().fg(th.accent));
    if let Some(p) = c.prompt {
        block = block.title_bottom(
            Line::from(Span::styled(
                // Whole clauses drop from the end ("y escapes · n stays"), never half a word.
                format!(" {} ", fit(p, " · ", inner)),
                Style::default().fg(th.notice),
            ))
            .right_aligned(),
        );
    }
    let text: Vec<Line> = lines.into_iter().map(Line::from).collect();
    frame.render_widget(Clear, at);
    frame.render_widget(
        Paragraph::new(text)
            .style(Style::default().bg(th.background).fg(th.foreground))
            .block(block),
        at,
    );
}
