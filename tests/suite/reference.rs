//! Reference values the tests compare against, each stated once with where it comes from: a
//! closed form, the paper, or a converged run at a stated tolerance whose second opinion (or
//! certified bracket) is given. A test states its own tolerance against them.

/// ξ0c, the largest release radius at which a particle placed at rest in the lab stays (Fig. 6,
/// Eq. 22; the paper: 0.87): `turntable critical --tol 1e-13 --xtol 1e-11`, certified bracket
/// [0.872043856041, 0.872043856047].
pub const XI0C: f64 = 0.872043856044;

/// v_e(0.5, 0), case C's escape speed (Sec. IV; the paper's C at 0.6078 escapes):
/// `turntable escape --xi0 0.5 --phi 0 --tol 1e-13 --vtol 1e-12`, certified bracket
/// [0.6078236450945, 0.6078236450954].
pub const VE_C: f64 = 0.607823645095;

/// Case A (ξ0 0.5, φ π, v0 1): rest ξ and stop τ, `turntable run --tol 1e-13` (its second
/// opinion, tol 1e-14 in the other frame, within 1.3e-14 in τ).
pub const A_REST: (f64, f64) = (0.313404070781, 0.996881020206);

/// Case B (ξ0 0.5, φ 0, v0 0.6): rest ξ and stop τ, likewise (second opinion within 5.4e-14).
pub const B_REST: (f64, f64) = (0.945267965543, 2.700107136103);

/// Case D (ξ0 1.1, φ 1.2π, v0 1.3): rest ξ and stop τ, likewise (second opinion within 9.5e-14).
pub const D_REST: (f64, f64) = (0.674954994969, 0.764262693529);
