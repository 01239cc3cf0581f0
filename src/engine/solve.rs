//! Solvers over many runs (Sec. IV): the escape speed v_e(ξ0, φ) of Fig. 5, the critical
//! radius ξ0c of Fig. 6, and sweeps of both.

use super::doubt::doubt;
use super::method::{Scheme, Settings, TOL_RANGE};
use super::model::{Initial, Release};
use super::par::par_map;
use super::roots::{bisect, golden_min};
use super::run::{Outcome, Run};
use super::saddle::{Fate, fate, saddle_h};
use crate::engine::error::{Error, Field, Invalid, Range};
use serde::Serialize;

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
#[derive(Clone, Debug, Serialize, PartialEq)]
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
/// tolerance that placed them, each [`confirmed`] by its second opinion (the judge: 1000×
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
        let (yes, evals) = confirmed(at(x), settings, want)?;
        (t.runs, t.rhs_evals) = (t.runs + 2, t.rhs_evals + evals);
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

/// Whether the release `initial` ends as `want` (stuck, or escaped with its certificate) when
/// run in full at `settings` with no shortcut, and its second opinion ([`doubt`]: another frame,
/// 1000× tighter) agrees with a margin: what certifies one end of a bracket. Also the
/// right-hand-side evaluations both took.
pub fn confirmed(
    initial: Initial,
    settings: Settings,
    want: Outcome,
) -> Result<(bool, u64), Error> {
    let mut run = Run::new(initial, settings)?;
    let own = run.run(CLASSIFY_TAU, true)?;
    let d = doubt(&run, CLASSIFY_TAU);
    Ok((
        own == want && d.certain,
        run.cost().rhs_evals + d.check_evals,
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

/// Outcome of one classifying run at speed v0, and the smooth measure H at its end when the
/// run went all the way (see [`saddle_h`]).
struct Probe {
    escapes: bool,
    h: Option<f64>,
}

/// Classifies the release at `initial` with `settings`. With `early`, a run stops as soon as it
/// is certified to stick (H < 0 inside ξ < 1) and reports no H; otherwise a stuck run goes on
/// to its stop, and H there is reported.
fn probe(
    initial: Initial,
    settings: Settings,
    early: bool,
    evals: &mut u64,
    go_on: GoOn,
) -> Result<Probe, Error> {
    use super::run::Status;
    check(go_on)?;
    let mut run = Run::new(initial, settings)?;
    let result = loop {
        if let Status::Stuck { q, .. } = run.status() {
            let gap = 1.0 - q.length();
            break Probe {
                escapes: false,
                h: Some(-0.5 * gap * gap),
            };
        }
        if let Some(e) = run.escape() {
            let s = e.state;
            let h = saddle_h(&s);
            break Probe {
                escapes: true,
                h: (h > 0.0).then_some(h),
            };
        }
        if run.tau() >= CLASSIFY_TAU {
            // Lingering at the saddle: the threshold itself, counted as escaping.
            break Probe {
                escapes: true,
                h: None,
            };
        }
        let s = run.state();
        if early && s.xi() < 1.0 && saddle_h(&s) < 0.0 {
            break Probe {
                escapes: false,
                h: None,
            };
        }
        // Crawling up to the saddle: the slow manifold tells how it ends.
        if let Some(f) = fate(&s) {
            let (escapes, h) = match f {
                Fate::Escapes { h } => (true, h),
                Fate::Sticks { h } => (false, h),
            };
            break Probe {
                escapes,
                h: Some(h),
            };
        }
        if let Err(e) = run.step(CLASSIFY_TAU) {
            *evals += run.cost().rhs_evals;
            return Err(e.into());
        }
    };
    *evals += run.cost().rhs_evals;
    Ok(result)
}

/// Escape needs at most enough speed to reach ξ = 1 against full friction: the ceiling of
/// the scan for the escape speed at ξ0.
fn escape_scan_top(xi0: f64) -> f64 {
    2.0 * (1.0 + xi0) + 2.0
}

/// Largest ξ0 whose escape speed can be sought: the scan's speeds stay ≤ [`Initial::MAX`].
pub const MAX_ESCAPE_XI0: f64 = 4e11;

/// Why [`MAX_ESCAPE_XI0`] (with [`Initial::MAX`] = 1e12).
const ESCAPE_XI0_WHY: &str = " for an escape speed (the scan reaches v0 = 2(1 + xi0) + 2 ≤ 1e12)";

/// Whether [`escape_speed`] accepts `xi0` (so that a command can refuse it before any run).
pub fn check_escape_xi0(xi0: f64) -> Result<(), Error> {
    Initial::velocity(xi0, 0.0, 0.0).validate()?;
    if xi0 > MAX_ESCAPE_XI0 {
        return Err(Error::Invalid(Invalid {
            why: ESCAPE_XI0_WHY,
            ..Invalid::new(Field::Xi0, xi0, Range::AtMost(MAX_ESCAPE_XI0))
        }));
    }
    Ok(())
}

/// Tolerance of the scan runs, which only need the outcome far from the threshold.
const SCAN_TOL: f64 = 1e-6;
/// A secant step this many times the target width or smaller means the estimate is good
/// enough to try certifying it.
const CERTIFY_STEP: f64 = 1e3;

/// Escape speed v_e(ξ0, φ) (Sec. IV, Fig. 5): the least v0 for which the particle escapes,
/// to within `tol`, certified by a stuck run and an escaping run at most `tol` apart.
///
/// A coarse scan (at a loose tolerance, runs cut short by the stick certificate H < 0)
/// brackets the threshold and checks the escaping speeds form an interval. Then regula falsi
/// (Illinois) on H at the end of the run — smooth and nearly linear in v0 through the
/// threshold, see [`saddle_h`] — closes in; once its steps are small, a pair of runs straddling
/// the estimate by ±0.45 `tol` certifies it. Bisection on the outcome is the safeguard
/// whenever H is unavailable or the secant makes poor progress.
pub fn escape_speed(xi0: f64, phi: f64, settings: Settings, tol: f64) -> Result<Threshold, Error> {
    escape_speed_until(xi0, phi, settings, tol, &always)
}

/// [`escape_speed`], asking `go_on` before each run.
pub fn escape_speed_until(
    xi0: f64,
    phi: f64,
    settings: Settings,
    tol: f64,
    go_on: GoOn,
) -> Result<Threshold, Error> {
    if !(tol.is_finite() && tol > 0.0) {
        return Err(Error::invalid(Field::Bracket, tol, Range::Above(0.0)));
    }
    Initial::velocity(xi0, phi, 0.0).validate()?;
    if !settings.method().stick_events() {
        return Err(Error::refused(format!(
            "the escape speed needs stick events: {} never comes to rest",
            settings.method()
        )));
    }
    let settings = floor_tol(settings, tol);
    let mut evals = 0;
    let at = |v0: f64| Initial::velocity(xi0, phi, v0);
    let scan_settings = match settings.scheme {
        Scheme::Dp54 { tol } | Scheme::Dop853 { tol } => Settings {
            scheme: settings.scheme.with_knob(tol.max(SCAN_TOL)),
            ..settings
        },
        _ => settings,
    };
    check_escape_xi0(xi0)?;
    let top = escape_scan_top(xi0);
    let grid: Vec<f64> = (0..=40).map(|i| top * i as f64 / 40.0).collect();
    let (first, interval, scanned) = scan(&grid, |v0| {
        probe(at(v0), scan_settings, true, &mut evals, go_on).map(|p| p.escapes)
    })?;
    let mut runs = scanned.len() as u32;
    if first == 0 {
        return Ok(Threshold {
            value: 0.0,
            stuck_at: None,
            escapes_at: 0.0,
            interval,
            scan: scanned,
            runs,
            rhs_evals: evals,
            run_tol: settings.scheme.tol(),
            tightened: 0,
        });
    }
    // The bracket, confirmed at the full settings (the scan ran looser).
    let mut i = first;
    let (mut lo, mut glo, mut hi, mut ghi);
    loop {
        runs += 2;
        let a = probe(at(grid[i - 1]), settings, false, &mut evals, go_on)?;
        let b = probe(at(grid[i]), settings, false, &mut evals, go_on)?;
        match (a.escapes, b.escapes) {
            (false, true) => {
                (lo, glo, hi, ghi) = (grid[i - 1], a.h, grid[i], b.h);
                break;
            }
            (true, _) if i > 1 => i -= 1,
            (false, false) if i + 1 < grid.len() => i += 1,
            _ => {
                return Err(Error::NoAnswer(
                    "the escape speed could not be bracketed".into(),
                ));
            }
        }
    }
    // Secant on H through the latest two points, safeguarded by the bracket (Brent's rule:
    // each secant step must at least halve the one before, else regula falsi or bisection).
    let mut last2: [Option<(f64, f64)>; 2] = match (glo, ghi) {
        (Some(a), Some(b)) => [Some((lo, a)), Some((hi, b))],
        _ => [None, None],
    };
    let mut prev_step = f64::INFINITY;
    let mut certify = true;
    while hi - lo > tol {
        let secant = match (last2[0], last2[1]) {
            (Some((v1, g1)), Some((v2, g2))) if certify && g1 != g2 => {
                let c = v2 - g2 * (v2 - v1) / (g2 - g1);
                (c > lo && c < hi && (c - v2).abs() < 0.5 * prev_step)
                    .then_some((c, (c - v2).abs()))
            }
            _ => None,
        };
        if let Some((v, step)) = secant
            && step <= CERTIFY_STEP * tol
        {
            certify = false;
            let (Some((v1, g1)), Some((v2, g2))) = (last2[0], last2[1]) else {
                unreachable!("a secant needs two points")
            };
            let slope = (g2 - g1) / (v2 - v1);
            (lo, hi, runs) = close_in(lo, hi, v, slope, tol, runs, |x| {
                probe(at(x), settings, true, &mut evals, go_on)
            })?;
            glo = None;
            ghi = None;
            continue;
        }
        let falsi = match (glo, ghi) {
            (Some(a), Some(b)) if certify && a < 0.0 && b > 0.0 => {
                let c = lo - a * (hi - lo) / (b - a);
                (c > lo && c < hi).then_some(c)
            }
            _ => None,
        };
        let v = secant
            .map(|(c, _)| c)
            .or(falsi)
            .unwrap_or(0.5 * (lo + hi))
            .clamp(lo + 0.25 * tol, hi - 0.25 * tol);
        if !(v > lo && v < hi) {
            break;
        }
        prev_step = match (secant, last2[1]) {
            (Some((_, step)), _) => step,
            _ => f64::INFINITY,
        };
        runs += 1;
        // Once certification has been tried, only outcomes are needed: bisection.
        let p = probe(at(v), settings, !certify, &mut evals, go_on)?;
        if let Some(g) = p.h {
            last2 = [last2[1], Some((v, g))];
        }
        if p.escapes {
            (hi, ghi) = (v, p.h);
        } else {
            (lo, glo) = (v, p.h);
        }
    }
    Ok(Threshold {
        value: 0.5 * (lo + hi),
        stuck_at: Some(lo),
        escapes_at: hi,
        interval,
        scan: scanned,
        runs,
        rhs_evals: evals,
        run_tol: settings.scheme.tol(),
        tightened: 0,
    })
}

/// The last stage of [`escape_speed`]: from an estimate `est` of the root of H (slope `slope`
/// in v0), runs that pass close to the saddle certify a bracket of width ≤ `tol`. Each run's H
/// (read off the slow manifold, one smooth function through the threshold: see
/// [`super::saddle`]) pins the root (root ≈ v − H/slope), so an escaping run goes 0.7 `tol`
/// above the estimate, and a stuck run then just inside the width. Falls back to bisection on
/// the outcome.
fn close_in(
    mut lo: f64,
    mut hi: f64,
    mut est: f64,
    mut slope: f64,
    tol: f64,
    mut runs: u32,
    mut probe: impl FnMut(f64) -> Result<Probe, Error>,
) -> Result<(f64, f64, u32), Error> {
    let mut reach = 0.7 * tol;
    let mut last: Option<(f64, f64)> = None;
    for _ in 0..12 {
        if hi - lo <= tol {
            return Ok((lo, hi, runs));
        }
        let x = if hi - est <= 0.94 * tol {
            hi - 0.95 * tol
        } else {
            est + reach
        };
        let x = if x > lo && x < hi { x } else { 0.5 * (lo + hi) };
        runs += 1;
        let p = probe(x)?;
        // The local slope from the last two runs with an H, when sane: at loose tolerances H
        // bends near the saddle and the far secant's slope misleads.
        if let (Some((x0, h0)), Some(h)) = (last, p.h) {
            let local = (h0 - h) / (x0 - x);
            if local > 0.01 * slope && local < 100.0 * slope {
                slope = local;
            }
        }
        last = p.h.map(|h| (x, h)).or(last);
        if p.escapes {
            hi = x;
        } else {
            lo = x;
            // Below the root after all: reach farther.
            reach *= 2.0;
        }
        est = match p.h {
            Some(h) if slope > 0.0 => (x - h / slope).clamp(lo, hi),
            _ if p.escapes => 0.5 * (lo + hi),
            _ => est.max(lo),
        };
    }
    let (lo, hi, n) = bisect(lo, hi, tol, |x| probe(x).map(|p| p.escapes))?;
    Ok((lo, hi, runs + n))
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
    let mut evals = 0;
    let mut classify = |xi0: f64| -> Result<bool, Error> {
        check(go_on)?;
        let mut run = Run::new(Initial::at_rest(xi0, Release::LabRest), settings)?;
        let outcome = run.run(CLASSIFY_TAU, true)?;
        evals += run.cost().rhs_evals;
        Ok(outcome != Outcome::Stuck)
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
    })
}

/// One point of Fig. 5.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct EscapePoint {
    pub xi0: f64,
    pub phi: f64,
    pub v_escape: f64,
}

/// Fig. 5: v_e over `n` angles φ in [0, 2π) for each ξ0.
pub fn sweep_escape(
    xi0s: &[f64],
    n: usize,
    settings: Settings,
    tol: f64,
) -> Result<Vec<EscapePoint>, Error> {
    let jobs: Vec<(f64, f64)> = xi0s
        .iter()
        .flat_map(|&xi0| (0..n).map(move |i| (xi0, std::f64::consts::TAU * i as f64 / n as f64)))
        .collect();
    par_map(&jobs, |&(xi0, phi)| {
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

/// Fig. 6: the final rest position against ξ0 for release at rest in the lab.
pub fn sweep_rest(xi0s: &[f64], settings: Settings) -> Result<Vec<RestPoint>, Error> {
    par_map(xi0s, |&xi0| {
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

/// Where v_e(φ) is least for a given ξ0, to `phi_tol` (Fig. 5's minimum, which the paper
/// puts near φ ≈ 0.4 for every ξ0): a scan of `n` angles, then golden-section search.
pub fn easiest_angle(
    xi0: f64,
    n: usize,
    settings: Settings,
    tol: f64,
    phi_tol: f64,
) -> Result<(f64, f64), Error> {
    let ve = |phi: f64| escape_speed(xi0, phi, settings, tol).map(|t| t.value);
    let step = std::f64::consts::TAU / n as f64;
    let phis: Vec<f64> = (0..n).map(|i| step * i as f64).collect();
    let vals: Vec<Result<f64, Error>> = par_map(&phis, |&p| ve(p));
    let vals: Vec<f64> = vals.into_iter().collect::<Result<_, _>>()?;
    let imin = (0..n)
        .min_by(|&a, &b| vals[a].total_cmp(&vals[b]))
        .unwrap_or(0);
    let phi = golden_min(
        &mut |p| ve(p),
        phis[imin] - step,
        phis[imin] + step,
        phi_tol,
    )?;
    Ok((super::model::turn_angle(phi), ve(phi)?))
}
