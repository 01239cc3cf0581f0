//! The body's state: where it is (centre, velocity, angle, rate), which contacts hold, and the
//! six components the shared stepper integrates.

use crate::stepper::Vector;
use glam::DVec2;

/// The body at time τ in the table frame: centre q, its velocity u, the rod's angle ψ and its
/// rate ψ′ (both relative to the table).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RodState {
    pub tau: f64,
    pub q: DVec2,
    pub u: DVec2,
    pub psi: f64,
    pub w: f64,
}

/// Which contacts hold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    /// Both slide.
    Slip,
    /// Contact `i` (0: at q + (L/2)ê, 1: at q − (L/2)ê) is stuck at `anchor`; the body pivots,
    /// turning in the sense `sign` (the other contact's friction keeps it until ψ′ = 0, an
    /// event: integrated past it with that friction, the stop is a smooth crossing to locate).
    Pivot { i: usize, anchor: DVec2, sign: f64 },
    /// Both stuck: the body rides the table.
    Rest,
}

/// The side of each contact: contact i sits at q + S[i] (L/2) ê.
pub(super) const S: [f64; 2] = [1.0, -1.0];

/// The body's state as the shared stepper takes it: q, u, ψ, ψ′.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct V(pub(super) [f64; 6]);

impl std::ops::Index<usize> for V {
    type Output = f64;
    fn index(&self, j: usize) -> &f64 {
        &self.0[j]
    }
}

impl std::ops::Add for V {
    type Output = V;
    fn add(self, o: V) -> V {
        V(std::array::from_fn(|j| self.0[j] + o.0[j]))
    }
}

impl std::ops::Sub for V {
    type Output = V;
    fn sub(self, o: V) -> V {
        V(std::array::from_fn(|j| self.0[j] - o.0[j]))
    }
}

impl std::ops::Mul<f64> for V {
    type Output = V;
    fn mul(self, c: f64) -> V {
        V(self.0.map(|x| x * c))
    }
}

/// The max norm over the six components, each against tol·(1 + |y|) at the larger of its two
/// ends (the point's norm without its velocity bound).
impl Vector for V {
    fn err_norm(y0: V, y1: V, e: V, tol: f64, _vel: f64) -> f64 {
        (0..6)
            .map(|j| (e[j] / (tol * (1.0 + y0[j].abs().max(y1[j].abs())))).abs())
            .fold(0.0, f64::max)
    }
}

/// The rod's direction ê at angle ψ.
pub(super) fn axis(psi: f64) -> DVec2 {
    DVec2::from_angle(psi)
}

impl RodState {
    pub(super) fn y(&self) -> V {
        V([self.q.x, self.q.y, self.u.x, self.u.y, self.psi, self.w])
    }
    pub(super) fn from(tau: f64, y: V) -> RodState {
        RodState {
            tau,
            q: DVec2::new(y[0], y[1]),
            u: DVec2::new(y[2], y[3]),
            psi: y[4],
            w: y[5],
        }
    }
    /// Where the two masses are.
    pub fn contacts(&self, l: f64) -> [DVec2; 2] {
        S.map(|s| self.q + axis(self.psi) * (s * 0.5 * l))
    }
    /// The two contacts' slip velocities relative to the table.
    pub fn slips(&self, l: f64) -> [DVec2; 2] {
        S.map(|s| self.u + axis(self.psi).perp() * (s * 0.5 * l * self.w))
    }
    /// The Jacobi energy per unit mass, E = ½|u|² + (L²/8) ψ′² − ½|q|² (constants dropped).
    pub fn energy(&self, l: f64) -> f64 {
        0.5 * self.u.length_squared() + l * l / 8.0 * self.w * self.w
            - 0.5 * self.q.length_squared()
    }
}
