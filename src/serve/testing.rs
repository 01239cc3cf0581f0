//! What only the tests count of a server, kept out of its own surface (as `app::testing` is): a
//! test brings it in with `use turntable::serve::testing::Testing as _`.

use super::Shared;

/// A server inspected as the tests do.
pub trait Testing {
    /// Connections at the door now: not in, and in without an explorer.
    fn at_the_door(&self) -> (usize, usize);
}

impl Testing for Shared {
    fn at_the_door(&self) -> (usize, usize) {
        self.door.count()
    }
}
