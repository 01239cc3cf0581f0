//! Plain mode's loop (`--plain`): keys from the terminal, ticks by wall-clock time, and what
//! changed written as lines of text (see [`crate::ui::plain`]) — no alternate screen, no
//! cursor movement, no colour, so a screen reader reads stdout line by line. The terminal is
//! in raw mode for the keys only, with output processing kept (a `\n` starts a new line), and
//! is restored on quit, panic and every terminating signal, as the explorer's is.

use super::pace::Clock;
use super::{Flags, SaveRecording};
use crate::app::App;
use crate::session::Session;
use crate::ui::plain::{Seen, describe, opening};
use crossterm::event::{Event, KeyCode, KeyModifiers};
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
                Session::new(app, theme, TestBackend::new(w, h), recorder)
                    .map(Session::with_worker)
                    .map_err(|e| match e {})
            })
        },
        event_loop,
    )
}

/// Writes what changed since `seen`, and remembers the new state.
fn say(app: &App, seen: &mut Seen, out: &mut impl Write) -> io::Result<()> {
    let now = Seen::of(app);
    for line in describe(seen, &now) {
        writeln!(out, "{line}")?;
    }
    *seen = now;
    Ok(())
}

fn event_loop(session: &mut Session<TestBackend>, flags: &Flags) -> io::Result<()> {
    let mut out = io::stdout();
    for line in opening(&session.app) {
        writeln!(out, "{line}")?;
    }
    out.flush()?;
    let mut seen = Seen::of(&session.app);
    let mut clock = Clock::new(Instant::now());
    // Keys read here, not by crossterm: a paste start cannot swallow them (`super::input`).
    let mut input = super::input::Reader::new()?;
    while !session.app.should_quit() && !flags.stop.load(Ordering::Relaxed) {
        if flags.suspend.swap(false, Ordering::Relaxed) {
            restore();
            signal_hook::low_level::emulate_default_handler(signal_hook::consts::SIGTSTP)?;
            flags.resume.store(true, Ordering::Relaxed);
        }
        if flags.resume.swap(false, Ordering::Relaxed) {
            // crossterm skips enabling raw mode while it believes it on.
            disable_raw_mode()?;
            enter()?;
            clock.restart(Instant::now());
        }
        let Ok(_) = session.pump_lesson();
        session.ask_analysis();
        say(&session.app, &mut seen, &mut out)?;
        if session.is_playing() {
            for _ in 0..clock.due(Instant::now()) {
                if !session.is_playing() {
                    break;
                }
                session.tick();
                let Ok(_) = session.pump_lesson();
                say(&session.app, &mut seen, &mut out)?;
            }
        }
        out.flush()?;
        let mut wake = Instant::now() + Duration::from_millis(250);
        if session.is_playing() {
            wake = wake.min(clock.next());
        }
        // A page's pieces are taken as they arrive, as in the explorer's loop.
        if session.analysis.busy() {
            wake = wake.min(Instant::now() + super::PIECES_POLL);
        }
        if input.poll(wake.saturating_duration_since(Instant::now()))? {
            let mut queued: Vec<Event> = std::iter::from_fn(|| input.read()).collect();
            while input.poll(Duration::ZERO)? {
                queued.extend(std::iter::from_fn(|| input.read()));
            }
            for ev in queued {
                match ev {
                    Event::Key(k)
                        if k.code == KeyCode::Char('z')
                            && k.modifiers.contains(KeyModifiers::CONTROL) =>
                    {
                        flags.suspend.store(true, Ordering::Relaxed);
                    }
                    Event::Key(k) => {
                        session.key(k);
                        say(&session.app, &mut seen, &mut out)?;
                    }
                    Event::Resize(w, h) => session.resize(w, h),
                    // No mouse capture, no pasted keys: nothing else is an input here.
                    _ => {}
                }
            }
            out.flush()?;
        }
        if !session.is_playing() {
            clock.restart(Instant::now());
        }
    }
    Ok(())
}
