//! The escape speed v_e(ξ0, φ) (Sec. IV, Fig. 5): a coarse scan, a bracket confirmed at the
//! full settings, a secant on the smooth measure H through the threshold, and the last runs
//! that pass close to the saddle.

use super::{CLASSIFY_TAU, GoOn, Kept, Threshold, always, check, floor_tol, scan};
use crate::error::{Error, Field, Invalid, Range};
use crate::method::{Scheme, Settings};
use crate::model::Initial;
use crate::roots::bisect;
use crate::run::Run;
use crate::saddle::{Fate, fate, saddle_h};

/// Outcome of one classifying run at speed v0, and the smooth measure H at its end when the
/// run went all the way (see [`saddle_h`]).
struct Probe {
    escapes: bool,
    h: Option<f64>,
}

/// Classifies the release at `initial` with `settings`. With `early`, a run stops as soon as it
/// is certified to stick (H < 0 inside ξ < 1) and reports no H; otherwise a stuck run goes on
/// to its stop, and H there is reported. Also the run, where it stopped.
fn probe(
    initial: Initial,
    settings: Settings,
    early: bool,
    evals: &mut u64,
    go_on: GoOn,
) -> Result<(Probe, Run), Error> {
    use crate::run::Status;
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
    Ok((result, run))
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
    let settings = prepared(xi0, phi, settings, tol)?;
    let mut evals = 0;
    let at = |v0: f64| Initial::velocity(xi0, phi, v0);
    let scan_settings = match settings.scheme {
        Scheme::Dp54 { tol } | Scheme::Dop853 { tol } => Settings {
            scheme: settings.scheme.with_knob(tol.max(SCAN_TOL)),
            ..settings
        },
        _ => settings,
    };
    let top = escape_scan_top(xi0);
    let grid: Vec<f64> = (0..=40).map(|i| top * i as f64 / 40.0).collect();
    let (first, interval, scanned) = scan(&grid, |v0| {
        probe(at(v0), scan_settings, true, &mut evals, go_on).map(|(p, _)| p.escapes)
    })?;
    let mut runs = scanned.len() as u32;
    let mut kept = Kept::default();
    let (stuck_at, escapes_at) = if first == 0 {
        (None, 0.0)
    } else {
        let mut run = |v0: f64, early: bool| {
            let (p, run) = probe(at(v0), settings, early, &mut evals, go_on)?;
            kept.keep(v0, p.escapes, run);
            Ok(p)
        };
        let ends = bracket(&grid, first, &mut runs, |v0| run(v0, false))?;
        let (lo, hi) = narrow(ends, tol, &mut runs, run)?;
        (Some(lo), hi)
    };
    Ok(Threshold {
        value: stuck_at.map_or(0.0, |lo| 0.5 * (lo + escapes_at)),
        stuck_at,
        escapes_at,
        interval,
        scan: scanned,
        runs,
        rhs_evals: evals,
        run_tol: settings.scheme.tol(),
        tightened: 0,
        kept,
    })
}

/// `settings` for an escape speed to `tol` at (ξ0, φ), floored at `tol`/100 ([`floor_tol`]),
/// or why none can be sought.
fn prepared(xi0: f64, phi: f64, settings: Settings, tol: f64) -> Result<Settings, Error> {
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
    check_escape_xi0(xi0)?;
    Ok(floor_tol(settings, tol))
}

/// The first step from a guess in [`escape_bracket_near`], quadrupled until the outcome flips:
/// v_e moved by 0.011 to 0.013 from ξ0 = 0.49 to 0.5 (a held key's step), and a first step of
/// 0.01 took 1950 evaluations an angle to that ξ0's bracket, 0.02 1730.
const NEAR_STEP: f64 = 0.02;

/// A bracket (stuck, escapes) of width ≤ `tol` around v_e(ξ0, φ) (Sec. IV, Fig. 5) found from
/// a `guess` (v_e at a nearby ξ0), for a drawn curve: runs stepping away from the guess until
/// the outcome flips, then [`escape_speed`]'s secant on H, with no scan. So, unlike
/// [`escape_speed`], it neither checks that the escaping speeds are one interval above v_e nor
/// certifies its ends; a guess it cannot bracket below the scan's ceiling is refused. Also the
/// right-hand-side evaluations it spent.
pub fn escape_bracket_near(
    xi0: f64,
    phi: f64,
    settings: Settings,
    tol: f64,
    guess: f64,
    go_on: GoOn,
) -> Result<(f64, f64, u64), Error> {
    let settings = prepared(xi0, phi, settings, tol)?;
    let top = escape_scan_top(xi0);
    let mut evals = 0;
    let mut run = |v0: f64, early: bool| {
        probe(
            Initial::velocity(xi0, phi, v0),
            settings,
            early,
            &mut evals,
            go_on,
        )
        .map(|(p, _)| p)
    };
    let start = guess.clamp(0.0, top);
    let first = run(start, false)?;
    let (mut near, mut g_near) = (start, first.h);
    let mut step = NEAR_STEP;
    let ends = loop {
        // Down from an escaping guess, up from a stuck one.
        let v = if first.escapes {
            (near - step).max(0.0)
        } else {
            near + step
        };
        if v > top || (first.escapes && near == 0.0) {
            return Err(Error::NoAnswer(
                "the escape speed could not be bracketed from the guess".into(),
            ));
        }
        let p = run(v, false)?;
        if p.escapes != first.escapes {
            break if first.escapes {
                Ends {
                    lo: v,
                    glo: p.h,
                    hi: near,
                    ghi: g_near,
                }
            } else {
                Ends {
                    lo: near,
                    glo: g_near,
                    hi: v,
                    ghi: p.h,
                }
            };
        }
        (near, g_near, step) = (v, p.h, 4.0 * step);
    };
    let mut runs = 0;
    let (lo, hi) = narrow(ends, tol, &mut runs, run)?;
    Ok((lo, hi, evals))
}

/// A bracket of the threshold, the smooth measure H at each end where its run gave one.
struct Ends {
    lo: f64,
    glo: Option<f64>,
    hi: f64,
    ghi: Option<f64>,
}

/// The bracket confirmed at the full settings from the scan's `first` escaping speed on
/// `grid` (the scan ran looser): the neighbouring pair of grid speeds, one stuck, one escaping,
/// moving down or up the grid until they are.
fn bracket(
    grid: &[f64],
    first: usize,
    runs: &mut u32,
    mut probe: impl FnMut(f64) -> Result<Probe, Error>,
) -> Result<Ends, Error> {
    let mut i = first;
    loop {
        *runs += 2;
        let a = probe(grid[i - 1])?;
        let b = probe(grid[i])?;
        match (a.escapes, b.escapes) {
            (false, true) => {
                return Ok(Ends {
                    lo: grid[i - 1],
                    glo: a.h,
                    hi: grid[i],
                    ghi: b.h,
                });
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
}

/// The bracket `ends` closed to width `tol`: secant on H through the latest two points,
/// safeguarded by the bracket (Brent's rule: each secant step must at least halve the one
/// before, else regula falsi or bisection), and [`close_in`] once its steps are small. `probe`
/// runs a speed, stopping early at the stick certificate when told.
fn narrow(
    ends: Ends,
    tol: f64,
    runs: &mut u32,
    mut probe: impl FnMut(f64, bool) -> Result<Probe, Error>,
) -> Result<(f64, f64), Error> {
    let Ends {
        mut lo,
        mut glo,
        mut hi,
        mut ghi,
    } = ends;
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
            (lo, hi, *runs) = close_in(lo, hi, v, slope, tol, *runs, |x| probe(x, true))?;
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
        *runs += 1;
        // Once certification has been tried, only outcomes are needed: bisection.
        let p = probe(v, !certify)?;
        if let Some(g) = p.h {
            last2 = [last2[1], Some((v, g))];
        }
        if p.escapes {
            (hi, ghi) = (v, p.h);
        } else {
            (lo, glo) = (v, p.h);
        }
    }
    Ok((lo, hi))
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
