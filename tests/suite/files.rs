//! Files (issue 11): outputs never clobber what they were not asked to replace and never
//! follow a planted link; inputs are regular files of bounded size; messages cannot smuggle
//! control sequences; a replay writes nothing.

use std::io::{Read, Write};
use std::os::unix::fs::{FileTypeExt, OpenOptionsExt, PermissionsExt, symlink};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};
use turntable::files;

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("turntable-files-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs the binary in `cwd`, killing it if it has not ended within a minute (a hang is a
/// failure, reported as exit -1).
fn turntable_in(cwd: &Path, args: &[&str]) -> (i32, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .env("XDG_CONFIG_HOME", "/nonexistent/turntable-tests/config")
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let Output {
        status,
        stdout,
        stderr,
    } = child.wait_with_output().unwrap();
    (
        status.code().unwrap_or(-1),
        String::from_utf8_lossy(&stdout).into(),
        String::from_utf8_lossy(&stderr).into(),
    )
}

fn mkfifo(p: &Path) {
    let c = std::ffi::CString::new(p.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o644) }, 0);
}

/// The old temporary name was `.NAME.tmpPID`, created following symlinks: a link planted
/// there redirected the write into its target.
#[test]
fn a_planted_link_at_the_temporary_name_is_not_followed() {
    let d = dir("planted");
    let victim = d.join("victim");
    std::fs::write(&victim, "precious").unwrap();
    symlink(
        &victim,
        d.join(format!(".out.csv.tmp{}", std::process::id())),
    )
    .unwrap();
    files::write_atomic(&d.join("out.csv"), b"rows", false).unwrap();
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    assert_eq!(std::fs::read_to_string(d.join("out.csv")).unwrap(), "rows");
}

#[test]
fn destinations_that_are_not_regular_files() {
    let d = dir("dest");
    let victim = d.join("victim");
    std::fs::write(&victim, "precious").unwrap();
    symlink(&victim, d.join("link.csv")).unwrap();
    let (code, _, err) = turntable_in(&d, &["sweep", "fig6", "--points", "2", "--out", "link.csv"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("symbolic link"), "{err}");
    assert!(
        d.join("link.csv")
            .symlink_metadata()
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");

    // A FIFO with no reader: refused at once, not a hang.
    mkfifo(&d.join("fifo"));
    let (code, _, err) = turntable_in(&d, &["run", "--trajectory", "fifo"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("no reader"), "{err}");
    assert!(d.join("fifo").metadata().unwrap().file_type().is_fifo());

    // A FIFO with a reader gets the rows in place.
    let reader = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(d.join("fifo"))
        .unwrap();
    let (code, _, err) = turntable_in(&d, &["run", "--trajectory", "fifo"]);
    assert_eq!(code, 0, "{err}");
    let mut rows = String::new();
    (&reader).read_to_string(&mut rows).unwrap();
    assert!(
        rows.starts_with("tau,x,y,xq,yq,u,stuck,energy,work,approx_xi\n0,0.5,"),
        "{rows}"
    );

    // A device is written in place, never replaced by a regular file.
    let (code, _, err) = turntable_in(&d, &["run", "--trajectory", "/dev/null"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        Path::new("/dev/null")
            .metadata()
            .unwrap()
            .file_type()
            .is_char_device()
    );

    // A read-only file is not replaced; a directory is not a file.
    let ro = d.join("ro.csv");
    std::fs::write(&ro, "keep").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o444)).unwrap();
    let (code, _, err) = turntable_in(&d, &["sweep", "fig6", "--points", "2", "--out", "ro.csv"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("exists; --force replaces it"), "{err}");
    let (code, _, err) = turntable_in(
        &d,
        &[
            "sweep", "fig6", "--points", "2", "--out", "ro.csv", "--force",
        ],
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("read-only"), "{err}");
    assert_eq!(std::fs::read_to_string(&ro).unwrap(), "keep");
    let (code, _, _) = turntable_in(&d, &["sweep", "fig6", "--points", "2", "--out", "."]);
    assert_eq!(code, 2);
}

/// Rows stream into a temporary file; a run that then fails leaves the old file untouched
/// and no temporary file behind.
#[test]
fn a_failed_run_leaves_the_old_trajectory() {
    let d = dir("stream");
    std::fs::write(d.join("t.csv"), "old").unwrap();
    let (code, _, err) = turntable_in(
        &d,
        &[
            "run",
            "--method",
            "rk2-raw",
            "--dt",
            "1e-4",
            "--max-steps",
            "1000",
            "--trajectory",
            "t.csv",
            "--force",
        ],
    );
    assert_eq!(code, 1, "{err}");
    assert_eq!(std::fs::read_to_string(d.join("t.csv")).unwrap(), "old");
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
    let (code, _, err) = turntable_in(&d, &["run", "--v0", "0.6", "--trajectory", "t.csv"]);
    assert_eq!(code, 2, "an existing file is kept without --force: {err}");
    assert_eq!(std::fs::read_to_string(d.join("t.csv")).unwrap(), "old");
    let (code, _, _) = turntable_in(
        &d,
        &["run", "--v0", "0.6", "--trajectory", "t.csv", "--force"],
    );
    assert_eq!(code, 0);
    let csv = std::fs::read_to_string(d.join("t.csv")).unwrap();
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    assert!(csv.lines().count() > 100 && last[6] == "1", "{last:?}");
}

#[test]
fn inputs_are_regular_files_of_bounded_size() {
    let d = dir("inputs");
    mkfifo(&d.join("f.toml"));
    std::fs::write(d.join("big.keys"), "x ".repeat(600_000)).unwrap();
    for args in [
        &["--scene", "/dev/zero"][..],
        &["--scene", "f.toml"],
        &["--theme", "/dev/zero"],
        &["--theme", "f.toml"],
        &["replay", "/dev/urandom"],
        &["replay", "f.toml"],
        &["replay", "big.keys"],
        &["replay", "--scene", "f.toml", "big.keys"],
    ] {
        let (code, out, err) = turntable_in(&d, args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?}");
        assert!(
            err.contains("not a regular file") || err.contains("larger than 1024 KiB"),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn scene_files_are_strict_and_name_the_line() {
    let d = dir("strict");
    std::fs::write(
        d.join("typo.toml"),
        "name = \"x\"\n[initial]\nxi0 = 0.5\nphi = 0\nv0 = 0\nfrictionles = true\n",
    )
    .unwrap();
    let (code, _, err) = turntable_in(&d, &["replay", "--scene", "typo.toml", "-"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("typo.toml: line 6: unknown field `frictionles`"),
        "{err}"
    );
    std::fs::write(
        d.join("settings.toml"),
        "name = \"x\"\n[initial]\nxi0 = 0.5\nphi = 0\nv0 = 0\n\n[settings]\nmethod = \"dp54\"\ntoll = 1e-6\n",
    )
    .unwrap();
    let (code, _, err) = turntable_in(&d, &["replay", "--scene", "settings.toml", "-"]);
    assert_eq!(code, 2);
    assert!(err.contains("line 9: unknown field `toll`"), "{err}");
    std::fs::write(
        d.join("missing.toml"),
        "name = \"x\"\n\n[initial]\nphi = 0\nv0 = 0\n",
    )
    .unwrap();
    let (code, _, err) = turntable_in(&d, &["replay", "--scene", "missing.toml", "-"]);
    assert_eq!(code, 2);
    assert!(err.contains("line 3: missing field `xi0`"), "{err}");
}

#[test]
fn control_characters_are_escaped_in_messages() {
    let d = dir("controls");
    std::fs::write(d.join("evil.keys"), "x\x1b]0;pwned\x07 y\n").unwrap();
    let (code, _, err) = turntable_in(&d, &["replay", "evil.keys"]);
    assert_eq!(code, 2);
    assert!(!err.contains('\x1b') && !err.contains('\x07'), "{err:?}");
    assert!(err.contains("\\u{1b}]0;pwned\\u{7}"), "{err}");
    let (code, _, err) = turntable_in(&d, &["--scene", "a\x1b[2Jb.toml"]);
    assert_eq!(code, 2);
    assert!(!err.contains('\x1b'), "{err:?}");
}

#[test]
fn a_replay_writes_no_files() {
    let d = dir("replay-s");
    let (code, out, err) = turntable_in(&d, &["replay", "-"]);
    assert_eq!((code, err.as_str()), (0, ""));
    assert!(out.contains("snapshot 1: final"));
    std::fs::write(d.join("save.keys"), "s\nsnapshot\n").unwrap();
    let (code, out, _) = turntable_in(&d, &["replay", "save.keys"]);
    assert_eq!(code, 0);
    assert!(out.contains("replay saves nothing"), "{out}");
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1, "only the script");
}

/// `s` in the explorer never replaces a file: the second save takes the next free name.
#[test]
fn saving_twice_keeps_both() {
    use turntable::app::{Action, App, update};
    use turntable::scene::Scene;

    let d = dir("save");
    let mut app = App::new(Scene::default_scene());
    app.tell_save_path(d.join("turntable-scene.toml"));
    std::fs::write(app.save_path(), "mine").unwrap();
    let effects = update(&mut app, Action::Save);
    turntable::session::carry_out(&mut app, effects);
    assert_eq!(std::fs::read_to_string(app.save_path()).unwrap(), "mine");
    let second = d.join("turntable-scene-2.toml");
    assert!(
        app.notice()
            .as_deref()
            .unwrap()
            .ends_with("turntable-scene-2.toml")
    );
    assert!(Scene::load(second.to_str().unwrap()).is_ok());
    let effects = update(&mut app, Action::Save);
    turntable::session::carry_out(&mut app, effects);
    assert!(d.join("turntable-scene-3.toml").exists());
}

#[test]
fn record_paths_are_checked_before_the_session() {
    let d = dir("record");
    std::fs::write(d.join("file"), "x").unwrap();
    std::fs::write(d.join("s.toml"), Scene::default_scene().to_toml()).unwrap();
    for args in [
        &["--record", "file/x.keys"][..],
        &["--record", "no-such-dir/x.keys"],
        &["--record", "s.toml", "--scene", "s.toml"],
        &["--record", "./s.toml", "--scene", "s.toml"],
    ] {
        let (code, out, err) = turntable_in(&d, args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?}: no escape codes written");
        assert!(err.contains("--record"), "{args:?}: {err}");
    }
    assert_eq!(
        std::fs::read_to_string(d.join("s.toml")).unwrap(),
        Scene::default_scene().to_toml()
    );
    use turntable::scene::Scene;
}

/// A recording names a scene file by its absolute path, quoted when it holds blanks, so it
/// replays from any folder.
#[test]
fn a_recorded_scene_path_replays_from_anywhere() {
    let d = dir("rec scene");
    let mut scene = turntable::scene::Scene::preset("B").unwrap();
    scene.name = "my B".into();
    std::fs::write(d.join("my scene.toml"), scene.to_toml()).unwrap();
    let abs = d.join("my scene.toml").display().to_string();
    let script = format!(
        "# turntable key script\n# replay: --scene {}\nsnapshot\n",
        turntable::script::quote_word(&abs)
    );
    let elsewhere = dir("elsewhere");
    std::fs::write(elsewhere.join("rec.keys"), script).unwrap();
    let (code, out, err) = turntable_in(
        &std::env::temp_dir(),
        &["replay", elsewhere.join("rec.keys").to_str().unwrap()],
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("my B"), "{out}");
}

/// Snapshots go out as they are taken: a writer that fails after the first one stops the
/// replay there (nothing is held back to the end).
#[test]
fn replay_streams_its_snapshots() {
    struct FailAfter(usize, Vec<u8>);
    impl Write for FailAfter {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            if self.1.len() >= self.0 {
                return Err(std::io::Error::other("full"));
            }
            self.1.extend_from_slice(buf);
            Ok(buf.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    use turntable::app::App;
    use turntable::replay::{Options, replay_to};
    use turntable::scene::Scene;
    use turntable::script::parse;

    let steps = parse("snapshot one\ntick 2\nsnapshot two\nsnapshot three").unwrap();
    let app = App::new(Scene::default_scene());
    let mut w = FailAfter(100, Vec::new());
    assert!(replay_to(app, &steps, &Options::default(), &mut w).is_err());
    let text = String::from_utf8_lossy(&w.1);
    assert!(text.starts_with("--- snapshot 1: one"), "{text}");
    assert!(!text.contains("snapshot 2"));
}

/// Issue 33 item 1: a write killed midway (SIGKILL, nothing can be cleaned up; SIGTERM)
/// leaves no file at all: the rows go to an unnamed file until they are linked in. (A 56 MB
/// `.NAME.xxx.tmp` used to stay.)
#[test]
fn a_killed_write_leaves_no_temporary_file() {
    for signal in [libc::SIGKILL, libc::SIGTERM] {
        let d = dir(&format!("killed-{signal}"));
        let mut child = Command::new(env!("CARGO_BIN_EXE_turntable"))
            .env("XDG_CONFIG_HOME", "/nonexistent/turntable-tests/config")
            .args([
                "run",
                "--method",
                "rk2-raw",
                "--dt",
                "1e-6",
                "--max-steps",
                "1000000000",
                "--tau-max",
                "1000",
                "--follow",
                "--v0",
                "3",
                "--no-check",
                "--trajectory",
                "big.csv",
            ])
            .current_dir(&d)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        // Until a megabyte of rows is in the file being written.
        let start = Instant::now();
        let pid = child.id();
        let written = || {
            std::fs::read_dir(format!("/proc/{pid}/fd"))
                .into_iter()
                .flatten()
                .flatten()
                .filter_map(|e| std::fs::metadata(e.path()).ok())
                .filter(|m| m.is_file())
                .map(|m| m.len())
                .max()
                .unwrap_or(0)
        };
        while written() < 1 << 20 {
            assert!(start.elapsed() < Duration::from_secs(30), "no rows written");
            assert!(child.try_wait().unwrap().is_none(), "ended early");
            std::thread::sleep(Duration::from_millis(10));
        }
        // SAFETY: a signal to our child.
        unsafe { libc::kill(pid as i32, signal) };
        let status = child.wait().unwrap();
        assert!(!status.success());
        let left: Vec<_> = std::fs::read_dir(&d)
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert!(left.is_empty(), "signal {signal}: {left:?}");
        std::fs::remove_dir_all(&d).unwrap();
    }
}

/// Where the filesystem has no unnamed files the temporary is named `.NAME.PID.N.tmp`: gone
/// on every error (the output dropped), and one left by a killed process (its PID no longer
/// alive) is removed by the next write of that name; a live process's is kept.
#[test]
fn named_temporaries_are_removed_and_stale_ones_swept() {
    let d = dir("named");
    let dest = d.join("out.csv");
    let temporaries = || -> Vec<String> {
        std::fs::read_dir(&d)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(".out.csv.") && n.ends_with(".tmp"))
            .collect()
    };
    let mut out = files::Output::create_in(&dest, false, false).unwrap();
    out.write_all(b"rows").unwrap();
    assert_eq!(temporaries().len(), 1);
    drop(out);
    assert!(temporaries().is_empty() && !dest.exists());
    let mut out = files::Output::create_in(&dest, false, false).unwrap();
    out.write_all(b"rows").unwrap();
    out.finish().unwrap();
    assert!(temporaries().is_empty());
    assert_eq!(std::fs::read_to_string(&dest).unwrap(), "rows");
    // A process that has ended, and one alive (this one).
    let mut gone = Command::new("true").spawn().unwrap();
    let dead = gone.id();
    gone.wait().unwrap();
    let stale = d.join(format!(".out.csv.{dead}.3.tmp"));
    let alive = d.join(format!(".out.csv.{}.999.tmp", std::process::id()));
    std::fs::write(&stale, "half").unwrap();
    std::fs::write(&alive, "half").unwrap();
    let mut out = files::Output::create_in(&dest, true, false).unwrap();
    assert!(!stale.exists(), "the dead process's temporary is swept");
    assert!(alive.exists(), "a live process's is kept");
    out.write_all(b"new rows").unwrap();
    out.finish().unwrap();
    assert_eq!(std::fs::read_to_string(&dest).unwrap(), "new rows");
    assert_eq!(
        temporaries(),
        vec![alive.file_name().unwrap().to_string_lossy()]
    );
    // The unnamed kind replaces as atomically, and leaves nothing either.
    files::write_atomic(&dest, b"third", true).unwrap();
    assert_eq!(std::fs::read_to_string(&dest).unwrap(), "third");
    std::fs::remove_dir_all(&d).unwrap();
}
