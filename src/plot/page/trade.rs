//! The work–precision page's chart (issue 42, item 5): for the release on screen, each method
//! and tolerance (and the fixed-step methods at a few dt's, the paper's RK2 at 1e-3 among them)
//! as a point, its error against the converged reference over its work, both on decades; no
//! error told below the reference's resolution (drawn at it, said "< resolution"); the stated
//! bounds beside; the explorer's setting and the picked point marked.

use super::super::{Chart, Ink, Mark, Scale, Series, Style};
use crate::analysis::trade::{Ending, TRADE_TAU, trade_base};
use crate::app::App;
use crate::app::pages::{Trade, trade_picked, trade_schemes};
use crate::engine::method::Scheme;
use crate::engine::{Method, Outcome, Settings};
use crate::present::{accuracy, alternatives, sci};
use strum::VariantArray;

/// The runs computed for the release and settings on screen, if any.
pub fn shown(app: &App) -> Option<&Trade> {
    app.charts()
        .trade(&app.initial(), trade_base(app.settings()))
}

/// Whether every run of the page is in.
pub fn whole(app: &App) -> bool {
    shown(app).is_some_and(|t| {
        t.reference.is_some()
            && t.check.is_some()
            && trade_schemes(&app.initial(), app.settings())
                .iter()
                .all(|s| t.point(*s).is_some())
    })
}

/// A setting for people: `dop853 tol=1e-6`.
pub fn name(scheme: Scheme) -> String {
    let s = Settings {
        scheme,
        ..Settings::default()
    };
    format!("{} {}", scheme.method(), accuracy(&s))
}

/// The colour a method's points take.
fn ink(m: Method) -> Ink {
    match m {
        Method::Rk2Raw => Ink::Paper,
        Method::Rk2 => Ink::Friction,
        Method::Rk4 => Ink::Coriolis,
        Method::Dp54 => Ink::Trail,
        Method::Dop853 => Ink::Accent,
    }
}

/// The error a point is drawn at: its error against the reference, no lower than the
/// reference's resolution; None when it ended otherwise (or nothing is known yet).
fn drawn_error(t: &Trade, e: &Ending) -> Option<f64> {
    let (r, res) = (t.reference??, t.resolution()?);
    e.error(&r).map(|err| err.max(res))
}

/// What is measured, in words, from how the reference ended.
pub fn measured(t: Option<&Trade>) -> String {
    let Some(t) = t else {
        return "computing the reference…".into();
    };
    let reference = crate::sim::ending::reference(Settings::default()).scheme;
    let refname = format!("{} {}", reference.method(), sci(reference.knob(), 0));
    let Some(Some(r)) = t.reference else {
        return match t.reference {
            Some(None) => format!("the reference ({refname}) could not finish: no error is told"),
            _ => format!("computing the reference ({refname})…"),
        };
    };
    let what = match r.outcome {
        Outcome::Stuck => "when and where it stops",
        Outcome::Escaped => "when and where its escape is certified",
        Outcome::Running => "where it is at τ-max",
    };
    let res = match (t.check, t.resolution()) {
        (Some(_), Some(res)) => sci(res, 1),
        (None, _) => "…".into(),
        (Some(_), None) => "none (its cross-check ends otherwise)".into(),
    };
    alternatives(&[
        format!(
            "error: {what}, max(|Δτ|, |Δr|), against {refname}; resolution {res} (its agreement with dp54 tol=1e-12 in the other frame)"
        ),
        format!("error: {what}, max(|Δτ|, |Δr|), against {refname}; resolution {res}"),
        format!("error: {what} vs {refname} (resolution {res})"),
        format!("{what} vs {refname} (res. {res})"),
        format!("vs {refname} (res. {res})"),
    ])
}

/// One point in words after `lead` (`now`, `picked`): its error (or "< resolution"), the bound
/// it stated, its work, and whether the end game took its stop; a shorter wording for a
/// narrow box, whose clauses drop from the end.
pub fn said(t: Option<&Trade>, scheme: Scheme, lead: &str) -> String {
    let head = name(scheme);
    let short = format!("{} {}", scheme.method(), sci(scheme.knob(), 0));
    let Some(end) = t.and_then(|t| t.point(scheme)) else {
        return alternatives(&[
            format!("{lead} {head}: computing…"),
            format!("{lead} {short}: …"),
        ]);
    };
    let (Some(e), Some(t)) = (end, t) else {
        return alternatives(&[
            format!("{lead} {head}: could not finish within its step budget"),
            format!("{lead} {short}: did not finish"),
        ]);
    };
    let (error, brief) = match (t.reference, t.resolution()) {
        (Some(Some(r)), Some(res)) => match e.error(&r) {
            Some(err) if err < res => (
                format!("error < resolution {}", sci(res, 0)),
                format!("< res. {}", sci(res, 0)),
            ),
            Some(err) => (format!("error {}", sci(err, 1)), sci(err, 1)),
            None => (
                format!(
                    "ends otherwise: it {} where the reference {}",
                    ends(e.outcome),
                    ends(r.outcome)
                ),
                format!("{} (wrong)", ends(e.outcome)),
            ),
        },
        _ => ("error: awaiting the reference".into(), "…".into()),
    };
    let (stated, stated_brief) = match e.stated {
        None => ("states no error".to_string(), "states none".to_string()),
        Some(s) if s.is_finite() => (
            format!("stated ≤ {}", sci(s, 1)),
            format!("stated {}", sci(s, 1)),
        ),
        Some(_) => (
            "states none: outcome in doubt".to_string(),
            "in doubt".to_string(),
        ),
    };
    let end_game = if e.end_game {
        ", the end game took the stop"
    } else {
        ""
    };
    alternatives(&[
        format!("{lead} {head}: {error}, {stated}, {} RHS{end_game}", e.rhs),
        format!(
            "{lead} {short}: {brief} ({stated_brief}), {} RHS{end_game}",
            e.rhs
        ),
    ])
}

fn ends(o: Outcome) -> &'static str {
    match o {
        Outcome::Stuck => "stops",
        Outcome::Escaped => "escapes",
        Outcome::Running => "still moves at τ-max",
    }
}

/// Each method's line through its settings (loosest first), named at its tightest, with the
/// stated bounds beside and every value drawn (for the ranges).
#[derive(Default)]
struct Lines {
    series: Vec<Series>,
    names: Vec<Mark>,
    stated: Vec<(f64, f64)>,
    xs: Vec<f64>,
    ys: Vec<f64>,
}

/// [`Lines`] of `schemes`, each drawn where `at` puts it (None: not drawn).
fn lines(schemes: &[Scheme], at: &dyn Fn(Scheme) -> Option<(f64, f64, Ending)>) -> Lines {
    let mut l = Lines::default();
    for &m in Method::VARIANTS {
        let mut mine: Vec<Scheme> = schemes
            .iter()
            .copied()
            .filter(|s| s.method() == m)
            .collect();
        mine.sort_by(|a, b| b.knob().total_cmp(&a.knob()));
        let points: Vec<(f64, f64)> = mine
            .iter()
            .filter_map(|&s| at(s))
            .map(|(x, y, e)| {
                if let Some(b) = e.stated.filter(|b| b.is_finite() && *b > 0.0) {
                    l.stated.push((x, b.log10()));
                    l.ys.push(b.log10());
                }
                l.xs.push(x);
                l.ys.push(y);
                (x, y)
            })
            .collect();
        if let Some(&(x, y)) = points.last() {
            let name = match m {
                Method::Rk2Raw => "paper".to_string(),
                _ => m.to_string(),
            };
            // Named at its tightest setting too, where the lines part.
            l.names.push(Mark::Text {
                x,
                y,
                label: name.clone(),
                ink: ink(m),
            });
            l.series.push(Series::new(name, ink(m), true, points));
        }
    }
    l
}

/// The page's chart: error against RHS evaluations, one line per method through its settings
/// (loosest first), the resolution's line, the stated bounds as dots, the runs that ended
/// otherwise along the top, the explorer's setting and the picked point marked.
pub fn chart(app: &App) -> Chart {
    let (initial, settings) = (app.initial(), app.settings());
    let t = shown(app);
    let schemes = trade_schemes(&initial, settings);
    let done = t.map_or(0, |t| {
        schemes.iter().filter(|s| t.point(**s).is_some()).count()
    });
    let at = |s: Scheme| -> Option<(f64, f64, Ending)> {
        let e = t?.point(s)??;
        let y = drawn_error(t?, &e)?;
        Some(((e.rhs.max(1) as f64).log10(), y.log10(), e))
    };
    let Lines {
        mut series,
        names,
        stated,
        xs,
        ys,
    } = lines(&schemes, &at);
    let res = t.and_then(Trade::resolution).map(f64::log10);
    let lo = res
        .map_or(-12.0, |r| r - 0.5)
        .min(ys.iter().copied().fold(f64::INFINITY, f64::min) - 0.3);
    let hi = ys.iter().copied().fold(lo + 1.0, f64::max) + 0.5;
    let (x0, x1) = match (
        xs.iter().copied().reduce(f64::min),
        xs.iter().copied().reduce(f64::max),
    ) {
        (Some(a), Some(b)) => (a - 0.2, b.max(a + 1.0) + 0.2),
        _ => (1.0, 6.0),
    };
    // The runs that ended otherwise than the reference, along the top.
    let otherwise: Vec<(f64, f64)> = schemes
        .iter()
        .filter_map(|&s| {
            let (t, e) = (t?, t?.point(s)??);
            (e.error(&t.reference??).is_none()).then(|| ((e.rhs.max(1) as f64).log10(), hi - 0.1))
        })
        .collect();
    if let Some(r) = res {
        series.push(Series {
            name: "resolution".into(),
            points: vec![(x0, r), (x1, r)],
            style: Style::Line { dash: 1 },
            ink: Ink::Muted,
        });
    }
    if !stated.is_empty() {
        series.push(Series::new("stated bound", Ink::Muted, false, stated));
    }
    if !otherwise.is_empty() {
        series.push(Series::new(
            "ends otherwise",
            Ink::Escaped,
            false,
            otherwise,
        ));
    }
    let picked = trade_picked(app.view().trade_pick, &initial, settings);
    let mut marks = names;
    let mut mark = |s: Scheme, label: String, ink: Ink| {
        if let Some((x, y, _)) = at(s) {
            marks.push(Mark::Point { x, y, label, ink });
        }
    };
    if picked != settings.scheme {
        mark(picked, format!("{} (Enter)", name(picked)), Ink::Notice);
    }
    mark(settings.scheme, "now".into(), Ink::Particle);
    let progress = if done < schemes.len() {
        format!(", {done}/{} runs", schemes.len())
    } else {
        String::new()
    };
    Chart {
        title: alternatives(&[
            format!(
                "work-precision: error against work for this release, to τ ≤ {TRADE_TAU}{progress}"
            ),
            format!("work-precision{progress}"),
            "work-precision".to_string(),
        ]),
        note: measured(t),
        x_label: "RHS evaluations".into(),
        y_label: "error".into(),
        x: [x0, x1],
        y: [lo, hi],
        x_scale: Scale::Decades,
        y_scale: Scale::Decades,
        series,
        marks,
        ..Chart::default()
    }
}
