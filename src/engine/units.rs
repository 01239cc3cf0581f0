//! Physical units (Sec. II): the equations are dimensionless with lengths in
//! R_max = μg/Ω² and time in 1/Ω; a table turning at `rpm` with friction μ under gravity g
//! gives every length, time and speed its SI value (said for people by `present`; here only
//! what files and flags need: a length as typed, and metres written to read back exactly).

use crate::error::Error;
use crate::model::Initial;

/// μ, Ω (rad/s) and g (m/s²) of a real table.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Units {
    pub mu: f64,
    pub rpm: f64,
    #[serde(default = "default_g")]
    pub g: f64,
}

/// Gravity unless a scene, the configuration or a flag says otherwise (m/s²).
pub const G_DEFAULT: f64 = 9.81;

fn default_g() -> f64 {
    G_DEFAULT
}

impl Units {
    /// Smallest μ, rpm and g taken: with each in [`Units::MIN`], its maximum], every scale
    /// (R_max = μg/Ω² from 1e-23 m to 1e19 m, 1/Ω up to 1e7 s, μg/Ω) and every length, time
    /// and speed shown in SI is a finite number, never 0 or ∞ (nor NaN from their ratio).
    pub const MIN: f64 = 1e-6;

    /// Checks the values: μ in [1e-6, 10], rpm in [1e-6, 1e6], g in [1e-6, 1e4] (m/s²).
    pub fn new(mu: f64, rpm: f64, g: f64) -> Result<Units, Error> {
        use super::error::{Field, Range, check};
        for (field, x, max) in [
            (Field::Mu, mu, 10.0),
            (Field::Rpm, rpm, 1e6),
            (Field::G, g, 1e4),
        ] {
            check(field, x, Range::Within(Self::MIN, max))?;
        }
        Ok(Units { mu, rpm, g })
    }

    /// Ω in rad/s.
    pub fn omega(&self) -> f64 {
        self.rpm * std::f64::consts::TAU / 60.0
    }

    /// R_max = μg/Ω² in metres: the unit of ξ.
    pub fn r_max_m(&self) -> f64 {
        self.mu * self.g / (self.omega() * self.omega())
    }

    /// 1/Ω in seconds: the unit of τ.
    pub fn t_s(&self) -> f64 {
        1.0 / self.omega()
    }

    /// μg/Ω in m/s: the unit of speed.
    pub fn speed_m_s(&self) -> f64 {
        self.r_max_m() / self.t_s()
    }

    /// The same release on the table `to`: its metres and m/s held, its dimensionless ξ0 and
    /// v0 recomputed in `to`'s units (Sec. II: lengths in R_max = μg/Ω², speeds in μg/Ω; φ
    /// is an angle, the same in both). Larger μ: a larger R_max, so a smaller ξ0.
    pub fn carry(&self, initial: Initial, to: &Units) -> Initial {
        Initial {
            xi0: initial.xi0 * self.r_max_m() / to.r_max_m(),
            v0: initial.v0 * self.speed_m_s() / to.speed_m_s(),
            ..initial
        }
    }

    /// The table of the paper's μ measurement (Sec. IV, Eq. 22): μ = 0.15 at Ω = 3.3 rad/s,
    /// under g = 9.81 m/s². The explorer starts from it when SI units are first asked for.
    pub fn paper() -> Units {
        Units {
            mu: 0.15,
            rpm: 3.3 * 60.0 / std::f64::consts::TAU,
            g: 9.81,
        }
    }
}

/// A length as a user types one: a plain number in units of R_max (`0.1`), or a number with
/// a unit, `m`, `cm` or `mm` (`2cm`, `0.02 m`, `15 mm`), in metres. Metres need a real table
/// to become R_max ([`Length::to_r_max`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Length {
    /// Units of R_max = μg/Ω².
    RMax(f64),
    /// Metres.
    Metres(f64),
}

/// The units a [`Length`] may carry, each with its count per metre (longest name first:
/// `mm` before `m`).
const LENGTH_UNITS: [(&str, f64); 3] = [("mm", 1e3), ("cm", 1e2), ("m", 1.0)];

impl Length {
    /// Reads `2cm`, `0.02 m`, `15 mm` (metres) or a plain `0.1` (R_max). The number is any
    /// that Rust reads (NaN, inf and signs included: ranges are the caller's to check).
    pub fn parse(text: &str) -> Result<Length, String> {
        let t = text.trim();
        let bad = || {
            format!(
                "`{t}` is not a length: a number in units of R_max (0.1), or one with a unit m, cm or mm (2cm, 0.02 m, 15 mm)"
            )
        };
        for (unit, per_m) in LENGTH_UNITS {
            if let Some(x) = t.strip_suffix(unit) {
                let x: f64 = x.trim_end().parse().map_err(|_| bad())?;
                return Ok(Length::Metres(x / per_m));
            }
        }
        t.parse().map(Length::RMax).map_err(|_| bad())
    }

    /// In units of R_max: a plain number as it is; metres on the table `units` (None: there
    /// is no table to measure against, and metres cannot be converted).
    pub fn to_r_max(self, units: Option<&Units>) -> Option<f64> {
        match (self, units) {
            (Length::RMax(x), _) => Some(x),
            (Length::Metres(m), Some(u)) => Some(m / u.r_max_m()),
            (Length::Metres(_), None) => None,
        }
    }

    /// A body's size (`zero_ok`: a height, ≥ 0; else a length, > 0) in units of R_max on the
    /// table `units`. Metres are checked here; a plain number is `Body::validate`'s to check.
    pub fn size_in_r_max(self, units: Option<&Units>, zero_ok: bool) -> Result<f64, SizeRefused> {
        if let Length::Metres(m) = self
            && !(m.is_finite() && (m > 0.0 || (zero_ok && m == 0.0)))
        {
            return Err(SizeRefused::Range(if zero_ok {
                "at least 0"
            } else {
                "positive"
            }));
        }
        self.to_r_max(units).ok_or(SizeRefused::NoTable)
    }

    /// As it was typed, near enough for a message: `0.1` or `2 cm`.
    pub fn show(self) -> String {
        match self {
            Length::RMax(x) => Initial::show(x),
            Length::Metres(m) => show_metres(m),
        }
    }
}

/// Why [`Length::size_in_r_max`] refuses a size; the caller names the flag or key.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SizeRefused {
    /// Out of range in metres: it must be this ("positive", "at least 0").
    Range(&'static str),
    /// In metres, with no table to convert it on.
    NoTable,
}

/// `m` metres as the shortest text [`Length::parse`] reads back to exactly `m`, in the unit
/// that reads best (`2 cm`, `15 mm`, `1.5 m`).
pub fn show_metres(m: f64) -> String {
    show_metres_where(m, |back| back.to_bits() == m.to_bits())
}

/// `l` units of R_max on the table `units` as the shortest text in metres that reads back
/// to exactly `l` on that table, if any does; else the metres in full (back to within an
/// ulp or two).
pub fn show_r_max_in_metres(l: f64, units: &Units) -> String {
    let r = units.r_max_m();
    show_metres_where(l * r, |back| (back / r).to_bits() == l.to_bits())
}

/// The shortest decimal text of `m` metres in a readable unit (m from 1 m, cm from 1 cm, else
/// mm) whose value, read back, satisfies `same`; else `m` in metres in full.
fn show_metres_where(m: f64, same: impl Fn(f64) -> bool) -> String {
    let a = m.abs();
    let (unit, per_m) = if a >= 1.0 || !a.is_finite() {
        LENGTH_UNITS[2]
    } else if a >= 1e-2 {
        LENGTH_UNITS[1]
    } else {
        LENGTH_UNITS[0]
    };
    let v = m * per_m;
    if v.is_finite() {
        for d in 0..=20 {
            let text = format!("{v:.d$}");
            let text = if text.contains('.') {
                text.trim_end_matches('0').trim_end_matches('.')
            } else {
                &text
            };
            if text.parse::<f64>().is_ok_and(|x| same(x / per_m)) {
                return format!("{text} {unit}");
            }
        }
    }
    // Rust writes an f64 with the fewest digits that read back exactly, never in exponent
    // form.
    format!("{m} m")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_s_table() {
        // μ = 0.15 at Ω = 3.3 rad/s (31.5 rpm): R_max = 0.135 m, 1/Ω = 0.303 s.
        let u = Units::new(0.15, 3.3 * 60.0 / std::f64::consts::TAU, 9.81).unwrap();
        assert!((u.omega() - 3.3).abs() < 1e-12);
        assert!((u.r_max_m() - 0.15 * 9.81 / (3.3 * 3.3)).abs() < 1e-15);
        assert!((u.t_s() - 1.0 / 3.3).abs() < 1e-15);
        assert!((u.speed_m_s() - 0.15 * 9.81 / 3.3).abs() < 1e-14);
        assert_eq!(u, Units::paper());
        for bad in [(0.0, 33.0, 9.81), (0.2, f64::NAN, 9.81), (0.2, 33.0, -1.0)] {
            assert!(Units::new(bad.0, bad.1, bad.2).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn lengths_read_with_and_without_units() {
        let m = |t: &str| Length::parse(t).unwrap();
        assert_eq!(m("0.1"), Length::RMax(0.1));
        assert_eq!(m(" 2e-3 "), Length::RMax(2e-3));
        assert_eq!(m("2cm"), Length::Metres(0.02));
        assert_eq!(m("0.02m"), Length::Metres(0.02));
        assert_eq!(m("0.02 m"), Length::Metres(0.02));
        assert_eq!(m("15 mm"), Length::Metres(0.015));
        assert_eq!(m("1e-3m"), Length::Metres(1e-3));
        assert_eq!(m("-2cm"), Length::Metres(-0.02));
        assert!(matches!(m("nan cm"), Length::Metres(x) if x.is_nan()));
        for bad in ["", "cm", "2 in", "2 km", "2c m", "two cm", "2 CM"] {
            assert!(Length::parse(bad).is_err(), "{bad}");
        }
        let u = Units::new(0.2, 100.0 / 3.0, 9.81).unwrap();
        let omega = 100.0 / 3.0 * std::f64::consts::TAU / 60.0;
        let r = 0.2 * 9.81 / (omega * omega);
        assert!((m("2cm").to_r_max(Some(&u)).unwrap() - 0.02 / r).abs() < 1e-15);
        assert_eq!(m("2cm").to_r_max(None), None);
        assert_eq!(m("0.5").to_r_max(None), Some(0.5));
        assert_eq!(show_metres(0.02), "2 cm");
        assert_eq!(show_metres(0.015), "1.5 cm");
        assert_eq!(show_metres(0.004), "4 mm");
        assert_eq!(show_metres(1.5), "1.5 m");
        assert_eq!(show_r_max_in_metres(0.02 / u.r_max_m(), &u), "2 cm");
    }
}
