//! What only the tests read of a run, kept out of its own surface (as `app::testing` is): a
//! test brings it in with `use turntable::sim::testing::Testing as _`.

use super::Sim;

/// A run inspected as the tests do.
pub trait Testing {
    /// How far the run has been integrated (the screen may be behind).
    fn run_tau(&self) -> f64;
}

impl Testing for Sim {
    fn run_tau(&self) -> f64 {
        self.run.tau()
    }
}
