//! `turntable replay SCRIPT`: a key script run headlessly, its snapshots on stdout.

use super::{CmdResult, Failure};
use crate::replay::{Options, replay};
use clap::Args;
use std::io::{Read, Write};

#[derive(Args, Debug)]
pub struct ReplayArgs {
    /// The key script (`-` reads stdin).
    #[arg(value_name = "SCRIPT")]
    pub script: String,
    /// Initial size of the off-screen terminal, WxH (a `resize` step changes it).
    #[arg(long, value_name = "WxH", default_value = "80x24", value_parser = parse_size)]
    pub size: (u16, u16),
    /// Style the snapshots with ANSI colour escape sequences.
    #[arg(long)]
    pub ansi: bool,
    /// Scene to open, a preset (A, B, C, D, fig1, fig2) or a .toml file.
    #[arg(long, value_name = "NAME|PATH")]
    pub scene: Option<String>,
    /// Colour theme (dark, light, high-contrast, mono) or a .toml file; only --ansi shows it.
    /// NO_COLOR is ignored so that the output depends on the arguments alone.
    #[arg(long, value_name = "NAME|PATH")]
    pub theme: Option<String>,
}

/// `WxH`, each at most the scripts' own limit.
pub fn parse_size(s: &str) -> Result<(u16, u16), String> {
    let bad = || format!("bad size '{s}': expected WxH, e.g. 80x24");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let n = |t: &str| -> Result<u16, String> {
        if t.is_empty() || !t.bytes().all(|b| b.is_ascii_digit()) {
            return Err(bad());
        }
        match t.parse::<u16>() {
            Ok(v) if v <= crate::script::MAX_SIZE => Ok(v),
            _ => Err(format!(
                "size {t} out of range 0..={}",
                crate::script::MAX_SIZE
            )),
        }
    };
    Ok((n(w)?, n(h)?))
}

pub fn run(a: ReplayArgs) -> CmdResult {
    let text = if a.script == "-" {
        let mut t = String::new();
        std::io::stdin()
            .read_to_string(&mut t)
            .map_err(|e| Failure::Usage(format!("-: {e}")))?;
        t
    } else {
        std::fs::read_to_string(&a.script)
            .map_err(|e| Failure::Usage(format!("{}: {e}", a.script)))?
    };
    let steps =
        crate::script::parse(&text).map_err(|e| Failure::Usage(format!("{}: {e}", a.script)))?;
    let scene = match &a.scene {
        Some(s) => crate::scene::Scene::load(s).map_err(Failure::Usage)?,
        None => crate::scene::Scene::default_scene(),
    };
    let theme = crate::theme::Theme::resolve(a.theme.as_deref(), false).map_err(Failure::Usage)?;
    let app = crate::app::App::new(scene, theme);
    let out = replay(
        app,
        &steps,
        &Options {
            size: a.size,
            ansi: a.ansi,
        },
    );
    let mut so = std::io::stdout().lock();
    so.write_all(out.as_bytes())?;
    so.flush()?;
    Ok(())
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
}
