//! The explorer's state: the scene being edited, its run (and the paper's, to compare), and
//! how it is shown. Nothing here reads the clock: time passes only through ticks.

use super::pages::{Charts, Page};
use crate::analysis::Analysis;
use crate::engine::{Frame, Initial, Settings, State};
use crate::scene::Scene;
use crate::sim::Sim;
use crate::theme::Theme;
use crate::ui::panel::num;
use ratatui::layout::Rect;
use std::path::PathBuf;

/// Sim time per tick at speed 1 (at [`TICKS_PER_SECOND`]: 1.5 τ per second, about a quarter
/// turn).
pub const TICK_DT: f64 = 0.05;
/// The app's clock rate in wall-clock time (the terminal's, an asciicast's): each tick is
/// `TICK_DT × speed` of sim time.
pub const TICKS_PER_SECOND: u32 = 30;
/// Speed factor bounds (powers of two).
pub const SPEED_RANGE: (f64, f64) = (1.0 / 64.0, 256.0);
pub const ZOOM_RANGE: (f64, f64) = (1.0 / 64.0, 1024.0);
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
    /// How far the picture is turned (see [`App::turn`]).
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

#[derive(Clone, Debug)]
pub struct App {
    /// The scene as loaded (what `0` resets to).
    pub scene: Scene,
    /// The initial conditions and settings being explored.
    pub initial: Initial,
    pub settings: Settings,
    pub sim: Sim,
    /// The paper's scheme from the same initial conditions, when comparing.
    pub paper: Option<Sim>,
    /// The scene's finite body (the appendix's two masses on a rod) from the same release,
    /// drawn as a bar; None without a body, with μ = 0 or under Stokes drag.
    pub rod: Option<crate::engine::rod::RodTrack>,
    /// In a body scene, the point model's path and marker drawn beside the body (`C`).
    pub point_model: bool,
    /// What the last computed body track has to say (it was cut short), for the notice after
    /// the key that computed it.
    pub(crate) rod_notice: Option<String>,
    pub theme: Theme,
    pub playing: bool,
    pub speed: f64,
    /// The frame the picture is drawn in (lab or rotating).
    pub view: Frame,
    pub forces: bool,
    /// The net force's arrow (`A`) and the velocity's (`i`).
    pub net_force: bool,
    pub velocity: bool,
    /// Integrator step mode (`n`): step ends marked, step size and error shown.
    pub step_mode: bool,
    pub help: bool,
    /// The help's first row shown.
    pub help_scroll: u16,
    /// The time plots' τ span when fixed (`t`/`T`); None: the run so far.
    pub tau_window: Option<f64>,
    pub zoom: f64,
    /// The picture's turn (rad): the model releases on +x, the picture shows the release
    /// where it was clicked.
    pub turn: f64,
    /// View centre offset, in units of the auto-framed half-width.
    pub pan: glam::DVec2,
    pub mouse: bool,
    pub notice: Option<String>,
    /// How many times the readouts were asked for in words (`I`): plain mode prints them.
    pub readouts_asked: u64,
    /// The name being typed at the save prompt (`S`), while it is open.
    pub naming: Option<String>,
    pub save_path: PathBuf,
    /// False in a headless replay: `s` then says what it would save and writes nothing.
    pub writes_files: bool,
    pub quit: bool,
    /// What the body shows (`Tab` cycles).
    pub page: Page,
    /// What the analysis pages have received, and where it is computed.
    pub charts: Charts,
    pub analysis: Analysis,
    /// A real table (`--mu`, `--rpm`, `--g` or the scene's `[units]`): readouts in SI too.
    pub units: Option<crate::engine::units::Units>,
    /// The μ measurement of the rest-radius page (Eq. 22): Ω in rad/s and r0c in metres.
    pub mu_probe: (f64, f64),
    /// Runs pinned beside the one on screen (`b`), oldest first, at most
    /// [`crate::pin::MAX_PINS`].
    pub pins: Vec<crate::pin::Pin>,
    /// A narrated lesson's caption, question and wait.
    pub lesson: super::lesson::Lesson,
    pub(crate) dirty: bool,
    pub(crate) geom: Option<CanvasGeom>,
    /// The terminal's size, as its session last said (the outcome map's grid follows it).
    pub(crate) screen: (u16, u16),
    /// Mouse drag in progress: setting the initial velocity.
    pub(crate) dragging: bool,
}

/// Radius past which an escaped particle is no longer integrated.
pub fn view_radius(initial: &Initial) -> f64 {
    3.0 * initial.xi0.max(1.5)
}

impl App {
    pub(crate) fn build(scene: Scene, theme: Theme) -> App {
        let initial = sanitize(scene.initial);
        let settings = if scene.settings.validate().is_ok() {
            scene.settings
        } else {
            Settings::default()
        };
        let sim = make_sim(initial, settings);
        let rod = make_rod(scene.body, &initial, settings);
        let rod_notice = rod.as_ref().and_then(rod_cut_notice);
        let units = scene.units;
        let mut pins = Vec::new();
        for spec in scene.pins.iter().rev().take(crate::pin::MAX_PINS).rev() {
            // Checked when the scene was loaded: a pin that still fails is left out.
            if let Ok(p) = pin_of(spec.clone(), &pins) {
                pins.push(p);
            }
        }
        let view = scene.view.filter(|v| v.zoom.is_finite() && v.zoom > 0.0);
        App {
            scene,
            initial,
            settings,
            sim,
            paper: None,
            rod,
            point_model: view.is_none_or(|v| v.point),
            rod_notice: None,
            theme,
            playing: true,
            speed: 1.0,
            view: view.map_or(Frame::Lab, |v| v.frame),
            forces: view.is_some_and(|v| v.forces),
            net_force: view.is_some_and(|v| v.net_force),
            velocity: view.is_some_and(|v| v.velocity),
            step_mode: false,
            help: false,
            help_scroll: 0,
            tau_window: None,
            zoom: view.map_or(1.0, |v| v.zoom.clamp(ZOOM_RANGE.0, ZOOM_RANGE.1)),
            turn: 0.0,
            pan: glam::DVec2::ZERO,
            mouse: true,
            notice: rod_notice,
            readouts_asked: 0,
            save_path: PathBuf::from(SAVE_PATH),
            writes_files: true,
            naming: None,
            quit: false,
            page: view.map_or(Page::Turntable, |v| v.page),
            charts: Charts::default(),
            analysis: Analysis::inline(),
            mu_probe: MU_PROBE,
            units,
            pins,
            lesson: Default::default(),
            dirty: true,
            geom: None,
            screen: (80, 24),
            dragging: false,
        }
    }

    /// Restarts both runs at τ = 0 from the current initial conditions and settings.
    pub fn restart(&mut self) {
        self.initial = sanitize(self.initial);
        self.sim = make_sim(self.initial, self.settings);
        self.rod = make_rod(self.scene.body, &self.initial, self.settings);
        self.rod_notice = self.rod.as_ref().and_then(rod_cut_notice);
        if self.paper.is_some() {
            self.paper = Some(make_sim(self.initial, Settings::paper()));
        }
    }

    /// Brings the paper's run to the τ on screen, within one tick's step budget (so after `c`
    /// on a long session it catches up over several ticks). Returns whether it moved.
    pub fn catch_up(&mut self) -> bool {
        let target = self.sim.now().tau;
        self.paper.as_mut().is_some_and(|p| p.catch_up_to(target))
    }

    /// Whether the paper's run lags behind the one on screen (it is catching up).
    pub fn paper_lags(&self) -> bool {
        self.paper
            .as_ref()
            .is_some_and(|p| p.live() && p.now().tau < self.sim.now().tau - 1e-9)
    }

    /// Whether the point model is drawn: always, but in a body scene whose body is drawn and
    /// `C` has hidden it.
    pub fn point_shown(&self) -> bool {
        self.point_model || self.rod.is_none()
    }

    /// The state on screen.
    pub fn now(&self) -> State {
        self.sim.now()
    }

    /// Brings the analysis pages up to date for a frame: takes the pieces that arrived and
    /// asks for what the page on screen still lacks, computing it now when inline (headless).
    /// Returns whether anything arrived or was asked.
    pub fn sync_analysis(&mut self) -> bool {
        self.sync(true)
    }

    /// As [`App::sync_analysis`], but an inline request is only noted: keys and ticks call
    /// this, so fifty edits before a frame compute one page, not fifty.
    pub(crate) fn ask_analysis(&mut self) -> bool {
        self.sync(false)
    }

    fn sync(&mut self, compute: bool) -> bool {
        let mut moved = false;
        // Inline, each request completes when computed: a page needs at most five jobs.
        for _ in 0..8 {
            if compute {
                self.analysis.compute();
            }
            if let Some((job, settings)) = self.analysis.current() {
                for p in self.analysis.take() {
                    self.charts.apply(&job, settings, p);
                    moved = true;
                }
            }
            let settings = crate::analysis::settings_for(self.settings);
            let wanted = super::pages::wanted(
                self.page,
                &self.charts,
                &self.initial,
                self.settings,
                |v0_max| crate::ui::pages::map_grid(self, v0_max),
            );
            let Some(job) = wanted else {
                // Nothing is computed for a page that is not on screen.
                self.analysis.cancel();
                break;
            };
            if self.analysis.current() == Some((job, settings)) {
                // In flight, or done and still lacking (a failed piece): ask no more.
                break;
            }
            let todo = self.charts.missing(&job, settings);
            self.analysis.request(job, settings, todo);
            moved = true;
        }
        self.dirty |= moved;
        moved
    }

    /// The terminal's size as its session last said: the outcome map's grid follows it (see
    /// `ui::pages::map_grid`), a function of the size, not of when frames were drawn, so that
    /// the same keys give the same map.
    pub fn screen(&self) -> (u16, u16) {
        self.screen
    }

    /// Whether the initial conditions or settings differ from the scene as loaded, the scene
    /// taken as the app holds it (φ modulo 2π: D's 1.2π is −0.8π on screen, not an edit).
    pub fn edited(&self) -> bool {
        self.initial != sanitize(self.scene.initial) || self.settings != self.scene.settings
    }

    /// What the scene shows, one line: the scene's own words until it is edited, then what
    /// the run on screen does at the τ on screen, in the panel's notation.
    pub fn about(&self) -> String {
        if !self.edited() {
            return self.scene.about.to_string();
        }
        let base = self.scene.name.trim_end_matches(" (edited)");
        let sim = &self.sim;
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
        let run = &self.sim.run;
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

    /// The scene on screen as [`App::current_scene`], under the name `name` if given: a named
    /// scene is the user's own, so its description is what the run does.
    pub fn scene_named(&self, name: Option<&str>) -> Scene {
        let changed = self.edited() || name.is_some();
        Scene {
            name: if let Some(n) = name {
                n.into()
            } else if changed {
                format!("{} (edited)", self.scene.name.trim_end_matches(" (edited)")).into()
            } else {
                self.scene.name.clone()
            },
            about: if changed {
                self.ending().into()
            } else {
                self.scene.about.clone()
            },
            initial: self.initial,
            settings: self.settings,
            units: self.units,
            body: self.scene.body,
            view: Some(crate::scene::View {
                page: self.page,
                frame: self.view,
                forces: self.forces,
                zoom: self.zoom,
                net_force: self.net_force,
                velocity: self.velocity,
                point: self.point_model,
            }),
            pins: self.pins.iter().map(|p| p.spec.clone()).collect(),
        }
    }

    /// Pins the run on screen (`b`): its whole path, computed now at bounded cost, labelled
    /// by the scene's name, or by a letter once edited. A seventh pin replaces the oldest.
    pub fn pin_run(&mut self) {
        let dropped = if self.pins.len() >= crate::pin::MAX_PINS {
            Some(self.pins.remove(0))
        } else {
            None
        };
        let label = if self.edited() {
            let used = |c: char| self.pins.iter().any(|p| *p.spec.label == *c.to_string());
            ('A'..='Z').find(|c| !used(*c)).unwrap_or('?').to_string()
        } else {
            self.scene
                .name
                .chars()
                .take(crate::pin::LABEL_MAX)
                .collect()
        };
        let spec = crate::pin::PinSpec {
            label: label.into(),
            initial: self.initial,
            settings: self.settings,
            turn: self.turn,
            units: self.units,
        };
        match pin_of(spec, &self.pins) {
            Ok(p) => {
                let what = match p.outcome {
                    crate::engine::Outcome::Stuck => {
                        format!("sticks at ξ = {}", num(p.end().xi(), 4))
                    }
                    crate::engine::Outcome::Escaped => "escapes".into(),
                    crate::engine::Outcome::Running if p.end().tau < crate::pin::PIN_TAU_MAX => {
                        format!(
                            "still slides at τ = {}, where a pin's {} steps ran out",
                            num(p.end().tau, 3),
                            crate::pin::PIN_STEPS
                        )
                    }
                    crate::engine::Outcome::Running => {
                        format!("still slides at τ = {}", num(p.end().tau, 1))
                    }
                };
                let mut n = format!(
                    "pinned {}{} ({} of {}): {what}; B clears the pins",
                    p.marker,
                    p.spec.label,
                    self.pins.len() + 1,
                    crate::pin::MAX_PINS
                );
                if let Some(d) = dropped {
                    n.push_str(&format!(
                        "; {} pins at most: the oldest, {}{}, unpinned",
                        crate::pin::MAX_PINS,
                        d.marker,
                        d.spec.label
                    ));
                }
                self.pins.push(p);
                self.notice = Some(n);
            }
            Err(e) => self.notice = Some(format!("cannot pin this run: {e}")),
        }
    }

    /// The τ span the time plots show by default: the run so far, or the longest pin.
    pub fn plot_span(&self) -> f64 {
        self.pins
            .iter()
            .map(|p| p.end().tau * p.scale(self.units).1)
            .fold(self.sim.now().tau, f64::max)
    }
}

/// A pin of `spec`, its marker the first one `pins` leaves free.
fn pin_of(
    spec: crate::pin::PinSpec,
    pins: &[crate::pin::Pin],
) -> Result<crate::pin::Pin, crate::error::Error> {
    let marker = crate::pin::MARKERS
        .into_iter()
        .find(|m| pins.iter().all(|p| p.marker != *m))
        .unwrap_or(crate::pin::MARKERS[0]);
    let radius = view_radius(&spec.initial);
    crate::pin::Pin::compute(spec, marker, radius)
}

/// Keeps user-edited values valid: ξ0, v0 finite and clamped to [0, [`Initial::MAX`]] (an
/// edit past the bound stops there, it never panics); φ wrapped into (−π, π].
pub fn sanitize(mut i: Initial) -> Initial {
    let fin = |x: f64| if x.is_finite() { x } else { 0.0 };
    let clamp = |x: f64| ((fin(x) * 1e9).round() / 1e9).clamp(0.0, Initial::MAX);
    i.xi0 = clamp(i.xi0);
    i.v0 = clamp(i.v0);
    i.phi = crate::engine::model::wrap_angle(fin(i.phi));
    i
}

/// The body's track to draw, up to [`ROD_TAU`], an escaping body followed past its
/// certificate out to the point's [`view_radius`] (the class sees it leave), within the
/// track's step and state budgets; None where there is no body, no dry friction, or the body
/// is refused (the panel's conditions still show).
fn make_rod(
    body: Option<crate::engine::body::Body>,
    initial: &Initial,
    settings: Settings,
) -> Option<crate::engine::rod::RodTrack> {
    let body = body?;
    if initial.frictionless || settings.stokes().is_some() {
        return None;
    }
    let tol = settings.scheme.tol().unwrap_or(1e-10);
    use crate::engine::rod::{RodRun, RodTrack, TRACK_STATES, TRACK_STEPS};
    let run = RodRun::new(body, settings.hold(), initial, tol).ok()?;
    let run = run.following(view_radius(initial));
    Some(RodTrack::from_run(run, ROD_TAU, TRACK_STEPS, TRACK_STATES))
}

/// How far in τ the explorer runs the body.
pub const ROD_TAU: f64 = 200.0;

/// What to say when a body's track stopped short of its run's end: where, and why.
pub fn rod_cut_notice(rod: &crate::engine::rod::RodTrack) -> Option<String> {
    use crate::engine::rod::Cut;
    let at = num(rod.end_tau(), 3);
    if let (Some(c), Some(Cut::Budget(n))) = (rod.escape, rod.cut.as_ref()) {
        // Past the certificate the escape stands: only the drawing of it leaving stops.
        return Some(format!(
            "body escapes (τ = {}), drawn leaving to τ = {at} only: its {n}-step budget ran out",
            num(c, 3)
        ));
    }
    Some(match rod.cut.as_ref()? {
        Cut::Budget(n) => format!("body drawn to τ = {at} only: its {n}-step budget ran out"),
        Cut::Failed(e) => format!("body drawn to τ = {at} only: its run failed ({e})"),
    })
}

pub(crate) fn make_sim(initial: Initial, settings: Settings) -> Sim {
    Sim::new(initial, settings, view_radius(&initial))
        .or_else(|_| Sim::new(sanitize(initial), Settings::default(), 4.5))
        .expect("sanitized initial conditions and default settings are valid")
}
