//! The speed goals of issue 5, and the work saved by modelling only what a scene requires.

use super::runs::state_at;
use super::tasks::{ESCAPE_VTOL, Measure, Task, value_error};
use super::{Config, FAR_TAU, FREE_TAU, Row, Saving, Speed, TaskRatio, median, timed};
use crate::analysis::{Job, Piece, piece, pieces};
use crate::engine::method::Scheme;
use crate::engine::solve::{escape_speed, sweep_escape};
use crate::engine::stepper::adaptive_plain;
use crate::engine::{Frame, Initial, Method, Release, Run, Settings};
use crate::error::Error;
use crate::scene::Scene;
use std::time::Instant;

/// The work saved by modelling only what a scene requires, one row a saving (or a cost, for
/// the finite body).
pub(super) fn savings(cs: &[Initial]) -> Result<Vec<Saving>, Error> {
    let mut out = Vec::new();
    stop_at_the_stick(cs, &mut out)?;
    stop_at_the_certificate(&mut out)?;
    frame_far_out(&mut out)?;
    closed_forms(&mut out)?;
    static_friction(cs, &mut out)?;
    finite_body(cs, &mut out)?;
    Ok(out)
}

/// Stuck runs stopped at the stick and rotated in closed form.
fn stop_at_the_stick(cs: &[Initial], out: &mut Vec<Saving>) -> Result<(), Error> {
    // Stuck: closed-form rotation after the stop, against the paper's stepping to τ = 50.
    let (mut raw, mut rk2, mut dp) = (0, 0, 0);
    for i in cs {
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
    Ok(())
}

/// An escape stopped once certified.
fn stop_at_the_certificate(out: &mut Vec<Saving>) -> Result<(), Error> {
    // Escaping: stop at the certificate instead of following it out to τ = 400.
    let far = Initial::velocity(0.5, 0.4, 1.5);
    let mut follow = Run::new(far, Settings::default())?;
    follow.run(FAR_TAU, false)?;
    let mut stop = Run::new(far, Settings::default())?;
    stop.run(FAR_TAU, true)?;
    out.push(Saving {
        what: "far escape (0.5, 0.4, 1.5): stop at the certificate".into(),
        baseline: "dp54 followed to τ = 400".into(),
        baseline_evals: follow.cost().rhs_evals,
        lean: "dp54 stopped once certified".into(),
        lean_evals: stop.cost().rhs_evals,
        factor: follow.cost().rhs_evals as f64 / stop.cost().rhs_evals as f64,
    });
    Ok(())
}

/// The lab frame far out.
fn frame_far_out(out: &mut Vec<Saving>) -> Result<(), Error> {
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
    Ok(())
}

/// μ = 0 and Stokes drag in closed form.
fn closed_forms(out: &mut Vec<Saving>) -> Result<(), Error> {
    // μ = 0: the straight line in closed form, against integrating the frictionless
    // equations in the rotating frame (where the paper writes them) out to the view's edge.
    let free = Initial {
        frictionless: true,
        ..Initial::velocity(0.5, 0.0, 0.6078)
    };
    let s = free.state();
    let (y, evals) = adaptive_plain(
        |y| Frame::Table.rhs_free(y),
        Frame::Table.from_state(&s),
        FREE_TAU,
        Scheme::Dp54 { tol: 1e-10 },
    )
    .ok_or(Error::Failed(
        "dp54 on the frictionless equations: step size underflow".into(),
    ))?;
    let off = (Frame::Table.to_state(y, FREE_TAU).r - free.free_state(FREE_TAU).r).length();
    out.push(Saving {
        what: format!("μ = 0 from C's release to τ = {FREE_TAU} (ξ ≈ 25): closed form"),
        baseline: format!("dp54 tol=1e-10, table frame (|Δr| = {off:.0e})"),
        baseline_evals: evals,
        lean: "closed form: a straight line in the lab".into(),
        lean_evals: 0,
        factor: f64::INFINITY,
    });
    // Stokes drag (issue 23): its linear equations in closed form, against integrating them.
    let gamma = 0.5;
    let stokes = crate::engine::stokes::Stokes::new(gamma, free);
    let (y, evals) = adaptive_plain(
        |y| crate::engine::model::Y {
            p: y.w,
            w: -2.0 * crate::engine::model::zcross(y.w) + y.p - gamma * y.w,
        },
        Frame::Table.from_state(&s),
        STOKES_TAU,
        Scheme::Dp54 { tol: 1e-10 },
    )
    .ok_or(Error::Failed(
        "dp54 on the Stokes equations: step size underflow".into(),
    ))?;
    let exact = stokes.state(STOKES_TAU);
    let off = (Frame::Table.to_state(y, STOKES_TAU).r - exact.r).length() / exact.xi();
    out.push(Saving {
        what: format!(
            "Stokes drag γ = {gamma} from C's release to τ = {STOKES_TAU} (ξ ≈ {:.0}): closed form",
            exact.xi()
        ),
        baseline: format!("dp54 tol=1e-10, table frame (|Δr|/ξ = {off:.0e})"),
        baseline_evals: evals,
        lean: "closed form: e^{λ±τ}".into(),
        lean_evals: 0,
        factor: f64::INFINITY,
    });
    Ok(())
}

/// Static friction above kinetic: what its threshold costs.
fn static_friction(cs: &[Initial], out: &mut Vec<Saving>) -> Result<(), Error> {
    // μ_s > μ_k: the same stepping with another threshold, against the point model's.
    let (mut paper, mut held) = (0, 0);
    for i in cs {
        paper += state_at(*i, Settings::default(), 50.0)?.1;
        let s = Settings {
            coupling: crate::engine::Coupling::Coulomb { hold: 1.5 },
            ..Settings::default()
        };
        held += state_at(*i, s, 50.0)?.1;
    }
    out.push(Saving {
        what: format!(
            "{} cases to τ = 50: static friction above kinetic",
            cs.len()
        ),
        baseline: "dp54 tol=1e-10, μs = μk (the paper's)".into(),
        baseline_evals: paper,
        lean: "dp54 tol=1e-10, μs/μk = 1.5".into(),
        lean_evals: held,
        factor: paper as f64 / held as f64,
    });
    Ok(())
}

/// The appendix's body against the point.
fn finite_body(cs: &[Initial], out: &mut Vec<Saving>) -> Result<(), Error> {
    // The appendix's body (issue 23): two contacts, a rotation and their events, against the
    // point from the same releases.
    let (mut point, mut body) = (0, 0);
    let rod = crate::engine::body::Body {
        length: 0.01,
        height: None,
        angle: 0.0,
    };
    for i in cs {
        point += state_at(*i, Settings::default(), 50.0)?.1;
        let mut run = crate::engine::rod::RodRun::new(rod, 1.0, i, 1e-10)?;
        run.finish(50.0, |_| {})?;
        body += run.rhs_evals();
    }
    out.push(Saving {
        what: format!(
            "{} cases to τ = 50: the appendix's body, L = 0.01",
            cs.len()
        ),
        baseline: "dp54 tol=1e-10, the point".into(),
        baseline_evals: point,
        lean: "dp54 tol=1e-10, two masses on a rod".into(),
        lean_evals: body,
        factor: point as f64 / body as f64,
    });
    Ok(())
}

/// How long the Stokes saving runs: long enough for the growing mode to lead by far.
const STOKES_TAU: f64 = 20.0;

/// The `sweep map` of C's radius at 72×60 up to `v0_max`, on all cores.
fn outcome_map(v0_max: f64) -> Result<Vec<crate::analysis::MapRow>, Error> {
    let velocity = crate::engine::Release::Velocity;
    let done = Default::default();
    crate::analysis::outcome_map(0.5, velocity, (72, 60), v0_max, Settings::default(), &done)
}

/// The speed goals; `all` are the rest task's cases and `refs` their reference measures.
pub(super) fn speed(cfg: &Config, all: &[Initial], refs: &[Measure]) -> Result<Speed, Error> {
    let (t, escape_ms) = timed(if cfg.reps == 0 { 0 } else { cfg.reps.max(3) }, || {
        escape_speed(0.5, 0.0, Settings::default(), ESCAPE_VTOL)
    });
    let t = t?;
    let n = if cfg.quick { 24 } else { 72 };
    let xi0s = [0.8, 0.5, 0.2, 0.001];
    let (r, fig5_ms) = timed(cfg.reps.min(2), || {
        sweep_escape(&xi0s, n, Settings::default(), 1e-6, &Default::default())
    });
    r?;
    let fig5_ms_vtol_1e8 = if cfg.quick {
        None
    } else {
        let (r, ms) = timed(1, || {
            sweep_escape(&xi0s, n, Settings::default(), 1e-8, &Default::default())
        });
        r?;
        Some(ms)
    };
    // The escape-speed page's own work for a new ξ0 (the pieces of its job).
    let curve = Job::Curve { xi0: 0.5 };
    let (r, curve_ms) = timed(cfg.reps.min(2), || {
        (0..pieces(&curve))
            .map(|k| match piece(&curve, k, Settings::default()) {
                Piece::Escape {
                    v: crate::analysis::Speeds::Stick { hi, .. },
                    ..
                } => Ok(hi),
                _ => Err(Error::Failed(format!("no escape speed at angle {k}"))),
            })
            .collect::<Result<Vec<f64>, Error>>()
    });
    let top = r?.into_iter().fold(0.0, f64::max);
    let (curve_rhs, curve_near_rhs) = curve_evals()?;
    let (r, map_ms) = timed(cfg.reps.min(2), || outcome_map(1.3 * top));
    r?;
    let escape_angles = if cfg.quick { 3 } else { 12 };
    let escape_cli_ms = escape_cli(&xi0s, escape_angles, false);
    let escape_checked_ms = escape_cli(&xi0s, escape_angles, true);
    let (frame_ms, frame_trail) = frame_time(cfg.reps)?;
    // Ten seconds of play (three in --quick).
    let terminal_bytes = super::bytes::all(if cfg.quick { 90 } else { 300 })?;
    // A recording's worst tick: the largest screen is slow to draw, so a few ticks.
    let recording_bytes = vec![
        super::bytes::cast_worst(crate::replay::DEFAULT_SIZE, 30)?,
        super::bytes::cast_worst(
            (crate::script::MAX_SIZE, crate::script::MAX_SIZE),
            if cfg.quick { 2 } else { 5 },
        )?,
    ];
    // Ten seconds: the first screen alone takes 3.6 s at 4 KB/s.
    // The same with a body: the bar, its centre's path and the panel's body lines as it plays.
    let body = super::link::body_scene();
    let links = [Scene::default_scene(), body]
        .iter()
        .flat_map(|s| {
            super::link::RATES
                .iter()
                .map(move |&r| super::link::simulate_scene(s, r, 10.0))
        })
        .collect::<Result<Vec<_>, _>>()?;
    // The rk2 (stick events) dt = 1e-3 accuracy on the rest task, and the loosest dp54 tol
    // that matches it, on a grid of four tolerances per decade.
    let rest = |s: Settings| -> Result<Vec<Measure>, Error> {
        all.iter()
            .map(|i| Task::Rest.measure(*i, s, ESCAPE_VTOL))
            .collect()
    };
    let rk2 = rest(Settings::fixed(Method::Rk2, 1e-3))?;
    // The cases rk2 gets right and stuck, with their error.
    let right: Vec<(usize, f64)> = (0..all.len())
        .filter(|&k| rk2[k].outcome == refs[k].outcome && refs[k].value.is_some())
        .map(|k| (k, value_error(&rk2[k], &refs[k])))
        .collect();
    let rk2_err = median(&mut right.iter().map(|c| c.1).collect::<Vec<_>>());
    let mut matching = None;
    for k in 12..=40 {
        let tol = 10f64.powf(-k as f64 / 4.0);
        let (mut errs, mut ratios) = (Vec::new(), Vec::new());
        for &(c, _) in &right {
            let e = Task::Rest.measure(all[c], Settings::dp54(tol), ESCAPE_VTOL)?;
            errs.push(value_error(&e, &refs[c]));
            ratios.push(rk2[c].evals as f64 / e.evals as f64);
        }
        let err = median(&mut errs);
        if err <= rk2_err {
            matching = Some((tol, err, median(&mut ratios)));
            break;
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
        curve_ms,
        curve_rhs,
        curve_near_rhs,
        map_ms,
        escape_cli_ms,
        escape_checked_ms,
        escape_angles,
        rk2_err_median: rk2_err,
        matching_tol: matching.map(|m| m.0),
        matching_err_median: matching.map(|m| m.1),
        evals_ratio: matching.map(|m| m.2),
        frame_ms,
        frame_trail,
        terminal_bytes,
        recording_bytes,
        links,
    })
}

/// The median wall time of `turntable escape --xi0 X --phi P --vtol 1e-8` run as a process
/// (this executable), over `xi0s` × `n` angles, with the check of its bracket's ends (the
/// default) or `--no-check`. None if it cannot be run (a test harness).
fn escape_cli(xi0s: &[f64], n: usize, check: bool) -> Option<f64> {
    let exe = std::env::current_exe().ok()?;
    if exe.file_stem()? != "turntable" {
        return None;
    }
    let mut ms = Vec::new();
    for &xi0 in xi0s {
        for k in 0..n {
            let phi = crate::analysis::angle(k, n).to_string();
            let t = Instant::now();
            let out = std::process::Command::new(&exe)
                .args(["escape", "--xi0", &xi0.to_string(), "--phi", &phi])
                .args(["--vtol", "1e-8"])
                .args(if check { &[][..] } else { &["--no-check"][..] })
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::null())
                .status()
                .ok()?;
            if !out.success() {
                return None;
            }
            ms.push(t.elapsed().as_secs_f64() * 1e3);
        }
    }
    Some(median(&mut ms))
}

/// One frame of the explorer as it plays: a tick of simulation and a full draw of the default
/// scene at 160×48, with the paper's run beside it, once the trail holds 20 000 samples.
fn frame_time(reps: usize) -> Result<(f64, usize), Error> {
    use crate::app::{Action, App, update};
    let mut app = App::new(crate::scene::Scene::default_scene());
    update(&mut app, Action::ToggleCompare);
    while app.sim().samples.len() < 20_000 {
        app.tick();
    }
    let ms = super::tick_and_draw_ms(&mut app, (160, 48), reps)?;
    Ok((ms, app.sim().trail().len()))
}

/// For every task with an rk2 dt = 1e-3 row of its own method: the loosest dp54 row of its own at
/// least as accurate (median error), and how many times fewer RHS evaluations it takes (median
/// per case).
pub(super) fn task_ratios(rows: &[Row]) -> Vec<TaskRatio> {
    let own = |r: &&Row| r.measures_its_method();
    let mut out = Vec::new();
    for rk2 in rows
        .iter()
        .filter(|r| r.method == Method::Rk2 && (r.knob / 1e-3 - 1.0).abs() < 1e-9)
        .filter(own)
    {
        let mut dp: Vec<&Row> = rows
            .iter()
            .filter(|r| r.task == rk2.task && r.method == Method::Dp54)
            .filter(own)
            .collect();
        dp.sort_by(|a, b| b.knob.total_cmp(&a.knob));
        if let Some(d) = dp.into_iter().find(|d| d.err_median <= rk2.err_median) {
            out.push(TaskRatio {
                task: rk2.task,
                rk2_err: rk2.err_median,
                rk2_evals: rk2.evals_median,
                dp54_setting: d.setting.clone(),
                dp54_err: d.err_median,
                dp54_evals: d.evals_median,
                ratio: rk2.evals_median / d.evals_median,
            });
        }
    }
    out
}

/// The right-hand-side evaluations of the escape-speed page's curve at ξ0 = 0.5 (its angles, at
/// its settings and bracket): from no curve (a scan of speeds each), and from the curve at 0.49
/// as a held `x` leaves it (`analysis::NEAR_XI0`).
fn curve_evals() -> Result<(u64, u64), Error> {
    use crate::analysis::{CURVE_POINTS, CURVE_VTOL, angle, curve_settings, settings_for};
    use crate::engine::solve::{always, escape_bracket_near, escape_speed};
    let s = curve_settings(settings_for(Settings::default()));
    let (mut cold, mut near) = (0, 0);
    for k in 0..CURVE_POINTS {
        let phi = angle(k, CURVE_POINTS);
        let before = escape_speed(0.49, phi, s, CURVE_VTOL)?;
        cold += escape_speed(0.5, phi, s, CURVE_VTOL)?.rhs_evals;
        near += escape_bracket_near(0.5, phi, s, CURVE_VTOL, before.value, &always)?.2;
    }
    Ok((cold, near))
}
