//! Numbers for people: the one formatter the readouts, notices and captions share. It needs
//! nothing of the crate, so the model's notices (`app`) and the view (`ui`) both use it.

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
