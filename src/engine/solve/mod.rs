//! Solvers over many runs (Sec. IV): the escape speed v_e(ξ0, φ) of Fig. 5, the critical
//! radius ξ0c of Fig. 6, and sweeps of both.

use super::doubt::doubt;
use super::method::{Settings, TOL_RANGE};
use super::model::{Initial, Release};
use super::par::par_map_counted;
use super::roots::bisect;
use super::run::{Outcome, Run};
use crate::error::Error;
use serde::Serialize;
use std::sync::atomic::AtomicUsize;

mod escape;
mod kept;

pub use escape::{
    MAX_ESCAPE_XI0, check_escape_xi0, escape_bracket_near, escape_speed, escape_speed_until,
};
pub use kept::Kept;

/// Asked by a solver before each of its runs: `false` ends the solver with
/// [`Error::Cancelled`]. A caller whose answer became moot (the explorer's page asked for
/// another) so waits for at most one run, itself bounded by `Settings::max_steps`.
pub type GoOn<'a> = &'a dyn Fn() -> bool;

/// A [`GoOn`] that never cancels.
pub fn always() -> bool {
    true
}

fn check(go_on: GoOn) -> Result<(), Error> {
    if go_on() {
        Ok(())
    } else {
        Err(Error::Cancelled)
    }
}

/// Time limit of one classifying run. Every run ends stuck or certified long before this except
/// exactly at a threshold, where the particle lingers at the saddle ξ = 1, u = 0.
pub const CLASSIFY_TAU: f64 = 1e4;

/// A threshold located by bisection on the outcome, with its certificate: a run on each side.
#[derive(Clone, Debug, Serialize)]
pub struct Threshold {
    /// Midpoint of the final bracket.
    pub value: f64,
    /// Largest value below the threshold that a run saw stick (none if the least value
    /// scanned already escapes), and least value seen to escape.
    pub stuck_at: Option<f64>,
    pub escapes_at: f64,
    /// Whether the scan saw the escaping set as one interval above the threshold.
    pub interval: bool,
    /// The coarse scan: each value run and whether it escaped. Where the escaping values are
    /// not one interval, this is what is known of them.
    pub scan: Vec<(f64, bool)>,
    pub runs: u32,
    pub rhs_evals: u64,
    /// dp54's tolerance in the runs that decided the bracket: the one asked for, floored at
    /// 1/100 of the bracket's width (a looser run misplaces the threshold by more than that).
    pub run_tol: Option<f64>,
    /// How many times [`solve_certified`] solved again 100× tighter.
    pub tightened: u32,
    /// The runs at the bracket's ends where they stopped, for [`certify`] to continue.
    #[serde(skip)]
    pub kept: Kept,
}

/// `settings` with its adaptive method at `tol` (not below 1e-14); fixed-step settings as
/// they are.
fn with_tol(settings: Settings, tol: f64) -> Settings {
    match settings.scheme.tol() {
        Some(_) => Settings {
            scheme: settings.scheme.with_knob(tol.max(TOL_RANGE.0)),
            ..settings
        },
        None => settings,
    }
}

/// `settings` with an adaptive method's tolerance no looser than 1/100 of a bracket `width`:
/// near a threshold a run's error moves the threshold by about its tolerance (measured on
/// Fig. 5's points), and up to ~15× that near the rim.
pub fn floor_tol(settings: Settings, width: f64) -> Settings {
    match settings.scheme.tol() {
        Some(tol) => with_tol(settings, tol.min(1e-2 * width)),
        None => settings,
    }
}

/// Whether both ends of `t`'s bracket end as it says when run in full (no shortcut) at the
/// tolerance that placed them, each [`confirmed`] by its second opinion (the judge: dop853,
/// tighter, in the other frame). `at` makes the
/// release from the bracket's variable. A bracket with no stuck end has only its escaping end.
/// The runs and their cost are added to `t`'s.
pub fn certify(
    t: &mut Threshold,
    settings: Settings,
    at: impl Fn(f64) -> Initial,
) -> Result<bool, Error> {
    let settings = match t.run_tol {
        Some(tol) => with_tol(settings, tol),
        None => settings,
    };
    let mut ends = vec![(t.escapes_at, Outcome::Escaped)];
    ends.extend(t.stuck_at.map(|lo| (lo, Outcome::Stuck)));
    let mut ok = true;
    for (x, want) in ends {
        let (run, made) = match t.kept.take(x, want, at(x), settings) {
            Some(run) => (run, 1),
            None => (Run::new(at(x), settings)?, 2),
        };
        let (yes, evals) = confirmed(run, want)?;
        (t.runs, t.rhs_evals) = (t.runs + made, t.rhs_evals + evals);
        ok &= yes;
        if !ok {
            break;
        }
    }
    Ok(ok)
}

/// Solves with `solve` at `settings` and [`certify`]s the bracket; while that fails, solves
/// again with dp54 100× tighter (twice at most, not below 1e-14): a run misplaces the threshold
/// by about its tolerance, so an end placed within that of it may lie on the wrong side. The
/// answer (its cost counting every attempt), and whether its bracket is certified.
pub fn solve_certified<E: From<Error>>(
    settings: Settings,
    solve: impl Fn(Settings) -> Result<Threshold, E>,
    at: impl Fn(f64) -> Initial,
) -> Result<(Threshold, bool), E> {
    let mut t = solve(settings)?;
    for _ in 0..2 {
        if certify(&mut t, settings, &at)? {
            return Ok((t, true));
        }
        let Some(tol) = t.run_tol.filter(|&tol| tol > TOL_RANGE.0) else {
            return Ok((t, false));
        };
        let (runs, evals, tightened) = (t.runs, t.rhs_evals, t.tightened);
        t = solve(with_tol(settings, 1e-2 * tol))?;
        t.runs += runs;
        t.rhs_evals += evals;
        t.tightened = tightened + 1;
    }
    let ok = certify(&mut t, settings, &at)?;
    Ok((t, ok))
}

/// Whether `run`, run on in full with no shortcut (from its start, or from where a solver
/// stopped it: [`Kept`]), ends as `want` (stuck, or escaped with its certificate), and its
/// second opinion ([`doubt`]: another frame, dop853, tighter) agrees with a margin: what
/// certifies one end of a bracket. Also the right-hand-side evaluations both took from here.
pub fn confirmed(mut run: Run, want: Outcome) -> Result<(bool, u64), Error> {
    let before = run.cost().rhs_evals;
    let own = run.run(CLASSIFY_TAU, true)?;
    let d = doubt(&run, CLASSIFY_TAU);
    Ok((
        own == want && d.certain,
        run.cost().rhs_evals - before + d.check_evals,
    ))
}

/// Runs every value of `grid`: the index of the first that escapes, whether all after it
/// escape too, and each value's outcome.
#[allow(clippy::type_complexity)]
fn scan(
    grid: &[f64],
    mut escapes: impl FnMut(f64) -> Result<bool, Error>,
) -> Result<(usize, bool, Vec<(f64, bool)>), Error> {
    let outcomes = grid
        .iter()
        .map(|&x| escapes(x).map(|e| (x, e)))
        .collect::<Result<Vec<_>, _>>()?;
    let first = outcomes.iter().position(|o| o.1).ok_or(Error::NoAnswer(
        "no escape found in the scanned range".into(),
    ))?;
    let interval = outcomes[first..].iter().all(|o| o.1);
    Ok((first, interval, outcomes))
}

/// Critical radius ξ0c (Sec. IV, Fig. 6): the largest ξ0 at which a particle released at rest
/// in the lab still ends stuck.
pub fn critical_radius(settings: Settings, tol: f64) -> Result<Threshold, Error> {
    critical_radius_until(settings, tol, &always)
}

/// [`critical_radius`], asking `go_on` before each run.
pub fn critical_radius_until(
    settings: Settings,
    tol: f64,
    go_on: GoOn,
) -> Result<Threshold, Error> {
    let settings = floor_tol(settings, tol);
    let (mut evals, mut kept) = (0, Kept::default());
    let mut classify = |xi0: f64| -> Result<bool, Error> {
        check(go_on)?;
        let mut run = Run::new(Initial::at_rest(xi0, Release::LabRest), settings)?;
        let escapes = run.run(CLASSIFY_TAU, true)? != Outcome::Stuck;
        evals += run.cost().rhs_evals;
        kept.keep(xi0, escapes, run);
        Ok(escapes)
    };
    let grid: Vec<f64> = (0..=30).map(|i| 1.5 * i as f64 / 30.0).collect();
    let (first, interval, scanned) = scan(&grid, &mut classify)?;
    if first == 0 {
        return Err(Error::NoAnswer(
            "released at rest in the lab at the centre, the particle escaped".into(),
        ));
    }
    let (lo, hi, runs) = bisect(grid[first - 1], grid[first], tol, &mut classify)?;
    Ok(Threshold {
        value: 0.5 * (lo + hi),
        stuck_at: Some(lo),
        escapes_at: hi,
        interval,
        runs: scanned.len() as u32 + runs,
        scan: scanned,
        rhs_evals: evals,
        run_tol: settings.scheme.tol(),
        tightened: 0,
        kept,
    })
}

/// One point of Fig. 5.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct EscapePoint {
    pub xi0: f64,
    pub phi: f64,
    pub v_escape: f64,
}

/// Fig. 5: v_e over `n` angles φ in [0, 2π) for each ξ0; `done` counts the points found.
pub fn sweep_escape(
    xi0s: &[f64],
    n: usize,
    settings: Settings,
    tol: f64,
    done: &AtomicUsize,
) -> Result<Vec<EscapePoint>, Error> {
    let jobs: Vec<(f64, f64)> = xi0s
        .iter()
        .flat_map(|&xi0| (0..n).map(move |i| (xi0, std::f64::consts::TAU * i as f64 / n as f64)))
        .collect();
    par_map_counted(&jobs, done, |&(xi0, phi)| {
        escape_speed(xi0, phi, settings, tol).map(|t| EscapePoint {
            xi0,
            phi,
            v_escape: t.value,
        })
    })
    .into_iter()
    .collect()
}

/// One point of Fig. 6: where a particle released at rest in the lab at ξ0 ends.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct RestPoint {
    pub xi0: f64,
    pub outcome: Outcome,
    /// Final rest ξ and angle (table frame), when stuck.
    pub xi: Option<f64>,
    pub angle: Option<f64>,
}

/// Fig. 6: the final rest position against ξ0 for release at rest in the lab; `done` counts
/// the points found.
pub fn sweep_rest(
    xi0s: &[f64],
    settings: Settings,
    done: &AtomicUsize,
) -> Result<Vec<RestPoint>, Error> {
    par_map_counted(xi0s, done, |&xi0| {
        let mut run = Run::new(Initial::at_rest(xi0, Release::LabRest), settings)?;
        let (outcome, s) = run.finish(CLASSIFY_TAU)?;
        let stuck = outcome == Outcome::Stuck;
        let q = s.q();
        Ok(RestPoint {
            xi0,
            outcome,
            xi: stuck.then(|| q.length()),
            angle: stuck.then(|| q.y.atan2(q.x)),
        })
    })
    .into_iter()
    .collect()
}
