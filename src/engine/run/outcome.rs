//! How a run ends and how we know: stuck, escaped (with the certificate that proves it), or
//! still running; and the errors that stop a run early (Sec. II, properties 1 and 2).

use crate::model::State;
use glam::DVec2;
use serde::Serialize;

/// How escape was certified (CONVENTIONS.md "Outcomes"; Sec. II, property 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Certificate {
    /// ξ > 1 and ξ′ > 0: ξ′ can never turn negative again, so it never comes back (under
    /// Stokes drag too: `engine::stokes::Stokes::escape`).
    Radial,
    /// E = ½|u|² − ½ξ² < −½(μ_s/μ_k)² with dE/dτ = −|u|: it can never be at rest at
    /// ξ ≤ μ_s/μ_k (where it could hold) again.
    Energy,
}

impl Certificate {
    /// The bound in words, for messages.
    pub fn describe(self) -> &'static str {
        match self {
            Certificate::Radial => "radial: xi = 1 crossed moving out, never to turn back",
            Certificate::Energy => {
                "energy: E < -R^2/2 (R = mu_s/mu_k), which holds only beyond xi = R: it can never rest inside xi = R again (it may still be moving inward)"
            }
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Escape {
    pub tau: f64,
    pub by: Certificate,
    /// The particle where the certificate first holds.
    #[serde(skip)]
    pub state: State,
}

/// Where a run stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Status {
    Slipping,
    /// At rest on the table at `q` (table frame) since `tau`: it rides the table forever.
    Stuck {
        tau: f64,
        q: DVec2,
    },
}

/// What ended a call to [`Run::run`](super::Run::run).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Outcome {
    Stuck,
    Escaped,
    /// τ-max came first.
    Running,
}

impl Outcome {
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Stuck => "stuck",
            Outcome::Escaped => "escaped",
            Outcome::Running => "running",
        }
    }
}

/// Why a run could not go on.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RunError {
    /// The step budget ran out before the run ended.
    #[error("step budget of {steps} steps exhausted at tau = {tau:.6}")]
    Budget { steps: u64, tau: f64 },
    /// dp54 could not meet the tolerance with a representable step.
    #[error("step size underflow at tau = {tau:.6}: the tolerance cannot be met")]
    StepUnderflow { tau: f64 },
    /// A state was asked for at a τ the run cannot interpolate: it holds dense output for its
    /// latest step only, `from` to `to`.
    #[error("no state at tau = {tau}: the run can interpolate only from {from} to {to}")]
    OutOfRange { tau: f64, from: f64, to: f64 },
    /// A closed form's position left f64's range (Stokes drag grows exponentially).
    #[error(
        "the position overflows at tau = {tau:.6}: the particle is beyond any representable distance"
    )]
    Overflow { tau: f64 },
}

/// The paper's raw RK2 has no stop event, so it never sticks: it is taken to be at rest once
/// |u| is within one step's worth of friction (|u| ≤ dt) inside ξ ≤ 1 (Sec. IV's scheme). The
/// one rule the bench scores it by and the explorer labels it with.
pub fn raw_at_rest(s: &State, dt: f64) -> bool {
    s.u_lab().length() <= dt && s.xi() <= 1.0
}

/// Whether escape is certified at `s` under Coulomb friction that holds at rest out to
/// ξ = `hold` (= μ_s/μ_k, the paper's 1):
///
/// - Energy: a rest at ξ ≤ hold has E = −½ξ² ≥ −½hold², and E never rises.
/// - Radial: ξ > 1 and ξ′ > 0. Then ξ′ > 0 for ever and the particle never stops, so no
///   μ_s ≥ μ_k can catch it. Proof: while it slides, Eq. (6) gives ξ″ = ξθ′² − ξ′/|u| with
///   θ′ = 1 + w/ξ (w the tangential part of u), i.e. ξ″ = ξ + 2w + w²/ξ − ξ′/|u|. Let τ1 be
///   the first time after τ0 at which ξ′ = 0 or u = 0; before it ξ > ξ(τ0) > 1. If u(τ1) ≠ 0,
///   |u| ≥ m > 0 near τ1 and ξ″ ≥ −ξ′/m, so ξ′(τ1) ≥ ξ′(τa)e^{−(τ1−τa)/m} > 0. If u(τ1) = 0,
///   then w, ξ′ → 0, and as |ξ′/|u|| ≤ 1, ξ″ ≥ ξ − 1 + 2w + w²/ξ > (ξ(τ0) − 1)/2 > 0 on some
///   [τa, τ1), so ξ′(τ1) > ξ′(τa) > 0, yet a stop has ξ′ = 0. Either way a contradiction: a
///   stop outside ξ = 1 is only ever reached moving inward (ξ′ < 0).
pub(super) fn certificate(s: &State, hold: f64) -> Option<Certificate> {
    if s.energy() < -0.5 * hold * hold {
        Some(Certificate::Energy)
    } else if s.xi() > 1.0 && s.xi_dot() > 0.0 {
        Some(Certificate::Radial)
    } else {
        None
    }
}

/// Continuous margin whose sign tells whether escape is certified: > 0 iff certified.
pub(super) fn certificate_margin(s: &State, hold: f64) -> f64 {
    (s.xi() - 1.0)
        .min(s.xi_dot())
        .max(-(s.energy() + 0.5 * hold * hold))
}
