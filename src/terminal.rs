//! The terminal: raw mode, alternate screen, mouse capture, bracketed paste; always restored
//! (quit, panic, SIGTERM, SIGHUP) and taken back on SIGCONT. The event loop is the one every
//! explorer runs ([`drive()`]); here its terminal side: at most one frame in flight (see
//! [`pace`]), keys read by [`input`], Ctrl-Z and the signals.

use crate::app::App;
use crate::session::{Explorer, SharedRecorder, lock, new_recorder};
use crossterm::event::{
    DisableBracketedPaste, DisableMouseCapture, EnableBracketedPaste, EnableMouseCapture, Event,
    KeyCode, KeyModifiers,
};
use crossterm::terminal::{
    BeginSynchronizedUpdate, EndSynchronizedUpdate, EnterAlternateScreen, LeaveAlternateScreen,
    disable_raw_mode, enable_raw_mode,
};
use crossterm::{cursor, execute};
use ratatui::backend::CrosstermBackend;
use std::io::{self, Stdout, Write};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
use std::time::{Duration, Instant};

pub mod drive;
pub mod input;
pub mod pace;
pub mod plain;
use drive::{Link, Turn, Waited, drive};
use input::Reader;
use pace::Flight;

/// Puts the terminal back as it was. Safe to call more than once and on a dead terminal.
pub fn restore() {
    let mut out = io::stdout();
    let _ = execute!(
        out,
        EndSynchronizedUpdate,
        DisableMouseCapture,
        DisableBracketedPaste,
        LeaveAlternateScreen,
        cursor::Show
    );
    let _ = disable_raw_mode();
    let _ = out.flush();
}

fn setup(mouse: bool) -> io::Result<CrosstermBackend<Stdout>> {
    restore_on_panic(restore);
    enter(mouse)?;
    Ok(CrosstermBackend::new(io::stdout()))
}

/// A panic puts the terminal back (with `restore`) before its message is printed.
fn restore_on_panic(restore: fn()) {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        restore();
        hook(info);
    }));
}

/// Raw mode, the alternate screen, no cursor, bracketed paste (pasted text arrives as one
/// event, never as keys), and mouse capture if asked.
fn enter(mouse: bool) -> io::Result<()> {
    enable_raw_mode()?;
    let mut out = io::stdout();
    execute!(
        out,
        EnterAlternateScreen,
        cursor::Hide,
        EnableBracketedPaste
    )?;
    if mouse {
        execute!(out, EnableMouseCapture)?;
    }
    Ok(())
}

/// Watches for the terminal hanging up (a killed tmux, a dropped ssh connection). With no
/// controlling terminal (`setsid`) no SIGHUP comes, and crossterm's poll then spins on the
/// dead tty and never returns: so this thread raises the SIGHUP itself, and the signal
/// watcher restores, saves and ends as for any hang-up.
fn watch_hangup(finished: Arc<AtomicBool>) {
    std::thread::spawn(move || {
        while !finished.load(Ordering::Relaxed) {
            if hung_up() {
                let _ = signal_hook::low_level::raise(signal_hook::consts::SIGHUP);
                return;
            }
            std::thread::sleep(Duration::from_millis(200));
        }
    });
}

/// Whether the terminal on stdin has hung up.
fn hung_up() -> bool {
    use rustix::event::{PollFd, PollFlags, Timespec, poll};
    let stdin = io::stdin();
    let mut fds = [PollFd::new(&stdin, PollFlags::IN)];
    let now = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    poll(&mut fds, Some(&now)).is_ok_and(|n| n > 0)
        && fds[0]
            .revents()
            .intersects(PollFlags::HUP | PollFlags::ERR | PollFlags::NVAL)
}

/// Continued (SIGCONT, also after a SIGSTOP this process never saw, whose shell put the
/// terminal back in cooked mode): raw mode again, and a full redraw of a screen that may hold
/// anything now.
fn resume(session: &mut Explorer<CrosstermBackend<Stdout>>) -> io::Result<()> {
    // crossterm skips enabling raw mode while it believes it on: forget that belief first.
    disable_raw_mode()?;
    enter(session.app.mouse_capture())?;
    // Clear, and forget the last frame so the next draw repaints every cell (ratatui's own
    // clear would query the cursor position and wait for the terminal's answer).
    execute!(
        session.term.backend_mut(),
        crossterm::terminal::Clear(crossterm::terminal::ClearType::All)
    )?;
    session.term.swap_buffers();
    session.app.invalidate();
    Ok(())
}

/// Saves a recording: called with the script so far if the terminal dies under the explorer.
pub type SaveRecording = Box<dyn FnOnce(String) + Send>;

/// Runs the explorer until quit or a terminating signal. `fps` caps the frame rate (not the
/// speed of time).
/// Returns the signal (SIGTERM, SIGHUP, SIGINT, …) that ended it, if one did, and with `record` the
/// session as a key script (also after a signal or an error, as far as it got). If the
/// terminal is gone and the process must end without returning, `record` gets that script.
/// With `lesson`, its script is fed in as the session goes (`Explorer::pump_lesson`).
pub fn run(
    app: App,
    theme: crate::theme::Theme,
    fps: u32,
    record: Option<SaveRecording>,
    lesson: Option<crate::lesson::Driver>,
) -> (io::Result<Option<i32>>, Option<String>) {
    let mouse = app.mouse_capture();
    supervise(
        record,
        restore,
        lesson,
        // The analysis pages fill in off this thread: keys never wait for them.
        |recorder| {
            setup(mouse)
                .and_then(|b| Explorer::new(app, theme, b, recorder))
                .map(Explorer::with_worker)
        },
        |session, flags| event_loop(session, fps.clamp(1, 240), flags),
    )
}

/// What every mode does around its event loop: watches terminating signals and a hung-up
/// terminal (each restores the terminal with `restore` and saves the recording so far),
/// `start`s its session with the recorder, feeds a lesson in, runs `event_loop`, and puts the
/// terminal back. Returns the signal that ended it, if one did, and the recording.
fn supervise<B: ratatui::backend::Backend>(
    record: Option<SaveRecording>,
    restore: fn(),
    lesson: Option<crate::lesson::Driver>,
    start: impl FnOnce(Option<SharedRecorder>) -> io::Result<Explorer<B>>,
    event_loop: impl FnOnce(&mut Explorer<B>, &Flags) -> io::Result<()>,
) -> (io::Result<Option<i32>>, Option<String>) {
    let flags = Arc::new(Flags::default());
    let finished = Arc::new(AtomicBool::new(false));
    let recorder = record.is_some().then(new_recorder);
    let lost = Lost {
        finished: Arc::clone(&finished),
        recorder: recorder.clone(),
        save: record,
        restore,
    };
    if let Err(e) = watch_signals(Arc::clone(&flags), lost) {
        return (Err(e), None);
    }
    watch_hangup(Arc::clone(&finished));
    let mut session = match start(recorder) {
        Ok(s) => s,
        Err(e) => {
            restore();
            return (Err(e), None);
        }
    };
    if let Some(d) = lesson {
        session.start_lesson(d);
    }
    let result = event_loop(&mut session, &flags);
    finished.store(true, Ordering::Relaxed);
    restore();
    (
        result.map(|()| match flags.signal.load(Ordering::Relaxed) {
            0 => None,
            n => Some(n),
        }),
        session.take_recording(),
    )
}

/// Signals that end the process by default and can be caught: each ends the explorer with
/// the terminal restored and the recording saved.
const TERMINATING: [i32; 11] = [
    signal_hook::consts::SIGTERM,
    signal_hook::consts::SIGHUP,
    signal_hook::consts::SIGINT,
    signal_hook::consts::SIGQUIT,
    signal_hook::consts::SIGUSR1,
    signal_hook::consts::SIGUSR2,
    signal_hook::consts::SIGALRM,
    signal_hook::consts::SIGVTALRM,
    signal_hook::consts::SIGPROF,
    signal_hook::consts::SIGXCPU,
    signal_hook::consts::SIGXFSZ,
];

/// What the event loop learns from the signal watcher.
#[derive(Default)]
struct Flags {
    stop: AtomicBool,
    /// The terminating signal's number (0: none).
    signal: AtomicI32,
    suspend: AtomicBool,
    resume: AtomicBool,
}

/// What the signal watcher needs if the event loop never comes back.
struct Lost {
    finished: Arc<AtomicBool>,
    recorder: Option<SharedRecorder>,
    save: Option<SaveRecording>,
    /// How this mode puts the terminal back.
    restore: fn(),
}

/// A terminating signal asks the event loop to stop. If the terminal is gone (a dropped ssh
/// connection, a killed tmux), crossterm's `poll` spins on the closed tty and never returns:
/// then, after a grace period, this thread restores what it can, saves the recording so far
/// and ends the process.
fn watch_signals(flags: Arc<Flags>, lost: Lost) -> io::Result<()> {
    let mut signals = signal_hook::iterator::Signals::new(
        TERMINATING
            .iter()
            .chain(&[signal_hook::consts::SIGTSTP, signal_hook::consts::SIGCONT]),
    )?;
    std::thread::spawn(move || {
        let mut pending = signals.forever();
        let terminating = loop {
            match pending.next() {
                Some(signal_hook::consts::SIGTSTP) => flags.suspend.store(true, Ordering::Relaxed),
                Some(signal_hook::consts::SIGCONT) => flags.resume.store(true, Ordering::Relaxed),
                other => break other,
            }
        };
        if let Some(n) = terminating {
            flags.signal.store(n, Ordering::Relaxed);
            flags.stop.store(true, Ordering::Relaxed);
            std::thread::sleep(Duration::from_millis(600));
            if !lost.finished.load(Ordering::Relaxed) {
                (lost.restore)();
                if let (Some(save), Some(r)) = (lost.save, lost.recorder) {
                    save(lock(&r).clone().finish());
                }
                // The terminal may be gone: a failed write must not panic this thread.
                let _ = writeln!(io::stderr(), "turntable: ended by signal {n}");
                std::process::exit(128 + n);
            }
        }
    });
    Ok(())
}

/// The terminal's side of the loop ([`drive`]): signals, suspension, the frame in flight (see
/// [`pace`]), and the keys, the mouse, pastes (bounded) and resizes, read here and not by
/// crossterm.
struct Local<'a> {
    flags: &'a Flags,
    input: Reader,
    flight: Flight,
    fps: u32,
    mouse_on: bool,
}

/// Whether `ev` is Ctrl-Z: raw mode turns off the terminal's own, so the loop suspends as it
/// would.
fn ctrl_z(ev: &Event) -> bool {
    matches!(ev, Event::Key(k)
        if k.code == KeyCode::Char('z') && k.modifiers.contains(KeyModifiers::CONTROL))
}

/// A signal's word to the loop: stop, or suspend (`suspend`) and take the terminal back
/// (`resume`, also after a SIGSTOP this process never saw).
fn signalled(
    flags: &Flags,
    suspend: impl FnOnce() -> io::Result<()>,
    resume: impl FnOnce() -> io::Result<()>,
) -> io::Result<Turn> {
    if flags.stop.load(Ordering::Relaxed) {
        return Ok(Turn::Stop(String::new()));
    }
    if flags.suspend.swap(false, Ordering::Relaxed) {
        suspend()?;
        flags.resume.store(true, Ordering::Relaxed);
    }
    if flags.resume.swap(false, Ordering::Relaxed) {
        resume()?;
        return Ok(Turn::Resumed);
    }
    Ok(Turn::Go)
}

/// Everything standard input has queued, after a wait of up to `timeout` for the first.
fn read_all(input: &mut Reader, timeout: Duration) -> io::Result<Vec<Event>> {
    let mut queued = vec![];
    if input.poll(timeout)? {
        // Take everything queued before drawing again, so held keys cannot lag.
        queued.extend(std::iter::from_fn(|| input.read()));
        while input.poll(Duration::ZERO)? {
            queued.extend(std::iter::from_fn(|| input.read()));
        }
    }
    Ok(queued)
}

impl Link<CrosstermBackend<Stdout>> for Local<'_> {
    fn turn(&mut self, session: &mut Explorer<CrosstermBackend<Stdout>>) -> io::Result<Turn> {
        signalled(
            self.flags,
            || {
                restore();
                signal_hook::low_level::emulate_default_handler(signal_hook::consts::SIGTSTP)
            },
            || resume(session),
        )
    }

    fn free(&self) -> bool {
        !self.flight.awaiting()
    }

    fn gap(&self) -> Duration {
        self.flight.gap(self.fps)
    }

    fn show(
        &mut self,
        session: &mut Explorer<CrosstermBackend<Stdout>>,
        draw: bool,
    ) -> io::Result<bool> {
        if session.app.mouse_capture() != self.mouse_on {
            self.mouse_on = session.app.mouse_capture();
            if self.mouse_on {
                execute!(session.term.backend_mut(), EnableMouseCapture)?;
            } else {
                execute!(session.term.backend_mut(), DisableMouseCapture)?;
            }
        }
        if draw {
            execute!(session.term.backend_mut(), BeginSynchronizedUpdate)?;
            session.draw()?;
            execute!(session.term.backend_mut(), EndSynchronizedUpdate)?;
            self.flight.sent();
        }
        Ok(draw)
    }

    fn wait(
        &mut self,
        _session: &mut Explorer<CrosstermBackend<Stdout>>,
        wake: Instant,
    ) -> io::Result<Waited> {
        let timeout = if self.flight.awaiting() {
            // Nothing more is written until the frame has arrived; keys stay queued.
            pace::ask(&mut self.flight, &mut self.input)?;
            Duration::ZERO
        } else {
            wake.saturating_duration_since(Instant::now())
        };
        read_all(&mut self.input, timeout).map(Waited::Events)
    }

    fn apply(
        &mut self,
        session: &mut Explorer<CrosstermBackend<Stdout>>,
        ev: Event,
    ) -> io::Result<bool> {
        match ev {
            ev if ctrl_z(&ev) => self.flags.suspend.store(true, Ordering::Relaxed),
            Event::Key(k) => session.key(k),
            Event::Mouse(m) => {
                // The mouse maps through the canvas as drawn, so a changed screen is drawn
                // first: a frame in flight like any other.
                let draws = session.app.needs_redraw();
                if draws {
                    execute!(session.term.backend_mut(), BeginSynchronizedUpdate)?;
                }
                session.mouse(m)?;
                if draws {
                    execute!(session.term.backend_mut(), EndSynchronizedUpdate)?;
                    self.flight.sent();
                }
                return Ok(draws);
            }
            Event::Resize(w, h) => session.resized(w, h),
            // Pasted text is not keys (a `q` in it would quit): ignored, and left out of the
            // recording as it leaves the screen alone. At the save prompt it is the name: its
            // letters are typed (and recorded as such).
            Event::Paste(text) => {
                session.paste(&text);
            }
            _ => {}
        }
        Ok(false)
    }
}

fn event_loop(
    session: &mut Explorer<CrosstermBackend<Stdout>>,
    fps: u32,
    flags: &Flags,
) -> io::Result<()> {
    let mut local = Local {
        flags,
        input: Reader::new()?,
        flight: Flight::default(),
        fps,
        mouse_on: session.app.mouse_capture(),
    };
    drive(session, &mut local).map(|_| ())
}
