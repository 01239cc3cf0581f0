//! dop853 against dp54 at equal error: where the eighth-order method starts to need fewer
//! right-hand-side evaluations (issue 17, item 8).

use super::{Row, Task};
use crate::engine::Method;
use serde::Serialize;

/// One dop853 row against dp54's work at the same median error.
#[derive(Clone, Debug, Serialize)]
pub struct Versus {
    pub tol: f64,
    pub err: f64,
    pub dop853_evals: f64,
    /// dp54's median RHS per case at `err`, interpolated log–log between its tolerances.
    pub dp54_evals: f64,
    /// dp54's work over dop853's: above one, dop853 is cheaper.
    pub ratio: f64,
}

/// Per task: every dop853 row inside dp54's range of errors, loosest tol first, and the
/// crossover, the loosest of them from which on (every tighter tolerance too) dop853 is the
/// cheaper.
#[derive(Clone, Debug, Serialize)]
pub struct Crossover {
    pub task: Task,
    pub points: Vec<Versus>,
    /// (tol, error) of dop853 at the crossover; None if it never wins to the end.
    pub from: Option<(f64, f64)>,
}

/// (log10 error, log10 median RHS) of a method's rows on a task, by decreasing error.
fn curve(rows: &[Row], task: Task, m: Method) -> Vec<(f64, f64, f64)> {
    let mut c: Vec<(f64, f64, f64)> = rows
        .iter()
        .filter(|r| r.task == task && r.method == m && r.err_median > 0.0)
        .filter(|r| r.measures_its_method())
        .map(|r| (r.err_median.log10(), r.evals_median.log10(), r.knob))
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    c.sort_by(|a, b| b.0.total_cmp(&a.0));
    c
}

/// dp54's log10 work at log10 error `e`, between the two rows that bracket it.
fn work_at(c: &[(f64, f64, f64)], e: f64) -> Option<f64> {
    c.windows(2).find_map(|w| {
        let ((e0, w0, _), (e1, w1, _)) = (w[0], w[1]);
        ((e1..=e0).contains(&e) && e0 > e1).then(|| w0 + (w1 - w0) * (e - e0) / (e1 - e0))
    })
}

pub fn crossovers(rows: &[Row]) -> Vec<Crossover> {
    let mut out = Vec::new();
    for &task in <Task as strum::VariantArray>::VARIANTS {
        let dp = curve(rows, task, Method::Dp54);
        let mut points: Vec<Versus> = curve(rows, task, Method::Dop853)
            .into_iter()
            .filter_map(|(e, w, tol)| {
                let d = work_at(&dp, e)?;
                Some(Versus {
                    tol,
                    err: 10f64.powf(e),
                    dop853_evals: 10f64.powf(w),
                    dp54_evals: 10f64.powf(d),
                    ratio: 10f64.powf(d - w),
                })
            })
            .collect();
        points.sort_by(|a, b| b.tol.total_cmp(&a.tol));
        if points.is_empty() {
            continue;
        }
        let wins_on = points
            .iter()
            .rposition(|p| p.ratio < 1.0)
            .map_or(0, |i| i + 1);
        out.push(Crossover {
            task,
            from: points.get(wins_on).map(|p| (p.tol, p.err)),
            points,
        });
    }
    out
}
