//! A bracketed paste under way, bounded in bytes and time: the one rule for the local
//! terminal's reader and serve's, so an unpaired `ESC[200~` swallows no key for good in either.

use super::{PASTE_IDLE, PASTE_MAX, PASTE_TIME};
use std::time::Instant;

/// Where a paste's text starts and ends.
pub const PASTE_START: &[u8] = b"\x1b[200~";
pub const PASTE_END: &[u8] = b"\x1b[201~";

/// A paste begun and not yet ended.
pub struct Paste {
    text: Vec<u8>,
    /// The last bytes seen, to find `ESC[201~` once the text is no longer kept.
    tail: Vec<u8>,
    began: Instant,
    last: Instant,
}

/// What one byte did to a paste.
pub enum Step {
    Going,
    /// `ESC[201~`: its text.
    Ended(String),
    /// A Ctrl-C byte, which always reaches the program: the paste's text, then the key.
    CtrlC(String),
}

impl Paste {
    pub fn new(now: Instant) -> Paste {
        Paste {
            text: Vec::new(),
            tail: Vec::new(),
            began: now,
            last: now,
        }
    }

    /// The next byte, at `now`. The text is kept up to [`PASTE_MAX`] bytes (and the end
    /// marker's, to strip it whole); the rest is dropped.
    pub fn byte(&mut self, b: u8, now: Instant) -> Step {
        self.last = now;
        if b == 0x03 {
            return Step::CtrlC(self.take());
        }
        if self.text.len() < PASTE_MAX + PASTE_END.len() {
            self.text.push(b);
        }
        self.tail.push(b);
        if self.tail.len() > PASTE_END.len() {
            self.tail.remove(0);
        }
        if self.tail == PASTE_END {
            if self.text.ends_with(PASTE_END) {
                let n = self.text.len() - PASTE_END.len();
                self.text.truncate(n);
            }
            return Step::Ended(self.take());
        }
        Step::Going
    }

    /// When it ends if nothing ends it first: its bytes stopped for [`PASTE_IDLE`], or
    /// [`PASTE_TIME`] after it began.
    pub fn deadline(&self) -> Instant {
        (self.last + PASTE_IDLE).min(self.began + PASTE_TIME)
    }

    /// Its text as kept, at most [`PASTE_MAX`] bytes.
    pub fn take(&mut self) -> String {
        self.text.truncate(PASTE_MAX);
        String::from_utf8_lossy(&std::mem::take(&mut self.text)).into_owned()
    }
}
