//! Radau IIA with three stages, order 5 (Hairer & Wanner, *Solving ODEs II*, Sec. IV.5): the
//! implicit step for the stretch before a stop (Sec. II, property 1).
//!
//! There û turns onto q̂ at a rate |q|/|u| that grows without bound as |u| → 0, so explicit
//! steps are held to a few |u|/|q|. Near the rim the stop is then ~1/(1 − ξ_rest) such steps
//! ahead per e-fold of |u| (ten million at ξ0 = 0.9999): this L-stable step is not held, and it
//! integrates the whole equations, Coriolis included, where closed forms would drop terms.
//! Table frame (q′ = u, u′ = −2ẑ×u + q − û), its Jacobian in closed form; full Newton on the
//! stages; the error by step doubling.

use super::model::Y;
use glam::DVec2;

type V = [f64; 4];

const SQ6: f64 = 2.449_489_742_783_178;
/// The Butcher matrix; the last row is b (stiffly accurate: y1 = y0 + Z3).
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
/// Newton iterations allowed per step before it is refused (and retried shorter).
const NEWTON: usize = 12;

fn v(y: Y) -> V {
    [y.p.x, y.p.y, y.w.x, y.w.y]
}

fn y(v: V) -> Y {
    Y {
        p: DVec2::new(v[0], v[1]),
        w: DVec2::new(v[2], v[3]),
    }
}

/// The table-frame equations (CONVENTIONS.md) while slipping; `None` at u = 0.
fn rhs(x: V) -> Option<V> {
    let s = x[2].hypot(x[3]);
    (s > 0.0).then(|| {
        [
            x[2],
            x[3],
            2.0 * x[3] + x[0] - x[2] / s,
            -2.0 * x[2] + x[1] - x[3] / s,
        ]
    })
}

/// ∂f/∂(q, u): the friction block −(I − ûûᵀ)/|u| is what makes the stretch stiff.
fn jacobian(x: V) -> [[f64; 4]; 4] {
    let s = x[2].hypot(x[3]);
    let (ex, ey) = (x[2] / s, x[3] / s);
    [
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
        [1.0, 0.0, -(1.0 - ex * ex) / s, 2.0 + ex * ey / s],
        [0.0, 1.0, -2.0 + ex * ey / s, -(1.0 - ey * ey) / s],
    ]
}

/// Solves `m x = b` in place by Gaussian elimination with partial pivoting; false if singular.
fn solve<const N: usize>(m: &mut [[f64; N]; N], b: &mut [f64; N]) -> bool {
    for col in 0..N {
        let piv = (col..N)
            .max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))
            .unwrap_or(col);
        // Zero or NaN: singular.
        if m[piv][col].abs().partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return false;
        }
        m.swap(col, piv);
        b.swap(col, piv);
        let pivot = m[col];
        for row in col + 1..N {
            let f = m[row][col] / pivot[col];
            if f != 0.0 {
                for (x, p) in m[row][col..].iter_mut().zip(&pivot[col..]) {
                    *x -= f * p;
                }
                b[row] -= f * b[col];
            }
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

/// One Radau IIA step of `h` from table-frame `y0`, its stages solved by full Newton to a
/// hundredth of `tol` (or to rounding). `None` if Newton does not converge or a stage reaches
/// u = 0 (the step reached past the stop): the caller retries shorter. Returns the end point
/// and the right-hand-side evaluations made.
fn one(y0: V, h: f64, tol: f64) -> Option<(V, u64)> {
    let f0 = rhs(y0)?;
    let mut z = [[0.0; 4]; 3];
    for (i, zi) in z.iter_mut().enumerate() {
        for k in 0..4 {
            zi[k] = C[i] * h * f0[k];
        }
    }
    let mut evals = 1;
    for _ in 0..NEWTON {
        let mut f = [[0.0; 4]; 3];
        let mut jac = [[[0.0; 4]; 4]; 3];
        for j in 0..3 {
            let x = std::array::from_fn(|k| y0[k] + z[j][k]);
            f[j] = rhs(x)?;
            jac[j] = jacobian(x);
        }
        evals += 3;
        // G(Z) = Z − h (A ⊗ I) F(y0 + Z) and its derivative I − h a_ij J(y0 + Z_j).
        let mut g = [0.0; 12];
        let mut m = [[0.0; 12]; 12];
        for i in 0..3 {
            for k in 0..4 {
                let r = 4 * i + k;
                g[r] = -(z[i][k] - h * (0..3).map(|j| A[i][j] * f[j][k]).sum::<f64>());
                for j in 0..3 {
                    for l in 0..4 {
                        m[r][4 * j + l] = -h * A[i][j] * jac[j][k][l];
                    }
                }
                m[r][r] += 1.0;
            }
        }
        if !solve(&mut m, &mut g) {
            return None;
        }
        // Converged once every increment is a hundredth of the tolerance, or down to the
        // rounding of the stage's increment (|Z| + h·|f's terms| at a few ulps), which near a
        // stop at the rim is the larger: there |u| ~ 1e-12 is changed by h(q − û), both ~1.
        // (Not |y|'s rounding: near the saddle 1e-15 in ξ on every step moved a stop by 1e-7.)
        let mut converged = true;
        for i in 0..3 {
            for k in 0..4 {
                let dz = g[4 * i + k];
                z[i][k] += dz;
                let y1 = y0[k] + z[i][k];
                let scale = if k < 2 {
                    1.0 + y0[k].abs().max(y1.abs())
                } else {
                    y0[2]
                        .hypot(y0[3])
                        .max((y0[2] + z[i][2]).hypot(y0[3] + z[i][3]))
                };
                // The terms of u′ (q, û, Coriolis) are ~1 each however small their sum.
                let terms = if k < 2 {
                    f[i][k].abs()
                } else {
                    1.0 + y0[0].hypot(y0[1]) + 2.0 * scale
                };
                let floor = 8.0 * f64::EPSILON * (z[i][k].abs() + h * terms);
                converged &= dz.abs() <= (1e-2 * tol.max(1e-13) * scale).max(floor);
            }
        }
        if converged {
            let y1 = std::array::from_fn(|k| y0[k] + z[2][k]);
            // Past the stop, û would have turned back: not this model's stretch.
            let back = y1[2] * y0[2] + y1[3] * y0[3] <= 0.0;
            return (!back && rhs(y1).is_some()).then_some((y1, evals));
        }
    }
    None
}

/// The size of the error `e` of a step of `h` by `dz` against `tol`: the position against
/// 1 + |q|, the relative velocity against the larger |u| of the two ends. Near a stop the time
/// left is |u| over the deceleration, so |u| is held to its own relative accuracy, not to the
/// position's absolute one — down to what rounding allows: u′'s terms are ~1 each however
/// small their sum, so the step changes u by h·u′ to within a few ulps of h.
fn scaled(y0: V, dz: V, e: V, h: f64, tol: f64) -> f64 {
    let s = y0[2].hypot(y0[3]).max((y0[2] + dz[2]).hypot(y0[3] + dz[3]));
    let q = |k: usize| e[k].abs() / (tol * (1.0 + y0[k].abs().max((y0[k] + dz[k]).abs())));
    let floor = 16.0 * f64::EPSILON * h * (1.0 + y0[0].hypot(y0[1]) + 2.0 * s);
    q(0).max(q(1))
        .max(e[2].abs() / (tol * s + floor))
        .max(e[3].abs() / (tol * s + floor))
}

/// An accepted step: its length, the change of the point over it (table frame: the caller
/// adds it to the point, with compensated sums), and the size of its error against the
/// tolerance (≤ 1).
pub struct Step {
    pub h: f64,
    pub dy: Y,
    /// The point at `h/2`, where the pair's two half steps meet: the step's dense output
    /// passes through it.
    pub mid: Y,
    pub err: f64,
}

/// One accepted step from table-frame `y0` of at most `h`: the step of `h` and two of `h/2`,
/// compared (Richardson: their difference over 2⁵ − 1 is the error of the pair's end, which is
/// kept), retried shorter while the error exceeds `tol` or Newton fails. Also returns the
/// proposal for the next step. `None` if the step shrinks below `h_min`.
pub fn step(y0: Y, mut h: f64, tol: f64, h_min: f64, evals: &mut u64) -> Option<(Step, f64)> {
    let x0 = v(y0);
    while h >= h_min {
        let full = one(x0, h, tol);
        let half = one(x0, 0.5 * h, tol)
            .and_then(|(m, e1)| one(m, 0.5 * h, tol).map(|(x, e2)| (x, m, e1 + e2)));
        if let (Some((a, ea)), Some((b, m, eb))) = (full, half) {
            *evals += ea + eb;
            let diff: V = std::array::from_fn(|k| (b[k] - a[k]) / 31.0);
            let dz = std::array::from_fn(|k| b[k] - x0[k]);
            let err = scaled(x0, dz, diff, h, tol);
            if err <= 1.0 {
                let next = h * (0.9 * err.max(1e-10).powf(-1.0 / 6.0)).min(4.0);
                return Some((
                    Step {
                        h,
                        dy: y(dz),
                        mid: y(m),
                        err,
                    },
                    next,
                ));
            }
            h *= (0.9 * err.powf(-1.0 / 6.0)).clamp(0.1, 0.5);
        } else {
            h *= 0.25;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Far from any stop the implicit step agrees with the explicit one to its order: its
    /// error at h and at h/2 falls 2⁶ ≈ 64× (local order 6).
    #[test]
    fn the_step_is_of_local_order_six() {
        let x0 = [0.4, 0.1, 0.3, -0.2];
        let reference = |h: f64| {
            // Many tiny steps of the same method: converged to rounding.
            let n = 64;
            let mut x = x0;
            for _ in 0..n {
                x = one(x, h / n as f64, 1e-15).unwrap().0;
            }
            x
        };
        let err = |h: f64| {
            let (a, b) = (one(x0, h, 1e-15).unwrap().0, reference(h));
            (0..4).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
        };
        let ratio = err(0.2) / err(0.1);
        assert!((40.0..100.0).contains(&ratio), "ratio {ratio}");
    }

    #[test]
    fn a_step_past_the_stop_is_refused() {
        // Inside ξ = 1 moving out at 0.01: the stop is ≈ 0.01/(1 − 0.5) = 0.02 ahead.
        let x0 = [0.5, 0.0, 0.01, 0.0];
        assert!(one(x0, 0.01, 1e-12).is_some());
        assert!(one(x0, 0.1, 1e-12).is_none());
    }
}
