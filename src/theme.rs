//! Temporary stub of the theme API (the real module comes from branch `script`).

use ratatui::style::Color;

#[derive(Clone, Debug, PartialEq)]
pub struct Theme {
    pub name: String,
    pub background: Color,
    pub foreground: Color,
    pub muted: Color,
    pub accent: Color,
    pub table_edge: Color,
    pub spokes: Color,
    pub limit_circle: Color,
    pub particle: Color,
    pub trail: Color,
    pub arrow: Color,
    pub friction: Color,
    pub coriolis: Color,
    pub centrifugal: Color,
    pub slipping: Color,
    pub stuck: Color,
    pub escaped: Color,
    pub notice: Color,
}

impl Theme {
    pub fn builtin(name: &str) -> Option<Theme> {
        use Color::*;
        match name {
            "dark" => Some(Theme {
                name: "dark".into(),
                background: Reset,
                foreground: White,
                muted: DarkGray,
                accent: Cyan,
                table_edge: Gray,
                spokes: DarkGray,
                limit_circle: Yellow,
                particle: LightRed,
                trail: LightBlue,
                arrow: LightGreen,
                friction: Red,
                coriolis: Magenta,
                centrifugal: Green,
                slipping: Yellow,
                stuck: Green,
                escaped: Red,
                notice: LightYellow,
            }),
            "mono" => Some(Theme {
                name: "mono".into(),
                ..Theme::all(Reset)
            }),
            _ => None,
        }
    }
    fn all(c: Color) -> Theme {
        Theme {
            name: String::new(),
            background: c,
            foreground: c,
            muted: c,
            accent: c,
            table_edge: c,
            spokes: c,
            limit_circle: c,
            particle: c,
            trail: c,
            arrow: c,
            friction: c,
            coriolis: c,
            centrifugal: c,
            slipping: c,
            stuck: c,
            escaped: c,
            notice: c,
        }
    }
    pub fn load(name_or_path: &str) -> Result<Theme, String> {
        Theme::builtin(name_or_path).ok_or_else(|| format!("unknown theme '{name_or_path}'"))
    }
    pub fn resolve(requested: Option<&str>, no_color: bool) -> Result<Theme, String> {
        match requested {
            Some(r) => Theme::load(r),
            None if no_color => Ok(Theme::builtin("mono").unwrap()),
            None => Ok(Theme::builtin("dark").unwrap()),
        }
    }
}
