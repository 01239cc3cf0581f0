//! Readouts: where the particle is, how the run stands, what it costs; and, when comparing,
//! how the paper's scheme fares from the same start.

use crate::app::App;
use crate::engine::model::{turn_angle, wrap_angle};
use crate::engine::run::raw_at_rest;
use crate::engine::{Certificate, Method, Outcome, Status};
use crate::sim::Sim;
use crate::theme::Theme;
use ratatui::Frame as TuiFrame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use std::f64::consts::PI;

pub use crate::present::num;

/// A release speed: four decimals, up to six where they are not zeros (C's v0 = 0.6078 and
/// its escape speed 0.607797… differ in the sixth).
pub fn speed(v: f64) -> String {
    let s = num(v, 6);
    match s.find('.') {
        Some(dot) => {
            let keep = (dot + 5).max(s.trim_end_matches('0').len());
            s[..keep.min(s.len())].to_string()
        }
        None => s,
    }
}

/// Status of a run at the sample on screen, and its colour.
pub fn status_text(sim: &Sim, th: &Theme) -> (String, ratatui::style::Color) {
    if let Some(e) = &sim.error {
        let _ = e;
        return ("stopped: step budget / underflow".into(), th.escaped);
    }
    let (text, colour) = match sim.outcome_now() {
        Outcome::Stuck => match sim.run.status() {
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
        Outcome::Escaped => match sim.run.escape() {
            // What is certified, true from that instant on, before the particle leaves.
            Some(e) => (
                format!(
                    "escape certified\n  {}\n  at τ = {}",
                    match e.by {
                        Certificate::Radial => "ξ > 1, moving out",
                        Certificate::Energy if sim.run.settings().hold() == 1.0 => {
                            "E < −½: cannot rest"
                        }
                        Certificate::Energy => "E < −½R²: cannot rest",
                    },
                    num(e.tau, 3)
                ),
                th.escaped,
            ),
            None => ("escape certified".into(), th.escaped),
        },
        Outcome::Running => {
            let s = sim.now();
            let raw = sim.run.settings().method() == Method::Rk2Raw;
            if raw && raw_at_rest(&s, sim.run.settings().scheme.knob()) {
                ("≈ at rest (raw RK2 chatters)".into(), th.slipping)
            } else {
                ("slipping".into(), th.slipping)
            }
        }
    };
    match sim.doubt {
        Some(d) if !d.certain && sim.outcome_now() != Outcome::Running => (
            format!("{text}\n  in doubt: the run's\n  error could flip it"),
            colour,
        ),
        _ => (text, colour),
    }
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
pub fn lines(app: &App) -> Vec<Line<'static>> {
    readouts(app).0
}

/// The readout lines that fit in `rows`, most important first when not all do: the status
/// (stuck / slipping / escape certified), then ξ, τ, the body's phase (first of all when the
/// point model is hidden, `C`) and the release, then the rest.
pub fn lines_in(app: &App, rows: usize) -> Vec<Line<'static>> {
    let (all, status, rod) = readouts(app);
    if all.len() <= rows {
        return all;
    }
    let body_first = rod.filter(|_| !app.point_shown());
    let first: Vec<usize> = body_first
        .into_iter()
        .chain([status.start, XI_LINE, TAU_LINE])
        .chain(status.skip(1))
        .chain(rod.filter(|_| body_first.is_none()))
        .chain([0])
        .collect();
    let mut order = first.clone();
    order.extend((0..all.len()).filter(|i| !first.contains(i)));
    order
        .into_iter()
        .take(rows)
        .map(|i| all[i].clone())
        .collect()
}

/// Where τ and ξ stand in [`lines`].
const TAU_LINE: usize = 1;
const XI_LINE: usize = 2;

/// The readout lines, which of them hold the status, and which the body's phase.
fn readouts(app: &App) -> (Vec<Line<'static>>, std::ops::Range<usize>, Option<usize>) {
    let th = &app.theme;
    let s = app.sim().now();
    let i = &app.initial();
    let mut out: Vec<Line<'static>> = Vec::new();
    let init = match i.release {
        crate::engine::Release::Velocity => format!(
            "ξ0 {} φ {}π v0 {}",
            num(i.xi0, 3),
            num(turn_angle(i.phi) / PI, 2),
            speed(i.v0)
        ),
        crate::engine::Release::TableRest => format!("ξ0 {} rest on table", num(i.xi0, 3)),
        crate::engine::Release::LabRest => format!("ξ0 {} rest in lab", num(i.xi0, 3)),
    };
    out.push(Line::from(Span::styled(
        init,
        Style::default().fg(th.accent),
    )));
    // With a real table (--mu, --rpm), the SI value beside the dimensionless one.
    let si = |x: f64, show: fn(f64) -> String| {
        app.units
            .map_or(String::new(), |_| format!(" = {}", show(x)))
    };
    use crate::engine::units::{show_length, show_rate, show_speed, show_time};
    let (tau_si, xi_si, rate_si, xi_dot_si, u_si) = match app.units {
        Some(u) => (
            si(s.tau * u.t_s(), show_time),
            si(s.xi() * u.r_max_m(), show_length),
            u.omega(),
            si(s.xi_dot() * u.speed_m_s(), show_speed),
            si(s.u().length() * u.speed_m_s(), show_speed),
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
            format!("{} = {}", num(t, 4), show_rate(t * rate_si))
        } else {
            num(t, 4)
        }
    };
    out.push(kv("τ", format!("{}{tau_si}", num(s.tau, 3)), th));
    out.push(kv("ξ", format!("{}{xi_si}", num(s.xi(), 5)), th));
    // Angles in the frame shown: θ in the lab; in the rotating view the table-frame angle Θ
    // and Θ′ = θ′ − 1 (a particle at rest on the table has Θ′ = 0), with the paper's θ′ kept.
    let angle = |p: glam::DVec2| {
        if p.length_squared() > 0.0 {
            num(wrap_angle(p.y.atan2(p.x)), 4)
        } else {
            "—".into()
        }
    };
    let theta_dot = s.theta_dot();
    match app.view {
        crate::engine::Frame::Lab => {
            out.push(kv("θ", angle(s.r), th));
            out.push(kv("θ′", theta_dot.map_or("—".into(), lab_rate), th));
        }
        crate::engine::Frame::Table => {
            out.push(kv("Θ", angle(s.q()), th));
            out.push(kv(
                "Θ′",
                theta_dot.map_or("—".into(), |t| num(t - 1.0, 4)),
                th,
            ));
            out.push(kv("θ′ lab", theta_dot.map_or("—".into(), lab_rate), th));
        }
    }
    out.push(kv("ξ′", format!("{}{xi_dot_si}", num(s.xi_dot(), 4)), th));
    out.push(kv("|u|", format!("{}{u_si}", num(s.u().length(), 4)), th));
    let (st, col) = status_text(app.sim(), th);
    let status_start = out.len();
    for l in st.lines() {
        out.push(Line::from(Span::styled(
            l.to_string(),
            Style::default().fg(col).add_modifier(Modifier::BOLD),
        )));
    }
    let status = status_start..out.len();
    if let Some(u) = app.units {
        // The table and the release in SI, while units are on: what μ, rpm and g change.
        use crate::engine::units::show_length as len;
        let deg = turn_angle(i.phi).to_degrees();
        let r0 = match i.release {
            crate::engine::Release::Velocity => {
                format!("{} φ {}°", len(i.xi0 * u.r_max_m()), num(deg, 0))
            }
            _ => format!("{} at rest", len(i.xi0 * u.r_max_m())),
        };
        out.push(kv("r0", r0, th));
        if i.release == crate::engine::Release::Velocity {
            out.push(kv("v0", show_speed(i.v0 * u.speed_m_s()), th));
        }
        out.push(kv(
            "μ g",
            format!("{}, {} m/s²", num(u.mu, 2), num(u.g, 2)),
            th,
        ));
        out.push(kv(
            "Ω",
            format!(
                "{} {} rpm",
                show_rate(u.omega()),
                num(u.rpm, if u.rpm < 100.0 { 1 } else { 0 })
            ),
            th,
        ));
        out.push(kv(
            "R_max",
            u.unit_of(crate::engine::units::Quantity::Length),
            th,
        ));
    }
    let c = app.sim().run.cost();
    if i.frictionless {
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
            app.settings().accuracy_label(),
            th,
        ));
    }
    let rod = app.scene().body.map(|b| body_lines(app, b, &s, &mut out));
    out.push(kv("steps", format!("{} rej {}", c.steps, c.rejected), th));
    if app.step_mode
        && let Some(st) = app.sim().run.last_step()
    {
        out.push(kv("h", format!("{:.1e} {}", st.h, st.limit.describe()), th));
        if let Some(e) = st.err_ratio {
            let rej = if st.rejected > 0 {
                format!(" ({} rejected)", st.rejected)
            } else {
                String::new()
            };
            out.push(kv("err/tol", format!("{e:.2}{rej}"), th));
        }
    }
    out.push(kv("RHS", format!("{}", c.rhs_evals), th));
    let play = if app.playing { "▶" } else { "❚❚" };
    out.push(kv("speed", format!("×{} {play}", fmt_speed(app.speed)), th));
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
    if !app.pins.is_empty() {
        let names: Vec<String> = app
            .pins
            .iter()
            .map(|p| format!("{}{}", p.marker, p.spec.label))
            .collect();
        out.push(kv("pins", names.join(" "), th));
    }
    if (app.forces || app.net_force || app.velocity) && !app.point_shown() {
        out.push(Line::from(Span::styled(
            "arrows: point's, hidden (C)",
            Style::default().fg(th.muted),
        )));
    } else if app.forces || app.net_force || app.velocity {
        // The legend names exactly the arrows drawn, by their head labels; what is not drawn
        // for being zero says so.
        let drawn = crate::ui::canvas::arrows(app, 1.0, 1.0);
        let has = |l: &str| drawn.iter().any(|a| a.label == l);
        if app.forces && !drawn.iter().any(|a| ["fr", "co", "cf"].contains(&a.label)) {
            out.push(Line::from(Span::styled(
                "forces: none in the plane",
                Style::default().fg(th.muted),
            )));
        }
        for fa in &drawn {
            out.push(Line::from(vec![
                Span::styled(format!("{:<2} ", fa.label), Style::default().fg(fa.color)),
                Span::styled(fa.word, Style::default().fg(fa.color)),
            ]));
        }
        if app.net_force && !has("net") {
            out.push(Line::from(Span::styled(
                "net force 0: balanced",
                Style::default().fg(th.muted),
            )));
        }
        let (label, _, _) = crate::ui::canvas::velocity(app);
        if app.velocity && !has(label) {
            out.push(Line::from(Span::styled(
                format!("{label} = 0"),
                Style::default().fg(th.muted),
            )));
        }
    }
    (out, status, rod)
}

/// The body at the τ on screen, as the panel judges it: its centre's radius, whether it rests,
/// and its state and phase where its track has them.
pub struct BodyNow {
    pub xi: f64,
    pub rests: bool,
    pub at: Option<(crate::engine::rod::RodState, crate::engine::rod::Phase)>,
}

/// The body's state at `tau` from its track: where the track ends before `tau` (an escape's
/// certificate, a cut), its last state, not resting.
pub fn body_now(rod: &crate::engine::rod::RodTrack, tau: f64) -> Option<BodyNow> {
    use crate::engine::rod::Phase;
    match rod.at_with_phase(tau) {
        Some((st, ph)) => Some(BodyNow {
            xi: st.q.length(),
            rests: ph == Phase::Rest || (rod.outcome == Outcome::Stuck && tau >= rod.end_tau()),
            at: Some((st, ph)),
        }),
        None => rod.states.last().map(|l| BodyNow {
            xi: l.q.length(),
            rests: false,
            at: None,
        }),
    }
}

/// A body's phase in words: sliding, pivoting about one contact, riding the table.
pub fn phase_word(p: crate::engine::rod::Phase) -> &'static str {
    match p {
        crate::engine::rod::Phase::Slip => "sliding",
        crate::engine::rod::Phase::Pivot { .. } => "pivoting",
        crate::engine::rod::Phase::Rest => "riding the table",
    }
}

/// How the body's track ends, once the τ on screen has reached its end (None before): a key
/// and words that fit the panel, and the reason a cut track stopped. An escape ends at its
/// certificate, though the track follows the body on past it.
pub fn body_end(rod: &crate::engine::rod::RodTrack, tau: f64) -> Option<(String, Option<String>)> {
    use crate::engine::rod::Cut;
    if let Some(c) = rod.escape {
        return (tau >= c).then(|| (format!("escapes (τ = {})", num(c, 3)), None));
    }
    let end = rod.end_tau();
    if tau < end {
        return None;
    }
    Some(match (&rod.cut, rod.outcome) {
        (Some(Cut::Budget(n)), _) => (
            format!("cut at τ = {}", num(end, 2)),
            Some(format!("{n}-step budget")),
        ),
        (Some(Cut::Failed(_)), _) => (
            format!("cut at τ = {}", num(end, 2)),
            Some("its run failed".into()),
        ),
        (None, Outcome::Stuck) => {
            let xi = rod.states.last().map_or(f64::NAN, |s| s.q.length());
            (format!("rests at ξ = {}", num(xi, 5)), None)
        }
        (None, Outcome::Escaped) => (format!("escapes (τ = {})", num(end, 3)), None),
        (None, Outcome::Running) => (format!("slides past τ = {}", num(end, 0)), None),
    })
}

/// The appendix's body: its size, its own phase and centre at the τ on screen (from its
/// track), the two conditions for treating it as a point judged at the body's state (the
/// point's without a track), a warning when either is not ≪ 1, and how the body ends once the
/// τ on screen reaches it. Returns the index of the phase line.
fn body_lines(
    app: &App,
    b: crate::engine::body::Body,
    s: &crate::engine::State,
    out: &mut Vec<Line<'static>>,
) -> usize {
    let th = &app.theme;
    let tau = s.tau;
    let now = app.rod().and_then(|r| body_now(r, tau));
    let (xi, stuck) = match &now {
        Some(n) => (n.xi, n.rests),
        None => (s.xi(), app.sim().outcome_now() == Outcome::Stuck),
    };
    let f = crate::engine::body::friction(&app.settings(), app.initial().frictionless, stuck, xi);
    let c = b.conditions(xi, f, app.units.map(|u| u.mu));
    // In exponent form when small: a body 1e-9 long is not "L 0.0000".
    let size = match b.height {
        Some(h) => format!("L {} h {}", small(b.length), small(h)),
        None => format!("L {}", small(b.length)),
    };
    out.push(kv("body", size, th));
    if let Some(u) = app.units {
        // The same sizes in SI, on a line of their own under the value (the panel is 30
        // wide); one indented span, so plain mode reads it on the body's line.
        let m = |x: f64| crate::engine::units::show_length(x * u.r_max_m());
        let si = match b.height {
            Some(h) => format!("       = {} h {}", m(b.length), m(h)),
            None => format!("       = {}", m(b.length)),
        };
        out.push(Line::from(Span::styled(
            si,
            Style::default().fg(th.foreground),
        )));
    }
    let phase_line = out.len();
    let phase = match (&app.rod(), &now) {
        (None, _) if app.initial().frictionless => "not run: μ = 0".to_string(),
        (None, _) if app.settings().stokes().is_some() => "not run: Stokes".to_string(),
        (None, _) => "not run".to_string(),
        (
            Some(_),
            Some(BodyNow {
                at: Some((_, p)), ..
            }),
        ) => phase_word(*p).to_string(),
        (Some(r), _) if r.escape.is_some() => "escaped".into(),
        (Some(_), _) => "not computed here".into(),
    };
    out.push(kv("rod", phase, th));
    if let Some(BodyNow {
        at: Some((st, _)), ..
    }) = &now
    {
        out.push(kv(
            "rod ξ",
            format!("{} ψ {}", num(st.q.length(), 5), num(wrap_angle(st.psi), 4)),
            th,
        ));
    }
    let topple = match (c.topple, c.topple_verdict(), b.height) {
        // Without a real table μ_k = 1 bounds it: the number is an upper bound (but 0, with
        // no friction at all, is exact).
        (Some(t), Some(v), _) => format!(
            "{}{} {}",
            if c.mu_assumed && t > 0.0 { "≤ " } else { "" },
            small(t),
            v.word()
        ),
        (_, _, None) => "no height given".into(),
        _ => "not judged (Stokes)".into(),
    };
    out.push(kv("μh/L", topple, th));
    let rotation = if c.rotation.is_finite() {
        small(c.rotation)
    } else {
        "∞ at ξ = 0".into()
    };
    out.push(kv(
        "L/ξ",
        format!("{rotation} {}", c.rotation_verdict().word()),
        th,
    ));
    if c.out_of_depth() {
        out.push(Line::from(Span::styled(
            "point model out of its depth",
            Style::default().fg(th.notice).add_modifier(Modifier::BOLD),
        )));
    }
    if let Some((end, why)) = app.rod().and_then(|r| body_end(r, tau)) {
        out.push(kv("ends", end, th));
        if let Some(why) = why {
            out.push(kv("  by", why, th));
        }
    }
    phase_line
}

/// A ratio for the body's readouts: four decimals, or exponent form when small or large.
fn small(x: f64) -> String {
    if (1e-3..1e4).contains(&x) || x == 0.0 {
        num(x, 4)
    } else {
        format!("{x:.2e}")
    }
}

pub fn fmt_speed(s: f64) -> String {
    if s >= 1.0 {
        format!("{s}")
    } else {
        format!("1/{}", (1.0 / s).round())
    }
}

pub fn render(f: &mut TuiFrame, area: Rect, app: &App) {
    let th = &app.theme;
    let block = super::titled(format!(" scene {} ", app.scene().name), th);
    let rows = usize::from(block.inner(area).height);
    f.render_widget(
        Paragraph::new(lines_in(app, rows))
            .block(block)
            .style(Style::default().bg(th.background)),
        area,
    );
}
