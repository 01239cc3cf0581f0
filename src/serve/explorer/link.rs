//! A client's explorer as the one loop sees it (`terminal::drive`'s `Link`): its turns, its
//! clock or the presenter's, and a frame when the channel is free and the pace allows.

use super::super::frames::Key;
use super::*;

impl Link<Screen> for Remote<'_> {
    fn turn(&mut self, _s: &mut Explorer<Screen>) -> io::Result<Turn> {
        let limits = self.shared.limits;
        let now = Instant::now();
        if self.in_flight.is_some_and(|t| now - t > limits.stall) {
            return Ok(Turn::Stop(
                "your connection stopped taking the screen".into(),
            ));
        }
        // Following the class is attending it: a student who watches and types nothing for
        // the idle time is not idle.
        if self.following {
            self.last_input = now;
        }
        if now - self.last_input > limits.idle {
            return Ok(Turn::Stop(format!(
                "idle for {} s: closed",
                limits.idle.as_secs()
            )));
        }
        Ok(Turn::Go)
    }

    /// A follower's time and lesson move only when the presenter's do (`Lead::Tick`,
    /// `Lead::Lesson`).
    fn own_time(&self) -> bool {
        !self.following
    }

    fn ticked(&mut self, _s: &mut Explorer<Screen>) {
        self.shared.lead(self.id, Lead::Tick);
    }

    /// If the lesson moved, the followers' lessons move alike (a question it asked takes
    /// answers before any follower can see it).
    fn pumped(&mut self, s: &mut Explorer<Screen>, pumped: Pumped) -> io::Result<()> {
        if pumped.moved {
            self.tally(s);
            self.shared.lead(self.id, Lead::Lesson);
        }
        // A click the lesson made, in the model's terms: in the same place for every follower.
        if let Some(action) = pumped.act {
            self.shared.lead(self.id, Lead::Act(action));
        }
        Ok(())
    }

    /// The channel has taken the last frame (in plain mode no frame is drawn: its lines are
    /// said at every turn, see `show`).
    fn free(&self) -> bool {
        self.in_flight.is_none() && self.plain.is_none()
    }

    /// The explorer's rate for a frame that answers input, a slower one for a picture only
    /// time moves while the server's cores cannot draw it that often for every session.
    fn gap(&self) -> Duration {
        if self.answering || self.resized {
            Duration::from_secs(1) / FPS
        } else {
            self.still_gap
        }
    }

    fn pending(&self) -> bool {
        self.resized
    }

    fn show(&mut self, s: &mut Explorer<Screen>, draw: bool) -> io::Result<bool> {
        self.tally(s);
        self.mouse_capture(s)?;
        if self.in_flight.is_some() {
            return Ok(false);
        }
        if self.plain.is_some() {
            if self.resized {
                self.resize(s);
            }
            self.shared.gate.run(|| s.sync_analysis());
            self.say_plain(s)?;
        }
        if draw && self.resized {
            self.resize(s);
        }
        let draw = draw && s.app.needs_redraw();
        if draw {
            // The analysis pages are computed through the gate (as many at once as cores);
            // the frame itself is drawn outside it.
            self.shared.gate.run(|| s.sync_analysis());
            let cpu = thread_cpu();
            queue!(s.term.backend_mut(), BeginSynchronizedUpdate)?;
            // A follower at a known place shares the frame with the others there.
            let key = self
                .at
                .filter(|_| self.following)
                .and_then(|at| Key::of(at, &s.app, &s.theme));
            match key {
                Some(key) => {
                    if s.draw_sharing(&self.shared.frames.at(&key))? {
                        self.shared.counts.shared.fetch_add(1, Ordering::Relaxed);
                    }
                }
                None => s.draw()?,
            }
            queue!(s.term.backend_mut(), EndSynchronizedUpdate)?;
            let pace = &self.shared.pace;
            pace.drew(thread_cpu().saturating_sub(cpu));
            self.answering = false;
            self.still_gap = pace.gap(self.shared.sessions(), Duration::from_secs(1) / FPS);
            self.shared.counts.frames.fetch_add(1, Ordering::Relaxed);
        }
        if let Some(bytes) = s.term.backend_mut().take(&mut self.spare)
            && self.out.frame(bytes)
        {
            self.in_flight = Some(Instant::now());
        }
        Ok(draw)
    }

    fn deadline(&self) -> Option<Instant> {
        self.keys.deadline()
    }

    fn wait(&mut self, s: &mut Explorer<Screen>, wake: Instant) -> io::Result<Waited> {
        match self
            .inbox
            .recv_timeout(wake.saturating_duration_since(Instant::now()))
        {
            Ok(msg) => self.receive(s, msg),
            Err(RecvTimeoutError::Timeout) => {
                self.keys.expire(Instant::now());
                Ok(Waited::Events(self.keys.events()))
            }
            Err(RecvTimeoutError::Disconnected) => Ok(Waited::Stop(String::new())),
        }
    }

    fn apply(&mut self, s: &mut Explorer<Screen>, ev: Event) -> io::Result<bool> {
        self.event(s, ev)?;
        Ok(false)
    }
}
