//! The explorer over a slow link (issue 19): the real binary on a pseudo-terminal the test
//! opens itself (no TTY needed; skipped, saying so, where none can be opened), read through
//! a link that carries a few bytes at a time and holds everything else, as ssh's buffers do,
//! and that answers cursor-position queries when they arrive. The bounds are in frames and
//! bytes, not in time.

use crate::common;
use std::io::Read;
use std::os::fd::AsRawFd;
use std::process::{Child, Command};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Begins every frame (crossterm's BeginSynchronizedUpdate).
const FRAME: &[u8] = b"\x1b[?2026h";
const ASK: &[u8] = b"\x1b[6n";
/// Bytes the link carries per step (a step is a millisecond's sleep: at most 8 KB/s, about
/// half of what the explorer writes playing at 120×40 unpaced).
const STEP: usize = 8;

/// What the far end of the link has seen, and the worst backlog so far.
#[derive(Default)]
struct Link {
    produced: usize,
    delivered: Vec<u8>,
    frames_delivered: usize,
    /// The most frames written by the explorer and not yet delivered.
    most_in_flight: usize,
    /// The most bytes written by the explorer and not yet delivered.
    most_queued: usize,
    /// The largest frame delivered, in bytes.
    largest_frame: usize,
    last_frame_at: usize,
}

fn count(hay: &[u8], needle: &[u8]) -> usize {
    hay.windows(needle.len()).filter(|w| *w == needle).count()
}

struct Reap(Child);

impl Drop for Reap {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// The explorer, what the link saw, the master to type on, and the flag that stops the link.
type Spawned = (Reap, Arc<Mutex<Link>>, i32, Arc<AtomicBool>);

/// The explorer at 120×40 on a new pty behind a slow link.
fn spawn(rec: &std::path::Path) -> Option<Spawned> {
    let (master, slave) = common::openpty(120, 40)?;
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_turntable"));
    // Never the user's configuration.
    cmd.env("XDG_CONFIG_HOME", "/nonexistent/turntable-tests/config")
        .args(["--record", rec.to_str().unwrap()])
        .env("TERM", "xterm-256color")
        .env("LANG", "C.UTF-8")
        .env_remove("COLORTERM")
        .env_remove("NO_COLOR")
        .env_remove("LC_ALL");
    common::on_pty(&mut cmd, slave);
    let child = Reap(cmd.spawn().unwrap());
    let fd = master.as_raw_fd();
    let link = Arc::new(Mutex::new(Link::default()));
    let done = Arc::new(AtomicBool::new(false));
    let (seen, stop) = (Arc::clone(&link), Arc::clone(&done));
    std::thread::spawn(move || {
        let mut file = std::fs::File::from(master);
        // SAFETY: our descriptor; the link never blocks on the explorer.
        unsafe { libc::fcntl(fd, libc::F_SETFL, libc::O_NONBLOCK) };
        let mut queue = Vec::new();
        let mut buf = [0; 65536];
        while !stop.load(Ordering::Relaxed) {
            // The explorer's writes never block: the link holds everything.
            while let Ok(n @ 1..) = file.read(&mut buf) {
                queue.extend_from_slice(&buf[..n]);
                let mut l = seen.lock().unwrap();
                l.produced += n;
            }
            let n = STEP.min(queue.len());
            if n > 0 {
                let mut l = seen.lock().unwrap();
                l.most_queued = l.most_queued.max(queue.len());
                l.most_in_flight = l.most_in_flight.max(count(&queue, FRAME));
                let from = l.delivered.len().saturating_sub(ASK.len() - 1);
                l.delivered.extend(queue.drain(..n));
                // A query that arrives is answered, as a terminal at the far end would.
                let asks = count(&l.delivered[from..], ASK);
                for _ in 0..asks {
                    // SAFETY: the master is open while this thread runs.
                    unsafe { libc::write(fd, b"\x1b[20;1R".as_ptr().cast(), 7) };
                }
                let from = l.delivered.len().saturating_sub(n + FRAME.len() - 1);
                for _ in 0..count(&l.delivered[from..], FRAME) {
                    let at = l.delivered.len();
                    if l.frames_delivered > 0 {
                        l.largest_frame = l.largest_frame.max(at - l.last_frame_at);
                    }
                    l.last_frame_at = at;
                    l.frames_delivered += 1;
                }
            }
            std::thread::sleep(Duration::from_millis(1));
        }
    });
    Some((child, link, fd, done))
}

fn wait_for(what: &str, link: &Mutex<Link>, mut done: impl FnMut(&Link) -> bool) {
    let start = Instant::now();
    while !done(&link.lock().unwrap()) {
        assert!(start.elapsed() < Duration::from_secs(60), "never: {what}");
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn type_key(fd: i32, key: u8) {
    // SAFETY: the master is open while the link runs.
    assert_eq!(unsafe { libc::write(fd, [key].as_ptr().cast(), 1) }, 1);
}

#[test]
fn over_a_slow_link_one_frame_is_in_flight_and_keys_show_within_two_frames() {
    let rec = std::env::temp_dir().join(format!("turntable-link-{}.keys", std::process::id()));
    let Some((mut child, link, fd, done)) = spawn(&rec) else {
        return;
    };
    // Three frames: without the pacing, the explorer writes sixty while the first (a whole
    // screen, 14 KB) crosses the link.
    wait_for("3 frames delivered", &link, |l| l.frames_delivered >= 3);
    {
        let l = link.lock().unwrap();
        assert!(
            l.most_in_flight <= 1,
            "{} frames in flight",
            l.most_in_flight
        );
        // One frame and the bytes around it (the query, the screen set-up).
        assert!(
            l.most_queued <= l.largest_frame + 128,
            "{} bytes queued, the largest frame {}",
            l.most_queued,
            l.largest_frame
        );
    }
    // A key shows in the frame after the one in flight: Space, whose pause mark is a few
    // bytes (the help, open and closed again, was two screens to move).
    let (at, frames) = {
        let l = link.lock().unwrap();
        (l.delivered.len(), l.frames_delivered)
    };
    type_key(fd, b' ');
    wait_for("the pause mark", &link, |l| {
        count(&l.delivered[at..], "❚❚".as_bytes()) > 0
    });
    let l = link.lock().unwrap();
    assert!(
        l.frames_delivered - frames <= 2,
        "the pause mark came {} frames after its key",
        l.frames_delivered - frames
    );
    drop(l);
    // Paused: not a byte more. Half a second holds two of the idle loop's wakes (every
    // 250 ms) and fifteen ticks' worth of frames.
    wait_for("the queue to drain", &link, |l| {
        l.produced == l.delivered.len()
    });
    let frames = link.lock().unwrap().frames_delivered;
    std::thread::sleep(Duration::from_millis(250));
    let paused = link.lock().unwrap().produced;
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(
        link.lock().unwrap().produced,
        paused,
        "bytes written while paused"
    );
    let l = link.lock().unwrap();
    assert!(
        l.most_in_flight <= 1,
        "{} frames in flight",
        l.most_in_flight
    );
    drop(l);
    // A drag that the link cannot keep up with: a press, 30 drags and a release in one
    // burst are at most three frames (the drags fold into the last), not thirty.
    let at = link.lock().unwrap().frames_delivered;
    let mut burst = b"\x1b[<0;40;20M".to_vec();
    for c in 41..71 {
        burst.extend_from_slice(format!("\x1b[<32;{c};22M").as_bytes());
    }
    burst.extend_from_slice(b"\x1b[<0;70;22m");
    // SAFETY: the master is open while the link runs.
    let n = unsafe { libc::write(fd, burst.as_ptr().cast(), burst.len()) };
    assert_eq!(n, burst.len() as isize);
    wait_for("the drag drawn", &link, |l| {
        l.frames_delivered > at && l.produced == l.delivered.len()
    });
    std::thread::sleep(Duration::from_millis(100));
    let l = link.lock().unwrap();
    assert!(
        l.most_in_flight <= 3,
        "{} frames in flight",
        l.most_in_flight
    );
    drop(l);
    type_key(fd, b'q');
    let start = Instant::now();
    while child.0.try_wait().unwrap().is_none() {
        assert!(start.elapsed() < Duration::from_secs(30), "never quit");
        std::thread::sleep(Duration::from_millis(20));
    }
    done.store(true, Ordering::Relaxed);
    assert_eq!(child.0.wait().unwrap().code(), Some(0));
    // Time kept real time: the ticks (30 a second, all recorded) outnumber the frames the
    // link could carry (about 15 a second), where they used to be one a frame.
    let script = std::fs::read_to_string(&rec).unwrap();
    let _ = std::fs::remove_file(&rec);
    let ticks: usize = script
        .lines()
        .filter_map(|l| l.strip_prefix("tick"))
        .map(|n| n.trim().parse().unwrap_or(1))
        .sum();
    assert!(
        ticks * 10 > frames * 13,
        "{ticks} ticks for {frames} frames"
    );
}
