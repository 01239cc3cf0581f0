//! The contacts' mechanics: the friction a stuck contact needs, how a stop takes out a slip,
//! the direction a contact breaks loose in, and the equations of motion in each phase.

use super::state::{Phase, RodState, S, V, axis};
use glam::DVec2;

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
pub(super) fn pivot_need(l: f64, i: usize, anchor: DVec2, psi: f64, w: f64) -> DVec2 {
    let (s, e) = (S[i], axis(psi));
    let n = 0.5 * (s * l * w * w + 2.0 * s * l * w - anchor.dot(e) + s * l);
    e * n - anchor * 0.5
}

/// The rod's rate once contact `k`'s residual slip u_k (below the stop floor) is taken out by
/// a plastic impulse P at that contact: Δu = P, Δψ′ = 2 s (ê⊥·P)/L, so Δu_k = (1 + ê⊥ê⊥ᵀ) P
/// and P = −(ê êᵀ + ½ ê⊥ê⊥ᵀ) u_k. Kinetic energy changes by −½ u_kᵀ(ê êᵀ + ½ ê⊥ê⊥ᵀ) u_k ≤ 0;
/// simply dropping u_k from u (keeping ψ′) changes it by ½|u_k|² − u·u_k, which rises by up
/// to |u||u_k| ~ 10⁻⁸ at tol 10⁻¹⁰.
pub(super) fn stop_contact(l: f64, k: usize, s: &RodState) -> f64 {
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
pub(super) fn breakaway(need: DVec2, psi: f64) -> DVec2 {
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
pub(super) struct Friction {
    /// Where a contact's slip is zero: the direction it starts in.
    pub(super) fallback: [DVec2; 2],
    /// Contacts breaking loose, whose slip has not yet grown past `floor`.
    pub(super) breaking: [bool; 2],
    pub(super) floor: f64,
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
pub(super) fn rhs(l: f64, phase: Phase, friction: &Friction, y: V) -> V {
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
