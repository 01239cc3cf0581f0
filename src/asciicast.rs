//! An asciicast v2 recording of a replay (asciinema's format): a header line
//! `{"version": 2, "width": W, "height": H, ...}`, then one JSON array per event,
//! `[time, "o", data]` for output, `[time, "r", "WxH"]` for a resize and `[time, "m", label]`
//! for a marker (each snapshot). A frame is written when the screen differs from the last
//! one: the first whole, then only the cells that changed, each run after a cursor move (a
//! few hundred bytes a tick instead of the whole screen's twelve thousand); its time is the ticks passed so far at the explorer's own rate
//! (`TICKS_PER_SECOND`), plus the holds the replay asks for after a key or a caption
//! ([`Cast::hold`]: a cast shown to a class gives each key and caption time to be seen), so
//! the recording plays at the pace of the session and is the same bytes on every run.

use crate::app::TICKS_PER_SECOND;
use crate::ui::export::ansi_changes;
use ratatui::buffer::Buffer;
use serde_json::json;
use std::io::{self, Write};

/// Most frames a recording holds: an hour of play at the explorer's 30 a second. A script's
/// `tick 10000000` ends there, with an error naming the bound.
pub const MAX_FRAMES: u64 = 3600 * TICKS_PER_SECOND as u64;

/// Most cells a recording looks at, frame by frame: an hour of an 80×24 screen. Frames carry
/// only what changed, so bytes no longer bound a huge screen's work (a 1000×1000 screen whose
/// particle moves writes little a tick, but each tick draws and compares a million cells):
/// this does, at about 200 such frames.
pub const MAX_CELLS: u64 = MAX_FRAMES * 80 * 24;

/// The recording as it is written.
pub struct Cast<'a> {
    out: &'a mut dyn Write,
    /// The last frame written: unchanged cells (and frames) are not written again.
    last: Option<Buffer>,
    /// Frames written so far.
    frames: u64,
    /// Cells of the frames looked at so far.
    cells: u64,
    /// Seconds of holds so far, added to the ticks' time.
    held: f64,
    /// The same screens for an animated SVG (`replay --svg`).
    film: Option<&'a mut crate::film::Film>,
}

/// Seconds after the start at `ticks` with `held` seconds of holds, to the microsecond
/// (rounding keeps the order).
fn time(ticks: u64, held: f64) -> String {
    format!("{:.6}", ticks as f64 / f64::from(TICKS_PER_SECOND) + held)
}

impl<'a> Cast<'a> {
    /// Writes the header for a `width` × `height` terminal.
    pub fn new(out: &'a mut dyn Write, width: u16, height: u16, title: &str) -> io::Result<Self> {
        let header = json!({
            "version": 2,
            "width": width,
            "height": height,
            "title": title,
            "env": {"TERM": "xterm-256color"},
        });
        writeln!(out, "{header}")?;
        Ok(Cast {
            out,
            last: None,
            frames: 0,
            cells: 0,
            held: 0.0,
            film: None,
        })
    }

    /// Records the same screens into `film` too.
    pub fn filming(mut self, film: Option<&'a mut crate::film::Film>) -> Self {
        self.film = film;
        self
    }

    fn event(&mut self, ticks: u64, kind: &str, data: &str) -> io::Result<()> {
        let data = serde_json::Value::from(data);
        writeln!(self.out, "[{}, \"{kind}\", {data}]", time(ticks, self.held))
    }

    /// The screen at `ticks`, if it changed: the cells that differ from the last frame's
    /// (the first frame and the first after a resize clear the screen, hide the cursor and
    /// write every cell).
    pub fn frame(&mut self, ticks: u64, buf: &Buffer) -> io::Result<()> {
        self.cells += u64::from(buf.area.area());
        if self.cells > MAX_CELLS {
            return Err(io::Error::other(crate::files::BoundReached {
                message: format!(
                    "--asciicast reached its bound of {MAX_CELLS} cells looked at (an hour of an 80x24 screen at {TICKS_PER_SECOND} a second)"
                ),
            }));
        }
        let changes = ansi_changes(self.last.as_ref(), buf);
        if changes.is_empty() {
            return Ok(());
        }
        if self.frames >= MAX_FRAMES {
            return Err(io::Error::other(crate::files::BoundReached {
                message: format!(
                    "--asciicast reached its bound of {MAX_FRAMES} frames (an hour at {TICKS_PER_SECOND} a second)"
                ),
            }));
        }
        self.frames += 1;
        if let Some(film) = self.film.as_deref_mut() {
            film.frame(ticks as f64 / f64::from(TICKS_PER_SECOND) + self.held, buf)?;
        }
        let clear = if self.last.is_none() {
            "\x1b[?25l\x1b[2J"
        } else {
            ""
        };
        self.event(ticks, "o", &format!("{clear}{changes}"))?;
        // Into the last frame's cells, not a fresh copy: a huge screen's frame is tens of MB.
        match &mut self.last {
            Some(last) => {
                last.area = buf.area;
                last.content.clone_from(&buf.content);
            }
            None => self.last = Some(buf.clone()),
        }
        Ok(())
    }

    /// The terminal is now `width` × `height`: the next frame is drawn on a cleared screen.
    pub fn resize(&mut self, ticks: u64, width: u16, height: u16) -> io::Result<()> {
        self.last = None;
        self.event(ticks, "r", &format!("{width}x{height}"))
    }

    /// What is on screen stays `seconds` longer before the next event.
    pub fn hold(&mut self, seconds: f64) {
        self.held += seconds;
    }

    /// A marker (a snapshot's label): the player can jump to it.
    pub fn marker(&mut self, ticks: u64, label: &str) -> io::Result<()> {
        self.event(ticks, "m", label)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_are_ticks_at_the_explorers_rate() {
        assert_eq!(time(0, 0.0), "0.000000");
        assert_eq!(time(30, 0.0), "1.000000");
        assert_eq!(time(1, 0.0), "0.033333");
        assert_eq!(time(2, 0.5), "0.566667");
    }

    /// The issue's script (`resize 1000x1000`, `tick 10000000`) wrote 783 MB in 60 s. A
    /// 1000×1000 screen is a million cells a frame, so the bound, an hour of an 80×24 screen,
    /// is met at the 208th frame looked at, changed or not, with an error that names it and
    /// nothing written for that frame. The count starts where 205 frames would have left it:
    /// drawing them is ~30 s of CPU and adds nothing to what is checked.
    #[test]
    fn a_huge_screen_meets_the_cells_bound_after_about_200_frames() {
        use ratatui::layout::Rect;
        assert_eq!(MAX_CELLS, 207_360_000);
        let mut out = Vec::new();
        let mut cast = Cast::new(&mut out, 1000, 1000, "t").unwrap();
        let mut buf = Buffer::empty(Rect::new(0, 0, 1000, 1000));
        cast.cells = 205_000_000;
        // The 206th frame (the first written), then the 207th, unchanged: counted, not written.
        cast.frame(1, &buf).unwrap();
        cast.frame(2, &buf).unwrap();
        assert_eq!((cast.cells, cast.frames), (207_000_000, 1));
        buf[(5, 5)].set_symbol("x");
        let err = cast.frame(3, &buf).unwrap_err();
        assert_eq!(
            crate::files::bound_reached(&err).as_deref(),
            Some(
                "--asciicast reached its bound of 207360000 cells looked at (an hour of an 80x24 screen at 30 a second)"
            )
        );
        assert_eq!(cast.frames, 1);
        drop(cast);
        // The header and the one frame written.
        assert_eq!(out.iter().filter(|&&b| b == b'\n').count(), 2);
    }
}
