//! Solvers over many runs (Sec. IV): the escape speed v_e(ξ0, φ) of Fig. 5, the critical
//! radius ξ0c of Fig. 6, and sweeps of both.

use super::method::Settings;
use super::model::{Initial, Release};
use super::run::{Outcome, Run};
use serde::Serialize;

/// Time limit of one classifying run. Every run ends stuck or certified long before this except
/// exactly at a threshold, where the particle lingers at the saddle ξ = 1, u = 0.
pub const CLASSIFY_TAU: f64 = 1e4;

/// Whether the particle released with `initial` escapes. `None` if it neither sticks nor is
/// certified within [`CLASSIFY_TAU`].
pub fn escapes(initial: Initial, settings: Settings) -> Result<Option<bool>, String> {
    let mut run = Run::new(initial, settings)?;
    let outcome = run.run(CLASSIFY_TAU, true).map_err(|e| e.to_string())?;
    Ok(match outcome {
        Outcome::Escaped => Some(true),
        Outcome::Stuck => Some(false),
        Outcome::Running => None,
    })
}

/// A threshold located by bisection on the outcome, with its certificate: a run on each side.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct Threshold {
    /// Midpoint of the final bracket.
    pub value: f64,
    /// Largest value seen to stick, and least seen to escape.
    pub stuck_at: f64,
    pub escapes_at: f64,
    /// Whether the scan saw the escaping set as one interval above the threshold.
    pub interval: bool,
    pub runs: u32,
    pub rhs_evals: u64,
}

/// Bisection on a monotone outcome: `escapes(x)` false at `lo`, true at `hi`, down to width
/// `tol`. Runs that never settle count as escaping (the saddle is the threshold itself).
fn bisect(
    mut lo: f64,
    mut hi: f64,
    tol: f64,
    mut escapes: impl FnMut(f64) -> Result<bool, String>,
) -> Result<(f64, f64, u32), String> {
    let mut runs = 0;
    while hi - lo > tol {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        runs += 1;
        if escapes(mid)? { hi = mid } else { lo = mid }
    }
    Ok((lo, hi, runs))
}

/// Scans `grid` for the first escaping value, then checks the rest of the grid escapes too.
fn scan(
    grid: &[f64],
    mut escapes: impl FnMut(f64) -> Result<bool, String>,
) -> Result<(usize, bool, u32), String> {
    let mut first = None;
    let mut interval = true;
    let mut runs = 0;
    for (i, &x) in grid.iter().enumerate() {
        runs += 1;
        let e = escapes(x)?;
        match (first, e) {
            (None, true) => first = Some(i),
            (Some(_), false) => interval = false,
            _ => {}
        }
    }
    let first = first.ok_or("no escape found in the scanned range")?;
    Ok((first, interval, runs))
}

/// Escape speed v_e(ξ0, φ) (Sec. IV, Fig. 5): the least v0 for which the particle escapes,
/// to within `tol`. A coarse scan brackets it and checks the escaping speeds form an interval;
/// bisection on the outcome closes the bracket.
pub fn escape_speed(xi0: f64, phi: f64, settings: Settings, tol: f64) -> Result<Threshold, String> {
    if !(tol.is_finite() && tol > 0.0) {
        return Err(format!("tol must be > 0, got {tol}"));
    }
    Initial::velocity(xi0, phi, 0.0).validate()?;
    let mut evals = 0;
    let mut classify = |v0: f64| -> Result<bool, String> {
        let mut run = Run::new(Initial::velocity(xi0, phi, v0), settings)?;
        let outcome = run.run(CLASSIFY_TAU, true).map_err(|e| e.to_string())?;
        evals += run.cost.rhs_evals;
        Ok(outcome != Outcome::Stuck)
    };
    // Escape needs at most enough speed to reach ξ = 1 against full friction: a ceiling.
    let top = 2.0 * (1.0 + xi0) + 2.0;
    let grid: Vec<f64> = (0..=40).map(|i| top * i as f64 / 40.0).collect();
    let (first, interval, scan_runs) = scan(&grid, &mut classify)?;
    let (lo, hi, runs) = if first == 0 {
        (0.0, 0.0, 0)
    } else {
        bisect(grid[first - 1], grid[first], tol, &mut classify)?
    };
    Ok(Threshold {
        value: 0.5 * (lo + hi),
        stuck_at: lo,
        escapes_at: hi,
        interval,
        runs: scan_runs + runs,
        rhs_evals: evals,
    })
}

/// Critical radius ξ0c (Sec. IV, Fig. 6): the largest ξ0 at which a particle released at rest
/// in the lab still ends stuck.
pub fn critical_radius(settings: Settings, tol: f64) -> Result<Threshold, String> {
    let mut evals = 0;
    let mut classify = |xi0: f64| -> Result<bool, String> {
        let mut run = Run::new(Initial::at_rest(xi0, Release::LabRest), settings)?;
        let outcome = run.run(CLASSIFY_TAU, true).map_err(|e| e.to_string())?;
        evals += run.cost.rhs_evals;
        Ok(outcome != Outcome::Stuck)
    };
    let grid: Vec<f64> = (0..=30).map(|i| 1.5 * i as f64 / 30.0).collect();
    let (first, interval, scan_runs) = scan(&grid, &mut classify)?;
    if first == 0 {
        return Err("released at rest in the lab at the centre, the particle escaped".into());
    }
    let (lo, hi, runs) = bisect(grid[first - 1], grid[first], tol, &mut classify)?;
    Ok(Threshold {
        value: 0.5 * (lo + hi),
        stuck_at: lo,
        escapes_at: hi,
        interval,
        runs: scan_runs + runs,
        rhs_evals: evals,
    })
}

/// Maps `f` over `items` on all available cores, keeping order.
pub fn par_map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(items.len().max(1));
    let chunk = items.len().div_ceil(threads.max(1)).max(1);
    std::thread::scope(|scope| {
        let handles: Vec<_> = items
            .chunks(chunk)
            .map(|c| scope.spawn(|| c.iter().map(&f).collect::<Vec<R>>()))
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("sweep worker panicked"))
            .collect()
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
) -> Result<Vec<EscapePoint>, String> {
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
pub fn sweep_rest(xi0s: &[f64], settings: Settings) -> Result<Vec<RestPoint>, String> {
    par_map(xi0s, |&xi0| {
        let mut run = Run::new(Initial::at_rest(xi0, Release::LabRest), settings)?;
        let (outcome, s) = run.finish(CLASSIFY_TAU).map_err(|e| e.to_string())?;
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
) -> Result<(f64, f64), String> {
    let ve = |phi: f64| escape_speed(xi0, phi, settings, tol).map(|t| t.value);
    let step = std::f64::consts::TAU / n as f64;
    let phis: Vec<f64> = (0..n).map(|i| step * i as f64).collect();
    let vals: Vec<Result<f64, String>> = par_map(&phis, |&p| ve(p));
    let vals: Vec<f64> = vals.into_iter().collect::<Result<_, _>>()?;
    let imin = (0..n)
        .min_by(|&a, &b| vals[a].total_cmp(&vals[b]))
        .unwrap_or(0);
    let (mut a, mut b) = (phis[imin] - step, phis[imin] + step);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (ve(c)?, ve(d)?);
    while b - a > phi_tol {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - g * (b - a);
            fc = ve(c)?;
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + g * (b - a);
            fd = ve(d)?;
        }
    }
    let phi = 0.5 * (a + b);
    Ok((phi.rem_euclid(std::f64::consts::TAU), ve(phi)?))
}
