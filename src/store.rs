//! Files that outlive a session: atomic writes, TOML parse problems with file/line/column, and
//! named saved designs in the data directory. Front-end support, not physics. Every read and
//! write goes through [`crate::fsio`]: writes are atomic and never replace a file unasked or a
//! non-regular file at all; reads take only regular files up to [`fsio::MAX_READ_BYTES`].
//!
//! Every function takes the directory it works in, so tests use a temporary directory; the
//! `ProjectDirs`-based locations are in [`Dirs`].

use std::fmt;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::design::Design;
use crate::error::ThudError;
use crate::fsio::{self, FileKind, FsError, Overwrite};

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
    Lines::new(text).line_column(offset)
}

/// The line starts of a text, found once, so that placing each of many problems costs a
/// binary search and its own line, not a scan from the start.
#[derive(Debug)]
pub struct Lines<'t> {
    text: &'t str,
    /// Byte offset of each line's first character.
    starts: Vec<usize>,
}

impl<'t> Lines<'t> {
    pub fn new(text: &'t str) -> Self {
        let starts = std::iter::once(0).chain(text.match_indices('\n').map(|(i, _)| i + 1)).collect();
        Lines { text, starts }
    }

    /// 1-based (line, column) of byte `offset` (a column counts characters).
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= offset);
        let start = self.starts[line - 1];
        (line, self.text[start..offset].chars().count() + 1)
    }
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
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    /// The operating system refused: the path and the reason.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: io::Error,
    },
    /// The file exists and replacing it was not asked for (the caller may ask the user, then
    /// call again with `overwrite`).
    #[error("{}: already exists", .0.display())]
    Exists(PathBuf),
    /// The path is a directory, device, FIFO or socket: never read or replaced.
    #[error("{}: is {kind}, not a regular file", path.display())]
    NotRegular { path: PathBuf, kind: FileKind },
    /// The file is larger than [`fsio::MAX_READ_BYTES`]: not a settings or design file.
    #[error("{}: is larger than {limit_bytes} bytes", path.display())]
    TooLarge { path: PathBuf, limit_bytes: u64 },
    /// The file is there but is not valid (it is left untouched).
    #[error(transparent)]
    Invalid(#[from] FileProblem),
    /// A bad argument (e.g. a design name with a '/') or a design that fails its checks.
    #[error(transparent)]
    Thud(#[from] ThudError),
    /// No home directory, so no config or data directory.
    #[error("no home directory, so no {0} directory")]
    NoHome(&'static str),
}

impl From<FsError> for StoreError {
    fn from(e: FsError) -> Self {
        match e {
            FsError::Io { path, source } => StoreError::Io { path, source },
            FsError::Exists(path) => StoreError::Exists(path),
            FsError::NotRegular { path, kind } => StoreError::NotRegular { path, kind },
            FsError::TooLarge { path, limit_bytes } => StoreError::TooLarge { path, limit_bytes },
            e @ (FsError::Link(_) | FsError::NoReader(_) | FsError::Changed(_)) => {
                StoreError::Io { path: e.path().to_path_buf(), source: io::Error::other(e.reason()) }
            }
        }
    }
}

/// Writes `bytes` to `path` atomically, replacing what is there (for files the user asked to
/// save, like the config): see [`fsio::write`]. A reader sees the old or the new file, never a
/// part; a target that is not a regular file is refused. Creates the parent directory.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), StoreError> {
    Ok(fsio::write(path, bytes, Overwrite::Replace)?)
}

/// [`write_atomic`] with a seam: `before_rename(temp_path)` runs after the temporary file is
/// written and synced and before the rename. If it fails the temporary file is removed, the
/// target is untouched and the error is returned (tests use it to simulate a crash there).
pub fn write_atomic_with(
    path: &Path,
    bytes: &[u8],
    before_rename: impl FnOnce(&Path) -> io::Result<()>,
) -> Result<(), StoreError> {
    Ok(fsio::write_with(path, bytes, Overwrite::Replace, before_rename)?)
}

/// Reads `path` as text if it is a regular file of at most [`fsio::MAX_READ_BYTES`];
/// `Ok(None)` when it does not exist.
pub fn read_optional(path: &Path) -> Result<Option<String>, StoreError> {
    Ok(fsio::read_optional(path, fsio::MAX_READ_BYTES)?)
}

/// A design file: a one-line description and the design. The format of saved designs and of
/// the presets in `crates/thud-presets/presets/`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignFile {
    /// One line saying what the design is.
    #[serde(default)]
    pub description: String,
    /// The explorer's ensemble size N the design was saved with (absent: 1, the single run).
    /// Checked on load like a typed N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ensemble: Option<usize>,
    /// The relative standard uncertainties of values the design was fitted with (`fit
    /// structure --save`: its main-mass, k and c), by flag name; `fit damper --design` carries
    /// them into its interval.
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub uncertainty: std::collections::BTreeMap<String, f64>,
    pub design: Design,
}

impl DesignFile {
    /// The file as TOML text.
    pub fn to_toml(&self) -> Result<String, ThudError> {
        toml::to_string(self).map_err(|e| ThudError::invalid("design", format!("cannot be written as TOML: {e}")))
    }

    /// Parses TOML `text` read from `path` and validates the design and the uncertainties (each
    /// named by a flag `fit damper` takes it for, a finite fraction ≥ 0).
    pub fn parse(path: &Path, text: &str) -> Result<DesignFile, FileProblem> {
        let file: DesignFile = parse_toml(path, text)?;
        let problem = |message: String| FileProblem { path: path.to_path_buf(), line: None, column: None, message };
        file.design.validate().map_err(|e| problem(e.to_string()))?;
        for (name, u) in &file.uncertainty {
            if crate::fit::damper::Input::from_name(name).is_none() {
                return Err(problem(format!(
                    "unknown key `{name}` in [uncertainty]; expected one of main-mass, k, c, mass, gap, v0"
                )));
            }
            if !(u.is_finite() && *u >= 0.0) {
                return Err(problem(format!(
                    "[uncertainty] {name}: a relative standard uncertainty is a finite fraction ≥ 0"
                )));
            }
        }
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

/// Saves `file` as the design `name` in `data_dir`, atomically. A design of that name is
/// replaced only with `overwrite`; without it the answer is [`StoreError::Exists`] and the file
/// is untouched (the explorer asks the user, then calls again). Returns the path written.
pub fn save_design(data_dir: &Path, name: &str, file: &DesignFile, overwrite: bool) -> Result<PathBuf, StoreError> {
    let path = design_path(data_dir, name)?;
    file.design.validate()?;
    fsio::write(&path, file.to_toml()?.as_bytes(), Overwrite::from_force(overwrite))?;
    Ok(path)
}

/// Loads the saved design `name` from `data_dir`. A file that does not parse or holds an
/// invalid design is reported as [`StoreError::Invalid`] and left as it is.
pub fn load_design(data_dir: &Path, name: &str) -> Result<DesignFile, StoreError> {
    load_design_file(&design_path(data_dir, name)?)
}

/// Reads and validates the design file at `path` (a regular file of at most
/// [`fsio::MAX_READ_BYTES`]): the one loader of design files, for the explorer's saved designs
/// and every command's `--design`.
pub fn load_design_file(path: &Path) -> Result<DesignFile, StoreError> {
    let text = fsio::read_to_string(path, fsio::MAX_READ_BYTES)?;
    Ok(DesignFile::parse(path, &text)?)
}

/// Whether `text`, given for a design, names a file (a path with a `/`, a name ending in
/// `.toml`, or an existing file) rather than a design saved in the data directory.
pub fn names_a_file(text: &str) -> bool {
    text.contains('/') || text.to_ascii_lowercase().ends_with(".toml") || Path::new(text).is_file()
}

/// The design `text` names: a design file ([`names_a_file`]) or a design saved in the user's
/// data directory (the explorer's `s`, `thud fit … --save NAME`).
pub fn load_named_design(text: &str) -> Result<DesignFile, StoreError> {
    if names_a_file(text) {
        load_design_file(Path::new(text))
    } else {
        load_user_design(text)
    }
}

/// Deletes the saved design `name` from `data_dir`.
pub fn delete_design(data_dir: &Path, name: &str) -> Result<(), StoreError> {
    let path = design_path(data_dir, name)?;
    fs::remove_file(&path).map_err(|source| StoreError::Io { path, source })
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
        let parsed = fsio::read_to_string(&path, fsio::MAX_READ_BYTES)
            .map_err(|e| FileProblem { path: path.clone(), line: None, column: None, message: e.reason() })
            .and_then(|text| DesignFile::parse(&path, &text));
        match parsed {
            Ok(f) => list.designs.push(SavedEntry { name, description: f.description, path }),
            Err(p) => list.problems.push(p),
        }
    }
    Ok(list)
}

/// [`save_design`] in the user's data directory.
pub fn save_user_design(name: &str, file: &DesignFile, overwrite: bool) -> Result<PathBuf, StoreError> {
    save_design(&user_dirs()?.data_dir, name, file, overwrite)
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
    Dirs::project().ok_or(StoreError::NoHome("data"))
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
