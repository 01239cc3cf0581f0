//! Writes a key script from a live session.

use super::{HEADER, MAX_REPEAT, MAX_SIZE, MAX_TICKS, MOUSE};
use crate::app::Chord;
use crossterm::event::{MouseButton, MouseEvent, MouseEventKind};

/// Writes a key script from live events, folding runs of ticks and of
/// identical keys so that a recorded session stays short and readable.
#[derive(Clone, Debug, Default)]
pub struct Recorder {
    out: String,
    /// Key tokens written so far on the current line.
    line: String,
    /// The key being repeated, and how many times.
    run: Option<(String, u32)>,
    ticks: u64,
}

impl Recorder {
    pub fn new() -> Self {
        Self::default()
    }

    /// Records a key press.
    pub fn key(&mut self, chord: Chord) {
        let name = chord.to_string();
        self.flush_ticks();
        match &mut self.run {
            Some((last, n)) if *last == name && *n < MAX_REPEAT => *n += 1,
            _ => {
                self.end_run();
                self.run = Some((name, 1));
            }
        }
    }

    pub fn tick(&mut self) {
        self.flush_keys();
        self.ticks += 1;
        if self.ticks == MAX_TICKS {
            self.flush_ticks();
        }
    }

    /// Records a mouse event; returns false (and records nothing) for what
    /// the format cannot express (presses and drags of buttons other than
    /// the left one, plain moves, horizontal scrolling). Modifiers are
    /// dropped and any button's release is written `up`: the app looks at
    /// neither.
    pub fn mouse(&mut self, event: &MouseEvent) -> bool {
        let kind = match event.kind {
            MouseEventKind::Up(_) => MouseEventKind::Up(MouseButton::Left),
            kind => kind,
        };
        let Some((action, _)) = MOUSE.iter().find(|m| m.1 == kind) else {
            return false;
        };
        self.flush_keys();
        self.flush_ticks();
        self.out
            .push_str(&format!("mouse {action} {} {}\n", event.column, event.row));
        true
    }

    /// Records a resize, clamped to [`MAX_SIZE`] so the script stays
    /// parseable even from an enormous terminal.
    pub fn resize(&mut self, width: u16, height: u16) {
        self.flush_keys();
        self.flush_ticks();
        let (w, h) = (width.min(MAX_SIZE), height.min(MAX_SIZE));
        self.out.push_str(&format!("resize {w}x{h}\n"));
    }

    /// The finished script, starting with a header comment.
    pub fn finish(mut self) -> String {
        self.flush_keys();
        self.flush_ticks();
        format!("{HEADER}\n{}", self.out)
    }

    fn end_run(&mut self) {
        if let Some((name, n)) = self.run.take() {
            if !self.line.is_empty() {
                self.line.push(' ');
            }
            self.line.push_str(&name);
            if n > 1 {
                self.line.push_str(&format!("*{n}"));
            }
        }
    }

    fn flush_keys(&mut self) {
        self.end_run();
        if !self.line.is_empty() {
            self.out.push_str(&self.line);
            self.out.push('\n');
            self.line.clear();
        }
    }

    fn flush_ticks(&mut self) {
        match self.ticks {
            0 => {}
            1 => self.out.push_str("tick\n"),
            n => self.out.push_str(&format!("tick {n}\n")),
        }
        self.ticks = 0;
    }
}
