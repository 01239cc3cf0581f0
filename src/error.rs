//! The crate's one error type. Callers branch on its kind, not its words: input refused
//! (the CLI exits 2) or work that could not be done (exit 1). The mapping to exit codes is
//! [`Error::exit_code`], and nowhere else.

use crate::engine::RunError;
use crate::engine::error::{Field, Invalid};
use std::sync::Arc;

#[derive(Debug, Clone)]
pub enum Error {
    /// Input refused (flags, initial conditions, settings, scene, theme and script files),
    /// with why; `value` is the value the engine refused, when that is why.
    Invalid { why: String, value: Option<Refused> },
    /// A run that could not finish: its step budget, or a step size that underflowed.
    Run(RunError),
    /// Anything else that could not be done: a solver that found no answer, a file that could
    /// not be written, a terminal that failed.
    Failed(String),
    /// An input or output that failed, with what was being done (`what` may be empty).
    Io {
        what: String,
        source: Arc<std::io::Error>,
    },
    /// Work stopped by its caller (an analysis page that is no longer wanted).
    Cancelled,
}

/// A value the engine refused, by field, value and range, kept beside the words that say so.
/// Until it is `named` as the user typed it (`--v0`, `[initial] v0`: see `crate::check`), the
/// words give the engine's own name.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Refused {
    pub value: Invalid,
    pub named: bool,
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Error::Invalid { why: m, .. } | Error::Failed(m) => f.write_str(m),
            Error::Run(r) => r.fmt(f),
            Error::Io { what, source } if what.is_empty() => source.fmt(f),
            Error::Io { what, source } => write!(f, "{what}: {source}"),
            Error::Cancelled => f.write_str("cancelled"),
        }
    }
}

/// The cause kept: the `io::Error` itself, the refused value, the run's error.
impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(&**source),
            Error::Invalid { value: Some(r), .. } => Some(&r.value),
            Error::Run(r) => Some(r),
            Error::Invalid { value: None, .. } | Error::Failed(_) | Error::Cancelled => None,
        }
    }
}

impl From<RunError> for Error {
    fn from(e: RunError) -> Error {
        Error::Run(e)
    }
}

impl PartialEq for Error {
    fn eq(&self, other: &Error) -> bool {
        use Error::*;
        match (self, other) {
            (Invalid { why: a, value: v }, Invalid { why: b, value: w }) => a == b && v == w,
            (Failed(a), Failed(b)) => a == b,
            (Run(a), Run(b)) => a == b,
            (Cancelled, Cancelled) => true,
            (Io { what: a, source: s }, Io { what: b, source: t }) => {
                a == b && s.kind() == t.kind() && s.to_string() == t.to_string()
            }
            _ => false,
        }
    }
}

impl Error {
    /// Input refused, with why.
    pub fn invalid(why: impl Into<String>) -> Error {
        Error::Invalid {
            why: why.into(),
            value: None,
        }
    }

    /// The value the engine refused, its words the engine's own until it is named.
    pub fn refused(value: Invalid) -> Error {
        Error::Invalid {
            why: value.to_string(),
            value: Some(Refused {
                value,
                named: false,
            }),
        }
    }

    /// `what` (a file, a terminal) failed with `e`, kept as the source.
    pub fn io(what: impl Into<String>, e: std::io::Error) -> Error {
        Error::Io {
            what: what.into(),
            source: Arc::new(e),
        }
    }

    /// The value the engine refused (its field, value and range), if this is one.
    pub fn refused_value(&self) -> Option<&Invalid> {
        match self {
            Error::Invalid { value: Some(r), .. } => Some(&r.value),
            _ => None,
        }
    }

    /// The same error with a refused `field` called `name` (as typed), unless it is already
    /// named.
    pub fn name_field(self, name: impl FnOnce(Field) -> String) -> Error {
        match self {
            Error::Invalid {
                value: Some(r @ Refused { named: false, .. }),
                ..
            } => Error::named(r.value, &name(r.value.field)),
            e => e,
        }
    }

    /// The value the engine refused, called `name` (as typed).
    pub fn named(value: Invalid, name: &str) -> Error {
        Error::Invalid {
            why: value.named(name),
            value: Some(Refused { value, named: true }),
        }
    }

    /// The same error with `what` (a flag, a file) in front of its message.
    pub fn context(self, what: &str) -> Error {
        match self {
            Error::Invalid { .. } => Error::invalid(format!("{what}: {self}")),
            Error::Io { what: w, source } => Error::Io {
                what: if w.is_empty() {
                    what.to_string()
                } else {
                    format!("{what}: {w}")
                },
                source,
            },
            e => Error::Failed(format!("{what}: {e}")),
        }
    }

    /// The process's exit code for this error: 2 for input refused, else 1.
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Invalid { .. } => 2,
            Error::Run(_) | Error::Failed(_) | Error::Io { .. } | Error::Cancelled => 1,
        }
    }
}

/// The engine's errors keep their kind: input refused stays refused (exit 2), a value refused
/// keeps its field and range until it is named as typed.
impl From<crate::engine::error::Error> for Error {
    fn from(e: crate::engine::error::Error) -> Error {
        use crate::engine::error::Error as E;
        match e {
            E::Invalid(value) => Error::refused(value),
            E::Refused(m) => Error::invalid(m),
            E::Run(r) => Error::Run(r),
            E::NoAnswer(m) => Error::Failed(m.into_owned()),
            E::Cancelled => Error::Cancelled,
        }
    }
}

impl From<std::io::Error> for Error {
    fn from(e: std::io::Error) -> Error {
        Error::io("", e)
    }
}

impl From<std::convert::Infallible> for Error {
    fn from(e: std::convert::Infallible) -> Error {
        match e {}
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::error::Range;

    #[test]
    fn an_io_error_is_kept_as_the_source() {
        let e = Error::io(
            "--out x.csv",
            std::io::Error::from(std::io::ErrorKind::PermissionDenied),
        );
        assert_eq!(e.to_string(), "--out x.csv: permission denied");
        let source = std::error::Error::source(&e).expect("a source");
        let io = source
            .downcast_ref::<std::io::Error>()
            .expect("an io::Error");
        assert_eq!(io.kind(), std::io::ErrorKind::PermissionDenied);
        assert_eq!(e.exit_code(), 1);
        let e = Error::from(std::io::Error::other("disk on fire")).context("scene.toml");
        assert_eq!(e.to_string(), "scene.toml: disk on fire");
        assert!(std::error::Error::source(&e).is_some());
    }

    #[test]
    fn a_refused_value_keeps_its_field_until_named() {
        let e: Error = crate::engine::Initial::velocity(-1.0, 0.0, 0.5)
            .validate()
            .unwrap_err()
            .into();
        let v = *e.refused_value().expect("a refused value");
        assert_eq!((v.field, v.value), (Field::Xi0, -1.0));
        assert_eq!(v.range, Range::AtLeast(0.0));
        assert_eq!(e.exit_code(), 2);
        assert_eq!(e.to_string(), "xi0 must be ≥ 0, got -1");
        let e = e.name_field(|f| format!("--{f}"));
        assert_eq!(e.to_string(), "--xi0 must be ≥ 0, got -1");
        assert_eq!(e.refused_value(), Some(&v));
        // Named once: a later name does not replace the one typed.
        let e = e.name_field(|_| "[initial] xi0".into());
        assert_eq!(e.to_string(), "--xi0 must be ≥ 0, got -1");
    }
}
