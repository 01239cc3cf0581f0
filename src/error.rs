//! The crate's one error type. Callers branch on its kind, not its words: input refused
//! (the CLI exits 2) or work that could not be done (exit 1). The mapping to exit codes is
//! [`Error::exit_code`], and nowhere else.

use crate::engine::RunError;

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// Input refused: flags, initial conditions, settings, scene, theme and script files.
    #[error("{0}")]
    Invalid(String),
    /// A run that could not finish: its step budget, or a step size that underflowed.
    #[error(transparent)]
    Run(#[from] RunError),
    /// Anything else that could not be done: a solver that found no answer, a file that could
    /// not be written, a terminal that failed.
    #[error("{0}")]
    Failed(String),
}

impl Error {
    /// Input refused, with why.
    pub fn invalid(why: impl Into<String>) -> Error {
        Error::Invalid(why.into())
    }

    /// The same error with `what` (a flag, a file) in front of its message.
    pub fn context(self, what: &str) -> Error {
        match self {
            Error::Invalid(m) => Error::Invalid(format!("{what}: {m}")),
            e => Error::Failed(format!("{what}: {e}")),
        }
    }

    /// The process's exit code for this error: 2 for input refused, else 1.
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Invalid(_) => 2,
            Error::Run(_) | Error::Failed(_) => 1,
        }
    }
}

/// The engine's errors keep their kind: input refused stays refused (exit 2).
impl From<crate::engine::error::Error> for Error {
    fn from(e: crate::engine::error::Error) -> Error {
        use crate::engine::error::Error as E;
        match e {
            E::Invalid(m) => Error::Invalid(m),
            E::Run(r) => Error::Run(r),
            E::Failed(m) => Error::Failed(m),
            E::Cancelled => Error::Failed("cancelled".into()),
        }
    }
}

impl From<std::io::Error> for Error {
    fn from(e: std::io::Error) -> Error {
        Error::Failed(e.to_string())
    }
}

impl From<std::convert::Infallible> for Error {
    fn from(e: std::convert::Infallible) -> Error {
        match e {}
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
