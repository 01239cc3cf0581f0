//! A student in plain mode over SSH (`ssh plain@HOST`, or `TURNTABLE_PLAIN=1` sent by the
//! client): the explorer and the class said in lines a screen reader reads, as
//! `turntable --plain` says them (`ui::plain`): no screen drawn, no escape sequence, no mouse.

use super::{Remote, Screen};
use crate::session::Explorer;
use crate::ui::plain::{Seen, opening};
use std::io::{self, Write};

/// Writes `lines`, each ended by CR LF: the client's terminal is raw while ssh holds it, so a
/// bare LF would not return the cursor. A caption's paragraphs are lines of their own.
fn write_lines(s: &mut Explorer<Screen>, lines: Vec<String>) -> io::Result<()> {
    let b = s.term.backend_mut();
    for line in lines.iter().flat_map(|l| l.split('\n')) {
        b.write_all(line.as_bytes())?;
        b.write_all(b"\r\n")?;
    }
    Ok(())
}

impl Remote<'_> {
    /// The first lines (how to use plain mode, the scene, its release), and what a follower
    /// may do besides.
    pub(super) fn open_plain(&mut self, s: &mut Explorer<Screen>) -> io::Result<()> {
        let mut lines = opening(&s.app);
        lines.push(
            "in a class: F2 follows the presenter or steps out; y and n answer a question".into(),
        );
        write_lines(s, lines)?;
        self.plain = Some(Seen::of(&s.app));
        Ok(())
    }

    /// What changed since the last lines, written (they wait while the channel has not
    /// taken the last ones, and are then said together). Whether there were any.
    pub(super) fn say_plain(&mut self, s: &mut Explorer<Screen>) -> io::Result<bool> {
        let Some(seen) = self.plain.as_mut() else {
            return Ok(false);
        };
        let lines = seen.news(&s.app);
        let any = !lines.is_empty();
        write_lines(s, lines)?;
        Ok(any)
    }
}
