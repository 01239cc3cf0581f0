//! Files we read and write, with the care of a trusted command-line tool. One policy for
//! every file the program writes (`--out`, `--trajectory`, `--asciicast`, `--record`, the
//! explorer's `s` and `E`):
//! - never a file this command read (a scene, theme, key script or configuration, also a
//!   script redirected into stdin): compared by identity (device and inode), not by
//!   spelling, so `../d/s.keys`, a hard link or a link to it are the same file; refused even
//!   with `--force`;
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

/// Largest scene, theme or key script read.
pub const READ_CAP: u64 = 1 << 20;

/// A file this process read: its identity, and how it was named.
struct Input {
    dev: u64,
    ino: u64,
    shown: String,
}

/// Every regular file read so far: an output may not be one of them.
static INPUTS: Mutex<Vec<Input>> = Mutex::new(Vec::new());

/// Notes `file`, opened as `shown`, as an input of this command (if it is a regular file).
fn note_input(file: &impl std::os::fd::AsFd, shown: &str) {
    let Ok(st) = rustix::fs::fstat(file) else {
        return;
    };
    if rustix::fs::FileType::from_raw_mode(st.st_mode) != rustix::fs::FileType::RegularFile {
        return;
    }
    let (dev, ino) = (st.st_dev, st.st_ino);
    let mut inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
    if !inputs.iter().any(|i| (i.dev, i.ino) == (dev, ino)) {
        inputs.push(Input {
            dev,
            ino,
            shown: shown.to_string(),
        });
    }
}

/// How an input with this identity was named, if the command read one.
fn input_named(m: &std::fs::Metadata) -> Option<String> {
    let inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
    inputs
        .iter()
        .find(|i| (i.dev, i.ino) == (m.dev(), m.ino()))
        .map(|i| i.shown.clone())
}

/// An output file being written: see [`Output::create`]. Dropped without [`Output::finish`],
/// it leaves the destination as it was, and no temporary file.
pub struct Output {
    to: To,
    dest: PathBuf,
    /// `--force` was given and a file stood at `dest`: finishing replaces it.
    replace: bool,
    /// Put in place: no temporary left to remove.
    placed: bool,
}

enum To {
    /// An unnamed file in the destination's folder (`O_TMPFILE`), linked in on finish.
    Unnamed(File),
    /// A named temporary sibling (filesystems without unnamed files), removed on drop.
    Named(File, PathBuf),
    /// A terminal, device or FIFO, written in place.
    Direct(File),
}

impl Drop for Output {
    fn drop(&mut self) {
        if let (To::Named(_, tmp), false) = (&self.to, self.placed) {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

fn err(path: &Path, what: impl std::fmt::Display) -> io::Error {
    io::Error::other(format!("{}: {what}", shown(path)))
}

/// `e` met at `path`: the same kind, said with the path, `e` kept as the source.
fn at(path: &Path, e: io::Error) -> io::Error {
    io::Error::new(
        e.kind(),
        AtPath {
            path: shown(path),
            source: e,
        },
    )
}

/// An `io::Error` and the path it was met at.
#[derive(Debug)]
struct AtPath {
    path: String,
    source: io::Error,
}

impl std::fmt::Display for AtPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.path, self.source)
    }
}

impl std::error::Error for AtPath {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.source)
    }
}

fn err_kind(kind: io::ErrorKind, path: &Path, what: impl std::fmt::Display) -> io::Error {
    io::Error::new(kind, format!("{}: {what}", shown(path)))
}

/// A path as a message shows it.
fn shown(path: &Path) -> String {
    escape_controls(&path.display().to_string())
}

/// The folder a path's file is in.
fn folder(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// Temporary names made by this process, counted so that each is new.
static TMP_SERIAL: AtomicU64 = AtomicU64::new(0);

/// A fresh temporary name beside `dest`: `.NAME.PID.N.tmp`.
fn tmp_name(dir: &Path, name: &str) -> PathBuf {
    let n = TMP_SERIAL.fetch_add(1, Ordering::Relaxed);
    dir.join(format!(".{name}.{}.{n}.tmp", std::process::id()))
}

/// Removes the `.NAME.PID.N.tmp` files in `dir` whose process is gone (killed while
/// writing). Returns how many.
pub fn remove_stale(dir: &Path, name: &str) -> usize {
    let prefix = format!(".{name}.");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    let mut removed = 0;
    for e in entries.flatten() {
        let file = e.file_name();
        let Some((pid, serial)) = file
            .to_str()
            .and_then(|f| f.strip_prefix(&prefix))
            .and_then(|r| r.strip_suffix(".tmp"))
            .and_then(|r| r.split_once('.'))
        else {
            continue;
        };
        let (Ok(pid), Ok(_)) = (pid.parse::<i32>(), serial.parse::<u64>()) else {
            continue;
        };
        if !alive(pid)
            && e.file_type().is_ok_and(|t| t.is_file())
            && std::fs::remove_file(e.path()).is_ok()
        {
            removed += 1;
        }
    }
    removed
}

/// Whether process `pid` exists.
fn alive(pid: i32) -> bool {
    rustix::process::Pid::from_raw(pid).is_some_and(|p| {
        !matches!(
            rustix::process::test_kill_process(p),
            Err(rustix::io::Errno::SRCH)
        )
    })
}

/// Opens `path` for the output named by `flag` (`--out`, `--record`, …) under the policy
/// above: a refusal is input refused (exit 2) and names the flag.
pub fn open_output(flag: &str, path: &Path, force: bool) -> Result<Output, Error> {
    Output::create(path, force).map_err(|e| Error::Invalid(format!("{flag} {e}")))
}

impl Output {
    /// Opens `dest` for writing under the policy above, or says why it will not (with
    /// `force`, an existing regular file that is not an input will be replaced). Call it
    /// before computing what to write, so bad paths fail at once.
    pub fn create(dest: &Path, force: bool) -> io::Result<Output> {
        Self::create_in(dest, force, true)
    }

    /// As [`Output::create`]; with `unnamed` false, always through a named temporary file
    /// (as on a filesystem without `O_TMPFILE`).
    #[doc(hidden)]
    pub fn create_in(dest: &Path, force: bool, unnamed: bool) -> io::Result<Output> {
        let name = dest
            .file_name()
            .ok_or_else(|| err(dest, "not a file name"))?
            .to_string_lossy()
            .into_owned();
        let dir = folder(dest);
        let (mode, existed) = match std::fs::symlink_metadata(dest) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => (0o644, false),
            Err(e) => return Err(at(dest, e)),
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
                            _ => at(dest, e),
                        })?;
                    clear_nonblock(&f);
                    return Ok(Output {
                        to: To::Direct(f),
                        dest: dest.to_path_buf(),
                        replace: false,
                        placed: false,
                    });
                } else if !t.is_file() {
                    return Err(err(dest, "not a regular file, terminal, device or FIFO"));
                } else if let Some(input) = input_named(&m) {
                    let same = if Path::new(&input) == dest {
                        String::new()
                    } else {
                        format!(" (as {})", escape_controls(&input))
                    };
                    return Err(err_kind(
                        io::ErrorKind::InvalidInput,
                        dest,
                        format!(
                            "is a file this command reads{same}; name another (--force never replaces an input)"
                        ),
                    ));
                } else if !force {
                    return Err(err_kind(
                        io::ErrorKind::AlreadyExists,
                        dest,
                        "exists; --force replaces it",
                    ));
                } else if m.permissions().readonly() {
                    return Err(err(dest, "is read-only; not replacing it"));
                }
                (m.permissions().mode() & 0o7777, true)
            }
        };
        remove_stale(dir, &name);
        let to = match unnamed.then(|| open_unnamed(dir)).flatten() {
            Some(Ok(f)) => To::Unnamed(f),
            Some(Err(e)) => return Err(at(dest, e)),
            None => {
                let (f, tmp) = open_named(dir, &name).map_err(|e| at(dest, e))?;
                To::Named(f, tmp)
            }
        };
        let out = Output {
            to,
            dest: dest.to_path_buf(),
            replace: force && existed,
            placed: false,
        };
        out.file()
            .set_permissions(std::fs::Permissions::from_mode(mode))
            .map_err(|e| at(dest, e))?;
        Ok(out)
    }

    fn file(&self) -> &File {
        match &self.to {
            To::Unnamed(f) | To::Named(f, _) | To::Direct(f) => f,
        }
    }

    fn file_mut(&mut self) -> &mut File {
        match &mut self.to {
            To::Unnamed(f) | To::Named(f, _) | To::Direct(f) => f,
        }
    }

    /// Where this output goes.
    pub fn dest(&self) -> &Path {
        &self.dest
    }

    /// Whether this output is written in place (a terminal, device or FIFO): nothing to put
    /// in place at the end.
    pub fn is_direct(&self) -> bool {
        matches!(self.to, To::Direct(_))
    }

    /// Puts the file in place: over the file that stood there with `--force`, else only
    /// where nothing stands (a file that appeared meanwhile is kept: `AlreadyExists`).
    pub fn finish(mut self) -> io::Result<()> {
        let dest = self.dest.clone();
        let replace = self.replace;
        self.place(&dest, replace)
    }

    /// Puts the file in place as [`Output::finish`] does, or, if a file appeared there
    /// meanwhile, at the first free `NAME-N` (N up to `max`). Returns where.
    pub fn finish_numbered(mut self, max: u32) -> io::Result<PathBuf> {
        let dest = self.dest.clone();
        if self.is_direct() || self.replace {
            let replace = self.replace;
            return self.place(&dest, replace).map(|()| dest);
        }
        for n in 1..=max {
            let to = numbered(&dest, n);
            match self.place(&to, false) {
                Ok(()) => return Ok(to),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(e),
            }
        }
        Err(err(
            &dest,
            format!(
                "this name and the {} numbered ones after it are taken",
                max.saturating_sub(1)
            ),
        ))
    }

    /// Links the written file in at `to`: replacing what stands there if `replace`, else
    /// only if nothing does (`AlreadyExists` otherwise).
    fn place(&mut self, to: &Path, replace: bool) -> io::Result<()> {
        {
            let f = self.file_mut();
            f.flush().map_err(|e| at(to, e))?;
            if let To::Direct(_) = self.to {
                return Ok(());
            }
        }
        self.file().sync_all().map_err(|e| at(to, e))?;
        let from = match &self.to {
            To::Unnamed(f) => PathBuf::from(format!("/proc/self/fd/{}", f.as_raw_fd())),
            To::Named(_, tmp) => tmp.clone(),
            To::Direct(_) => return Ok(()),
        };
        let link = |at: &Path| {
            rustix::fs::linkat(
                rustix::fs::CWD,
                &from,
                rustix::fs::CWD,
                at,
                rustix::fs::AtFlags::SYMLINK_FOLLOW,
            )
            .map_err(io::Error::from)
        };
        let name = to
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        if replace {
            // Under a temporary name first, then renamed over the old file in one step.
            let tmp = match &self.to {
                To::Named(_, own) => own.clone(),
                _ => loop {
                    let tmp = tmp_name(folder(to), &name);
                    match link(&tmp) {
                        Ok(()) => break tmp,
                        Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                        Err(e) => return Err(at(to, e)),
                    }
                },
            };
            if let Err(e) = std::fs::rename(&tmp, to) {
                if let To::Unnamed(_) = self.to {
                    let _ = std::fs::remove_file(&tmp);
                }
                return Err(at(to, e));
            }
        } else {
            link(to).map_err(|e| at(to, e))?;
            if let To::Named(_, tmp) = &self.to {
                let _ = std::fs::remove_file(tmp);
            }
        }
        self.placed = true;
        Ok(())
    }
}

/// An unnamed file in `dir`, where the filesystem has them (`None` where it has not, or
/// where /proc, through which it is linked in, is missing).
fn open_unnamed(dir: &Path) -> Option<io::Result<File>> {
    use rustix::fs::{Mode, OFlags};
    if !Path::new("/proc/self/fd").is_dir() {
        return None;
    }
    match rustix::fs::open(
        dir,
        OFlags::TMPFILE | OFlags::WRONLY | OFlags::CLOEXEC,
        Mode::from_raw_mode(0o600),
    ) {
        Ok(fd) => Some(Ok(File::from(fd))),
        Err(rustix::io::Errno::OPNOTSUPP | rustix::io::Errno::ISDIR | rustix::io::Errno::INVAL) => {
            None
        }
        Err(e) => Some(Err(e.into())),
    }
}

/// A new named temporary file beside the destination, `.NAME.PID.N.tmp`: created
/// exclusively, never through a planted link.
fn open_named(dir: &Path, name: &str) -> io::Result<(File, PathBuf)> {
    for _ in 0..1000 {
        let tmp = tmp_name(dir, name);
        match OpenOptions::new()
            .write(true)
            .create_new(true)
            .mode(0o600)
            .custom_flags(libc::O_NOFOLLOW | libc::O_CLOEXEC)
            .open(&tmp)
        {
            Ok(f) => return Ok((f, tmp)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(io::Error::other("no free temporary name"))
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
        self.file_mut().write(buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.file_mut().flush()
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

/// Writes `contents` to a new file at `path`, or the first free `NAME-N` after it (N up to
/// `max`), as [`Output`] does; never over a file. Returns where.
pub fn write_new(path: &Path, contents: &[u8], max: u32) -> io::Result<PathBuf> {
    for n in 1..=max {
        let to = numbered(path, n);
        if to.symlink_metadata().is_ok() {
            continue;
        }
        let mut out = match Output::create(&to, false) {
            Ok(out) => out,
            // Taken since the look above: the next name.
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        };
        out.write_all(contents).map_err(|e| at(&to, e))?;
        match out.finish() {
            Ok(()) => return Ok(to),
            // Taken meanwhile: the next name.
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(err(
        path,
        format!(
            "this name and the {} numbered ones after it are taken",
            max.saturating_sub(1)
        ),
    ))
}

/// Writes `contents` to `path` as [`Output`] does (replacing a file there only with `force`).
pub fn write_atomic(path: &Path, contents: &[u8], force: bool) -> io::Result<()> {
    let mut out = Output::create(path, force)?;
    out.write_all(contents).map_err(|e| at(path, e))?;
    out.finish()
}

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
    note_input(&f, &path.display().to_string());
    read_capped(f, cap).map_err(|e| e.context(&name))
}

/// Reads stdin as [`read_capped`] does; a regular file redirected into it (`< s.keys`) is
/// noted as an input of this command.
pub fn read_stdin(cap: u64) -> Result<String, Error> {
    let stdin = io::stdin();
    note_input(&stdin, "stdin");
    read_capped(stdin.lock(), cap)
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
