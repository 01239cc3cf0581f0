//! Text that must fit a width loses whole fields, then whole words, from its end: never a
//! digit of a number (`ξ0 = 0` for 0.500 misreads; `ξ0 = 0.500` dropped does not).

use unicode_width::UnicodeWidthStr;

/// `text` cut to `width` columns: whole fields (separated by `sep`) from the end, then whole
/// words of the last field kept; empty when not even one word fits.
pub fn fit(text: &str, sep: &str, width: usize) -> String {
    if text.width() <= width {
        return text.to_string();
    }
    let mut out = String::new();
    for (i, field) in text.split(sep).enumerate() {
        let joined = if i == 0 {
            field.to_string()
        } else {
            format!("{out}{sep}{field}")
        };
        if joined.width() <= width {
            out = joined;
            continue;
        }
        if i == 0 {
            // The first field alone is too wide: as many of its words as fit.
            for (k, word) in field.split(' ').enumerate() {
                let next = if k == 0 {
                    word.to_string()
                } else {
                    format!("{out} {word}")
                };
                if next.width() > width {
                    break;
                }
                out = next;
            }
        }
        break;
    }
    out
}

/// Words that fit `width`: a parenthesis dropped whole first, then words from the end.
pub fn fit_label(label: &str, width: usize) -> String {
    if label.width() <= width {
        return label.to_string();
    }
    let bare = match (label.find(" ("), label.ends_with(')')) {
        (Some(k), true) => &label[..k],
        _ => label,
    };
    fit(bare, "\u{0}", width)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_then_words_go_whole() {
        let t = "escape speed v_e(φ), ξ0 = 0.500, 12/72 angles";
        assert_eq!(fit(t, ", ", 100), t);
        assert_eq!(fit(t, ", ", 40), "escape speed v_e(φ), ξ0 = 0.500");
        assert_eq!(fit(t, ", ", 30), "escape speed v_e(φ)");
        assert_eq!(fit(t, ", ", 15), "escape speed");
        assert_eq!(fit(t, ", ", 3), "");
        assert_eq!(fit(" c: compare with", "\0", 12), " c: compare");
        let note = "min 0.1723 at 0.17π, max 1.7559 at 1.25π";
        assert_eq!(fit(note, ", ", 30), "min 0.1723 at 0.17π");
        assert_eq!(fit("? help  q quit", "  ", 10), "? help");
        assert_eq!(
            fit_label("release sticks (in the window)", 20),
            "release sticks"
        );
        assert_eq!(fit_label("release sticks (in the window)", 10), "release");
    }
}
