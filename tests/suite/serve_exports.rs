//! `serve --exports DIR` (issue 44 item 7): the presenter's `E` writes the page there as SVG,
//! under the files' policy (never over a file) and within `serve::EXPORTS`; a student's `E`
//! never writes, alone or following. Driven by the in-process SSH client.

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
        limits: Limits::default(),
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
        // A key, then a resize: the next frame redraws every cell, so the notice's words
        // arrive whole.
        async fn said(t: &mut Term, key: &[u8], words: &[u8], w: u32) -> bool {
            let at = t.seen.len();
            t.send(key).await.unwrap();
            // The key's frame first (a notice that differs from the last by a digit
            // arrives as that digit alone).
            tokio::time::sleep(Duration::from_millis(300)).await;
            t.channel.window_change(w, 30, 0, 0).await.unwrap();
            t.until(at, words, SECS).await
        }
        // The presenter's E writes the page there, whole.
        assert!(said(&mut tp, b"E", b"wrote this page to", 150).await);
        assert_eq!(pages(dir.path()), ["turntable-table-1.svg"]);
        let svg = std::fs::read_to_string(dir.path().join("turntable-table-1.svg")).unwrap();
        assert!(svg.trim_end().ends_with("</svg>"), "{}", &svg[..200]);
        // Never over a file: one in the way is passed by.
        std::fs::write(dir.path().join("turntable-table-2.svg"), "mine").unwrap();
        assert!(said(&mut tp, b"E", b"turntable-table-3.svg", 160).await);
        let mine = std::fs::read_to_string(dir.path().join("turntable-table-2.svg")).unwrap();
        assert_eq!(mine, "mine");
        // The follower, given the presenter's E, wrote nothing of its own: three files; and
        // it is told nothing (it was told `not exported`, of an E it never pressed).
        assert_eq!(pages(dir.path()).len(), 3);
        ts.channel.window_change(150, 30, 0, 0).await.unwrap();
        assert!(ts.until(0, b"following", SECS).await);
        assert!(!ts.until(0, b"not exported", Duration::from_secs(2)).await);
        // Stepped out, the student's own E writes nothing.
        assert!(said(&mut ts, b"\x1bOQ", b"stepped", 150).await);
        assert!(said(&mut ts, b"E", b"not exported", 160).await);
        assert_eq!(pages(dir.path()).len(), 3);
        // Bounded: at the most pages allowed, E says so and writes nothing.
        for k in 3..EXPORTS.files {
            std::fs::write(dir.path().join(format!("turntable-x-{k}.svg")), "").unwrap();
        }
        assert_eq!(pages(dir.path()).len(), EXPORTS.files);
        assert!(said(&mut tp, b"E", b"the most allowed", 150).await);
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
