//! What an escape-speed curve says of a release, decided here and only worded by the page:
//! where (φ, v0) falls against the computed speeds, and the widest sticking window.

use super::{Speeds, angle};
use std::f64::consts::TAU;

/// The widest sticking window of a curve outside ξ = 1 (`ve`, its speeds at evenly spaced
/// angles): its angle and its lowest and highest sticking speeds.
pub fn widest_window(ve: &[Option<Speeds>]) -> Option<(f64, f64, f64)> {
    let n = ve.len();
    (0..n)
        .filter_map(|k| match ve[k]? {
            Speeds::Stick { lo, hi } => Some((angle(k, n), lo, hi)),
            _ => None,
        })
        .max_by(|a, b| (a.2 - a.1).total_cmp(&(b.2 - b.1)))
}

/// How a release at (φ, v0) ends, read off the curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// Below the window (outside ξ = 1): escapes.
    Below,
    /// Sticks.
    Inside,
    /// Above v_e or the window: escapes.
    Above,
    /// No speed sticks at this angle.
    Never,
    /// Too close to an edge for the chart to tell.
    Near,
}

/// The verdict at φ from the curve (`ve`, its speeds at evenly spaced angles): at a computed angle its own window, between two the span
/// of their edges (v_e is monotone between neighbours but at its extremes, where it is flat),
/// each widened by its bracket's half-width. `None` until both neighbours are known.
pub fn judge(ve: &[Option<Speeds>], phi: f64, v0: f64) -> Option<Verdict> {
    judge_padded(ve, phi, v0, 0.5 * super::CURVE_VTOL)
}

/// As [`judge`], for an outcome-map cell (`analysis::cells`), each edge also widened by how
/// far the curve may bow past its neighbours between two computed angles: half the larger
/// second difference of either edge at the two angles (a parabola bows by an eighth of it, a
/// kink midway by half). A second difference that cannot be taken (a neighbour with no
/// window) leaves the cell `Near`.
pub fn judge_cell(ve: &[Option<Speeds>], phi: f64, v0: f64) -> Option<Verdict> {
    let n = ve.len();
    if n < 3 {
        return Some(Verdict::Near);
    }
    let k = (phi / TAU * n as f64).floor() as usize % n;
    let edges = |i: usize| match ve[i % n] {
        Some(Speeds::Stick { lo, hi }) => Some((lo, hi)),
        _ => None,
    };
    let bow = |i: usize| {
        let (a, b, c) = (edges(i + n - 1), edges(i), edges(i + 1));
        match (a, b, c) {
            (Some(a), Some(b), Some(c)) => {
                let d2 = |x: f64, y: f64, z: f64| (x - 2.0 * y + z).abs();
                0.5 * d2(a.0, b.0, c.0).max(d2(a.1, b.1, c.1))
            }
            _ => f64::INFINITY,
        }
    };
    judge_padded(
        ve,
        phi,
        v0,
        0.5 * super::CURVE_VTOL + bow(k).max(bow(k + 1)),
    )
}

/// [`judge`] with each edge widened by `pad`.
fn judge_padded(ve: &[Option<Speeds>], phi: f64, v0: f64, pad: f64) -> Option<Verdict> {
    let n = ve.len();
    let x = phi / TAU * n as f64;
    let on_grid = (x - x.round()).abs() < 1e-9;
    let (a, b) = if on_grid {
        let k = x.round() as usize % n;
        (ve[k]?, ve[k]?)
    } else {
        let k = x.floor() as usize % n;
        (ve[k]?, ve[(k + 1) % n]?)
    };
    match (a, b) {
        (Speeds::Escapes, Speeds::Escapes) => Some(Verdict::Never),
        (Speeds::Stick { lo: l1, hi: h1 }, Speeds::Stick { lo: l2, hi: h2 }) => {
            // A floor of 0 (inside ξ = 1) is exact: no speed is below it.
            let lo = |x: f64| if x > 0.0 { x + pad } else { 0.0 };
            Some(if v0 > h1.max(h2) + pad {
                Verdict::Above
            } else if l1.min(l2) > 0.0 && v0 < l1.min(l2) - pad {
                Verdict::Below
            } else if v0 >= lo(l1.max(l2)) && v0 < h1.min(h2) - pad {
                Verdict::Inside
            } else {
                Verdict::Near
            })
        }
        (Speeds::Unknown, _) | (_, Speeds::Unknown) => None,
        _ => Some(Verdict::Near),
    }
}
