//! What every session of a process asks alike, computed once: the latest answers asked for,
//! each in a slot of its own that the first asker fills and later askers share (a run's second
//! opinion, `sim::doubts`; an analysis page's pieces, `analysis::shared`; a class's frame,
//! `serve::frames`). What is kept is bounded: a number of slots, and a budget of their keys'
//! weights, the oldest going first.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

/// Slots by what they answer, newest last.
pub struct Kept<K, V> {
    slots: Mutex<VecDeque<(K, Arc<V>)>>,
    limit: usize,
    weight: fn(&K) -> usize,
    budget: usize,
}

fn weightless<K>(_: &K) -> usize {
    0
}

impl<K: PartialEq, V> Kept<K, V> {
    /// At most `limit` slots.
    pub const fn new(limit: usize) -> Kept<K, V> {
        Kept::weighed(limit, weightless, 0)
    }

    /// At most `limit` slots, whose keys' `weight`s add up to `budget` at most (a slot over
    /// it alone is answered, not kept).
    pub const fn weighed(limit: usize, weight: fn(&K) -> usize, budget: usize) -> Kept<K, V> {
        Kept {
            slots: Mutex::new(VecDeque::new()),
            limit,
            weight,
            budget,
        }
    }

    /// The slot kept for `key`, or a new one that `make` gives it. An asker holding a slot
    /// keeps it whole after it leaves the list.
    pub fn slot(&self, key: &K, make: impl FnOnce(&K) -> V) -> Arc<V>
    where
        K: Clone,
    {
        self.slot_fitting(key, |k, _| k == key, make)
    }

    /// The first slot kept whose key and answer `fit` (an answer that holds for more than its
    /// own key), or a new one for `key` that `make` gives.
    pub fn slot_fitting(
        &self,
        key: &K,
        fit: impl Fn(&K, &V) -> bool,
        make: impl FnOnce(&K) -> V,
    ) -> Arc<V>
    where
        K: Clone,
    {
        let mut slots = self.lock();
        if let Some((_, slot)) = slots.iter().find(|(k, v)| fit(k, v)) {
            return Arc::clone(slot);
        }
        let slot = Arc::new(make(key));
        slots.push_back((key.clone(), Arc::clone(&slot)));
        let over = |slots: &VecDeque<(K, Arc<V>)>| {
            slots.len() > self.limit
                || slots.iter().map(|(k, _)| (self.weight)(k)).sum::<usize>() > self.budget
        };
        while over(&slots) {
            slots.pop_front();
        }
        slot
    }

    /// Keeps only the slots whose keys `keep`.
    pub fn retain(&self, mut keep: impl FnMut(&K) -> bool) {
        self.lock().retain(|(k, _)| keep(k));
    }

    /// Slots kept now.
    #[cfg(test)]
    pub fn kept(&self) -> usize {
        self.lock().len()
    }

    fn lock(&self) -> MutexGuard<'_, VecDeque<(K, Arc<V>)>> {
        self.slots.lock().unwrap_or_else(PoisonError::into_inner)
    }
}
