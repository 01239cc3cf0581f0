//! The headless numerical commands: run, escape, critical (sweep is in `sweep`).

use super::report::{BodyReport, CriticalReport, EscapeReport, Report, RunReport};
use super::{
    CmdResult, CriticalArgs, Error, EscapeArgs, RunArgs, bracket_width, check_initial, num,
    solver_budget,
};
use crate::engine::solve::{
    check_escape_xi0, critical_radius_until, escape_speed, solve_certified,
};
use crate::engine::{Initial, Outcome, Run, State, Status};
use crate::files::{Output, emit};
use std::io::{BufWriter, Write as _};

const TAU_MAX_LIMIT: f64 = 1e9;

/// The trajectory file's columns.
const TRAJECTORY_HEADER: &[u8] = b"tau,x,y,xq,yq,u,stuck,energy,work,approx_xi\n";

/// Writes trajectory rows: the state, E = ½|u|² − ½ξ² and −∫|u|dτ (Gauss–Legendre on each
/// step's dense output, [`crate::engine::work::Tally`]; dE/dτ = −|u|, so the two differ by
/// E(0) up to the run's own error), and the Sec. III
/// approximation of ξ for a release at rest (Eq. 13 in the lab, Eq. 19 on the table for
/// ξ0 > 1; valid only early, see docs/command-line.md), empty otherwise. Under Stokes drag the work is
/// −γ∫|u|²dτ, and no approximation applies.
struct Rows {
    initial: Initial,
    work: f64,
    /// The run is in closed form (μ = 0 or Stokes drag).
    closed: bool,
}

impl Rows {
    fn write(
        &mut self,
        csv: &mut impl std::io::Write,
        s: &State,
        stuck: bool,
    ) -> std::io::Result<()> {
        let (q, u) = (s.q(), s.u_lab().length());
        let i = self.initial;
        let approx = match i.release {
            _ if i.frictionless || self.closed => None,
            crate::engine::Release::LabRest => {
                Some(crate::engine::approx::lab_rest(i.xi0, s.tau).0)
            }
            crate::engine::Release::TableRest if i.xi0 > 1.0 => {
                Some(crate::engine::approx::table_rest(i.xi0, s.tau).0)
            }
            _ => None,
        };
        writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{}",
            num(s.tau),
            num(s.r.x),
            num(s.r.y),
            num(q.x),
            num(q.y),
            num(u),
            u8::from(stuck),
            num(s.energy()),
            num(self.work),
            approx.map_or(String::new(), |x| x.to_string())
        )
    }
}

/// Spacing in τ of the trajectory rows of a closed-form run (μ = 0, Stokes drag), which takes
/// no steps: as far as one quadrature of its work reaches.
const FREE_SAMPLE: f64 = crate::engine::work::CLOSED_PIECE;

pub fn run(a: RunArgs) -> CmdResult {
    let (initial, settings) = run_inputs(&a)?;
    let (settings, choice) = match a.error {
        Some(e) => {
            let c = choose(initial, settings, &a, e)?;
            (c.chosen.map_or(settings, |t| t.settings), Some(c))
        }
        None => (settings, None),
    };
    let units = a.units.units()?;
    let body = a
        .body
        .body(units.as_ref(), "--mu and --rpm (and optionally --g)")?;
    // The file is opened (and a bad path refused) before any work; rows stream into it.
    let csv = match &a.trajectory {
        Some(path) => Some(BufWriter::new(crate::files::open_output(
            "--trajectory",
            path,
            a.force,
        )?)),
        None => None,
    };
    let mut run = Run::new(initial, settings)?;
    let (end, ms) = crate::bench::time_ms(|| {
        integrate(&mut run, a.tau_max, !a.follow, csv, a.trajectory.as_deref())
    });
    let end = end?;
    let doubt = (!a.no_check).then(|| crate::engine::doubt::doubt(&run, a.tau_max));
    let mut report = RunReport::new(&run, &end, doubt, units);
    report.chosen = choice.map(|c| super::report::ChosenReport::new(&c, ms));
    report.body = match body {
        Some(b) => {
            let mut r = BodyReport::new(b, &run, &end, units);
            r.motion = rod_motion(b, &initial, settings, a.tau_max, !a.no_check)?;
            Some(r)
        }
        None => None,
    };
    report.body_outcome = report
        .body
        .as_ref()
        .and_then(|b| b.motion.as_ref())
        .map(|m| m.outcome);
    print(&report, a.json)
}

/// `run --error E`: the cheapest setting whose stated error is at most `error`
/// ([`crate::sim::accuracy`]), the rest of the settings from the flags; E refused as typed, and
/// a release no setting can state so well said as such (exit 1).
fn choose(
    initial: Initial,
    settings: crate::engine::Settings,
    a: &RunArgs,
    error: f64,
) -> Result<crate::sim::accuracy::Choice, Error> {
    use crate::sim::accuracy::{cheapest, refused};
    if let Some(why) = refused(error) {
        return Err(Error::invalid(format!(
            "--error {why} (the stated error of the end's time and place)"
        )));
    }
    if crate::engine::closed_form(&initial, settings) {
        return Err(Error::invalid(
            "--error chooses a method and tolerance: a frictionless or Stokes-drag run is in closed form, exact",
        ));
    }
    let c = cheapest(initial, settings, a.tau_max, !a.follow, error)?;
    if c.chosen.is_none() {
        return Err(Error::Failed(c.said(None)));
    }
    Ok(c)
}

/// The two-mass body run from the same release, under Coulomb friction (μ = 0 and Stokes drag
/// have no stick to model: None), at the run's tolerance (1e-10 for the fixed-step methods);
/// with `check`, again at tol/1000 (not below 1e-14) to measure how far its end lies.
fn rod_motion(
    body: crate::engine::body::Body,
    initial: &Initial,
    settings: crate::engine::Settings,
    tau_max: f64,
    check: bool,
) -> Result<Option<super::report::MotionReport>, Error> {
    if crate::engine::closed_form(initial, settings) {
        return Ok(None);
    }
    let tol = settings.scheme.tol().unwrap_or(1e-10);
    let end = |tol: f64| -> Result<_, Error> {
        let mut rod = crate::engine::rod::RodRun::new(body, settings.hold(), initial, tol)?
            .within(settings.max_steps);
        let outcome = rod.finish(tau_max, |_| {})?;
        Ok((rod, outcome))
    };
    let (rod, outcome) = end(tol)?;
    // At the tightest tol there is nothing tighter to ask.
    let tight = (tol * 1e-3).max(crate::engine::method::TOL_RANGE.0);
    let tight = (check && tight < tol).then(|| (tight, end(tight)));
    Ok(Some(super::report::MotionReport::new(&rod, outcome, tight)))
}

/// The release and settings `run` was asked for, checked.
fn run_inputs(a: &RunArgs) -> Result<(Initial, crate::engine::Settings), Error> {
    let initial = Initial {
        xi0: a.xi0,
        phi: a.phi,
        v0: a.v0,
        release: a.release,
        frictionless: a.frictionless,
    };
    if !(a.tau_max.is_finite() && a.tau_max > 0.0 && a.tau_max <= TAU_MAX_LIMIT) {
        return Err(Error::invalid(format!(
            "--tau-max must lie in (0, {TAU_MAX_LIMIT:e}], got {}",
            Initial::show(a.tau_max)
        )));
    }
    let settings = a.numerics.settings()?;
    crate::check::release(&initial, &settings, crate::check::Via::Flags)?;
    Ok((initial, settings))
}

/// Runs to its outcome (past the escape certificate unless `stop_on_escape`) or `tau_max`,
/// writing a trajectory row per step to `csv` (the file at `path`); returns the state that
/// decided it.
fn integrate(
    run: &mut Run,
    tau_max: f64,
    stop_on_escape: bool,
    mut csv: Option<BufWriter<Output>>,
    path: Option<&std::path::Path>,
) -> Result<State, Error> {
    let initial = run.initial();
    // Named with its path: a full disk or a device that takes nothing says which file.
    let what = path.map_or_else(String::new, |p| {
        let shown = crate::files::escape_controls(&p.display().to_string());
        format!("writing --trajectory {shown}")
    });
    let write_err = |e: std::io::Error| Error::io(what.clone(), e);
    let mut rows = Rows {
        initial,
        work: 0.0,
        closed: run.closed_form(),
    };
    if let Some(csv) = csv.as_mut() {
        csv.write_all(TRAJECTORY_HEADER).map_err(write_err)?;
        rows.write(csv, &run.state(), run.status() != Status::Slipping)
            .map_err(write_err)?;
    }
    let mut tally = crate::engine::work::Tally::new(run);
    while run.goes_on(tau_max, stop_on_escape) {
        let before = run.tau();
        run.step(tau_max)?;
        if let Some(csv) = csv.as_mut() {
            if rows.closed {
                // No steps to write: sample the closed form instead.
                let n = ((run.tau() - before) / FREE_SAMPLE).ceil().min(1e5) as usize;
                for i in 1..n {
                    let t = before + (run.tau() - before) * i as f64 / n as f64;
                    let s = run.state_at(t)?;
                    rows.work = tally.to(run, t)?;
                    rows.write(csv, &s, false).map_err(write_err)?;
                }
            }
            rows.work = tally.to(run, run.tau())?;
            rows.write(csv, &run.state(), run.status() != Status::Slipping)
                .map_err(write_err)?;
        }
    }
    if let Some(csv) = csv {
        csv.into_inner()
            .map_err(|e| write_err(e.into_error()))?
            .finish()
            .map_err(write_err)?;
    }
    Ok(match (run.outcome(), run.escape()) {
        (Outcome::Escaped, Some(e)) if stop_on_escape => e.state,
        _ => run.state(),
    })
}

/// Prints a report: one line of JSON, or its text.
fn print(report: &(impl Report + serde::Serialize), json: bool) -> CmdResult {
    let out = if json {
        serde_json::to_string(report).map_err(|e| Error::Failed(e.to_string()))? + "\n"
    } else {
        report.text()
    };
    emit(None, &out)?;
    Ok(())
}

/// Settings for the solvers, which classify runs by how they end: the paper's raw scheme never
/// comes to rest, so it cannot.
pub(super) fn solver_settings(n: &super::NumericsArgs) -> Result<crate::engine::Settings, Error> {
    let s = n.settings()?;
    if let Some(gamma) = s.stokes() {
        return Err(Error::invalid(format!(
            "under Stokes drag (gamma {}) there is no escape speed, critical radius or outcome map: every release leaves, at the rate {} (turntable run --coupling stokes says how)",
            Initial::show(gamma),
            crate::engine::stokes::growth_rate(gamma)
        )));
    }
    if !s.method().stick_events() {
        return Err(Error::invalid(format!(
            "{} has no stick event, so its runs never come to rest: the solvers need dp54, dop853, rk4 or rk2",
            s.method()
        )));
    }
    Ok(s)
}

pub(super) fn positive(name: &str, x: f64) -> Result<(), Error> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(format!(
            "--{name} must be a positive number, got {}",
            Initial::show(x)
        )))
    }
}

pub fn escape(a: EscapeArgs) -> CmdResult {
    check_initial(&Initial::velocity(a.xi0, a.phi, 0.0))?;
    check_escape_xi0(a.xi0)?;
    bracket_width("vtol", a.vtol)?;
    let settings = solver_settings(&a.numerics)?;
    let solve = |s| escape_speed(a.xi0, a.phi, s, a.vtol).map_err(solver_budget("--vtol"));
    let (t, certified) = if a.no_check {
        (solve(settings)?, None)
    } else {
        let at = |v0: f64| Initial::velocity(a.xi0, a.phi, v0);
        let (t, c) = solve_certified(settings, solve, at)?;
        (t, Some(c))
    };
    print(
        &EscapeReport::new(a.xi0, a.phi, &t, certified, &settings),
        a.json,
    )
}

pub fn critical(a: CriticalArgs) -> CmdResult {
    bracket_width("xtol", a.xtol)?;
    positive("g", a.g)?;
    if let (Some(w), Some(r)) = (a.omega, a.r0c) {
        positive("omega", w)?;
        positive("r0c", r)?;
        let m = w * w * r / a.g;
        if !(m.is_finite() && m > 0.0) {
            return Err(Error::invalid(format!(
                "mu = omega² r0c / (xi0c g) is out of range for omega {}, r0c {}, g {}: check the units (rad/s, m, m/s²)",
                Initial::show(w),
                Initial::show(r),
                Initial::show(a.g)
            )));
        }
    }
    let settings = solver_settings(&a.numerics)?;
    // The runs it takes: a scan of 31 radii, then a bisection to --xtol (and the bracket's
    // two ends in full with their second opinions).
    let runs = 31 + (0.05 / a.xtol).log2().ceil().max(0.0) as usize + 2 * usize::from(!a.no_check);
    let (t, certified) = super::progress::watch("critical radius: runs", runs, |done| {
        let counted = || {
            done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            true
        };
        let solve = |s| critical_radius_until(s, a.xtol, &counted).map_err(solver_budget("--xtol"));
        if a.no_check {
            Ok::<_, Error>((solve(settings)?, None))
        } else {
            let at = |xi0: f64| Initial::at_rest(xi0, crate::engine::Release::LabRest);
            let (t, c) = solve_certified(settings, solve, at)?;
            Ok((t, Some(c)))
        }
    })?;
    // The paper's Eq. 22: mu = Omega² r0c / (xi0c g), friction measured by the critical radius.
    let mu = a.omega.zip(a.r0c).map(|(w, r)| w * w * r / (t.value * a.g));
    print(&CriticalReport::new(&t, certified, mu, &settings), a.json)
}
