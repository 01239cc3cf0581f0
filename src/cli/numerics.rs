//! The headless numerical commands: run, escape, critical (sweep is in `sweep`).

use super::{CmdResult, CriticalArgs, Error, EscapeArgs, RunArgs, check_initial};
use crate::engine::solve::{Threshold, check_escape_xi0, critical_radius, escape_speed};
use crate::engine::{Initial, Outcome, Run, State, Status};
use crate::files::{Output, emit};
use serde_json::json;
use std::fmt::Write as _;
use std::io::{BufWriter, Write as _};

const TAU_MAX_LIMIT: f64 = 1e9;

/// The trajectory file's columns.
const TRAJECTORY_HEADER: &[u8] = b"tau,x,y,xq,yq,u,stuck,energy,work,approx_xi\n";

/// Writes trajectory rows: the state, E = ½|u|² − ½ξ² and −∫|u|dτ (trapezoids between rows;
/// dE/dτ = −|u|, so the two differ by E(0) up to the rule's error), and the Sec. III
/// approximation of ξ for a release at rest (Eq. 17 in the lab, Eq. 24 on the table for
/// ξ0 > 1; valid only early, see README), empty otherwise.
struct Rows {
    initial: Initial,
    prev: Option<State>,
    work: f64,
}

impl Rows {
    fn write(
        &mut self,
        csv: &mut impl std::io::Write,
        s: &State,
        stuck: bool,
    ) -> std::io::Result<()> {
        let (q, u) = (s.q(), s.u_lab().length());
        if let Some(p) = self.prev {
            self.work -= 0.5 * (s.tau - p.tau) * (u + p.u_lab().length());
        }
        self.prev = Some(*s);
        let i = self.initial;
        let approx = match i.release {
            _ if i.frictionless => None,
            crate::engine::Release::LabRest => {
                Some(crate::engine::approx::lab_rest(i.xi0, s.tau).0)
            }
            crate::engine::Release::TableRest if i.xi0 > 1.0 => {
                Some(crate::engine::approx::table_rest(i.xi0, s.tau).0)
            }
            _ => None,
        };
        writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{}",
            s.tau,
            s.r.x,
            s.r.y,
            q.x,
            q.y,
            u,
            u8::from(stuck),
            s.energy(),
            self.work,
            approx.map_or(String::new(), |x| x.to_string())
        )
    }
}

/// Spacing in τ of the trajectory rows of a frictionless run, which takes no steps.
const FREE_SAMPLE: f64 = 1e-2;

pub fn run(a: RunArgs) -> CmdResult {
    let initial = Initial {
        xi0: a.xi0,
        phi: a.phi,
        v0: a.v0,
        release: a.release,
        frictionless: a.frictionless,
    };
    check_initial(&initial)?;
    if !(a.tau_max.is_finite() && a.tau_max > 0.0 && a.tau_max <= TAU_MAX_LIMIT) {
        return Err(Error::Invalid(format!(
            "tau-max must lie in (0, {TAU_MAX_LIMIT:e}], got {}",
            Initial::show(a.tau_max)
        )));
    }
    let settings = a.numerics.settings()?;
    let mut run = Run::new(initial, settings)?;
    // The file is opened (and a bad path refused) before any work; rows stream into it.
    let mut csv = match &a.trajectory {
        Some(path) => Some(BufWriter::new(
            Output::create(path).map_err(|e| Error::Invalid(format!("--trajectory: {e}")))?,
        )),
        None => None,
    };
    let write_err = |e: std::io::Error| Error::Failed(format!("--trajectory: {e}"));
    let mut rows = Rows {
        initial,
        prev: None,
        work: 0.0,
    };
    if let Some(csv) = csv.as_mut() {
        csv.write_all(TRAJECTORY_HEADER).map_err(write_err)?;
        rows.write(csv, &run.state(), run.status != Status::Slipping)
            .map_err(write_err)?;
    }
    let stop_on_escape = !a.follow;
    while run.status == Status::Slipping
        && run.tau() < a.tau_max
        && !(stop_on_escape && run.escape.is_some())
    {
        let before = run.tau();
        run.step(a.tau_max)?;
        if let Some(csv) = csv.as_mut() {
            if initial.frictionless {
                // No steps to write: sample the closed form instead.
                let n = ((run.tau() - before) / FREE_SAMPLE).ceil().min(1e5) as usize;
                for i in 1..n {
                    let t = before + (run.tau() - before) * i as f64 / n as f64;
                    let s = run.state_at(t)?;
                    rows.write(csv, &s, false).map_err(write_err)?;
                }
            }
            rows.write(csv, &run.state(), run.status != Status::Slipping)
                .map_err(write_err)?;
        }
    }
    let outcome = run.outcome();
    let end = match (outcome, run.escape) {
        (Outcome::Escaped, Some(e)) if stop_on_escape => e.state,
        _ => run.state(),
    };
    if let Some(csv) = csv {
        csv.into_inner()
            .map_err(|e| write_err(e.into_error()))?
            .finish()
            .map_err(write_err)?;
    }
    let doubt = crate::engine::doubt::doubt(&run, a.tau_max);
    let q = end.q();
    let angle = crate::engine::model::turn_angle(q.y.atan2(q.x));
    let speed = end.u_lab().length();
    let c = run.cost;
    let units = a.units.units()?;
    if a.json {
        let mut v = json!({
            "outcome": outcome.name(),
            "certain": doubt.certain,
            "tau": end.tau,
            "xi": q.length(),
            "angle": angle,
            "speed": speed,
            "certificate": run.escape.map(|e| e.by),
            "escape_tau": run.escape.map(|e| e.tau),
            "steps": c.steps,
            "rejected": c.rejected,
            "rhs_evals": c.rhs_evals,
            "frictionless": initial.frictionless,
            "method": settings.method().to_string(),
            "frame": settings.frame.to_string(),
            "tol": settings.scheme.tol(),
            "dt": settings.scheme.fixed().map(|(_, dt)| dt),
        });
        if let Some(u) = units {
            let (l, t) = (u.r_max_m(), u.t_s());
            v["units"] = json!({
                "mu": u.mu,
                "rpm": u.rpm,
                "g": u.g,
                "R_max_m": l,
                "T_s": t,
                "tau_s": end.tau * t,
                "xi_m": q.length() * l,
                "speed_m_s": speed * u.speed_m_s(),
                "escape_tau_s": run.escape.map(|e| e.tau * t),
            });
        }
        emit(None, &format!("{v}\n"))?;
    } else {
        let how = match (outcome, run.escape) {
            (Outcome::Stuck, _) => "stuck: at rest on the table from tau on".to_string(),
            (Outcome::Escaped, Some(e)) => {
                format!("escaped: certified at tau ({})", e.by.describe())
            }
            _ => "running: still slipping at tau-max".to_string(),
        };
        let cost = if initial.frictionless {
            "closed form, 0 rhs evaluations (mu = 0: a straight line in the lab)".to_string()
        } else {
            format!(
                "{} steps, {} rejected, {} rhs evaluations ({} {})",
                c.steps,
                c.rejected,
                c.rhs_evals,
                settings.method(),
                settings.accuracy_label()
            )
        };
        let certain = if doubt.certain {
            String::new()
        } else {
            format!(
                "certain  no: this run's own error could change the outcome (|H| margin {:.1e}, error {:.1e} against a run 1000x tighter, which ends {})\n",
                doubt.margin,
                doubt.error,
                doubt.shadow.map_or("out of budget", |o| o.name())
            )
        };
        let mut text = format!(
            "outcome  {how}\n{certain}tau      {:.9}\nxi       {:.12}\nangle    {:.12} rad in [0, 2pi) (table frame, ccw from the release direction)\n|u|      {:.3e}\ncost     {cost}\n",
            end.tau,
            q.length(),
            angle,
            speed,
        );
        if let Some(u) = units {
            use crate::engine::units::{show_length, show_time};
            let _ = writeln!(
                text,
                "SI       tau = {}, xi = {}, |u| = {:.3e} m/s (mu {}, {} rpm, g {}: R_max = {}, 1/Omega = {})",
                show_time(end.tau * u.t_s()),
                show_length(q.length() * u.r_max_m()),
                speed * u.speed_m_s(),
                u.mu,
                u.rpm,
                u.g,
                show_length(u.r_max_m()),
                show_time(u.t_s())
            );
        }
        emit(None, &text)?;
    }
    Ok(())
}

/// Settings for the solvers, which classify runs by how they end: the paper's raw scheme never
/// comes to rest, so it cannot.
pub(super) fn solver_settings(n: &super::NumericsArgs) -> Result<crate::engine::Settings, Error> {
    let s = n.settings()?;
    if !s.method().stick_events() {
        return Err(Error::Invalid(format!(
            "{} has no stick event, so its runs never come to rest: the solvers need dp54, dop853, rk4 or rk2",
            s.method()
        )));
    }
    Ok(s)
}

pub(super) fn positive(name: &str, x: f64) -> Result<(), Error> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(Error::Invalid(format!(
            "{name} must be a positive number, got {}",
            Initial::show(x)
        )))
    }
}

/// The scan of a threshold search as runs of equal outcome: "0 to 1.2 escape; 1.35 to 2.4
/// stick; …" (what is known where the escaping values are not one interval).
fn scan_summary(t: &Threshold) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < t.scan.len() {
        let (x0, e) = t.scan[i];
        let mut j = i;
        while j + 1 < t.scan.len() && t.scan[j + 1].1 == e {
            j += 1;
        }
        let x1 = t.scan[j].0;
        let range = if j == i {
            format!("{x0:.4}")
        } else {
            format!("{x0:.4} to {x1:.4}")
        };
        parts.push(format!("{range} {}", if e { "escape" } else { "stick" }));
        i = j + 1;
    }
    parts.join("; ")
}

pub fn escape(a: EscapeArgs) -> CmdResult {
    check_initial(&Initial::velocity(a.xi0, a.phi, 0.0))?;
    check_escape_xi0(a.xi0)?;
    positive("vtol", a.vtol)?;
    let settings = solver_settings(&a.numerics)?;
    let t = escape_speed(a.xi0, a.phi, settings, a.vtol)?;
    let phi = crate::engine::model::turn_angle(a.phi);
    if a.json {
        let scan: Vec<_> = t
            .scan
            .iter()
            .map(|&(v0, e)| json!({"v0": v0, "outcome": if e { "escaped" } else { "stuck" }}))
            .collect();
        let v = json!({
            "xi0": a.xi0, "phi": phi, "v_escape": t.value,
            "stuck_at": t.stuck_at, "escapes_at": t.escapes_at, "interval": t.interval,
            "scan": scan, "runs": t.runs, "rhs_evals": t.rhs_evals,
        });
        emit(None, &format!("{v}\n"))?;
    } else {
        let mut text = match t.stuck_at {
            Some(lo) => format!(
                "v_escape {:.10}  (the least escaping speed)\nbracket  stuck at {lo:.10}, escapes at {:.10}\n",
                t.value, t.escapes_at
            ),
            None => "v_escape 0  (released at rest on the table here, it already escapes)\n".into(),
        };
        text.push_str(&format!(
            "cost     {} runs, {} rhs evaluations\n",
            t.runs, t.rhs_evals
        ));
        if !t.interval {
            text.push_str(&format!(
                "note     the escaping speeds are not one interval: some faster releases come to rest.\n         scanned v0: {}\n",
                scan_summary(&t)
            ));
        }
        emit(None, &text)?;
    }
    Ok(())
}

pub fn critical(a: CriticalArgs) -> CmdResult {
    positive("xtol", a.xtol)?;
    positive("g", a.g)?;
    if let (Some(w), Some(r)) = (a.omega, a.r0c) {
        positive("omega", w)?;
        positive("r0c", r)?;
        let m = w * w * r / a.g;
        if !(m.is_finite() && m > 0.0) {
            return Err(Error::Invalid(format!(
                "mu = omega² r0c / (xi0c g) is out of range for omega {}, r0c {}, g {}: check the units (rad/s, m, m/s²)",
                Initial::show(w),
                Initial::show(r),
                Initial::show(a.g)
            )));
        }
    }
    let settings = solver_settings(&a.numerics)?;
    let t = critical_radius(settings, a.xtol)?;
    // The paper's Eq. 22: mu = Omega² r0c / (xi0c g), friction measured by the critical radius.
    let mu = a.omega.zip(a.r0c).map(|(w, r)| w * w * r / (t.value * a.g));
    if a.json {
        let v = json!({
            "xi0c": t.value, "stuck_at": t.stuck_at, "escapes_at": t.escapes_at,
            "interval": t.interval, "runs": t.runs, "rhs_evals": t.rhs_evals, "mu": mu,
        });
        emit(None, &format!("{v}\n"))?;
    } else {
        let mut text = format!(
            "xi0c     {:.10}\nbracket  stuck at {:.10}, escapes at {:.10}\n",
            t.value,
            t.stuck_at.unwrap_or(0.0),
            t.escapes_at
        );
        if let Some(mu) = mu {
            text.push_str(&format!(
                "mu       {mu:.6}  (Eq. 22: Omega² r0c / (xi0c g))\n"
            ));
        }
        emit(None, &text)?;
    }
    Ok(())
}
