//! The events of a run, located inside the step: the stop ahead (Sec. II, property 1) taken
//! in closed form or approached in shrinking steps, the jump to it, and where the escape
//! certificate first holds (property 2).

use super::outcome::{Certificate, Escape, Status, certificate, certificate_margin};
use super::{Ahead, HOVER_STEPS, Limit, Run, SNAP_T, STIFF, STOP_CAP, StepInfo};
use crate::engine::model::{State, rotate, zcross};
use crate::engine::roots::illinois;
use crate::engine::saddle::carry;
use crate::engine::stepper::Segment;
use crate::engine::stop::radial_stop;
use glam::DVec2;

impl Run {
    /// Looks ahead for a stop. d|u|/dτ = q·û − 1 (Coriolis does no work), so a stop is
    /// ≈ |u|/(1 − q·û) ahead: steps are capped to a fraction of that, and a stop close enough
    /// is taken in closed form.
    ///
    /// Inside ξ = 1, û soon turns onto q̂ and the last stretch is radial with ρ″ = ρ − 1: from
    /// ρ and s = |u| it stops at ρ_s = 1 − √((1 − ρ)² − s²) after atanh(s/(1 − ρ)), having
    /// travelled at most s·atanh(s/(1 − ρ)). That end game takes over once the travel left is
    /// below the tolerance, or once explicit steps hover (their stability limit, ~|u|/|q|,
    /// shrinks with |u|).
    pub(super) fn stop_ahead(&self, s: &State) -> Ahead {
        let u = s.u_lab();
        let speed = u.length();
        if speed == 0.0 {
            return Ahead::Clear;
        }
        let rho = s.xi();
        // ξ′|q|: the radial models below hold only for a particle moving out.
        let out = s.r.dot(u);
        let decel = 1.0 - out / speed;
        let gap = 1.0 - rho;
        // Steps too long for û to be resolved, with û already on q̂: the radial end game is
        // then exact to O(|u|²) and the explicit step is not.
        let stiff = self.natural_step() * rho >= STIFF * speed;
        // û on q̂ (outward, never inward) to within an angle α whose share of the energy,
        // s²(1 − cos α), the end game may neglect.
        let aligned = out > 0.0 && speed * (speed - out / rho) <= self.travel_tol();
        let hovering = self.stiff_steps >= HOVER_STEPS;
        let end_game = (hovering && out > 0.0) || (stiff && aligned);
        if gap > 0.0 && speed < gap && out > 0.0 {
            let t = (speed / gap).atanh();
            // Short enough to neglect: the radial path is the slowest and longest way to the
            // stop (d|u|/dτ ≤ −(1 − ξ) in every direction), so off q̂ it bounds the error.
            let negligible = speed * t <= self.travel_tol() && (aligned || t <= self.snap_time());
            if negligible || end_game {
                return Ahead::Jump {
                    t,
                    q: radial_stop(s.q(), speed, t),
                    u: DVec2::ZERO,
                };
            }
        } else if end_game && gap > 0.0 && speed >= gap {
            // Over the saddle: it reaches ξ = 1 still moving out if I = s² − (1 − ρ)², carried
            // along the slow manifold ([`carry`]: û is on it here), stays positive beyond the
            // model's own error (its O(s) share of the loss of I on the way).
            let i0 = speed * speed - gap * gap;
            let (i, t) = carry(i0, gap);
            if i > (i0 - i) * speed {
                let q = s.q() / rho;
                return Ahead::Jump {
                    t,
                    q,
                    u: q * i.sqrt(),
                };
            }
        } else if hovering && gap <= 0.0 && out <= 0.0 {
            // At the saddle ξ ≈ 1 itself, not moving out: stop here and let Filippov's rule
            // decide. (Moving out beyond it, it escapes: property 2; `launch_time` takes it.)
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
        if self.snaps(rho, speed, t) {
            // Constant deceleration over a tiny interval.
            return Ahead::Jump {
                t,
                q: s.q() + s.u() * (0.5 * t),
                u: DVec2::ZERO,
            };
        }
        if stiff && !aligned {
            // Not yet on q̂: steps within the stability limit let û turn as it does.
            Ahead::Cap((STOP_CAP * t).min(speed / rho), Limit::Stability)
        } else {
            Ahead::Cap(STOP_CAP * t, Limit::StopAhead)
        }
    }

    /// At rest outside ξ = 1 (a release there, or a momentary stop): how long a stretch
    /// [`radial_launch`] takes it out. There û is stiff (it relaxes onto q̂ at a rate ρ/|u|),
    /// so explicit steps from rest are held to ~|u|/ρ and were rejected by the million: at
    /// ξ0 = 1.02 the run took ten million steps to τ = 0.21 and, each hover taken as a stop,
    /// never left ξ = 1.0200000. The launch neglects Coriolis' share of ρ″, −2ρs² (the loss of
    /// I in `radial_stop`), which over t from rest moves ρ by ρg²t⁴/6: the stretch keeps that
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
    fn snaps(&self, rho: f64, speed: f64, t: f64) -> bool {
        let within = self.snap_time();
        if rho < 1.0 {
            speed / (1.0 - rho) <= within
        } else {
            speed < rho - 1.0 && t <= within
        }
    }

    /// The error in a stop's time that a closed-form stop may make: dp54's tolerance, a fixed
    /// step's dt² (its own error per unit time), at most [`SNAP_T`].
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
    pub(super) fn jump(&mut self, t: f64, q: DVec2, u: DVec2) {
        let frame = self.settings.frame;
        let tau = self.stepper.t + t;
        let r = rotate(q, tau);
        let to = State {
            tau,
            r,
            v: rotate(u, tau) + zcross(r),
        };
        let seg = self.stepper.advance(
            |y| frame.rhs(y),
            t,
            frame.from_state(&to),
            None,
            &mut self.cost,
        );
        self.last = Some(seg);
        self.last_step = Some(StepInfo {
            t0: seg.t0,
            h: t,
            limit: Limit::ClosedForm,
            err_ratio: None,
            rejected: 0,
        });
        self.stiff_steps = 0;
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
