//! Command-line interface: the headless commands (clap definitions in `args`). With no command the
//! interactive explorer opens.

mod about;
mod args;
mod bench;
pub(crate) mod config;
pub mod lesson;
mod numerics;
mod plot;
mod progress;
pub mod replay;
mod report;
#[cfg(feature = "serve")]
mod serve;
mod spinup;
mod sweep;

use crate::engine::Initial;
use crate::error::Error;
use clap::Parser;
use std::io::Write;
use std::process::ExitCode;

pub use args::*;

pub type CmdResult = Result<(), Error>;

/// A release typed as flags, checked as every release is (`crate::check`).
pub fn check_initial(i: &Initial) -> Result<(), Error> {
    crate::check::initial(i, crate::check::Via::Flags)
}

/// A number as the CSV outputs write it: [`digits`](crate::engine::model::digits), plain
/// from 1e-5 to 1e16, and −0 as 0 (−0 + 0 is +0).
pub(crate) fn num(x: f64) -> String {
    crate::engine::model::digits(x + 0.0, 1e-5..1e16)
}

pub use crate::check::PHI_MAX;

/// The narrowest bracket `--vtol`/`--xtol` may ask for: a threshold of order 1 resolved to a few
/// thousand ulps, which the runs' own accuracy (dp54 at tol 1e-14) can still certify.
pub const BRACKET_MIN: f64 = 1e-12;

/// A bracket width: in [[`BRACKET_MIN`], 1].
pub(crate) fn bracket_width(name: &str, x: f64) -> Result<(), Error> {
    if (BRACKET_MIN..=1.0).contains(&x) {
        Ok(())
    } else {
        Err(Error::invalid(format!(
            "--{name} must lie in [{BRACKET_MIN:e}, 1] (narrower than the runs can certify), got {}",
            Initial::show(x)
        )))
    }
}

/// A solver's error as its command's flags name it: a step budget exhausted inside it, with
/// advice that names the solver's own flags (not --tau-max, which the solvers do not take),
/// and its bracket width as `tol_flag`.
pub(crate) fn solver_budget<E: Into<Error>>(tol_flag: &'static str) -> impl Fn(E) -> Error {
    move |e| match e.into() {
        Error::Run(crate::engine::RunError::Budget { steps, tau }) => Error::Failed(format!(
            "step budget of {steps} steps exhausted at tau = {tau:.6} (raise --max-steps, or loosen {tol_flag} or --tol)"
        )),
        e => crate::check::retyped(e, crate::engine::error::Field::Bracket, tol_flag),
    }
}

/// An error as the command line says it: a value the engine refused and nothing named is
/// named as its flag; a run that could not finish says which flags would let it.
fn as_typed(e: Error) -> String {
    use crate::engine::RunError;
    match crate::check::named(e, crate::check::Via::Flags) {
        e @ Error::Run(RunError::Budget { .. }) => {
            format!("{e} (raise --max-steps, lower --tau-max, or use a larger dt / looser tol)")
        }
        e @ Error::Run(RunError::Overflow { .. }) => format!("{e} (lower --tau-max)"),
        e => e.to_string(),
    }
}

/// Opens the explorer. Bad scenes, themes, configuration files and `--record` paths fail
/// before the terminal is touched. Returns the signal that ended it, if one did.
/// With `lesson`, the explorer runs it (`turntable lesson NAME`).
fn explore(
    cli: &Cli,
    look: &Look,
    lesson: Option<crate::lesson::Driver>,
    plain: bool,
) -> Result<Option<i32>, Error> {
    // `--config FILE` stands for the usual file; its themes are beside it.
    let config_dir = match &cli.config {
        Some(f) => Some(
            f.parent()
                .unwrap_or(std::path::Path::new("."))
                .to_path_buf(),
        ),
        None => config::dir(|v| std::env::var_os(v)),
    };
    let user_themes = config_dir.as_ref().map(|d| d.join("themes"));
    // `--theme` without a name lists them: asked for, not an error (whatever the
    // configuration says).
    if look.theme.as_deref() == Some("") {
        let list = crate::theme::available(user_themes.as_deref());
        crate::files::emit(None, &format!("themes: {list}\n"))?;
        return Ok(None);
    }
    let config = match (&cli.config, &config_dir) {
        (Some(f), _) => config::Config::read(f)?,
        (None, Some(d)) => config::Config::load(d)?,
        (None, None) => config::Config::default(),
    };
    let (scene, units) = scene_for(cli, look, &config)?;
    let theme = theme_for(cli, look, &config, user_themes.as_deref())?;
    let term = std::env::var("TERM").ok();
    let scene_ref = look.scene.as_deref().map(scene_reference);
    if term.as_deref() == Some("dumb") && !plain {
        return Err(Error::invalid(
            "TERM=dumb cannot show the explorer (it needs cursor movement); set TERM to your terminal's type (e.g. xterm), or use `turntable --plain` (the explorer in lines of text), `turntable replay SCRIPT` or a subcommand",
        ));
    }
    let recording = match &cli.record {
        Some(path) => Some(std::sync::Arc::new(Recording {
            out: std::sync::Mutex::new(Some(crate::files::open_output(
                "--record", path, cli.force,
            )?)),
            path: path.clone(),
            scene: scene_ref,
        })),
        None => None,
    };
    needs_terminal(plain)?;
    let mut app = crate::app::App::new(scene);
    // Units: the flags, else the scene's own, else the configuration's.
    if units.is_some() {
        app.tell_units(units);
    } else if app.units().is_none() {
        app.tell_units(config.units);
    }
    // Speed: the flag, else a saved scene's own, else the configuration's.
    if let Some(x) = cli
        .speed
        .or(config.speed.filter(|_| app.scene().view.is_none()))
    {
        app.tell_speed(x);
    }
    if cli.paused || config.paused == Some(true) {
        app.pause();
    }
    app.tell_mouse(match (cli.no_mouse, cli.mouse) {
        (true, _) => false,
        (_, true) => true,
        _ => config.mouse.unwrap_or(true),
    });
    // The terminal died under the explorer: the recording is kept all the same, and where
    // it went is said (the terminal is restored by then).
    let save = recording.clone().map(|r| {
        Box::new(move |script: String| match r.keep(script) {
            Ok(saved) => r.say_if_moved(&saved),
            Err(e) => {
                let m = crate::files::escape_controls(&e.to_string());
                let _ = writeln!(std::io::stderr(), "error: {m}");
            }
        }) as crate::terminal::SaveRecording
    });
    let fps = cli.fps.or(config.fps).unwrap_or(30);
    let (result, script) = if plain {
        crate::terminal::plain::run(app, theme, save, lesson)
    } else {
        crate::terminal::run(app, theme, fps, save, lesson)
    };
    keep_recording(recording, script, result)
}

/// The scene the explorer opens on: `--scene` or the default, with the coupling and the body
/// the flags give; and the units the flags give.
fn scene_for(
    cli: &Cli,
    look: &Look,
    config: &config::Config,
) -> Result<(crate::scene::Scene, Option<crate::engine::units::Units>), Error> {
    let mut scene = match &look.scene {
        Some(s) => crate::scene::Scene::load(s)?,
        None => crate::scene::Scene::default_scene(),
    };
    if let Some(c) = cli.coupling.coupling()? {
        if cli.record.is_some() {
            // A recording names its scene, not these flags: its replay would differ.
            return Err(Error::invalid(
                "--record keeps the scene, not --coupling/--mu-static-ratio/--gamma: put them in a scene file ([settings] coupling, mu_static_ratio, gamma) and pass --scene",
            ));
        }
        scene.settings.coupling = c;
        crate::check::release(&scene.initial, &scene.settings, crate::check::Via::Flags)?;
    }
    let units = cli.units.units()?;
    // The table a body's metres are measured on: the one the explorer opens on (the flags,
    // else the scene's, else the configuration's; see below).
    let table = units.or(scene.units).or(config.units);
    let where_units =
        "--mu and --rpm (and optionally --g), or a scene or configuration with [units]";
    if let Some(b) = cli.body.body(table.as_ref(), where_units)? {
        if cli.record.is_some() {
            return Err(Error::invalid(
                "--record keeps the scene, not --body-length/--body-height/--body-angle: put them in a scene file ([body] length, height, angle) and pass --scene",
            ));
        }
        scene.body = Some(b);
    }
    if let Some(r) = scene.spin {
        if scene.body.is_some() {
            return Err(Error::invalid(
                "--body-length/--body-height/--body-angle: a spin-up scene ([spin]) spins the table under a point coin, not a body",
            ));
        }
        crate::check::spin(
            &r,
            scene.initial.xi0,
            &scene.settings,
            crate::check::Via::Flags,
        )?;
    }
    Ok((scene, units))
}

/// The theme: `--theme`, else the configuration's (which, a user's choice, wins over NO_COLOR
/// too), at the terminal's colour depth, with the marker asked for or the locale's.
fn theme_for(
    cli: &Cli,
    look: &Look,
    config: &config::Config,
    user_themes: Option<&std::path::Path>,
) -> Result<crate::theme::Theme, Error> {
    let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
    let (term, colorterm) = (std::env::var("TERM").ok(), std::env::var("COLORTERM").ok());
    let marker = cli
        .marker
        .or(config.marker)
        .unwrap_or_else(|| MarkerArg::from_locale(|v| std::env::var(v).ok()));
    // The flag, else the configuration's (which, a user's choice, wins over NO_COLOR too).
    let theme_name = look.theme.clone().or(config.theme.clone());
    let theme = crate::theme::Theme::resolve_in(theme_name.as_deref(), no_color, user_themes)
        .map_err(|e| match look.theme {
            None if config.theme.is_some() => config.blame("theme", e),
            _ => e,
        })?
        .with_depth(crate::theme::Depth::detect(
            term.as_deref(),
            colorterm.as_deref(),
        ))
        .with_marker(marker.marker());
    Ok(theme)
}

/// The explorer needs a terminal: plain mode for its keys, the full screen for both.
fn needs_terminal(plain: bool) -> Result<(), Error> {
    use std::io::IsTerminal;
    if plain {
        // Plain mode writes lines: its output may go to a pipe or a file, its keys may not.
        if !std::io::stdin().is_terminal() {
            return Err(Error::invalid(
                "plain mode reads keys from a terminal (stdin must be a tty); headless, use `turntable replay --plain SCRIPT`",
            ));
        }
    } else if !(std::io::stdin().is_terminal() && std::io::stdout().is_terminal()) {
        return Err(Error::invalid(
            "the explorer needs a terminal (stdin and stdout must be a tty); headless, use `turntable replay SCRIPT` or a subcommand (see --help)",
        ));
    }
    Ok(())
}

/// The session's recording kept (where `--record` said, or beside it if that appeared in
/// the meantime, which is said), and the session's result.
fn keep_recording(
    recording: Option<std::sync::Arc<Recording>>,
    script: Option<String>,
    result: std::io::Result<Option<i32>>,
) -> Result<Option<i32>, Error> {
    if let (Some(r), Some(script)) = (recording, script) {
        let saved = match (r.keep(script), &result) {
            (Ok(saved), _) => saved,
            // Ended by a signal: that stays the exit status (128 + n); the message says
            // where the recording is.
            (Err(e), Ok(Some(_))) => {
                let m = crate::files::escape_controls(&e.to_string());
                let _ = writeln!(std::io::stderr(), "error: {m}");
                return result.map_err(|e| Error::io("terminal", e));
            }
            // The terminal failed too: both are said, the terminal's first.
            (Err(e), Err(t)) => {
                let t = crate::files::escape_controls(&format!("terminal: {t}"));
                let _ = writeln!(std::io::stderr(), "error: {t}");
                return Err(e);
            }
            (Err(e), Ok(None)) => return Err(e),
        };
        r.say_if_moved(&saved);
    }
    result.map_err(|e| Error::io("terminal", e))
}

/// How a recording names its scene: a preset by name, a file by its absolute path, so that
/// the recording replays from any folder.
fn scene_reference(scene: &str) -> String {
    if crate::scene::Scene::preset(scene).is_some() {
        return scene.to_string();
    }
    std::fs::canonicalize(scene).map_or_else(|_| scene.to_string(), |p| p.display().to_string())
}

/// A `--record` file, opened before the session (under the one output policy: never a file
/// the session reads, never an existing file without `--force`) and written once at its end
/// (or by the signal watcher if the terminal dies): a FIFO's reader stays connected
/// throughout.
struct Recording {
    out: std::sync::Mutex<Option<crate::files::Output>>,
    path: std::path::PathBuf,
    /// The scene the recording names, so that `replay FILE` alone opens the same one.
    scene: Option<String>,
}

/// Where a recording goes when its own file cannot be written at the end: a new file in the
/// temporary folder (`$TMPDIR`, else /tmp), `turntable-recording-PID.keys`.
pub fn record_fallback() -> std::path::PathBuf {
    std::env::temp_dir().join(format!("turntable-recording-{}.keys", std::process::id()))
}

impl Recording {
    /// Says on stderr where the recording went if that is not the file asked for (which
    /// appeared during the session); on either way out, the end or a terminal that died.
    fn say_if_moved(&self, saved: &std::path::Path) {
        if self.path != saved {
            let _ = writeln!(
                std::io::stderr(),
                "--record: {} appeared during the session (kept); the recording is in {}",
                crate::files::escape_controls(&self.path.display().to_string()),
                crate::files::escape_controls(&saved.display().to_string())
            );
        }
    }

    /// Writes the script atomically; returns where. A file that was not there before the
    /// session is never replaced (`s` may have saved a scene there meanwhile): the recording
    /// then goes to the first free `NAME-N`.
    fn save(&self, script: &str) -> std::io::Result<std::path::PathBuf> {
        let taken = self.out.lock().unwrap_or_else(|e| e.into_inner()).take();
        let mut out =
            taken.ok_or_else(|| std::io::Error::other("the recording was already saved"))?;
        out.write_all(script.as_bytes())?;
        out.finish_numbered(99)
    }

    /// Saves the script; if that fails, keeps it all the same: in [`record_fallback`], else
    /// (that failing too) on stderr. The error then says why and where the recording is.
    fn keep(&self, mut script: String) -> Result<std::path::PathBuf, Error> {
        if let Some(s) = &self.scene {
            let at = script.find('\n').map_or(0, |i| i + 1);
            script.insert_str(at, &crate::script::scene_line(s));
        }
        let why = match self.save(&script) {
            Ok(p) => return Ok(p),
            Err(e) => crate::files::escape_controls(&e.to_string()),
        };
        let path = crate::files::escape_controls(&self.path.display().to_string());
        match crate::files::write_new(&record_fallback(), script.as_bytes(), 99) {
            Ok(kept) => Err(Error::Failed(format!(
                "--record {path}: could not write it ({why}); the recording is kept in {}",
                crate::files::escape_controls(&kept.display().to_string())
            ))),
            Err(e2) => {
                let mut err = std::io::stderr().lock();
                let _ = writeln!(err, "--- the recording ({} bytes) ---", script.len());
                let _ = err.write_all(script.as_bytes());
                let _ = writeln!(err, "--- end of the recording ---");
                Err(Error::Failed(format!(
                    "--record {path}: could not write it ({why}), nor {} ({}); the recording is on stderr above",
                    crate::files::escape_controls(&record_fallback().display().to_string()),
                    crate::files::escape_controls(&e2.to_string())
                )))
            }
        }
    }
}

/// The explorer ended by signal `n`: as the shell reports a process a signal killed, 128 + n.
fn signalled(n: i32) -> ExitCode {
    let _ = writeln!(std::io::stderr(), "turntable: ended by signal {n}");
    ExitCode::from(128 + n as u8)
}

/// What clap's own exit does, but a `--help` or `--version` that cannot be written (stdout
/// on /dev/full, a closed descriptor) fails (exit 1) instead of exiting 0 with nothing said.
/// A reader that stopped reading (`| head`) took what it wanted.
fn clap_exit(e: &clap::Error) -> ExitCode {
    // An error echoes what was typed: its control characters are escaped, as in every other
    // message (clap's own colours go with them).
    let printed = if e.use_stderr() {
        let said = crate::files::escape_controls(&e.render().to_string());
        let mut err = std::io::stderr();
        err.write_all(said.as_bytes()).and_then(|()| err.flush())
    } else {
        e.print().and_then(|()| std::io::stdout().flush())
    };
    match printed {
        Ok(()) => ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2)),
        Err(err) if err.kind() == std::io::ErrorKind::BrokenPipe => {
            ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2))
        }
        Err(err) => {
            let what = if e.use_stderr() { "stderr" } else { "stdout" };
            let e = Error::Failed(format!("writing to {what}: {err}"));
            let _ = writeln!(std::io::stderr(), "error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

/// An error's lines cut at a screen's worth: a message may quote what it refuses (a key
/// script's line of a megabyte was echoed whole).
fn cut_long_lines(message: &str) -> String {
    const KEEP: usize = 300;
    let cut = |line: &str| {
        let n = line.chars().count();
        if n <= KEEP {
            return line.to_string();
        }
        let kept: String = line.chars().take(KEEP).collect();
        format!("{kept}… ({n} characters in all)")
    };
    message.split('\n').map(cut).collect::<Vec<_>>().join("\n")
}

/// Entry point of the binary.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return clap_exit(&e),
    };
    let result = match cli.command {
        None => match explore(&cli, &cli.look, None, cli.plain) {
            Ok(Some(n)) => return signalled(n),
            r => r.map(|_| ()),
        },
        Some(Command::Lesson(ref a)) => match lesson::run(a) {
            Ok(Some((look, driver))) => match explore(&cli, &look, Some(driver), a.plain) {
                Ok(Some(n)) => return signalled(n),
                r => r.map(|_| ()),
            },
            r => r.map(|_| ()),
        },
        Some(Command::Run(a)) => numerics::run(a),
        Some(Command::Escape(a)) => numerics::escape(a),
        Some(Command::Critical(a)) => numerics::critical(a),
        Some(Command::Sweep(a)) => sweep::sweep(a),
        Some(Command::Spinup(a)) => spinup::spinup(a),
        Some(Command::Plot(a)) => plot::plot(a),
        Some(Command::Bench(a)) => bench::bench(a),
        Some(Command::Replay(a)) => replay::run(a),
        #[cfg(feature = "serve")]
        Some(Command::Serve(ref a)) => serve::run(a),
        Some(Command::Completions(a)) => about::completions(a.shell),
        Some(Command::Man) => about::man(),
        Some(Command::Config(a)) => about::config(a.path, a.init),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let code = e.exit_code();
            let m = cut_long_lines(&crate::files::escape_controls(&as_typed(e)));
            let _ = writeln!(std::io::stderr(), "error: {m}");
            ExitCode::from(code)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::scene_reference;
    use std::path::Path;

    #[test]
    fn recordings_name_scene_files_absolutely() {
        assert_eq!(scene_reference("B"), "B");
        assert_eq!(
            scene_reference("Cargo.toml"),
            std::fs::canonicalize("Cargo.toml")
                .unwrap()
                .display()
                .to_string()
        );
        assert!(scene_reference("./src/../Cargo.toml").starts_with('/'));
    }

    #[test]
    fn record_paths() {
        let open = |p: &Path| crate::files::open_output("--record", p, false);
        let tmp = std::env::temp_dir();
        assert!(open(&tmp.join("x.keys")).is_ok());
        assert!(!tmp.join("x.keys").exists());
        assert!(open(&tmp).is_err());
        assert!(open(&tmp.join("no-such-dir-turntable/x.keys")).is_err());
        // Under a regular file: no directory to write in, even as root.
        let file = tmp.join(format!("turntable-record-{}", std::process::id()));
        std::fs::write(&file, "x").unwrap();
        assert!(open(&file.join("x.keys")).is_err());
        // Existing: only with --force; once read (a scene), never.
        assert!(open(&file).is_err());
        assert!(crate::files::open_output("--record", &file, true).is_ok());
        crate::files::read_bounded(&file, 10).unwrap();
        assert!(crate::files::open_output("--record", &file, true).is_err());
        assert!(open(Path::new("session.keys")).is_ok());
        std::fs::remove_file(&file).unwrap();
    }
}
