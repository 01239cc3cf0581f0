//! The table's linear spin-up, Ω(τ) = Ω0 + a τ, and the closed forms of a coin at rest on it:
//! the friction it needs, where it slips, and the μ a student infers from the slip.

use crate::error::{Error, Field, Range, check};

/// The table's rate ramps linearly from `omega0` at `rate` (units of Ω_ref and Ω_ref²: see
/// the module's units).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ramp {
    /// Ω̇ = a > 0: a spin-up (a spin-down would need other certificates).
    pub rate: f64,
    /// Ω at τ = 0, ≥ 0.
    #[serde(default)]
    pub omega0: f64,
}

/// Where a coin at rest on the ramping table slips.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Onset {
    /// The friction it needs exceeds static friction at τ = 0 (Ω0 too high, or a ≥ μ_s g/r0).
    AtOnce,
    /// At τ, the table then turning at Ω.
    At { tau: f64, omega: f64 },
    /// Never: at the centre it needs no friction.
    Never,
}

impl Ramp {
    /// Largest rate and Ω0 accepted: far beyond any table, with Ω⁴ still finite.
    pub const MAX: f64 = 1e6;

    /// Checks the values: rate in (0, [`Ramp::MAX`]], Ω0 in [0, [`Ramp::MAX`]].
    pub fn validate(&self) -> Result<(), Error> {
        check(Field::SpinRate, self.rate, Range::Finite)?;
        check(Field::SpinRate, self.rate, Range::Above(0.0))?;
        check(Field::SpinRate, self.rate, Range::AtMost(Self::MAX))?;
        check(Field::Omega0, self.omega0, Range::Within(0.0, Self::MAX))
    }

    /// Ω(τ) = Ω0 + a τ.
    pub fn omega(&self, tau: f64) -> f64 {
        self.omega0 + self.rate * tau
    }

    /// The table's angle turned since τ = 0: Ω0 τ + ½ a τ².
    pub fn angle(&self, tau: f64) -> f64 {
        tau * (self.omega0 + 0.5 * self.rate * tau)
    }

    /// The friction per unit mass (units of μ_k g) that holds a coin at rest on the table at
    /// radius ξ at τ: the centripetal Ω²ξ and the tangential Ω̇ξ (the Euler force's balance),
    /// ξ √(Ω⁴ + Ω̇²).
    pub fn grip(&self, xi: f64, tau: f64) -> f64 {
        let w = self.omega(tau);
        xi * (w * w).hypot(self.rate)
    }

    /// The slip in closed form for a coin at rest at ξ0 under static friction `hold`
    /// (μ_s/μ_k): ξ0 √(Ω⁴ + a²) = hold, so Ω_slip⁴ = (hold/ξ0)² − a², which needs
    /// a < hold/ξ0 (else it slips at once).
    pub fn onset(&self, xi0: f64, hold: f64) -> Onset {
        if xi0 == 0.0 {
            return Onset::Never;
        }
        if self.grip(xi0, 0.0) > hold {
            return Onset::AtOnce;
        }
        let h = hold / xi0;
        // (h − a)(h + a): no cancellation in h² − a² when a is near h.
        let omega = ((h - self.rate) * (h + self.rate)).sqrt().sqrt();
        Onset::At {
            tau: (omega - self.omega0) / self.rate,
            omega,
        }
    }
}

/// The μ a student infers from the slip, ignoring the Euler force: μ = Ω_slip² r0 / g, in
/// units of μ_k (dimensionless: Ω_slip² ξ0). Below the true μ_s by the factor
/// √(1 − (a ξ0/μ_s)²): the ramp's tangential pull shares the friction.
pub fn inferred_mu(omega_slip: f64, xi0: f64) -> f64 {
    omega_slip * omega_slip * xi0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_closed_form_onset_needs_exactly_static_friction() {
        let ramp = Ramp {
            rate: 0.1,
            omega0: 0.2,
        };
        let Onset::At { tau, omega } = ramp.onset(0.5, 1.0) else {
            panic!()
        };
        assert!((ramp.omega(tau) - omega).abs() < 1e-15);
        assert!((ramp.grip(0.5, tau) - 1.0).abs() < 1e-14);
        // The student's μ, below the true 1 by √(1 − (a ξ0)²).
        let mu = inferred_mu(omega, 0.5);
        assert!((mu - (1.0 - 0.05f64 * 0.05).sqrt()).abs() < 1e-14, "{mu}");
        assert_eq!(ramp.onset(0.0, 1.0), Onset::Never);
        assert_eq!(
            Ramp {
                rate: 2.5,
                omega0: 0.0
            }
            .onset(0.5, 1.0),
            Onset::AtOnce
        );
        assert_eq!(
            Ramp {
                rate: 0.1,
                omega0: 1.5
            }
            .onset(0.5, 1.0),
            Onset::AtOnce
        );
    }

    #[test]
    fn a_ramp_is_checked() {
        for (rate, omega0) in [
            (0.0, 0.0),
            (-1.0, 0.0),
            (f64::NAN, 0.0),
            (1.0, -1.0),
            (1e7, 0.0),
        ] {
            assert!(Ramp { rate, omega0 }.validate().is_err(), "{rate} {omega0}");
        }
        assert!(
            Ramp {
                rate: 0.1,
                omega0: 0.0
            }
            .validate()
            .is_ok()
        );
    }
}
