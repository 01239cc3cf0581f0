//! One explorer session: the app, a terminal to draw it on, and optionally a recorder of
//! everything applied. Every event goes through here, in the interactive loop (crossterm) and
//! in a headless replay (`TestBackend`) alike, so what `--record` writes is exactly what a
//! replay applies.

use crate::analysis::Analysis;
use crate::app::{Action, App, Chord};
use crate::script::{Recorder, Step};
use crate::theme::Theme;
use crossterm::event::{KeyEvent, MouseEvent};
use ratatui::Terminal;
use ratatui::backend::{Backend, TestBackend};
use ratatui::buffer::Buffer;
use ratatui::symbols::Marker;
use std::convert::Infallible;
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

mod carry;
mod lesson;

pub use carry::{Carry, ExportBound, Write, carry_out, export_svg};
pub use lesson::Pumped;

/// A recorder the terminal loop shares with its signal watcher, which saves what was recorded
/// if the terminal dies under the explorer.
pub type SharedRecorder = Arc<Mutex<Recorder>>;

/// An empty recorder to share.
pub fn new_recorder() -> SharedRecorder {
    Arc::new(Mutex::new(Recorder::new()))
}

/// The recorder, whatever a panicking holder left behind.
pub fn lock(r: &SharedRecorder) -> MutexGuard<'_, Recorder> {
    r.lock().unwrap_or_else(|e| e.into_inner())
}

/// The app, a terminal to draw it on, and optionally a recorder of everything applied.
/// Every event goes through here, in the interactive loop and in a replay alike.
pub struct Explorer<B: Backend> {
    pub app: App,
    /// How the app is drawn: the view's, not the model's.
    pub theme: Theme,
    pub term: Terminal<B>,
    recorder: Option<SharedRecorder>,
    /// An interactive lesson's script, fed in as time passes (see [`Explorer::pump_lesson`]).
    lesson: Option<crate::lesson::Driver>,
    /// How the effects `update` returns are carried out: [`Write`] (files written) unless the
    /// shell says otherwise ([`Explorer::carry_with`]).
    carry: Box<dyn Carry + Send>,
    /// Where the analysis pages are computed: inline (computed when a frame is drawn) unless
    /// [`Explorer::with_worker`].
    pub analysis: Analysis,
}

impl<B: Backend> Explorer<B> {
    /// With a `recorder` (see [`new_recorder`]), the script starts with the terminal's
    /// current size.
    pub fn new(
        app: App,
        theme: Theme,
        backend: B,
        recorder: Option<SharedRecorder>,
    ) -> Result<Self, B::Error> {
        let term = Terminal::new(backend)?;
        let size = term.size()?;
        if let Some(r) = &recorder {
            lock(r).resize(size.width, size.height);
        }
        let mut s = Explorer {
            app,
            theme,
            term,
            recorder,
            lesson: None,
            carry: Box::new(Write),
            analysis: Analysis::inline(),
        };
        tell_size(&mut s.app, size.width, size.height);
        s.ask_analysis();
        Ok(s)
    }

    /// The analysis pages computed on a worker thread (the interactive loops): keys and
    /// frames never wait for them.
    pub fn with_worker(mut self) -> Self {
        self.analysis.cancel();
        self.analysis = Analysis::threaded();
        self.ask_analysis();
        self
    }

    /// The effects `update` returns carried out by `carry` from now on (a replay answers them,
    /// a guest is refused them).
    pub fn carry_with(&mut self, carry: impl Carry + Send + 'static) {
        self.carry = Box::new(carry);
    }

    /// Whether time should tick: the model's runs (see [`App::is_playing`]), or a page
    /// filling in from the worker.
    pub fn is_playing(&self) -> bool {
        self.app.is_playing() || self.analysis.busy()
    }

    /// Brings the analysis pages up to date for a frame (inline: computed now).
    pub fn sync_analysis(&mut self) -> bool {
        sync(&mut self.app, &mut self.analysis, true)
    }

    /// As [`Explorer::sync_analysis`], but an inline request is only noted: keys and ticks
    /// call this, so fifty edits before a frame compute one page, not fifty.
    pub fn ask_analysis(&mut self) -> bool {
        sync(&mut self.app, &mut self.analysis, false)
    }

    /// A terminal's key event (releases and keys a script cannot name are ignored; repeats
    /// count as presses).
    pub fn key(&mut self, key: KeyEvent) {
        if let Some(chord) = Chord::from_event(&key) {
            self.press(chord);
        }
    }

    /// A key chord, recorded and pressed.
    pub fn press(&mut self, chord: Chord) {
        if let Some(r) = &self.recorder {
            lock(r).key(chord);
        }
        let effects = self.app.press(chord);
        self.carry.carry(&mut self.app, effects);
        self.ask_analysis();
    }

    /// Pasted text: typed, letter by letter, only at the prompt (a name, values);
    /// elsewhere ignored, since a `q` in it would quit. Line breaks and other control
    /// characters are dropped: a name is one line. Returns the keys pressed (a served class's
    /// followers press them too).
    pub fn paste(&mut self, text: &str) -> Vec<Chord> {
        let mut pressed = vec![];
        if self.app.prompt().is_none() {
            return pressed;
        }
        // The prompt is one line: a pasted line break joins the lines. Then cleaned as any text
        // from outside is (`crate::text`); what cleaning removed is not typed.
        let text = crate::text::Clean::new(&text.replace(['\r', '\n'], ""));
        for c in text.chars().filter(|&c| c != crate::text::MARK).take(200) {
            let chord = Chord::new(
                crossterm::event::KeyCode::Char(c),
                crossterm::event::KeyModifiers::NONE,
            );
            self.press(chord);
            pressed.push(chord);
        }
        pressed
    }

    /// A mouse event. The app maps cells through the canvas as last drawn, so anything
    /// changed since the last frame is drawn first: a recording and its replay then see the
    /// same canvas whatever else happened in between. Returns the action it made, if any
    /// (a served class's followers apply it: [`Explorer::act`]).
    pub fn mouse(&mut self, ev: MouseEvent) -> Result<Option<Action>, B::Error> {
        self.draw_if_needed()?;
        if let Some(r) = &self.recorder {
            lock(r).mouse(&ev);
        }
        let action = self.app.mouse_action(ev);
        if let Some(a) = action {
            self.act(a);
        }
        Ok(action)
    }

    /// An action in the model's terms, as another session's mouse made it (a script names
    /// keys and cells, not actions: it is not recorded).
    pub fn act(&mut self, action: Action) {
        let effects = crate::app::update(&mut self.app, action);
        self.carry.carry(&mut self.app, effects);
        self.ask_analysis();
    }

    /// One tick of the app's clock (as the interactive loop calls it while playing).
    pub fn tick(&mut self) {
        if let Some(r) = &self.recorder {
            lock(r).tick();
        }
        self.ask_analysis();
        // A lesson's `tick N` counts ticks of play: paused, the lesson holds where it is.
        let played = self.app.playing();
        self.app.tick();
        if let Some(d) = self.lesson.as_mut().filter(|_| played) {
            d.ticked();
        }
    }

    /// The interactive lesson's place in its script, while one runs.
    pub fn lesson(&self) -> Option<&crate::lesson::Driver> {
        self.lesson.as_ref()
    }

    /// Runs an interactive lesson: its steps are fed in by [`Explorer::pump_lesson`].
    pub fn start_lesson(&mut self, driver: crate::lesson::Driver) {
        self.app.tell_lesson(driver.name());
        self.lesson = Some(driver);
    }

    /// The lesson at the place another session's is (a served class's follower is handed the
    /// presenter's, with its state): None ends this one's. The app's caption is the app's.
    pub fn set_lesson(&mut self, driver: Option<crate::lesson::Driver>) {
        self.lesson = driver;
    }

    /// The terminal is now `width` × `height`: recorded, and the next frame is redrawn.
    pub fn resized(&mut self, width: u16, height: u16) {
        if let Some(r) = &self.recorder {
            lock(r).resize(width, height);
        }
        tell_size(&mut self.app, width, height);
        self.ask_analysis();
    }

    /// Draws the app, its analysis pages brought up to date first (headless, computed now).
    pub fn draw(&mut self) -> Result<(), B::Error> {
        self.sync_analysis();
        let mut geom = Vec::new();
        let ascii = self.theme.marker == Marker::Dot;
        self.term.draw(|f| {
            geom = crate::ui::draw(f, &self.app, &self.theme);
            if ascii {
                ascii_cells(f.buffer_mut());
            }
        })?;
        self.app.drawn(geom);
        Ok(())
    }

    /// Draws as [`Explorer::draw`] does, all but the status line ([`crate::ui::draw_common`])
    /// taken from `common` when another session drew it there at this size, else drawn here
    /// and left there (sessions in the same state, a served class's followers of one size,
    /// draw it once for them all: one draws while the others wait, then copy it). Whether it
    /// was taken.
    pub fn draw_sharing(&mut self, common: &OnceLock<Common>) -> Result<bool, B::Error> {
        self.sync_analysis();
        let (mut geom, mut taken) = (Vec::new(), false);
        let ascii = self.theme.marker == Marker::Dot;
        let (app, th) = (&self.app, &self.theme);
        self.term.draw(|f| {
            let mut drew = false;
            let c = common.get_or_init(|| {
                drew = true;
                let geom = crate::ui::draw_common(f, app, th);
                if ascii {
                    ascii_cells(f.buffer_mut());
                }
                Common {
                    buffer: f.buffer_mut().clone(),
                    geom,
                }
            });
            if drew {
                geom.clone_from(&c.geom);
            } else if c.buffer.area == f.buffer_mut().area {
                f.buffer_mut().content.clone_from_slice(&c.buffer.content);
                geom.clone_from(&c.geom);
                taken = true;
            } else {
                // Drawn at another size: this one's own.
                geom = crate::ui::draw_common(f, app, th);
            }
            crate::ui::draw_own(f, app, th);
            if ascii {
                ascii_cells(f.buffer_mut());
            }
        })?;
        self.app.drawn(geom);
        Ok(taken)
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
}

/// A frame but its status line, as [`Explorer::draw_sharing`] shares it: its cells and where
/// its canvases went.
pub struct Common {
    buffer: Buffer,
    geom: Vec<crate::app::CanvasGeom>,
}

/// Tells `app` the terminal is now `width` × `height`, and what the view measures there (the
/// help's page and end).
pub fn tell_size(app: &mut App, width: u16, height: u16) {
    app.resize(width, height);
    app.measured(crate::app::Measured {
        help_page: crate::ui::help::page(height),
        help_max_scroll: crate::ui::help::max_scroll(width, height),
    });
}

/// Brings `app`'s analysis pages up to date through `analysis`: takes the pieces that arrived
/// and asks for what the page on screen still lacks, the outcome map at the grid its plot
/// holds at the terminal's size (`ui::pages::map_grid`), computing it now when `compute` and
/// inline. Below the least size (`ui::layout::regions`) no page is on screen, only the notice
/// that says so: nothing is asked until the terminal is large enough. Returns whether anything
/// arrived or was asked (the app then redraws).
pub fn sync(app: &mut App, analysis: &mut Analysis, compute: bool) -> bool {
    let mut moved = false;
    // Inline, each request completes when computed: a page needs at most five jobs.
    for _ in 0..8 {
        if compute {
            analysis.compute();
        }
        if let Some((job, settings)) = analysis.current() {
            for p in analysis.take() {
                app.receive(&job, settings, p);
                moved = true;
            }
        }
        let (width, height) = app.screen();
        let wanted = crate::ui::layout::regions(width, height)
            .and_then(|_| app.wanted_job(|v0_max| crate::ui::pages::map_grid(app, v0_max)));
        let Some((job, settings)) = wanted else {
            // Nothing is computed for a page that is not on screen.
            analysis.cancel();
            break;
        };
        if analysis.current() == Some((job, settings)) {
            // In flight, or done and still lacking (a failed piece): ask no more.
            break;
        }
        let todo = app.charts().missing(&job, settings);
        // A map's cells lean on the escape speeds at its ξ0, which the page computed first; a
        // curve's start from a nearby ξ0's.
        let curve = match job {
            crate::analysis::Job::Map { xi0, .. } => app.charts().curve(xi0, settings),
            crate::analysis::Job::Curve { xi0 } => app.charts().near_curve(xi0, settings),
            _ => None,
        }
        .map(|c| c.ve.clone());
        analysis.request(job, settings, todo, curve);
        moved = true;
    }
    if moved {
        app.invalidate();
    }
    moved
}

/// A terminal that is not UTF-8 (`--marker ascii`, or a locale that says so) gets ASCII only:
/// each cell's symbol becomes one ASCII character, so the layout holds — box drawing as
/// `+ - |`, ratatui's dot marker as `*`, the glyphs and Greek letters as their nearest letter,
/// anything else `?`.
fn ascii_cells(buf: &mut Buffer) {
    for cell in &mut buf.content {
        let sym = cell.symbol();
        if sym.is_ascii() {
            continue;
        }
        let c = sym.chars().next().map_or('?', ascii_of);
        cell.set_char(c);
    }
}

/// The nearest ASCII character to `c`.
fn ascii_of(c: char) -> char {
    match c {
        '─' | '━' | '┄' | '═' | '–' | '—' => '-',
        '│' | '┃' | '║' | '❚' => '|',
        '┌' | '┐' | '└' | '┘' | '├' | '┤' | '┬' | '┴' | '┼' | '╭' | '╮' | '╯' | '╰' => {
            '+'
        }
        '•' | '∙' => '*',
        '●' | '○' | '◦' => 'o',
        // The body's centre.
        '⊕' => 'O',
        '■' | '▪' | '█' | '▓' | '▒' => '#',
        '░' | '·' | '…' => '.',
        '×' => 'x',
        '↺' => '@',
        '▶' | '→' | '≥' | '›' => '>',
        '←' | '≤' | '‹' => '<',
        '↑' | '▲' => '^',
        '↓' | '▼' => 'v',
        // The pins' markers (the letters beside them tell them apart too).
        '◆' => '+',
        '◇' => '%',
        '△' => '&',
        '▽' => '=',
        '≈' | '∼' => '~',
        '′' | '’' | '‘' => '\'',
        '²' => '2',
        'τ' => 't',
        'ξ' => 'x',
        'θ' | 'Θ' => 'o',
        'φ' | 'π' => 'p',
        'μ' => 'u',
        'Ω' => 'W',
        'α' => 'a',
        'Δ' => 'D',
        _ => '?',
    }
}

fn ok<T>(r: Result<T, Infallible>) -> T {
    match r {
        Ok(v) => v,
        Err(e) => match e {},
    }
}

impl Explorer<TestBackend> {
    /// A session on an off-screen terminal of `width` × `height` cells.
    pub fn headless(app: App, theme: Theme, width: u16, height: u16, record: bool) -> Self {
        let recorder = record.then(new_recorder);
        ok(Explorer::new(
            app,
            theme,
            TestBackend::new(width, height),
            recorder,
        ))
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

    /// Applies one script step (a snapshot step only draws; see [`replay`](crate::replay::replay) for the output).
    pub fn apply(&mut self, step: &Step) {
        match step {
            Step::Key(k) => self.press(*k),
            Step::Tick(n) => {
                for _ in 0..*n {
                    // Paused, a tick changes nothing (and a tick cannot unpause).
                    if !self.is_playing() {
                        break;
                    }
                    self.tick();
                }
            }
            Step::Resize(w, h) => self.resize(*w, *h),
            Step::Snapshot(_) => {
                self.screen();
            }
            Step::Mouse(m) => {
                ok(self.mouse(*m));
            }
            Step::Say(t) => self.app.say(t.clone()),
            Step::Ask(t) => self.app.ask(t.clone()),
            // Headless, a lesson goes on.
            Step::Wait => {}
            Step::Play(p) => self.app.play(*p),
            Step::Pause => self.app.pause(),
        }
    }
}
