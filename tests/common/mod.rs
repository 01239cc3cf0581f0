//! What the integration tests share: the binary run as a user runs it, and the explorer drawn
//! on an off-screen terminal. (Each test target uses part of it.)
#![allow(dead_code)]

use std::process::Command;

/// An XDG_CONFIG_HOME with nothing in it: tests never read the user's configuration.
pub const NO_CONFIG: &str = "/nonexistent/turntable-tests/config";

/// Runs `turntable` with `args`: exit code, stdout, stderr.
pub fn turntable(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_turntable"))
        .args(args)
        .env("XDG_CONFIG_HOME", NO_CONFIG)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// Draws `app` on a `w` × `h` off-screen terminal (recording the geometry, as the terminal
/// loop does) and returns the screen as text, one line per row.
pub fn render(app: &mut turntable::app::App, w: u16, h: u16) -> String {
    let mut t = ratatui::Terminal::new(ratatui::backend::TestBackend::new(w, h)).unwrap();
    app.resize(w, h);
    app.sync_analysis();
    let mut geom = None;
    t.draw(|f| geom = turntable::ui::draw(f, app)).unwrap();
    app.drawn(geom);
    let buf = t.backend().buffer();
    (0..buf.area.height)
        .map(|y| {
            (0..buf.area.width)
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
                + "\n"
        })
        .collect()
}
