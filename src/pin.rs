//! Pinned runs (`b`): a run kept on screen beside later ones, as a bounded, decimated path
//! computed once, when pinned, from its release and settings (never while drawing). A scene
//! saves a pin as its release; loading computes the path again, the same path.

use crate::engine::track::Track;
use crate::engine::units::Units;
use crate::engine::{Initial, Outcome, Run, Settings, State, Status};
use serde::{Deserialize, Serialize};

/// Most pins shown at once: a seventh replaces the oldest.
pub const MAX_PINS: usize = 6;
/// Most points a pin's path holds: at twice this the path keeps every other point (a
/// [`Track`] on a τ grid), so a run of any length costs the same memory.
pub const PIN_POINTS: usize = 1024;
/// Most steps a pin's run may take (rk2-raw chatters forever about a stop it has no event
/// for), and the latest τ it is followed to (μ = 0 at rest in the lab never leaves).
pub const PIN_STEPS: u64 = 200_000;
pub const PIN_TAU_MAX: f64 = 200.0;
/// Longest label (a scene's name is cut to it).
pub const LABEL_MAX: usize = 8;
/// The glyphs that tell pins apart without colour, one per pin slot.
pub const MARKERS: [char; MAX_PINS] = ['◆', '▲', '▼', '◇', '△', '▽'];

/// What a scene file holds of a pin: its label and the run's release, settings and turn.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PinSpec {
    /// Cleaned as read (`crate::text`).
    pub label: crate::text::Clean,
    pub initial: Initial,
    #[serde(default)]
    pub settings: Settings,
    /// How far the picture was turned when pinned (see `App::turn`).
    #[serde(default)]
    pub turn: f64,
    /// The real table it ran on, if SI units were on: drawn beside a run on another table,
    /// its lengths and times are converted to that table's units.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub units: Option<Units>,
}

/// A pinned run: its path on a τ grid (spacing 0.025 doubled as often as the bound needs),
/// ending exactly at its end: the stop, the point past the view where it left, or where its
/// budget ran out.
#[derive(Clone, Debug, PartialEq)]
pub struct Pin {
    pub spec: PinSpec,
    /// Its glyph along the path and at its end (one of [`MARKERS`]).
    pub marker: char,
    pub path: Vec<State>,
    pub outcome: Outcome,
}

impl Pin {
    /// Runs `spec` to its end at bounded cost: stuck, escaped past `view_radius`, [`PIN_TAU_MAX`]
    /// or [`PIN_STEPS`], whichever comes first.
    pub fn compute(
        spec: PinSpec,
        marker: char,
        view_radius: f64,
    ) -> Result<Pin, crate::error::Error> {
        let settings = Settings {
            max_steps: spec.settings.max_steps.min(PIN_STEPS),
            ..spec.settings
        };
        let mut run = Run::new(spec.initial, settings)?;
        // μ = 0 takes strides of 1000 τ in closed form: end it where it leaves the view.
        let tau_max = if spec.initial.frictionless {
            free_exit(&spec.initial, view_radius).min(PIN_TAU_MAX)
        } else {
            PIN_TAU_MAX
        };
        let mut path = Track::new(run.state(), 2 * PIN_POINTS);
        loop {
            let out = run.state().xi() > view_radius && run.escape().is_some();
            if out || !run.goes_on(tau_max, false) || run.step(tau_max).is_err() {
                break;
            }
            // The latest step's dense output (or the closed form) covers up to here.
            let end = match run.status() {
                Status::Stuck { tau, .. } => tau,
                Status::Slipping => run.tau(),
            };
            extend_to(&mut path, end, |t| run.state_at(t).ok());
        }
        let end = match run.status() {
            Status::Stuck { tau, q } => State::riding(q, tau),
            Status::Slipping => run.state(),
        };
        Ok(Pin {
            spec,
            marker,
            path: path.end_at(end, |s| s.tau),
            outcome: run.outcome(),
        })
    }

    /// Its lengths and times in the units of the table `now` (R_max and 1/Ω ratios): 1 and 1
    /// unless both it and `now` are real tables. (Each pin is drawn in its own table's
    /// rotating frame.)
    pub fn scale(&self, now: Option<Units>) -> (f64, f64) {
        match (self.spec.units, now) {
            (Some(p), Some(n)) => (p.r_max_m() / n.r_max_m(), p.t_s() / n.t_s()),
            _ => (1.0, 1.0),
        }
    }

    /// Where the run ended: its stop, or the last point followed.
    pub fn end(&self) -> State {
        self.path[self.path.len() - 1]
    }
}

/// μ = 0: when the straight line r0 + v τ reaches `radius` on its way out (∞ at rest in
/// the lab, or if it never does).
fn free_exit(initial: &Initial, radius: f64) -> f64 {
    let s0 = initial.state();
    let (r, v) = (s0.r, s0.v);
    let a = v.length_squared();
    let b = r.dot(v);
    let disc = b * b - a * (r.length_squared() - radius * radius);
    if a == 0.0 || disc < 0.0 {
        return f64::INFINITY;
    }
    ((-b + disc.sqrt()) / a).max(0.0)
}

/// `path` on its τ grid ([`crate::sim::TRAIL_DT`], its spacing doubled with each halving)
/// through `end`, the state at each grid point from `at` (its points between, which the
/// track would drop, are not computed).
fn extend_to(path: &mut Track<State>, end: f64, at: impl Fn(f64) -> Option<State>) {
    loop {
        let k = path.next_index();
        let t = k as f64 * crate::sim::TRAIL_DT;
        if t > end {
            return;
        }
        let Some(s) = at(t) else {
            return;
        };
        path.push_at(k, s);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Grid points are whole multiples of the spacing after any number of halvings, and the
    /// path never holds 2 × PIN_POINTS points.
    #[test]
    fn decimation_keeps_a_grid_and_a_bound() {
        let at = |t: f64| {
            Some(State {
                tau: t,
                r: glam::DVec2::X,
                v: glam::DVec2::ZERO,
            })
        };
        let mut d = Track::new(at(0.0).unwrap(), 2 * PIN_POINTS);
        extend_to(&mut d, 1000.0, at);
        assert!(d.len() < 2 * PIN_POINTS && d.len() >= PIN_POINTS / 2);
        let dt = d[1].tau - d[0].tau;
        for s in d.iter() {
            let k = s.tau / dt;
            assert!((k - k.round()).abs() < 1e-6, "{} off the grid {dt}", s.tau);
        }
        let last = d.last().unwrap().tau;
        assert!(1000.0 - last < dt + 1e-9, "{last}");
    }
}
