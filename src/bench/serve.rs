//! `turntable bench --serve N`: `turntable serve` on 127.0.0.1 and N SSH clients in this
//! process (`serve::client`) at 80×24, each playing and pressing `?` (help on, help off)
//! every 200 ms: the time from a key to the screen that shows it, per client; the process's
//! CPU; its memory per session (clients included: an upper bound on the server's); the bytes
//! each client receives a second; and the memory before, with them, once they have all left,
//! and once a second and a third round of as many have come and gone (the server up
//! throughout, as a class's is): what the first left behind is not held per session if the
//! rounds after it add nothing.

use super::cpu_s;
use crate::serve::client::{Login, Term, login};
use crate::serve::{Limits, Options};
use russh::keys::PrivateKey;
use russh::keys::ssh_key::private::Ed25519Keypair;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

/// One measurement.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Row {
    pub clients: usize,
    pub seconds: f64,
    /// Key → screen over every key of every client, in ms.
    pub p50_ms: f64,
    pub p95_ms: f64,
    /// The worst client's own p95, in ms.
    pub worst_p95_ms: f64,
    /// Keys whose screen never came (within 2 s; counted as 2 s above).
    pub lost: usize,
    pub keys: usize,
    /// CPU time of the process (server and clients) over wall time, in cores.
    pub cpu_cores: f64,
    /// Frames the server drew a second, over the second half.
    pub frames_per_s: f64,
    /// CPU of the process (clients included) per frame drawn, in ms: the cost of a frame as
    /// the load of the machine changes it least.
    pub cpu_ms_per_frame: f64,
    /// Resident memory added per session while all are open (clients included), in MB.
    pub rss_per_session_mb: f64,
    pub bytes_per_s_per_client: f64,
    pub rss_before_mb: f64,
    /// Midway, every session open.
    pub rss_with_mb: f64,
    /// Once they have all left (the server still up).
    pub rss_after_mb: f64,
    /// Once a second round of as many clients has come (pressing keys for up to 5 s) and gone.
    pub rss_second_mb: f64,
    /// And a third.
    pub rss_third_mb: f64,
}

const PRESS_EVERY: Duration = Duration::from_millis(200);
const ANSWER_WAIT: Duration = Duration::from_secs(2);

/// Resident memory, in MB (Linux's /proc; 0 elsewhere).
pub(super) fn rss_mb() -> f64 {
    let pages: f64 = std::fs::read_to_string("/proc/self/statm")
        .ok()
        .and_then(|s| s.split_whitespace().nth(1)?.parse().ok())
        .unwrap_or(0.0);
    pages * 4096.0 / 1e6
}

pub(super) fn key(seed: u8) -> PrivateKey {
    PrivateKey::from(Ed25519Keypair::from_seed(&[seed; 32]))
}

/// One client: logs in, then presses `?` every 200 ms for `seconds`; its latencies and the
/// bytes it received.
async fn client(addr: std::net::SocketAddr, until: Instant) -> (Vec<Duration>, usize, usize) {
    let Ok(Some(h)) = login(addr, "bench", Login::Key(&key(2))).await else {
        return (vec![], 0, 1);
    };
    let Ok(mut t) = Term::open(&h, 80, 24).await else {
        return (vec![], 0, 1);
    };
    if !t.until(0, b"lab frame", Duration::from_secs(30)).await {
        return (vec![], 0, 1);
    }
    let (lat, bytes, lost) = press(&mut t, until).await;
    (lat.into_iter().map(|(_, l)| l).collect(), bytes, lost)
}

/// Presses `?` on `t` every 200 ms until `until` (help on, help off): when each was sent and
/// how long its screen took (2 s when it never came), the bytes received, and the keys never
/// answered.
pub(super) async fn press(
    t: &mut Term,
    until: Instant,
) -> (Vec<(Instant, Duration)>, usize, usize) {
    let (mut lat, mut bytes, mut lost, mut help) = (vec![], 0, 0, false);
    let mut next = Instant::now();
    while Instant::now() < until {
        bytes += t.seen.len();
        t.seen.clear();
        let sent = Instant::now();
        if t.send(b"?").await.is_err() {
            break;
        }
        help = !help;
        let needle: &[u8] = if help { b"help:" } else { b"lab frame" };
        if t.until(0, needle, ANSWER_WAIT).await {
            lat.push((sent, sent.elapsed()));
        } else {
            lat.push((sent, ANSWER_WAIT));
            lost += 1;
        }
        next += PRESS_EVERY;
        let now = Instant::now();
        if next > now {
            // Read (and count) what comes meanwhile.
            t.until(t.seen.len(), b"\x00never", next - now).await;
        }
    }
    bytes += t.seen.len();
    (lat, bytes, lost)
}

/// What the clients measured, together: every latency (sorted), the worst client's p95 and
/// the bytes they read.
pub(super) struct Clients {
    pub all: Vec<Duration>,
    pub worst: f64,
    pub bytes: usize,
}

impl Clients {
    /// Of each client's latencies, bytes read and keys unanswered.
    pub fn of(results: &[(Vec<Duration>, usize, usize)]) -> Self {
        let mut all: Vec<Duration> = results.iter().flat_map(|r| r.0.clone()).collect();
        all.sort();
        let worst = results
            .iter()
            .map(|r| {
                let mut v = r.0.clone();
                v.sort();
                pct(&v, 0.95)
            })
            .fold(0.0, f64::max);
        let bytes = results.iter().map(|r| r.1).sum();
        Clients { all, worst, bytes }
    }
}

pub(super) fn pct(sorted: &[Duration], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let i = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[i].as_secs_f64() * 1e3
}

/// The clients' runtime: two threads, as many as the machine the goals are set on.
pub(super) fn runtime() -> std::io::Result<tokio::runtime::Runtime> {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
}

/// Runs the measurement with `clients` clients for `seconds`.
pub fn run(clients: usize, seconds: f64) -> std::io::Result<Row> {
    let rss_before = rss_mb();
    let server = server(
        false,
        Limits {
            sessions: clients + 1,
            per_minute: clients * 2 + 10,
            ..Limits::default()
        },
    )?;
    let rt = runtime()?;
    let addr = server.addr;
    let start = Instant::now();
    let until = start + Duration::from_secs_f64(seconds);
    let tasks: Vec<_> = (0..clients)
        .map(|_| rt.spawn(client(addr, until)))
        .collect();
    // Midway, with every session open: memory and CPU so far.
    std::thread::sleep(Duration::from_secs_f64(seconds / 2.0));
    let rss_during = rss_mb();
    let frames = || server.shared.counts.frames.load(Ordering::Relaxed) as f64;
    let (cpu0, t0, f0) = (cpu_s(), Instant::now(), frames());
    std::thread::sleep(until.saturating_duration_since(Instant::now()));
    let wall = t0.elapsed().as_secs_f64().max(1e-9);
    let (cpu, drawn) = (cpu_s() - cpu0, frames() - f0);
    let cpu_cores = cpu / wall;
    let results: Vec<_> = rt.block_on(async {
        let mut out = vec![];
        for t in tasks {
            out.extend(t.await.ok());
        }
        out
    });
    let rss_after = left(&server);
    // Two more rounds: as many again, in, pressing keys for up to 5 s, and out.
    let mut again = [0.0; 2];
    for rss in &mut again {
        let until = Instant::now() + Duration::from_secs_f64(seconds.min(5.0));
        let round: Vec<_> = (0..clients)
            .map(|_| rt.spawn(client(addr, until)))
            .collect();
        rt.block_on(async {
            for t in round {
                let _ = t.await;
            }
        });
        *rss = left(&server);
    }
    drop(rt);
    server.stop("bench done");
    let Clients { all, worst, bytes } = Clients::of(&results);
    Ok(Row {
        clients,
        seconds,
        p50_ms: pct(&all, 0.5),
        p95_ms: pct(&all, 0.95),
        worst_p95_ms: worst,
        lost: results.iter().map(|r| r.2).sum(),
        keys: all.len(),
        cpu_cores,
        frames_per_s: drawn / wall,
        cpu_ms_per_frame: cpu * 1e3 / drawn.max(1.0),
        rss_per_session_mb: (rss_during - rss_before) / clients.max(1) as f64,
        bytes_per_s_per_client: bytes as f64 / seconds / clients.max(1) as f64,
        rss_before_mb: rss_before,
        rss_with_mb: rss_during,
        rss_after_mb: rss_after,
        rss_second_mb: again[0],
        rss_third_mb: again[1],
    })
}

/// The memory once every session has left (within 10 s), the server still up.
fn left(server: &crate::serve::Running) -> f64 {
    let end = Instant::now() + Duration::from_secs(10);
    while server.shared.sessions() > 0 && Instant::now() < end {
        std::thread::sleep(Duration::from_millis(50));
    }
    // The sessions' threads a moment to end.
    std::thread::sleep(Duration::from_millis(300));
    rss_mb()
}

/// A row as the bench prints it: its speed, then its memory.
pub fn line(r: &Row) -> String {
    format!(
        "serve {:>3} clients {:>4.0} s: key→screen p50 {:>6.1} ms p95 {:>6.1} ms (worst client p95 {:>6.1} ms, {} of {} keys unanswered in 2 s), CPU {:.2} cores ({:.0} frames/s, {:.2} ms a frame), RSS {:.2} MB/session, {:.0} B/s/client\nserve {:>3} clients memory: RSS {:.0} MB before, {:.0} MB with them, {:.0} MB after they left, {:.0} MB after a second round, {:.0} MB after a third",
        r.clients,
        r.seconds,
        r.p50_ms,
        r.p95_ms,
        r.worst_p95_ms,
        r.lost,
        r.keys,
        r.cpu_cores,
        r.frames_per_s,
        r.cpu_ms_per_frame,
        r.rss_per_session_mb,
        r.bytes_per_s_per_client,
        r.clients,
        r.rss_before_mb,
        r.rss_with_mb,
        r.rss_after_mb,
        r.rss_second_mb,
        r.rss_third_mb
    )
}

/// The bench's server on 127.0.0.1 (a free port): its host key, the students' key and, if
/// asked, a presenter's, within `limits`.
pub(super) fn server(presenter: bool, limits: Limits) -> std::io::Result<crate::serve::Running> {
    crate::serve::start(Options {
        listen: std::net::SocketAddr::from(([127, 0, 0, 1], 0)),
        host_key: key(1),
        keys: vec![key(2).public_key().clone().into()],
        passphrase: None,
        presenter_keys: if presenter {
            vec![key(3).public_key().clone().into()]
        } else {
            vec![]
        },
        presenter_passphrase: None,
        lesson: None,
        exports: None,
        limits,
    })
}
