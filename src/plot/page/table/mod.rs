//! The turntable described once ([`Picture`]): what the page shows, worked out from the
//! explorer's state in world units (R_max) of the frame shown, turned as the picture is. The
//! terminal's canvas (`ui::canvas`) paints it; `E` writes it as a figure ([`figure`]).

mod figure;

pub use figure::figure;

use super::arrows::{ForceArrow, arrows_in};
use crate::app::App;
use crate::engine::model::rotate;
use crate::engine::rod::{RodState, RodTrack};
use crate::engine::{Frame, Outcome, State, Status};
use crate::present::num;
use crate::sim::{Sim, TRAIL_DT};
use glam::DVec2;

/// The words that name the ξ = 1 circle (R_max = μg/Ω²: inside it friction can hold) where
/// static and kinetic friction are the paper's one μ on a table at constant Ω.
pub const RING_LABEL: &str = "ξ=1 (R_max)";
/// The words for the table's sense of rotation (counterclockwise, in both frames).
pub const SENSE_LABEL: &str = "↺ table";
/// The body's centre (at the middle of its bar): a glyph of its own, read without colour.
pub const BODY_GLYPH: &str = "⊕";
/// Where the particle stuck.
pub const STUCK_GLYPH: &str = "×";
/// Markers along a pin's path: at its quarters (and its end, with the label).
const PIN_MARKS: usize = 4;
/// Integrator step mode: the latest step ends shown.
const STEP_MARKS: usize = 500;

/// A sample's position in the frame shown: lab `r`, or `q = R(−τ) r`.
pub fn in_frame(s: &State, frame: Frame) -> DVec2 {
    match frame {
        Frame::Lab => s.r,
        Frame::Table => s.q(),
    }
}

/// The auto-framed half-width: the table, the release point and everything the run's trail
/// reached, a little beyond. The paper's run beside it may widen the view by half at most, so
/// when it escapes it is seen leaving rather than shrinking the table to a dot.
pub fn auto_extent(app: &App) -> f64 {
    let reach = |sim: &Sim| sim.trail().iter().fold(0.0, |m: f64, s| m.max(s.xi()));
    let own = reach(app.sim()).max(app.initial().xi0).max(1.0);
    let m = app
        .paper()
        .map_or(own, |p| own.max(reach(p).min(1.5 * own)));
    // Pins widen it as the paper's run does, so a pinned D (from ξ0 = 1.1) stays in view.
    let m = app.pins().iter().fold(m, |m, p| {
        let r = p.path.iter().fold(0.0, |m: f64, s| m.max(s.xi())) * p.scale(app.units()).0;
        m.max(r.min(1.5 * own))
    });
    (m * 1.1)
        .max(1.5)
        .min(crate::app::exploration::view_radius(&app.initial()) * 1.1)
}

/// The turntable page as shown: every position in world units of the frame shown, turned by
/// the view's turn (a pin by its own) so a release clicked anywhere shows there (the physics
/// is rotationally symmetric: the model keeps its release on +x).
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    pub frame: Frame,
    pub turn: f64,
    /// What the zoom follows (and the pan moves), and the half-width shown about it.
    pub centre: DVec2,
    pub half_width: f64,
    /// World length per unit speed: the release's velocity and the velocity arrow.
    pub speed_scale: f64,
    pub table: Table,
    /// The release point and its velocity as the frame shown sees it, at `speed_scale`.
    pub release: (DVec2, DVec2),
    pub pins: Vec<PinPath>,
    /// The paper's RK2 run (`c`).
    pub paper: Option<Trace>,
    /// The point model; None when hidden (`C`).
    pub point: Option<Point>,
    /// The appendix's finite body, in a body scene that runs one.
    pub body: Option<Body>,
}

/// The table: its edge's radius, its angle in the picture (the rim marks turn with it), the
/// circle inside which friction holds and where the words for the sense go.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    pub r: f64,
    pub spin: f64,
    pub ring: Option<Ring>,
    /// Where [`SENSE_LABEL`] names the sense.
    pub sense: DVec2,
}

/// The circle inside which friction can hold a coin at rest on the table now
/// ([`crate::sim::Motion::hold_radius`]): ξ = 1, R_max, on the paper's table; μ_s/μ_k with
/// static friction above kinetic; on a table spinning up it shrinks as the table speeds up.
/// None where nothing is held (Stokes drag, μ = 0).
#[derive(Clone, Debug, PartialEq)]
pub struct Ring {
    pub r: f64,
    /// Its words ([`RING_LABEL`] where it is R_max) and where they go.
    pub label: String,
    pub at: DVec2,
}

impl Ring {
    /// The ring of radius `r` (`r_max`: it is the paper's R_max) on a picture turned by `turn`.
    fn new(r: f64, r_max: bool, turn: f64) -> Ring {
        Ring {
            r,
            label: if r_max {
                RING_LABEL.into()
            } else {
                format!("friction holds ξ≤{}", num(r, 3))
            },
            // Lower left, running right across the ring; a small ring (a table spun up
            // fast) is named from its lower right, running out, so its words cover no more
            // of it.
            at: rotate(
                if r >= 0.8 {
                    DVec2::new(-0.95, -0.72) * r
                } else {
                    DVec2::new(0.72, -0.72) * r
                },
                turn,
            ),
        }
    }
}

/// A pinned run: its path, its marker along it, its name at its end.
#[derive(Clone, Debug, PartialEq)]
pub struct PinPath {
    pub path: Vec<DVec2>,
    pub marker: char,
    /// The marker and the pin's label: how it reads without colour.
    pub name: String,
    /// Where the marker is printed along the path (its quarters).
    pub marks: Vec<DVec2>,
}

/// A run's path up to the τ on screen and where it is now.
#[derive(Clone, Debug, PartialEq)]
pub struct Trace {
    pub path: Vec<DVec2>,
    pub head: DVec2,
}

/// The point model: its trail, the particle and what is drawn at it.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub trail: Vec<DVec2>,
    pub at: DVec2,
    /// How its run stands, in words.
    pub status: String,
    pub stuck: Option<Stuck>,
    /// The arrows at the particle, turned as the picture is.
    pub arrows: Vec<ForceArrow>,
    /// Integrator step mode: each step's end so far (the latest `STEP_MARKS`), oldest first.
    pub steps: Vec<DVec2>,
}

/// Where and when it stuck: the rest point on the table in the frame shown (in the lab,
/// where that point of the table is now: the particle rides it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stuck {
    pub at: DVec2,
    pub tau: f64,
    /// Its radius (ξ), said on the canvas when it is within [`NEAR_RIM`] of ξ = 1.
    pub xi: f64,
}

/// How near the ξ = 1 circle a stop is said in numbers on the canvas: at a canvas's
/// resolution a stop at ξ = 0.99717 (case C) sits on the circle, read as the rim.
pub const NEAR_RIM: f64 = 0.01;

/// The finite body: its centre's path so far and, while it is shown, its bar (the two
/// masses) and centre.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    pub path: Vec<DVec2>,
    pub bar: Option<([DVec2; 2], DVec2)>,
}

impl Table {
    /// Three short marks on the rim at the table's angle: they show it turning.
    pub fn rim_marks(&self) -> [[DVec2; 2]; 3] {
        std::array::from_fn(|k| {
            let d = rotate(
                DVec2::X,
                self.spin + k as f64 * 2.0 * std::f64::consts::PI / 3.0,
            );
            [d * 0.9 * self.r, d * self.r]
        })
    }
}

impl Stuck {
    /// Its words: the glyph and when, and where when that is within [`NEAR_RIM`] of ξ = 1,
    /// so that a stop just inside reads apart from the circle it seems to sit on.
    pub fn label(&self) -> String {
        if (1.0 - self.xi).abs() < NEAR_RIM {
            let side = if self.xi < 1.0 { "<" } else { ">" };
            return format!(
                "{STUCK_GLYPH} stuck ξ={}{side}1 τ={}",
                num(self.xi, 5),
                num(self.tau, 2)
            );
        }
        format!("{STUCK_GLYPH} stuck τ={}", num(self.tau, 2))
    }
}

impl Picture {
    /// The turntable page of `app` as it stands.
    pub fn of(app: &App) -> Picture {
        Picture::in_frame(app, app.view().frame)
    }

    /// The turntable page of `app` as `frame` sees it (a split view draws both).
    pub fn in_frame(app: &App, frame: Frame) -> Picture {
        let turn = app.view().turn;
        let now = app.sim().now();
        let motion = app.sim().motion();
        let i = app.initial();
        let extent = auto_extent(app);
        let half_width = extent / app.view().zoom;
        let speed_scale = 0.3 * extent / i.xi0.max(1.0);
        let body = app.rod().map(|rod| Body::of(rod, now.tau, frame, turn));
        let point = app
            .point_shown()
            .then(|| Point::of(app, frame, half_width, speed_scale));
        // Zoomed in, the view follows the particle, or the body's centre with the point hidden.
        let followed = match (&point, body.as_ref().and_then(|b| b.bar)) {
            _ if app.view().zoom <= 1.0 => DVec2::ZERO,
            (None, Some((_, centre))) => centre,
            _ => rotate(motion.in_frame(&now, frame), turn),
        };
        let r = 1.5f64.max(i.xi0 * 1.2);
        let s0 = motion.start();
        let v0 = match frame {
            Frame::Lab => s0.v,
            Frame::Table => motion.u(&s0),
        };
        Picture {
            frame,
            turn,
            centre: followed + app.view().pan * extent,
            half_width,
            speed_scale,
            table: Table {
                r,
                spin: turn
                    + match frame {
                        Frame::Lab => motion.table_angle(now.tau),
                        Frame::Table => 0.0,
                    },
                ring: motion.hold_radius(now.tau).map(|h| {
                    let paper = matches!(motion, crate::sim::Motion::Steady(_)) && h == 1.0;
                    Ring::new(h, paper, turn)
                }),
                sense: DVec2::new(-0.8, 0.62) * r,
            },
            release: (
                rotate(DVec2::new(i.xi0, 0.0), turn),
                rotate(v0, turn) * speed_scale,
            ),
            pins: app
                .pins()
                .iter()
                .map(|p| PinPath::of(p, app, frame))
                .collect(),
            paper: app.paper().map(|p| Trace {
                path: shown(p, frame, turn),
                head: rotate(p.motion().in_frame(&p.now(), frame), turn),
            }),
            point,
            body,
        }
    }
}

/// The path of `sim` up to the τ on screen (a fixed τ grid, see [`TRAIL_DT`]), joined to
/// where it is now while the path is still growing there.
fn shown(sim: &Sim, frame: Frame, turn: f64) -> Vec<DVec2> {
    let path = sim.trail();
    let now = sim.now();
    let tail = path
        .last()
        .filter(|l| now.tau > l.tau && now.tau - l.tau <= TRAIL_DT)
        .map(|_| now);
    path.iter()
        .chain(tail.as_ref())
        .map(|s| rotate(sim.motion().in_frame(s, frame), turn))
        .collect()
}

impl PinPath {
    fn of(p: &crate::pin::Pin, app: &App, frame: Frame) -> PinPath {
        let k = p.scale(app.units()).0;
        let path: Vec<DVec2> = p
            .path
            .iter()
            .map(|s| rotate(in_frame(s, frame), p.spec.turn) * k)
            .collect();
        let n = path.len();
        let marks = (1..PIN_MARKS)
            .filter_map(|k| path.get(k * n.saturating_sub(1) / PIN_MARKS).copied())
            .collect();
        PinPath {
            path,
            marker: p.marker,
            name: format!("{}{}", p.marker, p.spec.label),
            marks,
        }
    }

    /// The last point of the path inside the box `x` × `y`: its end, or where an escape
    /// leaves the view (labelled there).
    pub fn end_in(&self, x: [f64; 2], y: [f64; 2]) -> Option<DVec2> {
        let inside = |q: &DVec2| (x[0]..=x[1]).contains(&q.x) && (y[0]..=y[1]).contains(&q.y);
        self.path.iter().rev().copied().find(inside)
    }
}

impl Point {
    /// The point model of `app` in `frame`, its force arrows scaled to `half_width`, its velocity by
    /// `speed_scale`.
    fn of(app: &App, frame: Frame, half_width: f64, speed_scale: f64) -> Point {
        let turn = app.view().turn;
        let now = app.sim().now();
        let motion = app.sim().motion();
        let stuck = match app.sim().status() {
            Status::Stuck { tau, q } if now.tau >= tau => {
                let at = match frame {
                    Frame::Lab => rotate(q, motion.table_angle(now.tau)),
                    Frame::Table => q,
                };
                Some(Stuck {
                    at: rotate(at, turn),
                    tau,
                    xi: q.length(),
                })
            }
            _ => None,
        };
        let status = match app.sim().outcome_now() {
            Outcome::Stuck => format!("stuck at ξ = {}", num(now.xi(), 5)),
            Outcome::Escaped => "escaped".into(),
            Outcome::Running => format!("τ = {}", num(now.tau, 3)),
        };
        let mut steps: Vec<DVec2> = Vec::new();
        if app.view().step_mode {
            steps = app
                .sim()
                .step_marks
                .iter()
                .filter(|m| m.tau <= now.tau)
                .map(|m| rotate(motion.in_frame(m, frame), turn))
                .collect();
            steps.drain(..steps.len().saturating_sub(STEP_MARKS));
        }
        Point {
            trail: shown(app.sim(), frame, turn),
            at: rotate(motion.in_frame(&now, frame), turn),
            status,
            stuck,
            arrows: arrows_in(app, frame, half_width, speed_scale)
                .into_iter()
                .map(|a| ForceArrow {
                    vec: rotate(a.vec, turn),
                    ..a
                })
                .collect(),
            steps,
        }
    }
}

impl Body {
    fn of(rod: &RodTrack, tau: f64, frame: Frame, turn: f64) -> Body {
        let n = rod.states.partition_point(|s| s.tau <= tau);
        let spin = |s: &RodState| turn + if frame == Frame::Lab { s.tau } else { 0.0 };
        // Where an escaping body left the view once its track has followed it out: kept
        // there, as the point is.
        let bar = rod.at(tau).or_else(|| rod.left().filter(|s| tau >= s.tau));
        Body {
            path: rod.states[..n]
                .iter()
                .map(|s| rotate(s.q, spin(s)))
                .collect(),
            bar: bar.map(|s| {
                (
                    s.contacts(rod.l).map(|c| rotate(c, spin(&s))),
                    rotate(s.q, spin(&s)),
                )
            }),
        }
    }
}
