//! One validation for every way a value comes in: flags, scene files (and their pins), the
//! configuration file. Each value passes through one function here ([`release`], [`units`],
//! [`body`]), whose ranges are the engine's own checks; what differs between the sources is
//! only the name an error gives the value, which is the one the user typed (`--v0`,
//! `[initial] v0`, `[units] rpm`), see [`Via`]. Key scripts carry no physical values (their
//! keys move them in steps the app keeps in range), only counts the script parser bounds.

use crate::engine::body::Body;
use crate::engine::error::Field;
use crate::engine::units::Units;
use crate::engine::{Coupling, Initial, Settings};
use crate::error::Error;

/// Largest |φ| taken (rad): beyond it the angle's remainder mod 2π has lost its digits.
pub const PHI_MAX: f64 = 1e6;

/// Where a value was typed, which names it in errors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Via {
    /// Command-line flags: `--xi0`, `--rpm`.
    Flags,
    /// A scene file: `[initial] xi0`, `[settings] tol`, `[units] rpm`, `[body] length`.
    Scene,
    /// A pin in a scene file: `[pins.initial] xi0`, `[pins.units] rpm`.
    Pin,
    /// The configuration file: `[units] rpm`.
    Config,
    /// The explorer's prompt (`:`): `v0`, `rpm`, as typed there.
    Prompt,
}

/// The values the engine checks by their flags' names (see [`flag`]), and each value's name
/// in a scene or configuration file.
const KEYS: [(&str, &str); 18] = [
    ("frictionless", "[initial] frictionless"),
    ("coupling", "[settings] coupling"),
    ("xi0", "[initial] xi0"),
    ("phi", "[initial] phi"),
    ("v0", "[initial] v0"),
    ("tol", "[settings] tol"),
    ("dt", "[settings] dt"),
    ("max-steps", "[settings] max_steps"),
    ("mu-static-ratio", "[settings] mu_static_ratio"),
    ("gamma", "[settings] gamma"),
    ("mu", "[units] mu"),
    ("rpm", "[units] rpm"),
    ("g", "[units] g"),
    ("body-length", "[body] length"),
    ("body-height", "[body] height"),
    ("body-angle", "[body] angle"),
    ("rate", "[spin] rate"),
    ("omega0", "[spin] omega0"),
];

impl Via {
    /// The value the engine calls `key`, as it is typed here.
    pub fn name(self, key: &str) -> String {
        match self {
            Via::Flags => format!("--{key}"),
            Via::Prompt => key.to_string(),
            Via::Scene | Via::Config | Via::Pin => {
                let typed = KEYS
                    .iter()
                    .find(|(k, _)| *k == key)
                    .map_or_else(|| key.to_string(), |(_, typed)| typed.to_string());
                match self {
                    Via::Pin => typed.replacen('[', "[pins.", 1),
                    _ => typed,
                }
            }
        }
    }
}

/// A value the engine checks, by the name of its flag (without `--`), which [`KEYS`] maps
/// to its key in a file; `None` for the solvers' bracket width, whose flag each command
/// names itself (`--vtol`, `--xtol`).
pub fn flag(f: Field) -> Option<&'static str> {
    Some(match f {
        Field::Xi0 => "xi0",
        Field::Phi => "phi",
        Field::V0 => "v0",
        Field::Tol => "tol",
        Field::Dt => "dt",
        Field::MaxSteps => "max-steps",
        Field::MuStaticRatio => "mu-static-ratio",
        Field::Gamma => "gamma",
        Field::Mu => "mu",
        Field::Rpm => "rpm",
        Field::G => "g",
        Field::BodyLength => "body-length",
        Field::BodyHeight => "body-height",
        Field::BodyAngle => "body-angle",
        Field::SpinRate => "rate",
        Field::Omega0 => "omega0",
        Field::Bracket => return None,
    })
}

impl Via {
    /// The engine's `field` as it is typed here (its own name if it has no flag).
    pub fn field(self, f: Field) -> String {
        flag(f).map_or_else(|| f.name().to_string(), |k| self.name(k))
    }
}

/// `e` with a value the engine refused named as typed `via` (unless it is already named).
pub fn named(e: impl Into<Error>, via: Via) -> Error {
    e.into().name_field(|f| via.field(f))
}

/// `e` with a refused `field` called `to`: a value checked as another (the sweeps'
/// `--xi0-max` as a release's `--xi0`).
pub fn retyped(e: Error, field: Field, to: &str) -> Error {
    match e {
        Error::Invalid { value: Some(r), .. } if r.value.field == field => {
            Error::named(r.value, to)
        }
        e => e,
    }
}

/// A release: finite, 0 ≤ ξ0, v0 ≤ `Initial::MAX`, |φ| ≤ [`PHI_MAX`].
pub fn initial(i: &Initial, via: Via) -> Result<(), Error> {
    i.validate().map_err(|e| named(e, via))?;
    if i.phi.abs() > PHI_MAX {
        return Err(Error::invalid(format!(
            "{} must lie in [-{PHI_MAX:e}, {PHI_MAX:e}] rad, got {}",
            via.name("phi"),
            Initial::show(i.phi)
        )));
    }
    Ok(())
}

/// Integrator and coupling settings: the method's knob in its range, a step budget, the
/// coupling's value.
pub fn settings(s: &Settings, via: Via) -> Result<(), Error> {
    s.validate().map_err(|e| named(e, via))
}

/// A release with its settings: each as above, and no coupling to the table for a
/// frictionless release (μ = 0 is no friction and no drag).
pub fn release(i: &Initial, s: &Settings, via: Via) -> Result<(), Error> {
    initial(i, via)?;
    settings(s, via)?;
    if i.frictionless && s.coupling != Coupling::PAPER {
        let on = match via {
            Via::Flags => "",
            _ => " = true",
        };
        let n = |k| via.name(k);
        return Err(Error::invalid(format!(
            "{}{on} is mu = 0, no coupling to the table at all: drop {}, {} and {}",
            n("frictionless"),
            n("coupling"),
            n("gamma"),
            n("mu-static-ratio")
        )));
    }
    Ok(())
}

/// A real table: μ, rpm and g in ranges where every scale (R_max, 1/Ω, the unit of speed)
/// and every length, time and speed shown in SI stays a finite, non-zero number.
pub fn units(u: &Units, via: Via) -> Result<Units, Error> {
    Units::new(u.mu, u.rpm, u.g).map_err(|e| named(e, via))
}

/// A finite body's size and angle.
pub fn body(b: &Body, via: Via) -> Result<(), Error> {
    b.validate().map_err(|e| named(e, via))
}

/// A spin-up (`engine::spinup`): its ramp, and a coin at rest at ξ0 under settings it takes
/// (dry friction, stick events).
pub fn spin(
    r: &crate::engine::spinup::Ramp,
    xi0: f64,
    s: &Settings,
    via: Via,
) -> Result<(), Error> {
    crate::engine::spinup::SpinRun::new(*r, xi0, *s)
        .map(|_| ())
        .map_err(|e| named(e, via))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_value_as_typed() {
        let i = Initial::velocity(0.5, 1e300, 0.6);
        let e = |via| initial(&i, via).unwrap_err().to_string();
        assert!(
            e(Via::Flags).starts_with("--phi must lie in"),
            "{}",
            e(Via::Flags)
        );
        assert!(
            e(Via::Scene).starts_with("[initial] phi must"),
            "{}",
            e(Via::Scene)
        );
        let i = Initial::velocity(0.5, 0.0, 1e13);
        let e = initial(&i, Via::Flags).unwrap_err();
        assert_eq!(
            retyped(e, Field::V0, "--v0-max").to_string(),
            "--v0-max must be ≤ 1e12, got 1e13"
        );
        let u = Units {
            mu: 0.1,
            rpm: -1.0,
            g: 9.81,
        };
        assert!(
            units(&u, Via::Config)
                .unwrap_err()
                .to_string()
                .starts_with("[units] rpm must")
        );
    }
}
