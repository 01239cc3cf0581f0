//! An independent reference for stop times: the table-frame equations in Sundman time
//! σ (dτ = |u| dσ), integrated by classic RK4 with step doubling. Nothing of the crate's
//! integrators, events or closed forms is used.
//!
//! In σ, dq/dσ = s u, du/dσ = s(q − 2ẑ×u) − u (s = |u|): û turns at a rate ~|q|, not
//! |q|/|u|, so the stretch before a stop is not stiff, and |u| decays like e^{−(1 − q·û)σ}: a
//! stop inside ξ = 1 lies at σ = ∞ and at a finite τ. The run ends once the time still to go is
//! bounded below `TAIL` (|u|/(1 − ξ), the slowest deceleration inside the rim), and that tail is
//! added as |u|/(1 − q·û).

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

fn f(x: &V) -> V {
    let s = x[2].hypot(x[3]);
    [
        s * x[2],
        s * x[3],
        s * (x[0] + 2.0 * x[3]) - x[2],
        s * (x[1] - 2.0 * x[2]) - x[3],
        s,
    ]
}

/// The increment of one RK4 step of `h` from `x`.
fn rk4(x: &V, h: f64) -> V {
    let add = |a: &V, b: &V, k: f64| -> V { std::array::from_fn(|i| a[i] + k * b[i]) };
    let k1 = f(x);
    let k2 = f(&add(x, &k1, 0.5 * h));
    let k3 = f(&add(x, &k2, 0.5 * h));
    let k4 = f(&add(x, &k3, h));
    std::array::from_fn(|i| h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
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
        let s = x[2].hypot(x[3]);
        let rho = x[0].hypot(x[1]);
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
        let full = rk4(&x, h);
        let d1 = rk4(&x, 0.5 * h);
        let (mut mid, mut cm) = (x, c);
        kahan(&mut mid, &mut cm, &d1);
        let d2 = rk4(&mid, 0.5 * h);
        let half: V = std::array::from_fn(|i| d1[i] + d2[i]);
        let scale = |i: usize| match i {
            0 | 1 => 1.0 + x[i].abs(),
            2 | 3 => s,
            _ => 1.0 + x[4],
        };
        let err = (0..5)
            .map(|i| (half[i] - full[i]).abs() / 15.0 / (tol * scale(i)))
            .fold(0.0, f64::max);
        if err <= 1.0 {
            (x, c) = (mid, cm);
            kahan(&mut x, &mut c, &d2);
        }
        // RK4 is stable to h ≈ 2.8 on the turn of û (rate ~|q| in σ).
        h = (h * (0.9 * err.max(1e-12).powf(-0.2)).clamp(0.2, 4.0)).min(2.0);
    }
    Fate::Unknown
}

/// The speed |u| and radius ξ at time `tau` (before any stop) at local tolerance `tol`: the
/// step that passes `tau` is taken again shorter, by bisection on its length, to land on it.
pub fn at(xi0: f64, phi: f64, v0: f64, tol: f64, tau: f64) -> Option<(f64, f64)> {
    let mut x: V = [xi0, 0.0, v0 * phi.cos(), v0 * phi.sin(), 0.0];
    let mut c: V = [0.0; 5];
    let mut h: f64 = 1e-3;
    let add = |x: &V, c: &V, d: &V| {
        let (mut x, mut c) = (*x, *c);
        kahan(&mut x, &mut c, d);
        (x, c)
    };
    for _ in 0..20_000_000u64 {
        let s = x[2].hypot(x[3]);
        let full = rk4(&x, h);
        let d1 = rk4(&x, 0.5 * h);
        let (mid, cm) = add(&x, &c, &d1);
        let d2 = rk4(&mid, 0.5 * h);
        let half: V = std::array::from_fn(|i| d1[i] + d2[i]);
        let scale = |i: usize| match i {
            0 | 1 => 1.0 + x[i].abs(),
            2 | 3 => s,
            _ => 1.0 + x[4],
        };
        let err = (0..5)
            .map(|i| (half[i] - full[i]).abs() / 15.0 / (tol * scale(i)))
            .fold(0.0, f64::max);
        if err <= 1.0 {
            let (end, ce) = add(&mid, &cm, &d2);
            if end[4] >= tau {
                // Land on τ: steps of h/n from x, n doubling, bisected on the length.
                let (mut lo, mut hi) = (0.0, h);
                let mut land = end;
                for _ in 0..60 {
                    let m = 0.5 * (lo + hi);
                    let (mut y, mut cy) = (x, c);
                    let n = 64;
                    for _ in 0..n {
                        let d = rk4(&y, m / n as f64);
                        kahan(&mut y, &mut cy, &d);
                    }
                    if y[4] >= tau {
                        (hi, land) = (m, y);
                    } else {
                        lo = m;
                    }
                }
                return Some((land[2].hypot(land[3]), land[0].hypot(land[1])));
            }
            (x, c) = (end, ce);
        }
        h = (h * (0.9 * err.max(1e-12).powf(-0.2)).clamp(0.2, 4.0)).min(2.0);
    }
    None
}
