//! README's generated parts: the picture is what `replay` prints for `docs/snapshot.keys`, the
//! key table is the keymap's, and the example key script replays as pasted.

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
        read("README.md").contains(&table),
        "README's key table should be:\n{table}"
    );
}

/// The example under "Key scripts", as a reader would paste it (comments after `#`).
#[test]
fn readme_example_script_replays() {
    let readme = read("README.md");
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
