//! `turntable sweep`: the data of Figs. 5 and 6 and of the outcome map, as CSV.

use super::numerics::{positive, solver_settings};
use super::{CmdResult, SweepArgs, check_initial};
use crate::engine::Initial;
use crate::engine::solve::{check_escape_xi0, sweep_escape, sweep_rest};
use crate::error::Error;
use crate::files::{Output, emit};
use std::fmt::Write as _;
use std::io::Write as _;

pub fn sweep(a: SweepArgs) -> CmdResult {
    positive("vtol", a.vtol)?;
    if a.points == 0 || a.points > 100_000 {
        return Err(Error::Invalid(format!(
            "points must lie in 1..=100000, got {}",
            a.points
        )));
    }
    let settings = solver_settings(&a.numerics)?;
    let out = a
        .out
        .as_deref()
        .map(Output::create)
        .transpose()
        .map_err(|e| Error::Invalid(format!("--out: {e}")))?;
    let mut csv = String::new();
    if a.figure == "map" {
        csv = sweep_map(&a, settings)?;
    } else if a.figure == "fig5" {
        let xi0s = if a.xi0.is_empty() {
            crate::analysis::PAPER_XI0.to_vec()
        } else {
            a.xi0.clone()
        };
        for &xi0 in &xi0s {
            check_escape_xi0(xi0)?;
        }
        csv.push_str("xi0,phi,v_escape\n");
        for p in sweep_escape(&xi0s, a.points, settings, a.vtol)? {
            let _ = writeln!(csv, "{},{},{}", p.xi0, p.phi, p.v_escape);
        }
    } else {
        positive("xi0-max", a.xi0_max)?;
        check_initial(&Initial::velocity(a.xi0_max, 0.0, 0.0))?;
        let xi0s: Vec<f64> = (0..a.points)
            .map(|i| a.xi0_max * i as f64 / (a.points - 1).max(1) as f64)
            .collect();
        csv.push_str("xi0,outcome,xi,angle\n");
        for p in sweep_rest(&xi0s, settings)? {
            let f = |x: Option<f64>| x.map_or(String::new(), |x| x.to_string());
            let _ = writeln!(
                csv,
                "{},{},{},{}",
                p.xi0,
                p.outcome.name(),
                f(p.xi),
                // Angles in [0, 2π), as `run` and `sweep map` give them.
                f(p.angle.map(crate::engine::model::turn_angle))
            );
        }
    }
    match out {
        Some(mut f) => {
            f.write_all(csv.as_bytes())?;
            f.finish()?;
        }
        None => emit(None, &csv)?,
    }
    Ok(())
}

/// `sweep map`: one row per (phi, v0) cell, as the explorer's outcome map classifies it.
fn sweep_map(a: &SweepArgs, settings: crate::engine::Settings) -> Result<String, Error> {
    let [xi0] = a.xi0[..] else {
        return Err(Error::invalid(format!(
            "sweep map takes one --xi0, got {}",
            a.xi0.len()
        )));
    };
    check_escape_xi0(xi0)?;
    for (name, n) in [("phi-points", a.phi_points), ("v0-points", a.v0_points)] {
        if !(1..=2000).contains(&n) {
            return Err(Error::invalid(format!(
                "{name} must lie in 1..=2000, got {n}"
            )));
        }
    }
    let v0_max = match a.v0_max {
        Some(v) => {
            positive("v0-max", v)?;
            check_initial(&Initial::velocity(xi0, 0.0, v))?;
            v
        }
        None => {
            let curve = sweep_escape(&[xi0], a.phi_points, settings, a.vtol)?;
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
            .map_or((String::new(), String::new()), |(x, t)| {
                (x.to_string(), t.to_string())
            });
        let _ = writeln!(
            csv,
            "{},{},{},{xi},{angle}",
            r.phi,
            r.v0,
            r.cell.outcome.name()
        );
    }
    Ok(csv)
}
