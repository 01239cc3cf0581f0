//! A class's lesson over `turntable serve --lesson`, driven by in-process SSH clients: the
//! presenter's lesson reaches every follower in step (captions, scenes, pauses, questions), the
//! followers' own answers are tallied on the presenter's screen, and a follower's answer moves
//! nobody else. Screens are read through a small terminal model of what the clients receive;
//! every wait polls for a condition, with room to spare on a loaded machine.

use russh::client::Handle;
use russh::keys::PrivateKey;
use russh::keys::ssh_key::private::Ed25519Keypair;
use std::time::Duration;
use turntable::app::testing::Testing as _;
use turntable::serve::client::{Login, Term, Trust, login};
use turntable::serve::{Limits, Options, Running, start};

pub(super) const WAIT: Duration = Duration::from_secs(30);

/// The class's lesson: two scenes, each held for Enter, then a question.
const LESSON: &str = "# a class's lesson, for the tests
6
pause
X*20
say First: at rest on the table at xi0 = 0.9.
wait
6
pause
say Second: at rest at xi0 = 1.1, outside R_max.
wait
ask Will it escape? (y/n)
play
tick 10
wait
say The end.
";

pub(super) fn key(n: u8) -> PrivateKey {
    PrivateKey::from(Ed25519Keypair::from_seed(&[n; 32]))
}

pub(super) fn server(dir: &std::path::Path) -> Running {
    let path = dir.join("class.keys");
    std::fs::write(&path, LESSON).unwrap();
    let lesson = turntable::cli::lesson::for_class(path.to_str().unwrap()).unwrap();
    serving(Some(lesson))
}

fn serving(lesson: Option<turntable::serve::Lesson>) -> Running {
    start(Options {
        listen: "127.0.0.1:0".parse().unwrap(),
        host_key: key(1),
        keys: vec![],
        passphrase: Some("ba-ke-di-lo".into()),
        presenter_keys: vec![key(3).public_key().clone().into()],
        presenter_passphrase: None,
        // Nothing is read after the stop: no linger for the last bytes.
        limits: Limits {
            linger: Duration::ZERO,
            ..Limits::default()
        },
        lesson,
        exports: None,
    })
    .unwrap()
}

pub(super) fn rt() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap()
}

/// What a terminal of `w` × `h` shows after `bytes`, as rows: the cursor moves, clears and
/// text that ratatui's crossterm backend writes (styles and modes are passed over).
pub(super) fn screen(bytes: &[u8], w: usize, h: usize) -> Vec<String> {
    let text = String::from_utf8_lossy(bytes);
    let mut grid = vec![vec![' '; w]; h];
    let (mut r, mut c) = (0usize, 0usize);
    let mut it = text.chars();
    while let Some(ch) = it.next() {
        match ch {
            '\x1b' => {
                if it.next() != Some('[') {
                    continue;
                }
                let mut params = String::new();
                let mut last = None;
                for x in it.by_ref() {
                    if ('\x40'..='\x7e').contains(&x) {
                        last = Some(x);
                        break;
                    }
                    params.push(x);
                }
                match last {
                    Some('H') => {
                        let mut p = params.split(';').map(|n| n.parse::<usize>().unwrap_or(1));
                        r = p.next().unwrap_or(1).saturating_sub(1);
                        c = p.next().unwrap_or(1).saturating_sub(1);
                    }
                    Some('J') if params == "2" => grid = vec![vec![' '; w]; h],
                    _ => {}
                }
            }
            '\r' => c = 0,
            '\n' => r += 1,
            ch if ch < ' ' => {}
            ch => {
                if r < h && c < w {
                    grid[r][c] = ch;
                }
                c += 1;
            }
        }
    }
    grid.into_iter()
        .map(|row| row.into_iter().collect::<String>().trim_end().to_string())
        .collect()
}

/// A client's terminal and its size.
struct Tty {
    t: Term,
    w: usize,
    h: usize,
}

impl Tty {
    async fn open(handle: &Handle<Trust>, w: usize, h: usize) -> Tty {
        let t = Term::open(handle, w as u32, h as u32).await.unwrap();
        Tty { t, w, h }
    }

    fn rows(&self) -> Vec<String> {
        screen(&self.t.seen, self.w, self.h)
    }

    fn shows(&self, text: &str) -> bool {
        self.rows().join("\n").contains(text)
    }

    async fn send(&self, bytes: &[u8]) {
        self.t.send(bytes).await.unwrap();
    }
}

/// Reads every terminal until `done` holds of their screens (or `WAIT` passes); whether it
/// did. The screens are read again as soon as bytes come (not after a fixed wait on each
/// terminal in turn). On failure the screens are printed.
async fn until(ttys: &mut [&mut Tty], done: impl Fn(&[Vec<String>]) -> bool) -> bool {
    let end = std::time::Instant::now() + WAIT;
    let mut screens = vec![];
    loop {
        let mut came = screens.is_empty();
        for tty in ttys.iter_mut() {
            // What has arrived, without waiting (a timeout polls its future first).
            while !tty.t.closed && tty.t.next(tokio::time::Instant::now()).await {
                came = true;
            }
        }
        if came {
            screens = ttys.iter().map(|t| t.rows()).collect();
            if done(&screens) {
                return true;
            }
        }
        if std::time::Instant::now() > end {
            for s in &screens {
                eprintln!("{}\n----", s.join("\n"));
            }
            return false;
        }
        if !came {
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
    }
}

/// Whether every screen shows each of `texts`.
fn all_show(screens: &[Vec<String>], texts: &[&str]) -> bool {
    screens.iter().all(|s| {
        let s = s.join("\n");
        texts.iter().all(|t| s.contains(t))
    })
}

/// The rows between the title and the two lines at the foot (notices, keys), but the
/// caption's lower edge (which says what this user's keys do): the picture, the panel and the
/// caption's words.
fn body(s: &[String]) -> Vec<&String> {
    s[1..s.len() - 2]
        .iter()
        .filter(|r| !r.starts_with('└'))
        .collect()
}

/// The presenter at 80×24 and two followers, at 80×24 and 60×20, the lesson at its first wait.
async fn class(addr: std::net::SocketAddr) -> (Vec<Handle<Trust>>, Tty, Tty, Tty) {
    let p = login(addr, "teacher", Login::Key(&key(3)))
        .await
        .unwrap()
        .unwrap();
    let mut tp = Tty::open(&p, 80, 24).await;
    assert!(until(&mut [&mut tp], |s| all_show(s, &["First: at rest"])).await);
    let mut handles = vec![p];
    let mut followers = vec![];
    for (w, h) in [(80, 24), (60, 20)] {
        let f = login(addr, "class", Login::Password("ba-ke-di-lo"))
            .await
            .unwrap()
            .unwrap();
        followers.push(Tty::open(&f, w, h).await);
        handles.push(f);
    }
    let (f2, f1) = (followers.pop().unwrap(), followers.pop().unwrap());
    (handles, tp, f1, f2)
}

/// The presenter's Enter moves the lesson on for everyone: the same captions and the same
/// scenes, held at the same waits; the question reaches the followers with their own prompt.
#[test]
fn a_presenters_lesson_runs_for_every_follower_in_step() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    rt().block_on(async {
        let (_h, mut tp, mut f1, mut f2) = class(s.addr).await;
        // Joined at the first wait: the scene as the lesson left it (ξ0 0.9, paused).
        let first = ["First: at rest", "ξ0 0.900", "following the class"];
        assert!(until(&mut [&mut f1, &mut f2], |s| all_show(s, &first)).await);
        // Paused, the presenter and the follower of its size show the same picture, panel and
        // caption.
        assert!(until(&mut [&mut tp, &mut f1], |s| body(&s[0]) == body(&s[1])).await);
        tp.send(b"\r").await;
        let second = ["Second: at rest", "ξ0 1.100"];
        assert!(
            until(&mut [&mut tp, &mut f1, &mut f2], |s| {
                all_show(s, &second) && body(&s[0]) == body(&s[1])
            })
            .await
        );
        tp.send(b"\r").await;
        // The question: the presenter answers for the class (y / n moves it on), a follower
        // answers for itself.
        assert!(
            until(&mut [&mut tp, &mut f1, &mut f2], |s| {
                all_show(
                    &s[..1],
                    &["Will it escape?", "y escapes · n stays · Space plays"],
                ) && all_show(&s[1..], &["Will it escape?", " y escapes · n stays ┘"])
            })
            .await
        );
        tp.send(b"y").await;
        // The run answers; then the presenter's Enter ends the lesson for all.
        let answered = ["Right: it escapes", "Enter: go on"];
        assert!(until(&mut [&mut tp], |s| all_show(s, &answered)).await);
        assert!(
            until(&mut [&mut f1, &mut f2], |s| all_show(
                s,
                &["The run: it escapes"]
            ))
            .await
        );
        tp.send(b"\r").await;
        assert!(
            until(&mut [&mut tp, &mut f1, &mut f2], |s| all_show(
                s,
                &["The end."]
            ))
            .await
        );
        // The last words close with the presenter's Esc, the followers' with it: each is
        // told whose key that is (a follower's own Esc is not applied).
        assert!(until(&mut [&mut tp], |s| all_show(s, &["Esc closes"])).await);
        assert!(
            until(&mut [&mut f1, &mut f2], |s| all_show(
                s,
                &["end · presenter closes it"]
            ))
            .await
        );
        tp.send(b"\x1b").await;
        assert!(
            until(&mut [&mut tp, &mut f1, &mut f2], |s| s
                .iter()
                .all(|rows| !rows.join("\n").contains("The end.")))
            .await
        );
    });
    s.stop("done");
}

/// The class from its first scene on to its question: the presenter's two Enters, each once
/// the lesson holds again (an Enter while it moves is not a go-on).
async fn on_to_the_question(tp: &mut Tty, f1: &mut Tty, f2: &mut Tty) {
    assert!(until(&mut [f1, f2], |s| all_show(s, &["First: at rest"])).await);
    tp.send(b"\r").await;
    assert!(until(&mut [&mut *tp], |s| all_show(s, &["Second", "Enter"])).await);
    tp.send(b"\r").await;
}

/// The followers' own y / n are counted on the presenter's screen as they come; the first
/// answer stands; once the presenter answers, the question takes no more and its tally stays
/// until the lesson says something else.
#[test]
fn the_followers_answers_are_tallied_on_the_presenters_screen() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    rt().block_on(async {
        let (_h, mut tp, mut f1, mut f2) = class(s.addr).await;
        on_to_the_question(&mut tp, &mut f1, &mut f2).await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["y 0 · n 0 · 2 not yet"])).await);
        assert!(
            until(&mut [&mut f1, &mut f2], |s| all_show(
                s,
                &["Will it escape?"]
            ))
            .await
        );
        f1.send(b"y").await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["y 1 · n 0 · 1 not yet"])).await);
        assert!(until(&mut [&mut f1], |s| all_show(s, &["answered"])).await);
        f2.send(b"n").await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["y 1 · n 1 · 0 not yet"])).await);
        // A second answer changes nothing: the first stands (a change would be on the
        // presenter's screen a frame or two after it).
        f1.send(b"n").await;
        tokio::time::sleep(Duration::from_millis(250)).await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["y 1 · n 1 · 0 not yet"])).await);
        // The presenter answers: the question closes, its tally stays while it is on screen.
        tp.send(b"n").await;
        assert!(
            until(&mut [&mut tp], |s| all_show(
                s,
                &["Not so: you said it does not escape"]
            ))
            .await
        );
        assert!(tp.shows("y 1 · n 1 · 0 not yet"));
        // Each follower is told about its own answer.
        assert!(until(&mut [&mut f1], |s| all_show(s, &["Right: it escapes"])).await);
        assert!(
            until(&mut [&mut f2], |s| all_show(
                s,
                &["Not so: you said it does not"]
            ))
            .await
        );
        // The next words of the lesson (once it waits for them): no tally.
        assert!(until(&mut [&mut tp], |s| all_show(s, &["Enter: go on"])).await);
        tp.send(b"\r").await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["The end."])).await);
        assert!(!tp.shows("not yet"));
    });
    s.stop("done");
}

/// A follower's answer is its own: the presenter's screen changes only in its tally, the
/// other follower's not at all, and the lesson holds until the presenter goes on.
#[test]
fn a_followers_answer_moves_neither_the_presenter_nor_the_others() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    rt().block_on(async {
        let (_h, mut tp, mut f1, mut f2) = class(s.addr).await;
        on_to_the_question(&mut tp, &mut f1, &mut f2).await;
        let asked = ["Will it escape?"];
        assert!(
            until(&mut [&mut tp, &mut f1, &mut f2], |s| {
                all_show(s, &asked) && all_show(&s[..1], &["2 not yet"])
            })
            .await
        );
        let (p_before, f2_before) = (tp.rows(), f2.rows());
        f1.send(b"y").await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["y 1 · n 0 · 1 not yet"])).await);
        assert!(until(&mut [&mut f1], |s| all_show(s, &["You said it escapes."])).await);
        assert!(
            !f1.shows("Right"),
            "the outcome given away before the class answered"
        );
        // Everything a while longer (ten frames): nothing else moves.
        tokio::time::sleep(Duration::from_millis(300)).await;
        until(&mut [&mut tp, &mut f2], |_| true).await;
        assert_eq!(f2.rows(), f2_before, "the other follower's screen moved");
        let rows = tp.rows();
        let changed: Vec<(&String, &String)> =
            p_before.iter().zip(&rows).filter(|(a, b)| a != b).collect();
        assert!(
            changed.len() == 1 && changed[0].1.contains("y 1 · n 0 · 1 not yet"),
            "the presenter's screen changed beyond its tally: {changed:?}"
        );
        assert!(
            tp.shows("y escapes · n stays · Space plays"),
            "the question was closed"
        );
    });
    s.stop("done");
}

/// A second presenter (the teacher back while the dropped connection lingers: the server has
/// not seen it go) takes the class over where it was, the lesson at the same step, and the
/// followers with it; the first leads no more and is told so. (It took the class over from
/// its own start: the lesson back at step 1 for everyone.)
#[test]
fn a_presenter_who_takes_over_takes_the_class_where_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    rt().block_on(async {
        let (_h, mut tp, mut f1, _f2) = class(s.addr).await;
        assert!(until(&mut [&mut f1], |s| all_show(s, &["First: at rest"])).await);
        tp.send(b"\r").await;
        assert!(until(&mut [&mut f1], |s| all_show(s, &["Second: at rest"])).await);
        let p2 = login(s.addr, "teacher", Login::Key(&key(3)))
            .await
            .unwrap()
            .unwrap();
        let mut tp2 = Tty::open(&p2, 80, 24).await;
        assert!(
            until(&mut [&mut tp2], |s| all_show(
                s,
                &["Second: at rest", "you present: the class as it was left"]
            ))
            .await
        );
        assert!(
            until(&mut [&mut tp], |s| all_show(
                s,
                &["another presenter took the class over"]
            ))
            .await
        );
        assert!(!tp2.shows("First: at rest") && !f1.shows("First: at rest"));
        assert!(until(&mut [&mut tp2, &mut f1], |s| body(&s[0]) == body(&s[1])).await);
        // The first presenter leads no more (a lead is on a follower's screen a frame or two
        // after the key); the second's Enter moves the class one step.
        tp.send(b"\r").await;
        tokio::time::sleep(Duration::from_millis(250)).await;
        until(&mut [&mut f1], |_| true).await;
        assert!(
            !f1.shows("Will it escape?"),
            "the first presenter still led"
        );
        tp2.send(b"\r").await;
        assert!(
            until(&mut [&mut tp2, &mut f1], |s| all_show(
                s,
                &["Will it escape?"]
            ))
            .await
        );
    });
    s.stop("done");
}

/// What the presenter pastes at the values prompt, the followers type too.
#[test]
fn a_presenters_paste_reaches_the_followers() {
    let s = serving(None);
    rt().block_on(async {
        let p = login(s.addr, "teacher", Login::Key(&key(3)))
            .await
            .unwrap()
            .unwrap();
        let mut tp = Tty::open(&p, 80, 24).await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["lab frame"])).await);
        let f = login(s.addr, "class", Login::Password("ba-ke-di-lo"))
            .await
            .unwrap()
            .unwrap();
        let mut tf = Tty::open(&f, 80, 24).await;
        assert!(until(&mut [&mut tf], |s| all_show(s, &["following the class"])).await);
        tp.send(b":").await;
        assert!(until(&mut [&mut tf], |s| all_show(s, &["set:"])).await);
        // A follower's own paste at the class's prompt waits, as its keys do.
        tf.send(b"\x1b[200~phi 1\x1b[201~").await;
        tp.send(b"\x1b[200~xi0 0.7\x1b[201~").await;
        tp.send(b"\r").await;
        assert!(until(&mut [&mut tp, &mut tf], |s| all_show(s, &["ξ0 0.700"])).await);
        // Paused, the two show the same.
        tp.send(b" ").await;
        assert!(until(&mut [&mut tp, &mut tf], |s| body(&s[0]) == body(&s[1])).await);
    });
    s.stop("done");
}

/// A local session of `w` × `h` on the default scene, paused: what a client of that size
/// shows when it does the same.
fn local(w: u16, h: u16) -> turntable::session::Explorer<ratatui::backend::TestBackend> {
    let app = turntable::app::App::new(turntable::scene::Scene::default_scene());
    let theme = turntable::theme::Theme::builtin("dark").unwrap();
    let mut s = turntable::session::Explorer::headless(app, theme, w, h, false);
    s.press(turntable::app::Chord::new(
        crossterm::event::KeyCode::Char(' '),
        crossterm::event::KeyModifiers::NONE,
    ));
    s
}

/// A local session's screen as rows, as `screen` reads a client's.
fn rows(s: &mut turntable::session::Explorer<ratatui::backend::TestBackend>) -> Vec<String> {
    let buf = s.screen();
    let (w, h) = (buf.area.width, buf.area.height);
    (0..h)
        .map(|y| {
            let row: String = (0..w).map(|x| buf[(x, y)].symbol()).collect();
            row.trim_end().to_string()
        })
        .collect()
}

/// What the presenter's mouse does reaches the followers in the model's terms: a click on the
/// table and a drag from it, at 100×30, give a follower at 70×22 the release and velocity a
/// session of its own size given the same actions shows (a cell would be elsewhere there).
#[test]
fn a_presenters_click_and_drag_reach_a_follower_of_another_size() {
    use crossterm::event::{MouseButton, MouseEventKind};
    let s = serving(None);
    // The presenter's gestures, and the actions its canvas makes of them, found locally.
    let mut presenter = local(100, 30);
    rows(&mut presenter);
    let g = presenter.app.geom_for_tests().unwrap();
    let (col, row) = crate::common::cell_under(&g, 0.6, 0.3);
    let gestures = [
        (MouseEventKind::Down(MouseButton::Left), col, row, 'M', 0),
        (
            MouseEventKind::Drag(MouseButton::Left),
            col + 8,
            row - 4,
            'M',
            32,
        ),
        (
            MouseEventKind::Up(MouseButton::Left),
            col + 8,
            row - 4,
            'm',
            0,
        ),
    ];
    let actions: Vec<_> = gestures
        .iter()
        .filter_map(|&(kind, c, r, ..)| presenter.mouse(crate::common::mouse(kind, c, r)).unwrap())
        .collect();
    assert_eq!(actions.len(), 3, "{actions:?}");
    let mut follower = local(70, 22);
    for a in actions {
        follower.act(a);
    }
    let (p_rows, f_rows) = (rows(&mut presenter), rows(&mut follower));
    assert!(f_rows.join("\n").contains("v0 = "), "{}", f_rows.join("\n"));
    rt().block_on(async {
        let p = login(s.addr, "teacher", Login::Key(&key(3)))
            .await
            .unwrap()
            .unwrap();
        let mut tp = Tty::open(&p, 100, 30).await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["lab frame"])).await);
        let f = login(s.addr, "class", Login::Password("ba-ke-di-lo"))
            .await
            .unwrap()
            .unwrap();
        let mut tf = Tty::open(&f, 70, 22).await;
        assert!(until(&mut [&mut tf], |s| all_show(s, &["following the class"])).await);
        tp.send(b" ").await;
        for (_, c, r, end, button) in gestures {
            let sgr = format!("\x1b[<{button};{};{}{end}", c + 1, r + 1);
            tp.send(sgr.as_bytes()).await;
        }
        assert!(
            until(&mut [&mut tp, &mut tf], |s| {
                body(&s[0]) == body(&p_rows) && body(&s[1]) == body(&f_rows)
            })
            .await
        );
    });
    s.stop("done");
}

/// The ξ0 a screen's panel shows (`ξ0 0.500 …`).
fn xi0_shown(rows: &[String]) -> Option<String> {
    rows.iter().find_map(|r| {
        let at = r.find("ξ0 ")?;
        r[at..].split_whitespace().nth(1).map(str::to_string)
    })
}

/// A click in the presenter's lesson reaches a follower of another size as the action it
/// made: both show the release it placed (the follower's own layout would put the cell in
/// its panel, placing nothing).
#[test]
fn a_click_in_the_presenters_lesson_reaches_a_follower_of_another_size() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("click.keys");
    let script = "pause\nsay Ready.\nwait\nmouse click 60 12\nmouse up 60 12\nsay Clicked.\nwait\n";
    std::fs::write(&path, script).unwrap();
    let lesson = turntable::cli::lesson::for_class(path.to_str().unwrap()).unwrap();
    let s = serving(Some(lesson));
    rt().block_on(async {
        let p = login(s.addr, "teacher", Login::Key(&key(3)))
            .await
            .unwrap()
            .unwrap();
        let mut tp = Tty::open(&p, 100, 30).await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["Ready."])).await);
        let f = login(s.addr, "class", Login::Password("ba-ke-di-lo"))
            .await
            .unwrap()
            .unwrap();
        let mut tf = Tty::open(&f, 70, 22).await;
        assert!(until(&mut [&mut tf], |s| all_show(s, &["Ready.", "following"])).await);
        tp.send(b"\r").await;
        assert!(
            until(&mut [&mut tp, &mut tf], |s| {
                let (a, b) = (xi0_shown(&s[0]), xi0_shown(&s[1]));
                all_show(s, &["Clicked."]) && a.is_some() && a == b && a.as_deref() != Some("0.500")
            })
            .await,
            "{}\n{}",
            tp.rows().join("\n"),
            tf.rows().join("\n")
        );
    });
    s.stop("done");
}

/// Students come before the teacher: one who logged in first is told it waits, and follows
/// the class as soon as the presenter is in, told so (it stayed on its own until it pressed
/// F2, and was not told when it began to follow).
#[test]
fn a_student_who_came_first_follows_the_presenter() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    rt().block_on(async {
        let f = login(s.addr, "class", Login::Password("ba-ke-di-lo"))
            .await
            .unwrap()
            .unwrap();
        let mut tf = Tty::open(&f, 60, 20).await;
        assert!(until(&mut [&mut tf], |s| all_show(s, &["no presenter yet"])).await);
        let p = login(s.addr, "teacher", Login::Key(&key(3)))
            .await
            .unwrap()
            .unwrap();
        let mut tp = Tty::open(&p, 80, 24).await;
        assert!(
            until(&mut [&mut tp, &mut tf], |s| all_show(
                s,
                &["First: at rest"]
            ))
            .await
                && until(&mut [&mut tf], |s| all_show(s, &["the presenter is here"])).await
        );
        // Keys a follower cannot use are not offered it (c compares only for the presenter).
        assert!(tp.shows("c: compare") && !tf.shows("c: "));
        tp.send(b"\r").await;
        assert!(
            until(&mut [&mut tp, &mut tf], |s| all_show(
                s,
                &["Second: at rest"]
            ))
            .await
        );
    });
    s.stop("done");
}

/// The teacher's connection drops and they log in again: the class follows them again, the
/// lesson at the step where it was left (it restarted at step 1, and nobody followed).
#[test]
fn a_presenter_back_after_a_drop_is_followed_where_the_class_was() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    rt().block_on(async {
        let (mut handles, tp, mut f1, mut f2) = class(s.addr).await;
        assert!(
            until(&mut [&mut f1, &mut f2], |s| all_show(
                s,
                &["First: at rest"]
            ))
            .await
        );
        tp.send(b"\r").await;
        assert!(
            until(&mut [&mut f1, &mut f2], |s| all_show(
                s,
                &["Second: at rest"]
            ))
            .await
        );
        // The presenter's connection goes.
        drop(tp);
        let p = handles.remove(0);
        p.disconnect(russh::Disconnect::ByApplication, "", "")
            .await
            .unwrap();
        drop(p);
        assert!(
            until(&mut [&mut f1, &mut f2], |s| all_show(
                s,
                &["presenter left"]
            ))
            .await
        );
        // Back: the class as it was, and everyone follows it again.
        let p = login(s.addr, "teacher", Login::Key(&key(3)))
            .await
            .unwrap()
            .unwrap();
        let mut tp = Tty::open(&p, 80, 24).await;
        assert!(until(&mut [&mut tp], |s| all_show(s, &["Second: at rest"])).await);
        assert!(!tp.shows("First: at rest"), "the lesson restarted");
        assert!(
            until(&mut [&mut f1, &mut f2], |s| all_show(
                s,
                &["the presenter is here"]
            ))
            .await
        );
        // The presenter's Enter moves them all on: the question.
        tp.send(b"\r").await;
        assert!(
            until(&mut [&mut tp, &mut f1, &mut f2], |s| all_show(
                s,
                &["Will it escape?"]
            ))
            .await
        );
    });
    s.stop("done");
}

/// Followers of one size share one drawing of each frame, and each still sees its own: one
/// who came later, while the presenter played, shows what the first shows; a follower's own
/// answer never reaches the other's screen; one of another size draws its own.
#[test]
fn followers_of_one_size_share_a_frame_and_each_sees_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let s = server(dir.path());
    rt().block_on(async {
        let (mut handles, mut tp, mut f1, mut f2) = class(s.addr).await;
        assert!(
            until(&mut [&mut f1, &mut f2], |s| all_show(
                s,
                &["First: at rest"]
            ))
            .await
        );
        // Played a while, a third follower coming meanwhile.
        tp.send(b" ").await;
        let f = login(s.addr, "class", Login::Password("ba-ke-di-lo"))
            .await
            .unwrap()
            .unwrap();
        let mut f3 = Tty::open(&f, 80, 24).await;
        handles.push(f);
        assert!(until(&mut [&mut f3], |s| all_show(s, &["First: at rest"])).await);
        tokio::time::sleep(Duration::from_millis(250)).await;
        tp.send(b" ").await;
        let same = |s: &[Vec<String>]| body(&s[0]) == body(&s[1]);
        assert!(until(&mut [&mut f1, &mut f3], same).await);
        let counts = &s.shared.counts;
        assert!(counts.shared.load(std::sync::atomic::Ordering::Relaxed) > 0);
        on_to_the_question(&mut tp, &mut f1, &mut f3).await;
        let asked = ["Will it escape?", "y escapes · n stays"];
        assert!(until(&mut [&mut f1, &mut f2, &mut f3], |s| all_show(s, &asked)).await);
        assert!(until(&mut [&mut f1, &mut f3], same).await);
        let before = counts.shared.load(std::sync::atomic::Ordering::Relaxed);
        f1.send(b"y").await;
        assert!(until(&mut [&mut f1], |s| all_show(s, &["You said it escapes."])).await);
        // The presenter plays on (the question stays open): the followers draw on.
        tp.send(b" ").await;
        tokio::time::sleep(Duration::from_millis(250)).await;
        until(&mut [&mut f2, &mut f3], |_| true).await;
        for f in [&f2, &f3] {
            assert!(
                !f.shows("You said"),
                "another's answer shown:\n{}",
                f.rows().join("\n")
            );
            assert!(f.shows("y escapes · n stays"));
        }
        assert!(counts.shared.load(std::sync::atomic::Ordering::Relaxed) >= before);
    });
    s.stop("done");
}
