//! `turntable spinup`: the table spun up under a coin at rest until it slides
//! (`engine::spinup`), the slip located and set beside its closed form, the μ a student would
//! infer from the slip rpm beside the true one, and how the slide ends.

use super::report::Report;
use super::{CmdResult, Error, NumericsArgs, UnitsArgs, num};
use crate::engine::spinup::{Onset, Phase, Ramp, SpinRun};
use crate::engine::units::Units;
use crate::engine::{Initial, Settings};
use clap::Args;
use serde::Serialize;
use std::fmt::Write as _;

#[derive(Args, Debug)]
pub struct SpinupArgs {
    /// Where the coin rests on the table, xi0 (units of R_max = mu_k g / Omega_ref^2, with
    /// Omega_ref the reference rate: --rpm, else the unit).
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub xi0: f64,
    /// The table's angular acceleration dOmega/dtau (> 0, units of Omega_ref^2).
    #[arg(long, allow_hyphen_values = true, required_unless_present = "scene")]
    pub rate: Option<f64>,
    /// The table's rate when the ramp starts (≥ 0, units of Omega_ref).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub omega0: f64,
    /// A scene file with [spin] (rate, omega0): its coin at rest, ramp, settings and units.
    #[arg(long, value_name = "PATH", conflicts_with_all = ["rate", "xi0", "omega0", "method", "tol", "dt", "frame", "max_steps", "coupling", "mu_static_ratio", "gamma", "mu", "rpm", "gravity"])]
    pub scene: Option<String>,
    /// Stop at this time if escape is not certified by then.
    #[arg(long, default_value_t = 100.0, allow_hyphen_values = true)]
    pub tau_max: f64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub numerics: NumericsArgs,
    #[command(flatten)]
    pub units: UnitsArgs,
}

/// `spinup --json`.
#[derive(Debug, Serialize)]
pub struct SpinupReport {
    pub xi0: f64,
    pub rate: f64,
    pub omega0: f64,
    pub mu_static_ratio: f64,
    pub slip_tau: Option<f64>,
    pub slip_omega: Option<f64>,
    pub closed_form_tau: Option<f64>,
    pub closed_form_omega: Option<f64>,
    pub mu_inferred: Option<f64>,
    pub outcome: &'static str,
    pub escape_tau: Option<f64>,
    pub tau: f64,
    pub xi: f64,
    pub steps: u64,
    pub rhs_evals: u64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub units: Option<SpinupUnits>,
}

/// `spinup --json`'s `units`: the slip as a student at a real table would read it.
#[derive(Debug, Serialize)]
pub struct SpinupUnits {
    pub mu: f64,
    pub rpm: f64,
    pub g: f64,
    pub r0_m: f64,
    pub alpha_rad_s2: f64,
    pub slip_rpm: Option<f64>,
    pub mu_s: f64,
    pub mu_inferred: Option<f64>,
}

/// The coin, ramp, settings and units asked for: a scene's, or the flags'.
fn inputs(a: &SpinupArgs) -> Result<(f64, Ramp, Settings, Option<Units>), Error> {
    if let Some(path) = &a.scene {
        let scene = crate::scene::Scene::load(path)?;
        let Some(ramp) = scene.spin else {
            return Err(Error::invalid(format!(
                "scene {path} has no [spin] (rate, omega0): add one, or give --rate"
            )));
        };
        return Ok((scene.initial.xi0, ramp, scene.settings, scene.units));
    }
    let ramp = Ramp {
        rate: a.rate.unwrap_or(f64::NAN),
        omega0: a.omega0,
    };
    Ok((a.xi0, ramp, a.numerics.settings()?, a.units.units()?))
}

pub fn spinup(a: SpinupArgs) -> CmdResult {
    let (xi0, ramp, settings, units) = inputs(&a)?;
    if !(a.tau_max.is_finite() && a.tau_max > 0.0 && a.tau_max <= 1e9) {
        return Err(Error::invalid(format!(
            "--tau-max must lie in (0, 1e9], got {}",
            Initial::show(a.tau_max)
        )));
    }
    let named = |e| crate::check::named(e, crate::check::Via::Flags);
    let mut run = SpinRun::new(ramp, xi0, settings).map_err(named)?;
    run.run(a.tau_max, true)?;
    let hold = settings.hold();
    let (closed_tau, closed_omega) = match ramp.onset(xi0, hold) {
        Onset::At { tau, omega } => (Some(tau), Some(omega)),
        Onset::AtOnce => (Some(0.0), Some(ramp.omega0)),
        Onset::Never => (None, None),
    };
    let slip = run.slip();
    let (outcome, end) = match (run.escape(), run.phase()) {
        (Some((_, s)), _) => ("escaped", s),
        (None, Phase::Stuck { .. }) => ("stuck", run.state_at(run.tau())?),
        (None, Phase::Sliding) => ("running", run.state_at(run.tau())?),
    };
    let report = SpinupReport {
        xi0,
        rate: ramp.rate,
        omega0: ramp.omega0,
        mu_static_ratio: hold,
        slip_tau: slip.map(|s| s.tau),
        slip_omega: slip.map(|s| s.omega),
        closed_form_tau: closed_tau,
        closed_form_omega: closed_omega,
        mu_inferred: slip.map(|s| s.inferred_mu),
        outcome,
        escape_tau: run.escape().map(|(t, _)| t),
        tau: end.tau,
        xi: end.xi(),
        steps: run.cost().steps,
        rhs_evals: run.cost().rhs_evals,
        units: units.map(|u| si(&u, xi0, ramp, hold, slip.map(|s| (s.omega, s.inferred_mu)))),
    };
    let out = if a.json {
        serde_json::to_string(&report).map_err(|e| Error::Failed(e.to_string()))? + "\n"
    } else {
        report.text()
    };
    crate::files::emit(None, &out)?;
    Ok(())
}

/// The slip on the table `u`, its rpm the reference rate.
fn si(u: &Units, xi0: f64, ramp: Ramp, hold: f64, slip: Option<(f64, f64)>) -> SpinupUnits {
    SpinupUnits {
        mu: u.mu,
        rpm: u.rpm,
        g: u.g,
        r0_m: xi0 * u.r_max_m(),
        alpha_rad_s2: ramp.rate * u.omega() * u.omega(),
        slip_rpm: slip.map(|(w, _)| w * u.rpm),
        mu_s: hold * u.mu,
        mu_inferred: slip.map(|(_, m)| m * u.mu),
    }
}

impl Report for SpinupReport {
    fn text(&self) -> String {
        let mut t = String::new();
        let _ = writeln!(
            t,
            "coin at rest at xi0 = {}, table spun up from Omega0 = {} at dOmega/dtau = {} (mu_s/mu_k = {})",
            num(self.xi0),
            num(self.omega0),
            num(self.rate),
            num(self.mu_static_ratio)
        );
        match (self.slip_tau, self.slip_omega, self.closed_form_tau) {
            (Some(tau), Some(w), Some(ct)) => {
                let _ = writeln!(
                    t,
                    "slips at tau = {tau:.12}, Omega = {w:.12} (closed form: tau = {ct:.12}, differs by {:.1e})",
                    (tau - ct).abs()
                );
            }
            _ => {
                let _ = writeln!(t, "never slips (it rests at the centre)");
            }
        }
        if let Some(m) = self.mu_inferred {
            let _ = writeln!(
                t,
                "mu inferred from the slip, Omega_slip^2 r0/g (no Euler force): {m:.6} mu_k, true mu_s = {} mu_k ({:+.3}%)",
                num(self.mu_static_ratio),
                100.0 * (m / self.mu_static_ratio - 1.0)
            );
        }
        if let Some(u) = &self.units {
            let _ = writeln!(
                t,
                "on the table mu {}, {} rpm reference, g {}: r0 = {:.4} m, alpha = {:.4} rad/s^2",
                num(u.mu),
                num(u.rpm),
                num(u.g),
                u.r0_m,
                u.alpha_rad_s2
            );
            if let (Some(rpm), Some(m)) = (u.slip_rpm, u.mu_inferred) {
                let _ = writeln!(
                    t,
                    "slips at {rpm:.3} rpm: a student infers mu = {m:.4}, the true mu_s is {:.4}",
                    u.mu_s
                );
            }
        }
        let _ = write!(t, "{}", self.outcome);
        if let Some(e) = self.escape_tau {
            let _ = write!(t, " (certified at tau = {e:.6}: xi Omega^2 > 1 moving out)");
        }
        let _ = writeln!(
            t,
            "; at tau = {:.6}, xi = {:.6}; {} steps, {} rhs evaluations",
            self.tau, self.xi, self.steps, self.rhs_evals
        );
        t
    }
}
