//! The "lesson" group: a prediction answered, a wait ended.

use super::super::action::Action;
use super::super::lesson::Prompt;
use super::super::state::App;

pub(super) fn apply(app: &mut App, action: Action) {
    match action {
        Action::Answer(yes) => {
            if let Some(q) = app.lesson.question.as_mut().filter(|q| q.answer.is_none()) {
                q.answer = Some(yes);
            }
        }
        Action::GoOn if app.lesson.prompt() == Prompt::Answer => {
            app.report("the question first: y if it escapes, n if it stays".into());
        }
        Action::GoOn => {
            app.lesson.waiting = false;
            if std::mem::take(&mut app.lesson.resume) {
                app.playing = true;
                app.view.step_mode = false;
            }
        }
        // Other groups' actions: `update` never sends them here.
        _ => {}
    }
}
