//! The turntable's [`Picture`] as a figure for `E`: what the canvas paints, from the same
//! description, square about the same centre.

use super::{BODY_GLYPH, Picture, SENSE_LABEL};
use crate::app::App;
use crate::engine::Frame;
use crate::plot::{Chart, Figure, Ink, Mark, Series};
use glam::DVec2;
use std::f64::consts::TAU;

/// A circle of radius `r` about the centre, as a closed line.
fn circle(r: f64) -> Vec<(f64, f64)> {
    (0..=180)
        .map(|k| {
            let a = TAU * f64::from(k) / 180.0;
            (r * a.cos(), r * a.sin())
        })
        .collect()
}

fn xy(p: &[DVec2]) -> Vec<(f64, f64)> {
    p.iter().map(|p| (p.x, p.y)).collect()
}

fn text(p: DVec2, label: impl Into<String>, ink: Ink) -> Mark {
    Mark::Text {
        x: p.x,
        y: p.y,
        label: label.into(),
        ink,
    }
}

fn point(p: DVec2, label: impl Into<String>, ink: Ink) -> Mark {
    Mark::Point {
        x: p.x,
        y: p.y,
        label: label.into(),
        ink,
    }
}

fn arrow(from: DVec2, vec: DVec2, label: impl Into<String>, ink: Ink) -> Mark {
    let to = from + vec;
    Mark::Arrow {
        from: (from.x, from.y),
        to: (to.x, to.y),
        label: label.into(),
        ink,
    }
}

/// The turntable page of `app` as a figure titled `title`: one panel, or in a split view
/// (`%`) one for each frame, the frame chosen first, as the canvas shows them.
pub fn figure(app: &App, title: String) -> Figure {
    let mut frames = vec![app.view().frame];
    if app.view().split {
        frames.push(match app.view().frame {
            Frame::Lab => Frame::Table,
            Frame::Table => Frame::Lab,
        });
    }
    Figure {
        title,
        panels: frames.into_iter().map(|f| panel(app, f)).collect(),
    }
}

/// The turntable as `frame` sees it, one panel.
fn panel(app: &App, frame: Frame) -> Chart {
    let pic = Picture::in_frame(app, frame);
    let (c, r) = (pic.centre, pic.half_width);
    let (x, y) = ([c.x - r, c.x + r], [c.y - r, c.y + r]);
    let (mut series, mut marks) = table(&pic);
    for p in &pic.pins {
        series.push(Series::new(&p.name, Ink::Muted, true, xy(&p.path)));
        let along = p.marks.iter().map(|&m| text(m, p.marker, Ink::Muted));
        marks.extend(along);
        if let Some(end) = p.end_in(x, y) {
            marks.push(text(end, &p.name, Ink::Muted));
        }
    }
    if let Some(paper) = &pic.paper {
        let name = "the paper's RK2 run (c)";
        series.push(Series::new(name, Ink::Paper, true, xy(&paper.path)));
        marks.push(point(paper.head, "paper's RK2", Ink::Paper));
    }
    let (at, v) = pic.release;
    marks.push(arrow(at, v, "release velocity", Ink::Arrow));
    if let Some(b) = &pic.body {
        series.push(Series::new(
            "the body's centre",
            Ink::Trail,
            true,
            xy(&b.path),
        ));
        if let Some((bar, centre)) = b.bar {
            series.push(Series::new("the body", Ink::Particle, true, xy(&bar)));
            marks.push(point(centre, format!("{BODY_GLYPH} body"), Ink::Particle));
        }
    }
    if let Some(p) = &pic.point {
        series.push(Series::new("particle", Ink::Trail, true, xy(&p.trail)));
        if !p.steps.is_empty() {
            let dots = Series::new("integrator steps", Ink::Notice, false, xy(&p.steps));
            series.push(dots);
        }
        for a in &p.arrows {
            marks.push(arrow(
                p.at,
                a.vec,
                format!("{} ({})", a.label, a.word),
                a.ink,
            ));
        }
        if let Some(s) = p.stuck {
            marks.push(point(s.at, s.label(), Ink::Stuck));
        }
        marks.push(point(p.at, p.status.clone(), Ink::Particle));
    }
    let name = match pic.frame {
        Frame::Lab => "the lab frame",
        Frame::Table => "the rotating frame (the table's)",
    };
    Chart {
        title: format!("the turntable in {name}"),
        x_label: "x (R_max)".into(),
        y_label: "y (R_max)".into(),
        x,
        y,
        equal_aspect: true,
        series,
        marks,
        ..Chart::default()
    }
}

/// The table: its edge, the circle inside which friction holds (ξ = 1 on the paper's), the marks on its rim at its angle, its sense.
fn table(pic: &Picture) -> (Vec<Series>, Vec<Mark>) {
    let t = &pic.table;
    let mut edge = Series::line("table edge", 0, circle(t.r));
    edge.ink = Ink::TableEdge;
    let ring = t.ring.as_ref().map(|ring| {
        let mut s = Series::line(&ring.label, 2, circle(ring.r));
        s.ink = Ink::LimitCircle;
        s
    });
    // The three marks as one line, broken between them.
    let rim = t
        .rim_marks()
        .iter()
        .flat_map(|[a, b]| [(a.x, a.y), (b.x, b.y), (f64::NAN, f64::NAN)])
        .collect();
    let rim = Series::new("the table's turn", Ink::TableEdge, true, rim);
    (
        [Some(edge), ring, Some(rim)]
            .into_iter()
            .flatten()
            .collect(),
        vec![text(t.sense, SENSE_LABEL, Ink::TableEdge)],
    )
}
