//! Whether a run's outcome could be flipped by the run's own error (Sec. II–IV: the threshold
//! between sticking and escaping is the saddle ξ = 1, u = 0, where runs are most sensitive).
//!
//! Near the saddle H = ½(|u|² − (1 − ξ)²) is nearly conserved and its final value is a smooth
//! function of the release ([`saddle_h`]): −½(1 − ξ_rest)² for a stuck run, ½|u|² where an
//! escaping one crosses ξ = 1. Its size is the outcome's margin. The run's error in it is
//! measured against a second opinion that shares nothing with the run: its own formulation,
//! Sundman time in rim distance ([`sundman`]: no Cartesian state, no frame, no explicit tableau,
//! no closed-form stop but its bounded tail), at 1e-3 of the run's tolerance and again 10×
//! looser to measure its own error. Where that form does not hold (at rest on the table, the
//! paper's raw scheme) the Cartesian check runs ([`second_opinion`]): dop853 at 0.3× the run's
//! tolerance in the *other* frame, with none of the run's closed forms ([`Run::checking`]).
//! The outcome is certain when the second opinion agrees and the difference is well inside the
//! margin. `certain` covers the outcome only: when and where it ended are given with their
//! errors ([`Doubt::tau_error`], [`Doubt::q_error`]), which near a threshold can be large while
//! the outcome is sure. With the Sundman form the τ error is a bound (the difference plus the
//! second opinion's own error): it covers the run's end game and its floating-point floor near
//! the saddle, which the second opinion does not share (docs/numerics.md, *Honest outcomes*).

use super::State;
use super::method::{Scheme, Settings, TOL_RANGE};
use super::model::{Frame, Initial};
use super::run::{Outcome, Run};
use super::saddle::saddle_h;
use super::sundman;

/// Second-opinion steps allowed: one that cannot finish within them leaves the outcome in
/// doubt.
pub const SHADOW_BUDGET: u64 = 200_000;
/// The error must be below this share of the margin.
const SHARE: f64 = 0.25;

/// The verdict on one run's outcome.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Doubt {
    /// False when the run's own error could flip its outcome.
    pub certain: bool,
    /// The margin |H| at the end of the run, and the run's error in it.
    pub margin: f64,
    pub error: f64,
    /// The second opinion's outcome (`None`: it could not finish within [`SHADOW_BUDGET`]).
    pub shadow: Option<Outcome>,
    /// |Δτ| and |Δq| (table frame) between the run's deciding state (the stop, the escape
    /// certificate, or τ-max) and the second opinion's. With the Sundman form each is a bound,
    /// the difference plus the second opinion's own error (its difference from itself 10×
    /// looser, and its tail's bound); with the Cartesian check the measured difference, |Δτ| at
    /// least what a closed-form stop of either may have dropped ([`Run::snap_bound`]).
    /// Infinite when the two end differently.
    pub tau_error: f64,
    pub q_error: f64,
    /// How the second opinion ran, and its right-hand-side evaluations.
    pub check: Settings,
    pub check_evals: u64,
    /// The tolerance of the Sundman-time form ([`sundman`]) when that was the second opinion;
    /// `None` where it does not hold and `check` ran instead.
    pub sundman: Option<f64>,
}

/// The second opinion's tolerance as a share of the run's: on the escape speed's bracket ends
/// 0.1 cost 1.25× the run's instructions, 0.2 1.12×, 0.3 1.06× (when it was chosen). Tighter does not state stop
/// times near the rim better: there a stop is ill-conditioned (τ moves by 1/(2|H|) per unit
/// of H) and the runs at tol 1e-13 and 1e-14 of either method in either frame scatter by
/// ±2.5e-8 at ξ0 = 0.9999 thrown within 1e-11 of escaping, by ±1e-10 at ξ0 = 0.99942, v0 =
/// 0.994 (1 − ξ0): the differences from any second opinion are that scatter.
const CHECK_SHARE: f64 = 0.3;

/// The second opinion on `run`: dop853 at 0.3× its tolerance (dp54's or dop853's; fixed-step
/// runs: tol 1e-12), at least 1e-14, in the other frame, with the same coupling.
pub fn second_opinion(run: &Run) -> Settings {
    let tol = if run.settings().method().adaptive() {
        (run.settings().scheme.knob() * CHECK_SHARE).max(TOL_RANGE.0)
    } else {
        1e-12
    };
    let frame = match run.settings().frame {
        Frame::Lab => Frame::Table,
        Frame::Table => Frame::Lab,
    };
    Settings {
        scheme: Scheme::Dop853 { tol },
        max_steps: SHADOW_BUDGET,
        frame,
        coupling: run.settings().coupling,
    }
}

/// The Sundman form's tolerance for `run`: 1e-3 of an adaptive run's (fixed-step runs:
/// 1e-13), within [1e-14, 1e-10]. It costs a few milliseconds at most.
pub fn sundman_tol(run: &Run) -> f64 {
    let s = run.settings();
    if s.method().adaptive() {
        (1e-3 * s.scheme.knob()).clamp(TOL_RANGE.0, 1e-10)
    } else {
        1e-13
    }
}

/// How the Sundman-time form is run: [`sundman::fate`]'s arguments and answer, computed by it or
/// taken from a store of its answers kept above the engine (the runs of one release at many
/// settings ask for the same few).
pub type Fate<'a> = &'a dyn Fn(&Initial, f64, f64, f64, u64) -> Option<sundman::Ending>;

/// The second opinion in Sundman time ([`sundman::fate`], through `fate`) at [`sundman_tol`]
/// and 10× looser, when the form holds for both and they end alike; `None` otherwise (the
/// Cartesian check runs).
fn sundman_pair(run: &Run, limit: f64, fate: Fate) -> Option<(sundman::Ending, sundman::Ending)> {
    if run.settings().stokes().is_some() || !run.settings().method().stick_events() {
        return None;
    }
    let tol = sundman_tol(run);
    let hold = run.settings().hold();
    let a = fate(&run.initial(), hold, tol, limit, SHADOW_BUDGET)?;
    let b = fate(&run.initial(), hold, 10.0 * tol, limit, SHADOW_BUDGET)?;
    (a.outcome == b.outcome).then_some((a, b))
}

/// The state at which a run's outcome was decided: the stop, the escape certificate, or its
/// latest state.
pub fn decided_state(run: &Run) -> State {
    match (run.outcome(), run.escape()) {
        (Outcome::Escaped, Some(e)) => e.state,
        _ => run.state(),
    }
}

/// The measure whose sign an outcome hangs on, at the deciding state `s`: H (module docs), or,
/// for a particle held at rest outside ξ = 1 by static friction above kinetic (μ_s/μ_k =
/// `hold` > 1), the room left to the most static friction can hold, hold − ξ: a stop beyond
/// it slips on.
fn measure(s: &State, stuck_outside: bool, hold: f64) -> f64 {
    if stuck_outside {
        hold - s.xi()
    } else {
        saddle_h(s)
    }
}

/// Checks a finished run (stuck, escaped, or run to `tau_max`) against its
/// [`second_opinion`].
pub fn doubt(run: &Run, tau_max: f64) -> Doubt {
    doubt_with(run, tau_max, &sundman::fate)
}

/// [`doubt`], the Sundman-time form run through `fate`.
pub fn doubt_with(run: &Run, tau_max: f64, fate: Fate) -> Doubt {
    let own = run.outcome();
    let end = decided_state(run);
    let hold = run.settings().hold();
    let outside = own == Outcome::Stuck && end.xi() > 1.0;
    let margin = measure(&end, outside, hold).abs();
    let check = second_opinion(run);
    if run.closed_form() {
        // Closed form: exact.
        return Doubt {
            certain: true,
            margin,
            error: 0.0,
            shadow: Some(own),
            tau_error: 0.0,
            q_error: 0.0,
            check,
            check_evals: 0,
            sundman: None,
        };
    }
    // A stuck or escaping run near the saddle may take the second opinion longer to decide.
    let limit = match own {
        Outcome::Running => tau_max,
        _ => (2.0 * end.tau + 10.0).min(tau_max.max(end.tau)),
    };
    let judge = |shadow: &State| measure(shadow, outside, hold) - measure(&end, outside, hold);
    if let Some((a, b)) = sundman_pair(run, limit, fate) {
        // Its own error: the same formulation 10× looser differs from it by more than it errs.
        let own_tau = (a.state.tau - b.state.tau).abs() + a.tail.max(b.tail);
        let error = judge(&a.state).abs() + (judge(&a.state) - judge(&b.state)).abs();
        let (tau_error, q_error) = if a.outcome == own {
            (
                (a.state.tau - end.tau).abs() + own_tau,
                (a.state.q() - end.q()).length() + (a.state.q() - b.state.q()).length(),
            )
        } else {
            (f64::INFINITY, f64::INFINITY)
        };
        return Doubt {
            certain: a.outcome == own && (own == Outcome::Running || error < SHARE * margin),
            margin,
            error,
            shadow: Some(a.outcome),
            tau_error,
            q_error,
            check,
            check_evals: a.evals + b.evals,
            sundman: Some(sundman_tol(run)),
        };
    }
    let mut check_evals = 0;
    let shadow = Run::checking(run.initial(), check).ok().and_then(|mut s| {
        let o = s.run(limit, true);
        check_evals = s.cost().rhs_evals;
        o.ok().map(|o| (o, decided_state(&s), s.snap_bound()))
    });
    match shadow {
        Some((o, s, shadow_snap)) => {
            let error = (measure(&s, outside, hold) - measure(&end, outside, hold)).abs();
            // What both may have dropped in a closed-form stop is not in their difference.
            let (tau_error, q_error) = if o == own {
                let dropped = run.snap_bound().max(shadow_snap);
                (
                    (s.tau - end.tau).abs().max(dropped),
                    (s.q() - end.q()).length(),
                )
            } else {
                (f64::INFINITY, f64::INFINITY)
            };
            Doubt {
                certain: o == own && (own == Outcome::Running || error < SHARE * margin),
                margin,
                error,
                shadow: Some(o),
                tau_error,
                q_error,
                check,
                check_evals,
                sundman: None,
            }
        }
        None => Doubt {
            certain: false,
            margin,
            error: f64::INFINITY,
            shadow: None,
            tau_error: f64::INFINITY,
            q_error: f64::INFINITY,
            check,
            check_evals,
            sundman: None,
        },
    }
}
