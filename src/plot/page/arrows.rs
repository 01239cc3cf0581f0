//! The arrows at the particle: the forces in the frame shown (Sec. II), their sum and the
//! velocity, scaled together and labelled at their heads.

use super::super::Ink;
use crate::app::App;
use crate::engine::Frame;
use crate::engine::model::rotate;
use glam::DVec2;

/// A force arrow as drawn: its label at the head (so it reads without colour), the word the
/// legend uses, and the vector in world units of the frame shown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceArrow {
    pub label: &'static str,
    pub word: &'static str,
    pub vec: DVec2,
    pub ink: Ink,
}

/// Share of the visible half-width the longest force arrow takes.
pub const FORCE_SHARE: f64 = 0.2;

/// The forces on the particle in the frame shown (Sec. II). In the lab, an inertial frame,
/// only friction (or Stokes drag) acts in the plane (gravity and the normal force cancel; at μ = 0 nothing
/// does). In the rotating frame the fictitious Coriolis and centrifugal forces act too, and
/// on a table speeding up the Euler force. All are scaled together so the longest is
/// [`FORCE_SHARE`] of `half_width`.
pub fn force_arrows(app: &App, half_width: f64) -> Vec<ForceArrow> {
    forces(app, app.view().frame, half_width).0
}

/// [`force_arrows`], and the net force at their scale (their sum: du/dτ in the rotating
/// frame, dv/dτ in the lab).
fn forces(app: &App, frame: Frame, half_width: f64) -> (Vec<ForceArrow>, DVec2) {
    let now = app.sim().now();
    let motion = app.sim().motion();
    let [fr, co, ce, eu] = motion.forces(&now, app.initial().frictionless);
    // Under Stokes drag the force opposing u is a drag, not friction: nothing is held.
    let (fr_label, fr_word) = if app.settings().stokes().is_some() {
        ("dr", "Stokes drag")
    } else {
        ("fr", "friction")
    };
    let mut out = Vec::new();
    let mut push = |label, word, vec: DVec2, ink| {
        if vec.length() > 0.0 {
            out.push(ForceArrow {
                label,
                word,
                vec,
                ink,
            });
        }
    };
    match frame {
        Frame::Lab => push(
            fr_label,
            fr_word,
            rotate(fr, motion.table_angle(now.tau)),
            Ink::Friction,
        ),
        Frame::Table => {
            push(fr_label, fr_word, fr, Ink::Friction);
            push("co", "Coriolis", co, Ink::Coriolis);
            push("cf", "centrifugal", ce, Ink::Centrifugal);
            push("eu", "Euler", eu, Ink::Accent);
        }
    }
    let mut net: DVec2 = out.iter().map(|f| f.vec).sum();
    let longest = out.iter().fold(0.0, |m: f64, f| m.max(f.vec.length()));
    if longest > 0.0 {
        let k = FORCE_SHARE * half_width / longest;
        for f in &mut out {
            f.vec *= k;
        }
        net *= k;
    }
    (out, net)
}

/// The arrows the canvas draws at the particle, each labelled at its head: the forces (`a`),
/// the net force (`A`, at the forces' scale) and the velocity (`i`: relative to the table in
/// the rotating frame, the lab velocity in the lab; `speed_scale` world units per unit speed,
/// as the initial velocity's arrow). A zero vector is not drawn.
pub fn arrows(app: &App, half_width: f64, speed_scale: f64) -> Vec<ForceArrow> {
    arrows_in(app, app.view().frame, half_width, speed_scale)
}

/// [`arrows`] as `frame` sees them (a split view draws both frames).
pub fn arrows_in(app: &App, frame: Frame, half_width: f64, speed_scale: f64) -> Vec<ForceArrow> {
    let (mut out, net) = forces(app, frame, half_width);
    if !app.view().forces {
        out.clear();
    }
    // Below this the sum is rounding: the forces balance (stuck).
    let balanced = 1e-9 * half_width;
    if app.view().net_force && net.length() > balanced {
        out.push(ForceArrow {
            label: "net",
            word: "net force",
            vec: net,
            ink: Ink::Foreground,
        });
    }
    if app.view().velocity {
        let (label, word, v) = velocity_in(app, frame);
        if v.length() > 0.0 {
            out.push(ForceArrow {
                label,
                word,
                vec: v * speed_scale,
                ink: Ink::Arrow,
            });
        }
    }
    out
}

/// The velocity the frame shown sees: `u` relative to the table (rotating), `v` (lab).
pub fn velocity(app: &App) -> (&'static str, &'static str, DVec2) {
    velocity_in(app, app.view().frame)
}

fn velocity_in(app: &App, frame: Frame) -> (&'static str, &'static str, DVec2) {
    let now = app.sim().now();
    match frame {
        Frame::Lab => ("v", "velocity (lab)", now.v),
        Frame::Table => ("u", "velocity rel. table", app.sim().motion().u(&now)),
    }
}
