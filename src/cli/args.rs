//! The command line as clap reads it: the explorer's flags, the subcommands and their
//! arguments, and the checks that turn them into engine settings.

use crate::engine::body::Body;
use crate::engine::units::G_DEFAULT;
use crate::engine::units::{Length, SizeRefused, Units};
use crate::engine::{Coupling, CouplingName, Frame, Method, Release, Settings};
use crate::error::Error;
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "turntable",
    version,
    about = "A particle sliding with dry friction on a rotating table (Agha, Gupta & Joseph 2015)",
    // The explorer's flags mean nothing to a subcommand: `turntable --fps 5 run` is an error.
    args_conflicts_with_subcommands = true,
    after_help = CONFIG_HELP
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    #[command(flatten)]
    pub look: Look,
    /// Explorer: frame-rate cap while playing [default: 30].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=240))]
    pub fps: Option<u32>,
    /// Explorer: how plots draw points: braille (2×4 dots a cell), block (half blocks) or
    /// ascii (`*`). Default: braille, or ascii where the locale (LC_ALL, LC_CTYPE, LANG) is
    /// not UTF-8.
    #[arg(long, value_enum, value_name = "KIND")]
    pub marker: Option<MarkerArg>,
    /// Explorer: do not capture the mouse (M toggles it inside).
    #[arg(long, overrides_with = "mouse")]
    pub no_mouse: bool,
    /// Explorer: capture the mouse (the default, unless the configuration says `mouse = false`).
    #[arg(long, overrides_with = "no_mouse")]
    pub mouse: bool,
    /// Explorer: record the session (keys, ticks, resizes, mouse) as a key script to FILE,
    /// written when the explorer exits; `turntable replay FILE` shows the same screens. An
    /// existing FILE is kept unless --force.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
    /// Explorer: replace the --record file if it exists (never a file the session reads).
    #[arg(long, requires = "record")]
    pub force: bool,
    /// Plain mode for screen readers: no canvas, no cursor movement, no colour; lines of text
    /// on stdout (the release, each change of state as it happens, notices, the readouts on
    /// `I`, the keys on `?`), keys as in the explorer. Works with TERM=dumb and with stdout
    /// piped (`| tee log`).
    #[arg(long)]
    pub plain: bool,
    #[command(flatten)]
    pub units: UnitsArgs,
    #[command(flatten)]
    pub coupling: CouplingArgs,
    #[command(flatten)]
    pub body: BodyArgs,
}

/// A finite body instead of a point (the paper's appendix), for the explorer and `run`.
/// Unset, a scene keeps its own.
#[derive(Args, Debug, Clone, Default)]
pub struct BodyArgs {
    /// The body's lateral size L (> 0): a plain number in units of R_max, or a length with a
    /// unit, m, cm or mm (`2cm`, `0.02m`, `15 mm`), on the table --mu and --rpm give (the
    /// explorer also takes a scene's or the configuration's [units]). The panel and
    /// `run --json` judge the appendix's conditions for treating it as a point, μh/L ≪ 1 and
    /// L/ξ ≪ 1.
    #[arg(long, value_name = "L", allow_hyphen_values = true, value_parser = length)]
    pub body_length: Option<Length>,
    /// The body's height h (≥ 0; with --body-length), as --body-length: R_max units or
    /// m, cm, mm. Toppling: μh/L.
    #[arg(long, value_name = "H", allow_hyphen_values = true, value_parser = length)]
    pub body_height: Option<Length>,
    /// The rod's angle at release in the table frame, from radially outward, ccw (rad, or
    /// degrees with `deg`: `30deg`; with --body-length).
    #[arg(long, value_name = "A", allow_hyphen_values = true, value_parser = angle)]
    pub body_angle: Option<f64>,
}

fn length(text: &str) -> Result<Length, String> {
    Length::parse(text)
}

/// Radians, or degrees with `deg` or `°`: `0.5`, `30deg`, `30 °`.
fn angle(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let (x, per_rad) = match t.strip_suffix("deg").or_else(|| t.strip_suffix('°')) {
        Some(x) => (x.trim_end(), 180.0 / std::f64::consts::PI),
        None => (t, 1.0),
    };
    x.parse::<f64>()
        .map(|x| x / per_rad)
        .map_err(|_| format!("`{t}` is not an angle: radians (0.5), or degrees with deg (30deg)"))
}

impl BodyArgs {
    /// The body asked for, checked, its sizes in R_max on the table `units` (a size in metres
    /// needs one; `where_units` says where the command takes it from); `None` if no flag was
    /// given.
    pub fn body(&self, units: Option<&Units>, where_units: &str) -> Result<Option<Body>, Error> {
        let Some(length) = self.body_length else {
            if self.body_height.is_some() || self.body_angle.is_some() {
                return Err(Error::invalid(
                    "--body-height and --body-angle describe a body: give its size with --body-length",
                ));
            }
            return Ok(None);
        };
        let r_max = |flag: &str, l: Length, zero_ok: bool| -> Result<f64, Error> {
            l.size_in_r_max(units, zero_ok).map_err(|e| Error::Invalid(match e {
                SizeRefused::Range(what) => format!("--{flag} must be {what}, got {}", l.show()),
                SizeRefused::NoTable => format!(
                    "--{flag} {} is a length in metres, which needs the real table's R_max: add {where_units}, or give it in units of R_max (a plain number)",
                    l.show()
                ),
            }))
        };
        let b = Body {
            length: r_max("body-length", length, false)?,
            height: self
                .body_height
                .map(|h| r_max("body-height", h, true))
                .transpose()?,
            angle: self.body_angle.unwrap_or(0.0),
        };
        crate::check::body(&b, crate::check::Via::Flags)?;
        Ok(Some(b))
    }
}

/// How the particle is coupled to the table (extends the paper), shared by the explorer and
/// every command. Unset, a scene keeps its own.
#[derive(Args, Debug, Clone, Default)]
pub struct CouplingArgs {
    /// coulomb (dry friction, the paper's) or stokes (drag −γ m u relative to the table, with
    /// --gamma; solved in closed form, every release but a measure-zero few leaves).
    #[arg(long, value_parser = variant::<CouplingName>())]
    pub coupling: Option<CouplingName>,
    /// Static over kinetic friction, mu_s/mu_k ≥ 1 (the paper: 1): at rest on the table the
    /// particle holds out to xi = R, and slides at mu_k once loose.
    #[arg(long, value_name = "R", allow_hyphen_values = true)]
    pub mu_static_ratio: Option<f64>,
    /// Stokes drag rate in units of Omega, ≥ 0 (implies --coupling stokes).
    #[arg(long, value_name = "G", allow_hyphen_values = true)]
    pub gamma: Option<f64>,
}

impl CouplingArgs {
    /// The coupling asked for, checked; `None` if no flag was given.
    pub fn coupling(&self) -> Result<Option<Coupling>, Error> {
        if self.coupling.is_none() && self.mu_static_ratio.is_none() && self.gamma.is_none() {
            return Ok(None);
        }
        let name = self.coupling.unwrap_or(if self.gamma.is_some() {
            CouplingName::Stokes
        } else {
            CouplingName::Coulomb
        });
        let c = name
            .with(self.mu_static_ratio, self.gamma)
            .map_err(|e| Error::Invalid(e.named("--gamma", "--mu-static-ratio", "--coupling")))?;
        c.validate()
            .map_err(|e| crate::check::named(e, crate::check::Via::Flags))?;
        Ok(Some(c))
    }
}

/// How plots draw points (`--marker`).
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum MarkerArg {
    Braille,
    Block,
    Ascii,
}

impl MarkerArg {
    /// Braille, unless the locale's character set is named and is not UTF-8 (`LANG=C`).
    pub fn from_locale(lookup: impl Fn(&str) -> Option<String>) -> MarkerArg {
        let set = ["LC_ALL", "LC_CTYPE", "LANG"]
            .into_iter()
            .find_map(|v| lookup(v).filter(|s| !s.is_empty()));
        match set {
            Some(s) if !s.to_ascii_lowercase().replace('-', "").contains("utf8") => {
                MarkerArg::Ascii
            }
            _ => MarkerArg::Braille,
        }
    }

    pub fn marker(self) -> ratatui::symbols::Marker {
        use ratatui::symbols::Marker;
        match self {
            MarkerArg::Braille => Marker::Braille,
            MarkerArg::Block => Marker::HalfBlock,
            MarkerArg::Ascii => Marker::Dot,
        }
    }
}

/// What the explorer shows, for the explorer and for `replay`.
#[derive(Args, Debug, Default, Clone)]
pub struct Look {
    /// Scene to open: a preset (A, B, C, D, fig1, fig2) or a .toml file. Default: C (replay:
    /// the script's own `# replay: --scene` line first).
    #[arg(long, value_name = "NAME|PATH")]
    pub scene: Option<String>,
    /// Colour theme: dark, light, high-contrast, mono, one of yours by name (explorer), or a
    /// .toml file; without a name, lists them. The explorer respects NO_COLOR; replay ignores it
    /// (its output depends on its arguments alone) and only --ansi shows colour.
    #[arg(long, value_name = "NAME|PATH", num_args = 0..=1, default_missing_value = "")]
    pub theme: Option<String>,
}

/// `turntable --help`, after the flags: the configuration file.
const CONFIG_HELP: &str = "Configuration (explorer only): $XDG_CONFIG_HOME/turntable/config.toml \
(~/.config/turntable/config.toml when XDG_CONFIG_HOME is unset) sets defaults for the explorer's \
flags, which win over it:

    theme = \"light\"        # a built-in, one of yours, or a .toml path (relative: to this folder)
    fps = 60
    mouse = false
    marker = \"block\"       # braille, block or ascii
    [units]                # as --mu, --rpm, --g (a scene's own [units] wins over these)
    mu = 0.15
    rpm = 33.3
    g = 9.81

Your themes: $XDG_CONFIG_HOME/turntable/themes/NAME.toml, chosen by NAME (`--theme NAME`); one \
named as a built-in replaces it. A bad file exits with code 2 naming the file and the key. \
`replay` and the numerical commands read no configuration (name a theme of yours by its path).";

/// `replay --help`: the script grammar, so that an installed binary documents it.
const REPLAY_ABOUT: &str = "Run a key script headlessly and print its snapshots.

A key script drives the explorer without a terminal: one step per token, top to bottom; a `#` that
begins a token starts a comment.

    resize 80x24                 # the off-screen terminal is now 80x24
    2 x*3 alt-v                  # keys by name; Name*N repeats a key N times
    tick 80                      # let 80 ticks pass (a tick is 0.05 of tau at speed 1)
    snapshot after 80 ticks
    space Right*5 ? esc          # pause, step five times, help on and off
    mouse click 20 8             # click|drag|up|scrollup|scrolldown COLUMN ROW (0-based)
    say C sticks.                # a caption over the scene (say alone clears it)

`snapshot LABEL` prints the screen (the rest of the line is its label). `say TEXT`, `ask TEXT`
(a prediction: y or n, yes meaning the run escapes) and `wait` narrate a lesson (see
`turntable lesson --help`). Keys: any single
character, space, hash, enter, esc, tab, backtab, backspace, delete, up, down, left, right, home,
end, pgup, pgdn, f1-f12, each with optional ctrl-, alt-, shift- prefixes. A first line
`# replay: [--size WxH] [--ansi] [--scene S] [--theme T]` sets options (flags win). The output
is byte-identical on every run: there is no clock, only ticks. `turntable --record FILE` writes
such a script from an interactive session.";

/// `lesson --help`: what a lesson is and how one runs.
const LESSON_ABOUT: &str = "Narrated lessons through the paper, shipped in the binary.

`turntable lesson --list` lists them; `turntable lesson NAME` runs one in the explorer, with a
caption over the scene: Space or Enter goes on where it waits, y or n answers its predictions
(\"Will it escape?\"), and the run then says whether the prediction was right; every other key
works as in the explorer. `turntable lesson NAME --headless [--size WxH]` prints its snapshots as
`replay` does (a wait goes on, a question stays unanswered).

A lesson is a key script (see `turntable replay --help`) with three more commands, which any key
script may use:

    say TEXT        # a caption over the scene until the next say or ask (say alone clears it)
    ask TEXT        # a prediction, y or n: yes means the run on screen escapes
    wait            # interactive: hold until Space or Enter; headless: go on";

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Integrate one trajectory and report how it ends.
    Run(RunArgs),
    /// Find the escape speed v_e(xi0, phi) (Fig. 5).
    Escape(EscapeArgs),
    /// Find the critical radius xi0c for release at rest in the lab (Fig. 6).
    Critical(CriticalArgs),
    /// CSV for Fig. 5 (v_e over phi), Fig. 6 (final rest xi over xi0) or the outcome map.
    Sweep(SweepArgs),
    /// A figure as SVG, for slides and notes: fig5, fig6, map, trajectory or time.
    Plot(PlotArgs),
    /// Work–precision measurements: error against cost for every method, and the speed goals.
    Bench(BenchArgs),
    /// Run a key script headlessly and print its snapshots.
    #[command(long_about = REPLAY_ABOUT)]
    Replay(super::replay::ReplayArgs),
    /// Narrated lessons through the paper: --list, NAME (in the explorer), NAME --headless.
    #[command(long_about = LESSON_ABOUT)]
    Lesson(super::lesson::LessonArgs),
    /// Print a shell completion script: `turntable completions bash > ~/.local/share/bash-completion/completions/turntable`.
    Completions(CompletionsArgs),
    /// Print the manual page (roff): `turntable man > ~/.local/share/man/man1/turntable.1`.
    Man,
}

#[derive(Args, Debug)]
pub struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// A small bench that finishes in seconds (fewer settings, cases and angles).
    #[arg(long)]
    pub quick: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Draw error against cost (log–log) as braille charts.
    #[arg(long)]
    pub plot: bool,
    /// Number of seeded random releases besides the paper's A, B and D.
    #[arg(long)]
    pub cases: Option<usize>,
    /// Seed of the random releases.
    #[arg(long)]
    pub seed: Option<u64>,
}

/// The integrator, shared by every command.
#[derive(Args, Debug, Clone)]
pub struct NumericsArgs {
    /// dp54 or dop853 (adaptive), rk4, rk2 (with stick events) or rk2-raw (the paper's scheme).
    #[arg(long, default_value = "dp54", value_parser = variant::<Method>())]
    pub method: Method,
    /// Tolerance of dp54 and dop853.
    #[arg(long, allow_hyphen_values = true)]
    pub tol: Option<f64>,
    /// Step of the fixed-step methods.
    #[arg(long, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Frame the equations are integrated in (lab is cheaper far from the centre).
    #[arg(long, default_value = "lab", value_parser = variant::<Frame>())]
    pub frame: Frame,
    /// Step budget of one run.
    #[arg(long, default_value_t = Settings::default().max_steps)]
    pub max_steps: u64,
    #[command(flatten)]
    pub coupling: CouplingArgs,
}

#[derive(Args, Debug)]
pub struct RunArgs {
    /// Release radius xi0 (units of R_max = mu g / Omega^2).
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub xi0: f64,
    /// Direction of the initial velocity in the table frame, from radially outward, ccw (rad).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub phi: f64,
    /// Initial speed relative to the table.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub v0: f64,
    /// How it is released: velocity (v0 at phi, table frame), table-rest (at rest on the
    /// table) or lab-rest (at rest in the lab).
    #[arg(long, default_value = "velocity", value_parser = variant::<Release>())]
    pub release: Release,
    /// mu = 0: no friction, a straight line in the lab, in closed form (no integration).
    #[arg(long)]
    pub frictionless: bool,
    #[command(flatten)]
    pub numerics: NumericsArgs,
    /// Stop at this time if the particle has neither stuck nor escaped.
    #[arg(long, default_value_t = 100.0, allow_hyphen_values = true)]
    pub tau_max: f64,
    /// Keep integrating after escape is certified, up to tau-max.
    #[arg(long)]
    pub follow: bool,
    /// Skip the second opinion (a run 1000x tighter in the other frame, dearer than this
    /// run): no `certain` then, nor measured errors.
    #[arg(long)]
    pub no_check: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Write the trajectory (one row per step) to this CSV file (atomically; an existing
    /// file is kept unless --force).
    #[arg(long)]
    pub trajectory: Option<PathBuf>,
    /// Replace the --trajectory file if it exists.
    #[arg(long, requires = "trajectory")]
    pub force: bool,
    #[command(flatten)]
    pub units: UnitsArgs,
    #[command(flatten)]
    pub body: BodyArgs,
}

/// A real table: every length, time and speed also in SI.
#[derive(Args, Debug, Clone, Default)]
pub struct UnitsArgs {
    /// Friction coefficient of a real table (with --rpm): SI values beside the dimensionless ones.
    #[arg(long, allow_hyphen_values = true)]
    pub mu: Option<f64>,
    /// The table's speed in revolutions per minute (with --mu).
    #[arg(long, allow_hyphen_values = true)]
    pub rpm: Option<f64>,
    /// Gravitational acceleration in m/s² (with --mu and --rpm) [default: 9.81].
    #[arg(long = "g", allow_hyphen_values = true)]
    pub gravity: Option<f64>,
}

impl UnitsArgs {
    /// The units asked for, if any: --mu and --rpm go together.
    pub fn units(&self) -> Result<Option<crate::engine::units::Units>, Error> {
        match (self.mu, self.rpm, self.gravity) {
            (None, None, None) => Ok(None),
            (Some(mu), Some(rpm), g) => {
                let u = Units {
                    mu,
                    rpm,
                    g: g.unwrap_or(G_DEFAULT),
                };
                crate::check::units(&u, crate::check::Via::Flags).map(Some)
            }
            _ => Err(Error::invalid(
                "physical units need both --mu and --rpm (and optionally --g)",
            )),
        }
    }
}

#[derive(Args, Debug)]
pub struct EscapeArgs {
    /// Release radius xi0 (units of R_max = mu g / Omega^2).
    #[arg(long, allow_hyphen_values = true)]
    pub xi0: f64,
    /// Direction of the initial velocity in the table frame, from radially outward, ccw (rad).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub phi: f64,
    /// Width of the final bracket on v0.
    #[arg(long = "vtol", default_value_t = 1e-8, allow_hyphen_values = true)]
    pub vtol: f64,
    /// Skip running the bracket's two ends in full against their second opinions: the
    /// bracket is then not certified.
    #[arg(long)]
    pub no_check: bool,
    #[command(flatten)]
    pub numerics: NumericsArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

#[derive(Args, Debug)]
pub struct CriticalArgs {
    /// Width of the final bracket on xi0.
    #[arg(long = "xtol", default_value_t = 1e-8, allow_hyphen_values = true)]
    pub xtol: f64,
    /// Skip running the bracket's two ends in full against their second opinions: the
    /// bracket is then not certified.
    #[arg(long)]
    pub no_check: bool,
    /// Measured: the table's angular speed Omega (rad/s). With --r0c it gives mu (Eq. 22).
    #[arg(long, requires = "r0c", allow_hyphen_values = true)]
    pub omega: Option<f64>,
    /// Measured: the largest release radius (m) at which a particle placed at rest in the lab
    /// still stays on the table.
    #[arg(long, requires = "omega", allow_hyphen_values = true)]
    pub r0c: Option<f64>,
    /// Gravitational acceleration (m/s²).
    #[arg(long, default_value_t = 9.81, allow_hyphen_values = true)]
    pub g: f64,
    #[command(flatten)]
    pub numerics: NumericsArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

#[derive(Args, Debug)]
pub struct SweepArgs {
    #[command(subcommand)]
    pub figure: SweepFigure,
}

/// What `sweep` computes: each takes only the flags that mean something to it.
#[derive(Subcommand, Debug)]
pub enum SweepFigure {
    /// Fig. 5: v_e over phi for each --xi0, as CSV `xi0,phi,v_escape`.
    Fig5(Fig5Args),
    /// Fig. 6: final rest xi over xi0 in [0, --xi0-max] for release at rest in the lab, as CSV
    /// `xi0,outcome,xi,angle`.
    Fig6(Fig6Args),
    /// The explorer's outcome map: stuck or escaped over (phi, v0) at one --xi0, as CSV
    /// `phi,v0,outcome,xi,angle`.
    Map(MapArgs),
    /// The appendix's body against the point: one release, the two-mass body of each
    /// --lengths run to rest, as CSV `length,l_over_r,outcome,xi,xi_point,xi_error,tau,tau_point`
    /// (r the point's rest radius): the appendix's "L ≪ r" as a number.
    Body(BodySweepArgs),
}

#[derive(Args, Debug)]
pub struct BodySweepArgs {
    /// Release radius [default: case A's 0.5].
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub xi0: f64,
    /// Direction of the initial velocity, table frame, rad [default: case A's π].
    #[arg(long, default_value_t = std::f64::consts::PI, allow_hyphen_values = true)]
    pub phi: f64,
    /// Initial speed relative to the table [default: case A's 1].
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub v0: f64,
    /// velocity, table-rest or lab-rest.
    #[arg(long, default_value = "velocity", value_parser = variant::<Release>())]
    pub release: Release,
    /// The body lengths L (units of R_max).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_values_t = [1e-6, 1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3])]
    pub lengths: Vec<f64>,
    /// The rod's angle at release (rad).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub body_angle: f64,
    /// Stop a run at this time if it has neither stuck nor escaped.
    #[arg(long, default_value_t = 100.0, allow_hyphen_values = true)]
    pub tau_max: f64,
    #[command(flatten)]
    pub numerics: NumericsArgs,
    #[command(flatten)]
    pub out: OutArg,
}

#[derive(Args, Debug)]
pub struct Fig5Args {
    #[command(flatten)]
    pub data: Fig5Data,
    #[command(flatten)]
    pub out: OutArg,
}

/// What Fig. 5 is computed from (`sweep fig5`, `plot fig5`).
#[derive(Args, Debug)]
pub struct Fig5Data {
    /// Release radii.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_values_t = [0.8, 0.5, 0.2, 0.001])]
    pub xi0: Vec<f64>,
    /// Number of angles phi in [0, 2π).
    #[arg(long, default_value_t = 72)]
    pub points: usize,
    /// Width of the final bracket on each escape speed.
    #[arg(long = "vtol", default_value_t = 1e-6, allow_hyphen_values = true)]
    pub vtol: f64,
    #[command(flatten)]
    pub numerics: NumericsArgs,
}

#[derive(Args, Debug)]
pub struct Fig6Args {
    #[command(flatten)]
    pub data: Fig6Data,
    #[command(flatten)]
    pub out: OutArg,
}

/// What Fig. 6 is computed from (`sweep fig6`, `plot fig6`).
#[derive(Args, Debug)]
pub struct Fig6Data {
    /// Number of release radii in [0, --xi0-max].
    #[arg(long, default_value_t = 72)]
    pub points: usize,
    /// Largest release radius.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub xi0_max: f64,
    #[command(flatten)]
    pub numerics: NumericsArgs,
}

#[derive(Args, Debug)]
pub struct MapArgs {
    #[command(flatten)]
    pub data: MapData,
    #[command(flatten)]
    pub out: OutArg,
}

/// What the outcome map is computed from (`sweep map`, `plot map`).
#[derive(Args, Debug)]
pub struct MapData {
    /// The release radius.
    #[arg(long, allow_hyphen_values = true)]
    pub xi0: f64,
    /// How phi and v0 are meant: velocity or table-rest, the speed relative to the table;
    /// lab-rest, the lab velocity (thrown from the lab, u0 = v − Ω×r).
    #[arg(long, default_value = "velocity", value_parser = variant::<Release>())]
    pub release: Release,
    /// Number of angles phi in [0, 2π).
    #[arg(long, default_value_t = 72)]
    pub phi_points: usize,
    /// Number of speeds v0 in (0, --v0-max].
    #[arg(long, default_value_t = 60)]
    pub v0_points: usize,
    /// Largest v0 [default: 1.3 × the largest v_e over phi, plus xi0 for lab-rest].
    #[arg(long, allow_hyphen_values = true)]
    pub v0_max: Option<f64>,
    /// Width of the bracket on the escape speeds that set the default --v0-max.
    #[arg(long = "vtol", default_value_t = 1e-6, allow_hyphen_values = true)]
    pub vtol: f64,
    #[command(flatten)]
    pub numerics: NumericsArgs,
}

#[derive(Args, Debug)]
pub struct OutArg {
    /// Write the CSV here instead of stdout (atomically; an existing file is kept unless
    /// --force).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace --out if it exists (never a file this command reads).
    #[arg(long, requires = "out")]
    pub force: bool,
}

#[derive(Args, Debug)]
pub struct PlotArgs {
    #[command(subcommand)]
    pub figure: PlotFigure,
}

/// What `plot` draws: each takes only the flags that mean something to it.
#[derive(Subcommand, Debug)]
pub enum PlotFigure {
    /// Fig. 5: v_e over phi, one curve per --xi0.
    Fig5 {
        #[command(flatten)]
        data: Fig5Data,
        #[command(flatten)]
        svg: SvgOut,
    },
    /// Fig. 6: final rest xi over xi0 for release at rest in the lab, with xi0c marked.
    Fig6 {
        #[command(flatten)]
        data: Fig6Data,
        #[command(flatten)]
        svg: SvgOut,
    },
    /// The outcome map over (phi, v0) at one --xi0, v_e(phi) drawn over it.
    Map {
        #[command(flatten)]
        data: MapData,
        #[command(flatten)]
        svg: SvgOut,
    },
    /// One run's path in the lab or the rotating frame, with the rim xi = 1.
    Trajectory {
        #[command(flatten)]
        run: PlotRun,
        /// The frame the path is drawn in.
        #[arg(long, default_value = "lab", value_parser = variant::<Frame>())]
        frame: Frame,
        #[command(flatten)]
        svg: SvgOut,
    },
    /// One run's xi, theta', |u| and energy against tau (the explorer's time plots).
    Time {
        #[command(flatten)]
        run: PlotRun,
        #[command(flatten)]
        svg: SvgOut,
    },
}

/// The run a trajectory or time figure shows: a scene, its release changed by the flags.
#[derive(Args, Debug)]
pub struct PlotRun {
    /// A preset (A, B, C, D, fig1, fig2) or a .toml scene file: its release and integrator.
    #[arg(long, default_value = "C", value_name = "NAME|PATH")]
    pub scene: String,
    /// Release radius xi0, instead of the scene's.
    #[arg(long, allow_hyphen_values = true)]
    pub xi0: Option<f64>,
    /// Direction of the initial velocity (rad), instead of the scene's.
    #[arg(long, allow_hyphen_values = true)]
    pub phi: Option<f64>,
    /// Initial speed relative to the table, instead of the scene's.
    #[arg(long, allow_hyphen_values = true)]
    pub v0: Option<f64>,
    /// How it is released, instead of the scene's: velocity, table-rest or lab-rest.
    #[arg(long, value_parser = variant::<Release>())]
    pub release: Option<Release>,
    /// Draw up to this time if the particle has neither stuck nor escaped far.
    #[arg(long, default_value_t = 100.0, allow_hyphen_values = true)]
    pub tau_max: f64,
}

/// Where a figure goes.
#[derive(Args, Debug)]
pub struct SvgOut {
    /// The SVG file to write (atomically; an existing file is kept unless --force).
    #[arg(long, value_name = "FILE.svg")]
    pub out: PathBuf,
    /// Replace --out if it exists (never a file this command reads).
    #[arg(long)]
    pub force: bool,
}

/// A clap parser for an engine enum: its names (from the strum derives) as the possible
/// values, so `--help` lists them and a typo is refused with the list; other spellings it
/// accepts (`rotating` for `table`) are aliases.
fn variant<T>() -> impl clap::builder::TypedValueParser<Value = T>
where
    T: strum::VariantArray + strum::EnumMessage + Into<&'static str> + std::str::FromStr,
    T: Clone + Send + Sync + 'static,
    T::Err: std::error::Error + Send + Sync + 'static,
{
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
    let values = T::VARIANTS.iter().map(|v| {
        let name: &'static str = v.clone().into();
        let aliases = v.get_serializations().iter().filter(|a| **a != name);
        PossibleValue::new(name).aliases(aliases)
    });
    PossibleValuesParser::new(values).try_map(|s| s.parse::<T>())
}

impl NumericsArgs {
    pub fn settings(&self) -> Result<Settings, Error> {
        let knob = if self.method.adaptive() {
            self.tol
        } else {
            self.dt
        };
        let s = Settings {
            scheme: self.method.with(knob.unwrap_or(self.method.default_knob())),
            frame: self.frame,
            max_steps: self.max_steps,
            coupling: self.coupling.coupling()?.unwrap_or(Coupling::PAPER),
        };
        match (self.method.adaptive(), self.tol, self.dt) {
            (true, _, Some(_)) => {
                return Err(Error::Invalid(format!(
                    "--dt applies to the fixed-step methods (rk4, rk2, rk2-raw); {} takes --tol",
                    self.method
                )));
            }
            (false, Some(_), _) => {
                return Err(Error::Invalid(format!(
                    "--tol applies to dp54 and dop853; {} takes --dt",
                    self.method
                )));
            }
            _ => {}
        }
        crate::check::settings(&s, crate::check::Via::Flags)?;
        Ok(s)
    }
}
