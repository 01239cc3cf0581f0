//! Writing a file under the policy (see the module above): [`Output`] opened, written and
//! linked into place; temporary files named, and those of dead processes removed; a new file
//! beside a taken name.

use super::*;
use rustix::fs::OFlags;
use rustix::io::Errno;

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
pub(super) fn at(path: &Path, e: io::Error) -> io::Error {
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
    Output::create(path, force).map_err(|e| Error::invalid(format!("{flag} {e}")))
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
                        .custom_flags(super::open_flags(OFlags::NONBLOCK))
                        .open(dest)
                        .map_err(|e| match e.raw_os_error() {
                            Some(e) if e == Errno::NXIO.raw_os_error() => {
                                err(dest, "a FIFO with no reader")
                            }
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
            .custom_flags(super::open_flags(OFlags::NOFOLLOW | OFlags::CLOEXEC))
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

/// Writes a secret (`serve`'s host key) to a new file at `path` that only its owner may read
/// (0600), in a folder made 0700 where missing; never over a file.
pub fn write_secret(path: &Path, contents: &[u8]) -> io::Result<()> {
    use std::os::unix::fs::DirBuilderExt;
    if let Some(dir) = path.parent() {
        std::fs::DirBuilder::new()
            .recursive(true)
            .mode(0o700)
            .create(dir)
            .map_err(|e| at(dir, e))?;
    }
    let mut out = Output::create(path, false)?;
    out.file()
        .set_permissions(std::fs::Permissions::from_mode(0o600))
        .map_err(|e| at(path, e))?;
    out.write_all(contents).map_err(|e| at(path, e))?;
    out.finish()
}

/// Writes `contents` to `path` as [`Output`] does (replacing a file there only with `force`).
pub fn write_atomic(path: &Path, contents: &[u8], force: bool) -> io::Result<()> {
    let mut out = Output::create(path, force)?;
    out.write_all(contents).map_err(|e| at(path, e))?;
    out.finish()
}
