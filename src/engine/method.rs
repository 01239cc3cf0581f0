//! Integrators: the paper's fixed-step RK2 (Sec. IV, δt = 1e-3), classical RK4, and
//! Dormand–Prince 5(4) with PI step control and dense output (Hairer, Nørsett & Wanner,
//! *Solving ODEs I*, II.5 and the DOPRI5 code).

use super::model::{Frame, Initial, Y};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
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
}

impl Method {
    pub const ALL: [Method; 4] = [Method::Rk2Raw, Method::Rk2, Method::Rk4, Method::Dp54];
    pub fn name(self) -> &'static str {
        match self {
            Method::Rk2Raw => "rk2-raw",
            Method::Rk2 => "rk2",
            Method::Rk4 => "rk4",
            Method::Dp54 => "dp54",
        }
    }
    pub fn adaptive(self) -> bool {
        self == Method::Dp54
    }
    /// Whether stops are located as events (all but the paper's raw scheme).
    pub fn stick_events(self) -> bool {
        self != Method::Rk2Raw
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| format!("unknown method '{s}' (dp54, rk4, rk2, rk2-raw)"))
    }
}

/// Allowed ranges, so a typo cannot ask for an endless or meaningless run.
pub const DT_RANGE: (f64, f64) = (1e-7, 0.5);
pub const TOL_RANGE: (f64, f64) = (1e-14, 1e-2);

/// The integrator and the one knob that sets its accuracy: a fixed step dt for the
/// Runge–Kutta schemes, a tolerance for dp54. No setting carries a value its method ignores.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scheme {
    Rk2Raw { dt: f64 },
    Rk2 { dt: f64 },
    Rk4 { dt: f64 },
    Dp54 { tol: f64 },
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
    /// The default knob: tol 1e-10 for dp54, dt 1e-3 (the paper's) for the others.
    pub fn default_knob(self) -> f64 {
        if self == Method::Dp54 { 1e-10 } else { 1e-3 }
    }
    /// This method with `knob` as its dt or tol.
    pub fn with(self, knob: f64) -> Scheme {
        match self {
            Method::Rk2Raw => Scheme::Rk2Raw { dt: knob },
            Method::Rk2 => Scheme::Rk2 { dt: knob },
            Method::Rk4 => Scheme::Rk4 { dt: knob },
            Method::Dp54 => Scheme::Dp54 { tol: knob },
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
        }
    }
    /// The dt or the tol.
    pub fn knob(self) -> f64 {
        match self {
            Scheme::Rk2Raw { dt } | Scheme::Rk2 { dt } | Scheme::Rk4 { dt } => dt,
            Scheme::Dp54 { tol } => tol,
        }
    }
    pub fn with_knob(self, knob: f64) -> Scheme {
        self.method().with(knob)
    }
    /// dp54's tolerance (None for the fixed-step schemes).
    pub fn tol(self) -> Option<f64> {
        match self {
            Scheme::Dp54 { tol } => Some(tol),
            _ => None,
        }
    }
    /// The fixed-step rule and its dt (None for dp54).
    pub fn fixed(self) -> Option<(FixedRk, f64)> {
        match self {
            Scheme::Rk2Raw { dt } | Scheme::Rk2 { dt } => Some((FixedRk::Midpoint, dt)),
            Scheme::Rk4 { dt } => Some((FixedRk::Classic, dt)),
            Scheme::Dp54 { .. } => None,
        }
    }
}

/// How a run is integrated: the user's speed/accuracy choice.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "SettingsFile", into = "SettingsFile")]
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

impl TryFrom<SettingsFile> for Settings {
    type Error = String;
    fn try_from(f: SettingsFile) -> Result<Self, String> {
        let knob = match f.method {
            Method::Dp54 => f.tol,
            _ => f.dt,
        };
        Ok(Settings {
            scheme: f.method.with(knob.unwrap_or(f.method.default_knob())),
            frame: f.frame,
            max_steps: f.max_steps,
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
    pub fn validate(&self) -> Result<(), String> {
        let (name, (lo, hi), k) = match self.scheme {
            Scheme::Dp54 { tol } => ("tol", TOL_RANGE, tol),
            s => ("dt", DT_RANGE, s.knob()),
        };
        if !(k.is_finite() && (lo..=hi).contains(&k)) {
            return Err(format!(
                "{name} must lie in [{lo:e}, {hi:e}], got {}",
                Initial::show(k)
            ));
        }
        if self.max_steps == 0 {
            return Err("max-steps must be at least 1".into());
        }
        Ok(())
    }
    /// "dt=1e-3" or "tol=1e-10": the knob that sets this method's accuracy.
    pub fn accuracy_label(&self) -> String {
        match self.scheme {
            Scheme::Dp54 { tol } => format!("tol={tol:.0e}"),
            s => format!("dt={:.0e}", s.knob()),
        }
    }
}

/// Work done by a run: what the speed side of the trade costs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Cost {
    pub steps: u64,
    pub rejected: u64,
    pub rhs_evals: u64,
}

/// Continuous extension of one step, for events and for sampling between steps.
#[derive(Clone, Copy, Debug)]
pub enum Dense {
    /// DOPRI5's fourth-order interpolant (Hairer's `contd5` coefficients).
    Dp5([Y; 5]),
    /// Cubic Hermite from the end values and slopes (fixed-step methods).
    Hermite { f0: Y, f1: Y },
}

/// One accepted step, in the integrator's frame, from `t0` to `t0 + h`.
#[derive(Clone, Copy, Debug)]
pub struct Segment {
    pub t0: f64,
    pub h: f64,
    pub y0: Y,
    pub y1: Y,
    pub dense: Dense,
}

impl Segment {
    pub fn t1(&self) -> f64 {
        self.t0 + self.h
    }
    /// The solution at `t` in [t0, t0 + h].
    pub fn at(&self, t: f64) -> Y {
        if self.h <= 0.0 {
            return self.y1;
        }
        let s = ((t - self.t0) / self.h).clamp(0.0, 1.0);
        let s1 = 1.0 - s;
        match self.dense {
            Dense::Dp5(r) => r[0] + (r[1] + (r[2] + (r[3] + r[4] * s1) * s) * s1) * s,
            Dense::Hermite { f0, f1 } => {
                let (h00, h10) = ((1.0 + 2.0 * s) * s1 * s1, s * s1 * s1);
                let (h01, h11) = (s * s * (3.0 - 2.0 * s), -s * s * s1);
                self.y0 * h00 + f0 * (h10 * self.h) + self.y1 * h01 + f1 * (h11 * self.h)
            }
        }
    }
}

/// A fixed step of `rk` from `y` with slope `f0 = f(y)`; returns the new point.
/// `evals` counts right-hand-side evaluations beyond `f0`.
pub fn fixed_step(rk: FixedRk, rhs: impl Fn(Y) -> Y, y: Y, f0: Y, h: f64, evals: &mut u64) -> Y {
    match rk {
        FixedRk::Midpoint => {
            *evals += 1;
            y + rhs(y + f0 * (0.5 * h)) * h
        }
        FixedRk::Classic => {
            *evals += 3;
            let k2 = rhs(y + f0 * (0.5 * h));
            let k3 = rhs(y + k2 * (0.5 * h));
            let k4 = rhs(y + k3 * h);
            y + (f0 + (k2 + k3) * 2.0 + k4) * (h / 6.0)
        }
    }
}

// Dormand–Prince 5(4) tableau (Hairer's DOPRI5).
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// The size of `e` in the max norm over the components, each against tol·(1 + |y|) at the
/// larger of its two ends: stricter than Hairer's RMS, which near the saddle ξ ≈ 1 lets the
/// error of one component hide behind the others.
fn err_norm(y0: Y, y1: Y, e: Y, tol: f64) -> f64 {
    let comp = |a: f64, b: f64, d: f64| (d / (tol + tol * a.abs().max(b.abs()))).abs();
    comp(y0.p.x, y1.p.x, e.p.x)
        .max(comp(y0.p.y, y1.p.y, e.p.y))
        .max(comp(y0.w.x, y1.w.x, e.w.x))
        .max(comp(y0.w.y, y1.w.y, e.w.y))
}

/// One DOPRI5 trial step: the new point, its slope (FSAL), the scaled error norm and the
/// dense-output coefficients. Six new right-hand-side evaluations.
pub struct Dp5Trial {
    pub y1: Y,
    pub f1: Y,
    pub err: f64,
    pub dense: Dense,
}

pub fn dp5_step(rhs: impl Fn(Y) -> Y, y: Y, k1: Y, h: f64, tol: f64) -> Dp5Trial {
    let k2 = rhs(y + k1 * (h * A21));
    let k3 = rhs(y + (k1 * A31 + k2 * A32) * h);
    let k4 = rhs(y + (k1 * A41 + k2 * A42 + k3 * A43) * h);
    let k5 = rhs(y + (k1 * A51 + k2 * A52 + k3 * A53 + k4 * A54) * h);
    let k6 = rhs(y + (k1 * A61 + k2 * A62 + k3 * A63 + k4 * A64 + k5 * A65) * h);
    let y1 = y + (k1 * A71 + k3 * A73 + k4 * A74 + k5 * A75 + k6 * A76) * h;
    let k7 = rhs(y1);
    let e = (k1 * E1 + k3 * E3 + k4 * E4 + k5 * E5 + k6 * E6 + k7 * E7) * h;
    let err = err_norm(y, y1, e, tol);
    let dy = y1 - y;
    let bspl = k1 * h - dy;
    let dense = Dense::Dp5([
        y,
        dy,
        bspl,
        dy - k7 * h - bspl,
        (k1 * D1 + k3 * D3 + k4 * D4 + k5 * D5 + k6 * D6 + k7 * D7) * h,
    ]);
    Dp5Trial {
        y1,
        f1: k7,
        err,
        dense,
    }
}

/// Hairer's starting step (`hinit` of DOPRI5; Hairer, Nørsett & Wanner, Sec. II.4): an Euler
/// probe of size h0 = 0.01·|y|/|f| measures how fast f changes, and the first step is sized so
/// that its fifth-order error would be 0.01·tol. One right-hand-side evaluation.
pub fn initial_step(rhs: impl Fn(Y) -> Y, y: Y, f0: Y, tol: f64) -> f64 {
    let norm = |v: Y| err_norm(y, y, v, tol);
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
        (0.01 / d).powf(0.2)
    };
    (100.0 * h0).min(h1)
}

/// Plain DOPRI5 from `y` over `[0, t_end]`, with no events: for smooth systems such as the
/// frictionless equations ([`Frame::rhs_free`]). Returns the end point and the number of
/// right-hand-side evaluations, or `None` if the step size underflows.
pub fn dp54_plain(rhs: impl Fn(Y) -> Y, y: Y, t_end: f64, tol: f64) -> Option<(Y, u64)> {
    let (mut y, mut f, mut t) = (y, rhs(y), 0.0);
    let mut h = initial_step(&rhs, y, f, tol);
    let mut evals = 2;
    let mut ctrl = Controller::default();
    while t < t_end {
        if h < 1e-14 * t.max(1.0) {
            return None;
        }
        let step = h.min(t_end - t);
        let trial = dp5_step(&rhs, y, f, step, tol);
        evals += 6;
        let (hnew, accepted) = ctrl.next(step, trial.err);
        if accepted {
            (y, f, t) = (trial.y1, trial.f1, t + step);
        }
        h = hnew;
    }
    Some((y, evals))
}

/// Hairer's PI step-size controller (β = 0.04, safety 0.9, factor in [0.2, 10]).
#[derive(Clone, Copy, Debug)]
pub struct Controller {
    facold: f64,
    rejected_last: bool,
}

impl Default for Controller {
    fn default() -> Self {
        Controller {
            facold: 1e-4,
            rejected_last: false,
        }
    }
}

impl Controller {
    const BETA: f64 = 0.04;
    const SAFE: f64 = 0.9;
    /// The next step size after a trial of size `h` with error `err`; `true` if accepted.
    pub fn next(&mut self, h: f64, err: f64) -> (f64, bool) {
        let expo1 = 0.2 - Self::BETA * 0.75;
        let fac11 = err.max(1e-300).powf(expo1);
        if err <= 1.0 {
            let fac = (fac11 / self.facold.powf(Self::BETA) / Self::SAFE).clamp(0.1, 5.0);
            let mut hnew = h / fac;
            if self.rejected_last {
                hnew = hnew.min(h);
            }
            self.facold = err.max(1e-4);
            self.rejected_last = false;
            (hnew, true)
        } else {
            self.rejected_last = true;
            (h / (fac11 / Self::SAFE).min(5.0), false)
        }
    }
}
