//! What one measurement runs: the seeded cases, and one run to its end or to a time.

use crate::engine::{Initial, Run, Settings, State, Status};
use crate::error::Error;
use std::f64::consts::{PI, TAU};

pub use crate::sim::ending::{audit, finish};

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
