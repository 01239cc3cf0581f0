//! The time plots' panels: ξ, θ (Θ), θ′ (Θ′ in the rotating view), |u| and the energy
//! identity dE/dτ = −|u| against τ, with the paper's Sec. III approximations (Eqs. 12–13,
//! 19–20) over their window for releases at rest, the paper's RK2 run beside the converged
//! one and the pins': what the page draws and `E` writes.

use super::super::{Chart, Ink, Mark, Scale, Series, Style, extent};
use crate::app::App;
use crate::engine::approx::table_rest;
use crate::engine::{Frame, Release, State, Status};
use crate::present::{Quantity, num};

/// Markers along a pin's line: at its thirds (and its end, with the label).
const PIN_MARKS: usize = 3;

/// The run's path up to the τ on screen, ending exactly there.
fn path(sim: &crate::sim::Sim) -> Vec<State> {
    let mut p = sim.trail().to_vec();
    let now = sim.now();
    if p.last().is_none_or(|s| s.tau < now.tau) {
        p.push(now);
    }
    p
}

/// What a plot draws of a path: its points (τ, y).
type PathPoints<'a> = dyn Fn(&[State]) -> Vec<(f64, f64)> + 'a;

/// One quantity of a path against τ, as points.
fn along(path: &[State], y: &dyn Fn(&State) -> f64) -> Vec<(f64, f64)> {
    path.iter().map(|s| (s.tau, y(s))).collect()
}

/// One quantity of a path against τ.
fn series(name: &str, ink: Ink, path: &[State], y: impl Fn(&State) -> f64) -> Series {
    Series {
        name: name.into(),
        ink,
        points: along(path, &y),
        style: Style::Line { dash: 0 },
    }
}

/// The five panels in order (ξ, θ, θ′, |u|, energy) over the τ window (the run so far, or
/// a span the user fixed: t / T), aligned in τ with the cursor at the τ on screen, the stop
/// and the escape certificate marked; each y range is what the window shows.
pub fn panels(app: &App) -> Vec<Chart> {
    let now = app.sim().now().tau;
    let span = app.view().tau_window.unwrap_or(app.plot_span()).max(1e-3);
    let window = crate::engine::approx::window(&app.initial());
    let marks = marks(app, now);
    // The window's end is marked only where Sec. III's approximation holds within it: ξ, and
    // in the lab θ and θ′ (on the table Eq. 20 drops the friction term: at ξ0 = 1.1 its Θ′ is
    // 1 + 1/(2(ξ0 − 1)) = 6 times the run's).
    let lab = app.initial().release == Release::LabRest;
    let window_mark = window.filter(|w| *w <= now).map(|w| Mark::VLine {
        x: w,
        label: "approx. valid ←".into(),
        ink: Ink::Muted,
    });
    let mut panels: Vec<Chart> = plots(app, now, window)
        .into_iter()
        .enumerate()
        .map(|(k, (name, measure, s, pm))| Chart {
            y: extent(
                s.iter()
                    .flat_map(|s| s.points.iter().filter(|p| p.0 <= span).map(|p| p.1)),
            ),
            x_label: super::super::axis("τ", Quantity::Time, app.units()),
            y_label: match measure {
                Measure::Si(q) => super::super::axis(name, q, app.units()),
                Measure::Angle => format!("{name} (rad)"),
                Measure::Bare => name.into(),
            },
            y_scale: match measure {
                Measure::Angle => Scale::Angle,
                _ => Scale::Plain,
            },
            x: [0.0, span],
            series: s,
            // The pins' labels last: placed first, so where a short plot has no room for
            // all, the run's own (τ, stop, escape) are drawn over them.
            marks: marks
                .iter()
                .cloned()
                .chain(window_mark.clone().filter(|_| k == 0 || (lab && k <= 2)))
                .chain(pm)
                .collect(),
            ..Chart::default()
        })
        .collect();
    if let Some(xi) = panels.first_mut() {
        near_the_rim(app, xi, span);
    }
    panels
}

/// The ξ plot near the rim: ξ = 1 drawn where the plot reaches it, and, with the paper's RK2
/// beside a run that stopped just inside ξ = 1, zoomed on the stop (a few times its distance
/// from the rim each way), where a stop at 0.997 is told from the rim and the paper's run is
/// seen crossing it and leaving through the top.
fn near_the_rim(app: &App, xi: &mut Chart, span: f64) {
    if xi.y[0] > 1.2 || xi.y[1] < 0.8 {
        return;
    }
    xi.series.push(Series {
        name: "ξ = 1 (R_max)".into(),
        ink: Ink::Muted,
        points: vec![(0.0, 1.0), (span, 1.0)],
        style: Style::Line { dash: 1 },
    });
    xi.y = [xi.y[0].min(1.0), xi.y[1].max(1.0)];
    if let (Some(_), Status::Stuck { tau, q }) = (app.paper(), app.sim().status())
        && tau <= app.sim().now().tau
        && (0.95..1.0).contains(&q.length())
    {
        let gap = 1.0 - q.length();
        xi.y = [1.0 - 4.0 * gap, 1.0 + 4.0 * gap];
        xi.y_label = format!("{} (zoom on the stop)", xi.y_label);
    }
}

/// The lines every plot marks: the cursor at the τ on screen, the stop and the escape
/// certificate, once reached.
fn marks(app: &App, now: f64) -> Vec<Mark> {
    let mut marks = vec![Mark::VLine {
        x: now,
        label: format!("τ={}", num(now, 2)),
        ink: Ink::Accent,
    }];
    if let Status::Stuck { tau, .. } = app.sim().status()
        && tau <= now
    {
        marks.push(Mark::VLine {
            x: tau,
            label: "stop".into(),
            ink: Ink::Stuck,
        });
    }
    if let Some(e) = app.sim().escape()
        && e.tau <= now
    {
        marks.push(Mark::VLine {
            x: e.tau,
            label: "escape cert.".into(),
            ink: Ink::Escaped,
        });
    }
    marks
}

/// What a plot's y axis measures: a quantity with an SI unit, an angle (in radians, read in
/// π), or a number alone (the energy's two sides).
#[derive(Clone, Copy)]
enum Measure {
    Si(Quantity),
    Angle,
    Bare,
}

/// One plot: its y axis name, what it measures, its series and its own marks (the pins').
type Plot<'a> = (&'a str, Measure, Vec<Series>, Vec<Mark>);

/// What the plots draw from: the run's path, the paper's, the pins', the approximations.
struct Sources<'a> {
    app: &'a App,
    /// The run's path and the paper's, up to the τ on screen.
    p: Vec<State>,
    paper: Option<Vec<State>>,
    now: f64,
    window: Option<f64>,
    /// The pins' markers per plot (ξ, θ, θ′, |u|).
    pin_marks: [Vec<Mark>; 4],
}

impl Sources<'_> {
    /// The approximation `y` over its window, as dots: told from the run's line without
    /// colour.
    fn approx(&self, name: &str, y: &dyn Fn(f64) -> Option<f64>) -> Option<Series> {
        self.window?;
        let n = 200;
        let now = self.now;
        let pts = (0..=n)
            .map(|k| now * k as f64 / n as f64)
            .filter_map(|t| y(t).map(|v| (t, v)))
            .collect();
        Some(Series {
            name: name.into(),
            ink: Ink::Muted,
            points: pts,
            style: Style::Dots,
        })
    }

    /// The paper's RK2 beside the run: the legend names the scheme (the plot names the
    /// variable, never twice: not `ξ ━ ξ`).
    fn paper_series(&self, y: &dyn Fn(&State) -> f64) -> Option<Series> {
        self.paper.as_ref().map(|pp| Series {
            name: PAPER.into(),
            ink: Ink::Paper,
            points: pp.iter().map(|s| (s.tau, y(s))).collect(),
            style: Style::Line { dash: 0 },
        })
    }

    /// Each pin dimmer, named in the legend by its marker and label, the marker along its
    /// line and the label at its end (into plot `k`'s marks): told apart without colour.
    /// `dims`: the powers of length and time in the plot's y, to convert a pin run on
    /// another table (ξ: length; θ′: 1/time; |u|: length/time).
    fn pin_series(&mut self, k: usize, dims: (i32, i32), y: &PathPoints<'_>) -> Vec<Series> {
        let app = self.app;
        let pin_marks = &mut self.pin_marks;
        app.pins()
            .iter()
            .map(|pin| {
                let (kl, kt) = pin.scale(app.units());
                let ky = kl.powi(dims.0) * kt.powi(dims.1);
                let points: Vec<(f64, f64)> = y(&pin.path)
                    .into_iter()
                    .map(|(x, y)| (x * kt, y * ky))
                    .collect();
                let n = points.len();
                for j in 1..PIN_MARKS {
                    let (x, y) = points[j * (n - 1) / PIN_MARKS];
                    pin_marks[k].push(Mark::Text {
                        x,
                        y,
                        label: pin.marker.to_string(),
                        ink: Ink::Muted,
                    });
                }
                let (x, y) = points[n - 1];
                pin_marks[k].push(Mark::Text {
                    x,
                    y,
                    label: format!("{}{}", pin.marker, pin.spec.label),
                    ink: Ink::Muted,
                });
                Series {
                    name: format!("{}{}", pin.marker, pin.spec.label),
                    ink: Ink::Muted,
                    points,
                    style: Style::Line { dash: 0 },
                }
            })
            .collect()
    }
}

/// θ unwrapped along the path (Figs. 1–2), Θ = θ − τ in the rotating view (`shift` 1).
fn unwrapped_angle(path: &[State], shift: f64) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(path.len());
    let mut last = 0.0;
    let mut turns = 0.0;
    for (k, s) in path.iter().enumerate() {
        let a = s.r.y.atan2(s.r.x);
        if k > 0 {
            let d = a - last;
            turns -= std::f64::consts::TAU * (d / std::f64::consts::TAU).round();
        }
        last = a;
        out.push((s.tau, a + turns - shift * s.tau));
    }
    out
}

/// The approximation's θ: its θ′ `rate` integrated (trapezoids on its own 200 points).
fn integrated(rate: &Series, ink: Ink) -> Series {
    let mut acc = 0.0;
    let pts = rate
        .points
        .iter()
        .enumerate()
        .map(|(k, &(t, v))| {
            if k > 0 {
                let (t0, v0) = rate.points[k - 1];
                acc += 0.5 * (t - t0) * (v + v0);
            }
            (t, acc)
        })
        .collect();
    Series {
        name: rate.name.clone(),
        ink,
        points: pts,
        style: Style::Dots,
    }
}

/// The five plots in order: ξ, θ (Θ), θ′ (Θ′), |u| and the energy identity.
/// The legend's name for Sec. III's approximations where they hold.
const APPROX: &str = "Sec. III approx.";
/// The legend's names for the run on screen and the paper's scheme beside it.
const RUN: &str = "run";
const PAPER: &str = "paper RK2";

fn plots(app: &App, now: f64, window: Option<f64>) -> [Plot<'static>; 5] {
    let rotating = app.view().frame == Frame::Table;
    let (theta_name, shift) = if rotating {
        ("Θ′", 1.0)
    } else {
        ("θ′", 0.0)
    };
    let mut src = Sources {
        app,
        p: path(app.sim()),
        paper: app.paper().map(path),
        now,
        window,
        pin_marks: Default::default(),
    };
    let i = app.initial();
    let xi_of = |s: &State| s.xi();
    let th_of = move |s: &State| s.theta_dot().map_or(f64::NAN, |t| t - shift);
    let u_of = |s: &State| s.u_lab().length();
    let angle = move |path: &[State]| unwrapped_angle(path, shift);
    let mut xi_s = vec![series(RUN, Ink::Trail, &src.p, xi_of)];
    xi_s.extend(src.paper_series(&xi_of));
    xi_s.extend(src.pin_series(0, (1, 0), &|p| along(p, &xi_of)));
    xi_s.extend(src.approx(APPROX, &|t| Some(crate::engine::approx::xi(&i, t))));
    let mut th_s = vec![series(RUN, Ink::Trail, &src.p, th_of)];
    th_s.extend(src.paper_series(&th_of));
    th_s.extend(src.pin_series(2, (0, -1), &|p| along(p, &th_of)));
    // On the table Eq. 20 drops the friction term, which near the release is the larger:
    // the legend says so.
    let th_approx = match i.release {
        Release::LabRest => APPROX,
        _ => "Eq. 20, friction dropped",
    };
    th_s.extend(src.approx(th_approx, &|t| match i.release {
        // θ = τ²/(2ξ0) (Eq. 12): θ′ = τ/ξ0 in the lab.
        Release::LabRest => Some(t / i.xi0 - shift),
        // Θ′ = 2 ln(ξ0/ξ) (Eq. 20), table frame.
        _ => Some(table_rest(i.xi0, t).1 + 1.0 - shift),
    }));
    let angle_name = if rotating { "Θ" } else { "θ" };
    let mut a_s = vec![Series {
        name: RUN.into(),
        ink: Ink::Trail,
        points: angle(&src.p),
        style: Style::Line { dash: 0 },
    }];
    a_s.extend(src.paper.as_ref().map(|pp| Series {
        name: PAPER.into(),
        ink: Ink::Paper,
        points: angle(pp),
        style: Style::Line { dash: 0 },
    }));
    a_s.extend(src.pin_series(1, (0, 0), &angle));
    if let Some(rate) = th_s.iter().find(|s| s.name == th_approx) {
        a_s.push(integrated(rate, Ink::Muted));
    }
    let mut u_s = vec![series(RUN, Ink::Trail, &src.p, u_of)];
    u_s.extend(src.paper_series(&u_of));
    u_s.extend(src.pin_series(3, (1, -1), &|p| along(p, &u_of)));
    let drag = if app.initial().frictionless {
        None
    } else {
        app.settings().stokes()
    };
    let [xi_m, a_m, th_m, u_m] = std::mem::take(&mut src.pin_marks);
    [
        ("ξ", Measure::Si(Quantity::Length), xi_s, xi_m),
        (angle_name, Measure::Angle, a_s, a_m),
        (theta_name, Measure::Si(Quantity::Rate), th_s, th_m),
        ("|u|", Measure::Si(Quantity::Speed), u_s, u_m),
        (
            if drag.is_some() {
                "E = ½|u|² − ½ξ² (table frame), dE/dτ = −γ|u|²:"
            } else {
                "E = ½|u|² − ½ξ² (table frame), dE/dτ = −|u|:"
            },
            Measure::Bare,
            energy_series(&src.p, app.sim(), drag),
            Vec::new(),
        ),
    ]
}

/// The energy identity's two sides: E − E(0) as a line, the run's work tally as dots.
fn energy_series(p: &[State], sim: &crate::sim::Sim, drag: Option<f64>) -> Vec<Series> {
    let [e, w] = super::super::build::energy_pair(p, sim.trail(), sim.trail_work());
    vec![
        Series {
            name: "E − E(0)".into(),
            ink: Ink::Trail,
            points: e,
            style: Style::Line { dash: 0 },
        },
        Series {
            name: if drag.is_some() {
                "−γ∫|u|²dτ"
            } else {
                "−∫|u|dτ"
            }
            .into(),
            ink: Ink::Centrifugal,
            points: w,
            style: Style::Dots,
        },
    ]
}
