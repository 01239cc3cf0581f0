//! The appendix's finite body (extends the paper's point particle): its size, and the
//! appendix's two order-of-magnitude conditions for treating it as a point — no toppling,
//! μh/L ≪ 1 (Appendix, from N₂ = mg/2 + μmg h/L), and no in-plane rotation, L ≪ r (Appendix,
//! from α ≲ μg/r against a′ ∼ μg).
//!
//! Units: lengths in R_max = μ_k g/Ω², as everywhere. That sets μ_k g = 1, not μ_k = 1: the
//! planar motion sees only the product μ_k g, while toppling weighs friction against weight,
//! F/(mg), in which μ_k itself appears. So the toppling number is μ_k f h/L, with f the
//! friction at the state in units of μ_k m g (1 while sliding; at rest on the table, the
//! centripetal force it supplies, ξ ≤ μ_s/μ_k). μ_k comes from a real table (`[units]`,
//! `--mu`); without one the paper's "μ is typically of order 1 or less" makes μ_k = 1 an upper
//! bound, and the number shown is that bound.

use super::error::Error;
use super::method::{Coupling, Settings};
use super::model::Initial;
use super::units::Units;
use serde::{Deserialize, Serialize};

/// The body's size and its rod's angle, as a scene's `[body]` or `--body-length`,
/// `--body-height`, `--body-angle` give them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// Lateral size L: the rod between the two masses m/2 (Appendix, Fig. 8), units of R_max.
    pub length: f64,
    /// Height h (Appendix, Fig. 7), units of R_max; unset, toppling is not judged.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// The rod's angle ψ at release in the table frame, from radially outward, counterclockwise
    /// (rad), measured like φ.
    #[serde(default)]
    pub angle: f64,
}

/// Where "≪ 1" ends: a condition above this says the point model is out of its depth. The
/// appendix's estimates are orders of magnitude; a tenth is the usual reading of "much less".
pub const MUCH_LESS: f64 = 0.1;

/// Where the body tips in the appendix's own model: N₁ = mg/2 − μmg h/L reaches 0 at
/// μh/L = ½, and the trailing contact leaves the table.
pub const TIPS: f64 = 0.5;

/// How a condition stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// ≤ [`MUCH_LESS`]: the point model holds.
    Ok,
    /// Above [`MUCH_LESS`]: not ≪ 1, the point model is out of its depth.
    NotSmall,
    /// μh/L ≥ [`TIPS`]: by the appendix's balance a contact lifts off.
    Tips,
}

impl Verdict {
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Ok => "≪ 1 ok",
            Verdict::NotSmall => "not ≪ 1",
            Verdict::Tips => "tips over",
        }
    }
}

/// The appendix's two conditions at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conditions {
    /// μ_k f h/L (None without a height or without friction to judge, e.g. Stokes drag).
    pub topple: Option<f64>,
    /// Whether μ_k = 1 was assumed (no real table given): then `topple` is an upper bound.
    pub mu_assumed: bool,
    /// L/ξ (infinite at the centre).
    pub rotation: f64,
}

impl Conditions {
    pub fn topple_verdict(&self) -> Option<Verdict> {
        self.topple.map(|t| {
            if t >= TIPS {
                Verdict::Tips
            } else if t > MUCH_LESS {
                Verdict::NotSmall
            } else {
                Verdict::Ok
            }
        })
    }
    pub fn rotation_verdict(&self) -> Verdict {
        if self.rotation > MUCH_LESS {
            Verdict::NotSmall
        } else {
            Verdict::Ok
        }
    }
    /// Whether the point model is out of its depth: either condition is not ≪ 1.
    pub fn out_of_depth(&self) -> bool {
        self.rotation_verdict() != Verdict::Ok
            || self.topple_verdict().is_some_and(|v| v != Verdict::Ok)
    }
}

impl Body {
    /// Largest length or height accepted, in R_max (far beyond any table, and squares stay
    /// finite).
    pub const MAX: f64 = 1e6;
    /// Smallest length accepted, in R_max: with h ≤ MAX and μ ≤ 10 the toppling number μh/L
    /// stays finite (at most 1e16), and a body this small is a point to every digit shown.
    pub const MIN_LENGTH: f64 = 1e-9;

    /// Checks the values a user may type: MIN_LENGTH ≤ L ≤ MAX, 0 ≤ h ≤ MAX,
    /// |ψ| ≤ [`Initial::MAX`].
    pub fn validate(&self) -> Result<(), Error> {
        use super::error::{Field, Range, check};
        check(
            Field::BodyLength,
            self.length,
            Range::Within(Self::MIN_LENGTH, Self::MAX),
        )?;
        if let Some(h) = self.height {
            check(Field::BodyHeight, h, Range::Within(0.0, Self::MAX))?;
        }
        check(
            Field::BodyAngle,
            self.angle,
            Range::Within(-Initial::MAX, Initial::MAX),
        )
    }

    /// The same body on the table `to`, its metres held (it was on `from`): its length and
    /// height in R_max recomputed, kept within (0, [`Body::MAX`]]. A larger μ: a larger
    /// R_max, so a shorter L.
    pub fn carried(self, from: &Units, to: &Units) -> Body {
        let k = from.r_max_m() / to.r_max_m();
        let keep = |x: f64| (x * k).clamp(f64::MIN_POSITIVE, Self::MAX);
        Body {
            length: keep(self.length),
            height: self.height.map(|h| if h == 0.0 { 0.0 } else { keep(h) }),
            angle: self.angle,
        }
    }

    /// The appendix's conditions at distance `xi` from the centre with friction `friction` in
    /// units of μ_k m g (None: no dry friction to judge), on a table of kinetic coefficient
    /// `mu` (None: unknown, taken as its bound 1).
    pub fn conditions(&self, xi: f64, friction: Option<f64>, mu: Option<f64>) -> Conditions {
        let mu_k = mu.unwrap_or(1.0);
        Conditions {
            topple: self
                .height
                .zip(friction)
                .map(|(h, f)| mu_k * f * h / self.length),
            mu_assumed: mu.is_none(),
            rotation: if xi > 0.0 {
                self.length / xi
            } else {
                f64::INFINITY
            },
        }
    }
}

/// The friction at a state in units of μ_k m g, for [`Body::conditions`]: 1 while sliding; at
/// rest on the table the centripetal force it supplies, ξ (Sec. II, property 1); 0 with μ = 0;
/// None under Stokes drag, which is no friction to weigh against the weight.
pub fn friction(settings: &Settings, frictionless: bool, stuck: bool, xi: f64) -> Option<f64> {
    match settings.coupling {
        _ if frictionless => Some(0.0),
        Coupling::Stokes { .. } => None,
        Coupling::Coulomb { .. } if stuck => Some(xi),
        Coupling::Coulomb { .. } => Some(1.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body(length: f64, height: Option<f64>) -> Body {
        Body {
            length,
            height,
            angle: 0.0,
        }
    }

    /// The appendix's numbers: μh/L from its torque balance, L/r from its rotation estimate,
    /// and the verdicts at the documented thresholds.
    #[test]
    fn conditions_are_the_appendixs_ratios() {
        let b = body(0.02, Some(0.004));
        // Sliding (f = 1) on a table of μ = 0.5: μh/L = 0.5 · 0.2 = 0.1, just ≪ 1.
        let c = b.conditions(0.4, Some(1.0), Some(0.5));
        assert!((c.topple.unwrap() - 0.1).abs() < 1e-15);
        assert!(!c.mu_assumed);
        assert_eq!(c.topple_verdict(), Some(Verdict::Ok));
        assert!((c.rotation - 0.05).abs() < 1e-15);
        assert_eq!(c.rotation_verdict(), Verdict::Ok);
        assert!(!c.out_of_depth());
        // No μ given: the bound μ_k = 1, h/L = 0.2, not ≪ 1.
        let c = b.conditions(0.4, Some(1.0), None);
        assert!(c.mu_assumed);
        assert_eq!(c.topple, Some(0.2));
        assert_eq!(c.topple_verdict(), Some(Verdict::NotSmall));
        assert!(c.out_of_depth());
        // At rest at ξ = 0.5 the friction is the centripetal 0.5: half the sliding number.
        let c = b.conditions(0.5, Some(0.5), None);
        assert!((c.topple.unwrap() - 0.1).abs() < 1e-15);
        // A tall body tips at μh/L = ½ (N₁ = 0).
        let tall = body(0.02, Some(0.01));
        let c = tall.conditions(0.4, Some(1.0), None);
        assert_eq!(c.topple_verdict(), Some(Verdict::Tips));
        // Close to the centre, L/ξ grows past a tenth; at the centre it is infinite.
        let c = b.conditions(0.1, Some(1.0), Some(0.1));
        assert!((c.rotation - 0.2).abs() < 1e-15);
        assert!(c.out_of_depth());
        assert_eq!(b.conditions(0.0, None, None).rotation, f64::INFINITY);
        // Without a height, or under Stokes drag, toppling is not judged.
        assert_eq!(
            body(0.02, None).conditions(0.4, Some(1.0), None).topple,
            None
        );
        assert_eq!(b.conditions(0.4, None, None).topple_verdict(), None);
    }

    #[test]
    fn bad_sizes_are_refused() {
        for b in [
            body(0.0, None),
            body(-1.0, None),
            body(f64::NAN, None),
            body(f64::INFINITY, None),
            body(2e6, None),
            body(0.1, Some(-0.1)),
            body(0.1, Some(f64::NAN)),
            Body {
                angle: f64::INFINITY,
                ..body(0.1, None)
            },
        ] {
            assert!(b.validate().is_err(), "{b:?}");
        }
        assert!(body(1e-6, Some(0.0)).validate().is_ok());
    }
}
