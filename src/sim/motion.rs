//! The run a [`Sim`](super::Sim) drives: the paper's table at constant Ω (`engine::run`), or
//! the table spun up under a coin at rest (`engine::spinup`), modelled only in a scene that
//! asks for it (`[spin]`). Both answer in lab-frame [`State`]s; the table's angle and rate
//! are the run's to say, so the frame shown turns with the table each has.

use crate::engine::model::{coupled_forces, rotate, zcross};
use crate::engine::run::{Escape, RunError, Status, StepInfo};
use crate::engine::spinup::{Phase, SpinRun, Z};
use crate::engine::{Certificate, Cost, Frame, Initial, Outcome, Release, Run, Settings, State};
use glam::DVec2;

#[derive(Clone, Debug)]
pub enum Motion {
    /// Ω = 1 throughout: the paper's table.
    Steady(Run),
    /// Ω(τ) = Ω0 + a τ.
    Spin(SpinRun),
}

impl Motion {
    pub fn settings(&self) -> Settings {
        match self {
            Motion::Steady(r) => r.settings(),
            Motion::Spin(s) => s.settings(),
        }
    }

    pub fn initial(&self) -> Initial {
        match self {
            Motion::Steady(r) => r.initial(),
            Motion::Spin(s) => Initial::at_rest(s.xi0(), Release::TableRest),
        }
    }

    pub fn cost(&self) -> Cost {
        match self {
            Motion::Steady(r) => r.cost(),
            Motion::Spin(s) => s.cost(),
        }
    }

    /// How far the run has got.
    pub fn tau(&self) -> f64 {
        match self {
            Motion::Steady(r) => r.tau(),
            Motion::Spin(s) => s.tau(),
        }
    }

    /// Where a run stands for good: stuck for ever (a spun-up coin only at the centre, where
    /// it needs no friction; elsewhere the growing grip loosens it), else slipping.
    pub fn status(&self) -> Status {
        match self {
            Motion::Steady(r) => r.status(),
            Motion::Spin(s) => match s.phase() {
                Phase::Stuck { tau, q } if q == DVec2::ZERO => Status::Stuck { tau, q },
                _ => Status::Slipping,
            },
        }
    }

    /// The escape and its certificate: on a spun-up table ξΩ² > 1 moving out, the radial
    /// certificate at the rate the table has reached (R_max = 1/Ω² only shrinks).
    pub fn escape(&self) -> Option<Escape> {
        match self {
            Motion::Steady(r) => r.escape(),
            Motion::Spin(s) => s.escape().map(|(tau, state)| Escape {
                tau,
                by: Certificate::Radial,
                state,
            }),
        }
    }

    pub fn outcome(&self) -> Outcome {
        match (self.status(), self.escape()) {
            (Status::Stuck { .. }, _) => Outcome::Stuck,
            (_, Some(_)) => Outcome::Escaped,
            _ => Outcome::Running,
        }
    }

    /// The latest integrator step, where the run keeps one (the spin-up does not).
    pub fn last_step(&self) -> Option<StepInfo> {
        match self {
            Motion::Steady(r) => r.last_step(),
            Motion::Spin(_) => None,
        }
    }

    /// Whether every τ has a closed form (μ = 0): the path then needs no step's dense output.
    pub fn closed_form(&self) -> bool {
        matches!(self, Motion::Steady(r) if r.closed_form())
    }

    pub fn goes_on(&self, tau_max: f64) -> bool {
        match self {
            Motion::Steady(r) => r.goes_on(tau_max, false),
            Motion::Spin(s) => s.goes_on(tau_max, false),
        }
    }

    /// One step, sized by the integrator, not by `target`; a spun-up coin riding the table
    /// rides only to `target` (its slip may lie far beyond, and the history up to the screen
    /// needs the ride's closed form).
    pub fn step(&mut self, target: f64) -> Result<(), RunError> {
        match self {
            Motion::Steady(r) => r.step(f64::INFINITY).map(drop),
            Motion::Spin(s) => {
                let to = match s.phase() {
                    Phase::Stuck { .. } => target,
                    Phase::Sliding => f64::INFINITY,
                };
                s.step(to).map(drop)
            }
        }
    }

    /// The run at the end of its integration so far.
    pub fn state(&self) -> State {
        match self {
            Motion::Steady(r) => r.state(),
            Motion::Spin(s) => s
                .state_at(s.tau())
                .unwrap_or_else(|_| self.initial().state()),
        }
    }

    pub fn state_at(&self, tau: f64) -> Result<State, RunError> {
        match self {
            Motion::Steady(r) => r.state_at(tau),
            Motion::Spin(s) => s.state_at(tau),
        }
    }

    /// The table's angle at τ: τ at Ω = 1; Ω0 τ + ½ a τ² spun up.
    pub fn table_angle(&self, tau: f64) -> f64 {
        match self {
            Motion::Steady(_) => tau,
            Motion::Spin(s) => s.ramp().angle(tau),
        }
    }

    /// The table's rate Ω at τ, in units of the reference rate.
    pub fn omega(&self, tau: f64) -> f64 {
        match self {
            Motion::Steady(_) => 1.0,
            Motion::Spin(s) => s.ramp().omega(tau),
        }
    }

    /// The radius inside which friction can hold a coin at rest on the table at τ, where the
    /// grip it needs, ξ √(Ω⁴ + Ω̇²), reaches static friction μ_s/μ_k: μ_s/μ_k on the paper's
    /// table (1, R_max, at μ_s = μ_k), shrinking as a spun-up table speeds up (infinite on a
    /// table not yet turning). None where nothing is held: Stokes drag, or μ = 0.
    pub fn hold_radius(&self, tau: f64) -> Option<f64> {
        let settings = self.settings();
        if crate::engine::closed_form(&self.initial(), settings) {
            return None;
        }
        Some(match self {
            Motion::Steady(_) => settings.hold(),
            Motion::Spin(s) => settings.hold() / s.ramp().grip(1.0, tau),
        })
    }

    /// The release at τ = 0 (a coin at rest on a table turning at Ω0 moves with it).
    pub fn start(&self) -> State {
        let s = self.initial().state();
        State {
            v: s.v + (self.omega(0.0) - 1.0) * zcross(s.r),
            ..s
        }
    }

    /// `s`'s position in `frame`: lab r, or on the table R(−angle) r.
    pub fn in_frame(&self, s: &State, frame: Frame) -> DVec2 {
        match frame {
            Frame::Lab => s.r,
            Frame::Table => rotate(s.r, -self.table_angle(s.tau)),
        }
    }

    /// `s`'s velocity relative to the table, lab components: v − Ω ẑ × r.
    pub fn u_lab(&self, s: &State) -> DVec2 {
        s.v - self.omega(s.tau) * zcross(s.r)
    }

    /// The forces per unit mass on `s` in the table's frame (Sec. II): friction, Coriolis,
    /// centrifugal and, on a table speeding up, the Euler force (zero at constant Ω).
    pub fn forces(&self, s: &State, frictionless: bool) -> [DVec2; 4] {
        match self {
            Motion::Steady(r) => {
                let [fr, co, cf] = coupled_forces(s, frictionless, r.settings().coupling);
                [fr, co, cf, DVec2::ZERO]
            }
            Motion::Spin(run) => {
                let ramp = run.ramp();
                let z = Z {
                    p: s.r,
                    w: s.v,
                    omega: ramp.omega(s.tau),
                };
                z.table_forces(ramp.rate, ramp.angle(s.tau), run.settings().hold())
            }
        }
    }

    /// Whether `s` rides a spun-up table: its velocity is the table's, exactly (the ride's
    /// closed form sets it so). On the paper's table the run's status says when it sticks.
    pub fn riding(&self, s: &State) -> bool {
        matches!(self, Motion::Spin(_)) && self.u_lab(s) == DVec2::ZERO
    }

    /// ξ′ at `s`. On a spun-up table it is r·u/|r| (the table's own velocity is across r), so
    /// a riding coin, whose u is exactly zero, reads exactly 0 and not the rounding of r·v.
    pub fn xi_dot(&self, s: &State) -> f64 {
        let xi = s.xi();
        match self {
            Motion::Spin(_) if xi > 0.0 => s.r.dot(self.u_lab(s)) / xi,
            _ => s.xi_dot(),
        }
    }

    /// `s`'s velocity relative to the table, in the table's frame.
    pub fn u(&self, s: &State) -> DVec2 {
        rotate(self.u_lab(s), -self.table_angle(s.tau))
    }
}
