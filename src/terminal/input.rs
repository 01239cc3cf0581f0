//! Keys from a terminal, local or over SSH: one decoder for both, reading bytes here rather
//! than by crossterm's event reader, so that a bracketed paste is bounded. crossterm's parser, after `ESC[200~`, keeps every byte
//! until `ESC[201~` arrives: an unpaired start swallowed every key, `q` and Ctrl-C included,
//! for good. Here a paste ends at `ESC[201~`; at a Ctrl-C byte (which then reaches the
//! program as Ctrl-C); when its bytes stop coming for [`PASTE_IDLE`]; or [`PASTE_TIME`] after
//! it began. Its text is kept up to [`PASTE_MAX`] bytes (the rest is dropped, not kept).
//!
//! [`Decoder`] turns bytes into crossterm's own `Event`s as crossterm's parser does (keys,
//! SGR and X10 mouse reports, focus, the cursor-position answer frame pacing waits for) and is
//! pure: bytes and instants in, events out, so tests feed it without a terminal. [`Reader`]
//! reads standard input into it and watches SIGWINCH for resizes; `serve` feeds it each SSH
//! message a client sends. Around the grammar, the rules both need: a paste bounded in bytes
//! and time, ESC ESC read as the Esc key and what the second ESC begins, and replies to
//! terminal queries never read as keys (a cursor-position answer is an [`Input::Cursor`], for
//! frame pacing; any other reply is dropped).
//!
//! The byte grammar follows crossterm 0.29's `event/sys/unix/parse.rs` (MIT), trimmed to the
//! sequences a terminal sends to a program that asks for no keyboard enhancement.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use seq::{Parsed, parse};
use std::collections::VecDeque;
use std::io;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

mod paste;
mod seq;

pub use paste::{PASTE_END, PASTE_START};
use paste::{Paste, Step};

/// Most bytes of a paste kept (the rest is dropped; the paste goes on to its end).
pub const PASTE_MAX: usize = 1 << 20;
/// A paste whose bytes stop coming for this long is ended (a terminal sends one at once).
pub const PASTE_IDLE: Duration = Duration::from_millis(500);
/// A paste is ended this long after it began, whatever comes.
pub const PASTE_TIME: Duration = Duration::from_secs(3);
/// Longest escape sequence waited for (a longer one is dropped, not kept growing).
const SEQ_MAX: usize = 64;
/// A lone ESC at the end of a read is held this long for the rest of a sequence: a link that
/// splits a terminal's reply (`ESC` | `[30;21R`) must not have its tail read as keys.
pub const ESC_WAIT: Duration = Duration::from_millis(30);

/// What the decoder read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Input {
    Event(Event),
    /// The terminal's answer to a cursor-position query (`ESC[6n`): column and row, 0-based.
    Cursor(u16, u16),
}

/// Bytes in, [`Input`]s out (see the module).
pub struct Decoder {
    /// A sequence begun and not yet complete.
    seq: Vec<u8>,
    paste: Option<Paste>,
    /// How long a lone ESC ending a read is held for the rest of a sequence.
    esc_wait: Duration,
    /// When a lone ESC ending a read becomes the Esc key, if nothing follows it.
    esc_until: Option<Instant>,
    out: VecDeque<Input>,
}

impl Default for Decoder {
    fn default() -> Decoder {
        Decoder::new()
    }
}

fn esc() -> Input {
    Input::Event(Event::Key(KeyEvent::new(KeyCode::Esc, KeyModifiers::NONE)))
}

impl Decoder {
    /// A terminal's decoder: a lone ESC ending a read waits [`ESC_WAIT`] for what may follow.
    pub fn new() -> Decoder {
        Decoder::with_esc_wait(ESC_WAIT)
    }

    /// A decoder whose lone ESC ending a read waits `wait` (zero: it is the Esc key at once,
    /// as for SSH, whose client sends a terminal's sequence whole, in one message).
    pub fn with_esc_wait(wait: Duration) -> Decoder {
        Decoder {
            seq: Vec::new(),
            paste: None,
            esc_wait: wait,
            esc_until: None,
            out: VecDeque::new(),
        }
    }

    /// Takes `bytes` read at `now`; `more` says more were waiting (the read filled its
    /// buffer), so that a lone ESC at the end is not yet taken for the Esc key.
    pub fn feed(&mut self, bytes: &[u8], more: bool, now: Instant) {
        self.expire(now);
        if bytes.is_empty() {
            return;
        }
        self.esc_until = None;
        for (i, &b) in bytes.iter().enumerate() {
            let more = more || i + 1 < bytes.len();
            if self.paste.is_some() {
                self.paste_byte(b, now);
                continue;
            }
            // ESC ESC: the first is the Esc key, the second begins what follows (a reply
            // `ESC[30;21R` behind an Esc is a reply, not `[30;21R` typed).
            if b == 0x1b && self.seq == [0x1b] {
                self.out.push_back(esc());
                self.seq.clear();
            }
            self.seq.push(b);
            if self.seq == [0x1b] && !more {
                if self.esc_wait.is_zero() {
                    self.seq.clear();
                    self.out.push_back(esc());
                } else {
                    self.esc_until = Some(now + self.esc_wait);
                }
                continue;
            }
            if self.seq == PASTE_START {
                self.seq.clear();
                self.paste = Some(Paste::new(now));
                continue;
            }
            match parse(&self.seq, more) {
                Parsed::Done(input) => {
                    self.out.extend(input);
                    self.seq.clear();
                }
                Parsed::More if self.seq.len() < SEQ_MAX => {}
                Parsed::More | Parsed::Bad => self.seq.clear(),
            }
        }
    }

    fn paste_byte(&mut self, b: u8, now: Instant) {
        let Some(p) = self.paste.as_mut() else {
            return;
        };
        match p.byte(b, now) {
            Step::Going => return,
            Step::Ended(text) => self.out.push_back(Input::Event(Event::Paste(text))),
            Step::CtrlC(text) => {
                self.out.push_back(Input::Event(Event::Paste(text)));
                self.out.push_back(Input::Event(Event::Key(KeyEvent::new(
                    KeyCode::Char('c'),
                    KeyModifiers::CONTROL,
                ))));
            }
        }
        self.paste = None;
    }

    /// Ends the paste under way: its text (as kept) is one event.
    fn end_paste(&mut self) {
        if let Some(mut p) = self.paste.take() {
            self.out.push_back(Input::Event(Event::Paste(p.take())));
        }
    }

    /// Ends a paste that has waited past its bounds by `now`; a held ESC past [`ESC_WAIT`] is
    /// the Esc key.
    pub fn expire(&mut self, now: Instant) {
        if self.esc_until.is_some_and(|d| now >= d) {
            self.esc_until = None;
            self.seq.clear();
            self.out.push_back(esc());
        }
        let paste = self.paste.as_ref().map(Paste::deadline);
        if paste.is_some_and(|d| now >= d) {
            self.end_paste();
        }
    }

    /// When the paste under way will be ended, or a held ESC taken for the key, if nothing
    /// comes first.
    pub fn deadline(&self) -> Option<Instant> {
        let paste = self.paste.as_ref().map(Paste::deadline);
        match (paste, self.esc_until) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }

    /// Whether a paste is under way.
    pub fn pasting(&self) -> bool {
        self.paste.is_some()
    }

    /// The next thing read, oldest first.
    pub fn next_input(&mut self) -> Option<Input> {
        self.out.pop_front()
    }

    /// Takes the first cursor-position answer queued, leaving everything else in order.
    pub fn take_cursor(&mut self) -> Option<(u16, u16)> {
        let i = self
            .out
            .iter()
            .position(|x| matches!(x, Input::Cursor(..)))?;
        match self.out.remove(i) {
            Some(Input::Cursor(x, y)) => Some((x, y)),
            _ => None,
        }
    }

    /// Whether an event (not a cursor answer) is queued.
    pub fn has_event(&self) -> bool {
        self.out.iter().any(|x| matches!(x, Input::Event(_)))
    }

    /// The next event, skipping cursor answers nobody waits for any more.
    pub fn next_event(&mut self) -> Option<Event> {
        while let Some(x) = self.out.pop_front() {
            if let Input::Event(e) = x {
                return Some(e);
            }
        }
        None
    }

    /// Every event queued, oldest first (cursor answers left out).
    pub fn events(&mut self) -> Vec<Event> {
        std::iter::from_fn(|| self.next_event()).collect()
    }
}

/// Standard input read into a [`Decoder`], and the terminal's size changes (SIGWINCH).
pub struct Reader {
    decoder: Decoder,
    resized: Arc<AtomicBool>,
}

impl Reader {
    pub fn new() -> io::Result<Reader> {
        let resized = Arc::new(AtomicBool::new(false));
        signal_hook::flag::register(signal_hook::consts::SIGWINCH, Arc::clone(&resized))?;
        Ok(Reader {
            decoder: Decoder::new(),
            resized,
        })
    }

    /// Waits up to `timeout` for an event; true when one is queued for [`Reader::read`].
    pub fn poll(&mut self, timeout: Duration) -> io::Result<bool> {
        let until = Instant::now() + timeout;
        loop {
            self.take_resize();
            if self.decoder.has_event() {
                return Ok(true);
            }
            let now = Instant::now();
            if now >= until {
                return Ok(false);
            }
            self.wait(until)?;
        }
    }

    /// The next event, if one is queued.
    pub fn read(&mut self) -> Option<Event> {
        self.decoder.next_event()
    }

    /// Waits up to `timeout` for the answer to a cursor-position query, keeping every event
    /// that comes meanwhile queued. False if none came.
    pub fn cursor(&mut self, timeout: Duration) -> io::Result<bool> {
        let until = Instant::now() + timeout;
        loop {
            if self.decoder.take_cursor().is_some() {
                return Ok(true);
            }
            if Instant::now() >= until {
                return Ok(false);
            }
            self.wait(until)?;
        }
    }

    fn take_resize(&mut self) {
        if self.resized.swap(false, Ordering::Relaxed)
            && let Ok((w, h)) = crossterm::terminal::size()
        {
            self.decoder
                .out
                .push_back(Input::Event(Event::Resize(w, h)));
        }
    }

    /// Reads what standard input has by `until` (or a paste's deadline, or a short slice, to
    /// notice a resize), into the decoder.
    fn wait(&mut self, until: Instant) -> io::Result<()> {
        use rustix::event::{PollFd, PollFlags, Timespec, poll};
        let now = Instant::now();
        let mut wake = until.min(now + Duration::from_millis(100));
        if let Some(d) = self.decoder.deadline() {
            wake = wake.min(d);
        }
        let left = wake.saturating_duration_since(now);
        let stdin = io::stdin();
        let mut fds = [PollFd::new(&stdin, PollFlags::IN)];
        let t = Timespec {
            tv_sec: left.as_secs() as i64,
            tv_nsec: i64::from(left.subsec_nanos()),
        };
        match poll(&mut fds, Some(&t)) {
            Ok(0) => {}
            Ok(_) => {
                let r = fds[0].revents();
                if r.contains(PollFlags::IN) {
                    let mut buf = [0u8; 1024];
                    match rustix::io::read(&stdin, &mut buf) {
                        Ok(0) => self.dead(),
                        Ok(n) => self.decoder.feed(&buf[..n], n == buf.len(), Instant::now()),
                        Err(rustix::io::Errno::INTR | rustix::io::Errno::AGAIN) => {}
                        Err(_) => self.dead(),
                    }
                } else {
                    // Hung up: nothing will come; the hang-up watcher ends the program.
                    self.dead();
                }
            }
            Err(rustix::io::Errno::INTR) => {}
            Err(e) => return Err(e.into()),
        }
        self.decoder.expire(Instant::now());
        Ok(())
    }

    /// A terminal gone: nothing more will come, and nothing can be drawn. Waits for good,
    /// as crossterm's reader did: the hang-up watcher (`super::watch_hangup`) raises SIGHUP,
    /// and the signal watcher restores what it can, saves the recording and ends the process.
    fn dead(&self) -> ! {
        loop {
            std::thread::sleep(Duration::from_secs(1));
        }
    }
}
