//! The interactive explorer's model: keys → actions → state. Rendering is in `crate::ui`,
//! the terminal loop in `crate::terminal`.

pub mod action;
pub mod keymap;
pub mod state;
pub mod update;

pub use action::Action;
pub use keymap::{Binding, KEYMAP};
pub use state::{App, CanvasGeom, TICK_DT};
pub use update::update;

use crate::engine::{Release, Settings};
use crate::scene::Scene;
use crate::theme::Theme;
use crossterm::event::{KeyEvent, KeyEventKind, MouseButton, MouseEvent, MouseEventKind};

impl App {
    pub fn new(scene: Scene, theme: Theme) -> App {
        App::build(scene, theme)
    }

    /// Keymap → action → update. Key releases are ignored.
    pub fn handle_key(&mut self, key: KeyEvent) {
        if key.kind == KeyEventKind::Release {
            return;
        }
        if let Some(a) = keymap::lookup(&key) {
            update(self, a);
        }
    }

    /// Click: place the release point at the clicked radius; drag: set the initial velocity
    /// (from the release point to the pointer, in the frame shown). Uses the canvas as last
    /// drawn.
    pub fn handle_mouse(&mut self, ev: MouseEvent) {
        if !self.mouse || self.help {
            return;
        }
        let Some(g) = self.geom else { return };
        let Some(p) = g.to_world(ev.column, ev.row) else {
            if matches!(ev.kind, MouseEventKind::Up(_)) {
                self.dragging = false;
            }
            return;
        };
        match ev.kind {
            MouseEventKind::Down(MouseButton::Left) => {
                // Clicked at an angle: the picture turns there (p is in model coordinates,
                // so its angle adds to the turn already shown).
                if p.length() > 0.0 {
                    self.turn = crate::engine::model::wrap_angle(self.turn + p.y.atan2(p.x));
                }
                self.initial.xi0 = p.length();
                self.dragging = true;
                self.restart();
                self.notice = Some(format!(
                    "release point ξ0 = {:.3}; drag to set the velocity",
                    self.initial.xi0
                ));
                self.dirty = true;
            }
            MouseEventKind::Drag(MouseButton::Left) if self.dragging => {
                let d = p - glam::DVec2::new(self.initial.xi0, 0.0);
                // The arrow shows u0 in the rotating view and the lab velocity in the lab view.
                let d = if g.frame == crate::engine::Frame::Lab {
                    d / g.arrow_scale - glam::DVec2::new(0.0, self.initial.xi0)
                } else {
                    d / g.arrow_scale
                };
                self.initial.release = Release::Velocity;
                self.initial.v0 = d.length();
                self.initial.phi = if d.length() > 0.0 {
                    d.y.atan2(d.x)
                } else {
                    0.0
                };
                self.restart();
                self.notice = Some(format!(
                    "v0 = {:.3}, φ = {:.3}π",
                    self.initial.v0,
                    self.initial.phi.rem_euclid(std::f64::consts::TAU) / std::f64::consts::PI
                ));
                self.dirty = true;
            }
            MouseEventKind::Up(_) => self.dragging = false,
            MouseEventKind::ScrollUp => update(self, Action::ZoomIn),
            MouseEventKind::ScrollDown => update(self, Action::ZoomOut),
            _ => {}
        }
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

    /// Forces the next frame to be drawn (after a resize).
    pub fn invalidate(&mut self) {
        self.dirty = true;
    }

    /// The canvas geometry of the last draw (where mouse cells land in world coordinates).
    pub fn geom_for_tests(&self) -> Option<CanvasGeom> {
        self.geom
    }

    /// Whether time should tick: playing, or the paper's run still catching up.
    pub fn is_playing(&self) -> bool {
        self.playing || self.paper_lags()
    }

    pub fn mouse_capture(&self) -> bool {
        self.mouse
    }

    /// No NaN or infinity in any readout, cursors in range, settings valid.
    pub fn check_invariants(&self) -> Result<(), String> {
        let check_sim = |name: &str, sim: &crate::sim::Sim| -> Result<(), String> {
            if sim.samples.is_empty() || sim.cursor >= sim.samples.len() {
                return Err(format!(
                    "{name}: cursor {} out of {} samples",
                    sim.cursor,
                    sim.samples.len()
                ));
            }
            let s = sim.now();
            let vals = [
                ("tau", s.tau),
                ("xi", s.xi()),
                ("xi'", s.xi_dot()),
                ("|u|", s.u().length()),
                ("theta", s.r.y.atan2(s.r.x)),
            ];
            for (k, v) in vals {
                if !v.is_finite() {
                    return Err(format!("{name}: {k} = {v}"));
                }
            }
            if let Some(t) = s.theta_dot()
                && !t.is_finite()
            {
                return Err(format!("{name}: theta' = {t}"));
            }
            Ok(())
        };
        check_sim("run", &self.sim)?;
        if let Some(p) = &self.paper {
            check_sim("paper", p)?;
            if p.run.settings != Settings::paper() {
                return Err("paper run does not use the paper's settings".into());
            }
        }
        self.initial.validate()?;
        self.settings.validate()?;
        if self.sim.run.initial != self.initial || self.sim.run.settings != self.settings {
            return Err("run is not from the current initial conditions".into());
        }
        if !(state::SPEED_RANGE.0..=state::SPEED_RANGE.1).contains(&self.speed) {
            return Err(format!("speed {} out of range", self.speed));
        }
        if !(self.zoom.is_finite() && self.zoom > 0.0 && self.pan.is_finite()) {
            return Err(format!("bad view: zoom {} pan {}", self.zoom, self.pan));
        }
        Ok(())
    }
}
