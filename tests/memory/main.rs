//! `turntable serve`'s memory when a class leaves: every byte its sessions and connections
//! held is given back, round after round, faulty clients included (one killed mid-frame, one
//! that never reads, a flood of keys, a hostile and a silent handshake). Counted by the
//! allocator itself, so this binary is a process of its own: no other test allocates here
//! (its tests take turns). And one follower's flood of F2 (step out, rejoin) holds a bounded
//! number of bytes.

use russh::keys::PrivateKey;
use russh::keys::ssh_key::private::Ed25519Keypair;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicIsize, Ordering};
use std::time::Duration;
use turntable::serve::client::{Login, Term, eventually, frozen_login, login};
use turntable::serve::{Limits, Options, Running, start};

/// The system's allocator, counting the bytes held: the server's, and the clients' apart.
struct Counting;

static HELD: AtomicIsize = AtomicIsize::new(0);
/// The most the server has held since it was last reset.
static PEAK: AtomicIsize = AtomicIsize::new(0);
static CLIENTS_HELD: AtomicIsize = AtomicIsize::new(0);

thread_local! {
    /// The clients' thread: what it holds is counted apart (the server's is what is tested).
    static CLIENTS: Cell<bool> = const { Cell::new(false) };
}

fn count() -> &'static AtomicIsize {
    if CLIENTS.try_with(Cell::get).unwrap_or(false) {
        &CLIENTS_HELD
    } else {
        &HELD
    }
}

// SAFETY: each call is the system allocator's own, with the same arguments.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            add(layout.size() as isize);
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            add(layout.size() as isize);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        count().fetch_sub(layout.size() as isize, Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, size) };
        if !p.is_null() {
            add(size as isize - layout.size() as isize);
        }
        p
    }
}

fn add(n: isize) {
    let counter = count();
    let now = counter.fetch_add(n, Ordering::Relaxed) + n;
    if std::ptr::eq(counter, &HELD) {
        PEAK.fetch_max(now, Ordering::Relaxed);
    }
}

/// The tests take turns: each counts the server's bytes alone.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

#[global_allocator]
static COUNTING: Counting = Counting;

fn held() -> isize {
    HELD.load(Ordering::Relaxed)
}

const SECS: Duration = Duration::from_secs(20);
/// Students in a class, besides the presenter and the faulty clients.
const STUDENTS: usize = 16;
/// What may stay after a class: a few maps' and queues' capacity grown to a class's size
/// (measured: under 2 KB). Below what a class holds (8 MB or more), so that a leak of a third
/// of what every session holds adds up past it within the three rounds.
const SLACK: isize = 8 * 1024 * 1024;

/// Begins every frame the server sends (crossterm's BeginSynchronizedUpdate).
const FRAME: &[u8] = b"\x1b[?2026h";

/// Sends `keys` and waits for a frame sent after them (what came before passed over): the
/// class goes at the server's pace, not a clock's.
async fn press(t: &mut Term, keys: &[&str]) {
    while !t.closed && t.next(tokio::time::Instant::now()).await {}
    let at = t.seen.len();
    for k in keys {
        t.send(k.as_bytes()).await.unwrap();
    }
    assert!(t.until(at, FRAME, SECS).await, "no frame came");
}

fn key(n: u8) -> PrivateKey {
    PrivateKey::from(Ed25519Keypair::from_seed(&[n; 32]))
}

fn server() -> Running {
    start(Options {
        listen: "127.0.0.1:0".parse().unwrap(),
        host_key: key(1),
        keys: vec![key(2).public_key().clone().into()],
        passphrase: None,
        presenter_keys: vec![key(3).public_key().clone().into()],
        presenter_passphrase: None,
        limits: Limits {
            // The frozen client is closed this long after its socket fills: each class waits
            // for it at its end (1 s made the four classes 5.2 s, 3.0 s of it this wait).
            stall: Duration::from_millis(300),
            handshake: Duration::from_secs(1),
            per_minute: 1000,
            ..Limits::default()
        },
        lesson: None,
        exports: None,
    })
    .unwrap()
}

/// One class: a presenter who plays and turns the pages, students who follow, some who step
/// out and explore, and the faulty clients; then everyone leaves.
async fn class(s: &Running) -> isize {
    use std::io::Write;
    let p = login(s.addr, "teacher", Login::Key(&key(3)))
        .await
        .unwrap()
        .unwrap();
    let mut tp = Term::open(&p, 100, 30).await.unwrap();
    assert!(tp.until(0, b"lab frame", SECS).await);
    let mut students = vec![];
    for i in 0..STUDENTS {
        let h = login(s.addr, "student", Login::Key(&key(2)))
            .await
            .unwrap()
            .unwrap();
        let mut t = Term::open(&h, 80, 24).await.unwrap();
        assert!(t.until(0, b"lab frame", SECS).await, "student {i}");
        students.push((h, t));
    }
    // The faulty: a connection that stops reading, one that floods, garbage and silence.
    let (frozen, stop) = frozen_login(s.addr, "student", &key(2), 16 * 1024)
        .await
        .unwrap()
        .unwrap();
    let mut tf = Term::open(&frozen, 200, 60).await.unwrap();
    assert!(tf.until(0, b"lab frame", SECS).await);
    stop.store(true, Ordering::Relaxed);
    let mut garbage = std::net::TcpStream::connect(s.addr).unwrap();
    garbage.write_all(&[0xff; 4096]).unwrap();
    let silent = std::net::TcpStream::connect(s.addr).unwrap();
    let (flood_h, flood) = students.pop().unwrap();
    for _ in 0..16 {
        flood.send("ä".repeat(16 * 1024).as_bytes()).await.unwrap();
    }
    // The presenter plays, compares with the paper's RK2, pins, and turns the pages.
    for k in [" ", "c", "e", "b", "%", "\t", "\t", " "] {
        press(&mut tp, &[k]).await;
    }
    // A third step out and explore on their own (the spin-up, a map).
    for (_, t) in students.iter_mut().step_by(3) {
        press(t, &["\x1bOQ", "7", " ", "x", "\t"]).await;
    }
    let in_class = held();
    // One is killed mid-frame; the rest quit; the frozen one is closed for stalling.
    let (killed_h, killed) = students.pop().unwrap();
    drop((killed, killed_h, flood, flood_h, garbage, silent));
    for (_, t) in &mut students {
        t.send(b"q").await.unwrap();
        assert!(t.until_closed(SECS).await);
    }
    tp.send(b"q").await.unwrap();
    assert!(tp.until_closed(SECS).await);
    drop((students, tp, p));
    assert!(
        eventually(SECS, || s.shared.sessions() == 0).await,
        "{} sessions still open",
        s.shared.sessions()
    );
    drop((tf, frozen));
    in_class
}

#[test]
fn a_class_that_leaves_gives_back_every_byte_it_held() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let s = server();
    CLIENTS.with(|c| c.set(true));
    let rt = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    rt.block_on(async {
        // The first class makes what lives as long as the server (lazy statics, the
        // runtime's wheels and queues): the baseline is after it, once its connections,
        // sessions and tasks are gone (3 s at most, as long as a fixed wait used to be).
        let tasks = s.tasks();
        class(&s).await;
        let gone = || s.shared.connections() == 0 && s.shared.sessions() == 0 && s.tasks() == tasks;
        eventually(Duration::from_secs(3), gone).await;
        let (base, tasks) = (held(), s.tasks());
        for round in 1..=3 {
            let in_class = class(&s).await;
            // The last connections close, and each session's thread gives back its last
            // frame's buffer, within a second or so.
            let gone = || s.shared.connections() == 0 && s.tasks() == tasks;
            eventually(Duration::from_secs(10), || gone() && held() - base <= SLACK).await;
            let after = held();
            eprintln!("round {round}: {base} B before, {in_class} B in class, {after} B after");
            assert!(
                in_class > base + 4_000_000,
                "a class held only {} B",
                in_class - base
            );
            assert_eq!(s.shared.connections(), 0, "round {round}: connections open");
            assert_eq!(s.tasks(), tasks, "round {round}: tasks left running");
            assert!(
                after - base <= SLACK,
                "round {round} left {} B behind (baseline {base} B)",
                after - base
            );
        }
    });
    s.stop("done");
}

/// A follower pressing F2 (step out, rejoin) ten thousand times (30 KB of input): the class's
/// state handed to it waits in one place, the latest, never queued. Before, each rejoin queued a
/// copy of the presenter's whole state: 10,000 presses held ~170 MB, a continuous flood GBs.
#[test]
fn a_followers_f2_flood_holds_a_bounded_number_of_bytes() {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let s = server();
    CLIENTS.with(|c| c.set(true));
    let rt = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    rt.block_on(async {
        let p = login(s.addr, "teacher", Login::Key(&key(3)))
            .await
            .unwrap()
            .unwrap();
        let mut tp = Term::open(&p, 100, 30).await.unwrap();
        assert!(tp.until(0, b"lab frame", SECS).await);
        // A presenter's state worth copying: a run played, compared and pinned.
        for k in [" ", "c", "b", "b"] {
            press(&mut tp, &[k]).await;
        }
        let f = login(s.addr, "student", Login::Key(&key(2)))
            .await
            .unwrap()
            .unwrap();
        let mut tf = Term::open(&f, 80, 24).await.unwrap();
        assert!(tf.until(0, b"following", SECS).await);
        let before = held();
        PEAK.store(before, Ordering::Relaxed);
        for _ in 0..100 {
            tf.send("\x1bOQ".repeat(100).as_bytes()).await.unwrap();
        }
        // The presses taken and answered: a `q` after them, which a follower may press whether
        // it follows or not, ends its session once they are (in place of a 5 s wait).
        let mut tf = tf;
        tf.send(b"q").await.unwrap();
        assert!(tf.until_closed(SECS).await);
        assert!(eventually(SECS, || s.shared.sessions() == 1).await);
        let peak = PEAK.load(Ordering::Relaxed) - before;
        eprintln!("10,000 F2s: the server held at most {peak} B more than before");
        assert!(
            peak < 16 * 1024 * 1024,
            "10,000 F2s held {} MB",
            peak / 1024 / 1024
        );
        assert!(s.shared.handed() <= 1);
    });
    s.stop("done");
}
