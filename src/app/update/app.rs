//! The "app" group: help, notices, saving, the mouse, quitting.

use super::super::action::{Action, NameEdit};
use super::super::effect::{Effect, Effects};
use super::super::state::App;

pub(super) fn apply(app: &mut App, action: Action) -> Effects {
    match action {
        // `q` and Ctrl-C quit whatever is open (the help included); Esc closes it.
        Action::Quit => app.quit = true,
        // The notice is already cleared by `update`.
        Action::Dismiss => app.help = false,
        Action::ToggleHelp => {
            app.help = !app.help;
            app.help_scroll = 0;
        }
        Action::HelpScroll(rows) => scroll_help(app, i32::from(rows)),
        Action::HelpPage(pages) => {
            let page = app.measured.help_page;
            scroll_help(app, i32::from(pages) * i32::from(page));
        }
        Action::Save => return vec![save(app, None)],
        Action::SaveAs => app.naming = Some(String::new()),
        Action::Name(edit) => return name(app, edit),
        Action::ExportSvg => {
            return vec![Effect::ExportSvg {
                dir: app
                    .save_path
                    .parent()
                    .unwrap_or(std::path::Path::new(""))
                    .to_path_buf(),
                page: app.page,
            }];
        }
        Action::ToggleMouse => {
            app.mouse = !app.mouse;
            app.notice = Some(
                if app.mouse {
                    "mouse on: click = release point, drag = initial velocity"
                } else {
                    "mouse off: select text with the mouse; M turns it back on"
                }
                .into(),
            );
        }
        Action::Readouts => {
            app.readouts_asked += 1;
            return vec![Effect::Readouts];
        }
        // Other groups' actions: `update` never sends them here.
        _ => {}
    }
    Effects::new()
}

/// Longest name the prompt takes (a scene's name is one line of its panel).
pub const NAME_MAX: usize = 40;

/// An edit at the save prompt: letters up to [`NAME_MAX`], Enter saves under the name (an
/// empty name is the scene's own), Esc closes the prompt without saving.
fn name(app: &mut App, edit: NameEdit) -> Effects {
    let Some(typed) = app.naming.as_mut() else {
        return Effects::new();
    };
    match edit {
        NameEdit::Char(c) if typed.chars().count() < NAME_MAX => typed.push(c),
        NameEdit::Char(_) => app.notice = Some(format!("a name has at most {NAME_MAX} characters")),
        NameEdit::Back => {
            typed.pop();
        }
        NameEdit::Cancel => {
            app.naming = None;
            app.notice = Some("not saved".into());
        }
        NameEdit::Done => {
            let typed = app.naming.take().unwrap_or_default();
            let typed = typed.trim();
            return vec![save(app, (!typed.is_empty()).then_some(typed))];
        }
    }
    Effects::new()
}

/// Asks to save the scene on screen (under `name`, in a file named after it) to a new file.
fn save(app: &App, name: Option<&str>) -> Effect {
    let path = match name {
        Some(n) => app
            .save_path
            .with_file_name(format!("{}.toml", file_stem(n))),
        None => app.save_path.clone(),
    };
    Effect::SaveScene {
        scene: Box::new(app.scene_named(name)),
        path,
    }
}

/// A file name for a scene called `name`: its letters and digits, lower case, words joined by
/// `-` ("Case D, μ × 2" → `case-d-μ-2`); `scene` when nothing is left.
fn file_stem(name: &str) -> String {
    let words: Vec<String> = name
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_lowercase)
        .collect();
    if words.is_empty() {
        "scene".into()
    } else {
        words.join("-")
    }
}

/// Moves the help by `rows` (no further than its end at this size); nothing when it is shut.
fn scroll_help(app: &mut App, rows: i32) {
    if app.help {
        let end = i32::from(app.measured.help_max_scroll);
        let to = (i32::from(app.help_scroll) + rows).clamp(0, end);
        app.help_scroll = u16::try_from(to).unwrap_or(0);
    }
}
