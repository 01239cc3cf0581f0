//! The invariants of ARCHITECTURE.md that a grep can hold: the rooms depend one way down the
//! layers (the engine on nothing else), no clock outside the terminal loop and the bench, no
//! `unsafe` at all, files written only through `files`, rooms of a size a person can hold. Each
//! reads the sources' code.

use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`, whole.
fn all_sources(dir: &Path) -> Vec<(PathBuf, String)> {
    let mut out = vec![];
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            out.extend(all_sources(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(&path).unwrap();
            out.push((path, text));
        }
    }
    out
}

/// Every `.rs` file under `dir`, with its text up to its `#[cfg(test)]` module.
fn sources(dir: &Path) -> Vec<(PathBuf, String)> {
    all_sources(dir)
        .into_iter()
        .map(|(path, text)| {
            let code = text.split("#[cfg(test)]").next().unwrap_or("").to_string();
            (path, code)
        })
        .collect()
}

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Lines of code (comments dropped) in files not under `allowed` that contain `needle`.
fn offenders(needle: &str, allowed: &[&str]) -> Vec<String> {
    let root = src();
    let mut found = vec![];
    for (path, code) in sources(&root) {
        let rel = path
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if allowed.iter().any(|a| rel.starts_with(a)) {
            continue;
        }
        for (n, line) in code.lines().enumerate() {
            let line = line.split("//").next().unwrap_or("");
            if line.contains(needle) {
                found.push(format!("src/{rel}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    found
}

/// The string literals in Rust source `code` (comments and char literals skipped), raw or not,
/// as written between their quotes.
fn string_literals(code: &str) -> Vec<String> {
    let c: Vec<char> = code.chars().collect();
    let mut out = vec![];
    let mut i = 0;
    while i < c.len() {
        match c[i] {
            '/' if c.get(i + 1) == Some(&'/') => {
                while i < c.len() && c[i] != '\n' {
                    i += 1;
                }
            }
            '/' if c.get(i + 1) == Some(&'*') => {
                i += 2;
                while i + 1 < c.len() && !(c[i] == '*' && c[i + 1] == '/') {
                    i += 1;
                }
                i += 2;
            }
            // A char literal ('"', '\'', 'x'); else a lifetime.
            '\'' if c.get(i + 1) == Some(&'\\') => {
                i += 2;
                while i < c.len() && c[i] != '\'' {
                    i += 1;
                }
                i += 1;
            }
            '\'' if c.get(i + 2) == Some(&'\'') => i += 3,
            'r' if (i == 0 || !(c[i - 1].is_alphanumeric() || c[i - 1] == '_'))
                && matches!(c.get(i + 1), Some('"' | '#')) =>
            {
                let mut j = i + 1;
                while c.get(j) == Some(&'#') {
                    j += 1;
                }
                if c.get(j) != Some(&'"') {
                    i += 1;
                    continue;
                }
                let hashes = j - i - 1;
                let start = j + 1;
                let mut k = start;
                while k < c.len()
                    && !(c[k] == '"' && (1..=hashes).all(|h| c.get(k + h) == Some(&'#')))
                {
                    k += 1;
                }
                out.push(c[start..k.min(c.len())].iter().collect());
                i = k + 1 + hashes;
            }
            '"' => {
                let start = i + 1;
                let mut k = start;
                while k < c.len() && c[k] != '"' {
                    k += if c[k] == '\\' { 2 } else { 1 };
                }
                out.push(c[start..k.min(c.len())].iter().collect());
                i = k + 1;
            }
            _ => i += 1,
        }
    }
    out
}

/// The engine knows values by what they are (`Field`), never by a command-line flag: no
/// string in it (its tests' too) holds `--name` or `--{name}`; the CLI names the flag.
#[test]
fn the_engine_names_no_flag() {
    let flag = |s: &str| {
        s.match_indices("--").any(|(at, _)| {
            s[at + 2..]
                .chars()
                .next()
                .is_some_and(|ch| ch.is_ascii_lowercase() || ch == '{')
        })
    };
    assert!(flag("raise --max-steps") && flag("--{name}") && !flag("a -- b"));
    let found = string_literals("let a = '\"'; // \"--x\"\n f(r#\"--y\"#, \"b\\\"--z\", 'a')");
    assert_eq!(found, ["--y", "b\\\"--z"]);
    let mut bad = vec![];
    let root = src().join("engine");
    let mut files = vec![];
    let mut dirs = vec![root];
    while let Some(d) = dirs.pop() {
        for entry in std::fs::read_dir(d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    assert!(files.len() > 10, "{files:?}");
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        for s in string_literals(&text).into_iter().filter(|s| flag(s)) {
            bad.push(format!("{}: {s:?}", path.display()));
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// Time advances by ticks inside the model, so the same keys give the same screens: the wall
/// clock is read by the terminal loop and serve's sessions (frame pacing, ticks, limits) and
/// the bench (timings) only.
#[test]
fn no_clock_outside_the_terminal_and_the_bench() {
    for clock in ["Instant", "SystemTime"] {
        let bad = offenders(clock, &["terminal", "serve", "bench/"]);
        assert!(bad.is_empty(), "{}", bad.join("\n"));
    }
}

/// System calls go through safe wrappers (rustix, signal-hook): no `unsafe` anywhere.
#[test]
fn no_unsafe_code() {
    let bad = offenders("unsafe", &[]);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// Files are written atomically, through `files` (a temporary file renamed into place).
#[test]
fn files_are_written_only_through_files() {
    for call in ["fs::write", "File::create", "fs::rename", "OpenOptions"] {
        let bad = offenders(call, &["files/"]);
        assert!(bad.is_empty(), "{}", bad.join("\n"));
    }
}

/// The UI draws what the state holds: it never integrates, solves or checks a run.
#[test]
fn the_ui_never_integrates() {
    let root = src();
    let mut bad = vec![];
    for (path, code) in sources(&root.join("ui")) {
        for call in [
            "Run::new",
            "RodTrack::from_run",
            ".step(",
            "engine::solve",
            "engine::doubt",
            "par_map",
        ] {
            if code.contains(call) {
                bad.push(format!("{}: {call}", path.display()));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// `update` is a pure state machine: the model (`app/`) asks the view nothing (the shell tells
/// it sizes), writes no file and holds no worker; what must happen outside it returns as
/// effects that the shell (session, terminal, replay) carries out.
#[test]
fn the_model_asks_nothing_of_the_view_or_the_world() {
    let mut bad = vec![];
    for (path, code) in sources(&src().join("app")) {
        for line in code.lines() {
            let code = line.split("//").next().unwrap_or("");
            for needle in [
                "crate::ui",
                "crate::files",
                "crate::session",
                "crate::terminal",
                "crate::replay",
                "Analysis",
                "save_new",
                "std::fs",
                "std::thread",
            ] {
                if code.contains(needle) {
                    bad.push(format!("{}: {}", path.display(), line.trim()));
                }
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// A run is advanced only by `Run::step` and read through its accessors: its fields are
/// private, so no caller can set a status or an escape of its own.
#[test]
fn runs_fields_are_private() {
    let text = std::fs::read_to_string(src().join("engine/run/mod.rs")).unwrap();
    let body = text
        .split("pub struct Run {")
        .nth(1)
        .and_then(|rest| rest.split("\n}").next())
        .unwrap();
    let fields: Vec<&str> = body
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("//"))
        .collect();
    assert!(fields.len() >= 8, "{fields:?}");
    let public: Vec<_> = fields.iter().filter(|l| l.starts_with("pub")).collect();
    assert!(public.is_empty(), "{public:?}");
}

/// The top level stays small: the project's own files, and nothing a test or a session left
/// behind (a random-key test once wrote 400 scene and SVG files there, and they were committed).
#[test]
fn the_top_level_holds_only_the_project_s_files() {
    const ALLOWED: [&str; 16] = [
        "Cargo.toml",
        "Cargo.lock",
        "src",
        "tests",
        "themes",
        "docs",
        "README.md",
        "CHANGELOG.md",
        "ARCHITECTURE.md",
        "LICENSE-MIT",
        "LICENSE-APACHE",
        ".ci",
        ".git",
        ".gitignore",
        "target",
        ".cargo",
    ];
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let stray: Vec<String> = std::fs::read_dir(root)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !ALLOWED.contains(&n.as_str()))
        .collect();
    assert!(stray.is_empty(), "not the project's: {stray:?}");
}

/// The layers of ARCHITECTURE.md as data, top to bottom: a room (a folder or file under `src/`)
/// may use rooms below its own layer, and rooms of its own layer without a cycle.
const LAYERS: &[&[&str]] = &[
    &["lib", "main", "cli", "bench"],
    &[
        "session",
        "terminal",
        "serve",
        "replay",
        "script",
        "lesson",
        "asciicast",
    ],
    // A replay's screens as an animated SVG (for the asciicast's recorder).
    &["ui", "film"],
    &["plot", "theme"],
    &["app"],
    // A scene: what a file or preset holds, read and written (the page it opens on, its pace).
    &["scene"],
    &["analysis"],
    &["sim", "pin"],
    // Numbers for people (`present`) need only the engine's types they say (a table's units, a
    // method's accuracy): the model's notices, the figures, the view and the CLI share them.
    &["check", "error", "files", "kept", "text", "rng", "present"],
    &["engine"],
];

/// Which room `rel` (a path under src/) is in.
fn room(rel: &str) -> String {
    rel.split('/')
        .next()
        .unwrap_or(rel)
        .trim_end_matches(".rs")
        .to_string()
}

/// How deep a file's module is below the crate's root (`lib.rs` 0, `app/mod.rs` 1,
/// `app/update/time.rs` 3): how many `super`s climb out of it.
fn module_depth(rel: &str) -> usize {
    let parts: Vec<&str> = rel.split('/').collect();
    let last = parts.last().copied().unwrap_or("");
    let own = usize::from(!matches!(last, "mod.rs" | "lib.rs" | "main.rs"));
    parts.len() - 1 + own
}

/// The rooms a file's code names, read by parsing it (`syn`): `use` trees, grouped or not
/// (`use crate::{ui, app::App}`), paths in code, `super::` chains that climb to the crate's
/// root, and `crate::` paths in macros' tokens; items under `#[cfg(test)]` left out.
struct Uses {
    depth: usize,
    rooms: std::collections::BTreeSet<String>,
}

impl Uses {
    fn of(code: &str, depth: usize) -> std::collections::BTreeSet<String> {
        let file = syn::parse_file(code).unwrap_or_else(|e| panic!("{e}"));
        let mut uses = Uses {
            depth,
            rooms: Default::default(),
        };
        syn::visit::Visit::visit_file(&mut uses, &file);
        uses.rooms
    }

    /// A path's room, if it leaves the module for the crate's root.
    fn path(&mut self, segments: &[String]) {
        let room = match segments.first().map(String::as_str) {
            Some("crate") => segments.get(1),
            Some("super") => {
                let climbs = segments.iter().take_while(|s| *s == "super").count();
                if climbs < self.depth {
                    return;
                }
                segments.get(climbs)
            }
            _ => return,
        };
        if let Some(room) = room {
            self.rooms.insert(room.clone());
        }
    }

    fn tree(&mut self, prefix: &mut Vec<String>, tree: &syn::UseTree) {
        match tree {
            syn::UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                self.tree(prefix, &p.tree);
                prefix.pop();
            }
            syn::UseTree::Name(n) => self.leaf(prefix, n.ident.to_string()),
            syn::UseTree::Rename(r) => self.leaf(prefix, r.ident.to_string()),
            syn::UseTree::Glob(_) => self.path(prefix),
            syn::UseTree::Group(g) => {
                for t in &g.items {
                    self.tree(prefix, t);
                }
            }
        }
    }

    fn leaf(&mut self, prefix: &[String], name: String) {
        let mut whole = prefix.to_vec();
        whole.push(name);
        self.path(&whole);
    }

    fn tokens(&mut self, tokens: proc_macro2::TokenStream) {
        let tokens: Vec<_> = tokens.into_iter().collect();
        for (i, t) in tokens.iter().enumerate() {
            match t {
                proc_macro2::TokenTree::Group(g) => self.tokens(g.stream()),
                proc_macro2::TokenTree::Ident(id) if id == "crate" => {
                    let colons = tokens[i + 1..].iter().take(2).all(
                        |t| matches!(t, proc_macro2::TokenTree::Punct(p) if p.as_char() == ':'),
                    );
                    if let (true, Some(proc_macro2::TokenTree::Ident(room))) =
                        (colons, tokens.get(i + 3))
                    {
                        self.rooms.insert(room.to_string());
                    }
                }
                _ => {}
            }
        }
    }
}

fn cfg_test(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("cfg")
            && a.meta.require_list().is_ok_and(|l| {
                l.tokens
                    .to_string()
                    .split(|c: char| !c.is_alphanumeric())
                    .any(|w| w == "test")
            })
    })
}

impl<'a> syn::visit::Visit<'a> for Uses {
    fn visit_item(&mut self, item: &'a syn::Item) {
        let attrs = match item {
            syn::Item::Mod(i) => &i.attrs,
            syn::Item::Fn(i) => &i.attrs,
            syn::Item::Impl(i) => &i.attrs,
            syn::Item::Use(i) => &i.attrs,
            syn::Item::Const(i) => &i.attrs,
            syn::Item::Static(i) => &i.attrs,
            syn::Item::Struct(i) => &i.attrs,
            syn::Item::Enum(i) => &i.attrs,
            syn::Item::Macro(i) => &i.attrs,
            _ => return syn::visit::visit_item(self, item),
        };
        if cfg_test(attrs) {
            return;
        }
        if let syn::Item::Mod(m) = item {
            self.depth += 1;
            syn::visit::visit_item_mod(self, m);
            self.depth -= 1;
            return;
        }
        syn::visit::visit_item(self, item);
    }

    fn visit_item_use(&mut self, u: &'a syn::ItemUse) {
        self.tree(&mut vec![], &u.tree);
    }

    fn visit_path(&mut self, p: &'a syn::Path) {
        let segments: Vec<String> = p.segments.iter().map(|s| s.ident.to_string()).collect();
        self.path(&segments);
        syn::visit::visit_path(self, p);
    }

    fn visit_macro(&mut self, m: &'a syn::Macro) {
        self.tokens(m.tokens.clone());
        syn::visit::visit_macro(self, m);
    }
}

/// The checker sees every form a use can take (a `crate::X` grep once missed
/// `use crate::{ui};` in the engine).
#[test]
fn the_import_graph_sees_every_form_of_use() {
    let rooms = |code: &str, depth| Uses::of(code, depth).into_iter().collect::<Vec<_>>();
    assert_eq!(rooms("use crate::{ui};", 1), ["ui"]);
    assert_eq!(
        rooms("use crate::{app::{App, view}, plot::*, ui as u};", 1),
        ["app", "plot", "ui"]
    );
    assert_eq!(rooms("fn f() { crate::sim::go(); }", 1), ["sim"]);
    assert_eq!(
        rooms(
            "fn f() { let _ = format!(\"{}\", crate::present::num(1.0)); }",
            1
        ),
        ["present"]
    );
    // Two `super`s from app/update/time.rs climb to app: inside the room.
    assert_eq!(rooms("use super::super::view;", 3), Vec::<String>::new());
    // Three climb to the root.
    assert_eq!(rooms("use super::super::super::ui::draw;", 3), ["ui"]);
    assert_eq!(rooms("use super::files;", 1), ["files"]);
    assert_eq!(
        rooms("#[cfg(test)]\nmod tests { use crate::ui; }", 1),
        Vec::<String>::new()
    );
    assert_eq!(
        rooms("#[cfg(all(test, unix))]\nfn t() { crate::ui::x(); }", 1),
        Vec::<String>::new()
    );
}

/// Every room's uses of other rooms in the main crate (the engine is a crate of its own: the
/// compiler holds that it uses nothing of this one).
fn import_graph() -> std::collections::BTreeMap<String, std::collections::BTreeSet<String>> {
    let root = src();
    let mut graph: std::collections::BTreeMap<String, std::collections::BTreeSet<String>> =
        Default::default();
    for (path, code) in all_sources(&root) {
        let rel = path
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let from = room(&rel);
        if from == "engine" {
            continue;
        }
        let uses = graph.entry(from.clone()).or_default();
        for to in Uses::of(&code, module_depth(&rel)) {
            if to != from {
                uses.insert(to);
            }
        }
    }
    graph
}

/// Whether `from` reaches `to` along the graph's uses.
fn reaches(
    graph: &std::collections::BTreeMap<String, std::collections::BTreeSet<String>>,
    from: &str,
    to: &str,
) -> bool {
    let mut seen = std::collections::BTreeSet::new();
    let mut stack = vec![from.to_string()];
    while let Some(r) = stack.pop() {
        if r == to {
            return true;
        }
        if seen.insert(r.clone()) {
            stack.extend(graph.get(&r).into_iter().flatten().cloned());
        }
    }
    false
}

fn layer(room: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&room))
}

/// The import graph between rooms, printed (`cargo test --release --test suite
/// architecture::the_rooms_depend_one_way -- --nocapture`), checked against `LAYERS`: every use
/// goes down a layer or stays in one without a cycle.
#[test]
fn the_rooms_depend_one_way() {
    let graph = import_graph();
    let mut bad = vec![];
    for (from, uses) in &graph {
        let Some(lf) = layer(from) else {
            bad.push(format!("{from}: in no layer of LAYERS"));
            continue;
        };
        eprintln!(
            "{from:>10} (layer {lf}) -> {}",
            uses.iter().cloned().collect::<Vec<_>>().join(", ")
        );
        for to in uses {
            let Some(lt) = layer(to) else {
                bad.push(format!("{to}: in no layer of LAYERS"));
                continue;
            };
            if lt < lf || reaches(&graph, to, from) {
                bad.push(format!("{from} (layer {lf}) uses {to} (layer {lt})"));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// Most lines in a source file, not counting its `#[cfg(test)] mod tests` block.
const FILE_LINES: usize = 500;
/// Most lines in a function, from its `fn` line to its closing brace.
const FN_LINES: usize = 120;

/// Files still over [`FILE_LINES`], each with its count when listed: remove an entry when its
/// file is split (the test fails on an entry no longer needed).
const LONG_FILES: [&str; 0] = [];

/// Functions still over [`FN_LINES`] (`file::name`), each with its count when listed: remove
/// an entry when its function is split (the test fails on an entry no longer needed).
const LONG_FNS: [&str; 0] = [];

/// A source file's lines outside its `#[cfg(test)] mod tests { … }` block, with their
/// numbers (from 1).
fn non_test_lines(text: &str) -> Vec<(usize, &str)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let next = lines.get(i + 1).map_or("", |l| l.trim());
        if lines[i].trim() == "#[cfg(test)]" && next.starts_with("mod tests") && next.ends_with('{')
        {
            let indent = &lines[i + 1][..lines[i + 1].len() - lines[i + 1].trim_start().len()];
            let close = format!("{indent}}}");
            i += 2;
            while i < lines.len() && lines[i].trim_end() != close {
                i += 1;
            }
            i += 1;
            continue;
        }
        out.push((i + 1, lines[i]));
        i += 1;
    }
    out
}

/// The functions among `lines` (as [`non_test_lines`] gives them): name and length, from the
/// `fn` line to the closing brace at its indentation.
fn functions(lines: &[(usize, &str)]) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for (k, &(n, line)) in lines.iter().enumerate() {
        let code = line.trim_start();
        let indent = &line[..line.len() - code.len()];
        let mut rest = code;
        loop {
            let before = rest;
            for q in [
                "pub(crate) ",
                "pub(super) ",
                "pub ",
                "const ",
                "async ",
                "unsafe ",
            ] {
                rest = rest.strip_prefix(q).unwrap_or(rest);
            }
            if rest == before {
                break;
            }
        }
        let Some(sig) = rest.strip_prefix("fn ") else {
            continue;
        };
        let name: String = sig
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        // Where the signature ends: a body's `{`, or a declaration's `;`.
        let Some(open) = lines[k..]
            .iter()
            .position(|(_, l)| l.trim_end().ends_with(['{', ';', '}']))
        else {
            continue;
        };
        let head = lines[k + open].1.trim_end();
        if head.ends_with(';') {
            continue;
        }
        if head.ends_with('}') {
            out.push((name, lines[k + open].0 - n + 1));
            continue;
        }
        let close = format!("{indent}}}");
        if let Some(&(end, _)) = lines[k + open..]
            .iter()
            .find(|(_, l)| l.trim_end() == close)
        {
            out.push((name, end - n + 1));
        }
    }
    out
}

/// Rooms a person can hold in their head: no source file over [`FILE_LINES`] lines of
/// non-test code, no function over [`FN_LINES`], but those listed (each still over).
#[test]
fn files_and_functions_are_short() {
    let root = src();
    let (mut long_files, mut long_fns) = (vec![], vec![]);
    for (path, text) in all_sources(&root) {
        let rel = path
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let lines = non_test_lines(&text);
        if lines.len() > FILE_LINES {
            long_files.push((rel.clone(), lines.len()));
        }
        for (name, n) in functions(&lines) {
            if n > FN_LINES {
                long_fns.push((format!("{rel}::{name}"), n));
            }
        }
    }
    let mut bad: Vec<String> = long_files
        .iter()
        .filter(|(f, _)| !LONG_FILES.contains(&f.as_str()))
        .map(|(f, n)| format!("src/{f}: {n} lines (at most {FILE_LINES})"))
        .chain(
            long_fns
                .iter()
                .filter(|(f, _)| !LONG_FNS.contains(&f.as_str()))
                .map(|(f, n)| format!("src/{f}: {n} lines (at most {FN_LINES})")),
        )
        .collect();
    bad.extend(
        LONG_FILES
            .iter()
            .filter(|f| !long_files.iter().any(|(g, _)| g == *f))
            .map(|f| {
                format!("src/{f} is no longer over {FILE_LINES} lines: drop it from LONG_FILES")
            }),
    );
    bad.extend(
        LONG_FNS
            .iter()
            .filter(|f| !long_fns.iter().any(|(g, _)| g == *f))
            .map(|f| format!("src/{f} is no longer over {FN_LINES} lines: drop it from LONG_FNS")),
    );
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The measure itself: a test module is not counted, a function runs from `fn` to the brace
/// closing it, a declaration without a body is no function.
#[test]
fn the_length_measure_counts_what_it_says() {
    let text = "fn a() {\n    let x = 1;\n}\npub(crate) fn b(\n    x: u8,\n) -> u8 {\n    x\n}\n\
                trait T {\n    fn c(&self);\n    fn d(&self) {}\n}\n#[cfg(test)]\nmod tests {\n    fn e() {\n    }\n}\n";
    let lines = non_test_lines(text);
    assert_eq!(lines.len(), 12);
    assert_eq!(
        functions(&lines),
        vec![("a".into(), 3), ("b".into(), 5), ("d".into(), 1)]
    );
}

/// ARCHITECTURE.md's table of rooms is the import graph: each row's *uses* are what its code
/// names, no more, no less (the engine's row: its crate's dependencies), and every room has a
/// row (but the crate's roots, `lib.rs` and `main.rs`, which only name the rooms).
#[test]
fn the_architecture_table_is_the_import_graph() {
    let doc =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("ARCHITECTURE.md"))
            .unwrap();
    let names = |cell: &str| -> std::collections::BTreeSet<String> {
        cell.split(',')
            .map(|w| w.split_whitespace().next().unwrap_or("").trim_matches('`'))
            .map(|w| w.trim_end_matches('/').trim_end_matches(".rs").to_string())
            .filter(|w| !w.is_empty() && w != "—")
            .collect()
    };
    let mut rows = std::collections::BTreeMap::new();
    let table = doc
        .split("| room | holds | uses |")
        .nth(1)
        .expect("the table of rooms");
    for line in table.lines().skip(2).take_while(|l| l.starts_with('|')) {
        let cells: Vec<&str> = line.trim_matches('|').split(" | ").map(str::trim).collect();
        assert_eq!(cells.len(), 3, "{line}");
        for room in names(cells[0]) {
            rows.insert(room, names(cells[2]));
        }
    }
    let mut graph = import_graph();
    graph.remove("lib");
    graph.remove("main");
    let manifest = std::fs::read_to_string(src().join("engine/Cargo.toml")).unwrap();
    let deps = manifest
        .split("[dependencies]")
        .nth(1)
        .unwrap()
        .split("\n[")
        .next()
        .unwrap();
    graph.insert(
        "engine".into(),
        deps.lines()
            .filter_map(|l| l.split_once(" = ").map(|(k, _)| k.trim().to_string()))
            .collect(),
    );
    let mut bad = vec![];
    for (room, uses) in &graph {
        match rows.get(room) {
            Some(row) if row == uses => {}
            Some(row) => bad.push(format!(
                "{room}: the table says {row:?}, the code uses {}",
                uses.iter().cloned().collect::<Vec<_>>().join(", ")
            )),
            None => bad.push(format!("{room}: no row")),
        }
    }
    bad.extend(
        rows.keys()
            .filter(|r| !graph.contains_key(*r))
            .map(|r| format!("{r}: a row for no room")),
    );
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
