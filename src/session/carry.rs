//! What the shell does with the effects `update` returns: files written, a page exported
//! within a bound, each reported back to the app as a notice.

use crate::app::{App, Effect, Effects};

/// What the shell does with the effects `update` returns, each reported back to the app as a
/// notice: written ([`Write`]), answered with what would have been written (a replay:
/// `crate::replay::Answer`), refused (a guest over SSH: `crate::serve::explorer::Guest`).
pub trait Carry {
    fn carry(&mut self, app: &mut App, effects: Effects);
}

/// Effects carried out for real: files written ([`carry_out`]).
pub struct Write;

impl Carry for Write {
    fn carry(&mut self, app: &mut App, effects: Effects) {
        carry_out(app, effects);
    }
}

/// Carries out what `update` asked for: a scene saved to a new file, the page on screen
/// written as SVG; each reported back to `app` as a notice (where it went, or why not).
pub fn carry_out(app: &mut App, effects: Effects) {
    for effect in effects {
        let notice = match effect {
            Effect::SaveScene { scene, path } => match scene.save_new(&path) {
                Ok(p) => format!("saved \"{}\" to {}", scene.name, p.display()),
                Err(e) => format!("could not save {}: {e}", path.display()),
            },
            Effect::ExportSvg { dir, page } => export_svg(app, &dir, page, None),
            Effect::Readouts => crate::ui::plain::summary(app),
        };
        app.report(notice);
    }
}

/// What exports a directory may hold (`serve --exports`): `turntable-*.svg` files and bytes.
#[derive(Clone, Copy, Debug)]
pub struct ExportBound {
    pub files: usize,
    pub bytes: u64,
}

/// The exported pages `dir` holds: how many and their bytes.
fn exported(dir: &std::path::Path) -> std::io::Result<(usize, u64)> {
    let mut held = (0, 0);
    for e in std::fs::read_dir(dir)? {
        let e = e?;
        let name = e.file_name();
        let name = name.to_string_lossy();
        if name.starts_with("turntable-") && name.ends_with(".svg") {
            held.0 += 1;
            held.1 += e.metadata().map_or(0, |m| m.len());
        }
    }
    Ok(held)
}

/// Writes the page on screen as SVG to the first free `turntable-PAGE-N.svg` in `dir`, within
/// `bound` if given; never over a file. Says where, or why not.
pub fn export_svg(
    app: &App,
    dir: &std::path::Path,
    page: crate::app::pages::Page,
    bound: Option<ExportBound>,
) -> String {
    use crate::app::pages::Page;
    use std::io::Write;
    if crate::engine::closed_form(&app.initial(), app.settings())
        && !matches!(page, Page::Turntable | Page::TimePlots)
    {
        return "not exported: in closed form (μ = 0 or Stokes drag) this page draws nothing"
            .to_string();
    }
    let (fig, whole) = crate::plot::page::figure(app);
    let text = crate::plot::to_svg(&fig);
    let slug = crate::plot::page::slug(page);
    if let Some(b) = bound {
        match exported(dir) {
            Err(e) => return format!("not exported: {e}"),
            Ok((n, _)) if n >= b.files => {
                return format!("not exported: the exports hold {n} pages, the most allowed");
            }
            Ok((_, bytes)) if bytes + text.len() as u64 > b.bytes => {
                return format!(
                    "not exported: the exports hold {} MB, and this page would pass {} MB",
                    bytes >> 20,
                    b.bytes >> 20
                );
            }
            Ok(_) => {}
        }
    }
    for n in 1..=999 {
        let path = dir.join(format!("turntable-{slug}-{n}.svg"));
        if path.symlink_metadata().is_ok() {
            continue;
        }
        let written = crate::files::Output::create(&path, false).and_then(|mut out| {
            out.write_all(text.as_bytes())?;
            out.finish()
        });
        return match written {
            Ok(()) if whole => format!("wrote this page to {}", path.display()),
            Ok(()) => format!(
                "wrote this page to {} (partial: it is still computing)",
                path.display()
            ),
            // Taken meanwhile: the next name.
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => format!("could not write {}: {e}", path.display()),
        };
    }
    format!("could not write turntable-{slug}-N.svg: 999 names taken")
}
