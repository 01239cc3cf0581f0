//! The work the table's friction does on the particle along a run, −∫|u|dτ (under Stokes drag,
//! which extends the paper, −γ∫|u|²dτ): by dE/dτ = −|u| it equals E − E(0), so it checks the
//! run. One tally for the headless trajectory rows and the explorer's energy plot.

use super::{Limit, Run, RunError};

/// 5-point Gauss–Legendre nodes and weights on [−1, 1].
const NODES: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_08),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_08),
];

/// Longest stretch of a closed-form run (μ = 0, Stokes drag) one quadrature covers.
pub const CLOSED_PIECE: f64 = 1e-2;

/// The work done up to a τ that only moves forward, read off the run's dense output as it
/// steps: ask [`Tally::to`] for each τ within the latest step (and its end) before the next.
#[derive(Clone, Copy, Debug)]
pub struct Tally {
    work: f64,
    tau: f64,
    energy: f64,
}

impl Tally {
    pub fn new(run: &Run) -> Tally {
        Tally {
            work: 0.0,
            tau: run.tau(),
            energy: run.state().energy(),
        }
    }

    /// The work up to `t` (held at the stop once stuck: nothing slides), counted on from the
    /// τ last asked. Inside a step, Gauss–Legendre on its dense output: |u| is smooth there
    /// (stops are its ends), so this is exact to the interpolant's order, where trapezoids on
    /// the explorer's τ grid were off by up to 1.8e-4.
    pub fn to(&mut self, run: &Run, t: f64) -> Result<f64, RunError> {
        let t = t.min(run.tau());
        if t <= self.tau {
            return Ok(self.work);
        }
        let energy = run.state_at(t)?.energy();
        self.work += match run.last_step().map(|l| l.limit) {
            // μ = 0 does no work.
            _ if run.initial().frictionless => 0.0,
            _ if run.closed_form() => {
                let n = ((t - self.tau) / CLOSED_PIECE).ceil().clamp(1.0, 1e5) as usize;
                let mut sum = 0.0;
                for k in 0..n {
                    let at = |k: usize| self.tau + (t - self.tau) * k as f64 / n as f64;
                    sum += gauss(run, at(k), at(k + 1))?;
                }
                sum
            }
            // A stretch taken in closed form has no dense output of its own (its segment is a
            // cubic between the ends): the identity gives its work.
            Some(Limit::ClosedForm) => energy - self.energy,
            _ => gauss(run, self.tau, t)?,
        };
        (self.tau, self.energy) = (t, energy);
        Ok(self.work)
    }
}

/// −∫ power dτ over [t0, t1] by 5-point Gauss–Legendre on the run's dense output.
fn gauss(run: &Run, t0: f64, t1: f64) -> Result<f64, RunError> {
    let power = |u: f64| match run.settings().stokes() {
        Some(gamma) => gamma * u * u,
        None => u,
    };
    let (mid, half) = (0.5 * (t0 + t1), 0.5 * (t1 - t0));
    NODES.iter().try_fold(0.0, |w, &(x, weight)| {
        let u = run.state_at(mid + half * x)?.u_lab().length();
        Ok(w - half * weight * power(u))
    })
}
