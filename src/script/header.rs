//! A script's own options, in `# replay:` lines: read here, and written here for a recording.

use crate::error::Error;

/// `WxH`, each at most the scripts' own limit.
pub fn parse_size(s: &str) -> Result<(u16, u16), Error> {
    let bad = || Error::invalid(format!("bad size '{s}': expected WxH, e.g. 80x24"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let n = |t: &str| -> Result<u16, Error> {
        if t.is_empty() || !t.bytes().all(|b| b.is_ascii_digit()) {
            return Err(bad());
        }
        match t.parse::<u16>() {
            Ok(v) if v <= crate::script::MAX_SIZE => Ok(v),
            _ => Err(Error::invalid(format!(
                "size {t} out of range 0..={}",
                crate::script::MAX_SIZE
            ))),
        }
    };
    Ok((n(w)?, n(h)?))
}

/// What a script asks for itself, in `# replay: [--size WxH] [--ansi] [--scene S] [--theme T]`
/// comment lines (a recording names its scene this way); command-line flags take precedence.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ScriptOptions {
    pub size: Option<(u16, u16)>,
    pub ansi: bool,
    pub scene: Option<String>,
    pub theme: Option<String>,
}

pub fn script_options(text: &str) -> Result<ScriptOptions, Error> {
    let mut o = ScriptOptions::default();
    for (n, line) in text.lines().enumerate() {
        let Some(args) = line.trim_start().strip_prefix("# replay:") else {
            continue;
        };
        let at = format!("line {}", n + 1);
        let words = split_words(args).map_err(|e| Error::invalid(format!("{at}: {e}")))?;
        let mut it = words.iter().map(String::as_str);
        while let Some(a) = it.next() {
            let mut value = || {
                it.next()
                    .ok_or_else(|| Error::invalid(format!("{at}: {a} needs a value")))
            };
            match a {
                "--ansi" => o.ansi = true,
                "--size" => o.size = Some(parse_size(value()?).map_err(|e| e.context(&at))?),
                "--scene" => o.scene = Some(value()?.to_string()),
                "--theme" => o.theme = Some(value()?.to_string()),
                other => {
                    return Err(Error::invalid(format!(
                        "{at}: unknown replay option '{other}'"
                    )));
                }
            }
        }
    }
    Ok(o)
}

/// Splits a `# replay:` line into words: blanks separate them, and a word in double quotes
/// may hold blanks (`\\` and `\"` inside quotes stand for `\` and `"`).
fn split_words(line: &str) -> Result<Vec<String>, String> {
    let mut words = Vec::new();
    let mut chars = line.chars().peekable();
    while let Some(&c) = chars.peek() {
        if c.is_whitespace() {
            chars.next();
            continue;
        }
        let mut w = String::new();
        if c == '"' {
            chars.next();
            loop {
                match chars.next() {
                    Some('"') => break,
                    Some('\\') => w.push(chars.next().ok_or("unterminated quote")?),
                    Some(c) => w.push(c),
                    None => return Err("unterminated quote".into()),
                }
            }
        } else {
            while let Some(&c) = chars.peek() {
                if c.is_whitespace() {
                    break;
                }
                w.push(c);
                chars.next();
            }
        }
        words.push(w);
    }
    Ok(words)
}

/// A word as `split_words` reads it back: quoted if it holds blanks, quotes or backslashes.
pub fn quote_word(w: &str) -> String {
    if !w.is_empty() && !w.contains(|c: char| c.is_whitespace() || c == '"' || c == '\\') {
        return w.to_string();
    }
    let mut q = String::from('"');
    for c in w.chars() {
        if c == '"' || c == '\\' {
            q.push('\\');
        }
        q.push(c);
    }
    q.push('"');
    q
}

/// The `# replay: --scene S` line a recording names its scene with (quoted if need be).
pub fn scene_line(scene: &str) -> String {
    format!("# replay: --scene {}\n", quote_word(scene))
}
