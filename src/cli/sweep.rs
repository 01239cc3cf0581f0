//! `turntable sweep`: the data of Figs. 5 and 6 and of the outcome map, as CSV.

use super::numerics::{positive, solver_settings};
use super::{
    CmdResult, Fig5Data, Fig6Data, MapData, OutArg, SweepArgs, SweepFigure, bracket_width,
    check_initial, num, solver_budget,
};
use crate::engine::Initial;
use crate::engine::solve::{check_escape_xi0, sweep_escape, sweep_rest};
use crate::error::Error;
use crate::files::{Output, emit};
use std::fmt::Write as _;
use std::io::Write as _;

pub fn sweep(a: SweepArgs) -> CmdResult {
    match a.figure {
        SweepFigure::Fig5(f) => fig5(&f.data, &f.out),
        SweepFigure::Fig6(f) => fig6(&f.data, &f.out),
        SweepFigure::Map(m) => sweep_map(&m.data, &m.out),
        SweepFigure::Body(b) => sweep_body(&b),
    }
}

/// `sweep body`: the two-mass body of each length against the point from one release.
fn sweep_body(a: &super::BodySweepArgs) -> CmdResult {
    let initial = Initial {
        xi0: a.xi0,
        phi: a.phi,
        v0: a.v0,
        release: a.release,
        frictionless: false,
    };
    check_initial(&initial)?;
    let settings = a.numerics.settings()?;
    if settings.stokes().is_some() {
        return Err(Error::invalid(
            "sweep body compares stops under dry friction: Stokes drag has none",
        ));
    }
    if !(a.tau_max.is_finite() && a.tau_max > 0.0 && a.tau_max <= 1e6) {
        return Err(Error::invalid(format!(
            "--tau-max must lie in (0, 1e6], got {}",
            Initial::show(a.tau_max)
        )));
    }
    points(a.lengths.len())?;
    let bodies = a
        .lengths
        .iter()
        .map(|&length| {
            let b = crate::engine::body::Body {
                length,
                height: None,
                angle: a.body_angle,
            };
            crate::check::body(&b, crate::check::Via::Flags).map_err(|e| {
                crate::check::retyped(e, crate::engine::error::Field::BodyLength, "--lengths")
            })?;
            Ok(b)
        })
        .collect::<Result<Vec<_>, Error>>()?;
    let out = open_out(&a.out)?;
    let mut run = crate::engine::Run::new(initial, settings)?;
    let (outcome, end) = run.finish(a.tau_max)?;
    let stuck = outcome == crate::engine::Outcome::Stuck;
    let r = end.q().length();
    let tol = settings.scheme.tol().unwrap_or(1e-10);
    let mut csv = String::from("length,l_over_r,outcome,xi,xi_point,xi_error,tau,tau_point\n");
    for b in bodies {
        let mut rod = crate::engine::rod::RodRun::new(b, settings.hold(), &initial, tol)?
            .within(settings.max_steps);
        let o = rod.finish(a.tau_max, |_| {})?;
        let xi = rod.state.q.length();
        // The error is a rest radius's: defined where both stop.
        // At the centre (r = 0) L/r is unbounded: the cell is left empty, and said so below.
        let (l_over_r, xi_point, err) = if stuck && o == crate::engine::Outcome::Stuck {
            let ratio = if r > 0.0 {
                num(b.length / r)
            } else {
                String::new()
            };
            (ratio, num(r), num(xi - r))
        } else {
            (String::new(), String::new(), String::new())
        };
        let _ = writeln!(
            csv,
            "{},{l_over_r},{},{},{xi_point},{err},{},{}",
            num(b.length),
            o.name(),
            num(xi),
            num(rod.state.tau),
            num(end.tau)
        );
    }
    if stuck && r == 0.0 {
        let _ = writeln!(
            std::io::stderr(),
            "note: the point rests at the centre (r = 0), where L/r is unbounded: l_over_r is left empty"
        );
    }
    write_csv(&csv, out, &a.out)
}

/// How many points a sweep may take.
pub(super) fn points(n: usize) -> Result<(), Error> {
    if n == 0 || n > 100_000 {
        return Err(Error::invalid(format!(
            "--points must lie in 1..=100000, got {n}"
        )));
    }
    Ok(())
}

/// Opens `--out` (refusing a bad path) before any work.
fn open_out(out: &OutArg) -> Result<Option<Output>, Error> {
    out.out
        .as_deref()
        .map(|p| crate::files::open_output("--out", p, out.force))
        .transpose()
}

/// Writes the CSV to the output opened by [`open_out`], or to stdout.
fn write_csv(csv: &str, out: Option<Output>, arg: &OutArg) -> CmdResult {
    match (out, &arg.out) {
        (Some(mut f), Some(path)) => f
            .write_all(csv.as_bytes())
            .and_then(|()| f.finish())
            .map_err(|e| {
                let path = crate::files::escape_controls(&path.display().to_string());
                // Errors from the file layer name it already.
                let e = e.to_string();
                Error::Failed(if e.contains(&path) {
                    format!("--out {e}")
                } else {
                    format!("--out {path}: {e}")
                })
            })?,
        _ => emit(None, csv)?,
    }
    Ok(())
}

/// `sweep fig5`: v_e over φ for each ξ0.
fn fig5(a: &Fig5Data, out_arg: &OutArg) -> CmdResult {
    let settings = fig5_check(a)?;
    let out = open_out(out_arg)?;
    let mut csv = String::from("xi0,phi,v_escape\n");
    for p in fig5_data(a, settings)? {
        let _ = writeln!(csv, "{},{},{}", num(p.xi0), num(p.phi), num(p.v_escape));
    }
    write_csv(&csv, out, out_arg)
}

/// Fig. 5's flags checked: the solver's settings.
pub(super) fn fig5_check(a: &Fig5Data) -> Result<crate::engine::Settings, Error> {
    bracket_width("vtol", a.vtol)?;
    points(a.points)?;
    let settings = solver_settings(&a.numerics)?;
    for &xi0 in &a.xi0 {
        check_escape_xi0(xi0)?;
    }
    Ok(settings)
}

/// Fig. 5's points, every curve in turn.
pub(super) fn fig5_data(
    a: &Fig5Data,
    settings: crate::engine::Settings,
) -> Result<Vec<crate::engine::solve::EscapePoint>, Error> {
    let total = a.xi0.len() * a.points;
    super::progress::watch("Fig. 5: escape speeds", total, |done| {
        sweep_escape(&a.xi0, a.points, settings, a.vtol, done)
    })
    .map_err(solver_budget("--vtol"))
}

/// `sweep fig6`: where a release at rest in the lab ends, over ξ0.
fn fig6(a: &Fig6Data, out_arg: &OutArg) -> CmdResult {
    let settings = fig6_check(a)?;
    let out = open_out(out_arg)?;
    let mut csv = String::from("xi0,outcome,xi,angle\n");
    for p in fig6_data(a, settings)? {
        let f = |x: Option<f64>| x.map_or(String::new(), num);
        let _ = writeln!(
            csv,
            "{},{},{},{}",
            num(p.xi0),
            p.outcome.name(),
            f(p.xi),
            // Angles in [0, 2π), as `run` and `sweep map` give them.
            f(p.angle.map(crate::engine::model::turn_angle))
        );
    }
    write_csv(&csv, out, out_arg)
}

/// Fig. 6's flags checked: the solver's settings.
pub(super) fn fig6_check(a: &Fig6Data) -> Result<crate::engine::Settings, Error> {
    points(a.points)?;
    positive("xi0-max", a.xi0_max)?;
    check_initial(&Initial::velocity(a.xi0_max, 0.0, 0.0))
        .map_err(|e| crate::check::retyped(e, crate::engine::error::Field::Xi0, "--xi0-max"))?;
    solver_settings(&a.numerics)
}

/// Fig. 6's points: `--points` radii evenly over [0, --xi0-max].
pub(super) fn fig6_data(
    a: &Fig6Data,
    settings: crate::engine::Settings,
) -> Result<Vec<crate::engine::solve::RestPoint>, Error> {
    let xi0s: Vec<f64> = (0..a.points)
        .map(|i| a.xi0_max * i as f64 / (a.points - 1).max(1) as f64)
        .collect();
    let rest = super::progress::watch("Fig. 6: rest radii", xi0s.len(), |done| {
        sweep_rest(&xi0s, settings, done)
    });
    Ok(rest?)
}

/// `sweep map`: one row per (phi, v0) cell, as the explorer's outcome map classifies it.
fn sweep_map(a: &MapData, out_arg: &OutArg) -> CmdResult {
    let settings = map_check(a)?;
    let out = open_out(out_arg)?;
    let rows = map_data(a, settings)?.rows;
    let mut csv = String::from("phi,v0,outcome,xi,angle\n");
    for r in rows {
        let (xi, angle) = r
            .cell
            .rest
            .map_or((String::new(), String::new()), |(x, t)| (num(x), num(t)));
        let _ = writeln!(
            csv,
            "{},{},{},{xi},{angle}",
            num(r.phi),
            num(r.v0),
            r.cell.outcome.name()
        );
    }
    write_csv(&csv, out, out_arg)
}

/// The map's flags checked: the solver's settings.
pub(super) fn map_check(a: &MapData) -> Result<crate::engine::Settings, Error> {
    bracket_width("vtol", a.vtol)?;
    let settings = solver_settings(&a.numerics)?;
    check_escape_xi0(a.xi0)?;
    for (name, n) in [("phi-points", a.phi_points), ("v0-points", a.v0_points)] {
        if !(1..=2000).contains(&n) {
            return Err(Error::invalid(format!(
                "--{name} must lie in 1..=2000, got {n}"
            )));
        }
    }
    if let Some(v) = a.v0_max {
        positive("v0-max", v)?;
        check_initial(&Initial::velocity(a.xi0, 0.0, v))
            .map_err(|e| crate::check::retyped(e, crate::engine::error::Field::V0, "--v0-max"))?;
    }
    Ok(settings)
}

/// The outcome map computed: its cells, its largest v0, and the escape-speed curve behind the
/// default --v0-max (None when --v0-max was given).
pub(super) struct MapComputed {
    pub rows: Vec<crate::analysis::MapRow>,
    pub v0_max: f64,
    pub curve: Option<Vec<crate::engine::solve::EscapePoint>>,
}

pub(super) fn map_data(
    a: &MapData,
    settings: crate::engine::Settings,
) -> Result<MapComputed, Error> {
    let lab = if a.release == crate::engine::Release::LabRest {
        a.xi0
    } else {
        0.0
    };
    let (v0_max, curve) = match a.v0_max {
        Some(v) => (v, None),
        // Outside ξ = 1 the speeds that stick are a window (Fig. 3 D), not those below a v_e
        // (the solver's v_e there is the window's floor, and a range above it alone showed
        // every cell escaping): the range covers the window's top, as the explorer's map.
        None if a.xi0 > 1.0 => {
            let n = a.phi_points;
            let phis: Vec<f64> = (0..n).map(|i| crate::analysis::angle(i, n)).collect();
            let top = crate::engine::par::par_map(&phis, |&phi| {
                crate::analysis::sticking_speeds(a.xi0, phi, settings, a.vtol).hi()
            })
            .into_iter()
            .flatten()
            .fold(0.0, f64::max);
            ((1.3 * (top + lab)).max(0.2), None)
        }
        None => {
            let curve = super::progress::watch("escape speeds", a.phi_points, |done| {
                sweep_escape(&[a.xi0], a.phi_points, settings, a.vtol, done)
            })
            .map_err(solver_budget("--vtol"))?;
            let top = curve.iter().map(|p| p.v_escape).fold(0.0, f64::max);
            ((1.3 * (top + lab)).max(0.2), Some(curve))
        }
    };
    let cells = a.phi_points * a.v0_points;
    let rows = super::progress::watch("outcome map", cells, |done| {
        crate::analysis::outcome_map(
            a.xi0,
            a.release,
            (a.phi_points, a.v0_points),
            v0_max,
            settings,
            done,
        )
    })?;
    Ok(MapComputed {
        rows,
        v0_max,
        curve,
    })
}
