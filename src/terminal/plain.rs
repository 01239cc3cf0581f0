//! Plain mode's loop (`--plain`): keys from the terminal, ticks by wall-clock time, and what
//! changed written as lines of text (see [`crate::ui::plain`]) — no alternate screen, no
//! cursor movement, no colour, so a screen reader reads stdout line by line. The terminal is
//! in raw mode for the keys only, with output processing kept (a `\n` starts a new line), and
//! is restored on quit, panic and every terminating signal, as the explorer's is.

use super::drive::{Link, Turn, Waited};
use super::{Flags, SaveRecording};
use crate::app::App;
use crate::session::{Explorer, Pumped};
use crate::ui::plain::{Seen, opening};
use crossterm::event::Event;
use crossterm::terminal::{disable_raw_mode, enable_raw_mode};
use ratatui::backend::TestBackend;
use std::io::{self, Write};
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

/// Puts the terminal back as it was: only the mode, as plain mode changed nothing else (and
/// writes no escape sequence).
pub fn restore() {
    let _ = disable_raw_mode();
    let _ = io::stdout().flush();
}

/// Raw mode for the keys (no echo, no line editing, Ctrl-C and Ctrl-Z as keys), with the
/// terminal's output processing back on so that lines end as lines.
fn enter() -> io::Result<()> {
    enable_raw_mode()?;
    use rustix::termios::{OptionalActions, OutputModes, tcgetattr, tcsetattr};
    let stdin = io::stdin();
    let mut t = tcgetattr(&stdin)?;
    t.output_modes |= OutputModes::OPOST | OutputModes::ONLCR;
    tcsetattr(&stdin, OptionalActions::Now, &t)?;
    Ok(())
}

/// Runs plain mode until quit or a terminating signal; returns as [`super::run`] does. The
/// app lives in a session on an off-screen terminal of the real one's size, never shown: a
/// lesson's mouse steps and a recording need one, and `--record` then replays to the same
/// screens.
pub fn run(
    app: App,
    theme: crate::theme::Theme,
    record: Option<SaveRecording>,
    lesson: Option<crate::lesson::Driver>,
) -> (io::Result<Option<i32>>, Option<String>) {
    super::supervise(
        record,
        restore,
        lesson,
        |recorder| {
            super::restore_on_panic(restore);
            let (w, h) = crossterm::terminal::size().unwrap_or(crate::replay::DEFAULT_SIZE);
            enter().and_then(|()| {
                // The analysis pages compute off this thread, as in the explorer: their
                // numbers are said when they arrive (`ui::pages::summary`), and keys never
                // wait for them.
                Explorer::new(app, theme, TestBackend::new(w, h), recorder)
                    .map(Explorer::with_worker)
                    .map_err(|e| match e {})
            })
        },
        event_loop,
    )
}

/// Writes what changed since `seen`, and remembers the new state.
fn say(app: &App, seen: &mut Seen, out: &mut impl Write) -> io::Result<()> {
    for line in seen.news(app) {
        writeln!(out, "{line}")?;
    }
    Ok(())
}

/// Plain mode's side of the loop ([`super::drive`]): what changed said as lines after every
/// step of time or of the lesson and every turn of the loop, no frames (its link is never free for one), and
/// the signals as the explorer's.
struct Lines<'a> {
    flags: &'a Flags,
    input: super::input::Reader,
    out: io::Stdout,
    seen: Seen,
}

impl Link<TestBackend> for Lines<'_> {
    fn turn(&mut self, _session: &mut Explorer<TestBackend>) -> io::Result<Turn> {
        super::signalled(
            self.flags,
            || {
                restore();
                signal_hook::low_level::emulate_default_handler(signal_hook::consts::SIGTSTP)
            },
            || {
                // crossterm skips enabling raw mode while it believes it on.
                disable_raw_mode()?;
                enter()
            },
        )
    }

    fn pumped(&mut self, session: &mut Explorer<TestBackend>, _: Pumped) -> io::Result<()> {
        say(&session.app, &mut self.seen, &mut self.out)
    }

    fn free(&self) -> bool {
        false
    }

    fn gap(&self) -> Duration {
        Duration::ZERO
    }

    fn show(&mut self, session: &mut Explorer<TestBackend>, _draw: bool) -> io::Result<bool> {
        say(&session.app, &mut self.seen, &mut self.out)?;
        self.out.flush()?;
        Ok(false)
    }

    fn wait(&mut self, _session: &mut Explorer<TestBackend>, wake: Instant) -> io::Result<Waited> {
        let timeout = wake.saturating_duration_since(Instant::now());
        super::read_all(&mut self.input, timeout).map(Waited::Events)
    }

    fn apply(&mut self, session: &mut Explorer<TestBackend>, ev: Event) -> io::Result<bool> {
        match ev {
            ev if super::ctrl_z(&ev) => self.flags.suspend.store(true, Ordering::Relaxed),
            // Said by the loop's `show`, once the lesson's steps the key let go are applied:
            // Enter after a wait said "playing from τ" for a scene the lesson then replaced.
            Event::Key(k) => session.key(k),
            Event::Resize(w, h) => session.resize(w, h),
            // No mouse capture, no pasted keys: nothing else is an input here.
            _ => {}
        }
        Ok(false)
    }
}

fn event_loop(session: &mut Explorer<TestBackend>, flags: &Flags) -> io::Result<()> {
    let mut out = io::stdout();
    for line in opening(&session.app) {
        writeln!(out, "{line}")?;
    }
    out.flush()?;
    let mut lines = Lines {
        flags,
        seen: Seen::of(&session.app),
        // Keys read here, not by crossterm: a paste start cannot swallow them (`super::input`).
        input: super::input::Reader::new()?,
        out,
    };
    super::drive::drive(session, &mut lines).map(|_| ())
}
