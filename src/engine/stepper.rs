//! One integrator step and its dense output, for every method: the fixed-step RK2 and RK4,
//! Dormand–Prince 5(4) with PI step control (Hairer, Nørsett & Wanner, *Solving ODEs I*,
//! II.4–II.6 and the DOPRI5 code) and DOP853 (its tableau in `dop853`). [`Stepper`] is the
//! one accept/reject loop; what a run does around its steps (stops, certificates) is in `run`.

use super::dop853;
use super::method::{FixedRk, Scheme};
use super::model::Y;
use serde::Serialize;

/// Work done by a run: what the speed side of the trade costs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Cost {
    pub steps: u64,
    pub rejected: u64,
    pub rhs_evals: u64,
}

/// Continuous extension of one step, for events and for sampling between steps.
#[derive(Clone, Copy, Debug)]
pub enum Dense {
    /// DOPRI5's fourth-order interpolant (Hairer's `contd5` coefficients).
    Dp5([Y; 5]),
    /// DOP853's seventh-order interpolant (Hairer's `contd8` coefficients).
    Dop853([Y; 8]),
    /// Cubic Hermite from the end values and slopes (fixed-step methods).
    Hermite { f0: Y, f1: Y },
}

/// One accepted step, in the integrator's frame, from `t0` to `t0 + h`.
#[derive(Clone, Copy, Debug)]
pub struct Segment {
    pub t0: f64,
    pub h: f64,
    pub y0: Y,
    pub y1: Y,
    pub dense: Dense,
}

impl Segment {
    pub fn t1(&self) -> f64 {
        self.t0 + self.h
    }
    /// The solution at `t` in [t0, t0 + h].
    pub fn at(&self, t: f64) -> Y {
        if self.h <= 0.0 {
            return self.y1;
        }
        let s = ((t - self.t0) / self.h).clamp(0.0, 1.0);
        let s1 = 1.0 - s;
        match self.dense {
            Dense::Dp5(r) => r[0] + (r[1] + (r[2] + (r[3] + r[4] * s1) * s) * s1) * s,
            Dense::Dop853(r) => dop853::at(&r, s),
            Dense::Hermite { f0, f1 } => {
                let (h00, h10) = ((1.0 + 2.0 * s) * s1 * s1, s * s1 * s1);
                let (h01, h11) = (s * s * (3.0 - 2.0 * s), -s * s * s1);
                self.y0 * h00 + f0 * (h10 * self.h) + self.y1 * h01 + f1 * (h11 * self.h)
            }
        }
    }
}

/// A fixed step of `rk` from `y` with slope `f0 = f(y)`; returns the new point.
/// `evals` counts right-hand-side evaluations beyond `f0`.
fn fixed_step(rk: FixedRk, rhs: impl Fn(Y) -> Y, y: Y, f0: Y, h: f64, evals: &mut u64) -> Y {
    match rk {
        FixedRk::Midpoint => {
            *evals += 1;
            y + rhs(y + f0 * (0.5 * h)) * h
        }
        FixedRk::Classic => {
            *evals += 3;
            let k2 = rhs(y + f0 * (0.5 * h));
            let k3 = rhs(y + k2 * (0.5 * h));
            let k4 = rhs(y + k3 * h);
            y + (f0 + (k2 + k3) * 2.0 + k4) * (h / 6.0)
        }
    }
}

// Dormand–Prince 5(4) tableau (Hairer's DOPRI5).
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// The size of `e` in the max norm over the components, each against tol·(1 + |y|) at the
/// larger of its two ends: stricter than Hairer's RMS, which near the saddle ξ ≈ 1 lets the
/// error of one component hide behind the others. The velocity's scale is at most `vel`: a
/// second opinion passes max(|u|, |1 − ξ|, 1e-3), as a stop's time is |u| over a deceleration
/// of at least |1 − ξ|, so near the rim |u| needs its own relative accuracy (`f64::INFINITY`:
/// none).
fn err_norm(y0: Y, y1: Y, e: Y, tol: f64, vel: f64) -> f64 {
    let comp = |a: f64, b: f64, d: f64| (d / (tol + tol * a.abs().max(b.abs()))).abs();
    // Not below what rounding allows w itself (lab frame: v ≈ ẑ×r + u, |v| ~ ξ however small u).
    let wcomp = |a: f64, b: f64, d: f64| {
        let w = a.abs().max(b.abs());
        (d / (tol * (1.0 + w).min(vel.max(10.0 * f64::EPSILON * w / tol)))).abs()
    };
    comp(y0.p.x, y1.p.x, e.p.x)
        .max(comp(y0.p.y, y1.p.y, e.p.y))
        .max(wcomp(y0.w.x, y1.w.x, e.w.x))
        .max(wcomp(y0.w.y, y1.w.y, e.w.y))
}

/// One DOPRI5 trial step: the new point, its slope (FSAL), the scaled error norm and the
/// dense-output coefficients. Six new right-hand-side evaluations.
struct Dp5Trial {
    y1: Y,
    f1: Y,
    err: f64,
    dense: Dense,
}

/// What DOPRI5's stages need of a state: sums and multiples. The point's [`Y`] and the
/// appendix body's six components (`rod`) share one set of stages.
pub(super) trait Linear:
    Copy + std::ops::Add<Output = Self> + std::ops::Mul<f64, Output = Self>
{
}
impl<V: Copy + std::ops::Add<Output = V> + std::ops::Mul<f64, Output = V>> Linear for V {}

/// DOPRI5's stages from `y` with slope `k1` over `h`: the new point, the slopes k1…k7 (k7 at the
/// new point, FSAL) and the embedded error estimate. Six new right-hand-side evaluations.
pub(super) fn dp5_stages<V: Linear>(rhs: impl Fn(V) -> V, y: V, k1: V, h: f64) -> (V, [V; 7], V) {
    let k2 = rhs(y + k1 * (h * A21));
    let k3 = rhs(y + (k1 * A31 + k2 * A32) * h);
    let k4 = rhs(y + (k1 * A41 + k2 * A42 + k3 * A43) * h);
    let k5 = rhs(y + (k1 * A51 + k2 * A52 + k3 * A53 + k4 * A54) * h);
    let k6 = rhs(y + (k1 * A61 + k2 * A62 + k3 * A63 + k4 * A64 + k5 * A65) * h);
    let y1 = y + (k1 * A71 + k3 * A73 + k4 * A74 + k5 * A75 + k6 * A76) * h;
    let k7 = rhs(y1);
    let e = (k1 * E1 + k3 * E3 + k4 * E4 + k5 * E5 + k6 * E6 + k7 * E7) * h;
    (y1, [k1, k2, k3, k4, k5, k6, k7], e)
}

fn dp5_step(rhs: impl Fn(Y) -> Y, y: Y, k1: Y, h: f64, tol: f64, vel: f64) -> Dp5Trial {
    let (y1, [_, _, k3, k4, k5, k6, k7], e) = dp5_stages(rhs, y, k1, h);
    let err = err_norm(y, y1, e, tol, vel);
    let dy = y1 - y;
    let bspl = k1 * h - dy;
    let dense = Dense::Dp5([
        y,
        dy,
        bspl,
        dy - k7 * h - bspl,
        (k1 * D1 + k3 * D3 + k4 * D4 + k5 * D5 + k6 * D6 + k7 * D7) * h,
    ]);
    Dp5Trial {
        y1,
        f1: k7,
        err,
        dense,
    }
}

/// Hairer's starting step (`hinit` of DOPRI5 and DOP853; Hairer, Nørsett & Wanner, Sec. II.4):
/// an Euler probe of size h0 = 0.01·|y|/|f| measures how fast f changes, and the first step is
/// sized so that its error of the method's `order` would be 0.01·tol. One right-hand-side
/// evaluation.
fn initial_step(rhs: impl Fn(Y) -> Y, y: Y, f0: Y, tol: f64, order: i32) -> f64 {
    let norm = |v: Y| err_norm(y, y, v, tol, f64::INFINITY);
    let (d0, d1) = (norm(y), norm(f0));
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let d2 = norm(rhs(y + f0 * h0) - f0) / h0;
    let d = d1.max(d2);
    let h1 = if d <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d).powf(1.0 / f64::from(order))
    };
    (100.0 * h0).min(h1)
}

/// Hairer's step-size controllers, with their codes' defaults (safety 0.9): DOPRI5's PI
/// control (β = 0.04, exponent 1/5 − 0.75β, factor in [0.2, 10]) and DOP853's (β = 0,
/// exponent 1/8, factor in [1/3, 6]), the latter with Gustafsson's predictive step (as in
/// Hairer's RADAU5): closing in on a stop its error grows ~10× per step at equal h, and
/// without the prediction nearly every step was first rejected (11 evaluations lost each).
#[derive(Clone, Copy, Debug)]
struct Controller {
    facold: f64,
    rejected_last: bool,
    beta: f64,
    expo: f64,
    /// Bounds of h/h_new: the largest shrink and the largest growth.
    shrink: f64,
    grow: f64,
    predictive: bool,
    /// The last accepted step and its error (predictive control only).
    last_accepted: Option<(f64, f64)>,
}

impl Controller {
    const SAFE: f64 = 0.9;
    fn dp54() -> Self {
        Controller {
            facold: 1e-4,
            rejected_last: false,
            beta: 0.04,
            expo: 0.2 - 0.04 * 0.75,
            shrink: 5.0,
            grow: 0.1,
            predictive: false,
            last_accepted: None,
        }
    }
    fn dop853() -> Self {
        Controller {
            beta: 0.0,
            expo: 1.0 / 8.0,
            shrink: 1.0 / 0.333,
            grow: 1.0 / 6.0,
            predictive: true,
            ..Controller::dp54()
        }
    }
    /// The next step size after a trial of size `h` with error `err`; `true` if accepted.
    fn next(&mut self, h: f64, err: f64) -> (f64, bool) {
        let fac11 = err.max(1e-300).powf(self.expo);
        if err <= 1.0 {
            let fac =
                (fac11 / self.facold.powf(self.beta) / Self::SAFE).clamp(self.grow, self.shrink);
            let mut hnew = h / fac;
            if let Some((hacc, erracc)) = self.last_accepted {
                // Gustafsson's predictive control: an error growing from step to step
                // (a stop ahead) shrinks the next step before it is rejected.
                let gus = (hacc / h) * (err * err / erracc).powf(self.expo) / Self::SAFE;
                hnew = hnew.min(h / gus.clamp(self.grow, self.shrink));
            }
            if self.predictive {
                self.last_accepted = Some((h, err.max(1e-2)));
            }
            if self.rejected_last {
                hnew = hnew.min(h);
            }
            self.facold = err.max(1e-4);
            self.rejected_last = false;
            (hnew, true)
        } else {
            self.rejected_last = true;
            (h / (fac11 / Self::SAFE).min(self.shrink), false)
        }
    }
}

/// Whether a step of `h` at time `t` is too short to advance t in floating point.
pub fn too_short(h: f64, t: f64) -> bool {
    h < 1e-14 * t.abs().max(1.0)
}

/// Why a step could not be taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepError {
    /// The adaptive step size shrank below what τ can resolve.
    Underflow,
    /// Accepted and rejected steps reached the run's budget.
    Budget,
}

/// The integrator between steps: time, point and its slope (first same as last), and the
/// adaptive method's next step size and controller. Every step and every closed-form stretch ends in a
/// [`Segment`] built here.
#[derive(Clone, Copy, Debug)]
pub struct Stepper {
    pub t: f64,
    pub y: Y,
    pub f: Y,
    /// The adaptive method's next step size (unused by the fixed-step methods).
    h: f64,
    ctrl: Controller,
}

impl Stepper {
    /// At `y` at t = 0: its slope and, for the adaptive methods, Hairer's starting step.
    pub fn new(rhs: impl Fn(Y) -> Y, y: Y, scheme: Scheme, cost: &mut Cost) -> Stepper {
        let f = rhs(y);
        cost.rhs_evals += 1;
        let (h, ctrl) = match scheme {
            Scheme::Dp54 { tol } => {
                cost.rhs_evals += 1;
                (initial_step(&rhs, y, f, tol, 5), Controller::dp54())
            }
            Scheme::Dop853 { tol } => {
                cost.rhs_evals += 1;
                (initial_step(&rhs, y, f, tol, 8), Controller::dop853())
            }
            _ => (0.0, Controller::dp54()),
        };
        Stepper {
            t: 0.0,
            y,
            f,
            h,
            ctrl,
        }
    }

    /// The step `scheme` would take next with nothing ahead.
    pub fn natural_step(&self, scheme: Scheme) -> f64 {
        scheme.fixed().map_or(self.h, |(_, dt)| dt)
    }

    /// One accepted step of at most `cap`, and the adaptive error against its tolerance (≤ 1),
    /// the velocity's error scaled by at most `vel` (see [`err_norm`]).
    /// Rejected tries are counted in `cost`; accepted and rejected together stay below
    /// `max_steps`.
    pub fn step(
        &mut self,
        rhs: impl Fn(Y) -> Y,
        scheme: Scheme,
        cap: f64,
        vel: f64,
        cost: &mut Cost,
        max_steps: u64,
    ) -> Result<(Segment, Option<f64>), StepError> {
        let Some(tol) = scheme.tol() else {
            let (rk, dt) = scheme.fixed().expect("a scheme is adaptive or fixed-step");
            let h = dt.min(cap);
            let y1 = fixed_step(rk, &rhs, self.y, self.f, h, &mut cost.rhs_evals);
            cost.steps += 1;
            return Ok((self.advance(&rhs, h, y1, None, cost), None));
        };
        loop {
            let h = self.h.min(cap);
            if too_short(h, self.t) {
                return Err(StepError::Underflow);
            }
            let trial = Trial::try_step(&rhs, scheme, self.y, self.f, h, (tol, vel), cost);
            let (hnew, accepted) = self.ctrl.next(h, trial.err());
            // A capped step says nothing about how large the next free step may be.
            self.h = if h < self.h && accepted {
                self.h.max(hnew)
            } else {
                hnew
            };
            if accepted {
                cost.steps += 1;
                let err = trial.err();
                return Ok((self.accept(&rhs, h, trial, cost), Some(err)));
            }
            cost.rejected += 1;
            if cost.steps + cost.rejected >= max_steps {
                return Err(StepError::Budget);
            }
        }
    }

    /// Moves to the end of an accepted `trial` of size `h`, with its dense output.
    fn accept(&mut self, rhs: impl Fn(Y) -> Y, h: f64, trial: Trial, cost: &mut Cost) -> Segment {
        let (y1, f1, dense) = trial.finish(rhs, cost);
        let seg = Segment {
            t0: self.t,
            h,
            y0: self.y,
            y1,
            dense,
        };
        (self.t, self.y, self.f) = (seg.t1(), y1, f1);
        seg
    }

    /// One step of exactly `h` through the adaptive scheme's tableau, accepted whatever its
    /// error: what the measured orders of convergence and of the dense output are taken on.
    pub fn forced(&mut self, rhs: impl Fn(Y) -> Y, scheme: Scheme, h: f64) -> Segment {
        let mut cost = Cost::default();
        let tol = scheme.tol().unwrap_or(1.0);
        let trial = Trial::try_step(
            &rhs,
            scheme,
            self.y,
            self.f,
            h,
            (tol, f64::INFINITY),
            &mut cost,
        );
        self.accept(&rhs, h, trial, &mut cost)
    }

    /// Moves to `y1` after `h`, with a cubic Hermite segment between (fixed steps, and the
    /// closed-form stretches of a run's events); `f1` is the slope there if already known.
    pub fn advance(
        &mut self,
        rhs: impl Fn(Y) -> Y,
        h: f64,
        y1: Y,
        f1: Option<Y>,
        cost: &mut Cost,
    ) -> Segment {
        let f1 = f1.unwrap_or_else(|| {
            cost.rhs_evals += 1;
            rhs(y1)
        });
        let seg = Segment {
            t0: self.t,
            h,
            y0: self.y,
            y1,
            dense: Dense::Hermite { f0: self.f, f1 },
        };
        (self.t, self.y, self.f) = (seg.t1(), y1, f1);
        seg
    }
}

/// A trial step of either adaptive method: DOPRI5's is complete, DOP853's dense output waits
/// until the step is accepted (a rejected step does not pay for it).
enum Trial {
    Dp5(Dp5Trial),
    Dop853 { t: dop853::Trial, err: f64 },
}

impl Trial {
    fn try_step(
        rhs: impl Fn(Y) -> Y,
        scheme: Scheme,
        y: Y,
        f: Y,
        h: f64,
        (tol, vel): (f64, f64),
        cost: &mut Cost,
    ) -> Trial {
        if let Scheme::Dop853 { .. } = scheme {
            cost.rhs_evals += 11;
            let t = dop853::trial(rhs, y, f, h);
            let err = dop853::combined_err(
                err_norm(y, t.y1, t.err5, tol, vel),
                err_norm(y, t.y1, t.err3, tol, vel),
            );
            Trial::Dop853 { t, err }
        } else {
            cost.rhs_evals += 6;
            Trial::Dp5(dp5_step(rhs, y, f, h, tol, vel))
        }
    }
    fn err(&self) -> f64 {
        match self {
            Trial::Dp5(t) => t.err,
            Trial::Dop853 { err, .. } => *err,
        }
    }
    /// The end point, its slope and the dense output.
    fn finish(self, rhs: impl Fn(Y) -> Y, cost: &mut Cost) -> (Y, Y, Dense) {
        match self {
            Trial::Dp5(t) => (t.y1, t.f1, t.dense),
            Trial::Dop853 { t, .. } => {
                cost.rhs_evals += 4;
                let (f1, r) = t.dense(rhs);
                (t.y1, f1, Dense::Dop853(r))
            }
        }
    }
}

/// Plain adaptive integration (dp54 or dop853) from `y` over `[0, t_end]`, with no events: for
/// smooth systems such as the frictionless equations ([`super::model::Frame::rhs_free`]).
/// Returns the end point and the number of right-hand-side evaluations, or `None` if the step
/// size underflows.
pub fn adaptive_plain(rhs: impl Fn(Y) -> Y, y: Y, t_end: f64, scheme: Scheme) -> Option<(Y, u64)> {
    let mut cost = Cost::default();
    let mut st = Stepper::new(&rhs, y, scheme, &mut cost);
    while !too_short(t_end - st.t, st.t) {
        st.step(
            &rhs,
            scheme,
            t_end - st.t,
            f64::INFINITY,
            &mut cost,
            u64::MAX,
        )
        .ok()?;
    }
    Some((st.y, cost.rhs_evals))
}
