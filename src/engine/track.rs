//! A path kept at bounded memory, for drawing a run of any length: the one container of the
//! explorer's trail (`sim`), a pin's path (`pin`) and the body's track (`rod`). It keeps
//! every `stride`-th point offered, its events and its ends; when it holds `cap` points it keeps
//! every other one and doubles its stride, so a path of any length costs the same memory.
//! Offered the points of a τ grid in turn, it keeps a grid (of a spacing that doubles), and
//! says which point it keeps next ([`Track::next_index`]), so the ones between need not be
//! computed.

/// A bounded, decimating path (see the module's note).
#[derive(Clone, Debug, PartialEq)]
pub struct Track<T> {
    points: Vec<T>,
    /// Per kept point: whether it is an event (kept through a halving while that halves the
    /// track enough), and its offer's index (0 for the first point).
    marks: Vec<(bool, u64)>,
    cap: usize,
    stride: u64,
    /// The last offer's index.
    offered: u64,
    /// The newest point offered when it was not kept (the path's end until a later one is).
    pending: Option<T>,
}

impl<T: Copy> Track<T> {
    /// A track from `first`, holding fewer than `cap` points (at least 4) while it grows.
    pub fn new(first: T, cap: usize) -> Track<T> {
        Track {
            points: vec![first],
            marks: vec![(true, 0)],
            cap: cap.max(4),
            stride: 1,
            offered: 0,
            pending: None,
        }
    }

    /// The next point of the path: kept if it is an `event`, or `stride` offers after the last
    /// kept one; an event keeps the newest point before it too (the path's last stretch
    /// before the event is drawn on its own chord).
    pub fn push(&mut self, point: T, event: bool) {
        self.offered += 1;
        if !event && self.offered - self.last_kept() < self.stride {
            self.pending = Some(point);
            return;
        }
        if event && let Some(p) = self.pending.take() {
            self.keep(p, false, self.offered - 1);
        }
        self.pending = None;
        self.keep(point, event, self.offered);
    }

    /// An event between two offers (a stop between two points of a grid): kept, as an event,
    /// the newest point before it too, without counting as an offer (a grid's indices go on).
    pub fn insert(&mut self, point: T) {
        if let Some(p) = self.pending.take() {
            self.keep(p, false, self.offered);
        }
        self.keep(point, true, self.last_kept());
    }

    /// The offer's index of the point this track keeps next, if offered every point in turn:
    /// a caller sampling a grid computes that one (and [`Track::push_at`] it), not those
    /// before, which would be thinned away.
    pub fn next_index(&self) -> u64 {
        self.offered.max(self.last_kept() + self.stride - 1) + 1
    }

    /// Thinned ahead of a stretch to offer index `last`: its stride doubled (and its points
    /// halved when full) until at most half its cap of points are still to be kept on the way,
    /// so that a stretch of any length costs at most that many computed points.
    pub fn reserve_for(&mut self, last: u64) {
        while last.saturating_sub(self.offered) / self.stride > (self.cap / 2) as u64 {
            self.halve();
        }
    }

    /// Offers the point of index `k` (at most [`Track::next_index`]), those before it skipped.
    pub fn push_at(&mut self, k: u64, point: T) {
        self.offered = self.offered.max(k.saturating_sub(1));
        self.push(point, false);
    }

    /// Points kept but the newest offered: what is drawn of a path still growing.
    pub fn points(&self) -> &[T] {
        &self.points
    }

    /// Room held for points (never above `cap`'s next power of two).
    pub fn capacity(&self) -> usize {
        self.points.capacity()
    }

    /// The kept points and the newest offered, if not kept: a finished path, to its end.
    pub fn finish(mut self) -> Vec<T> {
        if let Some(p) = self.pending.take() {
            self.points.push(p);
        }
        self.points
    }

    /// The kept points before `end`'s τ, and `end` itself: a path cut at a known end (the
    /// newest grid point offered, if not kept, is dropped with those at or past it).
    pub fn end_at(mut self, end: T, tau: impl Fn(&T) -> f64) -> Vec<T>
    where
        T: PartialEq,
    {
        while self.points.len() > 1 && self.points.last().is_some_and(|p| tau(p) >= tau(&end)) {
            self.points.pop();
        }
        if self.points.last() != Some(&end) {
            self.points.push(end);
        }
        self.points
    }

    fn last_kept(&self) -> u64 {
        self.marks.last().map_or(0, |m| m.1)
    }

    fn keep(&mut self, point: T, event: bool, at: u64) {
        self.points.push(point);
        self.marks.push((event, at));
        if self.points.len() >= self.cap {
            self.halve();
        }
    }

    /// Every other kept point dropped (events kept while that halves the track enough, then
    /// every other of whatever is left), the first always; a newest point dropped is the
    /// pending end again.
    fn halve(&mut self) {
        self.stride *= 2;
        let newest = self.points.last().copied();
        for events_too in [false, true] {
            if self.points.len() < self.cap / 4 * 3 {
                break;
            }
            let keep: Vec<bool> = (0..self.points.len())
                .map(|k| k % 2 == 0 || (!events_too && self.marks[k].0))
                .collect();
            let mut it = keep.iter();
            self.points.retain(|_| *it.next().unwrap_or(&true));
            let mut it = keep.iter();
            self.marks.retain(|_| *it.next().unwrap_or(&true));
        }
        if self.marks.last().is_some_and(|m| m.1 < self.offered) {
            self.pending = newest;
        }
    }
}

impl<T> std::ops::Deref for Track<T> {
    type Target = [T];
    /// A track reads as the points it keeps.
    fn deref(&self) -> &[T] {
        &self.points
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whatever is offered, a track never holds `cap` points, keeps its first and newest and
    /// every event while events are fewer than a quarter of it; offered a grid, it keeps a grid.
    #[test]
    fn a_track_is_bounded_and_keeps_its_ends_and_events() {
        let mut seed = 7u64;
        let mut rand = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            seed >> 33
        };
        for cap in [4usize, 5, 16, 64, 1000] {
            for n in [0u64, 1, 3, 10, 100, 10_000, 100_000] {
                let mut t = Track::new(0u64, cap);
                let mut events = vec![];
                for k in 1..=n {
                    let event = events.len() < cap / 8 && rand() % 97 == 0;
                    if event {
                        events.push(k);
                    }
                    t.push(k, event);
                    assert!(t.len() < cap.max(4), "cap {cap} n {n}: {}", t.len());
                }
                let all = t.finish();
                assert!(all.len() <= cap.max(4), "cap {cap} n {n}");
                assert_eq!((all[0], *all.last().unwrap()), (0, n), "cap {cap} n {n}");
                assert!(all.windows(2).all(|w| w[0] < w[1]));
                if cap >= 16 {
                    assert!(events.iter().all(|e| all.contains(e)), "cap {cap} n {n}");
                }
            }
        }
        // A grid: only the points it keeps are computed, and they are the grid's multiples.
        let mut t = Track::new(0u64, 64);
        let mut computed = 0;
        while t.next_index() <= 100_000 {
            let k = t.next_index();
            t.push_at(k, k);
            computed += 1;
        }
        let stride = t[1] - t[0];
        assert!(
            t.iter().all(|k| k % stride == 0) && t.len() >= 16,
            "{:?}",
            &t[..]
        );
        assert!(computed < 1000, "{computed}");
        // An event between two grid points is kept, and the grid goes on.
        let before = t.next_index();
        t.insert(before - 1);
        t.push_at(before, before);
        assert_eq!(t[t.len() - 2..], [before - 1, before]);
        // Thinned ahead, a stretch of any length computes at most half the cap.
        t.reserve_for(100_000_000);
        let mut computed = 0;
        while t.next_index() <= 100_000_000 {
            let k = t.next_index();
            t.push_at(k, k);
            computed += 1;
        }
        assert!(computed <= 32 && t.len() < 64, "{computed} {}", t.len());
        let cut = t.end_at(99_999_999, |k| *k as f64);
        assert_eq!(*cut.last().unwrap(), 99_999_999);
        assert!(cut.windows(2).all(|w| w[0] < w[1]));
    }
}
