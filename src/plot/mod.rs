//! Charts and figures described once: panels of curves, points, shaded cells, marks and
//! arrows on linear axes, with tick values (`axis`), axis names with units, a legend and a
//! title. The terminal draws a panel with ratatui (`ui::chart`), `svg` writes a figure as
//! SVG: an export carries what the screen shows. The data comes from the engine and the
//! analysis (`turntable plot`) or from what the explorer already holds (`E`, the pages);
//! nothing here computes physics.
//!
//! A small hand-written writer rather than the plotters crate: plotters' backends place
//! everything on integer pixels, so a figure could not carry its data to better than a pixel
//! (a test maps the polyline back to v_e to 1e-6), and what is drawn here (lines, dots, cells,
//! text) is a few hundred lines, not worth three more crates.

mod axis;
pub mod build;
pub mod page;
mod svg;

pub use axis::{Scale, axis, extent, sane, ticks};
pub use svg::{label_width, to_svg};

/// A figure: a title over panels stacked top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    pub title: String,
    pub panels: Vec<Chart>,
}

/// One plot: axes with names (units included), ranges, what is drawn, a legend.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Chart {
    pub title: String,
    /// A line of readouts (the terminal puts it under the x ticks, SVG after the title).
    pub note: String,
    pub x_label: String,
    pub y_label: String,
    pub x: [f64; 2],
    pub y: [f64; 2],
    /// How each axis is ticked and read (angles in π).
    pub x_scale: Scale,
    pub y_scale: Scale,
    /// One data unit is as long on both axes (a trajectory's plane).
    pub equal_aspect: bool,
    pub series: Vec<Series>,
    pub marks: Vec<Mark>,
}

/// A named set of points, drawn as `style` says in `ink`; the legend lists it under its name
/// (none when the name is empty).
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    pub ink: Ink,
}

/// What a thing drawn is, for its colour: the terminal takes the theme's colour of that
/// name; SVG gives lines and dots its palette in turn and draws `Muted` ones grey.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Ink {
    /// The run's own line.
    #[default]
    Trail,
    /// Second things: the pins, the paper's other curves, the approximations.
    Muted,
    Accent,
    /// The paper's RK2 run beside the converged one.
    Paper,
    Particle,
    Foreground,
    Stuck,
    Escaped,
    Notice,
    /// The velocity arrows.
    Arrow,
    Friction,
    Coriolis,
    Centrifugal,
    TableEdge,
    LimitCircle,
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
    VLine { x: f64, label: String, ink: Ink },
    /// A point with a label beside it.
    Point {
        x: f64,
        y: f64,
        label: String,
        ink: Ink,
    },
    /// A label alone, its left end at (x, y).
    Text {
        x: f64,
        y: f64,
        label: String,
        ink: Ink,
    },
    /// An arrow from `from` to `to`, labelled at its head.
    Arrow {
        from: (f64, f64),
        to: (f64, f64),
        label: String,
        ink: Ink,
    },
}

impl Series {
    pub fn line(name: &str, dash: usize, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            style: Style::Line { dash },
            ink: Ink::Trail,
        }
    }

    /// A line (`joined`) or dots, in `ink`.
    pub fn new(name: impl Into<String>, ink: Ink, joined: bool, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            style: match joined {
                true => Style::Line { dash: 0 },
                false => Style::Dots,
            },
            ink,
        }
    }

    /// Joined by lines (else dots or cells).
    pub fn joined(&self) -> bool {
        matches!(self.style, Style::Line { .. })
    }
}
