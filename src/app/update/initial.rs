//! The "initial conditions" group: ξ0, φ, v0, the release, friction, scenes and presets, and
//! the mouse's release point and velocity.

use super::super::action::Action;
use super::super::pages::Page;
use super::super::state::App;
use super::next_of;
use crate::engine::model::{wrap_angle, zcross};
use crate::engine::{Frame, Release};
use crate::present::{angle, num};
use crate::scene::{PRESETS, Scene};
use strum::VariantArray;

pub(super) fn apply(app: &mut App, action: Action) {
    match action {
        Action::Xi0(d) => app.exploration.edit_initial(|i| i.xi0 += d),
        Action::Phi(d) => app.exploration.edit_initial(|i| {
            i.phi += d;
            i.release = Release::Velocity;
        }),
        Action::V0(d) => app.exploration.edit_initial(|i| {
            i.v0 += d;
            i.release = Release::Velocity;
        }),
        Action::CycleRelease => app
            .exploration
            .edit_initial(|i| i.release = next_of(Release::VARIANTS, i.release)),
        Action::ToggleFriction => {
            app.exploration
                .edit_initial(|i| i.frictionless = !i.frictionless);
            app.notice = Some(if app.initial().frictionless {
                "μ = 0: no friction, so no force at all in the lab (closed form, no steps)".into()
            } else {
                "friction on: μg = 1".into()
            });
        }
        Action::ResetScene => app.exploration.reset(),
        Action::Preset(i) => {
            if let Some(mut scene) = PRESETS.get(i).and_then(|n| Scene::preset(n)) {
                // The body is the object, the preset its release: it stays (but the spin-up
                // spins a point coin).
                scene.body = app.scene().body.filter(|_| scene.spin.is_none());
                let mut kept = match scene.body {
                    Some(b) => format!(" (the body stays: L = {})", b.length),
                    None => String::new(),
                };
                if scene.spin.is_some() {
                    // What a spin-up scene file may not hold, the preset sets aside (Scene's
                    // check): pins and the other pages are the constant-Ω table's.
                    app.view.page = Page::Turntable;
                    if !app.pins.is_empty() {
                        kept = format!(
                            " ({} pins cleared: they run the constant-Ω table)",
                            app.pins.len()
                        );
                        app.pins.clear();
                    }
                }
                app.notice = Some(format!("preset {}: {}{kept}", scene.name, scene.about));
                app.exploration.load(scene);
                app.view.zoom = 1.0;
                app.view.turn = 0.0;
                app.view.pan = glam::DVec2::ZERO;
            }
        }
        Action::PlaceRelease(p) => {
            // Clicked at an angle: the picture turns there (p is in model coordinates, so its
            // angle adds to the turn already shown).
            if p.length() > 0.0 {
                app.view.turn = wrap_angle(app.view.turn + p.y.atan2(p.x));
            }
            app.exploration.edit_initial(|i| i.xi0 = p.length());
            app.dragging = true;
            app.notice = Some(format!(
                "release point ξ0 = {}; drag to set the velocity",
                num(app.initial().xi0, 3)
            ));
        }
        Action::AimVelocity(drawn, frame) => {
            let r0 = glam::DVec2::new(app.initial().xi0, 0.0);
            let u0 = match frame {
                Frame::Lab => drawn - zcross(r0),
                Frame::Table => drawn,
            };
            app.exploration.edit_initial(|i| {
                i.release = Release::Velocity;
                i.v0 = u0.length();
                i.phi = if u0.length() > 0.0 {
                    u0.y.atan2(u0.x)
                } else {
                    0.0
                };
            });
            app.notice = Some(format!(
                "v0 = {}, φ = {}",
                num(app.initial().v0, 3),
                angle(app.initial().phi)
            ));
        }
        Action::PickRelease(p) => {
            let release = match app.view.page {
                Page::OutcomeMap => app.initial().release,
                _ => Release::Velocity,
            };
            let chosen =
                crate::analysis::map_release(app.initial().xi0, release, p.x, p.y.max(0.0));
            app.exploration.set_initial(chosen);
            app.notice = Some(format!(
                "release v0 = {} at φ = {}: Enter runs it on the turntable",
                num(app.initial().v0, 4),
                angle(app.initial().phi)
            ));
        }
        // `EndDrag` is handled before dispatch; other groups' actions never come here.
        _ => {}
    }
}
