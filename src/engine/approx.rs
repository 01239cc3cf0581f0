//! The paper's Sec. III analytic approximations for short times after a release from rest,
//! with the windows in which the paper's own assumptions hold.

/// Sec. III A (Fig. 1), released at rest in the lab at ξ0 ≫ 1: θ = τ²/(2ξ0) (Eq. 12) and
/// ξ = τ⁴/(12ξ0) + ξ0 (Eq. 13). Returns (ξ, θ) with θ the lab angle.
pub fn lab_rest(xi0: f64, tau: f64) -> (f64, f64) {
    (tau.powi(4) / (12.0 * xi0) + xi0, tau * tau / (2.0 * xi0))
}

/// Sec. III A's assumptions θ′ ≪ 1, ξ′ ≪ ξ and |ξ − ξ0| ≪ ξ0 reduce to τ ≪ ξ0, τ ≪ ξ0^{2/3}
/// and τ ≪ √ξ0; the last fails first, so the approximation holds for τ ≲ √ξ0 (≈ 23 at
/// ξ0 = 500, as the paper observes).
pub fn lab_rest_window(xi0: f64) -> f64 {
    xi0.sqrt().min(xi0.powf(2.0 / 3.0)).min(xi0)
}

/// Sec. III B (Fig. 2), released at rest on the table at ξ0 > 1: ξ = (ξ0 − 1) cosh τ + 1
/// (Eq. 19) and the table-frame angular velocity Θ′ = 2 ln(ξ0/ξ) (Eq. 20), integrated here
/// by Simpson's rule for Θ. Returns (ξ, Θ′, Θ).
pub fn table_rest(xi0: f64, tau: f64) -> (f64, f64, f64) {
    let xi = |t: f64| (xi0 - 1.0) * t.cosh() + 1.0;
    let omega = |t: f64| 2.0 * (xi0 / xi(t)).ln();
    let n = 64;
    let h = tau / n as f64;
    let sum: f64 = (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * omega(h * i as f64)
        })
        .sum();
    (xi(tau), omega(tau), sum * h / 3.0)
}

/// Sec. III B's approximation for ξ holds for τ ≲ 1 (Fig. 2). Its Θ′ (Eq. 20) drops the
/// friction term ξΘ′/ξ′, which near a release from rest is the larger one: the converged
/// Θ is several times smaller at ξ0 = 1.1 (see tests/suite/approx.rs).
pub const TABLE_REST_WINDOW: f64 = 1.0;

/// Where Sec. III's approximations hold for a release at rest (none for a throw, nor at μ = 0):
/// τ ≲ √ξ0 in the lab (Sec. III A), τ ≲ 1 on the table outside ξ = 1 (Sec. III B).
pub fn window(i: &super::Initial) -> Option<f64> {
    match i.release {
        _ if i.frictionless => None,
        super::Release::LabRest => Some(lab_rest_window(i.xi0)),
        super::Release::TableRest if i.xi0 > 1.0 => Some(TABLE_REST_WINDOW),
        _ => None,
    }
}

/// Sec. III's ξ at τ for a release at rest (the lab's Eq. 13, else the table's Eq. 19).
pub fn xi(i: &super::Initial, tau: f64) -> f64 {
    match i.release {
        super::Release::LabRest => lab_rest(i.xi0, tau).0,
        _ => table_rest(i.xi0, tau).0,
    }
}
