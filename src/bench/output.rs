//! The report as a table and as braille work–precision charts.

use super::{Report, Speed, Task};
use crate::engine::Method;
use crate::error::Error;
use crate::plot::extent;
use crate::plot::{Chart, Ink, Mark, Series, Style};
use crate::theme::Theme;
use crate::ui::chart::render;
use crate::ui::export::plain_text;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use std::fmt::Write as _;

pub(super) fn sci(x: f64) -> String {
    if x.is_nan() {
        "—".into()
    } else if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.1e}")
    }
}

/// The aligned text table.
pub fn table(r: &Report) -> String {
    let mut o = String::new();
    header(&mut o, r);
    rows(&mut o, r);
    savings(&mut o, r);
    models(&mut o, r);
    let _ = writeln!(o, "\nspeed goals (release build, this machine):");
    if let Some(sp) = &r.speed {
        speed_goals(&mut o, sp);
    }
    let checked_ms = r.speed.as_ref().and_then(|sp| sp.escape_checked_ms);
    super::check::lines(&mut o, &r.checks, checked_ms, &r.scipy);
    page_goals(&mut o, &r.pages);
    comparisons(&mut o, r);
    if let Some(sp) = &r.speed {
        output_goals(&mut o, sp);
    }
    o
}

/// What was run, and under what load.
fn header(o: &mut String, r: &Report) {
    let _ = writeln!(
        o,
        "turntable bench ({}; {} random cases, seed {}; error = |Δposition| (rest: table frame), \
         |Δv_e| or relative |Δr| far out; work = RHS evaluations, wall = min of runs, one thread)",
        if r.config.quick { "quick" } else { "full" },
        r.config.cases,
        r.config.seed
    );
    if let Some(l) = &r.load {
        let _ = writeln!(
            o,
            "load average {l} on {} cores (wall times are minima over runs; RHS counts do not depend on load)",
            std::thread::available_parallelism().map_or(1, |n| n.get())
        );
    }
}

/// The reference's own agreement, then a row per task, method and setting.
fn rows(o: &mut String, r: &Report) {
    let _ = writeln!(o, "\nreference and its own agreement:");
    for c in &r.reference {
        let _ = writeln!(
            o,
            "  {:<22} {:<26} vs {:<28} {}",
            c.task.to_string(),
            c.reference,
            c.check,
            sci(c.agreement)
        );
    }
    let _ = writeln!(
        o,
        "\n{:<20} {:<8} {:<17} {:>9} {:>9} {:>9} {:>9} {:>5} {:>10} {:>10} {:>9}",
        "task",
        "method",
        "setting",
        "err med",
        "err max",
        "τ med",
        "τ max",
        "wrong",
        "RHS/case",
        "RHS total",
        "wall ms"
    );
    let mut last = None;
    for row in &r.rows {
        if last != Some(row.task) {
            let _ = writeln!(o, "{}", "-".repeat(119));
            last = Some(row.task);
        }
        let res = |x: f64| resolved(x, row.resolution);
        let _ = writeln!(
            o,
            "{:<20} {:<8} {:<17} {:>9} {:>9} {:>9} {:>9} {:>5} {:>10.0} {:>10} {:>9.2}",
            row.task.to_string(),
            row.method.to_string(),
            row.setting,
            res(row.err_median),
            res(row.err_worst),
            row.time_median.map_or("".into(), res),
            row.time_worst.map_or("".into(), res),
            row.wrong,
            row.evals_median,
            row.rhs_evals,
            row.wall_ms
        );
        if let (Some(st), Some(end)) = (&row.stated, &row.end_game) {
            super::stated::print(o, st, end);
        }
    }
}

/// An error as far as the reference can tell it: below its resolution, "<" the resolution.
fn resolved(x: f64, resolution: f64) -> String {
    if x < resolution {
        format!("<{}", sci(resolution))
    } else {
        sci(x)
    }
}

/// What modelling only what a scene requires saves.
fn savings(o: &mut String, r: &Report) {
    let _ = writeln!(o, "\nmodel only what a scene requires (RHS evaluations):");
    for s in &r.savings {
        let factor = if (0.5..2.0).contains(&s.factor) {
            format!("{:.3}× as much", 1.0 / s.factor)
        } else if s.factor < 0.5 {
            // A model that costs more than the point (the finite body).
            format!("{:.1}× more", 1.0 / s.factor)
        } else if s.factor.is_finite() {
            format!("{:.0}× less", s.factor)
        } else {
            "none at all".into()
        };
        let _ = writeln!(
            o,
            "  {}\n    {:<44} {:>10}\n    {:<44} {:>10}   {factor}",
            s.what, s.baseline, s.baseline_evals, s.lean, s.lean_evals
        );
    }
}

/// The price of each model: one run, one frame.
fn models(o: &mut String, r: &Report) {
    let _ = writeln!(
        o,
        "\nthe price of each model ({} releases to τ = 50: median RHS and mean wall of one run; one frame of the explorer playing it at 120×40, tick + draw; its outcome-map page at 120×40, curve and cells, one thread; the spin-up, a coin at rest at each release's ξ0, its frame past the slip (preset spin) and its page the runs over ξ0 × ramp rate at the map's grid):",
        r.config.cases + 3
    );
    for m in &r.models {
        let _ = writeln!(
            o,
            "  {:<36} run {:>7.0} RHS {:>8.1} µs   frame {:>5.2} ms   page {}",
            m.model,
            m.run_rhs,
            m.run_us,
            m.frame_ms,
            m.page_ms
                .map_or("the point's".into(), |ms| format!("{ms:>5.1} ms"))
        );
    }
}

/// The speed goals of the solvers, the pages and the sweeps.
fn speed_goals(o: &mut String, sp: &Speed) {
    let _ = writeln!(
        o,
        "  escape speed to 1e-8 at (0.5, 0), dp54 tol=1e-10: {:.2} ms, {} RHS, v_e = {:.10}   {}",
        sp.escape_ms,
        sp.escape_evals,
        sp.escape_value,
        goal(sp.escape_ms, 5.0, "ms")
    );
    let _ = writeln!(
        o,
        "  four Fig. 5 curves × {} angles (vtol {:e}, all cores): {:.0} ms   {}{}",
        sp.fig5_angles,
        sp.fig5_vtol,
        sp.fig5_ms,
        goal(sp.fig5_ms, 1000.0, "ms"),
        sp.fig5_ms_vtol_1e8
            .map_or(String::new(), |m| format!("; at vtol 1e-8: {m:.0} ms"))
    );
    let _ = writeln!(
        o,
        "  escape-speed page, one curve (ξ0 = 0.5, 72 angles, vtol {}, one thread, from no nearby curve): {:.0} ms, {} RHS; from ξ0 = 0.49's: {} RHS   {}",
        crate::present::sci(crate::analysis::CURVE_VTOL, 0),
        sp.curve_ms,
        sp.curve_rhs,
        sp.curve_near_rhs,
        goal(sp.curve_ms, 50.0, "ms")
    );
    if let Some(ms) = sp.escape_cli_ms {
        let _ = writeln!(
            o,
            "  `turntable escape --vtol 1e-8 --no-check` on Fig. 5's points (4 ξ0 × {} φ), process start included: {ms:.2} ms median   {}",
            sp.escape_angles,
            goal(ms, 3.0, "ms")
        );
    }
    if let Some(ms) = sp.escape_checked_ms {
        let _ = writeln!(
            o,
            "  the same with its bracket certified (the default: both ends run in full, each against a second opinion): {ms:.2} ms median"
        );
    }
    let _ = writeln!(
        o,
        "  outcome map 72 × 60 cells (sweep map, all cores): {:.0} ms   {}",
        sp.map_ms,
        goal(sp.map_ms, 1000.0, "ms")
    );
    match (sp.matching_tol, sp.evals_ratio) {
        (Some(tol), Some(ratio)) => {
            let _ = writeln!(
                o,
                "  rk2 dt=1e-3 median rest error {}: dp54 reaches it at tol={tol:.1e} (median {}) with {ratio:.0}× fewer RHS evaluations (median over cases; the 20× target is withdrawn)",
                sci(sp.rk2_err_median),
                sci(sp.matching_err_median.unwrap_or(f64::NAN))
            );
        }
        _ => {
            let _ = writeln!(
                o,
                "  rk2 dt=1e-3 median rest error {}: no dp54 tol matched it",
                sci(sp.rk2_err_median)
            );
        }
    }
}

/// The pages on all cores and a key's wait for them (issue 34).
fn page_goals(o: &mut String, p: &super::pages::PageTimes) {
    let (w, h) = super::pages::SIZE;
    let _ = writeln!(
        o,
        "  the pages at {w}×{h} on {} cores: one thread → all cores (wall), speedup; the most the split gives idle cores (CPU over the larger of a core's share and the longest piece)",
        p.cores
    );
    let rows = [
        (
            "escape-speed curve, ξ0 = 0.5, 72 angles".to_string(),
            &p.curve,
        ),
        (
            format!(
                "outcome map {}×{}, first runs at tol {:.0e}, {} refined",
                p.grid.0,
                p.grid.1,
                crate::analysis::CELL_TOL,
                p.refined
            ),
            &p.map,
        ),
        ("four Fig. 5 curves × 24 angles".to_string(), &p.fig5),
    ];
    for (what, s) in rows {
        let verdict = if p.cores < 2 {
            "one core: no goal".to_string()
        } else {
            goal_at_least(s.speedup(), 1.8, "×")
        };
        let _ = writeln!(
            o,
            "    {what:<58} {:>6.1} → {:>6.1} ms  {:>4.2}× {verdict}; at most {:.2}×",
            s.one_ms,
            s.all_ms,
            s.speedup(),
            s.bound()
        );
    }
    let _ = writeln!(
        o,
        "    outcome map {}×{}, every cell at the page's tol 1e-10 (before issue 34), one thread: {:.1} ms",
        p.grid.0, p.grid.1, p.map_full_one_ms
    );
    let keys = [
        (
            "its own frame while the map computes",
            p.key_frame_ms,
            Some(16.7),
        ),
        ("outcome map complete", p.key_map_ms, Some(60.0)),
        ("escape-speed curve complete", p.key_curve_ms, Some(40.0)),
        (
            "escape-speed page complete (least v_e too)",
            p.key_escape_ms,
            None,
        ),
    ];
    for (what, (median, worst), limit) in keys {
        let _ = writeln!(
            o,
            "    `x` → {what:<43} (threaded session, drawn; median / worst of {}): {median:>5.1} / {worst:>5.1} ms   {}",
            p.presses,
            limit.map_or(String::new(), |l| goal(median, l, "ms"))
        );
    }
    let _ = writeln!(
        o,
        "    `x` held (30 presses a second): {} of {} presses saw their map complete and drawn before the next; the last's complete {:.1} ms after it",
        p.held_complete, p.held, p.held_last_ms
    );
}

/// dp54 against rk2 and dop853 against dp54, task by task.
fn comparisons(o: &mut String, r: &Report) {
    if !r.ratios.is_empty() {
        let _ = writeln!(
            o,
            "  dp54 against rk2 dt=1e-3 task by task (loosest dp54 on the grid at least as accurate; median RHS per case; rows the end game took from the release left out):"
        );
        for t in &r.ratios {
            let _ = writeln!(
                o,
                "    {:<20} rk2 {} in {:>9.0} RHS   dp54 {:<9} {} in {:>7.0} RHS   {:>6.1}×",
                t.task.to_string(),
                sci(t.rk2_err),
                t.rk2_evals,
                t.dp54_setting,
                sci(t.dp54_err),
                t.dp54_evals,
                t.ratio
            );
        }
    }
    if !r.crossovers.is_empty() {
        let _ = writeln!(
            o,
            "  dop853 against dp54 at equal median error (dp54's RHS per case interpolated log–log; ratio = dp54 / dop853; rows the end game took from the release left out):"
        );
        for c in &r.crossovers {
            let from = c
                .from
                .map_or("never to the end of the grid".into(), |(tol, err)| {
                    format!("from tol={tol:.0e} (error {})", sci(err))
                });
            let pts: Vec<String> = c
                .points
                .iter()
                .map(|p| format!("{:.0e}:{:.1}×", p.tol, p.ratio))
                .collect();
            let _ = writeln!(
                o,
                "    {:<20} dop853 cheaper {from}   by tol {}",
                c.task.to_string(),
                pts.join(" ")
            );
        }
    }
}

/// The explorer's frame time, its output in bytes, a recording's bound and slow links.
fn output_goals(o: &mut String, sp: &Speed) {
    let _ = writeln!(
        o,
        "  explorer frame at 160×48, {}-point trail, paper's run beside it (tick + draw): {:.2} ms   {}",
        sp.frame_trail,
        sp.frame_ms,
        goal(sp.frame_ms, 2.0, "ms")
    );
    for b in &sp.terminal_bytes {
        let _ = writeln!(
            o,
            "  terminal output, default scene playing at {}×{} ({} frames), {:<13} {:<6}: {:>6.0} B/frame = {:>5.1} KB/s at {} fps   {}",
            b.size.0,
            b.size.1,
            b.frames,
            b.theme,
            b.depth,
            b.bytes_per_frame,
            b.kb_per_s,
            super::bytes::FPS,
            goal(b.kb_per_s, super::bytes::GOAL_KB_PER_S, "KB/s")
        );
    }
    for c in &sp.recording_bytes {
        let _ = writeln!(
            o,
            "  replay --asciicast at {}×{}, worst case (a whole-screen frame every tick; the largest of {} ticks, {} theme): {} B/tick; its bound ({}, {} frames) is reached after {} ticks ({:.0} s of play)",
            c.size.0,
            c.size.1,
            c.ticks,
            c.theme,
            c.worst_bytes_per_tick,
            crate::files::show_bytes(c.bound_bytes),
            c.bound_frames,
            c.ticks_to_bound,
            c.ticks_to_bound as f64 / f64::from(crate::app::TICKS_PER_SECOND)
        );
    }
    for l in &sp.links {
        let _ = writeln!(
            o,
            "  {} over a {:>2.0} KB/s link ({:.0} s): {:>5.0} B/frame, {:>4.1} frames/s, {} frame in flight (unpaced: {}), a key shows within {:.2} s (after the first screen), time kept {:.0} %",
            l.scene,
            l.rate_kb_per_s,
            l.seconds,
            l.bytes_per_frame,
            l.frames_per_s,
            l.in_flight,
            l.unpaced_in_flight,
            l.worst_key_s,
            100.0 * l.time_kept
        );
    }
}

/// The letter that marks a method's points on a chart without colours.
fn mark(m: Method) -> char {
    match m {
        Method::Rk2Raw => 'r',
        Method::Rk2 => '2',
        Method::Rk4 => '4',
        Method::Dp54 => 'd',
        Method::Dop853 => '8',
    }
}

/// Error against work (log–log) for one task: the explorer's braille chart, as plain text.
pub fn plot(r: &Report, task: Task, width: u16, height: u16) -> Result<String, Error> {
    let th = Theme::builtin("mono").ok_or(Error::Failed("no mono theme".into()))?;
    let mut series: Vec<Series> = Vec::new();
    let mut marks = Vec::new();
    for row in r.rows.iter().filter(|row| row.task == task) {
        let p = (
            row.evals_median.max(1.0).log10(),
            row.err_median.max(1e-16).log10(),
        );
        if !(p.0.is_finite() && p.1.is_finite()) {
            continue;
        }
        let name = format!("{} {}", mark(row.method), row.method);
        match series.iter_mut().find(|s| s.name == name) {
            Some(s) => s.points.push(p),
            None => series.push(Series {
                name,
                ink: Ink::Foreground,
                points: vec![p],
                style: Style::Line { dash: 0 },
            }),
        }
        marks.push(Mark::Text {
            x: p.0,
            y: p.1,
            label: mark(row.method).to_string(),
            ink: Ink::Foreground,
        });
    }
    let pts = || series.iter().flat_map(|s| s.points.iter().copied());
    if marks.is_empty() {
        return Ok(format!("{task}: nothing to plot\n"));
    }
    let chart = Chart {
        title: format!("{task}: work against precision"),
        note: String::new(),
        x_label: "log10 RHS evaluations per case".into(),
        y_label: "log10 median error".into(),
        x: extent(pts().map(|p| p.0)),
        y: extent(pts().map(|p| p.1)),
        series,
        marks,
        ..Chart::default()
    };
    let mut term = Terminal::new(TestBackend::new(width, height))?;
    term.draw(|f| {
        render(f, f.area(), &th, &chart);
    })?;
    Ok(plain_text(term.backend().buffer()))
}

/// A goal on a value that must be at least `limit`.
pub(super) fn goal_at_least(value: f64, limit: f64, unit: &str) -> String {
    let met = if value >= limit { "met" } else { "MISSED" };
    format!("(goal ≥ {limit}{unit}: {met})")
}

/// A speed goal and whether this run met it: a missed goal says so.
pub(super) fn goal(value: f64, limit: f64, unit: &str) -> String {
    if value <= limit {
        format!("(goal ≤ {limit} {unit}: met)")
    } else {
        format!("(goal ≤ {limit} {unit}: MISSED)")
    }
}
