//! The explorer's state: the scene being edited, its run (and the paper's, to compare), and
//! how it is shown. Nothing here reads the clock: time passes only through ticks.

use super::exploration::sanitize;
use super::pages::{Charts, Page};
use super::pins::pin_of;
use crate::engine::{Frame, Initial, Settings, State};
use crate::present::num;
use crate::scene::Scene;
use crate::sim::Sim;
use ratatui::layout::Rect;
use std::path::PathBuf;

/// Sim time per tick at speed 1 (at [`TICKS_PER_SECOND`]: 1.5 τ per second, about a quarter
/// turn).
pub const TICK_DT: f64 = 0.05;
/// The app's clock rate in wall-clock time (the terminal's, an asciicast's): each tick is
/// `TICK_DT × speed` of sim time.
pub const TICKS_PER_SECOND: u32 = 30;
pub use super::view::ZOOM_RANGE;
pub use crate::scene::{SPEED_RANGE, speed_power};
/// The μ measurement's starting values, an example (the paper gives Eq. 22, no table):
/// Ω = 3.3 rad/s and r0c = 0.12 m.
pub const MU_PROBE: (f64, f64) = (3.3, 0.12);

/// The table SI units start from (`u`, `w`, `g`): a record player at 33⅓ rpm with μ = 0.15.
/// An everyday example, not the paper's: it names no table speed and no μ.
pub fn record_player() -> crate::engine::units::Units {
    crate::engine::units::Units::new(0.15, 100.0 / 3.0, crate::engine::units::G_DEFAULT)
        .expect("a record player's values are in range")
}
/// Where `s` saves the scene.
pub const SAVE_PATH: &str = "turntable-scene.toml";

/// What the view measured for the model at the terminal's size: the shell tells it on resize
/// (`crate::session::tell_size`), so that `update` never asks the view.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Measured {
    /// Rows of the help a page (PgUp/PgDn) moves by.
    pub help_page: u16,
    /// The help's last first row: scrolled no further.
    pub help_max_scroll: u16,
}

/// The canvas as last drawn: where it is on screen and which world rectangle it shows, so
/// that mouse cells map back to table coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CanvasGeom {
    pub area: Rect,
    pub x: [f64; 2],
    pub y: [f64; 2],
    /// World length of the initial-velocity arrow per unit speed.
    pub arrow_scale: f64,
    /// The view frame the canvas was drawn in.
    pub frame: Frame,
    /// How far the picture is turned (see `View::turn`).
    pub turn: f64,
    /// The page drawn: on the turntable a click places the release; on the escape-speed and
    /// outcome-map pages the plot is the (φ, v0) plane and a click picks that release.
    pub page: Page,
}

impl CanvasGeom {
    /// World coordinates of the centre of a terminal cell, if it is inside the canvas.
    pub fn to_world(&self, col: u16, row: u16) -> Option<glam::DVec2> {
        let a = self.area;
        if a.width == 0 || a.height == 0 || !a.contains((col, row).into()) {
            return None;
        }
        let fx = (f64::from(col - a.x) + 0.5) / f64::from(a.width);
        let fy = (f64::from(row - a.y) + 0.5) / f64::from(a.height);
        let p = glam::DVec2::new(
            self.x[0] + fx * (self.x[1] - self.x[0]),
            self.y[1] - fy * (self.y[1] - self.y[0]),
        );
        Some(crate::engine::model::rotate(p, -self.turn))
    }
}

/// Where a screen's user stands in a served class: what its keys do there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum InClass {
    /// No class (the local explorer), or none to follow now.
    #[default]
    Alone,
    /// Following: the presenter's keys move this screen, its own (but F2, y/n, q) do not.
    Following,
    /// Stepped out of a class that goes on: F2 rejoins it.
    Out,
}

#[derive(Clone, Debug)]
pub struct App {
    /// The scene, the initial conditions and settings being explored, and their runs: read
    /// through [`App::initial`], [`App::sim`] and the like, changed only through its
    /// setters, which restart the runs.
    pub(super) exploration: super::exploration::Exploration,
    pub(super) playing: bool,
    pub(super) speed: f64,
    /// How it is shown: page, frame, framing, arrows, help.
    pub(super) view: super::view::View,
    pub(super) mouse: bool,
    pub(super) notice: Option<String>,
    /// How many times the readouts were asked for in words (`I`): plain mode prints them.
    pub(super) readouts_asked: u64,
    /// The line being typed (a name to save under, `S`, or values, `:`), while it is open.
    pub(super) prompt: Option<super::prompt::Prompt>,
    /// Where `s` saves (`S` beside it, `E` in its folder).
    pub(super) save_path: PathBuf,
    pub(super) quit: bool,
    /// What the analysis pages have received (the shell's worker computes them).
    pub(super) charts: Charts,
    /// A real table (`--mu`, `--rpm`, `--g` or the scene's `[units]`): readouts in SI too.
    pub(super) units: Option<crate::engine::units::Units>,
    /// The μ measurement of the rest-radius page (Eq. 22): Ω in rad/s and r0c in metres.
    pub(super) mu_probe: (f64, f64),
    /// Runs pinned beside the one on screen (`b`), oldest first, at most
    /// [`crate::pin::MAX_PINS`].
    pub(super) pins: Vec<crate::pin::Pin>,
    /// A narrated lesson's caption, question and wait.
    pub(super) lesson: super::lesson::Lesson,
    /// Where this screen's user stands in a served class (the shell says: `tell_class`).
    pub(crate) class: InClass,
    pub(crate) dirty: bool,
    /// The canvases as last drawn (two in a split view), clicks mapped through the one they
    /// land in.
    pub(crate) geom: Vec<CanvasGeom>,
    /// The terminal's size, as its session last said (the outcome map's grid follows it).
    pub(crate) screen: (u16, u16),
    /// What the view measured at that size.
    pub(crate) measured: Measured,
    /// Mouse drag in progress: setting the initial velocity.
    pub(crate) dragging: bool,
    /// The canvas the drag began in: it goes on mapping through that one.
    pub(crate) drag_canvas: usize,
}

impl App {
    /// Whether time plays (Space; [`App::is_playing`] adds a paper's run catching up).
    pub fn playing(&self) -> bool {
        self.playing
    }

    /// How it is shown: page, frame, framing, arrows, help.
    pub fn view(&self) -> &super::view::View {
        &self.view
    }

    /// How fast time plays: a power of two, ×1/64 to ×256.
    pub fn speed(&self) -> f64 {
        self.speed
    }

    /// The last notice: what was done, or why not.
    pub fn notice(&self) -> &Option<String> {
        &self.notice
    }

    /// How many times the readouts were asked for in words (`I`): plain mode prints them.
    pub fn readouts_asked(&self) -> u64 {
        self.readouts_asked
    }

    /// The line being typed (a name to save under, `S`, or values, `:`), while it is open.
    pub fn prompt(&self) -> &Option<super::prompt::Prompt> {
        &self.prompt
    }

    /// Where `s` saves (`S` beside it, `E` in its folder).
    pub fn save_path(&self) -> &std::path::Path {
        &self.save_path
    }

    /// The shell's word on where `s` saves (`S` beside it, `E` in its folder).
    pub fn tell_save_path(&mut self, path: PathBuf) {
        self.save_path = path;
    }

    /// What the analysis pages have received.
    pub fn charts(&self) -> &Charts {
        &self.charts
    }

    /// A real table's scales, if it has them: readouts in SI too.
    pub fn units(&self) -> Option<crate::engine::units::Units> {
        self.units
    }

    /// The μ measurement of the rest-radius page (Eq. 22): Ω in rad/s and r0c in metres.
    pub fn mu_probe(&self) -> (f64, f64) {
        self.mu_probe
    }

    /// The runs pinned beside the one on screen, oldest first.
    pub fn pins(&self) -> &[crate::pin::Pin] {
        &self.pins
    }

    /// A narrated lesson's caption, question and wait.
    pub fn lesson(&self) -> &super::lesson::Lesson {
        &self.lesson
    }

    /// The shell's word on a real table's scales (`--mu`, `--rpm`, `--g`, the configuration's):
    /// readouts in SI too. None: the scene's own, if it has them, are dropped.
    pub fn tell_units(&mut self, units: Option<crate::engine::units::Units>) {
        self.units = units;
        self.dirty = true;
    }

    /// The shell's word on how fast time plays at the start (`--speed`, the configuration's).
    pub fn tell_speed(&mut self, speed: f64) {
        self.speed = speed;
        self.dirty = true;
    }

    /// The shell's word on whether it reads the mouse (`--mouse`, `--no-mouse`; always over
    /// ssh).
    pub fn tell_mouse(&mut self, on: bool) {
        self.mouse = on;
        self.dirty = true;
    }

    /// The shell's word on where this screen's user stands in a served class.
    pub fn tell_class(&mut self, class: InClass) {
        if self.class != class {
            self.class = class;
            self.dirty = true;
        }
    }

    pub(crate) fn build(scene: Scene) -> App {
        let units = scene.units;
        let mut pins = Vec::new();
        for spec in scene.pins.iter().rev().take(crate::pin::MAX_PINS).rev() {
            // Checked when the scene was loaded: a pin that still fails is left out.
            if let Ok(p) = pin_of(spec.clone(), &pins) {
                pins.push(p);
            }
        }
        let view = scene.view.filter(|v| v.zoom.is_finite() && v.zoom > 0.0);
        let mut exploration = super::exploration::Exploration::new(scene);
        App {
            notice: exploration.take_rod_notice(),
            exploration,
            playing: true,
            speed: view.map_or(1.0, |v| v.speed),
            view: super::view::View::of(view),
            mouse: true,
            readouts_asked: 0,
            save_path: PathBuf::from(SAVE_PATH),
            prompt: None,
            quit: false,
            charts: Charts::default(),
            mu_probe: MU_PROBE,
            units,
            pins,
            lesson: Default::default(),
            class: InClass::Alone,
            dirty: true,
            geom: Vec::new(),
            screen: (80, 24),
            measured: Measured::default(),
            dragging: false,
            drag_canvas: 0,
        }
    }

    /// The scene as loaded (what `0` resets to).
    pub fn scene(&self) -> &Scene {
        self.exploration.scene()
    }

    /// The initial conditions being explored.
    pub fn initial(&self) -> Initial {
        self.exploration.initial()
    }

    pub fn settings(&self) -> Settings {
        self.exploration.settings()
    }

    /// The run on screen.
    pub fn sim(&self) -> &Sim {
        self.exploration.sim()
    }

    /// The paper's scheme from the same initial conditions, when comparing.
    pub fn paper(&self) -> Option<&Sim> {
        self.exploration.paper()
    }

    /// The scene's finite body (the appendix's two masses on a rod) from the same release,
    /// drawn as a bar; None without a body, with μ = 0 or under Stokes drag.
    pub fn rod(&self) -> Option<&crate::engine::rod::RodTrack> {
        self.exploration.rod()
    }

    /// What is explored, to read as a whole.
    pub fn exploration(&self) -> &super::exploration::Exploration {
        &self.exploration
    }

    /// What is explored, to change through its setters (each restarts the runs); the screen
    /// is redrawn.
    pub fn explore(&mut self) -> &mut super::exploration::Exploration {
        self.dirty = true;
        &mut self.exploration
    }

    /// Brings the paper's run to the τ on screen, within one tick's step budget (so after `c`
    /// on a long session it catches up over several ticks). Returns whether it moved.
    pub fn catch_up(&mut self) -> bool {
        self.exploration.catch_up()
    }

    /// Whether the paper's run lags behind the one on screen (it is catching up).
    pub fn paper_lags(&self) -> bool {
        self.paper()
            .as_ref()
            .is_some_and(|p| p.live() && p.now().tau < self.sim().now().tau - 1e-9)
    }

    /// Whether the point model is drawn: always, but in a body scene whose body is drawn and
    /// `C` has hidden it.
    pub fn point_shown(&self) -> bool {
        self.view.point_model || self.rod().is_none()
    }

    /// The state on screen.
    pub fn now(&self) -> State {
        self.sim().now()
    }

    /// The next analysis job the page on screen needs and lacks, if any, with the settings it
    /// is computed at; an outcome map at the grid `map_grid` gives for its speed range. The
    /// shell holds the worker and measures the plot (`crate::session::sync`).
    pub fn wanted_job(
        &self,
        map_grid: impl Fn(f64) -> Option<(usize, usize)>,
    ) -> Option<(crate::analysis::Job, Settings)> {
        let job = super::pages::wanted(
            self.view.page,
            &self.charts,
            &self.initial(),
            self.settings(),
            map_grid,
        )?;
        let settings = match job {
            crate::analysis::Job::Trade { .. } => {
                crate::analysis::trade::trade_base(self.settings())
            }
            _ => crate::analysis::settings_for(self.settings()),
        };
        Some((job, settings))
    }

    /// A piece of an analysis job, brought by the shell's worker.
    pub fn receive(
        &mut self,
        job: &crate::analysis::Job,
        settings: Settings,
        piece: crate::analysis::Piece,
    ) {
        self.charts.apply(job, settings, piece);
        self.dirty = true;
    }

    /// The terminal's size as its session last said: the outcome map's grid follows it (the
    /// shell measures it: `ui::pages::map_grid`), a function of the size, not of when frames were drawn, so that
    /// the same keys give the same map.
    pub fn screen(&self) -> (u16, u16) {
        self.screen
    }

    /// Whether the initial conditions or settings differ from the scene as loaded, the scene
    /// taken as the app holds it (φ modulo 2π: D's 1.2π is −0.8π on screen, not an edit).
    pub fn edited(&self) -> bool {
        self.initial() != sanitize(self.scene().initial) || self.settings() != self.scene().settings
    }

    /// What the scene shows, one line: the scene's own words until it is edited, then what
    /// the run on screen does at the τ on screen, in the panel's notation; only its name while
    /// a lesson's prediction is open.
    pub fn about(&self) -> String {
        // A scene's words tell how it ends: not while a prediction is open.
        if self.outcome_open() {
            return self.scene().name.to_string();
        }
        if !self.edited() {
            return self.scene().about.to_string();
        }
        let base = self.scene().name.trim_end_matches(" (edited)");
        let sim = &self.sim();
        let what = match sim.outcome_now() {
            crate::engine::Outcome::Running => {
                format!("sliding at τ = {}", num(sim.now().tau, 3))
            }
            _ => self.ending(),
        };
        format!("{base}, edited: {what}")
    }

    /// How the run ends, once it is decided (whatever τ is on screen): empty before.
    pub(crate) fn ending(&self) -> String {
        let run = self.sim();
        match (run.status(), run.escape()) {
            (crate::engine::Status::Stuck { tau, q }, _) => {
                format!("sticks at ξ = {} (τ = {})", num(q.length(), 4), num(tau, 3))
            }
            (_, Some(e)) => format!("escapes (certified at τ = {})", num(e.tau, 3)),
            _ => String::new(),
        }
    }

    /// The current initial conditions, settings and view as a scene (what `s` saves); its
    /// words say how the run ends, or nothing while that is undecided.
    pub fn current_scene(&self) -> Scene {
        self.scene_named(None)
    }

    /// The scene on screen as [`App::current_scene`], under the name `name` if given.
    pub fn scene_named(&self, name: Option<&str>) -> Scene {
        let changed = self.edited() || name.is_some();
        Scene {
            name: if let Some(n) = name {
                n.into()
            } else if changed {
                format!(
                    "{} (edited)",
                    self.scene().name.trim_end_matches(" (edited)")
                )
                .into()
            } else {
                self.scene().name.clone()
            },
            // Unedited, the scene's own words stay (a preset saved under a name of one's own);
            // edited, how the run ends, or the release while that is undecided.
            about: if !self.edited() {
                self.scene().about.clone()
            } else if self.ending().is_empty() {
                release_words(&self.initial()).into()
            } else {
                self.ending().into()
            },
            initial: self.initial(),
            settings: self.settings(),
            units: self.units,
            body: self.scene().body,
            spin: self.scene().spin,
            view: Some(self.view.saved(self.speed)),
            pins: self.pins.iter().map(|p| p.spec.clone()).collect(),
        }
    }
}

/// A release in words, for a scene's description before its run has decided.
fn release_words(i: &Initial) -> String {
    // Shortest digits of the values rounded as the panel's precision goes (0.5, not 0.5000).
    let r = |x: f64| crate::present::short(x, 4);
    format!(
        "released at ξ0 = {}, φ = {}, v0 = {}",
        r(i.xi0),
        crate::present::angle(i.phi),
        r(i.v0)
    )
}
