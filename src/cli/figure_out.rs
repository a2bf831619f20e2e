//! The files of a command that prints a table and can draw it (`thud sweep`): `--out`,
//! `--svg` and `--pdf`, each checked before any work and written as one set (all in place, or
//! none), as the studies of orbits write theirs.

use std::path::{Path, PathBuf};

use super::{AsciiArgs, CliError, Out};
use crate::error::ThudError;
use crate::fsio::{self, Overwrite};

/// Where a table and its figure go.
pub(super) struct FigureOutputs<'a> {
    out: Option<&'a Path>,
    svg: Option<&'a Path>,
    pdf: Option<&'a Path>,
    force: bool,
    ascii: AsciiArgs,
}

impl<'a> FigureOutputs<'a> {
    /// A command's `--out`, `--svg`, `--pdf`, `--force` and `--ascii`, as it parsed them.
    pub(super) fn new(
        out: &'a Option<PathBuf>,
        svg: &'a Option<PathBuf>,
        pdf: &'a Option<PathBuf>,
        force: bool,
        ascii: AsciiArgs,
    ) -> Self {
        FigureOutputs { out: out.as_deref(), svg: svg.as_deref(), pdf: pdf.as_deref(), force, ascii }
    }

    /// Whether a figure is asked for (`--svg` or `--pdf`).
    pub(super) fn wants_figure(&self) -> bool {
        self.svg.is_some() || self.pdf.is_some()
    }

    /// Every file checked first (an existing one without --force is refused before the work);
    /// two outputs naming one file, or both going to standard output, are refused before
    /// anything is written.
    pub(super) fn check(&self) -> Result<(), ThudError> {
        distinct_outputs(self.out, self.svg, self.pdf)?;
        for (flag, p) in self.files() {
            fsio::check_target(p, Overwrite::from_force(self.force))
                .map_err(|e| super::export::out_error(p, &e).renamed(flag))?;
        }
        Ok(())
    }

    /// Each file with the flag that named it (the table's only if not standard output).
    fn files(&self) -> impl Iterator<Item = (&'static str, &'a Path)> {
        [("--svg", self.svg), ("--pdf", self.pdf), ("--out", self.table_file())]
            .into_iter()
            .filter_map(|(flag, p)| p.map(|p| (flag, p)))
    }

    /// The table's file, if not standard output.
    fn table_file(&self) -> Option<&'a Path> {
        self.out.filter(|p| !fsio::is_stdout(p))
    }

    /// Writes `text` (the table) to `--out` or standard output and `figure` (an SVG document)
    /// to `--svg` and `--pdf`. Every output is made before the first file is written, so a
    /// failure to draw one leaves every file as it was.
    pub(super) fn write(&self, text: &str, figure: Option<String>, out: &mut Out) -> Result<(), CliError> {
        self.check()?;
        super::output::check_text(text)?;
        let svg = figure.filter(|_| self.wants_figure()).map(|f| self.ascii.figure(f));
        let pdf = match (self.pdf, &svg) {
            (Some(_), Some(svg)) => Some(
                crate::export::pdf::from_svg(svg)
                    .map_err(|e| ThudError::invalid("--pdf", format!("cannot draw the PDF: {e}")))?,
            ),
            _ => None,
        };
        let mut files: Vec<(&Path, &[u8])> = Vec::new();
        if let (Some(p), Some(svg)) = (self.svg, &svg) {
            files.push((p, svg.as_bytes()));
        }
        if let (Some(p), Some(pdf)) = (self.pdf, &pdf) {
            files.push((p, pdf));
        }
        if let Some(p) = self.table_file() {
            files.push((p, text.as_bytes()));
        }
        if let Err(e) = fsio::write_set(&files, Overwrite::from_force(self.force)) {
            let p = e.path().to_path_buf();
            let flag = self.files().find(|(_, f)| *f == p).map_or("--out", |(flag, _)| flag);
            return Err(super::export::write_error_as(flag, &p, &e));
        }
        for (p, _) in &files {
            super::warn(&format!("wrote {}", fsio::shown(p)));
        }
        match self.table_file() {
            Some(_) => Ok(()),
            None => out.text(text),
        }
    }
}

/// Refuses two of a command's outputs (`--out`, `--svg`, `--pdf`) naming one file, or both
/// going to standard output (`--out` missing or `-`: the table), naming the later flag.
pub(super) fn distinct_outputs(out: Option<&Path>, svg: Option<&Path>, pdf: Option<&Path>) -> Result<(), ThudError> {
    let outputs = [
        ("--out", out.unwrap_or(Path::new("-"))),
        ("--svg", svg.unwrap_or(Path::new(""))),
        ("--pdf", pdf.unwrap_or(Path::new(""))),
    ];
    for (i, (flag, path)) in outputs.iter().enumerate() {
        if path.as_os_str().is_empty() {
            continue;
        }
        if let Some((other, _)) = outputs[..i].iter().find(|(_, p)| same_output(p, path)) {
            let what = if fsio::is_stdout(path) {
                format!("standard output carries the {other} output already (without --out, the table)")
            } else {
                format!("'{}' is the {other} file too", fsio::shown(path))
            };
            return Err(ThudError::invalid(*flag, format!("{what}; give each output a file of its own")));
        }
    }
    Ok(())
}

/// Whether two outputs go to one place: both to standard output (`-`), or one file named two
/// ways (`o.svg`, `./o.svg`, `dir/../o.svg`, a symbolic link to the folder).
pub(super) fn same_output(a: &Path, b: &Path) -> bool {
    if fsio::is_stdout(a) || fsio::is_stdout(b) {
        return fsio::is_stdout(a) && fsio::is_stdout(b);
    }
    // The folder resolved, the name as given: the file itself need not exist yet.
    let place = |p: &Path| {
        let dir = match p.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        dir.canonicalize().ok().zip(p.file_name().map(std::ffi::OsStr::to_os_string))
    };
    match (place(a), place(b)) {
        (Some(x), Some(y)) => x == y,
        _ => a == b,
    }
}
