//! A session's part in the class: what a follower is told, the class's state taken over,
//! its own answers, the presenter's tally, and F2 (step out, rejoin, wait for a presenter).

use super::super::class::Handed;
use super::{Remote, Screen};
use crate::app::lesson::Prompt;
use crate::app::state::InClass;
use crate::session::Explorer;

// Each said two ways, the second for a narrow window (see `present::alternatives`): the
// key that does something about it is the part that must not be cut.

/// What a follower is told on joining, and at each key of its own while it follows.
pub(super) const FOLLOWING: &str =
    "following the class: F2 steps out to explore\u{1f}following the class (F2: step out)";

/// What a student who came before the presenter is told (and told again by F2).
pub(super) const WAITING: &str = "no presenter yet: you follow the class when they come (F2: on your own)\u{1f}no presenter yet: you follow when they come (F2: alone)";

/// What a student who waited for the presenter (see [`WAITING`], [`LEFT`]) is told when one
/// comes: the screen now moves with someone else's keys.
pub(super) const ARRIVED: &str = "the presenter is here: you follow the class (F2 steps out)\u{1f}the presenter is here: following (F2: step out)";

/// What a presenter who takes up a class its last presenter left (or still held) is told.
pub(super) const TAKEN_UP: &str = "you present: the class as it was left, and its followers";

/// What the followers are told when the presenter leaves.
pub(super) const LEFT: &str = "the presenter left: on your own until they are back (F2: stay on your own)\u{1f}the presenter left: on your own until they are back";

/// The class's state, handed over (to a follower, or to a presenter taking up the class its
/// last presenter left), drawn in this client's own theme and size; the presenter's tally is
/// the presenter's own.
pub(super) fn adopt(s: &mut Explorer<Screen>, (app, lesson): Handed) {
    let (w, h) = (s.app.screen.0, s.app.screen.1);
    s.app = *app;
    s.set_lesson(lesson);
    s.app.tell_tally(None);
    crate::session::tell_size(&mut s.app, w, h);
    s.app.invalidate();
    s.ask_analysis();
}

impl Remote<'_> {
    /// A follower's own answer to the open question: told to the presenter's tally, and shown
    /// on its own screen if counted (the presenter may have closed it meanwhile).
    pub(super) fn answer(&mut self, s: &mut Explorer<Screen>, yes: bool) {
        let taken = s
            .app
            .lesson()
            .question
            .as_ref()
            .is_some_and(|q| q.own.is_none())
            && self.shared.answer(self.id, s.app.lesson().asked, yes);
        if taken {
            s.app.answer_apart(yes);
        }
    }

    /// (The presenter's thread, while a question is on screen.) The class's answers so far,
    /// told to the model for the caption; reset by a new question.
    pub(super) fn tally(&mut self, s: &mut Explorer<Screen>) {
        let l = &s.app.lesson();
        if l.question.is_none() && l.tally.is_none() {
            return;
        }
        let open = l.prompt() == Prompt::Answer;
        let tally = self.shared.tally(self.id, l.asked, open);
        let shown = tally.filter(|_| l.question.is_some());
        s.app.tell_tally(shown);
    }

    /// F2: a follower steps out (and explores from where the class is); out, it rejoins.
    pub(super) fn follow_key(&mut self, s: &mut Explorer<Screen>) {
        if self.following {
            self.following = false;
            self.at = None;
            s.app.tell_class(InClass::Out);
            self.shared.unfollow(self.id);
            s.app
                .report("stepped out of the class: F2 rejoins it".into());
        } else if self.shared.class_led(self.id) {
            self.shared.join(self.id);
        } else if self.shared.presents(self.id) {
            s.app
                .report("you present: there is no class to follow".into());
        } else if self.shared.wait_for_class(self.id) {
            s.app.report(WAITING.into());
        } else {
            s.app
                .report("on your own: F2 follows the class when the presenter comes".into());
        }
    }
}
