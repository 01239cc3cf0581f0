//! How one run ends, measured: where and when it stopped (or was certified to escape), what it
//! cost, and what its second opinion states about it. The bench's work–precision rows, `run
//! --error`'s search and the explorer's work–precision page measure runs through these, against
//! the one converged reference ([`reference()`]) whose resolution is its agreement with
//! [`reference_check`].

use crate::engine::run::raw_at_rest;
use crate::engine::{Frame, Initial, Outcome, Run, Settings, State};
use crate::error::Error;
use glam::DVec2;

/// The converged reference: dp54 at tol 1e-13, the rest of the settings (frame, coupling,
/// budget) from `base`.
pub fn reference(base: Settings) -> Settings {
    Settings {
        scheme: crate::engine::Method::Dp54.with(1e-13),
        ..base
    }
}

/// What the reference is checked against across stops: dp54 at 1e-12 in the other frame. (rk4
/// at a small dt agrees on rest positions but not on stop times: its last steps before a stop
/// are at the stability limit of the stiff friction direction.)
pub fn reference_check(base: Settings) -> Settings {
    let frame = match base.frame {
        Frame::Lab => Frame::Table,
        Frame::Table => Frame::Lab,
    };
    Settings {
        scheme: crate::engine::Method::Dp54.with(1e-12),
        frame,
        ..base
    }
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
    /// Whether the second opinion found the outcome certain, and what it cost (its RHS
    /// evaluations).
    pub certain: bool,
    pub check_evals: u64,
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
    let d = super::doubts::second_opinion(&run, tau_max);
    let end = crate::engine::doubt::decided_state(&run);
    Ok(Audit {
        outcome: run.outcome(),
        tau: end.tau,
        q: end.q(),
        stated_tau: d.tau_error,
        stated_q: d.q_error,
        certain: d.certain,
        check_evals: d.check_evals,
        end_evals,
        evals: run.cost().rhs_evals,
        end_took_stop: last_end && run.outcome() == Outcome::Stuck,
        handover,
    })
}
