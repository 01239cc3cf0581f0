//! The runs a solver made at the ends of its bracket, kept where they stopped (the slow
//! manifold's verdict, the stick certificate, or the end) for [`super::certify`] to continue in
//! full instead of running them again from the start. A run is deterministic and a solver's
//! run is stepped as [`Run::run`] steps it, so continued it is the run in full: at the escape
//! speed's bracket ends that skips the two thirds of each run before its verdict.

use crate::method::Settings;
use crate::model::Initial;
use crate::run::{Outcome, Run};

/// The latest run on each side of a threshold, with the value it was made at: a bracket's end
/// moves to each new run on its side, so these are its ends' when they match them.
#[derive(Clone, Debug, Default)]
pub struct Kept {
    stuck: Option<(f64, Run)>,
    escaped: Option<(f64, Run)>,
}

impl Kept {
    /// Keeps `run`, made at `x`, as the latest on its side.
    pub(super) fn keep(&mut self, x: f64, escapes: bool, run: Run) {
        let side = if escapes {
            &mut self.escaped
        } else {
            &mut self.stuck
        };
        *side = Some((x, run));
    }

    /// The run kept at `x` on `want`'s side, if it was made from `initial` at `settings`.
    pub(super) fn take(
        &mut self,
        x: f64,
        want: Outcome,
        initial: Initial,
        settings: Settings,
    ) -> Option<Run> {
        let side = if want == Outcome::Stuck {
            &mut self.stuck
        } else {
            &mut self.escaped
        };
        side.take()
            .filter(|(at, r)| *at == x && r.initial() == initial && r.settings() == settings)
            .map(|(_, r)| r)
    }
}
