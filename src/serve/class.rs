//! The class: who presents, who follows (and who asks to), the class's state handed to a
//! follower, the presenter's keys and ticks to the followers, and their answers to its question.

use super::{In, Lead, Shared, lock};
use crate::app::App;
use crate::app::lesson::Tally;
use std::collections::HashMap;

/// The class: who presents, who follows, and their answers to the presenter's question.
#[derive(Default)]
pub struct Class {
    pub presenter: Option<u64>,
    pub followers: Vec<u64>,
    /// Asked to follow, the class not yet taken: asking again adds nothing (an F2 flood once
    /// queued a copy of the whole state a press, without bound).
    pub joining: Vec<u64>,
    /// Follow as soon as a class is led: came before the presenter, or the presenter left.
    pub waiting: Vec<u64>,
    /// The class's state handed to each follower, until it takes it: one at most, the latest;
    /// and the place it was taken at.
    pub handed: HashMap<u64, (Handed, Place)>,
    /// The class as its last presenter left it (a dropped connection): the next presenter
    /// takes it up there, the lesson at the same step. One at most.
    pub left: Option<Handed>,
    /// A presenter still in (the old) handing the class over to the one who took it (the new).
    pub handing: Option<(u64, u64)>,
    pub poll: Poll,
    /// What the presenters have led, in all: each lead's place in the class.
    pub led: u64,
}

/// Where the class's state is: who leads it, and the count of leads given then. Followers
/// handed the class at one place and given every lead since, in order, are in one state
/// (their own notices and answers apart), and see one screen at one size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Place {
    pub presenter: u64,
    pub led: u64,
}

impl Place {
    /// The place a follower at `self` is in once given the lead made at `next`: None when
    /// that is not the lead after its own (another presenter's), its state then unknown.
    pub fn then(self, next: Place) -> Option<Place> {
        (next.presenter == self.presenter && next.led == self.led + 1).then_some(next)
    }
}

/// The class's state as a follower takes it: the presenter's `App` and its lesson's place.
pub type Handed = (Box<App>, Option<crate::lesson::Driver>);

/// The followers' own answers to the question on the presenter's screen.
#[derive(Default)]
pub struct Poll {
    /// Which question (the presenter's count of questions asked).
    question: u32,
    /// Whether it still takes answers: until the presenter answers it and goes on.
    open: bool,
    /// By session; the first answer stands. A follower who leaves or steps out is not
    /// counted while out (its answer is kept, should it rejoin before the question closes).
    answers: HashMap<u64, bool>,
}

impl Shared {
    /// Whether `id` presents.
    pub(super) fn presents(&self, id: u64) -> bool {
        lock(&self.class).presenter == Some(id)
    }

    /// Whether a presenter other than `id` leads a class.
    pub(super) fn class_led(&self, id: u64) -> bool {
        lock(&self.class).presenter.is_some_and(|p| p != id)
    }

    /// `id` asks to follow: the presenter sends it the class (see [`Shared::welcome`]), once
    /// until it is taken.
    pub(super) fn join(&self, id: u64) {
        let mut class = lock(&self.class);
        if let Some(p) = class.presenter
            && !class.joining.contains(&id)
        {
            class.joining.push(id);
            self.send(p, In::Join(id));
        }
    }

    /// (The presenter's thread.) `follower` gets the class as it is, and from now on what
    /// the presenter does: one lock, so nothing falls between. The state waits in one place
    /// a follower, the latest replacing any not yet taken, at `id`'s place.
    pub(super) fn welcome(
        &self,
        id: u64,
        follower: u64,
        app: &App,
        lesson: Option<&crate::lesson::Driver>,
    ) {
        let mut class = lock(&self.class);
        // Asked of a presenter since replaced: the one who took the class answers it.
        if class.presenter != Some(id) {
            return;
        }
        if !class.followers.contains(&follower) {
            class.followers.push(follower);
        }
        let handed = (Box::new(app.clone()), lesson.cloned());
        let at = Place {
            presenter: id,
            led: class.led,
        };
        if class.handed.insert(follower, (handed, at)).is_none() {
            self.send(follower, In::Class);
        }
    }

    /// (A follower's thread, told [`In::Class`].) The class handed to it, and its place; it
    /// may ask again.
    pub(super) fn take_class(&self, id: u64) -> Option<(Handed, Place)> {
        let mut class = lock(&self.class);
        class.joining.retain(|&f| f != id);
        class.handed.remove(&id)
    }

    /// Class states handed to followers and not yet taken (at most one a follower).
    pub fn handed(&self) -> usize {
        lock(&self.class).handed.len()
    }

    /// (The presenter's thread.) Its question on screen now (the `asked`th, taking answers
    /// while `open`): the followers' answers to it so far; None when `id` does not present.
    /// A new question starts a new tally.
    pub(super) fn tally(&self, id: u64, asked: u32, open: bool) -> Option<Tally> {
        let mut class = lock(&self.class);
        if class.presenter != Some(id) {
            return None;
        }
        let class = &mut *class;
        if class.poll.question != asked {
            class.poll = Poll {
                question: asked,
                ..Poll::default()
            };
        }
        class.poll.open = open;
        let mut t = Tally::default();
        for f in &class.followers {
            match class.poll.answers.get(f) {
                Some(true) => t.yes += 1,
                Some(false) => t.no += 1,
                None => t.not_yet += 1,
            }
        }
        Some(t)
    }

    /// (A follower's thread.) Its own answer to the `asked`th question: counted if that is
    /// the presenter's question, still open, and `id` follows; whether it was.
    pub(super) fn answer(&self, id: u64, asked: u32, yes: bool) -> bool {
        let mut class = lock(&self.class);
        let p = &class.poll;
        if !(p.open && p.question == asked && class.followers.contains(&id)) {
            return false;
        }
        class.poll.answers.entry(id).or_insert(yes);
        if let Some(presenter) = class.presenter {
            self.send(presenter, In::Answered);
        }
        true
    }

    /// `id`'s answer to the `asked`th question, if it gave one in class.
    pub(super) fn answered(&self, id: u64, asked: u32) -> Option<bool> {
        let class = lock(&self.class);
        let p = &class.poll;
        (p.question == asked).then(|| p.answers.get(&id).copied())?
    }

    pub(super) fn unfollow(&self, id: u64) {
        let mut class = lock(&self.class);
        class.followers.retain(|&f| f != id);
        class.waiting.retain(|&f| f != id);
        class.handed.remove(&id);
    }

    /// `id` follows when a presenter comes (it came first, or asked with none there); false
    /// if it was already waiting, and now is not (F2 again: it explores on its own).
    pub(super) fn wait_for_class(&self, id: u64) -> bool {
        let mut class = lock(&self.class);
        if class.waiting.contains(&id) {
            class.waiting.retain(|&f| f != id);
            false
        } else {
            class.waiting.push(id);
            true
        }
    }

    /// (The presenter's thread, as it ends or hands the class over.) The class as it leaves
    /// it, for the next presenter to take up (told so if it is waiting for it).
    pub(super) fn leave_class(&self, id: u64, app: &App, lesson: Option<&crate::lesson::Driver>) {
        let mut class = lock(&self.class);
        let handing = class.handing.take_if(|(old, _)| *old == id);
        if class.presenter == Some(id) || handing.is_some() {
            class.left = Some((Box::new(app.clone()), lesson.cloned()));
        }
        if let Some((_, new)) = handing {
            self.send(new, In::TakeUp);
        }
    }

    /// (The presenter `id`'s thread, or the class's lock held for it.) Every follower, every
    /// one asking to follow and every one waiting for a class is sent to `id` to be handed
    /// its class: none is left applying its keys and lesson steps to another's.
    pub(super) fn call_class(&self, class: &Class, id: u64) {
        for &f in class.followers.iter().chain(&class.joining) {
            self.send(id, In::Join(f));
        }
    }

    /// (A presenter's thread, told [`In::TakeUp`].) The class handed over, if it was; its
    /// followers are called either way.
    pub(super) fn take_over(&self, id: u64) -> Option<Handed> {
        let handed = self.take_up_class(id);
        let class = lock(&self.class);
        if class.presenter == Some(id) {
            self.call_class(&class, id);
        }
        handed
    }

    /// (A new presenter's thread.) The class as the last presenter left it, if one did.
    pub(super) fn take_up_class(&self, id: u64) -> Option<Handed> {
        let mut class = lock(&self.class);
        if class.presenter != Some(id) {
            return None;
        }
        class.left.take()
    }

    /// (A session's thread.) If `id` presents, its followers do `lead` too, told its place.
    pub(super) fn lead(&self, id: u64, lead: Lead) {
        let mut class = lock(&self.class);
        if class.presenter != Some(id) {
            return;
        }
        class.led += 1;
        let at = Place {
            presenter: id,
            led: class.led,
        };
        let sessions = lock(&self.sessions);
        for f in &class.followers {
            if let Some(tx) = sessions.get(f) {
                let _ = tx.send(In::Lead(lead, at));
            }
        }
    }
}
