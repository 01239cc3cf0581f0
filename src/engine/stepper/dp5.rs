//! Dormand–Prince 5(4) (Hairer's DOPRI5; Hairer, Nørsett & Wanner, *Solving ODEs I*, II.5):
//! its tableau, one trial step with its error estimate, and the dense output's coefficients.

use super::{Dense, Vector};

// Dormand–Prince 5(4) tableau (Hairer's DOPRI5).
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// One DOPRI5 trial step: the new point, its slope (FSAL), the scaled error norm and the
/// dense-output coefficients. Six new right-hand-side evaluations.
pub(super) struct Dp5Trial<V> {
    pub(super) y1: V,
    pub(super) f1: V,
    pub(super) err: f64,
    pub(super) dense: Dense<V>,
}

/// DOPRI5's stages from `y` with slope `k1` over `h`: the new point, the slopes k3…k7 (k7 at the
/// new point, FSAL) and the embedded error estimate. Six new right-hand-side evaluations.
fn dp5_stages<V: Vector>(rhs: impl Fn(V) -> V, y: V, k1: V, h: f64) -> (V, [V; 5], V) {
    let k2 = rhs(y + k1 * (h * A21));
    let k3 = rhs(y + (k1 * A31 + k2 * A32) * h);
    let k4 = rhs(y + (k1 * A41 + k2 * A42 + k3 * A43) * h);
    let k5 = rhs(y + (k1 * A51 + k2 * A52 + k3 * A53 + k4 * A54) * h);
    let k6 = rhs(y + (k1 * A61 + k2 * A62 + k3 * A63 + k4 * A64 + k5 * A65) * h);
    let y1 = y + (k1 * A71 + k3 * A73 + k4 * A74 + k5 * A75 + k6 * A76) * h;
    let k7 = rhs(y1);
    let e = (k1 * E1 + k3 * E3 + k4 * E4 + k5 * E5 + k6 * E6 + k7 * E7) * h;
    (y1, [k3, k4, k5, k6, k7], e)
}

pub(super) fn dp5_step<V: Vector>(
    rhs: impl Fn(V) -> V,
    y: V,
    k1: V,
    h: f64,
    tol: f64,
    vel: f64,
) -> Dp5Trial<V> {
    let (y1, [k3, k4, k5, k6, k7], e) = dp5_stages(rhs, y, k1, h);
    let err = V::err_norm(y, y1, e, tol, vel);
    let dy = y1 - y;
    let bspl = k1 * h - dy;
    let dense = Dense::Dp5([
        y,
        dy,
        bspl,
        dy - k7 * h - bspl,
        (k1 * D1 + k3 * D3 + k4 * D4 + k5 * D5 + k6 * D6 + k7 * D7) * h,
    ]);
    Dp5Trial {
        y1,
        f1: k7,
        err,
        dense,
    }
}
