//! One input sequence at a time, bytes to crossterm's `Event`s: crossterm 0.29's grammar
//! (`event/sys/unix/parse.rs`, MIT), trimmed to what a terminal sends a program that asks for
//! no keyboard enhancement (see the module above).

use super::Input;
use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};

/// What one sequence is: complete (and what it gave, if anything), incomplete, or not one.
pub(super) enum Parsed {
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

/// One sequence at the start of `b`: crossterm's grammar (see the module).
pub(super) fn parse(b: &[u8], more: bool) -> Parsed {
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
