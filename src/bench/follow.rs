//! `turntable bench --serve N --followers`: a class of followers: a presenter at 80×24 playing
//! and pressing `?` every 200 ms (help on, help off), and N students at 80×24 following it,
//! each typing nothing. Per key: the time from the presenter's press to each follower's screen
//! showing it (and to the presenter's own); the process's CPU, the frames the server sent a
//! second and the CPU a frame (clients included), and the bytes a follower receives a second.

use super::cpu_s;
use super::serve::{key, pct, server};
use crate::serve::Limits;
use crate::serve::client::{Login, Term, login};
use std::net::SocketAddr;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};
use tokio::sync::watch;

/// One measurement.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FollowRow {
    pub students: usize,
    pub seconds: f64,
    /// The presenter's key → its own screen, in ms.
    pub presenter_p95_ms: f64,
    /// The presenter's key → a follower's screen, over every key and follower, in ms.
    pub p50_ms: f64,
    pub p95_ms: f64,
    /// The worst follower's own p95, in ms.
    pub worst_p95_ms: f64,
    /// Keys a follower never saw (within 2 s).
    pub lost: usize,
    pub keys: usize,
    /// CPU time of the process (server and clients) over wall time, in cores.
    pub cpu_cores: f64,
    /// Frames the server sent a second (drawn or shared), over the second half.
    pub frames_per_s: f64,
    /// Of them, a follower's taken from another's drawing of the same frame (its own status
    /// line drawn over it).
    pub shared_per_s: f64,
    /// CPU of the process (clients included) per frame sent, in ms.
    pub cpu_ms_per_frame: f64,
    pub bytes_per_s_per_follower: f64,
}

const ANSWER_WAIT: Duration = Duration::from_secs(2);

/// The presenter's presses so far: when each was sent (the `k`th opens the help if `k` is even).
type Presses = watch::Receiver<Vec<Instant>>;

/// A student in, following the class at 80×24; its screen once the class is handed to it.
async fn seated(addr: SocketAddr, k: u8) -> Option<Term> {
    let h = login(addr, "class", Login::Key(&key(k))).await.ok()??;
    let mut t = Term::open(&h, 80, 24).await.ok()?;
    let needle: &[u8] = if k == 3 {
        b"lab frame"
    } else {
        b"following the class"
    };
    t.until(0, needle, Duration::from_secs(60))
        .await
        .then_some(t)
}

/// A follower: for each press of the presenter's, how long after it its screen showed it (2 s
/// when it never did), the bytes it received, and the presses it never saw; until the
/// presenter stops pressing. Each press is timed on its own, from the bytes that came after it
/// was sent to the message that completed its needle: one late screen does not make the next
/// look late (searching only what came after this task got round to a press, a screen that
/// came while it still waited for the last one was missed, and every press after read ~400 ms).
async fn follower(
    addr: SocketAddr,
    ready: Arc<AtomicUsize>,
    mut presses: Presses,
) -> (Vec<Duration>, usize, usize) {
    let Some(t) = seated(addr, 2).await else {
        return (vec![], 0, 1);
    };
    ready.fetch_add(1, Ordering::Relaxed);
    let mut screen = Screen::new(t);
    let (mut lat, mut lost) = (vec![], 0);
    for k in 0.. {
        let sent = loop {
            if let Some(&sent) = presses.borrow_and_update().get(k) {
                break Some(sent);
            }
            // The screen is read while the press is awaited (a client that stops reading
            // holds its frames up).
            tokio::select! {
                changed = presses.changed() => if changed.is_err() { break None },
                open = screen.read(Instant::now() + ANSWER_WAIT) => {
                    if !open && screen.term.closed {
                        break None;
                    }
                }
            }
        };
        let Some(sent) = sent else { break };
        let needle: &[u8] = if k % 2 == 0 { b"help:" } else { b"lab frame" };
        match screen.shown(sent, needle).await {
            Some(when) => lat.push(when.saturating_duration_since(sent)),
            None => {
                lat.push(ANSWER_WAIT);
                lost += 1;
            }
        }
    }
    (lat, screen.dropped + screen.term.seen.len(), lost)
}

/// A follower's screen as it came: its bytes and when each message of them arrived.
struct Screen {
    term: Term,
    /// Each message's end in `term.seen`, and when it came.
    came: std::collections::VecDeque<(usize, Instant)>,
    /// Bytes read and let go (those before the last press).
    dropped: usize,
}

impl Screen {
    fn new(term: Term) -> Screen {
        Screen {
            term,
            came: std::collections::VecDeque::new(),
            dropped: 0,
        }
    }

    /// One message, by `end`, noted with when it came; false when none came.
    async fn read(&mut self, end: Instant) -> bool {
        let got = self.term.next(end.into()).await;
        if got {
            self.came.push_back((self.term.seen.len(), Instant::now()));
        }
        got && !self.term.closed
    }

    /// When the message came that completed `needle` among the bytes that came after `sent`
    /// (None if none did within [`ANSWER_WAIT`] of it); what came before `sent` is let go.
    async fn shown(&mut self, sent: Instant, needle: &[u8]) -> Option<Instant> {
        let before = self.came.iter().take_while(|(_, at)| *at < sent).count();
        if let Some(&(from, _)) = before.checked_sub(1).and_then(|i| self.came.get(i)) {
            self.term.seen.drain(..from);
            self.dropped += from;
            self.came.drain(..before);
            for (end, _) in &mut self.came {
                *end -= from;
            }
        }
        let mut searched = 0;
        loop {
            let seen = &self.term.seen;
            if let Some(i) = seen[searched..]
                .windows(needle.len())
                .position(|w| w == needle)
            {
                let end = searched + i + needle.len();
                return self.came.iter().find(|(e, _)| *e >= end).map(|&(_, at)| at);
            }
            searched = seen.len().saturating_sub(needle.len() - 1);
            if !self.read(sent + ANSWER_WAIT).await {
                return None;
            }
        }
    }
}

/// Runs the measurement with `students` followers for `seconds`.
pub fn run(students: usize, seconds: f64) -> std::io::Result<FollowRow> {
    let server = server(
        true,
        Limits {
            sessions: students + 1,
            per_minute: students * 2 + 10,
            ..Limits::default()
        },
    )?;
    let rt = super::serve::runtime()?;
    let addr = server.addr;
    let (tx, rx) = watch::channel(Vec::new());
    let ready = Arc::new(AtomicUsize::new(0));
    let presenter = rt.block_on(seated(addr, 3));
    let followers: Vec<_> = (0..students)
        .map(|_| rt.spawn(follower(addr, Arc::clone(&ready), rx.clone())))
        .collect();
    drop(rx);
    let end_wait = Instant::now() + Duration::from_secs(60);
    while ready.load(Ordering::Relaxed) < students && Instant::now() < end_wait {
        std::thread::sleep(Duration::from_millis(50));
    }
    let start = Instant::now();
    let end = start + Duration::from_secs_f64(seconds);
    let lead = rt.spawn(async move {
        let Some(mut t) = presenter else {
            return vec![];
        };
        // The followers stop when the presses do (`tx` dropped).
        lead(&mut t, end, tx).await
    });
    std::thread::sleep(Duration::from_secs_f64(seconds / 2.0));
    let counts = &server.shared.counts;
    let frames = || counts.frames.load(Ordering::Relaxed) as f64;
    let shared = || counts.shared.load(Ordering::Relaxed) as f64;
    let (cpu0, t0, f0, s0) = (cpu_s(), Instant::now(), frames(), shared());
    std::thread::sleep(end.saturating_duration_since(Instant::now()));
    let wall = t0.elapsed().as_secs_f64().max(1e-9);
    let (cpu, drawn, taken) = (cpu_s() - cpu0, frames() - f0, shared() - s0);
    let mut own = rt.block_on(lead).unwrap_or_default();
    let results: Vec<_> = rt.block_on(async {
        let mut out = vec![];
        for t in followers {
            out.extend(t.await.ok());
        }
        out
    });
    drop(rt);
    server.stop("bench done");
    own.sort();
    let super::serve::Clients { all, worst, bytes } = super::serve::Clients::of(&results);
    Ok(FollowRow {
        students,
        seconds,
        presenter_p95_ms: pct(&own, 0.95),
        p50_ms: pct(&all, 0.5),
        p95_ms: pct(&all, 0.95),
        worst_p95_ms: worst,
        lost: results.iter().map(|r| r.2).sum::<usize>() + students.saturating_sub(results.len()),
        keys: all.len(),
        cpu_cores: cpu / wall,
        frames_per_s: drawn / wall,
        shared_per_s: taken / wall,
        cpu_ms_per_frame: cpu * 1e3 / drawn.max(1.0),
        bytes_per_s_per_follower: bytes as f64 / seconds / students.max(1) as f64,
    })
}

/// The presenter presses `?` every 200 ms until `until` (help on, help off), each press told
/// to the followers as it is sent; its own key → screen times.
async fn lead(t: &mut Term, until: Instant, presses: watch::Sender<Vec<Instant>>) -> Vec<Duration> {
    let mut own = vec![];
    let mut next = Instant::now();
    while Instant::now() < until {
        t.seen.clear();
        let sent = Instant::now();
        presses.send_modify(|p| p.push(sent));
        if t.send(b"?").await.is_err() {
            break;
        }
        let needle: &[u8] = if presses.borrow().len() % 2 == 1 {
            b"help:"
        } else {
            b"lab frame"
        };
        own.push(if t.until(0, needle, ANSWER_WAIT).await {
            sent.elapsed()
        } else {
            ANSWER_WAIT
        });
        next += Duration::from_millis(200);
        let now = Instant::now();
        if next > now {
            t.until(t.seen.len(), b"\x00never", next - now).await;
        }
    }
    own
}

/// A row as the bench prints it.
pub fn line(r: &FollowRow) -> String {
    format!(
        "serve {:>3} followers {:>4.0} s: presenter's key→follower's screen p50 {:>6.1} ms p95 {:>6.1} ms (worst follower p95 {:>6.1} ms, {} of {} unseen in 2 s), presenter's own p95 {:>6.1} ms, CPU {:.2} cores ({:.0} frames/s, {:.0} of them shared, {:.2} ms a frame), {:.0} B/s/follower",
        r.students,
        r.seconds,
        r.p50_ms,
        r.p95_ms,
        r.worst_p95_ms,
        r.lost,
        r.keys,
        r.presenter_p95_ms,
        r.cpu_cores,
        r.frames_per_s,
        r.shared_per_s,
        r.cpu_ms_per_frame,
        r.bytes_per_s_per_follower,
    )
}
