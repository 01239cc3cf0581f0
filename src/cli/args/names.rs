//! A value that is a name from a list or a file's path (`--scene`, `--theme`): any text parses
//! (a path is read later, where the file is opened), and the names are its possible values, so
//! that the generated completion scripts offer the presets and the built-in themes.

use clap::builder::{PossibleValue, StringValueParser, TypedValueParser};
use std::ffi::OsStr;

/// The names a `NAME|PATH` value completes to; anything else is taken as a path.
#[derive(Clone, Debug)]
pub struct NameOrPath(Vec<&'static str>);

impl NameOrPath {
    pub fn new(names: impl IntoIterator<Item = &'static str>) -> Self {
        NameOrPath(names.into_iter().collect())
    }

    /// The scene presets (`scene::PRESETS`).
    pub fn scenes() -> Self {
        Self::new(crate::scene::PRESETS)
    }

    /// The presets a figure can play: all but the spun-up table (`plot` refuses `[spin]`).
    pub fn plot_scenes() -> Self {
        Self::new(crate::scene::PRESETS.into_iter().filter(|p| *p != "spin"))
    }

    /// The built-in themes (`theme::BUILTIN`).
    pub fn themes() -> Self {
        Self::new(crate::theme::BUILTIN)
    }
}

impl TypedValueParser for NameOrPath {
    type Value = String;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<String, clap::Error> {
        StringValueParser::new().parse_ref(cmd, arg, value)
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(self.0.iter().map(|n| PossibleValue::new(*n))))
    }
}

/// The completion script for `shell`, offering files too where a name or a path is taken:
/// clap's scripts offer only the possible values there. Bash's, zsh's and fish's gain the
/// files; the other shells' are as clap writes them (the names only).
pub fn with_files(shell: clap_complete::Shell, script: String) -> String {
    use clap_complete::Shell;
    let mut script = script;
    for NameOrPath(list) in [
        NameOrPath::scenes(),
        NameOrPath::plot_scenes(),
        NameOrPath::themes(),
    ] {
        let words = list.join(" ");
        let (only, both) = match shell {
            Shell::Bash => {
                let only = format!("$(compgen -W \"{words}\" -- \"${{cur}}\")");
                let both = format!("{only} $(compgen -f -- \"${{cur}}\")");
                (only, both)
            }
            Shell::Zsh => (
                format!(":NAME|PATH:({words})'"),
                format!(
                    ":NAME|PATH: _alternative \"names\\:name\\:({words})\" \"files\\:file\\:_files\"'"
                ),
            ),
            Shell::Fish => (
                format!("-r -f -a \"{}\\t''\n", list[0]),
                format!("-r -F -a \"{}\\t''\n", list[0]),
            ),
            _ => continue,
        };
        script = script.replace(&only, &both);
    }
    script
}
