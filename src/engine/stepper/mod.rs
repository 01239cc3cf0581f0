//! One integrator step and its dense output, for every method: the fixed-step RK2 and RK4,
//! Dormand–Prince 5(4) with PI step control (Hairer, Nørsett & Wanner, *Solving ODEs I*,
//! II.4–II.6 and the DOPRI5 code) and DOP853 (its tableau in `dop853`). [`Stepper`] is the
//! one accept/reject loop; what a run does around its steps (stops, certificates) is in `run`.

use super::dop853;
use super::method::{FixedRk, Scheme};
use super::model::Y;
use control::{Controller, initial_step};
use dp5::{Dp5Trial, dp5_step};
use serde::Serialize;
use std::ops::{Add, Mul, Sub};

mod control;
mod dp5;

/// What a stepper's state needs: sums, differences and multiples for the stages, and a size
/// for error control. The point's [`Y`] and the appendix body's state (`rod`) are stepped by
/// the same code.
pub trait Vector:
    Copy + Default + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self>
{
    /// The error `e` of a step from `y0` to `y1` against `tol` (≤ 1: accept); `vel` bounds the
    /// velocity's scale where the state has one (`f64::INFINITY`: no bound).
    fn err_norm(y0: Self, y1: Self, e: Self, tol: f64, vel: f64) -> f64;
}

/// Work done by a run: what the speed side of the trade costs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Cost {
    pub steps: u64,
    pub rejected: u64,
    pub rhs_evals: u64,
}

/// Continuous extension of one step, for events and for sampling between steps.
#[derive(Clone, Copy, Debug)]
pub enum Dense<V = Y> {
    /// DOPRI5's fourth-order interpolant (Hairer's `contd5` coefficients).
    Dp5([V; 5]),
    /// DOP853's seventh-order interpolant (Hairer's `contd8` coefficients).
    Dop853([V; 8]),
    /// Cubic Hermite from the end values and slopes (fixed-step methods, closed-form stretches,
    /// and the steps of a stepper that keeps only their ends, [`Stepper::ends_only`]).
    Hermite { f0: V, f1: V },
    /// Quintic Hermite through the ends and the midpoint, with their slopes: the implicit
    /// steps', whose error pair gives the midpoint. Order 6 like the step itself; their cubic
    /// was 50× further off than the step at tol 1e-12 (5e-11 in the work of a 1e-2 step).
    Hermite5 { f0: V, ym: V, fm: V, f1: V },
}

/// One accepted step, in the integrator's frame, from `t0` to `t0 + h`.
#[derive(Clone, Copy, Debug)]
pub struct Segment<V = Y> {
    pub t0: f64,
    pub h: f64,
    pub y0: V,
    pub y1: V,
    pub dense: Dense<V>,
}

impl<V: Vector> Segment<V> {
    pub fn t1(&self) -> f64 {
        self.t0 + self.h
    }
    /// The solution at `t` in [t0, t0 + h].
    pub fn at(&self, t: f64) -> V {
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
            Dense::Hermite5 { f0, ym, fm, f1 } => {
                // Newton's form on the nodes 0, 0, ½, ½, 1, 1 (divided differences).
                let (d0, dm, d1) = (f0 * self.h, fm * self.h, f1 * self.h);
                let (a, b) = ((ym - self.y0) * 2.0, (self.y1 - ym) * 2.0);
                let (c02, c13, c24, c35) = (
                    (a - d0) * 2.0,
                    (dm - a) * 2.0,
                    (b - dm) * 2.0,
                    (d1 - b) * 2.0,
                );
                let (c03, c14, c25) = ((c13 - c02) * 2.0, c24 - c13, (c35 - c24) * 2.0);
                let (c04, c15) = (c14 - c03, c25 - c14);
                let c05 = c15 - c04;
                let sm = s - 0.5;
                self.y0 + (d0 + (c02 + (c03 + (c04 + c05 * (s - 1.0)) * sm) * sm) * s) * s
            }
        }
    }
}

/// A fixed step of `rk` from `y` with slope `f0 = f(y)`; returns the new point.
/// `evals` counts right-hand-side evaluations beyond `f0`.
fn fixed_step<V: Vector>(
    rk: FixedRk,
    rhs: impl Fn(V) -> V,
    y: V,
    f0: V,
    h: f64,
    evals: &mut u64,
) -> V {
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

/// The size of `e` in the max norm over the components, each against tol·(1 + |y|) at the
/// larger of its two ends: stricter than Hairer's RMS, which near the saddle ξ ≈ 1 lets the
/// error of one component hide behind the others. The velocity's scale is at most `vel`: a
/// second opinion passes max(|u|, |1 − ξ|, 1e-3), as a stop's time is |u| over a deceleration
/// of at least |1 − ξ|, so near the rim |u| needs its own relative accuracy (`f64::INFINITY`:
/// none).
impl Vector for Y {
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
pub struct Stepper<V = Y> {
    pub t: f64,
    pub y: V,
    pub f: V,
    /// The adaptive method's next step size (unused by the fixed-step methods).
    h: f64,
    ctrl: Controller,
    /// Whether an accepted step pays for DOP853's dense output (three more evaluations): not
    /// where only the step's ends are read ([`Stepper::ends_only`]).
    dense: bool,
}

impl<V: Vector> Stepper<V> {
    /// At `y` at t = 0: its slope and, for the adaptive methods, Hairer's starting step.
    pub fn new(rhs: impl Fn(V) -> V, y: V, scheme: Scheme, cost: &mut Cost) -> Stepper<V> {
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
            dense: true,
        }
    }

    /// This stepper with its accepted steps carrying only a cubic Hermite interpolant of their
    /// ends, for a run that reads no state inside a step but where it retakes one
    /// ([`Stepper::retake`]): DOP853's dense output is three of its fifteen evaluations a step.
    pub fn ends_only(self) -> Stepper<V> {
        Stepper {
            dense: false,
            ..self
        }
    }

    /// The step `scheme` would take next with nothing ahead.
    pub fn natural_step(&self, scheme: Scheme) -> f64 {
        scheme.fixed().map_or(self.h, |(_, dt)| dt)
    }

    /// One accepted step of at most `cap`, and the adaptive error against its tolerance (≤ 1),
    /// the velocity's error scaled by at most `vel` (see `err_norm`).
    /// Rejected tries are counted in `cost`; accepted and rejected together stay below
    /// `max_steps`.
    pub fn step(
        &mut self,
        rhs: impl Fn(V) -> V,
        scheme: Scheme,
        cap: f64,
        vel: f64,
        cost: &mut Cost,
        max_steps: u64,
    ) -> Result<(Segment<V>, Option<f64>), StepError> {
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
    fn accept(
        &mut self,
        rhs: impl Fn(V) -> V,
        h: f64,
        trial: Trial<V>,
        cost: &mut Cost,
    ) -> Segment<V> {
        let (y1, f1, dense) = trial.finish(rhs, cost, self.dense);
        let seg = Segment {
            t0: self.t,
            h,
            y0: self.y,
            y1,
            dense: dense.unwrap_or(Dense::Hermite { f0: self.f, f1 }),
        };
        (self.t, self.y, self.f) = (seg.t1(), y1, f1);
        seg
    }

    /// The step from `start` (this stepper before its latest step) taken again, of exactly
    /// `h`: to an event located inside that step on its dense output, landed on by a full
    /// step. The step size and controller stay this stepper's (its step was accepted).
    pub fn retake(
        &mut self,
        rhs: impl Fn(V) -> V,
        scheme: Scheme,
        start: &Stepper<V>,
        h: f64,
        cost: &mut Cost,
    ) -> Segment<V> {
        (self.t, self.y, self.f) = (start.t, start.y, start.f);
        let tol = scheme.tol().unwrap_or(1.0);
        let trial = Trial::try_step(&rhs, scheme, self.y, self.f, h, (tol, f64::INFINITY), cost);
        let dense = std::mem::replace(&mut self.dense, true);
        let seg = self.accept(&rhs, h, trial, cost);
        self.dense = dense;
        seg
    }

    /// Moves to `y1` after `h`, with a cubic Hermite segment between (fixed steps, and the
    /// closed-form stretches of a run's events); `f1` is the slope there if already known.
    pub fn advance(
        &mut self,
        rhs: impl Fn(V) -> V,
        h: f64,
        y1: V,
        f1: Option<V>,
        cost: &mut Cost,
    ) -> Segment<V> {
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

    /// [`Stepper::advance`] with a quintic segment through `ym`, the point at `h/2` too (an
    /// implicit step's).
    pub fn advance_through(
        &mut self,
        rhs: impl Fn(V) -> V,
        h: f64,
        ym: V,
        y1: V,
        cost: &mut Cost,
    ) -> Segment<V> {
        cost.rhs_evals += 1;
        let fm = rhs(ym);
        let mut seg = self.advance(&rhs, h, y1, None, cost);
        if let Dense::Hermite { f0, f1 } = seg.dense {
            seg.dense = Dense::Hermite5 { f0, ym, fm, f1 };
        }
        seg
    }
}

/// A trial step of either adaptive method: DOPRI5's is complete, DOP853's dense output waits
/// until the step is accepted (a rejected step does not pay for it).
enum Trial<V> {
    Dp5(Dp5Trial<V>),
    Dop853 { t: dop853::Trial<V>, err: f64 },
}

impl<V: Vector> Trial<V> {
    fn try_step(
        rhs: impl Fn(V) -> V,
        scheme: Scheme,
        y: V,
        f: V,
        h: f64,
        (tol, vel): (f64, f64),
        cost: &mut Cost,
    ) -> Trial<V> {
        if let Scheme::Dop853 { .. } = scheme {
            cost.rhs_evals += 11;
            let t = dop853::trial(rhs, y, f, h);
            let err = dop853::combined_err(
                V::err_norm(y, t.y1, t.err5, tol, vel),
                V::err_norm(y, t.y1, t.err3, tol, vel),
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
    /// The end point, its slope and the dense output (DOP853's only if `dense`).
    fn finish(
        self,
        rhs: impl Fn(V) -> V,
        cost: &mut Cost,
        dense: bool,
    ) -> (V, V, Option<Dense<V>>) {
        match self {
            Trial::Dp5(t) => (t.y1, t.f1, Some(t.dense)),
            Trial::Dop853 { t, .. } if dense => {
                cost.rhs_evals += 4;
                let (f1, r) = t.dense(rhs);
                (t.y1, f1, Some(Dense::Dop853(r)))
            }
            Trial::Dop853 { t, .. } => {
                cost.rhs_evals += 1;
                (t.y1, rhs(t.y1), None)
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    /// The implicit steps' quintic is exact on any polynomial of degree 5 (its four components
    /// four of them, on a step not starting at 0), and only that: one of degree 6 misses.
    #[test]
    fn the_quintic_through_the_midpoint_is_exact_to_degree_five() {
        let (t0, h) = (0.7, 0.3);
        let poly = |c: &[f64], t: f64| c.iter().rev().fold(0.0, |a, &k| a * t + k);
        let slope = |c: &[f64], t: f64| {
            let d: Vec<f64> = c
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, &k)| i as f64 * k)
                .collect();
            poly(&d, t)
        };
        let coeffs = [
            vec![1.0, -2.0, 0.5, 3.0, -1.0, 2.0],
            vec![0.0, 1.0, 0.0, 0.0, 0.0, -4.0],
            vec![-0.3, 0.2, 0.1, 0.0, 5.0, 1.0],
            vec![2.0, 0.0, -1.0, 1.0, 0.0, 0.5],
        ];
        let at = |f: &dyn Fn(&[f64], f64) -> f64, t: f64| Y {
            p: DVec2::new(f(&coeffs[0], t), f(&coeffs[1], t)),
            w: DVec2::new(f(&coeffs[2], t), f(&coeffs[3], t)),
        };
        let seg = Segment {
            t0,
            h,
            y0: at(&poly, t0),
            y1: at(&poly, t0 + h),
            dense: Dense::Hermite5 {
                f0: at(&slope, t0),
                ym: at(&poly, t0 + 0.5 * h),
                fm: at(&slope, t0 + 0.5 * h),
                f1: at(&slope, t0 + h),
            },
        };
        for s in [0.0, 0.1, 0.37, 0.5, 0.81, 1.0] {
            let (t, got) = (t0 + s * h, seg.at(t0 + s * h));
            let want = at(&poly, t);
            assert!(
                (got.p - want.p).length() + (got.w - want.w).length() < 1e-13,
                "s {s}"
            );
        }
        // t⁶ (slope 6t⁵) is not reproduced: the check above can fail.
        let six = Segment {
            dense: Dense::Hermite5 {
                f0: Y {
                    p: DVec2::new(6.0 * t0.powi(5), 0.0),
                    w: DVec2::ZERO,
                },
                ym: Y {
                    p: DVec2::new((t0 + 0.5 * h).powi(6), 0.0),
                    w: DVec2::ZERO,
                },
                fm: Y {
                    p: DVec2::new(6.0 * (t0 + 0.5 * h).powi(5), 0.0),
                    w: DVec2::ZERO,
                },
                f1: Y {
                    p: DVec2::new(6.0 * (t0 + h).powi(5), 0.0),
                    w: DVec2::ZERO,
                },
            },
            y0: Y {
                p: DVec2::new(t0.powi(6), 0.0),
                w: DVec2::ZERO,
            },
            y1: Y {
                p: DVec2::new((t0 + h).powi(6), 0.0),
                w: DVec2::ZERO,
            },
            ..seg
        };
        let t = t0 + 0.25 * h;
        assert!((six.at(t).p.x - t.powi(6)).abs() > 1e-8);
    }
}
