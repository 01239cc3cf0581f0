//! The configuration file and the user's themes (issue 21), as a user meets them: the binary
//! run with XDG_CONFIG_HOME set to a folder the test writes (never the user's own).

use crate::common;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A fresh `XDG_CONFIG_HOME` for one test, with `turntable/config.toml` holding `config` (if
/// any) and `turntable/themes/NAME.toml` for each of `themes`.
fn home(tag: &str, config: Option<&str>, themes: &[(&str, &str)]) -> PathBuf {
    let d = std::env::temp_dir().join(format!("turntable-config-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("turntable/themes")).unwrap();
    if let Some(c) = config {
        std::fs::write(d.join("turntable/config.toml"), c).unwrap();
    }
    for (name, text) in themes {
        std::fs::write(d.join(format!("turntable/themes/{name}.toml")), text).unwrap();
    }
    d
}

/// `turntable ARGS` with XDG_CONFIG_HOME = `xdg`, stdin not a terminal: code, stdout, stderr.
fn run(xdg: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .args(args)
        .env("XDG_CONFIG_HOME", xdg)
        .env_remove("NO_COLOR")
        .stdin(Stdio::null())
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// The dark theme under another name, with a background no built-in theme has.
fn my_theme(name: &str) -> String {
    include_str!("../../themes/dark.toml")
        .replace("name = \"dark\"", &format!("name = \"{name}\""))
        .replace("#11151c", "#010203")
}

const NEEDS_TTY: &str = "the explorer needs a terminal";

#[test]
fn a_bad_configuration_exits_2_naming_the_file_and_the_key() {
    for (tag, text, key) in [
        (
            "unknown",
            "fps = 30\ncolour = \"red\"\n",
            "unknown key `colour`",
        ),
        ("type", "fps = \"fast\"\n", "key `fps`: expected an integer"),
        (
            "range",
            "fps = 500\n",
            "key `fps`: must lie in 1..=240, got 500",
        ),
        ("marker", "marker = \"dots\"\n", "key `marker`:"),
        ("mouse", "mouse = \"no\"\n", "key `mouse`:"),
        (
            "speed",
            "speed = 3\n",
            "key `speed`: must be a power of two from 1/64 to 256, got 3",
        ),
        (
            "paused",
            "paused = 1\n",
            "key `paused`: expected true or false",
        ),
        (
            "units",
            "[units]\nmu = 0.1\n",
            "key `units`: missing field `rpm`",
        ),
        (
            "theme",
            "theme = \"nope\"\n",
            "key `theme`: unknown theme 'nope'",
        ),
        (
            "theme-file",
            "theme = \"gone.toml\"\n",
            "key `theme`: theme file ",
        ),
        ("syntax", "fps = \n", "line 1: "),
    ] {
        let d = home(tag, Some(text), &[]);
        let file = d.join("turntable/config.toml");
        let (code, out, err) = run(&d, &[]);
        assert_eq!(code, 2, "{tag}: {err}");
        assert!(out.is_empty(), "{tag}");
        assert_eq!(err.lines().count(), 1, "{tag}: {err}");
        let head = format!("error: config file {}: ", file.display());
        assert!(err.starts_with(&head), "{tag}: {err}");
        assert!(err.contains(key), "{tag}: {err}");
        std::fs::remove_dir_all(&d).unwrap();
    }
    // Unreadable: a folder where the file should be, and bytes that are not UTF-8.
    for (tag, make) in [
        (
            "dir",
            (|p: &Path| std::fs::create_dir(p).unwrap()) as fn(&Path),
        ),
        ("binary", |p: &Path| {
            std::fs::write(p, [0xff, 0xfe]).unwrap()
        }),
    ] {
        let d = home(tag, None, &[]);
        make(&d.join("turntable/config.toml"));
        let (code, _, err) = run(&d, &[]);
        assert_eq!(code, 2, "{tag}: {err}");
        assert!(err.starts_with("error: config file "), "{tag}: {err}");
        std::fs::remove_dir_all(&d).unwrap();
    }
}

#[test]
fn a_good_configuration_gets_as_far_as_the_terminal() {
    let mine = my_theme("mine");
    let d = home(
        "good",
        Some(
            "theme = \"mine\"\nfps = 60\nmouse = false\nmarker = \"ascii\"\n[units]\nmu = 0.15\nrpm = 33.3\n",
        ),
        &[("mine", &mine)],
    );
    let (code, _, err) = run(&d, &[]);
    assert_eq!(code, 2);
    assert!(err.contains(NEEDS_TTY), "{err}");
    // No configuration at all (XDG_CONFIG_HOME unset, HOME without one) is no error either.
    let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .env_remove("XDG_CONFIG_HOME")
        .env("HOME", &d)
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&out.stderr).contains(NEEDS_TTY));
    std::fs::remove_dir_all(&d).unwrap();
}

/// Without XDG_CONFIG_HOME the file is `~/.config/turntable/config.toml`.
#[test]
fn without_xdg_config_home_the_file_is_under_home() {
    let d = std::env::temp_dir().join(format!("turntable-config-home-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join(".config/turntable")).unwrap();
    std::fs::write(d.join(".config/turntable/config.toml"), "fps = 0\n").unwrap();
    for xdg in [None, Some(""), Some("relative/dir")] {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_turntable"));
        match xdg {
            None => cmd.env_remove("XDG_CONFIG_HOME"),
            Some(x) => cmd.env("XDG_CONFIG_HOME", x),
        };
        let out = cmd.env("HOME", &d).stdin(Stdio::null()).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        let want = format!(
            "error: config file {}: key `fps`",
            d.join(".config/turntable/config.toml").display()
        );
        assert!(err.starts_with(&want), "{xdg:?}: {err}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn theme_names_list_the_built_in_and_the_users() {
    let d = home(
        "list",
        None,
        &[("zebra", &my_theme("zebra")), ("mine", &my_theme("mine"))],
    );
    let dir = d.join("turntable/themes");
    let all = format!(
        "(built-in: dark, light, high-contrast, mono; yours in {}: mine, zebra; or a path to a .toml file)",
        dir.display()
    );
    let (code, _, err) = run(&d, &["--theme", "nope"]);
    assert_eq!(code, 2);
    assert_eq!(err, format!("error: unknown theme 'nope' {all}\n"));
    // Listing them is asked for: on stdout, exit 0.
    let (code, out, err) = run(&d, &["--theme"]);
    assert_eq!((code, err.as_str()), (0, ""));
    assert_eq!(out, format!("themes: {}\n", &all[1..all.len() - 1]));
    // A user's theme by name, and a flag over a bad configured theme: on to the terminal.
    for args in [&["--theme", "zebra"][..], &["--theme", "light"]] {
        let (code, _, err) = run(&d, args);
        assert_eq!(code, 2);
        assert!(err.contains(NEEDS_TTY), "{args:?}: {err}");
    }
    std::fs::write(d.join("turntable/config.toml"), "theme = \"nope\"\n").unwrap();
    let (_, _, err) = run(&d, &["--theme", "mine"]);
    assert!(err.contains(NEEDS_TTY), "the flag wins: {err}");
    // A broken user theme is reported as its file.
    std::fs::write(dir.join("broken.toml"), "name = 3\n").unwrap();
    let (code, _, err) = run(&d, &["--theme", "broken"]);
    assert_eq!(code, 2);
    assert!(
        err.starts_with(&format!(
            "error: theme file {}: line 1",
            dir.join("broken.toml").display()
        )),
        "{err}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// `replay` reads no configuration: a configuration (even a broken one) and user themes,
/// one of them named `dark`, change none of its bytes, with or without colour.
#[test]
fn replay_is_independent_of_the_configuration() {
    let script = "resize 60x20\ntick 40\nsnapshot a\nf\ntick 5\nsnapshot b\n";
    let keys = std::env::temp_dir().join(format!("turntable-config-{}.keys", std::process::id()));
    std::fs::write(&keys, script).unwrap();
    let k = keys.to_str().unwrap();
    let empty = home("replay-empty", None, &[]);
    let dark = my_theme("dark");
    let configs = [
        "theme = \"light\"\nmarker = \"ascii\"\nmouse = false\nfps = 7\n[units]\nmu = 0.3\nrpm = 45\ng = 9.8\n",
        "theme = \"mine\"\nmarker = \"block\"\n",
        "this is not a configuration\n",
    ];
    for (i, c) in configs.iter().enumerate() {
        let d = home(
            &format!("replay-{i}"),
            Some(c),
            &[("dark", &dark), ("mine", &dark)],
        );
        for ansi in [&[][..], &["--ansi"]] {
            let args: Vec<&str> = ["replay", k].iter().chain(ansi).copied().collect();
            let want = run(&empty, &args);
            assert_eq!(want.0, 0, "{}", want.2);
            assert_eq!(run(&d, &args), want, "config {i} {ansi:?}");
        }
        // A theme of yours by name is not found there: it depends on no folder.
        let (code, _, err) = run(&d, &["replay", k, "--theme", "mine"]);
        assert_eq!(code, 2);
        assert!(err.contains("replay reads no configuration"), "{err}");
        std::fs::remove_dir_all(&d).unwrap();
    }
    // The SI units, the marker and the theme would show on these screens had they been read.
    let plain = run(&empty, &["replay", k]).1;
    assert!(plain.contains('⠀') || plain.contains('⣀') || plain.contains('⠉'));
    assert!(!plain.contains(" m/s") && !plain.contains("rpm"));
    std::fs::remove_dir_all(&empty).unwrap();
    std::fs::remove_file(&keys).unwrap();
}

/// The explorer on a pseudo-terminal of its own with XDG_CONFIG_HOME = `xdg`, quit with `q`
/// after its first frame: everything it wrote (None where no pty can be opened).
fn explorer_output(xdg: &Path, args: &[&str]) -> Option<Vec<u8>> {
    let (master, slave) = common::openpty(80, 24)?;
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_turntable"));
    cmd.args(args)
        .env("XDG_CONFIG_HOME", xdg)
        .env("TERM", "xterm-256color")
        .env("COLORTERM", "truecolor")
        .env("LANG", "C.UTF-8")
        .env_remove("NO_COLOR")
        .env_remove("LC_ALL");
    common::on_pty(&mut cmd, slave);
    let mut child = cmd.spawn().unwrap();
    drop(cmd);
    let writer = std::fs::File::from(master.try_clone().unwrap());
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut file = std::fs::File::from(master);
        let mut buf = [0; 4096];
        // Ends with an error (EIO) once the explorer has exited and closed the pty.
        while let Ok(n @ 1..) = file.read(&mut buf) {
            if tx.send(buf[..n].to_vec()).is_err() {
                break;
            }
        }
    });
    let mut seen = Vec::new();
    let start = Instant::now();
    let mut quit = false;
    let mut answered = 0;
    loop {
        while let Ok(chunk) = rx.try_recv() {
            seen.extend(chunk);
        }
        // Answer the cursor queries of its frame pacing, as a terminal does (unanswered, each
        // waits out crossterm's 2 s).
        let asked = seen.windows(4).filter(|w| w == b"\x1b[6n").count();
        for _ in answered..asked {
            use std::io::Write;
            let _ = (&writer).write_all(b"\x1b[1;1R");
        }
        answered = asked;
        if child.try_wait().unwrap().is_some() {
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "the explorer never ended"
        );
        // Quit once the first frame is out (the alternate screen, then the readouts).
        if !quit && has(&seen, b"\x1b[?1049h") && has(&seen, "ξ".as_bytes()) {
            use std::io::Write;
            (&writer).write_all(b"q").unwrap();
            quit = true;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    while let Ok(chunk) = rx.recv_timeout(Duration::from_millis(200)) {
        seen.extend(chunk);
    }
    Some(seen)
}

fn has(out: &[u8], needle: &[u8]) -> bool {
    out.windows(needle.len()).any(|w| w == needle)
}

const MOUSE_ON: &[u8] = b"\x1b[?1000h";
/// The background of [`my_theme`], in 24-bit colour.
const MY_BACKGROUND: &[u8] = b"48;2;1;2;3m";

/// The configuration's theme (one of the user's) and mouse reach the explorer; flags win.
#[test]
fn the_explorer_takes_the_configuration_and_flags_win() {
    let mine = my_theme("mine");
    let d = home(
        "explorer",
        Some("theme = \"mine\"\nmouse = false\n"),
        &[("mine", &mine)],
    );
    let Some(out) = explorer_output(&d, &[]) else {
        return;
    };
    assert!(has(&out, MY_BACKGROUND), "the configured theme");
    assert!(!has(&out, MOUSE_ON), "mouse = false");
    let out = explorer_output(&d, &["--theme", "light", "--mouse"]).unwrap();
    assert!(!has(&out, MY_BACKGROUND), "--theme wins");
    assert!(has(&out, MOUSE_ON), "--mouse wins");
    // Slow motion, paused, from the configuration; the flag's speed wins.
    std::fs::write(
        d.join("turntable/config.toml"),
        "speed = 0.25\npaused = true\n",
    )
    .unwrap();
    let out = explorer_output(&d, &[]).unwrap();
    assert!(has(&out, "×1/4 ❚❚".as_bytes()), "speed and paused");
    let out = explorer_output(&d, &["--speed", "2"]).unwrap();
    assert!(has(&out, "×2 ❚❚".as_bytes()), "--speed wins");
    let (code, _, err) = run(&d, &["--speed", "0.3"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("'0.3' is not a power of two"), "{err}");
    // A user theme named as a built-in replaces it, by name and as the default.
    std::fs::write(d.join("turntable/config.toml"), "").unwrap();
    std::fs::write(d.join("turntable/themes/dark.toml"), my_theme("dark")).unwrap();
    let out = explorer_output(&d, &[]).unwrap();
    assert!(has(&out, MY_BACKGROUND), "the user's dark");
    assert!(has(&out, MOUSE_ON), "the mouse by default");
    std::fs::remove_dir_all(&d).unwrap();
}
