//! What only the tests do to the explorer's runs, kept out of its own surface (as
//! `app::testing` is): a test brings it in with
//! `use turntable::app::exploration::testing::Testing as _`.

use super::{Exploration, make_rod, rod_cut_notice};

/// The runs set up as the tests do, past the keys.
pub trait Testing {
    /// A body (or none) in place of the scene's; the runs restart.
    fn set_body(&mut self, body: Option<crate::engine::body::Body>);
    /// The body's track computed again within `steps` steps, so cut short there as a track
    /// that runs out of its budget is: the same body, release and settings, a smaller budget.
    fn limit_body_steps(&mut self, steps: u64);
}

impl Testing for Exploration {
    fn set_body(&mut self, body: Option<crate::engine::body::Body>) {
        self.scene.body = body;
        self.restart();
    }

    fn limit_body_steps(&mut self, steps: u64) {
        self.rod = make_rod(self.scene.body, &self.initial, self.settings, steps);
        self.rod_notice = self.rod.as_ref().and_then(rod_cut_notice);
    }
}
