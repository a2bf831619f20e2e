//! Files that outlive a session: atomic writes, TOML parse problems with file/line/column, and
//! named saved designs in the data directory. Front-end support, not physics.
//!
//! Every function takes the directory it works in, so tests use a temporary directory; the
//! `ProjectDirs`-based locations are in [`Dirs`].

use std::fmt;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use serde::{Deserialize, Serialize};

use crate::design::Design;
use crate::error::ThudError;

/// The directories thud keeps its files in.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Dirs {
    /// Holds `config.toml` (on Linux `$XDG_CONFIG_HOME/thud`).
    pub config_dir: PathBuf,
    /// Holds `designs/*.toml` (on Linux `$XDG_DATA_HOME/thud`).
    pub data_dir: PathBuf,
}

impl Dirs {
    /// The platform's directories for `thud` (`directories::ProjectDirs::from("", "", "thud")`);
    /// `None` when no home directory can be found.
    pub fn project() -> Option<Dirs> {
        let p = directories::ProjectDirs::from("", "", "thud")?;
        Some(Dirs { config_dir: p.config_dir().to_path_buf(), data_dir: p.data_dir().to_path_buf() })
    }
}

/// A file that could not be used: where and what. Displays as `path:line:column: message`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileProblem {
    pub path: PathBuf,
    /// 1-based line of the problem, when known.
    pub line: Option<usize>,
    /// 1-based column (in characters) of the problem, when known.
    pub column: Option<usize>,
    pub message: String,
}

impl fmt::Display for FileProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if let Some(l) = self.line {
            write!(f, ":{l}")?;
            if let Some(c) = self.column {
                write!(f, ":{c}")?;
            }
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for FileProblem {}

/// 1-based (line, column) of byte `offset` in `text`.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// Parses TOML `text` read from `path` into `T`; a failure names the file, line, column and problem.
pub fn parse_toml<T: serde::de::DeserializeOwned>(path: &Path, text: &str) -> Result<T, FileProblem> {
    toml::from_str(text).map_err(|e| {
        let (line, column) = match e.span() {
            Some(span) => {
                let (l, c) = line_column(text, span.start);
                (Some(l), Some(c))
            }
            None => (None, None),
        };
        FileProblem { path: path.to_path_buf(), line, column, message: e.message().trim().to_string() }
    })
}

/// A failure to read or write one of thud's files.
#[derive(Debug)]
pub enum StoreError {
    /// The operating system refused: the path and the reason.
    Io { path: PathBuf, source: io::Error },
    /// The file is there but is not valid (it is left untouched).
    Invalid(FileProblem),
    /// A bad argument (e.g. a design name with a '/').
    Thud(ThudError),
}

impl fmt::Display for StoreError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StoreError::Io { path, source } => write!(f, "{}: {source}", path.display()),
            StoreError::Invalid(p) => write!(f, "{p}"),
            StoreError::Thud(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for StoreError {}

impl From<ThudError> for StoreError {
    fn from(e: ThudError) -> Self {
        StoreError::Thud(e)
    }
}

impl From<FileProblem> for StoreError {
    fn from(p: FileProblem) -> Self {
        StoreError::Invalid(p)
    }
}

impl From<StoreError> for ThudError {
    /// For the CLI: a store failure as a one-line error naming the file.
    fn from(e: StoreError) -> Self {
        match e {
            StoreError::Thud(t) => t,
            StoreError::Io { path, source } => ThudError::invalid("file", format!("{}: {source}", path.display())),
            StoreError::Invalid(p) => ThudError::invalid("file", p.to_string()),
        }
    }
}

fn io_err(path: &Path) -> impl FnOnce(io::Error) -> StoreError + '_ {
    move |source| StoreError::Io { path: path.to_path_buf(), source }
}

/// Writes `bytes` to `path` atomically: a temporary file in the same directory is written,
/// flushed to disk (fsync) and renamed over `path`, so a reader sees the old or the new file,
/// never a part. Creates the parent directory if needed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), StoreError> {
    write_atomic_with(path, bytes, |_| Ok(()))
}

/// [`write_atomic`] with a seam: `before_rename(temp_path)` runs after the temporary file is
/// written and synced and before the rename. If it fails the temporary file is removed, the
/// target is untouched and the error is returned (tests use it to simulate a crash there).
pub fn write_atomic_with(
    path: &Path,
    bytes: &[u8],
    before_rename: impl FnOnce(&Path) -> io::Result<()>,
) -> Result<(), StoreError> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    fs::create_dir_all(&dir).map_err(io_err(&dir))?;
    let name = path.file_name().map_or("file".into(), |n| n.to_string_lossy().into_owned());
    static SEQ: AtomicU64 = AtomicU64::new(0);
    let seq = SEQ.fetch_add(1, Ordering::Relaxed);
    let tmp = dir.join(format!(".{name}.{}-{seq}.tmp", std::process::id()));
    let result = write_synced(&tmp, bytes)
        .and_then(|()| before_rename(&tmp).map_err(io_err(&tmp)))
        .and_then(|()| fs::rename(&tmp, path).map_err(io_err(path)));
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
        return result;
    }
    sync_dir(&dir);
    Ok(())
}

/// Creates `path` with `bytes` and fsyncs it.
fn write_synced(path: &Path, bytes: &[u8]) -> Result<(), StoreError> {
    let mut f = fs::File::create(path).map_err(io_err(path))?;
    f.write_all(bytes).map_err(io_err(path))?;
    f.sync_all().map_err(io_err(path))
}

/// Makes a rename durable by syncing its directory (best effort; not possible everywhere).
fn sync_dir(dir: &Path) {
    if let Ok(d) = fs::File::open(dir) {
        let _ = d.sync_all();
    }
}

/// Reads `path` as text; `Ok(None)` when it does not exist.
pub fn read_optional(path: &Path) -> Result<Option<String>, StoreError> {
    match fs::read_to_string(path) {
        Ok(s) => Ok(Some(s)),
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(StoreError::Io { path: path.to_path_buf(), source: e }),
    }
}

/// A design file: a one-line description and the design. The format of saved designs and of
/// the presets in `assets/presets/`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignFile {
    /// One line saying what the design is.
    #[serde(default)]
    pub description: String,
    pub design: Design,
}

impl DesignFile {
    /// The file as TOML text.
    pub fn to_toml(&self) -> Result<String, ThudError> {
        toml::to_string(self).map_err(|e| ThudError::invalid("design", format!("cannot be written as TOML: {e}")))
    }

    /// Parses TOML `text` read from `path` and validates the design.
    pub fn parse(path: &Path, text: &str) -> Result<DesignFile, FileProblem> {
        let file: DesignFile = parse_toml(path, text)?;
        file.design.validate().map_err(|e| FileProblem {
            path: path.to_path_buf(),
            line: None,
            column: None,
            message: e.to_string(),
        })?;
        Ok(file)
    }
}

/// The folder of saved designs inside `data_dir`.
pub fn designs_dir(data_dir: &Path) -> PathBuf {
    data_dir.join("designs")
}

/// Checks a design name: 1–64 letters, digits, '-' or '_' (it becomes a file name).
pub fn check_design_name(name: &str) -> Result<(), ThudError> {
    let ok = (1..=64).contains(&name.len()) && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    if ok {
        Ok(())
    } else {
        Err(ThudError::invalid("name", format!("'{name}'; use 1 to 64 letters, digits, '-' or '_'")))
    }
}

/// Path of the saved design `name` in `data_dir`.
pub fn design_path(data_dir: &Path, name: &str) -> Result<PathBuf, ThudError> {
    check_design_name(name)?;
    Ok(designs_dir(data_dir).join(format!("{name}.toml")))
}

/// Saves `file` as the design `name` in `data_dir` (atomically, replacing one of that name).
/// Returns the path written.
pub fn save_design(data_dir: &Path, name: &str, file: &DesignFile) -> Result<PathBuf, StoreError> {
    let path = design_path(data_dir, name)?;
    file.design.validate()?;
    write_atomic(&path, file.to_toml()?.as_bytes())?;
    Ok(path)
}

/// Loads the saved design `name` from `data_dir`. A file that does not parse or holds an
/// invalid design is reported as [`StoreError::Invalid`] and left as it is.
pub fn load_design(data_dir: &Path, name: &str) -> Result<DesignFile, StoreError> {
    let path = design_path(data_dir, name)?;
    let text = fs::read_to_string(&path).map_err(io_err(&path))?;
    Ok(DesignFile::parse(&path, &text)?)
}

/// Deletes the saved design `name` from `data_dir`.
pub fn delete_design(data_dir: &Path, name: &str) -> Result<(), StoreError> {
    let path = design_path(data_dir, name)?;
    fs::remove_file(&path).map_err(io_err(&path))
}

/// One saved design in a listing.
#[derive(Debug, Clone, PartialEq)]
pub struct SavedEntry {
    pub name: String,
    pub description: String,
    pub path: PathBuf,
}

/// The saved designs of a data directory: the good ones by name, and the files that could not
/// be read (listed, not fatal).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DesignList {
    pub designs: Vec<SavedEntry>,
    pub problems: Vec<FileProblem>,
}

/// Lists the saved designs in `data_dir` (sorted by name). A missing folder is an empty list.
pub fn list_designs(data_dir: &Path) -> Result<DesignList, StoreError> {
    let dir = designs_dir(data_dir);
    let entries = match fs::read_dir(&dir) {
        Ok(e) => e,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(DesignList::default()),
        Err(e) => return Err(StoreError::Io { path: dir, source: e }),
    };
    let mut list = DesignList::default();
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for path in paths {
        let Some(name) = path.file_stem().and_then(|s| s.to_str()).map(str::to_string) else { continue };
        if path.extension().is_none_or(|e| e != "toml") || check_design_name(&name).is_err() {
            continue;
        }
        let parsed = fs::read_to_string(&path)
            .map_err(|e| FileProblem { path: path.clone(), line: None, column: None, message: e.to_string() })
            .and_then(|text| DesignFile::parse(&path, &text));
        match parsed {
            Ok(f) => list.designs.push(SavedEntry { name, description: f.description, path }),
            Err(p) => list.problems.push(p),
        }
    }
    Ok(list)
}

/// [`save_design`] in the user's data directory.
pub fn save_user_design(name: &str, file: &DesignFile) -> Result<PathBuf, StoreError> {
    save_design(&user_dirs()?.data_dir, name, file)
}

/// [`load_design`] from the user's data directory.
pub fn load_user_design(name: &str) -> Result<DesignFile, StoreError> {
    load_design(&user_dirs()?.data_dir, name)
}

/// [`list_designs`] of the user's data directory.
pub fn list_user_designs() -> Result<DesignList, StoreError> {
    list_designs(&user_dirs()?.data_dir)
}

fn user_dirs() -> Result<Dirs, StoreError> {
    Dirs::project()
        .ok_or_else(|| ThudError::invalid("home", "no home directory; cannot find the data directory").into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_of_offsets() {
        let t = "a = 1\nbé = x\n";
        assert_eq!(line_column(t, 0), (1, 1));
        assert_eq!(line_column(t, 6), (2, 1));
        assert_eq!(line_column(t, 11), (2, 5));
    }

    #[test]
    fn design_names_are_file_safe() {
        assert!(check_design_name("quiet-nylon_2").is_ok());
        for bad in ["", "../x", "a/b", "a.b", "a b", &"x".repeat(65)] {
            assert!(check_design_name(bad).is_err(), "{bad}");
        }
    }
}
