//! One integration run with its events: stick–slip (Sec. II, property 1) located inside the
//! step, the escape certificate (property 2 and the energy bound), and cost counters.

use super::method::{
    Controller, Cost, Dense, Segment, Settings, dp5_step, fixed_step, initial_step,
};
use super::model::{Initial, State, Y, rotate, zcross};
use super::stop::{frozen_stop, frozen_stop_error, radial_stop};
use glam::DVec2;
use serde::Serialize;
use std::fmt;

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

/// How escape was certified (CONVENTIONS.md "Outcomes"; Sec. II, property 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Certificate {
    /// ξ > 1 and ξ′ > 0: ξ′ can never turn negative again, so it never comes back.
    Radial,
    /// E = ½|u|² − ½ξ² < −½ with dE/dτ = −|u|: it can never be at rest at ξ ≤ 1 again.
    Energy,
}

impl Certificate {
    /// The bound in words, for messages.
    pub fn describe(self) -> &'static str {
        match self {
            Certificate::Radial => {
                "the radial certificate: xi = 1 crossed moving out, never to turn back"
            }
            Certificate::Energy => {
                "the energy certificate: E < -1/2, so it can never rest inside xi = 1 again (it may not have crossed xi = 1 yet)"
            }
        }
    }
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
        if settings.method.stick_events() && s0.u_lab() == DVec2::ZERO && s0.xi() <= 1.0 {
            run.status = Status::Stuck {
                tau: 0.0,
                q: s0.q(),
            };
        }
        if let Some(by) = certificate(&s0) {
            run.escape = Some(Escape { tau: 0.0, by });
        }
        if settings.method.adaptive() {
            run.h = initial_step(|y| frame.rhs(y), y, run.f, settings.tol);
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
        if self.settings.method.stick_events() && u != DVec2::ZERO && speed < UNDERFLOW_SPEED {
            let decel = 1.0 - q.dot(u / speed);
            self.jump(
                if decel > 0.0 { speed / decel } else { 0.0 },
                q,
                DVec2::ZERO,
            );
            return Ok(());
        }
        if self.settings.method.adaptive()
            && u != DVec2::ZERO
            && q.length() < 1.0
            && frozen_stop_error(q, u) <= FROZEN_SHARE * self.settings.tol
        {
            let (t, dq) = frozen_stop(q, u);
            if t <= cap {
                self.jump(t, q + dq, DVec2::ZERO);
                return Ok(());
            }
        }
        if self.settings.method.stick_events() {
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
        let (seg, err_ratio) = if self.settings.method.adaptive() {
            let (seg, err) = self.dp54_step(cap)?;
            (seg, Some(err))
        } else {
            (self.fixed_step(cap), None)
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

    fn fixed_step(&mut self, cap: f64) -> Segment {
        let frame = self.settings.frame;
        let h = self.settings.dt.min(cap);
        let y1 = fixed_step(
            self.settings.method,
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
    fn dp54_step(&mut self, cap: f64) -> Result<(Segment, f64), RunError> {
        let frame = self.settings.frame;
        loop {
            let h = self.h.min(cap);
            if h < 1e-14 * self.tau.abs().max(1.0) {
                return Err(RunError::StepUnderflow { tau: self.tau });
            }
            let trial = dp5_step(|y| frame.rhs(y), self.y, self.f, h, self.settings.tol);
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

    /// Looks ahead for a stop. d|u|/dτ = q·û − 1 (Coriolis does no work), so a stop is
    /// ≈ |u|/(1 − q·û) ahead: steps are capped to a fraction of that, and a stop close enough
    /// is taken in closed form.
    ///
    /// Inside ξ = 1, û soon turns onto q̂ and the last stretch is radial with ρ″ = ρ − 1: from
    /// ρ and s = |u| it stops at ρ_s = 1 − √((1 − ρ)² − s²) after atanh(s/(1 − ρ)), having
    /// travelled at most s·atanh(s/(1 − ρ)). That end game takes over once the travel left is
    /// below the tolerance, or once explicit steps hover (their stability limit, ~|u|/|q|,
    /// shrinks with |u|).
    fn stop_ahead(&self, s: &State) -> Ahead {
        let u = s.u_lab();
        let speed = u.length();
        if speed == 0.0 {
            return Ahead::Clear;
        }
        let rho = s.xi();
        let decel = 1.0 - s.r.dot(u) / speed;
        let gap = 1.0 - rho;
        // Steps too long for û to be resolved, with û already on q̂: the radial end game is
        // then exact to O(|u|²) and the explicit step is not.
        let stiff = self.natural_step() * rho >= STIFF * speed;
        // û on q̂ to within an angle α whose share of the energy, s²(1 − cos α), the end game
        // may neglect.
        let aligned = speed * (speed - s.r.dot(u) / rho) <= self.travel_tol();
        let end_game = self.stiff_steps >= HOVER_STEPS || (stiff && aligned);
        if gap > 0.0 && speed < gap {
            let t = (speed / gap).atanh();
            if speed * t <= self.travel_tol() || end_game {
                return Ahead::Jump {
                    t,
                    q: radial_stop(s.q(), speed, t),
                    u: DVec2::ZERO,
                };
            }
        } else if end_game && gap > 0.0 {
            // Over the saddle: it reaches ξ = 1 still moving out, if I = s² − (1 − ρ)² stays
            // positive despite the O(s³) loss dI/dτ = −4ρs³ on the way.
            let t = (gap / speed).atanh();
            let i = speed * speed - gap * gap;
            if i > 8.0 * speed.powi(3) * t {
                let q = s.q() / rho;
                return Ahead::Jump {
                    t,
                    q,
                    u: q * (i - 4.0 * speed.powi(3) * t).sqrt(),
                };
            }
        } else if self.stiff_steps >= HOVER_STEPS {
            // At the saddle ξ ≈ 1 itself: stop here and let Filippov's rule decide.
            return Ahead::Jump {
                t: 0.0,
                q: s.q(),
                u: DVec2::ZERO,
            };
        }
        if decel <= 0.0 {
            return Ahead::Clear;
        }
        let t = speed / decel;
        if stiff && !aligned && t > SNAP_T {
            // Not yet on q̂: steps within the stability limit let û turn as it does.
            return Ahead::Cap((STOP_CAP * t).min(speed / rho), Limit::Stability);
        }
        if t <= SNAP_T {
            // Constant deceleration over a tiny interval.
            Ahead::Jump {
                t,
                q: s.q() + s.u() * (0.5 * t),
                u: DVec2::ZERO,
            }
        } else {
            Ahead::Cap(STOP_CAP * t, Limit::StopAhead)
        }
    }

    /// The step the integrator would take with no stop ahead.
    fn natural_step(&self) -> f64 {
        if self.settings.method.adaptive() {
            self.h
        } else {
            self.settings.dt
        }
    }

    /// Distance a particle may still travel when its stop is taken in closed form.
    fn travel_tol(&self) -> f64 {
        if self.settings.method.adaptive() {
            1e-3 * self.settings.tol
        } else {
            1e-13
        }
    }

    /// Takes the closed-form stretch to `t` ahead, arriving at table-frame `q` with `u`. A
    /// stop (u = 0) sticks if ξ ≤ 1, else it slips on (Filippov).
    fn jump(&mut self, t: f64, q: DVec2, u: DVec2) {
        let frame = self.settings.frame;
        let tau = self.tau + t;
        let r = rotate(q, tau);
        let to = State {
            tau,
            r,
            v: rotate(u, tau) + zcross(r),
        };
        let y1 = frame.from_state(&to);
        let f1 = frame.rhs(y1);
        self.cost.rhs_evals += 1;
        let seg = Segment {
            t0: self.tau,
            h: t,
            y0: self.y,
            y1,
            dense: Dense::Hermite { f0: self.f, f1 },
        };
        self.advance(seg, f1);
        self.last = Some(seg);
        self.last_step = Some(StepInfo {
            t0: seg.t0,
            h: t,
            limit: Limit::ClosedForm,
            err_ratio: None,
            rejected: 0,
        });
        self.stiff_steps = 0;
        if u != DVec2::ZERO {
            return;
        }
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
