//! Files we read and write, with the care of a trusted command-line tool. One policy for
//! every file the program writes (`--out`, `--trajectory`, `--asciicast`, `--record`, the
//! explorer's `s` and `E`):
//! - never a file this command read (a scene, theme, key script or configuration, also a
//!   script redirected into stdin): compared by identity (device and inode, while the path
//!   read still names that file), not by spelling, so `../d/s.keys`, a hard link or a link to
//!   it are the same file; refused even with `--force`;
//! - never an existing file without `--force`, and never a file that appeared while the
//!   command ran (the explorer's save and export take the next free name instead);
//! - atomically: the bytes go to an unnamed temporary file (`O_TMPFILE`) in the destination's
//!   folder, linked into place at the end, so a reader never sees half a file, a failure
//!   leaves the old one intact, and a killed process (even by SIGKILL) leaves no temporary
//!   file behind. Where the filesystem has no unnamed files, a named one, `.NAME.PID.N.tmp`,
//!   stands in; it is removed on every error, and the next write of `NAME` removes those of
//!   processes no longer alive;
//! - a terminal or device such as /dev/null, and a FIFO that has a reader, is written in
//!   place (nothing is replaced); symbolic links, read-only files, directories and anything
//!   else are refused;
//! - input is read from regular files only, up to a size cap, and opening never blocks (a FIFO
//!   with no writer, /dev/zero and /dev/urandom are refused at once);
//! - an output a script drives is bounded ([`Capped`]);
//! - text echoed into a message has its control characters escaped.

use crate::error::Error;
use std::fs::{File, OpenOptions};
use std::io::{self, Read, Write};
use std::os::fd::AsRawFd;
use std::os::unix::fs::{FileTypeExt, MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

mod capped;
mod output;

pub use capped::{BoundReached, Capped, bound_reached, show_bytes};
pub use output::{
    Output, numbered, open_output, remove_stale, write_atomic, write_new, write_secret,
};

/// Largest scene, theme or key script read.
pub const READ_CAP: u64 = 1 << 20;

/// A file this process read: its identity, and the path it was read at (None: stdin, whose
/// open descriptor keeps its file, so its identity is never another's).
struct Input {
    dev: u64,
    ino: u64,
    path: Option<PathBuf>,
}

impl Input {
    /// How a message names it.
    fn shown(&self) -> String {
        self.path
            .as_ref()
            .map_or_else(|| "stdin".into(), |p| p.display().to_string())
    }

    /// Whether it is the file with this identity. A file removed after it was read frees its
    /// inode for the next file made: that one is not the input (the suite, one long process,
    /// once refused a new output as another test's deleted scene).
    fn is(&self, dev: u64, ino: u64) -> bool {
        (self.dev, self.ino) == (dev, ino)
            && self.path.as_ref().is_none_or(|p| {
                std::fs::metadata(p).is_ok_and(|m| (m.dev(), m.ino()) == (dev, ino))
            })
    }
}

/// Every regular file read so far: an output may not be one of them.
static INPUTS: Mutex<Vec<Input>> = Mutex::new(Vec::new());

/// Notes `file`, opened at `path` (None: stdin), as an input of this command (if it is a
/// regular file).
fn note_input(file: &impl std::os::fd::AsFd, path: Option<&Path>) {
    let Ok(st) = rustix::fs::fstat(file) else {
        return;
    };
    if rustix::fs::FileType::from_raw_mode(st.st_mode) != rustix::fs::FileType::RegularFile {
        return;
    }
    let (dev, ino) = (st.st_dev, st.st_ino);
    let mut inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
    // Kept while it is that file; a removed input's identity is another's to take.
    inputs.retain(|i| i.is(i.dev, i.ino));
    if !inputs.iter().any(|i| i.is(dev, ino)) {
        inputs.push(Input {
            dev,
            ino,
            path: path.map(Path::to_path_buf),
        });
    }
}

/// How an input with this identity was named, if the command read one.
fn input_named(m: &std::fs::Metadata) -> Option<String> {
    let inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
    inputs
        .iter()
        .find(|i| i.is(m.dev(), m.ino()))
        .map(Input::shown)
}

/// A path as a message shows it.
fn shown(path: &Path) -> String {
    escape_controls(&path.display().to_string())
}

/// Stdout, or a file written as [`Output`] does (never over an existing file).
pub fn emit(out: Option<&Path>, text: &str) -> io::Result<()> {
    match out {
        Some(p) => write_atomic(p, text.as_bytes(), false),
        None => {
            let mut so = io::stdout().lock();
            match so.write_all(text.as_bytes()).and_then(|()| so.flush()) {
                // The reader stopped reading (`| head`): what it took is what it wanted.
                Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
                r => r,
            }
        }
    }
}

/// Reads a regular file of at most `cap` bytes as UTF-8, and notes it as an input of this
/// command (no output may replace it). Errors name the file.
pub fn read_bounded(path: &Path, cap: u64) -> Result<String, Error> {
    let name = escape_controls(&path.display().to_string());
    let refuse = |e: String| Error::invalid(format!("{name}: {e}"));
    let f = OpenOptions::new()
        .read(true)
        .custom_flags(open_flags(rustix::fs::OFlags::NONBLOCK))
        .open(path)
        .map_err(|e| refuse(e.to_string()))?;
    let m = f.metadata().map_err(|e| refuse(e.to_string()))?;
    if !m.is_file() {
        return Err(refuse("not a regular file".into()));
    }
    note_input(&f, Some(path));
    read_capped(f, cap).map_err(|e| e.context(&name))
}

/// Reads stdin as [`read_capped`] does; a regular file redirected into it (`< s.keys`) is
/// noted as an input of this command.
pub fn read_stdin(cap: u64) -> Result<String, Error> {
    let stdin = io::stdin();
    note_input(&stdin, None);
    read_capped(stdin.lock(), cap)
}
/// Reads at most `cap` bytes of UTF-8 from `r`; more is an error.
pub fn read_capped(r: impl Read, cap: u64) -> Result<String, Error> {
    let mut bytes = Vec::new();
    r.take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::invalid(e.to_string()))?;
    if bytes.len() as u64 > cap {
        return Err(Error::invalid(format!("larger than {} KiB", cap >> 10)));
    }
    String::from_utf8(bytes).map_err(|_| Error::invalid("not UTF-8 text"))
}

/// A TOML parse error as "line L: problem", L counted from 1 at the error's start.
pub fn toml_error(text: &str, e: &toml::de::Error) -> String {
    let problem = e.message().trim().replace('\n', " ");
    match e.span() {
        Some(span) if span != (0..0) => {
            let line = text.as_bytes()[..span.start.min(text.len())]
                .iter()
                .filter(|&&b| b == b'\n')
                .count()
                + 1;
            format!("line {line}: {problem}")
        }
        _ => problem,
    }
}

/// `text` with control characters (C0, DEL, C1) and invisible marks (a byte-order mark, bidi
/// overrides: `crate::text::needs_escape`) shown as `\u{..}` escapes, so that a file name or a
/// script cannot move the cursor or retitle the terminal through a message, nor hide in it.
pub fn escape_controls(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if crate::text::needs_escape(c) && c != '\n' {
            out.push_str(&c.escape_unicode().to_string());
        } else {
            out.push(c);
        }
    }
    out
}

/// rustix's open flags as `OpenOptionsExt::custom_flags` takes them (a C `int`).
fn open_flags(flags: rustix::fs::OFlags) -> i32 {
    flags.bits() as i32
}

#[cfg(test)]
mod tests {
    use super::output::at;
    use super::*;

    /// Read, it is an input; removed, its inode is free for the next file made, which is not.
    #[test]
    fn a_removed_input_is_no_longer_one() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("scene.toml");
        std::fs::write(&p, "x").unwrap();
        read_bounded(&p, 10).unwrap();
        let m = std::fs::metadata(&p).unwrap();
        assert_eq!(input_named(&m), Some(p.display().to_string()));
        std::fs::remove_file(&p).unwrap();
        assert_eq!(input_named(&m), None);
    }

    #[test]
    fn controls_are_escaped() {
        assert_eq!(escape_controls("a\x1b]0;x\x07b"), "a\\u{1b}]0;x\\u{7}b");
        assert_eq!(escape_controls("ξ = 1\nnext\u{9b}"), "ξ = 1\nnext\\u{9b}");
    }

    #[test]
    fn caps() {
        assert_eq!(read_capped(&b"abc"[..], 3).unwrap(), "abc");
        assert!(read_capped(&b"abcd"[..], 3).is_err());
        // An error met at a path keeps its kind and its cause, and says the path.
        let cause = io::Error::from(io::ErrorKind::PermissionDenied);
        let e = at(Path::new("a/b.csv"), cause);
        assert_eq!(e.kind(), io::ErrorKind::PermissionDenied);
        assert_eq!(e.to_string(), "a/b.csv: permission denied");
        let inner = e.get_ref().and_then(std::error::Error::source);
        assert!(inner.is_some_and(|c| c.is::<io::Error>()));
        let bound = io::Error::other(BoundReached {
            message: "the cap".into(),
        });
        assert_eq!(
            bound_reached(&at(Path::new("x"), bound)).as_deref(),
            Some("the cap")
        );
        assert!(read_capped(&[0xff][..], 3).is_err());
    }
}
