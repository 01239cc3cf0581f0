//! Plain mode (`--plain`): the explorer's state described in lines of text for a screen
//! reader, not drawn. Another renderer of the same [`App`]: [`Seen::of`] reads what a listener
//! needs from the state, and [`Seen::news`] says in words what changed since it last looked —
//! the release, each change of state as the run on screen reaches it, notices, the help, and
//! the readouts when asked (`I`). Pure: the same keys and ticks give the same lines.

use crate::app::App;
use crate::app::lesson::Ask;
use crate::app::pages::Page;
use crate::engine::{Frame, Outcome, Release, Status};
use crate::present::{num, speed};
use crate::sim::Sim;
use crate::theme::Theme;

/// What plain mode says about an [`App`], compared from one moment to the next.
#[derive(Clone, Debug, PartialEq)]
pub struct Seen {
    release: String,
    /// At τ = 0 with nothing played yet (a restart shows as a return to this).
    fresh: bool,
    status: String,
    /// The body's events the τ on screen has reached, in words (see [`body_events`]).
    body: Vec<String>,
    /// The paper's comparison run's status, while comparing.
    paper: Option<String>,
    tau: f64,
    playing: bool,
    speed: f64,
    frame: Frame,
    /// Both frames drawn (`%`): plain mode says so, its readouts stay in `frame`.
    split: bool,
    forces: bool,
    page: Page,
    /// The analysis page's data in words once computed, and its verdict on the release
    /// (`ui::pages::summary`).
    summary: Option<(String, Option<String>)>,
    help: bool,
    notice: Option<String>,
    typing: Option<crate::app::prompt::Prompt>,
    caption: Option<String>,
    prompt: Option<&'static str>,
    readouts_asked: u64,
    readouts: Vec<String>,
}

impl Seen {
    pub fn of(app: &App) -> Seen {
        let caption = app.caption();
        Seen {
            release: release(app),
            fresh: app.sim().samples.len() == 1 && app.sim().cursor == 0,
            status: status(app.sim()),
            body: body_events(app),
            paper: app.paper().map(status),
            tau: app.now().tau,
            playing: app.playing(),
            speed: app.speed(),
            frame: app.view().frame,
            split: app.view().split,
            forces: app.view().forces,
            page: app.view().page,
            summary: super::pages::summary(app),
            help: app.view().help,
            notice: app.notice().clone(),
            typing: app.prompt().clone(),
            caption: caption.as_ref().map(|c| c.text.clone()),
            // Said only where a lesson runs (a scene's caption alone asks nothing).
            prompt: app.asked().and_then(|ask| match ask {
                Ask::Answered => Some("answered; the presenter goes on"),
                Ask::AnswerApart => Some("answer y if it escapes, n if it stays"),
                Ask::Answer => Some("answer y or n"),
                Ask::GoOnApart => Some("the presenter goes on"),
                Ask::GoOn => Some("Enter goes on (Space plays and pauses)"),
                _ if app.lesson().name.is_none() => None,
                Ask::EndApart => Some("end of the lesson"),
                Ask::End => Some("end of the lesson; Esc closes it, q quits"),
                Ask::Play => None,
            }),
            readouts_asked: app.readouts_asked(),
            readouts: readouts(app),
        }
    }
}

impl Seen {
    /// What changed since this was seen, and the app as it is now seen: the terminal's, a
    /// served student's and a replay's plain mode each say it as it comes.
    pub fn news(&mut self, app: &App) -> Vec<String> {
        let now = Seen::of(app);
        let lines = describe(self, &now);
        *self = now;
        lines
    }
}

/// The first lines: how to use plain mode, the scene, its release and how the run stands.
pub fn opening(app: &App) -> Vec<String> {
    let now = Seen::of(app);
    let mut out = vec![
        "turntable, plain mode: ? lists the keys, I reads the readouts, Space plays and pauses, q quits".to_string(),
        format!("scene {}: {}", app.scene().name, app.scene().about),
        now.release.clone(),
        now.status.clone(),
    ];
    out.extend(now.body.iter().cloned());
    out.extend(now.paper.iter().map(|p| format!("paper's RK2: {p}")));
    out.extend(now.caption.iter().flat_map(|c| c.lines().map(String::from)));
    out.extend(now.prompt.map(String::from));
    out
}

/// What changed from `was` to `now`, in lines (none when nothing a listener needs changed:
/// time playing on says nothing until the run's state changes).
fn describe(was: &Seen, now: &Seen) -> Vec<String> {
    let mut out = Vec::new();
    run_changes(was, now, &mut out);
    view_changes(was, now, &mut out);
    prompt_changes(was, now, &mut out);
    out
}

/// The run's changes: a release or a restart, play and pause, its status, the body's events
/// and the paper's run beside it.
fn run_changes(was: &Seen, now: &Seen, out: &mut Vec<String>) {
    let tau = num(now.tau, 3);
    let released = now.release != was.release;
    let restarted = released || (now.fresh && !was.fresh);
    if released {
        out.push(now.release.clone());
    } else if restarted {
        out.push("restart at τ = 0".into());
    }
    if now.playing != was.playing {
        out.push(if now.playing {
            format!("playing from τ = {tau}")
        } else {
            format!("paused at τ = {tau}")
        });
    } else if !now.playing && !restarted && now.tau != was.tau {
        // Stepped while paused: where it stands now.
        out.push(format!("τ = {tau}"));
    }
    if restarted || now.status != was.status {
        out.push(now.status.clone());
    }
    // The body's events, each once as the τ on screen reaches it (all again on a restart or a
    // new release; none on a step back).
    let body_new = match now.body.strip_prefix(was.body.as_slice()) {
        _ if restarted => &now.body[..],
        Some(tail) => tail,
        None if was.body.starts_with(&now.body) => &[],
        None => &now.body[..],
    };
    out.extend(body_new.iter().cloned());
    match (&was.paper, &now.paper) {
        (None, Some(p)) => {
            out.push("compare on: the paper's RK2 (rk2-raw, dt = 1e-3, no stick event) from the same release".into());
            out.push(format!("paper's RK2: {p}"));
        }
        (Some(_), None) => out.push("compare off".into()),
        (Some(a), Some(b)) if a != b || restarted => out.push(format!("paper's RK2: {b}")),
        _ => {}
    }
}

/// The view's changes: speed, frame, arrows, page (and its summary), help.
fn view_changes(was: &Seen, now: &Seen, out: &mut Vec<String>) {
    if now.speed != was.speed {
        out.push(format!("speed ×{}", crate::present::fmt_speed(now.speed)));
    }
    if now.frame != was.frame {
        out.push(match now.frame {
            Frame::Lab => "frame: lab".into(),
            Frame::Table => "frame: rotating (readouts in the table frame)".into(),
        });
    }
    if now.split != was.split {
        out.push(
            if now.split {
                "both frames drawn side by side, lab and rotating; the readouts stay in this frame"
            } else {
                "one frame drawn"
            }
            .into(),
        );
    }
    if now.forces != was.forces {
        out.push(if now.forces {
            "forces on: the readouts name them".into()
        } else {
            "forces off".into()
        });
    }
    if now.page != was.page {
        out.push(format!(
            "page: {} (drawn in the explorer only; the readouts stay{})",
            now.page.title(),
            if super::pages::summarized(now.page) {
                "; its numbers follow once computed"
            } else {
                ""
            }
        ));
    }
    if let Some((page, verdict)) = &now.summary {
        let (was_page, was_verdict) = was.summary.clone().unzip();
        if was_page.as_ref() != Some(page) {
            out.push(page.clone());
        }
        if let Some(v) = verdict
            && was_verdict.flatten().as_ref() != Some(v)
        {
            out.push(v.clone());
        }
    }
    if now.help != was.help {
        if now.help {
            out.extend(help());
        } else {
            out.push("help closed".into());
        }
    }
}

/// The words asked for or shown: naming a scene, the readouts, a notice, a lesson's caption,
/// a prompt.
fn prompt_changes(was: &Seen, now: &Seen, out: &mut Vec<String>) {
    let tau = num(now.tau, 3);
    match (&was.typing, &now.typing) {
        (None, Some(p)) => out.push(p.asking().into()),
        (Some(a), Some(b)) if a.refused != b.refused && b.refused.is_some() => out.push(format!(
            "refused: {}",
            b.refused.clone().unwrap_or_default()
        )),
        (Some(a), Some(b)) if a.typed != b.typed => out.push(format!("{}: {}", b.what(), b.typed)),
        _ => {}
    }
    if now.readouts_asked != was.readouts_asked {
        // Asked for: every readout, not the one-line notice the explorer shows.
        out.push(format!("readouts at τ = {tau}:"));
        out.extend(now.readouts.iter().cloned());
    } else if now.notice != was.notice
        && let Some(n) = &now.notice
    {
        // Said whole: a line is not cut to a width (its shorter wordings are for a screen).
        out.push(
            n.split(crate::present::OR)
                .next()
                .unwrap_or_default()
                .into(),
        );
    }
    if now.caption != was.caption
        && let Some(c) = &now.caption
    {
        // A verdict added or changed under a question: only the lines that are new (the
        // question is not read again when "You said it escapes." becomes the run's word).
        let same = was.caption.as_deref().map_or(0, |w| {
            w.lines().zip(c.lines()).take_while(|(a, b)| a == b).count()
        });
        out.extend(
            c.lines()
                .skip(same)
                .filter(|l| !l.trim().is_empty())
                .map(String::from),
        );
    }
    if now.prompt != was.prompt
        && let Some(p) = now.prompt
    {
        out.push(p.into());
    }
}

/// The release in words: scene, ξ0, φ, v0, how it is released, the method.
fn release(app: &App) -> String {
    let i = &app.initial();
    let edited = if app.edited() { " (edited)" } else { "" };
    let start = match i.release {
        Release::Velocity => format!(
            "ξ0 = {}, φ = {}, v0 = {} relative to the table",
            num(i.xi0, 3),
            crate::present::angle(i.phi),
            speed(i.v0)
        ),
        Release::TableRest => format!("ξ0 = {}, at rest on the table", num(i.xi0, 3)),
        Release::LabRest => format!("ξ0 = {}, at rest in the lab", num(i.xi0, 3)),
    };
    let how = if i.frictionless {
        "μ = 0, in closed form".to_string()
    } else if let Some(gamma) = app.settings().stokes() {
        format!("Stokes drag γ = {}, in closed form", num(gamma, 4))
    } else {
        let hold = app.settings().hold();
        let hold = if hold != 1.0 {
            format!(", μs/μk = {}", num(hold, 4))
        } else {
            String::new()
        };
        format!(
            "method {} {}{hold}",
            app.settings().method(),
            crate::present::accuracy(&app.settings())
        )
    };
    format!(
        "release: scene {}{edited}, {start}; {how}",
        app.scene().name
    )
}

/// How a run stands at the τ on screen, in words.
fn status(sim: &Sim) -> String {
    if sim.error.is_some() {
        return "stopped: step budget or underflow".into();
    }
    let text = match sim.outcome_now() {
        Outcome::Running if sim.motion().riding(&sim.now()) => return "riding the table".into(),
        Outcome::Running if sim.steady().is_none() => return "sliding".into(),
        Outcome::Running => return "slipping".into(),
        Outcome::Stuck => match sim.status() {
            Status::Stuck { tau, q } => {
                format!("stuck at ξ = {} (τ = {})", num(q.length(), 4), num(tau, 3))
            }
            Status::Slipping => "stuck".into(),
        },
        Outcome::Escaped => match sim.escape() {
            Some(e) => format!("escaped (certified at τ = {})", num(e.tau, 3)),
            None => "escaped".into(),
        },
    };
    match super::panel::doubt_words(sim) {
        Some([a, b]) => format!("{text}, {a} {b}"),
        None => text,
    }
}

/// What the body has done by the τ on screen, in words, one event a line in order of τ: each
/// start of a pivot about a stuck contact (where that contact is), its rest on the table
/// (where its centre rides) and its escape's certificate. Read off its track (the numbers are
/// the track's); empty without one.
fn body_events(app: &App) -> Vec<String> {
    use crate::engine::rod::Phase;
    let Some(rod) = app.rod() else {
        return Vec::new();
    };
    let tau = app.now().tau;
    let n = rod.states.partition_point(|s| s.tau <= tau);
    let mut events: Vec<(f64, String)> = Vec::new();
    let mut before = None;
    for (s, p) in rod.states[..n].iter().zip(&rod.phases) {
        match (before, *p) {
            (Some(Phase::Pivot { .. }), Phase::Pivot { .. }) | (Some(Phase::Rest), Phase::Rest) => {
            }
            (_, Phase::Pivot { anchor, .. }) => events.push((
                s.tau,
                format!(
                    "the body pivots about a stuck contact at ξ = {}, τ = {}",
                    num(anchor.length(), 5),
                    num(s.tau, 3)
                ),
            )),
            (_, Phase::Rest) => events.push((
                s.tau,
                format!(
                    "the body rests at ξ = {}, τ = {}",
                    num(s.q.length(), 5),
                    num(s.tau, 3)
                ),
            )),
            (_, Phase::Slip) => {}
        }
        before = Some(*p);
    }
    if let Some(c) = rod.escape.filter(|c| *c <= tau) {
        let at = events.partition_point(|(t, _)| *t <= c);
        events.insert(
            at,
            (
                c,
                format!("the body escapes (certified at τ = {})", num(c, 3)),
            ),
        );
    }
    events.into_iter().map(|(_, e)| e).collect()
}

/// The readout panel's lines as text, one readout a line: a status the panel wraps under
/// itself (a single indented span) is joined back into one line.
fn readouts(app: &App) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    // Words only: any theme's colours are dropped.
    let th = Theme::builtin("mono").expect("mono is built in");
    for l in crate::ui::panel::lines(app, &th) {
        let text: String = l.spans.iter().map(|s| s.content.as_ref()).collect();
        let wrapped = l.spans.len() == 1 && text.starts_with("  ");
        // The panel pads keys into a column: one blank is enough to hear.
        let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
        match out.last_mut() {
            _ if text.is_empty() => {}
            Some(last) if wrapped => {
                last.push(' ');
                last.push_str(&text);
            }
            _ => out.push(text),
        }
    }
    out
}

/// The help as lines: every key of the keymap by group, as the explorer's `?` lists them.
fn help() -> Vec<String> {
    let mut out = vec!["keys (? again closes this list):".to_string()];
    for (group, rows) in crate::ui::help::rows() {
        if rows.is_empty() {
            continue;
        }
        out.push(format!("{group}:"));
        out.extend(
            rows.into_iter()
                .map(|(keys, help)| format!("  {keys}: {help}")),
        );
    }
    out
}

/// The explorer's one-line answer to `I`: τ, ξ and how the run stands, and in a body scene
/// the body's phase and centre.
pub fn summary(app: &App) -> String {
    let s = app.now();
    let mut out = format!(
        "τ = {}, ξ = {}, |u| = {}: {}",
        num(s.tau, 3),
        num(s.xi(), 5),
        num(app.sim().motion().u_lab(&s).length(), 4),
        status(app.sim())
    );
    if let Some(b) = body(app) {
        out.push_str(&format!("; {b}"));
    }
    out
}

/// The body at the τ on screen in a few words: its centre's radius (one word to a line cut
/// short, joined by no-break spaces: kept or dropped whole, never `ξ =` without the number),
/// then sliding, pivoting or at rest; or how its track ended. None without a body's track.
fn body(app: &App) -> Option<String> {
    use crate::engine::rod::Phase;
    use crate::ui::panel::{body_end, body_now};
    let rod = app.rod()?;
    let tau = app.now().tau;
    let now = body_now(rod, tau)?;
    Some(match now.at {
        Some((st, ph)) => format!(
            "body\u{a0}ξ\u{a0}=\u{a0}{} {}",
            num(st.q.length(), 5),
            match ph {
                Phase::Slip => "sliding",
                Phase::Pivot { .. } => "pivoting",
                Phase::Rest => "at rest",
            }
        ),
        None => match body_end(rod, tau) {
            Some((end, Some(why))) => format!("body {end} ({why})"),
            Some((end, None)) => format!("body {end}"),
            None => "body not computed here".into(),
        },
    })
}
