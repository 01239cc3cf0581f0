//! `run --error E`'s report: what was asked, chosen and paid.

use serde::Serialize;

/// `run --error E`'s choice ([`crate::sim::accuracy`]).
#[derive(Debug, Serialize)]
pub struct ChosenReport {
    pub error: f64,
    /// The larger of the chosen run's stated errors of time and place.
    pub stated: f64,
    pub rhs_evals: u64,
    /// Wall time of the chosen run (its second opinion not included).
    pub ms: f64,
    /// Settings tried and all their RHS evaluations, second opinions included.
    pub tried: usize,
    pub search_rhs_evals: u64,
    #[serde(skip)]
    pub(super) said: String,
}

impl ChosenReport {
    pub fn new(c: &crate::sim::accuracy::Choice, ms: f64) -> ChosenReport {
        let t = c.chosen;
        ChosenReport {
            error: c.error,
            stated: t.map_or(f64::INFINITY, |t| t.stated),
            rhs_evals: t.map_or(0, |t| t.rhs),
            ms,
            tried: c.tried.len(),
            search_rhs_evals: c.rhs(),
            said: c.said(Some(ms)),
        }
    }
}
