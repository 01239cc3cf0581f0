//! Key scripts run headlessly: the real [`App`] update and [`crate::ui::draw`] code on an
//! off-screen `TestBackend` through the same [`Explorer`] as the interactive loop, with each
//! `snapshot` written out as it is taken, as plain text or ANSI-styled text.
//!
//! Nothing here reads the clock or the environment: the same script gives byte-identical
//! output on every run and machine.

use crate::app::{App, Effect, Effects};
use crate::asciicast::Cast;
use crate::script::Step;
use crate::session::Explorer;
use crate::ui::export::{ansi_text, plain_text};
use ratatui::backend::TestBackend;

/// Size of the off-screen terminal unless the script or `--size` says otherwise.
pub const DEFAULT_SIZE: (u16, u16) = (80, 24);

/// Most bytes `turntable replay` writes on stdout (snapshots, or plain mode's lines): a script
/// of 1 MiB can ask for far more (each `snapshot` of a 1000x1000 screen is megabytes).
pub const OUTPUT_MAX: u64 = 256 << 20;

/// Most bytes of an `--asciicast` recording (see [`crate::asciicast::MAX_FRAMES`] for its
/// frames).
pub const CAST_BYTES_MAX: u64 = 256 << 20;

/// How to run a script.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Options {
    /// Initial terminal size (a `resize` step changes it).
    pub size: (u16, u16),
    /// Style snapshots with ANSI SGR sequences from each cell's colours and modifiers.
    pub ansi: bool,
    /// Plain mode: the lines `--plain` prints, not screens (a snapshot reads the readouts).
    pub plain: bool,
    /// How the screens are drawn.
    pub theme: crate::theme::Theme,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            size: DEFAULT_SIZE,
            ansi: false,
            plain: false,
            theme: crate::theme::Theme::builtin("dark").expect("dark is built in"),
        }
    }
}

/// Runs `steps` against `app` and returns the snapshots, each after a header line
/// `--- snapshot N: LABEL (WxH, tau=T)`. A quit stops the script there; a script without
/// any snapshot gets one of its final screen.
pub fn replay(app: App, steps: &[Step], opts: &Options) -> String {
    let mut out = Vec::new();
    replay_to(app, steps, opts, &mut out).expect("writing to memory cannot fail");
    String::from_utf8(out).expect("screens are UTF-8")
}

/// Runs `steps` as [`replay`] does, writing each snapshot to `out` as it is taken, so that
/// memory stays bounded however many there are.
pub fn replay_to(
    app: App,
    steps: &[Step],
    opts: &Options,
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    run(app, steps, opts, out, None)
}

/// Runs `steps` as [`replay_to`] does and records them as an asciicast v2 (see
/// [`crate::asciicast`]) to `cast`: a frame after each key, tick, resize or mouse event that
/// changed the screen, timed by the ticks passed; the same screens into `film` if given.
pub fn replay_cast(
    app: App,
    steps: &[Step],
    opts: &Options,
    out: &mut dyn std::io::Write,
    cast: &mut dyn std::io::Write,
    title: &str,
    film: Option<&mut crate::film::Film>,
) -> std::io::Result<()> {
    let mut cast = Cast::new(cast, opts.size.0, opts.size.1, title)?.filming(film);
    run(app, steps, opts, out, Some(&mut cast))
}

fn run(
    app: App,
    steps: &[Step],
    opts: &Options,
    out: &mut dyn std::io::Write,
    mut cast: Option<&mut Cast>,
) -> std::io::Result<()> {
    if opts.plain {
        return plain(app, steps, opts, out);
    }
    let mut s = Explorer::headless(app, opts.theme.clone(), opts.size.0, opts.size.1, false);
    s.carry_with(Answer);
    let mut shots = 0;
    // Ticks passed: the recording's clock.
    let mut ticks = 0;
    if let Some(c) = cast.as_deref_mut() {
        c.frame(ticks, s.screen())?;
    }
    for step in steps {
        if s.app.should_quit() {
            break;
        }
        match (step, cast.as_deref_mut()) {
            (Step::Snapshot(label), c) => {
                shots += 1;
                snapshot(&mut s, out, shots, label.as_deref(), opts.ansi)?;
                if let Some(c) = c {
                    c.marker(ticks, label.as_deref().unwrap_or(""))?;
                    c.frame(ticks, s.screen())?;
                }
            }
            (Step::Tick(n), Some(c)) => tick_frames(&mut s, *n, &mut ticks, c)?,
            (step, c) => {
                s.apply(step);
                if let Some(c) = c {
                    if let Step::Resize(w, h) = step {
                        c.resize(ticks, *w, *h)?;
                    }
                    c.frame(ticks, s.screen())?;
                    c.hold(hold_after(step));
                }
            }
        }
    }
    if shots == 0 {
        snapshot(&mut s, out, 1, Some("final"), opts.ansi)?;
    }
    if let Some(c) = cast {
        c.frame(ticks, s.screen())?;
    }
    out.flush()
}

/// `n` ticks recorded tick by tick, a frame each, as the explorer draws them (while it plays);
/// `ticks` counts them, the recording's clock.
pub(crate) fn tick_frames(
    s: &mut Explorer<TestBackend>,
    n: u64,
    ticks: &mut u64,
    c: &mut Cast,
) -> std::io::Result<()> {
    for _ in 0..n {
        if !s.is_playing() {
            break;
        }
        s.apply(&Step::Tick(1));
        *ticks += 1;
        c.frame(*ticks, s.screen())?;
    }
    Ok(())
}

/// Seconds a recording holds the screen after `step`, so that a class sees what a key did
/// and reads a caption: half a second a key or click, a second at a `wait`, and a caption's
/// words at 200 a minute (3 s at least).
fn hold_after(step: &Step) -> f64 {
    let reading = |text: &str| (text.split_whitespace().count() as f64 * 0.3).max(3.0);
    match step {
        Step::Key(_) | Step::Mouse(_) => 0.5,
        Step::Wait => 1.0,
        Step::Say(Some(t)) | Step::Ask(t) => reading(t),
        _ => 0.0,
    }
}

/// Runs `steps` in plain mode: the lines `turntable --plain` would print, tick by tick, and at
/// each snapshot the readouts (as `I` asks for them) under `--- snapshot N: LABEL`.
fn plain(
    app: App,
    steps: &[Step],
    opts: &Options,
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    use crate::ui::plain::{Seen, opening};
    let mut s = Explorer::headless(app, opts.theme.clone(), opts.size.0, opts.size.1, false);
    s.carry_with(Answer);
    let mut seen = Seen::of(&s.app);
    let say = |s: &Explorer<TestBackend>, seen: &mut Seen, out: &mut dyn std::io::Write| {
        for line in seen.news(&s.app) {
            writeln!(out, "{line}")?;
        }
        std::io::Result::Ok(())
    };
    for line in opening(&s.app) {
        writeln!(out, "{line}")?;
    }
    let mut shots = 0;
    for step in steps {
        if s.app.should_quit() {
            break;
        }
        match step {
            Step::Snapshot(label) => {
                shots += 1;
                let label = label
                    .as_deref()
                    .map(|l| format!(": {l}"))
                    .unwrap_or_default();
                writeln!(out, "--- snapshot {shots}{label}")?;
                let effects = crate::app::update(&mut s.app, crate::app::Action::Readouts);
                answer(&mut s.app, effects);
            }
            Step::Tick(n) => {
                for _ in 0..*n {
                    if !s.is_playing() {
                        break;
                    }
                    s.apply(&Step::Tick(1));
                    say(&s, &mut seen, out)?;
                }
            }
            step => s.apply(step),
        }
        // A page's numbers are said once computed: headless, at once (the terminal's plain
        // mode says them when its worker brings them).
        if crate::ui::pages::summarized(s.app.view().page) {
            s.sync_analysis();
        }
        say(&s, &mut seen, out)?;
    }
    out.flush()
}

/// A replay's effects: answered, never written ([`answer`]).
pub struct Answer;

impl crate::session::Carry for Answer {
    fn carry(&mut self, app: &mut App, effects: Effects) {
        answer(app, effects);
    }
}

/// A replay writes no file: each effect is answered with what it would have written, where.
pub fn answer(app: &mut App, effects: Effects) {
    for effect in effects {
        let notice = match effect {
            Effect::SaveScene { scene, path } => format!(
                "replay saves nothing: \"{}\" → {} (or the next free name)",
                scene.name,
                path.display()
            ),
            Effect::ExportSvg { page, .. } => format!(
                "replay saves nothing: this page → turntable-{}-N.svg (the first free N)",
                crate::plot::page::slug(page)
            ),
            // Words on screen, not a file: said as in the explorer.
            Effect::Readouts => crate::ui::plain::summary(app),
        };
        app.report(notice);
    }
}

fn snapshot(
    s: &mut Explorer<TestBackend>,
    out: &mut dyn std::io::Write,
    n: usize,
    label: Option<&str>,
    ansi: bool,
) -> std::io::Result<()> {
    let tau = s.app.now().tau;
    let buf = s.screen();
    let (w, h) = (buf.area.width, buf.area.height);
    let label = label.map(|l| format!(": {l}")).unwrap_or_default();
    writeln!(out, "--- snapshot {n}{label} ({w}x{h}, tau={tau:.3})")?;
    let text = if ansi {
        ansi_text(buf)
    } else {
        plain_text(buf)
    };
    out.write_all(text.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use crate::script::parse;

    fn app() -> App {
        App::new(Scene::default_scene())
    }

    fn run(script: &str) -> String {
        replay(app(), &parse(script).unwrap(), &Options::default())
    }

    #[test]
    fn no_snapshot_prints_the_final_screen_once() {
        let out = run("tick 3");
        assert_eq!(out.matches("--- snapshot").count(), 1);
        assert!(
            out.starts_with("--- snapshot 1: final (80x24, tau=0.150)\n"),
            "{out}"
        );
        assert_eq!(out.lines().count(), 25);
    }

    /// A replay writes no file: `s` and `E` are answered with what would have been written.
    #[test]
    fn a_replay_answers_effects_without_writing() {
        let out = run("s\nsnapshot one\nE\nsnapshot two");
        assert!(out.contains("replay saves nothing: \"C\""), "{out}");
        assert!(out.contains("replay saves nothing: this page"), "{out}");
    }

    #[test]
    fn quit_stops_the_script() {
        let out = run("snapshot one\nq\nsnapshot two\ntick 5");
        assert_eq!(out.matches("--- snapshot").count(), 1);
        assert!(out.starts_with("--- snapshot 1: one (80x24, tau=0.000)\n"));
    }

    #[test]
    fn tiny_and_empty_screens() {
        let out = run("resize 0x0\nsnapshot\nresize 1x1\nsnapshot\nresize 80x24\nsnapshot");
        let mut heads = out.lines().filter(|l| l.starts_with("---"));
        assert_eq!(heads.next(), Some("--- snapshot 1 (0x0, tau=0.000)"));
        assert_eq!(heads.next(), Some("--- snapshot 2 (1x1, tau=0.000)"));
        assert_eq!(heads.next(), Some("--- snapshot 3 (80x24, tau=0.000)"));
        assert_eq!(out.lines().count(), 3 + 1 + 24);
    }

    #[test]
    fn ansi_resets_every_line() {
        let opts = Options {
            ansi: true,
            ..Options::default()
        };
        let out = replay(app(), &parse("snapshot").unwrap(), &opts);
        for line in out.lines().skip(1) {
            assert!(line.starts_with("\x1b[0"), "{line:?}");
            assert!(line.ends_with("\x1b[0m"), "{line:?}");
        }
        assert!(
            out.contains("38;2;") || out.contains("\x1b[0;3"),
            "colours: {out:?}"
        );
    }
}
