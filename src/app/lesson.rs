//! A narrated lesson's part of the state: the caption over the scene, the prediction asked
//! and its answer, and whether the lesson holds for Enter. A lesson script sets them
//! (`say`, `ask`, `wait`; see `crate::lesson`), the keys answer and go on; the caption's words,
//! the verdict included, are a function of this state and the run on screen.

use super::state::App;
use crate::engine::Outcome;

/// What a lesson shows and awaits.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Lesson {
    /// The lesson's name, for the caption's title (None: a key script's own captions).
    pub name: Option<String>,
    pub caption: Option<crate::text::Clean>,
    pub question: Option<Question>,
    /// Held until Enter (interactive lessons only: headless, `wait` goes on).
    pub waiting: bool,
    /// Time was playing when the lesson came to its `wait`: the wait held it, and Enter
    /// plays it again.
    pub resume: bool,
    /// The lesson's script has run to its end.
    pub done: bool,
    /// Questions asked so far: which one is on screen (others' answers are to that one).
    pub asked: u32,
    /// Set by the shell that gathers others' answers to the question on screen (a served
    /// class's presenter): shown under the question.
    pub tally: Option<Tally>,
}

/// Others' answers to a question so far.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    pub yes: usize,
    pub no: usize,
    pub not_yet: usize,
}

impl std::fmt::Display for Tally {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "y {} · n {} · {} not yet",
            self.yes, self.no, self.not_yet
        )
    }
}

/// A prediction: yes means the run on screen escapes.
#[derive(Clone, Debug, PartialEq)]
pub struct Question {
    pub text: crate::text::Clean,
    pub answer: Option<bool>,
    /// The τ on screen when it was asked: unanswered, the run answers only once time has
    /// moved on from there (a run decided at once must not give the answer away).
    pub asked_at: f64,
    /// The user's own answer when they answer apart ([`App::apart`]); the keys' answer
    /// still moves the lesson on.
    pub own: Option<bool>,
}

/// What the lesson waits for from the keys now: their bindings in the lesson group take
/// these keys first (see [`super::keymap::lookup_when`]). Space is never the lesson's: it
/// plays and pauses at every moment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Prompt {
    None,
    /// y or n.
    Answer,
    /// Enter.
    GoOn,
}

/// What the lesson asks of the user ([`App::asked`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ask {
    /// A follower who answered: the presenter goes on.
    Answered,
    /// A follower to answer y or n.
    AnswerApart,
    Answer,
    /// A follower at a wait: the presenter goes on.
    GoOnApart,
    /// Enter goes on.
    GoOn,
    /// A follower at the lesson's end: the presenter closes it.
    EndApart,
    /// The lesson's end: Esc closes it.
    End,
    /// Nothing held: Space plays or pauses.
    Play,
}

/// The caption box's contents.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Caption {
    pub title: String,
    /// Paragraphs, separated by `\n`.
    pub text: String,
    /// What the keys do now, for the box's lower edge.
    pub prompt: Option<&'static str>,
}

impl Lesson {
    /// What the keys answer now: a question's y/n first, then a wait's Space/Enter.
    pub fn prompt(&self) -> Prompt {
        if self.question.as_ref().is_some_and(|q| q.answer.is_none()) {
            Prompt::Answer
        } else if self.waiting {
            Prompt::GoOn
        } else {
            Prompt::None
        }
    }

    /// Whether an interactive lesson holds here (an unanswered question or a wait).
    pub fn holds(&self) -> bool {
        self.prompt() != Prompt::None
    }
}

impl App {
    /// `say`: a caption over the scene until the next `say` or `ask` (None clears it), in
    /// place of any notice.
    pub fn say(&mut self, text: Option<crate::text::Clean>) {
        // The lesson's words supersede a notice (a preset's, which may tell the outcome).
        if text.is_some() {
            self.notice = None;
        }
        self.lesson.caption = text;
        self.lesson.question = None;
        self.lesson.tally = None;
        self.dirty = true;
    }

    /// `ask`: a prediction for the user to make, y or n; the run then answers it. A notice
    /// (a preset's words) may tell the outcome: it goes.
    pub fn ask(&mut self, text: crate::text::Clean) {
        self.lesson.caption = None;
        self.notice = None;
        self.lesson.question = Some(Question {
            text,
            answer: None,
            asked_at: self.now().tau,
            own: None,
        });
        self.lesson.asked = self.lesson.asked.wrapping_add(1);
        // Nobody has answered this one yet: the shell says who has.
        self.lesson.tally = None;
        self.dirty = true;
    }

    /// Whether the keys that move the lesson are not this screen's user's (a served class's
    /// follower, led by the presenter, as the shell told: [`App::tell_class`]): the user answers
    /// on their own, and the caption speaks to that answer ([`Question::own`]).
    pub fn apart(&self) -> bool {
        self.class == super::state::InClass::Following
    }

    /// The lesson's name, for the caption's title (the shell runs it).
    pub fn tell_lesson(&mut self, name: &str) {
        self.lesson.name = Some(name.to_string());
        self.dirty = true;
    }

    /// The shell's word that the lesson's script has run to its end.
    pub fn end_lesson(&mut self) {
        if !self.lesson.done {
            self.lesson.done = true;
            self.dirty = true;
        }
    }

    /// The user's own answer to the open question, when they answer apart (see
    /// [`App::apart`]); the first stands. Whether it was taken.
    pub fn answer_apart(&mut self, yes: bool) -> bool {
        let open = self.lesson.prompt() == Prompt::Answer;
        match self.lesson.question.as_mut() {
            Some(q) if open && q.own.is_none() => {
                q.own = Some(yes);
                self.dirty = true;
                true
            }
            _ => false,
        }
    }

    /// The shell's word on others' answers to the question on screen (None: it gathers none).
    pub fn tell_tally(&mut self, tally: Option<Tally>) {
        if self.lesson.tally != tally {
            self.lesson.tally = tally;
            self.dirty = true;
        }
    }

    /// `wait` in an interactive lesson: hold until Enter, and hold time with it (a preset
    /// left playing would move on while the class reads; Space still plays it). Enter takes
    /// time up as the wait found it.
    pub fn wait(&mut self) {
        self.lesson.waiting = true;
        self.lesson.resume = self.playing;
        self.playing = false;
        self.dirty = true;
    }

    /// `play [SPEED]`: time plays at 2^`power` (×1 when None), whatever it did before.
    pub fn play(&mut self, power: Option<i8>) {
        self.playing = true;
        self.view.step_mode = false;
        self.speed = f64::from(power.unwrap_or(0)).exp2();
        self.dirty = true;
    }

    /// `pause`: time stands still.
    pub fn pause(&mut self) {
        self.playing = false;
        self.dirty = true;
    }

    /// What the lesson asks of the user now, worded by the caption's title and by plain mode
    /// for their places. A user following a served class is asked only what is theirs to do:
    /// their own answer; Enter and Esc are the presenter's.
    pub fn asked(&self) -> Option<Ask> {
        let l = &self.lesson;
        let apart = self.apart();
        Some(match l.prompt() {
            Prompt::Answer if apart && l.question.as_ref().is_some_and(|q| q.own.is_some()) => {
                Ask::Answered
            }
            Prompt::Answer if apart => Ask::AnswerApart,
            Prompt::Answer => Ask::Answer,
            Prompt::GoOn if apart => Ask::GoOnApart,
            Prompt::GoOn => Ask::GoOn,
            Prompt::None if l.done && apart => Ask::EndApart,
            Prompt::None if l.done => Ask::End,
            Prompt::None if apart => return None,
            Prompt::None => Ask::Play,
        })
    }

    /// The caption box, when there is something to say.
    pub fn caption(&self) -> Option<Caption> {
        let l = &self.lesson;
        let text = match (&l.caption, &l.question) {
            (_, Some(q)) => {
                let mut text = q.text.to_string();
                if let Some(v) = self.verdict(q) {
                    text = format!("{text}\n{v}");
                }
                if let Some(t) = l.tally {
                    text = format!("{text}\nanswers: {t}");
                }
                text
            }
            (Some(c), None) => c.to_string(),
            (None, None) if l.done && l.name.is_some() => "End of the lesson.".into(),
            (None, None) if l.waiting => String::new(),
            (None, None) => return None,
        };
        // Which key pauses is said wherever the lesson is (it never moves the lesson on). What
        // y and n mean is said with them, however the question is worded ("will it stay?"
        // reads the other way).
        let prompt = self.asked().map(|ask| match (ask, self.playing) {
            (Ask::Answered, _) => "answered · the presenter goes on",
            (Ask::AnswerApart, _) => "y escapes · n stays",
            (Ask::GoOnApart, _) => "the presenter goes on",
            (Ask::EndApart, _) => "end · presenter closes it",
            (Ask::Answer, true) => "y escapes · n stays · Space pauses",
            (Ask::Answer, false) => "y escapes · n stays · Space plays",
            (Ask::GoOn, true) => "Enter: go on · Space pauses",
            (Ask::GoOn, false) => "Enter: go on · Space plays",
            (Ask::End, _) => "end · Esc closes · q quits",
            (Ask::Play, true) => "Space pauses",
            (Ask::Play, false) => "Space plays",
        });
        let title = l
            .name
            .as_ref()
            .map_or_else(|| "lesson".into(), |n| format!("lesson: {n}"));
        Some(Caption {
            title,
            text,
            prompt,
        })
    }

    /// Whether a prediction is open and nothing on screen may say how the run ends: asked,
    /// and the line under it does not yet say (see `App::verdict`).
    pub fn outcome_open(&self) -> bool {
        self.lesson.question.as_ref().is_some_and(|q| {
            self.sim().outcome_now() == Outcome::Running
                || (q.answer.is_none() && self.now().tau <= q.asked_at)
        })
    }

    /// The line under a prediction: what was said while the run on screen is undecided, then
    /// whether it was right and how the run ended.
    fn verdict(&self, q: &Question) -> Option<String> {
        // Answering apart, the user's own answer is the one spoken to (none: the run's word).
        let answer = if self.apart() { q.own } else { q.answer };
        if answer.is_none() && self.now().tau <= q.asked_at {
            return None;
        }
        let said = |yes: bool| {
            if yes {
                "it escapes"
            } else {
                "it does not escape"
            }
        };
        // Answering apart, the run's word waits for the keys' (the others may not have
        // answered yet: the outcome is not given away).
        if self.apart() && q.answer.is_none() && self.now().tau <= q.asked_at {
            return answer.map(|a| format!("You said {}.", said(a)));
        }
        let escaped = match self.sim().outcome_now() {
            Outcome::Running => {
                return answer.map(|a| format!("You said {}. Watch the run.", said(a)));
            }
            o => o == Outcome::Escaped,
        };
        let ending = self.ending();
        Some(match answer {
            None => format!("The run: it {ending}."),
            Some(a) if a == escaped => format!("Right: it {ending}."),
            Some(a) => format!("Not so: you said {}, but it {ending}.", said(a)),
        })
    }
}
