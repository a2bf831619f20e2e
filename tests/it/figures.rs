#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Figures ready for a paper: the zone chart's grid under its cells, legend glyphs drawn as their
//! series are, no colour used twice in a figure (the paper's and the model's curve of one gap in
//! one colour), round colour-bar ticks, `--no-title` and `--size`.

use crate::common;
use std::collections::BTreeSet;

use common::thud;
use roxmltree::{Document, Node};
use thud::design::{linspace, Thresholds};
use thud::export::svg::Look;
use thud::export::{self, figures, Artifact, ExportOptions};
use thud::{paper, presets};

fn small_grid() -> ExportOptions {
    ExportOptions {
        masses_kg: Some(linspace(0.03, 0.06, 4)),
        gaps_m: Some(linspace(0.02, 0.04, 3)),
        ..Default::default()
    }
}

fn svg_of(kind: Artifact) -> String {
    let d = presets::preset("default").unwrap().check().unwrap();
    String::from_utf8(export::render(kind, &d, &small_grid()).unwrap()).unwrap()
}

fn attr(n: &Node, name: &str) -> f64 {
    n.attribute(name).unwrap().parse().unwrap()
}

fn paper_svg(id: &str) -> String {
    let table = paper::get(id).unwrap().unwrap();
    figures::paper_figure(&table, &Thresholds::default(), &Look::default()).unwrap()
}

#[test]
fn the_zone_chart_draws_its_grid_under_the_cells_and_no_line_over_a_digit() {
    let doc = svg_of(Artifact::SvgChart);
    let xml = Document::parse(&doc).unwrap();
    let order: Vec<Node> = xml.descendants().filter(Node::is_element).collect();
    let first_cell =
        order.iter().position(|n| n.has_tag_name("rect") && n.attribute("stroke") == Some("white")).expect("cells");
    let grid: Vec<usize> = (0..order.len())
        .filter(|&i| order[i].has_tag_name("line") && order[i].attribute("stroke") == Some("#e6e6e6"))
        .collect();
    assert!(!grid.is_empty(), "the chart has a grid");
    assert!(grid.iter().all(|&i| i < first_cell), "every grid line is drawn before (under) the cells");
    // No line drawn after the cells passes through a zone digit.
    let digits: Vec<(f64, f64)> = order
        .iter()
        .filter(|n| n.has_tag_name("text") && n.text().is_some_and(|t| ["1", "2", "3", "4"].contains(&t)))
        .map(|n| (attr(n, "x"), attr(n, "y")))
        .collect();
    assert!(!digits.is_empty());
    for line in order[first_cell..].iter().filter(|n| n.has_tag_name("line")) {
        let (x1, y1, x2, y2) = (attr(line, "x1"), attr(line, "y1"), attr(line, "x2"), attr(line, "y2"));
        for &(x, y) in &digits {
            let near_x = (x1.min(x2) - 6.0..=x1.max(x2) + 6.0).contains(&x);
            let near_y = (y1.min(y2) - 12.0..=y1.max(y2) + 4.0).contains(&y);
            assert!(!(near_x && near_y), "a line crosses the digit at ({x}, {y})");
        }
    }
}

/// (stroke, dashed) of every polyline, and the legend's glyphs: (stroke, dashed) of its lines and
/// the fills of its markers, right of the plotting area's right edge `right`.
#[allow(clippy::type_complexity)]
fn series_and_legend(doc: &str, right: f64) -> (BTreeSet<(String, bool)>, BTreeSet<(String, bool)>, BTreeSet<String>) {
    let xml = Document::parse(doc).unwrap();
    let dashed = |n: &Node| n.attribute("stroke-dasharray").is_some();
    let curves = xml
        .descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .map(|n| (n.attribute("stroke").unwrap().to_string(), dashed(&n)))
        .collect();
    let legend_lines = xml
        .descendants()
        .filter(|n| n.has_tag_name("line") && attr(n, "x1") > right)
        .map(|n| (n.attribute("stroke").unwrap().to_string(), dashed(&n)))
        .collect();
    let legend_marks = xml
        .descendants()
        .filter(|n| (n.has_tag_name("circle") && attr(n, "cx") > right) || (n.has_tag_name("polygon")))
        .filter_map(|n| n.attribute("fill").map(str::to_string))
        .collect();
    (curves, legend_lines, legend_marks)
}

#[test]
fn legend_glyphs_are_drawn_as_their_series_line_dash_and_marker() {
    // Directivity: SPL as line + markers, the peak level dashed.
    let doc = svg_of(Artifact::SvgDirectivity);
    let (curves, legend_lines, legend_marks) = series_and_legend(&doc, 660.0);
    assert_eq!(curves.len(), 2, "{curves:?}");
    for c in &curves {
        assert!(legend_lines.contains(c), "legend line for {c:?}: {legend_lines:?}");
    }
    let solid = curves.iter().find(|c| !c.1).unwrap();
    assert!(legend_marks.contains(&solid.0), "the line + markers series has its marker in the legend");
    let dashed = curves.iter().find(|c| c.1).unwrap();
    assert!(!legend_marks.contains(&dashed.0), "the dashed series has no marker");
    assert!(!doc.contains(r##"height="10" fill="#1f77b4""##), "no plain swatch for a line series");
}

#[test]
fn no_colour_stands_for_two_curves_and_paper_and_model_share_a_gap_s_colour() {
    // Fig 10: one curve per impact mass (15 of them, more than the palette's 10).
    let doc = paper_svg("fig10");
    let (curves, _, _) = series_and_legend(&doc, 660.0);
    let xml = Document::parse(&doc).unwrap();
    let strokes: Vec<&str> =
        xml.descendants().filter(|n| n.has_tag_name("polyline")).map(|n| n.attribute("stroke").unwrap()).collect();
    assert!(strokes.len() >= 15, "{}", strokes.len());
    assert_eq!(curves.len(), strokes.len(), "every curve has a colour of its own: {strokes:?}");
    // Table 3: the paper's points and the model's line of each gap in one colour, gaps apart.
    let doc = paper_svg("table3");
    let xml = Document::parse(&doc).unwrap();
    let lines: BTreeSet<&str> =
        xml.descendants().filter(|n| n.has_tag_name("polyline")).map(|n| n.attribute("stroke").unwrap()).collect();
    let points: BTreeSet<&str> = xml
        .descendants()
        .filter(|n| n.has_tag_name("circle") && attr(n, "cx") < 660.0)
        .map(|n| n.attribute("fill").unwrap())
        .collect();
    assert!(lines.len() >= 3, "one colour per gap: {lines:?}");
    assert_eq!(lines, points, "the paper's points and the model's line of a gap share its colour");
}

#[test]
fn colour_bar_ticks_are_round_numbers() {
    for id in ["fig15", "fig16"] {
        let doc = paper_svg(id);
        let xml = Document::parse(&doc).unwrap();
        let ticks: Vec<f64> = xml
            .descendants()
            .filter(|n| n.has_tag_name("text") && attr(n, "x") > 690.0)
            .filter_map(|n| n.text().and_then(|t| t.parse::<f64>().ok()))
            .collect();
        assert!(ticks.len() >= 3, "{id}: {ticks:?}");
        let step = (ticks[1] - ticks[0]).abs();
        let mag = 10f64.powf(step.log10().floor());
        let mantissa = step / mag;
        assert!([1.0, 2.0, 5.0].iter().any(|m| (mantissa - m).abs() < 1e-9), "{id}: step {step}");
        for t in &ticks {
            let k = t / step;
            assert!((k - k.round()).abs() < 1e-6, "{id}: {t} is not a multiple of {step}");
        }
    }
}

#[test]
fn svg_no_title_and_size_change_the_figure_and_bad_sizes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c.svg");
    let o = out.to_str().unwrap();
    let grid = ["--masses", "30g:60g:3", "--gaps", "2cm:4cm:3"];
    let (code, _, err) =
        thud(&[&["export", "svg", "chart", "--no-title", "--size", "1200x800", "--out", o][..], &grid[..]].concat());
    assert_eq!(code, 0, "{err}");
    let doc = std::fs::read_to_string(&out).unwrap();
    let xml = Document::parse(&doc).unwrap();
    let root = xml.root_element();
    assert_eq!((root.attribute("width"), root.attribute("height")), (Some("1200"), Some("800")));
    let title = root.children().find(|n| n.has_tag_name("title")).unwrap().text().unwrap().to_string();
    assert!(title.starts_with("Design chart"), "the <title> stays: {title}");
    assert!(!xml.descendants().any(|n| n.has_tag_name("text") && n.text() == Some(title.as_str())), "no drawn title");
    // The plot fills the new size: its box reaches past the default width.
    let boxes: Vec<f64> = xml
        .descendants()
        .filter(|n| n.has_tag_name("rect") && n.attribute("fill") == Some("none"))
        .map(|n| attr(&n, "x") + attr(&n, "width"))
        .collect();
    assert!(boxes.iter().any(|&r| r > 900.0 && r <= 1200.0), "{boxes:?}");
    for bad in ["0x0", "100x100", "5000x800", "1200", "wide", "1200x-8", "nanxnan"] {
        let path = dir.path().join("bad.svg");
        let (code, out, err) = thud(&["export", "svg", "waveform", "--size", bad, "--out", path.to_str().unwrap()]);
        assert_eq!((code, out.as_str()), (2, ""), "{bad}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("--size") && err.contains(bad) && err.contains("480 to 4000"), "{err}");
        assert!(!path.exists());
    }
}
