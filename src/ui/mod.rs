//! Pure rendering of the explorer's state into a ratatui frame.

pub mod canvas;
pub(crate) mod caption;
pub mod chart;
pub mod export;
pub mod fit;
pub mod help;
pub(crate) mod layout;
pub mod pages;
pub mod panel;
pub mod plain;
pub mod time_plots;

use crate::app::{App, CanvasGeom};
use crate::engine::Outcome;
use crate::present::alternatives;
use crate::theme::Theme;
use ratatui::Frame;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Wrap};
use unicode_width::UnicodeWidthStr;

pub use layout::{MIN_SIZE, PANEL_W};

/// Draws the whole screen and returns where the canvases went (none, one, or two in a split
/// view), for the caller to hand to [`App::drawn`] so mouse cells map to the table. Pure: it
/// reads the state only. Never panics, whatever the size.
pub fn draw(frame: &mut Frame, app: &App, th: &Theme) -> Vec<CanvasGeom> {
    let geom = draw_common(frame, app, th);
    draw_own(frame, app, th);
    geom
}

/// All of the screen but its status line and what lies over it ([`draw_own`]): what a served
/// class's followers of one size, in the same state, see alike, so that it can be drawn once
/// for them all.
pub fn draw_common(frame: &mut Frame, app: &App, th: &Theme) -> Vec<CanvasGeom> {
    let area = frame.area();
    let base = Style::default().bg(th.background).fg(th.foreground);
    let Some(r) = layout::regions(area.width, area.height) else {
        let msg = format!(
            "terminal too small ({}×{}): need ≥ {}×{}",
            area.width, area.height, MIN_SIZE.0, MIN_SIZE.1
        );
        frame.render_widget(
            Paragraph::new(msg)
                .style(base)
                .alignment(Alignment::Center)
                .wrap(Wrap { trim: true }),
            area,
        );
        return Vec::new();
    };
    paint(frame.buffer_mut(), area, th);
    frame.render_widget(
        Paragraph::new(Line::from(vec![
            Span::styled(" turntable ", Style::default().fg(th.accent)),
            Span::styled(
                fit::fit(&app.about(), ", ", usize::from(area.width) - 11),
                Style::default().fg(th.muted),
            ),
        ])),
        r.title,
    );
    let canvas_area = caption::picture(&r, app);
    let geom = match app.view().page {
        crate::app::pages::Page::Turntable => canvas::render(frame, canvas_area, app, th),
        _ => pages::render(frame, canvas_area, app, th)
            .into_iter()
            .collect(),
    };
    panel::render(frame, r.panel, app, th);
    frame.render_widget(
        Paragraph::new(Span::styled(
            fit::fit(&lesson_line(app), "\0", usize::from(area.width)),
            Style::default().fg(th.notice),
        )),
        r.lesson,
    );
    caption::render(frame, &r, app, th);
    unset_background(frame.buffer_mut(), area, th);
    geom
}

/// The status line (a notice, the prompt, the keys: one user's own while the rest is the
/// class's) and the help over it, on a screen [`draw_common`] drew, for this state or for
/// another that differs only here (its status row painted and left empty).
pub fn draw_own(frame: &mut Frame, app: &App, th: &Theme) {
    let area = frame.area();
    let Some(r) = layout::regions(area.width, area.height) else {
        return;
    };
    paint(frame.buffer_mut(), r.status, th);
    frame.render_widget(
        Paragraph::new(status_line(app, th, r.status.width)),
        r.status,
    );
    let over = if app.view().help {
        help::render(frame, r.help, app, th);
        r.help
    } else {
        r.status
    };
    unset_background(frame.buffer_mut(), over, th);
}

/// A theme that sets a background sets it on every cell of `area`: widgets that paint none
/// (chart interiors, cleared cells) would show the terminal's own, white boxes on a dark theme.
fn unset_background(buf: &mut ratatui::buffer::Buffer, area: Rect, th: &Theme) {
    if th.background == ratatui::style::Color::Reset {
        return;
    }
    let area = area.intersection(buf.area);
    for y in area.top()..area.bottom() {
        let start = buf.index_of(area.x, y);
        for cell in &mut buf.content[start..start + usize::from(area.width)] {
            if cell.bg == ratatui::style::Color::Reset {
                cell.bg = th.background;
            }
        }
    }
}

/// The theme's colours on every cell of `area`, a row at a time (as a paragraph styled over
/// it would, which goes through the buffer's index a cell at a time: a tenth of a served
/// frame's cost).
fn paint(buf: &mut ratatui::buffer::Buffer, area: Rect, th: &Theme) {
    let area = area.intersection(buf.area);
    for y in area.top()..area.bottom() {
        let start = buf.index_of(area.x, y);
        for cell in &mut buf.content[start..start + usize::from(area.width)] {
            cell.fg = th.foreground;
            cell.bg = th.background;
        }
    }
}

/// The one-line lesson: the paper's scheme against the converged run, or what μ = 0 means;
/// said several ways, longest first (`present::alternatives`), so a narrow screen reads a whole
/// shorter sentence.
pub fn lesson_line(app: &App) -> String {
    if app.initial().frictionless {
        return alternatives(&[
            " μ = 0: a straight line in the lab, a spiral in the rotating frame (f switches)",
            " μ = 0: a straight line in the lab, a spiral on the table",
            " μ = 0: a straight line in the lab",
        ]);
    }
    if app.scene().spin.is_some() {
        return alternatives(&[
            " the table spins up: the coin rides it until friction cannot hold it, then slides",
            " the table spins up until the coin slides",
            " the table spins up",
        ]);
    }
    if let Some(gamma) = app.settings().stokes() {
        let rate = crate::present::num(crate::engine::stokes::growth_rate(gamma), 4);
        return alternatives(&[
            format!(" Stokes drag γ = {gamma}: linear, in closed form; it leaves as e^({rate}τ)"),
            format!(" Stokes drag γ = {gamma}: it leaves as e^({rate}τ)"),
            format!(" Stokes: leaves as e^({rate}τ)"),
        ]);
    }
    let Some(p) = app.paper().filter(|_| !app.outcome_open()) else {
        // A follower's c is not applied: the comparison is the presenter's to show.
        if app.class == crate::app::state::InClass::Following {
            return String::new();
        }
        // A newcomer, in no lesson and none taken, is told where the lessons are.
        if app.lesson().name.is_none() && !app.lesson().done {
            return alternatives(&[
                " c: compare with the paper's scheme (raw RK2, fixed dt = 1e-3, no stick event) · new here? `turntable lesson` lists the lessons",
                " c: compare with the paper's RK2 · new here? `turntable lesson` lists the lessons",
                " c: compare with the paper's RK2 · new here? `turntable lesson`",
                " c: the paper's RK2 · new here? `turntable lesson`",
                " c: compare with the paper's RK2",
                " c: the paper's RK2",
            ]);
        }
        return alternatives(&[
            " c: compare with the paper's scheme (raw RK2, fixed dt = 1e-3, no stick event)",
            " c: compare with the paper's scheme (RK2, dt = 1e-3)",
            " c: compare with the paper's RK2",
            " c: the paper's RK2",
        ]);
    };
    let (a, b) = (app.sim().outcome_now(), p.outcome_now());
    let name = |o: Outcome| match o {
        Outcome::Stuck => "sticks",
        Outcome::Escaped => "escapes",
        Outcome::Running => "still slides",
    };
    let both = |o: Outcome| match o {
        Outcome::Stuck => "both stick",
        Outcome::Escaped => "both escape",
        Outcome::Running => "both still slide",
    };
    let method = app.settings().method();
    if a == b {
        alternatives(&[
            format!(
                " paper's RK2 (○) and {method} (●) agree so far: {}",
                both(a)
            ),
            format!(" ○ paper's RK2, ● {method}: {}", both(a)),
            format!(" ○ ●: {}", both(a)),
        ])
    } else if a == Outcome::Stuck && b == Outcome::Escaped {
        alternatives(&[
            " ● sticks; the paper's fixed-step RK2 (○) steps over the stop and escapes",
            " ● sticks; the paper's RK2 (○) steps over the stop",
            " ● sticks, ○ escapes",
        ])
    } else if a == Outcome::Stuck {
        alternatives(&[
            " ● sticks; the paper's RK2 (○) has no stop event: it dithers about |u| = 0",
            " ● sticks; the paper's RK2 (○) dithers about |u| = 0",
            " ● sticks, ○ dithers",
        ])
    } else {
        alternatives(&[
            format!(
                " disagree: {method} (●) {}, paper's RK2 (○) {}",
                name(a),
                name(b)
            ),
            format!(" ● {}, ○ {}", name(a), name(b)),
        ])
    }
}

fn status_line(app: &App, th: &Theme, width: u16) -> Line<'static> {
    if let Some(p) = &app.prompt() {
        // The end of a long line stays in sight: what is typed is what shows.
        let label = format!(" {}: ", p.label());
        let room = usize::from(width).saturating_sub(label.width() + "▏".width());
        // The hint (or why Enter was refused) only where it leaves room for the line.
        let hint = format!("  {}", p.refused.as_deref().unwrap_or(p.hint()));
        let (hint, room) = match room.checked_sub(hint.width()) {
            Some(r) if r >= 20 => (hint, r),
            _ => (String::new(), room),
        };
        let mut shown: Vec<char> = p.typed.chars().rev().collect();
        while shown.iter().collect::<String>().width() > room {
            shown.pop();
        }
        let shown: String = shown.into_iter().rev().collect();
        return Line::from(Span::styled(
            fit::fit(&format!("{label}{shown}▏{hint}"), "\0", usize::from(width)),
            Style::default().fg(th.notice),
        ));
    }
    if let Some(n) = &app.notice() {
        return Line::from(Span::styled(
            // Clauses (", ") drop whole before words do: "comes to" is not left hanging.
            fit::fit(
                &n.split(crate::present::OR)
                    .map(|wording| format!(" {wording}"))
                    .collect::<Vec<_>>()
                    .join(&crate::present::OR.to_string()),
                ", ",
                usize::from(width),
            ),
            Style::default().fg(th.notice),
        ));
    }
    let mouse = if app.mouse_capture() {
        ""
    } else {
        "  [mouse off]"
    };
    // A follower's own keys are not applied: the footer lists only what is theirs.
    if app.class == crate::app::state::InClass::Following {
        return Line::from(Span::styled(
            fit::fit(
                " following the class  F2 step out  y/n answer its question  q quit",
                "  ",
                usize::from(width),
            ),
            Style::default().fg(th.muted),
        ));
    }
    let rejoin = match app.class {
        crate::app::state::InClass::Out => "  F2 rejoin",
        _ => "",
    };
    // The long hint where it fits, measured; else the short one, whole hints dropped from
    // its end.
    let room = usize::from(width).saturating_sub(mouse.width());
    // Space's hint says what it does now (while a lesson waits, it goes on).
    let space = if app.playing() { "pause" } else { "play" };
    // A spun-up table has no paper's run and takes only ξ0.
    let (compare, edit) = match app.scene().spin {
        Some(_) => ("", "x"),
        None => ("  c compare", "x/p/v"),
    };
    let long = format!(
        " ? help{rejoin}  Space {space}  .,  step  [] speed  f frame  m method{compare}  a forces  1-7 presets  {edit} edit  q quit"
    );
    let keys = if long.width() <= room {
        long
    } else {
        fit::fit(
            &format!(
                " ? help{rejoin}  q quit  Space {space}  ., step  f frame  m method{compare}  1-7 presets"
            ),
            "  ",
            room,
        )
    };
    Line::from(vec![
        Span::styled(keys, Style::default().fg(th.muted)),
        Span::styled(mouse.to_string(), Style::default().fg(th.notice)),
    ])
}

/// The bordered box every part of the screen sits in: a muted border, the title in the accent
/// colour.
pub fn titled(title: String, th: &crate::theme::Theme) -> ratatui::widgets::Block<'static> {
    ratatui::widgets::Block::default()
        .borders(ratatui::widgets::Borders::ALL)
        .border_style(Style::default().fg(th.muted))
        .title(Span::styled(title, Style::default().fg(th.accent)))
}

/// A frame area as a rectangle helper for tests.
pub fn screen(width: u16, height: u16) -> Rect {
    Rect::new(0, 0, width, height)
}
