//! The "app" group: help, notices, saving, the mouse, quitting.

use super::super::action::{Action, Edit};
use super::super::effect::{Effect, Effects};
use super::super::lesson::Lesson;
use super::super::prompt::TYPED_MAX;
use super::super::prompt::{Asks, Prompt};
use super::super::state::{App, record_player};

pub(super) fn apply(app: &mut App, action: Action) -> Effects {
    match action {
        // `q` and Ctrl-C quit whatever is open (the help included); Esc closes it.
        Action::Quit => app.quit = true,
        // The notice is already cleared by `update`; with the help closed, a finished
        // lesson's last words go too (they would stay on screen for the rest of the hour).
        Action::Dismiss if app.view.help => app.view.help = false,
        Action::Dismiss if app.lesson.done => {
            app.lesson = Lesson {
                done: true,
                ..Lesson::default()
            }
        }
        Action::Dismiss => {}
        // Over serve the session takes F2 first: here there is no class.
        Action::Follow => {
            app.notice =
                Some("F2 steps in and out of a class over `turntable serve`: none here".into())
        }
        Action::ToggleHelp => {
            app.view.help = !app.view.help;
            app.view.help_scroll = 0;
        }
        Action::HelpScroll(rows) => scroll_help(app, i32::from(rows)),
        Action::HelpPage(pages) => {
            let page = app.measured.help_page;
            scroll_help(app, i32::from(pages) * i32::from(page));
        }
        Action::Save => return vec![save(app, None)],
        Action::SaveAs => app.prompt = Some(Prompt::new(Asks::Name)),
        Action::SetValues => app.prompt = Some(Prompt::new(Asks::Values)),
        Action::Type(edit) => return typed(app, edit),
        Action::ExportSvg => {
            return vec![Effect::ExportSvg {
                dir: app
                    .save_path
                    .parent()
                    .unwrap_or(std::path::Path::new(""))
                    .to_path_buf(),
                page: app.view.page,
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

/// An edit at the prompt: letters up to [`TYPED_MAX`]; Enter saves under the name (an empty
/// name is the scene's own) or sets the values (refused with the reason, the line kept to
/// mend); Esc closes the prompt and changes nothing.
fn typed(app: &mut App, edit: Edit) -> Effects {
    let Some(p) = app.prompt.as_mut() else {
        return Effects::new();
    };
    p.refused = None;
    match edit {
        Edit::Char(c) if p.typed.chars().count() < TYPED_MAX => p.typed.push(c),
        Edit::Char(_) => p.refused = Some(format!("at most {TYPED_MAX} characters")),
        Edit::Back => {
            p.typed.pop();
        }
        Edit::Cancel => {
            app.notice = Some(match p.asks {
                Asks::Name => "not saved".into(),
                Asks::Values => "nothing set".into(),
            });
            app.prompt = None;
        }
        Edit::Done if p.asks == Asks::Name => {
            let typed = app.prompt.take().map(|p| p.typed).unwrap_or_default();
            let typed = typed.trim();
            return vec![save(app, (!typed.is_empty()).then_some(typed))];
        }
        Edit::Done => {
            let line = p.typed.clone();
            if let Some(asked) = super::super::prompt::asked_error(&line) {
                accuracy(app, asked);
                return Effects::new();
            }
            match super::super::prompt::values(&line, app.initial(), app.units, record_player()) {
                Ok((i, u)) => {
                    app.prompt = None;
                    if u != app.units
                        && let Some(u) = u
                    {
                        super::view::set_units(app, u);
                    }
                    app.explore().set_initial(i);
                    // As the app holds it: ξ0 and v0 as set, φ read as every angle is.
                    let i = app.initial();
                    app.notice = Some(format!(
                        "set: ξ0 = {}, φ = {}, v0 = {}{}",
                        i.xi0,
                        crate::present::angle(i.phi),
                        i.v0,
                        app.units.map_or_else(String::new, |u| format!(
                            "; {}",
                            crate::present::table(&u)
                        ))
                    ));
                }
                Err(why) => {
                    if let Some(p) = app.prompt.as_mut() {
                        p.refused = Some(why);
                    }
                }
            }
        }
    }
    Effects::new()
}

/// `error E` at the prompt: the run switched to the cheapest setting whose stated error is at
/// most E ([`crate::sim::accuracy`]; a bounded search, at most 22 runs to [`EXPLORER_TAU`] and
/// their second opinions), said in a notice with its cost in RHS evaluations (the model reads no
/// clock); a bad E, a closed-form scene or a release nothing states so well stays at the prompt
/// with the reason.
fn accuracy(app: &mut App, asked: Result<f64, String>) {
    use crate::sim::accuracy::{EXPLORER_TAU, cheapest};
    let settings = app.settings();
    let chosen = asked.and_then(|e| {
        if crate::engine::closed_form(&app.initial(), settings) {
            return Err(
                "closed form here (μ = 0 or Stokes drag): exact, no tolerance to choose".into(),
            );
        }
        let c =
            cheapest(app.initial(), settings, EXPLORER_TAU, true, e).map_err(|e| e.to_string())?;
        match c.chosen {
            Some(t) => Ok((t.settings, c.said(None))),
            None => Err(c.said(None)),
        }
    });
    match chosen {
        Ok((s, said)) => {
            app.prompt = None;
            app.explore().set_settings(s);
            app.notice = Some(said);
        }
        Err(why) => {
            if let Some(p) = app.prompt.as_mut() {
                p.refused = Some(why);
            }
        }
    }
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
    if app.view.help {
        let end = i32::from(app.measured.help_max_scroll);
        let to = (i32::from(app.view.help_scroll) + rows).clamp(0, end);
        app.view.help_scroll = u16::try_from(to).unwrap_or(0);
    }
}
