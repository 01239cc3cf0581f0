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

/// Moves the help by `rows` (no further than its end at this size); nothing when it is shut.
fn scroll_help(app: &mut App, rows: i32) {
    if app.help {
        let (w, h) = app.screen();
        let end = i32::from(crate::ui::help::max_scroll(w, h, &app.theme));
        let to = (i32::from(app.help_scroll) + rows).clamp(0, end);
        app.help_scroll = u16::try_from(to).unwrap_or(0);
    }
}
