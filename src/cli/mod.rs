//! Command-line interface: the headless commands (clap definitions in `args`). With no command the
//! interactive explorer opens.

mod args;
mod bench;
mod numerics;
pub mod replay;
mod sweep;

use crate::engine::Initial;
use crate::error::Error;
use clap::Parser;
use std::io::Write;
use std::process::ExitCode;

pub use args::*;

pub type CmdResult = Result<(), Error>;

pub fn check_initial(i: &Initial) -> Result<(), Error> {
    i.validate()
}

/// Opens the explorer. Bad scenes, themes and `--record` paths fail before the terminal is
/// touched.
fn explore(cli: &Cli) -> CmdResult {
    let (scene, theme) = (&cli.look.scene, &cli.look.theme);
    let scene = match scene {
        Some(s) => crate::scene::Scene::load(s)?,
        None => crate::scene::Scene::default_scene(),
    };
    let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
    let (term, colorterm) = (std::env::var("TERM").ok(), std::env::var("COLORTERM").ok());
    let marker = cli
        .marker
        .unwrap_or_else(|| MarkerArg::from_locale(|v| std::env::var(v).ok()));
    let theme = crate::theme::Theme::resolve(theme.as_deref(), no_color)?
        .with_depth(crate::theme::Depth::detect(
            term.as_deref(),
            colorterm.as_deref(),
        ))
        .with_marker(marker.marker());
    let units = cli.units.units()?;
    let scene_ref = cli.look.scene.as_deref().map(scene_reference);
    if let Some(path) = &cli.record {
        check_record_path(path, [&cli.look.scene, &cli.look.theme])?;
    }
    if term.as_deref() == Some("dumb") {
        return Err(Error::Invalid(
            "TERM=dumb cannot show the explorer (it needs cursor movement); set TERM to your terminal's type (e.g. xterm), or use `turntable replay SCRIPT` or a subcommand".into(),
        ));
    }
    use std::io::IsTerminal;
    if !(std::io::stdin().is_terminal() && std::io::stdout().is_terminal()) {
        return Err(Error::Invalid(
            "the explorer needs a terminal (stdin and stdout must be a tty); headless, use `turntable replay SCRIPT` or a subcommand (see --help)".into(),
        ));
    }
    let mut app = crate::app::App::new(scene, theme);
    if units.is_some() {
        app.units = units;
    }
    if cli.no_mouse {
        app.mouse = false;
    }
    let save = cli.record.clone().map(|path| {
        let scene = scene_ref.clone();
        Box::new(move |script: String| {
            let _ = save_recording(&path, scene.as_deref(), script);
        }) as crate::terminal::SaveRecording
    });
    let (result, recording) = crate::terminal::run(app, cli.fps, save);
    if let (Some(path), Some(script)) = (&cli.record, recording) {
        save_recording(path, scene_ref.as_deref(), script)
            .map_err(|e| Error::Failed(format!("--record: {e}")))?;
    }
    match result {
        Ok(false) => Ok(()),
        Ok(true) => Err(Error::Failed("ended by a signal".into())),
        Err(e) => Err(Error::Failed(format!("terminal: {e}"))),
    }
}

/// How a recording names its scene: a preset by name, a file by its absolute path, so that
/// the recording replays from any folder.
fn scene_reference(scene: &str) -> String {
    if crate::scene::Scene::preset(scene).is_some() {
        return scene.to_string();
    }
    std::fs::canonicalize(scene).map_or_else(|_| scene.to_string(), |p| p.display().to_string())
}

/// Writes a recorded session atomically. It names its scene, so that `replay FILE` alone
/// opens the same one.
fn save_recording(
    path: &std::path::Path,
    scene: Option<&str>,
    mut script: String,
) -> std::io::Result<()> {
    if let Some(s) = scene {
        let at = script.find('\n').map_or(0, |i| i + 1);
        script.insert_str(at, &crate::script::scene_line(s));
    }
    crate::files::write_atomic(path, script.as_bytes())
}

/// A `--record` file must be writable where it is named, and must not be one of the files
/// the session reads: fail before the session, not after.
fn check_record_path(path: &std::path::Path, inputs: [&Option<String>; 2]) -> Result<(), Error> {
    let usage = |e: String| Error::Invalid(format!("--record {e}"));
    if let Ok(rec) = std::fs::canonicalize(path) {
        for input in inputs.into_iter().flatten() {
            if std::fs::canonicalize(input).is_ok_and(|i| i == rec) {
                return Err(usage(format!(
                    "{}: is the file the session reads (--scene/--theme); name another",
                    crate::files::escape_controls(&path.display().to_string())
                )));
            }
        }
    }
    // Opening it is the test: the temporary file is created and removed again.
    drop(crate::files::Output::create(path).map_err(|e| usage(e.to_string()))?);
    Ok(())
}

/// Entry point of the binary.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => explore(&cli),
        Some(Command::Run(a)) => numerics::run(a),
        Some(Command::Escape(a)) => numerics::escape(a),
        Some(Command::Critical(a)) => numerics::critical(a),
        Some(Command::Sweep(a)) => sweep::sweep(a),
        Some(Command::Bench(a)) => bench::bench(a),
        Some(Command::Replay(a)) => replay::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let m = crate::files::escape_controls(&e.to_string());
            let _ = writeln!(std::io::stderr(), "error: {m}");
            ExitCode::from(e.exit_code())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{check_record_path, scene_reference};
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
        let none = [&None, &None];
        let tmp = std::env::temp_dir();
        assert!(check_record_path(&tmp.join("x.keys"), none).is_ok());
        assert!(!tmp.join("x.keys").exists());
        assert!(check_record_path(&tmp, none).is_err());
        assert!(check_record_path(&tmp.join("no-such-dir-turntable/x.keys"), none).is_err());
        // Under a regular file: no directory to write in, even as root.
        let file = tmp.join(format!("turntable-record-{}", std::process::id()));
        std::fs::write(&file, "x").unwrap();
        assert!(check_record_path(&file.join("x.keys"), none).is_err());
        let scene = Some(file.display().to_string());
        assert!(check_record_path(&file, [&scene, &None]).is_err());
        assert!(check_record_path(Path::new("session.keys"), [&scene, &None]).is_ok());
        std::fs::remove_file(&file).unwrap();
    }
}
