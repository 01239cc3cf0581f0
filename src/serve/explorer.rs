//! One client's explorer: a [`Explorer`] on a `Screen`, on its own thread, in the explorer's
//! one loop (`terminal::drive`) with its own tick clock. A frame is drawn only once the last one has been taken by the channel (its flow
//! control: a client that reads slowly gets fewer frames, never older ones), while τ keeps
//! wall-clock time. A follower applies the presenter's keys, mouse actions and ticks instead of
//! its clock.

use super::pace::thread_cpu;
use super::screen::{Screen, Window};
use super::{In, Lead, Out, Shared};
use crate::app::lesson::Prompt;
use crate::app::state::InClass;
use crate::app::{App, Chord};
use crate::session::{Explorer, Pumped};
use crate::terminal::drive::{Link, Turn, Waited, drive};
use crate::terminal::input::Decoder;
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

mod carry;
mod follow;
mod link;
mod plain;
pub use carry::Guest;
use carry::Presenter;
use follow::{ARRIVED, FOLLOWING, LEFT, TAKEN_UP, WAITING, adopt};
/// The key that steps out of the class, and back into it (not bound in the explorer).
pub const FOLLOW_KEY: KeyCode = KeyCode::F(2);

/// The user name that asks for plain mode (`ssh plain@HOST`): any other name is the
/// explorer's screen.
pub const PLAIN_USER: &str = "plain";

/// What the client said about its terminal.
#[derive(Clone, Debug, Default)]
pub struct Client {
    pub term: String,
    pub width: u16,
    pub height: u16,
    /// LANG (or LC_ALL, LC_CTYPE), if the client sent it.
    pub lang: Option<String>,
    pub colorterm: Option<String>,
    /// Plain mode: lines for a screen reader, no screen (user `plain`, or `TURNTABLE_PLAIN`).
    pub plain: bool,
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
    app.tell_mouse(!client.plain);
    let mut s = match Explorer::new(app, theme, Screen::new(w, h), None) {
        Ok(s) => s,
        Err(_) => {
            shared.leave(id);
            return;
        }
    };
    s.carry_with(Guest);
    if let Some(l) = lesson {
        s.start_lesson(l.driver.clone());
    }
    // The teacher back after a dropped connection takes the class up where it was left, its
    // lesson at the same step (the followers, waiting, are handed this).
    if let Some(class) = shared.take_up_class(id) {
        adopt(&mut s, class);
        s.app.tell_class(InClass::Alone);
        s.app.report(TAKEN_UP.into());
    }
    if let Some(dir) = shared
        .options
        .exports
        .as_ref()
        .filter(|_| shared.presents(id))
    {
        s.app.tell_save_path(dir.join(crate::app::state::SAVE_PATH));
        s.carry_with(Presenter);
    }
    let mut run = Remote {
        shared: &shared,
        id,
        out: &out,
        inbox: &inbox,
        // A client sends a terminal's sequence whole, in one message: a lone ESC ending one
        // is the Esc key at once.
        keys: Decoder::with_esc_wait(Duration::ZERO),
        in_flight: None,
        last_input: Instant::now(),
        mouse_on: s.app.mouse_capture(),
        following: false,
        at: None,
        spare: Vec::new(),
        size,
        resized: false,
        plain: None,
        answering: false,
        still_gap: Duration::from_secs(1) / FPS,
        waiting: false,
    };
    let said = run
        .start(&mut s, client.plain)
        .and_then(|()| drive(&mut s, &mut run));
    let why = said.unwrap_or_else(|e| format!("error: {e}"));
    let mut bytes = s
        .term
        .backend_mut()
        .take(&mut run.spare)
        .unwrap_or_default();
    if run.plain.is_none() {
        let _ = queue!(
            bytes,
            DisableMouseCapture,
            DisableBracketedPaste,
            LeaveAlternateScreen,
            cursor::Show
        );
    }
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

/// One SSH client's explorer, as the one loop drives it (`terminal::drive::Link`): the
/// terminal's `Local` and plain mode's `Lines` are the others.
struct Remote<'a> {
    shared: &'a Shared,
    id: u64,
    out: &'a Outbox,
    /// The connection's, the writer's and the class's messages.
    inbox: &'a Receiver<In>,
    keys: Decoder,
    /// When the frame the channel has not yet taken was handed to it.
    in_flight: Option<Instant>,
    last_input: Instant,
    mouse_on: bool,
    /// Applying the presenter's keys and ticks.
    following: bool,
    /// Following, the class's place its state is at (None: not known, its frames its own).
    at: Option<super::class::Place>,
    /// The last frame's buffer, handed back by the channel: the next is drawn into it.
    spare: Vec<u8>,
    /// The client's window size, applied when the next frame is drawn if `resized`.
    size: Arc<Window>,
    resized: bool,
    /// In plain mode, what its last lines said (see `plain`).
    plain: Option<crate::ui::plain::Seen>,
    /// Input came (the client's, or the presenter's keys and mouse) since the last frame: the
    /// next one answers it, at the explorer's rate.
    answering: bool,
    /// The least time between frames that only time moved, as the server's load allows
    /// (`pace`), measured at the last frame.
    still_gap: Duration,
    /// Told there is no presenter (none yet, or the last left): the class handed next is a
    /// presenter's arrival, and is announced as one.
    waiting: bool,
}

impl Remote<'_> {
    fn start(&mut self, s: &mut Explorer<Screen>, plain: bool) -> io::Result<()> {
        if plain {
            self.open_plain(s)?;
        } else {
            let b = s.term.backend_mut();
            queue!(b, EnterAlternateScreen, cursor::Hide, EnableBracketedPaste)?;
            if self.mouse_on {
                queue!(b, EnableMouseCapture)?;
            }
        }
        if self.shared.class_led(self.id) {
            self.shared.join(self.id);
        } else if !self.shared.presents(self.id) && self.shared.wait_for_class(self.id) {
            // Students come before the teacher: they follow once the teacher is in.
            s.app.report(WAITING.into());
            self.waiting = true;
        }
        Ok(())
    }

    /// One message from the connection, the writer or the class: the keys it brought, or why
    /// the session ends.
    fn receive(&mut self, s: &mut Explorer<Screen>, msg: In) -> io::Result<Waited> {
        match msg {
            In::Data(bytes) => {
                self.answering = true;
                let now = Instant::now();
                self.last_input = now;
                self.keys.feed(&bytes, false, now);
                return Ok(Waited::Events(self.keys.events()));
            }
            In::Resize => self.resized = true,
            In::Sent(buffer) => {
                self.in_flight = None;
                self.spare = buffer;
            }
            In::Close(why) => return Ok(Waited::Stop(why)),
            In::Lead(lead, at) if self.following => {
                self.at = self.at.and_then(|was| was.then(at));
                self.lead(s, lead)?;
            }
            In::Lead(..) => {}
            In::Unled if self.following => {
                self.following = false;
                self.waiting = true;
                self.at = None;
                s.app.tell_class(InClass::Alone);
                s.app.report(LEFT.into());
            }
            In::Unled | In::Answered => {}
            In::Join(follower) => self.shared.welcome(self.id, follower, &s.app, s.lesson()),
            In::HandOver => {
                self.shared.leave_class(self.id, &s.app, s.lesson());
                s.app.tell_tally(None);
                s.app.report(
                    "another presenter took the class over, as it was: you are on your own".into(),
                );
            }
            In::TakeUp => {
                if let Some(class) = self.shared.take_over(self.id) {
                    adopt(s, class);
                    s.app.tell_class(InClass::Alone);
                    s.app.report(TAKEN_UP.into());
                }
            }
            In::Class => {
                let Some((class, at)) = self.shared.take_class(self.id) else {
                    return Ok(Waited::Events(vec![]));
                };
                adopt(s, class);
                self.at = Some(at);
                // A follower answers for itself (the answer it gave in class before stepping
                // out, if this question is open).
                s.app.tell_class(InClass::Following);
                if let Some(yes) = self.shared.answered(self.id, s.app.lesson().asked) {
                    s.app.answer_apart(yes);
                }
                s.app.report(if std::mem::take(&mut self.waiting) {
                    ARRIVED.into()
                } else {
                    FOLLOWING.into()
                });
                self.following = true;
            }
        }
        Ok(Waited::Events(vec![]))
    }

    /// The presenter's key, mouse action, tick or lesson step, applied by a follower.
    fn lead(&mut self, s: &mut Explorer<Screen>, lead: Lead) -> io::Result<()> {
        match lead {
            Lead::Key(chord) => {
                self.answering = true;
                s.press(chord);
            }
            Lead::Act(action) => {
                self.answering = true;
                s.act(action);
            }
            Lead::Tick => s.tick(),
            Lead::Lesson => {
                s.follow_lesson()?;
            }
        }
        Ok(())
    }

    /// The client's latest window size, laid out for the frame about to be drawn.
    fn resize(&mut self, s: &mut Explorer<Screen>) {
        self.resized = false;
        let (w, h) = self.size.take();
        let (w, h) = clamp(self.shared, w, h);
        s.term.backend_mut().resize(w, h);
        s.resized(w, h);
        self.shared.counts.layouts.fetch_add(1, Ordering::Relaxed);
    }

    /// One event of the client's: keys and the mouse applied and led to the followers; a
    /// follower's own refused but for F2, its answers, `q` and Ctrl-C.
    fn event(&mut self, s: &mut Explorer<Screen>, ev: Event) -> io::Result<()> {
        {
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
                        && s.app.lesson().prompt() == Prompt::Answer =>
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

    fn mouse_capture(&mut self, s: &mut Explorer<Screen>) -> io::Result<()> {
        // Plain mode sends no escape sequence (a class handed over asks for the mouse).
        if self.plain.is_none() && s.app.mouse_capture() != self.mouse_on {
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
