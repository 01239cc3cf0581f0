//! The "app" group: help, notices, saving, the mouse, quitting.

use super::super::action::{Action, NameEdit};
use super::super::state::App;

pub(super) fn apply(app: &mut App, action: Action) {
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
            let page = crate::ui::help::page(app.screen().1);
            scroll_help(app, i32::from(pages) * i32::from(page));
        }
        Action::Save => save(app, None),
        Action::SaveAs => app.naming = Some(String::new()),
        Action::Name(edit) => name(app, edit),
        Action::ExportSvg if !app.writes_files => {
            app.notice = Some(format!(
                "replay saves nothing: this page → turntable-{}-N.svg (the first free N)",
                crate::ui::figure::slug(app.page)
            ));
        }
        Action::ExportSvg => app.notice = Some(export_svg(app)),
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
            app.notice = Some(crate::ui::plain::summary(app));
        }
        // Other groups' actions: `update` never sends them here.
        _ => {}
    }
}

/// Longest name the prompt takes (a scene's name is one line of its panel).
pub const NAME_MAX: usize = 40;

/// An edit at the save prompt: letters up to [`NAME_MAX`], Enter saves under the name (an
/// empty name is the scene's own), Esc closes the prompt without saving.
fn name(app: &mut App, edit: NameEdit) {
    let Some(typed) = app.naming.as_mut() else {
        return;
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
            save(app, (!typed.is_empty()).then_some(typed));
        }
    }
}

/// Saves the scene on screen (under `name`, in a file named after it) to a new file; replay
/// writes none and says where it would have.
fn save(app: &mut App, name: Option<&str>) {
    let path = match name {
        Some(n) => app
            .save_path
            .with_file_name(format!("{}.toml", file_stem(n))),
        None => app.save_path.clone(),
    };
    let scene = app.scene_named(name);
    app.notice = Some(if !app.writes_files {
        format!(
            "replay saves nothing: \"{}\" → {} (or the next free name)",
            scene.name,
            path.display()
        )
    } else {
        match scene.save_new(&path) {
            Ok(p) => format!("saved \"{}\" to {}", scene.name, p.display()),
            Err(e) => format!("could not save {}: {e}", path.display()),
        }
    });
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

/// Writes the page on screen as SVG to the first free `turntable-PAGE-N.svg` in the folder
/// scenes are saved to (the current one); never over a file. Says where, or why not.
fn export_svg(app: &App) -> String {
    use std::io::Write;
    let (fig, whole) = crate::ui::figure::page(app);
    let text = crate::figure::to_svg(&fig);
    let slug = crate::ui::figure::slug(app.page);
    let dir = app.save_path.parent().unwrap_or(std::path::Path::new(""));
    for n in 1..=999 {
        let path = dir.join(format!("turntable-{slug}-{n}.svg"));
        if path.symlink_metadata().is_ok() {
            continue;
        }
        let written = crate::files::Output::create(&path, false).and_then(|mut out| {
            out.write_all(text.as_bytes())?;
            out.finish()
        });
        return match written {
            Ok(()) if whole => format!("wrote this page to {}", path.display()),
            Ok(()) => format!(
                "wrote this page to {} (partial: it is still computing)",
                path.display()
            ),
            // Taken meanwhile: the next name.
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => format!("could not write {}: {e}", path.display()),
        };
    }
    format!("could not write turntable-{slug}-N.svg: 999 names taken")
}

/// Moves the help by `rows` (no further than its end at this size); nothing when it is shut.
fn scroll_help(app: &mut App, rows: i32) {
    if app.help {
        let (w, h) = app.screen();
        let end = i32::from(crate::ui::help::max_scroll(w, h, &app.theme));
        let to = (i32::from(app.help_scroll) + rows).clamp(0, end);
        app.help_scroll = u16::try_from(to).unwrap_or(0);
    }
}
