//! The rest radius page's chart: Fig. 6, where a particle released at rest in the lab comes to
//! rest, against ξ0.

use super::super::{Chart, Ink, Mark, Series};
use crate::analysis::{REST_POINTS, REST_XI0_MAX};
use crate::app::App;
use crate::app::pages::Rest;
use crate::present::{Quantity, num};

/// The radii computed for the settings on screen, if any.
pub fn shown(app: &App) -> Option<&Rest> {
    let settings = crate::analysis::settings_for(app.settings());
    app.charts()
        .rest
        .as_ref()
        .filter(|r| r.settings == settings)
}

/// Fig. 6's chart: the final ξ of each release at rest in the lab against its ξ0 (those that
/// escape drawn at 1), ξ0c and the ξ0 on screen marked.
pub fn chart(app: &App) -> Chart {
    let rest = shown(app);
    let xi0c = rest.and_then(|r| r.critical.flatten());
    let mut points = Vec::new();
    let mut escaped = Vec::new();
    let mut marks = Vec::new();
    let mut progress = ", computing…".to_string();
    if let Some(r) = rest {
        for (k, v) in r.xi.iter().enumerate() {
            let xi0 = REST_XI0_MAX * k as f64 / (REST_POINTS - 1) as f64;
            match v {
                Some(Some(xi)) => points.push((xi0, *xi)),
                Some(None) => escaped.push((xi0, 1.0)),
                None => {}
            }
        }
        let done = r.xi.iter().filter(|v| v.is_some()).count();
        progress = if done < r.xi.len() || r.critical.is_none() {
            format!(", {done}/{} radii", r.xi.len())
        } else {
            String::new()
        };
        if let Some(c) = xi0c {
            marks.push(Mark::VLine {
                x: c,
                label: format!("ξ0c={}", num(c, 4)),
                ink: Ink::Escaped,
            });
        }
    }
    marks.push(Mark::VLine {
        x: app.initial().xi0.min(REST_XI0_MAX),
        label: "now".into(),
        ink: Ink::Particle,
    });
    Chart {
        title: crate::present::alternatives(&[
            format!("rest radius (Fig. 6): at rest in the lab at ξ0{progress}"),
            format!("rest radius (Fig. 6){progress}"),
            "rest radius".to_string(),
        ]),
        note: xi0c.map_or(String::new(), |c| format!("ξ0c = {}", num(c, 6))),
        x_label: crate::plot::axis("ξ0", Quantity::Length, app.units()),
        y_label: crate::plot::axis("final ξ", Quantity::Length, app.units()),
        x: [0.0, REST_XI0_MAX],
        y: [0.0, 1.05],
        series: vec![
            Series {
                name: "stuck".into(),
                ink: Ink::Trail,
                points,
                style: crate::plot::Style::Dots,
            },
            Series {
                name: "escapes (drawn at 1)".into(),
                ink: Ink::Escaped,
                points: escaped,
                style: crate::plot::Style::Dots,
            },
        ],
        marks,
        ..Chart::default()
    }
}
