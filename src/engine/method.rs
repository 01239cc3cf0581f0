//! Integrators: the paper's fixed-step RK2 (Sec. IV, δt = 1e-3), classical RK4, and
//! Dormand–Prince 5(4) and 8(5,3) with step control and dense output (Hairer, Nørsett &
//! Wanner, *Solving ODEs I*, II.5 and the DOPRI5 and DOP853 codes).

use super::model::Frame;
use crate::error::Error;
use serde::{Deserialize, Serialize};
use strum::{Display, EnumMessage, EnumString, IntoStaticStr, VariantArray};

/// The integration methods on offer; names (`rk2-raw`, `dp54`, …) from the derives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[derive(Display, EnumString, IntoStaticStr, VariantArray, EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum Method {
    /// The paper's scheme as it made the figures: midpoint RK2, fixed step, no stick event.
    Rk2Raw,
    /// Midpoint RK2, fixed step, with stick events.
    Rk2,
    /// Classical RK4, fixed step, with stick events.
    Rk4,
    /// Adaptive Dormand–Prince 5(4), with stick events.
    #[default]
    Dp54,
    /// Adaptive Dormand–Prince 8(5,3) with seventh-order dense output, with stick events.
    Dop853,
}

impl Method {
    /// Whether the method sets its steps from a tolerance (dp54, dop853).
    pub fn adaptive(self) -> bool {
        matches!(self, Method::Dp54 | Method::Dop853)
    }
    /// Whether stops are located as events (all but the paper's raw scheme).
    pub fn stick_events(self) -> bool {
        self != Method::Rk2Raw
    }
}

/// Allowed ranges, so a typo cannot ask for an endless or meaningless run.
pub const DT_RANGE: (f64, f64) = (1e-7, 0.5);
pub const TOL_RANGE: (f64, f64) = (1e-14, 1e-2);

/// The integrator and the one knob that sets its accuracy: a fixed step dt for the
/// Runge–Kutta schemes, a tolerance for dp54 and dop853. No setting carries a value its method ignores.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scheme {
    Rk2Raw { dt: f64 },
    Rk2 { dt: f64 },
    Rk4 { dt: f64 },
    Dp54 { tol: f64 },
    Dop853 { tol: f64 },
}

/// The fixed-step Runge–Kutta rules.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FixedRk {
    /// The midpoint rule (the paper's second order).
    Midpoint,
    /// Classical fourth order.
    Classic,
}

impl Method {
    /// The default knob: tol 1e-10 for the adaptive methods, dt 1e-3 (the paper's) for the
    /// others.
    pub fn default_knob(self) -> f64 {
        if self.adaptive() { 1e-10 } else { 1e-3 }
    }
    /// This method with `knob` as its dt or tol.
    pub fn with(self, knob: f64) -> Scheme {
        match self {
            Method::Rk2Raw => Scheme::Rk2Raw { dt: knob },
            Method::Rk2 => Scheme::Rk2 { dt: knob },
            Method::Rk4 => Scheme::Rk4 { dt: knob },
            Method::Dp54 => Scheme::Dp54 { tol: knob },
            Method::Dop853 => Scheme::Dop853 { tol: knob },
        }
    }
}

impl Scheme {
    pub fn method(self) -> Method {
        match self {
            Scheme::Rk2Raw { .. } => Method::Rk2Raw,
            Scheme::Rk2 { .. } => Method::Rk2,
            Scheme::Rk4 { .. } => Method::Rk4,
            Scheme::Dp54 { .. } => Method::Dp54,
            Scheme::Dop853 { .. } => Method::Dop853,
        }
    }
    /// The dt or the tol.
    pub fn knob(self) -> f64 {
        match self {
            Scheme::Rk2Raw { dt } | Scheme::Rk2 { dt } | Scheme::Rk4 { dt } => dt,
            Scheme::Dp54 { tol } | Scheme::Dop853 { tol } => tol,
        }
    }
    pub fn with_knob(self, knob: f64) -> Scheme {
        self.method().with(knob)
    }
    /// The adaptive method's tolerance (None for the fixed-step schemes).
    pub fn tol(self) -> Option<f64> {
        match self {
            Scheme::Dp54 { tol } | Scheme::Dop853 { tol } => Some(tol),
            _ => None,
        }
    }
    /// The fixed-step rule and its dt (None for the adaptive methods).
    pub fn fixed(self) -> Option<(FixedRk, f64)> {
        match self {
            Scheme::Rk2Raw { dt } | Scheme::Rk2 { dt } => Some((FixedRk::Midpoint, dt)),
            Scheme::Rk4 { dt } => Some((FixedRk::Classic, dt)),
            Scheme::Dp54 { .. } | Scheme::Dop853 { .. } => None,
        }
    }
}

/// How the particle is coupled to the table. The paper's is dry friction with μ_s = μ_k
/// (Sec. II); the rest extends it (its Summary's closing remarks).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Coupling {
    /// Coulomb friction, Eq. (2), sliding at μ_k (the unit: μ_k g = 1). Extends the paper with
    /// static friction above kinetic: at rest on the table the particle holds while the friction
    /// it needs, the centripetal force ξ (Sec. II, property 1), is ≤ `hold` = μ_s/μ_k ≥ 1; the
    /// paper's is 1.
    Coulomb { hold: f64 },
    /// Stokes drag F = −γ m u instead (extends the paper: "Stokes' drag coupling", its
    /// Summary), γ in units of Ω. Linear, so solved in closed form (`engine::stokes`).
    Stokes { gamma: f64 },
}

impl Coupling {
    /// The paper's: μ_s = μ_k.
    pub const PAPER: Coupling = Coupling::Coulomb { hold: 1.0 };
    /// Largest μ_s/μ_k and γ accepted: far beyond any real surface, and small enough that
    /// squares stay finite.
    pub const MAX: f64 = 1e6;

    /// Checks the values a user may type: μ_s/μ_k in [1, MAX], γ in [0, MAX].
    pub fn validate(self) -> Result<(), Error> {
        use super::error::{Field, Range, check};
        let (field, x, lo) = match self {
            Coupling::Coulomb { hold } => (Field::MuStaticRatio, hold, 1.0),
            Coupling::Stokes { gamma } => (Field::Gamma, gamma, 0.0),
        };
        check(field, x, Range::Within(lo, Self::MAX))
    }
}

/// How a run is integrated — the user's speed/accuracy choice — and how the particle is
/// coupled to the table, which every run of a scene, solver or check shares.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "SettingsFile", into = "SettingsFile")]
pub struct Settings {
    pub scheme: Scheme,
    pub frame: Frame,
    /// Accepted plus rejected steps a run may take before it gives up.
    pub max_steps: u64,
    pub coupling: Coupling,
}

/// Settings as a scene file spells them: the method and its knob (`dt` or `tol`). Files
/// written before the knob belonged to the method carry both; the method's own is read.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SettingsFile {
    method: Method,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    dt: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tol: Option<f64>,
    #[serde(default)]
    frame: Frame,
    #[serde(default = "default_max_steps")]
    max_steps: u64,
    /// `coulomb` (the paper's) or `stokes`.
    #[serde(default, skip_serializing_if = "is_default")]
    coupling: CouplingName,
    /// μ_s/μ_k of Coulomb friction (default 1, the paper's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mu_static_ratio: Option<f64>,
    /// The Stokes drag rate γ, units of Ω (Stokes only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    gamma: Option<f64>,
}

/// A coupling's name in scene files and on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[derive(Display, EnumString, IntoStaticStr, VariantArray, EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum CouplingName {
    /// Dry friction (the paper's), with its static ratio mu_s/mu_k.
    #[default]
    Coulomb,
    /// Stokes drag −γ m u, with its rate γ.
    Stokes,
}

fn is_default<T: Default + PartialEq>(x: &T) -> bool {
    *x == T::default()
}

/// A coupling's parameter given to the coupling that does not take it, or missing. Its
/// message names the values as a scene file does (`gamma`, `mu_static_ratio`, `coupling`);
/// [`Mismatch::named`] as typed elsewhere.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}", self.named("gamma", "mu_static_ratio", "coupling"))]
pub enum Mismatch {
    /// γ with dry friction.
    GammaWithoutStokes,
    /// μ_s/μ_k with Stokes drag.
    RatioWithStokes,
    /// Stokes drag with no γ.
    StokesWithoutGamma,
}

impl Mismatch {
    /// The mismatch in words, with γ, μ_s/μ_k and the coupling called as typed.
    pub fn named(self, gamma: &str, ratio: &str, coupling: &str) -> String {
        match self {
            Mismatch::GammaWithoutStokes => {
                format!("{gamma} is the Stokes drag rate: it needs {coupling} stokes")
            }
            Mismatch::RatioWithStokes => format!(
                "{ratio} is a property of dry friction: it does not apply to {coupling} stokes"
            ),
            Mismatch::StokesWithoutGamma => {
                format!("{coupling} stokes needs {gamma}, the drag rate in units of Omega")
            }
        }
    }
}

impl CouplingName {
    /// The coupling named, with its parameter: μ_s/μ_k (Coulomb, default 1) or γ (Stokes,
    /// required). A parameter the coupling does not take is refused.
    pub fn with(
        self,
        mu_static_ratio: Option<f64>,
        gamma: Option<f64>,
    ) -> Result<Coupling, Mismatch> {
        match (self, mu_static_ratio, gamma) {
            (CouplingName::Coulomb, r, None) => Ok(Coupling::Coulomb {
                hold: r.unwrap_or(1.0),
            }),
            (CouplingName::Coulomb, _, Some(_)) => Err(Mismatch::GammaWithoutStokes),
            (CouplingName::Stokes, None, Some(gamma)) => Ok(Coupling::Stokes { gamma }),
            (CouplingName::Stokes, Some(_), _) => Err(Mismatch::RatioWithStokes),
            (CouplingName::Stokes, None, None) => Err(Mismatch::StokesWithoutGamma),
        }
    }
}

fn default_max_steps() -> u64 {
    Settings::default().max_steps
}

impl TryFrom<SettingsFile> for Settings {
    type Error = String;
    fn try_from(f: SettingsFile) -> Result<Self, String> {
        let knob = if f.method.adaptive() { f.tol } else { f.dt };
        Ok(Settings {
            scheme: f.method.with(knob.unwrap_or(f.method.default_knob())),
            frame: f.frame,
            max_steps: f.max_steps,
            coupling: f
                .coupling
                .with(f.mu_static_ratio, f.gamma)
                .map_err(|e| e.to_string())?,
        })
    }
}

impl From<Settings> for SettingsFile {
    fn from(s: Settings) -> Self {
        SettingsFile {
            method: s.method(),
            dt: s.scheme.fixed().map(|(_, dt)| dt),
            tol: s.scheme.tol(),
            frame: s.frame,
            max_steps: s.max_steps,
            coupling: match s.coupling {
                Coupling::Coulomb { .. } => CouplingName::Coulomb,
                Coupling::Stokes { .. } => CouplingName::Stokes,
            },
            mu_static_ratio: match s.coupling {
                Coupling::Coulomb { hold } if hold != 1.0 => Some(hold),
                _ => None,
            },
            gamma: match s.coupling {
                Coupling::Stokes { gamma } => Some(gamma),
                Coupling::Coulomb { .. } => None,
            },
        }
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            scheme: Scheme::Dp54 { tol: 1e-10 },
            frame: Frame::Lab,
            max_steps: 20_000_000,
            coupling: Coupling::PAPER,
        }
    }
}

impl Settings {
    /// The paper's own integration: raw RK2 at δt = 1e-3 (Sec. IV).
    pub fn paper() -> Self {
        Settings::fixed(Method::Rk2Raw, 1e-3)
    }
    pub fn dp54(tol: f64) -> Self {
        Settings {
            scheme: Scheme::Dp54 { tol },
            ..Settings::default()
        }
    }
    pub fn fixed(method: Method, dt: f64) -> Self {
        Settings {
            scheme: method.with(dt),
            ..Settings::default()
        }
    }
    pub fn method(&self) -> Method {
        self.scheme.method()
    }
    pub fn validate(&self) -> Result<(), Error> {
        use super::error::{Field, Range, check};
        let (field, (lo, hi), k) = match self.scheme.tol() {
            Some(tol) => (Field::Tol, TOL_RANGE, tol),
            None => (Field::Dt, DT_RANGE, self.scheme.knob()),
        };
        check(field, k, Range::Within(lo, hi))?;
        check(Field::MaxSteps, self.max_steps as f64, Range::AtLeast(1.0))?;
        self.coupling.validate()?;
        if self.hold() != 1.0 && !self.method().stick_events() {
            return Err(Error::refused(format!(
                "{} is the paper's scheme, with mu_s = mu_k and no stops: a static friction ratio mu_s/mu_k other than 1 needs a method with stick events",
                self.method()
            )));
        }
        Ok(())
    }
    /// μ_s/μ_k: the largest ξ at which a particle at rest on the table holds (Sec. II,
    /// property 1, extended; 1 for the paper, and for Stokes drag, which never holds).
    pub fn hold(&self) -> f64 {
        match self.coupling {
            Coupling::Coulomb { hold } => hold,
            Coupling::Stokes { .. } => 1.0,
        }
    }
    /// The Stokes drag rate γ, if the coupling is Stokes drag.
    pub fn stokes(&self) -> Option<f64> {
        match self.coupling {
            Coupling::Stokes { gamma } => Some(gamma),
            Coupling::Coulomb { .. } => None,
        }
    }
}
