//! What one measurement runs: the seeded cases, and one run to its end or to a time.

use crate::engine::run::raw_at_rest;
use crate::engine::{Initial, Outcome, Run, Settings, State, Status};
use crate::error::Error;
use glam::DVec2;
use std::f64::consts::{PI, TAU};

/// A, B and D of the paper, then `n` seeded releases (ξ0 ∈ [0, 0.9], φ ∈ [0, 2π),
/// v0 ∈ [0, 0.5]: most of them stick).
pub fn cases(n: usize, seed: u64) -> Vec<Initial> {
    let mut v = vec![
        Initial::velocity(0.5, PI, 1.0),
        Initial::velocity(0.5, 0.0, 0.6),
        Initial::velocity(1.1, 1.2 * PI, 1.3),
    ];
    let mut rng = crate::rng::SplitMix64(seed);
    for _ in 0..n {
        let xi0 = 0.9 * rng.unit();
        let phi = TAU * rng.unit();
        let v0 = 0.5 * rng.unit();
        v.push(Initial::velocity(xi0, phi, v0));
    }
    v
}

/// How a run ended, where, and at what cost.
#[derive(Clone, Copy, Debug)]
pub struct End {
    pub outcome: Outcome,
    /// Stop time (stuck) or certificate time (escaped).
    pub tau: f64,
    /// Rest position in the table frame (stuck).
    pub q: DVec2,
    pub evals: u64,
}

/// Runs to the stop or the escape certificate. The paper's raw scheme has no stick event: its
/// stop is declared at the first step with |u| ≤ dt at ξ ≤ 1 (one step's worth of friction).
pub fn finish(initial: Initial, settings: Settings, tau_max: f64) -> Result<End, Error> {
    let mut run = Run::new(initial, settings)?;
    if settings.method().stick_events() {
        let (outcome, s) = run.finish(tau_max)?;
        return Ok(End {
            outcome,
            tau: s.tau,
            q: s.q(),
            evals: run.cost().rhs_evals,
        });
    }
    let dt = settings.scheme.knob();
    while run.goes_on(tau_max, true) && !raw_at_rest(&run.state(), dt) {
        run.step(tau_max)?;
    }
    let s = run.state();
    let (outcome, tau, q) = match run.escape() {
        Some(e) => (Outcome::Escaped, e.tau, e.state.q()),
        None if raw_at_rest(&s, dt) => (Outcome::Stuck, s.tau, s.q()),
        None => (Outcome::Running, s.tau, s.q()),
    };
    Ok(End {
        outcome,
        tau,
        q,
        evals: run.cost().rhs_evals,
    })
}

/// The lab state at exactly `tau` (no stopping at escape), and the cost.
pub fn state_at(initial: Initial, settings: Settings, tau: f64) -> Result<(State, u64), Error> {
    let mut run = Run::new(initial, settings)?;
    run.run(tau, false)?;
    let s = match run.status() {
        Status::Stuck { .. } => run.state_at(tau)?,
        Status::Slipping => run.state(),
    };
    Ok((s, run.cost().rhs_evals))
}

/// What one run to its stop (or escape) states about itself, and what its end game did: the
/// input of a row's stated-against-actual and end-game lines (not timed).
#[derive(Clone, Copy, Debug)]
pub struct Audit {
    /// How and where it ended: the stop (or the certificate, or τ-max) and the rest place.
    pub outcome: Outcome,
    pub tau: f64,
    pub q: DVec2,
    /// The second opinion's stated errors of the stop time and the rest place
    /// ([`crate::engine::doubt::Doubt`]'s `tau_error`, `q_error`).
    pub stated_tau: f64,
    pub stated_q: f64,
    /// RHS evaluations in the end game (implicit steps and closed-form stops), and in all.
    pub end_evals: u64,
    pub evals: u64,
    /// Whether the end game took the stop (the run's last step was one of its).
    pub end_took_stop: bool,
    /// The state where the end game first took a step: up to there the method integrated the
    /// run itself.
    pub handover: Option<State>,
}

/// Runs `initial` with `settings` (a method with stick events) step by step to its stop, its
/// escape certificate or `tau_max`, tallying the end game's steps, then asks its second opinion.
pub fn audit(initial: Initial, settings: Settings, tau_max: f64) -> Result<Audit, Error> {
    use crate::engine::Limit;
    let mut run = Run::new(initial, settings)?;
    let (mut end_evals, mut handover, mut last_end) = (0, None, false);
    while run.goes_on(tau_max, true) {
        let (before, at) = (run.cost().rhs_evals, run.state());
        run.step(tau_max)?;
        last_end = matches!(
            run.last_step().map(|s| s.limit),
            Some(Limit::Implicit | Limit::ClosedForm)
        );
        if last_end {
            end_evals += run.cost().rhs_evals - before;
            handover.get_or_insert(at);
        }
    }
    let d = crate::engine::doubt::doubt(&run, tau_max);
    let end = crate::engine::doubt::decided_state(&run);
    Ok(Audit {
        outcome: run.outcome(),
        tau: end.tau,
        q: end.q(),
        stated_tau: d.tau_error,
        stated_q: d.q_error,
        end_evals,
        evals: run.cost().rhs_evals,
        end_took_stop: last_end && run.outcome() == Outcome::Stuck,
        handover,
    })
}
