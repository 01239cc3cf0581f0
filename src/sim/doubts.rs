//! Second opinions computed once a process: a run's [`doubt`](crate::engine::doubt::doubt)
//! hangs on nothing but what it reads of the run (its initial conditions, settings, outcome,
//! deciding state and snap bound), so every session holding the same run (a served class's
//! followers, each applying the presenter's ticks; students exploring the same scene; a run
//! restarted as it was) takes the one opinion the first of them computed. Each computing its
//! own cost a class 6–7 ms of CPU a follower at the one tick where the run stopped: 100
//! followers took both cores for a third of a second, and the presenter's keys waited behind.
//!
//! Beneath them, the runs of the Sundman-time form ([`FATES`]): a run's form is run at a
//! tolerance set by its settings' ([`crate::engine::doubt::sundman_tol`]: 1e-10 for every
//! adaptive tolerance from 1e-7 up, 1e-13 for every fixed step), so one release at many
//! settings (the work–precision page, the bench's rows, `run --error`'s ladder) asks for the
//! same few, each computed once here.

use crate::engine::doubt::{Doubt, decided_state, doubt_with};
use crate::engine::run::{Outcome, Run};
use crate::engine::sundman::{Ending, fate};
use crate::engine::{Initial, Release, Settings, State};
use crate::kept::Kept;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};

/// Opinions kept at most, the oldest going first.
const KEPT: usize = 64;

/// All that [`doubt`] reads of a run (the run itself is a function of its initial conditions
/// and settings, and where it was decided of the steps it took): runs equal in these have
/// the same second opinion, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Asked {
    initial: Initial,
    settings: Settings,
    outcome: Outcome,
    decided: State,
    snap_bound: f64,
    tau_max: f64,
}

impl Asked {
    fn of(run: &Run, tau_max: f64) -> Asked {
        Asked {
            initial: run.initial(),
            settings: run.settings(),
            outcome: run.outcome(),
            decided: decided_state(run),
            snap_bound: run.snap_bound(),
            tau_max,
        }
    }
}

/// The opinions asked for lately, each computed once: a session asking for one another is
/// computing waits for it rather than computing it again.
pub struct Doubts {
    kept: Kept<Asked, OnceLock<Doubt>>,
    computed: AtomicU64,
}

/// The process's: the sessions' runs ask here (see [`super::Sim`]).
pub static DOUBTS: Doubts = Doubts::new();

impl Doubts {
    pub const fn new() -> Doubts {
        Doubts {
            kept: Kept::new(KEPT),
            computed: AtomicU64::new(0),
        }
    }

    /// `doubt(run, tau_max)`, computed here once for every run equal in what it reads.
    pub fn of(&self, run: &Run, tau_max: f64) -> Doubt {
        let slot = self
            .kept
            .slot(&Asked::of(run, tau_max), |_| OnceLock::new());
        *slot.get_or_init(|| {
            self.computed.fetch_add(1, Ordering::Relaxed);
            second_opinion(run, tau_max)
        })
    }

    /// Opinions computed so far.
    #[cfg(test)]
    fn computed(&self) -> u64 {
        self.computed.load(Ordering::Relaxed)
    }

    /// Opinions kept now.
    #[cfg(test)]
    fn kept(&self) -> usize {
        self.kept.kept()
    }
}

impl Default for Doubts {
    fn default() -> Doubts {
        Doubts::new()
    }
}

/// `doubt(run, tau_max)`, its Sundman-time runs taken from [`FATES`]: the same opinion, bit
/// for bit.
pub fn second_opinion(run: &Run, tau_max: f64) -> Doubt {
    doubt_with(run, tau_max, &|i, hold, tol, limit, steps| {
        FATES.of(i, hold, tol, limit, steps)
    })
}

/// Runs of the Sundman-time form kept at most, the oldest going first: the bench's rim rows
/// ask for 9 releases × 6 tolerances over and over.
const FATES_KEPT: usize = 256;

/// All that [`fate`] reads, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
struct FateAsked {
    release: Release,
    frictionless: bool,
    /// ξ0, φ, v0, hold, tol.
    bits: [u64; 5],
    limit: u64,
    steps: u64,
}

impl FateAsked {
    fn of(i: &Initial, hold: f64, tol: f64, limit: f64, steps: u64) -> FateAsked {
        FateAsked {
            release: i.release,
            frictionless: i.frictionless,
            bits: [i.xi0, i.phi, i.v0, hold, tol].map(f64::to_bits),
            limit: limit.to_bits(),
            steps,
        }
    }
}

/// The runs of the Sundman-time form asked for lately, each computed once. One asked under
/// another time limit is that of a run that stopped or escaped before both limits: it took
/// the same steps to the same end ([`Ending::reach`]).
pub struct Fates {
    kept: Kept<FateAsked, OnceLock<Option<Ending>>>,
    computed: AtomicU64,
}

/// The process's: [`second_opinion`] asks here.
pub static FATES: Fates = Fates::new();

impl Fates {
    pub const fn new() -> Fates {
        Fates {
            kept: Kept::new(FATES_KEPT),
            computed: AtomicU64::new(0),
        }
    }

    /// `fate(i, hold, tol, limit, steps)`, computed here once.
    pub fn of(&self, i: &Initial, hold: f64, tol: f64, limit: f64, steps: u64) -> Option<Ending> {
        let asked = FateAsked::of(i, hold, tol, limit, steps);
        let fits = |a: &FateAsked, slot: &OnceLock<Option<Ending>>| {
            *a == asked
                || *a
                    == (FateAsked {
                        limit: a.limit,
                        ..asked
                    })
                    && slot
                        .get()
                        .copied()
                        .flatten()
                        .is_some_and(|e| e.outcome != Outcome::Running && e.reach < limit)
        };
        let slot = self.kept.slot_fitting(&asked, fits, |_| OnceLock::new());
        *slot.get_or_init(|| {
            self.computed.fetch_add(1, Ordering::Relaxed);
            fate(i, hold, tol, limit, steps)
        })
    }

    /// Runs computed so far.
    #[cfg(test)]
    fn computed(&self) -> u64 {
        self.computed.load(Ordering::Relaxed)
    }
}

impl Default for Fates {
    fn default() -> Fates {
        Fates::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::doubt::doubt;

    /// The default scene's run (Fig. 3 C: it stops just inside ξ = 1) at ξ0 + `dxi`, run to
    /// its end.
    fn ended(dxi: f64) -> Run {
        let initial = Initial::velocity(0.5 + dxi, 0.0, 0.6078);
        let mut run = Run::new(initial, Settings::default()).unwrap();
        run.run(100.0, true).unwrap();
        assert_ne!(run.outcome(), Outcome::Running);
        run
    }

    /// A run asked for again, or by another session holding the same run, is not computed
    /// again, and is what `doubt` says; another run is computed.
    #[test]
    fn an_opinion_is_computed_once_for_equal_runs() {
        let doubts = Doubts::new();
        let (a, b) = (ended(0.0), ended(0.0));
        let first = doubts.of(&a, 100.0);
        assert_eq!(first, doubt(&a, 100.0));
        assert_eq!(doubts.of(&b, 100.0), first);
        assert_eq!(doubts.of(&a, 100.0), first);
        assert_eq!(doubts.computed(), 1);
        let other = ended(0.01);
        assert_eq!(doubts.of(&other, 100.0), doubt(&other, 100.0));
        assert_eq!(doubts.of(&a, 50.0), doubt(&a, 50.0));
        assert_eq!(doubts.computed(), 3);
    }

    /// A class whose runs stop at the same tick asks all at once: one of them computes the
    /// opinion, the others wait for it (however the threads interleave).
    #[test]
    fn a_class_asking_at_once_computes_it_once() {
        let doubts = Doubts::new();
        let runs: Vec<Run> = (0..8).map(|_| ended(0.0)).collect();
        let got: Vec<Doubt> = std::thread::scope(|s| {
            let asks: Vec<_> = runs
                .iter()
                .map(|r| s.spawn(|| doubts.of(r, 100.0)))
                .collect();
            asks.into_iter().map(|a| a.join().unwrap()).collect()
        });
        assert!(got.iter().all(|d| *d == got[0]));
        assert_eq!(doubts.computed(), 1);
    }

    /// One release at many settings: the Sundman-time runs are computed once a tolerance and
    /// time limit (or once for limits beyond a run that ended before them), and every opinion
    /// is `doubt`'s, bit for bit: stuck, escaping and run out to the limit.
    #[test]
    fn the_sundman_runs_are_computed_once_and_answer_as_doubt() {
        use crate::engine::Method;
        let fates = Fates::new();
        let via = |run: &Run, tau_max: f64| {
            doubt_with(run, tau_max, &|i, hold, tol, limit, steps| {
                fates.of(i, hold, tol, limit, steps)
            })
        };
        let mut asked = 0;
        for (xi0, v0, tau_max) in [(0.5, 0.6078, 100.0), (0.5, 0.7, 100.0), (0.5, 0.6078, 1.0)] {
            for s in [
                Settings::dp54(1e-4),
                Settings::dp54(1e-6),
                Settings::fixed(Method::Rk4, 1e-3),
                Settings::fixed(Method::Rk2, 1e-3),
                Settings::dp54(1e-10),
            ] {
                let mut run = Run::new(Initial::velocity(xi0, 0.0, v0), s).unwrap();
                run.run(tau_max, true).unwrap();
                let d = doubt(&run, tau_max);
                assert_eq!(via(&run, tau_max), d, "{xi0} {v0} {s:?}");
                asked += 2 * usize::from(d.sundman.is_some());
            }
        }
        assert!(asked >= 24, "{asked}");
        assert!(
            fates.computed() * 2 <= asked as u64,
            "{} of {asked}",
            fates.computed()
        );
    }

    /// However many runs ask, at most [`KEPT`] opinions are kept.
    #[test]
    fn the_opinions_kept_are_bounded() {
        let doubts = Doubts::new();
        let run = ended(0.0);
        for i in 0..KEPT + 5 {
            doubts.of(&run, 20.0 + i as f64);
        }
        assert_eq!(doubts.kept(), KEPT);
        assert_eq!(doubts.computed(), (KEPT + 5) as u64);
    }
}
