//! The report as a table and as braille work–precision charts.

use super::Report;

fn sci(x: f64) -> String {
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
    use std::fmt::Write as _;
    let mut o = String::new();
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
    let _ = writeln!(o, "\nreference and its own agreement:");
    for c in &r.reference {
        let _ = writeln!(
            o,
            "  {:<22} {:<26} vs {:<28} {}",
            c.task,
            c.reference,
            c.check,
            sci(c.agreement)
        );
    }
    let _ = writeln!(
        o,
        "\n{:<20} {:<8} {:<17} {:>8} {:>8} {:>8} {:>8} {:>5} {:>10} {:>10} {:>9}",
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
    let mut last = String::new();
    for row in &r.rows {
        if row.task != last {
            let _ = writeln!(o, "{}", "-".repeat(115));
            last = row.task.clone();
        }
        let _ = writeln!(
            o,
            "{:<20} {:<8} {:<17} {:>8} {:>8} {:>8} {:>8} {:>5} {:>10.0} {:>10} {:>9.2}",
            row.task,
            row.method,
            row.setting,
            sci(row.err_median),
            sci(row.err_worst),
            row.time_median.map_or("".into(), sci),
            row.time_worst.map_or("".into(), sci),
            row.wrong,
            row.evals_median,
            row.rhs_evals,
            row.wall_ms
        );
    }
    let _ = writeln!(o, "\nmodel only what a scene requires (RHS evaluations):");
    for s in &r.savings {
        let factor = if s.factor.is_finite() {
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
    let sp = &r.speed;
    let _ = writeln!(o, "\nspeed goals (release build, this machine):");
    let _ = writeln!(
        o,
        "  escape speed to 1e-8 at (0.5, 0), dp54 tol=1e-10: {:.2} ms, {} RHS, v_e = {:.10}   (goal ≤ 5 ms)",
        sp.escape_ms, sp.escape_evals, sp.escape_value
    );
    let _ = writeln!(
        o,
        "  four Fig. 5 curves × {} angles (vtol {:e}, all cores): {:.0} ms   (goal ≤ 1000 ms){}",
        sp.fig5_angles,
        sp.fig5_vtol,
        sp.fig5_ms,
        sp.fig5_ms_vtol_1e8
            .map_or(String::new(), |m| format!("; at vtol 1e-8: {m:.0} ms"))
    );
    let _ = writeln!(
        o,
        "  escape-speed page, one curve (ξ0 = 0.5, 72 angles, vtol 1e-6, one thread): {:.0} ms   (goal ≤ 50 ms)",
        sp.curve_ms
    );
    let _ = writeln!(
        o,
        "  outcome map 72 × 60 cells (sweep map, all cores): {:.0} ms   (goal ≤ 1000 ms)",
        sp.map_ms
    );
    match (sp.matching_tol, sp.evals_ratio) {
        (Some(tol), Some(ratio)) => {
            let _ = writeln!(
                o,
                "  rk2 dt=1e-3 median rest error {}: dp54 reaches it at tol={tol:.1e} (median {}) with {ratio:.0}× fewer RHS evaluations (median over cases; goal ≥ 20×)",
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
    if !r.ratios.is_empty() {
        let _ = writeln!(
            o,
            "  dp54 against rk2 dt=1e-3 task by task (loosest dp54 on the grid at least as accurate; median RHS per case):"
        );
        for t in &r.ratios {
            let _ = writeln!(
                o,
                "    {:<20} rk2 {} in {:>9.0} RHS   dp54 {:<9} {} in {:>7.0} RHS   {:>6.1}×",
                t.task,
                sci(t.rk2_err),
                t.rk2_evals,
                t.dp54_setting,
                sci(t.dp54_err),
                t.dp54_evals,
                t.ratio
            );
        }
    }
    let _ = writeln!(
        o,
        "  explorer frame at 160×48, {}-point trail, paper's run beside it (tick + draw): {:.2} ms   (goal ≤ 2 ms)",
        sp.frame_trail, sp.frame_ms
    );
    for b in &sp.terminal_bytes {
        let _ = writeln!(
            o,
            "  terminal output, default scene playing at {}×{} ({} frames), {:<13} {:<6}: {:>6.0} B/frame = {:>5.1} KB/s at {} fps   (goal ≤ {} KB/s)",
            b.size.0,
            b.size.1,
            b.frames,
            b.theme,
            b.depth,
            b.bytes_per_frame,
            b.kb_per_s,
            super::bytes::FPS,
            super::bytes::GOAL_KB_PER_S
        );
    }
    o
}

/// Error against work (log–log) for one task, as a braille chart in plain text.
pub fn plot(r: &Report, task: &str, width: usize, height: usize) -> String {
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for row in r.rows.iter().filter(|row| row.task == task) {
        let p = (
            row.evals_median.max(1.0).log10(),
            row.err_median.max(1e-16).log10(),
        );
        if !(p.0.is_finite() && p.1.is_finite()) {
            continue;
        }
        match series.iter_mut().find(|(m, _)| *m == row.method) {
            Some((_, v)) => v.push(p),
            None => series.push((row.method.clone(), vec![p])),
        }
    }
    let pts: Vec<(f64, f64)> = series.iter().flat_map(|(_, v)| v.iter().copied()).collect();
    if pts.is_empty() {
        return format!("{task}: nothing to plot\n");
    }
    let (x0, x1) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
        (a.0.min(p.0.floor()), a.1.max(p.0.ceil()))
    });
    let (y0, y1) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
        (a.0.min(p.1.floor()), a.1.max(p.1.ceil()))
    });
    let (x1, y1) = (x1.max(x0 + 1.0), y1.max(y0 + 1.0));
    let (dw, dh) = (width * 2, height * 4);
    let mut dots = vec![vec![false; dw]; dh];
    let to_dot = |p: (f64, f64)| {
        let x = ((p.0 - x0) / (x1 - x0) * (dw - 1) as f64).round() as i64;
        let y = ((y1 - p.1) / (y1 - y0) * (dh - 1) as f64).round() as i64;
        (x, y)
    };
    let mut labels: Vec<(usize, usize, char)> = Vec::new();
    let marks = ['r', '2', '4', 'd', 'e', 'f'];
    for (k, (name, v)) in series.iter().enumerate() {
        let mark = match name.as_str() {
            "rk2-raw" => 'r',
            "rk2" => '2',
            "rk4" => '4',
            "dp54" => 'd',
            _ => marks[k % marks.len()],
        };
        for w in v.windows(2) {
            let (a, b) = (to_dot(w[0]), to_dot(w[1]));
            let n = (b.0 - a.0).abs().max((b.1 - a.1).abs()).max(1);
            for i in 0..=n {
                let x = a.0 + (b.0 - a.0) * i / n;
                let y = a.1 + (b.1 - a.1) * i / n;
                if (0..dw as i64).contains(&x) && (0..dh as i64).contains(&y) {
                    dots[y as usize][x as usize] = true;
                }
            }
        }
        for &p in v {
            let (x, y) = to_dot(p);
            labels.push(((x / 2) as usize, (y / 4) as usize, mark));
        }
    }
    let mut grid: Vec<Vec<char>> = (0..height)
        .map(|cy| {
            (0..width)
                .map(|cx| {
                    // Braille dot bits: (0,0)=1 (0,1)=2 (0,2)=4 (1,0)=8 (1,1)=16 (1,2)=32
                    // (0,3)=64 (1,3)=128.
                    let bits = [[0x01, 0x08], [0x02, 0x10], [0x04, 0x20], [0x40, 0x80]];
                    let mut b = 0u32;
                    for (dy, row) in bits.iter().enumerate() {
                        for (dx, bit) in row.iter().enumerate() {
                            if dots[cy * 4 + dy][cx * 2 + dx] {
                                b |= bit;
                            }
                        }
                    }
                    char::from_u32(0x2800 + b).unwrap_or(' ')
                })
                .collect()
        })
        .collect();
    for (cx, cy, m) in labels {
        if cy < height && cx < width {
            grid[cy][cx] = m;
        }
    }
    let mut o = format!(
        "{task}: median error (log10, up) against RHS evaluations per case (log10, right)\n"
    );
    for (cy, line) in grid.iter().enumerate() {
        let label = if cy == 0 {
            format!("{y1:>4.0} ")
        } else if cy == height - 1 {
            format!("{y0:>4.0} ")
        } else {
            "     ".into()
        };
        o.push_str(&label);
        o.push('│');
        o.extend(line.iter());
        o.push('\n');
    }
    o.push_str(&format!("     └{}\n", "─".repeat(width)));
    o.push_str(&format!(
        "      {:<w$}{:>4.0}\n",
        format!("{x0:.0}"),
        x1,
        w = width - 4
    ));
    o.push_str("      r = rk2-raw, 2 = rk2, 4 = rk4, d = dp54\n");
    o
}
