//! The "app" group: help, notices, saving, the mouse, quitting.

use super::super::action::Action;
use super::super::state::App;

pub(super) fn apply(app: &mut App, action: Action) {
    match action {
        Action::Quit => {
            if app.help {
                app.help = false;
            } else {
                app.quit = true;
            }
        }
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
        Action::Save if !app.writes_files => {
            app.notice = Some(format!(
                "replay writes no files: s would save this scene to {} (or the next free name)",
                app.save_path.display()
            ));
        }
        Action::Save => {
            let scene = app.current_scene();
            app.notice = Some(match scene.save_new(&app.save_path) {
                Ok(p) => format!("saved scene to {}", p.display()),
                Err(e) => format!("could not save {}: {e}", app.save_path.display()),
            });
        }
        Action::ExportSvg if !app.writes_files => {
            app.notice = Some(format!(
                "replay writes no files: E would write this page to turntable-{}-N.svg (the first free N)",
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
        // Other groups' actions: `update` never sends them here.
        _ => {}
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
        let written = crate::files::Output::create(&path).and_then(|mut out| {
            out.write_all(text.as_bytes())?;
            out.finish_new()
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
