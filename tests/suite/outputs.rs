//! Issue 33 items 1 and 4: one output policy for every command that writes a file, tried
//! over many output paths (new, existing, an input by every spelling, links, devices,
//! folders), with and without `--force`, and the bounds on what a script can make a replay
//! write. Each case is classed by what the policy says must happen, independently of how the
//! program decides it; the counts per class are printed (`--nocapture` shows them).

use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// A command that writes a file: its arguments around the output path, and the files it reads.
struct Writer {
    name: &'static str,
    /// The arguments, `OUT` standing for the output path.
    args: &'static [&'static str],
    /// The flag that takes the output, as errors name it.
    flag: &'static str,
    /// Files (in the case's folder) the command reads.
    inputs: &'static [&'static str],
    /// A file fed to stdin, if any.
    stdin: Option<&'static str>,
    /// The explorer: it writes only with a terminal, so an accepted path ends at "needs a
    /// terminal" with nothing written.
    explorer: bool,
}

const WRITERS: &[Writer] = &[
    Writer {
        name: "replay --asciicast",
        args: &[
            "replay",
            "in.keys",
            "--scene",
            "scene.toml",
            "--theme",
            "theme.toml",
            "--asciicast",
            "OUT",
        ],
        flag: "--asciicast",
        inputs: &["in.keys", "scene.toml", "theme.toml"],
        stdin: None,
        explorer: false,
    },
    Writer {
        name: "replay - --asciicast (script on stdin)",
        args: &["replay", "-", "--asciicast", "OUT"],
        flag: "--asciicast",
        inputs: &["in.keys"],
        stdin: Some("in.keys"),
        explorer: false,
    },
    Writer {
        name: "run --trajectory",
        args: &["run", "--tau-max", "1", "--no-check", "--trajectory", "OUT"],
        flag: "--trajectory",
        inputs: &[],
        stdin: None,
        explorer: false,
    },
    Writer {
        name: "sweep fig6 --out",
        args: &["sweep", "fig6", "--points", "2", "--out", "OUT"],
        flag: "--out",
        inputs: &[],
        stdin: None,
        explorer: false,
    },
    Writer {
        name: "sweep body --out",
        args: &["sweep", "body", "--lengths", "0.1", "--out", "OUT"],
        flag: "--out",
        inputs: &[],
        stdin: None,
        explorer: false,
    },
    Writer {
        name: "plot trajectory --out",
        args: &[
            "plot",
            "trajectory",
            "--scene",
            "scene.toml",
            "--tau-max",
            "1",
            "--out",
            "OUT",
        ],
        flag: "--out",
        inputs: &["scene.toml"],
        stdin: None,
        explorer: false,
    },
    Writer {
        name: "explorer --record",
        args: &[
            "--record",
            "OUT",
            "--scene",
            "scene.toml",
            "--theme",
            "theme.toml",
        ],
        flag: "--record",
        inputs: &["scene.toml", "theme.toml"],
        stdin: None,
        explorer: true,
    },
];

/// What the policy says of an output path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Class {
    /// One of the command's inputs, however spelled: refused, even with --force.
    InputRefused,
    /// An existing file without --force: refused.
    ClobberRefused,
    /// A symbolic link, a folder, a missing folder: refused.
    PathRefused,
    /// Written (new, or replaced with --force, or a device).
    Written,
    /// Accepted by the explorer, which then needs a terminal: nothing written.
    AcceptedNoTerminal,
}

/// A case's folder: the inputs, an existing output `old.out`, a subfolder, links.
fn setup(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("turntable-outputs-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("sub")).unwrap();
    std::fs::write(d.join("in.keys"), "# turntable key script\nx\ntick 2\n").unwrap();
    std::fs::write(
        d.join("scene.toml"),
        turntable::scene::Scene::default_scene().to_toml(),
    )
    .unwrap();
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("themes/dark.toml"),
        d.join("theme.toml"),
    )
    .unwrap();
    std::fs::write(d.join("old.out"), "old").unwrap();
    for input in ["in.keys", "scene.toml", "theme.toml"] {
        std::fs::hard_link(d.join(input), d.join(format!("hard-{input}"))).unwrap();
        std::os::unix::fs::symlink(d.join(input), d.join(format!("link-{input}"))).unwrap();
    }
    std::os::unix::fs::symlink(d.join("old.out"), d.join("link-old.out")).unwrap();
    std::os::unix::fs::symlink(d.join("nowhere"), d.join("dangling.out")).unwrap();
    d
}

/// Every regular file's bytes in `d` (links not followed), by name.
fn snapshot(d: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut m = BTreeMap::new();
    for e in std::fs::read_dir(d).unwrap().flatten() {
        if e.file_type().unwrap().is_file() {
            m.insert(
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            );
        }
    }
    m
}

/// Hidden temporary files left in `d` or `d/sub`.
fn temporaries(d: &Path) -> Vec<String> {
    [d.to_path_buf(), d.join("sub")]
        .iter()
        .flat_map(|d| std::fs::read_dir(d).unwrap().flatten())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.') && n.ends_with(".tmp"))
        .collect()
}

fn run(w: &Writer, d: &Path, out: &str, force: bool) -> (i32, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_turntable"));
    cmd.env("XDG_CONFIG_HOME", "/nonexistent/turntable-tests/config")
        .env("TERM", "xterm")
        .current_dir(d)
        .args(w.args.iter().map(|a| if *a == "OUT" { out } else { a }))
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    if force {
        cmd.arg("--force");
    }
    cmd.stdin(match w.stdin {
        Some(f) => Stdio::from(std::fs::File::open(d.join(f)).unwrap()),
        None => Stdio::null(),
    });
    let o = cmd.output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// An output path and the file it names (by the case folder's names), or what else it is.
#[derive(Clone, Debug)]
enum Target {
    /// A regular file in the folder, named `file`, spelled `spelling`.
    File {
        file: String,
        spelling: String,
    },
    New(String),
    Link(String),
    Device,
    Folder(String),
}

/// `name` in `d`, spelled in one of many ways: plain, `./`, through `sub/..`, from the parent
/// by the folder's name, absolute, or several of these in turn.
fn spell(d: &Path, name: &str, pick: u64) -> String {
    let dir = d.file_name().unwrap().to_string_lossy().into_owned();
    let mut s = name.to_string();
    let mut k = pick;
    for _ in 0..1 + pick % 3 {
        if s.starts_with('/') {
            break;
        }
        s = match k % 5 {
            0 => s,
            1 => format!("./{s}"),
            2 => format!("sub/../{s}"),
            3 => format!("../{dir}/{s}"),
            _ => format!("{}/{s}", d.display()),
        };
        k /= 5;
    }
    s
}

/// The class the policy gives `t` for command `w`.
fn expected(w: &Writer, t: &Target, force: bool) -> Class {
    let accepted = if w.explorer {
        Class::AcceptedNoTerminal
    } else {
        Class::Written
    };
    match t {
        Target::File { file, .. } => {
            let real = file.trim_start_matches("hard-");
            if w.inputs.contains(&real) {
                Class::InputRefused
            } else if !force {
                Class::ClobberRefused
            } else {
                accepted
            }
        }
        Target::New(_) | Target::Device => accepted,
        Target::Link(_) | Target::Folder(_) => Class::PathRefused,
    }
}

fn out_path(t: &Target) -> String {
    match t {
        Target::File { spelling, .. } => spelling.clone(),
        Target::New(p) | Target::Link(p) | Target::Folder(p) => p.clone(),
        Target::Device => "/dev/null".into(),
    }
}

/// Runs `w` on `t` in a fresh folder and checks what happened against the class.
fn check(w: &Writer, t: &Target, force: bool, tag: &str) -> Class {
    let d = setup(tag);
    let t = match t {
        // Spellings that need the folder's own name are made here.
        Target::File { file, spelling } => Target::File {
            file: file.clone(),
            spelling: spell(&d, file, spelling.parse().unwrap_or(0)),
        },
        t => t.clone(),
    };
    let out = out_path(&t);
    let class = expected(w, &t, force);
    let before = snapshot(&d);
    let (code, err) = run(w, &d, &out, force);
    let what = format!("{} → {out:?} (force {force}): {class:?}", w.name);
    let after = snapshot(&d);
    assert!(temporaries(&d).is_empty(), "{what}: temporaries left");
    // The inputs are never touched.
    for input in w.inputs {
        assert_eq!(before[*input], after[*input], "{what}: {input} changed");
    }
    match class {
        Class::InputRefused => {
            assert_eq!(code, 2, "{what}: {err}");
            assert!(
                err.contains(w.flag) && err.contains("reads"),
                "{what}: {err}"
            );
            assert_eq!(before, after, "{what}");
        }
        Class::ClobberRefused => {
            assert_eq!(code, 2, "{what}: {err}");
            assert!(err.contains("exists; --force replaces it"), "{what}: {err}");
            assert_eq!(before, after, "{what}");
        }
        Class::PathRefused => {
            assert_eq!(code, 2, "{what}: {err}");
            assert!(err.contains(w.flag), "{what}: {err}");
            assert_eq!(before, after, "{what}");
        }
        Class::AcceptedNoTerminal => {
            assert_eq!(code, 2, "{what}: {err}");
            assert!(err.contains("needs a terminal"), "{what}: {err}");
            assert_eq!(before, after, "{what}");
        }
        Class::Written => {
            assert_eq!(code, 0, "{what}: {err}");
            match &t {
                Target::File { file, .. } => {
                    assert_ne!(after[file.as_str()], b"old", "{what}: replaced");
                    assert!(!after[file.as_str()].is_empty(), "{what}");
                }
                Target::New(p) => {
                    let name = Path::new(p).file_name().unwrap().to_string_lossy();
                    let written = std::fs::read(d.join(p)).unwrap();
                    assert!(!written.is_empty(), "{what}");
                    if !p.contains('/') {
                        assert!(after.contains_key(name.as_ref()), "{what}");
                    }
                }
                _ => {}
            }
        }
    }
    std::fs::remove_dir_all(&d).unwrap();
    class
}

/// A small deterministic generator (xorshift64*).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
}

#[test]
fn every_writing_command_follows_the_one_output_policy() {
    let mut counts: BTreeMap<Class, usize> = BTreeMap::new();
    let mut rng = Rng(0x7475_726e_7461_626c);
    let mut cases = 0;
    for (k, w) in WRITERS.iter().enumerate() {
        let mut targets = vec![
            Target::New("new.out".into()),
            Target::New("sub/new.out".into()),
            Target::Device,
            Target::Folder("sub".into()),
            Target::Folder("nodir/x.out".into()),
            Target::Link("link-old.out".into()),
            Target::Link("dangling.out".into()),
            Target::Link("link-in.keys".into()),
            Target::Link("link-scene.toml".into()),
            Target::Link("link-theme.toml".into()),
        ];
        for file in [
            "old.out",
            "in.keys",
            "scene.toml",
            "theme.toml",
            "hard-in.keys",
            "hard-scene.toml",
            "hard-theme.toml",
        ] {
            // Every spelling kind once, then random mixes; a mix that spells the file as one
            // already tried is the same command on the same folder, and is not run again.
            let mut spelled = BTreeSet::new();
            for pick in (0..5).chain((0..4).map(|_| rng.next() % 125)) {
                if spelled.insert(spell(Path::new("/case"), file, pick)) {
                    targets.push(Target::File {
                        file: file.into(),
                        spelling: pick.to_string(),
                    });
                }
            }
        }
        for (n, t) in targets.iter().enumerate() {
            for force in [false, true] {
                let class = check(w, t, force, &format!("{k}-{n}-{force}"));
                *counts.entry(class).or_default() += 1;
                cases += 1;
            }
        }
    }
    eprintln!(
        "output policy: {cases} cases over {} commands",
        WRITERS.len()
    );
    for (class, n) in &counts {
        eprintln!("  {class:?}: {n}");
    }
    assert!(counts[&Class::InputRefused] > 100);
    assert!(counts[&Class::ClobberRefused] > 30);
    assert!(counts[&Class::Written] > 50);
}

/// The 3-line script: `--asciicast` wrote 783 MB in 60 s. Now a recording stops at a
/// bound, says which (exit 2), and writes nothing: neither the cast nor the SVG beside it, and
/// no temporary. The bound met here is `--svg`'s (1200 screens, ~3600 ticks of a 40x12 screen,
/// ~1 s); the cells bound that stops the 1000x1000 screen is the cast's own, checked
/// where it is counted (`asciicast`'s tests: ~30 s of CPU to draw here), and every bound reaches
/// this command through the same error.
#[test]
fn a_script_cannot_drive_an_unbounded_recording() {
    let d = setup("bounded");
    std::fs::write(
        d.join("big.keys"),
        "# three lines\nresize 40x12\ntick 10000000\n",
    )
    .unwrap();
    let (code, err) = run(
        &Writer {
            name: "replay --asciicast --svg",
            args: &[
                "replay",
                "big.keys",
                "--svg",
                "big.svg",
                "--asciicast",
                "OUT",
            ],
            flag: "--asciicast",
            inputs: &["big.keys"],
            stdin: None,
            explorer: false,
        },
        &d,
        "big.cast",
        false,
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(
            "--svg reached its bound of 1200 screens (two minutes at ten a second); nothing was written to "
        ),
        "{err}"
    );
    assert!(!d.join("big.cast").exists() && !d.join("big.svg").exists());
    assert!(temporaries(&d).is_empty());
    std::fs::remove_dir_all(&d).unwrap();
}

/// Every output a script drives stops at its bound: for many scripts and bounds, what got
/// through is a prefix of the unbounded output, no longer than the bound, and the error names
/// the bound.
#[test]
fn bounded_outputs_stop_at_their_bound_and_say_so() {
    use turntable::files::{Capped, bound_reached};
    use turntable::replay::{Options, replay_cast, replay_to};
    let app = || turntable::app::App::new(turntable::scene::Scene::default_scene());
    let scripts = [
        "tick 30\nsnapshot a\nx*3\nsnapshot b",
        "resize 120x40\nsnapshot\ntick 10\nsnapshot",
        "?\nsnapshot help\nq",
        "resize 10x5\ntick 100\nsnapshot",
    ];
    let (mut bounded, mut whole) = (0, 0);
    let mut rng = Rng(33);
    for (plain, ansi) in [(false, false), (false, true), (true, false)] {
        let opts = Options {
            plain,
            ansi,
            ..Options::default()
        };
        for text in scripts {
            let steps = turntable::script::parse(text).unwrap();
            let mut full = Vec::new();
            replay_to(app(), &steps, &opts, &mut full).unwrap();
            let mut full_cast = Vec::new();
            if !plain {
                replay_cast(
                    app(),
                    &steps,
                    &opts,
                    &mut Vec::new(),
                    &mut full_cast,
                    "t",
                    None,
                )
                .unwrap();
            }
            // Exactly enough, one byte short, then anywhere.
            let pick = |i: u64, len: usize, rng: &mut Rng| match i {
                0 => len as u64,
                1 => len as u64 - 1,
                _ => rng.next() % (len as u64 + 2),
            };
            for i in 0..8 {
                let cap = pick(i, full.len(), &mut rng);
                let mut out = Capped::new(Vec::new(), cap, "the replay's output on stdout");
                let r = replay_to(app(), &steps, &opts, &mut out);
                let got = out.into_inner();
                assert!(got.len() as u64 <= cap && full.starts_with(&got));
                match r {
                    Ok(()) => {
                        assert_eq!(got, full);
                        whole += 1;
                    }
                    Err(e) => {
                        let m = bound_reached(&e).expect("the bound's error");
                        assert!(m.contains(&format!("({cap} bytes)")), "{m}");
                        bounded += 1;
                    }
                }
                if plain {
                    continue;
                }
                let cap = pick(i, full_cast.len(), &mut rng);
                let mut cast = Capped::new(Vec::new(), cap, "--asciicast");
                let r = replay_cast(app(), &steps, &opts, &mut Vec::new(), &mut cast, "t", None);
                let got = cast.into_inner();
                assert!(got.len() as u64 <= cap && full_cast.starts_with(&got));
                match r {
                    Ok(()) => {
                        assert_eq!(got, full_cast);
                        whole += 1;
                    }
                    Err(e) => {
                        let m = bound_reached(&e).expect("the bound's error");
                        assert!(m.starts_with("--asciicast reached its bound"), "{m}");
                        bounded += 1;
                    }
                }
            }
        }
    }
    eprintln!("bounded outputs: {bounded} stopped at their bound, {whole} within it");
    assert!(bounded > 20 && whole > 0);
    let _ = std::io::stderr().flush();
}
