//! The help overlay, generated from `KEYMAP` (the table the keys dispatch on).

use crate::app::App;
use crate::app::keymap::{GROUPS, KEYMAP};
use ratatui::Frame as TuiFrame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Clear, Paragraph, Wrap};
use unicode_width::UnicodeWidthStr;

/// Help rows per group: bindings with the same help text share a row, keys joined by `/`
/// (a shared modifier written once: `Alt-x/X`, `Shift-←/↓/↑/→`; the same keys again with a
/// modifier after them: `x/X (Alt)`).
pub fn rows() -> Vec<(&'static str, Vec<(String, &'static str)>)> {
    GROUPS
        .iter()
        .map(|g| {
            let mut rows: Vec<(Vec<&crate::app::Binding>, &'static str)> = Vec::new();
            for b in KEYMAP.iter().filter(|b| b.group == *g) {
                match rows.iter_mut().find(|(_, h)| *h == b.help) {
                    Some((keys, _)) => keys.push(b),
                    None => rows.push((vec![b], b.help)),
                }
            }
            let rows = rows
                .into_iter()
                .map(|(keys, help)| {
                    let mods = keys[0].chord.mods;
                    let tails = |m| -> Vec<String> {
                        keys.iter()
                            .filter(|b| b.chord.mods == m)
                            .map(|b| b.chord.key_label())
                            .collect()
                    };
                    let others: Vec<&crate::app::Binding> = keys
                        .iter()
                        .copied()
                        .filter(|b| b.chord.mods != mods)
                        .collect();
                    let label = if others.is_empty() {
                        keys[0].chord.mods_label() + &tails(mods).join("/")
                    } else if others.iter().all(|b| b.chord.mods == others[0].chord.mods)
                        && tails(others[0].chord.mods) == tails(mods)
                    {
                        // The same keys again with a modifier: `x/X (Alt)`.
                        let m = others[0].chord.mods_label();
                        format!("{} ({})", tails(mods).join("/"), m.trim_end_matches('-'))
                    } else {
                        let labels: Vec<String> = keys.iter().map(|b| b.chord.label()).collect();
                        labels.join("/")
                    };
                    (label, help)
                })
                .collect();
            (*g, rows)
        })
        .collect()
}

pub fn render(f: &mut TuiFrame, area: Rect, app: &App) {
    let th = &app.theme;
    let w = area.width.min(100);
    let h = area.height;
    let popup = Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y,
        width: w,
        height: h,
    };
    f.render_widget(Clear, popup);
    let block = Block::default()
        .borders(Borders::ALL)
        .border_style(Style::default().fg(th.accent))
        .title(Span::styled(
            " help — ? or Esc closes ",
            Style::default().fg(th.accent),
        ))
        .style(Style::default().bg(th.background).fg(th.foreground));
    let inner = block.inner(popup);
    f.render_widget(block, popup);
    // Two columns of equal height; a long group may run on into the second. In each column
    // labels take its widest label's width and two blanks, so no help text is glued to its
    // keys.
    let mut items: Vec<(Option<&str>, String, &str)> = Vec::new();
    for (g, rs) in rows() {
        items.push((Some(g), String::new(), ""));
        items.extend(rs.into_iter().map(|(k, h)| (None, k, h)));
    }
    let mut half = items.len().div_ceil(2);
    if items[half - 1].0.is_some() {
        half -= 1; // no header left alone at the foot of a column
    }
    let column = |items: &[(Option<&str>, String, &str)]| -> Vec<Line> {
        let lw = items.iter().map(|(_, k, _)| k.width()).max().unwrap_or(0) + 2;
        items
            .iter()
            .map(|(g, k, help)| match g {
                Some(g) => Line::from(Span::styled(
                    g.to_string(),
                    Style::default().fg(th.accent).add_modifier(Modifier::BOLD),
                )),
                None => Line::from(vec![
                    Span::styled(
                        format!(" {k}{}", " ".repeat(lw - k.width())),
                        Style::default().fg(th.notice),
                    ),
                    Span::styled(help.to_string(), Style::default().fg(th.foreground)),
                ]),
            })
            .collect()
    };
    // Narrow columns wrap at word boundaries rather than cut a word; below 60 cells one
    // column.
    let wrap = Wrap { trim: false };
    if inner.width < 60 {
        f.render_widget(Paragraph::new(column(&items)).wrap(wrap), inner);
        return;
    }
    let (a, b) = (column(&items[..half]), column(&items[half..]));
    let halves = Layout::horizontal([Constraint::Percentage(50), Constraint::Percentage(50)])
        .spacing(1)
        .split(inner);
    f.render_widget(Paragraph::new(a).wrap(wrap), halves[0]);
    f.render_widget(Paragraph::new(b).wrap(wrap), halves[1]);
}
