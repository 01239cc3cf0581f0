//! The second opinion's own formulation (Sec. II's equations near a stop): the table-frame
//! motion in Sundman time σ (dτ = |u| dσ) and rim-distance variables, integrated by Radau IIA
//! with step doubling. It shares nothing with a run: no Cartesian state, no frame, no explicit
//! tableau, no closed-form stop.
//!
//! With g = 1 − ξ, ℓ = ln|u| and α the angle of û from q̂ (s = |u|, ρ = 1 − g), Sec. II's
//! equations (Coriolis included) are exactly
//!   dg/dσ = −s² cos α,  dℓ/dσ = ρ cos α − 1 = −(g + 2ρ sin²(α/2)),
//!   dα/dσ = −ρ sin α − 2s − s² sin α/ρ,  dθ/dσ = s² sin α/ρ,  dτ/dσ = s.
//! In τ, û turns at a rate ρ/s without bound near a stop; in σ at a rate ρ, and |u| decays as
//! e^{−(1 − ρ cos α)σ}: a stop inside ξ = 1 lies at σ = ∞ and a finite τ, reached without
//! stiffness in the turn of û (what is left is the ratio ρ/g between that turn and the decay,
//! which Radau IIA's L-stability takes in long steps). Near the rim g is carried with its own
//! relative precision and 1 − ρ cos α without cancellation: a Cartesian state rounds ξ near 1 to
//! 1e-16, H = ½(s² − g²) by g·1e-16, and a stop near the saddle, which moves by ~1/(2|H|) per
//! unit of H, by as much as 4e-10 (measured on the runs of issue 42).
//!
//! It holds for ξ ≥ [`RHO_MIN`] (polar coordinates are singular at the centre) and a release
//! with u ≠ 0; elsewhere, and at a momentary stop outside ξ = 1, it gives no answer.

use super::model::{Initial, State, rotate, zcross};
use super::run::Outcome;
use glam::DVec2;

/// (g, ℓ, α): the part of the state the others depend on.
type Core = [f64; 3];

/// Smallest ξ the polar form is used at.
pub const RHO_MIN: f64 = 0.05;

const SQ6: f64 = 2.449_489_742_783_178;
/// Radau IIA, three stages (order 5); the last row is b (stiffly accurate).
const A: [[f64; 3]; 3] = [
    [
        (88.0 - 7.0 * SQ6) / 360.0,
        (296.0 - 169.0 * SQ6) / 1800.0,
        (-2.0 + 3.0 * SQ6) / 225.0,
    ],
    [
        (296.0 + 169.0 * SQ6) / 1800.0,
        (88.0 + 7.0 * SQ6) / 360.0,
        (-2.0 - 3.0 * SQ6) / 225.0,
    ],
    [(16.0 - SQ6) / 36.0, (16.0 + SQ6) / 36.0, 1.0 / 9.0],
];
const C: [f64; 3] = [(4.0 - SQ6) / 10.0, (4.0 + SQ6) / 10.0, 1.0];
const NEWTON: usize = 10;

/// d(g, ℓ, α)/dσ and d(θ, τ)/dσ.
fn rhs(x: Core) -> Option<(Core, [f64; 2])> {
    let [g, l, a] = x;
    let (s, rho) = (l.exp(), 1.0 - g);
    if !(rho > 0.0 && s.is_finite()) {
        return None;
    }
    let (sin, cos) = a.sin_cos();
    let half = (0.5 * a).sin();
    let s2 = s * s;
    Some((
        [
            -s2 * cos,
            -(g + 2.0 * rho * half * half),
            -rho * sin - 2.0 * s - s2 * sin / rho,
        ],
        [s2 * sin / rho, s],
    ))
}

fn jacobian(x: Core) -> [[f64; 3]; 3] {
    let [g, l, a] = x;
    let (s, rho) = (l.exp(), 1.0 - g);
    let (sin, cos) = a.sin_cos();
    let s2 = s * s;
    [
        [0.0, -2.0 * s2 * cos, s2 * sin],
        [-cos, 0.0, -rho * sin],
        [
            sin - s2 * sin / (rho * rho),
            -2.0 * s - 2.0 * s2 * sin / rho,
            -rho * cos - s2 * cos / rho,
        ],
    ]
}

/// Solves `m x = b` in place (Gaussian elimination, partial pivoting); false if singular.
fn solve<const N: usize>(m: &mut [[f64; N]; N], b: &mut [f64; N]) -> bool {
    for col in 0..N {
        let piv = (col..N)
            .max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))
            .unwrap_or(col);
        if m[piv][col].abs().partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return false;
        }
        m.swap(col, piv);
        b.swap(col, piv);
        let pivot = m[col];
        for row in col + 1..N {
            let f = m[row][col] / pivot[col];
            for (x, p) in m[row][col..].iter_mut().zip(&pivot[col..]) {
                *x -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    for col in (0..N).rev() {
        let mut acc = b[col];
        for k in col + 1..N {
            acc -= m[col][k] * b[k];
        }
        b[col] = acc / m[col][col];
    }
    b.iter().all(|x| x.is_finite())
}

/// The scale each core component's error is held to: g to its own size (but not below |u|,
/// where it crosses the rim), ℓ (|u|'s relative error) and α absolutely.
fn scale(x: Core) -> Core {
    [x[0].abs().max(x[1].exp()).max(1e-300), 1.0, 1.0]
}

/// One Radau IIA step of `h` from `x0`: the change of the core and of (θ, τ). `None` if Newton
/// does not converge or a stage leaves the formulation's domain.
fn one(x0: Core, h: f64, tol: f64, evals: &mut u64) -> Option<(Core, [f64; 2])> {
    let (f0, _) = rhs(x0)?;
    *evals += 1;
    let mut z = [[0.0; 3]; 3];
    for (i, zi) in z.iter_mut().enumerate() {
        for k in 0..3 {
            zi[k] = C[i] * h * f0[k];
        }
    }
    let sc = scale(x0);
    for _ in 0..NEWTON {
        let mut f = [[0.0; 3]; 3];
        let mut jac = [[[0.0; 3]; 3]; 3];
        for j in 0..3 {
            let x = std::array::from_fn(|k| x0[k] + z[j][k]);
            f[j] = rhs(x)?.0;
            jac[j] = jacobian(x);
        }
        *evals += 3;
        let mut r = [0.0; 9];
        let mut m = [[0.0; 9]; 9];
        for i in 0..3 {
            for k in 0..3 {
                let row = 3 * i + k;
                r[row] = -(z[i][k] - h * (0..3).map(|j| A[i][j] * f[j][k]).sum::<f64>());
                for j in 0..3 {
                    for l in 0..3 {
                        m[row][3 * j + l] = -h * A[i][j] * jac[j][k][l];
                    }
                }
                m[row][row] += 1.0;
            }
        }
        if !solve(&mut m, &mut r) {
            return None;
        }
        let mut converged = true;
        for i in 0..3 {
            for k in 0..3 {
                let dz = r[3 * i + k];
                z[i][k] += dz;
                let floor = 4.0 * f64::EPSILON * (z[i][k].abs() + h * f[i][k].abs());
                converged &= dz.abs() <= (1e-3 * tol * sc[k]).max(floor);
            }
        }
        if converged {
            let mut quad = [0.0; 2];
            for (j, zj) in z.iter().enumerate() {
                let (_, fq) = rhs(std::array::from_fn(|k| x0[k] + zj[k]))?;
                for (q, fq) in quad.iter_mut().zip(fq) {
                    *q += h * A[2][j] * fq;
                }
            }
            *evals += 3;
            return Some((z[2], quad));
        }
    }
    None
}

/// A point of the formulation, τ kept with the rounding of its sum (Kahan).
#[derive(Clone, Copy, Debug)]
struct Point {
    x: Core,
    theta: f64,
    tau: f64,
    tau_c: f64,
}

impl Point {
    fn speed(&self) -> f64 {
        self.x[1].exp()
    }
    fn plus(&self, dz: Core, dq: [f64; 2]) -> Point {
        let d = dq[1] - self.tau_c;
        let tau = self.tau + d;
        Point {
            x: std::array::from_fn(|k| self.x[k] + dz[k]),
            theta: self.theta + dq[0],
            tau,
            tau_c: (tau - self.tau) - d,
        }
    }
    /// The particle as the engine's [`State`] (lab frame).
    fn state(&self) -> State {
        let [g, l, a] = self.x;
        let q = DVec2::from_angle(self.theta) * (1.0 - g);
        let u = DVec2::from_angle(self.theta + a) * l.exp();
        let r = rotate(q, self.tau);
        State {
            tau: self.tau,
            r,
            v: rotate(u, self.tau) + zcross(r),
        }
    }
    /// > 0 where escape is certified: ξ > 1 moving out, or E < −½hold².
    fn escape_margin(&self, hold: f64) -> f64 {
        let [g, _, a] = self.x;
        let (s, rho) = (self.speed(), 1.0 - g);
        let energy = 0.5 * s * s - 0.5 * rho * rho;
        (-g).min(s * a.cos()).max(-(energy + 0.5 * hold * hold))
    }
}

/// Two Radau steps of `h/2` from `p`, and the error of their end against `tol` (≤ 1: accept)
/// by comparison with one step of `h` (Richardson: their difference over 2⁵ − 1).
fn doubled(p: &Point, h: f64, tol: f64, evals: &mut u64) -> Option<(Point, f64)> {
    let full = one(p.x, h, tol, evals)?;
    let (dz1, dq1) = one(p.x, 0.5 * h, tol, evals)?;
    let mid = p.plus(dz1, dq1);
    let (dz2, dq2) = one(mid.x, 0.5 * h, tol, evals)?;
    let end = mid.plus(dz2, dq2);
    let sc = scale(p.x);
    let mut err: f64 = 0.0;
    for k in 0..3 {
        let both = dz1[k] + dz2[k];
        err = err.max((both - full.0[k]).abs() / 31.0 / (tol * sc[k]));
    }
    let dtau = dq1[1] + dq2[1];
    err = err.max((dtau - full.1[1]).abs() / 31.0 / (tol * dtau.max(1e-300)));
    err = err.max((dq1[0] + dq2[0] - full.1[0]).abs() / 31.0 / tol);
    Some((end, err))
}

/// How a run in this formulation ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ending {
    pub outcome: Outcome,
    /// The stop, the first point where escape is certified, or the state at the time limit.
    pub state: State,
    /// At a stop: a bound on the error of the closed-form tail after the last step.
    pub tail: f64,
    pub evals: u64,
    /// The latest τ a step reached short of `tau_limit` before a stop or an escape (0 if none):
    /// under any limit above it the run takes the same steps to the same end.
    pub reach: f64,
}

/// The time still to go from `p`, inside ξ = 1, and a bound on its error, where |u| is small
/// beside g: the deceleration 1 − ρ cos α = D stays within [g − 2s²/g, D + 4s²/ρ²] on the way
/// (g falls by at most s·T ≤ s²/g, and û stays within its slow manifold, sin α ≈ −2s/ρ).
fn tail(p: &Point) -> Option<(f64, f64)> {
    let [g, _, a] = p.x;
    let (s, rho) = (p.speed(), 1.0 - g);
    let d = g + 2.0 * rho * (0.5 * a).sin().powi(2);
    let lo = g - 2.0 * s * s / g;
    if !(g > 0.0 && lo > 0.0) {
        return None;
    }
    let t = s / d;
    let bound = (s / lo - t).max(t - s / (d + 4.0 * s * s / (rho * rho)));
    Some((t, bound))
}

/// Runs `initial` in this formulation to its stop, its escape certificate, or `tau_limit`, at
/// tolerance `tol` (the stop's tail within a hundredth of it), with μ_s/μ_k = `hold`, in at
/// most `max_steps` steps. `None` where it does not hold (module docs) or out of steps.
pub fn fate(
    initial: &Initial,
    hold: f64,
    tol: f64,
    tau_limit: f64,
    max_steps: u64,
) -> Option<Ending> {
    let u0 = initial.u0();
    let s0 = u0.length();
    if initial.frictionless || s0 == 0.0 || !s0.is_finite() || initial.xi0 < RHO_MIN {
        return None;
    }
    let mut p = Point {
        x: [1.0 - initial.xi0, s0.ln(), u0.y.atan2(u0.x)],
        theta: 0.0,
        tau: 0.0,
        tau_c: 0.0,
    };
    let (mut evals, mut reach) = (0, 0.0);
    let ending = |outcome, state, tail, evals, reach| {
        Some(Ending {
            outcome,
            state,
            tail,
            evals,
            reach,
        })
    };
    if p.escape_margin(hold) > 0.0 {
        return ending(Outcome::Escaped, p.state(), 0.0, evals, reach);
    }
    let mut h: f64 = 1e-3;
    for _ in 0..max_steps {
        if let Some((t, bound)) = tail(&p)
            && bound <= 1e-2 * tol * t.max(1e-3)
        {
            let mut at = p;
            at.tau += t;
            let mut s = at.state();
            s.v = zcross(s.r);
            return ending(Outcome::Stuck, s, bound, evals, reach);
        }
        let [g, _, _] = p.x;
        if 1.0 - g < RHO_MIN || (g < 0.0 && p.speed() < 1e-6 * -g) {
            return None;
        }
        let Some((next, err)) = doubled(&p, h, tol, &mut evals) else {
            h *= 0.25;
            if h < 1e-300 {
                return None;
            }
            continue;
        };
        if err > 1.0 {
            h *= (0.9 * err.powf(-1.0 / 6.0)).clamp(0.1, 0.5);
            continue;
        }
        // Where the step passes an event, the event is located on shorter steps from its start.
        let escaped = next.escape_margin(hold) > 0.0;
        if escaped || next.tau >= tau_limit {
            let hit = |q: &Point| {
                if escaped {
                    q.escape_margin(hold) > 0.0
                } else {
                    q.tau >= tau_limit
                }
            };
            let (mut lo, mut hi, mut at) = (0.0, h, next);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                match doubled(&p, mid, tol, &mut evals) {
                    Some((q, _)) if hit(&q) => (hi, at) = (mid, q),
                    Some(_) => lo = mid,
                    None => return None,
                }
            }
            let outcome = if escaped {
                Outcome::Escaped
            } else {
                at.tau = tau_limit;
                Outcome::Running
            };
            return ending(outcome, at.state(), 0.0, evals, reach);
        }
        reach = next.tau;
        p = next;
        h *= (0.9 * err.max(1e-10).powf(-1.0 / 6.0)).min(4.0);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Release, Run, Settings};

    /// A converged Cartesian run (the engine's own equations, dp54 at 1e-13, no closed-form
    /// stop): its end and its time.
    fn converged(i: Initial) -> (Outcome, State) {
        let mut run = Run::checking(i, Settings::dp54(1e-13)).unwrap();
        run.finish(200.0).unwrap()
    }

    #[test]
    fn it_ends_where_a_converged_run_does() {
        // Cases A and B stop; v0 0.7 from ξ0 0.5 escapes.
        for (xi0, phi, v0) in [
            (0.5, std::f64::consts::PI, 1.0),
            (0.5, 0.0, 0.6),
            (0.5, 0.0, 0.7),
        ] {
            let i = Initial::velocity(xi0, phi, v0);
            let e = fate(&i, 1.0, 1e-13, 200.0, 200_000).unwrap();
            let (o, s) = converged(i);
            assert_eq!(e.outcome, o, "{i:?}");
            assert!(
                (e.state.tau - s.tau).abs() < 1e-10,
                "{i:?}: {} {}",
                e.state.tau,
                s.tau
            );
            assert!((e.state.r - s.r).length() < 1e-10, "{i:?}");
        }
    }

    #[test]
    fn it_answers_only_where_it_holds() {
        let rest = Initial::at_rest(1.2, Release::TableRest);
        assert!(fate(&rest, 1.0, 1e-10, 10.0, 1000).is_none());
        let centre = Initial::velocity(0.01, 0.0, 0.1);
        assert!(fate(&centre, 1.0, 1e-10, 10.0, 1000).is_none());
        // Out of steps: no answer rather than a guess.
        let b = Initial::velocity(0.5, 0.0, 0.6);
        assert!(fate(&b, 1.0, 1e-10, 200.0, 3).is_none());
    }
}
