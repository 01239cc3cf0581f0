//! An outcome-map cell as the page needs it: one character, so its outcome and its rest
//! radius to the quarter it is shaded by, not to the explorer's tolerance. A first run at
//! [`CELL_TOL`] answers where two independent witnesses agree that its answer is safe: the
//! escape-speed curve already on the page (computed far tighter) puts the cell clearly on
//! one side of v_e, and the run ends on that side too, stuck well inside its quarter. Any
//! doubt (near v_e or a window's edge, near ¼, ½ or ¾, a curve not yet known, a fixed-step
//! method) and the cell is run again at the explorer's own settings, as every cell used to be.

use super::verdict::{Verdict, judge_cell};
use super::{Cell, Speeds, classify, map_release};
use crate::engine::model::turn_angle;
use crate::engine::{Outcome, Release, Settings};

/// Tolerance of a cell's first run: its rest radius is off by at most 3.3e-6 on the bench's
/// rest cases (median 4e-8), for a quarter of the RHS evaluations of the default 1e-10.
pub const CELL_TOL: f64 = 1e-6;
/// The edges of the rest-radius shading (`·` `:` `▒` `▓`).
pub const BANDS: [f64; 3] = [0.25, 0.5, 0.75];
/// A first run's rest radius is trusted to its quarter only this far from an edge: 300× the
/// worst error measured at [`CELL_TOL`].
pub const BAND_MARGIN: f64 = 1e-3;

/// What a cell's answer is when its runs fail: unknown (drawn `?`).
const UNKNOWN: Cell = Cell {
    outcome: Outcome::Running,
    rest: None,
};

/// The quarter a rest radius is shaded by: how many of `BANDS` lie at or below it.
pub fn band(xi: f64) -> usize {
    BANDS.iter().filter(|&&b| xi >= b).count()
}

/// Map cell (φ, v0) at ξ0 in `release` mode as the page shows it, `curve` the escape speeds
/// at ξ0 (those of `Job::Curve`, on evenly spaced angles) when the page has them. Refined at
/// `settings` unless the first run's answer is safe (module docs); also whether it was.
pub fn map_cell_answer(
    xi0: f64,
    release: Release,
    (phi, v0): (f64, f64),
    settings: Settings,
    curve: Option<&[Option<Speeds>]>,
) -> (Cell, bool) {
    let initial = map_release(xi0, release, phi, v0);
    let refined = || (classify(initial, settings).unwrap_or(UNKNOWN), true);
    let (Some(curve), Some(first)) = (curve, first_settings(settings)) else {
        return refined();
    };
    // The curve's angles and speeds are relative to the table, as the release made.
    let Some(verdict) = judge_cell(curve, turn_angle(initial.phi), initial.v0) else {
        return refined();
    };
    let Ok(cell) = classify(initial, first) else {
        return refined();
    };
    let safe = match (verdict, cell.outcome) {
        (Verdict::Inside, Outcome::Stuck) => cell
            .rest
            .is_some_and(|(xi, _)| BANDS.iter().all(|b| (xi - b).abs() > BAND_MARGIN)),
        (Verdict::Above | Verdict::Below | Verdict::Never, Outcome::Escaped) => true,
        _ => false,
    };
    if safe { (cell, false) } else { refined() }
}

/// The settings of a cell's first run: an adaptive method at [`CELL_TOL`] when that is
/// looser than `settings` (else no first run: the cell is run at `settings` at once).
fn first_settings(settings: Settings) -> Option<Settings> {
    let tol = settings.scheme.tol()?;
    (tol < CELL_TOL).then(|| Settings {
        scheme: settings.scheme.with_knob(CELL_TOL),
        ..settings
    })
}
