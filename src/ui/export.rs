//! A drawn screen as text: plain (trailing blanks trimmed) or styled with ANSI SGR sequences,
//! for replays, goldens and tests.

use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use unicode_width::UnicodeWidthStr;

/// Columns a cell's symbol takes, at least one. A one-byte symbol (ASCII, most of a screen)
/// takes one without asking unicode-width: this runs for every cell of every recorded frame.
fn columns(c: &ratatui::buffer::Cell) -> usize {
    let s = c.symbol();
    if s.len() == 1 { 1 } else { s.width().max(1) }
}

/// The cells of each row that are drawn: a wide symbol hides the cells it covers.
fn rows(buf: &Buffer) -> impl Iterator<Item = Vec<&ratatui::buffer::Cell>> {
    let w = usize::from(buf.area.width).max(1);
    buf.content.chunks(w).map(|cells| {
        let mut shown = Vec::with_capacity(cells.len());
        let mut skip = 0usize;
        for c in cells {
            if skip == 0 {
                shown.push(c);
            }
            skip = skip.max(columns(c)) - 1;
        }
        shown
    })
}

/// The screen as plain text, one line per row, trailing blanks trimmed.
pub fn plain_text(buf: &Buffer) -> String {
    let mut out = String::new();
    for row in rows(buf) {
        let line: String = row.iter().map(|c| c.symbol()).collect();
        out.push_str(line.trim_end_matches(' '));
        out.push('\n');
    }
    out
}

/// The screen with SGR sequences: a full reset and the cell's style whenever the style
/// changes along a row, and a reset at the end of each row.
pub fn ansi_text(buf: &Buffer) -> String {
    let mut out = String::new();
    for row in rows(buf) {
        let mut current = None;
        for c in row {
            let style = (c.fg, c.bg, c.modifier);
            if current != Some(style) {
                out.push_str(&sgr(c.fg, c.bg, c.modifier));
                current = Some(style);
            }
            out.push_str(c.symbol());
        }
        out.push_str("\x1b[0m\n");
    }
    out
}

/// What turns the screen `prev` showed into `buf`: each run of changed cells after a move to
/// its start, styled as [`ansi_text`] styles it, then a reset; every row when there is no
/// `prev` (or it was another size). A cell beside a wide symbol, in either screen, is written
/// again with it, so that no half of a wide symbol is left behind.
pub fn ansi_changes(prev: Option<&Buffer>, buf: &Buffer) -> String {
    let prev = prev.filter(|p| p.area == buf.area);
    let w = usize::from(buf.area.width);
    let wide = |b: &Buffer, i: usize| b.content.get(i).is_some_and(|c| columns(c) > 1);
    let differs = |i: usize| match prev {
        None => true,
        Some(p) => {
            let (a, b) = (&p.content[i], &buf.content[i]);
            a.symbol() != b.symbol()
                || (a.fg, a.bg, a.modifier) != (b.fg, b.bg, b.modifier)
                || (!i.is_multiple_of(w) && (wide(p, i - 1) || wide(buf, i - 1)))
        }
    };
    let mut out = String::new();
    for (y, row) in rows(buf).enumerate() {
        let mut x = 0usize;
        let mut current = None;
        let mut in_run = false;
        for c in row {
            let i = y * w + x;
            if differs(i) {
                if !in_run {
                    out.push_str(&format!("\x1b[{};{}H", y + 1, x + 1));
                    current = None;
                    in_run = true;
                }
                let style = (c.fg, c.bg, c.modifier);
                if current != Some(style) {
                    out.push_str(&sgr(c.fg, c.bg, c.modifier));
                    current = Some(style);
                }
                out.push_str(c.symbol());
            } else {
                in_run = false;
            }
            x += columns(c);
        }
        if current.is_some() {
            out.push_str("\x1b[0m");
        }
    }
    out
}

fn sgr(fg: Color, bg: Color, m: Modifier) -> String {
    let mut codes = vec!["0".to_string()];
    for (flag, code) in [
        (Modifier::BOLD, "1"),
        (Modifier::DIM, "2"),
        (Modifier::ITALIC, "3"),
        (Modifier::UNDERLINED, "4"),
        (Modifier::SLOW_BLINK, "5"),
        (Modifier::RAPID_BLINK, "6"),
        (Modifier::REVERSED, "7"),
        (Modifier::HIDDEN, "8"),
        (Modifier::CROSSED_OUT, "9"),
    ] {
        if m.contains(flag) {
            codes.push(code.into());
        }
    }
    if let Some(c) = colour(fg, false) {
        codes.push(c);
    }
    if let Some(c) = colour(bg, true) {
        codes.push(c);
    }
    format!("\x1b[{}m", codes.join(";"))
}

/// The SGR parameter for a colour; None for the terminal's default (already reset).
fn colour(c: Color, background: bool) -> Option<String> {
    let base = if background { 40 } else { 30 };
    let code = |n: u8| Some((base + u16::from(n)).to_string());
    let bright = |n: u8| Some((base + 60 + u16::from(n)).to_string());
    match c {
        Color::Reset => None,
        Color::Black => code(0),
        Color::Red => code(1),
        Color::Green => code(2),
        Color::Yellow => code(3),
        Color::Blue => code(4),
        Color::Magenta => code(5),
        Color::Cyan => code(6),
        Color::Gray => code(7),
        Color::DarkGray => bright(0),
        Color::LightRed => bright(1),
        Color::LightGreen => bright(2),
        Color::LightYellow => bright(3),
        Color::LightBlue => bright(4),
        Color::LightMagenta => bright(5),
        Color::LightCyan => bright(6),
        Color::White => bright(7),
        Color::Indexed(i) => Some(format!("{};5;{i}", base + 8)),
        Color::Rgb(r, g, b) => Some(format!("{};2;{r};{g};{b}", base + 8)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sgr_codes() {
        assert_eq!(
            sgr(Color::Reset, Color::Reset, Modifier::empty()),
            "\x1b[0m"
        );
        assert_eq!(
            sgr(Color::Rgb(1, 2, 3), Color::Blue, Modifier::BOLD),
            "\x1b[0;1;38;2;1;2;3;44m"
        );
        assert_eq!(
            sgr(Color::White, Color::Indexed(7), Modifier::empty()),
            "\x1b[0;97;48;5;7m"
        );
    }
}
