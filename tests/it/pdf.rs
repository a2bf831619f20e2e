#![allow(clippy::unwrap_used, clippy::expect_used, clippy::case_sensitive_file_extension_comparisons)] // a panic is how a test fails; file names here are ours
//! PDF figures: `thud export pdf` and `thud paper all --pdf`, checked as files
//! (a PDF of one page of the asked size with its font embedded) and as pictures: the exported
//! SVG and the PDF's own source tree rendered to pixels with resvg (and the PDF file itself with
//! `pdftoppm` where it is installed), then real properties of the pixels asserted — zone colours
//! at the cells, a title drawn or not, the size, digits clear of grid lines.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::thud;
use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg;
use roxmltree::Document;
use thud::design::linspace;
use thud::export::{self, pdf, Artifact, ExportOptions};
use thud::presets;

/// A chart whose cell centres lie on the axes' ticks, so every vertical and horizontal grid
/// line passes through a row or column of zone digits: 8 masses 30–100 g (10 g apart), 7 gaps
/// 2–5 cm (0.5 cm apart).
const GRID: [&str; 4] = ["--masses", "30g:100g:8", "--gaps", "2cm:5cm:7"];

fn chart_options() -> ExportOptions {
    ExportOptions {
        masses_kg: Some(linspace(0.03, 0.10, 8)),
        gaps_m: Some(linspace(0.02, 0.05, 7)),
        ..Default::default()
    }
}

fn chart_svg(opts: &ExportOptions) -> String {
    let d = presets::preset("default").unwrap().check().unwrap();
    String::from_utf8(export::render(Artifact::SvgChart, &d, opts).unwrap()).unwrap()
}

/// The SVG file parsed on its own, as any SVG reader would (a font database of the test's own
/// holding the font thud ships, so no system font is needed).
fn svg_file_tree(svg: &str) -> usvg::Tree {
    let mut options = usvg::Options::default();
    options.fontdb_mut().load_font_data(pdf::FONT.to_vec());
    options.fontdb_mut().set_sans_serif_family(pdf::FONT_FAMILY);
    usvg::Tree::from_str(svg, &options).unwrap()
}

/// `tree` rendered at 1 px per SVG px on white.
fn png(tree: &usvg::Tree) -> Pixmap {
    let size = tree.size().to_int_size();
    let mut pixmap = Pixmap::new(size.width(), size.height()).unwrap();
    pixmap.fill(resvg::tiny_skia::Color::WHITE);
    resvg::render(tree, Transform::identity(), &mut pixmap.as_mut());
    pixmap
}

fn rgb(p: &Pixmap, x: f64, y: f64) -> [u8; 3] {
    let c = p.pixel(x as u32, y as u32).unwrap().demultiply();
    [c.red(), c.green(), c.blue()]
}

fn hex(color: &str) -> [u8; 3] {
    let v = u32::from_str_radix(color.trim_start_matches('#'), 16).unwrap();
    [(v >> 16) as u8, (v >> 8) as u8, v as u8]
}

fn close(a: [u8; 3], b: [u8; 3], tol: u8) -> bool {
    a.iter().zip(b).all(|(x, y)| x.abs_diff(y) <= tol)
}

/// The zone cells of a chart SVG: (x, y, w, h, fill), each with the box of its digit (the
/// digit's text element, found by position), or None for a cell without one.
struct Cell {
    rect: (f64, f64, f64, f64),
    fill: String,
}

fn cells(svg: &str) -> Vec<Cell> {
    let xml = Document::parse(svg).unwrap();
    let attr = |n: &roxmltree::Node, k: &str| n.attribute(k).unwrap().parse::<f64>().unwrap();
    xml.descendants()
        .filter(|n| n.has_tag_name("rect") && n.attribute("stroke") == Some("white"))
        .map(|n| Cell {
            rect: (attr(&n, "x"), attr(&n, "y"), attr(&n, "width"), attr(&n, "height")),
            fill: n.attribute("fill").unwrap().to_string(),
        })
        .collect()
}

/// Asserts the cells' colours: a point a quarter in from each cell's corner (clear of its
/// digit and its white border) has the cell's zone colour.
fn assert_cell_colours(p: &Pixmap, cells: &[Cell], tol: u8, what: &str) {
    assert!(cells.len() >= 56, "{what}: {} cells", cells.len());
    let mut fills: Vec<&str> = cells.iter().map(|c| c.fill.as_str()).collect();
    fills.dedup();
    assert!(fills.len() >= 2, "{what}: the chart shows more than one zone: {fills:?}");
    for c in cells {
        let (x, y, w, h) = c.rect;
        for (fx, fy) in [(0.25, 0.25), (0.75, 0.25)] {
            let got = rgb(p, x + fx * w, y + fy * h);
            assert!(close(got, hex(&c.fill), tol), "{what}: cell at ({x}, {y}) is {got:?}, not {}", c.fill);
        }
    }
}

/// The boxes (x0, y0, x1, y1 in px) of the text nodes of `tree` whose text is one of `texts`.
fn text_boxes(tree: &usvg::Tree, texts: &[&str]) -> Vec<(f32, f32, f32, f32)> {
    fn walk(g: &usvg::Group, texts: &[&str], out: &mut Vec<(f32, f32, f32, f32)>) {
        for n in g.children() {
            match n {
                usvg::Node::Group(g) => walk(g, texts, out),
                usvg::Node::Text(t)
                    if texts.iter().any(|s| t.chunks().iter().map(usvg::TextChunk::text).collect::<String>() == *s) =>
                {
                    let b = t.abs_bounding_box();
                    out.push((b.left(), b.top(), b.right(), b.bottom()));
                }
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    walk(tree.root(), texts, &mut out);
    out
}

/// Whether every pixel inside each digit's box is the cell's colour darkened towards the
/// digit's black, by one fraction for all three channels: a grid line drawn across a digit
/// (light grey over a coloured cell) leaves pixels that are no such blend.
fn digits_clear_of_grid(p: &Pixmap, tree: &usvg::Tree, cells: &[Cell]) -> Result<usize, String> {
    let boxes = text_boxes(tree, &["1", "2", "3", "4"]);
    let mut checked = 0;
    for (x0, y0, x1, y1) in &boxes {
        let (cx, cy) = (f64::from(x0 + x1) / 2.0, f64::from(y0 + y1) / 2.0);
        let cell = cells
            .iter()
            .find(|c| {
                let (x, y, w, h) = c.rect;
                (x..x + w).contains(&cx) && (y..y + h).contains(&cy)
            })
            .ok_or_else(|| format!("the digit at ({cx}, {cy}) is in no cell"))?;
        let fill = hex(&cell.fill).map(f64::from);
        for y in (y0.floor() as u32)..(y1.ceil() as u32) {
            for x in (x0.floor() as u32)..(x1.ceil() as u32) {
                let got = rgb(p, f64::from(x), f64::from(y)).map(f64::from);
                let dark: Vec<f64> = (0..3).map(|k| 1.0 - got[k] / fill[k]).collect();
                let spread =
                    dark.iter().copied().fold(f64::MIN, f64::max) - dark.iter().copied().fold(f64::MAX, f64::min);
                if spread > 0.08 || dark.iter().any(|&a| a < -0.03) {
                    return Err(format!(
                        "pixel ({x}, {y}) in a digit's box is {got:?}, no blend of {fill:?} and black"
                    ));
                }
                checked += 1;
            }
        }
    }
    if boxes.len() < 50 {
        return Err(format!("only {} digits found", boxes.len()));
    }
    Ok(checked)
}

/// Dark pixels (any channel below 128) in the box, in px.
fn dark_pixels(p: &Pixmap, (x0, y0, x1, y1): (f64, f64, f64, f64)) -> usize {
    let mut n = 0;
    for y in (y0 as u32)..(y1 as u32) {
        for x in (x0 as u32)..(x1 as u32) {
            n += usize::from(rgb(p, f64::from(x), f64::from(y)).iter().any(|&c| c < 128));
        }
    }
    n
}

/// Where the title is drawn: the top band above the plotting area, between the y axis's tick
/// labels and the legend column, in px of a figure `width` wide.
fn title_band(width: f64, no_title: bool) -> (f64, f64, f64, f64) {
    (100.0, 2.0, width - 210.0, if no_title { 17.0 } else { 45.0 })
}

#[test]
fn a_pdf_is_one_page_of_the_asked_size_with_its_font_embedded() {
    let dir = tempfile::tempdir().unwrap();
    for (size, points) in [(None, (645.0, 405.0)), (Some("1200x800"), (900.0, 600.0))] {
        let out = dir.path().join(format!("c{}.pdf", size.unwrap_or("")));
        let o = out.to_str().unwrap();
        let mut args = vec!["export", "pdf", "chart", "--out", o];
        args.extend(GRID);
        args.extend(size.iter().flat_map(|s| ["--size", s]));
        let (code, stdout, err) = thud(&args);
        assert_eq!((code, stdout.as_str()), (0, ""), "{err}");
        let bytes = std::fs::read(&out).unwrap();
        assert!(bytes.starts_with(b"%PDF-"), "{:?}", &bytes[..8]);
        let text = String::from_utf8_lossy(&bytes);
        assert_eq!(
            text.matches("/Type /Page\n").count()
                + text.matches("/Type /Page/").count()
                + text.matches("/Type /Page ").count(),
            1,
            "one page"
        );
        let media = text.split("/MediaBox [").nth(1).unwrap().split(']').next().unwrap();
        let nums: Vec<f64> = media.split_whitespace().map(|v| v.parse().unwrap()).collect();
        assert_eq!(nums.len(), 4, "{media}");
        assert!((nums[2] - points.0).abs() < 0.01 && (nums[3] - points.1).abs() < 0.01, "{size:?}: {media}");
        assert!(text.contains("/FontFile2"), "a TrueType font program is embedded");
        let base = text.split("/BaseFont /").nth(1).unwrap().split(['/', ' ', '\n', '>']).next().unwrap();
        assert!(base.ends_with("+DejaVuSans"), "the embedded font is a DejaVu Sans subset: {base}");
    }
}

#[test]
fn every_figure_converts_with_every_glyph_of_its_text_in_the_embedded_font() {
    let d = presets::preset("default").unwrap().check().unwrap();
    let opts = ExportOptions {
        masses_kg: Some(linspace(0.03, 0.06, 3)),
        gaps_m: Some(linspace(0.02, 0.04, 3)),
        points: 300,
        ..Default::default()
    };
    for kind in Artifact::ALL.into_iter().filter(|k| k.is_figure() && !k.is_response()) {
        let bytes = export::render_pdf(kind, &d, &opts).unwrap_or_else(|e| panic!("{kind:?}: {e}"));
        assert!(bytes.starts_with(b"%PDF-"), "{kind:?}");
    }
    // The response figure, of the default design under a forcing.
    let mut forced = d.clone().into_design();
    (forced.damper.force_n, forced.damper.freq_hz, forced.damper.v0_m_s) = (1.0, 4.0, 0.0);
    let forced = forced.check().unwrap();
    let ro = ExportOptions { freqs_hz: Some(linspace(3.0, 5.0, 5)), ..opts.clone() };
    let bytes = export::render_pdf(Artifact::SvgResponse, &forced, &ro).unwrap();
    assert!(bytes.starts_with(b"%PDF-"));
    // Every table figure of the paper, through `paper all --with-pdf`'s own conversion.
    let files = export::report::paper_bundle();
    let pdfs = export::report::pdf_files(&files).unwrap();
    assert_eq!(pdfs.len(), files.iter().filter(|f| f.name.ends_with(".svg")).count());
    assert!(pdfs.iter().all(|(_, b)| b.starts_with(b"%PDF-")));
    // A figure only is made a PDF.
    assert!(export::render_pdf(Artifact::CsvSweep, &d, &opts).is_err());
}

#[test]
fn the_chart_rendered_from_the_svg_and_from_the_pdf_tree_has_its_zone_colours_a_title_and_clear_digits() {
    let opts = chart_options();
    let svg = chart_svg(&opts);
    let cells = cells(&svg);
    for (what, tree) in [("SVG", svg_file_tree(&svg)), ("PDF tree", pdf::tree(&svg).unwrap())] {
        let p = png(&tree);
        assert_eq!((p.width(), p.height()), (860, 540), "{what}");
        assert_cell_colours(&p, &cells, 1, what);
        let checked = digits_clear_of_grid(&p, &tree, &cells).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(checked > 1000, "{what}: {checked} pixels");
        assert!(dark_pixels(&p, title_band(860.0, false)) > 300, "{what}: the title is drawn");
    }
    // The digit check can fail: the same chart with its grid moved over the cells fails it.
    let (grid, rest): (Vec<&str>, Vec<&str>) =
        svg.lines().partition(|l| l.starts_with("<line") && l.contains("#e6e6e6"));
    assert!(grid.len() > 10, "{} grid lines", grid.len());
    let end = rest.len() - 1;
    let over = [&rest[..end], &grid[..], &rest[end..]].concat().join("\n");
    let tree = svg_file_tree(&over);
    assert!(digits_clear_of_grid(&png(&tree), &tree, &cells).is_err(), "a grid over the digits is seen");
}

#[test]
fn no_title_and_size_show_in_the_pixels_of_svg_and_pdf() {
    let look = thud::export::svg::Look { size: Some((1200.0, 800.0)), title: false };
    let opts = ExportOptions { look, ..chart_options() };
    let svg = chart_svg(&opts);
    let cells = cells(&svg);
    for (what, tree) in [("SVG", svg_file_tree(&svg)), ("PDF tree", pdf::tree(&svg).unwrap())] {
        let p = png(&tree);
        assert_eq!((p.width(), p.height()), (1200, 800), "{what}");
        assert_cell_colours(&p, &cells, 1, what);
        assert_eq!(dark_pixels(&p, title_band(1200.0, true)), 0, "{what}: no title above the plot");
        // Past the default figure's whole width (860 px); the legend column grows with the text.
        assert!(cells.iter().any(|c| c.rect.0 + c.rect.2 > 900.0), "{what}: the cells fill the wider figure");
    }
}

/// `pdftoppm` at 96 dpi (1 px per SVG px), or None with the reason printed when it is absent.
fn pdftoppm(pdf: &Path) -> Option<Pixmap> {
    let prefix = pdf.with_extension("");
    match Command::new("pdftoppm").args(["-r", "96", "-png", "-singlefile"]).arg(pdf).arg(&prefix).status() {
        Ok(s) if s.success() => Some(Pixmap::load_png(prefix.with_extension("png")).unwrap()),
        Ok(s) => panic!("pdftoppm failed: {s}"),
        Err(e) => {
            crate::support::skip::skip(&format!(
                "the PDF itself is not rasterized, pdftoppm is not on PATH ({e}); install poppler-utils"
            ));
            None
        }
    }
}

#[test]
fn the_pdf_file_rasterized_by_pdftoppm_matches_the_svg_render() {
    let dir = tempfile::tempdir().unwrap();
    for (extra, size, titled) in
        [(&[][..], (860, 540), true), (&["--no-title", "--size", "1200x800"][..], (1200, 800), false)]
    {
        let out = dir.path().join(format!("c{}.pdf", size.0));
        let svg_out = dir.path().join(format!("c{}.svg", size.0));
        for (fmt, path) in [("pdf", &out), ("svg", &svg_out)] {
            let mut args = vec!["export", fmt, "chart", "--out", path.to_str().unwrap()];
            args.extend(GRID);
            args.extend(extra);
            let (code, _, err) = thud(&args);
            assert_eq!(code, 0, "{err}");
        }
        let svg = std::fs::read_to_string(&svg_out).unwrap();
        let Some(p) = pdftoppm(&out) else { return };
        assert_eq!((p.width(), p.height()), size, "the page rasterizes to the asked size");
        let cells = cells(&svg);
        assert_cell_colours(&p, &cells, 6, "pdftoppm");
        let reference = png(&svg_file_tree(&svg));
        let band = title_band(f64::from(size.0), !titled);
        let (ours, theirs) = (dark_pixels(&p, band), dark_pixels(&reference, band));
        if titled {
            assert!(ours > 300 && ours.abs_diff(theirs) * 4 < theirs, "title ink: pdftoppm {ours}, resvg {theirs}");
        } else {
            assert_eq!((ours, theirs), (0, 0), "no title");
        }
    }
}

#[test]
fn export_pdf_keeps_an_existing_file_and_never_follows_a_planted_link() {
    let dir = tempfile::tempdir().unwrap();
    let existing = dir.path().join("e.pdf");
    std::fs::write(&existing, "precious").unwrap();
    let o = existing.to_str().unwrap();
    let (code, out, err) = thud(&["export", "pdf", "waveform", "--out", o]);
    assert_eq!((code, out.as_str(), err.lines().count()), (2, "", 1), "{err}");
    assert!(err.contains("--force"), "{err}");
    assert_eq!(std::fs::read_to_string(&existing).unwrap(), "precious");
    let target = dir.path().join("target.txt");
    std::fs::write(&target, "kept").unwrap();
    let link = dir.path().join("l.pdf");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let (code, _, err) = thud(&["export", "pdf", "waveform", "--out", link.to_str().unwrap(), "--force"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("symbolic link"), "{err}");
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "kept");
    let (code, _, err) = thud(&["export", "pdf", "waveform", "--out", o, "--force"]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read(&existing).unwrap().starts_with(b"%PDF-"));
    let names: Vec<String> =
        std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    assert_eq!(names.len(), 3, "no temporary file left: {names:?}");
}

#[test]
fn completions_and_man_pages_offer_export_pdf() {
    let (code, fish, err) = thud(&["completions", "fish"]);
    assert_eq!(code, 0, "{err}");
    assert!(fish.contains("csv svg pdf wav"), "export's formats complete");
    assert!(fish.contains("__fish_thud_using_subcommand paper") && fish.contains("-l pdf"), "paper --pdf completes");
    let (code, page, err) = thud(&["man", "export", "pdf"]);
    assert_eq!(code, 0, "{err}");
    assert!(page.starts_with(".TH thud-export-pdf 1"), "{}", &page[..page.len().min(80)]);
    assert!(page.contains("\\-\\-no\\-title") && page.contains("\\-\\-size"), "the page lists --no-title and --size");
}

#[test]
fn paper_all_pdf_writes_a_pdf_beside_every_svg() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("paper");
    let (code, _, err) = thud(&["paper", "all", "--with-pdf", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let expected = export::report::expected_files_with(true);
    let svgs = expected.iter().filter(|n| n.ends_with(".svg")).count();
    assert!(svgs > 0 && expected.iter().filter(|n| n.ends_with(".pdf")).count() == svgs);
    for name in &expected {
        let bytes = std::fs::read(out.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        if name.ends_with(".pdf") {
            assert!(bytes.starts_with(b"%PDF-"), "{name}");
        }
    }
    // A previous set with PDFs is replaced by one without (--force), and --with-pdf needs `all`.
    let (code, _, err) = thud(&["paper", "all", "--force", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.join(expected.iter().find(|n| n.ends_with(".pdf")).unwrap()).exists());
    let (code, _, err) = thud(&["paper", "table1", "--with-pdf"]);
    assert_eq!((code, err.lines().count()), (2, 1), "{err}");
    assert!(err.contains("--with-pdf"), "{err}");
    // `--pdf` names a figure's PDF file (bifurcation, impact-map, basins); its old use here is
    // refused with one line naming the switch, and nothing is written.
    for old in [&["paper", "all", "--pdf", "--out"][..], &["paper", "all", "--out"][..]] {
        let fresh = dir.path().join("fresh");
        let mut args = old.to_vec();
        args.push(fresh.to_str().unwrap());
        if old.len() == 3 {
            args.extend(["--pdf", "x.pdf"]);
        }
        let (code, _, err) = thud(&args);
        assert_eq!((code, err.lines().count()), (2, 1), "{args:?}: {err}");
        assert!(err.contains("--with-pdf"), "{err}");
        assert!(!fresh.exists(), "{args:?}");
    }
}
