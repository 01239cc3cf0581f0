//! `serve --exports DIR` (issue 44 item 7): the presenter's `E` writes the page there as SVG,
//! under the files' policy (never over a file) and within `serve::EXPORTS`; a student's `E`
//! never writes, alone or following. Driven by the in-process SSH client; screens read
//! through the class tests' terminal model (`serve_class::screen`).

use russh::keys::PrivateKey;
use russh::keys::ssh_key::private::Ed25519Keypair;
use std::path::Path;
use std::time::Duration;
use turntable::serve::client::{Login, Term, login};
use turntable::serve::{EXPORTS, Limits, Options, Running, start};

const SECS: Duration = Duration::from_secs(10);

fn key(n: u8) -> PrivateKey {
    PrivateKey::from(Ed25519Keypair::from_seed(&[n; 32]))
}

fn server(exports: &Path) -> Running {
    start(Options {
        listen: "127.0.0.1:0".parse().unwrap(),
        host_key: key(1),
        keys: vec![key(2).public_key().clone().into()],
        passphrase: None,
        presenter_keys: vec![key(3).public_key().clone().into()],
        presenter_passphrase: None,
        // Nothing is read after the stop: no linger for the last bytes.
        limits: Limits {
            linger: Duration::ZERO,
            ..Limits::default()
        },
        lesson: None,
        exports: Some(exports.to_path_buf()),
    })
    .unwrap()
}

/// The exported pages in `dir`, sorted.
fn pages(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Whether the 160 × 30 screen shows `words` (on one row) within `SECS`.
async fn shows(t: &mut Term, words: &str) -> bool {
    let end = tokio::time::Instant::now() + SECS;
    loop {
        if super::serve_class::screen(&t.seen, 160, 30)
            .iter()
            .any(|row| row.contains(words))
        {
            return true;
        }
        if t.closed || !t.next(end).await {
            return false;
        }
    }
}

#[test]
fn the_presenters_e_writes_to_the_exports_and_a_students_never() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    let rt = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    rt.block_on(async {
        let p = login(s.addr, "teacher", Login::Key(&key(3)))
            .await
            .unwrap()
            .unwrap();
        let mut tp = Term::open(&p, 160, 30).await.unwrap();
        assert!(tp.until(0, b"lab frame", SECS).await);
        let st = login(s.addr, "student", Login::Key(&key(2)))
            .await
            .unwrap()
            .unwrap();
        let mut ts = Term::open(&st, 160, 30).await.unwrap();
        assert!(ts.until(0, b"following", SECS).await);
        // A key, then its notice on the screen (read whole: a notice that differs from the
        // last by a digit arrives as that digit alone).
        async fn said(t: &mut Term, key: &[u8], words: &str) -> bool {
            t.send(key).await.unwrap();
            shows(t, words).await
        }
        // The presenter's E writes the page there, whole.
        assert!(said(&mut tp, b"E", "wrote this page to").await);
        assert_eq!(pages(dir.path()), ["turntable-table-1.svg"]);
        let svg = std::fs::read_to_string(dir.path().join("turntable-table-1.svg")).unwrap();
        assert!(svg.trim_end().ends_with("</svg>"), "{}", &svg[..200]);
        // Never over a file: one in the way is passed by.
        std::fs::write(dir.path().join("turntable-table-2.svg"), "mine").unwrap();
        assert!(said(&mut tp, b"E", "turntable-table-3.svg").await);
        let mine = std::fs::read_to_string(dir.path().join("turntable-table-2.svg")).unwrap();
        assert_eq!(mine, "mine");
        // The follower, given the presenter's E, wrote nothing of its own: three files; and
        // it is told nothing (it was told `not exported`, of an E it never pressed).
        assert_eq!(pages(dir.path()).len(), 3);
        // The presenter's next key (the rotating frame) reaches the follower after its Es:
        // once it shows, the Es were taken, and no frame of the follower's said a word.
        let at = ts.seen.len();
        tp.send(b"f").await.unwrap();
        assert!(ts.until(at, b"rotating", SECS).await);
        assert!(!String::from_utf8_lossy(&ts.seen).contains("not exported"));
        // Stepped out, the student's own E writes nothing.
        assert!(said(&mut ts, b"\x1bOQ", "stepped").await);
        assert!(said(&mut ts, b"E", "not exported").await);
        assert_eq!(pages(dir.path()).len(), 3);
        // Bounded: at the most pages allowed, E says so and writes nothing.
        for k in 3..EXPORTS.files {
            std::fs::write(dir.path().join(format!("turntable-x-{k}.svg")), "").unwrap();
        }
        assert_eq!(pages(dir.path()).len(), EXPORTS.files);
        assert!(said(&mut tp, b"E", "the most allowed").await);
        assert_eq!(pages(dir.path()).len(), EXPORTS.files);
    });
    s.stop("done");
}

/// `--exports` must name a directory: anything else is refused at start (exit 2).
#[test]
fn exports_must_be_a_directory() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("f");
    std::fs::write(&file, "").unwrap();
    for bad in [file, dir.path().join("missing")] {
        let (code, _, err) = super::common::turntable(&[
            "serve",
            "--host-key",
            dir.path().join("hk").to_str().unwrap(),
            "--exports",
            bad.to_str().unwrap(),
        ]);
        assert_eq!(code, 2, "{err}");
        assert!(
            err.contains("--exports") && err.contains("not a directory"),
            "{err}"
        );
    }
}
