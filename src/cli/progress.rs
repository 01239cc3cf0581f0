//! Progress on stderr for the long commands (`sweep`, `plot`, `critical`, `bench`): a bar while the
//! work runs, drawn only where stderr is a terminal (nothing in a pipe or a log), cleared
//! when it ends.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

/// How often the bar reads the count.
const EVERY: Duration = Duration::from_millis(100);

/// Runs `work`, which counts what it has done of `total` in the counter it is given, with a
/// bar saying `what` on stderr meanwhile; returns what `work` returns.
pub fn watch<R>(what: &str, total: usize, work: impl FnOnce(&AtomicUsize) -> R) -> R {
    watch_on(ProgressDrawTarget::stderr(), what, total, work)
}

/// A spinner saying which task runs (`set_message`), for work of unknown length (`bench`),
/// drawn only where stderr is a terminal; `finish_and_clear` when done.
pub fn tasks() -> ProgressBar {
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} {elapsed}") {
        bar.set_style(style);
    }
    bar.enable_steady_tick(EVERY);
    bar
}

/// [`watch`], drawn on `target` (hidden: a test's, or stderr that is not a terminal).
fn watch_on<R>(
    target: ProgressDrawTarget,
    what: &str,
    total: usize,
    work: impl FnOnce(&AtomicUsize) -> R,
) -> R {
    let bar = ProgressBar::with_draw_target(Some(total as u64), target);
    if let Ok(style) =
        ProgressStyle::with_template("{msg} {wide_bar} {pos}/{len} {elapsed} (eta {eta})")
    {
        bar.set_style(style);
    }
    bar.set_message(what.to_string());
    let done = AtomicUsize::new(0);
    let finished = AtomicBool::new(false);
    let out = std::thread::scope(|s| {
        let ticker = s.spawn(|| {
            while !finished.load(Ordering::Relaxed) {
                bar.set_position(done.load(Ordering::Relaxed) as u64);
                std::thread::park_timeout(EVERY);
            }
        });
        let out = work(&done);
        finished.store(true, Ordering::Relaxed);
        ticker.thread().unpark();
        out
    });
    bar.finish_and_clear();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_work_is_done_and_counted_whatever_the_bar() {
        let out = watch_on(ProgressDrawTarget::hidden(), "test", 10, |done| {
            for _ in 0..10 {
                done.fetch_add(1, Ordering::Relaxed);
            }
            done.load(Ordering::Relaxed) * 2
        });
        assert_eq!(out, 20);
    }
}
