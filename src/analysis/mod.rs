//! The paper's analysis behind the explorer's pages (Sec. IV, Figs. 5 and 6): escape-speed
//! curves, the outcome map, the rest radius. Work is split into small pieces (one escape speed,
//! one cell, one radius) computed off the UI thread and streamed back, so a page fills in
//! progressively and a key never waits. A newer request cancels an older one between pieces.
//! Headless (tests, replay) the same pieces are computed inline, so screens stay a function
//! of the keys.

use crate::engine::model::turn_angle;
use crate::engine::roots::bisect;
use crate::engine::solve::{
    CLASSIFY_TAU, GoOn, always, critical_radius_until, escape_bracket_near, escape_speed_until,
};
use crate::engine::{Initial, Outcome, Release, Run, Settings};
use crate::error::Error;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};

mod cells;
pub mod shared;
pub mod trade;
pub mod verdict;
mod worker;

pub use cells::{CELL_TOL, band, map_cell_answer};
pub use worker::{Analysis, Progress};

/// Angles of an escape-speed curve (every 5°, as `sweep fig5`'s default).
pub const CURVE_POINTS: usize = 72;
/// Width of the final bracket on each escape speed of a curve: what the line drawn needs. A
/// braille dot of the page's chart is its speed range over four dots a row: 0.009 to 0.018 at
/// 120×40 (1.1 × v_e's greatest, 1.2 to 2.6, over 36 rows), 7e-4 on a 1000-row terminal; each
/// point, within 5e-5 of v_e, is within a thirteenth of a dot even there
/// (`tests/suite/curve_cells.rs` draws it against a tight curve, cell by cell). It was 1e-6. Its runs are at 1e-7 ([`curve_settings`]). The printed speeds that need more
/// are sought to their own width: the least v_e ([`LEAST_VTOL`]); the greatest is printed to
/// what it is known to.
pub const CURVE_VTOL: f64 = 1e-4;
/// A curve at a ξ0 this close to another's is where the other's escape speeds start
/// (`engine::solve::escape_bracket_near`; v_e moves about as much as ξ0 there): a held key
/// moves ξ0 by 0.01.
pub const NEAR_XI0: f64 = 0.05;
/// The paper's Fig. 5 radii.
pub const PAPER_XI0: [f64; 4] = [0.8, 0.5, 0.2, 0.001];
/// The most cells an outcome map has, whatever the terminal: up to this the grid is the plot's
/// size, one cell a character (see `ui::pages::map_grid`); a larger plot gets a coarser grid of
/// its shape, each cell drawn over several characters. A 1000×1000 terminal so costs what a
/// 250×64 plot does (about 0.6 s of pieces), not 80 000 cells.
pub const MAP_CELLS: usize = 16_000;

/// The grid for a plot of `w` × `h` characters: the plot's own, scaled down to at most
/// [`MAP_CELLS`] cells, keeping its shape.
pub fn map_grid_for(w: usize, h: usize) -> (usize, usize) {
    let cells = w * h;
    if cells <= MAP_CELLS {
        return (w, h);
    }
    let k = (MAP_CELLS as f64 / cells as f64).sqrt();
    let scale = |n: usize| ((n as f64 * k) as usize).max(1);
    (scale(w), scale(h))
}
/// Radii of the rest-radius curve (Fig. 6), over [0, [`REST_XI0_MAX`]].
pub const REST_POINTS: usize = 101;
pub const REST_XI0_MAX: f64 = 1.5;

/// What a page asks to be computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Job {
    /// v_e(φ) at ξ0 (Fig. 5).
    Curve { xi0: f64 },
    /// The least v_e at ξ0 (inside ξ = 1), refined from a curve's least angle `near`.
    Least { xi0: f64, near: f64 },
    /// Stuck or escaped over (φ, v0) at ξ0 in a release mode, speeds up to `v0_max`, on a
    /// grid of `size` = angles × speeds.
    Map {
        xi0: f64,
        release: Release,
        v0_max: f64,
        size: (usize, usize),
    },
    /// Final rest ξ against ξ0, released at rest in the lab, and ξ0c (Fig. 6).
    Rest,
    /// The work–precision page for `initial`: the reference, its cross-check, then each
    /// setting of [`trade::schemes`] (`paper`: the paper's raw RK2 among them; `extra`: the
    /// explorer's setting when it is none of the others).
    Trade {
        initial: Initial,
        paper: bool,
        extra: Option<crate::engine::method::Scheme>,
    },
}

/// One computed piece of a job.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Piece {
    /// The sticking speeds at angle index `i`.
    Escape { i: usize, v: Speeds },
    /// Outcome-map cell `i` (row-major, φ fastest).
    Cell { i: usize, cell: Cell },
    /// Fig. 6 point `i`: the final rest ξ (`None`: it escaped).
    Rest { i: usize, xi: Option<f64> },
    /// The critical radius ξ0c.
    Critical(f64),
    /// Where v_e is least and its value (φ, v_e); `None` if the search failed.
    Least(Option<(f64, f64)>),
    /// Work–precision piece `i` (see [`Job::Trade`]): how its run ended, `None` if it could
    /// not finish.
    Trade {
        i: usize,
        end: Option<trade::Ending>,
    },
}

/// The release speeds at one angle that end stuck.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Speeds {
    /// Thrown with lo ≤ v0 < hi it comes to rest, outside that it escapes. Inside ξ = 1,
    /// lo = 0 and hi is the escape speed v_e; outside, too slow a throw escapes too (Fig. 3 D).
    Stick { lo: f64, hi: f64 },
    /// Every speed escapes (outside ξ = 1 only).
    Escapes,
    /// The solver could not bracket it.
    Unknown,
}

impl Speeds {
    /// The greatest sticking speed (v_e inside ξ = 1), if there is one.
    pub fn hi(self) -> Option<f64> {
        match self {
            Speeds::Stick { hi, .. } => Some(hi),
            _ => None,
        }
    }
}

/// Speeds scanned for a sticking window outside ξ = 1: windows are 0.8 wide or more at ξ0 ≤ 3
/// and the scan's step is 0.04 at ξ0 = 2 (one narrower than a step is missed).
const WINDOW_SCAN: usize = 200;

/// The speeds at (ξ0, φ) that end stuck, to `tol`. Inside ξ = 1: below the escape speed (the
/// engine's certified solver). Outside: a scan of `WINDOW_SCAN` speeds up to the solver's
/// ceiling 2(1 + ξ0) + 2 finds the window, bisection on the outcome sets each edge.
pub fn sticking_speeds(xi0: f64, phi: f64, settings: Settings, tol: f64) -> Speeds {
    sticking_speeds_until(xi0, phi, settings, tol, None, &always)
}

/// [`sticking_speeds`], asking `go_on` before each run (once it says stop, what is left is
/// `Unknown`), inside ξ = 1 from a `guess` of v_e when given ([`escape_bracket_near`]: no
/// scan; the solver's own search where the guess brackets nothing).
fn sticking_speeds_until(
    xi0: f64,
    phi: f64,
    settings: Settings,
    tol: f64,
    guess: Option<f64>,
    go_on: GoOn,
) -> Speeds {
    if xi0 <= 1.0 {
        let stick = |hi: f64| Speeds::Stick { lo: 0.0, hi };
        let near = guess.map(|g| escape_bracket_near(xi0, phi, settings, tol, g, go_on));
        return match near {
            Some(Ok((lo, hi, _))) => stick(0.5 * (lo + hi)),
            Some(Err(crate::engine::error::Error::Cancelled)) => Speeds::Unknown,
            _ => escape_speed_until(xi0, phi, settings, tol, go_on)
                .map_or(Speeds::Unknown, |t| stick(t.value)),
        };
    }
    let sticks = |v0: f64| {
        if !go_on() {
            return Err(Error::Cancelled);
        }
        classify(Initial::velocity(xi0, phi, v0), settings).map(|c| c.outcome == Outcome::Stuck)
    };
    let top = 2.0 * (1.0 + xi0) + 2.0;
    let grid: Vec<f64> = (0..=WINDOW_SCAN)
        .map(|k| top * k as f64 / WINDOW_SCAN as f64)
        .collect();
    let Ok(stuck) = grid
        .iter()
        .map(|&v| sticks(v))
        .collect::<Result<Vec<_>, _>>()
    else {
        return Speeds::Unknown;
    };
    let (Some(first), Some(last)) = (
        stuck.iter().position(|s| *s),
        stuck.iter().rposition(|s| *s),
    ) else {
        return Speeds::Escapes;
    };
    if first == 0 || last + 1 == grid.len() {
        return Speeds::Unknown;
    }
    let lo = bisect(grid[first - 1], grid[first], tol, sticks);
    let hi = bisect(grid[last], grid[last + 1], tol, |v| sticks(v).map(|s| !s));
    match (lo, hi) {
        (Ok((a, b, _)), Ok((c, d, _))) => Speeds::Stick {
            lo: 0.5 * (a + b),
            hi: 0.5 * (c + d),
        },
        _ => Speeds::Unknown,
    }
}

/// One cell of the outcome map: how a release there ends, and where it rests if it sticks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    pub outcome: Outcome,
    /// Final rest ξ and angle (table frame, in [0, 2π) as every output gives angles) when stuck.
    pub rest: Option<(f64, f64)>,
}

/// Most integrator steps one run of a page's piece may take. A piece is then bounded
/// whatever the scene's step (rk2 at dt 1e-7 took 1e11 steps to [`CLASSIFY_TAU`] per run, and
/// the pages never finished), so a newer request waits for at most one bounded piece. A run
/// over budget leaves its piece unknown, as any failed run does.
pub const PIECE_STEPS: u64 = 20_000;

/// The settings the analysis runs with: the explorer's method if it has stick events, else
/// the default (the paper's raw RK2 never stops, so it cannot classify); at most
/// [`PIECE_STEPS`] steps a run.
pub fn settings_for(s: Settings) -> Settings {
    let s = if s.method().stick_events() {
        s
    } else {
        Settings {
            coupling: s.coupling,
            ..Settings::default()
        }
    };
    Settings {
        max_steps: s.max_steps.min(PIECE_STEPS),
        ..s
    }
}

/// The integration behind a curve's escape speeds: an adaptive method no tighter than
/// [`CURVE_VTOL`]/1000. Runs at its /100 (1e-6) misplaced the threshold near the rim by up to
/// 3.1e-4 beyond the bracket (ξ0 = 0.999; 1.8e-4 at 0.9), and a map's cells, whose first runs
/// are at 1e-6 too, lean on the curve; at 1e-7 every point of 72 on eight ξ0 from 0.5 to 0.999
/// was within its bracket's half-width of a tight v_e, for 1.3× the evaluations.
pub fn curve_settings(s: Settings) -> Settings {
    let s = settings_for(s);
    match s.scheme.tol() {
        Some(tol) => Settings {
            scheme: s.scheme.with_knob(tol.max(1e-3 * CURVE_VTOL)),
            ..s
        },
        None => s,
    }
}

/// The least v_e is sought to this width in φ (rad): 3e-4 π, the page's third decimal in π.
pub const LEAST_PHI_TOL: f64 = 1e-3;
/// ... with escape speeds to this width: v_e is quadratic at its minimum, so φ is resolved to
/// about √(vtol / v_e″) ≈ 3e-4 rad there (v_e″ ≈ 0.1 at ξ0 = 0.5).
pub const LEAST_VTOL: f64 = 1e-8;

/// Where v_e(φ) is least at `xi0` (Fig. 5's minimum) between the neighbours of a curve's least
/// angle `near`, by golden-section search: (φ in [0, 2π), v_e).
fn least(xi0: f64, near: f64, settings: Settings, go_on: GoOn) -> Option<(f64, f64)> {
    let ve = |phi: f64| escape_speed_until(xi0, phi, settings, LEAST_VTOL, go_on).map(|t| t.value);
    let step = angle(1, CURVE_POINTS);
    let phi =
        crate::engine::roots::golden_min(&mut |p| ve(p), near - step, near + step, LEAST_PHI_TOL)
            .ok()?;
    Some((turn_angle(phi), ve(phi).ok()?))
}

/// The angles of a curve: φ_i = 2π i / n.
pub fn angle(i: usize, n: usize) -> f64 {
    std::f64::consts::TAU * i as f64 / n as f64
}

/// The (φ, v0) at the centre of map cell `k` (row-major, φ fastest, speeds from the bottom) of
/// a grid of `size` = angles × speeds over [0, 2π) × [0, v0_max]: what a character of the
/// map stands for.
pub fn map_cell(k: usize, (n, m): (usize, usize), v0_max: f64) -> (f64, f64) {
    let (i, j) = (k % n, k / n);
    let phi = std::f64::consts::TAU * (i as f64 + 0.5) / n as f64;
    (phi, v0_max * (j as f64 + 0.5) / m as f64)
}

/// The release a map cell stands for. With velocity and table-rest releases (φ, v0) are the
/// speed relative to the table; with lab-rest they are the lab velocity, so the particle is
/// thrown from the lab at (φ, v0) and u0 = v − ẑ×r.
pub fn map_release(xi0: f64, release: Release, phi: f64, v0: f64) -> Initial {
    let u0 = glam::DVec2::from_angle(phi) * v0
        - match release {
            Release::LabRest => glam::DVec2::new(0.0, xi0),
            _ => glam::DVec2::ZERO,
        };
    Initial::velocity(xi0, u0.y.atan2(u0.x), u0.length())
}

/// How one release ends, run to its stop or its escape certificate.
pub fn classify(initial: Initial, settings: Settings) -> Result<Cell, Error> {
    let mut run = Run::new(initial, settings)?;
    let (outcome, s) = run.finish(CLASSIFY_TAU)?;
    let q = s.q();
    Ok(Cell {
        outcome,
        rest: (outcome == Outcome::Stuck).then(|| (q.length(), turn_angle(q.y.atan2(q.x)))),
    })
}

/// One row of `sweep map`: a cell's release and how it ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapRow {
    pub phi: f64,
    pub v0: f64,
    pub cell: Cell,
}

/// The outcome map as `sweep map` prints it (the page's own grid and classification): `n`
/// angles φ_i = 2π i/n by `m` speeds v0_max (j + 1)/m, φ fastest, on all cores; `done`
/// counts the cells classified. Fails on the first run that cannot finish.
pub fn outcome_map(
    xi0: f64,
    release: Release,
    (n, m): (usize, usize),
    v0_max: f64,
    settings: Settings,
    done: &std::sync::atomic::AtomicUsize,
) -> Result<Vec<MapRow>, Error> {
    let cells: Vec<(f64, f64)> = (0..n * m).map(|k| map_cell(k, (n, m), v0_max)).collect();
    crate::engine::par::par_map_counted(&cells, done, |&(phi, v0)| {
        classify(map_release(xi0, release, phi, v0), settings).map(|cell| MapRow { phi, v0, cell })
    })
    .into_iter()
    .collect()
}

/// The number of pieces a job has.
pub fn pieces(job: &Job) -> usize {
    match job {
        Job::Curve { .. } => CURVE_POINTS,
        Job::Least { .. } => 1,
        Job::Map { size, .. } => size.0 * size.1,
        Job::Rest => REST_POINTS + 1,
        Job::Trade { paper, extra, .. } => {
            trade::REFERENCE_PIECES + trade::schemes(*paper, *extra).len()
        }
    }
}

/// Piece `k` of `job`.
pub fn piece(job: &Job, k: usize, settings: Settings) -> Piece {
    piece_until(job, k, settings, &always).expect("never cancelled")
}

/// Piece `k` of `job`, asking `go_on` before each run: `None` once it said stop (the piece is
/// then moot, and its partial answer is dropped). `go_on` must stay false once it is false.
pub fn piece_until(job: &Job, k: usize, settings: Settings, go_on: GoOn) -> Option<Piece> {
    piece_with(job, k, settings, None, go_on)
}

/// [`piece_until`], a map's cells leaning on `curve`, the escape speeds at the map's ξ0 when
/// the page has them (see [`map_cell_answer`]); a curve's escape speeds starting from
/// `curve`'s, a nearby ξ0's (within [`NEAR_XI0`]).
pub fn piece_with(
    job: &Job,
    k: usize,
    settings: Settings,
    curve: Option<&[Option<Speeds>]>,
    go_on: GoOn,
) -> Option<Piece> {
    let p = match *job {
        Job::Curve { xi0 } => {
            let phi = angle(k, CURVE_POINTS);
            let guess = curve.and_then(|c| c.get(k).copied().flatten()?.hi());
            let s = curve_settings(settings);
            let v = sticking_speeds_until(xi0, phi, s, CURVE_VTOL, guess, go_on);
            Piece::Escape { i: k, v }
        }
        Job::Least { xi0, near } => Piece::Least(least(xi0, near, curve_settings(settings), go_on)),
        Job::Map {
            xi0,
            release,
            v0_max,
            size,
        } => {
            let (cell, _) =
                map_cell_answer(xi0, release, map_cell(k, size, v0_max), settings, curve);
            Piece::Cell { i: k, cell }
        }
        Job::Rest if k == REST_POINTS => Piece::Critical(
            critical_radius_until(settings, 1e-6, go_on).map_or(f64::NAN, |t| t.value),
        ),
        Job::Rest => {
            let xi0 = REST_XI0_MAX * k as f64 / (REST_POINTS - 1) as f64;
            let cell = classify(Initial::at_rest(xi0, Release::LabRest), settings);
            let xi = cell.ok().and_then(|c| c.rest).map(|r| r.0);
            Piece::Rest { i: k, xi }
        }
        Job::Trade {
            initial,
            paper,
            extra,
        } => Piece::Trade {
            i: k,
            end: trade::piece(initial, paper, extra, k, settings),
        },
    };
    go_on().then_some(p)
}

/// A job: its generation (for the worker), the job, the pieces still to compute, and for a
/// map the escape-speed curve at its ξ0 when known, for a curve a nearby ξ0's (see
/// [`piece_with`]).
#[derive(Clone, Debug)]
struct Request {
    generation: u64,
    job: Job,
    settings: Settings,
    todo: Vec<usize>,
    curve: Option<Vec<Option<Speeds>>>,
}
