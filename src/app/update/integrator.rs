//! The "integrator" group: the method, its dt or tol, the paper's RK2 beside it, the error
//! estimate.

use super::super::action::Action;
use super::super::state::App;
use super::{next_of, round_sig};
use crate::engine::method::{DT_RANGE, TOL_RANGE};
use crate::engine::{Method, Settings};
use crate::present::{num, sci};
use strum::VariantArray;

pub(super) fn apply(app: &mut App, action: Action) {
    match action {
        Action::CycleMethod => {
            let (now, mut next) = (
                app.settings().scheme,
                next_of(Method::VARIANTS, app.settings().method()),
            );
            if !next.stick_events() && app.settings().hold() != 1.0 {
                // The paper's raw scheme has μ_s = μ_k and no stops: it cannot hold a particle
                // at μ_s/μ_k ≠ 1 (Settings::validate), so the cycle passes it by.
                app.notice = Some(format!(
                    "{next} skipped: the paper's scheme has μs = μk, and this scene μs/μk = {}",
                    app.settings().hold()
                ));
                next = next_of(Method::VARIANTS, next);
            } else if !next.stick_events() && app.scene().spin.is_some() {
                // The slip and the stops are the spin-up's events (SpinRun::new refuses it).
                app.notice = Some(format!(
                    "{next} skipped: the spin-up locates its slip and stops as events"
                ));
                next = next_of(Method::VARIANTS, next);
            }
            // A fixed step carries over between the fixed-step methods, a tolerance between
            // the adaptive ones; else the default.
            let knob = match now.tol() {
                Some(tol) if next.adaptive() => tol,
                None if !next.adaptive() => now.knob(),
                _ => next.default_knob(),
            };
            let settings = Settings {
                scheme: next.with(knob),
                ..app.settings()
            };
            app.exploration.set_settings(settings);
        }
        Action::Loosen | Action::Tighten => {
            let k = if action == Action::Loosen {
                10f64.sqrt()
            } else {
                1.0 / 10f64.sqrt()
            };
            let mut settings = app.settings();
            let s = &mut settings.scheme;
            let range = if s.method().adaptive() {
                TOL_RANGE
            } else {
                DT_RANGE
            };
            *s = s.with_knob(round_sig(s.knob() * k).clamp(range.0, range.1));
            app.exploration.set_settings(settings);
        }
        Action::ToggleCompare => {
            // It catches up with the run on screen over the next ticks, within each tick's
            // step budget: the key itself does no integration.
            let on = app.paper().is_none();
            app.exploration.compare(on);
            app.catch_up();
        }
        Action::EstimateError if app.initial().frictionless => {
            app.notice =
                Some("μ = 0 is computed in closed form: exact, no error to estimate".into());
        }
        Action::EstimateError if app.settings().stokes().is_some() => {
            app.notice =
                Some("Stokes drag is computed in closed form: exact, no error to estimate".into());
        }
        Action::EstimateError => {
            app.notice = Some(match app.sim().error_estimate() {
                Ok(e) => format!(
                    "error at τ = {}: |Δr| = {} against dp54 tol={} ({} RHS)",
                    num(e.tau, 3),
                    sci(e.error, 1),
                    sci(e.tol, 0),
                    e.rhs_evals
                ),
                Err(e) => format!("no estimate: {e}"),
            });
        }
        // Other groups' actions: `update` never sends them here.
        _ => {}
    }
}
