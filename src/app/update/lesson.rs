//! The "lesson" group: a prediction answered, a wait ended.

use super::super::action::Action;
use super::super::state::App;

pub(super) fn apply(app: &mut App, action: Action) {
    match action {
        Action::Answer(yes) => {
            if let Some(q) = app.lesson.question.as_mut().filter(|q| q.answer.is_none()) {
                q.answer = Some(yes);
            }
        }
        Action::GoOn => app.lesson.waiting = false,
        // Other groups' actions: `update` never sends them here.
        _ => {}
    }
}
