//! The numerical commands' reports: one typed struct per command, whose fields are its `--json`
//! object (documented once, in docs/command-line.md's *JSON reports*, and checked against it by
//! `tests/suite/cli.rs`), and whose `text` is its plain output.

use crate::engine::body::{Body, friction};
use crate::engine::doubt::Doubt;
use crate::engine::model::turn_angle;
use crate::engine::rod::RodRun;
use crate::engine::solve::Threshold;
use crate::engine::units::Units;
use crate::engine::{Certificate, CouplingName, Frame, Method, Outcome, Run, Settings, State};
use crate::present::{angle_to, si_length, si_time};
use serde::Serialize;
use std::fmt::Write as _;

mod chosen;
mod threshold;

pub use chosen::ChosenReport;
pub use threshold::*;

/// A command's report: its fields are its JSON; this is its plain output.
pub trait Report {
    fn text(&self) -> String;
}

/// `run --json`.
#[derive(Debug, Serialize)]
pub struct RunReport {
    /// With a body (`--body-length`), how the two-mass body ends (`body.motion.outcome`),
    /// first: the body is what was asked about; `outcome` and what follows are the point
    /// model's from the same release.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body_outcome: Option<Outcome>,
    pub outcome: Outcome,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub certain: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub check: Option<CheckReport>,
    pub tau: f64,
    pub xi: f64,
    pub angle: f64,
    pub speed: f64,
    pub certificate: Option<Certificate>,
    pub escape_tau: Option<f64>,
    pub steps: u64,
    pub rejected: u64,
    pub rhs_evals: u64,
    pub frictionless: bool,
    pub coupling: CouplingName,
    pub mu_static_ratio: Option<f64>,
    pub gamma: Option<f64>,
    pub growth_rate: Option<f64>,
    pub method: Method,
    pub frame: Frame,
    pub tol: Option<f64>,
    pub dt: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub units: Option<UnitsReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body: Option<BodyReport>,
    /// With `--error`: what was asked, what was chosen, and what it cost.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub chosen: Option<ChosenReport>,
}

/// `run --json`'s `body`: the body's size and the appendix's two conditions: μh/L the run's
/// largest (while sliding), L/ξ at the end.
#[derive(Debug, Serialize)]
pub struct BodyReport {
    pub length: f64,
    pub height: Option<f64>,
    /// With units: the length in metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length_m: Option<f64>,
    /// With units: the height in metres (null without a height).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height_m: Option<Option<f64>>,
    pub angle: f64,
    pub mu_h_over_l: Option<f64>,
    pub mu_assumed: bool,
    pub l_over_xi: Option<f64>,
    pub point_ok: bool,
    pub motion: Option<MotionReport>,
}

/// `body.motion`: the two-mass body integrated from the same release (`engine::rod`).
#[derive(Debug, Serialize)]
pub struct MotionReport {
    pub outcome: Outcome,
    pub tau: f64,
    pub xi: f64,
    pub angle: f64,
    pub psi: f64,
    pub steps: u64,
    /// The same release run again at tol/1000 (without `--no-check`): not an independent
    /// method, so no `certain`, but the end's measured distance from a tighter run.
    pub check: Option<MotionCheck>,
}

/// `body.motion.check`: the body run again 1000 times tighter, and how far its end lies from
/// this one's.
#[derive(Debug, Serialize)]
pub struct MotionCheck {
    pub tol: f64,
    /// Null when the check's run failed (`failed` says why).
    pub outcome: Option<Outcome>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failed: Option<String>,
    /// Whether the outcomes agree.
    pub agrees: bool,
    /// |q − q_check|, the centre's distance (at the same outcome).
    pub q_error: Option<f64>,
    /// |ψ − ψ_check| (at the same outcome).
    pub psi_error: Option<f64>,
    /// |τ − τ_check|: when it came to rest or was certified to escape.
    pub tau_error: Option<f64>,
}

/// A body's run to its end, or why it failed.
pub type RodEnd = Result<(RodRun, Outcome), crate::error::Error>;

impl MotionReport {
    /// Its line of `run`'s text (the first, see [`RunReport`]'s).
    fn line(&self) -> String {
        format!(
            "rod      the two-mass body: {} at tau {:.9}, xi {:.12}, rod at psi {} ({} steps)\n",
            self.outcome.name(),
            self.tau,
            self.xi,
            angle_to(self.psi, 6),
            self.steps
        )
    }

    pub fn new(run: &RodRun, outcome: Outcome, check: Option<(f64, RodEnd)>) -> MotionReport {
        let s = run.state;
        MotionReport {
            outcome,
            tau: s.tau,
            xi: s.q.length(),
            angle: turn_angle(s.q.y.atan2(s.q.x)),
            psi: turn_angle(s.psi),
            steps: run.steps(),
            check: check.map(|(tol, c)| match c {
                Ok((c, o)) => {
                    let agrees = o == outcome;
                    let same = |x: f64| agrees.then_some(x).and_then(finite);
                    MotionCheck {
                        tol,
                        outcome: Some(o),
                        failed: None,
                        agrees,
                        q_error: same((s.q - c.state.q).length()),
                        psi_error: same((s.psi - c.state.psi).abs()),
                        tau_error: same((s.tau - c.state.tau).abs()),
                    }
                }
                Err(e) => MotionCheck {
                    tol,
                    outcome: None,
                    failed: Some(e.to_string()),
                    agrees: false,
                    q_error: None,
                    psi_error: None,
                    tau_error: None,
                },
            }),
        }
    }
}

impl BodyReport {
    /// The conditions at `end` of `run`, on the table `units` gives (μ_k = 1 assumed without).
    pub fn new(body: Body, run: &Run, end: &State, units: Option<Units>) -> BodyReport {
        let xi = end.q().length();
        let (settings, frictionless) = (run.settings(), run.initial().frictionless);
        let stuck = run.outcome() == Outcome::Stuck;
        // The appendix's toppling risk is while sliding (μ_k m g): the run's largest friction,
        // not the static friction at rest after a stop (ξ of it), unless it never slid.
        let slid = !matches!(run.status(), crate::engine::Status::Stuck { tau, .. } if tau == 0.0);
        let at_end = friction(&settings, frictionless, stuck, xi);
        let sliding = friction(&settings, frictionless, false, xi).filter(|_| slid);
        let f = match (at_end, sliding) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, _) => a,
        };
        let c = body.conditions(xi, f, units.map(|u| u.mu));
        BodyReport {
            length: body.length,
            height: body.height,
            length_m: units.map(|u| body.length * u.r_max_m()),
            height_m: units.map(|u| body.height.map(|h| h * u.r_max_m())),
            angle: body.angle,
            mu_h_over_l: c.topple,
            mu_assumed: c.mu_assumed,
            l_over_xi: finite(c.rotation),
            point_ok: !c.out_of_depth(),
            motion: None,
        }
    }
}

/// The second opinion on a run ([`crate::engine::doubt`]): dop853, tighter, in the other
/// frame, and the differences it measured (null where the two end differently).
#[derive(Debug, Serialize)]
pub struct CheckReport {
    /// The second opinion's method: `sundman-radau` (its own form, `engine::sundman`) or the
    /// Cartesian run's.
    pub method: String,
    pub tol: Option<f64>,
    pub frame: Frame,
    pub outcome: Option<Outcome>,
    pub margin: f64,
    pub h_error: Option<f64>,
    pub tau_error: Option<f64>,
    pub q_error: Option<f64>,
}

/// `run --json`'s `units`: the table's μ, rpm and g, its scales, and the end in SI.
#[derive(Debug, Serialize)]
#[allow(non_snake_case)]
pub struct UnitsReport {
    pub mu: f64,
    pub rpm: f64,
    pub g: f64,
    pub R_max_m: f64,
    pub T_s: f64,
    pub tau_s: f64,
    pub xi_m: f64,
    pub speed_m_s: f64,
    pub escape_tau_s: Option<f64>,
}

/// A JSON number, or null where a measured difference is infinite.
fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

impl CheckReport {
    fn new(d: &Doubt) -> CheckReport {
        CheckReport {
            method: match d.sundman {
                Some(_) => "sundman-radau".to_string(),
                None => d.check.method().to_string(),
            },
            tol: d.sundman.or(d.check.scheme.tol()),
            frame: if d.sundman.is_some() {
                Frame::Table
            } else {
                d.check.frame
            },
            outcome: d.shadow,
            margin: d.margin,
            h_error: finite(d.error),
            tau_error: finite(d.tau_error),
            q_error: finite(d.q_error),
        }
    }

    fn who(&self) -> String {
        let tol = self.tol.map_or(String::new(), |t| format!(" tol={t:.0e}"));
        if self.method == "sundman-radau" {
            return format!("Radau IIA{tol} in Sundman time and rim distance");
        }
        format!("{}{tol} in the {} frame", self.method, self.frame)
    }
}

impl RunReport {
    /// The report of `run`, ended at `end`, with its second opinion if one was asked for.
    pub fn new(run: &Run, end: &State, doubt: Option<Doubt>, units: Option<Units>) -> RunReport {
        let (q, speed) = (end.q(), end.u_lab().length());
        let settings: Settings = run.settings();
        RunReport {
            body_outcome: None,
            outcome: run.outcome(),
            certain: doubt.map(|d| d.certain),
            check: doubt.as_ref().map(CheckReport::new),
            tau: end.tau,
            xi: q.length(),
            angle: turn_angle(q.y.atan2(q.x)),
            speed,
            certificate: run.escape().map(|e| e.by),
            escape_tau: run.escape().map(|e| e.tau),
            steps: run.cost().steps,
            rejected: run.cost().rejected,
            rhs_evals: run.cost().rhs_evals,
            frictionless: run.initial().frictionless,
            coupling: match settings.stokes() {
                Some(_) => CouplingName::Stokes,
                None => CouplingName::Coulomb,
            },
            mu_static_ratio: settings.stokes().is_none().then(|| settings.hold()),
            gamma: settings.stokes(),
            growth_rate: run.stokes().map(|st| st.growth()),
            method: settings.method(),
            frame: settings.frame,
            tol: settings.scheme.tol(),
            dt: settings.scheme.fixed().map(|(_, dt)| dt),
            units: units.map(|u| {
                let (l, t) = (u.r_max_m(), u.t_s());
                UnitsReport {
                    mu: u.mu,
                    rpm: u.rpm,
                    g: u.g,
                    R_max_m: l,
                    T_s: t,
                    tau_s: end.tau * t,
                    xi_m: q.length() * l,
                    speed_m_s: speed * u.speed_m_s(),
                    escape_tau_s: run.escape().map(|e| e.tau * t),
                }
            }),
            body: None,
            chosen: None,
        }
    }
}

impl Report for RunReport {
    fn text(&self) -> String {
        let (how, cost, check) = (self.how(), self.cost(), self.check());
        // With a body, its run first: it is what was asked about.
        let mut text = match self.body.as_ref().and_then(|b| b.motion.as_ref()) {
            Some(m) => format!(
                "{}point    the point model from the same release:\n",
                m.line()
            ),
            None => String::new(),
        };
        if let Some(c) = &self.chosen {
            let _ = writeln!(text, "chosen   {}", c.said);
        }
        let _ = write!(
            text,
            "outcome  {how}\n{check}tau      {:.9}\nxi       {:.12}\nangle    {} in [0, 2π) (table frame, ccw from the release direction)\n|u|      {:.3e}\ncost     {cost}\n",
            self.tau,
            self.xi,
            angle_to(self.angle, 12),
            self.speed,
        );
        if let Some(r) = self.mu_static_ratio.filter(|&r| r != 1.0) {
            let _ = writeln!(
                text,
                "static   mu_s/mu_k = {r}: at rest it holds out to xi = {r}, slides at mu_k"
            );
        }
        if let Some(b) = &self.body {
            text.push_str(&b.text());
        }
        if let Some(u) = &self.units {
            let _ = writeln!(
                text,
                "SI       tau = {}, xi = {}, |u| = {:.3e} m/s (mu {}, {} rpm, g {}: R_max = {}, 1/Omega = {})",
                si_time(u.tau_s),
                si_length(u.xi_m),
                u.speed_m_s,
                u.mu,
                u.rpm,
                u.g,
                si_length(u.R_max_m),
                si_time(u.T_s)
            );
        }
        text
    }
}

impl RunReport {
    /// How the run ended, in words.
    fn how(&self) -> String {
        match (self.outcome, self.certificate) {
            (Outcome::Stuck, _) => "stuck: at rest on the table from tau on".to_string(),
            (Outcome::Escaped, Some(by)) => {
                format!("escaped: certified at tau ({})", by.describe())
            }
            _ if self.gamma.is_some() => {
                "running: not yet certified to leave at tau-max".to_string()
            }
            _ => "running: still slipping at tau-max".to_string(),
        }
    }

    /// What the run cost: closed forms, or its steps and evaluations.
    fn cost(&self) -> String {
        if self.frictionless {
            "closed form, 0 rhs evaluations (mu = 0: a straight line in the lab)".to_string()
        } else if let (Some(gamma), Some(rate)) = (self.gamma, self.growth_rate) {
            format!(
                "closed form, 0 rhs evaluations (Stokes drag gamma = {gamma}: linear)
growth   {rate:.12}  (Re lambda+: every release leaves as e^(rate tau) but those with u0 = lambda- q0, the centre at rest among them)"
            )
        } else {
            let knob = match (self.tol, self.dt) {
                (Some(tol), _) => format!("tol={tol:.0e}"),
                (_, Some(dt)) => format!("dt={dt:.0e}"),
                _ => String::new(),
            };
            format!(
                "{} steps, {} rejected, {} rhs evaluations ({} {knob})",
                self.steps, self.rejected, self.rhs_evals, self.method
            )
        }
    }

    /// The second opinion's line, if one was asked for (with its newline).
    fn check(&self) -> String {
        match (&self.check, self.certain) {
            (Some(_), Some(true)) if self.gamma.is_some() => {
                "check    closed form (Stokes drag): no integration error to check\n".to_string()
            }
            (Some(c), Some(true)) => format!(
                "check    outcome certain: {} agrees; {}tau measured within {:.1e} of it, position {:.1e}\n",
                c.who(),
                // Followed past the certificate (--follow): what was compared is the certificate.
                match self.escape_tau {
                    Some(te) if te < self.tau =>
                        format!("at the escape certificate (tau {te:.9}) "),
                    _ => String::new(),
                },
                c.tau_error.unwrap_or(f64::INFINITY),
                c.q_error.unwrap_or(f64::INFINITY),
            ),
            (Some(c), _) => format!(
                "certain  no: this run's own error could change the outcome (|H| margin {:.1e}, error {:.1e} against {}, which ends {})\n",
                c.margin,
                c.h_error.unwrap_or(f64::INFINITY),
                c.who(),
                c.outcome.map_or("out of budget", |o| o.name())
            ),
            _ => String::new(),
        }
    }
}

impl BodyReport {
    /// The body's lines of `run`'s text: its size and the two conditions at the end, and the
    /// two-mass body's run with its check.
    fn text(&self) -> String {
        let b = self;
        let mut text = String::new();
        let topple = match (b.mu_h_over_l, b.height) {
            (Some(t), _) if b.mu_assumed => {
                format!("mu h/L max <= {t:.3e} (mu_k <= 1 assumed)")
            }
            (Some(t), _) => format!("mu h/L max = {t:.3e}"),
            (None, None) => "no height given".into(),
            (None, Some(_)) => "toppling not judged under Stokes drag".into(),
        };
        let rot = b
            .l_over_xi
            .map_or("L/xi infinite (at the centre)".into(), |r| {
                format!("L/xi = {r:.3e}")
            });
        let verdict = if b.point_ok {
            "both << 1 (<= 0.1): a point"
        } else {
            "not both << 1 (<= 0.1): the point model is out of its depth"
        };
        let si = |x: f64, m: Option<f64>| match m {
            Some(m) => format!("{x} ({})", si_length(m)),
            None => format!("{x}"),
        };
        let size = match b.height {
            Some(h) => format!(
                "L = {}, h = {}",
                si(b.length, b.length_m),
                si(h, b.height_m.flatten())
            ),
            None => format!("L = {}", si(b.length, b.length_m)),
        };
        let _ = writeln!(
            text,
            "body     {size}: {topple}, {rot} at the end; {verdict}"
        );
        if let Some(c) = b.motion.as_ref().and_then(|m| m.check.as_ref()) {
            let e = |x: Option<f64>| x.map_or("-".into(), |x| format!("{x:.1e}"));
            let _ = writeln!(
                text,
                "rod      at tol {:e}: {}; the centre {} away, psi {}, tau {} (not independent: the same integrator)",
                c.tol,
                match (c.outcome, &c.failed) {
                    (Some(o), _) if c.agrees => format!("{} too", o.name()),
                    (Some(o), _) => format!("{}, DISAGREES", o.name()),
                    (None, f) => format!("failed ({})", f.as_deref().unwrap_or("")),
                },
                e(c.q_error),
                e(c.psi_error),
                e(c.tau_error)
            );
        }
        text
    }
}
