//! Whether a run's outcome could be flipped by the run's own error (Sec. II–IV: the threshold
//! between sticking and escaping is the saddle ξ = 1, u = 0, where runs are most sensitive).
//!
//! Near the saddle H = ½(|u|² − (1 − ξ)²) is nearly conserved and its final value is a smooth
//! function of the release ([`saddle_h`]): −½(1 − ξ_rest)² for a stuck run, ½|u|² where an
//! escaping one crosses ξ = 1. Its size is the outcome's margin. The run's error in it is
//! measured against a shadow run 1000× tighter (the explorer's `e` does the same for the
//! position): the outcome is certain when the shadow agrees and the difference is well inside
//! the margin.

use super::State;
use super::method::{Method, Settings, TOL_RANGE};
use super::run::{Outcome, Run};
use super::saddle::saddle_h;

/// Shadow steps allowed: a shadow that cannot finish within them leaves the outcome in doubt.
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
    /// The shadow's outcome (`None`: it could not finish within [`SHADOW_BUDGET`]).
    pub shadow: Option<Outcome>,
}

/// The state at which a run's outcome was decided: the stop, the escape certificate, or its
/// latest state.
pub fn decided_state(run: &Run) -> State {
    match (run.outcome(), run.escape) {
        (Outcome::Escaped, Some(e)) => e.state,
        _ => run.state(),
    }
}

/// Checks a finished run (stuck, escaped, or run to `tau_max`) against a shadow run with
/// dp54 at 1000× its tolerance (fixed-step runs: tol 1e-12), in the same frame.
pub fn doubt(run: &Run, tau_max: f64) -> Doubt {
    let own = run.outcome();
    let end = decided_state(run);
    let margin = saddle_h(&end).abs();
    if run.initial.frictionless {
        // Closed form: exact.
        return Doubt {
            certain: true,
            margin,
            error: 0.0,
            shadow: Some(own),
        };
    }
    let tol = match run.settings.method() {
        Method::Dp54 | Method::Dop853 => (run.settings.scheme.knob() * 1e-3).max(TOL_RANGE.0),
        _ => 1e-12,
    };
    let settings = Settings {
        max_steps: SHADOW_BUDGET,
        frame: run.settings.frame,
        ..Settings::dp54(tol)
    };
    // A stuck or escaping run near the saddle may take the shadow longer to decide.
    let limit = match own {
        Outcome::Running => tau_max,
        _ => (2.0 * end.tau + 10.0).min(tau_max.max(end.tau)),
    };
    let shadow = Run::new(run.initial, settings)
        .ok()
        .and_then(|mut s| s.run(limit, true).ok().map(|o| (o, decided_state(&s))));
    match shadow {
        Some((o, s)) => {
            let error = (saddle_h(&s) - saddle_h(&end)).abs();
            Doubt {
                certain: o == own && (own == Outcome::Running || error < SHARE * margin),
                margin,
                error,
                shadow: Some(o),
            }
        }
        None => Doubt {
            certain: false,
            margin,
            error: f64::INFINITY,
            shadow: None,
        },
    }
}
