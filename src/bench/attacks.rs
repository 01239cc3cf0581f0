//! `turntable bench --serve N --attacks`: a class (a presenter and N students, each student
//! stepped out to explore on its own, everyone pressing `?` every 200 ms) and beside it, one at
//! a time for the same seconds, each flood of issue 43 by one client: a follower's F2 (step
//! out, rejoin) as fast as the link takes it, a flood of keys, a window-change storm, and the
//! door held (200 silent TCP connections from 20 addresses, 50 logged in without a shell from 5
//! more). For each: what the attacker did, the presenter's and the students' key → screen p95
//! meanwhile, the CPU and the peak resident memory it adds to the class alone's (the clients
//! are in this process: the attacker's own client counts too, so the server's share is at most
//! that), and how long a login from an address of its own takes to its first screen, halfway
//! through.

use super::cpu_s;
use super::serve::{key, pct, press, rss_mb};
use crate::serve::Limits;
use crate::serve::client::{Login, Term, Trust, login};
use std::net::SocketAddr;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// One attack beside the class (or the class alone).
#[derive(Clone, Debug, serde::Serialize)]
pub struct AttackRow {
    pub attack: &'static str,
    pub students: usize,
    pub seconds: f64,
    /// What the attacker did in that time.
    pub did: String,
    pub presenter_p95_ms: f64,
    pub students_p95_ms: f64,
    /// Keys (presenter's and students') never answered within 2 s.
    pub lost: usize,
    pub keys: usize,
    /// CPU of the process, in cores (for an attack: over the class alone's).
    pub cpu_cores: f64,
    /// Peak resident memory of the process, in MB (for an attack: over the class alone's).
    pub rss_mb: f64,
    /// A login from an address of its own to its first screen, in ms (NaN: never).
    pub login_ms: f64,
}

#[derive(Clone, Copy, Debug)]
enum Attack {
    None,
    F2,
    Keys,
    Resize,
    Door,
}

const ATTACKS: [Attack; 5] = [
    Attack::None,
    Attack::F2,
    Attack::Keys,
    Attack::Resize,
    Attack::Door,
];

impl Attack {
    fn name(self) -> &'static str {
        match self {
            Attack::None => "class alone",
            Attack::F2 => "a follower's F2 flood",
            Attack::Keys => "a student's key flood",
            Attack::Resize => "a window-change storm",
            Attack::Door => "200 silent + 50 idle",
        }
    }

    /// Attacks until `until`, counting what it did in `done`.
    async fn run(self, addr: SocketAddr, until: Instant, done: Arc<AtomicUsize>) {
        match self {
            Attack::None => tokio::time::sleep_until(until.into()).await,
            Attack::F2 => flood(addr, until, &done, &"\x1bOQ".repeat(64)).await,
            Attack::Keys => flood(addr, until, &done, &"?".repeat(4096)).await,
            Attack::Resize => storm(addr, until, &done).await,
            Attack::Door => door(addr, until, &done).await,
        }
    }

    fn did(self, n: usize) -> String {
        match self {
            Attack::None => String::new(),
            Attack::F2 => format!("{n} F2 presses"),
            Attack::Keys => format!("{n} keys"),
            Attack::Resize => format!("{n} window changes"),
            Attack::Door => format!("{n} of 250 held"),
        }
    }
}

/// A client in as a student (following the presenter), its screen open.
async fn seated(addr: SocketAddr) -> Option<Term> {
    let h = login(addr, "attacker", Login::Key(&key(2))).await.ok()??;
    let mut t = Term::open(&h, 80, 24).await.ok()?;
    t.until(0, b"lab frame", Duration::from_secs(30))
        .await
        .then_some(t)
}

/// Sends `chunk` over and over, reading what comes back between writes.
async fn flood(addr: SocketAddr, until: Instant, done: &AtomicUsize, chunk: &str) {
    let Some(mut t) = seated(addr).await else {
        return;
    };
    let keys = if chunk.starts_with('\x1b') {
        chunk.len() / 3
    } else {
        chunk.len()
    };
    while Instant::now() < until {
        let sent = tokio::time::timeout_at(until.into(), t.send(chunk.as_bytes())).await;
        if !matches!(sent, Ok(Ok(()))) {
            break;
        }
        done.fetch_add(keys, Ordering::Relaxed);
        t.seen.clear();
        t.until(0, b"\x00never", Duration::from_millis(1)).await;
    }
}

async fn storm(addr: SocketAddr, until: Instant, done: &AtomicUsize) {
    let Some(mut t) = seated(addr).await else {
        return;
    };
    let mut i = 0u32;
    while Instant::now() < until {
        for _ in 0..100 {
            if t.channel
                .window_change(60 + i % 40, 20 + i % 10, 0, 0)
                .await
                .is_err()
            {
                return;
            }
            i += 1;
        }
        done.fetch_add(100, Ordering::Relaxed);
        t.seen.clear();
        t.until(0, b"\x00never", Duration::from_millis(1)).await;
    }
}

/// 200 silent connections from 127.0.3.1–20, 50 logged in without a shell from 127.0.4.1–5,
/// held until `until`; `done` counts those still open at the end.
async fn door(addr: SocketAddr, until: Instant, done: &AtomicUsize) {
    let mut silent = vec![];
    for i in 0..200u8 {
        if let Ok(tcp) = connect_from([127, 0, 3, 1 + i / 10], addr).await {
            silent.push(tcp);
        }
    }
    let mut idle = vec![];
    for i in 0..50u8 {
        let Ok(tcp) = connect_from([127, 0, 4, 1 + i / 10], addr).await else {
            continue;
        };
        let config = Arc::new(russh::client::Config::default());
        let Ok(mut h) = russh::client::connect_stream(config, tcp, Trust).await else {
            continue;
        };
        let k = russh::keys::PrivateKeyWithHashAlg::new(Arc::new(key(2)), None);
        if h.authenticate_publickey("idle", k)
            .await
            .is_ok_and(|r| r.success())
        {
            idle.push(h);
        }
    }
    tokio::time::sleep_until(until.into()).await;
    let open = silent.len() + idle.iter().filter(|h| !h.is_closed()).count();
    done.store(open, Ordering::Relaxed);
}

async fn connect_from(ip: [u8; 4], addr: SocketAddr) -> std::io::Result<tokio::net::TcpStream> {
    let socket = tokio::net::TcpSocket::new_v4()?;
    socket.bind((ip, 0).into())?;
    socket.connect(addr).await
}

/// A login from 127.0.9.1, to its first screen, in ms (NaN if it never came): a student's
/// key, not to take the class over (the door knows no one before they log in, and a
/// presenter's login passes it as a student's does).
async fn newcomer(addr: SocketAddr) -> f64 {
    let t0 = Instant::now();
    let Ok(tcp) = connect_from([127, 0, 9, 1], addr).await else {
        return f64::NAN;
    };
    let config = Arc::new(russh::client::Config::default());
    let Ok(mut h) = russh::client::connect_stream(config, tcp, Trust).await else {
        return f64::NAN;
    };
    let k = russh::keys::PrivateKeyWithHashAlg::new(Arc::new(key(2)), None);
    if !h
        .authenticate_publickey("newcomer", k)
        .await
        .is_ok_and(|r| r.success())
    {
        return f64::NAN;
    }
    let Ok(mut t) = Term::open(&h, 80, 24).await else {
        return f64::NAN;
    };
    if !t.until(0, b"lab frame", Duration::from_secs(10)).await {
        return f64::NAN;
    }
    t0.elapsed().as_secs_f64() * 1e3
}

/// A class member pressing `?` until `until`: the presenter, or a student stepped out.
async fn member(
    addr: SocketAddr,
    presenter: bool,
    until: Instant,
    ready: Arc<AtomicUsize>,
) -> Vec<(Instant, Duration)> {
    let k = key(if presenter { 3 } else { 2 });
    let Ok(Some(h)) = login(addr, "class", Login::Key(&k)).await else {
        return vec![];
    };
    let Ok(mut t) = Term::open(&h, 80, 24).await else {
        return vec![];
    };
    if !t.until(0, b"lab frame", Duration::from_secs(30)).await {
        return vec![];
    }
    if !presenter {
        // Following the class (once handed it): F2 steps out, to explore on its own.
        let at = t.seen.len();
        if !t.until(0, b"F2 step out", Duration::from_secs(30)).await
            || t.send(b"\x1bOQ").await.is_err()
            || !t.until(at, b"F2 rejoin", Duration::from_secs(30)).await
        {
            return vec![];
        }
    }
    ready.fetch_add(1, Ordering::Relaxed);
    press(&mut t, until).await.0
}

/// The class of `students` and the presenter, and each attack beside it for `seconds`.
pub fn run(students: usize, seconds: f64) -> std::io::Result<Vec<AttackRow>> {
    let server = super::serve::server(
        true,
        Limits {
            sessions: students + 8,
            per_minute: students * 2 + 20,
            ..Limits::default()
        },
    )?;
    let rt = super::serve::runtime()?;
    let addr = server.addr;
    let phase = Duration::from_secs_f64(seconds);
    let settle = Duration::from_secs(2);
    let end = Instant::now() + Duration::from_secs(40) + (phase + settle) * ATTACKS.len() as u32;
    let ready = Arc::new(AtomicUsize::new(0));
    let presenter = rt.spawn(member(addr, true, end, Arc::clone(&ready)));
    wait(|| ready.load(Ordering::Relaxed) >= 1);
    let class: Vec<_> = (0..students)
        .map(|_| rt.spawn(member(addr, false, end, Arc::clone(&ready))))
        .collect();
    wait(|| ready.load(Ordering::Relaxed) > students);
    std::thread::sleep(settle);
    let mut windows = vec![];
    for attack in ATTACKS {
        let done = Arc::new(AtomicUsize::new(0));
        let (t0, cpu0) = (Instant::now(), cpu_s());
        let attacker = rt.spawn(attack.run(addr, t0 + phase, Arc::clone(&done)));
        let login = rt.spawn(async move {
            tokio::time::sleep(phase / 2).await;
            newcomer(addr).await
        });
        let mut peak = rss_mb();
        while t0.elapsed() < phase {
            std::thread::sleep(Duration::from_millis(100));
            peak = peak.max(rss_mb());
        }
        let cores = (cpu_s() - cpu0) / t0.elapsed().as_secs_f64();
        let login_ms = rt.block_on(login).unwrap_or(f64::NAN);
        let _ = rt.block_on(attacker);
        windows.push((
            attack,
            t0,
            done.load(Ordering::Relaxed),
            cores,
            peak,
            login_ms,
        ));
        std::thread::sleep(settle);
    }
    let presenter = rt.block_on(presenter).unwrap_or_default();
    let class: Vec<_> = class
        .into_iter()
        .flat_map(|t| rt.block_on(t).unwrap_or_default())
        .collect();
    drop(rt);
    server.stop("bench done");
    let (base_cores, base_rss) = (windows[0].3, windows[0].4);
    Ok(windows
        .into_iter()
        .map(|(attack, t0, n, cores, peak, login_ms)| {
            let within = |v: &[(Instant, Duration)]| {
                let mut d: Vec<Duration> = v
                    .iter()
                    .filter(|(at, _)| *at >= t0 && *at < t0 + phase)
                    .map(|&(_, l)| l)
                    .collect();
                d.sort();
                d
            };
            let (p, s) = (within(&presenter), within(&class));
            let alone = matches!(attack, Attack::None);
            AttackRow {
                attack: attack.name(),
                students,
                seconds,
                did: attack.did(n),
                presenter_p95_ms: pct(&p, 0.95),
                students_p95_ms: pct(&s, 0.95),
                lost: p.iter().chain(&s).filter(|&&l| l >= ANSWER_WAIT).count(),
                keys: p.len() + s.len(),
                cpu_cores: if alone { cores } else { cores - base_cores },
                rss_mb: if alone { peak } else { peak - base_rss },
                login_ms,
            }
        })
        .collect())
}

const ANSWER_WAIT: Duration = Duration::from_secs(2);

/// Waits (30 s at most) for `done`.
fn wait(done: impl Fn() -> bool) {
    let end = Instant::now() + Duration::from_secs(30);
    while !done() && Instant::now() < end {
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A row as the bench prints it, with the goals where they apply: the attacker adds at
/// most 64 MB, a student's key is answered within 100 ms at p95, a login gets in within 2 s.
pub fn line(r: &AttackRow) -> String {
    let alone = r.attack == ATTACKS[0].name();
    let (of, cost) = if alone {
        (
            format!("{} students + presenter", r.students),
            format!("CPU {:.2} cores, RSS {:.1} MB", r.cpu_cores, r.rss_mb),
        )
    } else {
        (
            r.did.clone(),
            format!(
                "CPU {:+.2} cores, RSS {:+.1} MB{}",
                r.cpu_cores,
                r.rss_mb,
                goal(r.rss_mb <= 64.0, "≤ 64")
            ),
        )
    };
    format!(
        "serve attack {:<22} ({of}): presenter p95 {:>6.1} ms, students p95 {:>6.1} ms{}, {} of {} keys unanswered, {cost}, login in {:.0} ms{}",
        r.attack,
        r.presenter_p95_ms,
        r.students_p95_ms,
        goal(r.students_p95_ms <= 100.0, "≤ 100"),
        r.lost,
        r.keys,
        r.login_ms,
        goal(r.login_ms <= 2000.0, "≤ 2000"),
    )
}

fn goal(met: bool, bound: &str) -> String {
    format!(" ({bound}: {})", if met { "met" } else { "MISSED" })
}
