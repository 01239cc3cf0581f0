//! The appendix's body integrated (extends the paper, whose Appendix only estimates it): two
//! masses m/2 at q ± (L/2) ê(ψ), joined by a massless rigid rod that carries an axial force only,
//! each with Coulomb friction μ_k m g/2 against its own slip velocity. Rotating frame, units of
//! the paper's Eqs. (6)–(7) (μ_k g = 1, Ω = 1), per unit total mass m:
//!
//! - sliding: q′ = u, u′ = −2 ẑ × u + q − ½(û₁ + û₂), ψ″ = −(ê × û₁ − ê × û₂)/L, with the
//!   contacts' slips u_i = u ± (L/2) ψ′ ê⊥ (Coriolis and centrifugal forces have no torque
//!   about the centre of a two-mass rod; I = mL²/4);
//! - one contact stuck at a (it holds while the friction it needs, |N ê − ½a| with the rod's
//!   axial force N, is ≤ ½ μ_s/μ_k): the other pivots about it, ψ″ = −(s a·ê⊥ + sgn ψ′)/L;
//! - both stuck: the body rides the table iff some axial force keeps both within their cones,
//!   which works out to |q| ≤ μ_s/μ_k, the point's condition (Sec. II, property 1);
//! - a contact breaking loose slips along the one direction its slip can grow in
//!   ([`breakaway`]), taken as its friction's direction until its slip passes the stop floor.
//!
//! The Jacobi energy E = ½|u|² + (L²/8) ψ′² − ½|q|² falls at ½(|u₁| + |u₂|), so E < −½R²
//! (R = μ_s/μ_k) certifies that the body never rests. As L → 0 it is the point.

use super::body::Body;
use super::error::Error;
use super::method::{Coupling, Settings};
use super::model::{Initial, Release};
use super::roots::illinois;
use super::run::{Outcome, Run, Stop};
use super::stepper::dp5_stages;
use glam::DVec2;

/// The body at time τ in the table frame: centre q, its velocity u, the rod's angle ψ and its
/// rate ψ′ (both relative to the table).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RodState {
    pub tau: f64,
    pub q: DVec2,
    pub u: DVec2,
    pub psi: f64,
    pub w: f64,
}

/// Which contacts hold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    /// Both slide.
    Slip,
    /// Contact `i` (0: at q + (L/2)ê, 1: at q − (L/2)ê) is stuck at `anchor`; the body pivots,
    /// turning in the sense `sign` (the other contact's friction keeps it until ψ′ = 0, an
    /// event: integrated past it with that friction, the stop is a smooth crossing to locate).
    Pivot { i: usize, anchor: DVec2, sign: f64 },
    /// Both stuck: the body rides the table.
    Rest,
}

/// The side of each contact: contact i sits at q + S[i] (L/2) ê.
const S: [f64; 2] = [1.0, -1.0];

/// The body's state as DOPRI5 steps it: q, u, ψ, ψ′.
#[derive(Clone, Copy, Debug, PartialEq)]
struct V([f64; 6]);

impl std::ops::Index<usize> for V {
    type Output = f64;
    fn index(&self, j: usize) -> &f64 {
        &self.0[j]
    }
}

impl std::ops::Add for V {
    type Output = V;
    fn add(self, o: V) -> V {
        V(std::array::from_fn(|j| self.0[j] + o.0[j]))
    }
}

impl std::ops::Mul<f64> for V {
    type Output = V;
    fn mul(self, c: f64) -> V {
        V(self.0.map(|x| x * c))
    }
}

fn axis(psi: f64) -> DVec2 {
    DVec2::from_angle(psi)
}

impl RodState {
    fn y(&self) -> V {
        V([self.q.x, self.q.y, self.u.x, self.u.y, self.psi, self.w])
    }
    fn from(tau: f64, y: V) -> RodState {
        RodState {
            tau,
            q: DVec2::new(y[0], y[1]),
            u: DVec2::new(y[2], y[3]),
            psi: y[4],
            w: y[5],
        }
    }
    /// Where the two masses are.
    pub fn contacts(&self, l: f64) -> [DVec2; 2] {
        S.map(|s| self.q + axis(self.psi) * (s * 0.5 * l))
    }
    /// The two contacts' slip velocities relative to the table.
    pub fn slips(&self, l: f64) -> [DVec2; 2] {
        S.map(|s| self.u + axis(self.psi).perp() * (s * 0.5 * l * self.w))
    }
    /// The Jacobi energy per unit mass, E = ½|u|² + (L²/8) ψ′² − ½|q|² (constants dropped).
    pub fn energy(&self, l: f64) -> f64 {
        0.5 * self.u.length_squared() + l * l / 8.0 * self.w * self.w
            - 0.5 * self.q.length_squared()
    }
}

/// A unit vector along `v`, or along `fallback` where `v` is zero (a contact just breaking
/// loose: its friction opposes the push that breaks it).
fn dir(v: DVec2, fallback: DVec2) -> DVec2 {
    let n = v.length();
    if n > 0.0 {
        v / n
    } else {
        fallback.normalize_or_zero()
    }
}

/// The friction contact `i` needs to stay stuck at `anchor` while the other pivots at rate `w`
/// (per unit total mass): N ê − ½a, N the rod's axial force from the other mass's radial
/// balance.
fn pivot_need(l: f64, i: usize, anchor: DVec2, psi: f64, w: f64) -> DVec2 {
    let (s, e) = (S[i], axis(psi));
    let n = 0.5 * (s * l * w * w + 2.0 * s * l * w - anchor.dot(e) + s * l);
    e * n - anchor * 0.5
}

/// The rod's rate once contact `k`'s residual slip u_k (below the stop floor) is taken out by
/// a plastic impulse P at that contact: Δu = P, Δψ′ = 2 s (ê⊥·P)/L, so Δu_k = (1 + ê⊥ê⊥ᵀ) P
/// and P = −(ê êᵀ + ½ ê⊥ê⊥ᵀ) u_k. Kinetic energy changes by −½ u_kᵀ(ê êᵀ + ½ ê⊥ê⊥ᵀ) u_k ≤ 0;
/// simply dropping u_k from u (keeping ψ′) changes it by ½|u_k|² − u·u_k, which rises by up
/// to |u||u_k| ~ 10⁻⁸ at tol 10⁻¹⁰.
fn stop_contact(l: f64, k: usize, s: &RodState) -> f64 {
    let ep = axis(s.psi).perp();
    let uk = s.slips(l)[k];
    s.w - S[k] * ep.dot(uk) / l
}

/// The direction contact `i` slips in as it breaks loose, needing `need` (|need| > ½, more than
/// kinetic friction can give): the one direction d along which its slip then grows, the
/// Filippov-consistent start. Its slip accelerates as −M(need + ½d), M = 1 + ê⊥ê⊥ᵀ the
/// contact's mobility (a force along the rod moves the whole mass, across it only the half at
/// the contact, twice as fast), so d solves −M(need + ½d) = λd with λ > 0:
/// d = −(nₑ/(λ + ½)) ê − (2n⊥/(λ + 1)) ê⊥, |d| = 1 fixing λ (the left side falls with λ from
/// 4|need|² > 1 at λ = 0 to ≤ 1 at λ = 2|need|: one root, bisected). With μ_s = μ_k a contact
/// breaks loose at |need| = ½, where λ = 0 and d = −need/|need|; with μ_s > μ_k it breaks at
/// |need| = ½μ_s/μ_k, where −need is not consistent: its slip then turned back to zero step
/// after step, which stalled the run at slips of ~1e-10 until its step budget ran out.
fn breakaway(need: DVec2, psi: f64) -> DVec2 {
    let (e, ep) = (axis(psi), axis(psi).perp());
    let (ne, np) = (need.dot(e), need.dot(ep));
    let d = |lam: f64| -e * (ne / (lam + 0.5)) - ep * (2.0 * np / (lam + 1.0));
    let (mut lo, mut hi) = (0.0, 2.0 * need.length());
    if d(lo).length_squared() <= 1.0 {
        return -need.normalize_or_zero();
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if d(mid).length_squared() > 1.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    d(hi).normalize_or_zero()
}

/// How the sliding phase takes each contact's friction direction.
#[derive(Clone, Copy, Debug)]
struct Friction {
    /// Where a contact's slip is zero: the direction it starts in.
    fallback: [DVec2; 2],
    /// Contacts breaking loose, whose slip has not yet grown past `floor`.
    breaking: [bool; 2],
    floor: f64,
}

impl Friction {
    /// Contact `k`'s friction direction (friction is −½ of it): its slip's, except while it
    /// breaks loose. Then its slip grows from zero as λτ d, and its direction relaxes to d at
    /// a rate ~1/|u_k|: an explicit step from zero slip is unstable at any h when λ is small
    /// (each stage's direction error grows ~1/λ). Below the floor the direction is therefore
    /// taken as the consistent d itself, recomputed from the state (the quasi-static limit of
    /// that fast relaxation; it lags by ~|u_k| ≤ the floor); above it, the slip's own.
    fn dir(&self, l: f64, k: usize, st: &RodState, uk: DVec2) -> DVec2 {
        if self.breaking[k] && uk.length() <= self.floor {
            let need = pivot_need(l, k, st.contacts(l)[k], st.psi, st.w);
            breakaway(need, st.psi)
        } else {
            dir(uk, self.fallback[k])
        }
    }
}

/// The right-hand side in `phase`.
fn rhs(l: f64, phase: Phase, friction: &Friction, y: V) -> V {
    let st = RodState::from(0.0, y);
    let (e, ep) = (axis(st.psi), axis(st.psi).perp());
    match phase {
        Phase::Slip => {
            let [u1, u2] = st.slips(l);
            let (d1, d2) = (friction.dir(l, 0, &st, u1), friction.dir(l, 1, &st, u2));
            let du = -2.0 * st.u.perp() + st.q - (d1 + d2) * 0.5;
            let dw = -(e.perp_dot(d1) - e.perp_dot(d2)) / l;
            V([st.u.x, st.u.y, du.x, du.y, st.w, dw])
        }
        Phase::Pivot { i, anchor, sign } => {
            let s = S[i];
            let dw = -(s * anchor.dot(ep) + sign) / l;
            let u = -ep * (s * 0.5 * l * st.w);
            let du = -(ep * dw - e * (st.w * st.w)) * (s * 0.5 * l);
            V([u.x, u.y, du.x, du.y, st.w, dw])
        }
        Phase::Rest => V([0.0; 6]),
    }
}

/// One Dormand–Prince 5(4) step (`stepper`'s stages): the new point and the error estimate
/// scaled by the tolerance (≤ 1: accept).
fn dp54(f: impl Fn(V) -> V, y: V, h: f64, tol: f64) -> (V, f64) {
    let (y1, _, e) = dp5_stages(&f, y, f(y), h);
    let err = (0..6)
        .map(|j| (e[j] / (tol * (1.0 + y[j].abs().max(y1[j].abs())))).abs())
        .fold(0.0, f64::max);
    (y1, err)
}

/// A run of the body: its state, phase and cost.
#[derive(Clone, Debug)]
pub struct RodRun {
    pub l: f64,
    /// μ_s/μ_k.
    pub hold: f64,
    pub tol: f64,
    pub state: RodState,
    pub phase: Phase,
    fallback: [DVec2; 2],
    /// Contacts breaking loose (see [`Friction::dir`]).
    breaking: [bool; 2],
    /// Both contacts loose from rest: from then on the body slides as the point does (see
    /// [`RodRun::both_loose`]), and the point's own run carries it.
    translation: Option<Box<Translation>>,
    h: f64,
    /// Steps attempted (accepted and rejected).
    pub steps: u64,
    /// Right-hand-side evaluations, event location's included.
    evals: std::cell::Cell<u64>,
    /// Past the escape certificate, the body is stepped on while its centre is within this
    /// radius (see [`RodRun::following`]); None: a run stops at the certificate.
    follow_to: Option<f64>,
    /// τ at which a step first found the certificate, E < −½R².
    certified: Option<f64>,
}

/// The point's run that carries a body sliding without turning: released at rest on the table
/// where the body's centre was at `tau0`, on +x, so the body's table frame is its own turned
/// by `turn`.
#[derive(Clone, Debug)]
struct Translation {
    run: Run,
    turn: f64,
    tau0: f64,
}

/// A contact's slip below 10⁻²√tol (relative to 1 + |u|) has stopped: the steps that approach
/// a zero of |u_i| shrink with it, and below about 1e-11 their stages straddle the zero and
/// stall. Snapping at |u_i| moves the rest point by about |u_i|²/2, ≤ 10⁻⁴ tol.
const STOP_SCALE: f64 = 1e-2;

/// …and a slip below 100 tol has stopped too: with steps of about tol, the stages' friction
/// flips within a step and DOPRI5 has a spurious fixed point where the body creeps at a slip of
/// about tol, every step accepted (at tol 1e-6, 700 000 steps at |u| = 1.03e-5 against a floor
/// of 1.00e-5). This bound only bites above tol = 1e-8; the rest point then moves by ~10⁴ tol².
const CHATTER: f64 = 100.0;

/// …but never above 10⁻³ (tol ≥ 1e-5): a floor of 100 tol would stop every slip at once at
/// tol 1e-2. There a loose run may creep at its chatter, and says so by not resting.
const MAX_FLOOR: f64 = 1e-3;

/// Steps a run may take.
const MAX_STEPS: u64 = 5_000_000;

fn over_budget() -> Error {
    Error::NoAnswer("the body's run exceeded its step budget".into())
}

impl RodRun {
    /// The body released as `initial` says, the rod at `body.angle`. A thrown body or one at
    /// rest in the lab does not spin in the lab (ψ′ = −1, the appendix's case); one at rest on
    /// the table rides with it (ψ′ = 0).
    pub fn new(body: Body, hold: f64, initial: &Initial, tol: f64) -> Result<RodRun, Error> {
        body.validate()?;
        initial.validate()?;
        if initial.frictionless {
            return Err(Error::refused(
                "a body with mu = 0 feels no friction: its centre is the point's straight line",
            ));
        }
        let q = DVec2::new(initial.xi0, 0.0);
        let w = if initial.release == Release::TableRest {
            0.0
        } else {
            -1.0
        };
        let state = RodState {
            tau: 0.0,
            q,
            u: initial.u0(),
            psi: body.angle,
            w,
        };
        let mut run = RodRun {
            l: body.length,
            hold,
            tol,
            state,
            phase: Phase::Slip,
            fallback: state.contacts(body.length),
            breaking: [false; 2],
            translation: None,
            h: 1e-3,
            steps: 0,
            evals: std::cell::Cell::new(0),
            follow_to: None,
            certified: None,
        };
        if state.u == DVec2::ZERO && w == 0.0 {
            if q.length() <= hold {
                run.phase = Phase::Rest;
            } else {
                run.both_loose();
            }
        }
        Ok(run)
    }

    /// The run followed past its escape certificate while its centre is within `radius` (the
    /// explorer draws the body leaving, as it follows the point out to its view radius): its
    /// steps go on as before, and [`RodRun::step`] says `Escaped` once |q| ≥ `radius` (at once
    /// where it already is), `Running` before. The physics is the same; only where it stops.
    pub fn following(mut self, radius: f64) -> RodRun {
        self.follow_to = Some(radius);
        self
    }

    /// τ at which a step first found the escape certificate (E < −½R²), once one has: where a
    /// run that is not followed stops, and the escape's τ of one that is.
    pub fn certificate(&self) -> Option<f64> {
        self.certified
    }

    /// The slip below which a contact has stopped.
    fn floor(&self) -> f64 {
        (STOP_SCALE * self.tol.sqrt()).max((CHATTER * self.tol).min(MAX_FLOOR))
            * (1.0 + self.state.u.length())
    }

    /// Whether E < −½R² already certifies that the body never rests.
    fn escaped(&self) -> bool {
        self.state.energy(self.l) < -0.5 * self.hold * self.hold
    }

    /// Right-hand-side evaluations so far (seven a DP54 step).
    pub fn rhs_evals(&self) -> u64 {
        self.evals.get()
    }

    fn step_from(&self, y: V, h: f64) -> (V, f64) {
        self.evals.set(self.evals.get() + 7);
        let (l, phase) = (self.l, self.phase);
        let friction = Friction {
            fallback: self.fallback,
            breaking: self.breaking,
            floor: self.floor(),
        };
        dp54(|y| rhs(l, phase, &friction, y), y, h, self.tol)
    }

    /// The state after `h` from the current one, re-placed on the pivot's circle when
    /// pivoting (the stuck contact exactly at its anchor).
    fn trial(&self, h: f64) -> RodState {
        self.place(h, self.step_from(self.state.y(), h).0)
    }

    fn place(&self, h: f64, y: V) -> RodState {
        let mut s = RodState::from(self.state.tau + h, y);
        if let Phase::Pivot { i, anchor, .. } = self.phase {
            let ep = axis(s.psi).perp();
            s.q = anchor - axis(s.psi) * (S[i] * 0.5 * self.l);
            s.u = -ep * (S[i] * 0.5 * self.l * s.w);
        }
        s
    }

    /// Event functions of the phase at `s`, each positive until its event: a sliding
    /// contact's slip along its slip at the step's start; a pivot's rate along its start, and
    /// the stuck contact's cone margin.
    fn events(&self, s: &RodState) -> [f64; 2] {
        match self.phase {
            Phase::Slip => {
                let (a, b) = (self.state.slips(self.l), s.slips(self.l));
                [a[0].dot(b[0]), a[1].dot(b[1])]
            }
            Phase::Pivot { i, anchor, .. } => [
                self.state.w * s.w,
                0.5 * self.hold - pivot_need(self.l, i, anchor, s.psi, s.w).length(),
            ],
            Phase::Rest => [1.0, 1.0],
        }
    }

    /// Advances by one accepted step, or to the first event inside it; returns how the run
    /// stands then.
    pub fn step(&mut self, tau_max: f64) -> Result<Outcome, Error> {
        if self.phase == Phase::Rest {
            return Ok(Outcome::Stuck);
        }
        if self.certified.is_some() || self.escaped() {
            self.certified.get_or_insert(self.state.tau);
            // Followed, the certified body goes on until its centre reaches the radius.
            if !self.follow_to.is_some_and(|r| self.state.q.length() < r) {
                return Ok(Outcome::Escaped);
            }
        }
        if self.state.tau >= tau_max {
            return Ok(Outcome::Running);
        }
        if self.translation.is_some() {
            return self.translate(tau_max);
        }
        // A slip that has shrunk to roundoff is a stop: the approach to a zero of |u_i| takes
        // steps in proportion to |u_i| (the friction's direction turns ever faster).
        if self.phase == Phase::Slip {
            let slips = self.state.slips(self.l).map(|v| v.length());
            let floor = self.floor();
            if let Some(k) = (0..2)
                .filter(|&k| slips[k] > 0.0 && slips[k] <= floor)
                .min_by(|&a, &b| slips[a].total_cmp(&slips[b]))
            {
                self.event(k);
                if self.phase != Phase::Slip {
                    return Ok(self.standing());
                }
            }
        }
        // Events already at zero at the start (a contact just loose) are not watched.
        let live = self.events(&self.state).map(|g| g > 0.0);
        loop {
            self.steps += 1;
            if self.steps > MAX_STEPS {
                return Err(over_budget());
            }
            let h = self.h.min(tau_max - self.state.tau);
            let (y1, err) = self.step_from(self.state.y(), h);
            if err.is_nan() || err > 1.0 {
                self.h = h * (0.9 * err.powf(-0.2)).clamp(0.1, 0.9);
                if !self.h.is_finite() || self.h < 1e-15 * self.state.tau.max(1e-3) {
                    return Err(Error::NoAnswer("the body's step size underflowed".into()));
                }
                continue;
            }
            let grow = (0.9 * err.max(1e-10).powf(-0.2)).clamp(0.2, 5.0);
            let end = self.place(h, y1);
            let g = self.events(&end);
            let hit = (0..2)
                .filter(|&k| live[k] && g[k] <= 0.0)
                .min_by(|&a, &b| self.locate(a, h).total_cmp(&self.locate(b, h)));
            match hit {
                None => {
                    let floor = self.floor();
                    for (b, u) in self.breaking.iter_mut().zip(end.slips(self.l)) {
                        *b &= u.length() <= floor;
                    }
                    self.locate_certificate(h, &end);
                    self.state = end;
                    self.h = h * grow;
                }
                Some(k) => {
                    let at = self.locate(k, h);
                    self.state = self.trial(at);
                    self.h = (at * grow).max(1e-12);
                    self.event(k);
                }
            }
            return Ok(self.standing());
        }
    }

    fn standing(&self) -> Outcome {
        if self.phase == Phase::Rest {
            Outcome::Stuck
        } else {
            Outcome::Running
        }
    }

    /// Where in the step of `h` to `end` the escape certificate E < −½R² first holds, if it
    /// first holds there: located by Illinois on the step's length (as the point's run locates
    /// its certificates), not taken at the step's end.
    fn locate_certificate(&mut self, h: f64, end: &RodState) {
        let margin = |s: &RodState| -0.5 * self.hold * self.hold - s.energy(self.l);
        if self.certified.is_some() || self.escaped() || margin(end) <= 0.0 {
            return;
        }
        let at = illinois(|t| margin(&self.trial(t)), 0.0, h, 1e-14 * h.max(1e-300));
        self.certified = Some(self.state.tau + at);
    }

    /// Where in (0, h] event `k` first reaches zero, by bisection on the step length.
    fn locate(&self, k: usize, h: f64) -> f64 {
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.events(&self.trial(mid))[k] > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }

    /// What happens at event `k` of the current phase.
    fn event(&mut self, k: usize) {
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
    fn both_loose(&mut self) {
        let out = self.state.q.normalize_or_zero();
        self.fallback = [out, out];
        self.phase = Phase::Slip;
        let settings = Settings {
            coupling: Coupling::Coulomb { hold: self.hold },
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
    fn translate(&mut self, tau_max: f64) -> Result<Outcome, Error> {
        let Some(t) = self.translation.as_mut() else {
            return Ok(self.standing());
        };
        self.steps += 1;
        if self.steps > MAX_STEPS {
            return Err(over_budget());
        }
        let before = t.run.cost().rhs_evals;
        let stop = t.run.step(tau_max - t.tau0)?;
        self.evals
            .set(self.evals.get() + (t.run.cost().rhs_evals - before));
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
    ) -> Result<Outcome, Error> {
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

/// Most steps (accepted and rejected) a [`RodTrack`] takes: the explorer computes a track
/// inside a key press, so its cost is bounded whatever the release, to a frame: 50 000 steps
/// took 22 ms (200 000, 86 ms). Tracks need a few hundred: 2900 at most over 100 000 random
/// releases to τ = 20, 2098 over 40 000 followed to the view radius.
pub const TRACK_STEPS: u64 = 50_000;
/// Most states a [`RodTrack`] keeps: when it holds this many it keeps every other one (its
/// events and its end always), so a track of any length costs the same memory.
pub const TRACK_STATES: usize = 20_000;

/// Where a track stopped short of its run's end.
#[derive(Clone, Debug, PartialEq)]
pub enum Cut {
    /// [`TRACK_STEPS`] (or the budget given) ran out.
    Budget(u64),
    /// The run failed (its message); what came before is kept.
    Failed(String),
}

/// A body run's path for drawing it at any τ (the explorer's bar): its step ends, thinned to
/// at most [`TRACK_STATES`], each with the phase that holds from it on.
#[derive(Clone, Debug)]
pub struct RodTrack {
    pub l: f64,
    pub states: Vec<RodState>,
    /// `phases[k]`: the phase from `states[k]` until the next state.
    pub phases: Vec<Phase>,
    /// Stuck, Escaped (certified: the last state is the certificate's, or past it on a
    /// followed track), or Running: `tau_max` came first, or the track was cut before the
    /// certificate (see `cut`).
    pub outcome: Outcome,
    /// τ of the escape certificate (E < −½R²) where the run escapes: the escape's τ, whether
    /// or not the track goes on past it.
    pub escape: Option<f64>,
    /// The radius an escaping body is followed out to past its certificate (see
    /// [`RodTrack::from_run`]); None: the track ends at the certificate.
    pub follow_to: Option<f64>,
    /// Steps the run took.
    pub steps: u64,
    /// Why the track ends before its run did, if it does (on a followed track, possibly after
    /// the certificate: the escape stands, the drawing stops short).
    pub cut: Option<Cut>,
}

impl RodTrack {
    /// The track of `run` from where it stands, to rest, escape (followed on to its radius
    /// where [`RodRun::following`] says so) or `tau_max`, within `max_steps` and `max_states`
    /// (at least 4; the explorer's are [`TRACK_STEPS`] and [`TRACK_STATES`]); a run that fails
    /// or runs out of steps keeps what it computed, with `cut` saying so. The explorer's `RodTrack::from_run(RodRun::new(…)?.following(r), …)` draws
    /// an escaping body leaving, at the same cost bounds.
    pub fn from_run(mut run: RodRun, tau_max: f64, max_steps: u64, max_states: usize) -> RodTrack {
        let mut track = RodTrack {
            l: run.l,
            states: vec![run.state],
            phases: vec![run.phase],
            outcome: Outcome::Running,
            escape: None,
            follow_to: run.follow_to,
            steps: 0,
            cut: None,
        };
        let mut keep = Thinned::new(max_states.max(4));
        track.outcome = loop {
            if run.steps >= max_steps {
                track.cut = Some(Cut::Budget(max_steps));
                break Outcome::Running;
            }
            let before = (run.state, run.phase);
            let end = match run.step(tau_max) {
                Ok(end) => end,
                Err(e) => {
                    track.cut = Some(Cut::Failed(e.to_string()));
                    break Outcome::Running;
                }
            };
            let s = run.state;
            let finite = [s.tau, s.q.x, s.q.y, s.u.x, s.u.y, s.psi, s.w]
                .iter()
                .all(|x| x.is_finite());
            if !finite {
                track.cut = Some(Cut::Failed(format!(
                    "the body's state is not finite after τ = {}",
                    before.0.tau
                )));
                break Outcome::Running;
            }
            if (s, run.phase) != before {
                keep.push(&mut track, s, run.phase, run.phase != before.1);
            }
            if end != Outcome::Running {
                break end;
            }
            if s.tau >= tau_max {
                // At τ-max: once more, which only classifies (rest, the energy's certificate).
                break run.step(tau_max).unwrap_or(Outcome::Running);
            }
        };
        keep.finish(&mut track);
        track.steps = run.steps;
        track.escape = run.certificate();
        if track.escape.is_some() {
            // Certified, whether or not the following reached its radius.
            track.outcome = Outcome::Escaped;
        }
        track
    }

    /// The body at `tau` (linear between kept states), at rest for ever once stuck; None past
    /// the end of an escaping, unfinished or cut run.
    pub fn at(&self, tau: f64) -> Option<RodState> {
        self.at_with_phase(tau).map(|(s, _)| s)
    }

    /// The state and phase at `tau` (the phase that holds from the kept state at or before
    /// it).
    pub fn at_with_phase(&self, tau: f64) -> Option<(RodState, Phase)> {
        let last = *self.states.last()?;
        let phase = |k: usize| self.phases.get(k).copied().unwrap_or(Phase::Slip);
        if tau >= last.tau {
            return (self.outcome == Outcome::Stuck || tau == last.tau)
                .then_some((RodState { tau, ..last }, phase(self.states.len() - 1)));
        }
        if tau.is_nan() {
            return None;
        }
        let k = self.states.partition_point(|s| s.tau <= tau).max(1);
        let (a, b) = (self.states[k - 1], self.states[k]);
        let t = if b.tau > a.tau {
            ((tau - a.tau) / (b.tau - a.tau)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let s = RodState {
            tau,
            q: a.q.lerp(b.q, t),
            u: a.u.lerp(b.u, t),
            psi: a.psi + (b.psi - a.psi) * t,
            w: a.w + (b.w - a.w) * t,
        };
        Some((s, phase(k - 1)))
    }

    /// An escaping track followed out to its radius: its last state, where the body left (the
    /// explorer keeps it there, as it keeps the point where its run stopped). None otherwise.
    pub fn left(&self) -> Option<RodState> {
        let last = *self.states.last()?;
        let out = self.follow_to.is_some_and(|r| last.q.length() >= r);
        (self.escape.is_some() && self.cut.is_none() && out).then_some(last)
    }

    /// Where the track ends: its last state's τ.
    pub fn end_tau(&self) -> f64 {
        self.states.last().map_or(0.0, |s| s.tau)
    }
}

/// Step ends kept at a density that halves when `cap` are held: every `stride`-th step end,
/// and every phase change (so the phase at any τ is the run's), the newest end always.
struct Thinned {
    cap: usize,
    stride: u64,
    /// Step ends since the last kept one.
    since: u64,
    /// The newest step end when it was not kept (put back at the end).
    pending: Option<(RodState, Phase)>,
}

impl Thinned {
    fn new(cap: usize) -> Thinned {
        Thinned {
            cap,
            stride: 1,
            since: 0,
            pending: None,
        }
    }

    fn push(&mut self, t: &mut RodTrack, s: RodState, p: Phase, event: bool) {
        self.since += 1;
        if !event && self.since < self.stride {
            self.pending = Some((s, p));
            return;
        }
        if event && let Some((ps, pp)) = self.pending.take() {
            // The step end just before a phase change: kept, so the old phase's last stretch
            // is drawn on its own chord.
            Thinned::keep(t, ps, pp);
        }
        self.pending = None;
        self.since = 0;
        Thinned::keep(t, s, p);
        if t.states.len() >= self.cap {
            self.halve(t);
        }
    }

    fn keep(t: &mut RodTrack, s: RodState, p: Phase) {
        t.states.push(s);
        t.phases.push(p);
    }

    /// Every other kept state dropped (events kept while that halves them enough, then
    /// every other of whatever is left), the first and the newest always.
    fn halve(&mut self, t: &mut RodTrack) {
        self.stride *= 2;
        for events_too in [false, true] {
            if t.states.len() < self.cap * 3 / 4 {
                return;
            }
            let n = t.states.len();
            // A phase change: a state whose phase is not its predecessor's.
            let change = |k: usize| k > 0 && t.phases[k] != t.phases[k - 1];
            let keep: Vec<bool> = (0..n)
                .map(|k| k == 0 || k + 1 == n || k % 2 == 0 || (!events_too && change(k)))
                .collect();
            let mut it = keep.iter();
            t.states.retain(|_| *it.next().unwrap_or(&true));
            let mut it = keep.iter();
            t.phases.retain(|_| *it.next().unwrap_or(&true));
        }
    }

    /// The newest step end, if it was not kept.
    fn finish(&mut self, t: &mut RodTrack) {
        if let Some((s, p)) = self.pending.take() {
            Thinned::keep(t, s, p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The break-away direction is the consistent one: the slip's acceleration −M(need + ½d)
    /// lies along d, outward (λ > 0), wherever kinetic friction cannot hold (|need| > ½); at
    /// |need| = ½ it is −need's direction, the μ_s = μ_k break.
    #[test]
    fn a_contact_breaks_loose_along_its_slip_s_acceleration() {
        let mut worst: f64 = 0.0;
        for i in 0..24 {
            let psi = 0.27 * f64::from(i);
            let ep = axis(psi).perp();
            for j in 0..24 {
                for size in [0.5 + 1e-9, 0.505, 0.55, 0.75, 1.5, 40.0] {
                    let need = DVec2::from_angle(0.26 * f64::from(j)) * size;
                    let d = breakaway(need, psi);
                    let a = -(need + d * 0.5 + ep * ep.dot(need + d * 0.5));
                    assert!((d.length() - 1.0).abs() < 1e-12);
                    assert!(a.dot(d) > 0.0, "{need} {psi}: λ {}", a.dot(d));
                    worst = worst.max(a.perp_dot(d).abs() / (1.0 + size));
                }
            }
        }
        assert!(worst < 1e-14, "off its acceleration by {worst:e}");
        let need = DVec2::new(0.3, -0.4);
        assert!((breakaway(need, 0.7) + need / 0.5).length() < 1e-12);
    }
}
