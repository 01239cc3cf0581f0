//! `turntable sweep`: the data of Figs. 5 and 6 and of the outcome map, as CSV.

use super::numerics::{positive, solver_settings};
use super::{
    CmdResult, Fig5Args, Fig6Args, MapArgs, OutArg, SweepArgs, SweepFigure, bracket_width,
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
        SweepFigure::Fig5(f) => fig5(&f),
        SweepFigure::Fig6(f) => fig6(&f),
        SweepFigure::Map(m) => sweep_map(&m),
    }
}

/// How many points a sweep may take.
fn points(n: usize) -> Result<(), Error> {
    if n == 0 || n > 100_000 {
        return Err(Error::Invalid(format!(
            "points must lie in 1..=100000, got {n}"
        )));
    }
    Ok(())
}

/// Opens `--out` (refusing a bad path) before any work.
fn open_out(out: &OutArg) -> Result<Option<Output>, Error> {
    out.out
        .as_deref()
        .map(Output::create)
        .transpose()
        .map_err(|e| Error::Invalid(format!("--out: {e}")))
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
fn fig5(a: &Fig5Args) -> CmdResult {
    bracket_width("vtol", a.vtol)?;
    points(a.points)?;
    let settings = solver_settings(&a.numerics)?;
    for &xi0 in &a.xi0 {
        check_escape_xi0(xi0)?;
    }
    let out = open_out(&a.out)?;
    let mut csv = String::from("xi0,phi,v_escape\n");
    let curves =
        sweep_escape(&a.xi0, a.points, settings, a.vtol).map_err(solver_budget("--vtol"))?;
    for p in curves {
        let _ = writeln!(csv, "{},{},{}", num(p.xi0), num(p.phi), num(p.v_escape));
    }
    write_csv(&csv, out, &a.out)
}

/// `sweep fig6`: where a release at rest in the lab ends, over ξ0.
fn fig6(a: &Fig6Args) -> CmdResult {
    points(a.points)?;
    positive("xi0-max", a.xi0_max)?;
    check_initial(&Initial::velocity(a.xi0_max, 0.0, 0.0))?;
    let settings = solver_settings(&a.numerics)?;
    let out = open_out(&a.out)?;
    let xi0s: Vec<f64> = (0..a.points)
        .map(|i| a.xi0_max * i as f64 / (a.points - 1).max(1) as f64)
        .collect();
    let mut csv = String::from("xi0,outcome,xi,angle\n");
    for p in sweep_rest(&xi0s, settings)? {
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
    write_csv(&csv, out, &a.out)
}

/// `sweep map`: one row per (phi, v0) cell, as the explorer's outcome map classifies it.
fn sweep_map(a: &MapArgs) -> CmdResult {
    let xi0 = a.xi0;
    bracket_width("vtol", a.vtol)?;
    let settings = solver_settings(&a.numerics)?;
    check_escape_xi0(xi0)?;
    for (name, n) in [("phi-points", a.phi_points), ("v0-points", a.v0_points)] {
        if !(1..=2000).contains(&n) {
            return Err(Error::invalid(format!(
                "{name} must lie in 1..=2000, got {n}"
            )));
        }
    }
    if let Some(v) = a.v0_max {
        positive("v0-max", v)?;
        check_initial(&Initial::velocity(xi0, 0.0, v))?;
    }
    let out = open_out(&a.out)?;
    let v0_max = match a.v0_max {
        Some(v) => v,
        None => {
            let curve = sweep_escape(&[xi0], a.phi_points, settings, a.vtol)
                .map_err(solver_budget("--vtol"))?;
            let top = curve.iter().map(|p| p.v_escape).fold(0.0, f64::max);
            let lab = if a.release == crate::engine::Release::LabRest {
                xi0
            } else {
                0.0
            };
            (1.3 * (top + lab)).max(0.2)
        }
    };
    let rows = crate::analysis::outcome_map(
        xi0,
        a.release,
        (a.phi_points, a.v0_points),
        v0_max,
        settings,
    )?;
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
    write_csv(&csv, out, &a.out)
}
