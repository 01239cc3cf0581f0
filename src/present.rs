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
