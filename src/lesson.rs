//! Narrated lessons: key scripts that walk through the paper with captions (`say`),
//! predictions (`ask`) and pauses (`wait`), shipped inside the binary. `turntable lesson NAME`
//! runs one in the explorer; `--headless` prints its snapshots as `replay` does.

use crate::script::Step;

/// A lesson: its name, one line on what it covers, and its key script.
#[derive(Clone, Copy, Debug)]
pub struct Lesson {
    pub name: &'static str,
    pub about: &'static str,
    pub script: &'static str,
}

/// The lessons, in the order they are best taken.
pub const LESSONS: [Lesson; 4] = [
    Lesson {
        name: "stick",
        about: "the stick condition and R_max (Sec. II)",
        script: include_str!("lessons/stick.keys"),
    },
    Lesson {
        name: "cases",
        about: "Figs. 3-4, cases A-D, and why the paper's RK2 lets C escape (Sec. IV)",
        script: include_str!("lessons/cases.keys"),
    },
    Lesson {
        name: "escape",
        about: "the escape speed, its window beyond R_max, and xi0c (Figs. 5-6)",
        script: include_str!("lessons/escape.keys"),
    },
    Lesson {
        name: "spin",
        about: "the table spun up until the coin slides: mu read from the slip (Sec. IV)",
        script: include_str!("lessons/spin.keys"),
    },
];

/// The lesson named `name` (case ignored).
pub fn find(name: &str) -> Option<Lesson> {
    LESSONS
        .into_iter()
        .find(|l| l.name.eq_ignore_ascii_case(name))
}

/// The lessons' names, for messages.
pub fn names() -> String {
    LESSONS.map(|l| l.name).join(", ")
}

/// An interactive lesson's place in its script: the session feeds it in as time passes (see
/// `Session::pump_lesson`).
/// Cloned cheaply (its steps are shared): a served class hands each follower the presenter's.
#[derive(Clone, Debug)]
pub struct Driver {
    name: String,
    steps: std::sync::Arc<[Step]>,
    at: usize,
    /// Ticks still to pass for the current `tick N`.
    ticks: u64,
    /// Whether the script's own last word on time was `play` (not `pause`): then a `tick N`
    /// waits for N ticks of play, and a pause from the keys holds the lesson there.
    plays: bool,
}

impl Driver {
    pub fn new(name: &str, steps: Vec<Step>) -> Driver {
        Driver {
            name: name.to_string(),
            steps: steps.into(),
            at: 0,
            ticks: 0,
            plays: true,
        }
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    /// The next step (a `tick N` still counting is given up).
    pub fn next_step(&mut self) -> Option<Step> {
        self.ticks = 0;
        let step = self.steps.get(self.at).cloned();
        self.at += usize::from(step.is_some());
        match step {
            Some(Step::Play(_)) => self.plays = true,
            Some(Step::Pause) => self.plays = false,
            _ => {}
        }
        step
    }

    /// How many of the script's steps have been taken.
    pub fn taken(&self) -> usize {
        self.at
    }

    /// Whether the script's own last word on time was to play.
    pub fn plays(&self) -> bool {
        self.plays
    }

    /// A `tick N`: the next `n` ticks are the lesson's.
    pub fn count(&mut self, n: u64) {
        self.ticks = n;
    }

    /// Whether a `tick N` is still counting.
    pub fn counting(&self) -> bool {
        self.ticks > 0
    }

    /// One tick passed.
    pub fn ticked(&mut self) {
        self.ticks = self.ticks.saturating_sub(1);
    }
}
