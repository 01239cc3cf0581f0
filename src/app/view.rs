//! How the exploration is shown: the page, the frame, the framing and what is drawn on it.
//! Changing it never touches a run.

use super::pages::Page;
use crate::engine::Frame;

/// The scale of the picture against the auto-framed view (`+`/`-`, the wheel).
pub const ZOOM_RANGE: (f64, f64) = (1.0 / 64.0, 1024.0);

#[derive(Clone, Debug, PartialEq)]
pub struct View {
    /// What the body shows (`Tab` cycles).
    pub page: Page,
    /// The frame the picture is drawn in (lab or rotating).
    pub frame: Frame,
    /// Both frames at once (`%`): the frame above beside the other, the same run at the same τ.
    pub split: bool,
    pub zoom: f64,
    /// The picture's turn (rad): the model releases on +x, the picture shows the release
    /// where it was clicked.
    pub turn: f64,
    /// View centre offset, in units of the auto-framed half-width.
    pub pan: glam::DVec2,
    pub forces: bool,
    /// The net force's arrow (`A`) and the velocity's (`i`).
    pub net_force: bool,
    pub velocity: bool,
    /// In a body scene, the point model's path and marker drawn beside the body (`C`).
    pub point_model: bool,
    /// Integrator step mode (`n`): step ends marked, step size and error shown.
    pub step_mode: bool,
    pub help: bool,
    /// The help's first row shown.
    pub help_scroll: u16,
    /// The time plots' τ span when fixed (`t`/`T`); None: the run so far.
    pub tau_window: Option<f64>,
    /// The point picked on the work–precision page (`j`/`k`); None: the explorer's setting.
    pub trade_pick: Option<crate::engine::method::Scheme>,
}

impl View {
    /// The view a scene opens in (its `[view]`, or the defaults).
    pub fn of(scene: Option<crate::scene::View>) -> View {
        let v = scene.filter(|v| v.zoom.is_finite() && v.zoom > 0.0);
        View {
            page: v.map_or(Page::Turntable, |v| v.page),
            frame: v.map_or(Frame::Lab, |v| v.frame),
            split: v.is_some_and(|v| v.split),
            zoom: v.map_or(1.0, |v| v.zoom.clamp(ZOOM_RANGE.0, ZOOM_RANGE.1)),
            turn: 0.0,
            pan: glam::DVec2::ZERO,
            forces: v.is_some_and(|v| v.forces),
            net_force: v.is_some_and(|v| v.net_force),
            velocity: v.is_some_and(|v| v.velocity),
            point_model: v.is_none_or(|v| v.point),
            step_mode: false,
            help: false,
            help_scroll: 0,
            tau_window: None,
            trade_pick: None,
        }
    }

    /// This view as a scene keeps it (with the speed time plays at), so that the scene
    /// opens as it was saved.
    pub fn saved(&self, speed: f64) -> crate::scene::View {
        crate::scene::View {
            page: self.page,
            frame: self.frame,
            forces: self.forces,
            zoom: self.zoom,
            net_force: self.net_force,
            velocity: self.velocity,
            split: self.split,
            point: self.point_model,
            speed,
        }
    }
}
