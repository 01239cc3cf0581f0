//! Where a job's pieces are computed: inline, when a frame is about to be drawn (headless,
//! deterministic), or on worker threads (one a core) that a newer request cancels between runs.

use super::*;

/// A request in flight: which job, its generation, and the pieces received so far.
#[derive(Clone, Debug, PartialEq)]
pub struct Progress {
    pub job: Job,
    pub settings: Settings,
    pub done: usize,
}

/// Where pieces are computed: inline (headless, deterministic) or on worker threads.
#[derive(Debug)]
pub struct Analysis {
    worker: Option<Worker>,
    /// The job being filled in, and how far it got.
    pub progress: Option<Progress>,
    /// Pieces received and not yet taken by the app.
    inbox: Vec<Piece>,
    /// Inline, the request not yet computed: it waits for [`Analysis::compute`] (before a
    /// frame is drawn), so keys that supersede it cost nothing.
    pending: Option<Request>,
    /// Pieces computed inline so far: the work a headless session did, counted.
    computed: u64,
}

#[derive(Debug)]
struct Worker {
    jobs: Sender<Request>,
    pieces: Receiver<(u64, Piece)>,
    generation: Arc<AtomicU64>,
}

impl Clone for Analysis {
    /// A copy computes inline: a worker belongs to one app.
    fn clone(&self) -> Self {
        Analysis {
            worker: None,
            progress: self.progress.clone(),
            inbox: self.inbox.clone(),
            pending: self.pending.clone(),
            computed: self.computed,
        }
    }
}

impl Default for Analysis {
    fn default() -> Self {
        Analysis::inline()
    }
}

impl Analysis {
    /// Pieces computed on the caller's thread, when [`Analysis::compute`] asks.
    pub fn inline() -> Analysis {
        Analysis {
            worker: None,
            progress: None,
            inbox: Vec::new(),
            pending: None,
            computed: 0,
        }
    }

    /// Pieces computed on worker threads, one a core, and streamed back as each is done. A
    /// newer request stops the pieces running at their next run (see [`piece_until`]), so it
    /// waits for one bounded run at most; requests queued behind a newer one are skipped.
    pub fn threaded() -> Analysis {
        let (jobs, inbox) = channel::<Request>();
        let (out, received) = channel();
        let generation = Arc::new(AtomicU64::new(0));
        let current = Arc::clone(&generation);
        let threads = crate::engine::par::cores();
        std::thread::spawn(move || {
            while let Ok(mut r) = inbox.recv() {
                while let Ok(newer) = inbox.try_recv() {
                    r = newer;
                }
                let go_on = || current.load(Ordering::Relaxed) == r.generation;
                crate::engine::par::par_each(&r.todo, threads, |&k| {
                    piece_with(&r.job, k, r.settings, r.curve.as_deref(), &go_on)
                        .is_some_and(|p| out.send((r.generation, p)).is_ok())
                });
            }
        });
        Analysis {
            worker: Some(Worker {
                jobs,
                pieces: received,
                generation,
            }),
            progress: None,
            inbox: Vec::new(),
            pending: None,
            computed: 0,
        }
    }

    /// Asks for the pieces `todo` of `job` (cancelling any other job in flight): those a
    /// cancelled request left are not computed again. A map's cells lean on `curve`, the
    /// escape speeds at its ξ0, when given (see [`piece_with`]). Inline, they wait for
    /// [`Analysis::compute`].
    pub fn request(
        &mut self,
        job: Job,
        settings: Settings,
        todo: Vec<usize>,
        curve: Option<Vec<Option<Speeds>>>,
    ) {
        self.inbox.clear();
        let done = pieces(&job) - todo.len().min(pieces(&job));
        self.progress = Some(Progress {
            job,
            settings,
            done,
        });
        let mut r = Request {
            generation: 0,
            job,
            settings,
            todo,
            curve,
        };
        match &self.worker {
            Some(w) => {
                r.generation = w.generation.fetch_add(1, Ordering::Relaxed) + 1;
                if let Err(e) = w.jobs.send(r) {
                    self.worker = None;
                    self.request(job, settings, e.0.todo, e.0.curve);
                }
            }
            None => self.pending = Some(r),
        }
    }

    /// Inline, computes the pending request now; with a worker, nothing (it computes as it goes).
    pub fn compute(&mut self) {
        if let Some(r) = self.pending.take() {
            // Every session of the process asking for these shares them (see `shared`).
            let job = shared::PIECES.job(&r.job, r.settings, r.curve.as_deref());
            self.inbox = r
                .todo
                .iter()
                .filter_map(|&k| job.piece(k, &always))
                .collect();
            self.computed += r.todo.len() as u64;
            if let Some(p) = self.progress.as_mut() {
                p.done = pieces(&r.job);
            }
        }
    }

    /// Stops the job in flight, if any (its pieces so far are kept by whoever took them).
    pub fn cancel(&mut self) {
        if self.busy() || self.pending.is_some() {
            if let Some(w) = &self.worker {
                w.generation.fetch_add(1, Ordering::Relaxed);
            }
            self.progress = None;
            self.inbox.clear();
            self.pending = None;
        }
    }

    /// Pieces computed inline since this was made.
    pub fn computed(&self) -> u64 {
        self.computed
    }

    /// The job in flight (or last completed).
    pub fn current(&self) -> Option<(Job, Settings)> {
        self.progress.as_ref().map(|p| (p.job, p.settings))
    }

    /// Whether pieces are still to come from the worker (inline, nothing comes with time:
    /// [`Analysis::compute`] does it all).
    pub fn busy(&self) -> bool {
        self.worker.is_some()
            && self
                .progress
                .as_ref()
                .is_some_and(|p| p.done < pieces(&p.job))
    }

    /// The pieces that arrived since the last call (none after a newer request).
    pub fn take(&mut self) -> Vec<Piece> {
        if let Some(w) = &self.worker {
            let current = w.generation.load(Ordering::Relaxed);
            while let Ok((id, p)) = w.pieces.try_recv() {
                if id == current {
                    self.inbox.push(p);
                    if let Some(pr) = self.progress.as_mut() {
                        pr.done += 1;
                    }
                }
            }
        }
        std::mem::take(&mut self.inbox)
    }
}
