//! The one line the keys type into: a scene's name (`S`) or values (`:`, "v0 0.6078"). While
//! it is open, keys are its letters; Enter takes it, Esc closes it.

use crate::check::{self, Via};
use crate::engine::Initial;
use crate::engine::units::Units;

/// Longest line the prompt takes (a scene's name is one line of its panel; values fit).
pub const TYPED_MAX: usize = 40;

/// What the prompt asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Asks {
    /// A name to save the scene under.
    Name,
    /// Values to set: ξ0, φ, v0, and a real table's μ, Ω (rpm) and g.
    Values,
}

/// The prompt while it is open: what it asks, what is typed, and why the last Enter was
/// refused (shown beside it until the next key).
#[derive(Clone, Debug, PartialEq)]
pub struct Prompt {
    pub asks: Asks,
    pub typed: String,
    pub refused: Option<String>,
}

impl Prompt {
    pub fn new(asks: Asks) -> Prompt {
        Prompt {
            asks,
            typed: String::new(),
            refused: None,
        }
    }

    /// The prompt's label on the status line.
    pub fn label(&self) -> &'static str {
        match self.asks {
            Asks::Name => "save as",
            Asks::Values => "set",
        }
    }

    /// What it asks, in words (plain mode says it when it opens).
    pub fn asking(&self) -> &'static str {
        match self.asks {
            Asks::Name => "save as: type a name, Enter saves, Esc cancels",
            Asks::Values => {
                "set: type values (xi0, phi, v0; mu, rpm, omega, g), e.g. v0 0.6078, or an accuracy, e.g. error 1e-8; Enter sets, Esc cancels"
            }
        }
    }

    /// What is typed, one word.
    pub fn what(&self) -> &'static str {
        match self.asks {
            Asks::Name => "name",
            Asks::Values => "values",
        }
    }

    /// What Enter and Esc do, for the status line where there is room.
    pub fn hint(&self) -> &'static str {
        match self.asks {
            Asks::Name => "Enter saves · Esc cancels",
            Asks::Values => "xi0 phi v0 mu rpm omega g, e.g. v0 0.6078; error 1e-8 · Esc",
        }
    }
}

/// The names each value is typed by (the first is how messages name it).
const NAMES: [(&[&str], Value); 7] = [
    (&["xi0", "ξ0", "xi", "ξ"], Value::Xi0),
    (&["phi", "φ"], Value::Phi),
    (&["v0", "v"], Value::V0),
    (&["mu", "μ"], Value::Mu),
    (&["rpm"], Value::Rpm),
    (&["omega", "ω", "Ω"], Value::Omega),
    (&["g"], Value::G),
];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Value {
    Xi0,
    Phi,
    V0,
    Mu,
    Rpm,
    /// Ω in rad/s (kept as rpm).
    Omega,
    G,
}

/// The release and the table after `typed` ("xi0 1.1 phi 1.2pi v0=1.3", "mu 0.2, rpm 45"),
/// checked as any value from outside is (`crate::check`); `units` None means dimensionless
/// only, unless the line sets μ, rpm, Ω or g (then from `start`, a record player). φ takes
/// radians, a multiple of π (`0.5pi`, `-0.8π`) or degrees (`90deg`, `90°`).
pub fn values(
    typed: &str,
    initial: Initial,
    units: Option<Units>,
    start: Units,
) -> Result<(Initial, Option<Units>), String> {
    let words: Vec<&str> = typed
        .split(|c: char| c.is_whitespace() || c == '=' || c == ',')
        .filter(|w| !w.is_empty())
        .collect();
    if words.is_empty() {
        return Err("type a name and a value, e.g. v0 0.6078".into());
    }
    let (mut i, mut u) = (initial, units);
    for pair in words.chunks(2) {
        let name = pair[0];
        let Some((_, value)) = NAMES
            .iter()
            .find(|(names, _)| names.iter().any(|n| n.eq_ignore_ascii_case(name)))
        else {
            return Err(format!(
                "unknown value '{name}' (xi0, phi, v0, mu, rpm, omega, g)"
            ));
        };
        let Some(text) = pair.get(1) else {
            return Err(format!("{name} needs a value, e.g. {name} 1"));
        };
        let x = number(text, *value == Value::Phi)
            .ok_or_else(|| format!("{name}: '{text}' is not a number"))?;
        match value {
            Value::Xi0 => i.xi0 = x,
            Value::Phi => i.phi = x,
            Value::V0 => i.v0 = x,
            Value::Mu => u.get_or_insert(start).mu = x,
            Value::Rpm => u.get_or_insert(start).rpm = x,
            Value::Omega => u.get_or_insert(start).rpm = x * 60.0 / std::f64::consts::TAU,
            Value::G => u.get_or_insert(start).g = x,
        }
    }
    check::initial(&i, Via::Prompt).map_err(|e| e.to_string())?;
    if let Some(t) = u {
        check::units(&t, Via::Prompt).map_err(|e| e.to_string())?;
    }
    Ok((i, u))
}

/// An accuracy asked for (`error 1e-8`: the cheapest setting whose stated error is at most
/// that, [`crate::sim::accuracy`]): None when the line sets values instead; the number, or why
/// it cannot be asked for.
pub fn asked_error(typed: &str) -> Option<Result<f64, String>> {
    let mut words = typed
        .split(|c: char| c.is_whitespace() || c == '=')
        .filter(|w| !w.is_empty());
    if !words.next()?.eq_ignore_ascii_case("error") {
        return None;
    }
    let (Some(text), None) = (words.next(), words.next()) else {
        return Some(Err("error takes one number, e.g. error 1e-8".into()));
    };
    let Some(e) = text.parse::<f64>().ok() else {
        return Some(Err(format!("error: '{text}' is not a number")));
    };
    Some(match crate::sim::accuracy::refused(e) {
        Some(why) => Err(format!("error {why}")),
        None => Ok(e),
    })
}

/// A finite number; for an angle also `0.5pi`, `π`, `90deg`, `90°`.
fn number(text: &str, angle: bool) -> Option<f64> {
    let scaled = |suffixes: &[&str], scale: f64| {
        suffixes.iter().find_map(|s| {
            let head = text.strip_suffix(s)?;
            match head {
                "" => Some(scale),
                "-" => Some(-scale),
                h => h.parse::<f64>().ok().map(|x| x * scale),
            }
        })
    };
    let x = if angle {
        scaled(&["pi", "π"], std::f64::consts::PI)
            .or_else(|| scaled(&["deg", "°"], std::f64::consts::PI / 180.0))
            .or_else(|| text.parse().ok())
    } else {
        text.parse().ok()
    }?;
    x.is_finite().then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn start() -> Units {
        Units::new(0.15, 100.0 / 3.0, 9.81).unwrap()
    }

    #[test]
    fn values_as_typed() {
        let i = Initial::velocity(0.5, 0.0, 0.6);
        let (j, u) = values("xi0 1.1 phi=1.2pi, v0 1.3", i, None, start()).unwrap();
        assert_eq!((j.xi0, j.v0, u), (1.1, 1.3, None));
        assert!((j.phi - 1.2 * PI).abs() < 1e-15);
        let (j, _) = values("φ 90°", i, None, start()).unwrap();
        assert!((j.phi - PI / 2.0).abs() < 1e-15);
        let (j, _) = values("phi -π", i, None, start()).unwrap();
        assert_eq!(j.phi, -PI);
        // A table's value turns SI units on, from the record player.
        let (_, u) = values("mu 0.2", i, None, start()).unwrap();
        assert_eq!(u, Some(Units::new(0.2, 100.0 / 3.0, 9.81).unwrap()));
        let (j, u) = values("mu 0.2 xi0 0.5", i, None, start()).unwrap();
        assert_eq!((j.xi0, u.unwrap().mu), (0.5, 0.2));
        let (_, u) = values("omega 6.283185307179586", i, None, start()).unwrap();
        assert!((u.unwrap().rpm - 60.0).abs() < 1e-12);
    }

    #[test]
    fn an_accuracy_is_asked_for_by_one_number() {
        assert_eq!(asked_error("v0 0.3"), None);
        assert_eq!(asked_error("error 1e-8"), Some(Ok(1e-8)));
        assert_eq!(asked_error("Error=1e-6"), Some(Ok(1e-6)));
        for bad in [
            "error",
            "error 0",
            "error -1",
            "error nan",
            "error 1e300",
            "error x",
            "error 1e-8 v0 1",
        ] {
            assert!(matches!(asked_error(bad), Some(Err(_))), "{bad}");
        }
    }

    #[test]
    fn refusals_say_what_and_why() {
        let i = Initial::velocity(0.5, 0.0, 0.6);
        let err = |t: &str| values(t, i, None, start()).unwrap_err();
        assert_eq!(err(""), "type a name and a value, e.g. v0 0.6078");
        assert_eq!(
            err("speed 2"),
            "unknown value 'speed' (xi0, phi, v0, mu, rpm, omega, g)"
        );
        assert_eq!(err("v0"), "v0 needs a value, e.g. v0 1");
        assert_eq!(err("v0 fast"), "v0: 'fast' is not a number");
        assert_eq!(err("v0 inf"), "v0: 'inf' is not a number");
        assert!(err("v0 -1").contains("v0"), "{}", err("v0 -1"));
        assert!(err("mu 11").contains("mu"), "{}", err("mu 11"));
    }
}
