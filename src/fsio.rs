// Over 800 lines: every file rule (no clobber, no symlink, atomic writes) kept in one place, with its tests.
//! Every file thud writes (exports, sweep parts, merges, `paper all`, saved designs, the config)
//! and every settings, design or part file it reads goes through this module, so each rule below
//! holds everywhere:
//!
//! - **Never clobber.** A target that exists is refused unless the caller says
//!   [`Overwrite::Replace`] (`--force`); then a *regular file* there is replaced atomically.
//! - **Only a regular file is ever replaced.** A symbolic link, device, FIFO, socket or folder
//!   at the target is never replaced, with or without `--force`: it is written through when it
//!   is a stream ([`Sink`]: thud's own standard output — `-`, `/dev/stdout`, `/dev/fd/1` —, a
//!   terminal, a FIFO with a reader, `/dev/null`), and refused otherwise. A link that leads
//!   anywhere else (a file, a folder, nowhere) is refused: thud neither follows nor replaces it.
//!   The kind is checked when `--out` is read (before any work) and again on the file itself
//!   when it is written: a stream is opened without `O_CREAT`/`O_TRUNC` and checked with
//!   `fstat`; a replacement is an atomic exchange (`renameat2(RENAME_EXCHANGE)`) after which
//!   the replaced entry is inspected, and swapped back if it was not a regular file.
//! - **No half-written file and no planted symlink.** The contents go to a temporary file in the
//!   target's folder first, written and synced, then linked into place. On Linux a new file's
//!   temporary file has no name at all (`O_TMPFILE`, linked with `linkat(AT_EMPTY_PATH)` or
//!   through `/proc/self/fd`): nothing can be planted at it and nothing is left behind even
//!   after `kill -9`. Elsewhere (or where the file system lacks `O_TMPFILE`, or `--force` needs
//!   a name to exchange) it is a `tempfile` named `.NAME.thud-XXXXXX.tmp`, created exclusively
//!   (`O_EXCL`, so a symlink there is never followed), removed on every error path (its drop)
//!   and, through [`crate::signals`], on every signal that ends the process.
//! - **What `kill -9` leaves is removed by the next write.** A named temporary file is
//!   `flock`ed by its writer for its whole life. Each write first removes, from the folder it
//!   writes into, every `.*.thud-XXXXXX.tmp` regular file or folder whose lock is free and
//!   which is over a second old (its writer is gone); links and locked names are left alone.
//! - **Bounded reads.** Settings, designs and parts are read only from regular files (a symlink
//!   to one is fine) of at most a given size; a FIFO is opened non-blocking and refused, so a
//!   read never hangs and never eats `/dev/zero`.
//! - **Names are bytes.** Paths stay `Path`/`OsStr` end to end; [`shown`] renders one for a
//!   message with invalid UTF-8 as `\xNN` and control characters escaped.
//!
//! **What the crates carry.** `tempfile` carries the named temporary files and folders: random
//! names created with `O_EXCL` and the asked permissions, removed on every error path by their
//! drop (`NamedTempFile`, `TempDir`), published without replacing anything by
//! `persist_noclobber` (`renameat2(RENAME_NOREPLACE)` or link-then-unlink) and, where the file
//! system cannot exchange, over a regular file by `persist`. `rustix` carries `O_TMPFILE`,
//! `linkat`, `renameat2`, `flock` and `fstat` without `unsafe`; `signal-hook` the signals
//! ([`crate::signals`]). **Kept by hand**, each because no crate does it:
//! - the check of what is at the target, before the work and again on the file itself:
//!   `tempfile`'s `persist` and the atomic-write crates rename over a symlink or a device node,
//!   where thud replaces only a regular file, writes through a stream and refuses the rest;
//! - `--force` (a file, or `paper all`'s folder) as an exchange that is undone when the
//!   replaced entry may not be replaced (`exchange`);
//! - the anonymous file's `linkat` (`tempfile::tempfile` opens one but cannot name it), so a
//!   new file survives `kill -9` without a trace;
//! - the sweep of a killed run's names (by their `flock` and age), and the removal of the
//!   parent folders a failed write created ([`NewFolders`]: a full disk leaves none);
//! - bounded, non-blocking reads, and the escaped display of names that are bytes.

use std::ffi::OsString;
use std::fmt;
use std::fs::{self, File, Permissions};
use std::io::{self, Read, Write};
use std::os::fd::{AsFd, AsRawFd};
use std::os::unix::ffi::{OsStrExt, OsStringExt};
use std::os::unix::fs::{FileTypeExt, MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, SystemTime};

use rustix::fs::{AtFlags, FlockOperation, Mode, OFlags, RenameFlags, CWD};
use rustix::io::Errno;

use crate::signals;

/// The largest settings or design file read (1 MiB); a real one is a few hundred bytes.
pub const MAX_READ_BYTES: u64 = 1 << 20;

/// Set this environment variable to make every write use a named temporary file, as on a
/// system without `O_TMPFILE`: the tests use it to check that path too. Read only in a build
/// with the `test-hooks` feature (which the test suite turns on, through the package's
/// dev-dependency on itself): a release binary has no test hook.
pub const NAMED_TEMPS_FOR_TEST: &str = "THUD_TEST_NAMED_TEMPS";

/// Set this environment variable to a number of milliseconds to hold each write with its
/// temporary file complete and not yet linked into place: the tests use it to send a signal
/// mid-write. Read only with the `test-hooks` feature, as [`NAMED_TEMPS_FOR_TEST`].
pub const HOLD_TEMP_FOR_TEST: &str = "THUD_TEST_HOLD_TEMP_MS";

/// The marker of thud's temporary names: `.NAME` + this + six random characters + `.tmp`.
pub const TEMP_MARK: &str = ".thud-";

/// A temporary name whose lock is free is removed only once it is this old, so a file another
/// thud has just created (and not yet locked) is never taken for a leftover.
pub const STALE_AFTER: Duration = Duration::from_secs(1);

/// What to do when the target of a write exists.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Overwrite {
    /// Refuse with [`FsError::Exists`] (the default everywhere).
    Refuse,
    /// Replace a regular file atomically (`--force`, or the user confirmed).
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
    #[must_use]
    pub fn of(t: fs::FileType) -> Option<FileKind> {
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

/// A file that could not be read or written, and why. Each displays as `path: reason`, the
/// path [`shown`] (escaped, a very long one cut in its middle).
#[derive(Debug, thiserror::Error)]
pub enum FsError {
    /// The target exists (a regular file) and overwriting was not asked for.
    #[error("{}: already exists", shown(.0))]
    Exists(PathBuf),
    /// The path is a directory, device, FIFO or socket that is not written through.
    #[error("{}: is {kind}, not a regular file", shown(.path))]
    NotRegular { path: PathBuf, kind: FileKind },
    /// The path is a symbolic link that does not lead to a stream thud writes through.
    #[error("{}: is a symbolic link (thud neither follows nor replaces one)", shown(.0))]
    Link(PathBuf),
    /// The path is a FIFO nothing reads from (writing would block forever).
    #[error("{}: is a FIFO with no reader", shown(.0))]
    NoReader(PathBuf),
    /// What is at the path changed between the check and the write; nothing was replaced.
    #[error("{}: changed while it was being written; nothing was replaced", shown(.0))]
    Changed(PathBuf),
    /// The file is larger than the read limit.
    #[error("{}: is larger than {limit_bytes} bytes", shown(.path))]
    TooLarge { path: PathBuf, limit_bytes: u64 },
    /// The operating system refused.
    #[error("{}: {source}", shown(.path))]
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
            | FsError::Link(path)
            | FsError::NoReader(path)
            | FsError::Changed(path)
            | FsError::NotRegular { path, .. }
            | FsError::TooLarge { path, .. }
            | FsError::Io { path, .. } => path,
        }
    }

    /// The reason alone, without the path (for messages that name the path themselves).
    #[must_use]
    pub fn reason(&self) -> String {
        let full = self.to_string();
        let path = shown(self.path());
        full.strip_prefix(&format!("{path}: ")).map_or(full.clone(), str::to_string)
    }
}

fn io_at(path: &Path) -> impl FnOnce(io::Error) -> FsError + '_ {
    move |source| FsError::Io { path: path.to_path_buf(), source }
}

/// Longest path (in characters, after escaping) shown whole in a message; a longer one keeps
/// its start and its end around "…", so the reason after it is never cut away.
pub const MAX_SHOWN_CHARS: usize = 120;

/// `path` for a message: its bytes as UTF-8 where they are, every other byte as `\xNN`,
/// control characters escaped (so a name cannot start a second line), and a path longer than
/// [`MAX_SHOWN_CHARS`] cut in its middle.
#[must_use]
pub fn shown(path: &Path) -> String {
    let mut s = String::new();
    for chunk in path.as_os_str().as_bytes().utf8_chunks() {
        for c in chunk.valid().chars() {
            if c.is_control() {
                s.extend(c.escape_default());
            } else {
                s.push(c);
            }
        }
        for b in chunk.invalid() {
            s += &format!("\\x{b:02x}");
        }
    }
    let n = s.chars().count();
    if n <= MAX_SHOWN_CHARS {
        return s;
    }
    let head: String = s.chars().take(MAX_SHOWN_CHARS / 3).collect();
    let tail: String = s.chars().skip(n - (MAX_SHOWN_CHARS - MAX_SHOWN_CHARS / 3 - 1)).collect();
    format!("{head}…{tail}")
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

/// A stream a write goes through (see the module doc): never created, truncated or replaced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sink {
    /// thud's own standard output: `-`, or a path that is the very file of file descriptor 1.
    Stdout,
    /// A FIFO, a terminal or `/dev/null` at the path, opened for writing as it is; `link` when
    /// the path is a symbolic link to it (else it is opened with `O_NOFOLLOW`, so a link swapped
    /// in after the check is not followed).
    Stream { link: bool },
}

/// What a write to a path will do, decided from what is there now.
#[derive(Debug)]
pub enum Plan {
    /// Nothing is there: a new file is linked into place (never over anything).
    Create,
    /// A regular file is there and is replaced (`Replace`); the new file keeps these permissions.
    Replace(Permissions),
    /// A stream is there and is written through.
    Through(Sink),
}

/// Whether `meta` (links followed) is a terminal: a virtual console or serial line (major 4),
/// `/dev/tty` or the console (5,0 and 5,1), or a pseudo-terminal (136–143).
fn is_tty(meta: &fs::Metadata) -> bool {
    let (major, minor) = (rustix::fs::major(meta.rdev()), rustix::fs::minor(meta.rdev()));
    meta.file_type().is_char_device() && (major == 4 || (major == 5 && minor <= 1) || (136..=143).contains(&major))
}

/// Whether `path` (links followed) is a terminal (see `is_tty`).
#[must_use]
pub fn is_terminal(path: &Path) -> bool {
    fs::metadata(path).is_ok_and(|m| is_tty(&m))
}

/// Whether `meta` (of the file itself, links followed) is a stream thud writes through: a FIFO,
/// a terminal or `/dev/null` (1,3). Any other device (a disk, `/dev/mem`, a watchdog,
/// `/dev/full`…) is refused, never opened.
fn is_stream(meta: &fs::Metadata) -> bool {
    let null = meta.file_type().is_char_device() && meta.rdev() == rustix::fs::makedev(1, 3);
    meta.file_type().is_fifo() || null || is_tty(meta)
}

/// Whether `meta` is the file thud's standard output is.
fn is_own_stdout(meta: &fs::Metadata) -> bool {
    rustix::fs::fstat(io::stdout().as_fd()).is_ok_and(|s| s.st_dev == meta.dev() && s.st_ino == meta.ino())
}

/// What a write of `path` with `overwrite` will do (see the module doc), or why it may not
/// happen. Callers that write several files check them all first with this.
pub fn check_target(path: &Path, overwrite: Overwrite) -> Result<Plan, FsError> {
    if is_stdout(path) {
        return Ok(Plan::Through(Sink::Stdout));
    }
    let meta = match fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Plan::Create),
        Err(e) => return Err(io_at(path)(e)),
    };
    if meta.file_type().is_file() {
        return match overwrite {
            Overwrite::Refuse => Err(FsError::Exists(path.to_path_buf())),
            Overwrite::Replace => Ok(Plan::Replace(meta.permissions())),
        };
    }
    let link = meta.file_type().is_symlink();
    let target = if link { fs::metadata(path).map_err(|_| FsError::Link(path.to_path_buf()))? } else { meta };
    if is_own_stdout(&target) {
        Ok(Plan::Through(Sink::Stdout))
    } else if is_stream(&target) {
        Ok(Plan::Through(Sink::Stream { link }))
    } else if link {
        Err(FsError::Link(path.to_path_buf()))
    } else {
        let kind = FileKind::of(target.file_type()).unwrap_or(FileKind::Other);
        Err(FsError::NotRegular { path: path.to_path_buf(), kind })
    }
}

/// Writes `bytes` to `path` by the rules in the module doc: the target checked, a stream
/// written through, otherwise the contents written to a temporary file in its folder (created
/// if missing), synced, then linked into place without replacing anything (`Refuse`) or
/// exchanged with the regular file there (`Replace`).
pub fn write(path: &Path, bytes: &[u8], overwrite: Overwrite) -> Result<(), FsError> {
    write_via(path, bytes, overwrite, !named_temps_for_test(), |_| Ok(()))
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
    write_via(path, bytes, overwrite, false, before_link)
}

/// [`write()`] from a signal's clean-up ([`signals::on_signal`]), which may neither register a
/// clean-up nor enter a guarded step (the signal thread holds both locks): the target checked
/// as `write` checks it (a planted link refused, a stream written through, never replaced), the
/// contents written to a temporary file created new beside it (never through a link at its
/// name), then linked into place without replacing anything (`Refuse`) or renamed over the
/// regular file there (`Replace`). No folder is created; on an error the target is as it was
/// and the temporary file is gone.
pub fn write_from_cleanup(path: &Path, bytes: &[u8], overwrite: Overwrite) -> Result<(), FsError> {
    let permissions = match check_target(path, overwrite)? {
        Plan::Through(sink) => return write_through(path, sink, bytes),
        Plan::Create => None,
        Plan::Replace(p) => Some(p),
    };
    let prefix = temp_prefix(path);
    let mut temp = temp_builder(&prefix)
        .permissions(Permissions::from_mode(0o666))
        .tempfile_in(parent_dir(path))
        .map_err(io_at(path))?;
    rustix::fs::flock(temp.as_file(), FlockOperation::LockExclusive).map_err(|e| io_at(path)(e.into()))?;
    fill(temp.as_file_mut(), bytes, permissions).map_err(io_at(path))?;
    let regular = overwrite == Overwrite::Replace && fs::symlink_metadata(path).is_ok_and(|m| m.is_file());
    let placed = if regular { temp.persist(path) } else { temp.persist_noclobber(path) };
    placed.map_err(|e| match e.error.kind() {
        io::ErrorKind::AlreadyExists => FsError::Exists(path.to_path_buf()),
        _ => io_at(path)(e.error),
    })?;
    Ok(())
}

/// The body of [`write()`]: the folders it creates above the target are kept only if it
/// succeeds, thud's leftovers in the target's folder are removed first, and a new file
/// (`Refuse`) goes through an anonymous temporary file when `anonymous` and the file system
/// can name one, else (and always for `Replace`, which needs a name to exchange) a named one.
fn write_via(
    path: &Path,
    bytes: &[u8],
    overwrite: Overwrite,
    anonymous: bool,
    before_link: impl FnOnce(&Path) -> io::Result<()>,
) -> Result<(), FsError> {
    let permissions = match check_target(path, overwrite)? {
        Plan::Through(sink) => return write_through(path, sink, bytes),
        Plan::Create => None,
        Plan::Replace(p) => Some(p),
    };
    let dir = parent_dir(path);
    let new_folders = NewFolders::create(&dir).map_err(io_at(path))?;
    remove_stale_temps(&dir);
    let linked = anonymous && overwrite == Overwrite::Refuse && write_unnamed(&dir, path, bytes)?;
    if !linked {
        write_named(&dir, path, bytes, overwrite, permissions, before_link)?;
    }
    sync_dir(&dir);
    new_folders.keep();
    Ok(())
}

/// The folders a write created above its target: removed again — deepest first, each only if
/// still empty — when the write fails (a full disk, a refusal) or a signal ends the process;
/// kept by [`NewFolders::keep`] once the write succeeded. A folder that was there is never
/// touched.
#[derive(Debug)]
#[must_use = "the new folders are removed when this is dropped"]
pub struct NewFolders {
    made: Arc<Mutex<Vec<PathBuf>>>,
    _registration: Option<signals::Registration>,
}

impl NewFolders {
    /// Creates `dir` and every missing folder above it, as `create_dir_all` does, noting each
    /// one this call made.
    pub fn create(dir: &Path) -> io::Result<NewFolders> {
        // Any other failure to look stops the walk; `create_dir` then reports it.
        let missing: Vec<&Path> = dir
            .ancestors()
            .take_while(|d| {
                !d.as_os_str().is_empty() && fs::symlink_metadata(d).is_err_and(|e| e.kind() == io::ErrorKind::NotFound)
            })
            .collect();
        let made = Arc::new(Mutex::new(Vec::new()));
        if missing.is_empty() {
            return Ok(NewFolders { made, _registration: None });
        }
        signals::guarded(|| {
            let on_signal = made.clone();
            let registration = signals::on_signal(move || remove_empty(&on_signal)).0;
            let folders = NewFolders { made, _registration: Some(registration) };
            for d in missing.iter().rev() {
                match fs::create_dir(d) {
                    Ok(()) => folders.made.lock().unwrap_or_else(PoisonError::into_inner).insert(0, d.to_path_buf()),
                    Err(e) if e.kind() == io::ErrorKind::AlreadyExists && d.is_dir() => {}
                    Err(e) => return Err(e),
                }
            }
            Ok(folders)
        })
    }

    /// Keeps the new folders (the write succeeded).
    pub fn keep(self) {
        self.made.lock().unwrap_or_else(PoisonError::into_inner).clear();
    }
}

impl Drop for NewFolders {
    fn drop(&mut self) {
        signals::guarded(|| remove_empty(&self.made));
    }
}

/// Removes each folder of `dirs` (deepest first) that is empty.
fn remove_empty(dirs: &Mutex<Vec<PathBuf>>) {
    for d in dirs.lock().unwrap_or_else(PoisonError::into_inner).drain(..) {
        let _ = fs::remove_dir(d);
    }
}

/// Writes `bytes` through the stream at `path` (checked again on the opened file).
fn write_through(path: &Path, sink: Sink, bytes: &[u8]) -> Result<(), FsError> {
    let link = match sink {
        Sink::Stdout => return write_stdout(bytes).map_err(io_at(path)),
        Sink::Stream { link } => link,
    };
    let mut flags = OFlags::WRONLY | OFlags::NOCTTY | OFlags::CLOEXEC | OFlags::NONBLOCK;
    if !link {
        flags |= OFlags::NOFOLLOW;
    }
    let fd = rustix::fs::open(path, flags, Mode::empty()).map_err(|e| match e {
        Errno::NXIO => FsError::NoReader(path.to_path_buf()),
        Errno::LOOP => FsError::Changed(path.to_path_buf()),
        e => io_at(path)(e.into()),
    })?;
    let mut file = File::from(fd);
    let meta = file.metadata().map_err(io_at(path))?;
    if !is_stream(&meta) && !is_own_stdout(&meta) {
        return Err(FsError::Changed(path.to_path_buf()));
    }
    let blocking = rustix::fs::fcntl_getfl(&file).map(|f| f - OFlags::NONBLOCK);
    blocking.and_then(|f| rustix::fs::fcntl_setfl(&file, f)).map_err(|e| io_at(path)(e.into()))?;
    match file.write_all(bytes).and_then(|()| file.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
        other => other.map_err(io_at(path)),
    }
}

/// Writes `bytes` to an anonymous file in `dir` (`O_TMPFILE`: nothing to plant at, nothing left
/// even after `kill -9`) and gives it the name `path`, never over anything: `linkat` does not
/// replace, so whatever appeared at the target since the check stays. `Ok(false)`, with
/// nothing written at `dir`, where the file system has no `O_TMPFILE` or no way to link one.
fn write_unnamed(dir: &Path, path: &Path, bytes: &[u8]) -> Result<bool, FsError> {
    let flags = OFlags::WRONLY | OFlags::TMPFILE | OFlags::CLOEXEC;
    let mut file = match rustix::fs::open(dir, flags, Mode::from_bits_truncate(0o666)) {
        Ok(fd) => File::from(fd),
        // The "not supported here" answers to O_TMPFILE (as in `tempfile`), plus EINVAL.
        Err(Errno::OPNOTSUPP | Errno::ISDIR | Errno::NOENT | Errno::INVAL) => return Ok(false),
        Err(e) => return Err(io_at(path)(e.into())),
    };
    fill(&mut file, bytes, None).map_err(io_at(path))?;
    hold_for_test();
    link_unnamed(&file, path).map_err(|e| match e {
        Errno::EXIST => FsError::Exists(path.to_path_buf()),
        e => io_at(path)(e.into()),
    })
}

/// Gives the anonymous `file` the name `to`: `linkat(AT_EMPTY_PATH)` (Linux ≥ 6.10 for an
/// unprivileged caller, or with CAP_DAC_READ_SEARCH), else through `/proc/self/fd`. `Ok(false)`
/// when neither is possible here.
fn link_unnamed(file: &File, to: &Path) -> Result<bool, Errno> {
    match rustix::fs::linkat(file, "", CWD, to, AtFlags::EMPTY_PATH) {
        Ok(()) => return Ok(true),
        Err(Errno::NOENT | Errno::PERM | Errno::INVAL | Errno::ACCESS) => {}
        Err(e) => return Err(e),
    }
    let by_fd = format!("/proc/self/fd/{}", file.as_raw_fd());
    match rustix::fs::linkat(CWD, by_fd.as_str(), CWD, to, AtFlags::SYMLINK_FOLLOW) {
        Ok(()) => Ok(true),
        // No /proc (or its fd links do not lead back here).
        Err(Errno::NOENT | Errno::PERM | Errno::XDEV | Errno::ACCESS) if !Path::new(&by_fd).exists() => Ok(false),
        Err(e) => Err(e),
    }
}

/// The prefix of temporary names `.NAME.thud-XXXXXX.tmp` (six random characters follow; the
/// name's bytes are cut to 40 so the temporary name fits wherever the target's does).
fn temp_prefix(path: &Path) -> OsString {
    let name = path.file_name().map_or(b"file".as_slice(), OsStrExt::as_bytes);
    let mut prefix = b".".to_vec();
    prefix.extend_from_slice(&name[..name.len().min(40)]);
    prefix.extend_from_slice(TEMP_MARK.as_bytes());
    OsString::from_vec(prefix)
}

/// A builder of temporary names with `prefix` ([`temp_prefix`]).
fn temp_builder(prefix: &OsString) -> tempfile::Builder<'_, 'static> {
    let mut b = tempfile::Builder::new();
    b.prefix(prefix).suffix(".tmp").rand_bytes(6);
    b
}

/// Whether `name` has the shape of thud's temporary names (see [`temp_prefix`]).
fn is_temp_name(name: &[u8]) -> bool {
    let mark = TEMP_MARK.as_bytes();
    let Some(stem) = name.strip_suffix(b".tmp") else { return false };
    if !name.starts_with(b".") || stem.len() < 1 + mark.len() + 6 {
        return false;
    }
    let (head, random) = stem.split_at(stem.len() - 6);
    head.ends_with(mark) && random.iter().all(u8::is_ascii_alphanumeric)
}

/// Removes from `dir` the temporary files and folders of thud runs that are gone (killed with
/// SIGKILL, or a power cut): names of thud's shape, regular files or folders (never a link),
/// whose `flock` is free and which are over [`STALE_AFTER`] old. Best effort: an error leaves
/// the name where it is.
pub fn remove_stale_temps(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        if is_temp_name(entry.file_name().as_bytes()) {
            remove_if_stale(&entry.path());
        }
    }
}

fn remove_if_stale(path: &Path) {
    let flags = OFlags::RDONLY | OFlags::NOFOLLOW | OFlags::NONBLOCK | OFlags::CLOEXEC | OFlags::NOCTTY;
    let Ok(fd) = rustix::fs::open(path, flags, Mode::empty()) else { return };
    let file = File::from(fd);
    let Ok(meta) = file.metadata() else { return };
    let old =
        meta.modified().ok().and_then(|t| SystemTime::now().duration_since(t).ok()).is_some_and(|a| a >= STALE_AFTER);
    if !old || rustix::fs::flock(&file, FlockOperation::NonBlockingLockExclusive).is_err() {
        return;
    }
    // The name must still be the file that was locked.
    let same = fs::symlink_metadata(path).is_ok_and(|m| m.ino() == meta.ino() && m.dev() == meta.dev());
    if same && meta.is_file() {
        let _ = fs::remove_file(path);
    } else if same && meta.is_dir() {
        let _ = fs::remove_dir_all(path);
    }
}

/// Writes through a named temporary file (locked; removed on every error path and on signals).
fn write_named(
    dir: &Path,
    path: &Path,
    bytes: &[u8],
    overwrite: Overwrite,
    permissions: Option<Permissions>,
    before_link: impl FnOnce(&Path) -> io::Result<()>,
) -> Result<(), FsError> {
    let (mut temp, _registration) = named_temp(dir, path).map_err(io_at(path))?;
    fill(temp.as_file_mut(), bytes, permissions).map_err(io_at(path))?;
    before_link(temp.path()).map_err(io_at(temp.path()))?;
    hold_for_test();
    let replace = overwrite == Overwrite::Replace;
    // After an exchange `temp`'s name holds the replaced file: removed when `temp` is dropped.
    if !(replace && exchange(temp.path(), path, |old| fs::symlink_metadata(old).is_ok_and(|m| m.is_file()))?) {
        // Nothing is at `path`, or (`Replace`) the file system cannot exchange: then only a
        // regular file there, checked once more, is renamed over.
        let regular = replace && fs::symlink_metadata(path).is_ok_and(|m| m.is_file());
        let placed = if regular { temp.persist(path) } else { temp.persist_noclobber(path) };
        placed.map_err(|e| match e.error.kind() {
            io::ErrorKind::AlreadyExists if replace => FsError::Changed(path.to_path_buf()),
            io::ErrorKind::AlreadyExists => FsError::Exists(path.to_path_buf()),
            _ => io_at(path)(e.error),
        })?;
    }
    Ok(())
}

/// A named temporary file in `dir` for the target `path`: created exclusively (never through
/// a planted link), `flock`ed, and removed on a signal while the registration lives. Created
/// and registered with signals held off, so no signal falls between the two.
fn named_temp(dir: &Path, path: &Path) -> io::Result<(tempfile::NamedTempFile, signals::Registration)> {
    let prefix = temp_prefix(path);
    signals::guarded(|| {
        let temp = temp_builder(&prefix).permissions(Permissions::from_mode(0o666)).tempfile_in(dir)?;
        rustix::fs::flock(temp.as_file(), FlockOperation::LockExclusive)?;
        let name = temp.path().to_path_buf();
        let registration = signals::on_signal(move || {
            let _ = fs::remove_file(&name);
        });
        Ok::<_, io::Error>((temp, registration.0))
    })
}

/// Set this environment variable to `N` to make [`write_set`] fail after it has put `N` files
/// of the set in place (the tests check that the files already placed are put back). Read only
/// with the `test-hooks` feature, as [`NAMED_TEMPS_FOR_TEST`].
pub const FAIL_SET_AFTER_FOR_TEST: &str = "THUD_TEST_FAIL_SET_AFTER";

/// Set this environment variable to a number of milliseconds to hold [`write_set`] after it
/// has put the first file of the set in place and before the next (a signal then must wait for
/// the whole set). Read only with the `test-hooks` feature, as [`NAMED_TEMPS_FOR_TEST`].
pub const HOLD_SET_FOR_TEST: &str = "THUD_TEST_HOLD_SET_MS";

/// How one file of a set was put in place, so that it can be undone.
enum Placed {
    /// Linked where nothing was: undone by removing the name.
    Created(PathBuf),
    /// Exchanged with the old file, which the temporary file's name now holds (removed when
    /// the set is kept): undone by exchanging back.
    Exchanged(tempfile::NamedTempFile, PathBuf),
    /// Where the file system cannot exchange: the old file moved to a temporary name first,
    /// the new one linked in its place; undone by moving the old one back over it.
    Moved(tempfile::NamedTempFile<()>, PathBuf),
}

impl Placed {
    fn undo(self) {
        match self {
            Placed::Created(path) => {
                let _ = fs::remove_file(path);
            }
            Placed::Exchanged(old, path) => {
                if rustix::fs::renameat_with(CWD, old.path(), CWD, &path, RenameFlags::EXCHANGE).is_err() {
                    // The new file stays; the old one is kept under its temporary name.
                    let _ = old.keep();
                }
            }
            Placed::Moved(old, path) => {
                if fs::rename(old.path(), &path).is_err() {
                    let _ = old.keep();
                }
            }
        }
    }
}

/// Writes several files as one set: every file (a new one or, with [`Overwrite::Replace`], a
/// regular file to replace) is first written to a temporary file in its own folder and synced;
/// then all are put in place in one [`signals::guarded`] step. If putting one in place fails,
/// those already placed are put back (the old files return, the new names go) and the error is
/// returned; a signal before that step leaves the old set (the temporary files are removed), a
/// signal during it waits for the whole new set. Streams (standard output, a FIFO, a terminal)
/// cannot be taken back: they are written through after the files are in place. Two entries
/// naming one path are the caller's to refuse beforehand.
pub fn write_set(files: &[(&Path, &[u8])], overwrite: Overwrite) -> Result<(), FsError> {
    write_set_with_folder(files, None, overwrite)
}

/// [`write_set`] with a folder among the set: the staged `folder` is put in place first, then
/// the files, in the same guarded step; a failure puts back the old folder (or nothing) with
/// the old files, and a signal before that step removes the staged folder with the staged files.
pub fn write_set_with_folder(
    files: &[(&Path, &[u8])],
    folder: Option<StagedFolder>,
    overwrite: Overwrite,
) -> Result<(), FsError> {
    let mut streams = Vec::new();
    let mut staged = Vec::new();
    let mut folders = Vec::new();
    let mut dirs = Vec::new();
    // Each temporary file's clean-up on a signal, kept until the set is in place.
    let mut registrations = Vec::new();
    let plans: Vec<Plan> = files.iter().map(|(p, _)| check_target(p, overwrite)).collect::<Result<_, _>>()?;
    for ((path, bytes), plan) in files.iter().zip(plans) {
        let permissions = match plan {
            Plan::Through(sink) => {
                streams.push((*path, sink, *bytes));
                continue;
            }
            Plan::Create => None,
            Plan::Replace(p) => Some(p),
        };
        let dir = parent_dir(path);
        folders.push(NewFolders::create(&dir).map_err(io_at(path))?);
        remove_stale_temps(&dir);
        let (mut temp, registration) = named_temp(&dir, path).map_err(io_at(path))?;
        fill(temp.as_file_mut(), bytes, permissions).map_err(io_at(path))?;
        staged.push((*path, temp));
        registrations.push(registration);
        dirs.push(dir);
    }
    hold_for_test();
    signals::guarded(|| {
        let mut folder_placed = None;
        if let Some(f) = &folder {
            let names: Vec<&str> = f.names.iter().map(String::as_str).collect();
            folder_placed = Some(fail_set_for_test(0).and_then(|()| f.temp.rename_to(&f.target, f.replace, &names))?);
        }
        let first = usize::from(folder.is_some());
        let mut placed: Vec<Placed> = Vec::new();
        let mut result = Ok(());
        for (i, (path, temp)) in staged.into_iter().enumerate().map(|(i, s)| (i + first, s)) {
            if i > 0 {
                hold_set_for_test();
            }
            let step = fail_set_for_test(i).and_then(|()| place(temp, path, overwrite));
            match step {
                Ok(p) => placed.push(p),
                Err(e) => {
                    result = Err(e);
                    break;
                }
            }
        }
        if result.is_err() {
            placed.into_iter().rev().for_each(Placed::undo);
            if let (Some(f), Some(how)) = (&folder, folder_placed) {
                f.temp.undo(&f.target, how);
            }
        }
        result
    })?;
    for dir in &dirs {
        sync_dir(dir);
    }
    drop(registrations);
    folders.into_iter().for_each(NewFolders::keep);
    if let Some(f) = folder {
        sync_dir(&parent_dir(&f.target));
        f.folders.keep();
    }
    for (path, sink, bytes) in streams {
        write_through(path, sink, bytes)?;
    }
    Ok(())
}

/// Puts the written, synced temporary file `temp` at `path` (see [`write_set`]).
fn place(temp: tempfile::NamedTempFile, path: &Path, overwrite: Overwrite) -> Result<Placed, FsError> {
    let replace = overwrite == Overwrite::Replace;
    if replace && exchange(temp.path(), path, |old| fs::symlink_metadata(old).is_ok_and(|m| m.is_file()))? {
        return Ok(Placed::Exchanged(temp, path.to_path_buf()));
    }
    let regular = replace && fs::symlink_metadata(path).is_ok_and(|m| m.is_file());
    let moved = if regular {
        // No exchange here: the old file goes to a temporary name of its own (never over
        // anything), so it can come back.
        let prefix = temp_prefix(path);
        let old = temp_builder(&prefix)
            .make_in(parent_dir(path), |to| {
                rustix::fs::renameat_with(CWD, path, CWD, to, RenameFlags::NOREPLACE).map_err(io::Error::from)
            })
            .map_err(io_at(path))?;
        Some(old)
    } else {
        None
    };
    match temp.persist_noclobber(path) {
        Ok(_) => Ok(match moved {
            Some(old) => Placed::Moved(old, path.to_path_buf()),
            None => Placed::Created(path.to_path_buf()),
        }),
        Err(e) => {
            if let Some(old) = moved {
                if rustix::fs::renameat_with(CWD, old.path(), CWD, path, RenameFlags::NOREPLACE).is_err() {
                    let _ = old.keep();
                }
            }
            Err(match e.error.kind() {
                io::ErrorKind::AlreadyExists if replace => FsError::Changed(path.to_path_buf()),
                io::ErrorKind::AlreadyExists => FsError::Exists(path.to_path_buf()),
                _ => io_at(path)(e.error),
            })
        }
    }
}

/// The test seam of [`FAIL_SET_AFTER_FOR_TEST`]: an error before the file at index `i` is put
/// in place when the variable says `i` (nothing without the `test-hooks` feature).
fn fail_set_for_test(i: usize) -> Result<(), FsError> {
    #[cfg(feature = "test-hooks")]
    if std::env::var(FAIL_SET_AFTER_FOR_TEST).ok().and_then(|v| v.parse::<usize>().ok()) == Some(i) {
        return Err(FsError::Io {
            path: PathBuf::from(FAIL_SET_AFTER_FOR_TEST),
            source: io::Error::other("a failure injected by the test between two files of a set"),
        });
    }
    let _ = i;
    Ok(())
}

/// The test seam of [`HOLD_SET_FOR_TEST`] (nothing without the `test-hooks` feature).
fn hold_set_for_test() {
    #[cfg(feature = "test-hooks")]
    if let Some(ms) = std::env::var(HOLD_SET_FOR_TEST).ok().and_then(|v| v.parse::<u64>().ok()) {
        std::thread::sleep(Duration::from_millis(ms));
    }
}

/// Exchanges `temp` and `target` atomically (`RENAME_EXCHANGE`) and keeps the exchange if what
/// `temp` then names — the replaced entry — is `replaceable`; else swaps them back:
/// [`FsError::Changed`] (a link, device or folder appeared at `target` since the check).
/// `Ok(false)`, nothing done, when nothing is at `target` or the file system cannot exchange.
fn exchange(temp: &Path, target: &Path, replaceable: impl Fn(&Path) -> bool) -> Result<bool, FsError> {
    match rustix::fs::renameat_with(CWD, temp, CWD, target, RenameFlags::EXCHANGE) {
        Ok(()) if replaceable(temp) => Ok(true),
        Ok(()) => {
            rustix::fs::renameat_with(CWD, temp, CWD, target, RenameFlags::EXCHANGE)
                .map_err(|e| io_at(target)(e.into()))?;
            Err(FsError::Changed(target.to_path_buf()))
        }
        Err(Errno::NOENT | Errno::INVAL | Errno::NOSYS | Errno::OPNOTSUPP) => Ok(false),
        Err(e) => Err(io_at(target)(e.into())),
    }
}

/// A temporary folder beside a target folder (`.NAME.thud-XXXXXX.tmp`), `flock`ed for its
/// life, removed when dropped and on every signal of [`signals::handled`] (after SIGKILL, by
/// the next write beside it), until [`TempFolder::put_in_place`] gives it the target's name.
/// Each file is written into it, and it is put in place, as one [`signals::guarded`] step: a
/// signal's clean-up falls between two files, and nothing is written or renamed after it.
#[derive(Debug)]
pub struct TempFolder {
    dir: tempfile::TempDir,
    _lock: File,
    _registration: signals::Registration,
}

impl TempFolder {
    /// A new temporary folder in `parent` for the folder `target`.
    pub fn new(parent: &Path, target: &Path) -> io::Result<Self> {
        let prefix = temp_prefix(target);
        signals::guarded(|| {
            let dir = temp_builder(&prefix).tempdir_in(parent)?;
            let lock = File::open(dir.path())?;
            rustix::fs::flock(&lock, FlockOperation::LockExclusive)?;
            let path = dir.path().to_path_buf();
            let registration = signals::on_signal(move || {
                let _ = fs::remove_dir_all(&path);
            })
            .0;
            Ok(TempFolder { dir, _lock: lock, _registration: registration })
        })
    }

    /// Where the files go.
    #[must_use]
    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    /// Writes the new file `name` into the folder ([`write()`], never over anything).
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<(), FsError> {
        signals::guarded(|| write(&self.path().join(name), bytes, Overwrite::Refuse))
    }

    /// Makes the names in the folder durable (best effort).
    pub fn sync(&self) {
        sync_dir(self.path());
    }

    /// Gives the folder the name `target`: over nothing or an empty folder; with `replace`, by
    /// an atomic exchange with the folder there, which is then removed — if it still holds only
    /// regular files named in `names` (else it is swapped back and nothing is replaced).
    pub fn put_in_place(self, target: &Path, replace: bool, names: &[&str]) -> Result<(), FsError> {
        signals::guarded(|| self.rename_to(target, replace, names)).map(drop)
    }

    fn rename_to(&self, target: &Path, replace: bool, names: &[&str]) -> Result<FolderPlaced, FsError> {
        let temp = self.path();
        if replace && exchange(temp, target, |old| only_named_files(old, names))? {
            return Ok(FolderPlaced::Exchanged); // `temp` now names the old set: removed on drop.
        }
        match rustix::fs::renameat_with(CWD, temp, CWD, target, RenameFlags::NOREPLACE) {
            Ok(()) => Ok(FolderPlaced::Renamed(None)),
            // An empty folder is there: rename(2) replaces only an empty folder.
            Err(Errno::EXIST) => {
                let empty = fs::symlink_metadata(target).map(|m| m.permissions()).ok();
                fs::rename(temp, target).map_err(|e| match Errno::from_io_error(&e) {
                    Some(Errno::NOTEMPTY | Errno::NOTDIR | Errno::EXIST) => FsError::Changed(target.to_path_buf()),
                    _ => io_at(target)(e),
                })?;
                Ok(FolderPlaced::Renamed(empty))
            }
            Err(Errno::INVAL | Errno::NOSYS | Errno::OPNOTSUPP) if !target.exists() => {
                fs::rename(temp, target).map_err(io_at(target))?;
                Ok(FolderPlaced::Renamed(None))
            }
            Err(e) => Err(io_at(target)(e.into())),
        }
    }

    /// Takes back [`TempFolder::rename_to`]: the new folder returns to the temporary name
    /// (removed on drop) and the old folder, or the empty one, to `target`.
    fn undo(&self, target: &Path, placed: FolderPlaced) {
        let temp = self.path();
        match placed {
            FolderPlaced::Exchanged => {
                let _ = rustix::fs::renameat_with(CWD, temp, CWD, target, RenameFlags::EXCHANGE);
            }
            FolderPlaced::Renamed(empty) => {
                if rustix::fs::renameat_with(CWD, target, CWD, temp, RenameFlags::NOREPLACE).is_ok() {
                    if let Some(permissions) = empty {
                        let _ = fs::create_dir(target).and_then(|()| fs::set_permissions(target, permissions));
                    }
                }
            }
        }
    }
}

/// How a [`TempFolder`] was given its target's name, so that it can be taken back.
enum FolderPlaced {
    /// Exchanged with the previous folder, which the temporary name now holds.
    Exchanged,
    /// Renamed over nothing (`None`) or over an empty folder of these permissions.
    Renamed(Option<Permissions>),
}

/// A folder of files written beside its target and synced, to be put in place together with a
/// set of files by [`write_set_with_folder`] (or not at all: dropped, it is removed, and so are
/// the folders made above it).
#[derive(Debug)]
pub struct StagedFolder {
    temp: TempFolder,
    target: PathBuf,
    replace: bool,
    names: Vec<String>,
    folders: NewFolders,
}

impl StagedFolder {
    /// Writes `files` (name, contents) into a new temporary folder beside `target` (making
    /// the missing folders above it). With `replace`, the folder at `target` is exchanged with
    /// it if it holds only regular files named in `files` or in `replaceable`; else `target`
    /// must be absent or empty when the set is put in place.
    pub fn new(
        target: &Path,
        files: &[(&str, &[u8])],
        replace: bool,
        replaceable: &[String],
    ) -> Result<StagedFolder, FsError> {
        let parent = parent_dir(target);
        let folders = NewFolders::create(&parent).map_err(io_at(target))?;
        remove_stale_temps(&parent);
        let temp = TempFolder::new(&parent, target).map_err(io_at(target))?;
        for (name, contents) in files {
            temp.write(name, contents)?;
        }
        temp.sync();
        let mut names: Vec<String> = files.iter().map(|(n, _)| (*n).to_string()).collect();
        names.extend(replaceable.iter().filter(|n| !names.contains(n)).cloned().collect::<Vec<_>>());
        Ok(StagedFolder { temp, target: target.to_path_buf(), replace, names, folders })
    }
}

impl Drop for TempFolder {
    fn drop(&mut self) {
        // Removed here, guarded, rather than by `TempDir`'s drop: never beside the clean-up.
        signals::guarded(|| {
            let _ = fs::remove_dir_all(self.dir.path());
        });
    }
}

/// Whether the folder `dir` holds only regular files (no links) named in `names`.
fn only_named_files(dir: &Path, names: &[&str]) -> bool {
    let Ok(entries) = fs::read_dir(dir) else { return false };
    entries.into_iter().all(|e| {
        e.is_ok_and(|e| {
            names.iter().any(|n| e.file_name() == std::ffi::OsStr::new(n)) && e.file_type().is_ok_and(|t| t.is_file())
        })
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

/// The test seam of [`HOLD_TEMP_FOR_TEST`] (nothing without the `test-hooks` feature).
fn hold_for_test() {
    #[cfg(feature = "test-hooks")]
    if let Some(ms) = std::env::var(HOLD_TEMP_FOR_TEST).ok().and_then(|v| v.parse::<u64>().ok()) {
        std::thread::sleep(Duration::from_millis(ms));
    }
}

/// The test seam of [`NAMED_TEMPS_FOR_TEST`] (off without the `test-hooks` feature).
fn named_temps_for_test() -> bool {
    cfg!(feature = "test-hooks") && std::env::var_os(NAMED_TEMPS_FOR_TEST).is_some()
}

/// Makes a new name durable by syncing its directory (best effort; not possible everywhere).
fn sync_dir(dir: &Path) {
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
}

/// Opens `path` for reading if it is a regular file (or a symlink to one) of at most
/// `limit_bytes`. The path is checked before it is opened (a device is never opened), opened
/// non-blocking (a FIFO swapped in meanwhile does not hang) and checked again on the open file.
pub fn open_regular(path: &Path, limit_bytes: u64) -> Result<File, FsError> {
    check_readable(path, &fs::metadata(path).map_err(io_at(path))?, limit_bytes)?;
    let flags = OFlags::RDONLY | OFlags::NONBLOCK | OFlags::CLOEXEC | OFlags::NOCTTY;
    let file = File::from(rustix::fs::open(path, flags, Mode::empty()).map_err(|e| io_at(path)(e.into()))?);
    check_readable(path, &file.metadata().map_err(io_at(path))?, limit_bytes)?;
    Ok(file)
}

/// Reads `path` as UTF-8 text if it is a regular file (or a symlink to one) of at most
/// `limit_bytes` (see [`open_regular`]).
pub fn read_to_string(path: &Path, limit_bytes: u64) -> Result<String, FsError> {
    let file = open_regular(path, limit_bytes)?;
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

    #[test]
    fn a_symlink_is_never_replaced_and_its_pointee_never_written() {
        let dir = tempfile::tempdir().unwrap();
        let victim = dir.path().join("victim");
        fs::write(&victim, "keep").unwrap();
        let link = dir.path().join("out.csv");
        std::os::unix::fs::symlink(&victim, &link).unwrap();
        let dangling = dir.path().join("dangling.csv");
        std::os::unix::fs::symlink(dir.path().join("nowhere"), &dangling).unwrap();
        for p in [&link, &dangling] {
            for o in [Overwrite::Refuse, Overwrite::Replace] {
                assert!(matches!(write(p, b"x", o), Err(FsError::Link(_))), "{p:?} {o:?}");
                assert!(fs::symlink_metadata(p).unwrap().file_type().is_symlink());
            }
        }
        assert_eq!(fs::read_to_string(&victim).unwrap(), "keep");
        assert!(!dir.path().join("nowhere").exists());
    }

    #[test]
    fn dev_null_and_a_fifo_with_a_reader_are_written_through() {
        let null = Path::new("/dev/null");
        if fs::symlink_metadata(null).is_ok_and(|m| m.file_type().is_char_device()) {
            assert!(matches!(check_target(null, Overwrite::Replace), Ok(Plan::Through(_))));
            write(null, b"x", Overwrite::Replace).unwrap();
            assert!(fs::symlink_metadata(null).unwrap().file_type().is_char_device());
        }
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("pipe");
        rustix::fs::mknodat(CWD, &fifo, rustix::fs::FileType::Fifo, Mode::from_bits_truncate(0o600), 0).unwrap();
        assert!(matches!(write(&fifo, b"x", Overwrite::Replace), Err(FsError::NoReader(_))));
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || fs::read(fifo).unwrap())
        };
        // The reader opens the FIFO in its own time: retry until it is there.
        let start = std::time::Instant::now();
        loop {
            match write(&fifo, b"through\n", Overwrite::Refuse) {
                Ok(()) => break,
                Err(FsError::NoReader(_)) if start.elapsed() < Duration::from_secs(10) => {
                    std::thread::sleep(Duration::from_millis(10));
                }
                other => panic!("{other:?}"),
            }
        }
        assert_eq!(reader.join().unwrap(), b"through\n");
        assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    }

    #[test]
    fn stale_temporary_names_are_removed_and_live_or_foreign_ones_kept() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let stale = d.join(".e.csv.thud-aB3dE9.tmp");
        let stale_dir = d.join(".paper.thud-Zz9Zz9.tmp");
        let live = d.join(".f.csv.thud-Qw3rTy.tmp");
        let young = d.join(".g.csv.thud-Yo0nG1.tmp");
        let mine = d.join(".e.csv.backup.tmp");
        let link = d.join(".h.csv.thud-L1nkL1.tmp");
        for p in [&stale, &live, &young, &mine] {
            fs::write(p, "x").unwrap();
        }
        fs::create_dir(&stale_dir).unwrap();
        fs::write(stale_dir.join("REPORT.md"), "x").unwrap();
        std::os::unix::fs::symlink(&mine, &link).unwrap();
        let old = SystemTime::now() - Duration::from_secs(5);
        for p in [&stale, &live, &stale_dir, &mine] {
            File::open(p).unwrap().set_modified(old).unwrap();
        }
        let held = File::open(&live).unwrap();
        rustix::fs::flock(&held, FlockOperation::LockExclusive).unwrap();
        remove_stale_temps(d);
        assert!(!stale.exists() && !stale_dir.exists(), "the leftovers of a dead run are removed");
        for p in [&live, &young, &mine] {
            assert!(p.exists(), "{p:?} is kept");
        }
        assert!(fs::symlink_metadata(&link).unwrap().file_type().is_symlink(), "a link is never touched");
    }

    #[test]
    fn names_are_shown_escaped_and_long_ones_cut_in_the_middle() {
        use std::os::unix::ffi::OsStrExt;
        let p = Path::new(std::ffi::OsStr::from_bytes(b"caf\xe9\n.csv"));
        assert_eq!(shown(p), "caf\\xe9\\n.csv");
        let long = format!("/{}/end.csv", "d".repeat(500));
        let s = shown(Path::new(&long));
        assert_eq!(s.chars().count(), MAX_SHOWN_CHARS);
        assert!(s.starts_with("/ddd") && s.ends_with("ddd/end.csv") && s.contains('…'), "{s}");
        let e = FsError::Exists(long.into());
        assert_eq!(e.reason(), "already exists");
        assert!(e.to_string().ends_with("/end.csv: already exists"));
    }
}
