//! SciPy measured in the run (issue 42): the certified escape speed found by SciPy's compiled
//! DOP853 (`docs/scipy-escape.py`, the same search and certificates) against `turntable`'s own,
//! on the same points, each side's search timed without its process start (Python's start-up
//! and its import of SciPy; this process's own) — or, where python3 with SciPy is not found,
//! not measured at all: never a constant.

use super::{median, timed};
use crate::engine::solve::{escape_speed, solve_certified};
use crate::engine::{Initial, Settings};
use crate::error::Error;
use serde::Serialize;
use std::process::{Command, Stdio};
use std::time::Instant;

/// The script, in the binary: the bench runs it wherever it is started from.
const SCRIPT: &str = include_str!("../../docs/scipy-escape.py");
/// The escape speed's bracket, as `turntable escape --vtol 1e-8`.
const VTOL: f64 = 1e-8;

/// Both sides on the same points.
#[derive(Clone, Debug, Serialize)]
pub struct Scipy {
    /// (ξ0, φ) of each point: Fig. 5's four ξ0 × its angles.
    pub points: Vec<(f64, f64)>,
    /// SciPy's search per point, CPU ms from its first run to its verdict (its own clock), and
    /// the whole `python3` process's wall time.
    pub scipy_ms: Vec<f64>,
    pub scipy_process_ms: Vec<f64>,
    /// Of `scipy_ms`, the search before the certificate.
    pub scipy_search_ms: Vec<f64>,
    /// Points SciPy certified.
    pub scipy_certified: usize,
    /// `solve_certified` at the default settings in this process (the least of a few runs), and
    /// the search alone (`escape_speed`).
    pub ours_ms: Vec<f64>,
    pub ours_search_ms: Vec<f64>,
}

impl Scipy {
    /// SciPy's median over ours, start-up excluded on both sides.
    pub fn ratio(&self) -> f64 {
        median(&mut self.scipy_ms.clone()) / median(&mut self.ours_ms.clone())
    }
}

/// Whether `python3` with SciPy can be run here.
fn found() -> bool {
    Command::new("python3")
        .args(["-c", "import scipy.integrate"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// One point through the script: its CPU ms (all, the search's), whether it certified, and the
/// process's wall ms.
fn scipy_point(xi0: f64, phi: f64) -> Option<(f64, f64, bool, f64)> {
    use std::io::Write as _;
    let t = Instant::now();
    let mut child = Command::new("python3")
        .args(["-", &xi0.to_string(), &phi.to_string(), &VTOL.to_string()])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .ok()?;
    child.stdin.take()?.write_all(SCRIPT.as_bytes()).ok()?;
    let out = child.wait_with_output().ok()?;
    let wall = t.elapsed().as_secs_f64() * 1e3;
    let text = String::from_utf8_lossy(&out.stdout);
    let word = |w: &str| {
        let mut it = text.split_whitespace();
        it.find(|x| *x == w)?;
        it.next().map(str::to_owned)
    };
    let ms = word("ms")?.parse().ok()?;
    let search = word("search-ms")?.parse().ok()?;
    Some((ms, search, word("certified")? == "True", wall))
}

/// What became of the comparison.
#[derive(Clone, Debug, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Versus {
    Measured(Scipy),
    /// python3 with SciPy was not found, or its script failed.
    NotFound,
    /// Not the `turntable` binary (a test harness): not tried.
    NotRun,
}

/// The comparison on Fig. 5's four ξ0 × `angles` angles.
pub fn compare(angles: usize, reps: usize) -> Result<Versus, Error> {
    let binary = std::env::current_exe()
        .ok()
        .is_some_and(|e| e.file_stem().is_some_and(|s| s == "turntable"));
    if !binary {
        return Ok(Versus::NotRun);
    }
    Ok(match measure(angles, reps)? {
        Some(c) => Versus::Measured(c),
        None => Versus::NotFound,
    })
}

fn measure(angles: usize, reps: usize) -> Result<Option<Scipy>, Error> {
    if !found() {
        return Ok(None);
    }
    let mut c = Scipy {
        points: Vec::new(),
        scipy_ms: Vec::new(),
        scipy_process_ms: Vec::new(),
        scipy_search_ms: Vec::new(),
        scipy_certified: 0,
        ours_ms: Vec::new(),
        ours_search_ms: Vec::new(),
    };
    for xi0 in [0.8, 0.5, 0.2, 0.001] {
        for k in 0..angles {
            let phi = crate::analysis::angle(k, angles);
            let Some((ms, search, certified, wall)) = scipy_point(xi0, phi) else {
                return Ok(None);
            };
            let at = |v0: f64| Initial::velocity(xi0, phi, v0);
            let solve = |s| escape_speed(xi0, phi, s, VTOL);
            let (r, ours) = timed(reps.max(3), || {
                solve_certified(Settings::default(), solve, at)
            });
            r?;
            let (r, ours_search) = timed(reps.max(3), || solve(Settings::default()));
            r?;
            c.points.push((xi0, phi));
            c.scipy_ms.push(ms);
            c.scipy_search_ms.push(search);
            c.ours_search_ms.push(ours_search);
            c.scipy_process_ms.push(wall);
            c.scipy_certified += usize::from(certified);
            c.ours_ms.push(ours);
        }
    }
    Ok(Some(c))
}

/// The bench's lines: the ratio measured here, or that it was not.
pub fn lines(o: &mut String, v: &Versus) {
    use std::fmt::Write as _;
    match v {
        Versus::Measured(c) => {
            let ours = median(&mut c.ours_ms.clone());
            let theirs = median(&mut c.scipy_ms.clone());
            let process = median(&mut c.scipy_process_ms.clone());
            let search =
                median(&mut c.scipy_search_ms.clone()) / median(&mut c.ours_search_ms.clone());
            let _ = writeln!(
                o,
                "    SciPy's compiled DOP853 doing the same (docs/scipy-escape.py: the same search and certificates; {} points, {} certified): {theirs:.0} ms median, Python's start-up and import excluded (the whole process {process:.0} ms), against turntable's {ours:.2} ms in-process: {:.0}× (the search alone {search:.0}×)   {}",
                c.points.len(),
                c.scipy_certified,
                c.ratio(),
                super::output::goal_at_least(c.ratio(), 100.0, "×")
            );
        }
        Versus::NotFound => {
            let _ = writeln!(
                o,
                "    SciPy not found: not measured (python3 could not import scipy.integrate)"
            );
        }
        Versus::NotRun => {}
    }
}
