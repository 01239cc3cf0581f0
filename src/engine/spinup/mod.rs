//! The table spun up until the coin slides (extends the paper: its Sec. IV sets Eq. 22 against
//! the familiar measure of μ, raising Ω under a coin at rest until it slips). A model of its
//! own: the constant-Ω run (`run`), its closed forms, events and certificates stay as they are.
//!
//! Units: a reference rate Ω_ref (a scene's `[units] rpm`) takes the place of the constant Ω,
//! so τ = Ω_ref t, lengths are in R_max = μ_k g/Ω_ref², speeds in μ_k g/Ω_ref, Ω in Ω_ref and
//! the ramp's rate a = Ω̇/Ω_ref². A table that stops ramping at Ω = 1 is the paper's.
//!
//! The coin starts at rest on the table at (ξ0, 0). While stuck it turns with the table
//! (closed form); it slips where the friction it needs, ξ0 √(Ω⁴ + a²), passes static friction
//! μ_s/μ_k (located by Illinois, checked against [`Ramp::onset`]). Then it slides at μ_k in
//! the lab frame on the shared stepper, a stop ahead approached in shrinking steps and taken
//! in closed form within the tolerance; it sticks again where friction can hold it, and the
//! escape certificate (ξΩ² > 1 moving out, [`Z::certificate_margin`]) is located by Illinois.

use super::error::Error;
use super::method::Settings;
use super::model::{Initial, Release, State, rotate};
use super::roots::illinois;
use super::run::{RunError, Stop};
use super::stepper::{Cost, Segment, StepError, Stepper, too_short};
use glam::DVec2;

mod ramp;
mod slide;

pub use ramp::{Onset, Ramp, inferred_mu};
pub use slide::Z;

/// Fraction of the predicted time to a stop that one step may cover (as `run`'s).
const STOP_CAP: f64 = 0.7;

/// Where a spin-up run stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    /// At rest on the table at `q` (table frame) since `tau`.
    Stuck {
        tau: f64,
        q: DVec2,
    },
    Sliding,
}

/// The slip: when, at which rate, and the μ a student would infer from it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Slip {
    pub tau: f64,
    pub omega: f64,
    /// Ω_slip² ξ0 in units of μ_k ([`inferred_mu`]).
    pub inferred_mu: f64,
}

/// A coin at rest on a table spinning up: stuck, then sliding, perhaps stuck again.
#[derive(Clone, Debug)]
pub struct SpinRun {
    ramp: Ramp,
    xi0: f64,
    settings: Settings,
    phase: Phase,
    slip: Option<Slip>,
    /// When the escape certificate first held, and the coin there.
    escape: Option<(f64, State)>,
    /// Stops after which it slid on, and stops that held.
    restarts: u32,
    sticks: u32,
    stepper: Stepper<Z>,
    last: Option<Segment<Z>>,
    /// The latest ride that ended in a slip (from, to, table-frame q): its closed form still
    /// answers [`SpinRun::state_at`] there once the slide has begun in the same step.
    ride: Option<(f64, f64, DVec2)>,
    cost: Cost,
}

impl SpinRun {
    /// A coin at rest on the table at ξ0, the table ramping as `ramp` says; `settings` give the
    /// integrator, the step budget and μ_s/μ_k (Coulomb friction only; the slide is
    /// integrated in the lab frame whatever the settings' frame).
    pub fn new(ramp: Ramp, xi0: f64, settings: Settings) -> Result<SpinRun, Error> {
        ramp.validate()?;
        Initial::at_rest(xi0, Release::TableRest).validate()?;
        settings.validate()?;
        if settings.stokes().is_some() || !settings.method().stick_events() {
            return Err(Error::refused(
                "the spin-up is modelled with dry friction and stick events: Coulomb coupling and a method other than rk2-raw",
            ));
        }
        let rate = ramp.rate;
        let z0 = Z::riding(DVec2::new(xi0, 0.0), ramp.omega0);
        let mut cost = Cost::default();
        let stepper = Stepper::new(|z: Z| z.rhs(rate), z0, settings.scheme, &mut cost);
        Ok(SpinRun {
            ramp,
            xi0,
            settings,
            phase: Phase::Stuck { tau: 0.0, q: z0.p },
            slip: None,
            escape: None,
            restarts: 0,
            sticks: 0,
            stepper,
            last: None,
            ride: None,
            cost,
        })
    }

    pub fn ramp(&self) -> Ramp {
        self.ramp
    }
    pub fn xi0(&self) -> f64 {
        self.xi0
    }
    pub fn settings(&self) -> Settings {
        self.settings
    }
    pub fn phase(&self) -> Phase {
        self.phase
    }
    /// The first slip, once it has come.
    pub fn slip(&self) -> Option<Slip> {
        self.slip
    }
    /// When the escape certificate first held, and where.
    pub fn escape(&self) -> Option<(f64, State)> {
        self.escape
    }
    /// Momentary stops it slid on from, and stops that held.
    pub fn stops(&self) -> (u32, u32) {
        (self.restarts, self.sticks)
    }
    pub fn cost(&self) -> Cost {
        self.cost
    }

    /// How far the run has got: the slide's τ (a stuck coin's is any later τ).
    pub fn tau(&self) -> f64 {
        self.stepper.t
    }

    /// The coin at τ: riding the table in closed form while stuck (from its stick on), on the
    /// latest step's dense output while sliding; elsewhere an error, never a nearby state.
    pub fn state_at(&self, tau: f64) -> Result<State, RunError> {
        let now = self.stepper.t;
        match (self.phase, self.last) {
            (Phase::Stuck { tau: ts, q }, _) if tau >= ts => Ok(self.riding(q, tau)),
            _ if let Some((from, to, q)) = self.ride
                && (from..=to).contains(&tau) =>
            {
                Ok(self.riding(q, tau))
            }
            (_, Some(seg)) if tau >= seg.t0 && tau <= seg.t1() => Ok(lab(seg.at(tau), tau)),
            _ if tau == now => Ok(lab(self.stepper.y, now)),
            (_, seg) => Err(RunError::OutOfRange {
                tau,
                from: seg.map_or(now, |s| s.t0),
                to: now,
            }),
        }
    }

    /// The coin at rest on the table at table-frame `q`, at τ.
    fn riding(&self, q: DVec2, tau: f64) -> State {
        lab(
            Z::riding(rotate(q, self.ramp.angle(tau)), self.ramp.omega(tau)),
            tau,
        )
    }

    /// Whether a run stepping to its outcome goes on: before `tau_max`, not yet escaped if
    /// it stops there, and not stuck for good (it slips later only if the grip can still grow).
    pub fn goes_on(&self, tau_max: f64, stop_on_escape: bool) -> bool {
        let stuck_for_good = matches!(self.phase, Phase::Stuck { q, .. } if q == DVec2::ZERO);
        self.stepper.t < tau_max && !(stop_on_escape && self.escape.is_some()) && !stuck_for_good
    }

    /// Steps to `tau_max`, or to the escape certificate if `stop_on_escape`.
    pub fn run(&mut self, tau_max: f64, stop_on_escape: bool) -> Result<(), RunError> {
        while self.goes_on(tau_max, stop_on_escape) {
            self.step(tau_max)?;
        }
        Ok(())
    }

    /// One step without passing `tau_max`: while stuck, to the slip (located) or to `tau_max`;
    /// while sliding, one accepted step or one stop.
    pub fn step(&mut self, tau_max: f64) -> Result<Stop, RunError> {
        let certified = self.escape.is_some();
        if self.stepper.t < tau_max {
            match self.phase {
                Phase::Stuck { q, .. } => self.ride(q, tau_max),
                Phase::Sliding => self.advance(tau_max)?,
            }
        }
        Ok(match self.phase {
            _ if self.escape.is_some() && !certified => Stop::Escaped,
            Phase::Stuck { .. } if self.stepper.t >= tau_max => Stop::End,
            Phase::Stuck { .. } => Stop::Stuck,
            _ if self.stepper.t >= tau_max => Stop::End,
            _ => Stop::Stepped,
        })
    }

    /// Stuck at table-frame `q`: to the slip if it comes before `tau_max`, located by Illinois
    /// on the grip's excess over static friction (it only grows), else to `tau_max`.
    fn ride(&mut self, q: DVec2, tau_max: f64) {
        let (xi, hold, t0) = (q.length(), self.settings.hold(), self.stepper.t);
        let excess = |t: f64| self.ramp.grip(xi, t) - hold;
        let mut end = if tau_max.is_finite() {
            tau_max
        } else {
            t0 + 1.0
        };
        // An unbounded ride: double out to a bracket (the grip grows as τ², so soon).
        while !tau_max.is_finite() && excess(end) <= 0.0 && end < f64::MAX / 4.0 {
            end = t0 + 2.0 * (end - t0);
        }
        if xi == 0.0 || excess(end) <= 0.0 {
            self.stepper.t = end;
            self.stepper.y = Z::riding(rotate(q, self.ramp.angle(end)), self.ramp.omega(end));
            return;
        }
        let tau = illinois(excess, t0, end, 1e-15);
        if let Phase::Stuck { tau: since, .. } = self.phase {
            self.ride = Some((since, tau, q));
        }
        self.start_slide(tau, q, tau_max);
    }

    /// The coin loose at τ from rest at table-frame `q`: a fresh stepper there, and the
    /// slide's first stretch in closed form ([`slide::launch`]), not past `tau_max`.
    fn start_slide(&mut self, tau: f64, q: DVec2, tau_max: f64) {
        let (ramp, rate) = (self.ramp, self.ramp.rate);
        let rest = Z::riding(rotate(q, ramp.angle(tau)), ramp.omega(tau));
        self.stepper = Stepper::new(
            |z: Z| z.rhs(rate),
            rest,
            self.settings.scheme,
            &mut self.cost,
        );
        self.stepper.t = tau;
        self.phase = Phase::Sliding;
        if self.slip.is_none() {
            self.slip = Some(Slip {
                tau,
                omega: rest.omega,
                inferred_mu: inferred_mu(rest.omega, self.xi0),
            });
        }
        let travel = self.settings.scheme.tol().map_or(1e-13, |tol| 1e-3 * tol);
        let (t, q1, u1) = slide::launch(&ramp, q, tau, travel, tau_max - tau);
        let (angle, omega) = (ramp.angle(tau + t), ramp.omega(tau + t));
        let mut to = Z::riding(rotate(q1, angle), omega);
        to.w += rotate(u1, angle);
        let seg = self
            .stepper
            .advance(|z: Z| z.rhs(rate), t, to, None, &mut self.cost);
        self.last = Some(seg);
        self.locate_escape(&seg);
    }

    /// One step of the slide: a stop within the tolerance taken in closed form, else a step
    /// capped short of the stop ahead; the escape certificate located inside it.
    fn advance(&mut self, tau_max: f64) -> Result<(), RunError> {
        let tau = self.stepper.t;
        let max_steps = self.settings.max_steps;
        if self.cost.steps + self.cost.rejected >= max_steps {
            return Err(RunError::Budget {
                steps: max_steps,
                tau,
            });
        }
        let mut cap = tau_max - tau;
        if too_short(cap, tau) {
            self.stepper.t = tau_max;
            return Ok(());
        }
        let (z, rate) = (self.stepper.y, self.ramp.rate);
        let speed = z.u().length();
        if speed > 0.0 && z.speed_rate(rate) < 0.0 {
            let t = speed / -z.speed_rate(rate);
            if t <= self.snap_time() {
                self.stop(t);
                return Ok(());
            }
            cap = cap.min(STOP_CAP * t);
        }
        let scheme = self.settings.scheme;
        let (seg, _) = self
            .stepper
            .step(
                |z: Z| z.rhs(rate),
                scheme,
                cap,
                f64::INFINITY,
                &mut self.cost,
                max_steps,
            )
            .map_err(|e| match e {
                StepError::Underflow => RunError::StepUnderflow { tau },
                StepError::Budget => RunError::Budget {
                    steps: max_steps,
                    tau,
                },
            })?;
        self.last = Some(seg);
        self.locate_escape(&seg);
        Ok(())
    }

    /// The error in a stop's time a closed-form stop may make: the tolerance (a fixed step's
    /// dt²), at most 1e-6, as `run`'s.
    fn snap_time(&self) -> f64 {
        let s = self.settings.scheme;
        s.tol().unwrap_or_else(|| s.knob() * s.knob()).min(1e-6)
    }

    /// The stop `t` ahead at constant deceleration: there it sticks if static friction holds
    /// it, else it slides on (Filippov).
    fn stop(&mut self, t: f64) {
        let z = self.stepper.y;
        let tau = self.stepper.t + t;
        let to = Z::riding(z.p + z.w * t, self.ramp.omega(tau));
        let rate = self.ramp.rate;
        let seg = self
            .stepper
            .advance(|z: Z| z.rhs(rate), t, to, None, &mut self.cost);
        self.last = Some(seg);
        self.locate_escape(&seg);
        if self.ramp.grip(to.p.length(), tau) <= self.settings.hold() {
            self.sticks += 1;
        } else {
            self.restarts += 1;
        }
        // At rest: held, it rides until the grip outgrows static friction; else it is loose
        // again at once (`ride` finds the excess already positive).
        self.phase = Phase::Stuck {
            tau,
            q: rotate(to.p, -self.ramp.angle(tau)),
        };
    }

    /// Where in `seg` the escape certificate first holds, if it holds at its end.
    fn locate_escape(&mut self, seg: &Segment<Z>) {
        if self.escape.is_some() || seg.y1.certificate_margin() <= 0.0 {
            return;
        }
        let tau = illinois(|t| seg.at(t).certificate_margin(), seg.t0, seg.t1(), 1e-13);
        self.escape = Some((tau, lab(seg.at(tau), tau)));
    }
}

/// The lab state of a slide point at τ.
fn lab(z: Z, tau: f64) -> State {
    State {
        tau,
        r: z.p,
        v: z.w,
    }
}

#[cfg(test)]
mod tests;
