//! The explorer's one event loop, for the terminal, plain mode and each `serve` client alike:
//! time passes by ticks counted from the wall clock while playing (and none while paused or
//! suspended), the lesson is fed in as they pass, the analysis pages' pieces are taken as they
//! arrive, a frame is drawn when the app changed, the link is free (the last frame arrived)
//! and the frame rate allows, and the loop waits for input until the next of these falls due.
//! Where input comes from and where a frame goes is the backend's: a [`Link`].

use super::pace::{Clock, coalesce_drags};
use crate::session::{Explorer, Pumped};
use crossterm::event::Event;
use ratatui::backend::Backend;
use std::convert::Infallible;
use std::io;
use std::time::{Duration, Instant};

/// How often the loop looks for the analysis pages' pieces while they are coming: a key's page
/// completes within this of its last piece (not a tick, 33 ms, later).
pub const PIECES_POLL: Duration = Duration::from_millis(2);
/// The longest wait when nothing falls due: a signal or a limit is noticed within it.
const IDLE_WAKE: Duration = Duration::from_millis(250);

/// What a turn begins with.
pub enum Turn {
    Go,
    /// Back from a suspension: the time it stood still is not played.
    Resumed,
    /// The loop ends, and why (said to a served client).
    Stop(String),
}

/// What a wait for input brought.
pub enum Waited {
    /// Events to apply, in order (none if the wait ran out).
    Events(Vec<Event>),
    Stop(String),
}

/// A backend's error as an I/O error: the terminal's and serve's are; an off-screen
/// terminal's (plain mode's) has none.
pub trait IntoIo {
    fn into_io(self) -> io::Error;
}

impl IntoIo for io::Error {
    fn into_io(self) -> io::Error {
        self
    }
}

impl IntoIo for Infallible {
    fn into_io(self) -> io::Error {
        match self {}
    }
}

/// A backend of the loop: where input comes from and where frames go.
pub trait Link<B: Backend> {
    /// At the start of each turn: signals, suspension, a client's limits.
    fn turn(&mut self, s: &mut Explorer<B>) -> io::Result<Turn>;

    /// Whether the session keeps its own time and feeds its own lesson (a served class's
    /// follower takes the presenter's ticks and lesson steps instead).
    fn own_time(&self) -> bool {
        true
    }

    /// A tick was taken, before the lesson moves with it.
    fn ticked(&mut self, _s: &mut Explorer<B>) {}

    /// The lesson was fed (see [`Explorer::pump_lesson`]).
    fn pumped(&mut self, _s: &mut Explorer<B>, _pumped: Pumped) -> io::Result<()> {
        Ok(())
    }

    /// Whether the link can take a frame now (the last one has arrived).
    fn free(&self) -> bool;

    /// The least time between two frames.
    fn gap(&self) -> Duration;

    /// Whether the link has something to lay out at the next frame (a client's new size).
    fn pending(&self) -> bool {
        false
    }

    /// Once a turn: brings the link up to date, drawing a frame if `draw` (the link is free,
    /// a frame is due and the app or the link needs one). Returns whether it drew.
    fn show(&mut self, s: &mut Explorer<B>, draw: bool) -> io::Result<bool>;

    /// When the link must wake whatever else is due (a paste's or a held ESC's end).
    fn deadline(&self) -> Option<Instant> {
        None
    }

    /// Waits for input until `wake` at most.
    fn wait(&mut self, s: &mut Explorer<B>, wake: Instant) -> io::Result<Waited>;

    /// Applies one event; returns whether it drew a frame (a click maps through the screen as
    /// drawn).
    fn apply(&mut self, s: &mut Explorer<B>, ev: Event) -> io::Result<bool>;
}

/// Runs the loop until the app quits or the link stops it; returns why it ended ("bye" for a
/// quit).
pub fn drive<B, L>(s: &mut Explorer<B>, link: &mut L) -> io::Result<String>
where
    B: Backend,
    B::Error: IntoIo,
    L: Link<B>,
{
    let mut clock = Clock::new(Instant::now());
    let mut last_frame: Option<Instant> = None;
    loop {
        if s.app.should_quit() {
            return Ok("bye".into());
        }
        match link.turn(s)? {
            Turn::Go => {}
            Turn::Resumed => clock.restart(Instant::now()),
            Turn::Stop(why) => return Ok(why),
        }
        let own = link.own_time();
        if own {
            // A lesson's steps that are due (never a wait: it holds as state, the loop goes on).
            pump(s, link)?;
            // Time passes only through ticks, and a recording counts them (a replay of it
            // needs no clock); as many are due as wall-clock time says, however few frames
            // get drawn.
            if s.is_playing() {
                for _ in 0..clock.due(Instant::now()) {
                    if !s.is_playing() {
                        break;
                    }
                    s.tick();
                    link.ticked(s);
                    // A lesson's `tick N` ends on its own tick, not a frame later.
                    pump(s, link)?;
                }
            }
        }
        // Pieces are taken as they arrive, not at the next tick: a page's next job (the map
        // after its curve) is asked for at once, and its last piece drawn without waiting.
        if s.analysis.busy() {
            s.ask_analysis();
        }
        let now = Instant::now();
        let due = last_frame.map_or(now, |t| t + link.gap());
        let wanted = s.app.needs_redraw() || link.pending();
        if link.show(s, wanted && link.free() && now >= due)? {
            last_frame = Some(now);
        }
        // Paused and drawn: wait for input (waking now and then to notice signals and limits).
        let mut wake = now + IDLE_WAKE;
        if own && s.is_playing() {
            wake = wake.min(clock.next());
        }
        if s.analysis.busy() {
            wake = wake.min(now + PIECES_POLL);
        }
        if (s.app.needs_redraw() || link.pending()) && link.free() {
            wake = wake.min(due.max(now));
        }
        if let Some(d) = link.deadline() {
            wake = wake.min(d);
        }
        match link.wait(s, wake)? {
            Waited::Stop(why) => return Ok(why),
            Waited::Events(events) => {
                for ev in coalesce_drags(events) {
                    if link.apply(s, ev)? {
                        last_frame = Some(Instant::now());
                    }
                }
            }
        }
        if !own || !s.is_playing() {
            clock.restart(Instant::now());
        }
    }
}

fn pump<B, L>(s: &mut Explorer<B>, link: &mut L) -> io::Result<()>
where
    B: Backend,
    B::Error: IntoIo,
    L: Link<B>,
{
    let pumped = s.pump_lesson().map_err(IntoIo::into_io)?;
    link.pumped(s, pumped)
}
