//! Files we read and write, with the care of a trusted command-line tool:
//! - output replaces a regular file atomically (a random, exclusively created temporary
//!   sibling renamed into place, so a reader never sees half a file and a failure leaves the
//!   old one intact), writes straight into a terminal or device such as /dev/null and into a
//!   FIFO that has a reader, and refuses symbolic links, read-only files, directories and
//!   anything else;
//! - input is read from regular files only, up to a size cap, and opening never blocks (a FIFO
//!   with no writer, /dev/zero and /dev/urandom are refused at once);
//! - text echoed into a message has its control characters escaped.

use crate::error::Error;
use std::fs::{File, OpenOptions};
use std::io::{self, Read, Write};
use std::os::unix::fs::{FileTypeExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use tempfile::NamedTempFile;

/// Largest scene, theme or key script read.
pub const READ_CAP: u64 = 1 << 20;

/// An output file being written: see [`Output::create`]. Dropped without [`Output::finish`],
/// it leaves the destination as it was.
pub enum Output {
    /// A temporary sibling, renamed over `dest` on finish.
    Replace { tmp: NamedTempFile, dest: PathBuf },
    /// A terminal, device or FIFO, written in place.
    Direct(File),
}

fn err(path: &Path, what: impl std::fmt::Display) -> io::Error {
    io::Error::other(format!(
        "{}: {what}",
        escape_controls(&path.display().to_string())
    ))
}

impl Output {
    /// Opens `dest` for writing, or says why it will not. Call it before computing what to
    /// write, so bad paths fail at once.
    pub fn create(dest: &Path) -> io::Result<Output> {
        let name = dest
            .file_name()
            .ok_or_else(|| err(dest, "not a file name"))?;
        let dir = match dest.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let mode = match std::fs::symlink_metadata(dest) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => 0o644,
            Err(e) => return Err(err(dest, e)),
            Ok(m) => {
                let t = m.file_type();
                if t.is_symlink() {
                    return Err(err(
                        dest,
                        "is a symbolic link; not following it (name its target)",
                    ));
                } else if t.is_dir() {
                    return Err(err(dest, "is a directory"));
                } else if t.is_char_device() || t.is_fifo() {
                    // O_NONBLOCK: a FIFO with no reader fails (ENXIO) instead of hanging.
                    let f = OpenOptions::new()
                        .write(true)
                        .custom_flags(libc::O_NONBLOCK)
                        .open(dest)
                        .map_err(|e| match e.raw_os_error() {
                            Some(libc::ENXIO) => err(dest, "a FIFO with no reader"),
                            _ => err(dest, e),
                        })?;
                    clear_nonblock(&f);
                    return Ok(Output::Direct(f));
                } else if !t.is_file() {
                    return Err(err(dest, "not a regular file, terminal, device or FIFO"));
                } else if m.permissions().readonly() {
                    return Err(err(dest, "is read-only; not replacing it"));
                }
                m.permissions().mode() & 0o7777
            }
        };
        let tmp = tempfile::Builder::new()
            .prefix(&format!(".{}.", name.to_string_lossy()))
            .suffix(".tmp")
            .tempfile_in(dir)
            .map_err(|e| err(dest, e))?;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(mode))
            .map_err(|e| err(dest, e))?;
        Ok(Output::Replace {
            tmp,
            dest: dest.to_path_buf(),
        })
    }

    /// Puts the file in place.
    pub fn finish(self) -> io::Result<()> {
        match self {
            Output::Replace { tmp, dest } => {
                tmp.as_file().sync_all().map_err(|e| err(&dest, e))?;
                tmp.persist(&dest).map_err(|e| err(&dest, e.error))?;
                Ok(())
            }
            Output::Direct(mut f) => f.flush(),
        }
    }

    /// Puts the file in place unless something already stands at the destination.
    pub fn finish_new(self) -> io::Result<()> {
        match self {
            Output::Replace { tmp, dest } => {
                tmp.as_file().sync_all().map_err(|e| err(&dest, e))?;
                // Keeps the kind: a caller tries the next name on AlreadyExists.
                tmp.persist_noclobber(&dest).map_err(|e| {
                    let kind = e.error.kind();
                    io::Error::new(kind, err(&dest, e.error))
                })?;
                Ok(())
            }
            Output::Direct(_) => Err(io::Error::from(io::ErrorKind::AlreadyExists)),
        }
    }
}

/// Writes to a device or FIFO block as usual once it is open.
fn clear_nonblock(f: &File) {
    use rustix::fs::{OFlags, fcntl_getfl, fcntl_setfl};
    if let Ok(flags) = fcntl_getfl(f) {
        let _ = fcntl_setfl(f, flags - OFlags::NONBLOCK);
    }
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Output::Replace { tmp, .. } => tmp.write(buf),
            Output::Direct(f) => f.write(buf),
        }
    }
    fn flush(&mut self) -> io::Result<()> {
        match self {
            Output::Replace { tmp, .. } => tmp.flush(),
            Output::Direct(f) => f.flush(),
        }
    }
}

/// `path` itself for n = 1, else `NAME-n.EXT`: the names tried, in turn, for a new file.
pub fn numbered(path: &Path, n: u32) -> PathBuf {
    if n == 1 {
        return path.to_path_buf();
    }
    let stem = path
        .file_stem()
        .map_or("file".into(), |s| s.to_string_lossy());
    path.with_file_name(match path.extension() {
        Some(e) => format!("{stem}-{n}.{}", e.to_string_lossy()),
        None => format!("{stem}-{n}"),
    })
}

/// Writes `contents` to `path` as [`Output`] does.
pub fn write_atomic(path: &Path, contents: &[u8]) -> io::Result<()> {
    let mut out = Output::create(path)?;
    out.write_all(contents).map_err(|e| err(path, e))?;
    out.finish()
}

/// Stdout, or a file written as [`Output`] does.
pub fn emit(out: Option<&Path>, text: &str) -> io::Result<()> {
    match out {
        Some(p) => write_atomic(p, text.as_bytes()),
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

/// Reads a regular file of at most `cap` bytes as UTF-8. Errors name the file.
pub fn read_bounded(path: &Path, cap: u64) -> Result<String, Error> {
    let name = escape_controls(&path.display().to_string());
    let refuse = |e: String| Error::Invalid(format!("{name}: {e}"));
    let f = OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map_err(|e| refuse(e.to_string()))?;
    let m = f.metadata().map_err(|e| refuse(e.to_string()))?;
    if !m.is_file() {
        return Err(refuse("not a regular file".into()));
    }
    read_capped(f, cap).map_err(|e| e.context(&name))
}

/// Reads at most `cap` bytes of UTF-8 from `r`; more is an error.
pub fn read_capped(r: impl Read, cap: u64) -> Result<String, Error> {
    let mut bytes = Vec::new();
    r.take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::Invalid(e.to_string()))?;
    if bytes.len() as u64 > cap {
        return Err(Error::Invalid(format!("larger than {} KiB", cap >> 10)));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controls_are_escaped() {
        assert_eq!(escape_controls("a\x1b]0;x\x07b"), "a\\u{1b}]0;x\\u{7}b");
        assert_eq!(escape_controls("ξ = 1\nnext\u{9b}"), "ξ = 1\nnext\\u{9b}");
    }

    #[test]
    fn caps() {
        assert_eq!(read_capped(&b"abc"[..], 3).unwrap(), "abc");
        assert!(read_capped(&b"abcd"[..], 3).is_err());
        assert!(read_capped(&[0xff][..], 3).is_err());
    }
}
