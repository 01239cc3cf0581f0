//! How often a session draws a frame that only time moved: as often as the explorer does while
//! the cores can draw that for every session, less often when they cannot, so that a frame
//! answering a key (never held back by this) finds a core free. The class grows by playing
//! its animation at fewer frames a second, not by answering keys later.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// The share of the cores the frames that only time moved may take, all sessions together:
/// the rest is for the frames that answer keys, the ticks and SSH.
const SHARE: f64 = 0.5;
/// The longest a moving picture waits for its next frame, however many are drawing.
const LONGEST: Duration = Duration::from_millis(500);

/// A frame's cost, as the sessions measure it.
pub struct Pace {
    /// CPU time a frame takes, in ns: a running mean over the last sixteen or so.
    frame_ns: AtomicU64,
    cores: f64,
}

impl Pace {
    pub fn new(cores: usize) -> Pace {
        Pace {
            frame_ns: AtomicU64::new(0),
            cores: cores.max(1) as f64,
        }
    }

    /// A frame took `cpu` of its thread's time.
    pub fn drew(&self, cpu: Duration) {
        let ns = u64::try_from(cpu.as_nanos()).unwrap_or(u64::MAX);
        // Sessions racing here lose a sample now and then: a mean needs no more.
        let mean = self.frame_ns.load(Ordering::Relaxed);
        let next = if mean == 0 {
            ns
        } else {
            mean - mean / 16 + ns / 16
        };
        self.frame_ns.store(next, Ordering::Relaxed);
    }

    /// The least time between two frames that only time moved, with `sessions` drawing: at
    /// least `base` (the explorer's), at most [`LONGEST`], and long enough that their frames
    /// take [`SHARE`] of the cores at most.
    pub fn gap(&self, sessions: usize, base: Duration) -> Duration {
        let ns = self.frame_ns.load(Ordering::Relaxed) as f64 * sessions as f64;
        let needed = Duration::from_secs_f64(ns / (self.cores * SHARE) / 1e9);
        needed.clamp(base, LONGEST.max(base))
    }
}

/// The CPU time the calling thread has used.
pub fn thread_cpu() -> Duration {
    let t = rustix::time::clock_gettime(rustix::time::ClockId::ThreadCPUTime);
    Duration::new(
        u64::try_from(t.tv_sec).unwrap_or(0),
        u32::try_from(t.tv_nsec).unwrap_or(0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: Duration = Duration::from_millis(33);

    /// A few sessions draw at the explorer's rate; a class whose frames would take more than
    /// half of the cores at that rate draws each picture less often, in proportion, up to
    /// half a second between frames.
    #[test]
    fn the_gap_grows_with_the_class_once_the_cores_are_half_taken() {
        let pace = Pace::new(2);
        assert_eq!(pace.gap(300, BASE), BASE, "nothing measured yet");
        pace.drew(Duration::from_micros(300));
        // 10 sessions at 30 frames a second: 90 ms of a core a second.
        assert_eq!(pace.gap(10, BASE), BASE);
        // 300 sessions: 300 × 0.3 ms on one core (half of two) is 90 ms.
        assert_eq!(pace.gap(300, BASE), Duration::from_millis(90));
        assert_eq!(pace.gap(100_000, BASE), LONGEST);
        // The mean follows the frames' cost: sixteen at 0.6 ms take it to
        // 600 − 300·(15/16)^16 ≈ 493 µs, so 300 sessions draw every 148 ms.
        for _ in 0..16 {
            pace.drew(Duration::from_micros(600));
        }
        let g = pace.gap(300, BASE).as_secs_f64() * 1e3;
        assert!((147.0..149.0).contains(&g), "{g} ms");
    }

    #[test]
    fn a_thread_counts_its_own_cpu() {
        let t0 = thread_cpu();
        let mut x = 0u64;
        for i in 0..2_000_000u64 {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(i);
        }
        std::hint::black_box(x);
        assert!(thread_cpu() > t0);
    }
}
