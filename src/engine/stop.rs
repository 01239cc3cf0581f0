//! Closed forms near a stop (Sec. II, property 1), each used only where its error was measured
//! to be within the run's tolerance: the launch from rest outside ξ = 1, and the stop inside it
//! with q frozen (for ξ ≤ 0.95). Elsewhere the stretch before a stop is integrated in implicit
//! steps (`radau`).

use super::model::zcross;
use glam::DVec2;

/// The first, radial stretch out from rest at table-frame `q` (|q| = ρ > 1), `t` ahead:
/// Filippov's rule points friction against q̂ at full strength, so it moves out along q̂ with
/// ρ″ = ρ − 1 (Sec. II, Eq. 5 with û = q̂): ρ − 1 = g cosh t from g = ρ − 1. Coriolis turns u
/// off q̂ by ≈ 2s/ρ, which changes ρ″ by O(s²): see `Run::launch_time` for the stretch this is
/// good for. Returns the table-frame position and velocity at its end.
pub fn radial_launch(q: DVec2, t: f64) -> (DVec2, DVec2) {
    let rho = q.length();
    let dir = q / rho;
    let g = rho - 1.0;
    (dir * (1.0 + g * t.cosh()), dir * (g * t.sinh()))
}

/// The stop from table-frame `q` (|q| = k < 1) at relative velocity `u`, in closed form:
/// the time to it and the displacement on the way.
///
/// With q frozen and Coriolis set aside, u′ = q − û is solvable (Sec. II's equations near a
/// stop): the angle α of û to q̂ obeys tan(α/2) ∝ e^{−kσ} in the Sundman time dτ = |u|dσ, and
/// |u| ∝ tan(α/2)^{1/k}/sin α. Integrating gives, with a = cos²(α/2), b = sin²(α/2),
///   T = s [a/(1−k) + b/(1+k)],
///   Δ∥ = ½s² [a²/(1−k) − b²/(1+k)],   Δ⊥ = s² sin α [a/(2−k) + b/(2+k)].
/// Coriolis turns u at rate 2, which, seen from u, turns q the other way: its first-order
/// effect on T is 2k/(1−k²)·∫τ sin α dτ along the frozen solution, also in closed form. What
/// is left is O((s/(1−k))³) in both T and Δ: see [`frozen_stop_error`].
pub fn frozen_stop(q: DVec2, u: DVec2) -> (f64, DVec2) {
    let s = u.length();
    let k = q.length();
    let e = u / s;
    let f = if k > 0.0 { q / k } else { e };
    let (c, sin) = (f.dot(e), f.perp_dot(e));
    let (a, b) = (0.5 * (1.0 + c), 0.5 * (1.0 - c));
    let t = s * (a / (1.0 - k) + b / (1.0 + k));
    let lag = s * (a / ((1.0 - k) * (2.0 - k)) + b / ((1.0 + k) * (2.0 + k)));
    let coriolis = 2.0 * k / (1.0 - k * k) * s * sin * (t - lag);
    let along = 0.5 * s * s * (a * a / (1.0 - k) - b * b / (1.0 + k));
    let across = s * s * sin * (a / (2.0 - k) + b / (2.0 + k));
    (t + coriolis, f * along + zcross(f) * across)
}

/// The particle inside a closed-form stop from table-frame `q` at `u` (|q| = k < 1), the
/// share `left` ∈ [0, 1] of its time still to go: the table-frame position and velocity, on
/// the frozen solution of [`frozen_stop`] (Coriolis, which turns û by 2 per unit time and does
/// no work, set aside). In Sundman time σ, x = tan(α/2) = x0 e^{−kσ} and
/// |u| = s e^{−(1−k)σ}(1 + x²)/(1 + x0²), so the time still to go,
/// |u|[a/(1−k) + b/(1+k)], falls monotonically in σ: σ is found by bisection. The position is the
/// stop's less the displacement still to come. What the readouts inside a stop's last stretch
/// show: a cubic through its ends, the stop's slope there 0, put |u| 30 % low (issue 42).
pub fn frozen_at(q: DVec2, u: DVec2, left: f64) -> (DVec2, DVec2) {
    let s = u.length();
    let k = q.length();
    let e = u / s;
    let f = if k > 0.0 { q / k } else { e };
    let alpha0 = f.perp_dot(e).atan2(f.dot(e));
    let (_, to_stop) = frozen_stop(q, u);
    let rest = q + to_stop;
    let at = |sigma: f64| {
        if alpha0.abs() > std::f64::consts::PI - 1e-9 {
            // Straight in: û stays put (a turn off it grows only at second order here).
            return (alpha0, s * (-(1.0 + k) * sigma).exp());
        }
        let x0 = (0.5 * alpha0).tan();
        let x = x0 * (-k * sigma).exp();
        let speed = s * (-(1.0 - k) * sigma).exp() * (1.0 + x * x) / (1.0 + x0 * x0);
        (2.0 * x.atan(), speed)
    };
    let to_go = |sigma: f64| {
        let (a, speed) = at(sigma);
        let c = a.cos();
        speed * (0.5 * (1.0 + c) / (1.0 - k) + 0.5 * (1.0 - c) / (1.0 + k))
    };
    let target = left.clamp(0.0, 1.0) * to_go(0.0);
    if target <= 0.0 {
        return (rest, DVec2::ZERO);
    }
    let mut hi = 1.0;
    while to_go(hi) > target && hi < 1e6 {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if to_go(mid) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (a, speed) = at(0.5 * (lo + hi));
    let v = DVec2::from_angle(a).rotate(f) * speed;
    (rest - frozen_stop(q, v).1, v)
}

/// A bound on the error of [`frozen_stop`] in both the stop time and the rest position,
/// measured against converged runs over k ∈ [0, 0.95] and every α (tests below): the
/// neglected terms are the second-order Coriolis turn and the drift of q on the way.
pub fn frozen_stop_error(q: DVec2, u: DVec2) -> f64 {
    0.5 * (u.length() / (1.0 - q.length())).powi(3)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Initial, Outcome, Run, Settings};

    /// The stop from (k, 0) at speed s in direction α, by a converged run that does not take
    /// this closed form itself.
    fn converged(k: f64, alpha: f64, s: f64) -> (f64, DVec2) {
        let mut run = Run::checking(Initial::velocity(k, alpha, s), Settings::dp54(1e-13)).unwrap();
        assert_eq!(run.run(10.0, true).unwrap(), Outcome::Stuck);
        (run.tau(), run.state().q())
    }

    #[test]
    fn frozen_stop_is_within_its_bound_for_every_direction() {
        for k in [0.0, 0.3, 0.6, 0.8, 0.95] {
            for alpha in [0.0, 0.7, 1.6, 2.5, -2.0, std::f64::consts::PI] {
                for s in [0.3 * (1.0 - k), 0.03 * (1.0 - k), 0.003 * (1.0 - k)] {
                    let (q, u) = (DVec2::new(k, 0.0), DVec2::from_angle(alpha) * s);
                    let (t, dq) = frozen_stop(q, u);
                    let (t_ref, q_ref) = converged(k, alpha, s);
                    let bound = frozen_stop_error(q, u);
                    let (et, eq) = ((t - t_ref).abs(), (q + dq - q_ref).length());
                    assert!(
                        et <= bound && eq <= bound,
                        "k={k} α={alpha} s={s}: |ΔT|={et:e} |Δq|={eq:e} > {bound:e}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_coriolis_term_makes_the_stop_time_third_order() {
        // Without it the error in T would fall 100× per 10× in s; with it, 1000×.
        let (k, alpha) = (0.5, 1.0);
        let err = |s: f64| {
            let (t, _) = frozen_stop(DVec2::new(k, 0.0), DVec2::from_angle(alpha) * s);
            (t - converged(k, alpha, s).0).abs()
        };
        let ratio = err(0.02) / err(0.002);
        assert!((600.0..1700.0).contains(&ratio), "ratio {ratio}");
    }

    #[test]
    fn frozen_stop_at_the_centre_is_a_straight_braking_line() {
        let u = DVec2::new(0.3, -0.4);
        let (t, dq) = frozen_stop(DVec2::ZERO, u);
        assert!((t - 0.5).abs() < 1e-15);
        assert!((dq - u * 0.25).length() < 1e-15);
    }
}
