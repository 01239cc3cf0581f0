//! The explorer's configuration file, `$XDG_CONFIG_HOME/turntable/config.toml`: defaults for
//! the explorer's flags (theme, fps, mouse, marker, units). Flags win over it; `replay` and the
//! numerical commands never read it.

use super::MarkerArg;
use crate::engine::units::Units;
use crate::error::Error;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// The keys a configuration file may hold, as its error messages list them.
const KEYS: &str = "theme, fps, mouse, marker, speed, paused, units";

/// What a configuration file sets; `None` where it says nothing.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Config {
    /// The file read, for messages (None: there was none).
    pub path: Option<PathBuf>,
    /// A theme's name, or a path (a relative one is taken from the configuration's folder).
    pub theme: Option<String>,
    pub fps: Option<u32>,
    pub mouse: Option<bool>,
    pub marker: Option<MarkerArg>,
    /// How fast time plays at the start (a power of two), and whether it starts paused.
    pub speed: Option<f64>,
    pub paused: Option<bool>,
    pub units: Option<Units>,
}

/// turntable's configuration folder as the XDG Base Directory spec places it:
/// `$XDG_CONFIG_HOME/turntable`, or `$HOME/.config/turntable` where XDG_CONFIG_HOME is unset,
/// empty or relative (the spec says to ignore a relative one). None without either.
pub fn dir(var: impl Fn(&str) -> Option<OsString>) -> Option<PathBuf> {
    let absolute = |v: Option<OsString>| v.map(PathBuf::from).filter(|p| p.is_absolute());
    absolute(var("XDG_CONFIG_HOME"))
        .or_else(|| absolute(var("HOME")).map(|h| h.join(".config")))
        .map(|d| d.join("turntable"))
}

/// What `turntable config` prints after the path: every key, commented out, with what it
/// does. Uncommented, it is a valid configuration (a test reads it so).
pub const TEMPLATE: &str = r#"# turntable's configuration: defaults for the explorer's flags (flags win).
# Remove a leading '# ' to set a key.
# theme = "light"     # dark, light, high-contrast, mono, one of yours (themes/NAME.toml
#                     # beside this file), or a .toml path (relative: to this folder)
# fps = 60            # frame-rate cap while playing, 1 to 240
# speed = 0.25        # how fast time plays at the start: a power of two (0.25: slow
#                     # motion); a saved scene's own speed wins
# paused = true       # start paused (Space plays)
# mouse = false       # do not capture the mouse (M toggles it)
# marker = "block"    # braille, block or ascii
# [units]             # a real table, as --mu, --rpm, --g (a scene's own [units] wins)
# mu = 0.15
# rpm = 33.3
# g = 9.81
"#;

impl Config {
    /// Reads `DIR/config.toml`; a file that is not there is an empty configuration, one that
    /// cannot be read or says something wrong is refused (exit 2) with the file and the key.
    pub fn load(dir: &Path) -> Result<Config, Error> {
        let path = dir.join("config.toml");
        match path.symlink_metadata() {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Config::default()),
            _ => {}
        }
        Config::read(&path)
    }

    /// Reads the configuration file `path` (`--config`): it must be there.
    pub fn read(path: &Path) -> Result<Config, Error> {
        let text = crate::files::read_bounded(path, crate::files::READ_CAP)
            .map_err(|e| Error::invalid(format!("config file {e}")))?;
        Config::parse(&text, path)
    }

    /// A configuration file's text; `path` names it in errors (and anchors relative theme
    /// paths).
    pub fn parse(text: &str, path: &Path) -> Result<Config, Error> {
        let shown = crate::files::escape_controls(&path.display().to_string());
        let refuse = |m: String| Error::invalid(format!("config file {shown}: {m}"));
        let table: toml::Table =
            toml::from_str(text).map_err(|e| refuse(crate::files::toml_error(text, &e)))?;
        let mut c = Config {
            path: Some(path.to_path_buf()),
            ..Config::default()
        };
        for (key, value) in &table {
            let bad = |want: &str| {
                refuse(format!(
                    "key `{key}`: {want}, got {}",
                    crate::files::escape_controls(&value.to_string())
                ))
            };
            match key.as_str() {
                "theme" => {
                    let name = value.as_str().ok_or_else(|| bad("expected a string"))?;
                    let is_path = name.contains('/') || name.ends_with(".toml");
                    c.theme = Some(match (is_path, path.parent()) {
                        (true, Some(d)) => d.join(name).display().to_string(),
                        _ => name.to_string(),
                    });
                }
                "fps" => {
                    let n = value
                        .as_integer()
                        .ok_or_else(|| bad("expected an integer"))?;
                    c.fps = Some(
                        u32::try_from(n)
                            .ok()
                            .filter(|n| (1..=240).contains(n))
                            .ok_or_else(|| bad("must lie in 1..=240"))?,
                    );
                }
                "speed" => {
                    let x = value
                        .as_float()
                        .or_else(|| value.as_integer().map(|n| n as f64))
                        .ok_or_else(|| bad("expected a number"))?;
                    crate::app::speed_power(x)
                        .ok_or_else(|| bad("must be a power of two from 1/64 to 256"))?;
                    c.speed = Some(x);
                }
                "paused" => {
                    c.paused = Some(
                        value
                            .as_bool()
                            .ok_or_else(|| bad("expected true or false"))?,
                    )
                }
                "mouse" => {
                    c.mouse = Some(
                        value
                            .as_bool()
                            .ok_or_else(|| bad("expected true or false"))?,
                    )
                }
                "marker" => {
                    use clap::ValueEnum;
                    let s = value.as_str().ok_or_else(|| bad("expected a string"))?;
                    c.marker = Some(
                        MarkerArg::from_str(s, false)
                            .map_err(|_| bad("expected braille, block or ascii"))?,
                    );
                }
                "units" => {
                    let u: Units = value.clone().try_into().map_err(|e: toml::de::Error| {
                        refuse(format!(
                            "key `units`: {} (a table: mu = 0.15, rpm = 33.3, g = 9.81)",
                            e.message().trim().replace('\n', " ")
                        ))
                    })?;
                    c.units = Some(
                        crate::check::units(&u, crate::check::Via::Config)
                            .map_err(|e| refuse(e.to_string()))?,
                    );
                }
                _ => {
                    return Err(refuse(format!(
                        "unknown key `{}` (known: {KEYS})",
                        crate::files::escape_controls(key)
                    )));
                }
            }
        }
        Ok(c)
    }

    /// An error about the key `key` of this file (a theme it names that cannot be loaded).
    pub fn blame(&self, key: &str, e: Error) -> Error {
        match &self.path {
            Some(p) => e.context(&format!(
                "config file {}: key `{key}`",
                crate::files::escape_controls(&p.display().to_string())
            )),
            None => e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Config, String> {
        Config::parse(text, Path::new("/c/turntable/config.toml")).map_err(|e| {
            assert_eq!(e.exit_code(), 2);
            e.to_string()
        })
    }

    #[test]
    fn the_template_uncommented_sets_every_key() {
        let text: String = TEMPLATE
            .lines()
            .filter_map(|l| l.strip_prefix("# "))
            .filter(|l| !l.starts_with(' ') && l.contains('='))
            .map(|l| format!("{}\n", l.split("  #").next().unwrap_or(l)))
            .collect();
        // `[units]` has no `=`: put it before its keys.
        let text = text.replacen("mu =", "[units]\nmu =", 1);
        let c = parse(&text).unwrap();
        assert_eq!(c.theme.as_deref(), Some("light"));
        assert_eq!(
            (c.fps, c.speed, c.paused, c.mouse),
            (Some(60), Some(0.25), Some(true), Some(false))
        );
        assert_eq!(c.marker, Some(MarkerArg::Block));
        assert_eq!(
            c.units.map(|u| (u.mu, u.rpm, u.g)),
            Some((0.15, 33.3, 9.81))
        );
        for key in KEYS.split(", ") {
            assert!(
                TEMPLATE.contains(&format!("# {key} ")) || TEMPLATE.contains(&format!("[{key}]")),
                "{key}"
            );
        }
    }

    #[test]
    fn every_key() {
        let c = parse(
            "theme = \"light\"\nfps = 60\nmouse = false\nmarker = \"block\"\n\
             [units]\nmu = 0.2\nrpm = 45\n",
        )
        .unwrap();
        assert_eq!(c.theme.as_deref(), Some("light"));
        assert_eq!(
            (c.fps, c.mouse, c.marker),
            (Some(60), Some(false), Some(MarkerArg::Block))
        );
        assert_eq!(c.units, Some(Units::new(0.2, 45.0, 9.81).unwrap()));
        assert_eq!(parse("").unwrap().theme, None);
        // A theme file named relative to the configuration is found beside it.
        assert_eq!(
            parse("theme = \"mine.toml\"").unwrap().theme.as_deref(),
            Some("/c/turntable/mine.toml")
        );
        assert_eq!(
            parse("theme = \"/t/x.toml\"").unwrap().theme.as_deref(),
            Some("/t/x.toml")
        );
    }

    #[test]
    fn errors_name_the_file_and_the_key() {
        let f = "config file /c/turntable/config.toml: ";
        for (text, want) in [
            (
                "colour = 1",
                "unknown key `colour` (known: theme, fps, mouse, marker, speed, paused, units)",
            ),
            (
                "fps = \"fast\"",
                "key `fps`: expected an integer, got \"fast\"",
            ),
            ("fps = 0", "key `fps`: must lie in 1..=240, got 0"),
            (
                "fps = 1e9",
                "key `fps`: expected an integer, got 1000000000.0",
            ),
            (
                "fps = 99999999999",
                "key `fps`: must lie in 1..=240, got 99999999999",
            ),
            ("mouse = 1", "key `mouse`: expected true or false, got 1"),
            (
                "marker = \"dots\"",
                "key `marker`: expected braille, block or ascii, got \"dots\"",
            ),
            ("theme = 3", "key `theme`: expected a string, got 3"),
            (
                "[units]\nmu = -1\nrpm = 3",
                "[units] mu must lie in [1e-6, 10], got -1",
            ),
        ] {
            assert_eq!(parse(text).unwrap_err(), format!("{f}{want}"), "{text}");
        }
        let e = parse("[units]\nmu = 0.1\nrpms = 3").unwrap_err();
        assert!(
            e.starts_with(&format!("{f}key `units`: unknown field `rpms`")),
            "{e}"
        );
        let e = parse("fps = 30\nfps = 31").unwrap_err();
        assert!(e.starts_with(&format!("{f}line 2: ")), "{e}");
        let e = parse("units = 3").unwrap_err();
        assert!(e.starts_with(&format!("{f}key `units`: ")), "{e}");
    }

    #[test]
    fn the_folder_follows_the_xdg_spec() {
        let env = |xdg: Option<&str>, home: Option<&str>| {
            dir(move |v| match v {
                "XDG_CONFIG_HOME" => xdg.map(OsString::from),
                "HOME" => home.map(OsString::from),
                _ => None,
            })
        };
        let p = |s: &str| Some(PathBuf::from(s));
        assert_eq!(env(Some("/x"), Some("/h")), p("/x/turntable"));
        assert_eq!(env(None, Some("/h")), p("/h/.config/turntable"));
        assert_eq!(env(Some(""), Some("/h")), p("/h/.config/turntable"));
        assert_eq!(env(Some("rel"), Some("/h")), p("/h/.config/turntable"));
        assert_eq!(env(None, None), None);
    }
}
