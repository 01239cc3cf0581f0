//! Key names in scripts: `x`, `X`, `space`, `hash`, `f1`–`f12`, `ctrl-`/`alt-`/`shift-`
//! prefixes. One spelling for the parser, the recorder and the help.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

/// Named keys, in the spelling [`key_name`] writes (parsing ignores case).
pub(super) const NAMED: [(&str, KeyCode); 16] = [
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

/// Modifier prefixes, in the order [`key_name`] writes them.
pub(super) const MODIFIERS: [(&str, KeyModifiers); 3] = [
    ("ctrl-", KeyModifiers::CONTROL),
    ("alt-", KeyModifiers::ALT),
    ("shift-", KeyModifiers::SHIFT),
];

pub(super) fn parse_key(name: &str) -> Option<KeyEvent> {
    let mut modifiers = KeyModifiers::NONE;
    let mut rest = name;
    while let Some((prefix, m)) = MODIFIERS.iter().find(|(p, _)| {
        rest.len() > p.len()
            && rest
                .get(..p.len())
                .is_some_and(|h| h.eq_ignore_ascii_case(p))
    }) {
        modifiers |= *m;
        rest = &rest[prefix.len()..];
    }
    let mut chars = rest.chars();
    let code = match (chars.next(), chars.next()) {
        (Some(c), None) if !c.is_control() => KeyCode::Char(c),
        _ => named_key(rest)?,
    };
    // The app matches shifted characters as the character itself, which is
    // also what terminals report, so `shift-a` is `A`.
    let code = match code {
        KeyCode::Char(c) if modifiers.contains(KeyModifiers::SHIFT) => {
            modifiers.remove(KeyModifiers::SHIFT);
            KeyCode::Char(c.to_ascii_uppercase())
        }
        code => code,
    };
    Some(KeyEvent::new(code, modifiers))
}

pub(super) fn named_key(name: &str) -> Option<KeyCode> {
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

/// The script spelling of a key press, or `None` when the format cannot
/// express it (releases, unusual keys, super/hyper/meta modifiers).
pub fn key_name(key: &KeyEvent) -> Option<String> {
    let expressible = KeyModifiers::CONTROL | KeyModifiers::ALT | KeyModifiers::SHIFT;
    if key.kind != KeyEventKind::Press || !expressible.contains(key.modifiers) {
        return None;
    }
    let mut modifiers = key.modifiers;
    let code = match key.code {
        KeyCode::Char(c) if c.is_control() => return None,
        KeyCode::Char(c) if modifiers.contains(KeyModifiers::SHIFT) => {
            modifiers.remove(KeyModifiers::SHIFT);
            KeyCode::Char(c.to_ascii_uppercase())
        }
        code => code,
    };
    let base = match code {
        KeyCode::F(n @ 1..=12) => format!("f{n}"),
        code => match NAMED.iter().find(|(_, c)| *c == code) {
            Some((name, _)) => name.to_string(),
            None => match code {
                KeyCode::Char(c) => c.to_string(),
                _ => return None,
            },
        },
    };
    let prefix: String = MODIFIERS
        .iter()
        .filter(|(_, m)| modifiers.contains(*m))
        .map(|(p, _)| *p)
        .collect();
    Some(prefix + &base)
}
