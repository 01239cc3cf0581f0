//! The readouts of a spun-up table: how the coin stands (riding, sliding, escaped), the
//! table's rate now and, once it has slipped, at which rate, the μ a student reads from that
//! rate (Ω² r0 / g, the Euler force ignored) beside the true μ_s, and the closed form.

use super::kv;
use crate::app::App;
use crate::engine::Outcome;
use crate::engine::spinup::{Onset, SpinRun};
use crate::present::num;
use crate::sim::{Motion, Sim};
use crate::theme::Theme;
use ratatui::style::Color;
use ratatui::text::Line;

/// How the coin stands at the sample on screen, and its colour: what a student sees, so the
/// slip is said only once it has come.
pub fn status(sim: &Sim, th: &Theme) -> (String, Color) {
    let now = sim.now();
    match (sim.outcome_now(), sim.escape()) {
        (Outcome::Escaped, Some(e)) => (
            format!(
                "escape certified\n  ξΩ² > 1, moving out\n  at τ = {}",
                num(e.tau, 3)
            ),
            th.escaped,
        ),
        _ if sim.motion().riding(&now) => ("riding the table".into(), th.stuck),
        _ => ("sliding".into(), th.slipping),
    }
}

/// The table's rate now, and the slip once it has come.
pub fn lines(app: &App, th: &Theme, out: &mut Vec<Line<'static>>) {
    let Motion::Spin(run) = app.sim().motion() else {
        return;
    };
    let tau = app.sim().now().tau;
    let ramp = run.ramp();
    let rpm = |omega: f64| {
        app.units().map_or(String::new(), |u| {
            format!(" = {} rpm", num(omega * u.rpm, 1))
        })
    };
    let omega = ramp.omega(tau);
    out.push(kv("Ω", format!("{}{}", num(omega, 4), rpm(omega)), th));
    out.push(kv("Ω′", num(ramp.rate, 4), th));
    match run.slip().filter(|s| tau >= s.tau) {
        Some(slip) => {
            out.push(kv("slip τ", num(slip.tau, 3), th));
            out.push(kv(
                "slip Ω",
                format!("{}{}", num(slip.omega, 4), rpm(slip.omega)),
                th,
            ));
            out.push(kv("μ read", mu_read(app, run, slip.inferred_mu), th));
            if let Onset::At { omega, .. } = ramp.onset(run.xi0(), run.settings().hold()) {
                out.push(kv("closed", format!("Ω {}", num(omega, 6)), th));
            }
        }
        None => out.push(kv("slip", "not yet".into(), th)),
    }
}

/// Ω_slip² r0 / g: as a fraction of the true μ_s, or beside it with a real table.
fn mu_read(app: &App, run: &SpinRun, inferred: f64) -> String {
    let hold = run.settings().hold();
    match app.units() {
        Some(u) => format!("{} (μs {})", num(inferred * u.mu, 4), num(hold * u.mu, 4)),
        None => format!("{} μs", num(inferred / hold, 4)),
    }
}
