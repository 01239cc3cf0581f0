//! The help overlay, generated from `KEYMAP` (the table the keys dispatch on).

use super::fit::fit;
use crate::app::App;
use crate::app::keymap::{GROUPS, KEYMAP};
use crate::theme::Theme;
use ratatui::Frame as TuiFrame;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Paragraph, Widget};
use std::sync::{Arc, Mutex};
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

/// What the mouse does, listed after the keys.
const MOUSE: [(&str, &str); 3] = [
    (
        "click",
        "place the release; on the v_e and map pages, pick (φ, v0)",
    ),
    ("drag", "aim the initial velocity"),
    ("wheel", "zoom; in this help, scroll"),
];

/// The glyphs of the picture.
const GLYPHS: [(&str, &str); 9] = [
    ("●", "particle (converged run)"),
    ("⊕", "the body's centre, on its bar (a body scene)"),
    ("○", "paper's RK2 run (c)"),
    ("■", "particle at rest"),
    ("×", "where it stopped"),
    ("·", "step ends (n)"),
    ("↺", "table's sense of rotation"),
    ("◆▲▼◇△▽", "pinned runs (b), named at the end"),
    ("net u v", "net force (A), velocity (i)"),
];

/// One entry: a group header, or a key (or glyph) and its help.
type Item = (Option<String>, String, &'static str);

fn items() -> Vec<Item> {
    let mut items: Vec<Item> = Vec::new();
    for (g, rs) in rows() {
        items.push((Some(g.to_string()), String::new(), ""));
        items.extend(rs.into_iter().map(|(k, h)| (None, k, h)));
    }
    for (g, rs) in [("mouse", &MOUSE[..]), ("glyphs", &GLYPHS[..])] {
        items.push((Some(g.to_string()), String::new(), ""));
        items.extend(rs.iter().map(|(k, h)| (None, k.to_string(), *h)));
    }
    items
}

/// The help's box in `area` (the help region of the layout), at most 100 wide.
fn popup(area: Rect) -> Rect {
    let w = area.width.min(100);
    Rect {
        x: area.x + (area.width - w) / 2,
        width: w,
        ..area
    }
}

/// One row of the help: a group's header, or a key's label (padded to its column's widest)
/// and a piece of its help.
enum Row {
    Header(String),
    Entry { key: String, text: String },
}

impl Row {
    fn line(&self, th: &Theme) -> Line<'_> {
        match self {
            Row::Header(g) => heading(g.as_str(), th),
            Row::Entry { key, text } => Line::from(vec![
                Span::styled(key.as_str(), Style::default().fg(th.notice)),
                Span::styled(text.as_str(), Style::default().fg(th.foreground)),
            ]),
        }
    }
}

/// A group's heading.
fn heading<'a>(g: impl Into<std::borrow::Cow<'a, str>>, th: &Theme) -> Line<'a> {
    Line::from(Span::styled(
        g,
        Style::default().fg(th.accent).add_modifier(Modifier::BOLD),
    ))
}

/// The help's columns at one inside width, each its rows.
type Laid = Vec<Vec<Row>>;

/// Widths whose help is kept laid out: a class's few window sizes.
const LAID_KEPT: usize = 16;

/// The help laid out for a box whose inside is `width` wide: once a width for every session
/// (its text is the key table's), not once a frame (choosing the split lays it out once per
/// place it could split: a served help frame cost several plain ones).
fn laid(width: u16) -> Arc<Laid> {
    static KEPT: Mutex<Vec<(u16, Arc<Laid>)>> = Mutex::new(Vec::new());
    let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, l)) = kept.iter().find(|(w, _)| *w == width) {
        return Arc::clone(l);
    }
    let l = Arc::new(columns(width));
    if kept.len() >= LAID_KEPT {
        kept.remove(0);
    }
    kept.push((width, Arc::clone(&l)));
    l
}

/// The help's columns for a box whose inside is `width` wide: two from 60 cells, else one.
/// Each is its rows, a help text too long for the column wrapped at words under itself.
fn columns(width: u16) -> Laid {
    let items = items();
    if width < 60 {
        return vec![column(&items, usize::from(width))];
    }
    // Two columns, split where the taller is shortest (wrapped rows counted), never leaving
    // a header alone at the foot of the first; a group split between them is headed again at
    // the top of the second (`view (cont.)`).
    let colw = usize::from((width - 1) / 2);
    (1..items.len())
        .filter(|&k| items[k - 1].0.is_none())
        .map(|k| vec![column(&items[..k], colw), column(&rest(&items, k), colw)])
        .min_by_key(|cols| cols.iter().map(Vec::len).max())
        .unwrap_or_default()
}

/// The items from `k` on, headed by their group's name and `(cont.)` when `k` is inside a group.
fn rest(items: &[Item], k: usize) -> Vec<Item> {
    let mut out = Vec::with_capacity(items.len() - k + 1);
    if items[k].0.is_none() {
        let group = items[..k].iter().rev().find_map(|(g, _, _)| g.as_deref());
        if let Some(g) = group {
            out.push((Some(format!("{g} (cont.)")), String::new(), ""));
        }
    }
    out.extend_from_slice(&items[k..]);
    out
}

/// One column: labels take its widest label's width and two blanks, so no help text is glued
/// to its keys.
fn column(items: &[Item], width: usize) -> Vec<Row> {
    let lw = items.iter().map(|(_, k, _)| k.width()).max().unwrap_or(0) + 2;
    let room = width.saturating_sub(1 + lw).max(8);
    let mut out = Vec::new();
    for (g, k, help) in items {
        if let Some(g) = g {
            out.push(Row::Header(g.clone()));
            continue;
        }
        let mut chunks = vec![String::new()];
        for word in help.split(' ') {
            let last = chunks.last_mut().expect("one chunk");
            if last.is_empty() {
                last.push_str(word);
            } else if last.width() + 1 + word.width() <= room {
                last.push(' ');
                last.push_str(word);
            } else {
                chunks.push(word.to_string());
            }
        }
        for (i, text) in chunks.into_iter().enumerate() {
            let key = if i == 0 { k.as_str() } else { "" };
            out.push(Row::Entry {
                key: format!(" {key}{}", " ".repeat(lw - key.width())),
                text,
            });
        }
    }
    out
}

/// How far the help scrolls at a `width` × `height` terminal: its rows less those shown, and
/// one more for the heading a scrolled column repeats at its top.
pub fn max_scroll(width: u16, height: u16) -> u16 {
    let Some(r) = super::layout::regions(width, height) else {
        return 0;
    };
    let p = popup(r.help);
    let rows = laid(p.width.saturating_sub(2))
        .iter()
        .map(Vec::len)
        .max()
        .unwrap_or(0);
    u16::try_from(last_top(rows, usize::from(p.height.saturating_sub(2)))).unwrap_or(u16::MAX)
}

/// The last row the help can scroll to the top with `rows` rows, `shown` of them in view.
fn last_top(rows: usize, shown: usize) -> usize {
    if rows > shown { rows - shown + 1 } else { 0 }
}

/// Rows one PgUp/PgDn scrolls at this size: the help's visible rows.
pub fn page(height: u16) -> u16 {
    height.saturating_sub(3).max(1)
}

pub fn render(f: &mut TuiFrame, area: Rect, app: &App, th: &Theme) {
    let popup = popup(area);
    let key = Drawn {
        popup,
        scroll: app.view().help_scroll,
        colours: [th.accent, th.notice, th.foreground, th.background],
    };
    let drawn = drawn(key, th);
    let buf = f.buffer_mut();
    let area = popup.intersection(buf.area);
    for y in area.top()..area.bottom() {
        let (to, from) = (buf.index_of(area.x, y), drawn.index_of(area.x, y));
        let n = usize::from(area.width);
        buf.content[to..to + n].clone_from_slice(&drawn.content[from..from + n]);
    }
}

/// What the help's box shows is a function of these alone.
#[derive(Clone, Copy, PartialEq)]
struct Drawn {
    popup: Rect,
    scroll: u16,
    colours: [ratatui::style::Color; 4],
}

/// The help's boxes kept drawn: a class's sizes and themes, and where their readers scrolled.
const DRAWN_KEPT: usize = 32;

/// The help's box as `key` has it, drawn once for every session that shows it so (a served
/// help frame drew its hundred rows of text each time: its cells are copied instead).
fn drawn(key: Drawn, th: &Theme) -> Arc<Buffer> {
    static KEPT: Mutex<Vec<(Drawn, Arc<Buffer>)>> = Mutex::new(Vec::new());
    let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, b)) = kept.iter().find(|(k, _)| *k == key) {
        return Arc::clone(b);
    }
    let mut b = Buffer::empty(key.popup);
    draw_box(&mut b, key.popup, key.scroll, th);
    let b = Arc::new(b);
    if kept.len() >= DRAWN_KEPT {
        kept.remove(0);
    }
    kept.push((key, Arc::clone(&b)));
    b
}

/// The help's box on `buf` (empty) at `popup`, scrolled `scroll` rows down (at most to its end).
fn draw_box(buf: &mut Buffer, popup: Rect, scroll: u16, th: &Theme) {
    let cols = laid(popup.width.saturating_sub(2));
    let rows = cols.iter().map(Vec::len).max().unwrap_or(0);
    let shown = usize::from(popup.height.saturating_sub(2));
    let top = usize::from(scroll).min(last_top(rows, shown));
    let views: Vec<View> = cols.iter().map(|c| View::of(c, top, shown)).collect();
    let end = views.iter().map(|v| v.end).max().unwrap_or(0);
    let more = views.iter().zip(cols.iter()).any(|(v, c)| v.end < c.len());
    let title = fit(
        " help: ? or Esc closes, ↑ ↓ PgUp PgDn wheel scroll ",
        ", ",
        usize::from(popup.width).saturating_sub(2),
    );
    // Where the reader is, when not all of it fits.
    let place = if rows > shown {
        format!(
            " rows {}–{} of {}{} ",
            top + 1,
            end,
            rows,
            if more { ", ↓ more" } else { "" }
        )
    } else {
        String::new()
    };
    let block = Block::default()
        .borders(Borders::ALL)
        .border_style(Style::default().fg(th.accent))
        .title(Span::styled(title, Style::default().fg(th.accent)))
        .title_bottom(
            Line::from(Span::styled(place, Style::default().fg(th.notice))).right_aligned(),
        )
        .style(Style::default().bg(th.background).fg(th.foreground));
    let inner = block.inner(popup);
    block.render(popup, buf);
    // The rows in view only (a paragraph scrolled past the others lays them out too).
    let shown_of = |i: usize| views[i].lines(&cols[i], th);
    if cols.len() == 1 {
        Paragraph::new(shown_of(0)).render(inner, buf);
        return;
    }
    // The widths `columns` wrapped to, a blank between.
    let w = (inner.width - 1) / 2;
    let halves = [
        Rect { width: w, ..inner },
        Rect {
            x: inner.x + w + 1,
            width: inner.width - w - 1,
            ..inner
        },
    ];
    for (i, area) in halves.into_iter().enumerate().take(cols.len()) {
        Paragraph::new(shown_of(i)).render(area, buf);
    }
}

/// What a column shows scrolled to `top`: its rows from there, under its group's heading
/// again (`view (cont.)`) when the first of them is inside a group.
struct View {
    heading: Option<String>,
    from: usize,
    end: usize,
}

impl View {
    fn of(col: &[Row], top: usize, shown: usize) -> View {
        let from = top.min(col.len());
        let heading = match col.get(from) {
            Some(Row::Entry { .. }) => col[..from].iter().rev().find_map(|r| match r {
                Row::Header(g) => Some(format!("{} (cont.)", g.trim_end_matches(" (cont.)"))),
                Row::Entry { .. } => None,
            }),
            _ => None,
        };
        let room = shown.saturating_sub(usize::from(heading.is_some()));
        View {
            heading,
            from,
            end: (from + room).min(col.len()),
        }
    }

    fn lines<'a>(&self, col: &'a [Row], th: &Theme) -> Vec<Line<'a>> {
        let head = self.heading.iter().map(|g| heading(g.clone(), th));
        head.chain(col[self.from..self.end].iter().map(|r| r.line(th)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sessions showing the help alike share one drawing of its box, which is the box drawn
    /// directly; another scroll is another drawing.
    #[test]
    fn the_helps_box_is_drawn_once_for_all_who_show_it_alike() {
        let th = Theme::builtin("dark").unwrap();
        let key = Drawn {
            popup: Rect::new(3, 1, 97, 27),
            scroll: 2,
            colours: [th.accent, th.notice, th.foreground, th.background],
        };
        let (a, b) = (drawn(key, &th), drawn(key, &th));
        assert!(Arc::ptr_eq(&a, &b));
        let mut direct = Buffer::empty(key.popup);
        draw_box(&mut direct, key.popup, key.scroll, &th);
        assert_eq!(*a, direct);
        let other = drawn(Drawn { scroll: 3, ..key }, &th);
        assert!(!Arc::ptr_eq(&a, &other));
        assert_ne!(*a, *other);
    }

    /// Issue 46 item 6: at every width (one column below 60, two from it) and every scroll,
    /// each column's top row is a group's heading (its own, or `… (cont.)`), and the last
    /// scroll shows every column to its end.
    #[test]
    fn every_column_opens_on_a_heading_at_every_scroll() {
        for width in 58..=98 {
            let cols = columns(width);
            let rows = cols.iter().map(Vec::len).max().unwrap_or(0);
            for shown in [6, 12, 21, 40] {
                let last = last_top(rows, shown);
                for top in 0..=last {
                    for (i, col) in cols.iter().enumerate() {
                        let v = View::of(col, top, shown);
                        let opens = v.heading.is_some()
                            || matches!(col.get(v.from), Some(Row::Header(_)) | None);
                        assert!(opens, "width {width}, column {i}, top {top}");
                        assert!(v.end - v.from + usize::from(v.heading.is_some()) <= shown);
                        if top == last {
                            assert_eq!(v.end, col.len(), "width {width} column {i}: cut");
                        }
                    }
                }
            }
        }
    }
}
