//! The command line as clap reads it: the explorer's flags, the subcommands and their
//! arguments, and the checks that turn them into engine settings.

use crate::engine::body::Body;
use crate::engine::units::G_DEFAULT;
use crate::engine::units::{Length, SizeRefused, Units};
use crate::engine::{Coupling, CouplingName, Frame, Method, Release, Settings};
use crate::error::Error;
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

mod figures;
mod model;
mod names;

pub use figures::*;
pub use model::*;
pub use names::{NameOrPath, with_files};

#[derive(Parser, Debug)]
#[command(
    name = "turntable",
    version,
    about = "A particle sliding with dry friction on a rotating table (Agha, Gupta & Joseph 2015)",
    // The explorer's flags mean nothing to a subcommand: `turntable --fps 5 run` is an error.
    args_conflicts_with_subcommands = true,
    after_help = "The explorer's defaults: `turntable config` prints where they are kept and how.",
    after_long_help = CONFIG_HELP
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Frame-rate cap while playing [default: 30].
    #[arg(long, help_heading = "Explorer", value_parser = clap::value_parser!(u32).range(1..=240))]
    pub fps: Option<u32>,
    /// How plots draw points: braille, block or ascii.
    ///
    /// braille (2×4 dots a cell), block (half blocks) or ascii (`*`). Default: braille, or
    /// ascii where the locale (LC_ALL, LC_CTYPE, LANG) is not UTF-8.
    #[arg(long, help_heading = "Explorer", value_enum, value_name = "KIND")]
    pub marker: Option<MarkerArg>,
    /// How fast time plays at the start: a power of two from 1/64 to 256.
    ///
    /// 0.25 is slow motion; `[` and `]` halve and double it inside [default: the scene's,
    /// else 1].
    #[arg(long, help_heading = "Explorer", value_name = "X", value_parser = parse_speed)]
    pub speed: Option<f64>,
    /// Start paused (Space plays).
    #[arg(long, help_heading = "Explorer")]
    pub paused: bool,
    /// Do not capture the mouse (M toggles it inside).
    #[arg(long, help_heading = "Explorer", overrides_with = "mouse")]
    pub no_mouse: bool,
    /// Capture the mouse (the default, unless the configuration says `mouse = false`).
    #[arg(long, help_heading = "Explorer", overrides_with = "no_mouse")]
    pub mouse: bool,
    /// Record the session as a key script to FILE.
    ///
    /// Keys, ticks, resizes and the mouse, written when the explorer exits; `turntable replay
    /// FILE` shows the same screens. An existing FILE is kept unless --force.
    #[arg(long, help_heading = "Explorer", value_name = "FILE")]
    pub record: Option<PathBuf>,
    /// Replace the --record file if it exists (never a file the session reads).
    #[arg(long, help_heading = "Explorer", requires = "record")]
    pub force: bool,
    /// Plain mode for screen readers: lines of text, no screen.
    ///
    /// No canvas, no cursor movement, no colour; lines of text on stdout (the release, each
    /// change of state as it happens, notices, the readouts on `I`, the keys on `?`), keys as
    /// in the explorer. Works with TERM=dumb and with stdout piped (`| tee log`).
    #[arg(long, help_heading = "Explorer")]
    pub plain: bool,
    /// Read this configuration file instead of the usual one (`turntable config` shows it).
    #[arg(long, value_name = "FILE", help_heading = "Explorer")]
    pub config: Option<PathBuf>,
    #[command(flatten)]
    pub look: Look,
    #[command(flatten)]
    pub units: UnitsArgs,
    #[command(flatten)]
    pub coupling: CouplingArgs,
    #[command(flatten)]
    pub body: BodyArgs,
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
    // Its help names every preset (`scene::PRESETS`).
    #[arg(long, value_name = "NAME|PATH", value_parser = NameOrPath::scenes(), hide_possible_values = true,
        help = scene_help(false), long_help = scene_help(true))]
    pub scene: Option<String>,
    /// Colour theme: dark, light, high-contrast, mono, yours, or a .toml file; alone, lists them.
    ///
    /// One of yours by name in the explorer (see the configuration below). The explorer
    /// respects NO_COLOR; replay ignores it (its output depends on its arguments alone) and
    /// only --ansi shows colour.
    #[arg(long, value_name = "NAME|PATH", num_args = 0..=1, default_missing_value = "",
        value_parser = NameOrPath::themes(), hide_possible_values = true)]
    pub theme: Option<String>,
}

/// `--scene`'s help: what it opens, every preset by name.
fn scene_help(long: bool) -> String {
    let short = format!(
        "Scene to open: a preset ({}) or a .toml file [default: C]",
        crate::scene::PRESETS.join(", ")
    );
    if long {
        short + ".\n\nFor replay, the script's own `# replay: --scene` line comes first."
    } else {
        short + "."
    }
}

/// `turntable --help`, after the flags: the configuration file.
const CONFIG_HELP: &str = "Configuration (explorer only): $XDG_CONFIG_HOME/turntable/config.toml \
(~/.config/turntable/config.toml when XDG_CONFIG_HOME is unset, or --config FILE) sets defaults \
for the explorer's flags, which win over it: theme, fps, speed, paused, mouse, marker and \
[units]. `turntable config` prints its path and a commented template.

Your themes: themes/NAME.toml beside the configuration, chosen by NAME (`--theme NAME`); one \
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
caption over the scene: Enter goes on where it waits, y or n answers its predictions (\"Will it
escape?\"), and the run then says whether the prediction was right; Space plays and pauses at
every moment (a pause holds the lesson, it never moves it on); every other key works as in the
explorer. `turntable lesson PATH` runs a lesson of your own, a key script file, the same way.
`turntable lesson NAME|PATH --headless [--size WxH]` prints its snapshots as `replay` does (a
wait goes on, a question stays unanswered).

A lesson is a key script (see `turntable replay --help`) with five more commands, which any key
script may use:

    say TEXT        # a caption over the scene until the next say or ask (say alone clears it)
    ask TEXT        # a prediction, y or n: yes means the run on screen escapes
    wait            # interactive: hold until Enter; headless: go on
    play [SPEED]    # time plays, at SPEED (a power of two, e.g. 0.25) or x1
    pause           # time stands still";

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
    /// Spin the table up under a coin at rest until it slides: the slip, the mu it suggests.
    Spinup(super::spinup::SpinupArgs),
    /// A figure as SVG, for slides and notes: fig5, fig6, map, trajectory or time.
    Plot(PlotArgs),
    /// Work–precision measurements: error against cost for every method, and the speed goals.
    Bench(BenchArgs),
    /// Run a key script headlessly and print its snapshots.
    #[command(long_about = REPLAY_ABOUT)]
    Replay(super::replay::ReplayArgs),
    /// Serve the explorer over SSH to a class: each connection its own explorer, a presenter
    /// who leads (`ssh -p 2222 class@HOST`).
    #[cfg(feature = "serve")]
    Serve(super::serve::ServeArgs),
    /// Narrated lessons through the paper: --list, NAME (in the explorer), NAME --headless.
    #[command(long_about = LESSON_ABOUT)]
    Lesson(super::lesson::LessonArgs),
    /// Print a shell completion script (bash, zsh, fish, powershell, elvish): where each goes
    /// is in docs/command-line.md, *Installing the extras*.
    ///
    /// For bash: `mkdir -p ~/.local/share/bash-completion/completions && turntable completions
    /// bash > ~/.local/share/bash-completion/completions/turntable`; zsh: `mkdir -p ~/.zfunc && turntable
    /// completions zsh > ~/.zfunc/_turntable` with `fpath=(~/.zfunc $fpath)` before compinit; fish:
    /// `turntable completions fish > ~/.config/fish/completions/turntable.fish`; PowerShell:
    /// `turntable completions powershell | Out-String | Invoke-Expression` in $PROFILE.
    Completions(CompletionsArgs),
    /// Print the manual page (roff): `mkdir -p ~/.local/share/man/man1 && turntable man >
    /// ~/.local/share/man/man1/turntable.1`.
    ///
    /// `man turntable` finds it there when ~/.local/bin is on PATH; else add
    /// `export MANPATH="$HOME/.local/share/man:$MANPATH"` to ~/.profile.
    Man,
    /// Print where the explorer's configuration is kept, and a commented template (--init
    /// writes it there).
    Config(ConfigArgs),
}

#[derive(Args, Debug)]
pub struct ConfigArgs {
    /// Print only the path.
    #[arg(long, conflicts_with = "init")]
    pub path: bool,
    /// Write the commented template there, making its folder; never over a file.
    #[arg(long)]
    pub init: bool,
}

#[derive(Args, Debug)]
pub struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Measure `turntable serve` instead: the server on 127.0.0.1 and this many in-process
    /// SSH clients at 80x24, each playing and pressing a key every 200 ms (a list, e.g.
    /// 10,30,60: one row each).
    #[cfg(feature = "serve")]
    #[arg(long, value_name = "N,...", value_delimiter = ',')]
    pub serve: Vec<usize>,
    /// Seconds each --serve row runs.
    #[cfg(feature = "serve")]
    #[arg(long, default_value_t = 60.0, requires = "serve")]
    pub seconds: f64,
    /// With --serve N: also a presenter and N students, and beside them, one at a time for
    /// --seconds each, one client's floods (F2, keys, window changes) and the door held (200
    /// silent connections, 50 logins without a shell): latencies, the CPU and memory each
    /// costs, and a login meanwhile.
    #[cfg(feature = "serve")]
    #[arg(long, requires = "serve")]
    pub attacks: bool,
    /// With --serve N: a class of followers instead: a presenter playing and pressing a key
    /// every 200 ms, and N students following it: the presenter's key to each follower's
    /// screen, the CPU and the CPU a frame.
    #[cfg(feature = "serve")]
    #[arg(long, requires = "serve")]
    pub followers: bool,
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
    /// The Python interpreter whose SciPy (compiled DOP853, docs/scipy-escape.py) a certified
    /// escape is measured against; where it or SciPy is missing, the bench says so.
    #[arg(long, value_name = "PATH", default_value = "python3")]
    pub python: std::path::PathBuf,
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
    /// Stop at this time if the particle has neither stuck nor escaped.
    #[arg(long, default_value_t = 100.0, allow_hyphen_values = true)]
    pub tau_max: f64,
    /// Ask for an accuracy instead of a method and tolerance: run the cheapest of dp54 and
    /// dop853 (tol 1e-3 … 1e-13) whose stated error of the end's time and place is at most
    /// this, and say which it chose and what it cost.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["method", "tol", "dt", "no_check"])]
    pub error: Option<f64>,
    /// Keep integrating after escape is certified, up to tau-max.
    #[arg(long)]
    pub follow: bool,
    /// Skip the second opinion (dop853, tighter, in the other frame: about as dear as this
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
    pub numerics: NumericsArgs,
    #[command(flatten)]
    pub units: UnitsArgs,
    #[command(flatten)]
    pub body: BodyArgs,
}

#[derive(Args, Debug)]
pub struct EscapeArgs {
    /// Release radius xi0 (units of R_max = mu g / Omega^2).
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub xi0: f64,
    /// Direction of the initial velocity in the table frame, from radially outward, ccw (rad).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub phi: f64,
    /// Width of the final bracket on v0.
    #[arg(long = "vtol", default_value = "1e-8", allow_hyphen_values = true)]
    pub vtol: f64,
    /// Skip running the bracket's two ends in full against their second opinions: the
    /// bracket is then not certified.
    #[arg(long)]
    pub no_check: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub numerics: NumericsArgs,
}

#[derive(Args, Debug)]
pub struct CriticalArgs {
    /// Width of the final bracket on xi0.
    #[arg(long = "xtol", default_value = "1e-8", allow_hyphen_values = true)]
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
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub numerics: NumericsArgs,
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
                return Err(Error::invalid(format!(
                    "--dt applies to the fixed-step methods (rk4, rk2, rk2-raw); {} takes --tol",
                    self.method
                )));
            }
            (false, Some(_), _) => {
                return Err(Error::invalid(format!(
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

/// `--speed`: a power of two in the explorer's speed range.
fn parse_speed(s: &str) -> Result<f64, String> {
    s.parse::<f64>()
        .ok()
        .filter(|&x| crate::app::speed_power(x).is_some())
        .ok_or_else(|| format!("'{s}' is not a power of two from 1/64 to 256 (e.g. 0.25, 1, 4)"))
}
