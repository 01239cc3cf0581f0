//! One run in time, as the explorer shows it: the run advanced tick by tick, a history of
//! samples to step back through, and only the work the scene needs (stuck: closed-form
//! rotation; escaped and out of view: no more steps). The run is the paper's table at
//! constant Ω, or a table spun up where the scene asks ([`Motion`]).

pub mod accuracy;
pub mod doubts;
pub mod ending;
mod motion;
pub mod testing;

pub use motion::Motion;

use crate::engine::doubt::Doubt;
use crate::engine::method::TOL_RANGE;
use crate::engine::run::{Escape, Outcome, Run, RunError, Status, StepInfo};
use crate::engine::spinup::{Ramp, SpinRun};
use crate::engine::stepper::Cost;
use crate::engine::track::Track;
use crate::engine::work::Tally;
use crate::engine::{Initial, Settings, State};
use crate::error::Error;

/// Most samples kept; older ones are dropped first.
pub const HISTORY: usize = 100_000;
/// Most step marks kept.
pub const MAX_MARKS: usize = 2000;
/// Spacing in τ of the trail's points, whatever the speed: the same curve at ×1 and ×256.
pub const TRAIL_DT: f64 = 0.025;
/// Most trail points kept: at this many the path keeps every other one (a [`Track`] on the
/// τ grid, its spacing doubled), so a run of any length costs the same memory.
pub const TRAIL_MAX: usize = 200_000;
/// Most integration steps one tick may take, so a tiny dt at high speed cannot freeze the
/// screen: the sample then lags behind the tick's target time.
pub const STEPS_PER_TICK: u64 = 200_000;

/// What a [`Sim`] has computed: the integrator steps it took and the trail points it
/// evaluated. Ticks and keys are held to bounds on these, not on clocks.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Work {
    pub steps: u64,
    pub points: u64,
}

#[derive(Clone, Debug)]
pub struct Sim {
    /// The run, advanced only here; read through the accessors below.
    run: Motion,
    /// One sample per tick, oldest first: the history stepped through.
    pub samples: Vec<State>,
    /// The path on a τ grid ([`TRAIL_DT`], doubled as often as [`TRAIL_MAX`] needs), from the
    /// run's dense output (closed form once stuck, one turn of the table at most), with the
    /// stop in its place: the trail is drawn from these.
    pub path: Track<State>,
    /// The work friction did up to each point of `path` (−∫|u|dτ, [`Tally`]): the energy
    /// plot's second side, thinned in lockstep with the path (the same offers and events).
    /// NaN on a spun-up table, whose scene shows no energy plot (no tally is kept).
    path_work: Track<f64>,
    tally: Option<Tally>,
    /// End points of the integrator steps taken one at a time ([`Sim::step_once`]).
    pub step_marks: Vec<State>,
    /// Whether the stop is in the path.
    stop_in_path: bool,
    /// Index of the sample on screen.
    pub cursor: usize,
    /// Escaped and past this radius: integration stops.
    pub view_radius: f64,
    /// Why the run stopped early, if it did.
    pub error: Option<RunError>,
    /// The work done for the screen so far, counted.
    pub work: Work,
    /// Once the outcome is decided: whether the run's own error could flip it.
    pub doubt: Option<Doubt>,
}

impl Sim {
    pub fn new(initial: Initial, settings: Settings, view_radius: f64) -> Result<Sim, Error> {
        let run = Run::new(initial, settings)?;
        Ok(Sim::of(
            Some(Tally::new(&run)),
            Motion::Steady(run),
            view_radius,
        ))
    }

    /// A coin at rest on the table at ξ0, the table spun up as `ramp` says.
    pub fn spin(ramp: Ramp, xi0: f64, settings: Settings, view_radius: f64) -> Result<Sim, Error> {
        let run = SpinRun::new(ramp, xi0, settings)?;
        Ok(Sim::of(None, Motion::Spin(run), view_radius))
    }

    fn of(tally: Option<Tally>, run: Motion, view_radius: f64) -> Sim {
        let s0 = run.state();
        Sim {
            tally,
            run,
            samples: vec![s0],
            path: Track::new(s0, TRAIL_MAX),
            path_work: Track::new(0.0, TRAIL_MAX),
            step_marks: Vec::new(),
            stop_in_path: false,
            cursor: 0,
            view_radius,
            error: None,
            work: Work::default(),
            doubt: None,
        }
    }

    /// The run this sim drives.
    pub fn motion(&self) -> &Motion {
        &self.run
    }
    /// The paper's table's run; None on a spun-up table.
    pub fn steady(&self) -> Option<&Run> {
        match &self.run {
            Motion::Steady(r) => Some(r),
            Motion::Spin(_) => None,
        }
    }
    pub fn status(&self) -> Status {
        self.run.status()
    }
    pub fn escape(&self) -> Option<Escape> {
        self.run.escape()
    }
    pub fn settings(&self) -> Settings {
        self.run.settings()
    }
    pub fn initial(&self) -> Initial {
        self.run.initial()
    }
    pub fn cost(&self) -> Cost {
        self.run.cost()
    }
    pub fn last_step(&self) -> Option<StepInfo> {
        self.run.last_step()
    }
    /// How the run ends, as far as it has been integrated (not the sample on screen).
    pub fn outcome(&self) -> Outcome {
        self.run.outcome()
    }

    /// The state on screen.
    pub fn now(&self) -> State {
        self.samples[self.cursor]
    }

    /// The path up to the τ on screen: the visible trail.
    pub fn trail(&self) -> &[State] {
        let tau = self.now().tau;
        let n = self.path.partition_point(|s| s.tau <= tau);
        &self.path[..n.max(1)]
    }

    /// The work done up to each point of [`Sim::trail`].
    pub fn trail_work(&self) -> &[f64] {
        &self.path_work[..self.trail().len()]
    }

    /// Extends the path on its τ grid through the latest step, from its dense output (or the
    /// closed form once stuck, where one turn of the table draws the whole circle), the stop
    /// itself in its place. Only the grid points the path keeps are computed: one μ = 0
    /// stride of 1000 τ spans 40,000.
    fn extend_path(&mut self, tau: f64) {
        let (end, stop) = match self.run.status() {
            Status::Stuck { tau: ts, q } => (tau.min(ts + std::f64::consts::TAU), Some((ts, q))),
            // All the latest step covers: its dense output is gone after the next step.
            Status::Slipping => (self.run.tau(), None),
        };
        if end.is_finite() {
            self.path.reserve_for((end / TRAIL_DT) as u64);
            self.path_work.reserve_for((end / TRAIL_DT) as u64);
        }
        loop {
            let k = self.path.next_index();
            let t = k as f64 * TRAIL_DT;
            if let Some((ts, q)) = stop
                && !self.stop_in_path
                && ts <= end
                && ts <= t
            {
                // (A spun-up coin is stuck for good only at the centre, where this is exact too.)
                self.path.insert(State::riding(q, ts));
                // Nothing slides after the stop: the tally holds there.
                let w = self.work_to(ts).unwrap_or(f64::NAN);
                self.path_work.insert(w);
                self.stop_in_path = true;
            }
            if t > end {
                break;
            }
            match self.run.state_at(t).and_then(|s| Ok((s, self.work_to(t)?))) {
                Ok((s, w)) => {
                    self.path.push_at(k, s);
                    self.path_work.push_at(k, w);
                    self.work.points += 1;
                }
                Err(e) => {
                    self.error = Some(e);
                    return;
                }
            }
        }
        // Through the latest step's end, before the next replaces its dense output (a
        // closed form has one at every τ: its grid points carry the tally).
        if !self.run.closed_form()
            && let Err(e) = self.work_to(self.run.tau())
        {
            self.error = Some(e);
        }
    }

    /// The work friction did up to τ (NaN where no tally is kept: a spun-up table).
    fn work_to(&mut self, tau: f64) -> Result<f64, RunError> {
        match (&mut self.tally, &self.run) {
            (Some(t), Motion::Steady(run)) => t.to(run, tau),
            _ => Ok(f64::NAN),
        }
    }

    pub fn at_latest(&self) -> bool {
        self.cursor + 1 == self.samples.len()
    }

    /// Whether more time can pass: not once escaped and out of view, nor after an error.
    pub fn live(&self) -> bool {
        let s = self.samples[self.samples.len() - 1];
        self.error.is_none() && !(self.run.escape().is_some() && s.xi() > self.view_radius)
    }

    /// The status at the sample on screen.
    pub fn outcome_now(&self) -> Outcome {
        let tau = self.now().tau;
        match (self.run.status(), self.run.escape()) {
            (Status::Stuck { tau: ts, .. }, _) if tau >= ts => Outcome::Stuck,
            (_, Some(e)) if tau >= e.tau => Outcome::Escaped,
            _ => Outcome::Running,
        }
    }

    /// One tick forward by `dtau`: through history if the cursor is behind, else integrate.
    pub fn advance(&mut self, dtau: f64) {
        if !self.at_latest() {
            self.cursor += 1;
            return;
        }
        if !self.live() {
            return;
        }
        let target = self.now().tau + dtau;
        let budget = self.run.cost().steps + self.run.cost().rejected + STEPS_PER_TICK;
        while self.run.goes_on(target) {
            if self.run.cost().steps + self.run.cost().rejected >= budget {
                break;
            }
            self.work.steps += 1;
            if let Err(e) = self.run.step(target) {
                self.error = Some(e);
                break;
            }
            // Each step's dense output covers only that step: take its grid points now
            // (μ = 0 has a closed form at every τ: its points are taken once, below).
            if !self.run.closed_form() {
                self.extend_path(target);
            }
            self.note_outcome();
        }
        let t = target.min(match self.run.status() {
            Status::Stuck { .. } => f64::INFINITY,
            Status::Slipping => self.run.tau(),
        });
        self.extend_path(t);
        match self.run.state_at(t) {
            Ok(s) => self.samples.push(s),
            Err(e) => self.error = Some(e),
        }
        if self.samples.len() > HISTORY {
            self.samples.drain(..HISTORY / 10);
        }
        self.cursor = self.samples.len() - 1;
    }

    /// Exactly one integrator step (after any tries it rejected), shown at its end: the
    /// integrator step mode. Behind the latest sample it steps through history instead.
    /// Returns whether anything moved.
    pub fn step_once(&mut self) -> bool {
        if !self.at_latest() {
            self.cursor += 1;
            return true;
        }
        let tau = self.now().tau;
        let ahead = match self.run.status() {
            Status::Stuck { tau: ts, .. } => ts > tau,
            Status::Slipping => self.run.tau() > tau,
        };
        if ahead {
            // Ticks integrate past the screen, but stop at the first step that reaches their
            // target: the run's latest step holds the τ on screen. Show its end, stepping
            // nothing (re-integrating from τ = 0 took seconds on a long run).
        } else if !self.live() || !self.run.goes_on(f64::INFINITY) {
            return false;
        } else {
            self.work.steps += 1;
            if let Err(e) = self.run.step(f64::INFINITY) {
                self.error = Some(e);
                return false;
            }
        }
        self.note_outcome();
        self.extend_path(self.run.tau());
        let s = self.run.state();
        if s.tau <= tau {
            return false;
        }
        self.samples.push(s);
        if self.samples.len() > HISTORY {
            self.samples.drain(..HISTORY / 10);
        }
        self.cursor = self.samples.len() - 1;
        self.step_marks.push(s);
        if self.step_marks.len() > MAX_MARKS {
            self.step_marks.drain(..MAX_MARKS / 10);
        }
        true
    }

    /// Once the outcome is decided: whether the run's own error could flip it (once per run,
    /// right after the step that decided it, while its dense output still covers the
    /// certificate; within one tick's budget, the shadow's).
    fn note_outcome(&mut self) {
        if let Motion::Steady(run) = &self.run
            && self.doubt.is_none()
            && run.outcome() != Outcome::Running
        {
            // Every session holding this run asks: one computes it (see `doubts`).
            self.doubt = Some(doubts::DOUBTS.of(run, f64::INFINITY));
        }
    }

    /// Brings this run to `tau` if it lags behind, within one tick's step budget (another
    /// run on screen sets the pace). Returns whether it moved.
    pub fn catch_up_to(&mut self, tau: f64) -> bool {
        let before = (self.cursor, self.samples.len());
        if self.now().tau < tau {
            self.advance(tau - self.now().tau);
        }
        before != (self.cursor, self.samples.len())
    }
}

/// How far the state on screen is from a shadow run at a tighter setting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorEstimate {
    pub tau: f64,
    /// |Δr| in the lab frame.
    pub error: f64,
    /// The shadow run's tolerance (dp54) and its cost.
    pub tol: f64,
    pub rhs_evals: u64,
}

impl Sim {
    /// An error estimate for the state on screen, from a shadow run with dp54 at a tolerance
    /// 1000× tighter than the run's own (at most 1e-13). Computed only when asked.
    pub fn error_estimate(&self) -> Result<ErrorEstimate, Error> {
        let own = self.run.settings().scheme.tol().unwrap_or(1e-10);
        let tol = (own * 1e-3).clamp(TOL_RANGE.0, 1e-13);
        let now = self.now();
        // Within one tick's budget, so the key never waits long.
        let settings = Settings {
            max_steps: STEPS_PER_TICK,
            coupling: self.run.settings().coupling,
            ..Settings::dp54(tol)
        };
        let (at, rhs_evals) = match &self.run {
            Motion::Steady(run) => {
                let mut shadow = Run::new(run.initial(), settings)?;
                shadow.run(now.tau, false)?;
                (shadow.state_at(now.tau)?, shadow.cost().rhs_evals)
            }
            Motion::Spin(run) => {
                let mut shadow = SpinRun::new(run.ramp(), run.xi0(), settings)?;
                shadow.run(now.tau, false)?;
                (shadow.state_at(now.tau)?, shadow.cost().rhs_evals)
            }
        };
        Ok(ErrorEstimate {
            tau: now.tau,
            error: (at.r - now.r).length(),
            tol,
            rhs_evals,
        })
    }
}
