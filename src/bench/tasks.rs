//! The work–precision tasks: each method over its knob, on rest positions, a smooth stretch,
//! the escape speed and a Fig. 5 curve.

use super::runs::{End, finish, state_at};
use super::{Config, ESCAPE_VTOL, REST_TAU, Row, Setting, median, reference, timed, worst};
use crate::engine::solve::escape_speed;
use crate::engine::{Initial, Method, Outcome, Settings};
use crate::error::Error;
use glam::DVec2;
use std::f64::consts::TAU;

fn setting_label(s: &Setting) -> String {
    s.settings.accuracy_label()
}

pub(super) fn methods_for(cfg: &Config, fixed_min_dt: f64, raw: bool) -> Vec<Setting> {
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
pub(super) struct RestCase {
    pub(super) err: f64,
    pub(super) evals: u64,
}

pub(super) fn rest_rows(
    cfg: &Config,
    cs: &[(String, Initial)],
    refs: &[End],
    per_case: &mut Vec<(Setting, Vec<Option<RestCase>>)>,
) -> Result<Vec<Row>, Error> {
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
        // The raw scheme never stops by itself (nor in `run --method rk2-raw`): its row
        // names the rule the bench stops it by.
        let rule = if s.settings.method().stick_events() {
            ""
        } else {
            " |u|≤dt"
        };
        rows.push(Row {
            task: "rest".into(),
            method: s.settings.method().to_string(),
            setting: format!("{}{rule}", setting_label(&s)),
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
pub(super) fn position_rows(
    cfg: &Config,
    task: &str,
    cs: &[Initial],
    refs: &[DVec2],
    tau: f64,
    settings: &[Setting],
) -> Result<Vec<Row>, Error> {
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
            method: s.settings.method().to_string(),
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
pub fn position_error(initial: Initial, method: Method, dt: f64, tau: f64) -> Result<f64, Error> {
    let (r, _) = state_at(initial, reference(), tau)?;
    let (s, _) = state_at(initial, Setting::new(method, dt).settings, tau)?;
    Ok((s.r - r.r).length())
}

pub(super) fn escape_rows(cfg: &Config, v_ref: f64) -> Result<Vec<Row>, Error> {
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
            method: s.settings.method().to_string(),
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

pub(super) fn fig5_curve(
    settings: Settings,
    n: usize,
    vtol: f64,
) -> Result<(Vec<f64>, u64), Error> {
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

pub(super) fn fig5_rows(
    cfg: &Config,
    n: usize,
    refs: &[f64],
    vtol: f64,
) -> Result<Vec<Row>, Error> {
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
            method: s.settings.method().to_string(),
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
