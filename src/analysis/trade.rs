//! The work–precision page's points (issue 42, item 5): the release on screen run by each
//! method and tolerance the explorer offers, and by the fixed-step methods at a few dt's (the
//! paper's RK2 at its 1e-3 among them), each to its stop or escape certificate, beside the one
//! converged reference and the reference's cross-check, whose agreement is the resolution below
//! which no error is told. One run a piece, on the analysis workers, as the other pages'.

use crate::engine::method::Scheme;
use crate::engine::{Initial, Method, Outcome, Settings};
use crate::error::Error;
use crate::sim::ending::{audit, finish, reference, reference_check};
use glam::DVec2;

/// How long a run of the page may go (`run`'s default τ-max): where neither a stop nor an
/// escape came by then, the place at this τ is what is measured.
pub const TRADE_TAU: f64 = crate::sim::accuracy::EXPLORER_TAU;
/// Most steps one run of the page takes: rk4 at dt 1e-4 to [`TRADE_TAU`] is 1e6. A run over
/// it (the explorer's own dt of 1e-7, say) is left without a point, as any run that failed.
pub const TRADE_STEPS: u64 = 2_000_000;
/// The fixed steps of rk2, rk4 and the paper's raw RK2 (its own 1e-3 among them).
pub const FIXED_DTS: [f64; 3] = [1e-2, 1e-3, 1e-4];
/// Pieces before the points: the reference, then its cross-check.
pub const REFERENCE_PIECES: usize = 2;

/// The settings the page's runs share: the explorer's frame and coupling, at most
/// [`TRADE_STEPS`] steps, and the reference's scheme, which each piece replaces (so a change
/// of method or tolerance leaves the page's job as it was).
pub fn trade_base(s: Settings) -> Settings {
    Settings {
        max_steps: TRADE_STEPS,
        ..reference(s)
    }
}

/// The page's points in the order `j`/`k` walk them: dp54 and dop853 over the tolerances `run
/// --error` chooses among ([`crate::sim::accuracy::ladder`]), rk2 and rk4 at [`FIXED_DTS`],
/// the paper's raw RK2 at them where the scene allows it (`paper`: μs = μk), then `extra`, the
/// explorer's own setting when it is none of these.
pub fn schemes(paper: bool, extra: Option<Scheme>) -> Vec<Scheme> {
    let mut fixed = vec![Method::Rk2, Method::Rk4];
    if paper {
        fixed.push(Method::Rk2Raw);
    }
    let mut v: Vec<Scheme> = crate::sim::accuracy::ladder(Settings::default())
        .into_iter()
        .map(|s| s.scheme)
        .chain(
            fixed
                .into_iter()
                .flat_map(|m| FIXED_DTS.map(|dt| m.with(dt))),
        )
        .collect();
    v.extend(extra.filter(|e| !v.contains(e)));
    v
}

/// How one run of the page ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ending {
    pub scheme: Scheme,
    pub outcome: Outcome,
    /// When and where it ended: the stop, the escape certificate, or [`TRADE_TAU`]; the place
    /// in the table frame.
    pub tau: f64,
    pub q: DVec2,
    /// Its right-hand-side evaluations (its second opinion's not counted): the work.
    pub rhs: u64,
    /// The larger of the errors of time and place its second opinion states, where the
    /// outcome is certain (infinite where it is not); None for the paper's raw scheme, which
    /// states none.
    pub stated: Option<f64>,
    /// Its last step was the end game's (implicit steps, a closed-form stop): the stop is the
    /// end game's as much as the method's.
    pub end_game: bool,
}

impl Ending {
    /// What the page measures against `reference`: the larger of |Δτ| and |Δq| of the end,
    /// None when the two end differently (stuck against escaped).
    pub fn error(&self, reference: &Ending) -> Option<f64> {
        (self.outcome == reference.outcome).then(|| {
            (self.tau - reference.tau)
                .abs()
                .max((self.q - reference.q).length())
        })
    }
}

/// Runs `initial` with `settings` to its end (see [`Ending`]).
pub fn ending(initial: Initial, settings: Settings) -> Result<Ending, Error> {
    let scheme = settings.scheme;
    if !settings.method().stick_events() {
        let e = finish(initial, settings, TRADE_TAU)?;
        return Ok(Ending {
            scheme,
            outcome: e.outcome,
            tau: e.tau,
            q: e.q,
            rhs: e.evals,
            stated: None,
            end_game: false,
        });
    }
    let a = audit(initial, settings, TRADE_TAU)?;
    Ok(Ending {
        scheme,
        outcome: a.outcome,
        tau: a.tau,
        q: a.q,
        rhs: a.evals,
        stated: Some(if a.certain {
            a.stated_tau.max(a.stated_q)
        } else {
            f64::INFINITY
        }),
        end_game: a.end_took_stop,
    })
}

/// Piece `k` of the page for `initial` (see [`schemes`]) at `base` ([`trade_base`]): the
/// reference, its cross-check, then the points. None where the run could not finish.
pub fn piece(
    initial: Initial,
    paper: bool,
    extra: Option<Scheme>,
    k: usize,
    base: Settings,
) -> Option<Ending> {
    let settings = match k {
        0 => reference(base),
        1 => reference_check(base),
        _ => Settings {
            scheme: *schemes(paper, extra).get(k - REFERENCE_PIECES)?,
            ..base
        },
    };
    ending(initial, settings).ok()
}

/// The reference's resolution: its disagreement with its cross-check (as the end is measured),
/// at least a few ulps of the stop time; None when the two end differently.
pub fn resolution(reference: &Ending, check: &Ending) -> Option<f64> {
    let ulps = 4.0 * f64::EPSILON * reference.tau.abs().max(1.0);
    check.error(reference).map(|e| e.max(ulps))
}
