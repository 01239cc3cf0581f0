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
pub const LESSONS: [Lesson; 6] = [
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
    Lesson {
        name: "forces",
        about: "finite-time stops, Stokes drag, forces by frame, v_e >= 1 - xi0 (Sec. II)",
        script: include_str!("lessons/forces.keys"),
    },
    Lesson {
        name: "slow",
        about: "slow on the table and in the lab (Figs. 1-2, Sec. III); properties 3-4",
        script: include_str!("lessons/slow.keys"),
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
/// `Explorer::pump_lesson`).
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

/// What a teacher should know of a lesson before class (`turntable lesson --check`): the
/// authoring traps a run in front of a class finds too late, each with its line.
#[derive(Debug, Default, PartialEq)]
pub struct Check {
    pub captions: usize,
    pub questions: usize,
    pub waits: usize,
    /// Seconds of `tick N` at the explorer's rate, holds not counted.
    pub seconds: f64,
    /// `line N: …`, in script order.
    pub findings: Vec<String>,
}

/// Ticks a verdict stays on screen before a caption may replace it (3 s).
const READ_TICKS: u64 = 3 * crate::app::TICKS_PER_SECOND as u64;

/// Reads `script` as an interactive lesson runs it: where it holds (a `wait` holds time too),
/// and where a caption replaces a verdict before it can be read.
pub fn check(script: &str) -> Result<Check, crate::script::ParseError> {
    // Parsed whole first: a script that does not parse is refused as `replay` refuses it.
    crate::script::parse(script)?;
    let mut c = Check::default();
    // The last question not yet followed by a `wait`, and the ticks played since.
    let mut open_question = None;
    for (index, line) in script.lines().enumerate() {
        let n = index + 1;
        for step in crate::script::parse(line)? {
            match step {
                Step::Tick(t) => {
                    c.seconds += t as f64 / f64::from(crate::app::TICKS_PER_SECOND);
                    if let Some((_, since)) = open_question.as_mut() {
                        *since += t;
                    }
                }
                Step::Wait => {
                    c.waits += 1;
                    open_question = None;
                }
                Step::Say(text) => {
                    c.captions += usize::from(text.is_some());
                    if let Some((q, _)) = open_question.take().filter(|(_, t)| *t < READ_TICKS) {
                        c.findings.push(format!(
                            "line {n}: this say replaces the question of line {q} as soon as it is answered: its verdict is not read (a `wait` between holds it)"
                        ));
                    }
                }
                Step::Ask(_) => {
                    c.questions += 1;
                    if let Some((q, _)) = open_question
                        .replace((n, 0))
                        .filter(|(_, t)| *t < READ_TICKS)
                    {
                        c.findings.push(format!(
                            "line {n}: this question replaces the one of line {q} as soon as it is answered: its verdict is not read (a `wait` between holds it)"
                        ));
                    }
                }
                _ => {}
            }
        }
    }
    if c.waits + c.questions == 0 {
        c.findings.push(format!(
            "the lesson never holds (no wait, no ask): in the explorer it runs to its end in {:.0} s",
            c.seconds
        ));
    }
    Ok(c)
}

impl std::fmt::Display for Check {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "{}, {}, {}; {:.0} s of play between the holds",
            crate::present::count(self.captions, "caption"),
            crate::present::count(self.questions, "question"),
            crate::present::count(self.waits, "wait"),
            self.seconds
        )?;
        if self.findings.is_empty() {
            return writeln!(f, "nothing to warn of");
        }
        self.findings.iter().try_for_each(|l| writeln!(f, "{l}"))
    }
}
