//! Frame pacing over any link. Time keeps wall-clock time whatever the frame rate: ticks are
//! caught up and frames dropped, never the other way round. And at most one frame is in
//! flight: after a frame the loop asks the terminal where its cursor is; the answer travels
//! behind the frame, so it means the frame arrived, and only then is the next one drawn.
//! Over ssh (whose buffers never push back on `write`) a key then waits for one frame at
//! most, not for a backlog of them.

use crossterm::event::{Event, MouseEventKind};
use std::time::{Duration, Instant};

use crate::app::TICKS_PER_SECOND;
/// Ticks caught up at once: more than a wait for an answer (2 s) or the first screen over a
/// 4 KB/s link (4 s). A longer gap is a stall (a stopped process, a slow machine), and its
/// time is dropped rather than integrated in one burst.
pub const MAX_CATCH_UP: u32 = 5 * TICKS_PER_SECOND;
/// Frames per second for a terminal that never answers its cursor-position query.
pub const FALLBACK_FPS: u32 = 4;
/// Unanswered queries (each waits crossterm's 2 s) before a terminal that has never answered
/// is taken for one that never will. The first screen is the largest frame: over a 4 KB/s
/// link it takes about 4 s to arrive.
pub const FIRST_WAITS: u32 = 3;

/// Counts the ticks due by wall-clock time.
#[derive(Clone, Copy, Debug)]
pub struct Clock {
    base: Instant,
    done: u64,
}

impl Clock {
    pub fn new(now: Instant) -> Clock {
        Clock { base: now, done: 0 }
    }

    /// No time passes before `now` (paused, or back from a suspension).
    pub fn restart(&mut self, now: Instant) {
        *self = Clock::new(now);
    }

    /// The ticks due since the last call: as many as wall-clock time asks, up to
    /// [`MAX_CATCH_UP`] (the rest is dropped).
    pub fn due(&mut self, now: Instant) -> u32 {
        let period = Duration::from_secs(1) / TICKS_PER_SECOND;
        let total =
            (now.saturating_duration_since(self.base).as_nanos() / period.as_nanos()) as u64;
        let n = total.saturating_sub(self.done);
        if n > u64::from(MAX_CATCH_UP) {
            self.restart(now);
            return MAX_CATCH_UP;
        }
        self.done = total;
        n as u32
    }

    /// When the next tick falls due.
    pub fn next(&self) -> Instant {
        self.base + Duration::from_secs(1) / TICKS_PER_SECOND * (self.done + 1) as u32
    }
}

/// The frame in flight, told apart from answers owed to earlier queries (a query that timed
/// out is still answered later, and that answer must not release the next frame).
#[derive(Clone, Copy, Debug, Default)]
pub struct Flight {
    /// Queries sent whose answers have not been read.
    owed: u32,
    /// Of those, the ones sent before the frame in flight.
    stale: u32,
    /// A frame was sent and its arrival is not confirmed.
    awaiting: bool,
    /// The terminal has answered once: it will again, however slow the link.
    answers: bool,
    /// Unanswered waits of a terminal that has never answered.
    waits: u32,
    /// The terminal never answers: frames go at [`FALLBACK_FPS`], unconfirmed.
    fallback: bool,
}

impl Flight {
    /// A frame was written: answers owed so far do not confirm it.
    pub fn sent(&mut self) {
        self.stale = self.owed;
        self.awaiting = !self.fallback;
    }

    /// Whether the last frame is still on its way (draw nothing until it arrives).
    pub fn awaiting(&self) -> bool {
        self.awaiting
    }

    pub fn fallback(&self) -> bool {
        self.fallback
    }

    /// A query was sent.
    pub fn asked(&mut self) {
        self.owed += 1;
    }

    /// An answer was read: the oldest owed one.
    pub fn answered(&mut self) {
        self.owed = self.owed.saturating_sub(1);
        self.answers = true;
        if self.stale > 0 {
            self.stale -= 1;
        } else {
            self.awaiting = false;
        }
    }

    /// A wait ended with no answer. A terminal that answers is only slow: keep waiting.
    pub fn timed_out(&mut self) {
        if !self.answers {
            self.waits += 1;
            if self.waits >= FIRST_WAITS {
                self.fallback = true;
                self.awaiting = false;
            }
        }
    }

    /// The least time between two frames for a frame-rate cap of `fps`.
    pub fn gap(&self, fps: u32) -> Duration {
        let fps = if self.fallback {
            fps.min(FALLBACK_FPS)
        } else {
            fps
        };
        Duration::from_secs(1) / fps.max(1)
    }
}

/// Events queued together, each run of mouse drags folded into its last: a drag redraws
/// before it applies (see `Explorer::mouse`), and a backlog of drags would be a backlog of
/// frames.
pub fn coalesce_drags(events: Vec<Event>) -> Vec<Event> {
    let drag =
        |e: &Event| matches!(e, Event::Mouse(m) if matches!(m.kind, MouseEventKind::Drag(_)));
    let mut out: Vec<Event> = Vec::with_capacity(events.len());
    for e in events {
        if drag(&e) && out.last().is_some_and(drag) {
            out.pop();
        }
        out.push(e);
    }
    out
}

/// How long a cursor-position query is waited for (as crossterm waited).
pub const ANSWER_WAIT: Duration = Duration::from_secs(2);

/// Asks the terminal where its cursor is and waits (up to [`ANSWER_WAIT`]) for an answer,
/// keeping any keys that come meanwhile queued for the event loop.
pub fn ask(flight: &mut Flight, input: &mut super::input::Reader) -> std::io::Result<()> {
    use std::io::Write;
    flight.asked();
    let mut out = std::io::stdout();
    out.write_all(b"\x1b[6n")?;
    out.flush()?;
    if input.cursor(ANSWER_WAIT)? {
        flight.answered();
    } else {
        // Timed out: the answer may still come.
        flight.timed_out();
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn the_clock_counts_wall_time_whatever_the_frame_rate() {
        let t0 = Instant::now();
        let mut c = Clock::new(t0);
        assert_eq!(c.due(t0 + ms(10)), 0);
        // One frame after a second (a slow link): 30 ticks, not one.
        assert_eq!(c.due(t0 + ms(1010)), 30);
        assert_eq!(c.due(t0 + ms(1030)), 0);
        assert_eq!(c.due(t0 + ms(1040)), 1);
        assert_eq!(c.next(), t0 + Duration::from_secs(1) / 30 * 32);
        // 6 s at once is a stall: five seconds' ticks, the rest dropped.
        assert_eq!(c.due(t0 + ms(7040)), MAX_CATCH_UP);
        assert_eq!(c.due(t0 + ms(7050)), 0);
        assert_eq!(c.due(t0 + ms(7080)), 1);
        c.restart(t0 + ms(9000));
        assert_eq!(c.due(t0 + ms(9020)), 0);
    }

    #[test]
    fn one_frame_in_flight_and_late_answers_do_not_release_the_next() {
        let mut f = Flight::default();
        f.sent();
        assert!(f.awaiting());
        f.asked();
        f.answered();
        assert!(!f.awaiting());
        // A large frame: the first query times out, a second is sent, then both answer.
        f.sent();
        f.asked();
        f.timed_out();
        assert!(f.awaiting(), "it has answered before: only slow");
        f.asked();
        f.answered();
        assert!(!f.awaiting());
        // The second query's answer is still owed: it is stale for the next frame.
        f.sent();
        f.asked();
        f.answered();
        assert!(f.awaiting(), "a late answer released a frame");
        f.answered();
        assert!(!f.awaiting());
        assert!(!f.fallback());
    }

    #[test]
    fn runs_of_drags_fold_into_their_last() {
        use crossterm::event::{KeyModifiers, MouseButton, MouseEvent};
        let m = |kind, column| {
            Event::Mouse(MouseEvent {
                kind,
                column,
                row: 5,
                modifiers: KeyModifiers::NONE,
            })
        };
        let drag = |c| m(MouseEventKind::Drag(MouseButton::Left), c);
        let down = m(MouseEventKind::Down(MouseButton::Left), 1);
        let up = m(MouseEventKind::Up(MouseButton::Left), 9);
        let got = coalesce_drags(vec![
            down.clone(),
            drag(2),
            drag(3),
            drag(4),
            up.clone(),
            drag(7),
        ]);
        assert_eq!(got, vec![down, drag(4), up, drag(7)]);
    }

    #[test]
    fn a_terminal_that_never_answers_falls_back_to_a_low_rate() {
        let mut f = Flight::default();
        f.sent();
        for _ in 0..FIRST_WAITS {
            assert!(f.awaiting());
            f.asked();
            f.timed_out();
        }
        assert!(f.fallback() && !f.awaiting());
        f.sent();
        assert!(!f.awaiting());
        assert_eq!(f.gap(30), ms(250));
        assert_eq!(Flight::default().gap(30), Duration::from_secs(1) / 30);
    }
}
