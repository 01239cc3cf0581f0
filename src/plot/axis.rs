//! Axes for both backends: round tick values, their labels, and ranges that can always be
//! drawn. The terminal's charts and the SVG writer place the same ticks.

use crate::engine::units::Units;
use crate::present::tick_label;
use crate::present::{Quantity, angle_tick, unit_of};
use std::f64::consts::PI;

/// How an axis reads its values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Scale {
    /// Numbers: 1-2-5 ticks, [`tick_label`]s.
    #[default]
    Plain,
    /// Angles in radians, ticked at round multiples of π and read in π (`0`, `0.5π`, `π`),
    /// as an angle reads everywhere else (`present::angle`).
    Angle,
    /// Powers of ten drawn as their logarithms (a value v stands for 10^v): ticked at whole
    /// decades and read as the power (`1e-6`, `1`, `100`).
    Decades,
}

impl Scale {
    /// About `n` tick values over `[a, b]`, round in this scale.
    pub fn ticks(self, a: f64, b: f64, n: usize) -> Vec<f64> {
        match self {
            Scale::Plain => ticks(a, b, n),
            Scale::Angle => {
                // A span too small for round fractions of π (a coin at rest at Θ = 0 before
                // it slips read `2e-4π`): plain radians, as the axis name says.
                if (b - a) / PI / (n.max(1) as f64) < ANGLE_STEP {
                    ticks(a, b, n)
                } else {
                    let t = ticks(a / PI, b / PI, n);
                    t.into_iter().map(|t| t * PI).collect()
                }
            }
            Scale::Decades => {
                let step = ((b - a) / n.max(1) as f64).ceil().max(1.0);
                let (first, last) = ((a / step).ceil(), (b / step).floor());
                if !(first.is_finite() && last.is_finite()) {
                    return vec![a];
                }
                (first as i64..=last as i64)
                    .take(1000)
                    .map(|k| k as f64 * step)
                    .collect()
            }
        }
    }

    /// A tick value's label.
    pub fn label(self, v: f64) -> String {
        match self {
            Scale::Plain => tick_label(v),
            Scale::Angle => {
                let x = v / PI / ANGLE_STEP;
                if (x - x.round()).abs() < 1e-9 {
                    angle_tick(v)
                } else {
                    tick_label(v)
                }
            }
            Scale::Decades => match v.round() as i32 {
                k @ 0..=2 => 10i32.pow(k as u32).to_string(),
                k => format!("1e{k}"),
            },
        }
    }
}

/// The finest step an angle axis ticks in π (0.05π); below it, radians.
const ANGLE_STEP: f64 = 0.05;

/// An axis name with the SI value of its unit beside it when the table is real:
/// `τ (1 = 303 ms)`.
pub fn axis(name: &str, q: Quantity, units: Option<Units>) -> String {
    match units {
        Some(u) => format!("{name} (1 = {})", unit_of(&u, q)),
        None => name.to_string(),
    }
}

/// Tick values: a 1-2-5 step giving about `n` ticks over `[a, b]`.
pub fn ticks(a: f64, b: f64, n: usize) -> Vec<f64> {
    let span = b - a;
    if !(span.is_finite() && span > 0.0) || n == 0 {
        return vec![a];
    }
    let raw = span / n as f64;
    let e = raw.log10().floor() as i32;
    let mag = 10f64.powi(e);
    let m = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .find(|m| m * mag >= raw)
        .unwrap_or(10.0);
    let step = m * mag;
    let first = (a / step).ceil() as i64;
    let last = (b / step).floor() as i64;
    // k·m·10^e, divided rather than multiplied for e < 0 so 0.6 is 0.6.
    let at = |k: i64| {
        let v = k as f64 * m;
        if e < 0 { v / 10f64.powi(-e) } else { v * mag }
    };
    (first..=last).take(1000).map(at).collect()
}

/// Widens a degenerate or non-finite range so a chart can always be drawn.
pub fn sane(r: [f64; 2]) -> [f64; 2] {
    let [a, b] = r;
    if !(a.is_finite() && b.is_finite()) {
        return [0.0, 1.0];
    }
    if b - a > 1e-12 * a.abs().max(b.abs()).max(1e-300) {
        [a, b]
    } else {
        let pad = 0.5 * a.abs().max(1e-3);
        [a - pad, b + pad]
    }
}

/// The bounds of some points with a small margin.
pub fn extent(points: impl Iterator<Item = f64>) -> [f64; 2] {
    let (lo, hi) = points
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    let pad = 0.05 * (hi - lo);
    sane([lo - pad, hi + pad])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        assert_eq!(ticks(0.0, 1.0, 5), vec![0.0, 0.2, 0.4, 0.6, 0.8, 1.0]);
        assert_eq!(
            ticks(0.0, std::f64::consts::TAU, 4),
            vec![0.0, 2.0, 4.0, 6.0]
        );
        let t = ticks(-0.37, 12.5, 3);
        assert_eq!(t, vec![0.0, 5.0, 10.0]);
        assert_eq!(ticks(1.0, 1.0, 3), vec![1.0]);
    }

    #[test]
    fn labels_are_short() {
        assert_eq!(tick_label(0.6), "0.6");
        assert_eq!(tick_label(1.0 / 3.0), "0.333");
        assert_eq!(tick_label(12.0), "12");
        assert_eq!(tick_label(-0.25), "-0.25");
        assert_eq!(tick_label(1e-4), "1e-4");
        assert_eq!(tick_label(0.0), "0");
    }

    #[test]
    fn angle_axes_tick_in_pi() {
        let s = Scale::Angle;
        let labels: Vec<String> = s
            .ticks(0.0, std::f64::consts::TAU, 4)
            .into_iter()
            .map(|v| s.label(v))
            .collect();
        assert_eq!(labels, ["0", "0.5π", "π", "1.5π", "2π"]);
        let labels: Vec<String> = s
            .ticks(-20.0, 1.0, 2)
            .into_iter()
            .map(|v| s.label(v))
            .collect();
        assert_eq!(labels, ["-5π", "0"]);
        // Too narrow for round fractions of π: radians, never `2e-4π`.
        let labels: Vec<String> = s
            .ticks(-1e-3, 1e-3, 2)
            .into_iter()
            .map(|v| s.label(v))
            .collect();
        assert_eq!(labels, ["-0.001", "0", "0.001"]);
        let labels: Vec<String> = s
            .ticks(1.4, 1.8, 3)
            .into_iter()
            .map(|v| s.label(v))
            .collect();
        assert_eq!(labels, ["1.4", "1.6", "1.8"]);
    }

    #[test]
    fn decades_tick_at_whole_powers_of_ten() {
        let s = Scale::Decades;
        let labels: Vec<String> = s
            .ticks(-12.3, -2.5, 5)
            .into_iter()
            .map(|v| s.label(v))
            .collect();
        assert_eq!(labels, ["1e-12", "1e-10", "1e-8", "1e-6", "1e-4"]);
        let labels: Vec<String> = s
            .ticks(0.5, 4.2, 8)
            .into_iter()
            .map(|v| s.label(v))
            .collect();
        assert_eq!(labels, ["10", "100", "1e3", "1e4"]);
    }

    #[test]
    fn ranges_are_never_degenerate() {
        assert_eq!(sane([f64::NAN, 1.0]), [0.0, 1.0]);
        let [a, b] = sane([2.0, 2.0]);
        assert!(a < 2.0 && b > 2.0);
        let [a, b] = extent([f64::INFINITY, 1.0, 3.0].into_iter());
        assert!(a < 1.0 && b > 3.0);
    }
}
