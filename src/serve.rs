//! `turntable serve`: the explorer over SSH, for a class. Each connection that gets in (an
//! authorized key, or the passphrase) and asks for a shell gets its own explorer
//! ([`explorer`]), on the same [`Explorer`](crate::session::Explorer) the terminal and replay
//! use, drawn at the client's size into the channel; nothing else is served (no command, no
//! SFTP, no forwarding: `conn`). A presenter leads: followers apply the presenter's keys,
//! mouse actions and ticks, not its frames. Guests write no file on the server. Limits bound what any
//! client can cost: sessions, connections per address per minute, connections not logged in
//! (per address and in all, apart from the class: `door`), the time to log in and then to ask
//! for a shell, idle time, terminal size, a stalled reader, and the analysis work (on as many
//! threads at once as there are cores).

mod auth;
mod class;
pub mod client;
pub mod conn;
mod door;
pub mod explorer;
mod frames;
mod keyfile;
mod out;
mod pace;
mod screen;
pub mod testing;

pub use auth::{fingerprint, host_key, host_key_path, passphrase};
pub use keyfile::{Authorized, authorized_keys};

use crate::app::{Action, Chord};
use russh::keys::PrivateKey;
use std::collections::{HashMap, VecDeque};
use std::net::{IpAddr, SocketAddr};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::Sender;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// What bounds a client's cost (each but `stall` and `refusal` has a flag; see
/// `turntable serve --help`).
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Explorers open at once.
    pub sessions: usize,
    /// New connections from one address in a minute.
    pub per_minute: usize,
    /// A session with no input this long, and not following the class, is closed.
    pub idle: Duration,
    /// The largest terminal drawn (a larger window is drawn at this size).
    pub max_cols: u16,
    pub max_rows: u16,
    /// A connection not in (authenticated) by then is closed.
    pub handshake: Duration,
    /// A connection in without an explorer this long (it asked for no shell, or its explorer
    /// ended) is closed.
    pub shell_grace: Duration,
    /// Connections not in at once, in all (None: 100, or the class's size and 16 more if
    /// larger) and from one address (None: the class's size and 16 more), apart from the
    /// class's: a class behind one address (a school's NAT), all typing the passphrase at
    /// once, is never turned away.
    pub waiting: Option<usize>,
    pub waiting_per_address: Option<usize>,
    /// A client that takes no bytes this long (its window and the socket full) is closed.
    pub stall: Duration,
    /// A refused login (a wrong passphrase or key) is answered this late: what slows a
    /// guesser down, beside `per_minute`.
    pub refusal: Duration,
    /// At [`Running::stop`], once the sessions have ended, their last bytes (the message
    /// saying why) are given this long to leave before the connections are dropped.
    pub linger: Duration,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            sessions: 64,
            per_minute: 30,
            idle: Duration::from_secs(30 * 60),
            max_cols: 400,
            max_rows: 150,
            handshake: Duration::from_secs(30),
            shell_grace: Duration::from_secs(20),
            waiting: None,
            waiting_per_address: None,
            stall: Duration::from_secs(60),
            refusal: Duration::from_secs(1),
            linger: Duration::from_millis(200),
        }
    }
}

/// Who gets in, and as what.
#[derive(Clone, Debug)]
pub struct Options {
    pub listen: SocketAddr,
    pub host_key: PrivateKey,
    /// Keys that get in as guests (from where and until when their options say).
    pub keys: Vec<Authorized>,
    /// The class's passphrase (any user name).
    pub passphrase: Option<String>,
    /// Keys that get in as the presenter.
    pub presenter_keys: Vec<Authorized>,
    /// The presenter's passphrase.
    pub presenter_passphrase: Option<String>,
    pub limits: Limits,
    /// A lesson each presenter's session runs from its start (`--lesson`), and so the class.
    pub lesson: Option<Lesson>,
    /// Where the presenter's `E` writes its pages (`--exports`), within [`EXPORTS`]; without
    /// it, and for every student, nothing is written on the server.
    pub exports: Option<std::path::PathBuf>,
}

/// What the presenter's `E` may write in `--exports`: pages in all, and their bytes.
pub const EXPORTS: crate::session::ExportBound = crate::session::ExportBound {
    files: 200,
    bytes: 256 << 20,
};

/// A lesson for the class: the scene it opens on and its script at the first step.
#[derive(Clone, Debug)]
pub struct Lesson {
    pub scene: crate::scene::Scene,
    pub driver: crate::lesson::Driver,
}

/// To a session's thread: from its connection, its writer, or the class.
pub enum In {
    Data(conn::Queued),
    /// The client's window changed (its latest size waits in `screen::Window`).
    Resize,
    /// The channel took the last frame (a copy): its buffer comes back, to be drawn into
    /// again and freed on the session's own thread. glibc gives a thread's arena back to the
    /// system only above its last chunk in use, and a buffer another thread frees waits in
    /// that thread's cache, in use: 30 sessions left 16 MB behind them so, 9 MB without.
    Sent(Vec<u8>),
    /// End, saying why.
    Close(String),
    /// The presenter's key or tick (applied while following), and its place in the class.
    Lead(Lead, class::Place),
    /// (To the presenter.) This session asks to follow: send it the class.
    Join(u64),
    /// (To a follower.) The class as it is now, its lesson's place included, is waiting to be
    /// taken (`Shared::take_class`); what it is sent next applies to that.
    Class,
    /// (To a follower.) The presenter left.
    Unled,
    /// (To a presenter still in, the class taken by another: the teacher back while the dropped
    /// connection lingers, or their second window.) Hand the class over to it.
    HandOver,
    /// (To a presenter who took the class from one still in.) The class it handed over is
    /// waiting (`Shared::take_up_class`), or nothing is, should it have ended first.
    TakeUp,
    /// (To the presenter.) A follower answered its question: the tally changed.
    Answered,
}

/// What the presenter's session did, for the followers to do alike: the same keys, mouse
/// actions, ticks and lesson steps, in the same order, give the same state.
#[derive(Clone, Copy, Debug)]
pub enum Lead {
    Key(Chord),
    /// What its mouse did, in the model's terms (a cell means another place on another size).
    Act(Action),
    Tick,
    /// Its lesson took the steps that were due (a follower's lesson, at the same place, takes
    /// the same ones: it never moves on its own while following).
    Lesson,
}

/// From a session's thread to its channel.
pub enum Out {
    Frame(Vec<u8>),
    /// The last bytes; then the channel closes.
    End(Vec<u8>),
}

/// At most `n` at once: the analysis and drawing work of all sessions shares the cores.
pub struct Gate {
    busy: Mutex<usize>,
    free: Condvar,
    n: usize,
}

impl Gate {
    fn new(n: usize) -> Gate {
        Gate {
            busy: Mutex::new(0),
            free: Condvar::new(),
            n: n.max(1),
        }
    }

    pub fn run<T>(&self, work: impl FnOnce() -> T) -> T {
        let mut busy = lock(&self.busy);
        while *busy >= self.n {
            busy = self.free.wait(busy).unwrap_or_else(|e| e.into_inner());
        }
        *busy += 1;
        drop(busy);
        let out = work();
        *lock(&self.busy) -= 1;
        self.free.notify_one();
        out
    }
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// Work done by all sessions, counted: what a client made the server do.
#[derive(Default)]
pub struct Counts {
    /// Frames drawn (all of them, or all but a follower's status line: see `shared`).
    pub frames: AtomicU64,
    /// Of them, a follower's taken from another's drawing of the same frame, its own line
    /// drawn over it.
    pub shared: AtomicU64,
    /// Sizes applied to a session (each lays its screen out again).
    pub layouts: AtomicU64,
}

/// What every connection and session shares.
pub struct Shared {
    pub limits: Limits,
    options: Options,
    config: Arc<russh::server::Config>,
    sessions: Mutex<HashMap<u64, Sender<In>>>,
    class: Mutex<class::Class>,
    next: AtomicU64,
    connections: AtomicUsize,
    /// Input bytes received and not yet taken by their session (all sessions).
    queued: AtomicUsize,
    door: Arc<door::Door>,
    pub counts: Counts,
    pub gate: Gate,
    /// What a frame costs: how often a picture that only time moves is drawn.
    pub pace: pace::Pace,
    /// The class's frames, drawn once for all its followers of one size.
    pub frames: frames::Frames,
    stopping: AtomicBool,
}

impl Shared {
    /// A new session's number and inbox, or None when the server is full: the class at
    /// `sessions`, with two places beyond it for the presenter (two: the teacher back while
    /// the dropped connection lingers).
    fn enter(&self, tx: Sender<In>, presenter: bool) -> Option<u64> {
        let mut sessions = lock(&self.sessions);
        let room = self.limits.sessions + if presenter { 2 } else { 0 };
        if sessions.len() >= room || self.stopping.load(Ordering::Relaxed) {
            return None;
        }
        let id = self.next.fetch_add(1, Ordering::Relaxed);
        sessions.insert(id, tx);
        // The class's lock is taken before the sessions' everywhere: never inside it.
        drop(sessions);
        if presenter {
            let mut class = lock(&self.class);
            let before = class.presenter.replace(id);
            class.poll = class::Poll::default();
            let waiting = std::mem::take(&mut class.waiting);
            class.joining.extend(waiting);
            match before {
                // The teacher back while the dropped connection lingers (the server has not
                // seen it go): that session hands its class over, lesson and all, and the
                // class is called once it is taken up (`In::TakeUp`).
                Some(old) => {
                    class.handing = Some((old, id));
                    self.send(old, In::HandOver);
                }
                None => self.call_class(&class, id),
            }
        }
        Some(id)
    }

    fn leave(&self, id: u64) {
        let empty = {
            let mut sessions = lock(&self.sessions);
            sessions.remove(&id);
            sessions.is_empty()
        };
        let mut class = lock(&self.class);
        if empty {
            // Nobody left to take the class up for: it gives back what it held.
            class.left = None;
            self.frames.forget(None);
        }
        // Gone before it handed its class over: the new presenter is not kept waiting.
        if let Some((_, new)) = class.handing.take_if(|(old, _)| *old == id) {
            self.send(new, In::TakeUp);
        }
        if class.presenter == Some(id) {
            self.frames.forget(Some(id));
            class.presenter = None;
            class.poll = class::Poll::default();
            // Followers go on from where the class was, on their own clocks, and follow
            // again when a presenter comes back; those asking to follow wait alike.
            let joining = std::mem::take(&mut class.joining);
            for f in std::mem::take(&mut class.followers)
                .into_iter()
                .chain(joining)
            {
                class.waiting.push(f);
                self.send(f, In::Unled);
            }
        }
        class.followers.retain(|&f| f != id);
        class.joining.retain(|&f| f != id);
        class.waiting.retain(|&f| f != id);
        class.handed.remove(&id);
    }

    fn send(&self, id: u64, msg: In) {
        if let Some(tx) = lock(&self.sessions).get(&id) {
            let _ = tx.send(msg);
        }
    }

    /// Sessions open now.
    pub fn sessions(&self) -> usize {
        lock(&self.sessions).len()
    }

    /// Connections open now, in or not.
    pub fn connections(&self) -> usize {
        self.connections.load(Ordering::Relaxed)
    }
}

/// A server running on its own threads.
pub struct Running {
    pub addr: SocketAddr,
    pub shared: Arc<Shared>,
    runtime: Option<tokio::runtime::Runtime>,
}

/// Starts serving on `options.listen` (port 0: any free port; see [`Running::addr`]).
pub fn start(options: Options) -> std::io::Result<Running> {
    let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(cores.min(4))
        .enable_io()
        .enable_time()
        .thread_name("turntable-serve")
        .build()?;
    let listener = std::net::TcpListener::bind(options.listen)?;
    listener.set_nonblocking(true)?;
    let addr = listener.local_addr()?;
    let config = Arc::new(conn::config(&options));
    let l = options.limits;
    let door = Arc::new(door::Door::new(door::Bounds {
        waiting: l.waiting.unwrap_or((l.sessions + 16).max(100)),
        per_address: l.waiting_per_address.unwrap_or(l.sessions + 16),
        idle: l.sessions + 16,
    }));
    let shared = Arc::new(Shared {
        limits: options.limits,
        options,
        config,
        sessions: Mutex::default(),
        class: Mutex::default(),
        next: AtomicU64::new(1),
        connections: AtomicUsize::new(0),
        queued: AtomicUsize::new(0),
        door,
        counts: Counts::default(),
        gate: Gate::new(cores),
        pace: pace::Pace::new(cores),
        frames: frames::Frames::default(),
        stopping: AtomicBool::new(false),
    });
    let listener = {
        let _guard = runtime.enter();
        tokio::net::TcpListener::from_std(listener)?
    };
    runtime.spawn(accept(listener, Arc::clone(&shared)));
    Ok(Running {
        addr,
        shared,
        runtime: Some(runtime),
    })
}

impl Running {
    /// Tasks alive on the server's runtime: the accept loop's, and each connection's.
    pub fn tasks(&self) -> usize {
        self.runtime
            .as_ref()
            .map_or(0, |r| r.metrics().num_alive_tasks())
    }

    /// Closes every session, saying `why` to each, waits (a few seconds at most) for them to
    /// go, and stops.
    pub fn stop(mut self, why: &str) {
        self.shared.stopping.store(true, Ordering::Relaxed);
        let ids: Vec<u64> = lock(&self.shared.sessions).keys().copied().collect();
        for id in ids {
            self.shared.send(id, In::Close(why.to_string()));
        }
        let until = Instant::now() + Duration::from_secs(3);
        while self.shared.sessions() > 0 && Instant::now() < until {
            std::thread::sleep(Duration::from_millis(5));
        }
        // The last bytes a moment to leave.
        std::thread::sleep(self.shared.limits.linger);
        if let Some(rt) = self.runtime.take() {
            rt.shutdown_timeout(Duration::from_secs(1));
        }
    }
}

/// Who came in within the last minute, by address.
#[derive(Default)]
struct Recent(HashMap<IpAddr, VecDeque<Instant>>);

impl Recent {
    fn admit(&mut self, ip: IpAddr, per_minute: usize, now: Instant) -> bool {
        let minute = Duration::from_secs(60);
        self.0
            .retain(|_, v| v.back().is_some_and(|&t| now - t < minute));
        let v = self.0.entry(ip).or_default();
        while v.front().is_some_and(|&t| now - t >= minute) {
            v.pop_front();
        }
        if v.len() >= per_minute {
            return false;
        }
        v.push_back(now);
        true
    }
}

async fn accept(listener: tokio::net::TcpListener, shared: Arc<Shared>) {
    let mut recent = Recent::default();
    loop {
        let (tcp, peer) = match listener.accept().await {
            Ok(x) => x,
            Err(_) => {
                // Out of descriptors, or the like: wait, rather than spin.
                tokio::time::sleep(Duration::from_millis(100)).await;
                continue;
            }
        };
        // Handshakes cost too: bounded at the door, apart from the class's sessions.
        if !recent.admit(peer.ip(), shared.limits.per_minute, Instant::now()) {
            continue;
        }
        let Some(pass) = shared.door.arrive(peer.ip()) else {
            continue;
        };
        shared.connections.fetch_add(1, Ordering::Relaxed);
        let shared = Arc::clone(&shared);
        tokio::spawn(async move {
            conn::serve(tcp, Arc::clone(&shared), pass).await;
            shared.connections.fetch_sub(1, Ordering::Relaxed);
        });
    }
}
