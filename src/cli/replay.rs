//! `turntable replay SCRIPT`: a key script run headlessly, its snapshots on stdout.

use super::{CmdResult, Error};
use crate::replay::{Options, replay_cast, replay_to};
use crate::script::{parse_size, script_options};
use clap::Args;

#[derive(Args, Debug, Default)]
#[command(group(clap::ArgGroup::new("recording").args(["asciicast", "svg"]).multiple(true)))]
pub struct ReplayArgs {
    /// The key script (`-` reads stdin).
    #[arg(value_name = "SCRIPT")]
    pub script: String,
    /// Initial size of the off-screen terminal, WxH (a `resize` step changes it); default the
    /// script's `# replay: --size` line, else 80x24.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u16, u16)>,
    /// Style the snapshots with ANSI colour escape sequences.
    #[arg(long)]
    pub ansi: bool,
    /// Print what plain mode (`turntable --plain`) says, line by line, instead of screens; a
    /// snapshot prints the readouts.
    #[arg(long, conflicts_with_all = ["ansi", "asciicast", "svg"])]
    pub plain: bool,
    /// Also record the replay as an asciicast v2 file (asciinema's player plays it at the
    /// pace of the ticks, 30 a second), written atomically; an existing file is kept unless
    /// --force, and the script, scene and theme never.
    #[arg(long, value_name = "OUT.cast")]
    pub asciicast: Option<std::path::PathBuf>,
    /// Also record the replay as an animated SVG, which a browser (or a project's page on a
    /// forge) plays with nothing installed: the same screens, at most ten a second, written
    /// atomically as --asciicast is.
    #[arg(long, value_name = "OUT.svg")]
    pub svg: Option<std::path::PathBuf>,
    /// Replace the --asciicast or --svg file if it exists.
    #[arg(long, requires = "recording")]
    pub force: bool,
    #[command(flatten)]
    pub look: super::Look,
}

pub fn run(a: ReplayArgs) -> CmdResult {
    let text = if a.script == "-" {
        crate::files::read_stdin(crate::files::READ_CAP).map_err(|e| e.context("-"))?
    } else {
        crate::files::read_bounded(std::path::Path::new(&a.script), crate::files::READ_CAP)?
    };
    // The script, scene and theme are read first: the output may be none of them.
    let (app, opts, steps) = prepare(&text, &a)?;
    // Opened before the work, so a bad path fails at once.
    let cast = match &a.asciicast {
        Some(path) => Some(crate::files::open_output("--asciicast", path, a.force)?),
        None => None,
    };
    let svg = match &a.svg {
        Some(path) => Some(crate::files::open_output("--svg", path, a.force)?),
        None => None,
    };
    let mut film = svg
        .as_ref()
        .map(|_| crate::film::Film::new(opts.size.0, opts.size.1, opts.theme.background));
    let title = crate::text::clean(&format!("turntable replay {}", a.script));
    let so = std::io::BufWriter::new(std::io::stdout().lock());
    let mut so = crate::files::Capped::new(
        so,
        crate::replay::OUTPUT_MAX,
        "the replay's output on stdout",
    );
    let bounded = |e: std::io::Error| match crate::files::bound_reached(&e) {
        Some(m) => Error::invalid(format!(
            "{m}; stopped there (shorten the script: fewer snapshots, ticks or a smaller resize)"
        )),
        None => Error::from(e),
    };
    // Nothing is written should a bound stop the recording: each file says so.
    let nothing = |e: std::io::Error, dests: &[String]| match crate::files::bound_reached(&e) {
        Some(m) => Error::invalid(format!(
            "{m}; nothing was written to {} (shorten the script: fewer ticks or a smaller resize)",
            crate::files::escape_controls(&dests.join(" or "))
        )),
        None => Error::from(e),
    };
    let svg_dest = svg.as_ref().map(|f| f.dest().display().to_string());
    match cast {
        Some(out) => {
            let mut file = crate::files::Capped::new(
                std::io::BufWriter::new(out),
                crate::replay::CAST_BYTES_MAX,
                "--asciicast",
            );
            let dest = file.get_ref().get_ref().dest().display().to_string();
            let dests: Vec<String> = std::iter::once(dest).chain(svg_dest.clone()).collect();
            replay_cast(
                app,
                &steps,
                &opts,
                &mut so,
                &mut file,
                &title,
                film.as_mut(),
            )
            .map_err(|e| nothing(e, &dests))?;
            file.into_inner()
                .into_inner()
                .map_err(|e| e.into_error())?
                .finish()?;
        }
        None if film.is_some() => {
            let dests: Vec<String> = svg_dest.clone().into_iter().collect();
            let sink = &mut std::io::sink();
            replay_cast(app, &steps, &opts, &mut so, sink, &title, film.as_mut())
                .map_err(|e| nothing(e, &dests))?;
        }
        None => replay_to(app, &steps, &opts, &mut so).map_err(bounded)?,
    }
    if let (Some(film), Some(out)) = (film, svg) {
        let mut file = crate::files::Capped::new(
            std::io::BufWriter::new(out),
            crate::replay::CAST_BYTES_MAX,
            "--svg",
        );
        film.write(&title, &mut file)?;
        file.into_inner()
            .into_inner()
            .map_err(|e| e.into_error())?
            .finish()?;
    }
    Ok(())
}

/// A script's app, options and steps as `turntable replay` runs it: the flags in `a` first,
/// then the script's own `# replay:` lines. Writes no files (`s` only says what it would).
pub fn prepare(
    text: &str,
    a: &ReplayArgs,
) -> Result<(crate::app::App, Options, Vec<crate::script::Step>), Error> {
    let steps =
        crate::script::parse(text).map_err(|e| Error::invalid(format!("{}: {e}", a.script)))?;
    let own = script_options(text).map_err(|e| e.context(&a.script))?;
    let scene = match a.look.scene.as_ref().or(own.scene.as_ref()) {
        Some(s) => crate::scene::Scene::load(s)?,
        None => crate::scene::Scene::default_scene(),
    };
    let theme = a.look.theme.as_ref().or(own.theme.as_ref());
    // No user themes by name: a replay reads no configuration.
    let theme =
        crate::theme::Theme::resolve(theme.map(String::as_str), false).map_err(|e| match e {
            Error::Invalid {
                why: m,
                value: None,
            } if !m.starts_with("theme file") => Error::invalid(format!(
                "{m}; replay reads no configuration: name a theme of yours by its path"
            )),
            e => e,
        })?;
    let app = crate::app::App::new(scene);
    let opts = Options {
        size: a.size.or(own.size).unwrap_or(crate::replay::DEFAULT_SIZE),
        ansi: (a.ansi || own.ansi) && !a.plain,
        plain: a.plain,
        theme,
    };
    Ok((app, opts, steps))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::replay::DEFAULT_SIZE;

    #[test]
    fn sizes() {
        assert_eq!(parse_size("80x24"), Ok(DEFAULT_SIZE));
        assert_eq!(parse_size("0X0"), Ok((0, 0)));
        assert!(parse_size("80").is_err());
        assert!(parse_size("80x").is_err());
        assert!(parse_size("-1x5").is_err());
        assert!(parse_size("1001x5").is_err());
    }

    #[test]
    fn a_script_names_its_own_options() {
        let o = script_options(
            "# turntable key script\n# replay: --scene B --size 60x16\n# replay: --ansi\nx\n",
        )
        .unwrap();
        assert_eq!(
            (o.scene.as_deref(), o.size, o.ansi, o.theme),
            (Some("B"), Some((60, 16)), true, None)
        );
        assert_eq!(
            script_options("# replay: --size").unwrap_err(),
            Error::invalid("line 1: --size needs a value")
        );
        assert!(
            script_options("\n# replay: --fast")
                .unwrap_err()
                .to_string()
                .starts_with("line 2: unknown")
        );
    }
}
