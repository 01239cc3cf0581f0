//! What the binary says about itself: shell completions, the manual page and where its
//! configuration is kept.

use super::{Cli, CmdResult, config};
use crate::error::Error;

/// A completion script for `shell`, from the clap definitions.
pub fn completions(shell: clap_complete::Shell) -> CmdResult {
    use clap::CommandFactory;
    let mut out = Vec::new();
    clap_complete::generate(shell, &mut Cli::command(), "turntable", &mut out);
    let script = super::args::with_files(shell, String::from_utf8_lossy(&out).into_owned());
    crate::files::emit(None, &script)?;
    Ok(())
}

/// Where the explorer's configuration is kept and, unless `path_only`, a commented template.
pub fn config(path_only: bool, init: bool) -> CmdResult {
    let Some(dir) = config::dir(|v| std::env::var_os(v)) else {
        return Err(Error::Failed(
            "no configuration folder: neither XDG_CONFIG_HOME nor HOME is an absolute path (use --config FILE)".into(),
        ));
    };
    let path = dir.join("config.toml");
    let shown = crate::files::escape_controls(&path.display().to_string());
    if init {
        return write_template(&dir, &path, &shown);
    }
    let text = if path_only {
        format!("{shown}\n")
    } else {
        let there = if path.exists() {
            "there"
        } else {
            "not there yet"
        };
        format!(
            "# {shown} ({there}; themes of yours: {}/NAME.toml)\n{}",
            crate::files::escape_controls(&dir.join("themes").display().to_string()),
            config::TEMPLATE
        )
    };
    crate::files::emit(None, &text)?;
    Ok(())
}

/// `config --init`: the template written to `path`, its folder made; an existing file kept.
fn write_template(dir: &std::path::Path, path: &std::path::Path, shown: &str) -> CmdResult {
    use std::io::Write;
    let failed = |e: std::io::Error| Error::Failed(format!("{shown}: {e}"));
    if path.symlink_metadata().is_ok() {
        return Err(Error::invalid(format!(
            "{shown} is there already: kept as it is (`turntable config` prints the template)"
        )));
    }
    std::fs::create_dir_all(dir).map_err(failed)?;
    let mut out = crate::files::Output::create(path, false).map_err(failed)?;
    out.write_all(config::TEMPLATE.as_bytes()).map_err(failed)?;
    out.finish().map_err(failed)?;
    crate::files::emit(None, &format!("wrote {shown}\n"))?;
    Ok(())
}

/// The manual page, in roff, from the clap definitions and the key table: the command, its
/// options, the explorer's KEYS, then each subcommand (and theirs) with its options. Every
/// subcommand is in this one page: it names no other page.
pub fn man() -> CmdResult {
    use clap::CommandFactory;
    let cmd = Cli::command();
    let page = clap_mangen::Man::new(cmd.clone());
    let mut out = Vec::new();
    page.render_title(&mut out)?;
    page.render_name_section(&mut out)?;
    page.render_synopsis_section(&mut out)?;
    page.render_description_section(&mut out)?;
    page.render_options_section(&mut out)?;
    out.extend_from_slice(man_keys().as_bytes());
    man_subcommands(&cmd, "turntable", &mut out)?;
    page.render_extra_section(&mut out)?;
    page.render_version_section(&mut out)?;
    crate::files::emit(None, &String::from_utf8_lossy(&out))?;
    Ok(())
}

/// Text for roff: backslashes doubled, a leading dot or quote kept from being a request.
fn roff(text: &str) -> String {
    let t = text.replace('\\', "\\\\");
    match t.starts_with(['.', '\'']) {
        true => format!("\\&{t}"),
        false => t,
    }
}

/// The explorer's keys, from the table they dispatch on (as the `?` overlay shows them).
fn man_keys() -> String {
    let mut s = String::from(".SH KEYS\nIn the explorer (`?` shows them on screen):\n");
    for (group, rows) in crate::ui::help::rows() {
        s.push_str(&format!(".SS {}\n", roff(group)));
        for (keys, help) in rows {
            s.push_str(&format!(".TP\n\\fB{}\\fR\n{}\n", roff(&keys), roff(help)));
        }
    }
    s
}

/// Each subcommand of `cmd` (named `path` so far) with its about and options, depth first.
fn man_subcommands(cmd: &clap::Command, path: &str, out: &mut Vec<u8>) -> CmdResult {
    for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
        let name = format!("{path} {}", sub.get_name());
        let about = sub
            .get_long_about()
            .or(sub.get_about())
            .map(|a| a.to_string())
            .unwrap_or_default();
        let head = format!(".SH \"{}\"\n{}\n", name.to_uppercase(), roff(&about));
        out.extend_from_slice(head.as_bytes());
        if sub.get_arguments().any(|a| !a.is_hide_set()) {
            // Its headings (OPTIONS, Friction…) are subsections of this one.
            let mut options = Vec::new();
            clap_mangen::Man::new(sub.clone()).render_options_section(&mut options)?;
            let options = String::from_utf8_lossy(&options).replace("\n.SH ", "\n.SS ");
            let options = options
                .strip_prefix(".SH ")
                .map_or(options.clone(), |o| format!(".SS {o}"));
            out.extend_from_slice(options.as_bytes());
        }
        man_subcommands(sub, &name, out)?;
    }
    Ok(())
}
