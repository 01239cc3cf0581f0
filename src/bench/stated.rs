//! Issue 42: what a row's runs state against what they are off by, and what their end game
//! (implicit steps, closed-form stops) did, on the tasks that time stops. Run apart from the
//! timed pass: asking each run's second opinion costs about as much as the run.

use super::runs::{audit, state_at};
use super::tasks::Measure;
use super::{REST_TAU, median, reference};
use crate::engine::{Initial, Outcome, Settings};
use crate::error::Error;
use serde::Serialize;

/// Stated error against actual (against the reference) over a row's stops.
#[derive(Clone, Debug, Serialize)]
pub struct Stated {
    /// Stops compared: those stuck in both the row and the reference.
    pub cases: usize,
    /// Of them, those whose actual stop-time (rest-place) error is within the stated one. An
    /// actual error below the reference's resolution counts as within when the stated one is
    /// at least the resolution; when both are below it the reference cannot tell
    /// (`unresolved`), and the case counts neither way.
    pub tau_within: usize,
    pub q_within: usize,
    pub tau_unresolved: usize,
    pub q_unresolved: usize,
    /// The largest actual ÷ stated among the cases the reference resolves (0 if none), the actual
    /// less the reference's resolution (`judge`).
    pub tau_worst: f64,
    pub q_worst: f64,
}

/// The end game's share of a row.
#[derive(Clone, Debug, Serialize)]
pub struct EndGame {
    pub cases: usize,
    /// Cases whose stop the end game took (its last step was implicit or closed form).
    pub took_stop: usize,
    /// Its RHS evaluations over all of the row's.
    pub evals_share: f64,
    /// Median over the cases it took part in of the method's own error (|Δr| against the
    /// reference) where it handed over: what the method itself delivered.
    pub handover_err: Option<f64>,
}

impl EndGame {
    /// Whether in most of the row's runs the end game took over at the release: the row then
    /// measures the end game, not its method.
    pub fn took_the_row(&self) -> bool {
        self.handover_err == Some(0.0)
    }
}

/// One case's comparison: (within, unresolved, ratio when resolved). The actual error is known
/// only to within the reference's resolution, so what it can tell is the actual less that: a stop
/// 9.7e-9 off against a reference good to 7.3e-9 was counted further off than its stated 2.4e-9
/// (the rim's dp54 rows at tol 1e-11, "0/1 within, worst 4.06×").
fn judge(actual: f64, stated: f64, resolution: f64) -> (bool, bool, Option<f64>) {
    if actual < resolution {
        (stated >= resolution, stated < resolution, None)
    } else {
        let told = actual - resolution;
        (told <= stated, false, Some(told / stated))
    }
}

/// The stated-against-actual and end-game lines of setting `s` over `cases`, against the
/// reference's measures `refs`, whose resolution (agreement with its cross-check) is
/// `resolution`. None for a method with no stick event (the raw scheme states no error).
pub(super) fn lines(
    s: Settings,
    cases: &[Initial],
    refs: &[Measure],
    resolution: f64,
) -> Result<Option<(Stated, EndGame)>, Error> {
    if !s.method().stick_events() {
        return Ok(None);
    }
    let mut st = Stated {
        cases: 0,
        tau_within: 0,
        q_within: 0,
        tau_unresolved: 0,
        q_unresolved: 0,
        tau_worst: 0.0,
        q_worst: 0.0,
    };
    let (mut took, mut end_evals, mut evals, mut handover) = (0, 0, 0, Vec::new());
    for (&i, r) in cases.iter().zip(refs) {
        let a = audit(i, s, REST_TAU)?;
        end_evals += a.end_evals;
        evals += a.evals;
        took += usize::from(a.end_took_stop);
        if let Some(h) = a.handover {
            let (at, _) = state_at(i, reference(), h.tau)?;
            handover.push((h.r - at.r).length());
        }
        let (Some(tau), Some(q)) = (r.tau, r.value) else {
            continue;
        };
        if a.outcome != Outcome::Stuck {
            continue;
        }
        st.cases += 1;
        let (w, u, ratio) = judge((a.tau - tau).abs(), a.stated_tau, resolution);
        st.tau_within += usize::from(w);
        st.tau_unresolved += usize::from(u);
        st.tau_worst = st.tau_worst.max(ratio.unwrap_or(0.0));
        let (w, u, ratio) = judge((a.q - q).length(), a.stated_q, resolution);
        st.q_within += usize::from(w);
        st.q_unresolved += usize::from(u);
        st.q_worst = st.q_worst.max(ratio.unwrap_or(0.0));
    }
    let end = EndGame {
        cases: cases.len(),
        took_stop: took,
        evals_share: end_evals as f64 / evals.max(1) as f64,
        handover_err: (!handover.is_empty()).then(|| median(&mut handover)),
    };
    Ok(Some((st, end)))
}

/// Under a row that times stops: what its runs stated against what they were off by, and what
/// the end game did (its stop, its price, and the method's own error where it handed over).
pub(super) fn print(o: &mut String, st: &Stated, end: &EndGame) {
    use std::fmt::Write as _;
    let sci = super::output::sci;
    let share = |within: usize, unresolved: usize, worst: f64| {
        let judged = st.cases - unresolved;
        let mut t = format!("{within}/{judged} within");
        if judged > 0 {
            let _ = write!(t, " ({:.0}%)", 100.0 * within as f64 / judged as f64);
        }
        if worst > 0.0 {
            let _ = write!(t, ", worst {worst:.2}×");
        }
        if unresolved > 0 {
            let _ = write!(t, ", {unresolved} both below resolution");
        }
        t
    };
    if st.cases > 0 {
        let _ = writeln!(
            o,
            "{:>20} stated vs actual: τ {}; place {}",
            "",
            share(st.tau_within, st.tau_unresolved, st.tau_worst),
            share(st.q_within, st.q_unresolved, st.q_worst)
        );
    }
    if end.evals_share > 0.0 {
        let _ = writeln!(
            o,
            "{:>20} end game (implicit steps, closed-form stops): took the stop in {}/{}, {:.0}% of the RHS{}",
            "",
            end.took_stop,
            end.cases,
            100.0 * end.evals_share,
            match end.handover_err {
                _ if end.took_the_row() => "; in most runs it took over at the release: the row measures the end game, not the method".into(),
                Some(e) => format!("; the method's own error where it handed over: median {}", sci(e)),
                None => String::new(),
            }
        );
    }
}

#[cfg(test)]
mod tests {
    use super::judge;

    #[test]
    fn an_error_below_the_references_resolution_is_judged_only_against_it() {
        let ratio = |a: f64, s: f64, r: f64| judge(a, s, r).2.map(|x| (x * 100.0).round() / 100.0);
        assert!(!judge(2.1e-9, 1e-9, 1e-10).0);
        assert_eq!(ratio(2.1e-9, 1e-9, 1e-10), Some(2.0));
        assert_eq!(judge(5e-11, 1e-9, 1e-10), (true, false, None));
        assert_eq!(judge(5e-11, 1e-11, 1e-10), (false, true, None));
        assert!(judge(1.1e-9, 1e-9, 1e-10).0);
        // Off by less than the stated error and the reference's resolution together: within.
        assert!(judge(9.7e-9, 2.5e-9, 7.3e-9).0);
        assert_eq!(ratio(9.7e-9, 2.5e-9, 7.3e-9), Some(0.96));
    }
}
