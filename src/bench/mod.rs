//! Work–precision measurements (issue 5), in the manner of the ODE community's work–precision
//! diagrams: error against work (RHS evaluations and wall time) for each method over a sweep of
//! its step or tolerance, on the paper's cases and on seeded random releases; then the speed goals, which also time
//! the explorer's frame and its terminal output.

#[cfg(feature = "serve")]
pub mod attacks;
pub mod bytes;
pub mod check;
mod crossover;
#[cfg(feature = "serve")]
pub mod follow;
mod goals;
pub mod link;
pub mod models;
mod output;
pub mod pages;
mod runs;
pub mod scipy;
#[cfg(feature = "serve")]
pub mod serve;
pub mod stated;
mod tasks;

use crate::engine::{Method, Settings};
use crate::error::Error;
use goals::{savings, speed, task_ratios};
use serde::Serialize;
use std::time::Instant;
use strum::VariantArray;
use tasks::{ESCAPE_VTOL, Measure, apart, distance, label};

pub use crossover::{Crossover, Versus};
pub use output::{plot, table};
pub use runs::cases;
pub use tasks::{Task, position_error};

/// What to measure and how thoroughly.
#[derive(Clone, Debug, Serialize)]
pub struct Config {
    pub quick: bool,
    /// Number of seeded random releases besides A, B and D.
    pub cases: usize,
    pub seed: u64,
    /// Timed repetitions after the warm-up (the minimum is reported).
    pub reps: usize,
    /// The Python interpreter whose SciPy the certified escape is measured against (None: not
    /// tried).
    pub python: Option<std::path::PathBuf>,
    /// Whether to measure the speed goals, and to time the second opinion and a key's wait on
    /// the pages steadily (false: a test of the rows, which asserts none of it, is spared them;
    /// one pass each, a press or two). The command always does.
    #[serde(skip)]
    pub goals: bool,
}

impl Config {
    pub fn full() -> Self {
        Config {
            quick: false,
            cases: 100,
            seed: 5,
            reps: 3,
            python: None,
            goals: true,
        }
    }
    pub fn quick() -> Self {
        Config {
            quick: true,
            cases: 12,
            seed: 5,
            reps: 1,
            python: None,
            goals: true,
        }
    }
    fn dts(&self) -> Vec<f64> {
        let all = [1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5];
        all.into_iter()
            .filter(|&d| !self.quick || d >= 1e-3)
            .collect()
    }
    fn tols(&self) -> Vec<f64> {
        (3..=12).map(|k| 10f64.powi(-k)).collect()
    }
}

/// One line of the work–precision table.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    pub task: Task,
    pub method: Method,
    /// The knob as the table prints it (with the raw scheme's stop rule on the rest task).
    pub setting: String,
    pub knob: f64,
    pub cases: usize,
    /// Median and worst error of the task's main quantity (position, or v_e).
    pub err_median: f64,
    pub err_worst: f64,
    /// Stop-time error (rest task only).
    pub time_median: Option<f64>,
    pub time_worst: Option<f64>,
    /// Outcomes (stuck/escaped) that disagree with the reference.
    pub wrong: usize,
    pub rhs_evals: u64,
    /// Median over the cases of the RHS evaluations of one case.
    pub evals_median: f64,
    pub wall_ms: f64,
    /// The reference's resolution on this task (its agreement with its cross-check): errors
    /// below it are printed as below it, never as a number.
    pub resolution: f64,
    /// Tasks that time stops, methods with stick events: the stated errors against the actual,
    /// and what the end game did.
    pub stated: Option<stated::Stated>,
    pub end_game: Option<stated::EndGame>,
}

impl Row {
    /// Whether the row measures its own method: one the end game took from the release does
    /// not (near the rim every method takes the same implicit steps: rk2 against dp54 was 0.998×,
    /// dop853 against dp54 1.0× at every tolerance).
    pub fn measures_its_method(&self) -> bool {
        !self.end_game.as_ref().is_some_and(|e| e.took_the_row())
    }
}

/// The reference's own agreement with a second method, per task.
#[derive(Clone, Debug, Serialize)]
pub struct RefCheck {
    pub task: Task,
    pub reference: String,
    pub check: String,
    pub agreement: f64,
}

/// Work saved by modelling only what a scene requires.
#[derive(Clone, Debug, Serialize)]
pub struct Saving {
    pub what: String,
    pub baseline: String,
    pub baseline_evals: u64,
    pub lean: String,
    pub lean_evals: u64,
    pub factor: f64,
}

/// The speed goals of issue 5, as measured.
#[derive(Clone, Debug, Serialize)]
pub struct Speed {
    /// Escape speed to 1e-8 at ξ0 = 0.5, φ = 0, default settings, one thread.
    pub escape_ms: f64,
    pub escape_evals: u64,
    pub escape_value: f64,
    /// The four Fig. 5 curves (ξ0 = 0.8, 0.5, 0.2, 0.001), on all cores.
    pub fig5_angles: usize,
    pub fig5_vtol: f64,
    pub fig5_ms: f64,
    pub fig5_ms_vtol_1e8: Option<f64>,
    /// Issue 10: the escape-speed page's curve for a new ξ0 (0.5; 72 angles, vtol `analysis::CURVE_VTOL`, no nearby curve to start from) on one
    /// thread, and the outcome map's 72 × 60 cells (`sweep map`) on all cores.
    pub curve_ms: f64,
    /// Its right-hand-side evaluations, and those from the curve at ξ0 = 0.49 (a held `x`'s).
    pub curve_rhs: u64,
    pub curve_near_rhs: u64,
    pub map_ms: f64,
    /// `turntable escape --vtol 1e-8` as a user runs it, process start included: the median
    /// wall time over Fig. 5 points (the paper's four ξ0 × `escape_angles` angles).
    pub escape_cli_ms: Option<f64>,
    /// The same with the default check of the bracket's ends (certification), no goal: the
    /// price of `certified`.
    pub escape_checked_ms: Option<f64>,
    pub escape_angles: usize,
    /// dp54 against rk2 (with stick events) at dt = 1e-3 on the rest task.
    pub rk2_err_median: f64,
    pub matching_tol: Option<f64>,
    pub matching_err_median: Option<f64>,
    /// Median over the cases of evals(rk2 dt=1e-3) / evals(dp54 at the matching tol).
    pub evals_ratio: Option<f64>,
    /// The explorer at 160×48 with a 20 000-point trail: one tick plus one full draw (min).
    pub frame_ms: f64,
    pub frame_trail: usize,
    /// Bytes written to the terminal while the default scene plays at 120×40, per theme and
    /// colour depth.
    pub terminal_bytes: Vec<bytes::Bytes>,
    /// An `--asciicast` recording's worst bytes per tick, at 80×24 and at the largest screen
    /// a script may `resize` to (1000×1000), with the ticks until its bound.
    pub recording_bytes: Vec<bytes::CastBytes>,
    /// The same over a 4 and a 16 KB/s link: paced frames, and the backlog unpaced.
    pub links: Vec<link::Link>,
}

/// dp54 against rk2 (with stick events) at dt = 1e-3 on one task: the loosest dp54 tolerance
/// on the grid whose median error is no larger, and the ratio of median RHS evaluations.
#[derive(Clone, Debug, Serialize)]
pub struct TaskRatio {
    pub task: Task,
    pub rk2_err: f64,
    pub rk2_evals: f64,
    pub dp54_setting: String,
    pub dp54_err: f64,
    pub dp54_evals: f64,
    pub ratio: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub config: Config,
    /// /proc/loadavg when the bench ended: wall times on a shared machine are only as good as
    /// the machine was idle (RHS evaluations do not depend on it).
    pub load: Option<String>,
    pub reference: Vec<RefCheck>,
    pub rows: Vec<Row>,
    pub savings: Vec<Saving>,
    /// None when the config leaves the goals out.
    pub speed: Option<Speed>,
    pub ratios: Vec<TaskRatio>,
    /// dop853 against dp54 at equal error, task by task.
    pub crossovers: Vec<Crossover>,
    /// Issue 34: the pages' work on one thread and on all cores, and a key's wait for them.
    pub pages: pages::PageTimes,
    /// Issue 34: the price of each model, one run and one frame.
    pub models: Vec<models::ModelCost>,
    /// Issue 34: the second opinion's price against the runs it checks.
    pub checks: Vec<check::CheckCost>,
    /// Issue 42: a certified escape speed against SciPy's DOP853 doing the same, measured here.
    pub scipy: scipy::Versus,
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn worst(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

/// One frame of `app` playing on a `size` terminal, the least over at least five: a tick and
/// a whole draw, the mouse's geometry handed back as the shell does.
fn tick_and_draw_ms(
    app: &mut crate::app::App,
    size: (u16, u16),
    reps: usize,
) -> Result<f64, Error> {
    use ratatui::{Terminal, backend::TestBackend};
    let theme = crate::theme::Theme::builtin("dark").ok_or(Error::invalid("no dark theme"))?;
    let mut term = Terminal::new(TestBackend::new(size.0, size.1))?;
    let (r, ms) = timed(reps.max(5), || {
        app.tick();
        let mut geom = Vec::new();
        term.draw(|f| geom = crate::ui::draw(f, app, &theme))?;
        app.drawn(geom);
        Ok::<(), std::convert::Infallible>(())
    });
    r?;
    Ok(ms)
}

/// Times `f` once (the wall clock is the bench's): what `run --error` says its choice cost.
pub fn time_ms<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let out = f();
    (out, t.elapsed().as_secs_f64() * 1e3)
}

/// Times `f`: one warm-up, then up to `reps` runs (fewer if one is slow); the minimum.
fn timed<T>(reps: usize, mut f: impl FnMut() -> T) -> (T, f64) {
    let t0 = Instant::now();
    let out = f();
    let mut best = t0.elapsed().as_secs_f64();
    let reps = if best > 0.5 { reps.min(1) } else { reps };
    for _ in 0..reps {
        let t = Instant::now();
        let _ = f();
        best = best.min(t.elapsed().as_secs_f64());
    }
    (out, best * 1e3)
}

/// This thread's CPU time (s).
pub(super) fn thread_cpu() -> f64 {
    let t = rustix::time::clock_gettime(rustix::time::ClockId::ThreadCPUTime);
    t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64
}

/// CPU time used by the process (user and system), in seconds (USER_HZ is 100 on Linux): what a
/// served class costs, all its threads together, on a machine shared with other work.
#[cfg(feature = "serve")]
pub(super) fn cpu_s() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<f64> = after
        .split_whitespace()
        .filter_map(|x| x.parse().ok())
        .collect();
    // Fields 14 and 15 of the file, 12 and 13 after the name's `)` and the state.
    (f.get(10).copied().unwrap_or(0.0) + f.get(11).copied().unwrap_or(0.0)) / 100.0
}

/// The reference: dp54 at tol 1e-13 (`sim::ending::reference`, the page's too).
pub fn reference() -> Settings {
    crate::sim::ending::reference(Settings::default())
}

const REST_TAU: f64 = 200.0;
/// How long the frictionless saving runs: ξ ≈ 25 by then, far past any view.
const FREE_TAU: f64 = 30.0;
const FAR_TAU: f64 = 400.0;

/// Runs the whole bench. `progress` hears about each task as it starts.
pub fn run(cfg: &Config, mut progress: impl FnMut(&str)) -> Result<Report, Error> {
    let all = cases(cfg.cases, cfg.seed);
    let (mut agreement, mut rows, mut rest) = (Vec::new(), Vec::new(), Vec::new());
    for &task in Task::VARIANTS {
        progress(&task.to_string());
        let cs = task.cases(cfg, &all);
        let measure = |s: Settings, vtol: f64| {
            cs.iter()
                .map(|i| task.measure(*i, s, vtol))
                .collect::<Result<Vec<Measure>, Error>>()
        };
        let vtol = task.reference_vtol();
        let refs = measure(reference(), vtol)?;
        let checks = measure(task.check(), vtol)?;
        let vtag = if task.escape() {
            format!(" vtol={vtol:.0e}")
        } else {
            String::new()
        };
        agreement.push(RefCheck {
            task,
            reference: label(reference()) + &vtag,
            check: label(task.check()),
            agreement: refs
                .iter()
                .zip(&checks)
                .map(|(a, b)| apart(a, b))
                .fold(0.0, f64::max),
        });
        let resolution = agreement.last().map_or(0.0, |c: &RefCheck| c.agreement);
        for s in task.settings(cfg) {
            let vtol = row_vtol(task, s);
            let (out, ms) = timed(cfg.reps, || measure(s, vtol));
            let mut r = row(task, s, vtol, &refs, &out?, ms);
            r.resolution = resolution;
            if task.times_stops()
                && let Some((st, end)) = stated::lines(s, &cs, &refs, resolution)?
            {
                (r.stated, r.end_game) = (Some(st), Some(end));
            }
            rows.push(r);
        }
        if task == Task::Rest {
            rest = refs;
        }
    }
    progress("model only what a scene requires");
    let savings = savings(&all)?;
    progress("the price of each model");
    let models = models::model_costs(&all, cfg.reps)?;
    let speed = if cfg.goals {
        progress("speed goals");
        Some(speed(cfg, &all, &rest)?)
    } else {
        None
    };
    progress("the second opinion's price");
    let checks = check::check_costs(
        &all,
        if cfg.quick { 3 } else { 12 },
        cfg.goals.then_some(cfg.reps),
    )?;
    progress("the pages on all cores");
    // A key's wait over a few presses, and a key held for a second (30 presses).
    let (presses, held) = match (cfg.goals, cfg.quick) {
        (false, _) => (1, 2),
        (true, true) => (4, 30),
        (true, false) => (8, 30),
    };
    let pages = pages::page_times(cfg.reps, presses, held)?;
    progress("SciPy's DOP853 on the same escape speeds");
    let scipy = scipy::compare(
        cfg.python.as_deref(),
        if cfg.quick { 1 } else { 3 },
        cfg.reps,
        scipy::POINT_LIMIT,
    )?;
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|l| l.split_whitespace().take(3).collect::<Vec<_>>().join(" "));
    Ok(Report {
        config: cfg.clone(),
        load,
        reference: agreement,
        ratios: task_ratios(&rows),
        crossovers: crossover::crossovers(&rows),
        rows,
        savings,
        speed,
        pages,
        models,
        checks,
        scipy,
    })
}

/// The escape-speed tolerance of an escape task's row. The solver runs an adaptive method no
/// looser than a hundredth of it, so at one vtol every looser tolerance would run as that one:
/// each row's vtol is 100× its tolerance (at least [`ESCAPE_VTOL`]), and it runs at the
/// tolerance it names.
fn row_vtol(task: Task, s: Settings) -> f64 {
    match s.scheme.tol() {
        Some(tol) if task.escape() => (100.0 * tol).max(ESCAPE_VTOL),
        _ => ESCAPE_VTOL,
    }
}

/// One row: `out` (one setting's measures of the task's cases) against the reference's.
fn row(task: Task, s: Settings, vtol: f64, refs: &[Measure], out: &[Measure], wall_ms: f64) -> Row {
    let (mut errs, mut times, mut wrong) = (Vec::new(), Vec::new(), 0);
    for (m, r) in out.iter().zip(refs) {
        if m.outcome != r.outcome {
            wrong += 1;
            continue;
        }
        if let (Some(a), Some(b)) = (m.value, r.value) {
            errs.push(distance(a, b));
        }
        if let (Some(a), Some(b)) = (m.tau, r.tau) {
            times.push((a - b).abs());
        }
    }
    let mut evals: Vec<f64> = out.iter().map(|m| m.evals as f64).collect();
    // The raw scheme never stops by itself (nor in `run --method rk2-raw`): its row names the
    // rule the bench stops it by.
    let rule = if task.times_stops() && !s.method().stick_events() {
        " |u|≤dt".to_string()
    } else if task.escape() {
        format!(" vtol={vtol:.0e}")
    } else {
        String::new()
    };
    let stops = task.times_stops();
    Row {
        task,
        method: s.method(),
        setting: format!("{}{rule}", crate::present::accuracy(&s)),
        knob: s.scheme.knob(),
        cases: out.len(),
        err_median: median(&mut errs.clone()),
        err_worst: worst(&errs),
        time_median: stops.then(|| median(&mut times.clone())),
        time_worst: stops.then(|| worst(&times)),
        wrong,
        rhs_evals: out.iter().map(|m| m.evals).sum(),
        evals_median: median(&mut evals),
        wall_ms,
        resolution: 0.0,
        stated: None,
        end_game: None,
    }
}
