//! What only the tests use, kept out of the model's own surface: the integration tests
//! (`tests/`) reach only what is public, so these are public, but no shell and nothing in the
//! library calls them. A test brings them in with `use turntable::app::testing::Testing as _`;
//! the program's door into the model stays [`update`](super::update()) and the `tell_*` methods.

use super::{App, CanvasGeom, Chord, Effects, state, update};
use crate::engine::Settings;
use crossterm::event::{KeyEvent, MouseEvent};

/// The model driven and inspected as the tests do, without a session around it.
pub trait Testing {
    /// A terminal's key event: its chord, if it has one (releases have none). Returns what
    /// the shell must carry out (see [`update()`]).
    fn handle_key(&mut self, key: KeyEvent) -> Effects;
    /// The mouse as actions, through the canvas as last drawn: a click places the release
    /// point, a drag sets the initial velocity, the wheel zooms. Returns what the shell must
    /// carry out (see [`update()`]).
    fn handle_mouse(&mut self, ev: MouseEvent) -> Effects;
    /// The canvas geometry of the last draw (where mouse cells land in world coordinates):
    /// the first canvas.
    fn geom_for_tests(&self) -> Option<CanvasGeom>;
    /// Every canvas of the last draw (two in a split view).
    fn geoms_for_tests(&self) -> &[CanvasGeom];
    /// No NaN or infinity in any readout, cursors in range, settings valid.
    fn check_invariants(&self) -> Result<(), String>;
}

impl Testing for App {
    fn handle_key(&mut self, key: KeyEvent) -> Effects {
        match Chord::from_event(&key) {
            Some(chord) => self.press(chord),
            None => Effects::new(),
        }
    }

    fn handle_mouse(&mut self, ev: MouseEvent) -> Effects {
        match self.mouse_action(ev) {
            Some(a) => update(self, a),
            None => Effects::new(),
        }
    }

    fn geom_for_tests(&self) -> Option<CanvasGeom> {
        self.geom.first().copied()
    }

    fn geoms_for_tests(&self) -> &[CanvasGeom] {
        &self.geom
    }

    fn check_invariants(&self) -> Result<(), String> {
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
        check_sim("run", self.sim())?;
        if let Some(p) = self.paper() {
            check_sim("paper", p)?;
            if p.settings() != Settings::paper() {
                return Err("paper run does not use the paper's settings".into());
            }
        }
        // The runs are those of the initial conditions shown: `Exploration` holds that.
        self.initial().validate().map_err(|e| e.to_string())?;
        self.settings().validate().map_err(|e| e.to_string())?;
        if self.pins.len() > crate::pin::MAX_PINS {
            return Err(format!("{} pins", self.pins.len()));
        }
        for p in &self.pins {
            let finite = |s: &crate::engine::State| {
                [s.tau, s.r.x, s.r.y, s.v.x, s.v.y]
                    .iter()
                    .all(|v| v.is_finite())
            };
            if p.path.is_empty() || p.path.len() > 2 * crate::pin::PIN_POINTS {
                return Err(format!("pin {}: {} points", p.spec.label, p.path.len()));
            }
            if !p.path.iter().all(finite) {
                return Err(format!("pin {}: a point not finite", p.spec.label));
            }
        }
        if !(state::SPEED_RANGE.0..=state::SPEED_RANGE.1).contains(&self.speed) {
            return Err(format!("speed {} out of range", self.speed));
        }
        if !(self.view.zoom.is_finite() && self.view.zoom > 0.0 && self.view.pan.is_finite()) {
            return Err(format!(
                "bad view: zoom {} pan {}",
                self.view.zoom, self.view.pan
            ));
        }
        Ok(())
    }
}
