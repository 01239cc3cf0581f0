//! SciPy measured in the run (issue 42): the certified escape speed found by SciPy's compiled
//! DOP853 (`docs/scipy-escape.py`, the same search and certificates) against `turntable`'s own,
//! on the same points, each side's search timed without its process start (Python's start-up
//! and its import of SciPy; this process's own) — or, where the interpreter with SciPy is not
//! found, not measured at all: never a constant. The interpreter is the bench's `--python`
//! (python3 by default); each of its runs is a child process given at most [`POINT_LIMIT`].

use super::{median, timed};
use crate::engine::solve::{escape_speed, solve_certified};
use crate::engine::{Initial, Settings};
use crate::error::Error;
use serde::Serialize;
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The script, in the binary: the bench runs it wherever it is started from.
const SCRIPT: &str = include_str!("../../docs/scipy-escape.py");
/// The escape speed's bracket, as `turntable escape --vtol 1e-8`.
const VTOL: f64 = 1e-8;
/// The longest one point's script may run (wall time: about 2–6 s of CPU a point here, but
/// over 300 s of wall time at a load of 15 on 2 cores): past it the child is killed and SciPy
/// not measured.
pub const POINT_LIMIT: Duration = Duration::from_secs(900);

/// Both sides on the same points.
#[derive(Clone, Debug, Serialize)]
pub struct Scipy {
    /// The SciPy version the script ran with.
    pub version: String,
    /// (ξ0, φ) of each point: Fig. 5's four ξ0 × its angles.
    pub points: Vec<(f64, f64)>,
    /// SciPy's search per point, CPU ms from its first run to its verdict (its own clock), and
    /// the whole interpreter process's wall time.
    pub scipy_ms: Vec<f64>,
    pub scipy_process_ms: Vec<f64>,
    /// Of `scipy_ms`, the search before the certificate.
    pub scipy_search_ms: Vec<f64>,
    /// SciPy's right-hand-side evaluations per point.
    pub scipy_rhs: Vec<u64>,
    /// Points SciPy certified.
    pub scipy_certified: usize,
    /// `solve_certified` at the default settings in this process (the least of a few runs), and
    /// the search alone (`escape_speed`), and its right-hand-side evaluations.
    pub ours_ms: Vec<f64>,
    pub ours_search_ms: Vec<f64>,
    pub ours_rhs: Vec<u64>,
}

impl Scipy {
    /// SciPy's median over ours, start-up excluded on both sides.
    pub fn ratio(&self) -> f64 {
        median(&mut self.scipy_ms.clone()) / median(&mut self.ours_ms.clone())
    }
    /// The same for the search alone, certificates left out on both sides.
    pub fn search_ratio(&self) -> f64 {
        median(&mut self.scipy_search_ms.clone()) / median(&mut self.ours_search_ms.clone())
    }
}

/// What the script printed for one point.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// CPU ms from its first run to its verdict, and of it the search's.
    pub ms: f64,
    pub search_ms: f64,
    pub certified: bool,
    pub rhs: u64,
    pub version: String,
}

/// The script's line read: `... certified True runs N rhs N scipy V ms X search-ms Y`, or None
/// when any of it is missing or not a number.
pub fn parse(text: &str) -> Option<Point> {
    let word = |w: &str| {
        let mut it = text.split_whitespace();
        it.find(|x| *x == w)?;
        it.next()
    };
    let ms: f64 = word("ms")?.parse().ok()?;
    let search_ms: f64 = word("search-ms")?.parse().ok()?;
    let certified = match word("certified")? {
        "True" => true,
        "False" => false,
        _ => return None,
    };
    let version = word("scipy")?;
    let clean = |c: char| c.is_ascii_alphanumeric() || ".+-".contains(c);
    (ms.is_finite() && ms >= 0.0 && search_ms.is_finite() && search_ms >= 0.0)
        .then_some(())
        .filter(|()| version.chars().all(clean) && version.len() <= 32)?;
    Some(Point {
        ms,
        search_ms,
        certified,
        rhs: word("rhs")?.parse().ok()?,
        version: version.to_owned(),
    })
}

/// Waits for `child` at most `limit`, killing it past that (None).
fn wait_at_most(mut child: Child, limit: Duration) -> Option<Output> {
    let t = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(_)) => return child.wait_with_output().ok(),
            Ok(None) if t.elapsed() < limit => std::thread::sleep(Duration::from_millis(20)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                return None;
            }
        }
    }
}

/// Why SciPy was not measured, in the bench's words.
fn not_found(python: &Path, why: &str) -> String {
    format!("{} {why}", python.display())
}

/// The least time the import check is given, whatever the script's limit: a loaded machine
/// starts an interpreter slowly, and a slow start is not a missing SciPy.
const IMPORT_LIMIT: Duration = Duration::from_secs(30);

/// Starts `cmd`, again while the executable is busy (ETXTBSY: a just-written interpreter held
/// open for a moment by another thread's fork).
fn spawn(cmd: &mut Command) -> std::io::Result<std::process::Child> {
    let mut tries = 0;
    loop {
        match cmd.spawn() {
            Err(e) if e.raw_os_error() == Some(26) && tries < 50 => {
                tries += 1;
                std::thread::sleep(Duration::from_millis(10));
            }
            r => return r,
        }
    }
}

/// One point through the script: what it printed, and the process's wall ms; or why not.
fn scipy_point(python: &Path, xi0: f64, phi: f64, limit: Duration) -> Result<(Point, f64), String> {
    use std::io::Write as _;
    let t = Instant::now();
    let mut child = spawn(
        Command::new(python)
            .args(["-", &xi0.to_string(), &phi.to_string(), &VTOL.to_string()])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null()),
    )
    .map_err(|_| not_found(python, "could not be started"))?;
    // The script is read whole before it runs: a pipe's buffer holds it.
    let fed = child
        .stdin
        .take()
        .is_some_and(|mut i| i.write_all(SCRIPT.as_bytes()).is_ok());
    let out = wait_at_most(child, limit);
    let wall = t.elapsed().as_secs_f64() * 1e3;
    let Some(out) = out else {
        return Err(not_found(
            python,
            &format!("ran the script over {} s", limit.as_secs_f64()),
        ));
    };
    if !fed || !out.status.success() {
        return Err(not_found(python, "failed to run docs/scipy-escape.py"));
    }
    parse(&String::from_utf8_lossy(&out.stdout))
        .map(|p| (p, wall))
        .ok_or_else(|| not_found(python, "printed what docs/scipy-escape.py does not"))
}

/// What became of the comparison.
#[derive(Clone, Debug, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Versus {
    Measured(Scipy),
    /// The interpreter with SciPy was not found, or its script failed: why.
    NotFound(String),
    /// No interpreter given (a test's bench): not tried.
    NotRun,
}

/// The comparison on Fig. 5's four ξ0 × `angles` angles, through `python` (None: not tried).
pub fn compare(
    python: Option<&Path>,
    angles: usize,
    reps: usize,
    limit: Duration,
) -> Result<Versus, Error> {
    let Some(python) = python else {
        return Ok(Versus::NotRun);
    };
    let found = spawn(
        Command::new(python)
            .args(["-c", "import scipy.integrate"])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null()),
    )
    .ok()
    .and_then(|c| wait_at_most(c, limit.max(IMPORT_LIMIT)))
    .is_some_and(|o| o.status.success());
    if !found {
        return Ok(Versus::NotFound(not_found(
            python,
            "could not import scipy.integrate",
        )));
    }
    let mut c = Scipy {
        version: String::new(),
        points: Vec::new(),
        scipy_ms: Vec::new(),
        scipy_process_ms: Vec::new(),
        scipy_search_ms: Vec::new(),
        scipy_rhs: Vec::new(),
        scipy_certified: 0,
        ours_ms: Vec::new(),
        ours_search_ms: Vec::new(),
        ours_rhs: Vec::new(),
    };
    for xi0 in [0.8, 0.5, 0.2, 0.001] {
        for k in 0..angles {
            let phi = crate::analysis::angle(k, angles);
            let (p, wall) = match scipy_point(python, xi0, phi, limit) {
                Ok(p) => p,
                Err(why) => return Ok(Versus::NotFound(why)),
            };
            let at = |v0: f64| Initial::velocity(xi0, phi, v0);
            let solve = |s| escape_speed(xi0, phi, s, VTOL);
            let (r, ours) = timed(reps.max(3), || {
                solve_certified(Settings::default(), solve, at)
            });
            c.ours_rhs.push(r?.0.rhs_evals);
            let (r, ours_search) = timed(reps.max(3), || solve(Settings::default()));
            r?;
            c.points.push((xi0, phi));
            c.scipy_ms.push(p.ms);
            c.scipy_search_ms.push(p.search_ms);
            c.scipy_rhs.push(p.rhs);
            c.scipy_process_ms.push(wall);
            c.scipy_certified += usize::from(p.certified);
            c.version = p.version;
            c.ours_search_ms.push(ours_search);
            c.ours_ms.push(ours);
        }
    }
    Ok(Versus::Measured(c))
}

/// The bench's lines: the ratio measured here and how, or that it was not measured.
pub fn lines(o: &mut String, v: &Versus) {
    use std::fmt::Write as _;
    match v {
        Versus::Measured(c) => {
            let ours = median(&mut c.ours_ms.clone());
            let theirs = median(&mut c.scipy_ms.clone());
            let process = median(&mut c.scipy_process_ms.clone());
            let rhs = |v: &[u64]| median(&mut v.iter().map(|&x| x as f64).collect::<Vec<_>>());
            let _ = writeln!(
                o,
                "    SciPy {} compiled DOP853, import excluded (docs/scipy-escape.py: the same search and certificates; {} points, {} certified): {theirs:.0} ms median CPU from its first run (the whole process {process:.0} ms wall), against turntable's {ours:.2} ms in-process: {:.0}×   {}",
                c.version,
                c.points.len(),
                c.scipy_certified,
                c.ratio(),
                super::output::goal_at_least(c.ratio(), 100.0, "×")
            );
            let _ = writeln!(
                o,
                "      the search alone (certificates left out on both sides): {:.0}×; RHS evaluations a point {:.0} against {:.0} (the certificate's runs in full crawl to the rim in explicit steps: SciPy has no implicit end game)",
                c.search_ratio(),
                rhs(&c.scipy_rhs),
                rhs(&c.ours_rhs),
            );
        }
        Versus::NotFound(why) => {
            let _ = writeln!(o, "    SciPy not found: not measured ({why})");
        }
        Versus::NotRun => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LINE: &str = "v_escape 0.6078236473  bracket 0.60782364 0.60782365  certified True  runs 56  rhs 1231464  scipy 1.17.1  ms 2657.3  search-ms 34.7\n";

    #[test]
    fn the_scripts_line_is_read() {
        assert_eq!(
            parse(LINE),
            Some(Point {
                ms: 2657.3,
                search_ms: 34.7,
                certified: true,
                rhs: 1_231_464,
                version: "1.17.1".into(),
            })
        );
        let uncertified = LINE.replace("True", "False");
        assert_eq!(parse(&uncertified).map(|p| p.certified), Some(false));
        for bad in [
            "",
            "Traceback (most recent call last):",
            &LINE.replace("ms 2657.3", "ms nan"),
            &LINE.replace("ms 2657.3", "ms -1"),
            &LINE.replace("True", "maybe"),
            &LINE.replace("search-ms 34.7", "search-ms"),
            &LINE.replace("1.17.1", "1.17\u{1b}[2J"),
            &LINE.replace("rhs 1231464", "rhs many"),
        ] {
            assert_eq!(parse(bad), None, "{bad:?}");
        }
    }

    /// A fake interpreter: a shell script that swallows the script fed to it and prints `body`.
    fn fake(dir: &Path, name: &str, body: &str) -> std::path::PathBuf {
        use std::os::unix::fs::PermissionsExt as _;
        let path = dir.join(name);
        std::fs::write(&path, format!("#!/bin/sh\ncat > /dev/null\n{body}\n")).unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
        path
    }

    fn said(v: &Versus) -> String {
        let mut o = String::new();
        lines(&mut o, v);
        o
    }

    #[test]
    fn without_scipy_the_bench_says_not_measured() {
        let dir = tempfile::tempdir().unwrap();
        let limit = Duration::from_secs(60);
        let absent = dir.path().join("no-python");
        let failing = fake(dir.path(), "failing", "exit 1");
        let garbled = fake(dir.path(), "garbled", "echo hello");
        for (python, why) in [
            (absent, "could not import scipy.integrate"),
            (failing, "could not import scipy.integrate"),
            (garbled, "printed what docs/scipy-escape.py does not"),
        ] {
            let v = compare(Some(&python), 1, 0, limit).unwrap();
            let text = said(&v);
            assert!(
                text.starts_with("    SciPy not found: not measured (") && text.contains(why),
                "{text}"
            );
            assert!(!text.contains('×'), "{text}");
        }
        assert!(matches!(compare(None, 1, 0, limit), Ok(Versus::NotRun)));
    }

    #[test]
    fn a_scripts_figures_are_measured_against_ours() {
        let dir = tempfile::tempdir().unwrap();
        let python = fake(dir.path(), "python", &format!("printf '{}'", LINE.trim()));
        let Versus::Measured(c) = compare(Some(&python), 1, 0, Duration::from_secs(60)).unwrap()
        else {
            panic!("not measured")
        };
        assert_eq!((c.points.len(), c.scipy_certified), (4, 4));
        assert_eq!(c.version, "1.17.1");
        assert!(c.scipy_ms.iter().all(|&ms| ms == 2657.3));
        assert!(c.ours_ms.iter().all(|&ms| ms > 0.0 && ms < 2657.3));
        assert!(c.ours_rhs.iter().all(|&n| n > 1000));
        let text = said(&Versus::Measured(c.clone()));
        assert!(
            text.contains("SciPy 1.17.1 compiled DOP853, import excluded")
                && text.contains(&format!("{:.0}×", c.ratio())),
            "{text}"
        );
    }

    #[test]
    fn a_script_that_runs_over_its_limit_is_stopped() {
        let dir = tempfile::tempdir().unwrap();
        // Answers the import check at once, then hangs on the script.
        let python = fake(
            dir.path(),
            "slow",
            "[ \"$1\" = - ] && exec sleep 600\nexit 0",
        );
        let v = compare(Some(&python), 1, 0, Duration::from_millis(300)).unwrap();
        assert!(
            said(&v).contains("ran the script over 0.3 s"),
            "{}",
            said(&v)
        );
    }
}
