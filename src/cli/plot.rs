//! `turntable plot`: a figure as SVG, its data from the same code as `sweep` (Figs. 5 and 6,
//! the outcome map) or from one run as the explorer plays it (trajectory, time plots).

use super::numerics::positive;
use super::sweep::{fig5_check, fig5_data, fig6_check, fig6_data, map_check, map_data};
use super::{CmdResult, PlotArgs, PlotFigure, PlotRun, SvgOut};
use crate::engine::solve::critical_radius;
use crate::engine::{Initial, Release, State, Status};
use crate::error::Error;
use crate::files::Output;
use crate::plot::{Figure, build};
use crate::present::{angle, num};
use std::io::Write as _;

pub fn plot(a: PlotArgs) -> CmdResult {
    match a.figure {
        PlotFigure::Fig5 { data, svg } => {
            let settings = fig5_check(&data)?;
            let out = open(&svg)?;
            let points = fig5_data(&data, settings)?;
            let curves: Vec<(f64, Vec<(f64, f64)>)> = data
                .xi0
                .iter()
                .map(|&xi0| {
                    let pts = points.iter().filter(|p| p.xi0 == xi0);
                    (xi0, pts.map(|p| (p.phi, p.v_escape)).collect())
                })
                .collect();
            // True on both sides of ξ = 1 (beyond it slow throws escape too, and a window sticks).
            let title = "Escape speed v_e(φ): thrown faster than v_e at φ, the particle escapes";
            write(out, &svg, &build::escape_speed(title, &curves, None))
        }
        PlotFigure::Fig6 { data, svg } => {
            let settings = fig6_check(&data)?;
            let out = open(&svg)?;
            let points: Vec<(f64, Option<f64>)> = fig6_data(&data, settings)?
                .iter()
                .map(|p| (p.xi0, p.xi))
                .collect();
            let xi0c = critical_radius(settings, 1e-6)
                .map_err(super::solver_budget("--tol"))?
                .value;
            let title = "Released at rest in the lab: the final rest radius";
            write(out, &svg, &build::rest_radius(title, &points, Some(xi0c)))
        }
        PlotFigure::Map { data, svg } => {
            let settings = map_check(&data)?;
            let out = open(&svg)?;
            let super::sweep::MapComputed {
                rows,
                v0_max,
                curve,
            } = map_data(&data, settings)?;
            let cells: Vec<_> = rows
                .iter()
                .map(|r| (r.phi, r.v0, r.cell.rest.map(|(xi, _)| xi)))
                .collect();
            // v_e is a speed relative to the table: drawn where the map's v0 means one.
            let curve = curve
                .filter(|_| data.release != Release::LabRest)
                .map(|c| c.iter().map(|p| (p.phi, p.v_escape)).collect());
            let v_axis = match data.release {
                Release::LabRest => "v0, lab speed of the throw (μg/Ω)",
                _ => "v0, speed relative to the table (μg/Ω)",
            };
            let title = format!("Outcome map at ξ0 = {}", data.xi0);
            let size = (data.phi_points, data.v0_points);
            let fig = build::outcome_map(&title, &cells, size, v0_max, curve, v_axis);
            write(out, &svg, &fig)
        }
        PlotFigure::Trajectory { run, frame, svg } => {
            let picked = pick(&run)?;
            let out = open(&svg)?;
            let played = picked
                .into_iter()
                .map(|(name, i, settings)| Ok((name, play(i, settings, run.tau_max)?)))
                .collect::<Result<Vec<_>, Error>>()?;
            let runs: Vec<build::Traced> = played
                .iter()
                .map(|(name, r)| build::Traced {
                    name: name.clone(),
                    path: &r.path,
                    end: r.end.clone(),
                })
                .collect();
            let title = match &played[..] {
                [(_, one)] => one.title.clone(),
                [rest @ .., (last, _)] => {
                    let rest: Vec<&str> = rest.iter().map(|(n, _)| n.as_str()).collect();
                    format!("{} and {last}", rest.join(", "))
                }
                [] => String::new(),
            };
            write(out, &svg, &build::trajectory(&title, &runs, frame))
        }
        PlotFigure::Time { run, svg } => {
            let [(_, initial, settings)] = &pick(&run)?[..] else {
                return Err(Error::invalid(
                    "plot time draws one run: give one --scene and at most one --method",
                ));
            };
            let out = open(&svg)?;
            let r = play(*initial, *settings, run.tau_max)?;
            let fig = build::time(&r.title, initial, &r.path, &r.work, r.stop);
            write(out, &svg, &fig)
        }
    }
}

/// Opens `--out` before any work: an existing file is refused unless `--force`, an input
/// (the `--scene` file) always.
fn open(svg: &SvgOut) -> Result<Output, Error> {
    crate::files::open_output("--out", &svg.out, svg.force)
}

/// Writes the figure and puts the file in place (never over a file that appeared meanwhile).
fn write(mut out: Output, svg: &SvgOut, fig: &Figure) -> CmdResult {
    let text = crate::plot::to_svg(fig);
    out.write_all(text.as_bytes())
        .and_then(|()| out.finish())
        .map_err(|e| {
            let shown = crate::files::escape_controls(&svg.out.display().to_string());
            Error::io(format!("--out {shown}"), e)
        })
}

/// Each scene's release with the flags' changes, with each --method (else its own
/// integrator), named for the legend.
fn pick(r: &PlotRun) -> Result<Vec<(String, Initial, crate::engine::Settings)>, Error> {
    positive("tau-max", r.tau_max)?;
    let mut out = Vec::new();
    for name in &r.scene {
        let scene = crate::scene::Scene::load(name)?;
        if scene.spin.is_some() {
            return Err(Error::invalid(format!(
                "scene {name}: [spin] spins the table up; `plot` draws the constant-Ω table: open it in the explorer (`turntable --scene {name}`) or report it with `turntable spinup --scene {name}`"
            )));
        }
        let mut i = scene.initial;
        i.xi0 = r.xi0.unwrap_or(i.xi0);
        i.phi = r.phi.unwrap_or(i.phi);
        i.v0 = r.v0.unwrap_or(i.v0);
        i.release = r.release.unwrap_or(i.release);
        let methods = match r.method.is_empty() {
            true => vec![None],
            false => r.method.iter().copied().map(Some).collect(),
        };
        for m in methods {
            let mut settings = scene.settings;
            if let Some(m) = m.filter(|m| *m != settings.method()) {
                settings.scheme = m.with(m.default_knob());
            }
            crate::check::settings(&settings, crate::check::Via::Flags)?;
            crate::check::release(&i, &settings, crate::check::Via::Flags)?;
            // The scene's name is cleaned where it is read (`text::Clean`).
            out.push((
                format!("{} ({})", scene.name.as_str(), settings.method()),
                i,
                settings,
            ));
        }
    }
    Ok(out)
}

/// One run as the explorer plays it, tick by tick: its path on the explorer's τ grid up to
/// the stop (or the escape out of view, or τ-max), how it ended, and a title.
struct Played {
    path: Vec<State>,
    /// The work done up to each point of `path`.
    work: Vec<f64>,
    stop: Option<f64>,
    end: String,
    title: String,
}

fn play(i: Initial, settings: crate::engine::Settings, tau_max: f64) -> Result<Played, Error> {
    let mut sim = crate::sim::Sim::new(i, settings, crate::app::exploration::view_radius(&i))?;
    // Until the τ on screen passes the stop, so that the path holds the stop itself.
    while sim.live()
        && sim.now().tau < tau_max
        && !matches!(sim.status(), Status::Stuck { tau, .. } if sim.now().tau >= tau)
    {
        sim.advance(crate::app::TICK_DT);
    }
    if let Some(e) = sim.error {
        return Err(Error::Run(e));
    }
    let (stop, end) = match (sim.status(), sim.escape()) {
        (Status::Stuck { tau, q }, _) => (
            Some(tau),
            format!("stuck at ξ = {}, τ = {}", num(q.length(), 5), num(tau, 3)),
        ),
        (_, Some(e)) => (None, format!("escaped (certified τ = {})", num(e.tau, 3))),
        _ => (None, format!("τ = {}", sim.now().tau)),
    };
    let until = stop.unwrap_or(f64::INFINITY).min(tau_max);
    let (path, work): (Vec<State>, Vec<f64>) = sim
        .trail()
        .iter()
        .zip(sim.trail_work())
        .filter(|(s, _)| s.tau <= until)
        .map(|(s, w)| (*s, *w))
        .unzip();
    let release = match i.release {
        Release::Velocity => format!("ξ0 = {}, φ = {}, v0 = {}", i.xi0, angle(i.phi), i.v0),
        Release::TableRest => format!("ξ0 = {}, at rest on the table", i.xi0),
        Release::LabRest => format!("ξ0 = {}, at rest in the lab", i.xi0),
    };
    let knob = match settings.scheme.method().adaptive() {
        true => "tol",
        false => "dt",
    };
    let title = format!(
        "Released at {release} ({} {knob} {:e})",
        settings.scheme.method(),
        settings.scheme.knob()
    );
    Ok(Played {
        path,
        work,
        stop,
        end,
        title,
    })
}
