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

pub fn render(frame: &mut Frame, r: &Regions, app: &App, th: &Theme) {
    let Some(c) = app.caption() else { return };
    let room = area(r);
    if room.width < 3 || room.height < 3 {
        return;
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
    let inner = usize::from(room.width).saturating_sub(4);
    let mut block = super::titled(format!(" {} ", fit(&c.title, "\0", inner)), th)
        .border_style(Style::default().fg(th.accent));
    if let Some(p) = c.prompt {
        block = block.title_bottom(
            Line::from(Span::styled(
                format!(" {} ", fit(p, "\0", inner)),
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
