//! Figures under `--ascii`: every figure thud writes — `export svg|pdf`,
//! `paper all`, the `--svg` of the studies of orbits — holds only ASCII text with `--ascii`
//! (the minus sign `-`, `^2`, `theta`, `u` for micro, `tau`), each character spelled rather than
//! dropped, while the default keeps the true minus sign and the Unicode units.

use std::fs;
use std::path::Path;

use crate::common::thud_in;

/// `text`'s characters beyond ASCII, as the explorer's `--ascii` spells them, escaped for XML.
fn folded(text: &str) -> String {
    let mut buf = [0u8; 4];
    text.chars()
        .map(|c| {
            if c.is_ascii() {
                c.to_string()
            } else {
                thud::export::svg::escape(&thud::tui::theme::fold(c.encode_utf8(&mut buf)))
            }
        })
        .collect()
}

/// The text of every `<text>` and the `<title>` of an SVG document.
fn texts(svg: &str) -> Vec<String> {
    let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("not XML: {e}\n{svg}"));
    doc.descendants()
        .filter(|n| n.has_tag_name("text") || n.has_tag_name("title"))
        .filter_map(|n| n.text())
        .map(String::from)
        .collect()
}

/// Checks the pair (default, `--ascii`) of one figure named `what`: the ASCII one is pure ASCII
/// and valid XML, is the default with each character spelled, and spells no `?` (a default
/// figure all in ASCII is the same with `--ascii`).
fn check_pair(what: &str, default: &str, ascii: &str) {
    assert!(ascii.is_ascii(), "{what}: non-ASCII under --ascii: {:?}", ascii.chars().find(|c| !c.is_ascii()));
    assert_eq!(ascii, folded(default), "{what}: --ascii is not the default spelled in ASCII");
    for t in texts(ascii) {
        assert!(!t.contains('?'), "{what}: a character left unspelled in {t:?}");
    }
}

fn run_ok(home: &Path, args: &[&str]) {
    let (code, _, err) = thud_in(home, args);
    assert_eq!(code, 0, "{args:?}: {err}");
}

#[test]
fn every_export_figure_is_pure_ascii_with_ascii_and_keeps_the_true_minus_without() {
    let home = tempfile::tempdir().unwrap();
    let at = |name: &str| home.path().join(name).to_string_lossy().into_owned();
    let grid = ["--masses", "30g:60g:3", "--gaps", "2cm:4cm:3"];
    let forced = ["--preset", "forced-rattle", "--freqs", "6Hz:9Hz:4", "--periods", "20"];
    let mut minus = Vec::new();
    for what in ["waveform", "directivity", "history", "restitution", "chart", "fig17", "response"] {
        let extra: &[&str] = if what == "response" { &forced } else { &grid };
        let [plain, ascii] = [format!("{what}.svg"), format!("{what}-ascii.svg")];
        let base = [&["export", "svg", what][..], extra].concat();
        run_ok(home.path(), &[&base[..], &["--out", &at(&plain)]].concat());
        run_ok(home.path(), &[&base[..], &["--ascii", "--out", &at(&ascii)]].concat());
        let plain = fs::read_to_string(home.path().join(plain)).unwrap();
        let ascii = fs::read_to_string(home.path().join(ascii)).unwrap();
        check_pair(what, &plain, &ascii);
        if texts(&plain).iter().any(|t| t.contains('\u{2212}')) {
            let hyphen = |t: &String| t.strip_prefix('-').is_some_and(|r| r.starts_with(|c: char| c.is_ascii_digit()));
            assert!(!texts(&plain).iter().any(hyphen), "{what}: a tick with a hyphen for its minus sign");
            minus.push(what);
        }
    }
    // The figures with negative ticks (the pressure pulse, the displacement history) draw them
    // with U+2212 by default.
    for what in ["waveform", "history"] {
        assert!(minus.contains(&what), "{what} has no true minus sign by default: {minus:?}");
    }
    let directivity = fs::read_to_string(home.path().join("directivity-ascii.svg")).unwrap();
    assert!(texts(&directivity).iter().any(|t| t.contains("theta") && t.contains("(deg)")), "{directivity}");
    assert!(texts(&directivity).iter().any(|t| t.contains("dB re 20 uPa")), "{directivity}");
    // A PDF drawn from the ASCII figure.
    run_ok(home.path(), &[&["export", "pdf", "waveform", "--ascii", "--out", &at("w.pdf")][..], &grid[..]].concat());
    assert!(fs::read(home.path().join("w.pdf")).unwrap().starts_with(b"%PDF-"));
}

#[test]
fn paper_all_with_ascii_writes_every_figure_in_ascii_and_the_default_keeps_unicode() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path().join("ascii");
    run_ok(home.path(), &["paper", "all", "--ascii", "--out", &dir.to_string_lossy()]);
    let defaults = thud::export::report::paper_bundle();
    let (mut figures, mut unicode) = (0, 0);
    let is_svg = |f: &&thud::export::report::BundleFile| Path::new(&f.name).extension().is_some_and(|e| e == "svg");
    for f in defaults.iter().filter(is_svg) {
        let ascii = fs::read_to_string(dir.join(&f.name)).unwrap();
        check_pair(&f.name, &f.contents, &ascii);
        figures += 1;
        unicode += usize::from(!f.contents.is_ascii());
    }
    assert!(figures >= 10 && unicode * 2 > figures, "{figures} figures, {unicode} with Unicode by default");
    // The tables are written as without --ascii (ASCII already); the report is ASCII, every
    // line of it, and its ASCII lines are the default report's.
    for f in defaults.iter().filter(|f| !is_svg(f)) {
        let written = fs::read_to_string(dir.join(&f.name)).unwrap();
        if f.name == "REPORT.md" {
            let odd: Vec<&str> = written.lines().filter(|l| !l.is_ascii()).collect();
            assert!(odd.is_empty(), "{} non-ASCII lines in REPORT.md, e.g. {:?}", odd.len(), odd.first());
            assert!(!written.contains('?'), "every symbol spelled, none unknown");
            assert!(f.contents.lines().filter(|l| !l.is_ascii()).count() > 10, "the default report keeps Unicode");
            for (a, b) in f.contents.lines().zip(written.lines()).filter(|(a, _)| a.is_ascii()) {
                assert_eq!(a, b);
            }
        } else {
            assert_eq!(written, f.contents, "{}", f.name);
        }
    }
    // One item prints a table, not a figure: --ascii is refused there, naming the flag.
    let (code, out, err) = thud_in(home.path(), &["paper", "table1", "--ascii"]);
    assert_eq!((code, out.as_str(), err.lines().count()), (2, "", 1), "{err}");
    assert!(err.contains("--ascii") && err.contains("paper all"), "{err}");
}

#[test]
fn the_figure_of_a_study_of_orbits_is_ascii_with_ascii() {
    let home = tempfile::tempdir().unwrap();
    let at = |name: &str| home.path().join(name).to_string_lossy().into_owned();
    let base = ["bifurcation", "--preset", "forced-rattle", "--vary", "f=7.5Hz:7.7Hz:3", "--periods", "20"];
    run_ok(home.path(), &[&base[..], &["--transient", "20", "--svg", &at("b.svg")]].concat());
    run_ok(home.path(), &[&base[..], &["--transient", "20", "--svg", &at("a.svg"), "--ascii"]].concat());
    let plain = fs::read_to_string(home.path().join("b.svg")).unwrap();
    let ascii = fs::read_to_string(home.path().join("a.svg")).unwrap();
    check_pair("bifurcation", &plain, &ascii);
    assert!(!plain.is_ascii(), "the title's dash is Unicode by default");
}
