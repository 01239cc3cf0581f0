//! The explorer's pages (Tab cycles them) and the analysis results they show. A page asks for
//! what it lacks ([`wanted`]); results arrive piece by piece ([`Charts::apply`]).

use crate::analysis::trade::{self, Ending, REFERENCE_PIECES};
use crate::analysis::{
    CURVE_POINTS, Cell, Job, PAPER_XI0, Piece, REST_POINTS, Speeds, pieces, settings_for,
};
use crate::engine::method::Scheme;
use crate::engine::{Initial, Release, Settings};

pub use crate::scene::Page;

/// The sticking speeds over φ at one ξ0 (v_e(φ) inside ξ = 1), filled in as they arrive
/// (`None`: not yet).
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    pub xi0: f64,
    pub settings: Settings,
    pub ve: Vec<Option<Speeds>>,
    /// Where v_e is least, refined between the angles (inside ξ = 1): `None` not yet,
    /// `Some(None)` the search failed.
    pub least: Option<Option<(f64, f64)>>,
}

impl Curve {
    pub fn complete(&self) -> bool {
        self.ve.iter().all(Option::is_some)
    }

    /// The computed points (φ, v_e): the greatest sticking speed at each angle.
    pub fn points(&self) -> Vec<(f64, f64)> {
        self.edge(|lo, hi| (hi, lo))
    }

    /// Outside ξ = 1, the least sticking speed at each angle (φ, lo): the window's floor.
    pub fn floor(&self) -> Vec<(f64, f64)> {
        self.edge(|lo, hi| (lo, hi))
    }

    fn edge(&self, pick: impl Fn(f64, f64) -> (f64, f64)) -> Vec<(f64, f64)> {
        let n = self.ve.len();
        (0..n)
            .filter_map(|i| match self.ve[i]? {
                Speeds::Stick { lo, hi } => Some((crate::analysis::angle(i, n), pick(lo, hi).0)),
                _ => None,
            })
            .collect()
    }

    /// The least and greatest v_e found (the window's top outside ξ = 1), with their angles.
    pub fn extremes(&self) -> Option<((f64, f64), (f64, f64))> {
        let pts = self.points();
        let min = pts.iter().copied().min_by(|a, b| a.1.total_cmp(&b.1))?;
        let max = pts.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1))?;
        Some((min, max))
    }
}

/// The outcome map for one ξ0, release mode and speed range.
#[derive(Clone, Debug, PartialEq)]
pub struct Map {
    pub job: Job,
    pub settings: Settings,
    pub cells: Vec<Option<Cell>>,
}

/// Fig. 6: final rest ξ against ξ0 (`Some(None)`: escaped), and ξ0c.
#[derive(Clone, Debug, PartialEq)]
pub struct Rest {
    pub settings: Settings,
    pub xi: Vec<Option<Option<f64>>>,
    /// `Some(None)`: the bisection failed.
    pub critical: Option<Option<f64>>,
}

/// The work–precision page's runs of one release (see [`crate::analysis::trade`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Trade {
    pub initial: Initial,
    pub settings: Settings,
    /// The reference and its cross-check (`Some(None)`: could not finish).
    pub reference: Option<Option<Ending>>,
    pub check: Option<Option<Ending>>,
    /// Each setting's end as it arrives, whatever the job that asked for it (an `extra` of
    /// one job is kept for the next).
    pub points: Vec<(Scheme, Option<Ending>)>,
}

impl Trade {
    /// How `scheme`'s run ended: `None` not yet, `Some(None)` it could not finish.
    pub fn point(&self, scheme: Scheme) -> Option<Option<Ending>> {
        self.points
            .iter()
            .find(|(s, _)| *s == scheme)
            .map(|(_, e)| *e)
    }

    /// The reference's resolution once it and its cross-check are in (see
    /// [`trade::resolution`]).
    pub fn resolution(&self) -> Option<f64> {
        trade::resolution(&self.reference??, &self.check??)
    }
}

/// What the analysis pages have received.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Charts {
    /// Escape-speed curves, newest last (a few kept, so that going back is instant).
    pub curves: Vec<Curve>,
    pub map: Option<Map>,
    pub rest: Option<Rest>,
    pub trade: Option<Trade>,
}

/// Curves kept besides the paper's four.
const CURVES_KEPT: usize = 8;

impl Charts {
    pub fn curve(&self, xi0: f64, settings: Settings) -> Option<&Curve> {
        self.curves
            .iter()
            .find(|c| c.xi0 == xi0 && c.settings == settings)
    }

    /// The curve at the ξ0 nearest `xi0` (other than `xi0`, within `analysis::NEAR_XI0`, both
    /// inside ξ = 1, at `settings`): where the escape speeds of `xi0`'s start.
    pub fn near_curve(&self, xi0: f64, settings: Settings) -> Option<&Curve> {
        self.curves
            .iter()
            .filter(|c| c.settings == settings && c.xi0 != xi0 && c.xi0 <= 1.0 && xi0 <= 1.0)
            .filter(|c| (c.xi0 - xi0).abs() <= crate::analysis::NEAR_XI0)
            .min_by(|a, b| (a.xi0 - xi0).abs().total_cmp(&(b.xi0 - xi0).abs()))
    }

    /// Files one piece of `job` where it belongs.
    pub fn apply(&mut self, job: &Job, settings: Settings, piece: Piece) {
        match (job, piece) {
            (Job::Curve { xi0 }, Piece::Escape { i, v }) => {
                let at = match self
                    .curves
                    .iter()
                    .position(|c| c.xi0 == *xi0 && c.settings == settings)
                {
                    Some(at) => at,
                    None => {
                        self.curves.push(Curve {
                            xi0: *xi0,
                            settings,
                            ve: vec![None; CURVE_POINTS],
                            least: None,
                        });
                        let extra = self
                            .curves
                            .len()
                            .saturating_sub(CURVES_KEPT + PAPER_XI0.len());
                        let paper = |c: &Curve| PAPER_XI0.contains(&c.xi0);
                        // Drop the oldest non-paper curves first.
                        for _ in 0..extra {
                            if let Some(old) = self.curves.iter().position(|c| !paper(c)) {
                                self.curves.remove(old);
                            }
                        }
                        self.curves.len() - 1
                    }
                };
                if let Some(slot) = self.curves[at].ve.get_mut(i) {
                    *slot = Some(v);
                }
            }
            (Job::Least { xi0, .. }, Piece::Least(at)) => {
                if let Some(c) = self
                    .curves
                    .iter_mut()
                    .find(|c| c.xi0 == *xi0 && c.settings == settings)
                {
                    c.least = Some(at);
                }
            }
            (Job::Map { .. }, Piece::Cell { i, cell }) => {
                let fresh = self
                    .map
                    .as_ref()
                    .is_none_or(|m| m.job != *job || m.settings != settings);
                if fresh {
                    self.map = Some(Map {
                        job: *job,
                        settings,
                        cells: vec![None; pieces(job)],
                    });
                }
                if let Some(slot) = self.map.as_mut().and_then(|m| m.cells.get_mut(i)) {
                    *slot = Some(cell);
                }
            }
            (Job::Rest, Piece::Rest { i, xi }) => {
                if let Some(slot) = self.rest_for(settings).xi.get_mut(i) {
                    *slot = Some(xi);
                }
            }
            (Job::Rest, Piece::Critical(x)) => {
                self.rest_for(settings).critical = Some(x.is_finite().then_some(x));
            }
            (
                Job::Trade {
                    initial,
                    paper,
                    extra,
                },
                Piece::Trade { i, end },
            ) => {
                let t = self.trade_for(*initial, settings);
                match i {
                    0 => t.reference = Some(end),
                    1 => t.check = Some(end),
                    _ => {
                        if let Some(&s) = trade::schemes(*paper, *extra).get(i - REFERENCE_PIECES)
                            && t.point(s).is_none()
                        {
                            t.points.push((s, end));
                        }
                    }
                }
            }
            _ => {}
        }
    }

    /// The pieces of `job` not yet received (all of them for a job not begun).
    pub fn missing(&self, job: &Job, settings: Settings) -> Vec<usize> {
        let have: Vec<bool> = match job {
            Job::Curve { xi0 } => self
                .curve(*xi0, settings)
                .map(|c| c.ve.iter().map(Option::is_some).collect())
                .unwrap_or_default(),
            Job::Least { xi0, .. } => vec![
                self.curve(*xi0, settings)
                    .is_some_and(|c| c.least.is_some()),
            ],
            Job::Map { .. } => self
                .map
                .as_ref()
                .filter(|m| m.job == *job && m.settings == settings)
                .map(|m| m.cells.iter().map(Option::is_some).collect())
                .unwrap_or_default(),
            Job::Rest => self
                .rest
                .as_ref()
                .filter(|r| r.settings == settings)
                .map(|r| {
                    let mut v: Vec<bool> = r.xi.iter().map(Option::is_some).collect();
                    v.push(r.critical.is_some());
                    v
                })
                .unwrap_or_default(),
            Job::Trade {
                initial,
                paper,
                extra,
            } => match self.trade(initial, settings) {
                Some(t) => [t.reference.is_some(), t.check.is_some()]
                    .into_iter()
                    .chain(
                        trade::schemes(*paper, *extra)
                            .into_iter()
                            .map(|s| t.point(s).is_some()),
                    )
                    .collect(),
                None => Vec::new(),
            },
        };
        (0..pieces(job))
            .filter(|&k| !have.get(k).copied().unwrap_or(false))
            .collect()
    }

    /// The work–precision runs of `initial` at `settings`, if any.
    pub fn trade(&self, initial: &Initial, settings: Settings) -> Option<&Trade> {
        self.trade
            .as_ref()
            .filter(|t| t.initial == *initial && t.settings == settings)
    }

    fn trade_for(&mut self, initial: Initial, settings: Settings) -> &mut Trade {
        if self.trade(&initial, settings).is_none() {
            self.trade = Some(Trade {
                initial,
                settings,
                reference: None,
                check: None,
                points: Vec::new(),
            });
        }
        self.trade.as_mut().expect("just set")
    }

    fn rest_for(&mut self, settings: Settings) -> &mut Rest {
        if self.rest.as_ref().is_none_or(|r| r.settings != settings) {
            self.rest = Some(Rest {
                settings,
                xi: vec![None; REST_POINTS],
                critical: None,
            });
        }
        self.rest.as_mut().expect("just set")
    }

    /// The speed range of the outcome map for this release: a margin above the escape
    /// curve's greatest speed (thrown from the lab, the table's own speed ξ0 added).
    pub fn map_v0_max(curve: &Curve, release: Release, xi0: f64) -> f64 {
        let top = curve.extremes().map_or(1.0, |(_, max)| max.1);
        let top = if release == Release::LabRest {
            top + xi0
        } else {
            top
        };
        (1.3 * top).max(0.2)
    }
}

/// The next job `page` needs and lacks for these initial conditions and settings, if any; an
/// outcome map of the grid `map_grid` gives for its speed range (none when no plot fits).
pub fn wanted(
    page: Page,
    charts: &Charts,
    initial: &Initial,
    settings: Settings,
    map_grid: impl Fn(f64) -> Option<(usize, usize)>,
) -> Option<Job> {
    let explorer = settings;
    let settings = settings_for(settings);
    let missing_curve = |xi0: f64| {
        let have = charts.curve(xi0, settings);
        (!have.is_some_and(Curve::complete)).then_some(Job::Curve { xi0 })
    };
    match page {
        Page::Turntable | Page::TimePlots => None,
        // Closed forms (μ = 0, Stokes drag): no threshold, and every method gives the same run.
        _ if crate::engine::closed_form(initial, explorer) => None,
        Page::EscapeSpeed => std::iter::once(initial.xi0)
            .chain(PAPER_XI0)
            .find_map(missing_curve)
            .or_else(|| {
                // Then Fig. 5's minimum, refined (outside ξ = 1 the curve is a window's top).
                let c = charts.curve(initial.xi0, settings)?;
                let ((near, _), _) = c.extremes()?;
                (initial.xi0 <= 1.0 && c.least.is_none()).then_some(Job::Least {
                    xi0: initial.xi0,
                    near,
                })
            }),
        Page::OutcomeMap => {
            if let Some(job) = missing_curve(initial.xi0) {
                return Some(job);
            }
            let curve = charts.curve(initial.xi0, settings)?;
            let v0_max = Charts::map_v0_max(curve, initial.release, initial.xi0);
            let job = Job::Map {
                xi0: initial.xi0,
                release: initial.release,
                v0_max,
                size: map_grid(v0_max)?,
            };
            let done = charts.map.as_ref().is_some_and(|m| {
                m.job == job && m.settings == settings && m.cells.iter().all(Option::is_some)
            });
            (!done).then_some(job)
        }
        Page::RestRadius => {
            let done = charts.rest.as_ref().is_some_and(|r| {
                r.settings == settings && r.critical.is_some() && r.xi.iter().all(Option::is_some)
            });
            (!done).then_some(Job::Rest)
        }
        Page::WorkPrecision => {
            let job = trade_job(initial, explorer);
            let base = trade::trade_base(explorer);
            (!charts.missing(&job, base).is_empty()).then_some(job)
        }
    }
}

/// The work–precision page's settings in the order `j`/`k` walk them, for `initial` with the
/// explorer at `settings` (see [`crate::analysis::trade::schemes`]).
pub fn trade_schemes(initial: &Initial, settings: Settings) -> Vec<Scheme> {
    match trade_job(initial, settings) {
        Job::Trade { paper, extra, .. } => trade::schemes(paper, extra),
        _ => Vec::new(),
    }
}

/// The point picked on the work–precision page: `pick` when it is one of the page's, else the
/// explorer's own setting.
pub fn trade_picked(pick: Option<Scheme>, initial: &Initial, settings: Settings) -> Scheme {
    pick.filter(|p| trade_schemes(initial, settings).contains(p))
        .unwrap_or(settings.scheme)
}

/// The work–precision job for `initial` with the explorer at `settings` (its setting an extra
/// point when it is none of the page's).
pub fn trade_job(initial: &Initial, settings: Settings) -> Job {
    let paper = settings.hold() == 1.0;
    let extra = Some(settings.scheme).filter(|s| !trade::schemes(paper, None).contains(s));
    Job::Trade {
        initial: *initial,
        paper,
        extra,
    }
}

/// Cells of the map that have arrived, out of all.
pub fn map_filled(map: &Map) -> (usize, usize) {
    let done = map.cells.iter().filter(|c| c.is_some()).count();
    (done, map.cells.len())
}
