//! The work–precision tasks: what each measures, on which cases, against which cross-check of
//! the reference, and over which settings of each method's knob.

use super::runs::{finish, state_at};
use super::{Config, FAR_TAU, REST_TAU, reference};
use crate::analysis::angle;
use crate::engine::solve::escape_speed;
use crate::engine::{Frame, Initial, Method, Outcome, Settings};
use crate::error::Error;
use glam::DVec2;
use serde::{Serialize, Serializer};
use strum::{Display, VariantArray};

/// Escape speeds in the rows are found to this tolerance.
pub(super) const ESCAPE_VTOL: f64 = 1e-8;
const DRIFT_TAU: f64 = 20.0;
const SMOOTH_TAU: f64 = 0.5;

/// The tasks of the work–precision table, in the order they run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Display, VariantArray)]
pub enum Task {
    /// Rest position (table frame) and stop time of every case.
    #[strum(to_string = "rest")]
    Rest,
    /// The same near the rim: releases at ξ0 = 0.99 … 0.9999 moving out at up to 0.9999 of
    /// the speed that would carry them to ξ = 1, where a stop comes slowly and late (issue 35).
    /// The reference takes no closed form there but stops within its tolerance: the stretch
    /// before the stop is integrated in implicit steps (`tests/suite/rim_times.rs` checks it
    /// against an independent form).
    #[strum(to_string = "rim stops")]
    Rim,
    /// Case A's position at τ = 0.5, before its stop: a smooth stretch.
    #[strum(to_string = "A@τ=0.5")]
    Smooth,
    /// Positions at τ = 20, long after most stops: does the particle creep?
    #[strum(to_string = "drift τ=20")]
    Drift,
    /// An escape followed to τ = 400 (ξ ~ 1e4): the error relative to the distance.
    #[strum(to_string = "far τ=400 (rel)")]
    Far,
    /// The escape speed at ξ0 = 0.5, φ = 0 (Sec. IV).
    #[strum(to_string = "v_e(0.5,0)")]
    Escape,
    /// One Fig. 5 curve: v_e over the angles at ξ0 = 0.5.
    #[strum(to_string = "fig5 ξ0=0.5")]
    Fig5,
}

impl Serialize for Task {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// One case's result under one setting.
#[derive(Clone, Copy, Debug)]
pub(super) struct Measure {
    /// Stuck or escaped (rest task only: it is what the others' values assume).
    pub(super) outcome: Option<Outcome>,
    /// The quantity compared: a position, or (v_e, 0). None where it has no meaning (the
    /// rest task's escaping cases).
    pub(super) value: Option<DVec2>,
    /// The stop time (rest task, stuck cases).
    pub(super) tau: Option<f64>,
    pub(super) evals: u64,
}

/// |a − b|, relative to |b| far out (the far escape runs to ξ ~ 1e4).
pub(super) fn distance(a: DVec2, b: DVec2) -> f64 {
    let e = (a - b).length();
    if b.length() > 10.0 { e / b.length() } else { e }
}

/// The cross-check of the reference across stops: dp54 at 1e-12 in the other frame
/// (`sim::ending::reference_check`, the page's too).
fn stop_check() -> Settings {
    crate::sim::ending::reference_check(Settings::default())
}

/// A setting as the table names it: method, knob, and the frame when not the lab's.
pub(super) fn label(s: Settings) -> String {
    let frame = if s.frame == Frame::Table {
        " table frame"
    } else {
        ""
    };
    format!("{} {}{frame}", s.method(), crate::present::accuracy(&s))
}

impl Task {
    /// The releases measured: all seeded cases for the rest, a few for the others.
    pub(super) fn cases(self, cfg: &Config, all: &[Initial]) -> Vec<Initial> {
        let at = |phi| Initial::velocity(0.5, phi, 0.0);
        match self {
            Task::Rest => all.to_vec(),
            Task::Rim => [0.99, 0.999, 0.9999]
                .into_iter()
                .flat_map(|xi0| {
                    [0.5, 0.99, 0.9999].map(|f| Initial::velocity(xi0, 0.0, f * (1.0 - xi0)))
                })
                .collect(),
            Task::Smooth => all[..1].to_vec(),
            Task::Drift => all.iter().take(3 + cfg.cases.min(20)).copied().collect(),
            Task::Far => vec![Initial::velocity(0.5, 0.4, 1.5)],
            Task::Escape => vec![at(0.0)],
            Task::Fig5 => {
                let n = if cfg.quick { 12 } else { 72 };
                (0..n).map(|i| at(angle(i, n))).collect()
            }
        }
    }

    /// The second method the reference is checked against.
    pub(super) fn check(self) -> Settings {
        match self {
            Task::Rest | Task::Rim | Task::Drift | Task::Escape => stop_check(),
            Task::Smooth => Settings::fixed(Method::Rk4, 1e-4),
            Task::Far => Settings::fixed(Method::Rk4, 1e-3),
            Task::Fig5 => Settings::dp54(1e-11),
        }
    }

    /// Whether the task measures escape speeds.
    pub(super) fn escape(self) -> bool {
        matches!(self, Task::Escape | Task::Fig5)
    }

    /// The escape-speed tolerance of the reference and its check (escape tasks only).
    pub(super) fn reference_vtol(self) -> f64 {
        if self == Task::Fig5 { 1e-9 } else { 1e-10 }
    }

    /// Whether the task times stops (the τ columns).
    pub(super) fn times_stops(self) -> bool {
        matches!(self, Task::Rest | Task::Rim)
    }

    /// The settings measured: each method over its knob, within what the task can afford.
    pub(super) fn settings(self, cfg: &Config) -> Vec<Settings> {
        let fixed = |methods: &[Method], dts: &[f64]| -> Vec<Settings> {
            methods
                .iter()
                .flat_map(|&m| dts.iter().map(move |&dt| Settings::fixed(m, dt)))
                .collect()
        };
        // Both adaptive methods over the same tolerances, for their crossover.
        let dp54 = |keep: &dyn Fn(f64) -> bool| -> Vec<Settings> {
            [Method::Dp54, Method::Dop853]
                .into_iter()
                .flat_map(|m| {
                    cfg.tols()
                        .into_iter()
                        .filter(|t| keep(*t))
                        .map(move |t| Settings {
                            scheme: m.with(t),
                            ..Settings::default()
                        })
                })
                .collect()
        };
        let all = [Method::Rk2Raw, Method::Rk2, Method::Rk4];
        let smooth = [Method::Rk2, Method::Rk4];
        let (fixed, dp) = match self {
            Task::Rest | Task::Rim | Task::Smooth | Task::Drift => {
                (fixed(&all, &cfg.dts()), dp54(&|_| true))
            }
            Task::Far => {
                let min = if cfg.quick { 1e-2 } else { 1e-3 };
                let dts: Vec<f64> = cfg.dts().into_iter().filter(|&d| d >= min).collect();
                (fixed(&all, &dts), dp54(&|_| true))
            }
            Task::Escape => {
                let dts: &[f64] = if cfg.quick {
                    &[1e-2]
                } else {
                    &[1e-2, 3e-3, 1e-3]
                };
                (fixed(&smooth, dts), dp54(&|t| !cfg.quick || t >= 1e-10))
            }
            Task::Fig5 => {
                let dts: &[f64] = if cfg.quick { &[] } else { &[1e-2] };
                let even = |t: f64| t.log10().round() as i32 % 2 == 0;
                let keep = |t: f64| t <= 1e-4 && (!cfg.quick || t >= 1e-10) && even(t);
                (fixed(&smooth, dts), dp54(&keep))
            }
        };
        fixed.into_iter().chain(dp).collect()
    }

    /// One case under one setting.
    pub(super) fn measure(
        self,
        initial: Initial,
        settings: Settings,
        vtol: f64,
    ) -> Result<Measure, Error> {
        let tau = match self {
            Task::Rest | Task::Rim => {
                let e = finish(initial, settings, REST_TAU)?;
                let stuck = e.outcome == Outcome::Stuck;
                return Ok(Measure {
                    outcome: Some(e.outcome),
                    value: stuck.then_some(e.q),
                    tau: stuck.then_some(e.tau),
                    evals: e.evals,
                });
            }
            Task::Escape | Task::Fig5 => {
                let t = escape_speed(initial.xi0, initial.phi, settings, vtol)?;
                return Ok(Measure {
                    outcome: None,
                    value: Some(DVec2::new(t.value, 0.0)),
                    tau: None,
                    evals: t.rhs_evals,
                });
            }
            Task::Smooth => SMOOTH_TAU,
            Task::Drift => DRIFT_TAU,
            Task::Far => FAR_TAU,
        };
        let (s, evals) = state_at(initial, settings, tau)?;
        Ok(Measure {
            outcome: None,
            value: Some(s.r),
            tau: None,
            evals,
        })
    }
}

/// How far the values of two measures of one case lie apart; infinitely far when the
/// outcomes differ.
pub(super) fn value_error(a: &Measure, b: &Measure) -> f64 {
    if a.outcome != b.outcome {
        return f64::INFINITY;
    }
    match (a.value, b.value) {
        (Some(x), Some(y)) => distance(x, y),
        _ => 0.0,
    }
}

/// How far two measures of one case lie apart in value and stop time.
pub(super) fn apart(a: &Measure, b: &Measure) -> f64 {
    let t = match (a.tau, b.tau) {
        (Some(x), Some(y)) => (x - y).abs(),
        _ => 0.0,
    };
    value_error(a, b).max(t)
}

/// Error of the position at τ = `tau` of `initial` with a fixed-step method at `dt`, against
/// the reference: for measuring the order of the fixed-step methods on a smooth stretch.
pub fn position_error(initial: Initial, method: Method, dt: f64, tau: f64) -> Result<f64, Error> {
    let (r, _) = state_at(initial, reference(), tau)?;
    let (s, _) = state_at(initial, Settings::fixed(method, dt), tau)?;
    Ok((s.r - r.r).length())
}
