//! Pieces computed once a process: a piece hangs on nothing but its job, its index, the
//! settings and the curve it leans on ([`piece_with`]), so every session asking for the same
//! one (a served class's followers turning the page with the presenter; headless sessions of
//! one scene) takes the one the first of them computed, the others waiting for it. Each
//! computing its own cost a class one escape-speed curve a follower at the presenter's Tab
//! (16 followers: 8 s of CPU in the memory test's four classes, 0.5 s without the pages), and
//! the presenter's keys waited behind them at the gate.

use super::{GoOn, Job, Piece, Settings, Speeds, piece_with, pieces};
use crate::kept::Kept;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

/// Jobs kept at most, the oldest going first. An outcome map has at most
/// [`super::MAP_CELLS`] pieces (under 100 bytes each), so what is kept stays under 16 MB
/// whatever is asked; a class's pages are a few jobs.
const KEPT: usize = 8;

/// All that [`piece_with`] reads besides the piece's index: jobs equal in these have the same
/// pieces, bit for bit.
#[derive(Clone, Debug, PartialEq)]
struct Asked {
    job: Job,
    settings: Settings,
    curve: Option<Vec<Option<Speeds>>>,
}

/// A job's pieces, each computed by the first who asks while the others asking wait.
type Slot = Vec<Mutex<Option<Piece>>>;

/// The pieces asked for lately.
pub struct Shared {
    kept: Kept<Asked, Slot>,
    computed: AtomicU64,
}

/// The process's: the inline sessions' requests ask here (see [`super::Analysis::compute`]).
pub static PIECES: Shared = Shared::new();

/// One job's pieces as kept: [`Pieces::piece`] asks for each.
pub struct Pieces<'a> {
    asked: Asked,
    slot: Arc<Slot>,
    shared: &'a Shared,
}

impl Shared {
    pub const fn new() -> Shared {
        Shared {
            kept: Kept::new(KEPT),
            computed: AtomicU64::new(0),
        }
    }

    /// The pieces of `job` at `settings`, leaning on `curve` (see [`piece_with`]).
    pub fn job(
        &self,
        job: &Job,
        settings: Settings,
        curve: Option<&[Option<Speeds>]>,
    ) -> Pieces<'_> {
        let asked = Asked {
            job: *job,
            settings,
            curve: curve.map(<[_]>::to_vec),
        };
        let slot = self.kept.slot(&asked, |a| {
            (0..pieces(&a.job)).map(|_| Mutex::new(None)).collect()
        });
        Pieces {
            asked,
            slot,
            shared: self,
        }
    }

    /// Pieces computed so far.
    #[cfg(test)]
    fn computed(&self) -> u64 {
        self.computed.load(Ordering::Relaxed)
    }

    /// Jobs kept now.
    #[cfg(test)]
    fn kept(&self) -> usize {
        self.kept.kept()
    }
}

impl Default for Shared {
    fn default() -> Shared {
        Shared::new()
    }
}

impl Pieces<'_> {
    /// Piece `k`: the one computed already, or computed now (`None` once `go_on` said stop,
    /// and then left for the next asker).
    pub fn piece(&self, k: usize, go_on: GoOn) -> Option<Piece> {
        let a = &self.asked;
        let mut kept = self
            .slot
            .get(k)?
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        if kept.is_none() {
            *kept = piece_with(&a.job, k, a.settings, a.curve.as_deref(), go_on);
            if kept.is_some() {
                self.shared.computed.fetch_add(1, Ordering::Relaxed);
            }
        }
        *kept
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::solve::always;

    fn curve(xi0: f64) -> Job {
        Job::Curve { xi0 }
    }

    /// A piece asked for again, or by another session, is not computed again and is what
    /// `piece_with` says; another job's, another setting's or another curve's is computed.
    #[test]
    fn a_piece_is_computed_once_for_equal_jobs() {
        let shared = Shared::new();
        let s = Settings::default();
        let first = shared.job(&curve(0.5), s, None).piece(3, &always);
        assert_eq!(first, piece_with(&curve(0.5), 3, s, None, &always));
        assert_eq!(shared.job(&curve(0.5), s, None).piece(3, &always), first);
        assert_eq!(shared.computed(), 1);
        let near: Vec<Option<Speeds>> = vec![Some(Speeds::Stick { lo: 0.0, hi: 1.2 }); 72];
        let leaning = shared.job(&curve(0.5), s, Some(&near)).piece(3, &always);
        assert_eq!(leaning, piece_with(&curve(0.5), 3, s, Some(&near), &always));
        let fewer = Settings {
            max_steps: s.max_steps / 2,
            ..s
        };
        shared.job(&curve(0.5), fewer, None).piece(3, &always);
        shared.job(&curve(0.6), s, None).piece(3, &always);
        assert_eq!(shared.computed(), 4);
        assert_eq!(shared.kept(), 4);
    }

    /// A class turning the page at once: each piece is computed by one of them, the others
    /// waiting for it (however the threads interleave), and all get the same pieces.
    #[test]
    fn a_class_asking_at_once_computes_each_piece_once() {
        let shared = Shared::new();
        let s = Settings::default();
        let got: Vec<Vec<Option<Piece>>> = std::thread::scope(|sc| {
            let asks: Vec<_> = (0..4)
                .map(|_| {
                    sc.spawn(|| {
                        let job = shared.job(&curve(0.5), s, None);
                        (0..8).map(|k| job.piece(k, &always)).collect()
                    })
                })
                .collect();
            asks.into_iter().map(|a| a.join().unwrap()).collect()
        });
        assert!(got.iter().all(|g| *g == got[0]));
        assert!(got[0].iter().all(Option::is_some));
        assert_eq!(shared.computed(), 8);
    }

    /// A piece stopped by its asker is not kept: the next asker computes it. However many
    /// jobs are asked for, at most [`KEPT`] are kept.
    #[test]
    fn a_stopped_piece_is_left_and_the_jobs_kept_are_bounded() {
        let shared = Shared::new();
        let s = Settings::default();
        assert_eq!(shared.job(&curve(0.5), s, None).piece(0, &|| false), None);
        assert_eq!(shared.computed(), 0);
        assert!(shared.job(&curve(0.5), s, None).piece(0, &always).is_some());
        assert_eq!(shared.computed(), 1);
        for i in 0..KEPT + 3 {
            shared.job(
                &Job::Least {
                    xi0: 0.5,
                    near: i as f64,
                },
                s,
                None,
            );
        }
        assert_eq!(shared.kept(), KEPT);
        // Under 100 bytes a piece: what the bound on memory above says.
        assert!(std::mem::size_of::<Mutex<Option<Piece>>>() < 100);
    }
}
