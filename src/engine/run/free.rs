//! The runs in closed form throughout: μ = 0 (the straight line) and Stokes drag (its linear
//! solution), one stride at a time to τ-max, stopping at the escape certificate on the way.

use super::{Certificate, Escape, Limit, Run, RunError, StepInfo};
use crate::model::State;

/// How far one closed-form stride of a frictionless run reaches when no end is given: any
/// length costs the same.
const FREE_STRIDE: f64 = 1e3;
impl Run {
    /// The closed-form state at τ: the straight line (μ = 0) or the Stokes solution.
    pub(super) fn exact_state(&self, tau: f64) -> State {
        match &self.stokes {
            Some(st) => st.state(tau),
            None => self.initial.free_state(tau),
        }
    }

    /// μ = 0 or Stokes drag: one closed-form stride to `tau_max` (or [`FREE_STRIDE`] on when
    /// that is infinite), stopping at the escape certificate on the way.
    #[cold]
    #[inline(never)]
    pub(super) fn free_step(&mut self, tau_max: f64) -> Result<(), RunError> {
        let mut end = if tau_max.is_finite() {
            tau_max
        } else {
            self.stepper.t + FREE_STRIDE
        };
        if self.escape.is_none()
            && let Some(te) = match &self.stokes {
                Some(st) => st.escape(),
                None => self.initial.free_escape(),
            }
            && te <= end
        {
            end = te.max(self.stepper.t);
            self.escape = Some(Escape {
                tau: te,
                by: Certificate::Radial,
                state: self.exact_state(te),
            });
        }
        let to = self.exact_state(end);
        if !(to.r.is_finite() && to.v.is_finite()) {
            // Stokes drag grows exponentially: e^{Re λ+ τ} past f64's range.
            return Err(RunError::Overflow { tau: end });
        }
        let frame = self.settings.frame;
        self.last_step = Some(StepInfo {
            t0: self.stepper.t,
            h: end - self.stepper.t,
            limit: if self.stokes.is_some() {
                Limit::Drag
            } else {
                Limit::Frictionless
            },
            err_ratio: None,
            rejected: 0,
        });
        self.stepper.y = frame.from_state(&to);
        self.stepper.t = end;
        self.last = None;
        Ok(())
    }
}
