//! One integration run: the stepping loop (dp54, rk4, rk2, the paper's raw rk2, μ = 0 in closed
//! form), what bounded each step, and cost counters. Its events are in `events`: stick–slip
//! (Sec. II, property one) located inside the step, and where the escape certificate (property
//! two, or the energy bound) first holds. How a run ends is in `outcome`.

use super::method::{
    Controller, Cost, Dense, FixedRk, Segment, Settings, dp5_step, fixed_step, initial_step,
};
use super::model::{Initial, State, Y};
use super::stop::{frozen_stop, frozen_stop_error};
use glam::DVec2;

mod events;
mod outcome;

use outcome::certificate;
pub use outcome::{Certificate, Escape, Outcome, RunError, Status};

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
    /// Held to the stability limit |u|/|q| while û turns.
    Stability,
    /// The stop (or the pass over the saddle) taken in closed form.
    ClosedForm,
    /// μ = 0: the straight line in closed form.
    Frictionless,
    /// τ-max.
    End,
}

impl Limit {
    pub fn describe(self) -> &'static str {
        match self {
            Limit::Tolerance => "tolerance",
            Limit::FixedStep => "fixed dt",
            Limit::StopAhead => "stop ahead",
            Limit::Stability => "stability",
            Limit::ClosedForm => "closed form",
            Limit::Frictionless => "μ=0 exact",
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

/// Fraction of the predicted time to a stop that one step may cover: the stop is approached in
/// steps that shrink geometrically, never stepped through.
const STOP_CAP: f64 = 0.7;
/// Below this predicted time to a momentary stop outside ξ = 1, the stop is taken in closed
/// form (constant deceleration): the error is O(T²|u|), far below any tolerance on offer.
const SNAP_T: f64 = 1e-6;
/// Near a stop the direction of u turns at a rate ~|q|/|u| that grows without bound: once a
/// step is longer than a few |u|/|q|, explicit steps are unstable and can hover at a small
/// |u| instead of stopping. This many such steps in a row without |u| halving mean hovering:
/// the stop is then taken in closed form.
const HOVER_STEPS: u32 = 50;
/// Hovering is a small-|u| failure: faster particles (far out, |u| ≈ ξ) are left alone.
const HOVER_SPEED: f64 = 1e-3;
/// A step is stiff once it is longer than this many |u|/|q|: the stability limit of the
/// explicit methods on offer (RK2's is 2, RK4's 2.8, DOPRI5's 3.3).
const STIFF: f64 = 2.0;

/// dp54 takes a stop inside ξ = 1 in closed form ([`frozen_stop`]) once that form's error
/// bound is below this share of its tolerance.
const FROZEN_SHARE: f64 = 0.1;

/// How far one closed-form stride of a frictionless run reaches when no end is given: any
/// length costs the same.
const FREE_STRIDE: f64 = 1e3;
/// A relative speed below this is a stop now: its square underflows (|u|² < 1e-300 loses
/// digits, below 1e-308 it is zero, and û = u/|u| with it), so the equations can no longer
/// tell it from rest. The stop is |u|/(1 − q·û) ≤ 1e-150 ahead, beyond what τ can resolve.
const UNDERFLOW_SPEED: f64 = 1e-150;

/// What lies ahead of the particle: see [`Run::stop_ahead`].
enum Ahead {
    Clear,
    Cap(f64, Limit),
    /// Closed form to time `t` ahead, to table-frame position `q` and velocity `u`.
    Jump {
        t: f64,
        q: DVec2,
        u: DVec2,
    },
}

/// A run from given initial conditions with given settings.
#[derive(Clone, Debug)]
pub struct Run {
    pub initial: Initial,
    pub settings: Settings,
    pub cost: Cost,
    pub status: Status,
    pub escape: Option<Escape>,
    /// The latest step (or stop), for dense sampling between its ends.
    pub last: Option<Segment>,
    /// Momentary stops at ξ > 1 after which the particle slipped on.
    pub slip_restarts: u32,
    /// The latest step, for the explorer's integrator step mode.
    pub last_step: Option<StepInfo>,
    /// Consecutive steps longer than the time |u|/|q| in which û turns, and |u| when they
    /// began.
    stiff_steps: u32,
    stiff_speed: f64,
    tau: f64,
    y: Y,
    f: Y,
    h: f64,
    ctrl: Controller,
}

impl Run {
    pub fn new(initial: Initial, settings: Settings) -> Result<Run, String> {
        initial.validate()?;
        settings.validate()?;
        let frame = settings.frame;
        let s0 = initial.state();
        let y = frame.from_state(&s0);
        let mut run = Run {
            initial,
            settings,
            cost: Cost {
                rhs_evals: 1,
                ..Cost::default()
            },
            status: Status::Slipping,
            escape: None,
            last: None,
            slip_restarts: 0,
            last_step: None,
            stiff_steps: 0,
            stiff_speed: 0.0,
            tau: 0.0,
            y,
            f: frame.rhs(y),
            h: 0.0,
            ctrl: Controller::default(),
        };
        if initial.frictionless {
            // Closed form throughout: nothing to evaluate.
            run.cost.rhs_evals = 0;
            return Ok(run);
        }
        // Filippov at u = 0: at rest on the table inside ξ ≤ 1 it stays (property 1).
        if settings.method().stick_events() && s0.u_lab() == DVec2::ZERO && s0.xi() <= 1.0 {
            run.status = Status::Stuck {
                tau: 0.0,
                q: s0.q(),
            };
        }
        if let Some(by) = certificate(&s0) {
            run.escape = Some(Escape { tau: 0.0, by });
        }
        if settings.method().adaptive() {
            run.h = initial_step(|y| frame.rhs(y), y, run.f, settings.scheme.knob());
            run.cost.rhs_evals += 1;
        }
        Ok(run)
    }

    pub fn tau(&self) -> f64 {
        match self.status {
            Status::Slipping => self.tau,
            Status::Stuck { tau, .. } => tau,
        }
    }

    /// The particle at the end of the integration so far (at the stop, once stuck).
    pub fn state(&self) -> State {
        self.settings.frame.to_state(self.y, self.tau)
    }

    /// The particle at any τ not beyond the integration so far that lies in the latest step,
    /// or at any τ after a stick (closed-form rotation with the table).
    pub fn state_at(&self, tau: f64) -> State {
        if self.initial.frictionless {
            return self.initial.free_state(tau);
        }
        match self.status {
            Status::Stuck { tau: ts, q } if tau >= ts => State::riding(q, tau),
            _ => match self.last {
                Some(seg) if tau >= seg.t0 && tau <= seg.t1() => {
                    self.settings.frame.to_state(seg.at(tau), tau)
                }
                _ => self.state(),
            },
        }
    }

    pub fn outcome(&self) -> Outcome {
        match (self.status, self.escape) {
            (Status::Stuck { .. }, _) => Outcome::Stuck,
            (_, Some(_)) => Outcome::Escaped,
            _ => Outcome::Running,
        }
    }

    /// Integrates until stuck, until escape is certified (if `stop_on_escape`), or `tau_max`.
    pub fn run(&mut self, tau_max: f64, stop_on_escape: bool) -> Result<Outcome, RunError> {
        while self.status == Status::Slipping && self.tau < tau_max {
            if stop_on_escape && self.escape.is_some() {
                break;
            }
            self.step(tau_max)?;
        }
        Ok(self.outcome())
    }

    /// Runs as [`Run::run`] and returns the state at the outcome's time: the stop, the escape
    /// certificate, or τ-max.
    pub fn finish(&mut self, tau_max: f64) -> Result<(Outcome, State), RunError> {
        let outcome = self.run(tau_max, true)?;
        let s = match (outcome, self.escape) {
            (Outcome::Escaped, Some(e)) => self.state_at(e.tau),
            _ => self.state(),
        };
        Ok((outcome, s))
    }

    /// Advances by one accepted step, or one located stop, without passing `tau_max`.
    /// Does nothing once stuck.
    pub fn step(&mut self, tau_max: f64) -> Result<(), RunError> {
        if self.status != Status::Slipping || self.tau >= tau_max {
            return Ok(());
        }
        if self.cost.steps + self.cost.rejected >= self.settings.max_steps {
            return Err(RunError::Budget {
                steps: self.settings.max_steps,
                tau: self.tau,
            });
        }
        if self.initial.frictionless {
            self.free_step(tau_max);
            return Ok(());
        }
        let frame = self.settings.frame;
        let s = self.state();
        let mut cap = tau_max - self.tau;
        let mut limit = Limit::End;
        if cap <= 1e-14 * self.tau.abs().max(1.0) {
            // τ-max to within rounding: no step could be that short.
            self.tau = tau_max;
            return Ok(());
        }
        let (q, u) = (s.q(), s.u());
        let speed = u.x.hypot(u.y);
        if self.settings.method().stick_events() && u != DVec2::ZERO && speed < UNDERFLOW_SPEED {
            let decel = 1.0 - q.dot(u / speed);
            self.jump(
                if decel > 0.0 { speed / decel } else { 0.0 },
                q,
                DVec2::ZERO,
            );
            return Ok(());
        }
        if self.settings.method().adaptive()
            && u != DVec2::ZERO
            && q.length() < 1.0
            && frozen_stop_error(q, u) <= FROZEN_SHARE * self.settings.scheme.knob()
        {
            let (t, dq) = frozen_stop(q, u);
            if t <= cap {
                self.jump(t, q + dq, DVec2::ZERO);
                return Ok(());
            }
        }
        if self.settings.method().stick_events() {
            match self.stop_ahead(&s) {
                Ahead::Jump { t, q, u } if t <= cap => {
                    self.jump(t, q, u);
                    return Ok(());
                }
                Ahead::Cap(c, why) => {
                    if c < cap {
                        (cap, limit) = (c, why);
                    }
                }
                Ahead::Clear | Ahead::Jump { .. } => {}
            }
        }
        let rejected_before = self.cost.rejected;
        let (seg, err_ratio) = match self.settings.scheme.fixed() {
            Some((rk, dt)) => (self.fixed_step(rk, dt, cap), None),
            None => {
                let (seg, err) = self.dp54_step(self.settings.scheme.knob(), cap)?;
                (seg, Some(err))
            }
        };
        self.last = Some(seg);
        self.last_step = Some(StepInfo {
            t0: seg.t0,
            h: seg.h,
            limit: if seg.h >= cap {
                limit
            } else if err_ratio.is_some() {
                Limit::Tolerance
            } else {
                Limit::FixedStep
            },
            err_ratio,
            rejected: (self.cost.rejected - rejected_before) as u32,
        });
        let speed = s.u_lab().length();
        if speed > HOVER_SPEED || seg.h * s.xi() < STIFF * speed {
            self.stiff_steps = 0;
        } else if self.stiff_steps == 0 || speed < 0.5 * self.stiff_speed {
            (self.stiff_steps, self.stiff_speed) = (1, speed);
        } else {
            self.stiff_steps += 1;
        }
        if self.escape.is_none() && certificate(&frame.to_state(seg.y1, seg.t1())).is_some() {
            self.escape = Some(self.locate_escape(&seg));
        }
        Ok(())
    }

    /// μ = 0: one closed-form stride to `tau_max` (or [`FREE_STRIDE`] on when that is
    /// infinite), stopping at the escape certificate on the way.
    fn free_step(&mut self, tau_max: f64) {
        let mut end = if tau_max.is_finite() {
            tau_max
        } else {
            self.tau + FREE_STRIDE
        };
        if self.escape.is_none()
            && let Some(te) = self.initial.free_escape()
            && te <= end
        {
            end = te.max(self.tau);
            self.escape = Some(Escape {
                tau: te,
                by: Certificate::Radial,
            });
        }
        let frame = self.settings.frame;
        self.last_step = Some(StepInfo {
            t0: self.tau,
            h: end - self.tau,
            limit: Limit::Frictionless,
            err_ratio: None,
            rejected: 0,
        });
        self.y = frame.from_state(&self.initial.free_state(end));
        self.tau = end;
        self.last = None;
    }

    fn fixed_step(&mut self, rk: FixedRk, dt: f64, cap: f64) -> Segment {
        let frame = self.settings.frame;
        let h = dt.min(cap);
        let y1 = fixed_step(
            rk,
            |y| frame.rhs(y),
            self.y,
            self.f,
            h,
            &mut self.cost.rhs_evals,
        );
        let f1 = frame.rhs(y1);
        self.cost.rhs_evals += 1;
        self.cost.steps += 1;
        let seg = Segment {
            t0: self.tau,
            h,
            y0: self.y,
            y1,
            dense: Dense::Hermite { f0: self.f, f1 },
        };
        self.advance(seg, f1);
        seg
    }

    /// One accepted dp54 step of at most `cap`, and its error against the tolerance.
    fn dp54_step(&mut self, tol: f64, cap: f64) -> Result<(Segment, f64), RunError> {
        let frame = self.settings.frame;
        loop {
            let h = self.h.min(cap);
            if h < 1e-14 * self.tau.abs().max(1.0) {
                return Err(RunError::StepUnderflow { tau: self.tau });
            }
            let trial = dp5_step(|y| frame.rhs(y), self.y, self.f, h, tol);
            self.cost.rhs_evals += 6;
            let (hnew, accepted) = self.ctrl.next(h, trial.err);
            // A capped step says nothing about how large the next free step may be.
            self.h = if h < self.h && accepted {
                self.h.max(hnew)
            } else {
                hnew
            };
            if accepted {
                self.cost.steps += 1;
                let seg = Segment {
                    t0: self.tau,
                    h,
                    y0: self.y,
                    y1: trial.y1,
                    dense: trial.dense,
                };
                self.advance(seg, trial.f1);
                return Ok((seg, trial.err));
            }
            self.cost.rejected += 1;
            if self.cost.steps + self.cost.rejected >= self.settings.max_steps {
                return Err(RunError::Budget {
                    steps: self.settings.max_steps,
                    tau: self.tau,
                });
            }
        }
    }

    fn advance(&mut self, seg: Segment, f1: Y) {
        self.tau = seg.t1();
        self.y = seg.y1;
        self.f = f1;
    }
}
