//! What `update` asks of the world outside the model. `update` changes the state only; an
//! effect it returns is carried out by the shell (`crate::session::carry_out` writes the file,
//! `crate::replay::answer` says what would have been written), which reports back with
//! [`App::report`](super::App::report).

use super::pages::Page;
use crate::scene::Scene;
use std::path::PathBuf;

/// One thing to do outside the model.
#[derive(Clone, Debug, PartialEq)]
pub enum Effect {
    /// Save `scene` to a new file at `path`, or the next free name beside it.
    SaveScene { scene: Box<Scene>, path: PathBuf },
    /// Write `page`, as it is on screen, as SVG to the first free `turntable-PAGE-N.svg` in
    /// `dir`.
    ExportSvg { dir: PathBuf, page: Page },
    /// Say the readouts in words (`I`): words for people are the view's, so the shell puts
    /// them in the notice.
    Readouts,
}

/// What one action asks of the shell, in order (most actions: nothing).
pub type Effects = Vec<Effect>;
