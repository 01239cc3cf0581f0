//! Scenes: initial conditions plus integrator settings, as serde data. The paper's presets
//! (Figs. 1–4) are built in; others load from and save to TOML files.

use crate::engine::body::Body;
use crate::engine::units::{Length, SizeRefused, Units, show_metres, show_r_max_in_metres};
use crate::engine::{Initial, Release, Settings};
use crate::error::Error;
use crate::text::Clean;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::path::Path;

/// A scene as the explorer holds it: every length in units of R_max. Its file form is
/// `SceneFile`, where the body's sizes may be in metres (`length = "2 cm"`) when the scene
/// has `[units]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "SceneFile", into = "SceneFile")]
pub struct Scene {
    /// Cleaned as read (`crate::text`), as every text from a file is.
    pub name: Clean,
    /// What the scene shows, one line.
    #[serde(default)]
    pub about: Clean,
    pub initial: Initial,
    #[serde(default)]
    pub settings: Settings,
    /// A real table (μ, rpm, g): readouts in SI too.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub units: Option<crate::engine::units::Units>,
    /// A finite body (the paper's appendix) instead of a point: its size, and the appendix's
    /// conditions on the panel.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<crate::engine::body::Body>,
    /// The table spun up under a coin at rest (`engine::spinup`): the explorer shows it on
    /// the turntable page, `turntable spinup` reports it; the constant-Ω commands refuse it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin: Option<crate::engine::spinup::Ramp>,
    /// How the explorer showed it when saved.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub view: Option<View>,
    /// Runs pinned beside this one (`b`), oldest first: each as its release, recomputed
    /// when loaded.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pins: Vec<crate::pin::PinSpec>,
}

/// A scene as its TOML file holds it: [`Scene`]'s fields, the body's sizes as written.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    name: Clean,
    #[serde(default)]
    about: Clean,
    initial: Initial,
    #[serde(default)]
    settings: Settings,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    units: Option<Units>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    body: Option<BodyFile>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    spin: Option<crate::engine::spinup::Ramp>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    view: Option<View>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pins: Vec<crate::pin::PinSpec>,
}

/// `[body]` as written: `length` and `height` in units of R_max (numbers) or, on a scene with
/// `[units]`, in metres (`"2 cm"`, `"0.02 m"`, `"15 mm"`); `angle` in radians.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyFile {
    length: SizeField,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    height: Option<SizeField>,
    #[serde(default)]
    angle: f64,
}

/// A body size in a scene file: a number (R_max) or a string with a unit (metres).
#[derive(Clone, Copy)]
struct SizeField(Length);

impl Serialize for SizeField {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.0 {
            Length::RMax(x) => s.serialize_f64(x),
            Length::Metres(m) => s.serialize_str(&show_metres(m)),
        }
    }
}

impl<'de> Deserialize<'de> for SizeField {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = SizeField;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number in units of R_max (0.1) or a length with a unit m, cm or mm (\"2 cm\")")
            }
            fn visit_f64<E: serde::de::Error>(self, x: f64) -> Result<SizeField, E> {
                Ok(SizeField(Length::RMax(x)))
            }
            fn visit_i64<E: serde::de::Error>(self, x: i64) -> Result<SizeField, E> {
                Ok(SizeField(Length::RMax(x as f64)))
            }
            fn visit_u64<E: serde::de::Error>(self, x: u64) -> Result<SizeField, E> {
                Ok(SizeField(Length::RMax(x as f64)))
            }
            fn visit_str<E: serde::de::Error>(self, t: &str) -> Result<SizeField, E> {
                Length::parse(t).map(SizeField).map_err(E::custom)
            }
        }
        d.deserialize_any(V)
    }
}

impl TryFrom<SceneFile> for Scene {
    type Error = String;
    /// The body's metres become R_max on the scene's own table; without `[units]` they are
    /// refused.
    fn try_from(f: SceneFile) -> Result<Scene, String> {
        let units = f.units;
        let body = match f.body {
            None => None,
            Some(b) => {
                let size = |key: &str, l: Length, zero_ok: bool| -> Result<f64, String> {
                    l.size_in_r_max(units.as_ref(), zero_ok).map_err(|e| match e {
                        SizeRefused::Range(what) => {
                            format!("[body] {key} must be {what}, got {}", l.show())
                        }
                        SizeRefused::NoTable => format!(
                            "[body] {key} = \"{}\" is a length in metres, which needs the table's R_max: add a [units] table (mu, rpm, optionally g), or give {key} in units of R_max (a plain number)",
                            l.show()
                        ),
                    })
                };
                Some(Body {
                    length: size("length", b.length.0, false)?,
                    height: b.height.map(|h| size("height", h.0, true)).transpose()?,
                    angle: b.angle,
                })
            }
        };
        Ok(Scene {
            name: f.name,
            about: f.about,
            initial: f.initial,
            settings: f.settings,
            units,
            body,
            spin: f.spin,
            view: f.view,
            pins: f.pins,
        })
    }
}

impl From<Scene> for SceneFile {
    /// With `[units]` the body's sizes are written in metres, as the explorer holds them, in
    /// the fewest digits that read back to the same R_max; without, in R_max.
    fn from(s: Scene) -> SceneFile {
        let size = |x: f64| {
            SizeField(match &s.units {
                // Back on this table to the same R_max (to an ulp or two where no decimal
                // does it exactly).
                Some(u) => Length::Metres(
                    Length::parse(&show_r_max_in_metres(x, u))
                        .ok()
                        .and_then(|l| match l {
                            Length::Metres(m) => Some(m),
                            Length::RMax(_) => None,
                        })
                        .unwrap_or(x * u.r_max_m()),
                ),
                None => Length::RMax(x),
            })
        };
        let body = s.body.map(|b| BodyFile {
            length: size(b.length),
            height: b.height.map(size),
            angle: b.angle,
        });
        SceneFile {
            name: s.name,
            about: s.about,
            initial: s.initial,
            settings: s.settings,
            units: s.units,
            body,
            spin: s.spin,
            view: s.view,
            pins: s.pins,
        }
    }
}

/// The explorer's view of a scene: the page, the frame drawn, the arrows, zoom.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct View {
    pub page: Page,
    pub frame: crate::engine::Frame,
    pub forces: bool,
    pub zoom: f64,
    /// The net force's arrow (`A`) and the velocity's (`i`).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub net_force: bool,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub velocity: bool,
    /// Both frames side by side (`%`); saved only when on.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub split: bool,
    /// In a body scene, the point model's path and marker beside the body (`C`); saved only
    /// when hidden.
    #[serde(default = "shown", skip_serializing_if = "is_shown")]
    pub point: bool,
    /// How fast time plays (a power of two, ×1/64 to ×256); saved unless ×1.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub speed: f64,
}

fn one() -> f64 {
    1.0
}

fn is_one(x: &f64) -> bool {
    *x == 1.0
}

fn shown() -> bool {
    true
}

fn is_shown(b: &bool) -> bool {
    *b
}

/// What the body of the screen shows, in `Tab` order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Page {
    #[default]
    Turntable,
    TimePlots,
    EscapeSpeed,
    OutcomeMap,
    RestRadius,
    /// Error against work for each method and tolerance, on the release on screen.
    WorkPrecision,
}

impl Page {
    /// Every page, in Tab's order.
    pub const ORDER: [Page; 6] = [
        Page::Turntable,
        Page::TimePlots,
        Page::EscapeSpeed,
        Page::OutcomeMap,
        Page::RestRadius,
        Page::WorkPrecision,
    ];

    pub fn next(self) -> Page {
        let i = Page::ORDER.iter().position(|p| *p == self).unwrap_or(0);
        Page::ORDER[(i + 1) % Page::ORDER.len()]
    }

    pub fn prev(self) -> Page {
        let i = Page::ORDER.iter().position(|p| *p == self).unwrap_or(0);
        Page::ORDER[(i + Page::ORDER.len() - 1) % Page::ORDER.len()]
    }

    /// The page's name, in its title.
    pub fn title(self) -> &'static str {
        match self {
            Page::Turntable => "turntable",
            Page::TimePlots => "time plots",
            Page::EscapeSpeed => "escape speed",
            Page::OutcomeMap => "outcome map",
            Page::RestRadius => "rest radius",
            Page::WorkPrecision => "work-precision",
        }
    }
}

/// Speed factor bounds (powers of two).
pub const SPEED_RANGE: (f64, f64) = (1.0 / 64.0, 256.0);

/// `x` as a speed: a power of two in [`SPEED_RANGE`] (what the explorer's `[` and `]` step through), with
/// its exponent; None otherwise.
pub fn speed_power(x: f64) -> Option<i8> {
    let n = x.log2().round();
    ((SPEED_RANGE.0..=SPEED_RANGE.1).contains(&x) && x == n.exp2()).then_some(n as i8)
}

/// The paper's reference cases (CONVENTIONS.md), in the order of their keys, and the table
/// spun up under a coin (Sec. IV's familiar measure of μ, set against its Eq. 22).
pub const PRESETS: [&str; 7] = ["A", "B", "C", "D", "fig1", "fig2", "spin"];

/// The `spin` preset's ramp: from rest at a = 0.2, so a coin at ξ0 = 0.5 slips at τ ≈ 7
/// (some 5 s at ×1), and the μ read from its slip is low by ½ % (the Euler force's share).
const SPIN_RAMP: crate::engine::spinup::Ramp = crate::engine::spinup::Ramp {
    rate: 0.2,
    omega0: 0.0,
};

impl Scene {
    pub fn preset(name: &str) -> Option<Scene> {
        let (initial, about) = match name.to_ascii_lowercase().as_str() {
            // Clauses drop whole from the end where the line is short (the title, a notice):
            // the outcome comes first, and each prefix reads true.
            "a" => (
                Initial::velocity(0.5, PI, 1.0),
                "Fig. 3 A: comes to rest on the table, thrown inward",
            ),
            "b" => (
                Initial::velocity(0.5, 0.0, 0.6),
                "Fig. 3 B: comes to rest on the table, thrown outward",
            ),
            "c" => (
                Initial::velocity(0.5, 0.0, 0.6078),
                "Fig. 3 C: stops inside ξ = 1, escapes in the paper",
            ),
            "d" => (
                Initial::velocity(1.1, 1.2 * PI, 1.3),
                "Fig. 3 D: comes to rest on the table inside ξ = 1, thrown from outside",
            ),
            "fig1" => (
                Initial::at_rest(500.0, Release::LabRest),
                "Fig. 1: at rest in the lab at ξ0 = 500",
            ),
            "fig2" => (
                Initial::at_rest(1.1, Release::TableRest),
                "Fig. 2: at rest on the table at ξ0 = 1.1",
            ),
            "spin" => (
                Initial::at_rest(0.5, Release::TableRest),
                "a coin at rest at ξ0 = 0.5, the table spun up from rest until it slides",
            ),
            _ => return None,
        };
        let name = PRESETS
            .iter()
            .find(|p| p.eq_ignore_ascii_case(name))?
            .to_string();
        let spin = (name == "spin").then_some(SPIN_RAMP);
        Some(Scene {
            name: name.into(),
            about: about.into(),
            initial,
            settings: Settings::default(),
            units: None,
            body: None,
            spin,
            view: None,
            pins: Vec::new(),
        })
    }

    /// The default scene: the paper's case C, where the paper's scheme and a converged run
    /// disagree.
    pub fn default_scene() -> Scene {
        Scene::preset("C").expect("C is a preset")
    }

    /// A preset name, or a path to a TOML scene file. Errors name the file and the problem.
    /// A spin-up scene's `[spin]` is checked: at rest on the table (the model's release), a
    /// ramp and settings the spin-up takes, shown on the turntable page.
    pub fn load(name_or_path: &str) -> Result<Scene, Error> {
        if let Some(s) = Scene::preset(name_or_path) {
            return Ok(s);
        }
        if !(name_or_path.contains('/') || name_or_path.ends_with(".toml")) {
            return Err(Error::invalid(format!(
                "unknown scene '{name_or_path}' (presets: {}; or a path to a .toml file)",
                PRESETS.join(", ")
            )));
        }
        let text = crate::files::read_bounded(Path::new(name_or_path), crate::files::READ_CAP)
            .map_err(|e| Error::invalid(format!("scene file {e}")))?;
        let file = format!("scene file {name_or_path}");
        let scene: Scene = toml::from_str(&text).map_err(|e| {
            Error::invalid(format!("{file}: {}", crate::files::toml_error(&text, &e)))
        })?;
        let scene_file = crate::check::Via::Scene;
        crate::check::release(&scene.initial, &scene.settings, scene_file)
            .map_err(|e| e.context(&file))?;
        if scene.pins.len() > crate::pin::MAX_PINS {
            return Err(Error::invalid(format!(
                "{file}: {} pins, at most {} are kept",
                scene.pins.len(),
                crate::pin::MAX_PINS
            )));
        }
        for (k, p) in scene.pins.iter().enumerate() {
            let what = format!("{file}: pin {} ({:?})", k + 1, p.label.as_str());
            if p.label.chars().count() > crate::pin::LABEL_MAX {
                return Err(Error::invalid(format!(
                    "{what}: a label is at most {} characters",
                    crate::pin::LABEL_MAX
                )));
            }
            if !p.turn.is_finite() {
                return Err(Error::invalid(format!("{what}: turn must be finite")));
            }
            let pin = crate::check::Via::Pin;
            if let Some(u) = p.units {
                crate::check::units(&u, pin).map_err(|e| e.context(&what))?;
            }
            crate::check::release(&p.initial, &p.settings, pin).map_err(|e| e.context(&what))?;
        }
        if let Some(u) = scene.units {
            crate::check::units(&u, scene_file).map_err(|e| e.context(&file))?;
        }
        if let Some(v) = scene.view
            && speed_power(v.speed).is_none()
        {
            return Err(Error::invalid(format!(
                "{file}: [view] speed must be a power of two from 1/64 to 256, got {}",
                crate::engine::Initial::show(v.speed)
            )));
        }
        if let Some(b) = scene.body {
            crate::check::body(&b, scene_file).map_err(|e| e.context(&file))?;
        }
        if let Some(r) = scene.spin {
            if scene.initial.release != Release::TableRest
                || scene.body.is_some()
                || !scene.pins.is_empty()
                || scene.view.is_some_and(|v| v.page != Page::Turntable)
            {
                return Err(Error::invalid(format!(
                    "{file}: [spin] spins the table up under a coin at rest on it: it needs [initial] release = \"table-rest\", no [body] or pins, and the turntable page"
                )));
            }
            crate::check::spin(&r, scene.initial.xi0, &scene.settings, scene_file)
                .map_err(|e| e.context(&file))?;
        }
        Ok(scene)
    }

    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("a scene always serializes")
    }

    /// Writes the scene atomically to a new file: `path`, or if something stands there
    /// already, the first free `STEM-2.EXT`, `STEM-3.EXT`, …; never replaces a file. Returns
    /// the path written.
    pub fn save_new(&self, path: &Path) -> std::io::Result<std::path::PathBuf> {
        crate::files::write_new(path, self.to_toml().as_bytes(), 99)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::method::Scheme;

    /// Settings carry one knob, their method's: a saved scene writes only it, and a scene
    /// written when both were carried still reads (the method's own is taken).
    #[test]
    fn settings_carry_their_methods_knob() {
        let mut s = Scene::preset("B").unwrap();
        s.settings = Settings::fixed(crate::engine::Method::Rk4, 0.01);
        let text = s.to_toml();
        assert!(
            text.contains("dt = 0.01") && !text.contains("tol"),
            "{text}"
        );
        let back: Scene = toml::from_str(&text).unwrap();
        assert_eq!(back.settings.scheme, Scheme::Rk4 { dt: 0.01 });
        let old = "name = \"old\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.6\n[settings]\n\
                   method = \"dp54\"\ndt = 0.001\ntol = 1e-8\nframe = \"lab\"\nmax_steps = 1000\n";
        let old: Scene = toml::from_str(old).unwrap();
        assert_eq!(old.settings.scheme, Scheme::Dp54 { tol: 1e-8 });
        assert_eq!(old.settings.max_steps, 1000);
        // The knob may be left out: the method's default.
        let bare: Scene = toml::from_str(
            "name = \"x\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.6\n[settings]\nmethod = \"rk2\"\n",
        )
        .unwrap();
        assert_eq!(bare.settings.scheme, Scheme::Rk2 { dt: 1e-3 });
        // dop853 carries a tol (its default 1e-10), as dp54 does.
        s.settings.scheme = Scheme::Dop853 { tol: 1e-12 };
        let text = s.to_toml();
        assert!(
            text.contains("method = \"dop853\"")
                && text.contains("\ntol = ")
                && !text.contains("\ndt = "),
            "{text}"
        );
        let back: Scene = toml::from_str(&text).unwrap();
        assert_eq!(back.settings.scheme, Scheme::Dop853 { tol: 1e-12 });
        let bare: Scene = toml::from_str(
            "name = \"x\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.6\n[settings]\nmethod = \"dop853\"\n",
        )
        .unwrap();
        assert_eq!(bare.settings.scheme, Scheme::Dop853 { tol: 1e-10 });
        assert_eq!(crate::present::accuracy(&bare.settings), "tol=1e-10");
        assert!(
            toml::from_str::<Scene>(
                "name = \"x\"\n[initial]\nxi0 = 0.5\nphi = 0.0\nv0 = 0.6\n[settings]\nmethod = \"rk2\"\ntoll = 1\n"
            )
            .is_err()
        );
    }
}
