//! One integration run with its events: stick–slip (Sec. II, property 1) located inside the
//! step, the escape certificate (property 2 and the energy bound), and cost counters.

use super::method::{Controller, Cost, Dense, Method, Segment, Settings, dp5_step, fixed_step};
use super::model::{Frame, Initial, State, Y};
use glam::DVec2;
use serde::Serialize;
use std::fmt;

/// Fraction of the predicted time to a stop that one step may cover: the stop is approached in
/// steps that shrink geometrically, never stepped through.
const STOP_CAP: f64 = 0.7;
/// Below this predicted time to a stop, the stop is taken in closed form (constant
/// deceleration): the error is O(T³) ≈ 1e-18, far below any tolerance on offer.
const SNAP_T: f64 = 1e-6;

/// How escape was certified (CONVENTIONS.md "Outcomes"; Sec. II, property 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Certificate {
    /// ξ > 1 and ξ′ > 0: ξ′ can never turn negative again, so it never comes back.
    Radial,
    /// E = ½|u|² − ½ξ² < −½ with dE/dτ = −|u|: it can never be at rest at ξ ≤ 1 again.
    Energy,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Escape {
    pub tau: f64,
    pub by: Certificate,
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

/// What ended a call to [`Run::run`].
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

#[derive(Clone, Debug, PartialEq)]
pub enum RunError {
    /// The step budget ran out before the run ended.
    Budget { steps: u64, tau: f64 },
    /// dp54 could not meet the tolerance with a representable step.
    StepUnderflow { tau: f64 },
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            RunError::Budget { steps, tau } => write!(
                f,
                "step budget of {steps} steps exhausted at tau = {tau:.6} (raise --max-steps, lower --tau-max, or use a larger dt / looser tol)"
            ),
            RunError::StepUnderflow { tau } => {
                write!(
                    f,
                    "step size underflow at tau = {tau:.6}: the tolerance cannot be met"
                )
            }
        }
    }
}

impl std::error::Error for RunError {}

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
    tau: f64,
    y: Y,
    f: Y,
    h: f64,
    ctrl: Controller,
    /// Set once a step near a stop failed to shed speed as friction does (d|u|/dτ = −decel):
    /// the explicit scheme is at its stability limit in the stiff direction of û, where it
    /// can stall at a small |u| forever. From then on steps are capped at |u| until the stop.
    stiff: bool,
}

fn certificate(s: &State) -> Option<Certificate> {
    if s.energy() < -0.5 {
        Some(Certificate::Energy)
    } else if s.xi() > 1.0 && s.xi_dot() > 0.0 {
        Some(Certificate::Radial)
    } else {
        None
    }
}

/// Continuous margin whose sign tells whether escape is certified: > 0 iff certified.
fn certificate_margin(s: &State) -> f64 {
    (s.xi() - 1.0).min(s.xi_dot()).max(-(s.energy() + 0.5))
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
            tau: 0.0,
            y,
            f: frame.rhs(y),
            h: 0.1 * settings.tol.powf(0.2),
            ctrl: Controller::default(),
            stiff: false,
        };
        // Filippov at u = 0: at rest on the table inside ξ ≤ 1 it stays (property 1).
        if settings.method.stick_events() && s0.u_lab() == DVec2::ZERO && s0.xi() <= 1.0 {
            run.status = Status::Stuck {
                tau: 0.0,
                q: s0.q(),
            };
        }
        if let Some(by) = certificate(&s0) {
            run.escape = Some(Escape { tau: 0.0, by });
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
        let frame = self.settings.frame;
        let s = self.state();
        let mut cap = tau_max - self.tau;
        let mut approach = None;
        if self.settings.method.stick_events() {
            // d|u|/dτ = q·û − 1 (Coriolis does no work): the time left to a stop.
            let u = s.u_lab();
            let speed = u.length();
            let decel = 1.0 - s.r.dot(u) / speed.max(f64::MIN_POSITIVE);
            if speed > 0.0 && decel > 0.0 {
                let t_stop = speed / decel;
                if t_stop <= SNAP_T && t_stop <= cap {
                    self.stop(s, t_stop);
                    return Ok(());
                }
                // Near a stop û locks onto ±q̂ (it relaxes at rate 1/|u|) and what is left is
                // a nearly straight deceleration over the path |u| T / 2. The closed form misses
                // the turn of u on the way: from the part of q across u (|q⊥|/decel of the path)
                // and from Coriolis (~2T). dp54 takes the stop in closed form once that is well
                // within its tolerance (the fixed-step methods keep to SNAP_T).
                let path = 0.5 * speed * t_stop;
                let turn = s.r.perp_dot(u).abs() / (speed * decel) + 2.0 * t_stop;
                if self.settings.method.adaptive()
                    && path * turn <= 0.1 * self.settings.tol
                    && t_stop <= cap
                {
                    self.stop(s, t_stop);
                    return Ok(());
                }
                cap = cap.min(STOP_CAP * t_stop);
                if self.stiff {
                    cap = cap.min(speed);
                }
                approach = Some((speed, decel));
            } else {
                self.stiff = false;
            }
        }
        let seg = if self.settings.method.adaptive() {
            self.dp54_step(cap)?
        } else {
            self.fixed_step(cap)
        };
        if let Some((speed, decel)) = approach {
            let after = frame.to_state(seg.y1, seg.t1()).u_lab().length();
            if after > speed - 0.5 * decel * seg.h {
                self.stiff = true;
            }
            // Closing on a stop, the solution's derivatives grow like 1/|u|^k, so the step the
            // tolerance allows shrinks in proportion to |u|: predicting that spares dp54 the
            // rejected trial it would otherwise take at nearly every step of the approach.
            if self.settings.method.adaptive() && speed / decel <= 4.0 * seg.h && after < speed {
                self.h = self.h.min(seg.h * after / speed * 1.1);
            }
        }
        self.last = Some(seg);
        if self.escape.is_none() && certificate(&frame.to_state(seg.y1, seg.t1())).is_some() {
            self.escape = Some(self.locate_escape(&seg));
        }
        Ok(())
    }

    fn fixed_step(&mut self, cap: f64) -> Segment {
        let frame = self.settings.frame;
        let h = self.settings.dt.min(cap);
        let y1 = fixed_step(
            self.settings.method,
            frame,
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

    fn dp54_step(&mut self, cap: f64) -> Result<Segment, RunError> {
        let frame = self.settings.frame;
        loop {
            let h = self.h.min(cap);
            if h < 1e-14 * self.tau.abs().max(1.0) {
                return Err(RunError::StepUnderflow { tau: self.tau });
            }
            let trial = dp5_step(frame, self.y, self.f, h, self.settings.tol);
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
                return Ok(seg);
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

    /// The stop `t_stop` ahead, in closed form under constant deceleration; then stuck if
    /// ξ ≤ 1, else slipping on from u = 0 (Filippov).
    fn stop(&mut self, s: State, t_stop: f64) {
        let frame = self.settings.frame;
        let tau = self.tau + t_stop;
        let q = s.q() + s.u() * (0.5 * t_stop);
        let rest = State::riding(q, tau);
        let y1 = frame.from_state(&rest);
        let f1 = frame.rhs(y1);
        self.cost.rhs_evals += 1;
        let seg = Segment {
            t0: self.tau,
            h: t_stop,
            y0: self.y,
            y1,
            dense: Dense::Hermite { f0: self.f, f1 },
        };
        self.advance(seg, f1);
        self.last = Some(seg);
        if q.length() <= 1.0 {
            self.status = Status::Stuck { tau, q };
        } else {
            self.slip_restarts += 1;
        }
    }

    /// The first time in `seg` at which escape is certified (Illinois on the margin).
    fn locate_escape(&self, seg: &Segment) -> Escape {
        let frame = self.settings.frame;
        let state = |t: f64| frame.to_state(seg.at(t), t);
        let g = |t: f64| certificate_margin(&state(t));
        let tau = illinois(g, seg.t0, seg.t1(), 1e-13);
        let by = certificate(&state(tau)).unwrap_or(Certificate::Radial);
        Escape { tau, by }
    }

    pub fn method(&self) -> Method {
        self.settings.method
    }
    pub fn frame(&self) -> Frame {
        self.settings.frame
    }
}

/// The first crossing of `g` from ≤ 0 to > 0 in [a, b], given g(b) > 0: the Illinois variant
/// of regula falsi, which keeps a superlinear rate where plain regula falsi stalls.
/// Returns a point where g > 0 within `xtol` of the crossing.
pub fn illinois(g: impl Fn(f64) -> f64, mut a: f64, mut b: f64, xtol: f64) -> f64 {
    let (mut ga, mut gb) = (g(a), g(b));
    if ga > 0.0 {
        return a;
    }
    let mut side = 0;
    for _ in 0..200 {
        if (b - a).abs() <= xtol * b.abs().max(1.0) {
            break;
        }
        let mut c = (a * gb - b * ga) / (gb - ga);
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let gc = g(c);
        if gc > 0.0 {
            b = c;
            gb = gc;
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        } else {
            a = c;
            ga = gc;
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        }
    }
    b
}
