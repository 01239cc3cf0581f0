//! Key scripts run headlessly: the real [`App`] update and [`crate::ui::draw`] code on an
//! off-screen [`TestBackend`], with each `snapshot` printed as plain text (or ANSI-styled
//! text). The same [`Session`] drives the interactive loop, so what `--record` writes is
//! exactly what a replay applies.
//!
//! Nothing here reads the clock or the environment: the same script gives byte-identical
//! output on every run and machine.

use crate::app::App;
use crate::script::{Recorder, Step};
use crossterm::event::{KeyEvent, KeyEventKind, MouseEvent};
use ratatui::Terminal;
use ratatui::backend::{Backend, TestBackend};
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use std::convert::Infallible;
use std::sync::{Arc, Mutex, MutexGuard};
use unicode_width::UnicodeWidthStr;

/// Size of the off-screen terminal unless the script or `--size` says otherwise.
pub const DEFAULT_SIZE: (u16, u16) = (80, 24);

/// A recorder the terminal loop shares with its signal watcher, which saves what was recorded
/// if the terminal dies under the explorer.
pub type SharedRecorder = Arc<Mutex<Recorder>>;

/// The recorder, whatever a panicking holder left behind.
pub fn lock(r: &SharedRecorder) -> MutexGuard<'_, Recorder> {
    r.lock().unwrap_or_else(|e| e.into_inner())
}

/// The app, a terminal to draw it on, and optionally a recorder of everything applied.
/// Every event goes through here, in the interactive loop and in a replay alike.
pub struct Session<B: Backend> {
    pub app: App,
    pub term: Terminal<B>,
    recorder: Option<SharedRecorder>,
}

impl<B: Backend> Session<B> {
    /// With `record`, the script starts with the terminal's current size.
    pub fn new(app: App, backend: B, record: bool) -> Result<Self, B::Error> {
        let term = Terminal::new(backend)?;
        let recorder = if record {
            let size = term.size()?;
            let mut r = Recorder::new();
            r.resize(size.width, size.height);
            Some(Arc::new(Mutex::new(r)))
        } else {
            None
        };
        Ok(Session {
            app,
            term,
            recorder,
        })
    }

    /// A key press (releases are ignored, repeats count as presses).
    pub fn key(&mut self, key: KeyEvent) {
        if key.kind == KeyEventKind::Release {
            return;
        }
        let key = KeyEvent {
            kind: KeyEventKind::Press,
            ..key
        };
        if let Some(r) = &self.recorder {
            lock(r).key(&key);
        }
        self.app.handle_key(key);
    }

    /// A mouse event. The app maps cells through the canvas as last drawn, so anything
    /// changed since the last frame is drawn first: a recording and its replay then see the
    /// same canvas whatever else happened in between.
    pub fn mouse(&mut self, ev: MouseEvent) -> Result<(), B::Error> {
        self.draw_if_needed()?;
        if let Some(r) = &self.recorder {
            lock(r).mouse(&ev);
        }
        self.app.handle_mouse(ev);
        Ok(())
    }

    /// One tick of the app's clock (as the interactive loop calls it while playing).
    pub fn tick(&mut self) {
        if let Some(r) = &self.recorder {
            lock(r).tick();
        }
        self.app.tick();
    }

    /// The terminal is now `width` × `height`: recorded, and the next frame is redrawn.
    pub fn resized(&mut self, width: u16, height: u16) {
        if let Some(r) = &self.recorder {
            lock(r).resize(width, height);
        }
        self.app.invalidate();
    }

    pub fn draw(&mut self) -> Result<(), B::Error> {
        self.term.draw(|f| crate::ui::draw(f, &mut self.app))?;
        Ok(())
    }

    /// Draws when the app asks for it; returns whether it drew.
    pub fn draw_if_needed(&mut self) -> Result<bool, B::Error> {
        if self.app.needs_redraw() {
            self.draw()?;
            return Ok(true);
        }
        Ok(false)
    }

    /// The script recorded so far (None when not recording); recording stops here.
    pub fn take_recording(&mut self) -> Option<String> {
        self.recorder.take().map(|r| lock(&r).clone().finish())
    }

    /// The recorder, to read what was recorded from elsewhere (None when not recording).
    pub fn recorder(&self) -> Option<SharedRecorder> {
        self.recorder.clone()
    }
}

fn ok<T>(r: Result<T, Infallible>) -> T {
    match r {
        Ok(v) => v,
        Err(e) => match e {},
    }
}

impl Session<TestBackend> {
    /// A session on an off-screen terminal of `width` × `height` cells.
    pub fn headless(app: App, width: u16, height: u16, record: bool) -> Self {
        ok(Session::new(app, TestBackend::new(width, height), record))
    }

    pub fn resize(&mut self, width: u16, height: u16) {
        self.term.backend_mut().resize(width, height);
        self.resized(width, height);
    }

    /// Draws the whole screen and returns it.
    pub fn screen(&mut self) -> &Buffer {
        ok(self.draw());
        self.term.backend().buffer()
    }

    /// Applies one script step (a snapshot step only draws; see [`replay`] for the output).
    pub fn apply(&mut self, step: &Step) {
        match step {
            Step::Key(k) => self.key(*k),
            Step::Tick(n) => {
                for _ in 0..*n {
                    // Paused, a tick changes nothing (and a tick cannot unpause).
                    if !self.app.is_playing() {
                        break;
                    }
                    self.tick();
                }
            }
            Step::Resize(w, h) => self.resize(*w, *h),
            Step::Snapshot(_) => {
                self.screen();
            }
            Step::Mouse(m) => ok(self.mouse(*m)),
        }
    }
}

/// `WxH`, each at most the scripts' own limit.
pub fn parse_size(s: &str) -> Result<(u16, u16), String> {
    let bad = || format!("bad size '{s}': expected WxH, e.g. 80x24");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let n = |t: &str| -> Result<u16, String> {
        if t.is_empty() || !t.bytes().all(|b| b.is_ascii_digit()) {
            return Err(bad());
        }
        match t.parse::<u16>() {
            Ok(v) if v <= crate::script::MAX_SIZE => Ok(v),
            _ => Err(format!(
                "size {t} out of range 0..={}",
                crate::script::MAX_SIZE
            )),
        }
    };
    Ok((n(w)?, n(h)?))
}

/// What a script asks for itself, in `# replay: [--size WxH] [--ansi] [--scene S] [--theme T]`
/// comment lines (a recording names its scene this way); command-line flags take precedence.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ScriptOptions {
    pub size: Option<(u16, u16)>,
    pub ansi: bool,
    pub scene: Option<String>,
    pub theme: Option<String>,
}

pub fn script_options(text: &str) -> Result<ScriptOptions, String> {
    let mut o = ScriptOptions::default();
    for (n, line) in text.lines().enumerate() {
        let Some(args) = line.trim_start().strip_prefix("# replay:") else {
            continue;
        };
        let words = split_words(args).map_err(|e| format!("line {}: {e}", n + 1))?;
        let mut it = words.iter().map(String::as_str);
        while let Some(a) = it.next() {
            let mut value = || {
                it.next()
                    .ok_or_else(|| format!("line {}: {a} needs a value", n + 1))
            };
            match a {
                "--ansi" => o.ansi = true,
                "--size" => {
                    o.size = Some(parse_size(value()?).map_err(|e| format!("line {}: {e}", n + 1))?)
                }
                "--scene" => o.scene = Some(value()?.to_string()),
                "--theme" => o.theme = Some(value()?.to_string()),
                other => return Err(format!("line {}: unknown replay option '{other}'", n + 1)),
            }
        }
    }
    Ok(o)
}

/// Splits a `# replay:` line into words: blanks separate them, and a word in double quotes
/// may hold blanks (`\\` and `\"` inside quotes stand for `\` and `"`).
fn split_words(line: &str) -> Result<Vec<String>, String> {
    let mut words = Vec::new();
    let mut chars = line.chars().peekable();
    while let Some(&c) = chars.peek() {
        if c.is_whitespace() {
            chars.next();
            continue;
        }
        let mut w = String::new();
        if c == '"' {
            chars.next();
            loop {
                match chars.next() {
                    Some('"') => break,
                    Some('\\') => w.push(chars.next().ok_or("unterminated quote")?),
                    Some(c) => w.push(c),
                    None => return Err("unterminated quote".into()),
                }
            }
        } else {
            while let Some(&c) = chars.peek() {
                if c.is_whitespace() {
                    break;
                }
                w.push(c);
                chars.next();
            }
        }
        words.push(w);
    }
    Ok(words)
}

/// A word as [`split_words`] reads it back: quoted if it holds blanks, quotes or backslashes.
pub fn quote_word(w: &str) -> String {
    if !w.is_empty() && !w.contains(|c: char| c.is_whitespace() || c == '"' || c == '\\') {
        return w.to_string();
    }
    let mut q = String::from('"');
    for c in w.chars() {
        if c == '"' || c == '\\' {
            q.push('\\');
        }
        q.push(c);
    }
    q.push('"');
    q
}

/// How to run a script.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// Initial terminal size (a `resize` step changes it).
    pub size: (u16, u16),
    /// Style snapshots with ANSI SGR sequences from each cell's colours and modifiers.
    pub ansi: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            size: DEFAULT_SIZE,
            ansi: false,
        }
    }
}

/// Runs `steps` against `app` and returns the snapshots, each after a header line
/// `--- snapshot N: LABEL (WxH, tau=T)`. A quit stops the script there; a script without
/// any snapshot gets one of its final screen.
pub fn replay(app: App, steps: &[Step], opts: &Options) -> String {
    let mut out = Vec::new();
    replay_to(app, steps, opts, &mut out).expect("writing to memory cannot fail");
    String::from_utf8(out).expect("screens are UTF-8")
}

/// Runs `steps` as [`replay`] does, writing each snapshot to `out` as it is taken, so that
/// memory stays bounded however many there are.
pub fn replay_to(
    app: App,
    steps: &[Step],
    opts: &Options,
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    let mut s = Session::headless(app, opts.size.0, opts.size.1, false);
    let mut shots = 0;
    for step in steps {
        if s.app.should_quit() {
            break;
        }
        match step {
            Step::Snapshot(label) => {
                shots += 1;
                snapshot(&mut s, out, shots, label.as_deref(), opts.ansi)?;
            }
            step => s.apply(step),
        }
    }
    if shots == 0 {
        snapshot(&mut s, out, 1, Some("final"), opts.ansi)?;
    }
    out.flush()
}

fn snapshot(
    s: &mut Session<TestBackend>,
    out: &mut dyn std::io::Write,
    n: usize,
    label: Option<&str>,
    ansi: bool,
) -> std::io::Result<()> {
    let tau = s.app.now().tau;
    let buf = s.screen();
    let (w, h) = (buf.area.width, buf.area.height);
    let label = label.map(|l| format!(": {l}")).unwrap_or_default();
    writeln!(out, "--- snapshot {n}{label} ({w}x{h}, tau={tau:.3})")?;
    let text = if ansi {
        ansi_text(buf)
    } else {
        plain_text(buf)
    };
    out.write_all(text.as_bytes())
}

/// The cells of each row that are drawn: a wide symbol hides the cells it covers.
fn rows(buf: &Buffer) -> impl Iterator<Item = Vec<&ratatui::buffer::Cell>> {
    let w = usize::from(buf.area.width).max(1);
    buf.content.chunks(w).map(|cells| {
        let mut shown = Vec::with_capacity(cells.len());
        let mut skip = 0usize;
        for c in cells {
            if skip == 0 {
                shown.push(c);
            }
            skip = skip.max(c.symbol().width()).saturating_sub(1);
        }
        shown
    })
}

/// The screen as plain text, one line per row, trailing blanks trimmed.
pub fn plain_text(buf: &Buffer) -> String {
    let mut out = String::new();
    for row in rows(buf) {
        let line: String = row.iter().map(|c| c.symbol()).collect();
        out.push_str(line.trim_end_matches(' '));
        out.push('\n');
    }
    out
}

/// The screen with SGR sequences: a full reset and the cell's style whenever the style
/// changes along a row, and a reset at the end of each row.
pub fn ansi_text(buf: &Buffer) -> String {
    let mut out = String::new();
    for row in rows(buf) {
        let mut current = None;
        for c in row {
            let style = (c.fg, c.bg, c.modifier);
            if current != Some(style) {
                out.push_str(&sgr(c.fg, c.bg, c.modifier));
                current = Some(style);
            }
            out.push_str(c.symbol());
        }
        out.push_str("\x1b[0m\n");
    }
    out
}

fn sgr(fg: Color, bg: Color, m: Modifier) -> String {
    let mut codes = vec!["0".to_string()];
    for (flag, code) in [
        (Modifier::BOLD, "1"),
        (Modifier::DIM, "2"),
        (Modifier::ITALIC, "3"),
        (Modifier::UNDERLINED, "4"),
        (Modifier::SLOW_BLINK, "5"),
        (Modifier::RAPID_BLINK, "6"),
        (Modifier::REVERSED, "7"),
        (Modifier::HIDDEN, "8"),
        (Modifier::CROSSED_OUT, "9"),
    ] {
        if m.contains(flag) {
            codes.push(code.into());
        }
    }
    if let Some(c) = colour(fg, false) {
        codes.push(c);
    }
    if let Some(c) = colour(bg, true) {
        codes.push(c);
    }
    format!("\x1b[{}m", codes.join(";"))
}

/// The SGR parameter for a colour; None for the terminal's default (already reset).
fn colour(c: Color, background: bool) -> Option<String> {
    let base = if background { 40 } else { 30 };
    let code = |n: u8| Some((base + u16::from(n)).to_string());
    let bright = |n: u8| Some((base + 60 + u16::from(n)).to_string());
    match c {
        Color::Reset => None,
        Color::Black => code(0),
        Color::Red => code(1),
        Color::Green => code(2),
        Color::Yellow => code(3),
        Color::Blue => code(4),
        Color::Magenta => code(5),
        Color::Cyan => code(6),
        Color::Gray => code(7),
        Color::DarkGray => bright(0),
        Color::LightRed => bright(1),
        Color::LightGreen => bright(2),
        Color::LightYellow => bright(3),
        Color::LightBlue => bright(4),
        Color::LightMagenta => bright(5),
        Color::LightCyan => bright(6),
        Color::White => bright(7),
        Color::Indexed(i) => Some(format!("{};5;{i}", base + 8)),
        Color::Rgb(r, g, b) => Some(format!("{};2;{r};{g};{b}", base + 8)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use crate::script::parse;
    use crate::theme::Theme;

    fn app() -> App {
        App::new(Scene::default_scene(), Theme::builtin("dark").unwrap())
    }

    fn run(script: &str) -> String {
        replay(app(), &parse(script).unwrap(), &Options::default())
    }

    #[test]
    fn no_snapshot_prints_the_final_screen_once() {
        let out = run("tick 3");
        assert_eq!(out.matches("--- snapshot").count(), 1);
        assert!(
            out.starts_with("--- snapshot 1: final (80x24, tau=0.150)\n"),
            "{out}"
        );
        assert_eq!(out.lines().count(), 25);
    }

    #[test]
    fn quit_stops_the_script() {
        let out = run("snapshot one\nq\nsnapshot two\ntick 5");
        assert_eq!(out.matches("--- snapshot").count(), 1);
        assert!(out.starts_with("--- snapshot 1: one (80x24, tau=0.000)\n"));
    }

    #[test]
    fn tiny_and_empty_screens() {
        let out = run("resize 0x0\nsnapshot\nresize 1x1\nsnapshot\nresize 80x24\nsnapshot");
        let mut heads = out.lines().filter(|l| l.starts_with("---"));
        assert_eq!(heads.next(), Some("--- snapshot 1 (0x0, tau=0.000)"));
        assert_eq!(heads.next(), Some("--- snapshot 2 (1x1, tau=0.000)"));
        assert_eq!(heads.next(), Some("--- snapshot 3 (80x24, tau=0.000)"));
        assert_eq!(out.lines().count(), 3 + 1 + 24);
    }

    #[test]
    fn ansi_resets_every_line() {
        let opts = Options {
            ansi: true,
            ..Options::default()
        };
        let out = replay(app(), &parse("snapshot").unwrap(), &opts);
        for line in out.lines().skip(1) {
            assert!(line.starts_with("\x1b[0"), "{line:?}");
            assert!(line.ends_with("\x1b[0m"), "{line:?}");
        }
        assert!(
            out.contains("38;2;") || out.contains("\x1b[0;3"),
            "colours: {out:?}"
        );
    }

    #[test]
    fn sgr_codes() {
        assert_eq!(
            sgr(Color::Reset, Color::Reset, Modifier::empty()),
            "\x1b[0m"
        );
        assert_eq!(
            sgr(Color::Rgb(1, 2, 3), Color::Blue, Modifier::BOLD),
            "\x1b[0;1;38;2;1;2;3;44m"
        );
        assert_eq!(
            sgr(Color::White, Color::Indexed(7), Modifier::empty()),
            "\x1b[0;97;48;5;7m"
        );
    }
}
