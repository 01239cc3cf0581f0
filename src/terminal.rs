//! The terminal: raw mode, alternate screen, mouse capture; always restored (quit, panic,
//! SIGTERM, SIGHUP). The event loop ticks at a capped frame rate while playing and blocks
//! when paused (no redraw when idle).

use crate::app::App;
use crossterm::event::{self, DisableMouseCapture, EnableMouseCapture, Event, KeyEventKind};
use crossterm::terminal::{
    BeginSynchronizedUpdate, EndSynchronizedUpdate, EnterAlternateScreen, LeaveAlternateScreen,
    disable_raw_mode, enable_raw_mode,
};
use crossterm::{cursor, execute};
use ratatui::Terminal;
use ratatui::backend::CrosstermBackend;
use std::io::{self, Stdout, Write};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Puts the terminal back as it was. Safe to call more than once and on a dead terminal.
pub fn restore() {
    let mut out = io::stdout();
    let _ = execute!(
        out,
        EndSynchronizedUpdate,
        DisableMouseCapture,
        LeaveAlternateScreen,
        cursor::Show
    );
    let _ = disable_raw_mode();
    let _ = out.flush();
}

fn setup(mouse: bool) -> io::Result<Terminal<CrosstermBackend<Stdout>>> {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        restore();
        hook(info);
    }));
    enable_raw_mode()?;
    let mut out = io::stdout();
    execute!(out, EnterAlternateScreen, cursor::Hide)?;
    if mouse {
        execute!(out, EnableMouseCapture)?;
    }
    Terminal::new(CrosstermBackend::new(out))
}

/// Runs the explorer until quit or a terminating signal. `fps` caps the frame rate.
/// Returns whether a signal (SIGTERM, SIGHUP, SIGINT) ended it.
pub fn run(mut app: App, fps: u32) -> io::Result<bool> {
    let stop = Arc::new(AtomicBool::new(false));
    for sig in [
        signal_hook::consts::SIGTERM,
        signal_hook::consts::SIGHUP,
        signal_hook::consts::SIGINT,
    ] {
        signal_hook::flag::register(sig, Arc::clone(&stop))?;
    }
    let mut term = match setup(app.mouse_capture()) {
        Ok(t) => t,
        Err(e) => {
            restore();
            return Err(e);
        }
    };
    let result = event_loop(&mut term, &mut app, fps.clamp(1, 240), &stop);
    restore();
    result.map(|()| stop.load(Ordering::Relaxed))
}

fn event_loop(
    term: &mut Terminal<CrosstermBackend<Stdout>>,
    app: &mut App,
    fps: u32,
    stop: &AtomicBool,
) -> io::Result<()> {
    let frame = Duration::from_secs(1) / fps;
    let mut next_tick = Instant::now() + frame;
    let mut mouse_on = app.mouse_capture();
    while !app.should_quit() && !stop.load(Ordering::Relaxed) {
        if app.mouse_capture() != mouse_on {
            mouse_on = app.mouse_capture();
            if mouse_on {
                execute!(term.backend_mut(), EnableMouseCapture)?;
            } else {
                execute!(term.backend_mut(), DisableMouseCapture)?;
            }
        }
        if app.needs_redraw() {
            execute!(term.backend_mut(), BeginSynchronizedUpdate)?;
            term.draw(|f| crate::ui::draw(f, app))?;
            execute!(term.backend_mut(), EndSynchronizedUpdate)?;
        }
        // Paused: wait for input (waking now and then only to notice signals).
        let timeout = if app.is_playing() {
            next_tick.saturating_duration_since(Instant::now())
        } else {
            Duration::from_millis(250)
        };
        if event::poll(timeout)? {
            // Take everything queued before drawing again, so held keys cannot lag.
            loop {
                match event::read()? {
                    Event::Key(k) if k.kind != KeyEventKind::Release => app.handle_key(k),
                    Event::Mouse(m) => app.handle_mouse(m),
                    Event::Resize(..) => app.invalidate(),
                    _ => {}
                }
                if !event::poll(Duration::ZERO)? {
                    break;
                }
            }
        }
        let now = Instant::now();
        if app.is_playing() {
            if now >= next_tick {
                app.tick();
                next_tick += frame;
                if next_tick < now {
                    next_tick = now + frame;
                }
            }
        } else {
            next_tick = now + frame;
        }
    }
    Ok(())
}
