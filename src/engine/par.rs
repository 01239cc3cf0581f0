//! Many independent runs on all cores (the sweeps of Sec. IV, the outcome map, the explorer's
//! analysis pages).

use std::sync::atomic::{AtomicUsize, Ordering};

/// The cores available to this process (1 if unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Maps `f` over `items` on all available cores, keeping order. Items are handed out one at a
/// time (an atomic counter), so a few slow items (escape speeds near a saddle) do not leave a
/// core idle as a fixed split would.
pub fn par_map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    par_map_counted(items, &AtomicUsize::new(0), f)
}

/// [`par_map`], counting the items done in `done` as they finish (for a progress bar read
/// from another thread).
pub fn par_map_counted<T: Sync, R: Send>(
    items: &[T],
    done: &AtomicUsize,
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    let f = |item: &T| {
        let r = f(item);
        done.fetch_add(1, Ordering::Relaxed);
        r
    };
    let threads = cores().min(items.len().max(1));
    if threads <= 1 {
        return items.iter().map(f).collect();
    }
    let next = AtomicUsize::new(0);
    let mut out: Vec<(usize, R)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(item) = items.get(i) else { break };
                        done.push((i, f(item)));
                    }
                    done
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("sweep worker panicked"))
            .collect()
    });
    out.sort_by_key(|(i, _)| *i);
    out.into_iter().map(|(_, r)| r).collect()
}

/// Calls `f` on each of `items` on `threads` threads (the caller's among them), handed out
/// one at a time in order; all stop taking items once one call returns `false`. For work
/// that streams its answers out as they come (the explorer's pages) rather than collecting
/// them.
pub fn par_each<T: Sync>(items: &[T], threads: usize, f: impl Fn(&T) -> bool + Sync) {
    let next = AtomicUsize::new(0);
    let work = || {
        while let Some(item) = items.get(next.fetch_add(1, Ordering::Relaxed)) {
            if !f(item) {
                // The others stop at their next item.
                next.store(items.len(), Ordering::Relaxed);
                break;
            }
        }
    };
    let threads = threads.clamp(1, items.len().max(1));
    std::thread::scope(|scope| {
        for _ in 1..threads {
            scope.spawn(work);
        }
        work();
    });
}
