//! Root finding on a bracket, shared by event location and the solvers.

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
