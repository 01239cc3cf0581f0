//! The latest answers a process was asked for, each in a slot of its own that the first asker
//! fills and later askers share: what every session asks alike (a second opinion,
//! [`super::doubts`]; an analysis page's pieces, `analysis::shared`) is computed once, and no
//! more than a bounded number are kept.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

/// Slots by what they answer, the oldest going first past `limit`.
pub struct Kept<K, V> {
    slots: Mutex<VecDeque<(K, Arc<V>)>>,
    limit: usize,
}

impl<K: PartialEq, V> Kept<K, V> {
    pub const fn new(limit: usize) -> Kept<K, V> {
        Kept {
            slots: Mutex::new(VecDeque::new()),
            limit,
        }
    }

    /// The slot kept for `key`, or a new one that `make` gives it. An asker holding a slot
    /// keeps it whole after it leaves the list.
    pub fn slot(&self, key: K, make: impl FnOnce(&K) -> V) -> Arc<V> {
        let mut slots = self.lock();
        if let Some((_, slot)) = slots.iter().find(|(k, _)| *k == key) {
            return Arc::clone(slot);
        }
        let slot = Arc::new(make(&key));
        slots.push_back((key, Arc::clone(&slot)));
        if slots.len() > self.limit {
            slots.pop_front();
        }
        slot
    }

    /// Slots kept now.
    pub fn kept(&self) -> usize {
        self.lock().len()
    }

    fn lock(&self) -> MutexGuard<'_, VecDeque<(K, Arc<V>)>> {
        self.slots.lock().unwrap_or_else(PoisonError::into_inner)
    }
}
