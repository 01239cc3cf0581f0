//! The price of each model on one page (issue 34 item 4): per scene kind, what one run of the
//! bench's releases to τ = 50 costs, one frame of the explorer playing it at 120×40 (a tick
//! and a whole draw), and its outcome-map page (the escape-speed curve, then the map's cells,
//! one thread), so that "model only what a scene requires" is a table to read. The pages
//! follow the point with its coupling: a μ = 0 or a body scene's pages are the point's. The
//! spin-up (`engine::spinup`, preset `spin`) is played on the turntable page only: its frame
//! is timed past the slip, and its page is the work one would hold, its runs over a grid of ξ0
//! and ramp rates.

use super::runs::state_at;
use super::timed;
use crate::app::App;
use crate::engine::body::Body;
use crate::engine::{Coupling, Initial, Release, Settings};
use crate::error::Error;
use crate::scene::Scene;
use serde::Serialize;

/// How long each run goes.
const TAU: f64 = 50.0;

/// One scene kind's costs.
#[derive(Clone, Debug, Serialize)]
pub struct ModelCost {
    pub model: String,
    /// Median RHS evaluations of one run, and the mean wall time of one (µs).
    pub run_rhs: f64,
    pub run_us: f64,
    /// One frame of the explorer playing the scene: a tick and a whole draw (ms, the least of
    /// the frames timed).
    pub frame_ms: f64,
    /// The outcome-map page at 120×40 (ξ0 = 0.5): its curve and its cells, one thread (ms);
    /// none where the pages are the point's.
    pub page_ms: Option<f64>,
}

/// A kind of scene: its name, its settings and initial conditions from a release, its body.
struct Kind {
    model: &'static str,
    settings: Settings,
    frictionless: bool,
    body: Option<Body>,
}

/// The appendix's body the bench plays (as its slow-link rows).
const BODY: Body = Body {
    length: 0.1,
    height: Some(0.01),
    angle: 0.0,
};

fn kinds() -> [Kind; 5] {
    let with = |coupling| Settings {
        coupling,
        ..Settings::default()
    };
    [
        Kind {
            model: "point, dry friction (the paper's)",
            settings: Settings::default(),
            frictionless: false,
            body: None,
        },
        Kind {
            model: "μ = 0, closed form",
            settings: Settings::default(),
            frictionless: true,
            body: None,
        },
        Kind {
            model: "Stokes drag γ = 0.5, closed form",
            settings: with(Coupling::Stokes { gamma: 0.5 }),
            frictionless: false,
            body: None,
        },
        Kind {
            model: "μs/μk = 1.5",
            settings: with(Coupling::Coulomb { hold: 1.5 }),
            frictionless: false,
            body: None,
        },
        Kind {
            model: "the appendix's body, L = 0.1",
            settings: Settings::default(),
            frictionless: false,
            body: Some(BODY),
        },
    ]
}

/// Each kind's run over `cases` and its frame.
pub fn model_costs(cases: &[Initial], reps: usize) -> Result<Vec<ModelCost>, Error> {
    kinds()
        .iter()
        .map(|k| {
            let release = |i: &Initial| Initial {
                frictionless: k.frictionless,
                ..*i
            };
            let run = |i: &Initial| -> Result<u64, Error> {
                match k.body {
                    Some(b) => {
                        let hold = k.settings.hold();
                        let mut r = crate::engine::rod::RodRun::new(b, hold, &release(i), 1e-10)?;
                        r.finish(TAU, |_| {})?;
                        Ok(r.rhs_evals())
                    }
                    None => Ok(state_at(release(i), k.settings, TAU)?.1),
                }
            };
            let (evals, ms) = timed(reps.max(1), || {
                cases.iter().map(run).collect::<Result<Vec<_>, _>>()
            });
            let mut evals: Vec<f64> = evals?.into_iter().map(|e| e as f64).collect();
            Ok(ModelCost {
                model: k.model.into(),
                run_rhs: super::median(&mut evals),
                run_us: 1e3 * ms / cases.len().max(1) as f64,
                frame_ms: frame(k, reps)?,
                page_ms: (k.body.is_none() && !k.frictionless).then(|| map_page(k.settings, reps)),
            })
        })
        .chain([spin_cost(cases, reps)])
        .collect()
}

/// The spin-up's ramp: Ω̇ = 0.05 Ω_ref² from rest, so a coin at ξ0 = 0.5 slips at τ ≈ 28.
const SPIN_RATE: f64 = 0.05;

/// The spin-up: a coin at rest at each release's ξ0 on a table ramping at [`SPIN_RATE`], run
/// to τ = 50 or its escape; its page, a coin at each of the map's cells over ξ0 in (0, 1.5) and
/// ramp rates in (0, 0.5] (what a spin-up page of the explorer would hold).
fn spin_cost(cases: &[Initial], reps: usize) -> Result<ModelCost, Error> {
    use crate::engine::spinup::{Ramp, SpinRun};
    let run = |xi0: f64, rate: f64| -> Result<u64, Error> {
        let ramp = Ramp { rate, omega0: 0.0 };
        let mut r = SpinRun::new(ramp, xi0, Settings::default())?;
        r.run(TAU, true)?;
        Ok(r.cost().rhs_evals)
    };
    let (evals, ms) = timed(reps.max(1), || {
        cases
            .iter()
            .map(|i| run(i.xi0, SPIN_RATE))
            .collect::<Result<Vec<_>, _>>()
    });
    let mut evals: Vec<f64> = evals?.into_iter().map(|e| e as f64).collect();
    let (page, page_ms) = timed(reps, || {
        (0..GRID.0 * GRID.1)
            .map(|k| {
                let (i, j) = (k % GRID.0, k / GRID.0);
                let xi0 = 1.5 * (i as f64 + 0.5) / GRID.0 as f64;
                run(xi0, 0.5 * (j as f64 + 1.0) / GRID.1 as f64)
            })
            .collect::<Result<Vec<_>, _>>()
    });
    page?;
    Ok(ModelCost {
        model: "spin-up, dΩ/dτ = 0.05".into(),
        run_rhs: super::median(&mut evals),
        run_us: 1e3 * ms / cases.len().max(1) as f64,
        frame_ms: spin_frame(reps)?,
        page_ms: Some(page_ms),
    })
}

/// One frame of the explorer playing the `spin` preset at 120×40, past the slip (τ ≈ 9).
fn spin_frame(reps: usize) -> Result<f64, Error> {
    let scene = Scene::preset("spin").ok_or_else(|| Error::invalid("no spin preset"))?;
    frame_after(scene, 6, reps)
}

/// One frame of the explorer playing `kind` from the default scene's release at 120×40,
/// after a second of play: a tick and a whole draw, the least of a few.
fn frame(kind: &Kind, reps: usize) -> Result<f64, Error> {
    let mut scene = Scene::default_scene();
    scene.settings = kind.settings;
    scene.initial.frictionless = kind.frictionless;
    scene.body = kind.body;
    frame_after(scene, 1, reps)
}

/// One frame of the explorer playing `scene` at 120×40 after `seconds` of play: a tick and a
/// whole draw, the least of a few.
fn frame_after(scene: Scene, seconds: usize, reps: usize) -> Result<f64, Error> {
    let mut app = App::new(scene);
    for _ in 0..seconds * crate::app::TICKS_PER_SECOND as usize {
        app.tick();
    }
    super::tick_and_draw_ms(&mut app, (120, 40), reps)
}

/// The map's grid at 120×40 (`bench::pages` measures it).
const GRID: (usize, usize) = (84, 32);

/// The outcome-map page's work at ξ0 = 0.5 from nothing: its escape-speed curve, then its
/// cells, one thread (ms).
fn map_page(settings: Settings, reps: usize) -> f64 {
    use crate::analysis::{Job, Piece, map_cell, map_cell_answer, piece, pieces, settings_for};
    use crate::app::pages::{Charts, Curve};
    let s = settings_for(settings);
    let job = Job::Curve { xi0: 0.5 };
    let (_, ms) = timed(reps, || {
        let ve: Vec<_> = (0..pieces(&job))
            .map(|k| match piece(&job, k, s) {
                Piece::Escape { v, .. } => Some(v),
                _ => None,
            })
            .collect();
        let curve = Curve {
            xi0: 0.5,
            settings: s,
            ve,
            least: None,
        };
        let v0_max = Charts::map_v0_max(&curve, Release::Velocity, 0.5);
        (0..GRID.0 * GRID.1)
            .map(|k| {
                let at = map_cell(k, GRID, v0_max);
                map_cell_answer(0.5, Release::Velocity, at, s, Some(&curve.ve)).0
            })
            .collect::<Vec<_>>()
    });
    ms
}
