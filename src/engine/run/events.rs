//! The events of a run, located inside the step: the stop ahead (Sec. II, property 1) taken
//! in closed form or approached in shrinking steps, the jump to it, and where the escape
//! certificate first holds (property 2).

use super::outcome::{Certificate, Escape, Status, certificate, certificate_margin};
use super::{Ahead, Limit, Run, RunError, SNAP_T, STIFF, STOP_CAP, StepInfo};
use crate::model::{Frame, State, Y, rotate, zcross};
use crate::radau;
use crate::roots::illinois;
use crate::stepper::{Segment, Stepper, too_short};
use glam::DVec2;

/// The share of the time to the stop ahead that a second opinion's explicit step, held to its
/// stability limit, must still cover (else it goes implicit). With implicit steps that reach
/// [`REACH`] of the way, on the bench's forty stops at the rim and its 100 rest cases the
/// check took 1.48× and 1.08× the runs' RHS evaluations at 0.1, 1.01× and 1.04× at 0.2,
/// 0.99× and 1.01× at 0.35, and 0.99× and 0.98× with none held; but implicit evaluations cost
/// several explicit ones, and at 0.35 the time was 0.96× and 0.89× (1.12× on the quick
/// bench's 15 cases).
const CLOSE_IN: f64 = 0.35;
/// The share of the time to the stop ahead that a second opinion's implicit step may cover
/// ([`Run::implicit_cap`]): on the forty stops at the rim 0.7 (the run's) took 890 implicit
/// steps, 0.9 614, 0.97 509, 0.99 469.
const REACH: f64 = 0.97;

impl Run {
    /// Looks ahead for a stop. d|u|/dτ = q·û − 1 (Coriolis does no work), so a stop is
    /// ≈ |u|/(1 − q·û) ahead: steps are capped to a fraction of that, so that the stop is
    /// approached in steps that shrink geometrically and never stepped through, and a stop
    /// closer than the time tolerance is taken in closed form ([`Run::snaps`]).
    pub(super) fn stop_ahead(&self, q: DVec2, u: DVec2) -> Ahead {
        let speed = u.length();
        if speed == 0.0 {
            return Ahead::Clear;
        }
        let decel = 1.0 - q.dot(u) / speed;
        if decel <= 0.0 {
            return Ahead::Clear;
        }
        let t = speed / decel;
        if self.snaps(q, u, t) {
            // Constant deceleration over a tiny interval.
            return Ahead::Jump {
                t,
                q: q + u * (0.5 * t),
                u: DVec2::ZERO,
            };
        }
        Ahead::Cap(STOP_CAP * t, Limit::StopAhead)
    }

    /// The longest explicit step to take next, at most `cap` (bounded by `limit`), at |u| =
    /// `speed` (at rest, `cap`); `None` where the stretch is stiff and implicit steps take it
    /// ([`Run::implicit_step`]). Explicit steps are stable up to [`STIFF`] |u|/min(|q|, 1). The
    /// run goes implicit once its free step would pass that, and near the rim whatever its
    /// tolerance ([`near_rim`]); a second opinion, which integrates
    /// the stretch before a stop that the run takes in closed form, only once the step it takes
    /// (capped by the stop ahead) would, and before that holds its steps to the limit while each
    /// still closes [`CLOSE_IN`] of the time to the stop: that is all of it for a stop inside
    /// ξ ≈ 0.85, where implicit steps, each three Newton solves of 12 unknowns, cost it several
    /// times the run it checks.
    pub(super) fn explicit_cap(&self, q: DVec2, speed: f64, cap: f64, limit: Limit) -> Option<f64> {
        let step = self.natural_step();
        if speed == 0.0 {
            return Some(cap);
        }
        if !self.checking {
            let stiff = step * q.length().min(1.0) >= STIFF * speed;
            return (!stiff && !near_rim(q, speed)).then_some(cap);
        }
        let stable = STIFF * speed / q.length().min(1.0);
        // Not down to steps τ cannot resolve: the implicit step takes the stop there.
        if too_short(1e-3 * cap.min(stable), self.stepper.t) {
            return None;
        }
        if step.min(cap) < stable {
            return Some(cap);
        }
        (limit == Limit::StopAhead && stable >= CLOSE_IN * cap / STOP_CAP).then_some(stable)
    }

    /// The longest implicit step to take next, given the explicit `cap` (bounded by `limit`).
    /// A second opinion's implicit steps reach [`REACH`] of the way to a stop ahead, where the
    /// run's reach 0.7: there û has settled and u falls nearly linearly, which Radau IIA
    /// integrates nearly exactly, so its error control does not hold the step, and a step that
    /// would pass the stop is refused and retried shorter ([`radau::step`]). The check so also
    /// steps differently from the run where both take implicit steps.
    pub(super) fn implicit_cap(&self, cap: f64, limit: Limit) -> f64 {
        if self.checking && limit == Limit::StopAhead {
            cap * REACH / STOP_CAP
        } else {
            cap
        }
    }

    /// One implicit step of at most `cap` ([`radau`]), in the table frame, at the run's
    /// tolerance (a fixed-step method's: its [`Run::snap_time`]).
    pub(super) fn implicit_step(&mut self, cap: f64) -> Result<(), RunError> {
        let t0 = self.stepper.t;
        let scheme = self.settings.scheme;
        let tol = scheme
            .tol()
            .unwrap_or_else(|| (scheme.knob() * scheme.knob()).min(SNAP_T));
        // The first step is the end game's own, from the stop cap down by its error control:
        // the explicit method's step (Hairer's start, shorter at dop853's tol 1e-3 than at
        // 1e-4) made the end game's first step and its error depend on the method, and a loose
        // tolerance luckier than a tight one.
        // (With no stop ahead to cap it, the method's step: τ-max may be unbounded.)
        let h = if self.implicit_h > 0.0 {
            self.implicit_h
        } else if cap.is_finite() {
            cap
        } else {
            self.natural_step()
        }
        .min(cap);
        let y0 = self.table_y();
        let mut evals = 0;
        let step = radau::step(y0, h, tol, 1e-14 * t0.abs(), &mut evals);
        self.cost.rhs_evals += evals;
        let Some((step, next)) = step else {
            // No step as long as τ can resolve: if that is because the stop is closer still,
            // it is taken here, at constant deceleration (within the τ it cannot resolve).
            let (q, u) = (y0.p, y0.w);
            let speed = u.length();
            let decel = 1.0 - q.dot(u) / speed;
            let t = speed / decel;
            if decel > 0.0 && t <= 1e-12 * t0.abs() {
                self.snap_bound = self.snap_bound.max(super::worst_stop(q, u, t));
                self.jump(t, q + u * (0.5 * t), DVec2::ZERO, Limit::ClosedForm);
                return Ok(());
            }
            return Err(RunError::StepUnderflow { tau: t0 });
        };
        self.cost.steps += 1;
        // A capped step says nothing about how large the next free step may be.
        self.implicit_h = if step.h < h {
            next
        } else {
            next.max(self.implicit_h)
        };
        let (y1, c1) = kahan(y0, self.table_c(), step.dy);
        self.jump_through(step.h, Some(step.mid), y1.p, y1.w, Limit::Implicit);
        if let Some(info) = &mut self.last_step {
            info.err_ratio = Some(step.err);
        }
        self.end_game.implicit_error += step.err * tol;
        self.table = Some((self.stepper.t, y1, c1));
        Ok(())
    }

    /// The table-frame point now: kept from the latest implicit step if that is where the run
    /// is. Converted from the lab frame, u = v − ẑ×r loses ~1e-16 to cancellation, which at
    /// |u| ~ 1e-12 near the rim turns û by 1e-4 on every step, a transient that each implicit
    /// step would have to resolve again.
    /// It is kept with the rounding of its sums (Kahan): near the saddle a stop time moves by
    /// ~1/(2|H|) per unit of H, so the rounding of ξ on every step showed as 3e-8 at ξ0 = 0.9999
    /// whatever the tolerance.
    pub(super) fn table_y(&self) -> Y {
        match self.table {
            Some((t, y, _)) if t == self.stepper.t => y,
            _ => Frame::Table.from_state(&self.state()),
        }
    }

    /// The rounding carried with [`Run::table_y`] (zero when it was converted).
    fn table_c(&self) -> Y {
        match self.table {
            Some((t, _, c)) if t == self.stepper.t => c,
            _ => Y::default(),
        }
    }

    /// At rest outside ξ = 1 (a release there, or a momentary stop): how long a stretch
    /// [`radial_launch`] takes it out. There û is stiff (it relaxes onto q̂ at a rate ρ/|u|),
    /// so explicit steps from rest are held to ~|u|/ρ and were rejected by the million: at
    /// ξ0 = 1.02 the run took ten million steps to τ = 0.21 and, each hover taken as a stop,
    /// never left ξ = 1.0200000. The launch neglects Coriolis' share of ρ″, −2ρs² (the loss of
    /// I = s² − (1 − ρ)², see `saddle`), which over t from rest moves ρ by ρg²t⁴/6: the stretch keeps that
    /// within the travel tolerance. (Chained from a moving start the shares add up; explicit
    /// steps take over instead.)
    pub(super) fn launch_time(&self, s: &State) -> Option<f64> {
        let rho = s.xi();
        // At rest within ξ = μs/μk it is stuck, not launched.
        if rho <= self.settings.hold() || s.u_lab() != DVec2::ZERO {
            return None;
        }
        let g = rho - 1.0;
        Some((6.0 * self.travel_tol() / (rho * g * g)).powf(0.25))
    }

    /// Whether the stop `t` ahead at constant deceleration may be taken in closed form: only
    /// where that model cannot be wrong by more than [`Run::snap_time`], whichever way û turns
    /// on the way. Inside ξ = 1 the deceleration is at least 1 − ξ in every direction, so the
    /// stop comes within s/(1 − ξ). Outside, only once s < ξ − 1: then H < 0, so it can never
    /// come back inside ξ = 1 (where H ≥ 0 is needed to arrive) and the stop is momentary.
    /// Near ξ = 1 neither holds and the stop is integrated: there û swings onto q̂ and the
    /// deceleration falls to 1 − ξ, which a snap would not see. (With μ_s > μ_k the stop
    /// outside may hold, at ξ ≤ μ_s/μ_k: its place is the snap's, within s·t.)
    /// A stop closer than 1e-12 τ is one τ cannot resolve much better (a few thousand ulps):
    /// taken then too, within that. A second opinion takes a stop that close at constant
    /// deceleration whatever its bound, and states the bound: on the saddle, where û may yet
    /// swing out and the particle crawl on at a deceleration of 1 − ξ, its explicit steps would
    /// otherwise follow one way down to what τ resolves and hide the other.
    /// (Either way within [`super::worst_stop`], which [`Run::snap_bound`] keeps.)
    fn snaps(&self, q: DVec2, u: DVec2, t: f64) -> bool {
        let tau = self.stepper.t.abs();
        let within = self.snap_time().max(1e-12 * tau);
        let rho = q.length();
        (rho < 1.0 || u.length() < rho - 1.0)
            && (super::worst_stop(q, u, t) <= within || self.checking && t <= 1e-12 * tau)
    }

    /// The error in a stop's time that a closed-form stop may make: the adaptive method's
    /// tolerance, a fixed step's dt² (its own error per unit time), at most [`SNAP_T`]. A second
    /// opinion's is its own tolerance, below the run's: the bound it snaps within is a bound
    /// whichever way û turns ([`Run::snaps`]), not the run's frozen stop, and what either
    /// dropped is stated with the difference ([`Run::snap_bound`]).
    pub(super) fn snap_time(&self) -> f64 {
        let scheme = self.settings.scheme;
        scheme
            .tol()
            .unwrap_or_else(|| scheme.knob() * scheme.knob())
            .min(SNAP_T)
    }

    /// The step the integrator would take with no stop ahead.
    pub(super) fn natural_step(&self) -> f64 {
        self.stepper.natural_step(self.settings.scheme)
    }

    /// Distance a particle may still travel when its stop is taken in closed form.
    pub(super) fn travel_tol(&self) -> f64 {
        self.settings.scheme.tol().map_or(1e-13, |tol| 1e-3 * tol)
    }

    /// Takes the closed-form stretch to `t` ahead, arriving at table-frame `q` with `u`. A
    /// stop (u = 0) sticks if static friction can hold it, ξ ≤ μ_s/μ_k (the paper's 1), else
    /// it slips on at μ_k (Filippov).
    pub(super) fn jump(&mut self, t: f64, q: DVec2, u: DVec2, limit: Limit) {
        self.jump_through(t, None, q, u, limit);
    }

    /// [`Run::jump`] whose segment also passes through the table-frame point `mid` at `t/2`.
    fn jump_through(&mut self, t: f64, mid: Option<Y>, q: DVec2, u: DVec2, limit: Limit) {
        let frame = self.settings.frame;
        // A stop's last stretch is read off its closed form ([`Run::state_at`]).
        let from = self.table_y();
        self.stop_from = (u == DVec2::ZERO && from.w != DVec2::ZERO && from.p.length() < 1.0)
            .then_some((self.stepper.t, from));
        let at = |tau: f64, q: DVec2, u: DVec2| {
            let r = rotate(q, tau);
            State {
                tau,
                r,
                v: rotate(u, tau) + zcross(r),
            }
        };
        let tau = self.stepper.t + t;
        let to = at(tau, q, u);
        let rhs = |y| frame.rhs(y);
        let y1 = frame.from_state(&to);
        let seg = match mid {
            Some(m) => {
                let ym = frame.from_state(&at(self.stepper.t + 0.5 * t, m.p, m.w));
                self.stepper.advance_through(rhs, t, ym, y1, &mut self.cost)
            }
            None => self.stepper.advance(rhs, t, y1, None, &mut self.cost),
        };
        self.last = Some(seg);
        match limit {
            Limit::Implicit => {
                self.end_game.implicit_steps += 1;
                self.end_game.implicit_tau += t;
            }
            _ => {
                self.end_game.closed_steps += 1;
                self.end_game.closed_tau += t;
            }
        }
        self.last_step = Some(StepInfo {
            t0: seg.t0,
            h: t,
            limit,
            err_ratio: None,
            rejected: 0,
        });
        if self.escape.is_none() && certificate(&to, self.settings.hold()).is_some() {
            self.escape = Some(self.locate_escape(&seg));
        }
        if u != DVec2::ZERO {
            return;
        }
        if q.length() <= self.settings.hold() {
            self.status = Status::Stuck { tau, q };
        } else {
            self.slip_restarts += 1;
        }
    }

    /// Locates the escape certificate if it first holds at the end of `seg`, the step just
    /// taken from `start`; the step kept. A second opinion's steps carry no dense output: the
    /// one its escape is located in is taken again with it (the same step).
    pub(super) fn escape_in(&mut self, mut seg: Segment, start: &Stepper) -> Segment {
        let frame = self.settings.frame;
        if self.escape.is_none()
            && certificate(&frame.to_state(seg.y1, seg.t1()), self.settings.hold()).is_some()
        {
            if self.checking {
                seg = self.stepper.retake(
                    |y| frame.rhs(y),
                    self.settings.scheme,
                    start,
                    seg.h,
                    &mut self.cost,
                );
            }
            self.escape = Some(self.locate_escape(&seg));
        }
        seg
    }

    /// The first time in `seg` at which escape is certified (Illinois on the margin).
    pub(super) fn locate_escape(&self, seg: &Segment) -> Escape {
        let frame = self.settings.frame;
        let state = |t: f64| frame.to_state(seg.at(t), t);
        let hold = self.settings.hold();
        let g = |t: f64| certificate_margin(&state(t), hold);
        let tau = illinois(g, seg.t0, seg.t1(), 1e-13);
        let state = state(tau);
        let by = certificate(&state, hold).unwrap_or(Certificate::Radial);
        Escape { tau, by, state }
    }
}

/// Within this distance of the rim (1 − ξ) a run that cannot cross it in its present state
/// (|u| ≤ 1 − ξ, H ≤ 0: a stop ahead inside) takes the end game's implicit steps whatever its
/// tolerance.
const RIM: f64 = 0.1;

/// Whether table-frame `q` at |u| = `speed` is near the rim in the sense of [`RIM`]. There the
/// stop is ≈ |u|/(1 − ξ) ahead, so an explicit step's error in u, held to tol·(1 + |v|), moves it
/// by up to 1/(1 − ξ) times as much, where the implicit step holds |u| to its relative accuracy.
/// The switch once hung on the tolerance alone (the explicit step outgrowing the stability
/// limit, [`STIFF`] |u|/|q|): a loose tolerance had the end game take the whole stop and a
/// tighter one stepped there itself, up to 4000× further off (ξ0 0.99, v0 0.005 by dp54:
/// 2.6e-11 at tol 1e-7, 1.0e-7 at 1e-8; ξ0 0.99, v0 0.008, φ −1: 7.7e-7 at 1e-5, 7.8e-4 at
/// 1e-6). Holding the explicit steps to |u|'s relative accuracy there instead cost 4× the
/// evaluations at tol 1e-12; the implicit steps cost fewer than the explicit ones did.
fn near_rim(q: DVec2, speed: f64) -> bool {
    let g = 1.0 - q.length();
    g > 0.0 && g <= RIM && speed <= g
}

/// `y + dy` with the rounding of the sum carried in `c` (Kahan's compensated summation).
fn kahan(y: Y, c: Y, dy: Y) -> (Y, Y) {
    let add = |x: f64, c: f64, d: f64| {
        let d = d - c;
        let t = x + d;
        (t, (t - x) - d)
    };
    let (px, cpx) = add(y.p.x, c.p.x, dy.p.x);
    let (py, cpy) = add(y.p.y, c.p.y, dy.p.y);
    let (wx, cwx) = add(y.w.x, c.w.x, dy.w.x);
    let (wy, cwy) = add(y.w.y, c.w.y, dy.w.y);
    (
        Y {
            p: DVec2::new(px, py),
            w: DVec2::new(wx, wy),
        },
        Y {
            p: DVec2::new(cpx, cpy),
            w: DVec2::new(cwx, cwy),
        },
    )
}
