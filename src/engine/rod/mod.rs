//! The appendix's body integrated (extends the paper, whose Appendix only estimates it): two
//! masses m/2 at q ± (L/2) ê(ψ), joined by a massless rigid rod that carries an axial force only,
//! each with Coulomb friction μ_k m g/2 against its own slip velocity. Rotating frame, units of
//! the paper's Eqs. (6)–(7) (μ_k g = 1, Ω = 1), per unit total mass m:
//!
//! - sliding: q′ = u, u′ = −2 ẑ × u + q − ½(û₁ + û₂), ψ″ = −(ê × û₁ − ê × û₂)/L, with the
//!   contacts' slips u_i = u ± (L/2) ψ′ ê⊥ (Coriolis and centrifugal forces have no torque
//!   about the centre of a two-mass rod; I = mL²/4);
//! - one contact stuck at a (it holds while the friction it needs, |N ê − ½a| with the rod's
//!   axial force N, is ≤ ½ μ_s/μ_k): the other pivots about it, ψ″ = −(s a·ê⊥ + sgn ψ′)/L;
//! - both stuck: the body rides the table iff some axial force keeps both within their cones,
//!   which works out to |q| ≤ μ_s/μ_k, the point's condition (Sec. II, property 1);
//! - a contact breaking loose slips along the one direction its slip can grow in
//!   (`breakaway`), taken as its friction's direction until its slip passes the stop floor.
//!
//! The Jacobi energy E = ½|u|² + (L²/8) ψ′² − ½|q|² falls at ½(|u₁| + |u₂|), so E < −½R²
//! (R = μ_s/μ_k) certifies that the body never rests. As L → 0 it is the point.

//!
//! The body is stepped by the point's integrator (`stepper`: DOPRI5, its controller and dense
//! output), its events (a contact's stop, a pivot's end, the escape certificate) located on
//! the dense output by Illinois (`roots`), as the point's are.

use super::body::Body;
use super::error::Error;
use super::method::Scheme;
use super::model::{Initial, Release};
use super::roots::illinois;
use super::run::{Outcome, Run, RunError};
use super::stepper::{Cost, Segment, StepError, Stepper, too_short};
use contact::{Friction, rhs};
use glam::DVec2;

mod contact;
mod events;
mod state;
mod track;

pub use state::{Phase, RodState};
use state::{S, V, axis};
pub use track::{Cut, RodTrack, TRACK_STATES, TRACK_STEPS};

/// A run of the body: its state, phase and cost.
#[derive(Clone, Debug)]
pub struct RodRun {
    pub l: f64,
    /// μ_s/μ_k.
    pub hold: f64,
    pub tol: f64,
    pub state: RodState,
    pub phase: Phase,
    fallback: [DVec2; 2],
    /// Contacts breaking loose (see [`Friction::dir`]).
    breaking: [bool; 2],
    /// Both contacts loose from rest: from then on the body slides as the point does (see
    /// [`RodRun::both_loose`]), and the point's own run carries it.
    translation: Option<Box<Translation>>,
    /// The shared integrator, at `state` (re-placed on the pivot's circle after each step).
    stepper: Stepper<V>,
    /// Whether the stepper's slope at its point was taken under other friction than holds now
    /// (an event since): it is taken again before the next step.
    stale: bool,
    /// Steps (accepted, rejected; a step of the point's run that carries the body counts as
    /// one) and right-hand-side evaluations, event location's and the carrying run's included.
    cost: Cost,
    /// Steps the run may take, accepted and rejected (see [`RodRun::within`]).
    max_steps: u64,
    /// Past the escape certificate, the body is stepped on while its centre is within this
    /// radius (see [`RodRun::following`]); None: a run stops at the certificate.
    follow_to: Option<f64>,
    /// τ at which a step first found the certificate, E < −½R².
    certified: Option<f64>,
}

/// The point's run that carries a body sliding without turning: released at rest on the table
/// where the body's centre was at `tau0`, on +x, so the body's table frame is its own turned
/// by `turn`.
#[derive(Clone, Debug)]
struct Translation {
    run: Run,
    turn: f64,
    tau0: f64,
}

/// A contact's slip below 10⁻²√tol (relative to 1 + |u|) has stopped: the steps that approach
/// a zero of |u_i| shrink with it, and below about 1e-11 their stages straddle the zero and
/// stall. Snapping at |u_i| moves the rest point by about |u_i|²/2, ≤ 10⁻⁴ tol.
const STOP_SCALE: f64 = 1e-2;

/// …and a slip below 100 tol has stopped too: with steps of about tol, the stages' friction
/// flips within a step and DOPRI5 has a spurious fixed point where the body creeps at a slip of
/// about tol, every step accepted (at tol 1e-6, 700 000 steps at |u| = 1.03e-5 against a floor
/// of 1.00e-5). This bound only bites above tol = 1e-8; the rest point then moves by ~10⁴ tol².
const CHATTER: f64 = 100.0;

/// …but never above 10⁻³ (tol ≥ 1e-5): a floor of 100 tol would stop every slip at once at
/// tol 1e-2. There a loose run may creep at its chatter, and says so by not resting.
const MAX_FLOOR: f64 = 1e-3;

/// Steps a run may take unless told otherwise ([`RodRun::within`]).
pub const MAX_STEPS: u64 = 5_000_000;

/// The slip below which a contact has stopped, at `tol` for a centre moving at `u`.
fn floor(tol: f64, u: DVec2) -> f64 {
    (STOP_SCALE * tol.sqrt()).max((CHATTER * tol).min(MAX_FLOOR)) * (1.0 + u.length())
}

impl RodRun {
    /// The body released as `initial` says, the rod at `body.angle`. A thrown body or one at
    /// rest in the lab does not spin in the lab (ψ′ = −1, the appendix's case); one at rest on
    /// the table rides with it (ψ′ = 0).
    pub fn new(body: Body, hold: f64, initial: &Initial, tol: f64) -> Result<RodRun, Error> {
        body.validate()?;
        initial.validate()?;
        if initial.frictionless {
            return Err(Error::refused(
                "a body with mu = 0 feels no friction: its centre is the point's straight line",
            ));
        }
        let (l, q) = (body.length, DVec2::new(initial.xi0, 0.0));
        let w = if initial.release == Release::TableRest {
            0.0
        } else {
            -1.0
        };
        let state = RodState {
            tau: 0.0,
            q,
            u: initial.u0(),
            psi: body.angle,
            w,
        };
        let friction = Friction {
            fallback: state.contacts(l),
            breaking: [false; 2],
            floor: floor(tol, state.u),
        };
        let mut cost = Cost::default();
        let stepper = Stepper::new(
            |y| rhs(l, Phase::Slip, &friction, y),
            state.y(),
            Scheme::Dp54 { tol },
            &mut cost,
        );
        let mut run = RodRun {
            l,
            hold,
            tol,
            state,
            phase: Phase::Slip,
            fallback: friction.fallback,
            breaking: friction.breaking,
            translation: None,
            stepper,
            stale: false,
            cost,
            max_steps: MAX_STEPS,
            follow_to: None,
            certified: None,
        };
        if state.u == DVec2::ZERO && w == 0.0 {
            if q.length() <= hold {
                run.phase = Phase::Rest;
            } else {
                run.both_loose();
            }
        }
        Ok(run)
    }

    /// The run followed past its escape certificate while its centre is within `radius` (the
    /// explorer draws the body leaving, as it follows the point out to its view radius): its
    /// steps go on as before, and [`RodRun::step`] says `Escaped` once |q| ≥ `radius` (at once
    /// where it already is), `Running` before. The physics is the same; only where it stops.
    pub fn following(mut self, radius: f64) -> RodRun {
        self.follow_to = Some(radius);
        self
    }

    /// The run within `max_steps` steps, accepted and rejected (a point's run's budget,
    /// `Settings::max_steps`): past it [`RodRun::step`] fails with [`RunError::Budget`], as the
    /// point's run does.
    pub fn within(mut self, max_steps: u64) -> RodRun {
        self.max_steps = max_steps;
        self
    }

    /// τ at which a step first found the escape certificate (E < −½R²), once one has: where a
    /// run that is not followed stops, and the escape's τ of one that is.
    pub fn certificate(&self) -> Option<f64> {
        self.certified
    }

    /// The slip below which a contact has stopped.
    fn floor(&self) -> f64 {
        floor(self.tol, self.state.u)
    }

    /// Whether E < −½R² already certifies that the body never rests.
    fn escaped(&self) -> bool {
        self.state.energy(self.l) < -0.5 * self.hold * self.hold
    }

    /// Right-hand-side evaluations so far (six a DOPRI5 step, as the point's).
    pub fn rhs_evals(&self) -> u64 {
        self.cost.rhs_evals
    }

    /// Steps taken so far, accepted and rejected.
    pub fn steps(&self) -> u64 {
        self.cost.steps + self.cost.rejected
    }

    /// The friction the sliding phase feels from the current state on.
    fn friction(&self) -> Friction {
        Friction {
            fallback: self.fallback,
            breaking: self.breaking,
            floor: self.floor(),
        }
    }

    /// The state `y` at `tau`, re-placed on the pivot's circle when pivoting (the stuck contact
    /// exactly at its anchor).
    fn place(&self, tau: f64, y: V) -> RodState {
        let mut s = RodState::from(tau, y);
        if let Phase::Pivot { i, anchor, .. } = self.phase {
            let ep = axis(s.psi).perp();
            s.q = anchor - axis(s.psi) * (S[i] * 0.5 * self.l);
            s.u = -ep * (S[i] * 0.5 * self.l * s.w);
        }
        s
    }

    /// The stepper moved to `state` (after an event changed it): its slope is taken again
    /// before the next step.
    fn sync(&mut self) {
        self.stepper.t = self.state.tau;
        self.stepper.y = self.state.y();
        self.stale = true;
    }

    /// Event functions of the phase at `s`, each positive until its event: a sliding
    /// contact's slip along its slip at the step's start; a pivot's rate along its start, and
    /// the stuck contact's cone margin.
    fn events(&self, s: &RodState) -> [f64; 2] {
        match self.phase {
            Phase::Slip => {
                let (a, b) = (self.state.slips(self.l), s.slips(self.l));
                [a[0].dot(b[0]), a[1].dot(b[1])]
            }
            Phase::Pivot { i, anchor, .. } => [
                self.state.w * s.w,
                0.5 * self.hold - contact::pivot_need(self.l, i, anchor, s.psi, s.w).length(),
            ],
            Phase::Rest => [1.0, 1.0],
        }
    }

    /// Advances by one accepted step, or to the first event inside it; returns how the run
    /// stands then.
    pub fn step(&mut self, tau_max: f64) -> Result<Outcome, RunError> {
        if self.phase == Phase::Rest {
            return Ok(Outcome::Stuck);
        }
        if self.certified.is_some() || self.escaped() {
            self.certified.get_or_insert(self.state.tau);
            // Followed, the certified body goes on until its centre reaches the radius.
            if !self.follow_to.is_some_and(|r| self.state.q.length() < r) {
                return Ok(Outcome::Escaped);
            }
        }
        if self.state.tau >= tau_max {
            return Ok(Outcome::Running);
        }
        if self.steps() >= self.max_steps {
            return Err(RunError::Budget {
                steps: self.max_steps,
                tau: self.state.tau,
            });
        }
        if self.translation.is_some() {
            return self.translate(tau_max);
        }
        // A slip that has shrunk to roundoff is a stop: the approach to a zero of |u_i| takes
        // steps in proportion to |u_i| (the friction's direction turns ever faster).
        if self.phase == Phase::Slip {
            let slips = self.state.slips(self.l).map(|v| v.length());
            let floor = self.floor();
            if let Some(k) = (0..2)
                .filter(|&k| slips[k] > 0.0 && slips[k] <= floor)
                .min_by(|&a, &b| slips[a].total_cmp(&slips[b]))
            {
                self.event(k);
                self.sync();
                if self.phase != Phase::Slip {
                    return Ok(self.standing());
                }
            }
        }
        let cap = tau_max - self.state.tau;
        if too_short(cap, self.state.tau) {
            // τ-max to within rounding: no step could be that short.
            self.state.tau = tau_max;
            self.stepper.t = tau_max;
            return Ok(self.standing());
        }
        self.stride(cap)?;
        Ok(self.standing())
    }

    /// One step of the shared stepper of at most `cap`, or to the first event inside it.
    fn stride(&mut self, cap: f64) -> Result<(), RunError> {
        // Events already at zero at the start (a contact just loose) are not watched.
        let live = self.events(&self.state).map(|g| g > 0.0);
        let (l, phase, friction) = (self.l, self.phase, self.friction());
        let f = |y| rhs(l, phase, &friction, y);
        // Friction still breaking loose depends on the floor at the step's start, which
        // moves with |u|: its slope is taken afresh, as after an event.
        if self.stale || self.breaking.contains(&true) {
            self.stepper.f = f(self.stepper.y);
            self.cost.rhs_evals += 1;
            self.stale = false;
        }
        let (start, tau, scheme) = (self.stepper, self.state.tau, Scheme::Dp54 { tol: self.tol });
        let (seg, _) = self
            .stepper
            .step(
                &f,
                scheme,
                cap,
                f64::INFINITY,
                &mut self.cost,
                self.max_steps,
            )
            .map_err(|e| match e {
                StepError::Underflow => RunError::StepUnderflow { tau },
                StepError::Budget => RunError::Budget {
                    steps: self.max_steps,
                    tau,
                },
            })?;
        let end = self.place(seg.t1(), seg.y1);
        let g = self.events(&end);
        let hit = (0..2)
            .filter(|&k| live[k] && g[k] <= 0.0)
            .map(|k| (k, self.locate(k, &seg)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match hit {
            None => {
                let floor = self.floor();
                for (b, u) in self.breaking.iter_mut().zip(end.slips(self.l)) {
                    *b &= u.length() <= floor;
                }
                self.locate_certificate(&seg, &end);
                self.state = end;
                self.stepper.y = end.y();
            }
            Some((k, at)) => {
                // Taken again from the step's start to the event: a full step, not the dense
                // output, so the state there is as accurate as a step end.
                let to = self
                    .stepper
                    .retake(&f, scheme, &start, at - seg.t0, &mut self.cost);
                self.state = self.place(to.t1(), to.y1);
                self.event(k);
                self.sync();
            }
        }
        Ok(())
    }

    fn standing(&self) -> Outcome {
        if self.phase == Phase::Rest {
            Outcome::Stuck
        } else {
            Outcome::Running
        }
    }

    /// The body at `t` inside the step `seg`, on its dense output.
    fn dense(&self, seg: &Segment<V>, t: f64) -> RodState {
        self.place(t, seg.at(t))
    }

    /// Where in the step `seg` to `end` the escape certificate E < −½R² first holds, if it
    /// first holds there: located by Illinois on the dense output, as the point's run locates
    /// its certificates (Sec. II, property 2, with the body's energy).
    fn locate_certificate(&mut self, seg: &Segment<V>, end: &RodState) {
        let margin = |s: &RodState| -0.5 * self.hold * self.hold - s.energy(self.l);
        if self.certified.is_some() || self.escaped() || margin(end) <= 0.0 {
            return;
        }
        let at = illinois(|t| margin(&self.dense(seg, t)), seg.t0, seg.t1(), 1e-14);
        self.certified = Some(at);
    }

    /// Where in the step `seg` event `k` first passes zero: Illinois on the dense output.
    fn locate(&self, k: usize, seg: &Segment<V>) -> f64 {
        illinois(
            |t| -self.events(&self.dense(seg, t))[k],
            seg.t0,
            seg.t1(),
            1e-14,
        )
    }
}
