//! What a session over SSH does with the effects `update` returns: a guest writes nothing on
//! the server; a presenter with `--exports` writes its pages there.

use crate::app::{App, Effect, Effects};

/// A guest writes nothing on the server: saving and exporting are refused with a notice.
pub struct Guest;

impl crate::session::Carry for Guest {
    fn carry(&mut self, app: &mut App, effects: Effects) {
        guest(app, effects);
    }
}

fn guest(app: &mut App, effects: Effects) {
    for effect in effects {
        // A follower given the presenter's `s`, `S` or `E`: the presenter's to write (or
        // not), not the follower's to be told it was refused.
        if app.apart() && !matches!(effect, Effect::Readouts) {
            continue;
        }
        let notice = refused(app, effect);
        app.report(notice);
    }
}

/// What a guest is told of an effect.
fn refused(app: &App, effect: Effect) -> String {
    match effect {
        Effect::SaveScene { .. } => "not saved: over ssh nothing is written on the server".into(),
        Effect::ExportSvg { .. } => {
            "not exported: over ssh nothing is written on the server".into()
        }
        Effect::Readouts => crate::ui::plain::summary(app),
    }
}

/// The presenter with `--exports`: its `E` writes the page there (its app's save path is
/// set in that directory, so the effect names it), within [`super::super::EXPORTS`], under the
/// files' policy; the rest as a guest.
pub(super) struct Presenter;

impl crate::session::Carry for Presenter {
    fn carry(&mut self, app: &mut App, effects: Effects) {
        presenter(app, effects);
    }
}

fn presenter(app: &mut App, effects: Effects) {
    for effect in effects {
        let notice = match effect {
            Effect::ExportSvg { dir, page } => {
                crate::session::export_svg(app, &dir, page, Some(super::super::EXPORTS))
            }
            effect => refused(app, effect),
        };
        app.report(notice);
    }
}
