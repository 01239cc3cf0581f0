//! Runs pinned beside the one on screen (`b`): pinning the run on screen, at bounded cost,
//! under a label and a marker of their own.

use super::exploration::view_radius;
use super::state::App;
use crate::present::num;

impl App {
    /// Pins the run on screen (`b`): its whole path, computed now at bounded cost, labelled
    /// by the scene's name, or by a letter once edited. A seventh pin replaces the oldest.
    pub fn pin_run(&mut self) {
        let dropped = if self.pins.len() >= crate::pin::MAX_PINS {
            Some(self.pins.remove(0))
        } else {
            None
        };
        let label = if self.edited() {
            let used = |c: char| self.pins.iter().any(|p| *p.spec.label == *c.to_string());
            ('A'..='Z').find(|c| !used(*c)).unwrap_or('?').to_string()
        } else {
            self.scene()
                .name
                .chars()
                .take(crate::pin::LABEL_MAX)
                .collect()
        };
        let spec = crate::pin::PinSpec {
            label: label.into(),
            initial: self.initial(),
            settings: self.settings(),
            turn: self.view.turn,
            units: self.units,
        };
        match pin_of(spec, &self.pins) {
            Ok(p) => {
                let what = match p.outcome {
                    crate::engine::Outcome::Stuck => {
                        format!("sticks at ξ = {}", num(p.end().xi(), 4))
                    }
                    crate::engine::Outcome::Escaped => "escapes".into(),
                    crate::engine::Outcome::Running if p.end().tau < crate::pin::PIN_TAU_MAX => {
                        format!(
                            "still slides at τ = {}, where a pin's {} steps ran out",
                            num(p.end().tau, 3),
                            crate::pin::PIN_STEPS
                        )
                    }
                    crate::engine::Outcome::Running => {
                        format!("still slides at τ = {}", num(p.end().tau, 1))
                    }
                };
                let mut n = format!(
                    "pinned {}{} ({} of {}): {what}; B clears the pins",
                    p.marker,
                    p.spec.label,
                    self.pins.len() + 1,
                    crate::pin::MAX_PINS
                );
                if let Some(d) = dropped {
                    n.push_str(&format!(
                        "; {} pins at most: the oldest, {}{}, unpinned",
                        crate::pin::MAX_PINS,
                        d.marker,
                        d.spec.label
                    ));
                }
                self.pins.push(p);
                self.notice = Some(n);
            }
            Err(e) => self.notice = Some(format!("cannot pin this run: {e}")),
        }
    }

    /// The τ span the time plots show by default: the run so far, or the longest pin.
    pub fn plot_span(&self) -> f64 {
        self.pins
            .iter()
            .map(|p| p.end().tau * p.scale(self.units).1)
            .fold(self.sim().now().tau, f64::max)
    }
}

/// A pin of `spec`, its marker the first one `pins` leaves free.
pub(super) fn pin_of(
    spec: crate::pin::PinSpec,
    pins: &[crate::pin::Pin],
) -> Result<crate::pin::Pin, crate::error::Error> {
    let marker = crate::pin::MARKERS
        .into_iter()
        .find(|m| pins.iter().all(|p| p.marker != *m))
        .unwrap_or(crate::pin::MARKERS[0]);
    let radius = view_radius(&spec.initial);
    crate::pin::Pin::compute(spec, marker, radius)
}
