//! The engine's own errors: it knows nothing of processes, exit codes or how a value was typed
//! (`crate::error` maps these to exit codes, `crate::check` names a value as the user typed
//! it: `--v0`, `[initial] v0`), so the engine depends on no other part of the crate. A value
//! refused keeps its field, the value and the range it missed, never a flag's name.

use super::model::Initial;
use super::run::RunError;
use std::borrow::Cow;
use std::fmt;

/// A value the engine checks, by what it is (not by how it was typed).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Field {
    /// Release radius ξ0 (units of R_max).
    Xi0,
    /// Direction of the release velocity φ (rad).
    Phi,
    /// Release speed v0 (units of μg/Ω).
    V0,
    /// An adaptive method's tolerance.
    Tol,
    /// A fixed-step method's step.
    Dt,
    /// A run's step budget.
    MaxSteps,
    /// μ_s/μ_k, the static friction's ratio to the kinetic.
    MuStaticRatio,
    /// Stokes drag's rate γ.
    Gamma,
    /// The friction coefficient μ of a real table.
    Mu,
    /// A real table's speed (rpm).
    Rpm,
    /// Gravity g (m/s²).
    G,
    /// A finite body's length L.
    BodyLength,
    /// A finite body's height h.
    BodyHeight,
    /// A finite body's angle ψ.
    BodyAngle,
    /// A solver's target width: how close the ends of the bracket it certifies may be.
    Bracket,
    /// The table's angular acceleration Ω̇ as it spins up (units of Ω_ref², `spinup`).
    SpinRate,
    /// The table's rate when the spin-up starts (units of Ω_ref, `spinup`).
    Omega0,
}

impl Field {
    /// Every field, for tables that name them all.
    pub const ALL: [Field; 17] = [
        Field::Xi0,
        Field::Phi,
        Field::V0,
        Field::Tol,
        Field::Dt,
        Field::MaxSteps,
        Field::MuStaticRatio,
        Field::Gamma,
        Field::Mu,
        Field::Rpm,
        Field::G,
        Field::BodyLength,
        Field::BodyHeight,
        Field::BodyAngle,
        Field::Bracket,
        Field::SpinRate,
        Field::Omega0,
    ];

    /// The engine's own name for the value (the paper's symbol, in ASCII).
    pub fn name(self) -> &'static str {
        match self {
            Field::Xi0 => "xi0",
            Field::Phi => "phi",
            Field::V0 => "v0",
            Field::Tol => "tol",
            Field::Dt => "dt",
            Field::MaxSteps => "max_steps",
            Field::MuStaticRatio => "mu_static_ratio",
            Field::Gamma => "gamma",
            Field::Mu => "mu",
            Field::Rpm => "rpm",
            Field::G => "g",
            Field::BodyLength => "body length",
            Field::BodyHeight => "body height",
            Field::BodyAngle => "body angle",
            Field::Bracket => "bracket width",
            Field::SpinRate => "spin rate",
            Field::Omega0 => "omega0",
        }
    }

    /// What the value means or its unit, where its name alone does not say (shown after the
    /// name, whichever it is).
    pub fn gloss(self) -> &'static str {
        match self {
            Field::MuStaticRatio => " (mu_s/mu_k)",
            Field::Gamma => " (Stokes drag rate, units of Omega)",
            Field::BodyLength | Field::BodyHeight => " (units of R_max)",
            Field::BodyAngle => " (rad)",
            Field::SpinRate => " (dOmega/dtau, units of Omega_ref^2)",
            Field::Omega0 => " (units of Omega_ref)",
            _ => "",
        }
    }
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The values a field takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// Any finite number.
    Finite,
    /// x ≥ the bound.
    AtLeast(f64),
    /// x ≤ the bound.
    AtMost(f64),
    /// x > the bound.
    Above(f64),
    /// lo ≤ x ≤ hi.
    Within(f64, f64),
}

impl Range {
    /// Whether `x` lies in the range (never a NaN).
    pub fn contains(self, x: f64) -> bool {
        match self {
            Range::Finite => x.is_finite(),
            Range::AtLeast(lo) => x >= lo,
            Range::AtMost(hi) => x <= hi,
            Range::Above(lo) => x > lo,
            Range::Within(lo, hi) => (lo..=hi).contains(&x),
        }
    }
}

/// A range's bound as messages show it: plain near 1, else in exponent form (1e-14, 1e6).
fn bound(x: f64) -> String {
    if x == 0.0 || (0.1..1e4).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Range::Finite => write!(f, "be a finite number"),
            Range::AtLeast(lo) => write!(f, "be ≥ {}", bound(lo)),
            Range::AtMost(hi) => write!(f, "be ≤ {}", bound(hi)),
            Range::Above(lo) => write!(f, "be > {}", bound(lo)),
            Range::Within(lo, hi) => write!(f, "lie in [{}, {}]", bound(lo), bound(hi)),
        }
    }
}

/// A value refused: which, what it was, the range it missed, and (rarely) why that range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Invalid {
    pub field: Field,
    pub value: f64,
    pub range: Range,
    /// Why the range is what it is, where that is not the value's own (empty, or ` for …`).
    pub why: &'static str,
}

impl Invalid {
    /// `field` = `value` refused, for missing `range`.
    pub fn new(field: Field, value: f64, range: Range) -> Invalid {
        Invalid {
            field,
            value,
            range,
            why: "",
        }
    }

    /// The refusal with the value called `name` (as the user typed it: `--v0`, `[initial] v0`).
    pub fn named(&self, name: &str) -> String {
        format!(
            "{name}{} must {}{}, got {}",
            self.field.gloss(),
            self.range,
            self.why,
            Initial::show(self.value)
        )
    }
}

impl fmt::Display for Invalid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.named(self.field.name()))
    }
}

impl std::error::Error for Invalid {}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A value out of its range: initial conditions, settings, a table, a body, solver bounds.
    #[error(transparent)]
    Invalid(#[from] Invalid),
    /// Input refused as a whole, though each value lies in its range: a combination the
    /// engine does not take (a frictionless body, static friction for the paper's scheme).
    #[error("{0}")]
    Refused(Cow<'static, str>),
    /// A run that could not finish: its step budget, or a step size that underflowed.
    #[error(transparent)]
    Run(#[from] RunError),
    /// A solver (or the body's run) that found no answer.
    #[error("{0}")]
    NoAnswer(Cow<'static, str>),
    /// A solver stopped by its caller between runs (see [`super::solve::GoOn`]).
    #[error("cancelled")]
    Cancelled,
}

impl Error {
    /// `field` = `value` refused, for missing `range`.
    pub fn invalid(field: Field, value: f64, range: Range) -> Error {
        Error::Invalid(Invalid::new(field, value, range))
    }

    /// Input refused as a whole, with why.
    pub fn refused(why: impl Into<Cow<'static, str>>) -> Error {
        Error::Refused(why.into())
    }

    /// Whether this is input refused (rather than work that could not be done).
    pub fn is_refusal(&self) -> bool {
        matches!(self, Error::Invalid(_) | Error::Refused(_))
    }
}

/// `x` as `field`, refused unless in `range`.
pub fn check(field: Field, x: f64, range: Range) -> Result<(), Error> {
    if range.contains(x) {
        Ok(())
    } else {
        Err(Error::invalid(field, x, range))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_refused_value_keeps_its_field_value_and_range() {
        let e = Error::invalid(Field::Rpm, -1.0, Range::Within(1e-6, 1e6));
        assert_eq!(
            e,
            Error::Invalid(Invalid {
                field: Field::Rpm,
                value: -1.0,
                range: Range::Within(1e-6, 1e6),
                why: ""
            })
        );
        assert_eq!(e.to_string(), "rpm must lie in [1e-6, 1e6], got -1");
        assert!(e.is_refusal());
        assert!(!Error::Cancelled.is_refusal());
    }

    #[test]
    fn a_value_is_named_as_asked_with_its_gloss() {
        let i = Invalid::new(Field::MuStaticRatio, 0.5, Range::Within(1.0, 1e6));
        assert_eq!(
            i.named("[settings] mu_static_ratio"),
            "[settings] mu_static_ratio (mu_s/mu_k) must lie in [1, 1e6], got 0.5"
        );
        assert_eq!(
            i.to_string(),
            "mu_static_ratio (mu_s/mu_k) must lie in [1, 1e6], got 0.5"
        );
    }

    #[test]
    fn ranges_hold_what_they_say() {
        assert!(Range::Finite.contains(1e300) && !Range::Finite.contains(f64::NAN));
        assert!(Range::AtLeast(0.0).contains(0.0) && !Range::AtLeast(0.0).contains(-1e-300));
        assert!(Range::AtMost(1e12).contains(1e12) && !Range::AtMost(1e12).contains(1e13));
        assert!(!Range::Above(0.0).contains(0.0));
        assert!(!Range::Within(1.0, 2.0).contains(f64::NAN));
        assert_eq!(
            check(Field::Dt, 0.6, Range::Within(1e-7, 0.5))
                .unwrap_err()
                .to_string(),
            "dt must lie in [1e-7, 0.5], got 0.6"
        );
        assert_eq!(Range::AtLeast(0.0).to_string(), "be ≥ 0");
        assert_eq!(Range::AtMost(1e12).to_string(), "be ≤ 1e12");
    }

    /// Each of the engine's checks refuses a value by its field and the range it missed.
    #[test]
    fn the_engines_checks_carry_field_value_and_range() {
        use crate::body::Body;
        use crate::units::Units;
        use crate::{Coupling, Settings};
        let invalid = |r: Result<(), Error>| match r {
            Err(Error::Invalid(i)) => (i.field, i.value, i.range),
            other => panic!("{other:?}"),
        };
        let release = |xi0, phi, v0| Initial::velocity(xi0, phi, v0).validate();
        assert_eq!(
            invalid(release(-1.0, 0.0, 0.5)),
            (Field::Xi0, -1.0, Range::AtLeast(0.0))
        );
        assert_eq!(
            invalid(release(0.5, f64::NAN, 0.5)).0,
            Field::Phi,
            "a NaN phi"
        );
        assert_eq!(
            invalid(release(0.5, 0.0, 1e13)),
            (Field::V0, 1e13, Range::AtMost(Initial::MAX))
        );
        let units = |mu, rpm, g| Units::new(mu, rpm, g).map(|_| ());
        assert_eq!(
            invalid(units(0.1, 1e7, 9.81)),
            (Field::Rpm, 1e7, Range::Within(Units::MIN, 1e6))
        );
        assert_eq!(invalid(units(0.1, 33.0, 0.0)).0, Field::G);
        let body = Body {
            length: 1.0,
            height: Some(-1.0),
            angle: 0.0,
        };
        assert_eq!(
            invalid(body.validate()),
            (Field::BodyHeight, -1.0, Range::Within(0.0, Body::MAX))
        );
        let s = Settings {
            max_steps: 0,
            ..Settings::default()
        };
        assert_eq!(
            invalid(s.validate()),
            (Field::MaxSteps, 0.0, Range::AtLeast(1.0))
        );
        let s = Settings {
            coupling: Coupling::Coulomb { hold: 0.5 },
            ..Settings::default()
        };
        assert_eq!(invalid(s.validate()).0, Field::MuStaticRatio);
        let e = crate::solve::check_escape_xi0(1e12).unwrap_err();
        assert_eq!(
            invalid(Err(e.clone())),
            (
                Field::Xi0,
                1e12,
                Range::AtMost(crate::solve::MAX_ESCAPE_XI0)
            )
        );
        assert!(e.to_string().contains("for an escape speed"), "{e}");
        let e = crate::solve::escape_speed(0.5, 0.0, Settings::default(), 0.0);
        assert_eq!(
            invalid(e.map(|_| ())),
            (Field::Bracket, 0.0, Range::Above(0.0))
        );
    }

    /// A combination refused is input refused too; a run's failure and a solver's are not.
    #[test]
    fn refusals_are_told_from_failures() {
        let mut s = crate::Settings::paper();
        s.coupling = crate::Coupling::Coulomb { hold: 2.0 };
        let e = s.validate().unwrap_err();
        assert!(matches!(e, Error::Refused(_)) && e.is_refusal(), "{e:?}");
        let e = Error::from(RunError::StepUnderflow { tau: 1.0 });
        assert!(!e.is_refusal());
        assert!(!Error::NoAnswer("none".into()).is_refusal());
    }

    #[test]
    fn no_field_is_named_like_a_flag() {
        for f in Field::ALL {
            assert!(!f.name().contains('-'), "{}", f.name());
        }
    }
}
