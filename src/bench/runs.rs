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
