//! Work–precision measurements (issue 5), in the manner of the ODE community's work–precision
//! diagrams: error against work (RHS evaluations and wall time) for each method over a sweep of
//! its step or tolerance, on the paper's cases and on seeded random releases. Engine only: no UI.

pub mod bytes;
mod goals;
mod output;
mod runs;
mod tasks;

use crate::engine::solve::escape_speed;
use crate::engine::{Frame, Initial, Method, Outcome, Settings};
use crate::error::Error;
use glam::DVec2;
use goals::{savings, speed, task_ratios};
use serde::Serialize;
use std::time::Instant;
use tasks::{escape_rows, fig5_curve, fig5_rows, methods_for, position_rows, rest_rows};

pub use output::{plot, table};
pub use runs::{End, cases, finish, rest_angle, state_at};
pub use tasks::position_error;

/// What to measure and how thoroughly.
#[derive(Clone, Debug, Serialize)]
pub struct Config {
    pub quick: bool,
    /// Number of seeded random releases besides A, B and D.
    pub cases: usize,
    pub seed: u64,
    /// Timed repetitions after the warm-up (the minimum is reported).
    pub reps: usize,
}

impl Config {
    pub fn full() -> Self {
        Config {
            quick: false,
            cases: 100,
            seed: 5,
            reps: 3,
        }
    }
    pub fn quick() -> Self {
        Config {
            quick: true,
            cases: 12,
            seed: 5,
            reps: 1,
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

/// A method at one setting of its accuracy knob.
#[derive(Clone, Copy, Debug)]
pub struct Setting {
    pub settings: Settings,
}

impl Setting {
    pub fn new(method: Method, knob: f64) -> Self {
        let settings = if method.adaptive() {
            Settings::dp54(knob)
        } else {
            Settings::fixed(method, knob)
        };
        Setting { settings }
    }
    pub fn knob(&self) -> f64 {
        self.settings.scheme.knob()
    }
}

/// One line of the work–precision table.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    pub task: String,
    pub method: String,
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
}

/// The reference's own agreement with a second method, per task.
#[derive(Clone, Debug, Serialize)]
pub struct RefCheck {
    pub task: String,
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
    /// Issue 10: the escape-speed page's curve for a new ξ0 (0.5; 72 angles, vtol 1e-6) on one
    /// thread, and the outcome map's 72 × 60 cells (`sweep map`) on all cores.
    pub curve_ms: f64,
    pub map_ms: f64,
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
}

/// dp54 against rk2 (with stick events) at dt = 1e-3 on one task: the loosest dp54 tolerance
/// on the grid whose median error is no larger, and the ratio of median RHS evaluations.
#[derive(Clone, Debug, Serialize)]
pub struct TaskRatio {
    pub task: String,
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
    pub speed: Speed,
    pub ratios: Vec<TaskRatio>,
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

/// The reference: dp54 at tol 1e-13.
pub fn reference() -> Settings {
    Settings::dp54(1e-13)
}

/// The cross-check of the reference on a smooth stretch: rk4 at a small step.
fn check_settings() -> Settings {
    Settings::fixed(Method::Rk4, 1e-4)
}

/// The cross-check of the reference across stops: dp54 at 1e-12 in the other frame. (rk4 at
/// a small dt agrees on rest positions but not on stop times: its last steps before a stop are
/// at the stability limit of the stiff friction direction, see the τ columns.)
fn stop_check_settings() -> Settings {
    Settings {
        frame: Frame::Table,
        ..Settings::dp54(1e-12)
    }
}

const REST_TAU: f64 = 200.0;
const DRIFT_TAU: f64 = 20.0;
/// How long the frictionless saving runs: ξ ≈ 25 by then, far past any view.
const FREE_TAU: f64 = 30.0;
const SMOOTH_TAU: f64 = 0.5;
const FAR_TAU: f64 = 400.0;
const ESCAPE_VTOL: f64 = 1e-8;

/// Runs the whole bench. `progress` hears about each task as it starts.
pub fn run(cfg: &Config, mut progress: impl FnMut(&str)) -> Result<Report, Error> {
    let cs = cases(cfg.cases, cfg.seed);
    let inits: Vec<Initial> = cs.iter().map(|(_, i)| *i).collect();
    let refset = reference();
    let check = check_settings();
    let mut reference = Vec::new();
    let mut rows = Vec::new();

    progress("reference: rest positions and stop times");
    let refs: Vec<End> = inits
        .iter()
        .map(|i| finish(*i, refset, REST_TAU))
        .collect::<Result<_, _>>()?;
    let stop_check = stop_check_settings();
    let checks: Vec<End> = inits
        .iter()
        .map(|i| finish(*i, stop_check, REST_TAU))
        .collect::<Result<_, _>>()?;
    let agree = refs
        .iter()
        .zip(&checks)
        .map(|(a, b)| {
            if a.outcome != b.outcome {
                f64::INFINITY
            } else if a.outcome == Outcome::Stuck {
                (a.q - b.q).length().max((a.tau - b.tau).abs())
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max);
    reference.push(RefCheck {
        task: "rest (pos & stop time)".into(),
        reference: refset.accuracy_label(),
        check: format!("dp54 {} table frame", stop_check.accuracy_label()),
        agreement: agree,
    });

    progress("rest position and stop time");
    let mut per_case = Vec::new();
    rows.extend(rest_rows(cfg, &cs, &refs, &mut per_case)?);

    progress("smooth stretch: case A at τ = 0.5");
    let a = [inits[0]];
    let a_ref = [state_at(a[0], refset, SMOOTH_TAU)?.0.r];
    let a_chk = state_at(a[0], check, SMOOTH_TAU)?.0.r;
    reference.push(RefCheck {
        task: "A@τ=0.5".into(),
        reference: refset.accuracy_label(),
        check: format!("rk4 {}", check.accuracy_label()),
        agreement: (a_ref[0] - a_chk).length(),
    });
    rows.extend(position_rows(
        cfg,
        "A@τ=0.5",
        &a,
        &a_ref,
        SMOOTH_TAU,
        &methods_for(cfg, 0.0, true),
    )?);

    progress("drift after the stop: position at τ = 20");
    let drift_cases: Vec<Initial> = inits.iter().take(3 + cfg.cases.min(20)).copied().collect();
    let drift_chk: Vec<DVec2> = drift_cases
        .iter()
        .map(|i| state_at(*i, stop_check, DRIFT_TAU).map(|s| s.0.r))
        .collect::<Result<_, _>>()?;
    let drift_ref: Vec<DVec2> = drift_cases
        .iter()
        .map(|i| state_at(*i, refset, DRIFT_TAU).map(|s| s.0.r))
        .collect::<Result<_, _>>()?;
    reference.push(RefCheck {
        task: "drift τ=20".into(),
        reference: refset.accuracy_label(),
        check: format!("dp54 {} table frame", stop_check.accuracy_label()),
        agreement: drift_ref
            .iter()
            .zip(&drift_chk)
            .map(|(a, b)| (*a - *b).length())
            .fold(0.0, f64::max),
    });
    rows.extend(position_rows(
        cfg,
        "drift τ=20",
        &drift_cases,
        &drift_ref,
        DRIFT_TAU,
        &methods_for(cfg, 0.0, true),
    )?);

    progress("far escape to τ = 400");
    let far = [Initial::velocity(0.5, 0.4, 1.5)];
    let far_ref = [state_at(far[0], refset, FAR_TAU)?.0.r];
    let far_chk = state_at(far[0], Settings::fixed(Method::Rk4, 1e-3), FAR_TAU)?
        .0
        .r;
    reference.push(RefCheck {
        task: "far τ=400 (relative)".into(),
        reference: refset.accuracy_label(),
        check: "rk4 dt=1e-3".into(),
        agreement: (far_ref[0] - far_chk).length() / far_ref[0].length(),
    });
    let far_min_dt = if cfg.quick { 1e-2 } else { 1e-3 };
    rows.extend(position_rows(
        cfg,
        "far τ=400 (rel)",
        &far,
        &far_ref,
        FAR_TAU,
        &methods_for(cfg, far_min_dt, true),
    )?);

    progress("escape speed at ξ0 = 0.5, φ = 0");
    let v_ref = escape_speed(0.5, 0.0, refset, 1e-10)?;
    let v_chk = escape_speed(
        0.5,
        0.0,
        Settings {
            frame: Frame::Table,
            ..Settings::dp54(1e-12)
        },
        1e-10,
    )?;
    reference.push(RefCheck {
        task: "v_e(0.5,0)".into(),
        reference: format!("{} vtol=1e-10", refset.accuracy_label()),
        check: "dp54 tol=1e-12 table frame".into(),
        agreement: (v_ref.value - v_chk.value).abs(),
    });
    rows.extend(escape_rows(cfg, v_ref.value)?);

    let n = if cfg.quick { 12 } else { 72 };
    progress("one Fig. 5 curve (ξ0 = 0.5)");
    let vtol = 1e-8;
    let (f_ref, _) = fig5_curve(refset, n, 1e-9)?;
    let (f_chk, _) = fig5_curve(Settings::dp54(1e-11), n, 1e-9)?;
    reference.push(RefCheck {
        task: "fig5 ξ0=0.5".into(),
        reference: format!("{} vtol=1e-9", refset.accuracy_label()),
        check: "dp54 tol=1e-11".into(),
        agreement: f_ref
            .iter()
            .zip(&f_chk)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max),
    });
    rows.extend(fig5_rows(cfg, n, &f_ref, vtol)?);

    progress("model only what a scene requires");
    let savings = savings(&cs)?;

    progress("speed goals");
    let speed = speed(cfg, &per_case)?;
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|l| l.split_whitespace().take(3).collect::<Vec<_>>().join(" "));
    Ok(Report {
        config: cfg.clone(),
        load,
        reference,
        ratios: task_ratios(&rows),
        rows,
        savings,
        speed,
    })
}
