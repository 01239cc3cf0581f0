//! Figures for slides and notes: panels of curves, points and shaded cells on linear axes,
//! with tick values, axis names with units, a legend and a title, written as SVG (`svg`).
//! The data comes from the engine and the analysis (`turntable plot`) or from what the
//! explorer already holds (`E`); nothing here computes physics.
//!
//! A small hand-written writer rather than the plotters crate: plotters' backends place
//! everything on integer pixels, so a figure could not carry its data to better than a pixel
//! (a test maps the polyline back to v_e to 1e-6), and what is drawn here (lines, dots, cells,
//! text) is a few hundred lines, not worth three more crates.

mod axis;
pub mod build;
mod svg;

pub use axis::{extent, sane, tick_label, ticks};
pub use svg::to_svg;

/// A figure: a title over panels stacked top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    pub title: String,
    pub panels: Vec<Panel>,
}

/// One plot: axes with names (units included), ranges, what is drawn, a legend.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x: [f64; 2],
    pub y: [f64; 2],
    /// One data unit is as long on both axes (a trajectory's plane).
    pub equal_aspect: bool,
    pub series: Vec<Series>,
    pub marks: Vec<Mark>,
}

/// A named set of points, drawn as `style` says; the legend lists it under its name.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Style {
    /// Joined by straight segments; a non-finite point breaks the line. `dash` picks one of a
    /// few dash patterns, so curves are told apart without colour.
    Line { dash: usize },
    /// A marker at each point.
    Dots,
    /// A filled cell `w` × `h` (data units) centred on each point, grey at `shade` (0 white,
    /// 1 black).
    Cells { w: f64, h: f64, shade: f64 },
}

/// Something marked and labelled on a panel.
#[derive(Clone, Debug, PartialEq)]
pub enum Mark {
    /// A vertical line at x.
    VLine { x: f64, label: String },
    /// A point with a label beside it.
    Point { x: f64, y: f64, label: String },
}

impl Series {
    pub fn line(name: &str, dash: usize, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            style: Style::Line { dash },
        }
    }
}
