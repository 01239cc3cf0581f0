//! The saddle ξ = 1, u = 0 (Sec. IV): releases near the escape speed slide up to it ever more
//! slowly, and their fate is read off before they get there.
//!
//! With s = |u|, ρ = ξ, g = 1 − ρ and α the angle between u and q, the equations of motion
//! (Sec. II) give exactly s′ = ρ cos α − 1 (Coriolis does no work) and ρ′ = s cos α, so
//! `I = s² − g²` (= 2H) obeys I′ = −2s(1 − cos α), and along the way out
//! dI/dg = 2(1 − cos α)/cos α. Friction's direction is stiff: misalignment decays at the rate
//! ρ/s, onto a slow manifold. There α′ = −ρ sin α/s − 2 − s sin α/ρ is small (α′ ≈ 2g/ρ), so
//! sin α = −(2 + α′)sρ/(ρ² + s²) ≈ −2s/(ρ² + s²) (as ρ + g = 1), and
//! 1 − cos α = k = 2s²/(ρ² + s²)² to a relative O(s²) (Coriolis, 2s, balancing the turn of
//! friction's direction; the bench measured 0.1–0.3 % at s = 0.006–0.013). Then
//! dI/dg = 2k/(1 − k) with s² = I + g², integrated to g = 0, gives I where the particle
//! reaches ξ = 1: positive, it passes the saddle moving out and escapes;
//! negative, I (hence H) turns negative inside ξ = 1 and it sticks. Either way I/2 there is one
//! smooth function of the release through the threshold: what the escape-speed secant needs.

use super::model::State;

/// `H = E + ξ − ½ = ½(|u|² − (1 − ξ)²)`: never increases (dH/dτ = −|u| + ξ′ ≤ 0, as
/// |ξ′| ≤ |u| and dE/dτ = −|u|), and at ξ = 1 it is ½|u|² ≥ 0. So H < 0 at ξ < 1 certifies that
/// the particle never reaches ξ = 1 again: it will stick. Near the saddle (ξ = 1, u = 0) H is
/// nearly conserved, and its final value (−½(1 − ξ_rest)² when stuck, ½|u|² on crossing ξ = 1
/// when escaping) is a smooth, nearly linear function of v0 through the escape speed.
pub fn saddle_h(s: &State) -> f64 {
    let gap = 1.0 - s.xi();
    0.5 * (s.u_lab().length_squared() - gap * gap)
}

/// The slow-manifold reading applies this close to the saddle (s and g), where its O(s)
/// correction is small.
const NEAR: f64 = 0.02;
/// Misalignment from the slow manifold (relative, in 1 − cos α) below which û counts as slaved.
const SLAVED: f64 = 0.1;
/// RK4 steps in g for dI/dg: the integrand is a quadratic in g to within O(g), so the error
/// (∝ (g/4)⁵) is far below the bound on the model's own.
const STEPS: usize = 4;

/// I = s² − g² carried along the slow manifold from gap `g` (= 1 − ξ) to ξ = 1:
/// dI/dg = 2k/(1 − k) with 1 − cos α = k = 2s²/(ρ² + s²)², s² = I + g² (module docs), by RK4
/// in g.
pub fn carry(i0: f64, g: f64) -> f64 {
    let k = |s2: f64, rho: f64| 2.0 * s2 / ((rho * rho + s2) * (rho * rho + s2));
    let slope = |g: f64, i: f64| {
        let k = k(i + g * g, 1.0 - g);
        2.0 * k / (1.0 - k)
    };
    let dg = -g / STEPS as f64;
    let (mut gg, mut i) = (g, i0);
    for _ in 0..STEPS {
        let k1 = slope(gg, i);
        let k2 = slope(gg + 0.5 * dg, i + 0.5 * dg * k1);
        let k3 = slope(gg + 0.5 * dg, i + 0.5 * dg * k2);
        let k4 = slope(gg + dg, i + dg * k3);
        i += dg / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        gg += dg;
    }
    i
}

/// What the slow manifold says of a particle sliding out near the saddle, with `h` = I/2
/// carried to ξ = 1 (for an escape, H as it crosses ξ = 1; for a stop, above −½(1 − ξ_rest)²
/// by O((1 − ξ_rest)³)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fate {
    /// It reaches ξ = 1 still moving out.
    Escapes { h: f64 },
    /// H turns negative inside ξ = 1.
    Sticks { h: f64 },
}

/// The fate of `s` read off the slow manifold (module docs), when `s` is on it close to the
/// saddle, sliding out, and the answer is certain beyond the model's error: its O(s²)
/// remainder (bounded by s, several times what was measured) and the measured misalignment
/// (three times), as shares of the loss of I still to come. None otherwise: keep integrating.
pub fn fate(s: &State) -> Option<Fate> {
    let (q, u) = (s.r, s.u_lab());
    let (rho, speed) = (q.length(), u.length());
    let g = 1.0 - rho;
    if !(speed > 0.0 && speed <= NEAR && g > 0.0 && g <= NEAR) {
        return None;
    }
    let (qh, uh) = (q / rho, u / speed);
    let cos = qh.dot(uh);
    if cos <= 0.0 {
        return None;
    }
    // On the manifold u lags q̂ clockwise, sin α ≈ −2s/(ρ² + s²). Judged on sin α itself:
    // 1 − cos α cannot tell α from its mirror −α, which a release near the rim sweeps through
    // while û is still turning onto the manifold (far from it, and off it the other way).
    let sin = qh.perp_dot(uh);
    let on = sin * (rho * rho + speed * speed) / (-2.0 * speed);
    let one_minus_cos = sin * sin / (1.0 + cos);
    let k = |s2: f64, rho: f64| 2.0 * s2 / ((rho * rho + s2) * (rho * rho + s2));
    let misaligned = (one_minus_cos / k(speed * speed, rho) - 1.0)
        .abs()
        .max((on - 1.0).abs());
    if misaligned > SLAVED {
        return None;
    }
    let i0 = speed * speed - g * g;
    // A first-order look (dI/dg ≈ 4(I + g²)) before the integral: most steps of a crawl are
    // still too close to call, and this is called on every one.
    let rough = 4.0 * (i0 * g + g * g * g / 3.0);
    if (i0 - rough).abs() < 0.5 * rough * (3.0 * misaligned + speed) {
        return None;
    }
    let i = carry(i0, g);
    let loss = i0 - i;
    let doubt = loss * (3.0 * misaligned + speed) + 1e-16;
    if i > doubt {
        Some(Fate::Escapes { h: 0.5 * i })
    } else if i < -doubt {
        Some(Fate::Sticks { h: 0.5 * i })
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::escape_speed;
    use crate::{Initial, Outcome, Run, Settings};

    /// Releases 1e-6 and 1e-8 either side of v_e(0.5, 0): where the slow manifold first gives
    /// a verdict it is the one the run reaches, well before the run does. The H it predicts at
    /// ξ = 1 settles as s shrinks (its first guess, at s ≈ 0.02, is within 10 % of its last,
    /// inside the doubt it allows for), and lies next to the run's own H: just below it on the
    /// last step it reads (H only decreases), or just above it at the stop.
    #[test]
    fn the_slow_manifold_foretells_the_outcome() {
        let ve = escape_speed(0.5, 0.0, Settings::dp54(1e-12), 1e-11)
            .unwrap()
            .value;
        for dv in [1e-6, -1e-6, 1e-8, -1e-8] {
            let mut run =
                Run::new(Initial::velocity(0.5, 0.0, ve + dv), Settings::default()).unwrap();
            let (mut first, mut last, mut h_inside) = (None, None, f64::NAN);
            while run.outcome() == Outcome::Running && run.tau() < 100.0 {
                run.step(100.0).unwrap();
                let s = run.state();
                let f = fate(&s).map(|f| (f, s.tau));
                first = first.or(f);
                last = f.or(last);
                if f.is_some() {
                    h_inside = saddle_h(&s);
                }
            }
            let end = run.outcome();
            let ((f0, at), (f1, _)) = (first.unwrap(), last.unwrap());
            assert!(
                at < run.tau() - 1.0,
                "{dv:e}: told at {at}, ended at {}",
                run.tau()
            );
            match (f0, f1) {
                (Fate::Escapes { h: h0 }, Fate::Escapes { h: h1 }) => {
                    assert_eq!(end, Outcome::Escaped, "{dv:e}");
                    assert!((h0 - h1).abs() < 0.1 * h1, "{dv:e}: {h0:e} then {h1:e}");
                    assert!(
                        h1 < h_inside && h1 > 0.9 * h_inside,
                        "{dv:e}: {h1:e}, {h_inside:e}"
                    );
                }
                (Fate::Sticks { h: h0 }, Fate::Sticks { h: h1 }) => {
                    assert_eq!(end, Outcome::Stuck, "{dv:e}");
                    assert!(
                        (h0 - h1).abs() < 0.2 * h1.abs(),
                        "{dv:e}: {h0:e} then {h1:e}"
                    );
                    // H at the stop, −½(1 − ξ_rest)²: I/2 carried on to ξ = 1 lies a little
                    // above it (inside the stop I + g² < 0, so dI/dg < 0).
                    let rest = -0.5 * (1.0 - run.state().xi()).powi(2);
                    assert!(h1 > rest && h1 < 0.95 * rest, "{dv:e}: {h1:e}, {rest:e}");
                }
                other => panic!("{dv:e}: verdicts differ: {other:?}"),
            }
        }
    }
}
