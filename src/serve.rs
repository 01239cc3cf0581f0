//! `turntable serve`: the explorer over SSH, for a class. Each connection that gets in (an
//! authorized key, or the passphrase) and asks for a shell gets its own explorer
//! ([`explorer`]), on the same [`Session`](crate::session::Session) the terminal and replay
//! use, drawn at the client's size into the channel; nothing else is served (no command, no
//! SFTP, no forwarding: `conn`). A presenter leads: followers apply the presenter's keys,
//! mouse actions and ticks, not its frames. Guests write no file on the server. Limits bound what any
//! client can cost: sessions, connections per address per minute, idle time, terminal size,
//! a stalled reader, the handshake's time, and the analysis work (on as many threads at once
//! as there are cores).

mod auth;
pub mod client;
pub mod conn;
pub mod explorer;
pub mod keys;
mod out;
mod screen;

pub use auth::{authorized_keys, fingerprint, host_key, host_key_path, passphrase};

use crate::app::lesson::Tally;
use crate::app::{Action, App, Chord};
use russh::keys::{PrivateKey, PublicKey};
use std::collections::{HashMap, VecDeque};
use std::net::{IpAddr, SocketAddr};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::Sender;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// What bounds a client's cost (each has a flag; see `turntable serve --help`).
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
    /// A client that takes no bytes this long (its window and the socket full) is closed.
    pub stall: Duration,
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
            stall: Duration::from_secs(60),
        }
    }
}

/// Who gets in, and as what.
#[derive(Clone, Debug)]
pub struct Options {
    pub listen: SocketAddr,
    pub host_key: PrivateKey,
    /// Keys that get in as guests.
    pub keys: Vec<PublicKey>,
    /// The class's passphrase (any user name).
    pub passphrase: Option<String>,
    /// Keys that get in as the presenter.
    pub presenter_keys: Vec<PublicKey>,
    /// The presenter's passphrase.
    pub presenter_passphrase: Option<String>,
    pub limits: Limits,
    /// A lesson each presenter's session runs from its start (`--lesson`), and so the class.
    pub lesson: Option<Lesson>,
}

/// A lesson for the class: the scene it opens on and its script at the first step.
#[derive(Clone, Debug)]
pub struct Lesson {
    pub scene: crate::scene::Scene,
    pub driver: crate::lesson::Driver,
}

/// To a session's thread: from its connection, its writer, or the class.
pub enum In {
    Data(conn::Queued),
    Resize(u16, u16),
    /// The channel took the last frame (a copy): its buffer comes back, to be drawn into
    /// again and freed on the session's own thread. glibc gives a thread's arena back to the
    /// system only above its last chunk in use, and a buffer another thread frees waits in
    /// that thread's cache, in use: 30 sessions left 16 MB behind them so, 9 MB without.
    Sent(Vec<u8>),
    /// End, saying why.
    Close(String),
    /// The presenter's key or tick (applied while following).
    Lead(Lead),
    /// (To the presenter.) This session asks to follow: send it the class.
    Join(u64),
    /// (To a follower.) The class as it is now, its lesson's place included; what it is sent
    /// next applies to this.
    Class(Box<App>, Option<crate::lesson::Driver>),
    /// (To a follower.) The presenter left.
    Unled,
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

/// The class: who presents, who follows, and their answers to the presenter's question.
#[derive(Default)]
struct Class {
    presenter: Option<u64>,
    followers: Vec<u64>,
    poll: Poll,
}

/// The followers' own answers to the question on the presenter's screen.
#[derive(Default)]
struct Poll {
    /// Which question (the presenter's count of questions asked).
    question: u32,
    /// Whether it still takes answers: until the presenter answers it and goes on.
    open: bool,
    /// By session; the first answer stands. A follower who leaves or steps out is not
    /// counted while out (its answer is kept, should it rejoin before the question closes).
    answers: HashMap<u64, bool>,
}

/// What every connection and session shares.
pub struct Shared {
    pub limits: Limits,
    options: Options,
    config: Arc<russh::server::Config>,
    sessions: Mutex<HashMap<u64, Sender<In>>>,
    class: Mutex<Class>,
    next: AtomicU64,
    connections: AtomicUsize,
    /// Input bytes received and not yet taken by their session (all sessions).
    queued: AtomicUsize,
    pub gate: Gate,
    stopping: AtomicBool,
}

impl Shared {
    /// A new session's number and inbox, or None when the server is full.
    fn enter(&self, tx: Sender<In>, presenter: bool) -> Option<u64> {
        let mut sessions = lock(&self.sessions);
        if sessions.len() >= self.limits.sessions || self.stopping.load(Ordering::Relaxed) {
            return None;
        }
        let id = self.next.fetch_add(1, Ordering::Relaxed);
        sessions.insert(id, tx);
        // The class's lock is taken before the sessions' everywhere: never inside it.
        drop(sessions);
        if presenter {
            let mut class = lock(&self.class);
            class.presenter = Some(id);
            class.poll = Poll::default();
            // A presenter who takes over (the teacher back after a dropped connection) is
            // sent the followers: each is handed this class, not left applying its keys and
            // lesson steps to the last one's.
            for &f in &class.followers {
                self.send(id, In::Join(f));
            }
        }
        Some(id)
    }

    fn leave(&self, id: u64) {
        lock(&self.sessions).remove(&id);
        let mut class = lock(&self.class);
        if class.presenter == Some(id) {
            class.presenter = None;
            class.poll = Poll::default();
            // Followers go on from where the class was, on their own clocks.
            for f in std::mem::take(&mut class.followers) {
                self.send(f, In::Unled);
            }
        }
        class.followers.retain(|&f| f != id);
    }

    fn send(&self, id: u64, msg: In) {
        if let Some(tx) = lock(&self.sessions).get(&id) {
            let _ = tx.send(msg);
        }
    }

    /// Whether `id` presents.
    fn presents(&self, id: u64) -> bool {
        lock(&self.class).presenter == Some(id)
    }

    /// Whether a presenter other than `id` leads a class.
    fn class_led(&self, id: u64) -> bool {
        lock(&self.class).presenter.is_some_and(|p| p != id)
    }

    /// `id` asks to follow: the presenter sends it the class (see [`Shared::welcome`]).
    fn join(&self, id: u64) {
        let presenter = lock(&self.class).presenter;
        if let Some(p) = presenter {
            self.send(p, In::Join(id));
        }
    }

    /// (The presenter's thread.) `follower` gets the class as it is, and from now on what
    /// the presenter does: one lock, so nothing falls between.
    fn welcome(&self, follower: u64, app: &App, lesson: Option<&crate::lesson::Driver>) {
        let mut class = lock(&self.class);
        if !class.followers.contains(&follower) {
            class.followers.push(follower);
        }
        self.send(follower, In::Class(Box::new(app.clone()), lesson.cloned()));
    }

    /// (The presenter's thread.) Its question on screen now (the `asked`th, taking answers
    /// while `open`): the followers' answers to it so far; None when `id` does not present.
    /// A new question starts a new tally.
    fn tally(&self, id: u64, asked: u32, open: bool) -> Option<Tally> {
        let mut class = lock(&self.class);
        if class.presenter != Some(id) {
            return None;
        }
        let class = &mut *class;
        if class.poll.question != asked {
            class.poll = Poll {
                question: asked,
                ..Poll::default()
            };
        }
        class.poll.open = open;
        let mut t = Tally::default();
        for f in &class.followers {
            match class.poll.answers.get(f) {
                Some(true) => t.yes += 1,
                Some(false) => t.no += 1,
                None => t.not_yet += 1,
            }
        }
        Some(t)
    }

    /// (A follower's thread.) Its own answer to the `asked`th question: counted if that is
    /// the presenter's question, still open, and `id` follows; whether it was.
    fn answer(&self, id: u64, asked: u32, yes: bool) -> bool {
        let mut class = lock(&self.class);
        let p = &class.poll;
        if !(p.open && p.question == asked && class.followers.contains(&id)) {
            return false;
        }
        class.poll.answers.entry(id).or_insert(yes);
        if let Some(presenter) = class.presenter {
            self.send(presenter, In::Answered);
        }
        true
    }

    /// `id`'s answer to the `asked`th question, if it gave one in class.
    fn answered(&self, id: u64, asked: u32) -> Option<bool> {
        let class = lock(&self.class);
        let p = &class.poll;
        (p.question == asked).then(|| p.answers.get(&id).copied())?
    }

    fn unfollow(&self, id: u64) {
        lock(&self.class).followers.retain(|&f| f != id);
    }

    /// (A session's thread.) If `id` presents, its followers do `lead` too.
    fn lead(&self, id: u64, lead: Lead) {
        let class = lock(&self.class);
        if class.presenter != Some(id) {
            return;
        }
        let sessions = lock(&self.sessions);
        for f in &class.followers {
            if let Some(tx) = sessions.get(f) {
                let _ = tx.send(In::Lead(lead));
            }
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
    let shared = Arc::new(Shared {
        limits: options.limits,
        options,
        config,
        sessions: Mutex::default(),
        class: Mutex::default(),
        next: AtomicU64::new(1),
        connections: AtomicUsize::new(0),
        queued: AtomicUsize::new(0),
        gate: Gate::new(cores),
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
            std::thread::sleep(Duration::from_millis(20));
        }
        // The last bytes a moment to leave.
        std::thread::sleep(Duration::from_millis(200));
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
        let l = shared.limits;
        // Handshakes cost too: a few more connections than sessions, no more.
        if !recent.admit(peer.ip(), l.per_minute, Instant::now())
            || shared.connections.load(Ordering::Relaxed) >= l.sessions + 16
        {
            drop(tcp);
            continue;
        }
        shared.connections.fetch_add(1, Ordering::Relaxed);
        let shared = Arc::clone(&shared);
        tokio::spawn(async move {
            conn::serve(tcp, Arc::clone(&shared)).await;
            shared.connections.fetch_sub(1, Ordering::Relaxed);
        });
    }
}
