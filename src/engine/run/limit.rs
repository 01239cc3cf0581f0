//! What a step did, for the explorer's integrator step mode: where it left the run, what
//! bounded it, its length and error; what the end game near a stop contributed.

use serde::Serialize;

/// Where a step left the run (as diffsol's `step() -> StopReason`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// Still slipping, before τ-max.
    Stepped,
    /// The escape certificate first held in this step (later steps, following an escaped
    /// particle, are `Stepped`).
    Escaped,
    /// At rest on the table: it rides the table from now on.
    Stuck,
    /// τ-max reached.
    End,
}

/// What bounded a step (shown by the explorer's integrator step mode).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    /// dp54's error control chose it.
    Tolerance,
    /// The fixed step dt.
    FixedStep,
    /// Capped to a fraction of the time to the stop ahead, |u|/(1 − q·û): never stepped
    /// through.
    StopAhead,
    /// An implicit step (Radau IIA) where explicit ones would be held to the stability limit
    /// |u|/|q| while û turns: the stretch before a stop.
    Implicit,
    /// A stop within the run's time tolerance, or the launch from rest outside ξ = 1, taken in
    /// closed form.
    ClosedForm,
    /// μ = 0: the straight line in closed form.
    Frictionless,
    /// Stokes drag: the linear solution in closed form.
    Drag,
    /// τ-max.
    End,
}

impl Limit {
    pub fn describe(self) -> &'static str {
        match self {
            Limit::Tolerance => "tolerance",
            Limit::FixedStep => "fixed dt",
            Limit::StopAhead => "stop ahead",
            Limit::Implicit => "implicit",
            Limit::ClosedForm => "closed form",
            Limit::Frictionless => "μ=0 exact",
            Limit::Drag => "Stokes exact",
            Limit::End => "τ-max",
        }
    }
}

/// The latest step: its length, what bounded it, dp54's error estimate against the
/// tolerance (≤ 1 accepts), and the tries rejected before it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepInfo {
    pub t0: f64,
    pub h: f64,
    pub limit: Limit,
    pub err_ratio: Option<f64>,
    pub rejected: u32,
}

/// What set a run's result besides its method: the implicit steps (Radau IIA) it took before a
/// stop and the closed forms it took (stops, launches from rest). A fixed-step method's result
/// near a stop is the end game's where these are used; the bench labels its rows by them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct EndGame {
    /// Implicit steps, the τ they covered, and the sum of their local error estimates (each its
    /// error ratio times the tolerance it was held to): what they may have dropped, before any
    /// growth along the run.
    pub implicit_steps: u64,
    pub implicit_tau: f64,
    pub implicit_error: f64,
    /// Closed-form stretches, the τ they covered, and the bound on a closed-form stop's time
    /// error (`Run::snap_bound`).
    pub closed_steps: u64,
    pub closed_tau: f64,
    pub closed_bound: f64,
}

impl EndGame {
    /// Whether any of the run's result is the end game's rather than its method's.
    pub fn used(&self) -> bool {
        self.implicit_steps > 0 || self.closed_steps > 0
    }
}
