//! Numbers for people: the formatters the readouts, notices, captions, charts' ticks, figures
//! and the CLI's words share, so a value reads the same wherever a person meets it. Of the crate
//! it needs only the engine's `Units` and `Settings` (to say a table's scales in SI, a method's
//! accuracy), so the model's notices (`app`), the charts' descriptions (`plot`), the view (`ui`)
//! and the CLI all use it. Files and machine output (JSON, CSV, scene files) are not its
//! business: they keep full digits (angles in radians).

use crate::engine::Settings;
use crate::engine::units::Units;
use std::f64::consts::PI;

/// A number for a readout: never NaN or inf on screen.
pub fn num(x: f64, prec: usize) -> String {
    if x.is_finite() {
        let s = format!("{x:.prec$}");
        if s.trim_start_matches('-')
            .chars()
            .all(|c| c == '0' || c == '.')
        {
            s.trim_start_matches('-').to_string()
        } else {
            s
        }
    } else {
        "—".into()
    }
}

/// `n` of a `thing`, plural when it is not one: "1 question", "3 waits".
pub fn count(n: usize, thing: &str) -> String {
    format!("{n} {thing}{}", if n == 1 { "" } else { "s" })
}

/// The decimals of π an angle is said to: 0.0001π (3e-4 rad, 0.018°) keeps θ, Θ and ψ about
/// as fine as the panel read them in radians (to 1e-4), and is finer than a key's step
/// (0.01π) or the escape page's least v_e (found to 3e-4π, said to 0.001π).
pub const ANGLE_DECIMALS: usize = 4;

/// An angle for people, the one convention wherever one is read (φ, θ, Θ, ψ): the direction
/// `rad` (radians) in [0, 2π), as a multiple of π to [`ANGLE_DECIMALS`] with its trailing
/// zeros dropped: `0`, `0.2571π`, `π`, `1.2π` (as the paper writes case D's). Machine output
/// (JSON, CSV, scene files) keeps radians.
pub fn angle(rad: f64) -> String {
    angle_to(rad, ANGLE_DECIMALS)
}

/// [`angle`] to `decimals` of π: fewer where fewer are known (an angle off a grid of
/// angles), more where a researcher's report keeps its digits.
pub fn angle_to(rad: f64, decimals: usize) -> String {
    if !rad.is_finite() {
        return "—".into();
    }
    let text = short((rad / PI).rem_euclid(2.0), decimals);
    // Rounded up to 2π, it is the direction 0.
    if text == "2" {
        return "0".into();
    }
    times_pi(&text)
}

/// A tick on an axis of angles: `rad` as a multiple of π (`0`, `0.5π`, `π`, `2π`), as short
/// as [`tick_label`] and not wrapped (the φ axis runs to 2π, an unwrapped θ beyond).
pub fn angle_tick(rad: f64) -> String {
    times_pi(&tick_label(rad / PI))
}

/// The number written `x`, times π: `0`, `π`, `-π`, `0.5π`.
fn times_pi(x: &str) -> String {
    match x {
        "0" => "0".into(),
        "1" => "π".into(),
        "-1" => "-π".into(),
        _ => format!("{x}π"),
    }
}

/// A number to at most `prec` places, its trailing zeros dropped: `0.5`, `12`, `0`.
pub fn short(x: f64, prec: usize) -> String {
    let s = num(x, prec);
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A number in exponent form with `decimals` in its mantissa (`1.1e-3`): never NaN or inf.
pub fn sci(x: f64, decimals: usize) -> String {
    if x.is_finite() {
        format!("{x:.decimals$e}")
    } else {
        "—".into()
    }
}

/// A rate that may be below what `prec` places show (ξ′, |u| near a stop): in exponent form
/// then, so that "slipping" never stands beside a row of zeros; at `prec` places otherwise,
/// one significant digit enough (0.0005), as a rate dying away only needs its size.
pub fn rate(x: f64, prec: usize) -> String {
    if x != 0.0 && x.abs() < 0.5 * 10f64.powi(-(prec as i32)) {
        sci(x, 1)
    } else {
        num(x, prec)
    }
}

/// A size or ratio (a body's length and height, μh/L, L/ξ): four decimals, in exponent form
/// with three digits below 1e-3 or from 1e4. Unlike [`rate`] it keeps three digits at any
/// scale: a body's size is a value someone chose (3.3e-4, not 0.0003), and a ratio is judged
/// against 0.1.
pub fn ratio(x: f64) -> String {
    if (1e-3..1e4).contains(&x) || x == 0.0 {
        num(x, 4)
    } else {
        sci(x, 2)
    }
}

/// "dt=1e-3" or "tol=1e-10": the knob that sets a method's accuracy.
pub fn accuracy(s: &Settings) -> String {
    match s.scheme.tol() {
        Some(tol) => format!("tol={}", sci(tol, 0)),
        None => format!("dt={}", sci(s.scheme.knob(), 0)),
    }
}

/// Separates a text's wordings, longest first (see [`alternatives`]).
pub const OR: char = '\u{1f}';

/// A text said several ways, longest first: the terminal shows the first that fits whole
/// (`ui::fit`), so a narrow screen reads a shorter sentence, not a long one cut after "for" or
/// "dt ="; a figure has room for the first.
pub fn alternatives<S: AsRef<str>>(wordings: &[S]) -> String {
    let all: Vec<&str> = wordings.iter().map(AsRef::as_ref).collect();
    all.join(&OR.to_string())
}

/// A speed read off an escape-speed curve, bracketed to 1e-4 (`analysis::CURVE_VTOL`, what
/// its line needs): four decimals, no more than it knows.
pub fn curve_speed(v: f64) -> String {
    num(v, 4)
}

/// A release speed: four decimals, up to six where they are not zeros (C's v0 = 0.6078 and
/// its escape speed 0.607797… differ in the sixth).
pub fn speed(v: f64) -> String {
    let s = num(v, 6);
    match s.find('.') {
        Some(dot) => {
            let keep = (dot + 5).max(s.trim_end_matches('0').len());
            s[..keep.min(s.len())].to_string()
        }
        None => s,
    }
}

/// A tick value, short: `0.5`, `12`, `1e-3`, `-0.25`.
pub fn tick_label(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.0e}")
    } else {
        short(v, 3)
    }
}

/// The explorer's play speed: `2`, or `1/4` below one.
pub fn fmt_speed(s: f64) -> String {
    if s >= 1.0 {
        format!("{s}")
    } else {
        format!("1/{}", (1.0 / s).round())
    }
}

/// What an axis or a readout measures, for its SI unit: lengths in R_max, times in 1/Ω,
/// speeds in μg/Ω, angular velocities in Ω (Sec. II).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    Length,
    Time,
    Speed,
    Rate,
}

/// The SI value of one dimensionless unit of `q` on the table `u`: `13.5 cm`, `303 ms`,
/// `44.6 cm/s`, `3.30 rad/s`.
pub fn unit_of(u: &Units, q: Quantity) -> String {
    match q {
        Quantity::Length => si_length(u.r_max_m()),
        Quantity::Time => si_time(u.t_s()),
        Quantity::Speed => si_speed(u.speed_m_s()),
        Quantity::Rate => si_rate(u.omega()),
    }
}

/// A table and its scales, one line: `μ 0.15, 31.5 rpm, g 9.81 m/s²: R_max 13.5 cm, 1/Ω
/// 303 ms`.
pub fn table(u: &Units) -> String {
    format!(
        "μ {}, {} rpm, g {} m/s²: R_max {}, 1/Ω {}",
        sig(u.mu),
        sig(u.rpm),
        sig(u.g),
        unit_of(u, Quantity::Length),
        unit_of(u, Quantity::Time)
    )
}

/// `x` in the largest of `ladder` (factor, name) it reaches, three digits: `7.12 cm`.
fn scaled(x: f64, ladder: &[(f64, &str)]) -> String {
    let a = x.abs();
    let (f, name) = ladder
        .iter()
        .copied()
        .find(|(f, _)| a >= *f || a == 0.0 || !a.is_finite())
        .unwrap_or(ladder[ladder.len() - 1]);
    format!("{} {name}", sig(x / f))
}

/// A length in metres, short: `7.12 cm`, `1.5 m`, `820 µm`.
pub fn si_length(m: f64) -> String {
    scaled(m, &[(1.0, "m"), (1e-2, "cm"), (1e-3, "mm"), (1e-6, "µm")])
}

/// A speed in m/s, short: `1.20 m/s`, `45.0 cm/s`, `8.72 mm/s`.
pub fn si_speed(v: f64) -> String {
    scaled(v, &[(1.0, "m/s"), (1e-2, "cm/s"), (1e-3, "mm/s")])
}

/// An angular velocity in rad/s, short: `3.30 rad/s`.
pub fn si_rate(w: f64) -> String {
    format!("{} rad/s", sig(w))
}

/// A time in seconds, short: `303 ms`, `1.20 s`.
pub fn si_time(t: f64) -> String {
    scaled(t, &[(1.0, "s"), (1e-3, "ms")])
}

/// Three significant digits, no exponent below 10⁶.
fn sig(x: f64) -> String {
    if !x.is_finite() || x.abs() >= 1e6 || (x != 0.0 && x.abs() < 0.01) {
        return format!("{x:.2e}");
    }
    let d = if x.abs() >= 100.0 {
        0
    } else if x.abs() >= 10.0 {
        1
    } else {
        2
    };
    format!("{x:.d$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_read_in_pi_in_one_turn() {
        assert_eq!(angle(0.0), "0");
        assert_eq!(angle(PI), "π");
        assert_eq!(angle(0.5 * PI), "0.5π");
        // Case D as the scene holds it (3.7699…) and as the app does (−0.8π).
        assert_eq!(angle(3.7699111843077517), "1.2π");
        assert_eq!(angle(-0.8 * PI), "1.2π");
        assert_eq!(angle(0.257 * PI), "0.257π");
        // A whole turn, either way, and what rounds up to it: the direction 0.
        assert_eq!(angle(2.0 * PI), "0");
        assert_eq!(angle(-2.0 * PI), "0");
        assert_eq!(angle(-1e-12), "0");
        assert_eq!(angle(1.99996 * PI), "0");
        assert_eq!(angle(1.99994 * PI), "1.9999π");
        assert_eq!(angle(0.001), "0.0003π");
        assert_eq!(angle(-PI), "π");
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(angle(x), "—");
        }
        // Fewer digits where fewer are known, more where a report keeps them.
        assert_eq!(angle_to(0.5567, 3), "0.177π");
        assert_eq!(angle_to(1.2 * PI, 2), "1.2π");
        assert_eq!(angle_to(0.59, 12), "0.187802832848π");
        assert_eq!(angle_to(0.0, 12), "0");
    }

    #[test]
    fn angle_ticks_are_not_wrapped() {
        assert_eq!(angle_tick(0.0), "0");
        assert_eq!(angle_tick(2.0 * PI), "2π");
        assert_eq!(angle_tick(-PI), "-π");
        assert_eq!(angle_tick(1.5 * PI), "1.5π");
        assert_eq!(angle_tick(-20.0 * PI), "-20π");
    }

    #[test]
    fn rates_below_the_places_shown_keep_their_size() {
        assert_eq!(rate(0.61234, 4), "0.6123");
        assert_eq!(rate(0.0, 4), "0.0000");
        // Below half the last place shown: exponent form, never a row of zeros beside
        // "slipping".
        assert_eq!(rate(4.9e-5, 4), "4.9e-5");
        assert_eq!(rate(-3.2e-12, 4), "-3.2e-12");
        assert_eq!(rate(5e-5, 4), "0.0001");
        assert_eq!(rate(f64::NAN, 4), "—");
    }

    #[test]
    fn sizes_keep_three_digits_at_any_scale() {
        assert_eq!(ratio(0.1), "0.1000");
        assert_eq!(ratio(0.0), "0.0000");
        assert_eq!(ratio(1e-9), "1.00e-9");
        assert_eq!(ratio(3.3e-4), "3.30e-4");
        assert_eq!(ratio(2.5e4), "2.50e4");
        assert_eq!(ratio(f64::INFINITY), "—");
        assert_eq!(sci(1.06e-3, 1), "1.1e-3");
        assert_eq!(sci(f64::NAN, 1), "—");
    }

    #[test]
    fn the_paper_s_table_in_si() {
        // μ = 0.15 at Ω = 3.3 rad/s (31.5 rpm): R_max = 0.135 m, 1/Ω = 0.303 s.
        let u = Units::paper();
        assert_eq!(si_length(u.r_max_m()), "13.5 cm");
        assert_eq!(si_time(u.t_s()), "303 ms");
        assert_eq!(si_length(2.5), "2.50 m");
        assert_eq!(unit_of(&u, Quantity::Length), "13.5 cm");
        assert_eq!(unit_of(&u, Quantity::Time), "303 ms");
        assert_eq!(unit_of(&u, Quantity::Speed), "44.6 cm/s");
        assert_eq!(unit_of(&u, Quantity::Rate), "3.30 rad/s");
        assert_eq!(si_speed(0.00872), "8.72 mm/s");
        assert_eq!(si_speed(1.2), "1.20 m/s");
        assert_eq!(
            table(&u),
            "μ 0.15, 31.5 rpm, g 9.81 m/s²: R_max 13.5 cm, 1/Ω 303 ms"
        );
    }
}
