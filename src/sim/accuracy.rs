//! Ask for an accuracy, not a tolerance (issue 42 item 6): the cheapest adaptive setting whose
//! stated error — the second opinion's measured error of where and when the run ended
//! ([`crate::engine::doubt::Doubt`]'s `tau_error` and `q_error`), on a certain outcome — is
//! within a bound: dp54 and dop853 at each decade of tolerance from 1e-3 to 1e-13, and of those
//! whose statement meets it, the run that took the fewest right-hand-side evaluations.
//! It can be no better than the statement it trusts: how far that statement is a bound, the
//! bench's stated-against-actual lines measure.

use super::doubts::second_opinion;
use crate::engine::{Initial, error::Error};
use crate::engine::{Method, Run, Settings};

/// The errors one may ask for: below 1e-13 nothing on offer states so little (the tightest
/// tolerance is 1e-14 and a stop's time near the rim scatters by more), above 0.1 (of R_max,
/// or of the time unit 1/Ω) a run says nothing.
pub const ERROR_RANGE: (f64, f64) = (1e-13, 0.1);

/// How long the explorer's choice runs a release (`run`'s default τ-max): its stop or escape
/// certificate, as a rule, comes well before.
pub const EXPLORER_TAU: f64 = 100.0;

/// Tolerances tried, loosest first.
const TOLS: std::ops::RangeInclusive<i32> = 3..=13;

/// Why `error` cannot be asked for (the caller names it as typed), or None.
pub fn refused(error: f64) -> Option<String> {
    let (lo, hi) = ERROR_RANGE;
    (!(error.is_finite() && (lo..=hi).contains(&error)))
        .then(|| format!("must lie in [{lo:e}, {hi}], got {}", Initial::show(error)))
}

/// One setting tried.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tried {
    pub settings: Settings,
    /// The larger of the stated errors of time and place; infinite when the outcome is not
    /// certain, the second opinion ended differently, or the run could not finish.
    pub stated: f64,
    /// The run's and its second opinion's right-hand-side evaluations.
    pub rhs: u64,
    pub check_rhs: u64,
}

/// What was tried, and which met the bound at the least cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    pub error: f64,
    pub tried: Vec<Tried>,
    pub chosen: Option<Tried>,
}

impl Choice {
    /// All the search cost: every run and every second opinion.
    pub fn rhs(&self) -> u64 {
        self.tried.iter().map(|t| t.rhs + t.check_rhs).sum()
    }

    /// What was chosen and what it cost (its run's wall time `ms` where the caller timed it),
    /// or that nothing met the bound and the least stated, for people (the CLI's words, the
    /// explorer's notice).
    pub fn said(&self, ms: Option<f64>) -> String {
        use crate::present::{accuracy, sci};
        let name = |s: &Settings| format!("{} {}", s.method(), accuracy(s));
        // Clauses (", ") in the order a narrow screen keeps them (`ui::fit` drops them whole
        // from the end).
        let search = format!(
            "the search {} settings and {} RHS evaluations with their second opinions",
            self.tried.len(),
            self.rhs()
        );
        match self.chosen {
            Some(t) => format!(
                "error ≤ {}: chose {}, stated {}, its run {} RHS evaluations{}, {search}",
                sci(self.error, 0),
                name(&t.settings),
                sci(t.stated, 1),
                t.rhs,
                ms.map_or(String::new(), |ms| format!(" and {ms:.2} ms"))
            ),
            None => {
                let best = self
                    .tried
                    .iter()
                    .filter(|t| t.stated.is_finite())
                    .min_by(|a, b| a.stated.total_cmp(&b.stated));
                format!(
                    "no setting on offer states an error ≤ {} for this release: {}, {search}",
                    sci(self.error, 0),
                    best.map_or("none was certain".into(), |b| format!(
                        "the least stated was {} ({})",
                        sci(b.stated, 1),
                        name(&b.settings)
                    ))
                )
            }
        }
    }
}

/// The adaptive settings on offer: dp54 then dop853, each at tol 1e-3 … 1e-13, loosest first
/// (frame, coupling and budget from `base`). What [`cheapest`] chooses among, and the
/// work–precision page's adaptive points.
pub fn ladder(base: Settings) -> Vec<Settings> {
    [Method::Dp54, Method::Dop853]
        .into_iter()
        .flat_map(|method| {
            TOLS.map(move |k| Settings {
                scheme: method.with(10f64.powi(-k)),
                ..base
            })
        })
        .collect()
}

/// The cheapest of dp54 and dop853 at tol 1e-3 … 1e-13 whose stated error is ≤ `error`, for
/// `initial` run to `tau_max` (stopping at the escape certificate when `stop_on_escape`), the
/// rest of the settings from `base`. Every one is tried: neither the cost nor the stated error
/// is monotone in the tolerance (dop853's short runs: a tighter tolerance can cost less). The
/// caller has checked `error` ([`refused`]).
pub fn cheapest(
    initial: Initial,
    base: Settings,
    tau_max: f64,
    stop_on_escape: bool,
    error: f64,
) -> Result<Choice, Error> {
    let mut c = Choice {
        error,
        tried: Vec::new(),
        chosen: None,
    };
    for settings in ladder(base) {
        let mut run = Run::new(initial, settings)?;
        let (stated, check_rhs) = match run.run(tau_max, stop_on_escape) {
            Ok(_) => {
                let d = second_opinion(&run, tau_max);
                let stated = if d.certain {
                    d.tau_error.max(d.q_error)
                } else {
                    f64::INFINITY
                };
                (stated, d.check_evals)
            }
            Err(_) => (f64::INFINITY, 0),
        };
        let t = Tried {
            settings,
            stated,
            rhs: run.cost().rhs_evals,
            check_rhs,
        };
        c.tried.push(t);
        if stated <= error && c.chosen.is_none_or(|b| t.rhs < b.rhs) {
            c.chosen = Some(t);
        }
    }
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::refused;

    #[test]
    fn only_errors_a_run_can_state_are_asked_for() {
        for bad in [0.0, -1e-6, f64::NAN, f64::INFINITY, 1e300, 0.5, 1e-14] {
            assert!(refused(bad).is_some(), "{bad}");
        }
        for ok in [1e-13, 1e-8, 0.1] {
            assert_eq!(refused(ok), None, "{ok}");
        }
    }
}
