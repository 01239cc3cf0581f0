//! Bytes the explorer writes to the terminal while it plays: drawn through the real crossterm
//! backend into a counting writer, so what a slow link (ssh) carries is measured, not guessed.

use crate::app::App;
use crate::error::Error;
use crate::scene::Scene;
use crate::theme::{Depth, Theme};
use ratatui::Terminal;
use ratatui::backend::CrosstermBackend;
use serde::Serialize;
use std::cell::Cell;
use std::io::{self, Write};
use std::rc::Rc;

/// The explorer's default frame rate while playing.
pub const FPS: f64 = 30.0;
/// The budget for a slow link.
pub const GOAL_KB_PER_S: f64 = 30.0;

/// A writer that only counts, into a counter the caller keeps.
pub(super) struct Count(Rc<Cell<usize>>);

/// A terminal of `size` drawing through the real crossterm backend into a byte counter.
pub(super) type Counted = Terminal<CrosstermBackend<Count>>;

pub(super) fn counted(size: (u16, u16)) -> Result<(Counted, Rc<Cell<usize>>), Error> {
    let count = Rc::new(Cell::new(0));
    let backend = CrosstermBackend::new(Count(Rc::clone(&count)));
    let term = Terminal::with_options(
        backend,
        ratatui::TerminalOptions {
            viewport: ratatui::Viewport::Fixed(ratatui::layout::Rect::new(0, 0, size.0, size.1)),
        },
    )?;
    Ok((term, count))
}

/// Draws `app` as the explorer does.
pub(super) fn draw(term: &mut Counted, app: &mut App, th: &Theme) -> Result<(), Error> {
    crate::session::sync(app, &mut crate::analysis::Analysis::inline(), true);
    let mut geom = Vec::new();
    term.draw(|f| geom = crate::ui::draw(f, app, th))?;
    app.drawn(geom);
    Ok(())
}

impl Write for Count {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0.set(self.0.get() + buf.len());
        Ok(buf.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// One measurement: a theme at a colour depth.
#[derive(Clone, Debug, Serialize)]
pub struct Bytes {
    pub theme: String,
    pub depth: String,
    pub size: (u16, u16),
    pub frames: usize,
    pub bytes_per_frame: f64,
    /// At [`FPS`].
    pub kb_per_s: f64,
}

/// The default scene playing at `size` for `frames` ticks, each drawn as the explorer does
/// (one tick, one draw; the first full frame is not counted).
pub fn measure(theme: &str, depth: Depth, size: (u16, u16), frames: usize) -> Result<Bytes, Error> {
    let th = Theme::builtin(theme)
        .ok_or_else(|| Error::invalid(format!("no theme {theme}")))?
        .with_depth(depth);
    let mut app = App::new(Scene::default_scene());
    let (mut term, count) = counted(size)?;
    draw(&mut term, &mut app, &th)?;
    let start = count.get();
    for _ in 0..frames {
        app.tick();
        draw(&mut term, &mut app, &th)?;
    }
    let bytes = (count.get() - start) as f64 / frames.max(1) as f64;
    Ok(Bytes {
        theme: theme.into(),
        depth: depth.name().into(),
        size,
        frames,
        bytes_per_frame: bytes,
        kb_per_s: bytes * FPS / 1000.0,
    })
}

/// Every built-in theme at both depths, at 120×40 over 10 s of play.
pub fn all(frames: usize) -> Result<Vec<Bytes>, Error> {
    let mut out = Vec::new();
    for theme in crate::theme::BUILTIN {
        for depth in [Depth::TrueColor, Depth::Ansi256] {
            out.push(measure(theme, depth, (120, 40), frames)?);
        }
    }
    Ok(out)
}

/// The worst an `--asciicast` recording writes per tick at one screen size: every tick that
/// changes the screen writes a frame, and a frame is the whole screen as ANSI text (JSON
/// escaped), so the worst case per tick is the largest frame; with the recording's bounds.
#[derive(Clone, Debug, Serialize)]
pub struct CastBytes {
    /// The theme whose frames were largest.
    pub theme: String,
    pub size: (u16, u16),
    /// Ticks played (the default scene, from its start).
    pub ticks: usize,
    /// The largest frame, with its event's framing: bytes written by one tick at worst.
    pub worst_bytes_per_tick: usize,
    /// `replay::CAST_BYTES_MAX`.
    pub bound_bytes: u64,
    /// `asciicast::MAX_FRAMES`.
    pub bound_frames: u64,
    /// Ticks after which the worst case reaches a bound (bytes or frames, the first).
    pub ticks_to_bound: u64,
}

/// A writer that keeps the longest line written through it.
struct Lines {
    line: usize,
    longest: usize,
}

impl Write for Lines {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        for &b in buf {
            self.line += 1;
            if b == b'\n' {
                self.longest = self.longest.max(self.line);
                self.line = 0;
            }
        }
        Ok(buf.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// The default scene played for `ticks` at `size` and recorded as `replay --asciicast` does
/// (its first screen, then a frame a tick; not the text snapshot a replay ends with, nor its
/// last frame, the same screen again: two draws of four, and a whole screen as text, saved),
/// for every built-in theme (24-bit colour, as a replay's `--ansi` writes): the worst.
pub fn cast_worst(size: (u16, u16), ticks: usize) -> Result<CastBytes, Error> {
    let mut worst = (0, String::new());
    for theme in crate::theme::BUILTIN {
        let th =
            Theme::builtin(theme).ok_or_else(|| Error::invalid(format!("no theme {theme}")))?;
        let app = App::new(Scene::default_scene());
        let mut s = crate::session::Explorer::headless(app, th, size.0, size.1, false);
        let mut lines = Lines {
            line: 0,
            longest: 0,
        };
        let mut cast = crate::asciicast::Cast::new(&mut lines, size.0, size.1, "bench")?;
        cast.frame(0, s.screen())?;
        crate::replay::tick_frames(&mut s, ticks as u64, &mut 0, &mut cast)?;
        drop(cast);
        if lines.longest > worst.0 {
            worst = (lines.longest, theme.to_string());
        }
    }
    let bound_bytes = crate::replay::CAST_BYTES_MAX;
    let bound_frames = crate::asciicast::MAX_FRAMES;
    Ok(CastBytes {
        theme: worst.1,
        size,
        ticks,
        worst_bytes_per_tick: worst.0,
        bound_bytes,
        bound_frames,
        ticks_to_bound: (bound_bytes / worst.0.max(1) as u64).min(bound_frames),
    })
}
