//! The model's flags shared by the explorer and the commands: a finite body instead of a
//! point, the coupling to the table, a real table's units.

use super::*;

/// A finite body instead of a point (the paper's appendix), for the explorer and `run`.
/// Unset, a scene keeps its own.
#[derive(Args, Debug, Clone, Default)]
#[command(next_help_heading = "A finite body (the paper's appendix)")]
pub struct BodyArgs {
    /// The body's lateral size L (> 0), in R_max or with a unit: `0.1`, `2cm`.
    ///
    /// A plain number in units of R_max, or a length with a unit, m, cm or mm (`2cm`,
    /// `0.02m`, `15 mm`), on the table --mu and --rpm give (the
    /// explorer also takes a scene's or the configuration's `[units]`). The panel and
    /// `run --json` judge the appendix's conditions for treating it as a point, μh/L ≪ 1 and
    /// L/ξ ≪ 1.
    #[arg(long, value_name = "L", allow_hyphen_values = true, value_parser = length)]
    pub body_length: Option<Length>,
    /// The body's height h (≥ 0), as --body-length.
    ///
    /// In R_max units or m, cm, mm (with --body-length). Toppling: μh/L.
    #[arg(long, value_name = "H", allow_hyphen_values = true, value_parser = length)]
    pub body_height: Option<Length>,
    /// The rod's angle at release, ccw from radially outward: rad, or `30deg`.
    ///
    /// In the table frame, from radially outward, ccw (rad, or degrees with `deg`: `30deg`;
    /// with --body-length).
    #[arg(long, value_name = "A", allow_hyphen_values = true, value_parser = angle)]
    pub body_angle: Option<f64>,
}

fn length(text: &str) -> Result<Length, String> {
    Length::parse(text)
}

/// Radians, or degrees with `deg` or `°`: `0.5`, `30deg`, `30 °`.
fn angle(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let (x, per_rad) = match t.strip_suffix("deg").or_else(|| t.strip_suffix('°')) {
        Some(x) => (x.trim_end(), 180.0 / std::f64::consts::PI),
        None => (t, 1.0),
    };
    x.parse::<f64>()
        .map(|x| x / per_rad)
        .map_err(|_| format!("`{t}` is not an angle: radians (0.5), or degrees with deg (30deg)"))
}

impl BodyArgs {
    /// The body asked for, checked, its sizes in R_max on the table `units` (a size in metres
    /// needs one; `where_units` says where the command takes it from); `None` if no flag was
    /// given.
    pub fn body(&self, units: Option<&Units>, where_units: &str) -> Result<Option<Body>, Error> {
        let Some(length) = self.body_length else {
            if self.body_height.is_some() || self.body_angle.is_some() {
                return Err(Error::invalid(
                    "--body-height and --body-angle describe a body: give its size with --body-length",
                ));
            }
            return Ok(None);
        };
        let r_max = |flag: &str, l: Length, zero_ok: bool| -> Result<f64, Error> {
            l.size_in_r_max(units, zero_ok).map_err(|e| Error::invalid(match e {
                SizeRefused::Range(what) => format!("--{flag} must be {what}, got {}", l.show()),
                SizeRefused::NoTable => format!(
                    "--{flag} {} is a length in metres, which needs the real table's R_max: add {where_units}, or give it in units of R_max (a plain number)",
                    l.show()
                ),
            }))
        };
        let b = Body {
            length: r_max("body-length", length, false)?,
            height: self
                .body_height
                .map(|h| r_max("body-height", h, true))
                .transpose()?,
            angle: self.body_angle.unwrap_or(0.0),
        };
        crate::check::body(&b, crate::check::Via::Flags)?;
        Ok(Some(b))
    }
}

/// How the particle is coupled to the table (extends the paper), shared by the explorer and
/// every command. Unset, a scene keeps its own.
#[derive(Args, Debug, Clone, Default)]
#[command(next_help_heading = "Friction")]
pub struct CouplingArgs {
    /// coulomb (dry friction, the paper's) or stokes (linear drag, with --gamma).
    ///
    /// Stokes drag is −γ m u relative to the table, solved in closed form: every release but
    /// a measure-zero few leaves.
    #[arg(long, value_parser = variant::<CouplingName>())]
    pub coupling: Option<CouplingName>,
    /// Static over kinetic friction, mu_s/mu_k ≥ 1 (the paper: 1).
    ///
    /// At rest on the table the particle holds out to xi = R, and slides at mu_k once
    /// loose.
    #[arg(long, value_name = "R", allow_hyphen_values = true)]
    pub mu_static_ratio: Option<f64>,
    /// Stokes drag rate in units of Omega, ≥ 0 (implies --coupling stokes).
    #[arg(long, value_name = "G", allow_hyphen_values = true)]
    pub gamma: Option<f64>,
}

impl CouplingArgs {
    /// The coupling asked for, checked; `None` if no flag was given.
    pub fn coupling(&self) -> Result<Option<Coupling>, Error> {
        if self.coupling.is_none() && self.mu_static_ratio.is_none() && self.gamma.is_none() {
            return Ok(None);
        }
        let name = self.coupling.unwrap_or(if self.gamma.is_some() {
            CouplingName::Stokes
        } else {
            CouplingName::Coulomb
        });
        let c = name
            .with(self.mu_static_ratio, self.gamma)
            .map_err(|e| Error::invalid(e.named("--gamma", "--mu-static-ratio", "--coupling")))?;
        c.validate()
            .map_err(|e| crate::check::named(e, crate::check::Via::Flags))?;
        Ok(Some(c))
    }
}

/// A real table: every length, time and speed also in SI.
#[derive(Args, Debug, Clone, Default)]
#[command(next_help_heading = "A real table (SI beside R_max and 1/Omega)")]
pub struct UnitsArgs {
    /// Friction coefficient of a real table (with --rpm).
    #[arg(long, allow_hyphen_values = true)]
    pub mu: Option<f64>,
    /// The table's speed in revolutions per minute (with --mu).
    #[arg(long, allow_hyphen_values = true)]
    pub rpm: Option<f64>,
    /// Gravitational acceleration in m/s² (with --mu and --rpm) [default: 9.81].
    #[arg(long = "g", allow_hyphen_values = true)]
    pub gravity: Option<f64>,
}

impl UnitsArgs {
    /// The units asked for, if any: --mu and --rpm go together.
    pub fn units(&self) -> Result<Option<crate::engine::units::Units>, Error> {
        match (self.mu, self.rpm, self.gravity) {
            (None, None, None) => Ok(None),
            (Some(mu), Some(rpm), g) => {
                let u = Units {
                    mu,
                    rpm,
                    g: g.unwrap_or(G_DEFAULT),
                };
                crate::check::units(&u, crate::check::Via::Flags).map(Some)
            }
            _ => Err(Error::invalid(
                "physical units need both --mu and --rpm (and optionally --g)",
            )),
        }
    }
}
