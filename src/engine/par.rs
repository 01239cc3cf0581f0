//! Many independent runs on all cores (the sweeps of Sec. IV, the outcome map, the explorer's
//! analysis pages).

use std::sync::atomic::{AtomicUsize, Ordering};

/// The cores available to this process (1 if unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Items handed out at a time: a few per thread's hundredth of the work, so that the last
/// handout leaves a core idle for a hundredth at most, and items of a few microseconds (an
/// outcome-map cell) are not each a trip to the shared counter.
fn chunk(items: usize, threads: usize) -> usize {
    (items / (100 * threads)).max(1)
}

/// Maps `f` over `items` on all available cores, keeping order. Items are handed out a
/// `chunk` at a time (an atomic counter), so a few slow items (escape speeds near a saddle)
/// do not leave a core idle as a fixed split would.
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
    let (next, chunk) = (AtomicUsize::new(0), chunk(items.len(), threads));
    let mut out: Vec<(usize, R)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let i = next.fetch_add(chunk, Ordering::Relaxed);
                        let Some(some) = items.get(i..(i + chunk).min(items.len())) else {
                            break;
                        };
                        done.extend(some.iter().enumerate().map(|(k, x)| (i + k, f(x))));
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
/// a `chunk` at a time in order; all stop taking items once one call returns `false`. For
/// work that streams its answers out as they come (the explorer's pages) rather than
/// collecting them.
pub fn par_each<T: Sync>(items: &[T], threads: usize, f: impl Fn(&T) -> bool + Sync) {
    let threads = threads.clamp(1, items.len().max(1));
    let (next, chunk) = (AtomicUsize::new(0), chunk(items.len(), threads));
    let stop = std::sync::atomic::AtomicBool::new(false);
    let work = || {
        while let Some(some) = items.get(next.fetch_add(chunk, Ordering::Relaxed)..) {
            for item in &some[..chunk.min(some.len())] {
                if stop.load(Ordering::Relaxed) {
                    return;
                }
                if !f(item) {
                    // The others stop at their next item.
                    stop.store(true, Ordering::Relaxed);
                    return;
                }
            }
        }
    };
    std::thread::scope(|scope| {
        for _ in 1..threads {
            scope.spawn(work);
        }
        work();
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// Every item once, in order, whatever the chunk: none, one, fewer than the threads, a
    /// curve's 72 and a map's 2688 (chunks of 13).
    #[test]
    fn every_item_is_mapped_once_in_order() {
        for n in [0, 1, 3, 72, 2688, 2689] {
            let items: Vec<usize> = (0..n).collect();
            assert_eq!(
                par_map(&items, |&i| 2 * i),
                (0..n).map(|i| 2 * i).collect::<Vec<_>>()
            );
            let seen = Mutex::new(Vec::new());
            par_each(&items, 2, |&i| {
                seen.lock().unwrap().push(i);
                true
            });
            let mut seen = seen.into_inner().unwrap();
            seen.sort_unstable();
            assert_eq!(seen, items, "{n}");
        }
    }

    /// Once a call says stop, no item is taken after it on its thread, and the others stop at
    /// their next item: far fewer than all are seen.
    #[test]
    fn a_false_stops_the_others() {
        let items: Vec<usize> = (0..10_000).collect();
        let seen = AtomicUsize::new(0);
        par_each(&items, 2, |&i| {
            seen.fetch_add(1, Ordering::Relaxed);
            i < 100
        });
        let seen = seen.into_inner();
        assert!((101..1000).contains(&seen), "{seen}");
    }
}
