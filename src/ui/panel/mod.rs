//! Readouts: where the particle is, how the run stands, what it costs; and, when comparing,
//! how the paper's scheme fares from the same start.

use crate::app::App;
use crate::engine::run::raw_at_rest;
use crate::engine::{Certificate, Method, Outcome, Status};
use crate::sim::Sim;
use crate::theme::Theme;
use ratatui::Frame as TuiFrame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use unicode_width::UnicodeWidthStr;

mod body;
mod spin;

use body::body_lines;
pub use body::{BodyNow, body_end, body_now, phase_word};

use crate::present::{
    Quantity, angle, fmt_speed, num, rate, sci, si_length, si_rate, si_speed, si_time, speed,
    unit_of,
};

/// Status of a run at the sample on screen, and its colour.
pub fn status_text(sim: &Sim, th: &Theme) -> (String, ratatui::style::Color) {
    if sim.error.is_some() {
        return ("stopped: step budget / underflow".into(), th.escaped);
    }
    if sim.steady().is_none() {
        return spin::status(sim, th);
    }
    let (text, colour) = match sim.outcome_now() {
        Outcome::Stuck => match sim.status() {
            Status::Stuck { tau, q } => (
                format!(
                    "stuck at ξ = {}\n  since τ = {}",
                    num(q.length(), 5),
                    num(tau, 3)
                ),
                th.stuck,
            ),
            Status::Slipping => ("stuck".into(), th.stuck),
        },
        Outcome::Escaped => match sim.escape() {
            // What is certified, true from that instant on, before the particle leaves.
            Some(e) => (
                format!(
                    "escape certified\n  {}\n  at τ = {}",
                    match e.by {
                        Certificate::Radial => "ξ > 1, moving out",
                        // E said once where it is shown: the energy in the table's frame.
                        Certificate::Energy if sim.settings().hold() == 1.0 => {
                            "E < −½: cannot rest\n  E = ½|u|²−½ξ² (table)"
                        }
                        Certificate::Energy => "E < −½R²: cannot rest\n  E = ½|u|²−½ξ² (table)",
                    },
                    num(e.tau, 3)
                ),
                th.escaped,
            ),
            None => ("escape certified".into(), th.escaped),
        },
        Outcome::Running => {
            let s = sim.now();
            let raw = sim.settings().method() == Method::Rk2Raw;
            if raw && raw_at_rest(&s, sim.settings().scheme.knob()) {
                ("≈ at rest (raw RK2 chatters)".into(), th.slipping)
            } else {
                ("slipping".into(), th.slipping)
            }
        }
    };
    match doubt_words(sim) {
        Some([a, b]) => (format!("{text}\n  {a}\n  {b}"), colour),
        None => (text, colour),
    }
}

/// What a decided run's doubt means, in two short halves (the panel's lines; plain mode
/// joins them): which outcome holds and why, so a certificate beside it is not read as the
/// last word. None when the run is certain or undecided.
pub(crate) fn doubt_words(sim: &Sim) -> Option<[&'static str; 2]> {
    let d = sim.doubt.filter(|d| !d.certain)?;
    let own = sim.outcome_now();
    Some(match d.shadow {
        _ if own == Outcome::Running => return None,
        Some(Outcome::Stuck) if own != Outcome::Stuck => {
            ["but its error flips it:", "a converged run sticks"]
        }
        Some(Outcome::Escaped) if own != Outcome::Escaped => {
            ["but its error flips it:", "a converged run escapes"]
        }
        Some(_) => ["in doubt: the run's", "error could flip it"],
        None => ["in doubt: no second", "opinion finished"],
    })
}

fn kv<'a>(k: &'a str, v: String, th: &Theme) -> Line<'a> {
    Line::from(vec![
        // A blank always follows the key, however long (`rk2-raw dt=1e-3`, never glued).
        Span::styled(
            format!("{:<7}", format!("{k} ")),
            Style::default().fg(th.muted),
        ),
        Span::styled(v, Style::default().fg(th.foreground)),
    ])
}

/// The readout lines in reading order.
pub fn lines(app: &App, th: &Theme) -> Vec<Line<'static>> {
    readouts(app, th).lines
}

/// The readout lines that fit in `rows`, most important first when not all do: the status
/// (stuck / slipping / escape certified), then ξ, τ, the body's phase (first of all when the
/// point model is hidden, `C`) and the release, then the rest.
pub fn lines_in(app: &App, th: &Theme, rows: usize) -> Vec<Line<'static>> {
    let Readouts {
        lines: all,
        release,
        status,
        rod,
    } = readouts(app, th);
    if all.len() <= rows {
        return all;
    }
    // τ and ξ come first after the release (`motion_lines`).
    let (tau_line, xi_line) = (release.end, release.end + 1);
    let body_first = rod.filter(|_| !app.point_shown());
    let first: Vec<usize> = body_first
        .into_iter()
        .chain([status.start, xi_line, tau_line])
        .chain(status.skip(1))
        .chain(rod.filter(|_| body_first.is_none()))
        .chain(release)
        .collect();
    let mut order = first.clone();
    order.extend((0..all.len()).filter(|i| !first.contains(i)));
    order
        .into_iter()
        .take(rows)
        .map(|i| all[i].clone())
        .collect()
}

/// The readout lines, and which of them hold the release, the status and the body's phase.
struct Readouts {
    lines: Vec<Line<'static>>,
    release: std::ops::Range<usize>,
    status: std::ops::Range<usize>,
    rod: Option<usize>,
}

fn readouts(app: &App, th: &Theme) -> Readouts {
    let s = app.sim().now();
    let mut out: Vec<Line<'static>> = release(&app.initial())
        .into_iter()
        .map(|l| Line::from(Span::styled(l, Style::default().fg(th.accent))))
        .collect();
    let release = 0..out.len();
    motion_lines(app, th, &s, &mut out);
    // A lesson's open prediction: the status says nothing the run has not shown yet.
    let (st, col) = if app.outcome_open() && app.sim().outcome_now() != Outcome::Running {
        ("y or n: will it escape?".into(), th.slipping)
    } else {
        status_text(app.sim(), th)
    };
    let status_start = out.len();
    for l in st.lines() {
        out.push(Line::from(Span::styled(
            l.to_string(),
            Style::default().fg(col).add_modifier(Modifier::BOLD),
        )));
    }
    let status = status_start..out.len();
    spin::lines(app, th, &mut out);
    if let Some(u) = app.units() {
        table_lines(app, th, u, &mut out);
    }
    model_lines(app, th, &mut out);
    let rod = app
        .scene()
        .body
        .map(|b| body_lines(app, th, b, &s, &mut out));
    cost_lines(app, th, &mut out);
    if let Some(p) = &app.paper() {
        let (st, col) = status_text(p, th);
        out.push(Line::from(Span::styled(
            "paper: rk2-raw dt=1e-3 ○",
            Style::default().fg(th.accent),
        )));
        for l in st.lines() {
            out.push(Line::from(Span::styled(
                l.to_string(),
                Style::default().fg(col),
            )));
        }
        out.push(kv("  ξ", num(p.now().xi(), 5), th));
    }
    if !app.pins().is_empty() {
        let names: Vec<String> = app
            .pins()
            .iter()
            .map(|p| format!("{}{}", p.marker, p.spec.label))
            .collect();
        out.push(kv("pins", names.join(" "), th));
    }
    arrow_legend(app, th, &mut out);
    Readouts {
        lines: out,
        release,
        status,
        rod,
    }
}

/// The release, in the panel's first line; v0 on a second where the line would not fit the
/// panel (a φ and a v0 of many digits, as the mouse sets them), rather than cut a number.
fn release(i: &crate::engine::Initial) -> Vec<String> {
    let xi0 = num(i.xi0, 3);
    match i.release {
        crate::engine::Release::Velocity => {
            let (at, v0) = (format!("ξ0 {xi0} φ {}", angle(i.phi)), speed(i.v0));
            let line = format!("{at} v0 {v0}");
            if line.width() <= usize::from(super::PANEL_W - 2) {
                vec![line]
            } else {
                vec![at, format!("v0 {v0}")]
            }
        }
        crate::engine::Release::TableRest => vec![format!("ξ0 {xi0} rest on table")],
        crate::engine::Release::LabRest => vec![format!("ξ0 {xi0} rest in lab")],
    }
}

/// Where the particle is and how it moves at `s`: τ, ξ, the angles in the frame shown, ξ′
/// and |u|, each with its SI value beside it with a real table (--mu, --rpm).
fn motion_lines(app: &App, th: &Theme, s: &crate::engine::State, out: &mut Vec<Line<'static>>) {
    let motion = app.sim().motion();
    let si = |x: f64, show: fn(f64) -> String| {
        app.units()
            .map_or(String::new(), |_| format!(" = {}", show(x)))
    };
    let (tau_si, xi_si, rate_si, xi_dot_si, u_si) = match app.units() {
        Some(u) => (
            si(s.tau * u.t_s(), si_time),
            si(s.xi() * u.r_max_m(), si_length),
            u.omega(),
            si(motion.xi_dot(s) * u.speed_m_s(), si_speed),
            si(motion.u_lab(s).length() * u.speed_m_s(), si_speed),
        ),
        None => (
            String::new(),
            String::new(),
            f64::NAN,
            String::new(),
            String::new(),
        ),
    };
    // θ′ in rad/s: the table's own Ω times the dimensionless rate.
    let lab_rate = |t: f64| {
        if rate_si.is_finite() {
            format!("{} = {}", num(t, 4), si_rate(t * rate_si))
        } else {
            num(t, 4)
        }
    };
    // A spun-up table's rate changes: its τ is t·Ω_ref, the reference rate's (its seconds,
    // with a real table, are said beside it).
    let tau_si = match app.scene().spin {
        Some(_) if tau_si.is_empty() => " = t·Ω_ref".into(),
        _ => tau_si,
    };
    out.push(kv("τ", format!("{}{tau_si}", num(s.tau, 3)), th));
    out.push(kv("ξ", format!("{}{xi_si}", num(s.xi(), 5)), th));
    // Angles in the frame shown: θ in the lab; in the rotating view the table-frame angle Θ
    // and Θ′ = θ′ − 1 (a particle at rest on the table has Θ′ = 0), with the paper's θ′ kept.
    let direction = |p: glam::DVec2| {
        if p.length_squared() > 0.0 {
            angle(p.y.atan2(p.x))
        } else {
            "—".into()
        }
    };
    let theta_dot = s.theta_dot();
    match app.view().frame {
        crate::engine::Frame::Lab => {
            out.push(kv("θ", direction(s.r), th));
            out.push(kv("θ′", theta_dot.map_or("—".into(), lab_rate), th));
        }
        crate::engine::Frame::Table => {
            out.push(kv("Θ", direction(motion.in_frame(s, app.view().frame)), th));
            out.push(kv(
                "Θ′",
                theta_dot.map_or("—".into(), |t| num(t - motion.omega(s.tau), 4)),
                th,
            ));
            out.push(kv("θ′ lab", theta_dot.map_or("—".into(), lab_rate), th));
        }
    }
    out.push(kv(
        "ξ′",
        format!("{}{xi_dot_si}", rate(motion.xi_dot(s), 4)),
        th,
    ));
    out.push(kv(
        "|u|",
        format!("{}{u_si}", rate(motion.u_lab(s).length(), 4)),
        th,
    ));
}

/// The table and the release in SI, while units are on: what μ, rpm and g change.
fn table_lines(
    app: &App,
    th: &Theme,
    u: crate::engine::units::Units,
    out: &mut Vec<Line<'static>>,
) {
    let i = &app.initial();
    let r0 = match i.release {
        crate::engine::Release::Velocity => {
            format!("{} φ {}", si_length(i.xi0 * u.r_max_m()), angle(i.phi))
        }
        _ => format!("{} at rest", si_length(i.xi0 * u.r_max_m())),
    };
    out.push(kv("r0", r0, th));
    if i.release == crate::engine::Release::Velocity {
        out.push(kv("v0", si_speed(i.v0 * u.speed_m_s()), th));
    }
    out.push(kv(
        "μ g",
        format!("{}, {} m/s²", num(u.mu, 2), num(u.g, 2)),
        th,
    ));
    // A spun-up table's Ω moves: its [units] rpm is the reference rate of its units.
    out.push(kv(
        if app.scene().spin.is_some() {
            "Ω ref"
        } else {
            "Ω"
        },
        format!(
            "{} {} rpm",
            si_rate(u.omega()),
            num(u.rpm, if u.rpm < 100.0 { 1 } else { 0 })
        ),
        th,
    ));
    out.push(kv("R_max", unit_of(&u, Quantity::Length), th));
}

/// The model run: μ = 0's closed form, Stokes drag, or the friction's integrator.
fn model_lines(app: &App, th: &Theme, out: &mut Vec<Line<'static>>) {
    if app.initial().frictionless {
        out.push(kv("μ = 0", "closed form".into(), th));
    } else if let Some(gamma) = app.settings().stokes() {
        out.push(kv("Stokes γ", num(gamma, 4), th));
        out.push(kv(
            "leaves",
            format!("e^{}τ", num(crate::engine::stokes::growth_rate(gamma), 4)),
            th,
        ));
    } else {
        if app.settings().hold() != 1.0 {
            out.push(kv("μs/μk", num(app.settings().hold(), 4), th));
        }
        out.push(kv(
            app.settings().method().into(),
            crate::present::accuracy(&app.settings()),
            th,
        ));
    }
}

/// What the run costs (steps, the last step in step mode, right-hand sides) and how fast it
/// plays.
fn cost_lines(app: &App, th: &Theme, out: &mut Vec<Line<'static>>) {
    let c = app.sim().cost();
    out.push(kv("steps", format!("{} rej {}", c.steps, c.rejected), th));
    if app.view().step_mode
        && let Some(st) = app.sim().last_step()
    {
        out.push(kv(
            "h",
            format!("{} {}", sci(st.h, 1), st.limit.describe()),
            th,
        ));
        if let Some(e) = st.err_ratio {
            let rej = if st.rejected > 0 {
                format!(" ({} rejected)", st.rejected)
            } else {
                String::new()
            };
            out.push(kv("err/tol", format!("{}{rej}", num(e, 2)), th));
        }
    }
    out.push(kv("RHS", format!("{}", c.rhs_evals), th));
    let play = if app.playing() { "▶" } else { "❚❚" };
    out.push(kv(
        "speed",
        format!("×{} {play}", fmt_speed(app.speed())),
        th,
    ));
}

/// The arrows' legend: exactly the arrows drawn, by their head labels; what is not drawn for
/// being zero says so.
fn arrow_legend(app: &App, th: &Theme, out: &mut Vec<Line<'static>>) {
    if (app.view().forces || app.view().net_force || app.view().velocity) && !app.point_shown() {
        out.push(Line::from(Span::styled(
            "arrows: point's, hidden (C)",
            Style::default().fg(th.muted),
        )));
    } else if app.view().forces || app.view().net_force || app.view().velocity {
        let drawn = crate::ui::canvas::arrows(app, 1.0, 1.0);
        let has = |l: &str| drawn.iter().any(|a| a.label == l);
        if app.view().forces
            && !drawn
                .iter()
                .any(|a| ["fr", "dr", "co", "cf", "eu"].contains(&a.label))
        {
            out.push(Line::from(Span::styled(
                "forces: none in the plane",
                Style::default().fg(th.muted),
            )));
        }
        for fa in &drawn {
            let color = crate::ui::chart::ink(th, fa.ink);
            out.push(Line::from(vec![
                Span::styled(format!("{:<2} ", fa.label), Style::default().fg(color)),
                Span::styled(fa.word, Style::default().fg(color)),
            ]));
        }
        if app.view().net_force && !has("net") {
            out.push(Line::from(Span::styled(
                "net force 0: balanced",
                Style::default().fg(th.muted),
            )));
        }
        let (label, _, _) = crate::ui::canvas::velocity(app);
        if app.view().velocity && !has(label) {
            out.push(Line::from(Span::styled(
                format!("{label} = 0"),
                Style::default().fg(th.muted),
            )));
        }
    }
}

pub fn render(f: &mut TuiFrame, area: Rect, app: &App, th: &Theme) {
    let block = super::titled(format!(" scene {} ", app.scene().name), th);
    let rows = usize::from(block.inner(area).height);
    f.render_widget(
        Paragraph::new(lines_in(app, th, rows))
            .block(block)
            .style(Style::default().bg(th.background)),
        area,
    );
}
