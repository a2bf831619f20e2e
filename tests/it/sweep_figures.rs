//! `thud sweep --svg/--pdf`: the figure of a study over one or two parameters (`--vary`), of
//! an ensemble chart (`--ensemble N`) and of the zone chart, written with the table as one set
//! of files: checked before the work, kept unless --force, never through a planted symbolic
//! link, refused for what cannot be drawn.

use std::fs;
use std::path::Path;
use std::time::Duration;

use crate::common::{thud_within, Ran};

fn run(dir: &Path, args: &[&str]) -> Ran {
    thud_within(dir, args, Duration::from_secs(120))
}

/// Exit 2 with one line on stderr holding every needle, nothing on stdout.
fn refused(r: &Ran, needles: &[&str]) {
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stdout.is_empty(), "{}", r.stdout);
    assert_eq!(r.stderr.trim_end().lines().count(), 1, "{}", r.stderr);
    for n in needles {
        assert!(r.stderr.contains(n), "{n:?} not in {}", r.stderr);
    }
}

fn title(svg: &str) -> String {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants().find(|n| n.has_tag_name("title")).and_then(|n| n.text()).unwrap_or_default().to_string()
}

#[test]
fn a_study_over_one_parameter_draws_a_point_for_every_value_with_a_metric() {
    let home = tempfile::tempdir().unwrap();
    let args = ["sweep", "--vary", "v0=0.5:2.5:5", "--json", "--out", "s.json", "--svg", "s.svg", "--pdf", "s.pdf"];
    let r = run(home.path(), &args);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.is_empty(), "the table went to --out: {}", r.stdout);
    let svg = fs::read_to_string(home.path().join("s.svg")).unwrap();
    assert_eq!(title(&svg), "Study over v0 0.5–2.5 m/s");
    assert!(fs::read(home.path().join("s.pdf")).unwrap().starts_with(b"%PDF-"));
    // Every cell's e and SPLmax that the table holds is a marker of the figure (one series a
    // panel, so no legend's marker among them).
    let v: serde_json::Value = serde_json::from_str(&fs::read_to_string(home.path().join("s.json")).unwrap()).unwrap();
    let cells = v["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 5);
    let with = |key: &str| cells.iter().filter(|c| c[key].is_number()).count();
    let values = with("inclination_cm_s") + with("spl_max_db");
    assert!(values >= 5, "most strikes make impacts: {values}");
    assert_eq!(svg.matches("<circle").count(), values, "one marker per value");
    for label in ["damping inclination e (cm/s)", "SPLmax (dB re 20 µPa)", "v0 (m/s)"] {
        assert!(svg.contains(&format!(">{label}<")), "{label}");
    }
    assert!(!svg.contains("steady amplitude"), "no force, no steady amplitude");
}

#[test]
fn a_study_over_two_parameters_draws_a_heat_map_per_metric_and_a_forced_one_its_amplitude() {
    let home = tempfile::tempdir().unwrap();
    let args = [
        "sweep",
        "--force-amplitude",
        "1N",
        "--v0",
        "0",
        "--duration",
        "4",
        "--vary",
        "freq=4Hz:6Hz:4",
        "--vary",
        "gap=2cm:4cm:3",
        "--svg",
        "m.svg",
    ];
    let r = run(home.path(), &args);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains("amplitude (mm)"), "the table still goes to standard output: {}", r.stdout);
    let svg = fs::read_to_string(home.path().join("m.svg")).unwrap();
    assert_eq!(title(&svg), "Study over freq 4–6 Hz × gap 0.02–0.04 m");
    assert!(svg.contains(">steady amplitude (mm)<"), "the forced study's third map");
    // Each map: 4 × 3 cells (across × up), each filled; the maps' frames are three.
    let frames = svg.matches(r#"fill="none" stroke="black""#).count();
    assert!(frames >= 3, "{frames} frames");
}

#[test]
fn an_ensemble_chart_draws_each_cell_s_median_and_spread() {
    let home = tempfile::tempdir().unwrap();
    let args = ["sweep", "--masses", "30g:60g:3", "--gaps", "2cm:4cm:2", "--ensemble", "3", "--svg", "e.svg"];
    let r = run(home.path(), &args);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let svg = fs::read_to_string(home.path().join("e.svg")).unwrap();
    assert!(title(&svg).starts_with("Ensemble chart: 3 runs a cell over impact mass × gap"), "{}", title(&svg));
    for caption in ["median damping inclination e of the 3 runs", "spread of e: p90 − p10", "spread of SPLmax"] {
        assert!(svg.contains(caption), "{caption}");
    }
    // The plain chart draws the zones.
    let r = run(home.path(), &["sweep", "--masses", "30g:60g:3", "--gaps", "2cm:4cm:2", "--svg", "z.svg"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(title(&fs::read_to_string(home.path().join("z.svg")).unwrap()).starts_with("Design chart"));
}

#[test]
fn an_existing_figure_is_kept_without_force_and_a_planted_link_is_never_followed() {
    let home = tempfile::tempdir().unwrap();
    let h = home.path();
    fs::write(h.join("old.svg"), "kept").unwrap();
    let r = run(h, &["sweep", "--vary", "v0=1:2:2", "--svg", "old.svg", "--out", "t.txt"]);
    refused(&r, &["old.svg"]);
    assert_eq!(fs::read_to_string(h.join("old.svg")).unwrap(), "kept");
    assert!(!h.join("t.txt").exists(), "nothing of the set is written");
    let r = run(h, &["sweep", "--vary", "v0=1:2:2", "--svg", "old.svg", "--out", "t.txt", "--force"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(fs::read_to_string(h.join("old.svg")).unwrap().contains("<title>Study over v0 1–2 m/s</title>"));
    assert!(fs::read_to_string(h.join("t.txt")).unwrap().contains("study"));
    // A symbolic link where the figure goes: refused, with --force too; its target untouched.
    fs::write(h.join("target"), "precious").unwrap();
    std::os::unix::fs::symlink(h.join("target"), h.join("link.svg")).unwrap();
    let r = run(h, &["sweep", "--vary", "v0=1:2:2", "--svg", "link.svg", "--force"]);
    refused(&r, &["link.svg"]);
    assert_eq!(fs::read_to_string(h.join("target")).unwrap(), "precious");
}

#[test]
fn what_cannot_be_drawn_is_refused_naming_the_flag() {
    let home = tempfile::tempdir().unwrap();
    let h = home.path();
    let three = ["sweep", "--vary", "v0=1:2:2", "--vary", "c1=10:20:2", "--vary", "gap=2cm:3cm:2"];
    refused(&run(h, &[&three[..], &["--svg", "a.svg"]].concat()), &["--svg", "3", "two --vary"]);
    refused(&run(h, &[&three[..], &["--pdf", "a.pdf"]].concat()), &["--pdf"]);
    let r = run(h, &["sweep", "--vary", "v0=1:2:2", "--shard", "0/2", "--svg", "a.svg"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("--svg") && r.stderr.contains("--shard"), "{}", r.stderr);
    assert!(fs::read_dir(h)
        .unwrap()
        .filter_map(Result::ok)
        .all(|e| !e.file_name().to_string_lossy().ends_with(".svg")));
}
