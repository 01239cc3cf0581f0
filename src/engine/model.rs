//! The paper's dimensionless model: Sec. II (Eqs. 6–7) written in Cartesian form as in
//! Sec. IV, with the conventions of `shared/CONVENTIONS.md` (Ω = 1, μg = 1, the table turns
//! counterclockwise). Never polar inside: polar forms are singular at ξ = 0.

use crate::error::Error;
use glam::DVec2;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use strum::{Display, EnumMessage, EnumString, IntoStaticStr, VariantArray};

/// `ẑ × a`: the table's velocity at `a`, and the Coriolis direction (Sec. II).
pub fn zcross(a: DVec2) -> DVec2 {
    DVec2::new(-a.y, a.x)
}

/// `a` rotated counterclockwise by `angle`: `R(τ)` takes table-frame vectors to the lab.
pub fn rotate(a: DVec2, angle: f64) -> DVec2 {
    DVec2::from_angle(angle).rotate(a)
}

/// Wraps an angle into (−π, π], the range rest angles are reported in (CONVENTIONS.md).
pub fn wrap_angle(a: f64) -> f64 {
    let w = a.rem_euclid(2.0 * PI);
    if w > PI { w - 2.0 * PI } else { w }
}

/// An angle in [0, 2π). A hair below a whole turn (−0, or −1e-13 from a rest exactly on the
/// release direction) is 0: `rem_euclid` alone gives 2π − ε, printed as 6.283185307180.
pub fn turn_angle(a: f64) -> f64 {
    let w = a.rem_euclid(2.0 * PI);
    if 2.0 * PI - w < 1e-12 { 0.0 } else { w }
}

/// Dry friction on the particle (Eq. 2): −û while slipping. At u = 0 it is the Filippov value:
/// static friction balances the centrifugal pull `p` if it can (|p| ≤ 1, property 1 of Sec. II),
/// otherwise it opposes it at full strength, so the particle leaves the discontinuity along `p`.
/// `p` is the position (lab or table frame: only its length and direction matter here).
pub fn friction(u: DVec2, p: DVec2) -> DVec2 {
    let s = u.length();
    if s > 0.0 {
        -u / s
    } else {
        let n = p.length();
        if n > 1.0 { -p / n } else { -p }
    }
}

/// How a particle is released (CONVENTIONS.md; the paper's Figs. 1–5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[derive(Display, EnumString, IntoStaticStr, VariantArray, EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum Release {
    /// Speed `v0` in direction `φ`, both in the table frame (Figs. 3–5).
    #[default]
    Velocity,
    /// At rest on the table, u0 = 0 (Sec. III B, Fig. 2).
    TableRest,
    /// At rest in the lab, u0 = (0, −ξ0) (Sec. III A, Figs. 1 and 6).
    LabRest,
}

/// Initial conditions as in the paper's Figs. 3–5: start at (ξ0, 0); `v0` and `φ` in the table
/// frame, φ from the radially outward direction, counterclockwise positive.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Initial {
    pub xi0: f64,
    pub phi: f64,
    pub v0: f64,
    #[serde(default)]
    pub release: Release,
    /// μ = 0: no friction at all. Lengths keep the unit R_max of the table with friction, so
    /// the same ξ0 and v0 can be compared with and without it.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub frictionless: bool,
}

/// A number as the shortest digits that read back to it exactly: plain where its size lies
/// in `plain` (and 0, inf and NaN), else in e-notation (1e300, not 301 digits).
pub fn digits(x: f64, plain: std::ops::Range<f64>) -> String {
    if x == 0.0 || !x.is_finite() || plain.contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

impl Initial {
    pub fn velocity(xi0: f64, phi: f64, v0: f64) -> Self {
        Initial {
            xi0,
            phi,
            v0,
            release: Release::Velocity,
            frictionless: false,
        }
    }
    pub fn at_rest(xi0: f64, release: Release) -> Self {
        Initial {
            xi0,
            phi: 0.0,
            v0: 0.0,
            release,
            frictionless: false,
        }
    }

    /// μ = 0 in closed form: nothing acts in the plane, so the particle keeps its lab velocity
    /// and moves in a straight line (Newton's first law; the paper's Eq. 1 without friction).
    pub fn free_state(&self, tau: f64) -> State {
        let s0 = self.state();
        State {
            tau,
            r: s0.r + s0.v * tau,
            v: s0.v,
        }
    }

    /// μ = 0: when escape is certified, i.e. the first τ with ξ > 1 and ξ′ ≥ 0. On a straight
    /// line ξ′ never turns negative again once it is not, so it never comes back. `None` if
    /// the particle is at rest in the lab, where it stays forever.
    pub fn free_escape(&self) -> Option<f64> {
        let s0 = self.state();
        let (r, v) = (s0.r, s0.v);
        let a = v.length_squared();
        if a == 0.0 {
            return None;
        }
        // Closest approach, then the way out through ξ = 1.
        let closest = (-r.dot(v) / a).max(0.0);
        if (r + v * closest).length() > 1.0 {
            return Some(closest);
        }
        let b = r.dot(v);
        Some((-b + (b * b - a * (r.length_squared() - 1.0)).max(0.0).sqrt()) / a)
    }

    /// Largest ξ0 and v0 accepted: far beyond any table, and small enough that squares and
    /// energies stay finite.
    pub const MAX: f64 = 1e12;

    /// A number for a message: [`digits`], plain from 1e-4 to 1e9.
    pub fn show(x: f64) -> String {
        digits(x, 1e-4..1e9)
    }

    /// Checks the values a user may type: finite, 0 ≤ ξ0, v0 ≤ [`Initial::MAX`].
    pub fn validate(&self) -> Result<(), Error> {
        use super::error::{Field, Range, check};
        for (field, x) in [
            (Field::Xi0, self.xi0),
            (Field::Phi, self.phi),
            (Field::V0, self.v0),
        ] {
            check(field, x, Range::Finite)?;
        }
        check(Field::Xi0, self.xi0, Range::AtLeast(0.0))?;
        check(Field::V0, self.v0, Range::AtLeast(0.0))?;
        for (field, x) in [(Field::Xi0, self.xi0), (Field::V0, self.v0)] {
            check(field, x, Range::AtMost(Self::MAX))?;
        }
        Ok(())
    }

    /// Initial velocity relative to the table (at τ = 0 both frames coincide).
    pub fn u0(&self) -> DVec2 {
        match self.release {
            Release::Velocity => DVec2::from_angle(self.phi) * self.v0,
            Release::TableRest => DVec2::ZERO,
            Release::LabRest => DVec2::new(0.0, -self.xi0),
        }
    }

    pub fn state(&self) -> State {
        let r = DVec2::new(self.xi0, 0.0);
        State {
            tau: 0.0,
            r,
            v: self.u0() + zcross(r),
        }
    }
}

/// The particle at time τ, in the lab frame: position `r`, velocity `v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    pub tau: f64,
    pub r: DVec2,
    pub v: DVec2,
}

impl State {
    /// Velocity relative to the table, lab components: u = v − ẑ × r.
    pub fn u_lab(&self) -> DVec2 {
        self.v - zcross(self.r)
    }
    /// Position in the rotating frame, q = R(−τ) r.
    pub fn q(&self) -> DVec2 {
        rotate(self.r, -self.tau)
    }
    /// Relative velocity in the rotating frame.
    pub fn u(&self) -> DVec2 {
        rotate(self.u_lab(), -self.tau)
    }
    pub fn xi(&self) -> f64 {
        self.r.length()
    }
    /// ξ′ = r·v/|r| (= q·u/|q|); at ξ = 0 the particle moves straight out, so ξ′ = |v|.
    pub fn xi_dot(&self) -> f64 {
        let xi = self.xi();
        if xi > 0.0 {
            self.r.dot(self.v) / xi
        } else {
            self.v.length()
        }
    }
    /// θ′ (lab), undefined at ξ = 0.
    pub fn theta_dot(&self) -> Option<f64> {
        let xi2 = self.r.length_squared();
        (xi2 > 0.0).then(|| self.r.perp_dot(self.v) / xi2)
    }
    /// E = ½|u|² − ½|q|²: dE/dτ = −|u| (Coriolis does no work), so E < −½ means it can never
    /// stick again (a particle at rest at ξ ≤ 1 has E ≥ −½).
    pub fn energy(&self) -> f64 {
        0.5 * (self.u_lab().length_squared() - self.r.length_squared())
    }
    /// Lab position of a particle at rest on the table at `q` since time 0: closed-form rotation.
    pub fn riding(q: DVec2, tau: f64) -> State {
        let r = rotate(q, tau);
        State {
            tau,
            r,
            v: zcross(r),
        }
    }
}

/// The frame an integrator works in (CONVENTIONS.md, "Frames and state").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[derive(Display, EnumString, IntoStaticStr, VariantArray, EnumMessage)]
#[strum(serialize_all = "kebab-case")]
pub enum Frame {
    /// r′ = v, v′ = −û (the paper's Sec. IV system). Bounded right-hand side: cheap far out.
    #[default]
    Lab,
    /// q′ = u, u′ = −2ẑ×u + q − û (Coriolis, centrifugal, friction).
    #[strum(to_string = "table", serialize = "rotating")]
    Table,
}

/// Phase-space point of the integrator in its frame: position `p`, velocity `w`
/// (lab: r, v; table: q, u).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Y {
    pub p: DVec2,
    pub w: DVec2,
}

impl std::ops::Add for Y {
    type Output = Y;
    fn add(self, o: Y) -> Y {
        Y {
            p: self.p + o.p,
            w: self.w + o.w,
        }
    }
}

impl std::ops::Sub for Y {
    type Output = Y;
    fn sub(self, o: Y) -> Y {
        Y {
            p: self.p - o.p,
            w: self.w - o.w,
        }
    }
}

impl std::ops::Mul<f64> for Y {
    type Output = Y;
    fn mul(self, k: f64) -> Y {
        Y {
            p: self.p * k,
            w: self.w * k,
        }
    }
}

impl Frame {
    /// The equations of motion while slipping, in this frame (CONVENTIONS.md).
    pub fn rhs(self, y: Y) -> Y {
        match self {
            Frame::Lab => Y {
                p: y.w,
                w: friction(y.w - zcross(y.p), y.p),
            },
            Frame::Table => Y {
                p: y.w,
                w: -2.0 * zcross(y.w) + y.p + friction(y.w, y.p),
            },
        }
    }
    /// The equations of motion with μ = 0: straight lines in the lab, and in the rotating
    /// frame the Coriolis and centrifugal terms alone.
    pub fn rhs_free(self, y: Y) -> Y {
        match self {
            Frame::Lab => Y {
                p: y.w,
                w: DVec2::ZERO,
            },
            Frame::Table => Y {
                p: y.w,
                w: -2.0 * zcross(y.w) + y.p,
            },
        }
    }
    pub fn from_state(self, s: &State) -> Y {
        match self {
            Frame::Lab => Y { p: s.r, w: s.v },
            Frame::Table => Y { p: s.q(), w: s.u() },
        }
    }
    pub fn to_state(self, y: Y, tau: f64) -> State {
        match self {
            Frame::Lab => State {
                tau,
                r: y.p,
                v: y.w,
            },
            Frame::Table => {
                let r = rotate(y.p, tau);
                State {
                    tau,
                    r,
                    v: rotate(y.w, tau) + zcross(r),
                }
            }
        }
    }
}

/// The three forces per unit mass in the rotating frame (Sec. IV's explanation of Fig. 5):
/// friction (none if `frictionless`), Coriolis and centrifugal, in table-frame components.
pub fn table_forces(s: &State, frictionless: bool) -> [DVec2; 3] {
    coupled_forces(s, frictionless, crate::Coupling::PAPER)
}

/// [`table_forces`] with the table's coupling (extends the paper): Coulomb friction whose
/// static part holds out to ξ = μ_s/μ_k, or Stokes drag −γu.
pub fn coupled_forces(s: &State, frictionless: bool, coupling: crate::Coupling) -> [DVec2; 3] {
    use crate::Coupling;
    let (q, u) = (s.q(), s.u());
    let fr = match coupling {
        _ if frictionless => DVec2::ZERO,
        Coupling::Stokes { gamma } => -gamma * u,
        // At rest and held: static friction balances the centrifugal pull.
        Coupling::Coulomb { hold } if u == DVec2::ZERO && q.length() <= hold => -q,
        Coupling::Coulomb { .. } => friction(u, q),
    };
    [fr, -2.0 * zcross(u), q]
}
