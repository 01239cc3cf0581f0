//! The interactive explorer's model: keys → actions → state. Rendering is in `crate::ui`,
//! the terminal loop in `crate::terminal`.

pub mod action;
pub mod chord;
pub mod effect;
pub mod exploration;
pub mod keymap;
pub mod lesson;
pub mod pages;
pub mod pins;
pub mod prompt;
pub mod state;
pub mod testing;
pub mod update;
pub mod view;

pub use action::Action;
pub use chord::Chord;
pub use effect::{Effect, Effects};
pub use exploration::Exploration;
pub use keymap::{Binding, KEYMAP};
pub use state::{
    App, CanvasGeom, MU_PROBE, Measured, SPEED_RANGE, TICK_DT, TICKS_PER_SECOND, speed_power,
};
pub use update::update;
pub use view::View;

use crate::scene::Scene;
use crossterm::event::{KeyCode, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};

impl App {
    pub fn new(scene: Scene) -> App {
        App::build(scene)
    }

    /// Keymap → action → update; returns what the shell must carry out.
    pub fn press(&mut self, chord: Chord) -> Effects {
        // While the prompt is open, keys are its letters; only Ctrl-C keeps its meaning (quit).
        let ctrl_c = Chord::new(KeyCode::Char('c'), KeyModifiers::CONTROL);
        let action = match &self.prompt {
            Some(_) if chord != ctrl_c => action::Edit::of(chord).map(Action::Type),
            _ => keymap::lookup_when(chord, self.lesson.prompt()),
        };
        match action {
            Some(a) => update(self, a),
            None => Effects::new(),
        }
    }

    /// What the shell reports back once it has carried out an effect: the notice saying
    /// what was done (or why not).
    pub fn report(&mut self, notice: String) {
        self.notice = Some(notice);
        self.dirty = true;
    }

    /// What a mouse event asks for, through the canvas as last drawn, in the model's terms
    /// (a point, a velocity, a release), whatever the screen's size: applied to another app
    /// in the same state, it makes the same change (a served class's followers do).
    pub fn mouse_action(&mut self, ev: MouseEvent) -> Option<Action> {
        if !self.mouse {
            return None;
        }
        if self.view.help {
            return match ev.kind {
                MouseEventKind::ScrollUp => Some(Action::HelpScroll(-3)),
                MouseEventKind::ScrollDown => Some(Action::HelpScroll(3)),
                _ => None,
            };
        }
        // A drag goes on through the canvas it began in; a click picks the canvas it is in.
        let in_canvas = |g: &&CanvasGeom| g.to_world(ev.column, ev.row).is_some();
        let k = match ev.kind {
            MouseEventKind::Drag(_) | MouseEventKind::Up(_) => self.drag_canvas,
            _ => self.geom.iter().position(|g| in_canvas(&g)).unwrap_or(0),
        };
        let g = *self.geom.get(k)?;
        let at = g.to_world(ev.column, ev.row);
        if g.page != pages::Page::Turntable {
            // The plot is the (φ, v0) plane: a click picks that release.
            return match (ev.kind, at) {
                (MouseEventKind::Down(MouseButton::Left), Some(p)) => Some(Action::PickRelease(p)),
                _ => None,
            };
        }
        Some(match (ev.kind, at) {
            (MouseEventKind::Up(_), _) => Action::EndDrag,
            (MouseEventKind::Down(MouseButton::Left), Some(p)) => {
                self.drag_canvas = k;
                Action::PlaceRelease(p)
            }
            // The arrow from the release point (on +x in the model) to here, in speed units.
            (MouseEventKind::Drag(MouseButton::Left), Some(p)) if self.dragging => {
                let r0 = glam::DVec2::new(self.initial().xi0, 0.0);
                Action::AimVelocity((p - r0) / g.arrow_scale, g.frame)
            }
            (MouseEventKind::ScrollUp, Some(_)) => Action::ZoomIn,
            (MouseEventKind::ScrollDown, Some(_)) => Action::ZoomOut,
            _ => return None,
        })
    }

    /// One tick: advances the run(s) by `TICK_DT × speed` of sim time if playing.
    pub fn tick(&mut self) {
        if self.playing {
            update::step(self);
        } else if self.catch_up() {
            self.dirty = true;
        }
    }

    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// False when nothing changed since the last draw (paused and idle: no redraw).
    pub fn needs_redraw(&self) -> bool {
        self.dirty
    }

    /// Records a finished draw: the canvas geometry it returned (mouse cells map through it)
    /// and that the screen is up to date.
    pub fn drawn(&mut self, geom: Vec<CanvasGeom>) {
        self.geom = geom;
        self.dirty = false;
    }

    /// Forces the next frame to be drawn (after the terminal was cleared).
    pub fn invalidate(&mut self) {
        self.dirty = true;
    }

    /// The terminal is now `width` × `height`: redraw (the shell then asks for what the
    /// pages compute at this size).
    pub fn resize(&mut self, width: u16, height: u16) {
        self.screen = (width, height);
        self.dirty = true;
    }

    /// What the view measured at the terminal's size (the shell tells it after a resize).
    pub fn measured(&mut self, m: Measured) {
        self.measured = m;
    }

    /// Whether time should tick for the model: playing, or the paper's run still catching
    /// up (the shell adds a page filling in: `Explorer::is_playing`).
    pub fn is_playing(&self) -> bool {
        self.playing || self.paper_lags()
    }

    pub fn mouse_capture(&self) -> bool {
        self.mouse
    }
}
