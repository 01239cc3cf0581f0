//! Work–precision measurements (issue 5), in the manner of the ODE community's work–precision
//! diagrams: error against work (RHS evaluations and wall time) for each method over a sweep of
//! its step or tolerance, on the paper's cases and on seeded random releases. Engine only: no UI.

use crate::engine::method::dp54_plain;
use crate::engine::model::wrap_angle;
use crate::engine::solve::{escape_speed, sweep_escape};
use crate::engine::{Frame, Initial, Method, Outcome, Release, Run, Settings, State, Status};
use glam::DVec2;
use serde::Serialize;
use std::f64::consts::{PI, TAU};
use std::time::Instant;

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

/// splitmix64 (Steele, Lea & Flood 2014): a tiny deterministic generator for the random cases.
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
    pub fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len() as u64) as usize]
    }
}

/// A, B and D of the paper, then `n` seeded releases (ξ0 ∈ [0, 0.9], φ ∈ [0, 2π),
/// v0 ∈ [0, 0.5]: most of them stick).
pub fn cases(n: usize, seed: u64) -> Vec<(String, Initial)> {
    let mut v = vec![
        ("A".to_string(), Initial::velocity(0.5, PI, 1.0)),
        ("B".to_string(), Initial::velocity(0.5, 0.0, 0.6)),
        ("D".to_string(), Initial::velocity(1.1, 1.2 * PI, 1.3)),
    ];
    let mut rng = SplitMix64(seed);
    for i in 0..n {
        let xi0 = 0.9 * rng.unit();
        let phi = TAU * rng.unit();
        let v0 = 0.5 * rng.unit();
        v.push((format!("r{i}"), Initial::velocity(xi0, phi, v0)));
    }
    v
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
        if self.settings.method.adaptive() {
            self.settings.tol
        } else {
            self.settings.dt
        }
    }
}

/// How a run ended, where, and at what cost.
#[derive(Clone, Copy, Debug)]
pub struct End {
    pub outcome: Outcome,
    /// Stop time (stuck) or certificate time (escaped).
    pub tau: f64,
    /// Rest position in the table frame (stuck).
    pub q: DVec2,
    pub evals: u64,
}

/// Runs to the stop or the escape certificate. The paper's raw scheme has no stick event: its
/// stop is declared at the first step with |u| ≤ dt at ξ ≤ 1 (one step's worth of friction).
pub fn finish(initial: Initial, settings: Settings, tau_max: f64) -> Result<End, String> {
    let mut run = Run::new(initial, settings)?;
    if settings.method.stick_events() {
        let (outcome, s) = run.finish(tau_max).map_err(|e| e.to_string())?;
        return Ok(End {
            outcome,
            tau: s.tau,
            q: s.q(),
            evals: run.cost.rhs_evals,
        });
    }
    loop {
        let s = run.state();
        if let Some(e) = run.escape {
            return Ok(End {
                outcome: Outcome::Escaped,
                tau: e.tau,
                q: run.state_at(e.tau).q(),
                evals: run.cost.rhs_evals,
            });
        }
        if s.u_lab().length() <= settings.dt && s.xi() <= 1.0 {
            return Ok(End {
                outcome: Outcome::Stuck,
                tau: s.tau,
                q: s.q(),
                evals: run.cost.rhs_evals,
            });
        }
        if s.tau >= tau_max {
            return Ok(End {
                outcome: Outcome::Running,
                tau: s.tau,
                q: s.q(),
                evals: run.cost.rhs_evals,
            });
        }
        run.step(tau_max).map_err(|e| e.to_string())?;
    }
}

/// The lab state at exactly `tau` (no stopping at escape), and the cost.
pub fn state_at(initial: Initial, settings: Settings, tau: f64) -> Result<(State, u64), String> {
    let mut run = Run::new(initial, settings)?;
    run.run(tau, false).map_err(|e| e.to_string())?;
    let s = match run.status {
        Status::Stuck { .. } => run.state_at(tau),
        Status::Slipping => run.state(),
    };
    Ok((s, run.cost.rhs_evals))
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
    /// dp54 against rk2 (with stick events) at dt = 1e-3 on the rest task.
    pub rk2_err_median: f64,
    pub matching_tol: Option<f64>,
    pub matching_err_median: Option<f64>,
    /// Median over the cases of evals(rk2 dt=1e-3) / evals(dp54 at the matching tol).
    pub evals_ratio: Option<f64>,
    /// The explorer at 160×48 with a 20 000-point trail: one tick plus one full draw (min).
    pub frame_ms: f64,
    pub frame_trail: usize,
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

fn setting_label(s: &Setting) -> String {
    s.settings.accuracy_label()
}

fn methods_for(cfg: &Config, fixed_min_dt: f64, raw: bool) -> Vec<Setting> {
    let mut v = Vec::new();
    for m in [Method::Rk2Raw, Method::Rk2, Method::Rk4] {
        if m == Method::Rk2Raw && !raw {
            continue;
        }
        for dt in cfg.dts() {
            if dt >= fixed_min_dt {
                v.push(Setting::new(m, dt));
            }
        }
    }
    for tol in cfg.tols() {
        v.push(Setting::new(Method::Dp54, tol));
    }
    v
}

/// Per-case results of one setting on the rest task, kept for the speed ratio.
struct RestCase {
    err: f64,
    evals: u64,
}

fn rest_rows(
    cfg: &Config,
    cs: &[(String, Initial)],
    refs: &[End],
    per_case: &mut Vec<(Setting, Vec<Option<RestCase>>)>,
) -> Result<Vec<Row>, String> {
    let mut rows = Vec::new();
    for s in methods_for(cfg, 0.0, true) {
        let (ends, ms) = timed(cfg.reps, || {
            cs.iter()
                .map(|(_, i)| finish(*i, s.settings, REST_TAU))
                .collect::<Result<Vec<_>, _>>()
        });
        let ends = ends?;
        let (mut pe, mut te, mut ev) = (Vec::new(), Vec::new(), Vec::new());
        let mut wrong = 0;
        let mut pc = Vec::new();
        for (e, r) in ends.iter().zip(refs) {
            ev.push(e.evals as f64);
            if e.outcome != r.outcome {
                wrong += 1;
                pc.push(None);
                continue;
            }
            if r.outcome == Outcome::Stuck {
                let err = (e.q - r.q).length();
                pe.push(err);
                te.push((e.tau - r.tau).abs());
                pc.push(Some(RestCase {
                    err,
                    evals: e.evals,
                }));
            } else {
                pc.push(None);
            }
        }
        rows.push(Row {
            task: "rest".into(),
            method: s.settings.method.name().into(),
            setting: setting_label(&s),
            knob: s.knob(),
            cases: cs.len(),
            err_median: median(&mut pe.clone()),
            err_worst: worst(&pe),
            time_median: Some(median(&mut te.clone())),
            time_worst: Some(worst(&te)),
            wrong,
            rhs_evals: ends.iter().map(|e| e.evals).sum(),
            evals_median: median(&mut ev),
            wall_ms: ms,
        });
        per_case.push((s, pc));
    }
    Ok(rows)
}

/// Rows of a task whose error per case is |x − x_ref| of a position at a fixed time.
fn position_rows(
    cfg: &Config,
    task: &str,
    cs: &[Initial],
    refs: &[DVec2],
    tau: f64,
    settings: &[Setting],
) -> Result<Vec<Row>, String> {
    let mut rows = Vec::new();
    for s in settings {
        let (out, ms) = timed(cfg.reps, || {
            cs.iter()
                .map(|i| state_at(*i, s.settings, tau))
                .collect::<Result<Vec<_>, _>>()
        });
        let out = out?;
        let errs: Vec<f64> = out
            .iter()
            .zip(refs)
            .map(|((st, _), r)| {
                let e = (st.r - *r).length();
                // Relative far out (the far escape runs to ξ ~ 1e4).
                if r.length() > 10.0 { e / r.length() } else { e }
            })
            .collect();
        let mut ev: Vec<f64> = out.iter().map(|(_, e)| *e as f64).collect();
        rows.push(Row {
            task: task.into(),
            method: s.settings.method.name().into(),
            setting: setting_label(s),
            knob: s.knob(),
            cases: cs.len(),
            err_median: median(&mut errs.clone()),
            err_worst: worst(&errs),
            time_median: None,
            time_worst: None,
            wrong: 0,
            rhs_evals: out.iter().map(|(_, e)| e).sum(),
            evals_median: median(&mut ev),
            wall_ms: ms,
        });
    }
    Ok(rows)
}

/// Error of the position at τ = `tau` of `initial` with a fixed-step method at `dt`, against
/// the reference: for measuring the order of the fixed-step methods on a smooth stretch.
pub fn position_error(initial: Initial, method: Method, dt: f64, tau: f64) -> Result<f64, String> {
    let (r, _) = state_at(initial, reference(), tau)?;
    let (s, _) = state_at(initial, Setting::new(method, dt).settings, tau)?;
    Ok((s.r - r.r).length())
}

fn escape_rows(cfg: &Config, v_ref: f64) -> Result<Vec<Row>, String> {
    let mut settings: Vec<Setting> = vec![];
    let dts: &[f64] = if cfg.quick {
        &[1e-2]
    } else {
        &[1e-2, 3e-3, 1e-3]
    };
    for m in [Method::Rk2, Method::Rk4] {
        for &dt in dts {
            settings.push(Setting::new(m, dt));
        }
    }
    for tol in cfg.tols() {
        if !cfg.quick || tol >= 1e-10 {
            settings.push(Setting::new(Method::Dp54, tol));
        }
    }
    let mut rows = Vec::new();
    for s in settings {
        let (t, ms) = timed(cfg.reps, || escape_speed(0.5, 0.0, s.settings, ESCAPE_VTOL));
        let t = t?;
        let err = (t.value - v_ref).abs();
        rows.push(Row {
            task: "v_e(0.5,0)".into(),
            method: s.settings.method.name().into(),
            setting: setting_label(&s),
            knob: s.knob(),
            cases: 1,
            err_median: err,
            err_worst: err,
            time_median: None,
            time_worst: None,
            wrong: 0,
            rhs_evals: t.rhs_evals,
            evals_median: t.rhs_evals as f64,
            wall_ms: ms,
        });
    }
    Ok(rows)
}

fn fig5_curve(settings: Settings, n: usize, vtol: f64) -> Result<(Vec<f64>, u64), String> {
    let mut evals = 0;
    let mut v = Vec::with_capacity(n);
    for i in 0..n {
        let phi = TAU * i as f64 / n as f64;
        let t = escape_speed(0.5, phi, settings, vtol)?;
        evals += t.rhs_evals;
        v.push(t.value);
    }
    Ok((v, evals))
}

fn fig5_rows(cfg: &Config, n: usize, refs: &[f64], vtol: f64) -> Result<Vec<Row>, String> {
    let mut settings: Vec<Setting> = vec![];
    if !cfg.quick {
        for m in [Method::Rk2, Method::Rk4] {
            settings.push(Setting::new(m, 1e-2));
        }
    }
    for tol in cfg.tols() {
        if tol <= 1e-4 && (!cfg.quick || tol >= 1e-10) && tol.log10().round() as i32 % 2 == 0 {
            settings.push(Setting::new(Method::Dp54, tol));
        }
    }
    let mut rows = Vec::new();
    for s in settings {
        let (out, ms) = timed(cfg.reps.min(1), || fig5_curve(s.settings, n, vtol));
        let (vals, evals) = out?;
        let errs: Vec<f64> = vals.iter().zip(refs).map(|(a, b)| (a - b).abs()).collect();
        rows.push(Row {
            task: format!("fig5 ξ0=0.5 ({n}φ)"),
            method: s.settings.method.name().into(),
            setting: setting_label(&s),
            knob: s.knob(),
            cases: n,
            err_median: median(&mut errs.clone()),
            err_worst: worst(&errs),
            time_median: None,
            time_worst: None,
            wrong: 0,
            rhs_evals: evals,
            evals_median: evals as f64 / n as f64,
            wall_ms: ms,
        });
    }
    Ok(rows)
}

fn savings(cs: &[(String, Initial)]) -> Result<Vec<Saving>, String> {
    let mut out = Vec::new();
    // Stuck: closed-form rotation after the stop, against the paper's stepping to τ = 50.
    let (mut raw, mut rk2, mut dp) = (0, 0, 0);
    for (_, i) in cs {
        raw += state_at(*i, Settings::paper(), 50.0)?.1;
        rk2 += state_at(*i, Settings::fixed(Method::Rk2, 1e-3), 50.0)?.1;
        dp += state_at(*i, Settings::default(), 50.0)?.1;
    }
    for (lean, lean_evals) in [
        ("rk2 dt=1e-3, closed form after the stop", rk2),
        ("dp54 tol=1e-10 (default), closed form after", dp),
    ] {
        out.push(Saving {
            what: format!("{} cases to τ = 50: stop at the stick", cs.len()),
            baseline: "rk2-raw dt=1e-3 stepping on".into(),
            baseline_evals: raw,
            lean: lean.into(),
            lean_evals,
            factor: raw as f64 / lean_evals as f64,
        });
    }
    // Escaping: stop at the certificate instead of following it out to τ = 400.
    let far = Initial::velocity(0.5, 0.4, 1.5);
    let mut follow = Run::new(far, Settings::default())?;
    follow.run(FAR_TAU, false).map_err(|e| e.to_string())?;
    let mut stop = Run::new(far, Settings::default())?;
    stop.run(FAR_TAU, true).map_err(|e| e.to_string())?;
    out.push(Saving {
        what: "far escape (0.5, 0.4, 1.5): stop at the certificate".into(),
        baseline: "dp54 followed to τ = 400".into(),
        baseline_evals: follow.cost.rhs_evals,
        lean: "dp54 stopped once certified".into(),
        lean_evals: stop.cost.rhs_evals,
        factor: follow.cost.rhs_evals as f64 / stop.cost.rhs_evals as f64,
    });
    // Frame far out: ξ0 = 500 released at rest in the lab, to τ = 30 (Fig. 1).
    let fig1 = Initial::at_rest(500.0, Release::LabRest);
    let mut ev = [0u64; 2];
    for (k, frame) in [Frame::Table, Frame::Lab].into_iter().enumerate() {
        let s = Settings {
            frame,
            ..Settings::default()
        };
        ev[k] = state_at(fig1, s, 30.0)?.1;
    }
    out.push(Saving {
        what: "ξ0 = 500 at rest in the lab to τ = 30 (Fig. 1): frame".into(),
        baseline: "dp54 tol=1e-10, table frame".into(),
        baseline_evals: ev[0],
        lean: "dp54 tol=1e-10, lab frame".into(),
        lean_evals: ev[1],
        factor: ev[0] as f64 / ev[1] as f64,
    });
    // μ = 0: the straight line in closed form, against integrating the frictionless
    // equations in the rotating frame (where the paper writes them) out to the view's edge.
    let free = Initial {
        frictionless: true,
        ..Initial::velocity(0.5, 0.0, 0.6078)
    };
    let s = free.state();
    let (y, evals) = dp54_plain(
        |y| Frame::Table.rhs_free(y),
        Frame::Table.from_state(&s),
        FREE_TAU,
        1e-10,
    );
    let off = (Frame::Table.to_state(y, FREE_TAU).r - free.free_state(FREE_TAU).r).length();
    out.push(Saving {
        what: format!("μ = 0 from C's release to τ = {FREE_TAU} (ξ ≈ 25): closed form"),
        baseline: format!("dp54 tol=1e-10, table frame (|Δr| = {off:.0e})"),
        baseline_evals: evals,
        lean: "closed form: a straight line in the lab".into(),
        lean_evals: 0,
        factor: f64::INFINITY,
    });
    Ok(out)
}

fn speed(cfg: &Config, per_case: &[(Setting, Vec<Option<RestCase>>)]) -> Result<Speed, String> {
    let (t, escape_ms) = timed(if cfg.reps == 0 { 0 } else { cfg.reps.max(3) }, || {
        escape_speed(0.5, 0.0, Settings::default(), ESCAPE_VTOL)
    });
    let t = t?;
    let n = if cfg.quick { 24 } else { 72 };
    let xi0s = [0.8, 0.5, 0.2, 0.001];
    let (r, fig5_ms) = timed(cfg.reps.min(2), || {
        sweep_escape(&xi0s, n, Settings::default(), 1e-6)
    });
    r?;
    let fig5_ms_vtol_1e8 = if cfg.quick {
        None
    } else {
        let (r, ms) = timed(1, || sweep_escape(&xi0s, n, Settings::default(), 1e-8));
        r?;
        Some(ms)
    };
    let (frame_ms, frame_trail) = frame_time(cfg.reps)?;
    // The rk2 (stick events) dt = 1e-3 accuracy, and the loosest dp54 tol that matches it, on
    // a grid of four tolerances per decade.
    let cs = cases(cfg.cases, cfg.seed);
    let rk2 = per_case
        .iter()
        .find(|(s, _)| s.settings.method == Method::Rk2 && (s.knob() / 1e-3 - 1.0).abs() < 1e-9);
    let mut rk2_err = f64::NAN;
    let mut matching = None;
    if let Some((_, rk2)) = rk2 {
        let mut e: Vec<f64> = rk2.iter().flatten().map(|c| c.err).collect();
        rk2_err = median(&mut e);
        let refs: Vec<Option<End>> = cs
            .iter()
            .map(|(_, i)| finish(*i, reference(), REST_TAU).ok())
            .collect();
        for k in 12..=40 {
            let tol = 10f64.powf(-k as f64 / 4.0);
            let mut errs = Vec::new();
            let mut ratios = Vec::new();
            for (((_, i), r), a) in cs.iter().zip(&refs).zip(rk2) {
                let (Some(r), Some(a)) = (r, a) else { continue };
                let e = finish(*i, Settings::dp54(tol), REST_TAU)?;
                if e.outcome != r.outcome {
                    errs.push(f64::INFINITY);
                    continue;
                }
                errs.push((e.q - r.q).length());
                ratios.push(a.evals as f64 / e.evals as f64);
            }
            let err = median(&mut errs);
            if err <= rk2_err {
                matching = Some((tol, err, median(&mut ratios)));
                break;
            }
        }
    }
    Ok(Speed {
        escape_ms,
        escape_evals: t.rhs_evals,
        escape_value: t.value,
        fig5_angles: n,
        fig5_vtol: 1e-6,
        fig5_ms,
        fig5_ms_vtol_1e8,
        rk2_err_median: rk2_err,
        matching_tol: matching.map(|m| m.0),
        matching_err_median: matching.map(|m| m.1),
        evals_ratio: matching.map(|m| m.2),
        frame_ms,
        frame_trail,
    })
}

/// One frame of the explorer as it plays: a tick of simulation and a full draw of the default
/// scene at 160×48, with the paper's run beside it, once the trail holds 20 000 samples.
fn frame_time(reps: usize) -> Result<(f64, usize), String> {
    use crate::app::{Action, App, update};
    use ratatui::{Terminal, backend::TestBackend};
    let theme = crate::theme::Theme::builtin("dark").ok_or("no dark theme")?;
    let mut app = App::new(crate::scene::Scene::default_scene(), theme);
    update(&mut app, Action::ToggleCompare);
    while app.sim.samples.len() < 20_000 {
        app.tick();
    }
    let mut term = Terminal::new(TestBackend::new(160, 48)).map_err(|e| e.to_string())?;
    let (r, ms) = timed(reps.max(5), || {
        app.tick();
        term.draw(|f| crate::ui::draw(f, &mut app)).map(|_| ())
    });
    r.map_err(|e| e.to_string())?;
    Ok((ms, app.sim.trail().len()))
}

/// Runs the whole bench. `progress` hears about each task as it starts.
pub fn run(cfg: &Config, mut progress: impl FnMut(&str)) -> Result<Report, String> {
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
        rows,
        savings,
        speed,
    })
}

fn sci(x: f64) -> String {
    if x.is_nan() {
        "—".into()
    } else if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.1e}")
    }
}

/// The aligned text table.
pub fn table(r: &Report) -> String {
    use std::fmt::Write as _;
    let mut o = String::new();
    let _ = writeln!(
        o,
        "turntable bench ({}; {} random cases, seed {}; error = |Δposition| (rest: table frame), \
         |Δv_e| or relative |Δr| far out; work = RHS evaluations, wall = min of runs, one thread)",
        if r.config.quick { "quick" } else { "full" },
        r.config.cases,
        r.config.seed
    );
    if let Some(l) = &r.load {
        let _ = writeln!(
            o,
            "load average {l} on {} cores (wall times are minima over runs; RHS counts do not depend on load)",
            std::thread::available_parallelism().map_or(1, |n| n.get())
        );
    }
    let _ = writeln!(o, "\nreference and its own agreement:");
    for c in &r.reference {
        let _ = writeln!(
            o,
            "  {:<22} {:<26} vs {:<28} {}",
            c.task,
            c.reference,
            c.check,
            sci(c.agreement)
        );
    }
    let _ = writeln!(
        o,
        "\n{:<20} {:<8} {:<10} {:>8} {:>8} {:>8} {:>8} {:>5} {:>10} {:>10} {:>9}",
        "task",
        "method",
        "setting",
        "err med",
        "err max",
        "τ med",
        "τ max",
        "wrong",
        "RHS/case",
        "RHS total",
        "wall ms"
    );
    let mut last = String::new();
    for row in &r.rows {
        if row.task != last {
            let _ = writeln!(o, "{}", "-".repeat(108));
            last = row.task.clone();
        }
        let _ = writeln!(
            o,
            "{:<20} {:<8} {:<10} {:>8} {:>8} {:>8} {:>8} {:>5} {:>10.0} {:>10} {:>9.2}",
            row.task,
            row.method,
            row.setting,
            sci(row.err_median),
            sci(row.err_worst),
            row.time_median.map_or("".into(), sci),
            row.time_worst.map_or("".into(), sci),
            row.wrong,
            row.evals_median,
            row.rhs_evals,
            row.wall_ms
        );
    }
    let _ = writeln!(o, "\nmodel only what a scene requires (RHS evaluations):");
    for s in &r.savings {
        let factor = if s.factor.is_finite() {
            format!("{:.0}× less", s.factor)
        } else {
            "none at all".into()
        };
        let _ = writeln!(
            o,
            "  {}\n    {:<44} {:>10}\n    {:<44} {:>10}   {factor}",
            s.what, s.baseline, s.baseline_evals, s.lean, s.lean_evals
        );
    }
    let sp = &r.speed;
    let _ = writeln!(o, "\nspeed goals (release build, this machine):");
    let _ = writeln!(
        o,
        "  escape speed to 1e-8 at (0.5, 0), dp54 tol=1e-10: {:.2} ms, {} RHS, v_e = {:.10}   (goal ≤ 5 ms)",
        sp.escape_ms, sp.escape_evals, sp.escape_value
    );
    let _ = writeln!(
        o,
        "  four Fig. 5 curves × {} angles (vtol {:e}, all cores): {:.0} ms   (goal ≤ 1000 ms){}",
        sp.fig5_angles,
        sp.fig5_vtol,
        sp.fig5_ms,
        sp.fig5_ms_vtol_1e8
            .map_or(String::new(), |m| format!("; at vtol 1e-8: {m:.0} ms"))
    );
    match (sp.matching_tol, sp.evals_ratio) {
        (Some(tol), Some(ratio)) => {
            let _ = writeln!(
                o,
                "  rk2 dt=1e-3 median rest error {}: dp54 reaches it at tol={tol:.1e} (median {}) with {ratio:.0}× fewer RHS evaluations (median over cases; goal ≥ 20×)",
                sci(sp.rk2_err_median),
                sci(sp.matching_err_median.unwrap_or(f64::NAN))
            );
        }
        _ => {
            let _ = writeln!(
                o,
                "  rk2 dt=1e-3 median rest error {}: no dp54 tol matched it",
                sci(sp.rk2_err_median)
            );
        }
    }
    let _ = writeln!(
        o,
        "  explorer frame at 160×48, {}-point trail, paper's run beside it (tick + draw): {:.2} ms   (goal ≤ 2 ms)",
        sp.frame_trail, sp.frame_ms
    );
    o
}

/// Error against work (log–log) for one task, as a braille chart in plain text.
pub fn plot(r: &Report, task: &str, width: usize, height: usize) -> String {
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for row in r.rows.iter().filter(|row| row.task == task) {
        let p = (
            row.evals_median.max(1.0).log10(),
            row.err_median.max(1e-16).log10(),
        );
        if !(p.0.is_finite() && p.1.is_finite()) {
            continue;
        }
        match series.iter_mut().find(|(m, _)| *m == row.method) {
            Some((_, v)) => v.push(p),
            None => series.push((row.method.clone(), vec![p])),
        }
    }
    let pts: Vec<(f64, f64)> = series.iter().flat_map(|(_, v)| v.iter().copied()).collect();
    if pts.is_empty() {
        return format!("{task}: nothing to plot\n");
    }
    let (x0, x1) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
        (a.0.min(p.0.floor()), a.1.max(p.0.ceil()))
    });
    let (y0, y1) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
        (a.0.min(p.1.floor()), a.1.max(p.1.ceil()))
    });
    let (x1, y1) = (x1.max(x0 + 1.0), y1.max(y0 + 1.0));
    let (dw, dh) = (width * 2, height * 4);
    let mut dots = vec![vec![false; dw]; dh];
    let to_dot = |p: (f64, f64)| {
        let x = ((p.0 - x0) / (x1 - x0) * (dw - 1) as f64).round() as i64;
        let y = ((y1 - p.1) / (y1 - y0) * (dh - 1) as f64).round() as i64;
        (x, y)
    };
    let mut labels: Vec<(usize, usize, char)> = Vec::new();
    let marks = ['r', '2', '4', 'd', 'e', 'f'];
    for (k, (name, v)) in series.iter().enumerate() {
        let mark = match name.as_str() {
            "rk2-raw" => 'r',
            "rk2" => '2',
            "rk4" => '4',
            "dp54" => 'd',
            _ => marks[k % marks.len()],
        };
        for w in v.windows(2) {
            let (a, b) = (to_dot(w[0]), to_dot(w[1]));
            let n = (b.0 - a.0).abs().max((b.1 - a.1).abs()).max(1);
            for i in 0..=n {
                let x = a.0 + (b.0 - a.0) * i / n;
                let y = a.1 + (b.1 - a.1) * i / n;
                if (0..dw as i64).contains(&x) && (0..dh as i64).contains(&y) {
                    dots[y as usize][x as usize] = true;
                }
            }
        }
        for &p in v {
            let (x, y) = to_dot(p);
            labels.push(((x / 2) as usize, (y / 4) as usize, mark));
        }
    }
    let mut grid: Vec<Vec<char>> = (0..height)
        .map(|cy| {
            (0..width)
                .map(|cx| {
                    // Braille dot bits: (0,0)=1 (0,1)=2 (0,2)=4 (1,0)=8 (1,1)=16 (1,2)=32
                    // (0,3)=64 (1,3)=128.
                    let bits = [[0x01, 0x08], [0x02, 0x10], [0x04, 0x20], [0x40, 0x80]];
                    let mut b = 0u32;
                    for (dy, row) in bits.iter().enumerate() {
                        for (dx, bit) in row.iter().enumerate() {
                            if dots[cy * 4 + dy][cx * 2 + dx] {
                                b |= bit;
                            }
                        }
                    }
                    char::from_u32(0x2800 + b).unwrap_or(' ')
                })
                .collect()
        })
        .collect();
    for (cx, cy, m) in labels {
        if cy < height && cx < width {
            grid[cy][cx] = m;
        }
    }
    let mut o = format!(
        "{task}: median error (log10, up) against RHS evaluations per case (log10, right)\n"
    );
    for (cy, line) in grid.iter().enumerate() {
        let label = if cy == 0 {
            format!("{y1:>4.0} ")
        } else if cy == height - 1 {
            format!("{y0:>4.0} ")
        } else {
            "     ".into()
        };
        o.push_str(&label);
        o.push('│');
        o.extend(line.iter());
        o.push('\n');
    }
    o.push_str(&format!("     └{}\n", "─".repeat(width)));
    o.push_str(&format!(
        "      {:<w$}{:>4.0}\n",
        format!("{x0:.0}"),
        x1,
        w = width - 4
    ));
    o.push_str("      r = rk2-raw, 2 = rk2, 4 = rk4, d = dp54\n");
    o
}

/// The rest angle (table frame) of a stuck end, in (−π, π].
pub fn rest_angle(e: &End) -> f64 {
    wrap_angle(e.q.y.atan2(e.q.x))
}
