//! Plain mode over `serve`: a student who logs in as `plain` (or sends `TURNTABLE_PLAIN=1`)
//! reads the class in lines, as `turntable --plain` says them: no escape sequence, each line
//! ended by CR LF, following the presenter's lesson and answering its question in words.

use super::serve_class::{WAIT, key, rt, server};
use russh::client::Handle;
use turntable::serve::client::{Login, Term, Trust, login};

async fn student(addr: std::net::SocketAddr, user: &str) -> Handle<Trust> {
    login(addr, user, Login::Password("ba-ke-di-lo"))
        .await
        .unwrap()
        .unwrap()
}

/// Waits for each of `lines`, in order, from where the last was found.
async fn says(t: &mut Term, from: &mut usize, lines: &[&str]) {
    for line in lines {
        assert!(
            t.until(*from, line.as_bytes(), WAIT).await,
            "never said {line:?}:\n{}",
            String::from_utf8_lossy(&t.seen[*from..])
        );
        let at = t.seen[*from..]
            .windows(line.len())
            .position(|w| w == line.as_bytes())
            .unwrap();
        *from += at + line.len();
    }
}

/// Lines only: no escape sequence, and every line ends with CR LF.
fn only_lines(bytes: &[u8]) {
    let text = String::from_utf8(bytes.to_vec()).unwrap();
    assert!(!text.contains('\x1b'), "an escape sequence:\n{text:?}");
    assert!(
        text.split('\n').rev().skip(1).all(|l| l.ends_with('\r')),
        "a bare LF:\n{text:?}"
    );
}

/// A student in plain mode who came first: told it waits, then follows the presenter's
/// lesson in lines, answers the question for itself with y, and hears the verdict on its own
/// answer; the presenter's Enter ends the lesson for it too.
#[test]
fn a_plain_student_follows_the_lesson_and_answers_in_words() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    rt().block_on(async {
        let f = student(s.addr, "plain").await;
        let mut tf = Term::open(&f, 80, 24).await.unwrap();
        let mut at = 0;
        says(
            &mut tf,
            &mut at,
            &[
                "turntable, plain mode",
                "in a class: F2",
                "no presenter yet",
            ],
        )
        .await;
        let p = login(s.addr, "teacher", Login::Key(&key(3)))
            .await
            .unwrap()
            .unwrap();
        let tp = Term::open(&p, 80, 24).await.unwrap();
        says(
            &mut tf,
            &mut at,
            &[
                "the presenter is here: you follow the class",
                "First: at rest",
                "the presenter goes on",
            ],
        )
        .await;
        tp.send(b"\r").await.unwrap();
        says(&mut tf, &mut at, &["Second: at rest"]).await;
        tp.send(b"\r").await.unwrap();
        says(
            &mut tf,
            &mut at,
            &["Will it escape?", "answer y if it escapes, n if it stays"],
        )
        .await;
        tf.send(b"y").await.unwrap();
        says(
            &mut tf,
            &mut at,
            &["You said it escapes.", "answered; the presenter goes on"],
        )
        .await;
        tp.send(b"y").await.unwrap();
        // Enter once the lesson holds again (its `tick 10` over): before, it is the page's.
        says(
            &mut tf,
            &mut at,
            &["Right: it escapes", "the presenter goes on"],
        )
        .await;
        tp.send(b"\r").await.unwrap();
        says(&mut tf, &mut at, &["The end.", "end of the lesson\r\n"]).await;
        tf.send(b"q").await.unwrap();
        assert!(tf.until_closed(WAIT).await);
        only_lines(&tf.seen);
    });
    s.stop("done");
}

/// `TURNTABLE_PLAIN=1` sent by the client (`ssh -o SetEnv=TURNTABLE_PLAIN=1`) is plain mode
/// under any user name; the explorer's screen otherwise.
#[test]
fn the_environment_asks_for_plain_mode_too() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    rt().block_on(async {
        for (value, plain) in [("1", true), ("0", false)] {
            let f = student(s.addr, "class").await;
            let channel = f.channel_open_session().await.unwrap();
            channel
                .set_env(true, "TURNTABLE_PLAIN", value)
                .await
                .unwrap();
            channel
                .request_pty(true, "xterm-256color", 80, 24, 0, 0, &[])
                .await
                .unwrap();
            channel.request_shell(true).await.unwrap();
            let mut t = Term::on(channel);
            assert!(t.until(0, "no presenter yet".as_bytes(), WAIT).await);
            t.send(b"q").await.unwrap();
            assert!(t.until_closed(WAIT).await);
            assert_eq!(t.seen.contains(&0x1b), !plain, "TURNTABLE_PLAIN={value}");
            if plain {
                only_lines(&t.seen);
                assert!(String::from_utf8_lossy(&t.seen).contains("turntable, plain mode"));
            }
        }
    });
    s.stop("done");
}
