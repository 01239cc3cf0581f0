//! A key chord: one key and its modifiers, in the one normal form that dispatch, key scripts,
//! the recorder and the help screen share. Shift is folded into characters here and nowhere
//! else: `shift-x` is `X`, as terminals report it.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use std::fmt;
use std::str::FromStr;

/// A key and its modifiers (Ctrl, Alt, Shift only; Shift never on a character).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Chord {
    pub code: KeyCode,
    pub mods: KeyModifiers,
}

/// Named keys, in the script spelling [`Chord`] displays (parsing ignores case).
const NAMED: [(&str, KeyCode); 16] = [
    ("space", KeyCode::Char(' ')),
    ("hash", KeyCode::Char('#')),
    ("enter", KeyCode::Enter),
    ("esc", KeyCode::Esc),
    ("tab", KeyCode::Tab),
    ("backtab", KeyCode::BackTab),
    ("backspace", KeyCode::Backspace),
    ("delete", KeyCode::Delete),
    ("up", KeyCode::Up),
    ("down", KeyCode::Down),
    ("left", KeyCode::Left),
    ("right", KeyCode::Right),
    ("home", KeyCode::Home),
    ("end", KeyCode::End),
    ("pgup", KeyCode::PageUp),
    ("pgdn", KeyCode::PageDown),
];

/// Modifier prefixes, in the order they are written: script spelling and help spelling.
const MODIFIERS: [(&str, &str, KeyModifiers); 3] = [
    ("ctrl-", "Ctrl-", KeyModifiers::CONTROL),
    ("alt-", "Alt-", KeyModifiers::ALT),
    ("shift-", "Shift-", KeyModifiers::SHIFT),
];

impl Chord {
    /// A chord as written in a table; `code` must already be in normal form (an upper-case
    /// character, not Shift with a lower-case one).
    pub const fn new(code: KeyCode, mods: KeyModifiers) -> Chord {
        Chord { code, mods }
    }

    /// The chord a terminal's key event means, or `None` for a release and for what a script
    /// cannot express (control characters, unusual keys, super/hyper/meta). Repeats count as
    /// presses.
    pub fn from_event(key: &KeyEvent) -> Option<Chord> {
        if key.kind == KeyEventKind::Release {
            return None;
        }
        Chord::normal(key.code, key.modifiers)
    }

    fn normal(code: KeyCode, mut mods: KeyModifiers) -> Option<Chord> {
        let expressible = KeyModifiers::CONTROL | KeyModifiers::ALT | KeyModifiers::SHIFT;
        if !expressible.contains(mods) {
            return None;
        }
        let code = match code {
            KeyCode::Char(c) if c.is_control() => return None,
            KeyCode::Char(c) if mods.contains(KeyModifiers::SHIFT) => {
                mods.remove(KeyModifiers::SHIFT);
                KeyCode::Char(c.to_ascii_uppercase())
            }
            // Back-tab is Shift-Tab already; terminals report it with Shift or without.
            KeyCode::BackTab => {
                mods.remove(KeyModifiers::SHIFT);
                code
            }
            KeyCode::Char(_) | KeyCode::F(1..=12) => code,
            _ if NAMED.iter().any(|(_, c)| *c == code) => code,
            _ => return None,
        };
        Some(Chord { code, mods })
    }

    /// The key event a terminal sends for this chord (Shift reported on upper-case letters).
    pub fn event(self) -> KeyEvent {
        let mut mods = self.mods;
        if let KeyCode::Char(c) = self.code
            && c.is_ascii_uppercase()
        {
            mods |= KeyModifiers::SHIFT;
        }
        KeyEvent::new(self.code, mods)
    }

    /// The chord as the help shows it: `x`, `Alt-X`, `Shift-←`, `Space`, `Esc`.
    pub fn label(self) -> String {
        self.mods_label() + &self.key_label()
    }

    /// The modifiers as the help writes them: `Ctrl-Alt-`, or empty.
    pub fn mods_label(self) -> String {
        self.prefix(true)
    }

    /// The key without its modifiers as the help writes it: `X`, `←`, `Space`.
    pub fn key_label(self) -> String {
        match self.code {
            KeyCode::Char(' ') => "Space".to_string(),
            KeyCode::Char(c) => c.to_string(),
            KeyCode::Left => "←".into(),
            KeyCode::Right => "→".into(),
            KeyCode::Up => "↑".into(),
            KeyCode::Down => "↓".into(),
            KeyCode::PageUp => "PgUp".into(),
            KeyCode::PageDown => "PgDn".into(),
            other => format!("{other}"),
        }
    }

    /// The modifiers' prefixes, in the help's spelling or the script's.
    fn prefix(self, help: bool) -> String {
        MODIFIERS
            .iter()
            .filter(|m| self.mods.contains(m.2))
            .map(|m| if help { m.1 } else { m.0 })
            .collect()
    }
}

/// The script spelling: `x`, `X`, `space`, `hash`, `f1`–`f12`, with `ctrl-`, `alt-`, `shift-`.
impl fmt::Display for Chord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let prefix = self.prefix(false);
        match self.code {
            KeyCode::F(n) => write!(f, "{prefix}f{n}"),
            code => match NAMED.iter().find(|(_, c)| *c == code) {
                Some((name, _)) => write!(f, "{prefix}{name}"),
                None => match code {
                    KeyCode::Char(c) => write!(f, "{prefix}{c}"),
                    other => write!(f, "{prefix}{other}"),
                },
            },
        }
    }
}

/// A name no key has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnknownKey;

impl fmt::Display for UnknownKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("unknown key")
    }
}

impl std::error::Error for UnknownKey {}

/// Reads the script spelling; prefixes and named keys ignore case, characters do not.
impl FromStr for Chord {
    type Err = UnknownKey;

    fn from_str(name: &str) -> Result<Chord, UnknownKey> {
        let mut mods = KeyModifiers::NONE;
        let mut rest = name;
        while let Some((prefix, _, m)) = MODIFIERS.iter().find(|(p, _, _)| {
            rest.len() > p.len()
                && rest
                    .get(..p.len())
                    .is_some_and(|h| h.eq_ignore_ascii_case(p))
        }) {
            mods |= *m;
            rest = &rest[prefix.len()..];
        }
        let mut chars = rest.chars();
        let code = match (chars.next(), chars.next()) {
            (Some(c), None) => KeyCode::Char(c),
            _ => named(rest).ok_or(UnknownKey)?,
        };
        Chord::normal(code, mods).ok_or(UnknownKey)
    }
}

fn named(name: &str) -> Option<KeyCode> {
    if let Some((_, code)) = NAMED.iter().find(|(n, _)| n.eq_ignore_ascii_case(name)) {
        return Some(*code);
    }
    let digits = name.strip_prefix(['f', 'F'])?;
    if digits.starts_with('0') || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let n: u8 = digits.parse().ok()?;
    (1..=12).contains(&n).then_some(KeyCode::F(n))
}
