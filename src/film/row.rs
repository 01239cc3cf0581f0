//! One row of a screen as SVG: backgrounds as rectangles, box drawing as strokes, every other
//! glyph placed at its own cell. No glyph's width is trusted: braille is in no common
//! monospace font, so a browser borrows it from another whose advance differs, and a box
//! glyph's stroke ends short of a cell as tall as the film's.

use super::{CELL_H, CELL_W, escape, hex, num};
use ratatui::buffer::Cell;
use ratatui::style::{Color, Modifier};
use std::fmt::Write as _;

/// The colours a film has drawn so far: a row names each by its place (class `c0`, `c1`, …).
#[derive(Default)]
pub(super) struct Palette(pub(super) Vec<String>);

impl Palette {
    /// The class naming colour `c` (the terminal's own drawn as `default`), added if new.
    fn class(&mut self, c: Color, default: &str) -> String {
        let c = hex(c, default);
        let i = match self.0.iter().position(|k| *k == c) {
            Some(i) => i,
            None => {
                self.0.push(c);
                self.0.len() - 1
            }
        };
        format!("c{i}")
    }
}

/// The row `cells` drawn at the top of the picture: the cells whose background is not
/// `background` as rectangles, the lines and corners of boxes as strokes, then the glyphs.
pub(super) fn draw(cells: &[&Cell], background: Color, palette: &mut Palette) -> String {
    let mut out = backgrounds(cells, background, palette);
    out.push_str(&lines(cells, palette));
    out.push_str(&glyphs(cells, palette));
    out
}

/// The cells whose background is not the theme's, as a rectangle a run.
fn backgrounds(cells: &[&Cell], background: Color, palette: &mut Palette) -> String {
    let mut out = String::new();
    let mut x = 0;
    while x < cells.len() {
        let bg = cells[x].bg;
        let run = cells[x..].iter().take_while(|c| c.bg == bg).count();
        if bg != background && bg != Color::Reset {
            let _ = write!(
                out,
                r#"<rect class="{}" x="{}" width="{}" height="{}"/>"#,
                palette.class(bg, "#000000"),
                num(x as f64 * CELL_W),
                num(run as f64 * CELL_W),
                num(CELL_H)
            );
        }
        x += run;
    }
    out
}

/// The strokes of one colour and weight in a row.
struct Path {
    class: String,
    heavy: bool,
    /// The horizontal strokes, each from and to.
    spans: Vec<(f64, f64)>,
    /// The vertical strokes, drawn (`M x y V y` each).
    verticals: String,
}

/// The box-drawing cells as strokes from each cell's middle to its edges, a path for each
/// colour and weight; a line across cells is one stroke. Drawn, they meet the next row's as
/// a terminal's do, whatever the font.
fn lines(cells: &[&Cell], palette: &mut Palette) -> String {
    let mut paths: Vec<Path> = Vec::new();
    for (x, cell) in cells.iter().enumerate() {
        let Some((arms, heavy)) = box_arms(cell.symbol()) else {
            continue;
        };
        let class = palette.class(cell.fg, super::TEXT);
        let i = match paths
            .iter()
            .position(|p| p.class == class && p.heavy == heavy)
        {
            Some(i) => i,
            None => {
                paths.push(Path {
                    class,
                    heavy,
                    spans: Vec::new(),
                    verticals: String::new(),
                });
                paths.len() - 1
            }
        };
        let (left, mid) = (x as f64 * CELL_W, (x as f64 + 0.5) * CELL_W);
        let from = if arms & LEFT != 0 { left } else { mid };
        let to = if arms & RIGHT != 0 {
            left + CELL_W
        } else {
            mid
        };
        if from < to {
            let spans = &mut paths[i].spans;
            match spans.last_mut() {
                Some(last) if last.1 == from => last.1 = to,
                _ => spans.push((from, to)),
            }
        }
        let top = if arms & UP != 0 { 0.0 } else { CELL_H / 2.0 };
        let bottom = if arms & DOWN != 0 {
            CELL_H
        } else {
            CELL_H / 2.0
        };
        if top < bottom {
            let _ = write!(
                paths[i].verticals,
                "M{} {}V{}",
                num(mid),
                num(top),
                num(bottom)
            );
        }
    }
    let mut out = String::new();
    for path in paths {
        let heavy = if path.heavy { " h" } else { "" };
        let _ = write!(out, r#"<path class="{}{heavy}" d=""#, path.class);
        for (from, to) in path.spans {
            let _ = write!(out, "M{} {}H{}", num(from), num(CELL_H / 2.0), num(to));
        }
        let _ = write!(out, r#"{}"/>"#, path.verticals);
    }
    out
}

/// The glyphs (neither blank nor box drawing), each placed at its cell: a run for each colour
/// and weight, whose `x` lists where each of its characters goes.
fn glyphs(cells: &[&Cell], palette: &mut Palette) -> String {
    // Each run: its class, bold, its characters' places, its text.
    let mut runs: Vec<(String, bool, Vec<String>, String)> = Vec::new();
    for (x, cell) in cells.iter().enumerate() {
        let symbol = cell.symbol();
        if symbol.trim().is_empty() || box_arms(symbol).is_some() {
            continue;
        }
        let class = palette.class(cell.fg, super::TEXT);
        let bold = cell.modifier.contains(Modifier::BOLD);
        let i = match runs.iter().position(|r| r.0 == class && r.1 == bold) {
            Some(i) => i,
            None => {
                runs.push((class, bold, Vec::new(), String::new()));
                runs.len() - 1
            }
        };
        // A place for each character (those of one cell, as a combining mark's, share it).
        let at = num(x as f64 * CELL_W);
        runs[i].2.extend(symbol.chars().map(|_| at.clone()));
        runs[i].3.push_str(symbol);
    }
    if runs.is_empty() {
        return String::new();
    }
    let mut out = format!(r#"<text y="{}">"#, num(CELL_H * 0.78));
    for (class, bold, places, text) in runs {
        let bold = if bold { " b" } else { "" };
        let _ = write!(
            out,
            r#"<tspan class="{class}{bold}" x="{}">{}</tspan>"#,
            places.join(" "),
            escape(&text)
        );
    }
    out.push_str("</text>");
    out
}

/// Which way a box-drawing cell's strokes go from its middle.
const UP: u8 = 1;
const RIGHT: u8 = 2;
const DOWN: u8 = 4;
const LEFT: u8 = 8;

/// The strokes of a box-drawing symbol (light or heavy lines, corners, tees and crosses; a
/// rounded corner drawn square) and whether they are heavy; `None` for any other symbol.
fn box_arms(symbol: &str) -> Option<(u8, bool)> {
    let light = |arms: u8| Some((arms, false));
    let heavy = |arms: u8| Some((arms, true));
    match symbol {
        "─" => light(LEFT | RIGHT),
        "│" => light(UP | DOWN),
        "┌" | "╭" => light(RIGHT | DOWN),
        "┐" | "╮" => light(LEFT | DOWN),
        "└" | "╰" => light(UP | RIGHT),
        "┘" | "╯" => light(UP | LEFT),
        "├" => light(UP | DOWN | RIGHT),
        "┤" => light(UP | DOWN | LEFT),
        "┬" => light(LEFT | RIGHT | DOWN),
        "┴" => light(LEFT | RIGHT | UP),
        "┼" => light(UP | RIGHT | DOWN | LEFT),
        "╴" => light(LEFT),
        "╵" => light(UP),
        "╶" => light(RIGHT),
        "╷" => light(DOWN),
        "━" => heavy(LEFT | RIGHT),
        "┃" => heavy(UP | DOWN),
        "┏" => heavy(RIGHT | DOWN),
        "┓" => heavy(LEFT | DOWN),
        "┗" => heavy(UP | RIGHT),
        "┛" => heavy(UP | LEFT),
        "┣" => heavy(UP | DOWN | RIGHT),
        "┫" => heavy(UP | DOWN | LEFT),
        "┳" => heavy(LEFT | RIGHT | DOWN),
        "┻" => heavy(LEFT | RIGHT | UP),
        "╋" => heavy(UP | RIGHT | DOWN | LEFT),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::buffer::Buffer;
    use ratatui::layout::Rect;
    use ratatui::style::Style;

    /// Row `y` of `lines` (written in the terminal's own colours) as the film draws it, with
    /// the colours it named.
    fn drawn(lines: &[&str], y: u16) -> (String, Vec<String>) {
        let mut buf = Buffer::with_lines(lines.iter().copied());
        let area = buf.area;
        buf.set_style(area, Style::default().fg(Color::Reset).bg(Color::Reset));
        let cells: Vec<&Cell> = (0..area.width).map(|x| &buf[(x, y)]).collect();
        let mut palette = Palette::default();
        (draw(&cells, Color::Black, &mut palette), palette.0)
    }

    /// A box's lines are strokes through the cells' middles (4.5 px in, 9 px down): a line
    /// across cells is one stroke, a side runs the cell's whole height, so it meets the row
    /// below's; the text inside is placed cell by cell.
    #[test]
    fn boxes_are_drawn_as_strokes_that_meet() {
        let rows = ["┌─┐━━", "│x│┃ "];
        let (top, colours) = drawn(&rows, 0);
        assert_eq!(colours, ["#d0d0d0"]);
        assert_eq!(
            top,
            r#"<path class="c0" d="M4.5 9H22.5M4.5 9V18M22.5 9V18"/><path class="c0 h" d="M27 9H45"/>"#
        );
        let (middle, _) = drawn(&rows, 1);
        assert_eq!(
            middle,
            r#"<path class="c0" d="M4.5 0V18M22.5 0V18"/><path class="c0 h" d="M31.5 0V18"/><text y="14"><tspan class="c0" x="9">x</tspan></text>"#
        );
    }

    /// Every glyph sits at its own cell whatever the font's widths (braille, Greek and the
    /// rest alike), blanks are left out, and one colour and weight is one run.
    #[test]
    fn each_glyph_is_placed_at_its_cell() {
        let mut buf = Buffer::empty(Rect::new(0, 0, 8, 1));
        buf.set_string(0, 0, "ξ ⣿⠤", Style::default().fg(Color::Red));
        buf.set_string(4, 0, "a<", Style::default().fg(Color::Green).bold());
        buf.set_string(6, 0, "π", Style::default().fg(Color::Red));
        buf.set_style(Rect::new(5, 0, 3, 1), Style::default().bg(Color::Blue));
        let cells: Vec<&Cell> = (0..8).map(|x| &buf[(x, 0)]).collect();
        let mut palette = Palette::default();
        let row = draw(&cells, Color::Black, &mut palette);
        assert_eq!(
            row,
            concat!(
                r#"<rect class="c0" x="45" width="27" height="18"/>"#,
                r#"<text y="14"><tspan class="c1" x="0 18 27 54">ξ⣿⠤π</tspan>"#,
                r#"<tspan class="c2 b" x="36 45">a&lt;</tspan></text>"#
            )
        );
        assert_eq!(palette.0, ["#0000ee", "#cd0000", "#00cd00"]);
    }
}
