//! README's generated parts: the picture is what `replay` prints for `docs/snapshot.keys`, the
//! key table (docs/keys.md) is the keymap's, and the example key script (docs/key-scripts.md)
//! replays as pasted; the README stays a front page.

use std::path::Path;
use turntable::app::KEYMAP;
use turntable::cli::replay::{ReplayArgs, prepare};
use turntable::replay::replay;

fn read(path: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap()
}

fn run_script(script: &str) -> String {
    let Ok((app, opts, steps)) = prepare(script, &ReplayArgs::default()) else {
        panic!("script does not prepare:\n{script}")
    };
    replay(app, &steps, &opts)
}

/// The key table README shows: one row per (group, help text), keys in keymap order.
fn key_table() -> String {
    let mut rows: Vec<(&str, &str, Vec<String>)> = Vec::new();
    for b in KEYMAP {
        let key = format!("`{}`", b.chord);
        match rows
            .iter_mut()
            .find(|(g, h, _)| *g == b.group && *h == b.help)
        {
            Some(row) => row.2.push(key),
            None => rows.push((b.group, b.help, vec![key])),
        }
    }
    let mut out = String::from("| keys | does | group |\n| --- | --- | --- |\n");
    for (group, help, keys) in rows {
        let help = help.replace('|', "\\|");
        out.push_str(&format!("| {} | {help} | {group} |\n", keys.join(" ")));
    }
    out
}

#[test]
fn the_picture_is_what_replay_prints() {
    let expected = read("docs/snapshot.txt");
    assert_eq!(run_script(&read("docs/snapshot.keys")), expected);
    let readme = read("README.md");
    let body: String = expected
        .lines()
        .skip(1)
        .map(|l| format!("    {l}\n"))
        .collect();
    assert!(
        readme.contains(&body),
        "README's picture is not docs/snapshot.txt"
    );
}

#[test]
fn readme_lists_every_key_of_the_keymap() {
    let table = key_table();
    assert!(
        read("docs/keys.md").contains(&table),
        "docs/keys.md's key table should be:\n{table}"
    );
}

/// The example under "Key scripts", as a reader would paste it (comments after `#`).
#[test]
fn readme_example_script_replays() {
    let readme = read("docs/key-scripts.md");
    let section = readme.split("## Key scripts").nth(1).unwrap();
    let script: String = section
        .lines()
        .skip_while(|l| !l.starts_with("    "))
        .take_while(|l| l.starts_with("    "))
        .map(|l| format!("{}\n", &l[4..]))
        .collect();
    assert!(script.contains("resize 80x24"), "{script}");
    let out = run_script(&script);
    assert!(
        out.starts_with("--- snapshot 1: after 80 ticks (80x24"),
        "{out}"
    );
}

/// Runs the binary with `args` (its output paths among them), replacing what is there.
fn make(args: &[&std::ffi::OsStr]) {
    // From the repository's root, so that a path in an argument (the cast's title names its
    // script) reads the same in every clone.
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_turntable"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .arg("--force")
        .stdout(std::process::Stdio::null())
        .status()
        .unwrap();
    assert!(status.success(), "{args:?}");
}

/// Issue 32 item 2: README's moving picture (`docs/demo.cast`, recorded by the tool from
/// `docs/demo.keys`) and its Fig. 5 (`docs/fig5.svg`) are what the tool makes today, so they
/// never go stale. `UPDATE_GOLDENS=1` writes them again. One replay records the cast and the
/// SVG (the same frames, each file byte for byte what the flag alone writes), not two.
#[test]
fn the_docs_pictures_are_what_the_tool_makes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = tempfile::tempdir().unwrap();
    let at = |name: &str| tmp.path().join(name);
    let (cast, svg, fig5) = (at("demo.cast"), at("demo.svg"), at("fig5.svg"));
    make(&[
        "replay".as_ref(),
        "docs/demo.keys".as_ref(),
        "--asciicast".as_ref(),
        cast.as_os_str(),
        "--svg".as_ref(),
        svg.as_os_str(),
    ]);
    make(&[
        "plot".as_ref(),
        "fig5".as_ref(),
        "--out".as_ref(),
        fig5.as_os_str(),
    ]);
    for name in ["demo.cast", "demo.svg", "fig5.svg"] {
        let made = std::fs::read(at(name)).unwrap();
        let kept = root.join("docs").join(name);
        if std::env::var_os("UPDATE_GOLDENS").is_some() {
            std::fs::write(&kept, &made).unwrap();
        }
        assert!(
            std::fs::read(&kept).unwrap() == made,
            "docs/{name} is stale: UPDATE_GOLDENS=1 cargo test --release --test suite readme::"
        );
    }
    let readme = read("README.md");
    for name in ["docs/demo.cast", "docs/demo.svg", "docs/fig5.svg"] {
        assert!(readme.contains(name), "README does not show {name}");
    }
}

/// Issue 32 item 1: the README is a front page (at most 12 KB), every page it links to is
/// there, and every key its short table names is bound to what it says.
#[test]
fn the_readme_is_a_front_page() {
    let readme = read("README.md");
    assert!(
        readme.len() <= 12 * 1024,
        "README is {} bytes",
        readme.len()
    );
    for link in readme.split("](").skip(1) {
        let target = link.split(')').next().unwrap();
        let path = target.split('#').next().unwrap();
        assert!(
            Path::new(env!("CARGO_MANIFEST_DIR")).join(path).exists(),
            "README links to {target}, which is not there"
        );
    }
    let table = readme.split("## The keys that matter").nth(1).unwrap();
    let keys = table.split("\n## ").next().unwrap();
    for row in keys.lines().filter(|l| l.starts_with("| `")) {
        for key in row.split('|').nth(1).unwrap().split('`').skip(1).step_by(2) {
            let named = |k: &str| {
                KEYMAP
                    .iter()
                    .any(|b| b.chord.to_string() == k || b.chord.key_label() == k)
            };
            let bound = named(key) || named(&key.to_lowercase());
            assert!(bound, "README names key {key}, which is not bound");
        }
    }
    // The Tab row names the pages in the order Tab turns them.
    let tab = keys.lines().find(|l| l.starts_with("| `Tab`")).unwrap();
    let mut page = turntable::app::pages::Page::Turntable.next();
    let mut at = 0;
    while page != turntable::app::pages::Page::Turntable {
        let found = tab[at..].find(page.title());
        assert!(
            found.is_some(),
            "README's Tab row: {} not after {at}: {tab}",
            page.title()
        );
        at += found.unwrap();
        page = page.next();
    }
    for page in [
        "docs/keys.md",
        "docs/command-line.md",
        "docs/key-scripts.md",
        "docs/serve.md",
    ] {
        assert!(readme.contains(page), "README does not point to {page}");
    }
}

/// GitHub's anchor for a heading: lower case, letters, digits, `-` and `_` kept, spaces to `-`.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The anchors a markdown file offers: its headings' slugs and its explicit `id`s.
fn anchors(text: &str) -> Vec<String> {
    let mut out: Vec<String> = text
        .lines()
        .filter(|l| l.starts_with('#'))
        .map(|l| slug(l.trim_start_matches('#')))
        .collect();
    out.extend(
        text.split("<a id=\"")
            .skip(1)
            .filter_map(|s| s.split('"').next())
            .map(String::from),
    );
    out
}

/// Every relative link in the README and the docs reaches a file that is there, and a `#part`
/// a heading or an `id` of it (a link into another page broke when its heading became a
/// bullet).
#[test]
fn every_link_in_the_docs_leads_somewhere() {
    let pages = crate::common::doc_pages();
    let mut seen = 0;
    for page in &pages {
        let text = std::fs::read_to_string(page).unwrap();
        for link in text.split("](").skip(1) {
            let target = link.split(')').next().unwrap();
            if target.contains("://") || target.starts_with("mailto:") || target.contains(' ') {
                continue;
            }
            let (file, part) = target.split_once('#').unwrap_or((target, ""));
            let dest = if file.is_empty() {
                page.clone()
            } else {
                page.parent().unwrap().join(file)
            };
            assert!(dest.exists(), "{}: {target} is not there", page.display());
            if !part.is_empty() && dest.extension().is_some_and(|x| x == "md") {
                let have = anchors(&std::fs::read_to_string(&dest).unwrap());
                assert!(
                    have.iter().any(|a| a == part),
                    "{}: {target}: no heading or id #{part} in {}",
                    page.display(),
                    dest.display()
                );
            }
            seen += 1;
        }
    }
    assert!(seen > 20, "{seen} links");
}
