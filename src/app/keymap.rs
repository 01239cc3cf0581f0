//! The one key table: it dispatches keys and it generates the help overlay, so they cannot
//! disagree.

use super::action::{Action, Group, UnitKnob};
use super::chord::Chord;
use super::lesson::Prompt;
use crossterm::event::{KeyCode, KeyModifiers};
use std::f64::consts::PI;

/// A key, its action, the help text and the help group it is listed under.
#[derive(Clone, Copy, Debug)]
pub struct Binding {
    pub chord: Chord,
    pub action: Action,
    pub help: &'static str,
    pub group: &'static str,
}

const N: KeyModifiers = KeyModifiers::NONE;
const S: KeyModifiers = KeyModifiers::SHIFT;
const A: KeyModifiers = KeyModifiers::ALT;
const C: KeyModifiers = KeyModifiers::CONTROL;

const fn b(
    code: KeyCode,
    mods: KeyModifiers,
    action: Action,
    help: &'static str,
    group: &'static str,
) -> Binding {
    Binding {
        chord: Chord::new(code, mods),
        action,
        help,
        group,
    }
}

const fn ch(c: char) -> KeyCode {
    KeyCode::Char(c)
}

/// Fine and coarse steps of the initial conditions.
pub const XI0_FINE: f64 = 0.01;
pub const XI0_COARSE: f64 = 0.1;
pub const PHI_FINE: f64 = PI / 100.0;
pub const PHI_COARSE: f64 = PI / 10.0;
pub const V0_FINE: f64 = 0.001;
pub const V0_COARSE: f64 = 0.05;

/// Help groups, in the order the overlay shows them.
pub const GROUPS: [&str; 6] = [
    "time",
    "initial conditions",
    "integrator",
    "view",
    "app",
    "lesson",
];

#[rustfmt::skip]
pub const KEYMAP: &[Binding] = &[
    b(ch(' '), N, Action::PlayPause, "play / pause", "time"),
    b(ch('.'), N, Action::StepForward, "step forward (1 tick)", "time"),
    b(ch('l'), N, Action::StepForward, "step forward (1 tick)", "time"),
    b(KeyCode::Right, N, Action::StepForward, "step forward (1 tick)", "time"),
    b(ch('n'), N, Action::IntegratorStep, "one integrator step", "time"),
    b(ch(','), N, Action::StepBack, "step back (history)", "time"),
    b(ch('h'), N, Action::StepBack, "step back (history)", "time"),
    b(KeyCode::Left, N, Action::StepBack, "step back (history)", "time"),
    b(ch(']'), N, Action::Faster, "speed ×2 / ÷2", "time"),
    b(ch('['), N, Action::Slower, "speed ×2 / ÷2", "time"),
    b(ch('r'), N, Action::Restart, "restart at τ = 0", "time"),
    b(ch('x'), N, Action::Xi0(XI0_FINE), "ξ0 ±0.01 (Alt ±0.1)", "initial conditions"),
    b(ch('X'), N, Action::Xi0(-XI0_FINE), "ξ0 ±0.01 (Alt ±0.1)", "initial conditions"),
    b(ch('x'), A, Action::Xi0(XI0_COARSE), "ξ0 ±0.01 (Alt ±0.1)", "initial conditions"),
    b(ch('X'), A, Action::Xi0(-XI0_COARSE), "ξ0 ±0.01 (Alt ±0.1)", "initial conditions"),
    b(ch('p'), N, Action::Phi(PHI_FINE), "φ ±0.01π (Alt ±0.1π)", "initial conditions"),
    b(ch('P'), N, Action::Phi(-PHI_FINE), "φ ±0.01π (Alt ±0.1π)", "initial conditions"),
    b(ch('p'), A, Action::Phi(PHI_COARSE), "φ ±0.01π (Alt ±0.1π)", "initial conditions"),
    b(ch('P'), A, Action::Phi(-PHI_COARSE), "φ ±0.01π (Alt ±0.1π)", "initial conditions"),
    b(ch('v'), N, Action::V0(V0_FINE), "v0 ±0.001 (Alt ±0.05)", "initial conditions"),
    b(ch('V'), N, Action::V0(-V0_FINE), "v0 ±0.001 (Alt ±0.05)", "initial conditions"),
    b(ch('v'), A, Action::V0(V0_COARSE), "v0 ±0.001 (Alt ±0.05)", "initial conditions"),
    b(ch('V'), A, Action::V0(-V0_COARSE), "v0 ±0.001 (Alt ±0.05)", "initial conditions"),
    b(ch('R'), N, Action::CycleRelease, "release: v0/table/lab", "initial conditions"),
    b(ch('F'), N, Action::ToggleFriction, "friction off (μ = 0) / on", "initial conditions"),
    b(ch('0'), N, Action::ResetScene, "reset to the scene", "initial conditions"),
    b(ch('1'), N, Action::Preset(0), "presets A B C D fig1 fig2 spin", "initial conditions"),
    b(ch('2'), N, Action::Preset(1), "presets A B C D fig1 fig2 spin", "initial conditions"),
    b(ch('3'), N, Action::Preset(2), "presets A B C D fig1 fig2 spin", "initial conditions"),
    b(ch('4'), N, Action::Preset(3), "presets A B C D fig1 fig2 spin", "initial conditions"),
    b(ch('5'), N, Action::Preset(4), "presets A B C D fig1 fig2 spin", "initial conditions"),
    b(ch('6'), N, Action::Preset(5), "presets A B C D fig1 fig2 spin", "initial conditions"),
    b(ch('7'), N, Action::Preset(6), "presets A B C D fig1 fig2 spin", "initial conditions"),
    b(ch('m'), N, Action::CycleMethod, "method (cycle)", "integrator"),
    b(ch('<'), N, Action::Loosen, "dt/tol ×√10 / ÷√10", "integrator"),
    b(ch('>'), N, Action::Tighten, "dt/tol ×√10 / ÷√10", "integrator"),
    b(ch('c'), N, Action::ToggleCompare, "compare: paper's RK2", "integrator"),
    b(ch('f'), N, Action::ToggleFrame, "frame lab ↔ rotating", "view"),
    b(ch('%'), N, Action::ToggleSplit, "both frames at once", "view"),
    b(ch('a'), N, Action::ToggleForces, "force arrows", "view"),
    b(ch('A'), N, Action::ToggleNetForce, "net force arrow", "view"),
    b(ch('i'), N, Action::ToggleVelocity, "velocity arrow", "view"),
    b(ch('C'), N, Action::TogglePointModel, "body: point model beside it", "view"),
    b(ch('e'), N, Action::EstimateError, "error estimate", "integrator"),
    b(ch('+'), N, Action::ZoomIn, "zoom in / out", "view"),
    b(ch('='), N, Action::ZoomIn, "zoom in / out", "view"),
    b(ch('-'), N, Action::ZoomOut, "zoom in / out", "view"),
    b(ch('H'), N, Action::Pan(-0.2, 0.0), "pan", "view"),
    b(ch('J'), N, Action::Pan(0.0, -0.2), "pan", "view"),
    b(ch('K'), N, Action::Pan(0.0, 0.2), "pan", "view"),
    b(ch('L'), N, Action::Pan(0.2, 0.0), "pan", "view"),
    b(KeyCode::Left, S, Action::Pan(-0.2, 0.0), "pan (arrows)", "view"),
    b(KeyCode::Down, S, Action::Pan(0.0, -0.2), "pan (arrows)", "view"),
    b(KeyCode::Up, S, Action::Pan(0.0, 0.2), "pan (arrows)", "view"),
    b(KeyCode::Right, S, Action::Pan(0.2, 0.0), "pan (arrows)", "view"),
    b(ch('z'), N, Action::ResetView, "reset zoom and pan", "view"),
    b(ch('t'), N, Action::TauWindow(true), "time plots' τ window ÷2 / ×2", "view"),
    b(ch('T'), N, Action::TauWindow(false), "time plots' τ window ÷2 / ×2", "view"),
    b(KeyCode::Tab, N, Action::NextPage, "pages (6)", "view"),
    b(KeyCode::BackTab, N, Action::PrevPage, "pages (6)", "view"),
    b(KeyCode::Enter, N, Action::Choose, "run chosen release / setting", "view"),
    b(ch('j'), N, Action::PickPoint(1), "work-precision point ±1", "view"),
    b(ch('k'), N, Action::PickPoint(-1), "work-precision point ±1", "view"),
    b(ch('o'), N, Action::Omega(0.1), "μ probe: Ω, r0c", "view"),
    b(ch('O'), N, Action::Omega(-0.1), "μ probe: Ω, r0c", "view"),
    b(ch('d'), N, Action::R0c(0.001), "μ probe: Ω, r0c", "view"),
    b(ch('D'), N, Action::R0c(-0.001), "μ probe: Ω, r0c", "view"),
    b(ch('u'), N, Action::Unit(UnitKnob::Mu, 0.01), "SI units: μ ±0.01", "view"),
    b(ch('U'), N, Action::Unit(UnitKnob::Mu, -0.01), "SI units: μ ±0.01", "view"),
    b(ch('w'), N, Action::Unit(UnitKnob::Rpm, 1.0), "table rpm ±1", "view"),
    b(ch('W'), N, Action::Unit(UnitKnob::Rpm, -1.0), "table rpm ±1", "view"),
    b(ch('g'), N, Action::Unit(UnitKnob::G, 0.01), "g ±0.01 m/s²", "view"),
    b(ch('G'), N, Action::Unit(UnitKnob::G, -0.01), "g ±0.01 m/s²", "view"),
    b(ch('u'), A, Action::UnitsOff, "SI units off", "view"),
    b(ch('b'), N, Action::PinRun, "pin this run (up to 6)", "view"),
    b(ch('B'), N, Action::ClearPins, "clear the pins", "view"),
    b(ch('?'), N, Action::ToggleHelp, "help on / off", "app"),
    b(KeyCode::Up, N, Action::HelpScroll(-1), "scroll help", "app"),
    b(KeyCode::Down, N, Action::HelpScroll(1), "scroll help", "app"),
    b(KeyCode::PageUp, N, Action::HelpPage(-1), "scroll help", "app"),
    b(KeyCode::PageDown, N, Action::HelpPage(1), "scroll help", "app"),
    b(ch('s'), N, Action::Save, "save scene (toml)", "app"),
    b(ch('S'), N, Action::SaveAs, "save as… (name, Enter)", "app"),
    b(ch(':'), N, Action::SetValues, "type values: ξ0 φ v0 μ rpm g", "app"),
    b(ch('E'), N, Action::ExportSvg, "page as SVG (new file)", "app"),
    b(ch('M'), N, Action::ToggleMouse, "mouse capture on/off", "app"),
    b(ch('I'), N, Action::Readouts, "readouts in words", "app"),
    b(ch('q'), N, Action::Quit, "quit", "app"),
    b(KeyCode::Esc, N, Action::Dismiss, "close help / notice", "app"),
    b(KeyCode::F(2), N, Action::Follow, "serve: follow / step out", "app"),
    b(ch('c'), C, Action::Quit, "quit", "app"),
    // Only while a lesson asks or waits (see `lookup_when`): then these keys are the lesson's.
    b(ch('y'), N, Action::Answer(true), "answer yes / no", "lesson"),
    b(ch('n'), N, Action::Answer(false), "answer yes / no", "lesson"),
    b(KeyCode::Enter, N, Action::GoOn, "go on when it waits", "lesson"),
];

/// The action bound to `chord` outside a lesson's prompt, if any.
pub fn lookup(chord: Chord) -> Option<Action> {
    lookup_when(chord, Prompt::None)
}

/// The action bound to `chord` while a lesson awaits `prompt`: y/n answer its question, Enter
/// lets it go on (at a question, says it waits for y or n); otherwise the lesson's bindings
/// are passed over.
pub fn lookup_when(chord: Chord, prompt: Prompt) -> Option<Action> {
    let live = |a: Action| match a {
        Action::Answer(_) => prompt == Prompt::Answer,
        // Enter at a question says what it waits for (not the page's own Enter).
        Action::GoOn => prompt != Prompt::None,
        _ => true,
    };
    let bound = |lesson: bool| {
        KEYMAP
            .iter()
            .filter(|b| (b.action.group() == Group::Lesson) == lesson && live(b.action))
            .find(|b| b.chord == chord)
            .map(|b| b.action)
    };
    bound(true).or_else(|| bound(false))
}
