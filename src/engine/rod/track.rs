//! A body run's path for the explorer: its step ends and phases, bounded in steps and states.

use super::RodRun;
use super::state::{Phase, RodState};
use crate::run::Outcome;
use crate::track::Track;

/// Most steps (accepted and rejected) a [`RodTrack`] takes: the explorer computes a track
/// inside a key press, so its cost is bounded whatever the release, to a frame: 50 000 steps
/// took 22 ms (200 000, 86 ms). Tracks need a few hundred: 2900 at most over 100 000 random
/// releases to τ = 20, 2098 over 40 000 followed to the view radius.
pub const TRACK_STEPS: u64 = 50_000;
/// Most states a [`RodTrack`] keeps: when it holds this many it keeps every other one (its
/// events and its end always), so a track of any length costs the same memory.
pub const TRACK_STATES: usize = 20_000;

/// Where a track stopped short of its run's end.
#[derive(Clone, Debug, PartialEq)]
pub enum Cut {
    /// [`TRACK_STEPS`] (or the budget given) ran out.
    Budget(u64),
    /// The run failed (its message); what came before is kept.
    Failed(String),
}

/// A body run's path for drawing it at any τ (the explorer's bar): its step ends, thinned to
/// at most [`TRACK_STATES`], each with the phase that holds from it on.
#[derive(Clone, Debug)]
pub struct RodTrack {
    pub l: f64,
    pub states: Vec<RodState>,
    /// `phases[k]`: the phase from `states[k]` until the next state.
    pub phases: Vec<Phase>,
    /// Stuck, Escaped (certified: the last state is the certificate's, or past it on a
    /// followed track), or Running: `tau_max` came first, or the track was cut before the
    /// certificate (see `cut`).
    pub outcome: Outcome,
    /// τ of the escape certificate (E < −½R²) where the run escapes: the escape's τ, whether
    /// or not the track goes on past it.
    pub escape: Option<f64>,
    /// The radius an escaping body is followed out to past its certificate (see
    /// [`RodTrack::from_run`]); None: the track ends at the certificate.
    pub follow_to: Option<f64>,
    /// Steps the run took.
    pub steps: u64,
    /// Why the track ends before its run did, if it does (on a followed track, possibly after
    /// the certificate: the escape stands, the drawing stops short).
    pub cut: Option<Cut>,
}

impl RodTrack {
    /// The track of `run` from where it stands, to rest, escape (followed on to its radius
    /// where [`RodRun::following`] says so) or `tau_max`, within `max_steps` and `max_states`
    /// (at least 4; the explorer's are [`TRACK_STEPS`] and [`TRACK_STATES`]); a run that fails
    /// or runs out of steps keeps what it computed, with `cut` saying so. The explorer's `RodTrack::from_run(RodRun::new(…)?.following(r), …)` draws
    /// an escaping body leaving, at the same cost bounds.
    pub fn from_run(mut run: RodRun, tau_max: f64, max_steps: u64, max_states: usize) -> RodTrack {
        let mut track = RodTrack {
            l: run.l,
            states: vec![],
            phases: vec![],
            outcome: Outcome::Running,
            escape: None,
            follow_to: run.follow_to,
            steps: 0,
            cut: None,
        };
        let mut keep = Track::new((run.state, run.phase), max_states);
        track.outcome = loop {
            if run.steps() >= max_steps {
                track.cut = Some(Cut::Budget(max_steps));
                break Outcome::Running;
            }
            let before = (run.state, run.phase);
            let end = match run.step(tau_max) {
                Ok(end) => end,
                Err(e) => {
                    track.cut = Some(Cut::Failed(e.to_string()));
                    break Outcome::Running;
                }
            };
            let s = run.state;
            let finite = [s.tau, s.q.x, s.q.y, s.u.x, s.u.y, s.psi, s.w]
                .iter()
                .all(|x| x.is_finite());
            if !finite {
                track.cut = Some(Cut::Failed(format!(
                    "the body's state is not finite after τ = {}",
                    before.0.tau
                )));
                break Outcome::Running;
            }
            if (s, run.phase) != before {
                keep.push((s, run.phase), run.phase != before.1);
            }
            if end != Outcome::Running {
                break end;
            }
            if s.tau >= tau_max {
                // At τ-max: once more, which only classifies (rest, the energy's certificate).
                break run.step(tau_max).unwrap_or(Outcome::Running);
            }
        };
        (track.states, track.phases) = keep.finish().into_iter().unzip();
        track.steps = run.steps();
        track.escape = run.certificate();
        if track.escape.is_some() {
            // Certified, whether or not the following reached its radius.
            track.outcome = Outcome::Escaped;
        }
        track
    }

    /// The body at `tau` (linear between kept states), at rest for ever once stuck; None past
    /// the end of an escaping, unfinished or cut run.
    pub fn at(&self, tau: f64) -> Option<RodState> {
        self.at_with_phase(tau).map(|(s, _)| s)
    }

    /// The state and phase at `tau` (the phase that holds from the kept state at or before
    /// it).
    pub fn at_with_phase(&self, tau: f64) -> Option<(RodState, Phase)> {
        let last = *self.states.last()?;
        let phase = |k: usize| self.phases.get(k).copied().unwrap_or(Phase::Slip);
        if tau >= last.tau {
            return (self.outcome == Outcome::Stuck || tau == last.tau)
                .then_some((RodState { tau, ..last }, phase(self.states.len() - 1)));
        }
        if tau.is_nan() {
            return None;
        }
        let k = self.states.partition_point(|s| s.tau <= tau).max(1);
        let (a, b) = (self.states[k - 1], self.states[k]);
        let t = if b.tau > a.tau {
            ((tau - a.tau) / (b.tau - a.tau)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let s = RodState {
            tau,
            q: a.q.lerp(b.q, t),
            u: a.u.lerp(b.u, t),
            psi: a.psi + (b.psi - a.psi) * t,
            w: a.w + (b.w - a.w) * t,
        };
        Some((s, phase(k - 1)))
    }

    /// An escaping track followed out to its radius: its last state, where the body left (the
    /// explorer keeps it there, as it keeps the point where its run stopped). None otherwise.
    pub fn left(&self) -> Option<RodState> {
        let last = *self.states.last()?;
        let out = self.follow_to.is_some_and(|r| last.q.length() >= r);
        (self.escape.is_some() && self.cut.is_none() && out).then_some(last)
    }

    /// Where the track ends: its last state's τ.
    pub fn end_tau(&self) -> f64 {
        self.states.last().map_or(0.0, |s| s.tau)
    }
}
