//! Every file thud writes (exports, `paper all`, saved designs, the config) and every settings or
//! design file it reads goes through this module, so each rule below holds everywhere:
//!
//! - **Never clobber.** A target that exists is refused unless the caller says
//!   [`Overwrite::Replace`] (`--force`); then it is replaced atomically by a rename, and a
//!   symbolic link at the target is replaced itself (its pointee is left alone).
//! - **Only regular files.** A target that is a directory, a device (`/dev/null`, `/dev/full`),
//!   a FIFO or a socket is refused even with `Replace`: a rename would swap a device node for a
//!   regular file.
//! - **No half-written file and no planted symlink.** The contents go to a temporary file in the
//!   target's folder first, written and synced, then linked into place. On Linux the temporary
//!   file has no name at all (`O_TMPFILE`): nothing can be planted at it and nothing is left
//!   behind even after `kill -9`. Elsewhere (or where the file system lacks `O_TMPFILE`) it has
//!   an unpredictable name created exclusively (`O_EXCL`, so a symlink there is never followed),
//!   removed on every error path and, through [`crate::signals`], on SIGINT/SIGTERM/SIGHUP.
//! - **Bounded reads.** Settings and designs are read only from regular files (a symlink to one
//!   is fine) of at most [`MAX_READ_BYTES`]; a FIFO is opened non-blocking and refused, so a
//!   read never hangs and never eats `/dev/zero`.
//!
//! Why hand-written around the crates it uses: `tempfile` gives the exclusive random names and
//! the no-clobber persist, `rustix` the `O_TMPFILE` open and `linkat` without `unsafe`, and
//! `signal-hook` the signal handling; but no crate puts them together with a refusal of
//! non-regular targets (`tempfile`'s `persist` and the atomic-write crates rename over a device
//! node), no-clobber as the default, and an anonymous temporary file that survives `kill -9`
//! without a trace. This module is that glue and nothing more.

use std::fmt;
use std::fs::{self, File, Permissions};
use std::io::{self, Read, Write};
use std::os::fd::AsRawFd;
use std::os::unix::fs::{FileTypeExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::time::Duration;

use rustix::fs::{AtFlags, Mode, OFlags, CWD};
use rustix::io::Errno;

use crate::signals;

/// The largest settings or design file read (1 MiB); a real one is a few hundred bytes.
pub const MAX_READ_BYTES: u64 = 1 << 20;

/// Set this environment variable to make every write use a named temporary file, as on a
/// system without `O_TMPFILE`: the tests use it to check that path too.
pub const NAMED_TEMPS_FOR_TEST: &str = "THUD_TEST_NAMED_TEMPS";

/// Set this environment variable to a number of milliseconds to hold each write with its
/// temporary file complete and not yet linked into place: the tests use it to send a signal
/// mid-write.
pub const HOLD_TEMP_FOR_TEST: &str = "THUD_TEST_HOLD_TEMP_MS";

/// What to do when the target of a write exists.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Overwrite {
    /// Refuse with [`FsError::Exists`] (the default everywhere).
    Refuse,
    /// Replace it atomically (`--force`, or the user confirmed).
    Replace,
}

impl Overwrite {
    /// `Replace` when `force`, else `Refuse`.
    #[must_use]
    pub fn from_force(force: bool) -> Self {
        if force {
            Overwrite::Replace
        } else {
            Overwrite::Refuse
        }
    }
}

/// What a path is when it is not a regular file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    Directory,
    Fifo,
    CharDevice,
    BlockDevice,
    Socket,
    /// Anything else that is not a regular file.
    Other,
}

impl FileKind {
    /// The kind of `t`, or `None` for a regular file (and for a symlink, which callers handle).
    fn of(t: fs::FileType) -> Option<FileKind> {
        if t.is_file() || t.is_symlink() {
            None
        } else if t.is_dir() {
            Some(FileKind::Directory)
        } else if t.is_fifo() {
            Some(FileKind::Fifo)
        } else if t.is_char_device() {
            Some(FileKind::CharDevice)
        } else if t.is_block_device() {
            Some(FileKind::BlockDevice)
        } else if t.is_socket() {
            Some(FileKind::Socket)
        } else {
            Some(FileKind::Other)
        }
    }
}

impl fmt::Display for FileKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FileKind::Directory => "a directory",
            FileKind::Fifo => "a FIFO",
            FileKind::CharDevice => "a character device",
            FileKind::BlockDevice => "a block device",
            FileKind::Socket => "a socket",
            FileKind::Other => "a special file",
        })
    }
}

/// A file that could not be read or written, and why. Each displays as `path: reason`.
#[derive(Debug, thiserror::Error)]
pub enum FsError {
    /// The target exists (a file or a symlink) and overwriting was not asked for.
    #[error("{}: already exists", .0.display())]
    Exists(PathBuf),
    /// The path is a directory, device, FIFO or socket: thud only reads and writes regular files.
    #[error("{}: is {kind}, not a regular file", path.display())]
    NotRegular { path: PathBuf, kind: FileKind },
    /// The file is larger than the read limit.
    #[error("{}: is larger than {limit_bytes} bytes", path.display())]
    TooLarge { path: PathBuf, limit_bytes: u64 },
    /// The operating system refused.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: io::Error,
    },
}

impl FsError {
    /// The path the error is about.
    #[must_use]
    pub fn path(&self) -> &Path {
        match self {
            FsError::Exists(path)
            | FsError::NotRegular { path, .. }
            | FsError::TooLarge { path, .. }
            | FsError::Io { path, .. } => path,
        }
    }

    /// The reason alone, without the path (for messages that name the path themselves).
    #[must_use]
    pub fn reason(&self) -> String {
        match self {
            FsError::Exists(_) => "already exists".into(),
            FsError::NotRegular { kind, .. } => format!("is {kind}, not a regular file"),
            FsError::TooLarge { limit_bytes, .. } => format!("is larger than {limit_bytes} bytes"),
            FsError::Io { source, .. } => source.to_string(),
        }
    }
}

fn io_at(path: &Path) -> impl FnOnce(io::Error) -> FsError + '_ {
    move |source| FsError::Io { path: path.to_path_buf(), source }
}

/// True for the `--out` value that means standard output.
#[must_use]
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// The folder a file `path` lives in (`.` for a bare name).
fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Checks that `path` may be written with `overwrite`: absent, or (with `Replace`) a regular
/// file or a symlink. Returns the permissions of a regular file that will be replaced, so the
/// new file keeps them. Callers that write several files check them all first with this.
pub fn check_target(path: &Path, overwrite: Overwrite) -> Result<Option<Permissions>, FsError> {
    let meta = match fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(io_at(path)(e)),
    };
    if let Some(kind) = FileKind::of(meta.file_type()) {
        return Err(FsError::NotRegular { path: path.to_path_buf(), kind });
    }
    match overwrite {
        Overwrite::Refuse => Err(FsError::Exists(path.to_path_buf())),
        Overwrite::Replace if meta.file_type().is_symlink() => Ok(None),
        Overwrite::Replace => Ok(Some(meta.permissions())),
    }
}

/// Writes `bytes` to `path` by the rules in the module doc: the target checked, the contents
/// written to a temporary file in its folder (created if missing), synced, then linked into
/// place without replacing anything (`Refuse`) or renamed over the target (`Replace`).
pub fn write(path: &Path, bytes: &[u8], overwrite: Overwrite) -> Result<(), FsError> {
    let (dir, permissions) = prepare(path, overwrite)?;
    if std::env::var_os(NAMED_TEMPS_FOR_TEST).is_none() {
        if let Some(file) = open_unnamed(&dir, path)? {
            write_unnamed(file, &dir, path, bytes, overwrite, permissions)?;
            sync_dir(&dir);
            return Ok(());
        }
    }
    write_named(&dir, path, bytes, overwrite, permissions, |_| Ok(()))
}

/// [`write()`] always through a named temporary file, with a seam: `before_link(temp_path)` runs
/// after the temporary file is written and synced and before it is moved into place. If it
/// fails the temporary file is removed, the target is untouched and the error is returned
/// (tests use it to simulate a crash there).
pub fn write_with(
    path: &Path,
    bytes: &[u8],
    overwrite: Overwrite,
    before_link: impl FnOnce(&Path) -> io::Result<()>,
) -> Result<(), FsError> {
    let (dir, permissions) = prepare(path, overwrite)?;
    write_named(&dir, path, bytes, overwrite, permissions, before_link)
}

/// Checks the target and creates its folder; the folder and the permissions to keep.
fn prepare(path: &Path, overwrite: Overwrite) -> Result<(PathBuf, Option<Permissions>), FsError> {
    let permissions = check_target(path, overwrite)?;
    let dir = parent_dir(path);
    fs::create_dir_all(&dir).map_err(io_at(path))?;
    Ok((dir, permissions))
}

/// An anonymous file in `dir` (`O_TMPFILE`), or `None` where that is not available (no
/// `/proc` to link it by, or a file system without it).
fn open_unnamed(dir: &Path, path: &Path) -> Result<Option<File>, FsError> {
    if !Path::new("/proc/self/fd").is_dir() {
        return Ok(None);
    }
    let flags = OFlags::WRONLY | OFlags::TMPFILE | OFlags::CLOEXEC;
    match rustix::fs::open(dir, flags, Mode::from_bits_truncate(0o666)) {
        Ok(fd) => Ok(Some(File::from(fd))),
        // The "not supported here" answers to O_TMPFILE (as in `tempfile`), plus EINVAL.
        Err(Errno::OPNOTSUPP | Errno::ISDIR | Errno::NOENT | Errno::INVAL) => Ok(None),
        Err(e) => Err(io_at(path)(e.into())),
    }
}

/// Fills the anonymous `file` and gives it the name `path`.
fn write_unnamed(
    mut file: File,
    dir: &Path,
    path: &Path,
    bytes: &[u8],
    overwrite: Overwrite,
    permissions: Option<Permissions>,
) -> Result<(), FsError> {
    fill(&mut file, bytes, permissions).map_err(io_at(path))?;
    hold_for_test();
    let by_fd = format!("/proc/self/fd/{}", file.as_raw_fd());
    let link = |to: &Path| rustix::fs::linkat(CWD, by_fd.as_str(), CWD, to, AtFlags::SYMLINK_FOLLOW);
    match overwrite {
        // linkat never replaces: whatever appeared at the target since the check stays.
        Overwrite::Refuse => link(path).map_err(|e| match e {
            Errno::EXIST => FsError::Exists(path.to_path_buf()),
            e => io_at(path)(e.into()),
        }),
        // No call links over an existing name: link under a fresh exclusive name, then rename.
        Overwrite::Replace => {
            let prefix = temp_prefix(path);
            let (named, _registration) = signals::guarded(|| {
                let named = tempfile::Builder::new()
                    .prefix(&prefix)
                    .suffix(".tmp")
                    .make_in(dir, |p| link(p).map_err(io::Error::from))?;
                let (registration, _) = remove_on_signal(named.path());
                Ok::<_, io::Error>((named, registration))
            })
            .map_err(io_at(path))?;
            named.persist(path).map(drop).map_err(|e| io_at(path)(e.error))
        }
    }
}

/// Writes through a named temporary file (removed on every error path and on signals).
fn write_named(
    dir: &Path,
    path: &Path,
    bytes: &[u8],
    overwrite: Overwrite,
    permissions: Option<Permissions>,
    before_link: impl FnOnce(&Path) -> io::Result<()>,
) -> Result<(), FsError> {
    let prefix = temp_prefix(path);
    // Created and registered with signals held off, so no signal falls between the two.
    let (mut temp, _registration) = signals::guarded(|| {
        let temp = tempfile::Builder::new()
            .prefix(&prefix)
            .suffix(".tmp")
            .permissions(Permissions::from_mode(0o666))
            .tempfile_in(dir)?;
        let (registration, _) = remove_on_signal(temp.path());
        Ok::<_, io::Error>((temp, registration))
    })
    .map_err(io_at(path))?;
    fill(temp.as_file_mut(), bytes, permissions).map_err(io_at(path))?;
    before_link(temp.path()).map_err(io_at(temp.path()))?;
    hold_for_test();
    let persisted = match overwrite {
        Overwrite::Refuse => temp.persist_noclobber(path),
        Overwrite::Replace => temp.persist(path),
    };
    persisted.map_err(|e| match e.error.kind() {
        io::ErrorKind::AlreadyExists => FsError::Exists(path.to_path_buf()),
        _ => io_at(path)(e.error),
    })?;
    sync_dir(dir);
    Ok(())
}

/// The prefix of temporary names `.NAME.XXXXXX.tmp` (six random characters follow; the name
/// is cut to 40 characters so the temporary name fits wherever the target's does).
fn temp_prefix(path: &Path) -> String {
    let name = path.file_name().map_or_else(|| "file".into(), |n| n.to_string_lossy().into_owned());
    format!(".{}.", name.chars().take(40).collect::<String>())
}

/// Removes `path` if a signal ends the process while the registration lives.
fn remove_on_signal(path: &Path) -> (signals::Registration, io::Result<()>) {
    let path = path.to_path_buf();
    signals::on_signal(move || {
        let _ = fs::remove_file(&path);
    })
}

/// Writes `bytes`, keeps `permissions` of the file being replaced, and syncs to disk.
fn fill(file: &mut File, bytes: &[u8], permissions: Option<Permissions>) -> io::Result<()> {
    file.write_all(bytes)?;
    if let Some(p) = permissions {
        file.set_permissions(p)?;
    }
    file.sync_all()
}

/// The test seam of [`HOLD_TEMP_FOR_TEST`].
fn hold_for_test() {
    if let Some(ms) = std::env::var(HOLD_TEMP_FOR_TEST).ok().and_then(|v| v.parse::<u64>().ok()) {
        std::thread::sleep(Duration::from_millis(ms));
    }
}

/// Makes a new name durable by syncing its directory (best effort; not possible everywhere).
fn sync_dir(dir: &Path) {
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
}

/// Reads `path` as UTF-8 text if it is a regular file (or a symlink to one) of at most
/// `limit_bytes`. The path is checked before it is opened (a device is never opened), opened
/// non-blocking (a FIFO swapped in meanwhile does not hang) and checked again on the open file.
pub fn read_to_string(path: &Path, limit_bytes: u64) -> Result<String, FsError> {
    check_readable(path, &fs::metadata(path).map_err(io_at(path))?, limit_bytes)?;
    let flags = OFlags::RDONLY | OFlags::NONBLOCK | OFlags::CLOEXEC | OFlags::NOCTTY;
    let file = File::from(rustix::fs::open(path, flags, Mode::empty()).map_err(|e| io_at(path)(e.into()))?);
    check_readable(path, &file.metadata().map_err(io_at(path))?, limit_bytes)?;
    let mut bytes = Vec::new();
    file.take(limit_bytes + 1).read_to_end(&mut bytes).map_err(io_at(path))?;
    if bytes.len() as u64 > limit_bytes {
        return Err(FsError::TooLarge { path: path.to_path_buf(), limit_bytes });
    }
    String::from_utf8(bytes).map_err(|e| io_at(path)(io::Error::new(io::ErrorKind::InvalidData, e)))
}

/// [`read_to_string`], with `Ok(None)` when nothing is at `path`.
pub fn read_optional(path: &Path, limit_bytes: u64) -> Result<Option<String>, FsError> {
    match read_to_string(path, limit_bytes) {
        Ok(s) => Ok(Some(s)),
        Err(FsError::Io { source, .. }) if source.kind() == io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(e),
    }
}

fn check_readable(path: &Path, meta: &fs::Metadata, limit_bytes: u64) -> Result<(), FsError> {
    if let Some(kind) = FileKind::of(meta.file_type()) {
        return Err(FsError::NotRegular { path: path.to_path_buf(), kind });
    }
    if meta.len() > limit_bytes {
        return Err(FsError::TooLarge { path: path.to_path_buf(), limit_bytes });
    }
    Ok(())
}

/// Writes `bytes` to standard output (`--out -`). A closed pipe (the reader went away, e.g.
/// `| head`) ends quietly; any other failure is returned.
pub fn write_stdout(bytes: &[u8]) -> io::Result<()> {
    let mut out = io::stdout().lock();
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leftovers(dir: &Path, keep: &[&str]) -> Vec<String> {
        fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| !keep.contains(&n.as_str()))
            .collect()
    }

    #[test]
    fn refuse_keeps_the_old_file_and_replace_swaps_it() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.csv");
        write(&p, b"one\n", Overwrite::Refuse).unwrap();
        assert!(matches!(write(&p, b"two\n", Overwrite::Refuse), Err(FsError::Exists(_))));
        assert_eq!(fs::read(&p).unwrap(), b"one\n");
        write(&p, b"two\n", Overwrite::Replace).unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"two\n");
        assert_eq!(leftovers(dir.path(), &["a.csv"]), Vec::<String>::new());
    }

    #[test]
    fn a_replaced_file_keeps_its_permissions() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("private.toml");
        fs::write(&p, "x").unwrap();
        fs::set_permissions(&p, Permissions::from_mode(0o600)).unwrap();
        write(&p, b"y", Overwrite::Replace).unwrap();
        assert_eq!(fs::metadata(&p).unwrap().permissions().mode() & 0o777, 0o600);
    }

    #[test]
    fn directories_are_refused_even_when_replacing() {
        let dir = tempfile::tempdir().unwrap();
        let sub = dir.path().join("sub");
        fs::create_dir(&sub).unwrap();
        for o in [Overwrite::Refuse, Overwrite::Replace] {
            match write(&sub, b"x", o) {
                Err(FsError::NotRegular { kind: FileKind::Directory, .. }) => {}
                other => panic!("{other:?}"),
            }
        }
        assert!(sub.is_dir());
    }

    #[test]
    fn reads_refuse_what_is_not_a_small_regular_file() {
        let dir = tempfile::tempdir().unwrap();
        let big = dir.path().join("big.toml");
        fs::write(&big, vec![b'#'; 101]).unwrap();
        assert!(matches!(read_to_string(&big, 100), Err(FsError::TooLarge { limit_bytes: 100, .. })));
        assert_eq!(read_to_string(&big, 101).unwrap().len(), 101);
        assert!(matches!(read_to_string(dir.path(), 100), Err(FsError::NotRegular { .. })));
        assert_eq!(read_optional(&dir.path().join("none"), 100).unwrap(), None);
        let link = dir.path().join("link.toml");
        std::os::unix::fs::symlink(&big, &link).unwrap();
        assert_eq!(read_to_string(&link, 200).unwrap().len(), 101, "a symlink to a regular file is read");
    }

    #[test]
    fn errors_name_the_path_and_the_reason() {
        let e = FsError::NotRegular { path: "/dev/null".into(), kind: FileKind::CharDevice };
        assert_eq!(e.to_string(), "/dev/null: is a character device, not a regular file");
        assert_eq!(e.reason(), "is a character device, not a regular file");
        assert_eq!(e.path(), Path::new("/dev/null"));
    }
}
