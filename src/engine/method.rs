//! Integrators: the paper's fixed-step RK2 (Sec. IV, δt = 1e-3), classical RK4, and
//! Dormand–Prince 5(4) and 8(5,3) with step control and dense output (Hairer, Nørsett &
//! Wanner, *Solving ODEs I*, II.5 and the DOPRI5 and DOP853 codes).

use super::model::{Frame, Initial};
use crate::engine::error::Error;
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

/// How a run is integrated: the user's speed/accuracy choice.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(from = "SettingsFile", into = "SettingsFile")]
pub struct Settings {
    pub scheme: Scheme,
    pub frame: Frame,
    /// Accepted plus rejected steps a run may take before it gives up.
    pub max_steps: u64,
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
}

fn default_max_steps() -> u64 {
    Settings::default().max_steps
}

impl From<SettingsFile> for Settings {
    fn from(f: SettingsFile) -> Self {
        let knob = if f.method.adaptive() { f.tol } else { f.dt };
        Settings {
            scheme: f.method.with(knob.unwrap_or(f.method.default_knob())),
            frame: f.frame,
            max_steps: f.max_steps,
        }
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
        }
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            scheme: Scheme::Dp54 { tol: 1e-10 },
            frame: Frame::Lab,
            max_steps: 20_000_000,
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
        let (name, (lo, hi), k) = match self.scheme.tol() {
            Some(tol) => ("tol", TOL_RANGE, tol),
            None => ("dt", DT_RANGE, self.scheme.knob()),
        };
        if !(k.is_finite() && (lo..=hi).contains(&k)) {
            return Err(Error::invalid(format!(
                "{name} must lie in [{lo:e}, {hi:e}], got {}",
                Initial::show(k)
            )));
        }
        if self.max_steps == 0 {
            return Err(Error::invalid("max-steps must be at least 1"));
        }
        Ok(())
    }
    /// "dt=1e-3" or "tol=1e-10": the knob that sets this method's accuracy.
    pub fn accuracy_label(&self) -> String {
        match self.scheme.tol() {
            Some(tol) => format!("tol={tol:.0e}"),
            None => format!("dt={:.0e}", self.scheme.knob()),
        }
    }
}
