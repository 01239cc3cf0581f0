//! `turntable plot`: SVG figures parsed back — well formed, labelled, and their lines mapped
//! back through the tick labels to the values docs/numerics.md gives.

use crate::common;
use crate::reference;
use common::turntable;
use std::path::PathBuf;
use turntable::app::testing::Testing as _;

mod table;

fn out(tag: &str) -> PathBuf {
    let p = std::env::temp_dir().join(format!("turntable-plot-{tag}-{}.svg", std::process::id()));
    let _ = std::fs::remove_file(&p);
    p
}

/// A tag of the document: its name, attributes, and whether it opens, closes or is empty.
#[derive(Debug)]
struct Tag {
    name: String,
    attrs: Vec<(String, String)>,
    kind: Kind,
    /// The text right after it, up to the next tag.
    text: String,
}

#[derive(Debug, PartialEq)]
enum Kind {
    Open,
    Close,
    Empty,
}

impl Tag {
    fn attr(&self, k: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(a, _)| a == k)
            .map(|(_, v)| v.as_str())
    }
    fn num(&self, k: &str) -> f64 {
        self.attr(k).unwrap().parse().unwrap()
    }
}

/// Parses the SVG as XML enough to check it: every tag closes in order, attributes are quoted,
/// text holds no bare `<` or `&`. Panics otherwise.
fn parse(svg: &str) -> Vec<Tag> {
    let body = svg
        .strip_prefix("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n")
        .expect("an XML declaration");
    let mut tags = Vec::new();
    let mut stack: Vec<String> = Vec::new();
    let mut rest = body;
    while let Some(start) = rest.find('<') {
        let text = &rest[..start];
        assert!(!text.contains('>'), "bare > in {text:?}");
        check_text(text);
        if let Some(last) = tags.last_mut() {
            let t: &mut Tag = last;
            t.text = text.to_string();
        }
        let end = rest[start..].find('>').expect("an unclosed tag") + start;
        let inner = &rest[start + 1..end];
        rest = &rest[end + 1..];
        if let Some(name) = inner.strip_prefix('/') {
            assert_eq!(stack.pop().as_deref(), Some(name), "tags out of order");
            tags.push(Tag {
                name: name.into(),
                attrs: vec![],
                kind: Kind::Close,
                text: String::new(),
            });
            continue;
        }
        let (inner, kind) = match inner.strip_suffix('/') {
            Some(i) => (i, Kind::Empty),
            None => (inner, Kind::Open),
        };
        let name: String = inner.chars().take_while(|c| !c.is_whitespace()).collect();
        let mut attrs = Vec::new();
        let mut a = inner[name.len()..].trim();
        while !a.is_empty() {
            let eq = a.find("=\"").expect("an attribute with a quoted value");
            let key = a[..eq].trim().to_string();
            let close = a[eq + 2..].find('"').expect("a closing quote") + eq + 2;
            let value = &a[eq + 2..close];
            check_text(value);
            attrs.push((key, value.to_string()));
            a = a[close + 1..].trim();
        }
        if kind == Kind::Open {
            stack.push(name.clone());
        }
        tags.push(Tag {
            name,
            attrs,
            kind,
            text: String::new(),
        });
    }
    assert!(rest.trim().is_empty(), "text after the root: {rest:?}");
    assert!(stack.is_empty(), "unclosed: {stack:?}");
    assert_eq!(tags[0].name, "svg");
    tags
}

/// Entities only as `&amp;` `&lt;` `&gt;` `&quot;`.
fn check_text(t: &str) {
    assert!(!t.contains('<'), "bare < in {t:?}");
    for (i, _) in t.match_indices('&') {
        let e = &t[i..];
        assert!(
            ["&amp;", "&lt;", "&gt;", "&quot;"]
                .iter()
                .any(|x| e.starts_with(x)),
            "bare & in {t:?}"
        );
    }
}

fn with_class<'a>(tags: &'a [Tag], class: &str) -> Vec<&'a Tag> {
    tags.iter()
        .filter(|t| t.attr("class") == Some(class))
        .collect()
}

/// The polyline's points, in SVG coordinates.
fn points(t: &Tag) -> Vec<(f64, f64)> {
    t.attr("points")
        .unwrap()
        .split(' ')
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// A tick label's value: a number, or a multiple of π on an axis of angles (`0.5π`, `π`,
/// `-π`, `2π`), in radians.
fn tick_value(text: &str) -> f64 {
    match text.strip_suffix('π') {
        Some("") => std::f64::consts::PI,
        Some("-") => -std::f64::consts::PI,
        Some(k) => k.parse::<f64>().unwrap() * std::f64::consts::PI,
        None => text.parse().unwrap(),
    }
}

/// The affine map from an SVG coordinate to data, read off two tick labels of `class`
/// (`x-tick` by their x, `y-tick` by their y), within the panel starting at tag `from`.
fn axis(tags: &[Tag], class: &str) -> impl Fn(f64) -> f64 {
    let coord = if class == "x-tick" { "x" } else { "y" };
    let ticks: Vec<(f64, f64)> = with_class(tags, class)
        .iter()
        .map(|t| (t.num(coord), tick_value(&t.text)))
        .collect();
    assert!(ticks.len() >= 2, "{class}: {ticks:?}");
    let (a, b) = (ticks[0], ticks[ticks.len() - 1]);
    move |p| a.1 + (p - a.0) * (b.1 - a.1) / (b.0 - a.0)
}

fn text_of<'a>(tags: &'a [Tag], class: &str) -> Vec<&'a str> {
    with_class(tags, class)
        .iter()
        .map(|t| t.text.as_str())
        .collect()
}

/// The one line of the series named `name`.
fn named<'a>(tags: &'a [Tag], name: &str) -> &'a Tag {
    let found: Vec<_> = with_class(tags, "series")
        .into_iter()
        .filter(|t| t.attr("data-name") == Some(name))
        .collect();
    assert_eq!(found.len(), 1, "{name}");
    found[0]
}

/// The names in the (first) legend.
fn legend(tags: &[Tag]) -> Vec<String> {
    let start = tags
        .iter()
        .position(|t| t.attr("class") == Some("legend"))
        .unwrap();
    let mut depth = 0;
    let mut names = Vec::new();
    for t in &tags[start..] {
        match (t.name.as_str(), &t.kind) {
            ("g", Kind::Open) => depth += 1,
            ("g", Kind::Close) => depth -= 1,
            ("text", Kind::Open) => names.push(t.text.clone()),
            _ => {}
        }
        if depth == 0 {
            break;
        }
    }
    names
}

#[test]
fn fig5_maps_back_to_the_escape_speed() {
    let f = out("fig5");
    let p = f.to_str().unwrap();
    let (code, stdout, err) =
        turntable(&["plot", "fig5", "--xi0", "0.5", "--points", "8", "--out", p]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.is_empty());
    let svg = std::fs::read_to_string(&f).unwrap();
    let tags = parse(&svg);
    assert_eq!(
        text_of(&tags, "x-label")[0],
        "φ, direction of the throw from radially outward (rad)"
    );
    assert_eq!(text_of(&tags, "y-label")[0], "v_e, escape speed (μg/Ω)");
    assert!(text_of(&tags, "title")[0].starts_with("Escape speed v_e(φ)"));
    assert!(
        legend(&tags).contains(&"ξ0 = 0.5".to_string()),
        "{:?}",
        legend(&tags)
    );
    let lines = with_class(&tags, "series");
    assert_eq!(lines.len(), 1);
    let pts = points(lines[0]);
    assert_eq!(pts.len(), 8);
    let (x, y) = (axis(&tags, "x-tick"), axis(&tags, "y-tick"));
    for (k, &(px, _)) in pts.iter().enumerate() {
        let phi = std::f64::consts::TAU * k as f64 / 8.0;
        assert!((x(px) - phi).abs() < 1e-5, "point {k}: φ {}", x(px));
    }
    // The sweep's bracket is 1e-6 wide.
    let v = y(pts[0].1);
    assert!((v - reference::VE_C).abs() < 2e-6, "v_e {v}");
    // The peak lies near φ ≈ 4 (the grid point 5π/4 ≈ 3.93 of eight).
    let top = pts.iter().min_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
    assert!((x(top.0) - 5.0 * std::f64::consts::PI / 4.0).abs() < 1e-5);
    std::fs::remove_file(&f).unwrap();
}

#[test]
fn fig6_marks_the_critical_radius() {
    let f = out("fig6");
    let p = f.to_str().unwrap();
    let (code, _, err) = turntable(&["plot", "fig6", "--points", "11", "--out", p]);
    assert_eq!(code, 0, "{err}");
    let tags = parse(&std::fs::read_to_string(&f).unwrap());
    assert_eq!(text_of(&tags, "x-label")[0], "ξ0, release radius (R_max)");
    assert_eq!(text_of(&tags, "y-label")[0], "ξ, final rest radius (R_max)");
    // 0, 0.1, …, 0.8 stop (the escapes at 0.9 and 1 break nothing after them).
    let lines = with_class(&tags, "series");
    assert_eq!(lines.len(), 1);
    let pts = points(lines[0]);
    assert_eq!(pts.len(), 9);
    let (x, y) = (axis(&tags, "x-tick"), axis(&tags, "y-tick"));
    assert!(y(pts[0].1).abs() < 1e-5 && x(pts[0].0).abs() < 1e-5);
    // The table drags a release at rest in the lab outward: it rests no nearer the centre.
    for &(px, py) in &pts {
        assert!(y(py) >= x(px) - 1e-4, "{} {}", x(px), y(py));
    }
    let marks = text_of(&tags, "mark-label");
    assert_eq!(marks, ["ξ0c = 0.872044"]);
    let line = with_class(&tags, "mark")[0];
    assert!((x(line.num("x1")) - reference::XI0C).abs() < 1e-5);
    std::fs::remove_file(&f).unwrap();
}

#[test]
fn the_map_has_a_cell_per_stuck_release() {
    let f = out("map");
    let p = f.to_str().unwrap();
    let args = [
        "--xi0",
        "0.5",
        "--phi-points",
        "12",
        "--v0-points",
        "10",
        "--v0-max",
        "2",
    ];
    let (code, _, err) = turntable(&[&["plot", "map"][..], &args, &["--out", p]].concat());
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&f).unwrap();
    let tags = parse(&svg);
    let (_, csv, _) = turntable(&[&["sweep", "map"][..], &args].concat());
    let stuck = csv.lines().filter(|l| l.contains(",stuck,")).count();
    let cells = with_class(&tags, "cell").len();
    assert_eq!(cells, stuck);
    assert!(stuck > 0 && stuck < 120);
    assert_eq!(
        text_of(&tags, "y-label")[0],
        "v0, speed relative to the table (μg/Ω)"
    );
    std::fs::remove_file(&f).unwrap();
}

/// Outside ξ = 1 the default speed range covers the sticking window (Fig. 3 D): some cells
/// stick, in `sweep map` and in `plot map` alike (all escaped when the range stopped at the
/// window's floor), and the window's top lies below the range's.
#[test]
fn the_default_range_outside_the_rim_shows_the_sticking_window() {
    let f = out("map-window");
    let p = f.to_str().unwrap();
    let args = ["--xi0", "1.2", "--phi-points", "12", "--v0-points", "10"];
    let (code, csv, err) = turntable(&[&["sweep", "map"][..], &args].concat());
    assert_eq!(code, 0, "{err}");
    let stuck: Vec<f64> = csv
        .lines()
        .filter(|l| l.contains(",stuck,"))
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    let v0s: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    let top = v0s.iter().copied().fold(0.0, f64::max);
    assert!(stuck.len() >= 5, "{csv}");
    assert!(stuck.iter().all(|v| *v < top), "{stuck:?} {top}");
    let (code, _, err) = turntable(&[&["plot", "map"][..], &args, &["--out", p]].concat());
    assert_eq!(code, 0, "{err}");
    let tags = parse(&std::fs::read_to_string(&f).unwrap());
    assert_eq!(with_class(&tags, "cell").len(), stuck.len());
    std::fs::remove_file(&f).unwrap();
}

#[test]
fn the_trajectory_ends_where_the_run_stops() {
    let f = out("traj");
    let p = f.to_str().unwrap();
    for frame in ["lab", "table"] {
        let (code, _, err) = turntable(&[
            "plot",
            "trajectory",
            "--scene",
            "B",
            "--frame",
            frame,
            "--out",
            p,
            "--force",
        ]);
        assert_eq!(code, 0, "{err}");
        let tags = parse(&std::fs::read_to_string(&f).unwrap());
        let (x, y) = (axis(&tags, "x-tick"), axis(&tags, "y-tick"));
        let lines = with_class(&tags, "series");
        let path = points(lines[0]);
        let (sx, sy) = path[0];
        assert!(
            (x(sx) - 0.5).abs() < 1e-5 && y(sy).abs() < 1e-5,
            "release at (0.5, 0)"
        );
        let (ex, ey) = *path.last().unwrap();
        let xi = x(ex).hypot(y(ey));
        assert!(
            (xi - reference::B_REST.0).abs() < 1e-5,
            "{frame}: rests at {xi}"
        );
        // The rim ξ = 1, drawn as a circle, maps back to radius 1.
        let rim = points(lines[1]);
        assert!(
            rim.iter()
                .all(|&(a, b)| (x(a).hypot(y(b)) - 1.0).abs() < 1e-5)
        );
        let marks = text_of(&tags, "mark-label");
        assert_eq!(marks[0], "release");
        assert!(
            marks[1].starts_with("stuck at ξ = 0.94527, τ = 2.700"),
            "{marks:?}"
        );
    }
    std::fs::remove_file(&f).unwrap();
}

/// Several runs on one slide: C converged comes to rest inside ξ = 1, C by the paper's RK2
/// (`--method rk2-raw`) steps over the stop and escapes; each release carries its initial
/// velocity as an arrow. The time plots take one run.
#[test]
fn a_trajectory_draws_several_runs_with_their_arrows() {
    let f = out("traj-several");
    let p = f.to_str().unwrap();
    let (code, _, err) = turntable(&[
        "plot",
        "trajectory",
        "--scene",
        "C",
        "--method",
        "dp54",
        "--method",
        "rk2-raw",
        "--out",
        p,
    ]);
    assert_eq!(code, 0, "{err}");
    let tags = parse(&std::fs::read_to_string(&f).unwrap());
    assert_eq!(legend(&tags), ["C (dp54)", "C (rk2-raw)", "ξ = 1 (R_max)"]);
    // Issue 46 item 6: the title names the runs; the release and its arrow, shared by both,
    // are marked once; no two labels on one spot, and each point's label inside the plot.
    assert_eq!(text_of(&tags, "title"), ["C (dp54) and C (rk2-raw)"]);
    let marks = text_of(&tags, "mark-label");
    assert_eq!(marks[0], "release");
    assert!(
        marks[1].starts_with("C (dp54): stuck at ξ = 0.997"),
        "{marks:?}"
    );
    assert!(marks[2].starts_with("C (rk2-raw): escaped"), "{marks:?}");
    assert_eq!(marks[3], "v0");
    let labels: Vec<&Tag> = tags
        .iter()
        .filter(|t| t.attr("class") == Some("mark-label"))
        .collect();
    let frame = tags
        .iter()
        .find(|t| t.attr("class") == Some("frame"))
        .unwrap();
    let (left, right) = (frame.num("x"), frame.num("x") + frame.num("width"));
    for (i, a) in labels.iter().enumerate() {
        for b in &labels[i + 1..] {
            let apart = (a.num("x") - b.num("x")).abs() + (a.num("y") - b.num("y")).abs();
            assert!(apart > 11.0, "{} on {}", a.text, b.text);
        }
        let w = turntable::plot::label_width(&a.text);
        let (from, to) = match a.attr("text-anchor") {
            Some("end") => (a.num("x") - w, a.num("x")),
            _ => (a.num("x"), a.num("x") + w),
        };
        assert!(from >= left && to <= right, "{} cut: {from}..{to}", a.text);
    }
    // C's release: ξ0 = 0.5 thrown radially at 0.6078 relative to the table, so in the lab
    // v0 = (0.6078, 0.5) (the table's Ω×r added): the arrow points along it.
    let (x, y) = (axis(&tags, "x-tick"), axis(&tags, "y-tick"));
    let arrows: Vec<&Tag> = tags
        .iter()
        .filter(|t| t.name == "line")
        .filter(|t| t.attr("x1").is_some() && t.attr("stroke").is_none())
        .collect();
    assert_eq!(arrows.len(), 1, "one arrow for the release both runs share");
    for a in arrows {
        let (x0, y0) = (x(a.num("x1")), y(a.num("y1")));
        let (dx, dy) = (x(a.num("x2")) - x0, y(a.num("y2")) - y0);
        assert!((x0 - 0.5).abs() < 1e-4 && y0.abs() < 1e-4, "{x0} {y0}");
        assert!((dy / dx - 0.5 / 0.6078).abs() < 1e-3, "{dx} {dy}");
    }
    let (code, _, err) = turntable(&[
        "plot", "time", "--scene", "C", "--scene", "B", "--out", p, "--force",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("plot time draws one run"), "{err}");
    std::fs::remove_file(&f).unwrap();
}

/// `plot time --scene fig1` frames where Sec. III A holds (τ ≲ √ξ0 ≈ 22.4 at ξ0 = 500, twice
/// that shown), with Eq. 13's ξ beside the run's: they agree early, to 1e-3 of ξ0.
#[test]
fn the_time_plots_of_fig1_frame_the_approximations_window() {
    let f = out("time-fig1");
    let p = f.to_str().unwrap();
    let (code, _, err) = turntable(&["plot", "time", "--scene", "fig1", "--out", p]);
    assert_eq!(code, 0, "{err}");
    let tags = parse(&std::fs::read_to_string(&f).unwrap());
    let xi = panels(&tags)[0];
    let (x, y) = (axis(xi, "x-tick"), axis(xi, "y-tick"));
    let frame = with_class(xi, "frame")[0];
    let right = x(frame.num("x") + frame.num("width"));
    assert!((right - 2.0 * 500f64.sqrt()).abs() < 1e-3, "{right}");
    assert!(text_of(xi, "mark-label").contains(&"approx. valid ←"));
    let dots: Vec<(f64, f64)> = xi
        .iter()
        .skip_while(|t| t.attr("data-name") != Some("Sec. III approx."))
        .take_while(|t| t.name != "g" || t.attr("data-name").is_some())
        .filter(|t| t.name == "circle")
        .map(|t| (x(t.num("cx")), y(t.num("cy"))))
        .collect();
    assert_eq!(dots.len(), 201);
    let run = points(named(xi, "ξ"));
    for &(t, v) in dots.iter().filter(|d| d.0 <= 10.0) {
        // Eq. 13, ξ = τ⁴/(12ξ0) + ξ0, against the run's line at the nearest point.
        assert!((v - (t.powi(4) / 6000.0 + 500.0)).abs() < 1e-3, "{t}: {v}");
        let near = run
            .iter()
            .map(|&(a, b)| (x(a), y(b)))
            .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
            .unwrap();
        assert!((near.1 - v).abs() < 0.5, "{t}: run {near:?}, Eq. 13 {v}");
    }
    std::fs::remove_file(&f).unwrap();
}

#[test]
fn the_time_plots_hold_four_panels() {
    let f = out("time");
    let p = f.to_str().unwrap();
    let (code, _, err) = turntable(&["plot", "time", "--scene", "A", "--out", p]);
    assert_eq!(code, 0, "{err}");
    let tags = parse(&std::fs::read_to_string(&f).unwrap());
    assert_eq!(
        text_of(&tags, "y-label"),
        ["ξ (R_max)", "θ′ (Ω)", "|u| (μg/Ω)", "(μg/Ω)²"]
    );
    assert_eq!(text_of(&tags, "x-label"), ["τ (1/Ω)"; 4]);
    assert_eq!(with_class(&tags, "series").len(), 5);
    // The stop is marked in each panel at A's stop time (docs/numerics.md: τ = 0.99688).
    assert_eq!(text_of(&tags, "mark-label"), ["stuck τ=0.997"; 4]);
    std::fs::remove_file(&f).unwrap();
}

#[test]
fn plot_keeps_files_and_refuses_what_does_not_apply() {
    let f = out("keep");
    std::fs::write(&f, "mine").unwrap();
    let p = f.to_str().unwrap();
    let (code, _, err) = turntable(&["plot", "fig6", "--points", "3", "--out", p]);
    assert_eq!(code, 2);
    assert!(err.contains("exists; --force replaces it"), "{err}");
    assert_eq!(std::fs::read_to_string(&f).unwrap(), "mine");
    let (code, _, err) = turntable(&["plot", "fig6", "--points", "3", "--out", p, "--force"]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read_to_string(&f).unwrap().starts_with("<?xml"));
    std::fs::remove_file(&f).unwrap();
    for args in [
        &["plot", "fig6", "--xi0", "0.5", "--out", p][..],
        &["plot", "time", "--frame", "table", "--out", p],
        &["plot", "fig5"],
        &["plot", "fig5", "--points", "0", "--out", p],
        &["plot", "trajectory", "--scene", "nope", "--out", p],
        &["plot", "trajectory", "--xi0", "-1", "--out", p],
        &["plot", "fig6", "--out", "/nonexistent/dir/f.svg"],
    ] {
        let (code, _, err) = turntable(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(!f.exists(), "{args:?}");
    }
}

/// The explorer's `E`: the page on screen, from what the explorer holds, to a new file each
/// time (never over one), with a notice naming it.
#[test]
fn the_explorer_writes_the_page_to_a_new_file() {
    use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
    use turntable::app::App;
    let dir = std::env::temp_dir().join(format!("turntable-export-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut app = App::new(turntable::scene::Scene::preset("B").unwrap());
    app.tell_save_path(dir.join("turntable-scene.toml"));
    let press = |app: &mut App, code| {
        let effects = app.handle_key(KeyEvent::new(code, KeyModifiers::NONE));
        turntable::session::carry_out(app, effects);
    };
    // It plays from the start: 80 ticks are τ = 4, past B's stop.
    for _ in 0..80 {
        app.tick();
    }
    common::render(&mut app, 100, 30);
    press(&mut app, KeyCode::Char('E'));
    let first = dir.join("turntable-table-1.svg");
    assert_eq!(
        app.notice().as_deref(),
        Some(format!("wrote this page to {}", first.display()).as_str())
    );
    let tags = parse(&std::fs::read_to_string(&first).unwrap());
    let (x, y) = (axis(&tags, "x-tick"), axis(&tags, "y-tick"));
    // The trail ends where the particle is on screen: B at rest (docs/numerics.md).
    let end = *points(named(&tags, "particle")).last().unwrap();
    let now = app.sim().now();
    assert!((x(end.0) - now.r.x).abs() < 1e-5 && (y(end.1) - now.r.y).abs() < 1e-5);
    assert!(
        (now.xi() - reference::B_REST.0).abs() < 1e-8,
        "{}",
        now.xi()
    );
    // Never over a file: a second press, and a name taken meanwhile, give new names.
    std::fs::write(dir.join("turntable-table-3.svg"), "mine").unwrap();
    press(&mut app, KeyCode::Char('E'));
    press(&mut app, KeyCode::Char('E'));
    assert!(
        app.notice()
            .as_deref()
            .unwrap()
            .ends_with("turntable-table-4.svg")
    );
    assert!(dir.join("turntable-table-2.svg").exists());
    assert_eq!(
        std::fs::read_to_string(dir.join("turntable-table-3.svg")).unwrap(),
        "mine"
    );
    // The escape-speed page: the curves the page computed, v_e(0.5, 0) among them.
    press(&mut app, KeyCode::Tab);
    press(&mut app, KeyCode::Tab);
    common::render(&mut app, 100, 30);
    press(&mut app, KeyCode::Char('E'));
    let svg = std::fs::read_to_string(dir.join("turntable-escape-speed-1.svg")).unwrap();
    let tags = parse(&svg);
    let lines = with_class(&tags, "series");
    assert_eq!(lines.len(), 4, "ξ0 0.5 and the paper's 0.8, 0.2, 0.001");
    let (x, y) = (axis(&tags, "x-tick"), axis(&tags, "y-tick"));
    let mine = points(named(&tags, "ξ0=0.500 (now)"));
    assert_eq!(mine.len(), turntable::analysis::CURVE_POINTS);
    assert!(x(mine[0].0).abs() < 1e-5);
    assert!(
        // The curve's bracket (its half-width) and the SVG's rounding.
        (y(mine[0].1) - reference::VE_C).abs() < 0.5 * turntable::analysis::CURVE_VTOL + 2e-6,
        "{}",
        y(mine[0].1)
    );
    // The legend as the page's: the paper's curves are named at their peaks instead.
    assert_eq!(legend(&tags), ["ξ0=0.500 (now)"]);
    assert_eq!(
        text_of(&tags, "mark-label"),
        [
            "0.8",
            "0.2",
            "0.001",
            "min",
            "max",
            "release sticks (below v_e)"
        ]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A replay writes no files: `E` there says what it would write.
#[test]
fn a_replay_only_says_what_e_would_write() {
    let keys = out("replay").with_extension("keys");
    std::fs::write(&keys, "resize 100x24\ntab\nE\n").unwrap();
    let (code, screen, err) = turntable(&["replay", keys.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(
        screen.contains("replay saves nothing: this page → turntable-time-plots-N.svg"),
        "{screen}"
    );
    std::fs::remove_file(&keys).unwrap();
}

/// The SVG split at its panels: each panel's tags, its own axes among them.
fn panels(tags: &[Tag]) -> Vec<&[Tag]> {
    let starts: Vec<usize> = tags
        .iter()
        .enumerate()
        .filter(|(_, t)| t.name == "g" && t.attr("class") == Some("panel"))
        .map(|(k, _)| k)
        .collect();
    let ends = starts.iter().skip(1).copied().chain([tags.len()]);
    starts.iter().zip(ends).map(|(&a, b)| &tags[a..b]).collect()
}

/// The names of what a panel draws (lines, dots, cells, arrows), each once, in order.
fn drawn(tags: &[Tag]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for t in tags {
        if let Some(n) = t.attr("data-name")
            && !names.iter().any(|m| m == n)
        {
            names.push(n.to_string());
        }
    }
    names
}

/// `E` writes what the screen shows: on the turntable the pinned run, the paper's RK2 run
/// under `c`, the release's velocity and the arrows at the particle; on the time plots the
/// same, with the Sec. III approximations and the θ panel, each panel's legend the screen's.
#[test]
fn an_export_carries_what_the_screen_shows() {
    use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
    use turntable::app::App;
    let dir = std::env::temp_dir().join(format!("turntable-shows-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // Fig. 2: at rest on the table at ξ0 = 1.1, where Sec. III's approximations hold early.
    let mut app = App::new(turntable::scene::Scene::preset("fig2").unwrap());
    app.tell_save_path(dir.join("turntable-scene.toml"));
    let press = |app: &mut App, code| {
        let effects = app.handle_key(KeyEvent::new(code, KeyModifiers::NONE));
        turntable::session::carry_out(app, effects);
    };
    for _ in 0..40 {
        app.tick();
    }
    for key in ['b', 'c', 'i', 'a'] {
        press(&mut app, KeyCode::Char(key));
    }
    for _ in 0..40 {
        app.tick();
    }
    let pin = format!(
        "{}{}",
        app.pins()[0].marker,
        app.pins()[0].spec.label.as_str()
    );
    assert!(app.paper().is_some() && app.view().velocity && app.view().forces);
    common::render(&mut app, 160, 50);
    press(&mut app, KeyCode::Char('E'));
    let svg = std::fs::read_to_string(dir.join("turntable-table-1.svg")).unwrap();
    let tags = parse(&svg);
    assert_eq!(
        drawn(&tags),
        [
            "table edge",
            "ξ=1 (R_max)",
            "the table's turn",
            pin.as_str(),
            "the paper's RK2 run (c)",
            "particle",
            "release velocity",
            // In the lab only friction acts in the plane.
            "fr (friction)",
            "v (velocity (lab))",
        ]
        .map(String::from)
    );
    // The paper's run ends where its ○ is on screen, the particle's where ● is.
    let (x, y) = (axis(&tags, "x-tick"), axis(&tags, "y-tick"));
    for (name, now) in [
        ("the paper's RK2 run (c)", app.paper().unwrap().now()),
        ("particle", app.sim().now()),
    ] {
        let end = *points(named(&tags, name)).last().unwrap();
        assert!(
            (x(end.0) - now.r.x).abs() < 1e-4 && (y(end.1) - now.r.y).abs() < 1e-4,
            "{name}: {end:?} {:?}",
            now.r
        );
    }
    // The time plots: five panels, each drawing what its legend on screen names.
    press(&mut app, KeyCode::Tab);
    let screen = common::render(&mut app, 160, 50);
    press(&mut app, KeyCode::Char('E'));
    let svg = std::fs::read_to_string(dir.join("turntable-time-plots-1.svg")).unwrap();
    let tags = parse(&svg);
    let panels = panels(&tags);
    let names: Vec<Vec<String>> = panels.iter().map(|p| drawn(p)).collect();
    let with_pin =
        |a: &str, b: &str, approx: &str| [a, b, pin.as_str(), approx].map(String::from).to_vec();
    assert_eq!(
        names,
        [
            // ξ = 1 where the ξ plot reaches it (fig2 starts at 1.1).
            [
                with_pin("run", "paper RK2", "Sec. III approx."),
                vec!["ξ = 1 (R_max)".to_string()]
            ]
            .concat(),
            // On the table Eq. 20 drops the friction term: its legend says so.
            with_pin("run", "paper RK2", "Eq. 20, friction dropped"),
            with_pin("run", "paper RK2", "Eq. 20, friction dropped"),
            ["run", "paper RK2", pin.as_str()]
                .map(String::from)
                .to_vec(),
            ["E − E(0)", "−∫|u|dτ"].map(String::from).to_vec(),
        ]
    );
    for n in names.iter().flatten() {
        assert!(screen.contains(n.as_str()), "{n} not on screen:\n{screen}");
    }
    // Sec. III's ξ starts at the release, ξ0 = 1.1 (Eq. 19), and the run's ξ ends at the ξ
    // on screen.
    let (x, y) = (axis(panels[0], "x-tick"), axis(panels[0], "y-tick"));
    let dots: Vec<f64> = panels[0]
        .iter()
        .skip_while(|t| t.attr("data-name") != Some("Sec. III approx."))
        .take_while(|t| t.name != "g" || t.attr("data-name") == Some("Sec. III approx."))
        .filter(|t| t.name == "circle")
        .map(|t| y(t.num("cy")))
        .collect();
    assert!((dots[0] - 1.1).abs() < 1e-4, "{dots:?}");
    let lines: Vec<&Tag> = panels[0]
        .iter()
        .filter(|t| t.attr("data-name") == Some("run") && t.name == "polyline")
        .collect();
    let end = *points(lines[lines.len() - 1]).last().unwrap();
    let now = app.sim().now();
    assert!((x(end.0) - now.tau).abs() < 1e-4, "{end:?} {}", now.tau);
    assert!((y(end.1) - now.xi()).abs() < 1e-4, "{end:?} {}", now.xi());
    std::fs::remove_dir_all(&dir).unwrap();
}
