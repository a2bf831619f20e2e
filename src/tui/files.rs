//! What the explorer's export menu offers and where its files go: the menu's rows, the short
//! name of each kind, and a free file name beside the ones that exist or are being written.
//! The actions that save, load and export are the app's (`app/files.rs`).

use std::path::{Path, PathBuf};

use crate::export::Artifact;

/// What the export menu offers, in menu order, with how it is named there: the short name
/// matches the file's (`thud-waveform.csv` is "waveform CSV"), then what the file holds.
pub const EXPORTS: [(Artifact, &str); 11] = [
    (Artifact::CsvWaveform, "waveform CSV — pressure of the loudest impact"),
    (Artifact::SvgWaveform, "waveform SVG — the same pressure pulse as a figure"),
    (Artifact::CsvHistory, "history CSV — x(t) with and without the damper"),
    (Artifact::SvgHistory, "history SVG — the same x(t) as a figure"),
    (Artifact::CsvImpacts, "impacts CSV — every impact of the run"),
    (Artifact::CsvSweep, "sweep CSV — the chart's mass × gap grid"),
    (Artifact::SvgChart, "chart SVG — zones over mass × gap"),
    (Artifact::SvgFig17, "fig17 SVG — e against SPLmax (Fig 17)"),
    (Artifact::SvgDirectivity, "directivity SVG — SPL against θ"),
    (Artifact::SvgRestitution, "restitution SVG — R against impact mass (Fig 13)"),
    (Artifact::Wav, "sound WAV — the whole run at the observer, 48 kHz"),
];

/// The frequency response's rows, offered while the response view is shown.
pub const RESPONSE_EXPORTS: [(Artifact, &str); 2] = [
    (Artifact::CsvResponse, "response CSV — the frequency response on screen"),
    (Artifact::SvgResponse, "response SVG — the same response as a figure"),
];

/// The export menu's rows: [`EXPORTS`], and [`RESPONSE_EXPORTS`] while the frequency response
/// is on screen (`response`), so the menu offers what the screen shows.
pub fn export_menu(response: bool) -> Vec<(Artifact, &'static str)> {
    let extra = if response { &RESPONSE_EXPORTS[..] } else { &[] };
    EXPORTS.iter().chain(extra).copied().collect()
}

/// The short name of an export kind ("waveform CSV").
pub fn export_name(kind: Artifact) -> &'static str {
    let label = EXPORTS.iter().chain(&RESPONSE_EXPORTS).find(|(k, _)| *k == kind).map_or("file", |(_, l)| l);
    label.split(" — ").next().unwrap_or(label)
}

/// `dir/name`, or `dir/stem-1.ext`, `dir/stem-2.ext` … the first that neither exists nor is
/// in `pending`.
pub fn unique_path(dir: &Path, name: &str, pending: &[PathBuf]) -> PathBuf {
    let free = |p: &PathBuf| !p.exists() && !pending.contains(p);
    let first = dir.join(name);
    if free(&first) {
        return first;
    }
    let (stem, ext) = match name.rsplit_once('.') {
        Some((s, e)) => (s, format!(".{e}")),
        None => (name, String::new()),
    };
    (1..).map(|n| dir.join(format!("{stem}-{n}{ext}"))).find(free).unwrap_or(first)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unique_path_skips_existing_and_pending_files() {
        let dir = tempfile::tempdir().unwrap();
        let first = dir.path().join("out.csv");
        assert_eq!(unique_path(dir.path(), "out.csv", &[]), first);
        std::fs::write(&first, "x").unwrap();
        let pending = [dir.path().join("out-1.csv")];
        assert_eq!(unique_path(dir.path(), "out.csv", &pending), dir.path().join("out-2.csv"));
    }

    #[test]
    fn each_menu_name_is_the_file_name() {
        for (kind, label) in EXPORTS {
            // "thud-fig17.svg" is "fig17 SVG", "thud-sound.wav" is "sound WAV".
            let file = kind.default_file_name();
            let (stem, ext) = file.trim_start_matches("thud-").rsplit_once('.').unwrap();
            assert_eq!(export_name(kind), format!("{stem} {}", ext.to_uppercase()), "{label}");
        }
        let restitution = EXPORTS.iter().find(|(k, _)| *k == Artifact::SvgRestitution).unwrap().1;
        assert!(restitution.contains("R against impact mass"), "it plots R, not e");
    }

    #[test]
    fn export_names_are_the_menu_labels_short_form() {
        assert_eq!(export_name(Artifact::CsvWaveform), "waveform CSV");
        assert_eq!(export_name(Artifact::Wav), "sound WAV");
        assert!(EXPORTS.iter().all(|(k, _)| !export_name(*k).contains(" — ")));
    }
}
