//! An animated SVG of a replay (`replay --svg`): the screens its recording shows, at most ten
//! a second, stacked in one picture that a CSS animation steps through. A browser plays it,
//! and so does a README on a forge, with nothing installed (an asciicast needs a player).

use crate::theme::ansi16;
use ratatui::buffer::{Buffer, Cell};
use ratatui::style::Color;
use std::fmt::Write as _;
use std::io::{self, Write};

mod row;

/// A cell's size in the picture, in pixels (whole, so that places are short), and the font's
/// (a monospace font's advance is 0.6 of its size: `row` places each glyph at its cell, as
/// no font is trusted to have it).
const CELL_W: f64 = 9.0;
const CELL_H: f64 = 18.0;
const FONT: f64 = 15.0;

/// The colour of text in the terminal's own colour.
const TEXT: &str = "#d0d0d0";

/// The least time between two screens kept: a screen that follows sooner replaces the last.
const STEP: f64 = 0.1;

/// Most screens a picture holds: two minutes at ten a second.
pub const MAX_SCREENS: usize = 1200;

/// How long the last screen stays before the picture starts again, in seconds.
const END_HOLD: f64 = 3.0;

/// The screens recorded so far: each the second it shows from and its rows drawn as SVG (the
/// picture draws a row once however many screens show it: from one to the next most stay).
pub struct Film {
    width: u16,
    height: u16,
    background: Color,
    screens: Vec<(f64, Vec<String>)>,
    /// The colours its rows name.
    colours: row::Palette,
}

impl Film {
    /// A film of a `width` × `height` terminal whose theme paints `background`.
    pub fn new(width: u16, height: u16, background: Color) -> Self {
        Film {
            width,
            height,
            background,
            screens: Vec::new(),
            colours: row::Palette::default(),
        }
    }

    /// The screen `buf` from second `t` on (what lies outside the film's size is left out).
    pub fn frame(&mut self, t: f64, buf: &Buffer) -> io::Result<()> {
        let drawn = self.draw(buf);
        match self.screens.last_mut() {
            Some(last) if last.1 == drawn => return Ok(()),
            // (Less a hair: three ticks of a thirtieth add up to a tenth or a hair less, and
            // the screens would step unevenly, now three ticks apart, now four.)
            Some(last) if t - last.0 < STEP - 1e-9 => {
                last.1 = drawn;
                return Ok(());
            }
            _ => {}
        }
        if self.screens.len() >= MAX_SCREENS {
            return Err(io::Error::other(crate::files::BoundReached {
                message: format!(
                    "--svg reached its bound of {MAX_SCREENS} screens (two minutes at ten a second)"
                ),
            }));
        }
        self.screens.push((t, drawn));
        Ok(())
    }

    /// The picture: every screen, one below the other, and the animation that shows each in
    /// turn for its time, then starts again.
    pub fn write(&self, title: &str, out: &mut dyn Write) -> io::Result<()> {
        let (w, h) = (
            f64::from(self.width) * CELL_W,
            f64::from(self.height) * CELL_H,
        );
        let total = self.screens.last().map_or(0.0, |s| s.0) + END_HOLD;
        let mut frames = String::new();
        for (i, (t, _)) in self.screens.iter().enumerate() {
            let _ = write!(
                frames,
                "{:.4}%{{transform:translateY({}px)}}",
                100.0 * t / total,
                num(-(i as f64) * h)
            );
        }
        let mut colours = String::new();
        for (i, c) in self.colours.0.iter().enumerate() {
            let _ = write!(colours, ".c{i}{{color:{c}}}");
        }
        let (w, h) = (num(w), num(h));
        writeln!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
        )?;
        writeln!(out, "<title>{}</title>", escape(title))?;
        writeln!(
            out,
            "<style>text{{font-family:'DejaVu Sans Mono',Menlo,Consolas,'Liberation Mono',monospace;font-size:{FONT}px}}tspan,rect{{fill:currentColor}}path{{fill:none;stroke:currentColor;stroke-width:1.2px;stroke-linecap:square}}.h{{stroke-width:2.6px}}.b{{font-weight:bold}}{colours}@keyframes play{{{frames}}}#screens{{animation:play {total:.3}s steps(1,end) infinite}}</style>"
        )?;
        writeln!(
            out,
            r#"<rect width="100%" height="100%" style="fill:{}"/>"#,
            hex(self.background, "#000000")
        )?;
        // Each row once, by its first place in the order shown.
        let mut known: std::collections::HashMap<&str, usize> = Default::default();
        writeln!(out, "<defs>")?;
        for row in self.screens.iter().flat_map(|s| &s.1) {
            if !known.contains_key(row.as_str()) {
                writeln!(out, r#"<g id="r{}">{row}</g>"#, known.len())?;
                known.insert(row, known.len());
            }
        }
        writeln!(out, "</defs>")?;
        writeln!(out, r#"<g id="screens">"#)?;
        for (i, (_, rows)) in self.screens.iter().enumerate() {
            write!(
                out,
                r#"<g transform="translate(0 {})">"#,
                num(i as f64 * CELL_H * f64::from(self.height))
            )?;
            for (y, row) in rows.iter().enumerate() {
                let r = known[row.as_str()];
                write!(
                    out,
                    r##"<use href="#r{r}" y="{}"/>"##,
                    num(y as f64 * CELL_H)
                )?;
            }
            writeln!(out, "</g>")?;
        }
        writeln!(out, "</g></svg>")
    }

    /// One screen's rows, each drawn at the top (see `row`).
    fn draw(&mut self, buf: &Buffer) -> Vec<String> {
        let (w, h) = (
            self.width.min(buf.area.width),
            self.height.min(buf.area.height),
        );
        (0..h)
            .map(|y| {
                let row: Vec<&Cell> = (0..w)
                    .map(|x| &buf[(buf.area.x + x, buf.area.y + y)])
                    .collect();
                row::draw(&row, self.background, &mut self.colours)
            })
            .collect()
    }
}

/// A length in the picture, as short as it reads: `9`, `4.5`, `-36`.
fn num(v: f64) -> String {
    let tenths = (v * 10.0).round();
    if tenths % 10.0 == 0.0 {
        // (plus zero: -0 reads 0)
        format!("{}", tenths / 10.0 + 0.0)
    } else {
        format!("{:.1}", tenths / 10.0)
    }
}

/// XML's special characters escaped.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A terminal colour as the xterm palette shows it; `default` for the terminal's own.
fn hex(c: Color, default: &str) -> String {
    let indexed = |i: u8| match i {
        0..=15 => ansi16::indexed(i),
        16..=231 => {
            let level = |v: u8| if v == 0 { 0 } else { 55 + 40 * v };
            let i = i - 16;
            (level(i / 36), level(i / 6 % 6), level(i % 6))
        }
        _ => {
            let v = 8 + 10 * (i - 232);
            (v, v, v)
        }
    };
    let (r, g, b) = match c {
        Color::Indexed(i) => indexed(i),
        // Its own, or one of the 16 named.
        c => match ansi16::rgb(c) {
            Some(rgb) => rgb,
            None => return default.into(),
        },
    };
    format!("#{r:02x}{g:02x}{b:02x}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::layout::Rect;
    use ratatui::style::Style;

    /// A screen a tick (a thirtieth of a second, after a caption's hold) keeps one every
    /// three ticks: ten a second, evenly, each with the last of its ticks' screens.
    #[test]
    fn screens_step_evenly_at_ten_a_second() {
        let mut buf = Buffer::empty(Rect::new(0, 0, 3, 1));
        let mut film = Film::new(3, 1, Color::Black);
        for tick in 0..30_u32 {
            buf.set_string(0, 0, format!("{tick:3}"), Style::default());
            film.frame(f64::from(tick) / 30.0 + 5.1, &buf).unwrap();
        }
        let times: Vec<String> = film.screens.iter().map(|s| format!("{:.4}", s.0)).collect();
        let every_third: Vec<String> = (0..10)
            .map(|i| format!("{:.4}", 5.1 + f64::from(i) / 10.0))
            .collect();
        assert_eq!(times, every_third);
        // The screen from 5.1 s is the last of ticks 0, 1 and 2.
        assert!(
            film.screens[0].1[0].contains(r#"x="18">2<"#),
            "{:?}",
            film.screens[0]
        );
        assert!(
            film.screens[9].1[0].contains(r#"x="9 18">29<"#),
            "{:?}",
            film.screens[9]
        );
    }

    #[test]
    fn lengths_read_short() {
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(-36.0), "-36");
        assert_eq!(num(4.5), "4.5");
        assert_eq!(num(14.04), "14");
        assert_eq!(num(711.0), "711");
    }

    #[test]
    fn colours_are_xterms() {
        assert_eq!(hex(Color::Rgb(1, 2, 255), ""), "#0102ff");
        assert_eq!(hex(Color::Indexed(16), ""), "#000000");
        assert_eq!(hex(Color::Indexed(196), ""), "#ff0000");
        assert_eq!(hex(Color::Indexed(244), ""), "#808080");
        assert_eq!(hex(Color::Reset, "#123456"), "#123456");
    }

    /// Screens closer than a tenth of a second replace one another; the same screen again is
    /// not kept; each kept screen is shown from its time, in order, and the bound holds.
    #[test]
    fn screens_are_kept_a_tenth_apart_and_shown_in_turn() {
        let mut buf = Buffer::empty(Rect::new(0, 0, 4, 2));
        let mut film = Film::new(4, 2, Color::Black);
        buf.set_string(0, 0, "a<&", Style::default().fg(Color::Red));
        film.frame(0.0, &buf).unwrap();
        film.frame(0.05, &buf).unwrap();
        buf.set_string(0, 1, "b", Style::default());
        film.frame(0.05, &buf).unwrap();
        buf.set_string(0, 1, "c", Style::default());
        film.frame(0.5, &buf).unwrap();
        assert_eq!(film.screens.len(), 2);
        assert_eq!(film.screens[0].0, 0.0);
        assert!(film.screens[0].1[1].contains(r#"x="0">b</tspan>"#));
        let mut out = Vec::new();
        film.write("t<", &mut out).unwrap();
        let svg = String::from_utf8(out).unwrap();
        assert!(svg.contains("<title>t&lt;</title>"));
        // Red is the first colour drawn; each character at its cell, nine pixels apart.
        assert!(svg.contains(".c0{color:#cd0000}"), "{svg}");
        assert!(
            svg.contains(r#"<tspan class="c0" x="0 9 18">a&lt;&amp;</tspan>"#),
            "{svg}"
        );
        // 3.5 s in all: the second screen from 0.5 s, one screen's height (2 × 18 px) up.
        assert!(svg.contains("0.0000%{transform:translateY(0px)}"), "{svg}");
        assert!(
            svg.contains("14.2857%{transform:translateY(-36px)}"),
            "{svg}"
        );
        assert!(svg.contains(r#"width="36" height="36" viewBox="0 0 36 36""#));
        assert!(svg.contains("animation:play 3.500s"));
        // The first row is drawn once for both screens: three rows in all.
        assert_eq!(svg.matches(r#"<g id="r"#).count(), 3);
        assert_eq!(svg.matches(r##"<use href="#r0""##).count(), 2);
        let mut full = Film::new(4, 2, Color::Black);
        let err = (0..=MAX_SCREENS)
            .map(|i| {
                buf.set_string(0, 0, format!("{i:4}"), Style::default());
                full.frame(i as f64, &buf)
            })
            .find_map(Result::err)
            .unwrap();
        assert!(
            err.to_string()
                .contains("--svg reached its bound of 1200 screens")
        );
    }
}
