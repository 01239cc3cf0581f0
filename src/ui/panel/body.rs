//! The appendix's body in the panel: its size, its phase and centre at the τ on screen, the
//! two conditions for treating it as a point, and how its track ends.

use super::kv;
use crate::app::App;
use crate::engine::Outcome;
use crate::present::num;
use crate::present::{angle, ratio, si_length};
use crate::theme::Theme;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};

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
pub(super) fn body_lines(
    app: &App,
    th: &Theme,
    b: crate::engine::body::Body,
    s: &crate::engine::State,
    out: &mut Vec<Line<'static>>,
) -> usize {
    let tau = s.tau;
    let now = app.rod().and_then(|r| body_now(r, tau));
    let (xi, stuck) = match &now {
        Some(n) => (n.xi, n.rests),
        None => (s.xi(), app.sim().outcome_now() == Outcome::Stuck),
    };
    let f = crate::engine::body::friction(&app.settings(), app.initial().frictionless, stuck, xi);
    let c = b.conditions(xi, f, app.units().map(|u| u.mu));
    // In exponent form when small: a body 1e-9 long is not "L 0.0000".
    let size = match b.height {
        Some(h) => format!("L {} h {}", ratio(b.length), ratio(h)),
        None => format!("L {}", ratio(b.length)),
    };
    out.push(kv("body", size, th));
    if let Some(u) = app.units() {
        // The same sizes in SI, on a line of their own under the value (the panel is 30
        // wide); one indented span, so plain mode reads it on the body's line.
        let m = |x: f64| si_length(x * u.r_max_m());
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
            format!("{} ψ {}", num(st.q.length(), 5), angle(st.psi)),
            th,
        ));
    }
    let over_run = topple_lines(app, th, b, &c, xi, out);
    let rotation = if c.rotation.is_finite() {
        ratio(c.rotation)
    } else {
        "∞ at ξ = 0".into()
    };
    out.push(kv(
        "L/ξ",
        format!("{rotation} {}", c.rotation_verdict().word()),
        th,
    ));
    if c.out_of_depth() || over_run.is_some_and(|r| r.out_of_depth()) {
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

/// μh/L: the run's largest where the body has a track (the toppling risk is while sliding, at
/// μ_k m g: the appendix's case), and its value `now` where that differs (at rest, ξ of it:
/// the static friction after the stop, not the risk); else at the state on screen. Returns
/// the conditions over the run, where judged.
fn topple_lines(
    app: &App,
    th: &Theme,
    b: crate::engine::body::Body,
    c: &crate::engine::body::Conditions,
    xi: f64,
    out: &mut Vec<Line<'static>>,
) -> Option<crate::engine::body::Conditions> {
    let most = app.rod().map(|r| {
        let at = |(s, p): (&crate::engine::rod::RodState, &crate::engine::rod::Phase)| {
            let rests = *p == crate::engine::rod::Phase::Rest;
            crate::engine::body::friction(&app.settings(), false, rests, s.q.length())
        };
        r.states
            .iter()
            .zip(&r.phases)
            .filter_map(at)
            .fold(0.0, f64::max)
    });
    let mu = app.units().map(|u| u.mu);
    let over_run = most.map(|f| b.conditions(xi, Some(f), mu));
    let topple = |c: &crate::engine::body::Conditions, verdict: bool| match (
        c.topple,
        c.topple_verdict(),
        b.height,
    ) {
        // Without a real table μ_k = 1 bounds it: the number is an upper bound (but 0, with
        // no friction at all, is exact).
        (Some(t), Some(v), _) => format!(
            "{}{}{}",
            if c.mu_assumed && t > 0.0 { "≤ " } else { "" },
            ratio(t),
            if verdict {
                format!(" {}", v.word())
            } else {
                String::new()
            }
        ),
        (_, _, None) => "no height given".into(),
        _ => "not judged (Stokes)".into(),
    };
    match over_run.filter(|r| r.topple.is_some()) {
        Some(r) => {
            out.push(kv("μh/L max", topple(&r, true), th));
            if r.topple != c.topple {
                out.push(kv("  now", topple(c, false), th));
            }
        }
        None => out.push(kv("μh/L", topple(c, true), th)),
    }
    over_run
}
