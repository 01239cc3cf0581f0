//! Step-size control (Hairer, Nørsett & Wanner, *Solving ODEs I*, II.4): the starting step and
//! the controllers of DOPRI5 and DOP853.

use super::Vector;

/// Hairer's starting step (`hinit` of DOPRI5 and DOP853; Hairer, Nørsett & Wanner, Sec. II.4):
/// an Euler probe of size h0 = 0.01·|y|/|f| measures how fast f changes, and the first step is
/// sized so that its error of the method's `order` would be 0.01·tol. One right-hand-side
/// evaluation.
pub(super) fn initial_step<V: Vector>(
    rhs: impl Fn(V) -> V,
    y: V,
    f0: V,
    tol: f64,
    order: i32,
) -> f64 {
    let norm = |v: V| V::err_norm(y, y, v, tol, f64::INFINITY);
    let (d0, d1) = (norm(y), norm(f0));
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let d2 = norm(rhs(y + f0 * h0) - f0) / h0;
    let d = d1.max(d2);
    let h1 = if d <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d).powf(1.0 / f64::from(order))
    };
    (100.0 * h0).min(h1)
}

/// Hairer's step-size controllers, with their codes' defaults (safety 0.9): DOPRI5's PI
/// control (β = 0.04, exponent 1/5 − 0.75β, factor in [0.2, 10]) and DOP853's (β = 0,
/// exponent 1/8, factor in [1/3, 1.5], where Hairer's grows up to 6×: after `hinit`'s first
/// step, sized for 0.01·tol on a rough estimate, the second was up to six times longer and at
/// a tighter tolerance longer still, so that case A to τ 0.5 was 25× further off at tol 1e-6
/// than at 1e-3 for the same cost), the latter with Gustafsson's predictive step (as in
/// Hairer's RADAU5): closing in on a stop its error grows ~10× per step at equal h, and
/// without the prediction nearly every step was first rejected (11 evaluations lost each).
#[derive(Clone, Copy, Debug)]
pub(super) struct Controller {
    facold: f64,
    rejected_last: bool,
    beta: f64,
    expo: f64,
    /// Bounds of h/h_new: the largest shrink and the largest growth.
    shrink: f64,
    grow: f64,
    predictive: bool,
    /// The last accepted step and its error (predictive control only).
    last_accepted: Option<(f64, f64)>,
}

impl Controller {
    const SAFE: f64 = 0.9;
    pub(super) fn dp54() -> Self {
        Controller {
            facold: 1e-4,
            rejected_last: false,
            beta: 0.04,
            expo: 0.2 - 0.04 * 0.75,
            shrink: 5.0,
            grow: 0.1,
            predictive: false,
            last_accepted: None,
        }
    }
    pub(super) fn dop853() -> Self {
        Controller {
            beta: 0.0,
            expo: 1.0 / 8.0,
            shrink: 1.0 / 0.333,
            grow: 1.0 / 1.5,
            predictive: true,
            ..Controller::dp54()
        }
    }
    /// The next step size after a trial of size `h` with error `err`; `true` if accepted.
    pub(super) fn next(&mut self, h: f64, err: f64) -> (f64, bool) {
        // A NaN error (a state the right-hand side cannot take) is a rejection, never a growth.
        let err = if err.is_nan() { f64::INFINITY } else { err };
        let fac11 = err.max(1e-300).powf(self.expo);
        if err <= 1.0 {
            let fac =
                (fac11 / self.facold.powf(self.beta) / Self::SAFE).clamp(self.grow, self.shrink);
            let mut hnew = h / fac;
            if let Some((hacc, erracc)) = self.last_accepted {
                // Gustafsson's predictive control: an error growing from step to step
                // (a stop ahead) shrinks the next step before it is rejected.
                let gus = (hacc / h) * (err * err / erracc).powf(self.expo) / Self::SAFE;
                hnew = hnew.min(h / gus.clamp(self.grow, self.shrink));
            }
            if self.predictive {
                self.last_accepted = Some((h, err.max(1e-2)));
            }
            if self.rejected_last {
                hnew = hnew.min(h);
            }
            self.facold = err.max(1e-4);
            self.rejected_last = false;
            (hnew, true)
        } else {
            self.rejected_last = true;
            (h / (fac11 / Self::SAFE).min(self.shrink), false)
        }
    }
}
