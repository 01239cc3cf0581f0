//! An interactive lesson fed into the session as time passes: its steps applied up to where
//! it holds, a click's action handed back for a class's followers.

use super::Explorer;
use crate::app::Action;
use crate::script::Step;
use ratatui::backend::Backend;

/// What a pump of the lesson did: whether it moved, and what a click it ended on made.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pumped {
    pub moved: bool,
    pub act: Option<Action>,
}

impl<B: Backend> Explorer<B> {
    /// Applies the lesson's steps that are due: all of them up to a `tick N` still counting
    /// (it counts the session's ticks of play: a pause from the keys holds it, and after the
    /// script's own `pause` it ends at once, as in a replay), a `wait` or an unanswered `ask`
    /// (until the keys answer; the loop and the clock go on meanwhile), or the end. `resize`
    /// and `snapshot` mean nothing here. A `mouse` step ends the pump there: what its click
    /// did is handed back, for a class's followers to apply in its place (a click lands where
    /// each screen's own layout puts it). Says whether it moved (took a step, or ended): a
    /// pump that did not changed nothing, so a follower need only do the ones that did.
    pub fn pump_lesson(&mut self) -> Result<Pumped, B::Error> {
        self.pump_with(true)
    }

    /// [`Explorer::pump_lesson`] for a class's follower, whose lesson moves with the
    /// presenter's: its `mouse` steps are skipped, the presenter's click coming as the action
    /// it made, right after this pump.
    pub fn follow_lesson(&mut self) -> Result<Pumped, B::Error> {
        self.pump_with(false)
    }

    fn pump_with(&mut self, own_clicks: bool) -> Result<Pumped, B::Error> {
        let Some(mut d) = self.lesson.take() else {
            return Ok(Pumped::default());
        };
        let (at, done) = (d.taken(), self.app.lesson().done);
        let result = self.feed(&mut d, own_clicks);
        let moved = d.taken() != at || self.app.lesson().done != done;
        self.lesson = Some(d);
        result.map(|act| Pumped { moved, act })
    }

    fn feed(
        &mut self,
        d: &mut crate::lesson::Driver,
        own_clicks: bool,
    ) -> Result<Option<Action>, B::Error> {
        while !(self.app.lesson().holds() || self.app.should_quit()) {
            if d.counting() && (d.plays() || self.app.playing()) {
                return Ok(None);
            }
            let Some(step) = d.next_step() else {
                self.app.end_lesson();
                return Ok(None);
            };
            match step {
                Step::Tick(n) => d.count(n),
                Step::Wait => self.app.wait(),
                Step::Mouse(m) if own_clicks => return self.mouse(m),
                Step::Mouse(_) => return Ok(None),
                Step::Resize(..) | Step::Snapshot(_) => {}
                Step::Key(k) => self.press(k),
                Step::Say(t) => self.app.say(t),
                Step::Ask(t) => self.app.ask(t),
                Step::Play(p) => self.app.play(p),
                Step::Pause => self.app.pause(),
            }
        }
        Ok(None)
    }
}
