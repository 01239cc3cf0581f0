//! One integration run: the stepping loop (dp54, rk4, rk2, the paper's raw rk2, μ = 0 in closed
//! form), what bounded each step, and cost counters. Its events are in `events`: stick–slip
//! (Sec. II, property one) located inside the step, and where the escape certificate (property
//! two, or the energy bound) first holds. How a run ends is in `outcome`.

use super::method::Settings;
use super::model::{Initial, State, Y};
use super::model::{rotate, zcross};
use super::stepper::{Cost, Segment, StepError, Stepper, too_short};
use super::stokes::Stokes;
use super::stop::{frozen_at, frozen_stop, frozen_stop_error, radial_launch};
use crate::error::Error;
use glam::DVec2;

mod events;
mod free;
mod limit;
mod outcome;

pub use limit::{EndGame, Limit, StepInfo, Stop};
use outcome::certificate;
pub use outcome::{Certificate, Escape, Outcome, RunError, Status, raw_at_rest};

/// Fraction of the predicted time to a stop that one step may cover: the stop is approached in
/// steps that shrink geometrically, never stepped through.
const STOP_CAP: f64 = 0.7;
/// The largest error in a stop's time that a closed-form stop may make (see
/// `Run::snap_time`): the fixed-step methods' dt² is capped here.
const SNAP_T: f64 = 1e-6;
/// Near a stop the direction of u turns at a rate that grows without bound: ~|q|/|u| inside
/// ξ = 1 (the pull q against friction), at most 1/|u| (friction's Jacobian, −(I − ûûᵀ)/|u|).
/// A step is stiff once it is longer than this many |u|/min(|q|, 1), the stability limit of the
/// explicit methods on offer (RK2's is 2, RK4's 2.8, DOPRI5's 3.3): such stretches take implicit
/// steps ([`super::radau`]). (Far out, |u| ≈ ξ: never stiff.)
const STIFF: f64 = 2.0;

/// dp54 takes a stop inside ξ = 1 in closed form ([`frozen_stop`]) once that form's error
/// bound is below this share of its tolerance, and only within ξ ≤ [`FROZEN_K`], the range
/// over which the bound was measured.
const FROZEN_SHARE: f64 = 0.1;
const FROZEN_K: f64 = 0.95;

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

/// A run from given initial conditions with given settings. Its fields are private: it is
/// advanced only by [`Run::step`] (and the loops over it), and read through its accessors.
#[derive(Clone, Debug)]
pub struct Run {
    initial: Initial,
    settings: Settings,
    cost: Cost,
    status: Status,
    escape: Option<Escape>,
    /// The latest step (or stop), for dense sampling between its ends.
    last: Option<Segment>,
    /// Momentary stops at ξ > 1 after which the particle slipped on.
    slip_restarts: u32,
    /// The latest step, for the explorer's integrator step mode.
    last_step: Option<StepInfo>,
    /// The implicit method's next step size (0: none taken yet), and the table-frame point at
    /// the end of the latest implicit step (see [`Run::table_y`]).
    implicit_h: f64,
    table: Option<(f64, Y, Y)>,
    /// The largest error a closed-form stop of this run may have made in its time (see
    /// [`Run::snap_bound`]).
    snap_bound: f64,
    /// The start (τ, table-frame point) of the latest step when it was a closed-form stop
    /// inside ξ = 1: the state inside it is the closed form's ([`super::stop::frozen_at`]).
    stop_from: Option<(f64, Y)>,
    /// What the end game contributed ([`Run::end_game`]).
    end_game: EndGame,
    /// A second opinion ([`Run::checking`]): it must not share the run's closed forms, so it
    /// takes no [`frozen_stop`] and stops in closed form only within a bound that holds
    /// whichever way û turns; it holds |u| to its relative accuracy near the rim, takes the
    /// stretch before a stop in explicit steps where they are stable ([`Run::explicit_cap`])
    /// and in implicit ones that reach farther than the run's ([`Run::implicit_cap`]), and
    /// pays for no dense output but in the step its escape is located in.
    checking: bool,
    stepper: Stepper,
    /// Stokes drag (with friction on): the run in closed form. Boxed: a point-model run
    /// stays as small (and as fast) as it was.
    stokes: Option<Box<Stokes>>,
}

/// Whether a release under `settings` runs in closed form, every method giving the same exact
/// run: μ = 0 (a straight line in the lab) or Stokes drag (linear, Eq. 3 with a drag in place of
/// friction). Nothing then sticks and nothing has a threshold: no escape speed, outcome map,
/// rest radius, tolerance to choose or trade of work for error.
pub fn closed_form(initial: &Initial, settings: Settings) -> bool {
    initial.frictionless || settings.stokes().is_some()
}

impl Run {
    pub fn new(initial: Initial, settings: Settings) -> Result<Run, Error> {
        initial.validate()?;
        settings.validate()?;
        let frame = settings.frame;
        let s0 = initial.state();
        let mut cost = Cost::default();
        let stepper = Stepper::new(
            |y| frame.rhs(y),
            frame.from_state(&s0),
            settings.scheme,
            &mut cost,
        );
        let mut run = Run {
            initial,
            settings,
            cost,
            status: Status::Slipping,
            escape: None,
            last: None,
            slip_restarts: 0,
            last_step: None,
            implicit_h: 0.0,
            table: None,
            checking: false,
            snap_bound: 0.0,
            stop_from: None,
            end_game: EndGame::default(),
            stepper,
            stokes: settings
                .stokes()
                .filter(|_| !initial.frictionless)
                .map(|gamma| Box::new(Stokes::new(gamma, initial))),
        };
        if let Some(st) = &run.stokes {
            // Closed form throughout: nothing to evaluate.
            run.cost.rhs_evals = 0;
            if st.escape() == Some(0.0) {
                run.escape = Some(Escape {
                    tau: 0.0,
                    by: Certificate::Radial,
                    state: s0,
                });
            }
            return Ok(run);
        }
        if initial.frictionless {
            // Closed form throughout: nothing to evaluate.
            run.cost.rhs_evals = 0;
            return Ok(run);
        }
        // Filippov at u = 0: at rest on the table it stays while the friction it needs, ξ,
        // is within static friction's μ_s/μ_k (property 1; the paper's: ξ ≤ 1).
        let hold = settings.hold();
        if settings.method().stick_events() && s0.u_lab() == DVec2::ZERO && s0.xi() <= hold {
            run.status = Status::Stuck {
                tau: 0.0,
                q: s0.q(),
            };
        }
        if let Some(by) = certificate(&s0, hold) {
            run.escape = Some(Escape {
                tau: 0.0,
                by,
                state: s0,
            });
        }
        Ok(run)
    }

    /// A run for a second opinion: no closed-form stop but those it can bound within its time
    /// tolerance (`Run::snap_time`) or that τ cannot resolve; the stretch before a stop is
    /// integrated. Only its ends and its escape are read, so its steps carry no dense output
    /// ([`Stepper::ends_only`]) but the one its escape is located in.
    pub fn checking(initial: Initial, settings: Settings) -> Result<Run, Error> {
        let run = Run::new(initial, settings)?;
        Ok(Run {
            checking: true,
            stepper: run.stepper.ends_only(),
            ..run
        })
    }

    /// The largest error in a stop's time that the closed forms this run took may have made:
    /// the time to the stop at the slowest deceleration it could have, |u|/(1 − ξ) inside the
    /// rim, or the frozen stop's measured bound. A second opinion that took the same closed form
    /// cannot see it, so [`super::doubt`] states at least this.
    pub fn snap_bound(&self) -> f64 {
        self.snap_bound
    }

    /// The implicit steps and closed forms this run took, and their own errors.
    pub fn end_game(&self) -> EndGame {
        EndGame {
            closed_bound: self.snap_bound,
            ..self.end_game
        }
    }

    pub fn initial(&self) -> Initial {
        self.initial
    }

    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// What the run has cost so far.
    pub fn cost(&self) -> Cost {
        self.cost
    }

    pub fn status(&self) -> Status {
        self.status
    }

    /// Where the escape certificate first held, if it has.
    pub fn escape(&self) -> Option<Escape> {
        self.escape
    }

    /// The latest step (or stop), for dense sampling between its ends.
    pub fn last(&self) -> Option<Segment> {
        self.last
    }

    /// The latest step, for the explorer's integrator step mode.
    pub fn last_step(&self) -> Option<StepInfo> {
        self.last_step
    }

    /// Momentary stops at ξ > 1 after which the particle slipped on.
    pub fn slip_restarts(&self) -> u32 {
        self.slip_restarts
    }

    /// Whether the run is in closed form throughout (μ = 0, or Stokes drag): no steps.
    pub fn closed_form(&self) -> bool {
        closed_form(&self.initial, self.settings())
    }

    /// The Stokes solution, when the coupling is Stokes drag (and friction is on).
    pub fn stokes(&self) -> Option<&Stokes> {
        self.stokes.as_deref()
    }

    pub fn tau(&self) -> f64 {
        match self.status {
            Status::Slipping => self.stepper.t,
            Status::Stuck { tau, .. } => tau,
        }
    }

    /// The particle at the end of the integration so far (at the stop, once stuck).
    pub fn state(&self) -> State {
        self.settings.frame.to_state(self.stepper.y, self.stepper.t)
    }

    /// The particle at a τ in the latest step (or the latest τ itself), at any τ after a stick
    /// (closed-form rotation with the table), or at any τ at all when μ = 0 or under Stokes
    /// drag (closed forms).
    /// Elsewhere the run holds no dense output: an error, never a nearby state.
    pub fn state_at(&self, tau: f64) -> Result<State, RunError> {
        if self.closed_form() {
            return Ok(self.exact_state(tau));
        }
        let now = self.stepper.t;
        match (self.status, self.last) {
            (Status::Stuck { tau: ts, q }, _) if tau >= ts => Ok(State::riding(q, tau)),
            (_, Some(seg)) if tau >= seg.t0 && tau <= seg.t1() => {
                if let Some((_, y)) = self.stop_from.filter(|s| s.0 == seg.t0 && seg.h > 0.0) {
                    let (q, u) = frozen_at(y.p, y.w, (seg.t1() - tau) / seg.h);
                    let r = rotate(q, tau);
                    return Ok(State {
                        tau,
                        r,
                        v: rotate(u, tau) + zcross(r),
                    });
                }
                Ok(self.settings.frame.to_state(seg.at(tau), tau))
            }
            _ if tau == now => Ok(self.state()),
            (_, seg) => Err(RunError::OutOfRange {
                tau,
                from: seg.map_or(now, |s| s.t0),
                to: now,
            }),
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
        while self.goes_on(tau_max, stop_on_escape) {
            self.step(tau_max)?;
        }
        Ok(self.outcome())
    }

    /// Whether a run stepping to its outcome takes another step: slipping, before `tau_max`,
    /// and, if it stops at escape, not yet certified to escape. The one condition of every
    /// loop over [`Run::step`].
    pub fn goes_on(&self, tau_max: f64, stop_on_escape: bool) -> bool {
        self.status == Status::Slipping
            && self.stepper.t < tau_max
            && !(stop_on_escape && self.escape.is_some())
    }

    /// Runs as [`Run::run`] and returns the state at the outcome's time: the stop, the escape
    /// certificate, or τ-max.
    pub fn finish(&mut self, tau_max: f64) -> Result<(Outcome, State), RunError> {
        let outcome = self.run(tau_max, true)?;
        let s = match (outcome, self.escape) {
            (Outcome::Escaped, Some(e)) => e.state,
            _ => self.state(),
        };
        Ok((outcome, s))
    }

    /// Advances by one accepted step, or one located stop, without passing `tau_max`, and says
    /// where that leaves the run. Does nothing once stuck or at `tau_max`.
    pub fn step(&mut self, tau_max: f64) -> Result<Stop, RunError> {
        let certified = self.escape.is_some();
        if self.status == Status::Slipping && self.stepper.t < tau_max {
            self.advance(tau_max)?;
        }
        Ok(match self.status {
            Status::Stuck { .. } => Stop::Stuck,
            _ if self.escape.is_some() && !certified => Stop::Escaped,
            _ if self.stepper.t >= tau_max => Stop::End,
            _ => Stop::Stepped,
        })
    }

    /// One step of [`Run::step`].
    fn advance(&mut self, tau_max: f64) -> Result<(), RunError> {
        if self.cost.steps + self.cost.rejected >= self.settings.max_steps {
            return Err(RunError::Budget {
                steps: self.settings.max_steps,
                tau: self.stepper.t,
            });
        }
        if self.closed_form() {
            return self.free_step(tau_max);
        }
        let frame = self.settings.frame;
        let s = self.state();
        let mut cap = tau_max - self.stepper.t;
        let mut limit = Limit::End;
        if too_short(cap, self.stepper.t) {
            // τ-max to within rounding: no step could be that short.
            self.stepper.t = tau_max;
            return Ok(());
        }
        let Y { p: q, w: u } = self.table_y();
        let speed = u.x.hypot(u.y);
        if self.settings.method().stick_events() && u != DVec2::ZERO && speed < UNDERFLOW_SPEED {
            let decel = 1.0 - q.dot(u / speed);
            self.jump(
                if decel > 0.0 { speed / decel } else { 0.0 },
                q,
                DVec2::ZERO,
                Limit::ClosedForm,
            );
            return Ok(());
        }
        if !self.checking
            && self.settings.method().adaptive()
            && u != DVec2::ZERO
            && q.length() <= FROZEN_K
            && frozen_stop_error(q, u) <= FROZEN_SHARE * self.settings.scheme.knob()
        {
            let (t, dq) = frozen_stop(q, u);
            if t <= cap {
                self.snap_bound = self.snap_bound.max(frozen_stop_error(q, u));
                self.jump(t, q + dq, DVec2::ZERO, Limit::ClosedForm);
                return Ok(());
            }
        }
        if self.settings.method().stick_events()
            && let Some(t) = self.launch_time(&s)
        {
            let (q, u) = radial_launch(q, t.min(cap));
            self.jump(t.min(cap), q, u, Limit::ClosedForm);
            return Ok(());
        }
        if self.settings.method().stick_events() {
            match self.stop_ahead(q, u) {
                Ahead::Jump { t, q: to, u: end } if t <= cap => {
                    self.snap_bound = self.snap_bound.max(worst_stop(q, u, t));
                    self.jump(t, to, end, Limit::ClosedForm);
                    return Ok(());
                }
                Ahead::Cap(c, why) => {
                    if c < cap {
                        (cap, limit) = (c, why);
                    }
                }
                Ahead::Clear | Ahead::Jump { .. } => {}
            }
            match self.explicit_cap(q, speed, cap, limit) {
                Some(c) => cap = c,
                None => return self.implicit_step(self.implicit_cap(cap, limit)),
            }
        }
        if limit == Limit::End {
            cap = self.toward_end(cap);
        }
        let rejected_before = self.cost.rejected;
        let (tau, start) = (self.stepper.t, self.stepper);
        let (seg, err_ratio) = self
            .stepper
            .step(
                |y| frame.rhs(y),
                self.settings.scheme,
                cap,
                // A second opinion holds |u| to its relative accuracy near the rim: a stop's time
                // is |u| over a deceleration of at least |1 − ξ|, so there the absolute
                // 1 + |w| lets the time drift by tol/|1 − ξ| (at ξ0 = 1.00001 thrown in, a
                // tol 1e-7 check was 7e-5 off, and agreed with its run). Down to 1e-3: below,
                // the stretch before a stop turns implicit. The run itself keeps the cheaper
                // norm; the check measures what that costs it.
                if self.checking {
                    speed.max((1.0 - q.length()).abs()).max(1e-3)
                } else {
                    f64::INFINITY
                },
                &mut self.cost,
                self.settings.max_steps,
            )
            .map_err(|e| match e {
                StepError::Underflow => RunError::StepUnderflow { tau },
                StepError::Budget => RunError::Budget {
                    steps: self.settings.max_steps,
                    tau,
                },
            })?;
        let seg = self.escape_in(seg, &start);
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
        Ok(())
    }
}

impl Run {
    /// The next step toward τ-max, `left` ahead: an adaptive run takes the way in equal steps
    /// no longer than its natural one. Cut short, the last step was whatever was left, longer
    /// at a tighter tolerance whose first steps were shorter (case A to τ 0.5 by dop853 was
    /// 3.1e-9 off at tol 1e-3 and 7.9e-8 at 1e-6, both in two steps).
    fn toward_end(&self, left: f64) -> f64 {
        let h = self.natural_step();
        if self.settings.method().adaptive() && h > 0.0 && h < left {
            left / (left / h).ceil()
        } else {
            left
        }
    }
}

/// The slowest a stop from table-frame `q` at `u` could come: inside the rim the deceleration is
/// at least 1 − |q| whichever way û turns, so within |u|/(1 − |q|); outside, where a snap is
/// taken only once the stop is momentary, its constant-deceleration time `t`.
fn worst_stop(q: DVec2, u: DVec2, t: f64) -> f64 {
    let rho = q.length();
    if rho < 1.0 {
        (u.length() / (1.0 - rho)).max(t)
    } else {
        t
    }
}
