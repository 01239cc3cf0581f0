//! Text that must fit a width loses whole fields, then whole words, from its end: never a
//! digit of a number (`ξ0 = 0` for 0.500 misreads; `ξ0 = 0.500` dropped does not).

use unicode_width::UnicodeWidthStr;

use crate::present::OR;

/// `text` cut to `width` columns: its first wording that fits whole; else, of its last,
/// whole fields (separated by `sep`) from the end, then whole words of the last field kept;
/// empty when not even one word fits.
pub fn fit(text: &str, sep: &str, width: usize) -> String {
    if let Some(whole) = text.split(OR).find(|t| t.width() <= width) {
        return whole.to_string();
    }
    let text = text.rsplit(OR).next().unwrap_or_default();
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

/// A word that relates the words either side of it: a line never breaks next to it where the
/// formula fits on one (`ξ0 =` / `0.5` reads as a sentence cut short).
fn relation(word: &str) -> bool {
    matches!(
        word,
        "=" | "≈" | "<" | ">" | "≤" | "≥" | "≠" | "→" | "+" | "−" | "-" | "×" | "/" | "±"
    )
}

/// The words of `para` with each formula (words joined by a [`relation`]) kept as one, unless
/// it is wider than `width`, when its words go on their own.
fn units(para: &str, width: usize) -> Vec<String> {
    let mut formulas: Vec<Vec<&str>> = Vec::new();
    for word in para.split(' ').filter(|w| !w.is_empty()) {
        match formulas.last_mut() {
            Some(f) if relation(word) || f.last().is_some_and(|w| relation(w)) => f.push(word),
            _ => formulas.push(vec![word]),
        }
    }
    formulas
        .into_iter()
        .flat_map(|f| match f.join(" ") {
            whole if whole.width() <= width => vec![whole],
            _ => f.into_iter().map(String::from).collect(),
        })
        .collect()
}

/// `text` wrapped to `width` columns in at most `rows` lines: paragraphs at `\n`, lines
/// broken between words, never inside a formula that fits a line (see `relation`); a word
/// wider than the line is broken where it must be. When the lines are more than `rows`, the
/// last kept ends in `…`, whole words dropped to make room.
pub fn wrap(text: &str, width: usize, rows: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    if width == 0 || rows == 0 {
        return lines;
    }
    for para in text.split('\n') {
        let mut line = String::new();
        for word in units(para, width) {
            let word = word.as_str();
            let joined = if line.is_empty() {
                word.to_string()
            } else {
                format!("{line} {word}")
            };
            if joined.width() <= width {
                line = joined;
                continue;
            }
            if !line.is_empty() {
                lines.push(std::mem::take(&mut line));
            }
            // A word wider than the line: broken by characters, as it must be.
            for c in word.chars() {
                if !line.is_empty() && (line.clone() + &c.to_string()).width() > width {
                    lines.push(std::mem::take(&mut line));
                }
                line.push(c);
            }
        }
        lines.push(line);
    }
    if lines.len() > rows {
        lines.truncate(rows);
        let last = lines.pop().unwrap_or_default();
        let mut words = units(&last, width);
        loop {
            let cut = match words.join(" ") {
                kept if kept.is_empty() => "…".to_string(),
                kept => format!("{kept} …"),
            };
            if cut.width() <= width || words.is_empty() {
                lines.push(cut);
                break;
            }
            words.pop();
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::present::alternatives;

    #[test]
    fn wrap_breaks_between_words_and_marks_what_is_left_out() {
        let t = "Friction holds it inside ξ = 1.\nBeyond, it slides.";
        assert_eq!(
            wrap(t, 16, 9),
            [
                "Friction holds",
                "it inside ξ = 1.",
                "Beyond, it",
                "slides."
            ]
        );
        assert_eq!(wrap(t, 16, 2), ["Friction holds", "it inside …"]);
        // A formula is not broken where it fits a line, and dropped whole.
        let f = "It stops at ξ = 0.9453, u = v − Ω×r.";
        assert_eq!(
            wrap(f, 16, 9),
            ["It stops at", "ξ = 0.9453,", "u = v − Ω×r."]
        );
        assert_eq!(wrap(f, 24, 9), ["It stops at ξ = 0.9453,", "u = v − Ω×r."]);
        assert_eq!(wrap(f, 20, 2), ["It stops at", "ξ = 0.9453, …"]);
        assert_eq!(wrap("a ξ0 = 0.5", 5, 9), ["a ξ0", "= 0.5"]);
        assert_eq!(wrap("abcdefgh ij", 3, 9), ["abc", "def", "gh", "ij"]);
        assert_eq!(wrap("ab", 1, 1), ["…"]);
        assert!(wrap(t, 0, 5).is_empty() && wrap(t, 5, 0).is_empty());
        for w in 1..40 {
            for l in wrap(t, w, 3) {
                assert!(l.width() <= w.max(1), "{w}: {l:?}");
            }
        }
    }

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

    #[test]
    fn the_first_wording_that_fits_is_shown_whole() {
        let t = alternatives(&[
            "c: compare with the paper's scheme (raw RK2, dt = 1e-3)",
            "c: compare with the paper's RK2",
            "c: paper's RK2",
        ]);
        assert_eq!(
            fit(&t, "\0", 80),
            "c: compare with the paper's scheme (raw RK2, dt = 1e-3)"
        );
        assert_eq!(fit(&t, "\0", 40), "c: compare with the paper's RK2");
        assert_eq!(fit(&t, "\0", 20), "c: paper's RK2");
        // None fits: the shortest loses words from its end.
        assert_eq!(fit(&t, "\0", 10), "c: paper's");
        assert_eq!(fit("one way", "\0", 7), "one way");
    }
}
