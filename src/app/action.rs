//! Everything the user can ask for: keys and mouse map to these, `update` applies them.

/// One user intent. Keys map to actions through [`super::keymap::KEYMAP`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    Quit,
    /// Close the help or a notice (never quits).
    Dismiss,
    /// Over `turntable serve`, a student steps out of the class or back in (the server's
    /// session takes the key first; alone, the explorer says so).
    Follow,
    ToggleHelp,
    /// Scroll the help by this many rows, or pages (down positive).
    HelpScroll(i16),
    HelpPage(i16),
    /// The time plots' τ window: halve it (fixing it), or double it (back to the whole run
    /// once it reaches the τ on screen).
    TauWindow(bool),
    PlayPause,
    StepForward,
    StepBack,
    /// Exactly one integrator step, its end marked, its size and error shown.
    IntegratorStep,
    Faster,
    Slower,
    Restart,
    ToggleFrame,
    /// Both frames at once, side by side (or stacked where the canvas is narrow).
    ToggleSplit,
    CycleMethod,
    /// dt or tol × √10.
    Loosen,
    /// dt or tol ÷ √10.
    Tighten,
    /// Change ξ0 by this much.
    Xi0(f64),
    /// Change φ by this many radians.
    Phi(f64),
    /// Change v0 by this much.
    V0(f64),
    CycleRelease,
    /// μ = 0 on / off.
    ToggleFriction,
    ResetScene,
    /// Load preset `PRESETS[i]`.
    Preset(usize),
    ToggleCompare,
    ToggleForces,
    /// The net force's arrow; the velocity's.
    ToggleNetForce,
    ToggleVelocity,
    /// In a body scene, the point model's path and marker beside the body, or not.
    TogglePointModel,
    /// Estimate the error of the state on screen from a shadow run at a tighter setting.
    EstimateError,
    ZoomIn,
    ZoomOut,
    /// Pan the view by this fraction of the half-width (x right, y up).
    Pan(f64, f64),
    ResetView,
    Save,
    /// Opens the prompt for a name, then saves the scene under it.
    SaveAs,
    /// An edit of the name being typed (only while the prompt is open).
    /// A key typed at the prompt (bound to no key: the prompt takes keys while open).
    Type(Edit),
    /// Opens the prompt for values (ξ0, φ, v0; μ, rpm, Ω, g).
    SetValues,
    /// Write the page on screen as SVG to a new file.
    ExportSvg,
    ToggleMouse,
    /// The readouts in words: a notice in the explorer, every readout line in plain mode.
    Readouts,
    /// Mouse: the release point here (model coordinates, as the canvas maps the click).
    PlaceRelease(glam::DVec2),
    /// Mouse drag: the initial velocity as the arrow drawn from the release point shows it
    /// (the lab velocity in the lab frame, u0 in the rotating one), in the frame of the canvas
    /// the drag began in (in a split view, either).
    AimVelocity(glam::DVec2, crate::engine::Frame),
    EndDrag,
    /// The next / previous page (turntable, time plots, escape speed, outcome map, rest radius).
    NextPage,
    PrevPage,
    /// Back to the turntable with the release chosen on an analysis page; on the
    /// work–precision page, the run switched to the point picked.
    Choose,
    /// The work–precision page's next (+1) or previous (−1) point.
    PickPoint(i8),
    /// Mouse on the escape-speed or outcome-map page: the release (φ, v0) clicked.
    PickRelease(glam::DVec2),
    /// The μ measurement: change Ω (rad/s) or r0c (m) by this much.
    Omega(f64),
    R0c(f64),
    /// SI units: change μ, the table's rpm or g by this much (turning units on, from the
    /// record player of `state::record_player`, if they were off).
    Unit(UnitKnob, f64),
    /// Dimensionless readouts only.
    UnitsOff,
    /// Pin the run on screen beside later ones; clear the pins.
    PinRun,
    ClearPins,
    /// A lesson's prediction: yes (it escapes) or no.
    Answer(bool),
    /// A lesson waiting for Enter goes on.
    GoOn,
}

/// The physical constants the SI readouts rest on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnitKnob {
    Mu,
    Rpm,
    G,
}

/// The help group an action belongs to: `update` dispatches on it, and every binding of
/// [`super::keymap::KEYMAP`] is listed under its action's group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    Time,
    InitialConditions,
    Integrator,
    View,
    App,
    Lesson,
}

impl Group {
    /// The name the help overlay shows (one of [`super::keymap::GROUPS`]).
    pub fn name(self) -> &'static str {
        match self {
            Group::Time => "time",
            Group::InitialConditions => "initial conditions",
            Group::Integrator => "integrator",
            Group::View => "view",
            Group::App => "app",
            Group::Lesson => "lesson",
        }
    }
}

impl Action {
    pub fn group(self) -> Group {
        use Action::*;
        match self {
            PlayPause | StepForward | StepBack | IntegratorStep | Faster | Slower | Restart => {
                Group::Time
            }
            // The mouse sets the release too.
            Xi0(_) | Phi(_) | V0(_) | CycleRelease | ToggleFriction | ResetScene | Preset(_)
            | PlaceRelease(_) | AimVelocity(..) | EndDrag | PickRelease(_) => {
                Group::InitialConditions
            }
            CycleMethod | Loosen | Tighten | ToggleCompare | EstimateError => Group::Integrator,
            ToggleFrame | ToggleSplit | ToggleForces | ToggleNetForce | ToggleVelocity
            | TogglePointModel | ZoomIn | ZoomOut | Pan(..) | ResetView | TauWindow(_)
            | NextPage | PrevPage | Choose | PickPoint(_) | Omega(_) | R0c(_) | Unit(..)
            | UnitsOff | PinRun | ClearPins => Group::View,
            Quit | Dismiss | Follow | ToggleHelp | HelpScroll(_) | HelpPage(_) | Save | SaveAs
            | Type(_) | SetValues | ExportSvg | ToggleMouse | Readouts => Group::App,
            Answer(_) | GoOn => Group::Lesson,
        }
    }
}

/// What a key does to the line typed at the prompt.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Edit {
    Char(char),
    Back,
    Done,
    Cancel,
}

impl Edit {
    /// The edit a key makes at the prompt (none for keys it ignores: arrows, Tab, chords).
    pub fn of(chord: super::Chord) -> Option<Edit> {
        use crossterm::event::{KeyCode, KeyModifiers};
        let plain = chord.mods.difference(KeyModifiers::SHIFT).is_empty();
        match chord.code {
            KeyCode::Char(c) if plain && !crate::text::needs_escape(c) => Some(Edit::Char(c)),
            KeyCode::Backspace => Some(Edit::Back),
            KeyCode::Enter => Some(Edit::Done),
            KeyCode::Esc => Some(Edit::Cancel),
            _ => None,
        }
    }
}
