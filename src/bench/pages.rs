//! The explorer's pages on all cores (issue 34): the work of the escape-speed curve and the
//! outcome map on one thread and on every core, the map's cells all run at the page's
//! settings (as before) against first runs at a coarse tolerance refined where in doubt, the
//! Fig. 5 sweep's speedup, and a key → the page complete in the threaded session as a user
//! waits for it. Wall times on a shared machine say as much about its other load as about the
//! split, so each piece's own CPU time is counted too: the work over the larger of its share
//! per core and its longest piece is the most the split can give idle cores.

use super::{thread_cpu, timed};
use crate::analysis::{Job, Piece, Speeds, map_cell, map_cell_answer, piece, pieces};
use crate::app::pages::{Charts, Curve, Page};
use crate::app::{App, Chord};
use crate::engine::par::{cores, par_map};
use crate::engine::solve::escape_speed;
use crate::engine::{Release, Settings};
use crate::error::Error;
use crate::session::Explorer;
use serde::Serialize;
use std::time::{Duration, Instant};

/// The terminal the pages are measured at (the issue's).
pub const SIZE: (u16, u16) = (120, 40);

/// One piece of work on one thread and on all cores.
#[derive(Clone, Debug, Serialize)]
pub struct Split {
    pub one_ms: f64,
    pub all_ms: f64,
    /// CPU time of all the pieces, and of the longest, in the run on all cores.
    pub cpu_ms: f64,
    pub longest_ms: f64,
    pub cores: usize,
}

impl Split {
    /// The measured speedup (wall).
    pub fn speedup(&self) -> f64 {
        self.one_ms / self.all_ms
    }
    /// The most the split can give idle cores: the work over the larger of its share per
    /// core and the longest piece.
    pub fn bound(&self) -> f64 {
        self.cpu_ms / (self.cpu_ms / self.cores as f64).max(self.longest_ms)
    }
}

/// What the pages cost, measured.
#[derive(Clone, Debug, Serialize)]
pub struct PageTimes {
    pub cores: usize,
    /// The escape-speed curve at ξ0 = 0.5 (72 angles, vtol `analysis::CURVE_VTOL`), from no
    /// nearby curve.
    pub curve: Split,
    /// The outcome map's grid at [`SIZE`] (ξ0 = 0.5, velocity release).
    pub grid: (usize, usize),
    /// Every cell run at the page's settings (dp54 tol 1e-10), one thread.
    pub map_full_one_ms: f64,
    /// First runs at `analysis::CELL_TOL`, refined where in doubt, and how many cells were.
    pub map: Split,
    pub refined: usize,
    /// Four Fig. 5 curves × 24 angles (vtol 1e-6), as `sweep fig5`.
    pub fig5: Split,
    /// `x` (ξ0 + 0.01) → the page complete and drawn, in the threaded session at [`SIZE`]:
    /// median and worst over the presses: the outcome map, the escape-speed page's curve, and
    /// that page whole (its least v_e refined too).
    pub presses: usize,
    /// `x`'s own frame (the new ξ0 in the title) while the map computes: keys are answered
    /// within a frame whatever the workers do.
    pub key_frame_ms: (f64, f64),
    pub key_map_ms: (f64, f64),
    /// `x` held (pressed 30 times a second, as a key repeats): of `held` presses, how many
    /// saw their map complete and drawn before the next, and how long after the last press its
    /// map was complete and drawn (ms): a page that waited behind superseded ones would show.
    pub held: usize,
    pub held_complete: usize,
    pub held_last_ms: f64,
    pub key_curve_ms: (f64, f64),
    pub key_escape_ms: (f64, f64),
}

/// `f` over `items` on one thread and on all cores (`par_map`), then each piece's CPU time
/// counted in a run of its own: two clock readings a piece would be a third of a map cell's
/// seven microseconds, and its wall time with them a third of the speedup.
fn split<T: Sync, R: Send>(
    reps: usize,
    items: &[T],
    f: impl Fn(&T) -> R + Sync,
) -> (Vec<R>, Split) {
    let (out, one_ms) = timed(reps, || items.iter().map(&f).collect::<Vec<_>>());
    let (_, all_ms) = timed(reps, || par_map(items, &f));
    let ((cpu_ms, longest_ms), _) = timed(0, || {
        let spent = par_map(items, |x| {
            let t = thread_cpu();
            let _ = f(x);
            1e3 * (thread_cpu() - t)
        });
        (
            spent.iter().sum::<f64>(),
            spent.iter().copied().fold(0.0, f64::max),
        )
    });
    let s = Split {
        one_ms,
        all_ms,
        cpu_ms,
        longest_ms,
        cores: cores(),
    };
    (out, s)
}

/// Measures the pages' work and a key's wait (over `presses`, and `held` presses of a held key).
pub fn page_times(reps: usize, presses: usize, held: usize) -> Result<PageTimes, Error> {
    let s = crate::analysis::settings_for(Settings::default());
    let job = Job::Curve { xi0: 0.5 };
    let ks: Vec<usize> = (0..pieces(&job)).collect();
    let (ve, curve) = split(reps, &ks, |k| match piece(&job, *k, s) {
        Piece::Escape { v, .. } => Some(v),
        _ => None,
    });
    let c = Curve {
        xi0: 0.5,
        settings: s,
        ve: ve.clone(),
        least: None,
    };
    let v0_max = Charts::map_v0_max(&c, Release::Velocity, 0.5);
    let mut app = App::new(crate::scene::Scene::default_scene());
    app.resize(SIZE.0, SIZE.1);
    open(&mut app, Page::OutcomeMap);
    let grid = crate::ui::pages::map_grid(&app, v0_max).ok_or(Error::invalid("no map fits"))?;
    let cells: Vec<usize> = (0..grid.0 * grid.1).collect();
    let cell = |k: &usize, curve: Option<&[Option<Speeds>]>| {
        map_cell_answer(0.5, Release::Velocity, map_cell(*k, grid, v0_max), s, curve)
    };
    let (_, map_full_one_ms) = timed(reps, || {
        cells.iter().map(|k| cell(k, None)).collect::<Vec<_>>()
    });
    let (answers, map) = split(reps, &cells, |k| cell(k, Some(&ve)));
    let points: Vec<(f64, f64)> = [0.8, 0.5, 0.2, 0.001]
        .iter()
        .flat_map(|&x| (0..24).map(move |i| (x, crate::analysis::angle(i, 24))))
        .collect();
    let (_, fig5) = split(reps, &points, |&(x, p)| {
        escape_speed(x, p, Settings::default(), 1e-6).map(|t| t.value)
    });
    let [_, key_curve_ms, key_escape_ms] = key_to_page(Page::EscapeSpeed, presses)?;
    let [key_frame_ms, _, key_map_ms] = key_to_page(Page::OutcomeMap, presses)?;
    let (held_complete, held_last_ms) = held_key(held)?;
    Ok(PageTimes {
        cores: cores(),
        curve,
        grid,
        map_full_one_ms,
        map,
        refined: answers.iter().filter(|a| a.1).count(),
        fig5,
        presses,
        key_frame_ms,
        key_map_ms,
        held,
        held_complete,
        held_last_ms,
        key_curve_ms,
        key_escape_ms,
    })
}

/// Turns `app`'s pages to `page`, as the keys do.
fn open(app: &mut App, page: Page) {
    for _ in 0..16 {
        if app.view().page == page {
            return;
        }
        crate::app::update(app, crate::app::Action::NextPage);
    }
}

fn dark() -> Result<crate::theme::Theme, Error> {
    crate::theme::Theme::builtin("dark").ok_or(Error::invalid("no dark theme"))
}

/// A session at [`SIZE`] on `page`, with its workers, and the key `x`.
fn session_on(page: Page) -> Result<(Explorer<ratatui::backend::TestBackend>, Chord), Error> {
    let mut app = App::new(crate::scene::Scene::default_scene());
    open(&mut app, page);
    let x = Chord::new(
        crossterm::event::KeyCode::Char('x'),
        crossterm::event::KeyModifiers::NONE,
    );
    Ok((
        Explorer::headless(app, dark()?, SIZE.0, SIZE.1, false).with_worker(),
        x,
    ))
}

/// Whether the page on screen needs nothing more.
fn complete(session: &Explorer<ratatui::backend::TestBackend>) -> bool {
    let app = &session.app;
    app.wanted_job(|v| crate::ui::pages::map_grid(app, v))
        .is_none()
}

/// `x` held on the outcome map: `presses` presses 1/30 s apart (after a warm-up), the loop
/// taking pieces and drawing between them as the explorer's does; how many presses saw their
/// map complete and drawn before the next, and how long after the last press (ms) its map was
/// (the last press waits as long as it takes).
fn held_key(presses: usize) -> Result<(usize, f64), Error> {
    let (mut session, x) = session_on(Page::OutcomeMap)?;
    session.press(x);
    wait_for_page(&mut session)?;
    let period = Duration::from_secs(1) / 30;
    let mut next = Instant::now();
    let (mut completed, mut last_ms) = (0, f64::NAN);
    for k in 0..presses {
        let pressed = Instant::now();
        session.press(x);
        next += period;
        let last = k + 1 == presses;
        let mut drawn = Instant::now() - period;
        loop {
            session.ask_analysis();
            let done = complete(&session);
            if done || (session.app.needs_redraw() && drawn.elapsed() >= period / 2) {
                session.screen();
                drawn = Instant::now();
            }
            if done {
                completed += usize::from(pressed.elapsed() <= period);
                last_ms = 1e3 * pressed.elapsed().as_secs_f64();
                if !last {
                    std::thread::sleep(next.saturating_duration_since(Instant::now()));
                }
                break;
            }
            if !last && Instant::now() >= next {
                break;
            }
            if last && pressed.elapsed() > Duration::from_secs(10) {
                return Err(Error::Failed(
                    "the held key's last page did not complete in 10 s".into(),
                ));
            }
            std::thread::sleep(crate::terminal::drive::PIECES_POLL);
        }
    }
    Ok((completed, last_ms))
}

/// `x` pressed `presses` times on `page` in a threaded session at [`SIZE`], each time waiting
/// for the page to be complete and drawn as the explorer's loop does (pieces taken as they
/// arrive, a frame at most every 1/60 s while they do): the median and the worst wait (ms)
/// until the key's own frame is drawn, until the curve at the new ξ0 is complete, and until
/// the page is.
fn key_to_page(page: Page, presses: usize) -> Result<[(f64, f64); 3], Error> {
    let (mut session, x) = session_on(page)?;
    let (mut frame, mut curve, mut whole) = (Vec::new(), Vec::new(), Vec::new());
    // The first press is a warm-up, as the page's first fill is (the paper's curves).
    for _ in 0..=presses {
        let t = Instant::now();
        session.press(x);
        // The key's own frame (its new title), drawn while the workers compute.
        session.screen();
        frame.push(t.elapsed().as_secs_f64() * 1e3);
        let c = wait_for_page(&mut session)?;
        curve.push((t.elapsed() - c).as_secs_f64() * 1e3);
        whole.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let summary = |mut v: Vec<f64>| {
        v.remove(0);
        let worst = v.iter().copied().fold(0.0, f64::max);
        (super::median(&mut v), worst)
    };
    Ok([summary(frame), summary(curve), summary(whole)])
}

/// Waits until the page on screen needs nothing more and is drawn, taking pieces as the
/// explorer's loop does (every `terminal::drive::PIECES_POLL`) and drawing as they arrive (at most 60
/// frames a second); gives up after 10 s. How long it waited after the curve at
/// the app's ξ0 was complete.
fn wait_for_page(session: &mut Explorer<ratatui::backend::TestBackend>) -> Result<Duration, Error> {
    let start = Instant::now();
    let frame = Duration::from_secs(1) / 60;
    let mut drawn = start;
    let mut curve = None;
    loop {
        session.ask_analysis();
        let app = &session.app;
        let settings = crate::analysis::settings_for(app.settings());
        if curve.is_none()
            && app
                .charts()
                .curve(app.initial().xi0, settings)
                .is_some_and(Curve::complete)
        {
            curve = Some(start.elapsed());
        }
        let done = complete(session);
        if done || (session.app.needs_redraw() && drawn.elapsed() >= frame) {
            session.screen();
            drawn = Instant::now();
        }
        if done {
            return Ok(curve.map_or(Duration::ZERO, |c| start.elapsed() - c));
        }
        if start.elapsed() > Duration::from_secs(10) {
            return Err(Error::Failed("the page did not complete in 10 s".into()));
        }
        std::thread::sleep(crate::terminal::drive::PIECES_POLL);
    }
}
