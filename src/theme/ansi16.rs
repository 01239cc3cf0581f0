//! A theme in the 16 colours every terminal has (`TERM=xterm`, `screen`, `linux`, which do
//! not promise the 256-colour palette): each colour becomes the nearest of the 16 that keeps
//! its role legible against the background, judged on xterm's default palette.

use super::Theme;
use ratatui::style::Color;

/// The 16 colours and their RGB in xterm's default palette.
const PALETTE: [(Color, (u8, u8, u8)); 16] = [
    (Color::Black, (0, 0, 0)),
    (Color::Red, (205, 0, 0)),
    (Color::Green, (0, 205, 0)),
    (Color::Yellow, (205, 205, 0)),
    (Color::Blue, (0, 0, 238)),
    (Color::Magenta, (205, 0, 205)),
    (Color::Cyan, (0, 205, 205)),
    (Color::Gray, (229, 229, 229)),
    (Color::DarkGray, (127, 127, 127)),
    (Color::LightRed, (255, 0, 0)),
    (Color::LightGreen, (0, 255, 0)),
    (Color::LightYellow, (255, 255, 0)),
    (Color::LightBlue, (92, 92, 255)),
    (Color::LightMagenta, (255, 0, 255)),
    (Color::LightCyan, (0, 255, 255)),
    (Color::White, (255, 255, 255)),
];

/// The RGB of the 16's `i`th (0–15, their index in the 256-colour palette) in xterm's default
/// palette.
pub fn indexed(i: u8) -> (u8, u8, u8) {
    PALETTE[usize::from(i & 15)].1
}

/// A colour's RGB: its own, or for one of the 16 its xterm default.
pub fn rgb(c: Color) -> Option<(u8, u8, u8)> {
    match c {
        Color::Rgb(r, g, b) => Some((r, g, b)),
        _ => PALETTE.iter().find(|p| p.0 == c).map(|p| p.1),
    }
}

/// WCAG 2 relative luminance.
fn luminance((r, g, b): (u8, u8, u8)) -> f64 {
    let lin = |v: u8| {
        let x = f64::from(v) / 255.0;
        if x <= 0.03928 {
            x / 12.92
        } else {
            ((x + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b)
}

/// WCAG 2 contrast ratio (1 to 21).
pub fn contrast(a: (u8, u8, u8), b: (u8, u8, u8)) -> f64 {
    let (la, lb) = (luminance(a), luminance(b));
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}

/// The 16 colours as families: the greys by lightness, then each hue (at 0°, 60°, … 300°)
/// in its normal and bright forms.
const GREYS: [Color; 4] = [Color::Black, Color::DarkGray, Color::Gray, Color::White];
const HUES: [[Color; 2]; 6] = [
    [Color::Red, Color::LightRed],
    [Color::Yellow, Color::LightYellow],
    [Color::Green, Color::LightGreen],
    [Color::Cyan, Color::LightCyan],
    [Color::Blue, Color::LightBlue],
    [Color::Magenta, Color::LightMagenta],
];

/// The 16-colour form of `c`: the same hue family (greys for the nearly grey), the member
/// nearest in luminance among those with at least `min` contrast against `bg`; if the family
/// has none, the nearest grey that has (then any colour); the most contrasting if none has.
/// Colours that are not RGB (the terminal's own, `Reset`) stay as they are.
pub fn nearest(c: Color, bg: Option<(u8, u8, u8)>, min: f64) -> Color {
    let Color::Rgb(r, g, b) = c else {
        return c;
    };
    let (max, lo) = (r.max(g).max(b), r.min(g).min(b));
    let chroma = f64::from(max - lo);
    let family: &[Color] = if chroma < 0.25 * f64::from(max) || chroma < 24.0 {
        &GREYS
    } else {
        let (r, g, b) = (f64::from(r), f64::from(g), f64::from(b));
        let hue = (3f64.sqrt() * (g - b)).atan2(2.0 * r - g - b).to_degrees();
        &HUES[(hue.rem_euclid(360.0) / 60.0).round() as usize % 6]
    };
    let lum = luminance((r, g, b));
    let rgb_of = |p: &Color| rgb(*p).unwrap_or_default();
    let k = |p: &Color| bg.map_or(21.0, |bg| contrast(rgb_of(p), bg));
    let near = |p: &&Color| -(luminance(rgb_of(p)) - lum).abs();
    let all: Vec<Color> = PALETTE.iter().map(|p| p.0).collect();
    let best = |set: &[Color]| {
        set.iter()
            .filter(|p| k(p) >= min)
            .max_by(|a, b| near(a).total_cmp(&near(b)))
            .copied()
    };
    best(family)
        .or_else(|| best(&GREYS))
        .or_else(|| best(&all))
        .or_else(|| all.iter().copied().max_by(|a, b| k(a).total_cmp(&k(b))))
        .unwrap_or(c)
}

/// The theme in 16 colours: text and data at ≥ 4.5:1 against the background, the drawing at
/// ≥ 3:1 (high-contrast: everything at ≥ 7:1), as the 24-bit theme promises.
pub fn map(t: &mut Theme) {
    t.background = nearest(t.background, None, 0.0);
    let bg = rgb(t.background);
    let strict = t.name == "high-contrast";
    let text = [
        &mut t.foreground,
        &mut t.muted,
        &mut t.accent,
        &mut t.particle,
        &mut t.trail,
        &mut t.slipping,
        &mut t.stuck,
        &mut t.escaped,
        &mut t.notice,
    ];
    let min = if strict { 7.0 } else { 4.5 };
    for c in text {
        *c = nearest(*c, bg, min);
    }
    // The particle's colour (its marker, and a body's bar and centre's path) and the point's
    // trail stay apart where both fall on one of the 16 (dark: both yellow): the particle takes
    // its family's other member, if that keeps the contrast.
    if t.particle == t.trail
        && let Some(other) = sibling(t.particle, bg, min)
    {
        t.particle = other;
    }
    let drawing = [
        &mut t.table_edge,
        &mut t.limit_circle,
        &mut t.arrow,
        &mut t.friction,
        &mut t.coriolis,
        &mut t.centrifugal,
    ];
    for c in drawing {
        *c = nearest(*c, bg, if strict { 7.0 } else { 3.0 });
    }
    // The spokes may stay faint, but not vanish into the background.
    t.spokes = nearest(t.spokes, bg, 1.2);
}

/// The other colour of `c`'s family (its bright or normal form; a grey's nearest grey) with at
/// least `min` contrast against `bg`.
fn sibling(c: Color, bg: Option<(u8, u8, u8)>, min: f64) -> Option<Color> {
    let k = |p: Color| bg.map_or(21.0, |bg| contrast(rgb(p).unwrap_or_default(), bg));
    let lum = luminance(rgb(c)?);
    let family: &[Color] = HUES
        .iter()
        .find(|h| h.contains(&c))
        .map_or(&GREYS[..], |h| &h[..]);
    family
        .iter()
        .copied()
        .filter(|&p| p != c && k(p) >= min)
        .min_by(|a, b| {
            let d = |p: Color| (luminance(rgb(p).unwrap_or_default()) - lum).abs();
            d(*a).total_cmp(&d(*b))
        })
}
