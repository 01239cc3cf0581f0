//! What happens at the body's events: a contact's stop (it holds and the body pivots, or it
//! breaks loose), both at rest (the body rides, or slides out as the point does, carried by
//! the point's run), and the loop that runs a body to its end.

use super::contact::{breakaway, pivot_need, stop_contact};
use super::state::{Phase, RodState, S, axis};
use super::{RodRun, Translation};
use crate::method::{Coupling, Settings};
use crate::model::{Initial, Release};
use crate::run::{Outcome, Run, RunError, Stop};
use glam::DVec2;

impl RodRun {
    /// What happens at event `k` of the current phase.
    pub(super) fn event(&mut self, k: usize) {
        let l = self.l;
        let s = self.state;
        match self.phase {
            Phase::Slip => {
                let slips = s.slips(l);
                let start = slips[k].length();
                let other = slips[1 - k].length();
                // A zero of the projection where the slip only turned is no stop.
                if start > 10.0 * self.floor() {
                    return;
                }
                if other <= self.floor().max(start) {
                    return self.both_stop();
                }
                let anchor = s.contacts(l)[k];
                let w = stop_contact(l, k, &s);
                let need = pivot_need(l, k, anchor, s.psi, w);
                let holds = need.length() <= 0.5 * self.hold;
                // A contact that cannot hold and whose slip already grows is breaking loose:
                // left alone. One whose slip shrinks would pass through zero (and turn back,
                // step after step): it is stopped and set off along its consistent direction.
                let ep = axis(s.psi).perp();
                let mobility = |v: DVec2| v + ep * ep.dot(v);
                let uk = s.slips(l)[k];
                if !holds && uk.dot(-mobility(need + uk.normalize_or_zero() * 0.5)) > 0.0 {
                    return;
                }
                self.state.w = w;
                self.state.u = -ep * (S[k] * 0.5 * l * w);
                if holds {
                    self.phase = Phase::Pivot {
                        i: k,
                        anchor,
                        sign: w.signum(),
                    };
                    self.breaking = [false; 2];
                } else {
                    self.fallback[k] = breakaway(need, s.psi);
                    self.fallback[1 - k] = self.state.slips(l)[1 - k];
                    self.breaking[k] = true;
                }
            }
            Phase::Pivot { i, anchor, .. } => {
                if k == 0 {
                    self.state.w = 0.0;
                    self.state.u = DVec2::ZERO;
                    self.both_stop();
                } else {
                    // The stuck contact breaks loose, along the one direction its slip can grow in.
                    let need = pivot_need(l, i, anchor, s.psi, s.w);
                    self.fallback[i] = breakaway(need, s.psi);
                    self.fallback[1 - i] = s.slips(l)[1 - i];
                    self.breaking = [i == 0, i == 1];
                    self.phase = Phase::Slip;
                }
            }
            Phase::Rest => {}
        }
    }

    /// Both contacts at rest: the body rides if |q| ≤ R, else both break loose outward.
    fn both_stop(&mut self) {
        self.state.u = DVec2::ZERO;
        self.state.w = 0.0;
        self.breaking = [false; 2];
        if self.state.q.length() <= self.hold {
            self.phase = Phase::Rest;
        } else {
            self.both_loose();
        }
    }

    /// Both contacts break loose from rest (|q| > R). Each slip accelerates as
    /// a_i = (qₑ − ½(α₁ + α₂)) ê + (q⊥ − β_i) ê⊥ for friction directions d_i = α_i ê + β_i ê⊥
    /// (the rod's axial force shares the along-rod part; across it each half is on its own),
    /// and a_i = λ_i d_i with λ_i > 0 has the one solution d₁ = d₂ = q̂, λ = |q| − 1: both slip
    /// straight out from the centre, not each along its own radius (which, with the rod
    /// across the radius, turned both slips back step after step: 200 000 steps at slips of
    /// ~1e-10 within τ = 2e-5).
    ///
    /// With d₁ = d₂ and ψ′ = 0 the two frictions have no torque, so the body goes on sliding
    /// without turning, each contact's slip the centre's: it is the point, released at rest on
    /// the table where its centre is. That run carries it on (`engine::run`, which launches
    /// from rest in closed form: slipping from rest just outside R, the slip grows as e^{λτ},
    /// and explicit steps of the body's own took 50 000 steps to τ = 1.2 at |q| = 1.001).
    pub(super) fn both_loose(&mut self) {
        let out = self.state.q.normalize_or_zero();
        self.fallback = [out, out];
        self.phase = Phase::Slip;
        let settings = Settings {
            coupling: Coupling::Coulomb { hold: self.hold },
            max_steps: self.max_steps,
            ..Settings::dp54(self.tol)
        };
        let from = Initial::at_rest(self.state.q.length(), Release::TableRest);
        // Refused only for input the body's own run takes too: it then carries on itself.
        self.translation = Run::new(from, settings).ok().map(|run| {
            Box::new(Translation {
                run,
                turn: self.state.q.to_angle(),
                tau0: self.state.tau,
            })
        });
    }

    /// One step of the point's run that carries a body sliding without turning.
    pub(super) fn translate(&mut self, tau_max: f64) -> Result<Outcome, RunError> {
        let Some(t) = self.translation.as_mut() else {
            return Ok(self.standing());
        };
        self.cost.steps += 1;
        let before = t.run.cost().rhs_evals;
        let stop = t.run.step(tau_max - t.tau0)?;
        self.cost.rhs_evals += t.run.cost().rhs_evals - before;
        let p = t.run.state();
        let turn = DVec2::from_angle(t.turn);
        self.state.tau = t.tau0 + p.tau;
        self.state.q = turn.rotate(p.q());
        self.state.u = turn.rotate(p.u());
        self.state.w = 0.0;
        if stop == Stop::Stuck {
            self.translation = None;
            self.phase = Phase::Rest;
        }
        Ok(self.standing())
    }

    /// Runs to rest, the escape certificate or `tau_max`, calling `each` on every state.
    pub fn finish(
        &mut self,
        tau_max: f64,
        mut each: impl FnMut(&RodState),
    ) -> Result<Outcome, RunError> {
        each(&self.state);
        loop {
            let end = self.step(tau_max)?;
            each(&self.state);
            if end != Outcome::Running || self.state.tau >= tau_max {
                let certified = self.certified.is_some() || self.escaped();
                return Ok(if certified && end == Outcome::Running {
                    Outcome::Escaped
                } else {
                    end
                });
            }
        }
    }
}
