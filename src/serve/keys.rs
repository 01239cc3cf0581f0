//! A client's bytes as crossterm's key, mouse and paste events. The grammar is terminput's
//! (crossterm's parser, kept as a crate); around it, what a server must add: a paste bounded
//! in bytes and time (an unpaired `ESC[200~` swallows no key for good), ESC ESC read as the
//! Esc key followed by what the second ESC begins, and replies to terminal queries dropped,
//! never read as keys (serve asks none, but a client's terminal may still send one).

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use std::time::Instant;

use crate::terminal::input::SEQ_MAX;
use crate::terminal::input::paste::{PASTE_START, Paste, Step};
pub use crate::terminal::input::{PASTE_IDLE, PASTE_MAX, PASTE_TIME};

/// Bytes in, events out (see the module).
#[derive(Default)]
pub struct Keys {
    seq: Vec<u8>,
    paste: Option<Paste>,
}

fn esc() -> Event {
    Event::Key(KeyEvent::new(KeyCode::Esc, KeyModifiers::NONE))
}

/// `CSI row ; column R`: the answer to a cursor-position query, or `CSI ? … c`/`CSI ? … u`:
/// a device's or keyboard's attributes. Replies, not keys.
fn reply(seq: &[u8]) -> bool {
    let Some(body) = seq.strip_prefix(b"\x1b[") else {
        return false;
    };
    let cpr = body.ends_with(b"R")
        && body.contains(&b';')
        && body[..body.len() - 1]
            .iter()
            .all(|b| b.is_ascii_digit() || *b == b';');
    cpr || body.starts_with(b"?")
}

impl Keys {
    /// One message's bytes, taken at `now`. A lone ESC ending a message is the Esc key: a
    /// terminal sends a sequence whole, and ssh carries it in one message.
    pub fn feed(&mut self, bytes: &[u8], now: Instant) -> Vec<Event> {
        let mut out = self.expire(now);
        for (i, &b) in bytes.iter().enumerate() {
            if self.paste.is_some() {
                out.extend(self.paste_byte(b, now));
                continue;
            }
            if b == 0x1b && self.seq == [0x1b] {
                out.push(esc());
                self.seq.clear();
            }
            self.seq.push(b);
            if self.seq == PASTE_START {
                self.seq.clear();
                self.paste = Some(Paste::new(now));
                continue;
            }
            if self.seq == [0x1b] {
                if i + 1 == bytes.len() {
                    out.push(esc());
                    self.seq.clear();
                }
                continue;
            }
            self.parse(&mut out);
        }
        out
    }

    fn parse(&mut self, out: &mut Vec<Event>) {
        match terminput::Event::parse_from(&self.seq) {
            Ok(Some(ev)) => {
                if !reply(&self.seq)
                    && let Ok(ev) = terminput_crossterm::to_crossterm(ev)
                {
                    out.push(ev);
                }
                self.seq.clear();
            }
            Ok(None) if self.seq.len() < SEQ_MAX => {}
            _ => self.seq.clear(),
        }
    }

    fn paste_byte(&mut self, b: u8, now: Instant) -> Vec<Event> {
        let Some(p) = self.paste.as_mut() else {
            return vec![];
        };
        let out = match p.byte(b, now) {
            Step::Going => return vec![],
            Step::Ended(text) => vec![Event::Paste(text)],
            // Ctrl-C always arrives: the paste ends, and the key follows it.
            Step::CtrlC(text) => vec![
                Event::Paste(text),
                Event::Key(KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL)),
            ],
        };
        self.paste = None;
        out
    }

    fn end_paste(&mut self) -> Vec<Event> {
        match self.paste.take() {
            Some(mut p) => vec![Event::Paste(p.take())],
            None => vec![],
        }
    }

    /// Ends a paste past its bounds by `now` ([`PASTE_IDLE`] without a byte, [`PASTE_TIME`]
    /// in all).
    pub fn expire(&mut self, now: Instant) -> Vec<Event> {
        match self.deadline() {
            Some(d) if now >= d => self.end_paste(),
            _ => vec![],
        }
    }

    /// When a paste under way ends if nothing ends it first.
    pub fn deadline(&self) -> Option<Instant> {
        self.paste.as_ref().map(Paste::deadline)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crossterm::event::{MouseButton, MouseEvent, MouseEventKind};

    fn keys(bytes: &[u8]) -> Vec<Event> {
        Keys::default().feed(bytes, Instant::now())
    }

    fn k(code: KeyCode, m: KeyModifiers) -> Event {
        Event::Key(KeyEvent::new(code, m))
    }

    #[test]
    fn keys_mouse_and_paste_as_the_terminal_reads_them() {
        let none = KeyModifiers::NONE;
        assert_eq!(
            keys(b"aQ\r\x1b[A\x1b[1;2D\x1bx\x03"),
            vec![
                k(KeyCode::Char('a'), none),
                k(KeyCode::Char('Q'), KeyModifiers::SHIFT),
                k(KeyCode::Enter, none),
                k(KeyCode::Up, none),
                k(KeyCode::Left, KeyModifiers::SHIFT),
                k(KeyCode::Char('x'), KeyModifiers::ALT),
                k(KeyCode::Char('c'), KeyModifiers::CONTROL),
            ]
        );
        assert_eq!(keys(b"\x1b"), vec![k(KeyCode::Esc, none)]);
        assert_eq!(
            keys(b"\x1b[<0;5;3M"),
            vec![Event::Mouse(MouseEvent {
                kind: MouseEventKind::Down(MouseButton::Left),
                column: 4,
                row: 2,
                modifiers: none,
            })]
        );
        assert_eq!(
            keys(b"\x1b[200~sq\x1b[201~?"),
            vec![Event::Paste("sq".into()), k(KeyCode::Char('?'), none)]
        );
    }

    #[test]
    fn no_reply_is_keys_and_esc_esc_is_two_things() {
        let none = KeyModifiers::NONE;
        assert_eq!(keys(b"\x1b\x1b[30;21R"), vec![k(KeyCode::Esc, none)]);
        assert_eq!(keys(b"\x1b[?1;2c"), vec![]);
        assert_eq!(
            keys(b"\x1b\x1b[B"),
            vec![k(KeyCode::Esc, none), k(KeyCode::Down, none)]
        );
    }

    #[test]
    fn an_unpaired_paste_swallows_no_key_for_good() {
        let t0 = Instant::now();
        let mut d = Keys::default();
        assert_eq!(d.feed(b"\x1b[200~abc", t0), vec![]);
        assert_eq!(
            d.feed(b"\x03q", t0),
            vec![
                Event::Paste("abc".into()),
                k(KeyCode::Char('c'), KeyModifiers::CONTROL),
                k(KeyCode::Char('q'), KeyModifiers::NONE),
            ]
        );
        d.feed(b"\x1b[200~x", t0);
        assert_eq!(
            d.feed(b"q", t0 + PASTE_IDLE * 2),
            vec![
                Event::Paste("x".into()),
                k(KeyCode::Char('q'), KeyModifiers::NONE)
            ]
        );
        // A flood inside a paste keeps its bound.
        d.feed(PASTE_START, t0);
        let chunk = vec![b'a'; 1 << 16];
        for _ in 0..(PASTE_MAX / chunk.len() + 2) {
            assert!(d.feed(&chunk, t0).is_empty());
        }
        match d
            .feed(crate::terminal::input::paste::PASTE_END, t0)
            .as_slice()
        {
            [Event::Paste(t)] => assert_eq!(t.len(), PASTE_MAX),
            other => panic!("{other:?}"),
        }
    }
}
