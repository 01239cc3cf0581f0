//! The slide on the spinning-up table, in the lab frame: the state the shared stepper carries
//! (position, velocity and the table's rate, so that the autonomous stepper sees Ω(τ)), the
//! equations of motion, and the escape certificate.

use crate::model::{Y, rotate, zcross};
use crate::stepper::Vector;
use glam::DVec2;
use std::ops::{Add, Mul, Sub};

/// A point of the slide: lab position `p`, lab velocity `w`, and the table's rate `omega`
/// (Ω′ = a: carried in the state, the equations need no clock).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Z {
    pub p: DVec2,
    pub w: DVec2,
    pub omega: f64,
}

impl Add for Z {
    type Output = Z;
    fn add(self, o: Z) -> Z {
        Z {
            p: self.p + o.p,
            w: self.w + o.w,
            omega: self.omega + o.omega,
        }
    }
}

impl Sub for Z {
    type Output = Z;
    fn sub(self, o: Z) -> Z {
        Z {
            p: self.p - o.p,
            w: self.w - o.w,
            omega: self.omega - o.omega,
        }
    }
}

impl Mul<f64> for Z {
    type Output = Z;
    fn mul(self, k: f64) -> Z {
        Z {
            p: self.p * k,
            w: self.w * k,
            omega: self.omega * k,
        }
    }
}

impl Vector for Z {
    /// The point's norm on (p, w), and Ω against tol·(1 + |Ω|).
    fn err_norm(y0: Z, y1: Z, e: Z, tol: f64, vel: f64) -> f64 {
        let y = |z: Z| Y { p: z.p, w: z.w };
        let om = (e.omega / (tol + tol * y0.omega.abs().max(y1.omega.abs()))).abs();
        Y::err_norm(y(y0), y(y1), y(e), tol, vel).max(om)
    }
}

impl Z {
    /// The coin at rest on the table at lab position `p` while it turns at `omega`.
    pub fn riding(p: DVec2, omega: f64) -> Z {
        Z {
            p,
            w: zcross(p) * omega,
            omega,
        }
    }

    /// Velocity relative to the table surface beneath, u = v − Ω ẑ×r.
    pub fn u(&self) -> DVec2 {
        self.w - zcross(self.p) * self.omega
    }

    /// The acceleration of the table's surface at the coin, Ω̇ ẑ×r − Ω² r: what friction must
    /// supply to hold it there (its size is [`super::Ramp::grip`]).
    pub fn need(&self, rate: f64) -> DVec2 {
        zcross(self.p) * rate - self.p * (self.omega * self.omega)
    }

    /// The slide's equations, lab frame, units μ_k g = 1: r′ = v, v′ = −û, Ω′ = a. At u = 0
    /// (Filippov) friction gives what the surface's acceleration asks up to its kinetic
    /// strength, so a coin loose from rest leaves along it.
    pub fn rhs(self, rate: f64) -> Z {
        let u = self.u();
        let s = u.length();
        let f = if s > 0.0 {
            -u / s
        } else {
            let need = self.need(rate);
            let n = need.length();
            if n > 1.0 { need / n } else { need }
        };
        Z {
            p: self.w,
            w: f,
            omega: rate,
        }
    }

    /// The forces per unit mass on the coin as the table's frame sees them, turned by the
    /// table's `angle` (units μ_k g; Sec. II's, extended to a table speeding up): friction,
    /// Coriolis −2Ω ẑ×u, centrifugal Ω²q and Euler −Ω̇ ẑ×q. Friction is −û while it slides;
    /// at rest it gives what the surface's acceleration asks while static friction `hold` can
    /// (then the four sum to zero), else its kinetic strength along it (as [`Z::rhs`]).
    pub fn table_forces(&self, rate: f64, angle: f64, hold: f64) -> [DVec2; 4] {
        let need = self.need(rate);
        let lab = if self.u() == DVec2::ZERO && need.length() <= hold {
            need
        } else {
            self.rhs(rate).w
        };
        let (q, u) = (rotate(self.p, -angle), rotate(self.u(), -angle));
        let w = self.omega;
        [
            rotate(lab, -angle),
            -2.0 * w * zcross(u),
            w * w * q,
            -rate * zcross(q),
        ]
    }

    /// Rate of change of |u|: d|u|/dτ = −1 − û·need (Coriolis turns u, does no work on it).
    /// Negative: a stop ahead, about |u| over its size.
    pub fn speed_rate(&self, rate: f64) -> f64 {
        let u = self.u();
        -1.0 - (u / u.length()).dot(self.need(rate))
    }

    /// The escape certificate's margin, > 0 iff certified: ξΩ² > 1 and ξ′ > 0. Then ξ′ stays
    /// positive for ever on a table that only speeds up, so the coin never stops: with θ′ the
    /// lab rate, ξ″ = ξθ′² − ξ′/|u| = (ξΩ + w)²/ξ − ξ′/|u| (w the tangential slip). Let τ1
    /// be the first time ξ′ = 0 or u = 0; before it ξ and Ω grow, so ξΩ² > 1 holds. If
    /// u(τ1) ≠ 0, ξ″ ≥ −ξ′/m near it (|u| ≥ m > 0), so ξ′(τ1) > 0. If u(τ1) = 0, w → 0 and
    /// ξ″ → ξΩ² − ξ′/|u| ≥ ξΩ² − 1 > 0, so ξ′ grew into τ1. Either way no such τ1 (the
    /// constant-Ω certificate of `run::outcome` with Ω(τ) ≥ its value when it first held).
    pub fn certificate_margin(&self) -> f64 {
        let xi = self.p.length();
        let xi_dot = if xi > 0.0 {
            self.p.dot(self.w) / xi
        } else {
            self.w.length()
        };
        (xi * self.omega * self.omega - 1.0).min(xi_dot)
    }
}

/// 5-point Gauss–Legendre nodes and weights on [−1, 1].
const GAUSS: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_08),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_08),
];

/// The first stretch of a slide from rest at table-frame `q` at `tau`, in closed form: the
/// slip speed U grows as U′ = |need| − 1 along −need (the coin lags the surface), its direction
/// held there by friction's turning, which is stiff while U is small (û relaxes at a rate
/// 1/U, so explicit steps from rest would be held to ~U: two million of them from a slip at
/// μ_s = μ_k). The form neglects û's tilt off −need (about 2ΩU, the Coriolis turn) and the
/// surface's change under the coin; the stretch is kept short enough, at most `cap`, that the
/// place they move, about 2ΩU²t + (1 + Ω²)Ut³, stays within `travel`. Returns the stretch and
/// the table-frame position and slip there.
pub fn launch(
    ramp: &super::Ramp,
    q: DVec2,
    tau: f64,
    travel: f64,
    cap: f64,
) -> (f64, DVec2, DVec2) {
    let xi = q.length();
    // U(t) = ∫₀ᵗ (G − 1) and its integral ∫₀ᵗ (t − s)(G − 1), G the grip at q.
    let speeds = |t: f64| {
        GAUSS.iter().fold((0.0, 0.0), |(u, d), &(x, w)| {
            let s = 0.5 * t * (1.0 + x);
            let g = (ramp.grip(xi, tau + s) - 1.0) * 0.5 * t * w;
            (u + g, d + (t - s) * g)
        })
    };
    let mut t = cap.min(1.0);
    for _ in 0..200 {
        let (u, _) = speeds(t);
        let om = ramp.omega(tau + t);
        if 2.0 * om * u * u * t + (1.0 + om * om) * u * t * t * t <= travel {
            break;
        }
        t *= 0.5;
    }
    let dir = |s: f64| {
        let n = Z::riding(q, ramp.omega(tau + s)).need(ramp.rate);
        n / n.length()
    };
    let (u, d) = speeds(t);
    (t, q - dir(0.5 * t) * d, -dir(t) * u)
}
