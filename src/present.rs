//! Numbers for people: the formatters the readouts, notices, captions, charts' ticks and
//! figures share. It needs nothing of the crate, so the model's notices (`app`), the charts'
//! descriptions (`plot`) and the view (`ui`) all use it.

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

/// Separates a text's wordings, longest first (see [`alternatives`]).
pub const OR: char = '\u{1f}';

/// A text said several ways, longest first: the terminal shows the first that fits whole
/// (`ui::fit`), so a narrow screen reads a shorter sentence, not a long one cut after "for" or
/// "dt ="; a figure has room for the first.
pub fn alternatives<S: AsRef<str>>(wordings: &[S]) -> String {
    let all: Vec<&str> = wordings.iter().map(AsRef::as_ref).collect();
    all.join(&OR.to_string())
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
        let s = format!("{v:.3}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
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
