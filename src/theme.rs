//! Colour themes: TOML files giving a colour to each role in the UI, so the
//! display can suit a dark terminal, a light one, a projector, or no colour
//! at all. Colours are `"#rrggbb"` or ratatui colour names (`"lightblue"`,
//! `"reset"`, ...).

use crate::error::Error;
use std::path::Path;
use std::str::FromStr;

use ratatui::style::Color;
use ratatui::symbols::Marker;

pub mod ansi16;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer};

/// Names of the themes compiled into the binary.
pub const BUILTIN: [&str; 4] = ["dark", "light", "high-contrast", "mono"];

/// Every field is required and unknown fields are rejected, so a typo in a
/// theme file is reported instead of silently falling back to a default.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Theme {
    /// Cleaned as read (`crate::text`).
    pub name: crate::text::Clean,
    /// How plots and the canvas draw points: braille unless the locale or `--marker` says
    /// otherwise (not a theme file's choice).
    #[serde(skip, default = "braille")]
    pub marker: Marker,
    #[serde(deserialize_with = "colour")]
    pub background: Color,
    #[serde(deserialize_with = "colour")]
    pub foreground: Color,
    /// Secondary text: labels, hints, units.
    #[serde(deserialize_with = "colour")]
    pub muted: Color,
    /// Headings, selection and focus.
    #[serde(deserialize_with = "colour")]
    pub accent: Color,
    #[serde(deserialize_with = "colour")]
    pub table_edge: Color,
    #[serde(deserialize_with = "colour")]
    pub spokes: Color,
    /// The circle xi = 1.
    #[serde(deserialize_with = "colour")]
    pub limit_circle: Color,
    #[serde(deserialize_with = "colour")]
    pub particle: Color,
    #[serde(deserialize_with = "colour")]
    pub trail: Color,
    /// Velocity arrow.
    #[serde(deserialize_with = "colour")]
    pub arrow: Color,
    /// Force arrows, one colour per force.
    #[serde(deserialize_with = "colour")]
    pub friction: Color,
    #[serde(deserialize_with = "colour")]
    pub coriolis: Color,
    #[serde(deserialize_with = "colour")]
    pub centrifugal: Color,
    /// Particle states.
    #[serde(deserialize_with = "colour")]
    pub slipping: Color,
    #[serde(deserialize_with = "colour")]
    pub stuck: Color,
    #[serde(deserialize_with = "colour")]
    pub escaped: Color,
    /// Transient messages in the status line.
    #[serde(deserialize_with = "colour")]
    pub notice: Color,
}

fn colour<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Color, D::Error> {
    let text = String::deserialize(deserializer)?;
    Color::from_str(&text).map_err(|_| {
        D::Error::custom(format!(
            "invalid colour {text:?} (use \"#rrggbb\" or a name such as \"lightblue\")"
        ))
    })
}

/// How many colours the terminal shows, which decides how long each colour's escape
/// sequence is: 24-bit (`38;2;R;G;B`, up to 19 bytes) or the xterm 256-colour palette
/// (`38;5;N`, up to 11 bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Depth {
    TrueColor,
    Ansi256,
    /// The 8/16 colours of `TERM=xterm`, `screen`, `linux` (see [`ansi16`]).
    Ansi16,
}

impl Depth {
    /// From the COLORTERM convention: `truecolor` or `24bit` promise 24-bit colour; anything
    /// else gets the 256-colour palette every modern terminal has.
    pub fn from_colorterm(colorterm: Option<&str>) -> Depth {
        match colorterm {
            Some(c) if c.eq_ignore_ascii_case("truecolor") || c.eq_ignore_ascii_case("24bit") => {
                Depth::TrueColor
            }
            _ => Depth::Ansi256,
        }
    }

    /// From TERM and COLORTERM: 24-bit only where COLORTERM promises it; 16 colours for the
    /// terminal types that do not promise 256 (`xterm`, `screen`, `tmux`, `linux`, `vt100`…
    /// without `256color`); else the 256-colour palette every modern terminal has.
    pub fn detect(term: Option<&str>, colorterm: Option<&str>) -> Depth {
        const SIXTEEN: [&str; 10] = [
            "xterm", "screen", "tmux", "linux", "rxvt", "vt100", "vt102", "vt220", "ansi", "cygwin",
        ];
        match Depth::from_colorterm(colorterm) {
            Depth::TrueColor => Depth::TrueColor,
            _ => {
                let term = term.unwrap_or_default();
                let family = term.split(['-', '.']).next().unwrap_or_default();
                if !term.contains("256") && SIXTEEN.contains(&family) {
                    Depth::Ansi16
                } else {
                    Depth::Ansi256
                }
            }
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Depth::TrueColor => "24-bit",
            Depth::Ansi256 => "256",
            Depth::Ansi16 => "16",
        }
    }
}

/// The nearest colour of the xterm 256-colour palette (its 6×6×6 cube or its grey ramp).
pub fn nearest_256(r: u8, g: u8, b: u8) -> u8 {
    const LEVELS: [i32; 6] = [0, 95, 135, 175, 215, 255];
    let near = |v: u8| {
        (0..6)
            .min_by_key(|&i| (LEVELS[i] - i32::from(v)).abs())
            .unwrap_or(0)
    };
    let (ri, gi, bi) = (near(r), near(g), near(b));
    let dist = |c: (i32, i32, i32)| {
        (c.0 - i32::from(r)).pow(2) + (c.1 - i32::from(g)).pow(2) + (c.2 - i32::from(b)).pow(2)
    };
    let cube = (LEVELS[ri], LEVELS[gi], LEVELS[bi]);
    let mean = (i32::from(r) + i32::from(g) + i32::from(b)) / 3;
    let gi_ = ((mean - 8 + 5) / 10).clamp(0, 23);
    let grey = 8 + 10 * gi_;
    if dist((grey, grey, grey)) < dist(cube) {
        232 + gi_ as u8
    } else {
        16 + 36 * ri as u8 + 6 * gi as u8 + bi as u8
    }
}

fn braille() -> Marker {
    Marker::Braille
}

impl Theme {
    pub fn with_marker(mut self, marker: Marker) -> Theme {
        self.marker = marker;
        self
    }

    /// The theme with every colour as the terminal's depth shows it.
    pub fn with_depth(mut self, depth: Depth) -> Theme {
        if depth == Depth::Ansi16 {
            ansi16::map(&mut self);
        }
        if depth == Depth::Ansi256 {
            for c in [
                &mut self.background,
                &mut self.foreground,
                &mut self.muted,
                &mut self.accent,
                &mut self.table_edge,
                &mut self.spokes,
                &mut self.limit_circle,
                &mut self.particle,
                &mut self.trail,
                &mut self.arrow,
                &mut self.friction,
                &mut self.coriolis,
                &mut self.centrifugal,
                &mut self.slipping,
                &mut self.stuck,
                &mut self.escaped,
                &mut self.notice,
            ] {
                if let Color::Rgb(r, g, b) = *c {
                    *c = Color::Indexed(nearest_256(r, g, b));
                }
            }
        }
        self
    }

    /// A theme compiled into the binary, by name.
    pub fn builtin(name: &str) -> Option<Theme> {
        let source = match name {
            "dark" => include_str!("../themes/dark.toml"),
            "light" => include_str!("../themes/light.toml"),
            "high-contrast" => include_str!("../themes/high-contrast.toml"),
            "mono" => include_str!("../themes/mono.toml"),
            _ => return None,
        };
        Some(parse(source).expect("built-in themes are valid (checked by tests)"))
    }

    /// A built-in name, or a path to a TOML file (anything containing `/` or
    /// ending in `.toml`). Err is one human-readable line naming the file or
    /// name and the problem.
    pub fn load(name_or_path: &str) -> Result<Theme, Error> {
        Self::load_in(name_or_path, None)
    }

    /// As [`Theme::load`], with the user's themes in `user` (`NAME.toml`) found by name too.
    /// A user theme named as a built-in one replaces it, so a user can adjust `dark`.
    pub fn load_in(name_or_path: &str, user: Option<&Path>) -> Result<Theme, Error> {
        if name_or_path.contains('/') || name_or_path.ends_with(".toml") {
            return Self::read(Path::new(name_or_path));
        }
        if let Some(file) = user
            .filter(|_| !name_or_path.is_empty())
            .map(|d| d.join(format!("{name_or_path}.toml")))
            .filter(|f| f.symlink_metadata().is_ok())
        {
            return Self::read(&file);
        }
        Self::builtin(name_or_path).ok_or_else(|| {
            let what = match name_or_path {
                "" => "a theme name is needed".to_string(),
                n => format!("unknown theme '{n}'"),
            };
            Error::invalid(format!("{what} ({})", available(user)))
        })
    }

    fn read(path: &Path) -> Result<Theme, Error> {
        let text = crate::files::read_bounded(path, crate::files::READ_CAP)
            .map_err(|e| Error::invalid(format!("theme file {e}")))?;
        parse(&text).map_err(|p| {
            Error::invalid(format!(
                "theme file {}: {p}",
                crate::files::escape_controls(&path.display().to_string())
            ))
        })
    }

    /// The theme to use: an explicit request always wins; otherwise
    /// `no_color` (the NO_COLOR environment variable is set and non-empty,
    /// see no-color.org) selects mono, and the default is dark.
    pub fn resolve(requested: Option<&str>, no_color: bool) -> Result<Theme, Error> {
        Self::resolve_in(requested, no_color, None)
    }

    /// As [`Theme::resolve`], with the user's themes in `user`.
    pub fn resolve_in(
        requested: Option<&str>,
        no_color: bool,
        user: Option<&Path>,
    ) -> Result<Theme, Error> {
        let name = requested.unwrap_or(if no_color { "mono" } else { "dark" });
        Self::load_in(name, user)
    }
}

/// The user's themes: the names of the `NAME.toml` files in `dir`, sorted.
pub fn user_themes(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| {
            let p = e.path();
            let stem = p.file_stem()?.to_str()?;
            (p.extension()? == "toml" && !stem.is_empty() && !stem.starts_with('.'))
                .then(|| stem.to_string())
        })
        .collect();
    names.sort();
    names
}

/// What `--theme` takes, for messages: the built-in names, the user's (with `user`), a path.
pub fn available(user: Option<&Path>) -> String {
    let builtin = format!("built-in: {}", BUILTIN.join(", "));
    match user {
        None => format!("{builtin}; or a path to a .toml file"),
        Some(d) => {
            let mine = user_themes(d);
            let dir = crate::files::escape_controls(&d.display().to_string());
            match mine.is_empty() {
                true => format!("{builtin}; none of yours in {dir}; or a path to a .toml file"),
                false => format!(
                    "{builtin}; yours in {dir}: {}; or a path to a .toml file",
                    crate::files::escape_controls(&mine.join(", "))
                ),
            }
        }
    }
}

/// Parses theme TOML; errors read "line N: problem" when toml locates them,
/// except for problems with the whole document (a missing field), where a
/// line number would mislead.
fn parse(text: &str) -> Result<Theme, String> {
    toml::from_str(text).map_err(|e| crate::files::toml_error(text, &e))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// WCAG contrast of two colours (RGB, or one of the 16 as xterm shows it).
    fn contrast(a: Color, b: Color) -> f64 {
        let rgb = |c| ansi16::rgb(c).unwrap_or_else(|| panic!("no RGB for {c:?}"));
        ansi16::contrast(rgb(a), rgb(b))
    }

    /// Legible from the back of the room: WCAG contrast against the background, computed
    /// from the theme files. The data (trail, particle) and all text ≥ 4.5:1, the drawing
    /// (table edge, ξ = 1, arrows, forces) ≥ 3:1; in high-contrast everything ≥ 7:1. Spokes
    /// may stay faint. (mono uses the terminal's own colours.) The same in 16 colours.
    #[test]
    fn built_in_themes_are_legible() {
        for (name, depth) in ["dark", "light", "high-contrast"]
            .into_iter()
            .flat_map(|n| [(n, Depth::TrueColor), (n, Depth::Ansi16)])
        {
            let t = Theme::builtin(name).unwrap().with_depth(depth);
            let strict = name == "high-contrast";
            let text = [
                ("trail", t.trail),
                ("particle", t.particle),
                ("foreground", t.foreground),
                ("muted", t.muted),
                ("accent", t.accent),
                ("slipping", t.slipping),
                ("stuck", t.stuck),
                ("escaped", t.escaped),
                ("notice", t.notice),
            ];
            let drawing = [
                ("table_edge", t.table_edge),
                ("limit_circle", t.limit_circle),
                ("arrow", t.arrow),
                ("friction", t.friction),
                ("coriolis", t.coriolis),
                ("centrifugal", t.centrifugal),
            ];
            for (role, c, min) in text
                .iter()
                .map(|&(r, c)| (r, c, 4.5))
                .chain(drawing.iter().map(|&(r, c)| (r, c, 3.0)))
            {
                let min = if strict { 7.0 } else { min };
                let k = contrast(c, t.background);
                assert!(k >= min, "{name} {depth:?} {role}: {k:.2} < {min}");
            }
            // The data stands out from the furniture (in 16 colours, by its hue alone).
            if depth == Depth::TrueColor {
                assert!(contrast(t.trail, t.background) > contrast(t.table_edge, t.background));
            }
        }
        assert!((contrast(Color::Rgb(0, 0, 0), Color::Rgb(255, 255, 255)) - 21.0).abs() < 1e-9);
    }

    /// A body's bar and centre's path (drawn in the particle's colour) and the point's trail
    /// are told apart in 16 colours (`TERM=xterm`) as in 24-bit: dark's two yellows fell on one.
    #[test]
    fn the_particle_and_the_trail_differ_in_16_colours() {
        for name in ["dark", "light", "high-contrast"] {
            let t = Theme::builtin(name).unwrap().with_depth(Depth::Ansi16);
            assert_ne!(t.particle, t.trail, "{name}");
        }
        // Only where they fell together: the others keep their nearest colour.
        let light = Theme::builtin("light").unwrap();
        let mut mapped = light.clone();
        ansi16::map(&mut mapped);
        assert_eq!(
            mapped.particle,
            ansi16::nearest(light.particle, ansi16::rgb(mapped.background), 4.5)
        );
    }

    #[test]
    fn the_256_colour_palette() {
        assert_eq!(nearest_256(0, 0, 0), 16);
        assert_eq!(nearest_256(255, 255, 255), 231);
        assert_eq!(nearest_256(255, 0, 0), 196);
        assert_eq!(nearest_256(0, 95, 135), 24);
        // Greys go to the grey ramp: #808080 is 244 (8 + 10·12 = 128).
        assert_eq!(nearest_256(128, 128, 128), 244);
        assert_eq!(nearest_256(0x11, 0x15, 0x1c), 233);
        assert_eq!(Depth::from_colorterm(Some("truecolor")), Depth::TrueColor);
        assert_eq!(Depth::from_colorterm(Some("24bit")), Depth::TrueColor);
        assert_eq!(Depth::from_colorterm(None), Depth::Ansi256);
        let dark = Theme::builtin("dark").unwrap().with_depth(Depth::Ansi256);
        assert!(matches!(dark.trail, Color::Indexed(_)));
        assert!(matches!(dark.background, Color::Indexed(_)));
        let same = Theme::builtin("dark").unwrap();
        assert_eq!(same.clone().with_depth(Depth::TrueColor), same);
    }

    /// Writes `text` to a temp file unique to this process and test.
    fn temp_file(tag: &str, text: &str) -> String {
        let path = std::env::temp_dir().join(format!(
            "turntable-theme-test-{}-{tag}.toml",
            std::process::id()
        ));
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_owned()
    }

    fn dark_source() -> &'static str {
        include_str!("../themes/dark.toml")
    }

    /// Loads `text` from a temp file, returning the error and the path.
    fn load_err(tag: &str, text: &str) -> (String, String) {
        let path = temp_file(tag, text);
        let err = Theme::load(&path).expect_err(tag);
        std::fs::remove_file(&path).unwrap();
        assert_eq!(err.exit_code(), 2, "{err}");
        (err.to_string(), path)
    }

    #[test]
    fn every_builtin_parses_under_its_own_name() {
        for name in BUILTIN {
            let theme = Theme::builtin(name).unwrap();
            assert_eq!(theme.name, name);
            assert_eq!(Theme::load(name), Ok(theme));
        }
        assert_eq!(Theme::builtin("nope"), None);
    }

    #[test]
    fn builtins_look_as_intended() {
        let hc = Theme::builtin("high-contrast").unwrap();
        assert_eq!(hc.background, Color::Rgb(0, 0, 0));
        assert_eq!(hc.foreground, Color::Rgb(255, 255, 255));
        let mono = Theme::builtin("mono").unwrap();
        let colours = all_colours(&mono);
        assert!(colours.iter().all(|&c| c == Color::Reset), "{mono:?}");
    }

    fn all_colours(t: &Theme) -> [Color; 17] {
        [
            t.background,
            t.foreground,
            t.muted,
            t.accent,
            t.table_edge,
            t.spokes,
            t.limit_circle,
            t.particle,
            t.trail,
            t.arrow,
            t.friction,
            t.coriolis,
            t.centrifugal,
            t.slipping,
            t.stuck,
            t.escaped,
            t.notice,
        ]
    }

    #[test]
    fn terminals_that_promise_16_colours_get_16() {
        let d = |term, ct| Depth::detect(Some(term), ct);
        for term in [
            "xterm",
            "screen",
            "screen.xterm-new",
            "linux",
            "tmux",
            "vt100",
        ] {
            assert_eq!(d(term, None), Depth::Ansi16, "{term}");
        }
        for term in [
            "xterm-256color",
            "screen-256color",
            "tmux-256color",
            "alacritty",
        ] {
            assert_eq!(d(term, None), Depth::Ansi256, "{term}");
        }
        assert_eq!(d("xterm", Some("truecolor")), Depth::TrueColor);
        assert_eq!(d("xterm-256color", Some("yes")), Depth::Ansi256);
        assert_eq!(Depth::detect(None, None), Depth::Ansi256);
        for name in BUILTIN {
            let t = Theme::builtin(name).unwrap().with_depth(Depth::Ansi16);
            for c in all_colours(&t) {
                assert!(
                    !matches!(c, Color::Rgb(..) | Color::Indexed(_)),
                    "{name}: {c:?}"
                );
            }
        }
        let dark = Theme::builtin("dark").unwrap().with_depth(Depth::Ansi16);
        assert_eq!(
            (dark.background, dark.foreground),
            (Color::Black, Color::Gray)
        );
    }

    #[test]
    fn custom_file_with_names_and_hex() {
        let text = dark_source()
            .replace("\"#ffd166\"", "\"LightBlue\"")
            .replace("name = \"dark\"", "name = \"mine\"");
        let path = temp_file("custom", &text);
        let theme = Theme::load(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(theme.name, "mine");
        assert_eq!(theme.particle, Color::LightBlue);
        assert_eq!(theme.background, Color::Rgb(0x11, 0x15, 0x1c));
    }

    #[test]
    fn bad_colour_names_file_line_and_value() {
        let text = dark_source().replace("\"#d8dee9\"", "\"#12\"");
        let (err, path) = load_err("bad-colour", &text);
        assert!(
            err.starts_with(&format!(
                "theme file {path}: line 4: invalid colour \"#12\""
            )),
            "{err}"
        );
    }

    #[test]
    fn missing_field() {
        let text = dark_source().replace("accent = \"#88c0d0\"\n", "");
        let (err, path) = load_err("missing", &text);
        assert_eq!(err, format!("theme file {path}: missing field `accent`"));
    }

    #[test]
    fn unknown_field() {
        let text = format!("{}sparkle = \"red\"\n", dark_source());
        let (err, path) = load_err("unknown", &text);
        let line = text.lines().count();
        assert!(
            err.starts_with(&format!(
                "theme file {path}: line {line}: unknown field `sparkle`"
            )),
            "{err}"
        );
    }

    #[test]
    fn not_toml() {
        let (err, path) = load_err("not-toml", "name = \"x\"\nthis is not toml\n");
        assert!(
            err.starts_with(&format!("theme file {path}: line 2: ")),
            "{err}"
        );
        assert!(!err.contains('\n'), "{err}");
    }

    #[test]
    fn missing_file() {
        let path = temp_file("missing-file", "");
        std::fs::remove_file(&path).unwrap();
        let err = Theme::load(&path).unwrap_err().to_string();
        assert!(err.starts_with(&format!("theme file {path}: ")), "{err}");
    }

    #[test]
    fn unknown_name() {
        assert_eq!(
            Theme::load("foo").unwrap_err(),
            Error::invalid(
                "unknown theme 'foo' (built-in: dark, light, high-contrast, mono; \
                 or a path to a .toml file)"
            )
        );
        // Paths are recognised by shape, never mistaken for names.
        assert!(
            Theme::load("dark.toml")
                .unwrap_err()
                .to_string()
                .starts_with("theme file dark.toml: ")
        );
        assert!(
            Theme::load("./dark")
                .unwrap_err()
                .to_string()
                .starts_with("theme file ./dark: ")
        );
    }

    #[test]
    fn resolve_respects_no_color_only_without_a_request() {
        let named = |n| Theme::builtin(n).unwrap();
        assert_eq!(Theme::resolve(None, false), Ok(named("dark")));
        assert_eq!(Theme::resolve(None, true), Ok(named("mono")));
        assert_eq!(Theme::resolve(Some("light"), true), Ok(named("light")));
        assert_eq!(Theme::resolve(Some("light"), false), Ok(named("light")));
        assert!(Theme::resolve(Some("foo"), true).is_err());
    }
}
