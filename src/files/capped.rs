//! The bound on outputs a script drives: a writer that passes at most so many bytes on, and
//! the error that says so.

use super::*;

/// The error a [`Capped`] writer returns when its bound is reached.
#[derive(Debug)]
pub struct BoundReached {
    /// What was bounded (`--asciicast`, `the replay's output`), and the bound in words.
    pub message: String,
}

impl std::fmt::Display for BoundReached {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for BoundReached {}

/// `cap` bytes as a reader would say them: `256 MiB`, `64 KiB`, `100 bytes`.
pub fn show_bytes(cap: u64) -> String {
    if cap >= 1 << 20 && cap.is_multiple_of(1 << 20) {
        format!("{} MiB", cap >> 20)
    } else if cap >= 1 << 10 && cap.is_multiple_of(1 << 10) {
        format!("{} KiB", cap >> 10)
    } else {
        format!("{cap} bytes")
    }
}

/// A writer that passes at most `cap` bytes on to `inner`: the write that would cross the
/// bound fails with a [`BoundReached`] naming `what` and the bound, and writes nothing.
pub struct Capped<W> {
    inner: W,
    written: u64,
    cap: u64,
    what: String,
}

impl<W: Write> Capped<W> {
    pub fn new(inner: W, cap: u64, what: impl Into<String>) -> Self {
        Capped {
            inner,
            written: 0,
            cap,
            what: what.into(),
        }
    }

    /// Bytes passed on so far.
    pub fn written(&self) -> u64 {
        self.written
    }

    pub fn get_ref(&self) -> &W {
        &self.inner
    }

    pub fn into_inner(self) -> W {
        self.inner
    }
}

impl<W: Write> Write for Capped<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if self.written + buf.len() as u64 > self.cap {
            return Err(io::Error::other(BoundReached {
                message: format!(
                    "{} reached its bound of {} ({} bytes)",
                    self.what,
                    show_bytes(self.cap),
                    self.cap
                ),
            }));
        }
        let n = self.inner.write(buf)?;
        self.written += n as u64;
        Ok(n)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// The bound an error reports having reached, if it is one ([`Capped`], or a frame count).
pub fn bound_reached(e: &io::Error) -> Option<String> {
    // Its own error, or the cause of one (an error met at a path keeps its source).
    let mut cause = e
        .get_ref()
        .map(|inner| inner as &(dyn std::error::Error + 'static));
    while let Some(c) = cause {
        if let Some(b) = c.downcast_ref::<BoundReached>() {
            return Some(b.message.clone());
        }
        // An io::Error's own source skips its payload: look inside it.
        cause = match c.downcast_ref::<io::Error>() {
            Some(io) => io
                .get_ref()
                .map(|inner| inner as &(dyn std::error::Error + 'static)),
            None => c.source(),
        };
    }
    None
}
