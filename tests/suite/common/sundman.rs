//! An independent reference for stop times: the table-frame equations in Sundman time
//! σ (dτ = |u| dσ), integrated by the Kutta–Merson method (order 4, five stages, its own
//! estimate of each step's error). Nothing of the crate's integrators, events or closed forms
//! is used.
//!
//! In σ, dq/dσ = s u, du/dσ = s(q − 2ẑ×u) − u (s = |u|): û turns at a rate ~|q|, not
//! |q|/|u|, so the stretch before a stop is not stiff, and |u| decays like e^{−(1 − q·û)σ}: a
//! stop inside ξ = 1 lies at σ = ∞ and at a finite τ. The run ends once the time still to go is
//! bounded below `TAIL` (|u|/(1 − ξ), the slowest deceleration inside the rim), and that tail is
//! added as |u|/(1 − q·û).
//!
//! Near the rim that decay is ~1e4–1e6 times slower than the turn of û, and an explicit method's
//! steps are held by the turn, not by the tolerance: a stop at ξ = 1 − 1.4e-6 takes σ ~ 2e7
//! (a higher order does not help). Merson's method is stable to h ≈ 3.5 on it for five
//! evaluations a step, where RK4 with step doubling was stable to 2.8 for eleven: that, and
//! `sqrt` for `hypot`, make this reference about 4× cheaper than the RK4 one it replaced, whose
//! stop times it matches within their own error.

/// (q, u, τ).
type V = [f64; 5];

/// Where the reference run ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fate {
    /// At rest inside ξ = 1 at τ, at ξ.
    Stuck { tau: f64, xi: f64 },
    /// ξ > 1 moving out (property 2 of Sec. II).
    Escaped,
    /// A momentary stop outside ξ = 1, or out of budget: no verdict.
    Unknown,
}

const TAIL: f64 = 1e-13;
/// The longest step: inside Merson's stability (h ≈ 3.5 on the turn of û, rate ~|q| ≤ 1 in σ).
const H_MAX: f64 = 3.0;

/// |(a, b)| (no overflow to fear: |q| and |u| are of order 1 or below).
fn norm(a: f64, b: f64) -> f64 {
    (a * a + b * b).sqrt()
}

fn f(x: &V) -> V {
    let s = norm(x[2], x[3]);
    [
        s * x[2],
        s * x[3],
        s * (x[0] + 2.0 * x[3]) - x[2],
        s * (x[1] - 2.0 * x[2]) - x[3],
        s,
    ]
}

/// One Kutta–Merson step of `h` from `x`: the increment (order 4) and the estimate of its error,
/// h/30 (2k1 − 9k3 + 8k4 − k5).
fn merson(x: &V, h: f64) -> (V, V) {
    let at = |w: &[(f64, &V)]| -> V {
        std::array::from_fn(|i| x[i] + h * w.iter().map(|(c, k)| c * k[i]).sum::<f64>())
    };
    let k1 = f(x);
    let k2 = f(&at(&[(1.0 / 3.0, &k1)]));
    let k3 = f(&at(&[(1.0 / 6.0, &k1), (1.0 / 6.0, &k2)]));
    let k4 = f(&at(&[(1.0 / 8.0, &k1), (3.0 / 8.0, &k3)]));
    let k5 = f(&at(&[(0.5, &k1), (-1.5, &k3), (2.0, &k4)]));
    let dx = std::array::from_fn(|i| h / 6.0 * (k1[i] + 4.0 * k4[i] + k5[i]));
    let err = std::array::from_fn(|i| h / 30.0 * (2.0 * k1[i] - 9.0 * k3[i] + 8.0 * k4[i] - k5[i]));
    (dx, err)
}

/// A step of `h` from `x` and its error against the local tolerance `tol` (relative in |u| and
/// τ, absolute in q): at most 1 to be taken.
fn step(x: &V, h: f64, tol: f64) -> (V, f64) {
    let (dx, e) = merson(x, h);
    let s = norm(x[2], x[3]);
    let scale = |i: usize| match i {
        0 | 1 => 1.0 + x[i].abs(),
        2 | 3 => s,
        _ => 1.0 + x[4],
    };
    let err = (0..5)
        .map(|i| e[i].abs() / (tol * scale(i)))
        .fold(0.0, f64::max);
    (dx, err)
}

/// The next step's length after one of `h` with error `err`: 0.9·err^(−1/5), within [0.2, 4].
/// Below an error of 5e-4 that factor is over 4.1, and above 2e3 under 0.197: the bounds, taken
/// without `powf` (a quarter of the CPU of the runs, held by stability, not by the error).
fn next(h: f64, err: f64) -> f64 {
    let factor = if err < 5e-4 {
        4.0
    } else if err > 2e3 {
        0.2
    } else {
        (0.9 * err.max(1e-12).powf(-0.2)).clamp(0.2, 4.0)
    };
    (h * factor).min(H_MAX)
}

/// `x + dx` with the rounding of the sum carried in `c` (Kahan): near the saddle a stop time
/// moves by ~1/(2|H|) per unit of H, so the rounding of a million small steps would show.
fn kahan(x: &mut V, c: &mut V, dx: &V) {
    for i in 0..5 {
        let y = dx[i] - c[i];
        let t = x[i] + y;
        c[i] = (t - x[i]) - y;
        x[i] = t;
    }
}

/// The reference fate of a release (table frame, CONVENTIONS.md) at local tolerance `tol`
/// (relative in |u| and τ, absolute in q), within `max_steps` steps.
pub fn fate(xi0: f64, phi: f64, v0: f64, tol: f64, max_steps: u64) -> Fate {
    let mut x: V = [xi0, 0.0, v0 * phi.cos(), v0 * phi.sin(), 0.0];
    let mut c: V = [0.0; 5];
    let mut h: f64 = 1e-3;
    for _ in 0..max_steps {
        let s = norm(x[2], x[3]);
        let rho = norm(x[0], x[1]);
        if rho > 1.0 && x[0] * x[2] + x[1] * x[3] > 0.0 {
            return Fate::Escaped;
        }
        if rho < 1.0 && s / (1.0 - rho) < TAIL {
            let decel = 1.0 - (x[0] * x[2] + x[1] * x[3]) / s;
            return Fate::Stuck {
                tau: x[4] + s / decel,
                xi: rho,
            };
        }
        if s == 0.0 || (rho > 1.0 && s < 1e-13) {
            return Fate::Unknown;
        }
        let (dx, err) = step(&x, h, tol);
        if err <= 1.0 {
            kahan(&mut x, &mut c, &dx);
        }
        h = next(h, err);
    }
    Fate::Unknown
}

/// The speed |u| and radius ξ at time `tau` (before any stop) at local tolerance `tol`: the
/// step that passes `tau` is taken again shorter, by bisection on its length, to land on it.
pub fn at(xi0: f64, phi: f64, v0: f64, tol: f64, tau: f64) -> Option<(f64, f64)> {
    let mut x: V = [xi0, 0.0, v0 * phi.cos(), v0 * phi.sin(), 0.0];
    let mut c: V = [0.0; 5];
    let mut h: f64 = 1e-3;
    for _ in 0..20_000_000u64 {
        let (dx, err) = step(&x, h, tol);
        if err <= 1.0 {
            let (mut end, mut ce) = (x, c);
            kahan(&mut end, &mut ce, &dx);
            if end[4] >= tau {
                // Land on τ: 64 steps of m/64 from x, bisected on their length m.
                let (mut lo, mut hi) = (0.0, h);
                let mut land = end;
                for _ in 0..60 {
                    let m = 0.5 * (lo + hi);
                    let (mut y, mut cy) = (x, c);
                    let n = 64;
                    for _ in 0..n {
                        let (d, _) = merson(&y, m / n as f64);
                        kahan(&mut y, &mut cy, &d);
                    }
                    if y[4] >= tau {
                        (hi, land) = (m, y);
                    } else {
                        lo = m;
                    }
                }
                return Some((norm(land[2], land[3]), norm(land[0], land[1])));
            }
            (x, c) = (end, ce);
        }
        h = next(h, err);
    }
    None
}
