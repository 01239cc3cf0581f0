//! What the integration tests share: the binary run as a user runs it, and the explorer drawn
//! on an off-screen terminal. (Each test target uses part of it.)
#![allow(dead_code)]

pub mod sundman;

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
    render_with(
        app,
        &turntable::theme::Theme::builtin("dark").unwrap(),
        w,
        h,
    )
}

/// [`render`] in `theme`.
pub fn render_with(
    app: &mut turntable::app::App,
    theme: &turntable::theme::Theme,
    w: u16,
    h: u16,
) -> String {
    let mut t = ratatui::Terminal::new(ratatui::backend::TestBackend::new(w, h)).unwrap();
    turntable::session::tell_size(app, w, h);
    sync(app);
    let mut geom = Vec::new();
    t.draw(|f| geom = turntable::ui::draw(f, app, theme))
        .unwrap();
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

/// Brings `app`'s analysis pages up to date, computed now (as a headless session's frame
/// does).
pub fn sync(app: &mut turntable::app::App) {
    turntable::session::sync(app, &mut turntable::analysis::Analysis::inline(), true);
}

/// A new pseudo-terminal of `cols` × `rows`: master and slave, close-on-exec (as a terminal
/// emulator's master is: no other child may keep it up). Where none can be opened it panics,
/// unless `TURNTABLE_SKIP_PTY=1`: then None, and the caller skips, saying so.
pub fn openpty(cols: u16, rows: u16) -> Option<(std::os::fd::OwnedFd, std::os::fd::OwnedFd)> {
    use std::os::fd::FromRawFd;
    let (mut master, mut slave) = (0, 0);
    let ws = libc::winsize {
        ws_row: rows,
        ws_col: cols,
        ws_xpixel: 0,
        ws_ypixel: 0,
    };
    // SAFETY: out-pointers to two ints and a winsize.
    let r = unsafe {
        libc::openpty(
            &mut master,
            &mut slave,
            std::ptr::null_mut(),
            std::ptr::null(),
            &ws,
        )
    };
    if r != 0 {
        // A test that needs a terminal and cannot have one fails, unless told that none is
        // to be had here: a silent skip would pass where nothing was checked.
        assert!(
            std::env::var_os("TURNTABLE_SKIP_PTY").is_some_and(|v| v == "1"),
            "no pseudo-terminal could be opened (errno {}); set TURNTABLE_SKIP_PTY=1 to skip the tests that need one",
            std::io::Error::last_os_error()
        );
        eprintln!("skipped (TURNTABLE_SKIP_PTY=1): no pseudo-terminal here");
        return None;
    }
    // SAFETY: fresh descriptors we now own.
    unsafe {
        libc::fcntl(master, libc::F_SETFD, libc::FD_CLOEXEC);
        libc::fcntl(slave, libc::F_SETFD, libc::FD_CLOEXEC);
        Some((
            std::os::fd::OwnedFd::from_raw_fd(master),
            std::os::fd::OwnedFd::from_raw_fd(slave),
        ))
    }
}

/// `cmd` run with `slave` as its terminal: stdin, stdout and stderr, in a session of its own
/// (so the pty is its controlling terminal).
pub fn on_pty(cmd: &mut Command, slave: std::os::fd::OwnedFd) {
    use std::os::unix::process::CommandExt;
    cmd.stdin(slave.try_clone().unwrap())
        .stdout(slave.try_clone().unwrap())
        .stderr(slave);
    // SAFETY: setsid is async-signal-safe.
    unsafe {
        cmd.pre_exec(|| {
            libc::setsid();
            Ok(())
        });
    }
}

/// `n` steps of classical RK4 of length `h` on (q, u)′ = f(q, u): the tests' own integrator,
/// independent of the engine's.
pub fn rk4(
    f: impl Fn(glam::DVec2, glam::DVec2) -> (glam::DVec2, glam::DVec2),
    (mut q, mut u): (glam::DVec2, glam::DVec2),
    h: f64,
    n: usize,
) -> (glam::DVec2, glam::DVec2) {
    for _ in 0..n {
        let (a1, b1) = f(q, u);
        let (a2, b2) = f(q + 0.5 * h * a1, u + 0.5 * h * b1);
        let (a3, b3) = f(q + 0.5 * h * a2, u + 0.5 * h * b2);
        let (a4, b4) = f(q + h * a3, u + h * b3);
        q += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
        u += h / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4);
    }
    (q, u)
}

/// A property test's configuration with a fixed seed: CI sees the same `cases` every run, and
/// no failure file is written into the tree.
pub fn seeded(cases: u32) -> proptest::test_runner::Config {
    proptest::test_runner::Config {
        cases,
        rng_seed: proptest::test_runner::RngSeed::Fixed(23),
        failure_persistence: None,
        ..proptest::test_runner::Config::default()
    }
}

/// A body's track as the explorer computes it (within `TRACK_STEPS` and `TRACK_STATES`).
pub fn rod_track(
    body: turntable::engine::body::Body,
    hold: f64,
    initial: &turntable::engine::Initial,
    tol: f64,
    tau_max: f64,
) -> turntable::engine::rod::RodTrack {
    use turntable::engine::rod::{TRACK_STATES, TRACK_STEPS};
    rod_track_within(body, hold, initial, tol, tau_max, TRACK_STEPS, TRACK_STATES)
}

/// A body's track (what `RodTrack::from_run` makes of a new run), within `max_steps` and
/// `max_states`.
pub fn rod_track_within(
    body: turntable::engine::body::Body,
    hold: f64,
    initial: &turntable::engine::Initial,
    tol: f64,
    tau_max: f64,
    max_steps: u64,
    max_states: usize,
) -> turntable::engine::rod::RodTrack {
    let run = turntable::engine::rod::RodRun::new(body, hold, initial, tol).unwrap();
    turntable::engine::rod::RodTrack::from_run(run, tau_max, max_steps, max_states)
}

/// A test's budget (cases, seeds) from the environment variable `var`, else `default`: CI runs
/// the default; a longer hunt sets the variable.
pub fn budget(var: &str, default: u64) -> u64 {
    match std::env::var(var) {
        Ok(v) => v
            .parse()
            .unwrap_or_else(|_| panic!("{var} must be a whole number, got {v:?}")),
        Err(_) => default,
    }
}

/// The terminal cell whose centre lies over world point (`x`, `y`) of the canvas `g`.
pub fn cell_under(g: &turntable::app::CanvasGeom, x: f64, y: f64) -> (u16, u16) {
    let col = g.area.x + ((x - g.x[0]) / (g.x[1] - g.x[0]) * f64::from(g.area.width)) as u16;
    let row = g.area.y + ((g.y[1] - y) / (g.y[1] - g.y[0]) * f64::from(g.area.height)) as u16;
    (col, row)
}

/// A mouse event of `kind` at (`column`, `row`), no modifier.
pub fn mouse(
    kind: crossterm::event::MouseEventKind,
    column: u16,
    row: u16,
) -> crossterm::event::MouseEvent {
    crossterm::event::MouseEvent {
        kind,
        column,
        row,
        modifiers: crossterm::event::KeyModifiers::NONE,
    }
}

/// Turns `app`'s pages to `page`, as Tab does.
pub fn turn_to(app: &mut turntable::app::App, page: turntable::app::pages::Page) {
    for _ in 0..16 {
        if app.view().page == page {
            return;
        }
        turntable::app::update(app, turntable::app::Action::NextPage);
    }
    panic!("no page {page:?}");
}

/// Where v_e(φ) is least for a given ξ0, to `phi_tol` (Fig. 5's minimum, which the paper
/// puts near φ ≈ 0.4 for every ξ0): a scan of `n` angles, then golden-section search. The
/// tests' own (the analysis page seeks it from its curve: `analysis::least`). Each search is
/// made once for all the tests that ask the same (the lessons, the paper and plain mode ask
/// again for ξ0 = 0.2, 0.5 and 0.8).
pub fn easiest_angle(
    xi0: f64,
    n: usize,
    settings: turntable::engine::Settings,
    tol: f64,
    phi_tol: f64,
) -> Result<(f64, f64), turntable::engine::error::Error> {
    type Found = std::collections::HashMap<String, (f64, f64)>;
    static FOUND: std::sync::LazyLock<std::sync::Mutex<Found>> =
        std::sync::LazyLock::new(Default::default);
    let key = format!("{xi0:e} {n} {settings:?} {tol:e} {phi_tol:e}");
    let found = |f: &Found| f.get(&key).copied();
    if let Some(r) = found(&FOUND.lock().unwrap_or_else(|e| e.into_inner())) {
        return Ok(r);
    }
    let r = search_easiest_angle(xi0, n, settings, tol, phi_tol)?;
    FOUND
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(key, r);
    Ok(r)
}

fn search_easiest_angle(
    xi0: f64,
    n: usize,
    settings: turntable::engine::Settings,
    tol: f64,
    phi_tol: f64,
) -> Result<(f64, f64), turntable::engine::error::Error> {
    let ve =
        |phi: f64| turntable::engine::solve::escape_speed(xi0, phi, settings, tol).map(|t| t.value);
    let step = std::f64::consts::TAU / n as f64;
    let phis: Vec<f64> = (0..n).map(|i| step * i as f64).collect();
    let vals: Vec<Result<f64, turntable::engine::error::Error>> =
        turntable::engine::par::par_map(&phis, |&p| ve(p));
    let vals: Vec<f64> = vals.into_iter().collect::<Result<_, _>>()?;
    let imin = (0..n)
        .min_by(|&a, &b| vals[a].total_cmp(&vals[b]))
        .unwrap_or(0);
    let phi = turntable::engine::roots::golden_min(
        &mut |p| ve(p),
        phis[imin] - step,
        phis[imin] + step,
        phi_tol,
    )?;
    Ok((turntable::engine::model::turn_angle(phi), ve(phi)?))
}

/// The docs' pages: README, ARCHITECTURE and every page under docs/, in order.
pub fn doc_pages() -> Vec<std::path::PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut pages = vec![root.join("README.md"), root.join("ARCHITECTURE.md")];
    for e in std::fs::read_dir(root.join("docs")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "md") {
            pages.push(p);
        }
    }
    pages.sort();
    pages
}
