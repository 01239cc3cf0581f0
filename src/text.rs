//! Text from outside the program — a scene or theme file, a key script, a flag, pasted text —
//! made safe to show, once, where it is read: [`Clean`] is such text, and [`clean`] (through
//! [`Clean::new`] or deserialising a `Clean`) is the only way to make one. Every output (the
//! screen, plain mode, replay's snapshots, the CLI's words, SVG, asciicast, JSON) then shows
//! it as it is, with nothing left that a terminal would act on.
//!
//! What goes: every control character — C0 (ESC, BEL, CR, NUL, …, a tab or a newline become a
//! blank: a field is one line), DEL and C1 (U+0080–U+009F) — and every escape sequence whole
//! (CSI, OSC, DCS, SOS, PM, APC, and two-byte escapes, introduced by ESC or by their C1
//! form), each replaced by one visible [`MARK`] so that the reader sees something was there.
//! Invisible characters that change what text means — a byte-order mark, the bidirectional
//! overrides and isolates — become the mark too.

use serde::{Deserialize, Deserializer, Serialize};
use std::fmt;

/// What stands where a control character or an escape sequence was removed.
pub const MARK: char = '\u{FFFD}';

/// Text made safe to show by [`clean`]: printable characters only, on one line.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(transparent)]
pub struct Clean(String);

impl Clean {
    /// `raw` cleaned (see the module).
    pub fn new(raw: &str) -> Clean {
        Clean(clean(raw))
    }

    pub fn as_str(&self) -> &str {
        &self.0
    }

    pub fn into_string(self) -> String {
        self.0
    }

    /// Whether cleaning changed anything (the text as read held controls, sequences or
    /// invisible marks).
    pub fn changed(raw: &str) -> bool {
        clean(raw) != raw
    }
}

impl std::ops::Deref for Clean {
    type Target = str;
    fn deref(&self) -> &str {
        &self.0
    }
}

impl AsRef<str> for Clean {
    fn as_ref(&self) -> &str {
        &self.0
    }
}

impl fmt::Display for Clean {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<&str> for Clean {
    fn from(s: &str) -> Clean {
        Clean::new(s)
    }
}

impl From<String> for Clean {
    fn from(s: String) -> Clean {
        Clean::new(&s)
    }
}

impl PartialEq<str> for Clean {
    fn eq(&self, other: &str) -> bool {
        self.0 == other
    }
}

impl PartialEq<String> for Clean {
    fn eq(&self, other: &String) -> bool {
        self.0 == *other
    }
}

impl PartialEq<&str> for Clean {
    fn eq(&self, other: &&str) -> bool {
        self.0 == *other
    }
}

/// Read from a file: cleaned as it is read.
impl<'de> Deserialize<'de> for Clean {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Clean, D::Error> {
        String::deserialize(d).map(|s| Clean::new(&s))
    }
}

/// Invisible characters that change how text reads: shown as [`MARK`].
fn invisible(c: char) -> bool {
    matches!(c,
        '\u{FEFF}'                      // byte-order mark, zero-width no-break space
        | '\u{200E}' | '\u{200F}'       // left-to-right, right-to-left marks
        | '\u{202A}'..='\u{202E}'       // bidirectional embeddings and overrides
        | '\u{2066}'..='\u{2069}'       // bidirectional isolates
        | '\u{061C}'                    // Arabic letter mark
    )
}

/// Whether `c` is shown as an escape or a mark rather than as itself, in messages
/// (`files::escape_controls`) as in [`clean`]: controls (C0, DEL, C1) and the invisible
/// characters that change how text reads.
pub fn needs_escape(c: char) -> bool {
    c.is_control() || invisible(c)
}

/// How a sequence opened by ESC X (or its C1 form) ends.
#[derive(Clone, Copy, PartialEq)]
enum Seq {
    /// CSI: parameters and intermediates (0x20–0x3F), then one final byte (0x40–0x7E).
    Csi,
    /// OSC: a string ended by BEL or ST (ESC \ or U+009C).
    Osc,
    /// DCS, SOS, PM, APC: a string ended by ST.
    Str,
}

/// `raw` made safe to show on one line (see the module): escape sequences removed whole,
/// other controls and invisible marks replaced, each by one [`MARK`]; a tab or a line break
/// becomes a blank. Idempotent: cleaning clean text changes nothing.
pub fn clean(raw: &str) -> String {
    let mut out = String::with_capacity(raw.len());
    let mut chars = raw.chars().peekable();
    while let Some(c) = chars.next() {
        let seq = match c {
            '\t' | '\n' => {
                out.push(' ');
                continue;
            }
            '\r' => {
                // CR LF is one line break; a lone CR would move the cursor.
                if chars.peek() == Some(&'\n') {
                    continue;
                }
                out.push(MARK);
                continue;
            }
            '\u{1b}' => match chars.peek().copied() {
                Some('[') => Some(Seq::Csi),
                Some(']') => Some(Seq::Osc),
                Some('P' | 'X' | '^' | '_') => Some(Seq::Str),
                // A two-byte escape (ESC c resets the terminal, ESC 7 saves the cursor…):
                // the ESC and its final byte.
                Some(n @ '\u{20}'..='\u{7e}') => {
                    chars.next();
                    // nF escapes (ESC SP F, ESC ( B …) carry one more byte.
                    if ('\u{20}'..='\u{2f}').contains(&n)
                        && chars
                            .peek()
                            .is_some_and(|f| ('\u{30}'..='\u{7e}').contains(f))
                    {
                        chars.next();
                    }
                    out.push(MARK);
                    continue;
                }
                _ => None,
            },
            '\u{9b}' => {
                out.push(MARK);
                skip_csi(&mut chars);
                continue;
            }
            '\u{9d}' => {
                out.push(MARK);
                skip_string(&mut chars, true);
                continue;
            }
            '\u{90}' | '\u{98}' | '\u{9e}' | '\u{9f}' => {
                out.push(MARK);
                skip_string(&mut chars, false);
                continue;
            }
            c if needs_escape(c) => {
                out.push(MARK);
                continue;
            }
            c => {
                out.push(c);
                continue;
            }
        };
        out.push(MARK);
        match seq {
            // A lone ESC.
            None => {}
            Some(s) => {
                chars.next();
                match s {
                    Seq::Csi => skip_csi(&mut chars),
                    Seq::Osc => skip_string(&mut chars, true),
                    Seq::Str => skip_string(&mut chars, false),
                }
            }
        }
    }
    out
}

/// Past a CSI's parameters, intermediates and final byte; stops early (keeping it) at any
/// character that cannot be in one.
fn skip_csi(chars: &mut std::iter::Peekable<std::str::Chars>) {
    while let Some(&c) = chars.peek() {
        match c {
            '\u{20}'..='\u{3f}' => {
                chars.next();
            }
            '\u{40}'..='\u{7e}' => {
                chars.next();
                return;
            }
            _ => return,
        }
    }
}

/// Past a control string up to and including its terminator: ST (ESC \ or U+009C), or BEL
/// for an OSC; an unterminated one runs to the end of the text.
fn skip_string(chars: &mut std::iter::Peekable<std::str::Chars>, bel_ends: bool) {
    while let Some(c) = chars.next() {
        match c {
            '\u{9c}' => return,
            '\u{7}' if bel_ends => return,
            '\u{1b}' => {
                if chars.peek() == Some(&'\\') {
                    chars.next();
                }
                return;
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sequences_go_whole_and_controls_are_marked() {
        let m = MARK;
        assert_eq!(clean("plain ξ = 1"), "plain ξ = 1");
        assert_eq!(clean("a\x1b]0;title\x07b"), format!("a{m}b"));
        assert_eq!(clean("a\x1b]52;c;SGVsbG8=\x1b\\b"), format!("a{m}b"));
        assert_eq!(clean("a\x1b[2J\x1b[1;31mb"), format!("a{m}{m}b"));
        assert_eq!(clean("a\x1bP1$qm\x1b\\b"), format!("a{m}b"));
        assert_eq!(clean("a\u{9b}2Jb\u{9d}0;t\u{9c}c"), format!("a{m}b{m}c"));
        assert_eq!(clean("a\x1bcb"), format!("a{m}b"));
        assert_eq!(clean("a\x1b(Bb"), format!("a{m}b"));
        assert_eq!(clean("a\x07b\rc\r\nd\te\n"), format!("a{m}b{m}c d e "));
        assert_eq!(clean("\u{feff}name\u{202e}"), format!("{m}name{m}"));
        assert_eq!(clean("a\x1b"), format!("a{m}"));
        assert_eq!(clean("a\x1b]0;unterminated"), format!("a{m}"));
        assert_eq!(clean("\u{85}\u{7f}\0"), format!("{m}{m}{m}"));
    }

    #[test]
    fn cleaning_is_idempotent_and_leaves_nothing_to_act_on() {
        for raw in [
            "\x1b[\x1b]\x07",
            "\u{9b}\u{9b}",
            "x\x1b\x1b[m",
            "\x1bP\x1b\\\x1b",
        ] {
            let once = clean(raw);
            assert_eq!(clean(&once), once, "{raw:?}");
            assert!(!once.chars().any(needs_escape), "{raw:?} → {once:?}");
        }
    }
}
