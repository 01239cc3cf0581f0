//! Stokes drag instead of dry friction: F = −γ m u, u relative to the table (extends the
//! paper: its Summary's "Stokes' drag coupling indicates a completely different kind of
//! dynamics"). γ is in units of Ω; lengths keep the unit R_max of the table with friction, so
//! the same releases can be compared.
//!
//! In the rotating frame q′ = u, u′ = −2ẑ×u + q − γu (Sec. IV's Cartesian form with the
//! friction replaced): linear. Written with z = x + iy for q (ẑ× is a multiplication by i) it
//! is z″ + (2i + γ)z′ − z = 0, with characteristic roots λ± = c ± d/2, c = −(2i + γ)/2 and
//! d = √(γ(γ + 4i)) (principal root). Re λ+ > 0 > Re λ− for every γ > 0, so every release
//! leaves exponentially at the rate Re λ+ — except those with no growing part, z′(0) = λ− z(0)
//! (the centre at rest, and one speed and direction at each radius), which spiral into the
//! centre. At γ = 0 the roots meet at −i: the straight line in the lab (Newton's first law).
//!
//! Complex numbers are `DVec2` (x + iy): Cartesian, as everywhere in the engine.

use super::model::{Initial, State, rotate, zcross};
use super::roots::illinois;
use glam::DVec2;

fn mul(a: DVec2, b: DVec2) -> DVec2 {
    DVec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}

fn div(a: DVec2, b: DVec2) -> DVec2 {
    mul(a, DVec2::new(b.x, -b.y)) / b.length_squared()
}

fn exp(a: DVec2) -> DVec2 {
    DVec2::new(a.y.cos(), a.y.sin()) * a.x.exp()
}

/// cosh a and sinh(a)/a (the latter by its series near 0, where it is 1 + a²/6 + a⁴/120).
fn cosh_sinhc(a: DVec2) -> (DVec2, DVec2) {
    let (ch, sh) = (a.x.cosh(), a.x.sinh());
    let (c, s) = (a.y.cos(), a.y.sin());
    let cosh = DVec2::new(ch * c, sh * s);
    let sinhc = if a.length() < 1e-3 {
        let a2 = mul(a, a);
        DVec2::X + a2 / 6.0 + mul(a2, a2) / 120.0
    } else {
        div(DVec2::new(sh * c, ch * s), a)
    };
    (cosh, sinhc)
}

/// The roots λ+ (growing) and λ− of λ² + (2i + γ)λ − 1 = 0 — the paper's Sec. IV Cartesian
/// equations with Stokes drag for friction (extends the paper) — and Re λ+ computed without
/// the cancellation of −γ/2 + Re d/2 at large γ (where it is ≈ 1/γ).
pub fn roots(gamma: f64) -> (DVec2, DVec2, f64) {
    if gamma == 0.0 {
        return (-DVec2::Y, -DVec2::Y, 0.0);
    }
    // d = √(γ² + 4iγ): Re d = √((|w| + γ²)/2) with |w| = γ√(γ² + 16), Im d = 4γ/(2 Re d).
    // Re d as √γ √((|w|/γ + γ)/2): the product γ(√(γ² + 16) + γ)/2 underflows to 0 for a
    // subnormal γ (at 4.9e-324 Re d was 0, Im λ+ −∞, and every run overflowed), where
    // √γ does not.
    let root = (gamma * gamma + 16.0).sqrt();
    let re = gamma.sqrt() * (0.5 * (root + gamma)).sqrt();
    // Re λ+ = (Re d − γ)/2 = (Re d² − γ²)/(2(Re d + γ)), Re d² − γ² = 8γ/(√(γ² + 16) + γ),
    // and Im λ+ = −1 + γ/Re d = −(Re d − γ)/Re d: both free of the cancellation at large γ.
    let growth = 4.0 * gamma / ((root + gamma) * (re + gamma));
    let plus = DVec2::new(growth, -2.0 * growth / re);
    let minus = DVec2::new(-gamma - growth, -2.0 + 2.0 * growth / re);
    (plus, minus, growth)
}

/// The growth rate Re λ+ of every Stokes release that leaves (module docs): ≈ √(γ/2) for
/// small γ, ≈ 1/γ for large.
pub fn growth_rate(gamma: f64) -> f64 {
    roots(gamma).2
}

/// One release under Stokes drag, in closed form (extends the paper; module docs): the
/// paper's release (Figs. 3–5) with F = −γ m u for Eq. (2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stokes {
    gamma: f64,
    initial: Initial,
    /// Table-frame position and velocity at τ = 0, as complex numbers.
    z0: DVec2,
    w0: DVec2,
    c: DVec2,
    half_d: DVec2,
    /// z = A e^{λ+τ} + B e^{λ−τ} (γ > 0).
    a: DVec2,
    b: DVec2,
    plus: DVec2,
    minus: DVec2,
    growth: f64,
}

impl Stokes {
    pub fn new(gamma: f64, initial: Initial) -> Stokes {
        let s0 = initial.state();
        let (z0, w0) = (s0.q(), s0.u());
        let (plus, minus, growth) = roots(gamma);
        let c = 0.5 * (plus + minus);
        let half_d = 0.5 * (plus - minus);
        let (a, b) = if half_d == DVec2::ZERO {
            (DVec2::ZERO, DVec2::ZERO)
        } else {
            let d = 2.0 * half_d;
            (div(w0 - mul(minus, z0), d), div(mul(plus, z0) - w0, d))
        };
        Stokes {
            gamma,
            initial,
            z0,
            w0,
            c,
            half_d,
            a,
            b,
            plus,
            minus,
            growth,
        }
    }

    /// Re λ+: the rate at which the particle leaves ([`growth_rate`]).
    pub fn growth(&self) -> f64 {
        self.growth
    }

    /// Table-frame position q and velocity u at τ. Near the double root (|d|τ small) the
    /// form e^{cτ}[z0 cosh x + (w0 − c z0) τ sinh(x)/x], x = dτ/2, which has no cancellation;
    /// elsewhere A e^{λ+τ} + B e^{λ−τ}, which overflows only where the answer does.
    pub fn at(&self, tau: f64) -> (DVec2, DVec2) {
        let x = self.half_d * tau;
        if x.length() < 0.5 {
            let e = exp(self.c * tau);
            let (cosh, sinhc) = cosh_sinhc(x);
            let k = self.w0 - mul(self.c, self.z0);
            let z = mul(e, mul(self.z0, cosh) + mul(k, sinhc) * tau);
            let hd2 = mul(self.half_d, self.half_d);
            let w = mul(self.c, z) + mul(e, mul(mul(self.z0, hd2), sinhc) * tau + mul(k, cosh));
            (z, w)
        } else {
            let (ep, em) = (
                mul(self.a, exp(self.plus * tau)),
                mul(self.b, exp(self.minus * tau)),
            );
            (ep + em, mul(self.plus, ep) + mul(self.minus, em))
        }
    }

    /// The particle at τ, in the lab frame.
    pub fn state(&self, tau: f64) -> State {
        let (q, u) = self.at(tau);
        let r = rotate(q, tau);
        State {
            tau,
            r,
            v: rotate(u, tau) + zcross(r),
        }
    }

    /// When escape is certified: the first τ with ξ > 1 and ξ′ > 0, as under Coulomb friction
    /// (Sec. II, property 2). `None` if it never leaves.
    ///
    /// The drag's radial part is −γξ′ (the table moves tangentially), so Eq. (6) becomes
    /// ξ″ = ξθ′² − γξ′ ≥ −γξ′, and ξ′ ≥ ξ′(τ0)e^{−γ(τ−τ0)} > 0 from then on: ξ only grows. It
    /// grows without bound, as |z| ≥ |A e^{λ+τ}| − |B e^{λ−τ}| with A ≠ 0 (with A = 0, z → 0,
    /// so this never holds). Once it holds it holds for ever, so the τ at which it first holds
    /// is bracketed by doubling and located by Illinois.
    pub fn escape(&self) -> Option<f64> {
        if self.gamma == 0.0 {
            return self.initial.free_escape();
        }
        if self.a == DVec2::ZERO {
            return None;
        }
        let margin = |t: f64| {
            let (q, u) = self.at(t);
            let xi = q.length();
            (xi - 1.0).min(q.dot(u) / xi)
        };
        if margin(0.0) > 0.0 {
            return Some(0.0);
        }
        let mut hi = 1.0;
        // A NaN margin (past f64's range) is not positive either: doubling then stops below.
        while margin(hi).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            hi *= 2.0;
            if !self.at(hi).0.is_finite() {
                return None;
            }
        }
        let lo = if hi > 1.0 { 0.5 * hi } else { 0.0 };
        Some(illinois(margin, lo, hi, 1e-13))
    }
}
