//! Root finding and minimisation on a bracket, shared by event location and the solvers:
//! Illinois on a continuous function, bisection on a yes/no outcome, golden-section search.

use crate::error::Error;

/// The first crossing of `g` from ≤ 0 to > 0 in [a, b], given g(b) > 0: the Illinois variant
/// of regula falsi, which keeps a superlinear rate where plain regula falsi stalls.
/// Returns a point where g > 0 within `xtol` of the crossing.
pub fn illinois(g: impl Fn(f64) -> f64, mut a: f64, mut b: f64, xtol: f64) -> f64 {
    let (mut ga, mut gb) = (g(a), g(b));
    if ga > 0.0 {
        return a;
    }
    let mut side = 0;
    for _ in 0..200 {
        if (b - a).abs() <= xtol * b.abs().max(1.0) {
            break;
        }
        let mut c = (a * gb - b * ga) / (gb - ga);
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let gc = g(c);
        if gc > 0.0 {
            b = c;
            gb = gc;
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        } else {
            a = c;
            ga = gc;
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        }
    }
    b
}

/// Bisection on a monotone outcome: `escapes(x)` false at `lo`, true at `hi`, down to width
/// `tol`. Runs that never settle count as escaping (the saddle is the threshold itself).
pub fn bisect<E>(
    mut lo: f64,
    mut hi: f64,
    tol: f64,
    mut escapes: impl FnMut(f64) -> Result<bool, E>,
) -> Result<(f64, f64, u32), E> {
    let mut runs = 0;
    while hi - lo > tol {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        runs += 1;
        if escapes(mid)? { hi = mid } else { lo = mid }
    }
    Ok((lo, hi, runs))
}

/// The minimiser of a unimodal `f` on [a, b] to within `tol`, by golden-section search.
pub fn golden_min(
    f: &mut impl FnMut(f64) -> Result<f64, Error>,
    mut a: f64,
    mut b: f64,
    tol: f64,
) -> Result<f64, Error> {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c)?, f(d)?);
    while b - a > tol {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - g * (b - a);
            fc = f(c)?;
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + g * (b - a);
            fd = f(d)?;
        }
    }
    Ok(0.5 * (a + b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_finder_lands_on_its_answer() {
        let x = illinois(|t| t * t - 2.0, 0.0, 2.0, 1e-14);
        assert!((x - 2f64.sqrt()).abs() < 1e-13 && x * x > 2.0);
        let (lo, hi, _) = bisect(0.0, 1.0, 1e-9, |t| Ok::<_, Error>(t > 0.3)).unwrap();
        assert!(lo <= 0.3 && hi > 0.3 && hi - lo <= 1e-9);
        let m = golden_min(&mut |t: f64| Ok((t - 0.7).powi(2)), 0.0, 2.0, 1e-8).unwrap();
        assert!((m - 0.7).abs() < 1e-8);
    }
}
