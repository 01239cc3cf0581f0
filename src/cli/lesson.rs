//! `turntable lesson`: the narrated lessons shipped in the binary, listed, run in the explorer
//! or headless (snapshots as `replay` prints them); a teacher's own lesson, a key script file,
//! runs the same way.

use super::replay::{ReplayArgs, prepare};
use super::{Error, Look};
use crate::lesson::{Driver, LESSONS, Lesson, find, names};
use crate::script::parse_size;
use clap::Args;

#[derive(Args, Debug, Default)]
pub struct LessonArgs {
    /// The lesson to take (see --list), or the path of a lesson of your own (a key script
    /// with say, ask, wait, play and pause).
    #[arg(value_name = "NAME|PATH")]
    pub name: Option<String>,
    /// List the lessons (also what `turntable lesson` alone does).
    #[arg(long, conflicts_with_all = ["name", "headless"])]
    pub list: bool,
    /// Say what a teacher should know of the lesson before class: where it holds, whether it
    /// runs to its end at once, where a caption replaces a question's verdict unread.
    #[arg(long, requires = "name", conflicts_with_all = ["headless", "plain"])]
    pub check: bool,
    /// No terminal: run the lesson as `replay` runs a script and print its snapshots (a `wait`
    /// goes on, a question stays unanswered and the run answers it).
    #[arg(long)]
    pub headless: bool,
    /// With --headless: the off-screen terminal's size, WxH (default the lesson's own, 80x24).
    #[arg(long, value_name = "WxH", value_parser = parse_size, requires = "headless")]
    pub size: Option<(u16, u16)>,
    /// With --headless: style the snapshots with ANSI colour escape sequences.
    #[arg(long, requires = "headless")]
    pub ansi: bool,
    /// Plain mode for screen readers: lines of text, not a canvas (see `turntable --help`);
    /// with --headless, the lines instead of snapshots.
    #[arg(long, conflicts_with = "ansi")]
    pub plain: bool,
    /// Colour theme: dark, light, high-contrast, mono, or a .toml file.
    #[arg(long, value_name = "NAME|PATH", value_parser = crate::cli::args::NameOrPath::themes(),
        hide_possible_values = true)]
    pub theme: Option<String>,
}

/// `lesson --list`, `lesson NAME --headless`, or what the explorer needs for `lesson NAME`:
/// the look and the lesson's driver.
pub fn run(a: &LessonArgs) -> Result<Option<(Look, Driver)>, Error> {
    // `lesson` alone lists them too: a teacher trying the command sees what there is.
    let Some(name) = a.name.as_deref().filter(|_| !a.list) else {
        let width = LESSONS.iter().map(|l| l.name.len()).max().unwrap_or(0);
        let list: String = LESSONS
            .iter()
            .map(|l| format!("{:width$}  {}\n", l.name, l.about))
            .collect();
        crate::files::emit(None, &list)?;
        return Ok(None);
    };
    let lesson = source(name)?;
    if a.check {
        let check = crate::lesson::check(&lesson.script)
            .map_err(|e| Error::invalid(format!("{}: {e}", crate::files::escape_controls(name))))?;
        crate::files::emit(None, &format!("lesson {}: {check}", lesson.name))?;
        return Ok(None);
    }
    // A lesson of one's own may name its scene and theme (`# replay:`); the flag wins.
    let own = crate::script::script_options(&lesson.script).map_err(|e| e.context(name))?;
    let look = Look {
        scene: own.scene,
        theme: a.theme.clone().or(own.theme),
    };
    let (app, opts, steps) = prepared(&lesson, a.size, a.ansi, a.plain, &look)?;
    if !a.headless {
        return Ok(Some((look, Driver::new(&lesson.name, steps))));
    }
    let mut so = std::io::BufWriter::new(std::io::stdout().lock());
    crate::replay::replay_to(app, &steps, &opts, &mut so)?;
    Ok(None)
}

/// A shipped lesson by its name, else a lesson of one's own by its path.
fn source(name: &str) -> Result<Source, Error> {
    match find(name) {
        Some(l) => Ok(Source::from(l)),
        None => own(name),
    }
}

/// What `turntable serve --lesson NAME|PATH` gives each presenter's session: the lesson's
/// scene (its own `# replay: --scene`, if it names one) and its script at the first step.
#[cfg(feature = "serve")]
pub fn for_class(name: &str) -> Result<crate::serve::Lesson, Error> {
    let lesson = source(name)?;
    let own = crate::script::script_options(&lesson.script).map_err(|e| e.context(name))?;
    let look = Look {
        scene: own.scene,
        theme: None,
    };
    let (app, _, steps) = prepared(&lesson, None, false, false, &look)?;
    Ok(crate::serve::Lesson {
        scene: app.scene().clone(),
        driver: Driver::new(&lesson.name, steps),
    })
}

/// A lesson to run: its name (for the caption) and its key script.
struct Source {
    name: String,
    script: String,
}

impl From<Lesson> for Source {
    fn from(l: Lesson) -> Source {
        Source {
            name: l.name.into(),
            script: l.script.into(),
        }
    }
}

/// A lesson of one's own: the key script at `path`, named by its file's stem.
fn own(path: &str) -> Result<Source, Error> {
    let p = std::path::Path::new(path);
    if !p.is_file() {
        return Err(Error::invalid(format!(
            "unknown lesson '{}': neither one of the lessons ({}; `turntable lesson --list` says what each covers) nor a key script file",
            crate::files::escape_controls(path),
            names()
        )));
    }
    let script = crate::files::read_bounded(p, crate::files::READ_CAP)?;
    let stem = p
        .file_stem()
        .map(|s| s.to_string_lossy())
        .unwrap_or_default();
    Ok(Source {
        name: crate::text::clean(&stem).to_string(),
        script,
    })
}

/// What `lesson NAME --headless` prints, at `size` (default the lesson's own).
pub fn headless(lesson: Lesson, size: Option<(u16, u16)>) -> Result<String, Error> {
    let (app, opts, steps) = prepared(&lesson.into(), size, false, false, &Look::default())?;
    Ok(crate::replay::replay(app, &steps, &opts))
}

/// A lesson's app (its name on the caption), options and steps, as `replay` prepares a script.
fn prepared(
    lesson: &Source,
    size: Option<(u16, u16)>,
    ansi: bool,
    plain: bool,
    look: &Look,
) -> Result<
    (
        crate::app::App,
        crate::replay::Options,
        Vec<crate::script::Step>,
    ),
    Error,
> {
    let replay = ReplayArgs {
        script: format!("lesson {}", lesson.name),
        size,
        ansi,
        plain,
        look: look.clone(),
        asciicast: None,
        svg: None,
        force: false,
    };
    let (mut app, opts, steps) = prepare(&lesson.script, &replay)?;
    app.tell_lesson(&lesson.name);
    Ok((app, opts, steps))
}
