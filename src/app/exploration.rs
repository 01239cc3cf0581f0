//! What is explored: the scene as loaded, the initial conditions and settings being edited,
//! and the runs from them (the point's, the paper's to compare, the body's track). Its fields
//! are private and every setter restarts the runs, so the runs on screen are always those of
//! the initial conditions and settings shown: no caller places a `restart()` by hand, and
//! nothing checks at run time what the type holds.

use crate::engine::rod::{RodTrack, TRACK_STEPS};
use crate::engine::{Initial, Release, Settings};
use crate::present::num;
use crate::scene::Scene;
use crate::sim::Sim;

pub mod testing;

#[derive(Clone, Debug)]
pub struct Exploration {
    /// The scene as loaded (what `0` resets to).
    scene: Scene,
    initial: Initial,
    settings: Settings,
    sim: Sim,
    /// The paper's scheme from the same initial conditions, when comparing.
    paper: Option<Sim>,
    /// The scene's finite body from the same release; None without a body, with μ = 0 or
    /// under Stokes drag.
    rod: Option<RodTrack>,
    /// What the last computed body track has to say (it was cut short), until taken.
    rod_notice: Option<String>,
}

impl Exploration {
    /// The scene's release and settings (default settings if the scene's are refused), run
    /// from τ = 0.
    pub fn new(scene: Scene) -> Exploration {
        let initial = sanitize(scene.initial);
        let settings = valid(scene.settings);
        let mut e = Exploration {
            sim: make_sim(initial, settings, scene.spin),
            scene,
            initial,
            settings,
            paper: None,
            rod: None,
            rod_notice: None,
        };
        e.restart();
        e
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn initial(&self) -> Initial {
        self.initial
    }

    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// The run on screen.
    pub fn sim(&self) -> &Sim {
        &self.sim
    }

    /// The paper's run, when comparing.
    pub fn paper(&self) -> Option<&Sim> {
        self.paper.as_ref()
    }

    /// The body's track, in a body scene that runs one.
    pub fn rod(&self) -> Option<&RodTrack> {
        self.rod.as_ref()
    }

    /// New initial conditions (kept valid: see [`sanitize`]); the runs restart.
    pub fn set_initial(&mut self, initial: Initial) {
        self.initial = initial;
        self.restart();
    }

    /// An edit of the initial conditions; the runs restart.
    pub fn edit_initial(&mut self, edit: impl FnOnce(&mut Initial)) {
        let mut i = self.initial;
        edit(&mut i);
        self.set_initial(i);
    }

    /// New settings (default settings if refused); the runs restart.
    pub fn set_settings(&mut self, settings: Settings) {
        self.settings = valid(settings);
        self.restart();
    }

    /// A scene loaded in place of this one: its release and settings; the runs restart.
    pub fn load(&mut self, scene: Scene) {
        self.initial = scene.initial;
        self.settings = valid(scene.settings);
        self.scene = scene;
        self.restart();
    }

    /// Back to the scene as loaded; the runs restart.
    pub fn reset(&mut self) {
        self.initial = self.scene.initial;
        self.settings = valid(self.scene.settings);
        self.restart();
    }

    /// The release and the body carried to a new table (SI units changed); the runs restart.
    pub fn carry(&mut self, from: &crate::engine::units::Units, to: &crate::engine::units::Units) {
        self.initial = from.carry(self.initial, to);
        self.scene.body = self.scene.body.map(|b| b.carried(from, to));
        self.restart();
    }

    /// The paper's run beside the one on screen, or not. It starts at τ = 0 and catches up
    /// over the next ticks ([`Exploration::catch_up`]): the key itself integrates nothing.
    pub fn compare(&mut self, on: bool) {
        self.paper = on.then(|| make_sim(self.initial, Settings::paper(), None));
    }

    /// Restarts the runs at τ = 0 from the current initial conditions and settings.
    pub fn restart(&mut self) {
        self.initial = sanitize(self.initial);
        if self.scene.spin.is_some() {
            // The spin-up starts its coin at rest on the table, with friction: nothing else
            // would be run, so nothing else is shown.
            self.initial = Initial::at_rest(self.initial.xi0, Release::TableRest);
        }
        self.sim = make_sim(self.initial, self.settings, self.scene.spin);
        // The settings shown are those run (the spin-up refuses the paper's raw scheme).
        self.settings = self.sim.settings();
        // A spin-up spins a point coin: no body beside it.
        let body = self.scene.body.filter(|_| self.scene.spin.is_none());
        self.rod = make_rod(body, &self.initial, self.settings, TRACK_STEPS);
        self.rod_notice = self.rod.as_ref().and_then(rod_cut_notice);
        // The paper's RK2 runs a table at constant Ω: a spin-up has nothing to compare it with.
        if self.paper.is_some() {
            self.compare(self.scene.spin.is_none());
        }
    }

    /// What the body's track, computed by the last restart, has to say (it was cut short).
    pub fn take_rod_notice(&mut self) -> Option<String> {
        self.rod_notice.take()
    }

    /// The runs, to move along in time (advance, step, walk the history): their initial
    /// conditions and settings are not theirs to change.
    pub(crate) fn runs_mut(&mut self) -> (&mut Sim, Option<&mut Sim>) {
        (&mut self.sim, self.paper.as_mut())
    }

    /// Brings the paper's run to the τ on screen, within one tick's step budget (so after `c`
    /// on a long session it catches up over several ticks). Returns whether it moved.
    pub fn catch_up(&mut self) -> bool {
        let target = self.sim.now().tau;
        self.paper.as_mut().is_some_and(|p| p.catch_up_to(target))
    }
}

/// The settings, or the default ones if they are refused.
fn valid(settings: Settings) -> Settings {
    if settings.validate().is_ok() {
        settings
    } else {
        Settings::default()
    }
}

/// Radius past which an escaped particle is no longer integrated.
pub fn view_radius(initial: &Initial) -> f64 {
    3.0 * initial.xi0.max(1.5)
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
pub(super) fn make_rod(
    body: Option<crate::engine::body::Body>,
    initial: &Initial,
    settings: Settings,
    steps: u64,
) -> Option<crate::engine::rod::RodTrack> {
    let body = body?;
    if crate::engine::closed_form(initial, settings) {
        return None;
    }
    let tol = settings.scheme.tol().unwrap_or(1e-10);
    use crate::engine::rod::{RodRun, RodTrack, TRACK_STATES};
    let run = RodRun::new(body, settings.hold(), initial, tol).ok()?;
    let run = run.following(view_radius(initial));
    Some(RodTrack::from_run(run, ROD_TAU, steps, TRACK_STATES))
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

/// The point's run: on the scene's spun-up table if it has one (a coin at rest on it, as the
/// spin-up takes: `update` keeps a spin-up scene's release and method to those), else the
/// paper's table.
pub(super) fn make_sim(
    initial: Initial,
    settings: Settings,
    spin: Option<crate::engine::spinup::Ramp>,
) -> Sim {
    let radius = view_radius(&initial);
    let sim = match spin {
        Some(r) => Sim::spin(r, initial.xi0, settings, radius)
            .or_else(|_| Sim::spin(r, initial.xi0, Settings::default(), radius)),
        None => Sim::new(initial, settings, radius),
    };
    sim.or_else(|_| Sim::new(sanitize(initial), Settings::default(), 4.5))
        .expect("sanitized initial conditions and default settings are valid")
}
