//! The engine's own errors: it knows nothing of processes or exit codes (`crate::error` maps
//! these to them), so the engine depends on no other part of the crate.

use super::run::RunError;

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// Input refused: initial conditions, settings, solver bounds.
    #[error("{0}")]
    Invalid(String),
    /// A run that could not finish: its step budget, or a step size that underflowed.
    #[error(transparent)]
    Run(#[from] RunError),
    /// A solver that found no answer.
    #[error("{0}")]
    Failed(String),
    /// A solver stopped by its caller between runs (see [`super::solve::GoOn`]).
    #[error("cancelled")]
    Cancelled,
}

impl Error {
    /// Input refused, with why.
    pub fn invalid(why: impl Into<String>) -> Error {
        Error::Invalid(why.into())
    }
}
