//! Key scripts (`*.keys`): a line-oriented text format that drives the app
//! headlessly, and a [`Recorder`] that writes one from a live session so a
//! demonstration can be replayed exactly.
//!
//! ```text
//! # turntable key script
//! resize 80x24
//! Right*5 space ?      # five presses of Right, then space, then ?
//! tick 600
//! snapshot after five turns
//! mouse click 10 5
//! q
//! ```
//!
//! A `#` that begins a token starts a comment, so the `#` key is written
//! `hash`.
//!
//! Three commands narrate a lesson (`crate::lesson`): `say TEXT` shows a caption over the
//! scene (`say` alone clears it), `ask TEXT` asks a yes/no prediction (yes: the run on screen
//! escapes) that the run then answers, and `wait` holds an interactive lesson until Enter
//! (headless it goes on). `play [SPEED]` and `pause` set time going or standing outright (a
//! toggle would depend on what the keys did before).

mod header;
mod record;

pub use header::{ScriptOptions, parse_size, quote_word, scene_line, script_options};
pub use record::Recorder;

use crate::app::Chord;
use crate::text::Clean;

use std::fmt;
use std::ops::RangeInclusive;

use crossterm::event::{KeyModifiers, MouseButton, MouseEvent, MouseEventKind};

/// Largest `*N` repeat on one key token.
pub const MAX_REPEAT: u32 = 100_000;
/// Largest `tick N`.
pub const MAX_TICKS: u64 = 10_000_000;
/// Most key steps one script may expand to, so a short file cannot demand
/// unbounded memory.
pub const MAX_KEYS: usize = 1_000_000;
/// Largest width or height accepted by `resize`.
pub const MAX_SIZE: u16 = 1000;

const HEADER: &str = "# turntable key script";

/// Mouse actions by their script word: the parser reads and the recorder writes this table.
const MOUSE: [(&str, MouseEventKind); 5] = [
    ("click", MouseEventKind::Down(MouseButton::Left)),
    ("drag", MouseEventKind::Drag(MouseButton::Left)),
    ("up", MouseEventKind::Up(MouseButton::Left)),
    ("scrollup", MouseEventKind::ScrollUp),
    ("scrolldown", MouseEventKind::ScrollDown),
];

/// One thing a script asks the app to do.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Step {
    Key(Chord),
    /// Let this many ticks of simulated time pass.
    Tick(u64),
    /// Resize the off-screen terminal to width × height cells.
    Resize(u16, u16),
    /// Emit the screen, with an optional label.
    Snapshot(Option<Clean>),
    Mouse(MouseEvent),
    /// A caption over the scene (None: clear it).
    Say(Option<Clean>),
    /// A prediction to make: yes means the run on screen escapes.
    Ask(Clean),
    /// Interactive: hold the lesson until Enter. Headless: nothing.
    Wait,
    /// Time plays, at speed 2^n when given (`play 0.25`), else at ×1: a lesson's scene names
    /// its state outright, whatever keys were pressed before.
    Play(Option<i8>),
    /// Time stands still.
    Pause,
}

/// Where and why a script failed to parse; `line` and `column` are 1-based
/// (column counts characters) so editors can jump to the offending token.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParseError {
    pub line: usize,
    pub column: usize,
    pub message: String,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "line {}, column {}: {}",
            self.line, self.column, self.message
        )
    }
}

impl std::error::Error for ParseError {}

/// A failure within one line: column and message.
type Fail = (usize, String);

struct Token<'a> {
    text: &'a str,
    /// 1-based character column.
    column: usize,
    /// Byte offset in the line, to slice snapshot labels verbatim.
    start: usize,
}

/// Splits a line at whitespace, stopping at a token that begins with `#`.
fn tokens(line: &str) -> Vec<Token<'_>> {
    let mut out = Vec::new();
    let mut open: Option<(usize, usize)> = None;
    for (column, (byte, c)) in line.char_indices().enumerate() {
        match open {
            Some((start, col)) if c.is_whitespace() => {
                out.push(Token {
                    text: &line[start..byte],
                    column: col,
                    start,
                });
                open = None;
            }
            None if c == '#' => return out,
            None if !c.is_whitespace() => open = Some((byte, column + 1)),
            _ => {}
        }
    }
    if let Some((start, column)) = open {
        out.push(Token {
            text: &line[start..],
            column,
            start,
        });
    }
    out
}

/// Parses a whole script, expanding `*N` repeats into repeated steps.
pub fn parse(text: &str) -> Result<Vec<Step>, ParseError> {
    if text.starts_with('\u{feff}') {
        return Err(ParseError {
            line: 1,
            column: 1,
            message: "the script begins with a byte-order mark (U+FEFF, invisible in most editors): save it as UTF-8 without one".into(),
        });
    }
    let mut steps = Vec::new();
    let mut keys = 0;
    for (index, line) in text.lines().enumerate() {
        parse_line(line, &mut steps, &mut keys).map_err(|(column, message)| ParseError {
            line: index + 1,
            column,
            message,
        })?;
    }
    Ok(steps)
}

/// Parses one line onto `steps`; `keys` counts key steps so far, for the cap.
fn parse_line(line: &str, steps: &mut Vec<Step>, keys: &mut usize) -> Result<(), Fail> {
    let toks = tokens(line);
    let Some(first) = toks.first() else {
        return Ok(());
    };
    let command = first.text.to_ascii_lowercase();
    let need = |what: &str| (first.column, format!("{command} needs {what}"));
    // Each arm returns how many tokens it consumed; any more are an error.
    let consumed = match command.as_str() {
        "tick" => {
            let n = match toks.get(1) {
                Some(t) => number(t.text, t.column, 1..=MAX_TICKS, "tick count")?,
                None => 1,
            };
            steps.push(Step::Tick(n));
            2
        }
        "resize" => {
            let t = toks
                .get(1)
                .ok_or_else(|| need("WxH, e.g. `resize 80x24`"))?;
            let (w, h) = t.text.split_once(['x', 'X']).ok_or_else(|| {
                (
                    t.column,
                    format!("bad size '{}': expected WxH, e.g. 80x24", t.text),
                )
            })?;
            let max = u64::from(MAX_SIZE);
            let width = number(w, t.column, 0..=max, "width")?;
            let h_column = t.column + w.chars().count() + 1;
            let height = number(h, h_column, 0..=max, "height")?;
            steps.push(Step::Resize(width as u16, height as u16));
            2
        }
        "snapshot" => {
            steps.push(Step::Snapshot(rest(line, &toks)));
            toks.len()
        }
        "say" => {
            steps.push(Step::Say(rest(line, &toks)));
            toks.len()
        }
        "ask" => {
            let text = rest(line, &toks)
                .ok_or_else(|| need("a question, e.g. `ask Will it escape? (y/n)`"))?;
            steps.push(Step::Ask(text));
            toks.len()
        }
        "wait" => {
            steps.push(Step::Wait);
            1
        }
        "pause" => {
            steps.push(Step::Pause);
            1
        }
        "play" => {
            let power = toks.get(1).map(|t| speed(t.text, t.column)).transpose()?;
            steps.push(Step::Play(power));
            2
        }
        "mouse" => {
            let [_, action, x, y, ..] = toks.as_slice() else {
                return Err(need("an action and X Y, e.g. `mouse click 10 5`"));
            };
            let Some(&(_, kind)) = MOUSE
                .iter()
                .find(|(word, _)| word.eq_ignore_ascii_case(action.text))
            else {
                let words: Vec<&str> = MOUSE.iter().map(|m| m.0).collect();
                return Err((
                    action.column,
                    format!(
                        "unknown mouse action '{}' ({})",
                        action.text,
                        words.join(", ")
                    ),
                ));
            };
            let cell = 0..=u64::from(u16::MAX);
            steps.push(Step::Mouse(MouseEvent {
                kind,
                column: number(x.text, x.column, cell.clone(), "mouse X")? as u16,
                row: number(y.text, y.column, cell, "mouse Y")? as u16,
                modifiers: KeyModifiers::NONE,
            }));
            4
        }
        _ => {
            for (i, tok) in toks.iter().enumerate() {
                let (key, count) = key_token(tok, i == 0)?;
                *keys += count;
                if *keys > MAX_KEYS {
                    return Err((
                        tok.column,
                        format!("script expands to more than {MAX_KEYS} key presses"),
                    ));
                }
                steps.extend(std::iter::repeat_n(Step::Key(key), count));
            }
            toks.len()
        }
    };
    match toks.get(consumed) {
        Some(extra) => Err((
            extra.column,
            format!("unexpected '{}' after {command}", extra.text),
        )),
        None => Ok(()),
    }
}

/// The line after its command, as written (inner blanks kept, a comment left out) and
/// cleaned (`crate::text`); None when there is nothing after it.
fn rest(line: &str, toks: &[Token]) -> Option<Clean> {
    toks.get(1)
        .zip(toks.last())
        .map(|(from, to)| Clean::new(&line[from.start..to.start + to.text.len()]))
}

/// Parses a key token with its optional `*N` repeat; `*` alone (or last)
/// is the star key itself.
fn key_token(tok: &Token, first: bool) -> Result<(Chord, usize), Fail> {
    let (name, count) = match tok.text.rfind('*') {
        Some(i) if i > 0 && i + 1 < tok.text.len() => {
            let max = u64::from(MAX_REPEAT);
            let n = number(&tok.text[i + 1..], tok.column, 1..=max, "repeat count")?;
            (&tok.text[..i], n as usize)
        }
        _ => (tok.text, 1),
    };
    let key = name.parse().map_err(|_| {
        // A lone unknown word at the start of a line is most likely a
        // misspelt command.
        let what = if first && name.chars().count() > 1 && name.chars().all(char::is_alphabetic) {
            "command or key"
        } else {
            "key"
        };
        (tok.column, format!("unknown {what} '{name}'"))
    })?;
    Ok((key, count))
}

/// Parses a decimal number, insisting on plain digits so `+5` or `5.0` are
/// reported rather than silently accepted.
/// A `play` speed as its power of two (0.25, 1/4 or x0.25 is −2), a power of two in the
/// app's speed range.
fn speed(text: &str, column: usize) -> Result<i8, Fail> {
    let x = match text.split_once('/') {
        Some((a, b)) => a
            .parse::<f64>()
            .ok()
            .zip(b.parse::<f64>().ok())
            .map(|(a, b)| a / b),
        None => text.trim_start_matches(['x', '×']).parse().ok(),
    };
    x.and_then(crate::app::speed_power).ok_or_else(|| {
        (
            column,
            format!(
                "play's speed '{text}' is not a power of two from 1/64 to 256 (e.g. 0.25, 1, 4)"
            ),
        )
    })
}

fn number(text: &str, column: usize, range: RangeInclusive<u64>, what: &str) -> Result<u64, Fail> {
    if text.is_empty() || !text.bytes().all(|b| b.is_ascii_digit()) {
        return Err((column, format!("{what} '{text}' is not a number")));
    }
    match text.parse() {
        Ok(n) if range.contains(&n) => Ok(n),
        _ => Err((
            column,
            format!(
                "{what} {text} is out of range {}..={}",
                range.start(),
                range.end()
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crossterm::event::{KeyCode, KeyEvent, KeyEventKind};

    fn key(code: KeyCode, modifiers: KeyModifiers) -> Step {
        Step::Key(Chord::new(code, modifiers))
    }

    fn key_name(event: &KeyEvent) -> Option<String> {
        Chord::from_event(event).map(|c| c.to_string())
    }

    fn plain(code: KeyCode) -> Step {
        key(code, KeyModifiers::NONE)
    }

    fn err(text: &str) -> (usize, usize, String) {
        let e = parse(text).expect_err(text);
        (e.line, e.column, e.message)
    }

    fn assert_err(text: &str, line: usize, column: usize, needle: &str) {
        let (l, c, m) = err(text);
        assert_eq!((l, c), (line, column), "{text:?}: {m}");
        assert!(m.contains(needle), "{text:?}: {m:?} lacks {needle:?}");
    }

    #[test]
    fn every_key_name() {
        use KeyCode::*;
        let none = KeyModifiers::NONE;
        let cases = [
            ("a", Char('a'), none),
            ("A", Char('A'), none),
            ("?", Char('?'), none),
            ("+", Char('+'), none),
            ("-", Char('-'), none),
            ("[", Char('['), none),
            ("<", Char('<'), none),
            ("*", Char('*'), none),
            ("é", Char('é'), none),
            ("space", Char(' '), none),
            ("hash", Char('#'), none),
            ("enter", Enter, none),
            ("esc", Esc, none),
            ("tab", Tab, none),
            ("backtab", BackTab, none),
            ("backspace", Backspace, none),
            ("delete", Delete, none),
            ("up", Up, none),
            ("down", Down, none),
            ("left", Left, none),
            ("right", Right, none),
            ("home", Home, none),
            ("end", End, none),
            ("pgup", PageUp, none),
            ("pgdn", PageDown, none),
            ("ctrl-c", Char('c'), KeyModifiers::CONTROL),
            ("alt-x", Char('x'), KeyModifiers::ALT),
            ("shift-up", Up, KeyModifiers::SHIFT),
            ("ctrl--", Char('-'), KeyModifiers::CONTROL),
            ("ctrl-*", Char('*'), KeyModifiers::CONTROL),
            (
                "ctrl-alt-delete",
                Delete,
                KeyModifiers::CONTROL | KeyModifiers::ALT,
            ),
        ];
        for (name, code, modifiers) in cases {
            let event = KeyEvent::new(code, modifiers);
            assert_eq!(parse(name), Ok(vec![key(code, modifiers)]), "{name}");
            assert_eq!(key_name(&event).as_deref(), Some(name), "{name}");
        }
        for n in 1..=12 {
            let name = format!("f{n}");
            assert_eq!(parse(&name), Ok(vec![plain(F(n))]));
            assert_eq!(key_name(&KeyEvent::from(F(n))), Some(name));
        }
    }

    #[test]
    fn named_keys_and_modifiers_ignore_case_but_characters_do_not() {
        let ctrl = KeyModifiers::CONTROL;
        assert_eq!(
            parse("Right SPACE F12 Ctrl-c CTRL-ALT-Tab"),
            Ok(vec![
                plain(KeyCode::Right),
                plain(KeyCode::Char(' ')),
                plain(KeyCode::F(12)),
                key(KeyCode::Char('c'), ctrl),
                key(KeyCode::Tab, ctrl | KeyModifiers::ALT),
            ])
        );
        assert_ne!(parse("a"), parse("A"));
    }

    #[test]
    fn shift_on_a_character_gives_the_shifted_character() {
        let big_a = plain(KeyCode::Char('A'));
        assert_eq!(parse("shift-a"), Ok(vec![big_a.clone()]));
        assert_eq!(parse("A"), Ok(vec![big_a]));
        assert_eq!(
            parse("alt-shift-x"),
            Ok(vec![key(KeyCode::Char('X'), KeyModifiers::ALT)])
        );
        let shifted = KeyEvent::new(KeyCode::Char('a'), KeyModifiers::SHIFT);
        assert_eq!(key_name(&shifted).as_deref(), Some("A"));
    }

    #[test]
    fn repeats_expand() {
        let right = plain(KeyCode::Right);
        let star = plain(KeyCode::Char('*'));
        let mut expected = vec![right; 5];
        expected.extend([star.clone(), star.clone(), star]);
        expected.push(plain(KeyCode::Char('q')));
        assert_eq!(parse("Right*5 **3 q*1"), Ok(expected));
    }

    #[test]
    fn commands() {
        let text = "tick\nTICK 25\nresize 0x1\nresize 1000X1000\nsnapshot\n\
                    snapshot  after   five turns  # note\n\
                    mouse click 3 4\nmouse drag 5 6\nmouse up 0 65535\n";
        let at = |kind, column, row| {
            Step::Mouse(MouseEvent {
                kind,
                column,
                row,
                modifiers: KeyModifiers::NONE,
            })
        };
        assert_eq!(
            parse(text),
            Ok(vec![
                Step::Tick(1),
                Step::Tick(25),
                Step::Resize(0, 1),
                Step::Resize(1000, 1000),
                Step::Snapshot(None),
                Step::Snapshot(Some("after   five turns".into())),
                at(MouseEventKind::Down(MouseButton::Left), 3, 4),
                at(MouseEventKind::Drag(MouseButton::Left), 5, 6),
                at(MouseEventKind::Up(MouseButton::Left), 0, 65535),
            ])
        );
    }

    #[test]
    fn lesson_commands() {
        assert_eq!(
            parse(
                "say  Friction  holds it. # note\nSAY\nask Will it escape? (y/n)\nwait\nplay\nplay 0.25\nPLAY 1/64\nplay x4\npause\n"
            ),
            Ok(vec![
                Step::Say(Some("Friction  holds it.".into())),
                Step::Say(None),
                Step::Ask("Will it escape? (y/n)".into()),
                Step::Wait,
                Step::Play(None),
                Step::Play(Some(-2)),
                Step::Play(Some(-6)),
                Step::Play(Some(2)),
                Step::Pause,
            ])
        );
    }

    #[test]
    fn comments_and_blank_lines() {
        let text = "# header\n\n   \n\ta # the rest is ignored\n  #indented\nb#c\n";
        let e = parse(text).unwrap_err();
        assert_eq!(
            (e.line, e.column),
            (6, 1),
            "a # inside a token is not a comment"
        );
        assert_eq!(
            parse("# header\n\n   \n\ta # the rest\n  #indented\nsnapshot # none\n"),
            Ok(vec![plain(KeyCode::Char('a')), Step::Snapshot(None)])
        );
    }

    #[test]
    fn errors_name_line_and_column() {
        assert_err("a\n  b nope", 2, 5, "unknown key 'nope'");
        assert_err("hold 5", 1, 1, "unknown command or key 'hold'");
        assert_err("wait 5", 1, 6, "unexpected '5' after wait");
        assert_err("ask", 1, 1, "ask needs a question");
        assert_err("play 3", 1, 6, "not a power of two");
        assert_err("play 512", 1, 6, "from 1/64 to 256");
        assert_err("play fast", 1, 6, "play's speed 'fast'");
        assert_err("pause 2", 1, 7, "unexpected '2' after pause");
        assert_err("ask # only a comment", 1, 1, "ask needs a question");
        assert_err("ctrl-", 1, 1, "unknown key 'ctrl-'");
        assert_err("f13", 1, 1, "unknown key 'f13'");
        assert_err("f01", 1, 1, "unknown key");
        assert_err("*5", 1, 1, "unknown key '*5'");
        assert_err("x a*0", 1, 3, "repeat count 0 is out of range 1..=100000");
        assert_err("a*100001", 1, 1, "out of range");
        assert_err("a*b", 1, 1, "repeat count 'b' is not a number");
        assert_err("tick 0", 1, 6, "tick count 0 is out of range");
        assert_err("tick 10000001", 1, 6, "out of range");
        assert_err("tick +5", 1, 6, "tick count '+5' is not a number");
        assert_err("tick 99999999999999999999999", 1, 6, "out of range");
        assert_err("tick 5 6", 1, 8, "unexpected '6' after tick");
        assert_err("resize", 1, 1, "resize needs WxH");
        assert_err("resize 80", 1, 8, "bad size '80'");
        assert_err("resize 80x", 1, 11, "height '' is not a number");
        assert_err("resize 1001x5", 1, 8, "width 1001 is out of range 0..=1000");
        assert_err("resize 10x2000", 1, 11, "height 2000 is out of range");
        assert_err("resize 1x1 extra", 1, 12, "unexpected 'extra'");
        assert_err("mouse click 1", 1, 1, "mouse needs an action");
        assert_err("mouse wiggle 1 2", 1, 7, "unknown mouse action 'wiggle'");
        assert_err("mouse up 1 -2", 1, 12, "mouse Y '-2' is not a number");
        assert_err("mouse up 1 2 3", 1, 14, "unexpected '3'");
    }

    #[test]
    fn error_display() {
        let e = parse("tick\n  bogus").unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 2, column 3: unknown command or key 'bogus'"
        );
    }

    #[test]
    fn expansion_is_capped() {
        let line = "a*100000 ".repeat(10);
        assert_eq!(parse(&line).map(|s| s.len()), Ok(MAX_KEYS));
        let e = parse(&format!("{line}\n  b")).unwrap_err();
        assert_eq!((e.line, e.column), (2, 3));
        assert!(e.message.contains("more than 1000000"), "{}", e.message);
    }

    #[test]
    fn unexpressible_keys() {
        let release = KeyEvent::new_with_kind(
            KeyCode::Char('a'),
            KeyModifiers::NONE,
            KeyEventKind::Release,
        );
        for k in [
            release,
            KeyEvent::from(KeyCode::F(13)),
            KeyEvent::from(KeyCode::Insert),
            KeyEvent::from(KeyCode::Char('\u{7}')),
            KeyEvent::new(KeyCode::Char('a'), KeyModifiers::SUPER),
        ] {
            assert_eq!(key_name(&k), None, "{k:?}");
        }
    }

    /// Merges adjacent ticks, as the recorder does.
    fn coalesce(steps: Vec<Step>) -> Vec<Step> {
        let mut out: Vec<Step> = Vec::new();
        for step in steps {
            match (out.last_mut(), &step) {
                (Some(Step::Tick(a)), Step::Tick(b)) => *a += b,
                _ => out.push(step),
            }
        }
        out
    }

    #[test]
    fn recorder_output_is_compact() {
        let mut r = Recorder::new();
        r.resize(80, 24);
        for _ in 0..3 {
            r.tick();
        }
        for code in [KeyCode::Right, KeyCode::Right, KeyCode::Char('?')] {
            r.key(Chord::new(code, KeyModifiers::NONE));
        }
        r.tick();
        r.key(Chord::new(KeyCode::Char('c'), KeyModifiers::CONTROL));
        r.resize(2000, 5);
        assert_eq!(
            r.finish(),
            "# turntable key script\nresize 80x24\ntick 3\nright*2 ?\ntick\nctrl-c\nresize 1000x5\n"
        );
    }

    #[test]
    fn recorder_round_trips() {
        let ctrl = KeyModifiers::CONTROL;
        let events = [
            Step::Tick(1),
            Step::Tick(1),
            plain(KeyCode::Char('#')),
            plain(KeyCode::Char('*')),
            plain(KeyCode::Char('*')),
            plain(KeyCode::Char(' ')),
            plain(KeyCode::F(3)),
            key(KeyCode::Char('-'), ctrl),
            Step::Resize(0, 0),
            key(KeyCode::Left, KeyModifiers::SHIFT),
            Step::Tick(1),
            plain(KeyCode::Char('A')),
            plain(KeyCode::Char('a')),
            plain(KeyCode::Char('a')),
        ];
        let mut r = Recorder::new();
        for step in &events {
            match step {
                Step::Key(k) => r.key(*k),
                Step::Tick(_) => r.tick(),
                Step::Resize(w, h) => r.resize(*w, *h),
                _ => unreachable!(),
            }
        }
        let text = r.finish();
        assert!(text.starts_with("# turntable key script\n"));
        assert_eq!(parse(&text), Ok(coalesce(events.to_vec())), "{text}");
    }

    #[test]
    fn recorder_splits_runs_at_the_limits() {
        let mut r = Recorder::new();
        for _ in 0..=MAX_REPEAT {
            r.key(Chord::new(KeyCode::Up, KeyModifiers::NONE));
        }
        for _ in 0..=MAX_TICKS {
            r.tick();
        }
        let text = r.finish();
        assert!(
            text.ends_with("\nup*100000 up\ntick 10000000\ntick\n"),
            "{text}"
        );
        assert!(parse(&text).is_ok());
    }

    #[test]
    fn recorder_writes_mouse_events() {
        let ev = |kind, column, row| MouseEvent {
            kind,
            column,
            row,
            modifiers: KeyModifiers::NONE,
        };
        let events = [
            ev(MouseEventKind::Down(MouseButton::Left), 3, 4),
            ev(MouseEventKind::Drag(MouseButton::Left), 5, 6),
            ev(MouseEventKind::Up(MouseButton::Left), 7, 8),
            ev(MouseEventKind::ScrollUp, 1, 2),
            ev(MouseEventKind::ScrollDown, 0, 0),
        ];
        let mut r = Recorder::new();
        r.key(Chord::new(KeyCode::Up, KeyModifiers::NONE));
        for e in &events {
            assert!(r.mouse(e));
        }
        assert!(!r.mouse(&ev(MouseEventKind::Moved, 1, 1)));
        assert!(!r.mouse(&ev(MouseEventKind::Down(MouseButton::Right), 1, 1)));
        let mut expected = vec![plain(KeyCode::Up)];
        expected.extend(events.iter().map(|e| Step::Mouse(*e)));
        assert_eq!(parse(&r.finish()), Ok(expected));
    }
}
