//! The figures from their data, shared by `turntable plot` (which computes the data with the
//! engine and the analysis) and the explorer's `E` (which takes what it already holds). Axis
//! names carry the paper's units: lengths in R_max = μg/Ω², time in 1/Ω, speeds in μg/Ω.

use super::{Chart, Figure, Ink, Mark, Scale, Series, Style, extent};
use crate::engine::{Frame, Initial, State};
use crate::present::num;
use std::f64::consts::TAU;

const TAU_AXIS: &str = "τ (1/Ω)";
const PHI_AXIS: &str = "φ, direction of the throw from radially outward (rad)";
const VE_AXIS: &str = "v_e, escape speed (μg/Ω)";

/// The circle ξ = 1, where friction can just hold a particle at rest on the table.
fn rim() -> Series {
    let pts = (0..=180)
        .map(|k| {
            let a = TAU * f64::from(k) / 180.0;
            (a.cos(), a.sin())
        })
        .collect();
    Series::line("ξ = 1 (R_max)", 2, pts)
}

/// One run a trajectory figure draws: its name, its path, and how it ended.
pub struct Traced<'a> {
    pub name: String,
    pub path: &'a [State],
    pub end: String,
}

/// Paths in the plane of `frame` (lab: r; rotating: the table-frame position q), with the rim,
/// each release with its initial velocity (lab: v; rotating: u, relative to the table) as an
/// arrow, and where each path ends, labelled by its `end` (and its name when there are
/// several).
pub fn trajectory(title: &str, runs: &[Traced], frame: Frame) -> Figure {
    let at = |s: &State| {
        let p = match frame {
            Frame::Lab => s.r,
            Frame::Table => s.q(),
        };
        (p.x, p.y)
    };
    let paths: Vec<Vec<(f64, f64)>> = runs
        .iter()
        .map(|r| r.path.iter().map(at).collect())
        .collect();
    let reach = paths
        .iter()
        .flatten()
        .map(|(x, y)| x.abs().max(y.abs()))
        .fold(1.0_f64, f64::max)
        * 1.08;
    let mut marks = Vec::new();
    let mut arrows = Vec::new();
    // A release, and its initial velocity, that several runs share is marked once, named by
    // those runs (by none when all share it): the same spot labelled twice wrote the labels
    // over one another.
    let release = |k: usize| {
        let s0 = runs[k].path.first()?;
        let (v, word) = match frame {
            Frame::Lab => (s0.v, "v0"),
            Frame::Table => (s0.u(), "u0"),
        };
        Some((*paths[k].first()?, (v.x, v.y), word, s0.xi()))
    };
    for (k, (r, pts)) in runs.iter().zip(&paths).enumerate() {
        let named = |what: &str| match runs.len() {
            1 => what.to_string(),
            _ => format!("{}: {what}", r.name),
        };
        let (Some(&last), Some((first, v, word, xi0))) = (pts.last(), release(k)) else {
            continue;
        };
        let end = Mark::Point {
            x: last.0,
            y: last.1,
            label: named(&r.end),
            ink: Ink::Foreground,
        };
        let same: Vec<usize> = (0..runs.len())
            .filter(|&j| release(j).is_some_and(|(f, w, _, _)| f == first && w == v))
            .collect();
        if same[0] != k {
            marks.push(end);
            continue;
        }
        let shared = |what: &str| match same.len() {
            1 => named(what),
            n if n == runs.len() => what.to_string(),
            _ => {
                let names: Vec<&str> = same.iter().map(|&j| runs[j].name.as_str()).collect();
                format!("{}: {what}", names.join(", "))
            }
        };
        marks.push(Mark::Point {
            x: first.0,
            y: first.1,
            label: shared("release"),
            ink: Ink::Foreground,
        });
        marks.push(end);
        // As the canvas draws it: 0.3 of the view's reach per unit speed, beyond ξ = 1 less.
        let k = 0.3 * reach / xi0.max(1.0);
        arrows.push(Mark::Arrow {
            from: first,
            to: (first.0 + k * v.0, first.1 + k * v.1),
            label: shared(word),
            ink: Ink::Arrow,
        });
    }
    marks.append(&mut arrows);
    let (name, axes) = match frame {
        Frame::Lab => ("lab frame", ("x (R_max)", "y (R_max)")),
        Frame::Table => (
            "rotating frame (the table's)",
            ("x on the table (R_max)", "y on the table (R_max)"),
        ),
    };
    let mut series: Vec<Series> = runs
        .iter()
        .zip(paths)
        .enumerate()
        .map(|(k, (r, pts))| Series::line(&r.name, k, pts))
        .collect();
    series.push(rim());
    Figure {
        title: title.into(),
        panels: vec![Chart {
            title: format!("path in the {name}"),
            x_label: axes.0.into(),
            y_label: axes.1.into(),
            x: [-reach, reach],
            y: [-reach, reach],
            equal_aspect: true,
            series,
            marks,
            ..Chart::default()
        }],
    }
}

/// The time plots of a run released as `initial`: ξ, θ′, |u| and the energy identity
/// E − E(0) = −∫|u|dτ (the run's work at each point of the path, `work`) against τ, with the
/// stop marked at `stop` (if any). A release at rest shows Sec. III's ξ beside the run's, and
/// the figure frames twice the window where it holds when the run goes on beyond that.
pub fn time(
    title: &str,
    initial: &Initial,
    path: &[State],
    work: &[f64],
    stop: Option<f64>,
) -> Figure {
    let over = |f: &dyn Fn(&State) -> f64| -> Vec<(f64, f64)> {
        path.iter().map(|s| (s.tau, f(s))).collect()
    };
    let x = extent(path.iter().map(|s| s.tau));
    let window = crate::engine::approx::window(initial);
    let x = [
        path.first().map_or(x[0], |s| s.tau),
        window.map_or(x[1], |w| x[1].min(2.0 * w)),
    ];
    let marks: Vec<Mark> = stop
        .map(|t| Mark::VLine {
            x: t,
            label: format!("stuck τ={}", num(t, 3)),
            ink: Ink::Stuck,
        })
        .into_iter()
        .collect();
    let mut xi = vec![Series::line("ξ", 0, over(&State::xi))];
    let window_mark = window.map(|w| Mark::VLine {
        x: w,
        label: "approx. valid ←".into(),
        ink: Ink::Muted,
    });
    if window.is_some() {
        let pts = (0..=200)
            .map(|k| x[1] * f64::from(k) / 200.0)
            .map(|t| (t, crate::engine::approx::xi(initial, t)))
            .collect();
        xi.push(Series::new("Sec. III approx.", Ink::Trail, false, pts));
    }
    // Each y range is what the τ range shows.
    let panel = |title: &str, y_label: &str, series: Vec<Series>| Chart {
        title: title.into(),
        x_label: TAU_AXIS.into(),
        y_label: y_label.into(),
        x,
        y: extent(
            series
                .iter()
                .flat_map(|s| s.points.iter().filter(|p| p.0 <= x[1]).map(|p| p.1)),
        ),
        equal_aspect: false,
        series,
        marks: marks.clone(),
        ..Chart::default()
    };
    // The window's end is marked where the approximation is drawn: the ξ plot.
    let mut xi_panel = panel("distance from the centre", "ξ (R_max)", xi);
    xi_panel.marks.extend(window_mark);
    let [e, w] = energy_pair(path, path, work);
    Figure {
        title: title.into(),
        panels: vec![
            xi_panel,
            panel(
                "angular speed in the lab",
                "θ′ (Ω)",
                vec![Series::line(
                    "θ′",
                    0,
                    over(&|s| s.theta_dot().unwrap_or(f64::NAN)),
                )],
            ),
            panel(
                "speed relative to the table",
                "|u| (μg/Ω)",
                vec![Series::line("|u|", 0, over(&|s| s.u_lab().length()))],
            ),
            panel(
                "energy in the table's frame, E = ½|u|² − ½ξ²: dE/dτ = −|u|",
                "(μg/Ω)²",
                vec![
                    Series::line("E − E(0)", 0, e),
                    Series::line("−∫|u|dτ", 1, w),
                ],
            ),
        ],
    }
}

/// Fig. 5: v_e over φ, one curve per ξ0 (`curves`: ξ0 and its points), and a release
/// marked if given (φ, v0, label).
pub fn escape_speed(
    title: &str,
    curves: &[(f64, Vec<(f64, f64)>)],
    release: Option<(f64, f64, String)>,
) -> Figure {
    let series: Vec<Series> = curves
        .iter()
        .enumerate()
        .map(|(k, (xi0, pts))| Series::line(&format!("ξ0 = {xi0}"), k, pts.clone()))
        .collect();
    let top = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .chain(release.iter().map(|r| r.1))
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    Figure {
        title: title.into(),
        panels: vec![Chart {
            title: "escape speed against the direction of the throw (Fig. 5)".into(),
            x_label: PHI_AXIS.into(),
            x_scale: Scale::Angle,
            y_label: VE_AXIS.into(),
            x: [0.0, TAU],
            y: [0.0, (1.1 * top).max(0.1)],
            equal_aspect: false,
            series,
            marks: release
                .map(|(x, y, label)| Mark::Point {
                    x,
                    y,
                    label,
                    ink: Ink::Particle,
                })
                .into_iter()
                .collect(),
            ..Chart::default()
        }],
    }
}

/// Fig. 6: where a release at rest in the lab stops, against ξ0 (`None`: it escaped; the
/// line breaks there), with ξ0c marked if known.
pub fn rest_radius(title: &str, points: &[(f64, Option<f64>)], xi0c: Option<f64>) -> Figure {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .map(|&(x, r)| (x, r.unwrap_or(f64::NAN)))
        .collect();
    let x = [
        0.0,
        points.iter().map(|p| p.0).fold(0.0_f64, f64::max).max(1e-3),
    ];
    Figure {
        title: title.into(),
        panels: vec![Chart {
            title: "released at rest in the lab: where it stops (Fig. 6); beyond ξ0c it escapes"
                .into(),
            x_label: "ξ0, release radius (R_max)".into(),
            y_label: "ξ, final rest radius (R_max)".into(),
            x,
            y: [0.0, 1.05],
            equal_aspect: false,
            series: vec![Series::line("rest ξ", 0, pts)],
            marks: xi0c
                .map(|c| Mark::VLine {
                    x: c,
                    label: format!("ξ0c = {}", num(c, 6)),
                    ink: Ink::Escaped,
                })
                .into_iter()
                .collect(),
            ..Chart::default()
        }],
    }
}

/// The outcome map over (φ, v0): cells of `size` = angles × speeds up to `v0_max`, shaded by
/// where a stuck release rests (blank: it escapes), with the escape-speed curve over them.
pub fn outcome_map(
    title: &str,
    cells: &[(f64, f64, Option<f64>)],
    size: (usize, usize),
    v0_max: f64,
    curve: Option<Vec<(f64, f64)>>,
    v_axis: &str,
) -> Figure {
    let mut series = cells_by_rest(cells, size, v0_max);
    if let Some(pts) = curve {
        series.push(Series::line("v_e(φ)", 0, pts));
    }
    Figure {
        title: title.into(),
        panels: vec![Chart {
            title: "how a throw ends: shaded, it stops (by where); blank, it escapes".into(),
            x_label: PHI_AXIS.into(),
            x_scale: Scale::Angle,
            y_label: v_axis.into(),
            x: [0.0, TAU],
            y: [0.0, v0_max],
            equal_aspect: false,
            series,
            marks: vec![],
            ..Chart::default()
        }],
    }
}

/// An outcome map's cells over (φ, v0) (`size` = angles × speeds up to `v0_max`) as four
/// series shaded by where a stuck release rests; an escape is blank.
pub fn cells_by_rest(
    cells: &[(f64, f64, Option<f64>)],
    size: (usize, usize),
    v0_max: f64,
) -> Vec<Series> {
    let (w, h) = (TAU / size.0.max(1) as f64, v0_max / size.1.max(1) as f64);
    let bands = [
        ("stuck, rest ξ < ¼", 0.0, 0.25, 0.12),
        ("stuck, ¼ ≤ ξ < ½", 0.25, 0.5, 0.3),
        ("stuck, ½ ≤ ξ < ¾", 0.5, 0.75, 0.5),
        ("stuck, ξ ≥ ¾", 0.75, f64::INFINITY, 0.7),
    ];
    bands
        .iter()
        .map(|&(name, lo, hi, shade)| Series {
            name: name.into(),
            points: cells
                .iter()
                .filter(|c| c.2.is_some_and(|xi| (lo..hi).contains(&xi)))
                .map(|c| (c.0, c.1))
                .collect(),
            style: Style::Cells { w, h, shade },
            ink: Ink::Stuck,
        })
        .collect()
}

/// E − E(0) along `path`, beside the work done up to each point of `grid` (`work`, the run's
/// own tally, `engine::work`): the two sides of dE/dτ = −|u|.
pub fn energy_pair(path: &[State], grid: &[State], work: &[f64]) -> [Vec<(f64, f64)>; 2] {
    let e0 = path.first().map_or(0.0, State::energy);
    [
        path.iter().map(|s| (s.tau, s.energy() - e0)).collect(),
        grid.iter().zip(work).map(|(s, w)| (s.tau, *w)).collect(),
    ]
}
