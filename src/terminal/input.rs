//! The terminal's input, read and decoded here rather than by crossterm's event reader, so
//! that a bracketed paste is bounded. crossterm's parser, after `ESC[200~`, keeps every byte
//! until `ESC[201~` arrives: an unpaired start swallowed every key, `q` and Ctrl-C included,
//! for good. Here a paste ends at `ESC[201~`; at a Ctrl-C byte (which then reaches the
//! program as Ctrl-C); when its bytes stop coming for [`PASTE_IDLE`]; or [`PASTE_TIME`] after
//! it began. Its text is kept up to [`PASTE_MAX`] bytes (the rest is dropped, not kept).
//!
//! [`Decoder`] turns bytes into crossterm's own `Event`s as crossterm's parser does (keys,
//! SGR and X10 mouse reports, focus, the cursor-position answer frame pacing waits for) and is
//! pure: bytes and instants in, events out, so tests feed it without a terminal. [`Input`]
//! reads standard input into it and watches SIGWINCH for resizes.
//!
//! The byte grammar follows crossterm 0.29's `event/sys/unix/parse.rs` (MIT), trimmed to the
//! sequences a terminal sends to a program that asks for no keyboard enhancement.

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use std::collections::VecDeque;
use std::io;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

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

const PASTE_START: &[u8] = b"\x1b[200~";
const PASTE_END: &[u8] = b"\x1b[201~";

/// What the decoder read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Input {
    Event(Event),
    /// The terminal's answer to a cursor-position query (`ESC[6n`): column and row, 0-based.
    Cursor(u16, u16),
}

/// A paste under way.
struct Paste {
    text: Vec<u8>,
    /// The last bytes seen, to find `ESC[201~` once the text is no longer kept.
    tail: Vec<u8>,
    began: Instant,
    last: Instant,
}

/// Bytes in, [`Input`]s out (see the module).
#[derive(Default)]
pub struct Decoder {
    /// A sequence begun and not yet complete.
    seq: Vec<u8>,
    paste: Option<Paste>,
    /// When a lone ESC ending a read becomes the Esc key, if nothing follows it.
    esc_until: Option<Instant>,
    out: VecDeque<Input>,
}

/// What one sequence is: complete (and what it gave, if anything), incomplete, or not one.
enum Parsed {
    Done(Option<Input>),
    More,
    Bad,
}

fn key(code: KeyCode, modifiers: KeyModifiers) -> Parsed {
    Parsed::Done(Some(Input::Event(Event::Key(KeyEvent::new(
        code, modifiers,
    )))))
}

fn plain(code: KeyCode) -> Parsed {
    key(code, KeyModifiers::NONE)
}

fn esc() -> Input {
    Input::Event(Event::Key(KeyEvent::new(KeyCode::Esc, KeyModifiers::NONE)))
}

impl Decoder {
    pub fn new() -> Decoder {
        Decoder::default()
    }

    /// Takes `bytes` read at `now`; `more` says more were waiting (the read filled its
    /// buffer), so that a lone ESC at the end is not yet taken for the Esc key.
    pub fn feed(&mut self, bytes: &[u8], more: bool, now: Instant) {
        self.expire(now);
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
                self.esc_until = Some(now + ESC_WAIT);
                continue;
            }
            if self.seq == PASTE_START {
                self.seq.clear();
                self.paste = Some(Paste {
                    text: Vec::new(),
                    tail: Vec::new(),
                    began: now,
                    last: now,
                });
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
        p.last = now;
        if b == 0x03 {
            // Ctrl-C always reaches the program: the paste ends, and the key follows it.
            self.end_paste();
            self.out.push_back(Input::Event(Event::Key(KeyEvent::new(
                KeyCode::Char('c'),
                KeyModifiers::CONTROL,
            ))));
            return;
        }
        if p.text.len() < PASTE_MAX {
            p.text.push(b);
        }
        p.tail.push(b);
        if p.tail.len() > PASTE_END.len() {
            p.tail.remove(0);
        }
        if p.tail == PASTE_END {
            if p.text.ends_with(PASTE_END) {
                let n = p.text.len() - PASTE_END.len();
                p.text.truncate(n);
            }
            self.end_paste();
        }
    }

    /// Ends the paste under way: its text (as kept) is one event.
    fn end_paste(&mut self) {
        if let Some(p) = self.paste.take() {
            let text = String::from_utf8_lossy(&p.text).into_owned();
            self.out.push_back(Input::Event(Event::Paste(text)));
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
        let paste = self
            .paste
            .as_ref()
            .map(|p| (p.last + PASTE_IDLE).min(p.began + PASTE_TIME));
        if paste.is_some_and(|d| now >= d) {
            self.end_paste();
        }
    }

    /// When the paste under way will be ended, or a held ESC taken for the key, if nothing
    /// comes first.
    pub fn deadline(&self) -> Option<Instant> {
        let paste = self
            .paste
            .as_ref()
            .map(|p| (p.last + PASTE_IDLE).min(p.began + PASTE_TIME));
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
}

/// One sequence at the start of `b`: crossterm's grammar (see the module).
fn parse(b: &[u8], more: bool) -> Parsed {
    match b[0] {
        0x1b => parse_esc(b, more),
        b'\r' => plain(KeyCode::Enter),
        b'\t' => plain(KeyCode::Tab),
        0x7f => plain(KeyCode::Backspace),
        c @ 0x01..=0x1a => key(
            KeyCode::Char((c - 0x1 + b'a') as char),
            KeyModifiers::CONTROL,
        ),
        c @ 0x1c..=0x1f => key(
            KeyCode::Char((c - 0x1c + b'4') as char),
            KeyModifiers::CONTROL,
        ),
        0 => key(KeyCode::Char(' '), KeyModifiers::CONTROL),
        _ => match utf8(b) {
            Parsed::Done(Some(Input::Event(Event::Key(k)))) => {
                let mods = match k.code {
                    KeyCode::Char(c) if c.is_uppercase() => KeyModifiers::SHIFT,
                    _ => KeyModifiers::NONE,
                };
                key(k.code, mods)
            }
            other => other,
        },
    }
}

fn utf8(b: &[u8]) -> Parsed {
    match std::str::from_utf8(b) {
        Ok(s) => match s.chars().next() {
            Some(c) => plain(KeyCode::Char(c)),
            None => Parsed::Bad,
        },
        Err(e) if e.error_len().is_none() && b.len() < 4 => Parsed::More,
        Err(_) => Parsed::Bad,
    }
}

fn parse_esc(b: &[u8], more: bool) -> Parsed {
    if b.len() == 1 {
        return if more {
            Parsed::More
        } else {
            plain(KeyCode::Esc)
        };
    }
    match b[1] {
        b'O' => {
            if b.len() == 2 {
                return Parsed::More;
            }
            match (b[2], cursor_key(b[2])) {
                (_, Some(code)) => plain(code),
                (v @ b'P'..=b'S', _) => plain(KeyCode::F(1 + v - b'P')),
                _ => Parsed::Bad,
            }
        }
        b'[' => parse_csi(b),
        0x1b => plain(KeyCode::Esc),
        _ => match parse(&b[1..], more) {
            Parsed::Done(Some(Input::Event(Event::Key(mut k)))) => {
                k.modifiers |= KeyModifiers::ALT;
                Parsed::Done(Some(Input::Event(Event::Key(k))))
            }
            other => other,
        },
    }
}

/// The cursor keys' final byte, the same after `ESC O` and `ESC [`.
fn cursor_key(c: u8) -> Option<KeyCode> {
    Some(match c {
        b'D' => KeyCode::Left,
        b'C' => KeyCode::Right,
        b'A' => KeyCode::Up,
        b'B' => KeyCode::Down,
        b'H' => KeyCode::Home,
        b'F' => KeyCode::End,
        _ => return None,
    })
}

fn parse_csi(b: &[u8]) -> Parsed {
    if b.len() == 2 {
        return Parsed::More;
    }
    let last = b[b.len() - 1];
    match b[2] {
        b'[' => match b.get(3) {
            None => Parsed::More,
            Some(v @ b'A'..=b'E') => plain(KeyCode::F(1 + v - b'A')),
            Some(_) => Parsed::Bad,
        },
        c @ (b'D' | b'C' | b'A' | b'B' | b'H' | b'F') => cursor_key(c).map_or(Parsed::Bad, plain),
        b'Z' => key(KeyCode::BackTab, KeyModifiers::SHIFT),
        b'P' => plain(KeyCode::F(1)),
        b'Q' => plain(KeyCode::F(2)),
        b'S' => plain(KeyCode::F(4)),
        b'I' => Parsed::Done(Some(Input::Event(Event::FocusGained))),
        b'O' => Parsed::Done(Some(Input::Event(Event::FocusLost))),
        b'M' => x10_mouse(b),
        b'<' => {
            if last == b'M' || last == b'm' {
                sgr_mouse(b)
            } else {
                Parsed::More
            }
        }
        // Replies (keyboard flags, device attributes) nobody here asked for: read, dropped.
        b'?' | b'>' => {
            if (0x40..=0x7e).contains(&last) && b.len() > 3 {
                Parsed::Done(None)
            } else {
                Parsed::More
            }
        }
        b'0'..=b'9' | b';' => {
            if b.len() == 3 || !(0x40..=0x7e).contains(&last) {
                return Parsed::More;
            }
            let params = &b[2..b.len() - 1];
            match last {
                b'~' => special_key(params),
                b'R' => cursor(params),
                _ => modified_key(params, last),
            }
        }
        _ => Parsed::Bad,
    }
}

/// The numbers of a CSI's parameters, `;`-separated (a `:` sub-parameter after the first is
/// left out, as the event kind is).
fn numbers(params: &[u8]) -> Option<Vec<u16>> {
    std::str::from_utf8(params)
        .ok()?
        .split(';')
        .map(|p| p.split(':').next().unwrap_or("").parse().ok())
        .collect()
}

fn modifiers(mask: u16) -> KeyModifiers {
    let m = mask.saturating_sub(1);
    let mut out = KeyModifiers::NONE;
    for (bit, flag) in [
        (1, KeyModifiers::SHIFT),
        (2, KeyModifiers::ALT),
        (4, KeyModifiers::CONTROL),
        (8, KeyModifiers::SUPER),
        (16, KeyModifiers::HYPER),
        (32, KeyModifiers::META),
    ] {
        if m & bit != 0 {
            out |= flag;
        }
    }
    out
}

/// `CSI n ; m ~`: Home, Insert, Delete, End, PageUp, PageDown, F5–F20.
fn special_key(params: &[u8]) -> Parsed {
    let Some(n) = numbers(params) else {
        return Parsed::Bad;
    };
    let mods = n.get(1).map_or(KeyModifiers::NONE, |&m| modifiers(m));
    let code = match n.first().copied().unwrap_or(0) {
        1 | 7 => KeyCode::Home,
        2 => KeyCode::Insert,
        3 => KeyCode::Delete,
        4 | 8 => KeyCode::End,
        5 => KeyCode::PageUp,
        6 => KeyCode::PageDown,
        v @ 11..=15 => KeyCode::F((v - 10) as u8),
        v @ 17..=21 => KeyCode::F((v - 11) as u8),
        v @ 23..=26 => KeyCode::F((v - 12) as u8),
        v @ 28..=29 => KeyCode::F((v - 15) as u8),
        v @ 31..=34 => KeyCode::F((v - 17) as u8),
        _ => return Parsed::Bad,
    };
    Parsed::Done(Some(Input::Event(Event::Key(KeyEvent::new_with_kind(
        code,
        mods,
        KeyEventKind::Press,
    )))))
}

/// `CSI 1 ; m A`: an arrow, Home, End or F1–F4 with modifiers.
fn modified_key(params: &[u8], last: u8) -> Parsed {
    let mods = numbers(params)
        .and_then(|n| n.get(1).copied())
        .map_or(KeyModifiers::NONE, modifiers);
    let code = match last {
        b'A' => KeyCode::Up,
        b'B' => KeyCode::Down,
        b'C' => KeyCode::Right,
        b'D' => KeyCode::Left,
        b'F' => KeyCode::End,
        b'H' => KeyCode::Home,
        b'P' => KeyCode::F(1),
        b'Q' => KeyCode::F(2),
        b'R' => KeyCode::F(3),
        b'S' => KeyCode::F(4),
        // Anything else complete (a CSI u key, a rxvt mouse report): read, dropped.
        _ => return Parsed::Done(None),
    };
    key(code, mods)
}

/// `CSI row ; column R`: where the cursor is (the answer to `ESC[6n`).
fn cursor(params: &[u8]) -> Parsed {
    match numbers(params).as_deref() {
        Some(&[row, col]) if row > 0 && col > 0 => {
            Parsed::Done(Some(Input::Cursor(col - 1, row - 1)))
        }
        _ => Parsed::Bad,
    }
}

/// The button byte of a mouse report: what happened, and the modifiers held.
fn mouse_kind(cb: u16) -> Option<(MouseEventKind, KeyModifiers)> {
    let button = (cb & 0b11) | ((cb & 0b1100_0000) >> 4);
    let dragging = cb & 0b10_0000 != 0;
    let kind = match (button, dragging) {
        (0, false) => MouseEventKind::Down(MouseButton::Left),
        (1, false) => MouseEventKind::Down(MouseButton::Middle),
        (2, false) => MouseEventKind::Down(MouseButton::Right),
        (0, true) => MouseEventKind::Drag(MouseButton::Left),
        (1, true) => MouseEventKind::Drag(MouseButton::Middle),
        (2, true) => MouseEventKind::Drag(MouseButton::Right),
        (3, false) => MouseEventKind::Up(MouseButton::Left),
        (3..=5, true) => MouseEventKind::Moved,
        (4, false) => MouseEventKind::ScrollUp,
        (5, false) => MouseEventKind::ScrollDown,
        (6, false) => MouseEventKind::ScrollLeft,
        (7, false) => MouseEventKind::ScrollRight,
        _ => return None,
    };
    let mut mods = KeyModifiers::NONE;
    for (bit, flag) in [
        (0b100, KeyModifiers::SHIFT),
        (0b1000, KeyModifiers::ALT),
        (0b1_0000, KeyModifiers::CONTROL),
    ] {
        if cb & bit != 0 {
            mods |= flag;
        }
    }
    Some((kind, mods))
}

fn mouse(kind: MouseEventKind, column: u16, row: u16, modifiers: KeyModifiers) -> Parsed {
    Parsed::Done(Some(Input::Event(Event::Mouse(MouseEvent {
        kind,
        column,
        row,
        modifiers,
    }))))
}

/// `CSI M Cb Cx Cy`, each a byte offset by 32.
fn x10_mouse(b: &[u8]) -> Parsed {
    if b.len() < 6 {
        return Parsed::More;
    }
    let Some(cb) = b[3].checked_sub(32) else {
        return Parsed::Bad;
    };
    let Some((kind, mods)) = mouse_kind(u16::from(cb)) else {
        return Parsed::Bad;
    };
    let at = |v: u8| u16::from(v.saturating_sub(32)).saturating_sub(1);
    mouse(kind, at(b[4]), at(b[5]), mods)
}

/// `CSI < Cb ; Cx ; Cy M` (pressed) or `m` (released).
fn sgr_mouse(b: &[u8]) -> Parsed {
    let Some(n) = numbers(&b[3..b.len() - 1]) else {
        return Parsed::Bad;
    };
    let (Some(&cb), Some(&x), Some(&y)) = (n.first(), n.get(1), n.get(2)) else {
        return Parsed::Bad;
    };
    let Some((mut kind, mods)) = mouse_kind(cb) else {
        return Parsed::Bad;
    };
    if b[b.len() - 1] == b'm'
        && let MouseEventKind::Down(button) = kind
    {
        kind = MouseEventKind::Up(button);
    }
    mouse(kind, x.saturating_sub(1), y.saturating_sub(1), mods)
}

/// Standard input read into a [`Decoder`], and the terminal's size changes (SIGWINCH).
pub struct Reader {
    decoder: Decoder,
    resized: Arc<AtomicBool>,
}

impl Reader {
    pub fn new() -> io::Result<Reader> {
        let resized = Arc::new(AtomicBool::new(false));
        signal_hook::flag::register(libc::SIGWINCH, Arc::clone(&resized))?;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(bytes: &[u8]) -> Vec<Input> {
        let mut d = Decoder::new();
        let now = Instant::now();
        d.feed(bytes, false, now);
        d.expire(now + ESC_WAIT);
        std::iter::from_fn(|| d.next_input()).collect()
    }

    /// An Esc pressed as the terminal answers a cursor-position query: over ssh both arrive
    /// in one read (`ESC ESC[30;21R`), or the reply's ESC ends one read and its tail begins
    /// the next. Neither is `[30;21R` typed.
    #[test]
    fn a_reply_behind_an_esc_is_never_keys() {
        let esc = k(KeyCode::Esc, KeyModifiers::NONE);
        assert_eq!(
            decode(b"\x1b\x1b[30;21R"),
            vec![esc.clone(), Input::Cursor(20, 29)]
        );
        assert_eq!(
            decode(b"\x1b\x1b[A"),
            vec![esc.clone(), k(KeyCode::Up, KeyModifiers::NONE)]
        );
        let t0 = Instant::now();
        let mut d = Decoder::new();
        d.feed(b"\x1b", false, t0);
        assert_eq!(d.next_input(), None, "a lone ESC waits for what may follow");
        assert_eq!(d.deadline(), Some(t0 + ESC_WAIT));
        d.feed(b"[30;21R", false, t0 + ESC_WAIT / 2);
        assert_eq!(d.next_input(), Some(Input::Cursor(20, 29)));
        assert_eq!(d.next_input(), None);
        // Alone, it is the Esc key once the wait is over.
        d.feed(b"\x1b", false, t0);
        d.expire(t0 + ESC_WAIT);
        assert_eq!(d.next_input(), Some(esc));
    }

    fn k(code: KeyCode, m: KeyModifiers) -> Input {
        Input::Event(Event::Key(KeyEvent::new(code, m)))
    }

    #[test]
    fn keys_as_crossterm_reads_them() {
        let none = KeyModifiers::NONE;
        let ctrl = KeyModifiers::CONTROL;
        assert_eq!(
            decode(b"aQ\r\t\x7f\x03\x1b[A\x1b[1;2D\x1bOP\x1b[3~\x1b[Z\x1bx"),
            vec![
                k(KeyCode::Char('a'), none),
                k(KeyCode::Char('Q'), KeyModifiers::SHIFT),
                k(KeyCode::Enter, none),
                k(KeyCode::Tab, none),
                k(KeyCode::Backspace, none),
                k(KeyCode::Char('c'), ctrl),
                k(KeyCode::Up, none),
                k(KeyCode::Left, KeyModifiers::SHIFT),
                k(KeyCode::F(1), none),
                k(KeyCode::Delete, none),
                k(KeyCode::BackTab, KeyModifiers::SHIFT),
                k(KeyCode::Char('x'), KeyModifiers::ALT),
            ]
        );
        assert_eq!(decode("ξ".as_bytes()), vec![k(KeyCode::Char('ξ'), none)]);
        assert_eq!(decode(b"\x1b"), vec![k(KeyCode::Esc, none)]);
        assert_eq!(decode(b"\x1b[12;40R"), vec![Input::Cursor(39, 11)]);
        assert_eq!(
            decode(b"\x1b[<0;5;3M\x1b[<0;5;3m"),
            vec![
                Input::Event(Event::Mouse(MouseEvent {
                    kind: MouseEventKind::Down(MouseButton::Left),
                    column: 4,
                    row: 2,
                    modifiers: none,
                })),
                Input::Event(Event::Mouse(MouseEvent {
                    kind: MouseEventKind::Up(MouseButton::Left),
                    column: 4,
                    row: 2,
                    modifiers: none,
                })),
            ]
        );
    }

    #[test]
    fn a_paired_paste_is_one_event() {
        assert_eq!(
            decode(b"\x1b[200~sq\x1b[201~?"),
            vec![
                Input::Event(Event::Paste("sq".into())),
                k(KeyCode::Char('?'), KeyModifiers::NONE),
            ]
        );
    }

    #[test]
    fn an_unpaired_paste_ends_at_ctrl_c_or_in_time() {
        let t0 = Instant::now();
        let mut d = Decoder::new();
        d.feed(b"\x1b[200~abc", false, t0);
        assert!(d.pasting() && d.next_input().is_none());
        // Ctrl-C reaches the program at once.
        d.feed(b"q\x03q", false, t0);
        assert_eq!(
            d.next_input(),
            Some(Input::Event(Event::Paste("abcq".into())))
        );
        assert_eq!(
            d.next_input(),
            Some(k(KeyCode::Char('c'), KeyModifiers::CONTROL))
        );
        assert_eq!(
            d.next_input(),
            Some(k(KeyCode::Char('q'), KeyModifiers::NONE))
        );
        // Idle: ended PASTE_IDLE after its last byte, and keys are keys again.
        d.feed(b"\x1b[200~x", false, t0);
        d.expire(t0 + PASTE_IDLE / 2);
        assert!(d.pasting());
        d.feed(b"q", false, t0 + PASTE_IDLE + PASTE_IDLE / 2);
        assert_eq!(d.next_input(), Some(Input::Event(Event::Paste("x".into()))));
        assert_eq!(
            d.next_input(),
            Some(k(KeyCode::Char('q'), KeyModifiers::NONE))
        );
        // Keys typed without a pause: ended PASTE_TIME after it began.
        d.feed(b"\x1b[200~", false, t0);
        let step = PASTE_IDLE / 2;
        let mut t = t0;
        while t < t0 + PASTE_TIME {
            t += step;
            d.feed(b"q", false, t);
        }
        assert!(!d.pasting(), "ended by PASTE_TIME");
    }

    #[test]
    fn a_long_paste_keeps_at_most_its_bound() {
        let mut d = Decoder::new();
        let t0 = Instant::now();
        d.feed(PASTE_START, false, t0);
        let chunk = vec![b'a'; 64 * 1024];
        for _ in 0..(PASTE_MAX / chunk.len() + 4) {
            d.feed(&chunk, true, t0);
        }
        d.feed(PASTE_END, false, t0);
        match d.next_input() {
            Some(Input::Event(Event::Paste(t))) => assert_eq!(t.len(), PASTE_MAX),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn an_endless_sequence_is_dropped() {
        let mut bytes = b"\x1b[".to_vec();
        bytes.extend(std::iter::repeat_n(b'1', 200));
        bytes.push(b'q');
        assert_eq!(
            decode(&bytes).last(),
            Some(&k(KeyCode::Char('q'), KeyModifiers::NONE))
        );
    }
}
