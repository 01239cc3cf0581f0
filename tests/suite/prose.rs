//! The docs read in short paragraphs (issue 46 item 2): no paragraph of README.md,
//! ARCHITECTURE.md or docs/*.md runs over 200 words. A paragraph is text between blank lines;
//! fenced code, indented code and tables are not prose and are skipped; each list item counts
//! on its own.

const MOST_WORDS: usize = 200;

/// A line that starts a list item: `- `, `* `, `+ ` or `12. ` after any indent.
fn starts_item(line: &str) -> bool {
    let t = line.trim_start();
    if ["- ", "* ", "+ "].iter().any(|m| t.starts_with(m)) {
        return true;
    }
    let digits = t.chars().take_while(char::is_ascii_digit).count();
    digits > 0 && (t[digits..].starts_with(". ") || t[digits..].starts_with(") "))
}

/// The prose blocks of a markdown text, each with the line it starts on and its word count. A
/// block that opens indented by four spaces (not a list item) is indented code.
fn blocks(text: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut fenced = false;
    let mut code = false;
    let mut current: Option<(usize, usize)> = None;
    let mut at_start = true;
    for (n, line) in text.lines().enumerate() {
        let t = line.trim_start();
        let fence = t.starts_with("```") || t.starts_with("~~~");
        let blank = t.is_empty();
        if fence || fenced || blank || t.starts_with('|') || t.starts_with('#') {
            fenced ^= fence;
            out.extend(current.take());
            code = false;
            at_start = true;
            continue;
        }
        if at_start {
            code = line.starts_with("    ") && !starts_item(line);
            at_start = false;
        }
        if code {
            continue;
        }
        let mut words = line.split_whitespace().count();
        if starts_item(line) {
            out.extend(current.take());
            words -= 1;
        }
        match current.as_mut() {
            Some((_, w)) => *w += words,
            None => current = Some((n + 1, words)),
        }
    }
    out.extend(current);
    out
}

#[test]
fn no_paragraph_of_the_docs_runs_over_200_words() {
    let mut walls = Vec::new();
    let mut counted = 0;
    for page in crate::common::doc_pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        let name = page.file_name().unwrap().to_string_lossy().into_owned();
        for (line, words) in blocks(&text) {
            counted += 1;
            if words > MOST_WORDS {
                walls.push(format!("{name}:{line}: {words} words"));
            }
        }
    }
    assert!(counted > 100, "only {counted} paragraphs found");
    assert!(
        walls.is_empty(),
        "{} paragraphs over {MOST_WORDS} words (split them under headings or into lists):\n{}",
        walls.len(),
        walls.join("\n")
    );
}

#[test]
fn the_count_skips_code_and_tables_and_splits_lists() {
    let long = "word ".repeat(150);
    let text = format!(
        "{long}\n{long}\n\n```\n{long}\n{long}\n```\n\n| {long} |\n| {long} |\n\n- {long}\n- {long}\n  {}\n\n    {long}\n    {long}\n",
        "w ".repeat(10)
    );
    assert_eq!(
        blocks(&text).iter().map(|&(_, w)| w).collect::<Vec<_>>(),
        vec![300, 150, 160]
    );
}
