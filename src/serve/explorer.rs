//! One client's explorer: a [`Session`] on a `Screen`, on its own thread, with its own tick
//! clock. A frame is drawn only once the last one has been taken by the channel (its flow
//! control: a client that reads slowly gets fewer frames, never older ones), while τ keeps
//! wall-clock time. A follower applies the presenter's keys, mouse actions and ticks instead of
//! its clock.

use super::screen::{Screen, Window};
use super::{In, Lead, Out, Shared};
use crate::app::lesson::Prompt;
use crate::app::state::InClass;
use crate::app::{App, Chord, Effect, Effects};
use crate::session::Session;
use crate::terminal::input::Decoder;
use crate::terminal::pace::{Clock, coalesce_drags};
use crossterm::event::{
    DisableBracketedPaste, DisableMouseCapture, EnableBracketedPaste, EnableMouseCapture, Event,
    KeyCode, KeyModifiers,
};
use crossterm::terminal::{
    BeginSynchronizedUpdate, EndSynchronizedUpdate, EnterAlternateScreen, LeaveAlternateScreen,
};
use crossterm::{cursor, queue};
use std::io;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

/// Frames a second at most, as the local explorer's default.
const FPS: u32 = 30;

mod follow;
use follow::{FOLLOWING, WAITING, adopt};
/// The key that steps out of the class, and back into it (not bound in the explorer).
pub const FOLLOW_KEY: KeyCode = KeyCode::F(2);

/// What the client said about its terminal.
#[derive(Clone, Debug, Default)]
pub struct Client {
    pub term: String,
    pub width: u16,
    pub height: u16,
    /// LANG (or LC_ALL, LC_CTYPE), if the client sent it.
    pub lang: Option<String>,
    pub colorterm: Option<String>,
}

/// A guest writes nothing on the server: saving and exporting are refused with a notice.
fn guest(app: &mut App, effects: Effects) {
    for effect in effects {
        let notice = match effect {
            Effect::SaveScene { .. } => {
                "not saved: over ssh nothing is written on the server".to_string()
            }
            Effect::ExportSvg { .. } => {
                "not exported: over ssh nothing is written on the server".to_string()
            }
            Effect::Readouts => crate::ui::plain::summary(app),
        };
        app.report(notice);
    }
}

/// The client's screen size within the server's bound.
fn clamp(shared: &Shared, width: u16, height: u16) -> (u16, u16) {
    let l = &shared.limits;
    // Never `clamp(1, max)`: a bound of 0 (refused at start, but a library caller may give
    // it) would panic every session.
    (width.min(l.max_cols).max(1), height.min(l.max_rows).max(1))
}

fn theme(client: &Client) -> Option<crate::theme::Theme> {
    use crate::theme::{Depth, Theme};
    let utf8 = client
        .lang
        .as_deref()
        .is_none_or(|l| l.is_empty() || l.to_ascii_lowercase().replace('-', "").contains("utf8"));
    let marker = if utf8 {
        ratatui::symbols::Marker::Braille
    } else {
        ratatui::symbols::Marker::Dot
    };
    Some(
        Theme::builtin("dark")?
            .with_depth(Depth::detect(
                Some(&client.term),
                client.colorterm.as_deref(),
            ))
            .with_marker(marker),
    )
}

/// The explorer for one client, until it quits, idles, stalls, leaves or the server stops;
/// then its last bytes (the terminal put back, and why it ended) go out.
pub fn run(
    shared: Arc<Shared>,
    id: u64,
    client: Client,
    size: Arc<Window>,
    inbox: Receiver<In>,
    out: Outbox,
) {
    let (w, h) = clamp(&shared, client.width, client.height);
    let Some(theme) = theme(&client) else {
        shared.leave(id);
        return;
    };
    // A presenter runs the class's lesson, if there is one, from its scene.
    let lesson = shared
        .options
        .lesson
        .as_ref()
        .filter(|_| shared.presents(id));
    let scene = lesson.map_or_else(crate::scene::Scene::default_scene, |l| l.scene.clone());
    let mut app = App::new(scene);
    app.mouse = true;
    let mut s = match Session::new(app, theme, Screen::new(w, h), None) {
        Ok(s) => s,
        Err(_) => {
            shared.leave(id);
            return;
        }
    };
    s.carry = guest;
    if let Some(l) = lesson {
        s.start_lesson(l.driver.clone());
    }
    // The teacher back after a dropped connection takes the class up where it was left, its
    // lesson at the same step (the followers, waiting, are handed this).
    if let Some(class) = shared.take_up_class(id) {
        adopt(&mut s, class);
        s.app.lesson.apart = false;
        s.app.notice = Some("you present: the class as it was left, and its followers".into());
    }
    let mut run = Run {
        shared: &shared,
        id,
        out: &out,
        // A client sends a terminal's sequence whole, in one message: a lone ESC ending one
        // is the Esc key at once.
        keys: Decoder::with_esc_wait(Duration::ZERO),
        clock: Clock::new(Instant::now()),
        in_flight: None,
        last_frame: None,
        last_input: Instant::now(),
        mouse_on: s.app.mouse_capture(),
        following: false,
        spare: Vec::new(),
        size,
        resized: false,
    };
    let said = run
        .start(&mut s)
        .and_then(|()| run.event_loop(&mut s, &inbox));
    let why = said.unwrap_or_else(|e| format!("error: {e}"));
    let mut bytes = s
        .term
        .backend_mut()
        .take(&mut run.spare)
        .unwrap_or_default();
    let _ = queue!(
        bytes,
        DisableMouseCapture,
        DisableBracketedPaste,
        LeaveAlternateScreen,
        cursor::Show
    );
    bytes.extend(format!("turntable: {why}\r\n").as_bytes());
    out.end(bytes);
    shared.leave_class(id, &s.app, s.lesson());
    shared.leave(id);
    // Its last buffer comes back once taken, to be freed here (see `In::Sent`).
    let until = Instant::now() + Duration::from_secs(1);
    while let Ok(msg) = inbox.recv_timeout(until.saturating_duration_since(Instant::now())) {
        if matches!(msg, In::Sent(_)) {
            break;
        }
    }
}

/// Where a session's bytes go: the channel's writer task.
pub struct Outbox(pub tokio::sync::mpsc::Sender<Out>);

impl Outbox {
    fn frame(&self, bytes: Vec<u8>) -> bool {
        self.0.try_send(Out::Frame(bytes)).is_ok()
    }

    fn end(&self, bytes: Vec<u8>) {
        let _ = self.0.try_send(Out::End(bytes));
    }
}

struct Run<'a> {
    shared: &'a Shared,
    id: u64,
    out: &'a Outbox,
    keys: Decoder,
    clock: Clock,
    /// When the frame the channel has not yet taken was handed to it.
    in_flight: Option<Instant>,
    last_frame: Option<Instant>,
    last_input: Instant,
    mouse_on: bool,
    /// Applying the presenter's keys and ticks.
    following: bool,
    /// The last frame's buffer, handed back by the channel: the next is drawn into it.
    spare: Vec<u8>,
    /// The client's window size, applied when the next frame is drawn if `resized`.
    size: Arc<Window>,
    resized: bool,
}

impl Run<'_> {
    fn start(&mut self, s: &mut Session<Screen>) -> io::Result<()> {
        let b = s.term.backend_mut();
        queue!(b, EnterAlternateScreen, cursor::Hide, EnableBracketedPaste)?;
        if self.mouse_on {
            queue!(b, EnableMouseCapture)?;
        }
        if self.shared.class_led(self.id) {
            self.shared.join(self.id);
        } else if !self.shared.presents(self.id) && self.shared.wait_for_class(self.id) {
            // Students come before the teacher: they follow once the teacher is in.
            s.app.report(WAITING.into());
        }
        Ok(())
    }

    /// Returns why it ended, to be said to the client.
    fn event_loop(&mut self, s: &mut Session<Screen>, inbox: &Receiver<In>) -> io::Result<String> {
        let limits = self.shared.limits;
        let gap = Duration::from_secs(1) / FPS;
        loop {
            if s.app.should_quit() {
                return Ok("bye".into());
            }
            let now = Instant::now();
            if !self.following && s.is_playing() {
                for _ in 0..self.clock.due(now) {
                    if !s.is_playing() {
                        break;
                    }
                    s.tick();
                    self.shared.lead(self.id, Lead::Tick);
                    self.pump(s)?;
                }
            }
            // A follower's lesson moves only when the presenter's does (`Lead::Lesson`).
            if !self.following {
                self.pump(s)?;
            }
            self.tally(s);
            self.mouse(s)?;
            let frame_due = self.last_frame.map_or(now, |t| t + gap);
            if self.in_flight.is_none() {
                if self.resized && now >= frame_due {
                    self.resize(s);
                }
                if s.app.needs_redraw() && now >= frame_due {
                    // The analysis pages are computed through the gate (as many at once as
                    // cores); the frame itself is drawn outside it.
                    self.shared.gate.run(|| s.sync_analysis());
                    queue!(s.term.backend_mut(), BeginSynchronizedUpdate)?;
                    s.draw()?;
                    queue!(s.term.backend_mut(), EndSynchronizedUpdate)?;
                    self.last_frame = Some(now);
                    self.shared.counts.frames.fetch_add(1, Ordering::Relaxed);
                }
                if let Some(bytes) = s.term.backend_mut().take(&mut self.spare)
                    && self.out.frame(bytes)
                {
                    self.in_flight = Some(now);
                }
            }
            if self.in_flight.is_some_and(|t| now - t > limits.stall) {
                return Ok("your connection stopped taking the screen".into());
            }
            // Following the class is attending it: a student who watches and types nothing
            // for the idle time is not idle.
            if self.following {
                self.last_input = now;
            }
            if now - self.last_input > limits.idle {
                return Ok(format!("idle for {} s: closed", limits.idle.as_secs()));
            }
            let mut wake = now + Duration::from_millis(250);
            if s.is_playing() && !self.following {
                wake = wake.min(self.clock.next());
            }
            if (s.app.needs_redraw() || self.resized) && self.in_flight.is_none() {
                wake = wake.min(frame_due);
            }
            if let Some(d) = self.keys.deadline() {
                wake = wake.min(d);
            }
            match inbox.recv_timeout(wake.saturating_duration_since(now)) {
                Ok(msg) => {
                    if let Some(why) = self.receive(s, msg)? {
                        return Ok(why);
                    }
                }
                Err(RecvTimeoutError::Timeout) => {
                    self.keys.expire(Instant::now());
                    let events = self.keys.events();
                    self.events(s, events)?;
                }
                Err(RecvTimeoutError::Disconnected) => return Ok(String::new()),
            }
            if !s.is_playing() || self.following {
                self.clock.restart(Instant::now());
            }
        }
    }

    /// One message from the connection, the writer or the class; `Some` ends the session.
    fn receive(&mut self, s: &mut Session<Screen>, msg: In) -> io::Result<Option<String>> {
        match msg {
            In::Data(bytes) => {
                let now = Instant::now();
                self.last_input = now;
                self.keys.feed(&bytes, false, now);
                let events = self.keys.events();
                self.events(s, events)?;
            }
            In::Resize => self.resized = true,
            In::Sent(buffer) => {
                self.in_flight = None;
                self.spare = buffer;
            }
            In::Close(why) => return Ok(Some(why)),
            In::Lead(lead) if self.following => match lead {
                Lead::Key(chord) => s.press(chord),
                Lead::Act(action) => s.act(action),
                Lead::Tick => s.tick(),
                Lead::Lesson => {
                    s.follow_lesson()?;
                }
            },
            In::Lead(_) => {}
            In::Unled if self.following => {
                self.following = false;
                s.app.tell_class(InClass::Alone);
                s.app.lesson.apart = false;
                s.app.report(
                    "the presenter left: on your own until they are back (F2: stay on your own)"
                        .into(),
                );
            }
            In::Unled | In::Answered => {}
            In::Join(follower) => self.shared.welcome(follower, &s.app, s.lesson()),
            In::Class => {
                let Some(class) = self.shared.take_class(self.id) else {
                    return Ok(None);
                };
                adopt(s, class);
                // A follower answers for itself (the answer it gave in class before stepping
                // out, if this question is open).
                s.app.lesson.apart = true;
                if let Some(yes) = self.shared.answered(self.id, s.app.lesson.asked) {
                    s.app.answer_apart(yes);
                }
                s.app.notice = Some(FOLLOWING.into());
                self.following = true;
                s.app.tell_class(InClass::Following);
            }
        }
        Ok(None)
    }

    /// The client's latest window size, laid out for the frame about to be drawn.
    fn resize(&mut self, s: &mut Session<Screen>) {
        self.resized = false;
        let (w, h) = self.size.take();
        let (w, h) = clamp(self.shared, w, h);
        s.term.backend_mut().resize(w, h);
        s.resized(w, h);
        self.shared.counts.layouts.fetch_add(1, Ordering::Relaxed);
    }

    /// The lesson's steps that are due; if it moved, the followers' lessons move alike (a
    /// question it asked takes answers before any follower can see it).
    fn pump(&mut self, s: &mut Session<Screen>) -> io::Result<()> {
        let pumped = s.pump_lesson()?;
        if pumped.moved {
            self.tally(s);
            self.shared.lead(self.id, Lead::Lesson);
        }
        // A click the lesson made, in the model's terms: in the same place for every follower.
        if let Some(action) = pumped.act {
            self.shared.lead(self.id, Lead::Act(action));
        }
        Ok(())
    }

    fn events(&mut self, s: &mut Session<Screen>, events: Vec<Event>) -> io::Result<()> {
        for ev in coalesce_drags(events) {
            match ev {
                Event::Key(k) if k.code == FOLLOW_KEY && k.modifiers == KeyModifiers::NONE => {
                    self.follow_key(s)
                }
                // A follower answers the class's question for itself: counted on the
                // presenter's screen, and never led (the class goes on when the presenter does).
                Event::Key(k)
                    if self.following
                        && k.modifiers == KeyModifiers::NONE
                        && matches!(k.code, KeyCode::Char('y' | 'n'))
                        && s.app.lesson.prompt() == Prompt::Answer =>
                {
                    self.answer(s, k.code == KeyCode::Char('y'))
                }
                // A follower's own keys are not applied while it follows (Ctrl-C and q still
                // end it): each says so, and how to step out.
                Event::Key(k)
                    if self.following
                        && !matches!(k.code, KeyCode::Char('q'))
                        && !k.modifiers.contains(KeyModifiers::CONTROL) =>
                {
                    s.app.report(FOLLOWING.into());
                }
                Event::Key(k) => {
                    if let Some(chord) = Chord::from_event(&k) {
                        s.press(chord);
                        // The presenter quitting ends its own session, not the class's.
                        if !s.app.should_quit() {
                            self.shared.lead(self.id, Lead::Key(chord));
                        }
                    }
                }
                Event::Mouse(_) | Event::Paste(_) if self.following => {}
                // What the mouse did, the followers do (in the model's terms: the same
                // change whatever their screens' sizes).
                Event::Mouse(m) => {
                    if let Some(action) = s.mouse(m)? {
                        self.shared.lead(self.id, Lead::Act(action));
                    }
                }
                // What a paste typed at the prompt, the followers type too.
                Event::Paste(text) => {
                    for chord in s.paste(&text) {
                        self.shared.lead(self.id, Lead::Key(chord));
                    }
                }
                _ => {}
            }
        }
        Ok(())
    }

    fn mouse(&mut self, s: &mut Session<Screen>) -> io::Result<()> {
        if s.app.mouse_capture() != self.mouse_on {
            self.mouse_on = s.app.mouse_capture();
            if self.mouse_on {
                queue!(s.term.backend_mut(), EnableMouseCapture)?;
            } else {
                queue!(s.term.backend_mut(), DisableMouseCapture)?;
            }
        }
        Ok(())
    }
}
