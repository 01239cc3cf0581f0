//! The explorer's terminal as a user's dies or stops (issue 11), on a pseudo-terminal the
//! test opens itself (skipped, saying so, where none can be opened; no TTY is needed).

use crate::common;
use std::io::{Read, Write};
use std::os::fd::AsRawFd;
use std::os::unix::fs::OpenOptionsExt;
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

#[test]
fn without_a_terminal_the_explorer_refuses() {
    let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .env("XDG_CONFIG_HOME", "/nonexistent/turntable-tests/config")
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty(), "no escape codes into a file");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("needs a terminal"), "{err}");
}

/// The explorer on a new pty, in a session of its own (no controlling terminal, as under
/// `setsid`), recording to `rec`. Returns the child, the master, and everything it printed.
/// Kills the explorer if a test fails before it ends, so no process outlives the test.
struct Reap(Child);

impl Drop for Reap {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

impl std::ops::Deref for Reap {
    type Target = Child;
    fn deref(&self) -> &Child {
        &self.0
    }
}

impl std::ops::DerefMut for Reap {
    fn deref_mut(&mut self) -> &mut Child {
        &mut self.0
    }
}

/// Everything the explorer printed so far.
type Seen = Arc<Mutex<Vec<u8>>>;

fn spawn(rec: &std::path::Path) -> Option<(Reap, Pty, Seen)> {
    spawn_in(rec, &std::env::temp_dir())
}

/// As [`spawn`], in the folder `cwd` (where `s` saves scenes).
fn spawn_in(rec: &std::path::Path, cwd: &std::path::Path) -> Option<(Reap, Pty, Seen)> {
    spawn_with(rec, cwd, &[])
}

/// As [`spawn_in`], with more arguments for the explorer.
fn spawn_with(
    rec: &std::path::Path,
    cwd: &std::path::Path,
    args: &[&str],
) -> Option<(Reap, Pty, Seen)> {
    spawn_env(rec, cwd, args, &[])
}

/// As [`spawn_with`], with more environment variables.
fn spawn_env(
    rec: &std::path::Path,
    cwd: &std::path::Path,
    args: &[&str],
    envs: &[(&str, &std::path::Path)],
) -> Option<(Reap, Pty, Seen)> {
    // Other tests fork too: no child may inherit this master (it would keep the pty up).
    static FORK: Mutex<()> = Mutex::new(());
    let _one_at_a_time = FORK.lock().unwrap();
    let (master, slave) = common::openpty(80, 24)?;
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_turntable"));
    // Never the user's configuration.
    cmd.env("XDG_CONFIG_HOME", "/nonexistent/turntable-tests/config")
        .args(["--record", rec.to_str().unwrap()])
        .args(args)
        .envs(envs.iter().copied())
        .current_dir(cwd);
    common::on_pty(&mut cmd, slave);
    let child = cmd.spawn().unwrap();
    let seen = Arc::new(Mutex::new(Vec::new()));
    let fd = master.as_raw_fd();
    let hang_up = Arc::new(AtomicBool::new(false));
    let (sink, stop) = (Arc::clone(&seen), Arc::clone(&hang_up));
    // The reader owns the master: when told to hang up it closes the last copy of it.
    let reader = std::thread::spawn(move || {
        let mut file = std::fs::File::from(master);
        let mut buf = [0; 4096];
        while !stop.load(Ordering::Relaxed) {
            let mut p = libc::pollfd {
                fd,
                events: libc::POLLIN,
                revents: 0,
            };
            // SAFETY: one valid pollfd.
            if unsafe { libc::poll(&mut p, 1, 20) } <= 0 {
                continue;
            }
            match file.read(&mut buf) {
                Ok(n) if n > 0 => {
                    let mut seen = sink.lock().unwrap();
                    let from = seen.len().saturating_sub(3);
                    seen.extend_from_slice(&buf[..n]);
                    // Answer the explorer's cursor queries (its frame pacing) as a terminal
                    // does; unanswered, each waits out crossterm's 2 s.
                    let asked = seen[from..].windows(4).filter(|w| w == b"\x1b[6n").count();
                    for _ in 0..asked {
                        let _ = file.write_all(b"\x1b[1;1R");
                    }
                }
                _ => std::thread::sleep(Duration::from_millis(20)),
            }
        }
    });
    let pty = Pty {
        fd,
        hang_up,
        reader: Some(reader),
    };
    Some((Reap(child), pty, seen))
}

/// The master side of the pty, read by a thread until [`Pty::hang_up`].
struct Pty {
    fd: i32,
    hang_up: Arc<AtomicBool>,
    reader: Option<std::thread::JoinHandle<()>>,
}

impl Pty {
    fn type_keys(&self, keys: &[u8]) {
        // SAFETY: the master is open until hang_up.
        assert_eq!(
            unsafe { libc::write(self.fd, keys.as_ptr().cast(), keys.len()) },
            keys.len() as isize
        );
    }
    /// Closes the master, as a killed tmux does.
    fn hang_up(&mut self) {
        self.hang_up.store(true, Ordering::Relaxed);
        if let Some(r) = self.reader.take() {
            r.join().unwrap();
        }
    }
}

impl Drop for Pty {
    fn drop(&mut self) {
        self.hang_up();
    }
}

fn wait_for(what: &str, mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(start.elapsed() < Duration::from_secs(30), "never: {what}");
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn contains(seen: &Mutex<Vec<u8>>, from: usize, needle: &[u8]) -> bool {
    seen.lock().unwrap()[from..]
        .windows(needle.len())
        .any(|w| w == needle)
}

/// The state of process `pid` (`T`: stopped), as /proc says.
fn state(pid: i32) -> Option<char> {
    std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .ok()
        .and_then(|s| s.rsplit(')').next().map(|r| r.trim().chars().next()))
        .flatten()
}

/// Pauses the explorer (Space) and waits for the pause drawn and the query behind it
/// (answered as the reader reads it): from then on it draws nothing and asks nothing.
fn pause(pty: &Pty, seen: &Mutex<Vec<u8>>) {
    let mark = seen.lock().unwrap().len();
    pty.type_keys(b" ");
    wait_for("the pause", || {
        let seen = seen.lock().unwrap();
        let at = seen[mark..]
            .windows("❚❚".len())
            .position(|w| w == "❚❚".as_bytes());
        at.is_some_and(|at| seen[mark + at..].windows(4).any(|w| w == b"\x1b[6n"))
    });
}

const ALT_ON: &[u8] = b"\x1b[?1049h";
const ALT_OFF: &[u8] = b"\x1b[?1049l";
const MOUSE_OFF: &[u8] = b"\x1b[?1000l";

fn rec(tag: &str) -> std::path::PathBuf {
    let p = std::env::temp_dir().join(format!("turntable-term-{tag}-{}.keys", std::process::id()));
    let _ = std::fs::remove_file(&p);
    p
}

/// A killed tmux or a dropped connection with no controlling terminal: the explorer ends
/// (it used to spin at full CPU) and saves its recording.
#[test]
fn a_hung_up_terminal_ends_the_explorer_and_saves_the_recording() {
    let path = rec("hangup");
    let Some((mut child, mut pty, seen)) = spawn(&path) else {
        return;
    };
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    pty.hang_up();
    wait_for("the process to end", || child.try_wait().unwrap().is_some());
    let script = std::fs::read_to_string(&path).unwrap();
    assert!(
        script.starts_with("# turntable key script\nresize 80x24\n"),
        "{script}"
    );
}

/// SIGQUIT (like SIGTERM) restores the terminal first: alternate screen and mouse off; the
/// exit status is 128 + the signal's number.
#[test]
fn sigquit_restores_the_terminal() {
    let path = rec("quit");
    let Some((mut child, _pty, seen)) = spawn(&path) else {
        return;
    };
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    let mark = seen.lock().unwrap().len();
    // SAFETY: a signal to our child.
    unsafe { libc::kill(child.id() as i32, libc::SIGQUIT) };
    wait_for("the process to end", || child.try_wait().unwrap().is_some());
    wait_for("the restore", || {
        contains(&seen, mark, ALT_OFF) && contains(&seen, mark, MOUSE_OFF)
    });
    assert!(path.exists());
    // As a shell reports a process a signal ended (issue 18 item 22): 128 + 3.
    assert_eq!(child.wait().unwrap().code(), Some(131));
}

/// SIGTSTP hands the terminal back (cooked, main screen) before stopping; SIGCONT takes it
/// again and redraws.
#[test]
fn suspend_and_continue() {
    let path = rec("tstp");
    let Some((mut child, pty, seen)) = spawn(&path) else {
        return;
    };
    let pid = child.id() as i32;
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    let mark = seen.lock().unwrap().len();
    // SAFETY: signals to our child.
    unsafe { libc::kill(pid, libc::SIGTSTP) };
    wait_for("stopped", || state(pid) == Some('T'));
    // Written before it stopped; the reader thread may not have it yet on a loaded machine.
    wait_for("the terminal handed back", || {
        contains(&seen, mark, ALT_OFF)
    });
    let mark = seen.lock().unwrap().len();
    unsafe { libc::kill(pid, libc::SIGCONT) };
    wait_for("the screen back", || contains(&seen, mark, ALT_ON));
    wait_for("a redraw", || contains(&seen, mark, "ξ0".as_bytes()));
    pty.type_keys(b"q");
    wait_for("quit", || child.try_wait().unwrap().is_some());
    assert_eq!(child.wait().unwrap().code(), Some(0));
}

const PASTE_ON: &[u8] = b"\x1b[?2004h";
const PASTE_OFF: &[u8] = b"\x1b[?2004l";

/// Issue 18 item 19: the explorer asks for bracketed paste (and gives it back), so a paste
/// arrives as one event, not as keys: a pasted `q` does not quit, the keys after it still
/// work.
#[test]
fn pasted_text_is_not_keys() {
    let path = rec("paste");
    let Some((mut child, pty, seen)) = spawn(&path) else {
        return;
    };
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    wait_for("bracketed paste on", || contains(&seen, 0, PASTE_ON));
    let mark = seen.lock().unwrap().len();
    pty.type_keys(b"\x1b[200~sq\x1b[201~?");
    // Keys are taken in order: had the `q` quit, no help would be drawn.
    wait_for("the help", || contains(&seen, mark, b"help"));
    assert!(child.try_wait().unwrap().is_none());
    let mark = seen.lock().unwrap().len();
    pty.type_keys(b"?q");
    wait_for("quit", || child.try_wait().unwrap().is_some());
    assert_eq!(child.wait().unwrap().code(), Some(0));
    wait_for("bracketed paste off", || contains(&seen, mark, PASTE_OFF));
    let script = std::fs::read_to_string(&path).unwrap();
    assert!(!script.contains("\ns\n"), "{script}");
}

/// The explorer, paused, then sent a paste start that no end follows: what
/// [`an_unpaired_paste_start_swallows_no_key_for_good`] types after it. (Paused, it draws
/// nothing, so no answer to a cursor query joins the paste: playing, the quit after the paste
/// came some 2 s after the paste began, the query's wait.)
fn unpaired_paste(tag: &str) -> Option<(Reap, Pty, Seen, std::path::PathBuf)> {
    let path = rec(tag);
    let (child, pty, seen) = spawn(&path)?;
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    pause(&pty, &seen);
    pty.type_keys(b"\x1b[200~pasted, never ended: q");
    Some((child, pty, seen, path))
}

/// Types `key` and waits for the explorer to quit: the pasted text was no keys, the
/// recording's keys are the pause and the quitting key (`recorded`).
fn quits_after_the_paste(
    (mut child, pty, _seen, path): (Reap, Pty, Seen, std::path::PathBuf),
    key: &[u8],
    recorded: &str,
) {
    pty.type_keys(key);
    wait_for("quit", || child.try_wait().unwrap().is_some());
    assert_eq!(child.wait().unwrap().code(), Some(0), "{recorded}");
    let script = std::fs::read_to_string(&path).unwrap();
    let _ = std::fs::remove_file(&path);
    let keys: Vec<&str> = script
        .lines()
        .filter(|l| !["#", "resize", "tick"].iter().any(|p| l.starts_with(p)))
        .flat_map(str::split_whitespace)
        .collect();
    assert_eq!(keys, ["space", recorded], "{script}");
}

/// An unpaired paste start (issue 33) no longer swallows every key: Ctrl-C ends the paste
/// and reaches the explorer at once (it quits, saving the recording), and a paste whose
/// bytes stop coming is ended, after which `q` quits. (The two explorers run side by side:
/// the first's Ctrl-C while the second's paste waits out its silence.)
#[test]
fn an_unpaired_paste_start_swallows_no_key_for_good() {
    use turntable::terminal::input::PASTE_IDLE;
    let Some(idle) = unpaired_paste("paste-idle") else {
        return;
    };
    let pasted = Instant::now();
    let Some(ctrl_c) = unpaired_paste("paste-ctrl-c") else {
        return;
    };
    quits_after_the_paste(ctrl_c, b"\x03", "ctrl-c");
    // The paste is ended once its bytes have stopped for half a second (a paused explorer
    // reads them as they come: 300 ms to spare).
    std::thread::sleep((PASTE_IDLE + Duration::from_millis(300)).saturating_sub(pasted.elapsed()));
    quits_after_the_paste(idle, b"q", "q");
}

/// Whether the pty's line discipline is cooked (canonical input, echo).
fn cooked(fd: i32) -> bool {
    // SAFETY: a valid descriptor and an out-pointer to a termios.
    let mut t: libc::termios = unsafe { std::mem::zeroed() };
    assert_eq!(unsafe { libc::tcgetattr(fd, &mut t) }, 0);
    t.c_lflag & (libc::ICANON | libc::ECHO) != 0
}

/// Issue 18 item 20: SIGSTOP cannot be caught, and the shell puts the terminal back in cooked
/// mode while the job is stopped; SIGCONT (`fg`) takes raw mode back and redraws.
#[test]
fn sigstop_then_sigcont_takes_raw_mode_back() {
    let path = rec("stop");
    let Some((mut child, pty, seen)) = spawn(&path) else {
        return;
    };
    let pid = child.id() as i32;
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    // Paused, no frame's query is in flight when it stops: an answer left in the line
    // discipline as it turns cooked held the redraw for the query's 2 s, four runs in ten.
    pause(&pty, &seen);
    assert!(!cooked(pty.fd));
    // SAFETY: signals to our child; termios of our pty (through its master, as a shell's
    // own tcsetattr on the slave).
    let stopped_at = seen.lock().unwrap().len();
    unsafe { libc::kill(pid, libc::SIGSTOP) };
    // As the README says (issue 33 item 8): SIGSTOP cannot be caught, so nothing is given
    // back: no leaving the alternate screen, no mouse off. Once it is stopped nothing more
    // can come; the reader (polling every 20 ms) has what came before within 100 ms.
    wait_for("stopped", || state(pid) == Some('T'));
    std::thread::sleep(Duration::from_millis(100));
    assert!(!contains(&seen, stopped_at, ALT_OFF) && !contains(&seen, stopped_at, MOUSE_OFF));
    let mut t: libc::termios = unsafe { std::mem::zeroed() };
    assert_eq!(unsafe { libc::tcgetattr(pty.fd, &mut t) }, 0);
    t.c_lflag |= libc::ICANON | libc::ECHO;
    assert_eq!(unsafe { libc::tcsetattr(pty.fd, libc::TCSANOW, &t) }, 0);
    assert!(cooked(pty.fd));
    let mark = seen.lock().unwrap().len();
    unsafe { libc::kill(pid, libc::SIGCONT) };
    wait_for("raw mode back", || !cooked(pty.fd));
    wait_for("a redraw", || contains(&seen, mark, "ξ0".as_bytes()));
    // One key, no Enter: raw.
    pty.type_keys(b"q");
    wait_for("quit", || child.try_wait().unwrap().is_some());
    assert_eq!(child.wait().unwrap().code(), Some(0));
}

/// Issue 18 item 21: `--record` to a FIFO with a reader (as `cat FIFO`: it reads until the
/// last writer closes). The start-up check used to open and close it, ending the reader, so
/// the recording was lost; now the FIFO stays open and the reader gets the whole script.
#[test]
fn record_to_a_fifo_reaches_its_reader() {
    let fifo = rec("fifo");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    // Non-blocking, so this reader is there before the explorer opens the FIFO.
    let reader = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(&fifo)
        .unwrap();
    let got = Arc::new(Mutex::new((Vec::new(), false)));
    let sink = Arc::clone(&got);
    std::thread::spawn(move || {
        let mut reader = reader;
        let mut buf = [0; 4096];
        loop {
            let mut p = libc::pollfd {
                fd: reader.as_raw_fd(),
                events: libc::POLLIN,
                revents: 0,
            };
            // SAFETY: one valid pollfd; it wakes on data or once the last writer closes.
            unsafe { libc::poll(&mut p, 1, -1) };
            match reader.read(&mut buf) {
                Ok(0) => break,
                Ok(n) => sink.lock().unwrap().0.extend_from_slice(&buf[..n]),
                Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {}
                Err(_) => break,
            }
        }
        sink.lock().unwrap().1 = true;
    });
    let Some((mut child, pty, seen)) = spawn(&fifo) else {
        return;
    };
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    pty.type_keys(b"q");
    wait_for("quit", || child.try_wait().unwrap().is_some());
    let code = child.wait().unwrap().code();
    wait_for("the reader's end of file", || got.lock().unwrap().1);
    let text = String::from_utf8(got.lock().unwrap().0.clone()).unwrap();
    assert!(text.starts_with("# turntable key script\n"), "{text:?}");
    assert_eq!(code, Some(0));
    std::fs::remove_file(&fifo).unwrap();
}

/// Issue 18 item 21: `--record turntable-scene.toml` then `s`: `s` saves the scene there
/// (nothing stood there), and the recording must not replace it: it goes to the next free
/// name, and says so.
#[test]
fn a_recording_never_replaces_a_file_made_during_the_session() {
    let dir = std::env::temp_dir().join(format!("turntable-rec-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir(&dir).unwrap();
    let scene = dir.join("turntable-scene.toml");
    let Some((mut child, pty, seen)) = spawn_in(&scene, &dir) else {
        return;
    };
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    pty.type_keys(b"s");
    wait_for("the scene saved", || scene.exists());
    let saved = std::fs::read_to_string(&scene).unwrap();
    pty.type_keys(b"q");
    wait_for("quit", || child.try_wait().unwrap().is_some());
    assert_eq!(child.wait().unwrap().code(), Some(0));
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), saved);
    assert!(!saved.starts_with("# turntable key script"), "{saved}");
    let script = std::fs::read_to_string(dir.join("turntable-scene-2.toml")).unwrap();
    assert!(script.starts_with("# turntable key script\n"), "{script}");
    wait_for("the notice", || {
        contains(&seen, 0, b"turntable-scene-2.toml")
    });
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Plain mode (`--plain`, issue 22 item 6) on a real terminal: lines of text and not one
/// escape sequence, raw keys (one key, no Enter), each change of state said as time plays, the
/// terminal cooked again after SIGTERM; and its recording, replayed with `--plain`, says
/// exactly what the session said.
#[test]
fn plain_mode_writes_lines_and_gives_the_terminal_back() {
    let path = rec("plain");
    let Some((mut child, pty, seen)) = spawn_with(&path, &std::env::temp_dir(), &["--plain"])
    else {
        return;
    };
    wait_for("the opening", || {
        contains(&seen, 0, "slipping\r\n".as_bytes())
    });
    assert!(!cooked(pty.fd));
    // C plays from the start and stops at τ = 5.602: 3.7 s at 1.5 τ a second, ½ s at ×8.
    // Each `]` waits for the last to be said: keys read at once are said once (as a change).
    for speed in ["×2", "×4", "×8"] {
        pty.type_keys(b"]");
        wait_for("the speed", || {
            contains(&seen, 0, format!("speed {speed}\r\n").as_bytes())
        });
    }
    wait_for("the stop", || {
        contains(&seen, 0, "stuck at ξ = 0.9972 (τ = 5.602)\r\n".as_bytes())
    });
    pty.type_keys(b"I");
    wait_for("the readouts", || {
        contains(&seen, 0, "readouts at τ = ".as_bytes())
    });
    wait_for("the last readout", || {
        contains(&seen, 0, "speed ×8 ▶\r\n".as_bytes())
    });
    // SAFETY: a signal to our child.
    unsafe { libc::kill(child.id() as i32, libc::SIGTERM) };
    wait_for("the process to end", || child.try_wait().unwrap().is_some());
    assert_eq!(child.wait().unwrap().code(), Some(143));
    assert!(cooked(pty.fd), "the terminal is given back cooked");
    let said = String::from_utf8(seen.lock().unwrap().clone()).unwrap();
    assert!(!said.contains('\x1b'), "an escape sequence in {said:?}");
    let said = said.replace("\r\n", "\n");
    let said = said.trim_end_matches("turntable: ended by signal 15\n");
    let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .args(["replay", "--plain", path.to_str().unwrap()])
        .output()
        .unwrap();
    let _ = std::fs::remove_file(&path);
    assert_eq!(String::from_utf8(out.stdout).unwrap(), said);
}

/// Issue 33 item 6: a recording whose file cannot be written at the end (its folder removed
/// during the session) is kept in `$TMPDIR/turntable-recording-PID.keys`, and the error
/// (exit 1) names it; on quit and on a terminating signal alike.
#[test]
fn a_recording_that_cannot_be_written_at_exit_is_kept() {
    let base = std::env::temp_dir().join(format!("turntable-lost-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&base);
    let (gone, tmp) = (base.join("gone"), base.join("tmp"));
    std::fs::create_dir_all(&tmp).unwrap();
    for (how, code) in [("q", 1), ("SIGTERM", 143)] {
        std::fs::create_dir_all(&gone).unwrap();
        let Some((mut child, pty, seen)) =
            spawn_env(&gone.join("rec.keys"), &base, &[], &[("TMPDIR", &tmp)])
        else {
            return;
        };
        wait_for("the first frame", || contains(&seen, 0, ALT_ON));
        assert!(!contains(&seen, 0, b"rotating frame"));
        pty.type_keys(b"f");
        // The key read and drawn before the signal (SIGTERM could beat an unread key).
        wait_for("the key drawn", || contains(&seen, 0, b"rotating frame"));
        std::fs::remove_dir_all(&gone).unwrap();
        if how == "q" {
            pty.type_keys(b"q");
        } else {
            // SAFETY: a signal to our child.
            unsafe { libc::kill(child.id() as i32, libc::SIGTERM) };
        }
        wait_for("the end", || child.try_wait().unwrap().is_some());
        assert_eq!(child.wait().unwrap().code(), Some(code), "{how}");
        let kept = tmp.join(format!("turntable-recording-{}.keys", child.id()));
        wait_for("the message", || {
            contains(&seen, 0, b"the recording is kept in")
                && contains(&seen, 0, kept.display().to_string().as_bytes())
        });
        let script = std::fs::read_to_string(&kept).unwrap();
        assert!(
            script.starts_with("# turntable key script\n")
                && script
                    .lines()
                    .any(|l| l.split_whitespace().any(|k| k == "f")),
            "{how}: {script}"
        );
    }
    std::fs::remove_dir_all(&base).unwrap();
}

/// Issue 33 item 1: `--record` over an existing file is refused before the terminal is
/// touched (exit 2); with `--force` the file is replaced when the explorer ends.
#[test]
fn record_replaces_an_existing_file_only_with_force() {
    let path = rec("force");
    std::fs::write(&path, "precious").unwrap();
    let Some((mut child, _pty, seen)) = spawn(&path) else {
        return;
    };
    wait_for("the end", || child.try_wait().unwrap().is_some());
    assert_eq!(child.wait().unwrap().code(), Some(2));
    wait_for("the message", || {
        contains(&seen, 0, b"exists; --force replaces it")
    });
    assert!(!contains(&seen, 0, ALT_ON), "the terminal was not touched");
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "precious");
    let Some((mut child, pty, seen)) = spawn_with(&path, &std::env::temp_dir(), &["--force"])
    else {
        return;
    };
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    pty.type_keys(b"q");
    wait_for("quit", || child.try_wait().unwrap().is_some());
    assert_eq!(child.wait().unwrap().code(), Some(0));
    let script = std::fs::read_to_string(&path).unwrap();
    assert!(script.starts_with("# turntable key script\n"), "{script}");
    std::fs::remove_file(&path).unwrap();
}

/// Issue 33 item 8: with the help open, `q` quits (it used to close the help).
#[test]
fn q_quits_with_the_help_open() {
    let path = rec("helpq");
    let Some((mut child, pty, seen)) = spawn(&path) else {
        return;
    };
    wait_for("the first frame", || contains(&seen, 0, ALT_ON));
    let mark = seen.lock().unwrap().len();
    pty.type_keys(b"?");
    wait_for("the help", || contains(&seen, mark, b"help"));
    pty.type_keys(b"q");
    wait_for("quit", || child.try_wait().unwrap().is_some());
    assert_eq!(child.wait().unwrap().code(), Some(0));
    let _ = std::fs::remove_file(&path);
}

/// The Esc race (an Esc pressed as the terminal answers the frame pacing's cursor query):
/// over ssh `ESC ESC[30;21R` arrives in one read, and its tail was once typed as `[`, `3`,
/// `0`, `;`, `2`, `1`, `R`, reloading a preset, halving the speed and switching the release.
/// No reply is ever keys: the scene is what it was.
#[test]
fn an_esc_beside_a_cursor_reply_leaves_the_scene_alone() {
    use turntable::terminal::input::{Decoder, ESC_WAIT, Input};
    let scene = turntable::scene::Scene::preset("C").unwrap();
    let theme = turntable::theme::Theme::builtin("dark").unwrap();
    let mut s = turntable::session::Explorer::headless(
        turntable::app::App::new(scene),
        theme,
        80,
        24,
        false,
    );
    let before = s.app.current_scene();
    let t0 = Instant::now();
    let mut d = Decoder::new();
    d.feed(b"\x1b\x1b[30;21R", false, t0);
    d.feed(b"\x1b", false, t0);
    d.feed(b"[12;3R\x1b", false, t0 + ESC_WAIT / 2);
    d.expire(t0 + ESC_WAIT * 2);
    let mut keys = 0;
    while let Some(input) = d.next_input() {
        if let Input::Event(crossterm::event::Event::Key(k)) = input {
            keys += 1;
            s.key(k);
        }
    }
    assert_eq!(keys, 2, "two Esc keys, nothing else");
    assert_eq!(s.app.current_scene(), before);
}
