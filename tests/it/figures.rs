#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Figures ready for a paper: the zone chart's grid under its cells, legend glyphs drawn as their
//! series are, no colour used twice in a figure (the paper's and the model's curve of one gap in
//! one colour), round colour-bar ticks, `--no-title` and `--size`.

use crate::common;
use std::collections::BTreeSet;

use common::thud;
use roxmltree::{Document, Node};
use thud::design::{linspace, Thresholds};
use thud::export::svg::{Look, PALETTE};
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
    assert!(!doc.contains(&format!(r#"height="10" fill="{}""#, PALETTE[0])), "no plain swatch for a line series");
}

#[test]
fn no_two_curves_look_alike_and_paper_and_model_share_a_gap_s_colour() {
    // Fig 10: one curve per impact mass (15 of them, more than the palette's 7 colours): each
    // in a palette colour, and no two with the same colour and dash pattern.
    for id in ["fig10", "fig11", "fig14"] {
        let doc = paper_svg(id);
        let xml = Document::parse(&doc).unwrap();
        let looks: Vec<(String, String)> = xml
            .descendants()
            .filter(|n| n.has_tag_name("polyline"))
            .map(|n| {
                let dash = n.attribute("stroke-dasharray").unwrap_or("solid").to_string();
                (n.attribute("stroke").unwrap().to_string(), dash)
            })
            .collect();
        assert!(looks.len() >= 10, "{id}: {}", looks.len());
        let distinct: BTreeSet<&(String, String)> = looks.iter().collect();
        assert_eq!(distinct.len(), looks.len(), "{id}: two curves look alike: {looks:?}");
        assert!(looks.iter().all(|(c, _)| PALETTE.contains(&c.as_str())), "{id}: {looks:?}");
    }
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

/// The texts of `doc` right of x = `right` (the legend), top to bottom.
fn legend_texts(doc: &str, right: f64) -> Vec<String> {
    let xml = Document::parse(doc).unwrap();
    let mut t: Vec<(f64, String)> = xml
        .descendants()
        .filter(|n| n.has_tag_name("text") && attr(n, "x") > right)
        .map(|n| (attr(&n, "y"), n.text().unwrap_or_default().to_string()))
        .collect();
    t.sort_by(|a, b| a.0.total_cmp(&b.0));
    t.into_iter().map(|p| p.1).collect()
}

#[test]
fn the_legend_lists_the_curves_in_the_order_they_lie() {
    // Fig 11: SPLmax against mass, one curve per gap. The legend runs top to bottom as the
    // curves end at the right edge, highest first.
    let table = paper::get("fig11").unwrap().unwrap();
    let series_end: Vec<(String, f64)> = {
        let gap = table.columns.iter().position(|c| c.key == "gap_cm").unwrap();
        let spl = table.columns.iter().position(|c| c.key == "spl_max_db").unwrap();
        let mass = table.columns.iter().position(|c| c.key == "mass_g").unwrap();
        let num = |v: &paper::Value| if let paper::Value::Num(x) = v { *x } else { f64::NAN };
        let mut ends: Vec<(f64, f64, f64)> = Vec::new(); // (gap, mass, spl) of the largest mass per gap
        for row in &table.rows {
            let (g, m, y) = (num(&row[gap]), num(&row[mass]), num(&row[spl]));
            match ends.iter_mut().find(|e| e.0 == g) {
                Some(e) if m > e.1 && y.is_finite() => *e = (g, m, y),
                Some(_) => {}
                None if y.is_finite() => ends.push((g, m, y)),
                None => {}
            }
        }
        ends.sort_by(|a, b| b.2.total_cmp(&a.2));
        ends.into_iter().map(|e| (thud::units::short(e.0), e.2)).collect()
    };
    let doc = paper_svg("fig11");
    let legend: Vec<String> = legend_texts(&doc, 660.0);
    let order: Vec<String> =
        legend.iter().map(|l| l.split_whitespace().nth(1).unwrap_or_default().to_string()).collect();
    let want: Vec<String> = series_end.iter().map(|e| e.0.clone()).collect();
    assert_eq!(order, want, "legend {legend:?}");
}

#[test]
fn axes_fit_the_data_on_round_ticks_with_a_true_minus_and_units() {
    let ticks = |doc: &str, below: f64| -> Vec<String> {
        let xml = Document::parse(doc).unwrap();
        xml.descendants()
            .filter(|n| n.has_tag_name("text") && attr(n, "y") > below && attr(n, "y") < below + 40.0)
            .filter(|n| n.attribute("text-anchor") == Some("middle"))
            .map(|n| n.text().unwrap().to_string())
            .collect()
    };
    // Fig 3: θ from −90° to 90°, not ±100°.
    let doc = paper_svg("fig3");
    let xml = Document::parse(&doc).unwrap();
    let frame = xml
        .descendants()
        .find(|n| n.has_tag_name("rect") && n.attribute("fill") == Some("none"))
        .map(|n| attr(&n, "y") + attr(&n, "height"))
        .unwrap();
    let x_ticks = ticks(&doc, frame);
    assert_eq!(x_ticks.first().map(String::as_str), Some("\u{2212}90"), "{x_ticks:?}");
    assert_eq!(x_ticks.iter().rev().find(|t| t.parse::<f64>().is_ok()).map(String::as_str), Some("90"), "{x_ticks:?}");
    assert!(!doc.contains(">-"), "a hyphen for a minus sign");
    // Figs 7 and 12: r from 0.05 m to 20 m, not 0.01–100 m.
    for id in ["fig7", "fig12"] {
        let doc = paper_svg(id);
        let labels = ticks(&doc, frame);
        assert!(labels.contains(&"0.05".to_string()) && labels.contains(&"20".to_string()), "{id}: {labels:?}");
        assert!(!labels.contains(&"100".to_string()) && !labels.contains(&"0.01".to_string()), "{id}: {labels:?}");
    }
    // Every axis label of every figure carries a unit in parentheses.
    for kind in [Artifact::SvgWaveform, Artifact::SvgDirectivity, Artifact::SvgHistory, Artifact::SvgRestitution] {
        let doc = svg_of(kind);
        let xml = Document::parse(&doc).unwrap();
        let rotated: Vec<&str> = xml
            .descendants()
            .filter(|n| n.has_tag_name("text") && n.attribute("transform").is_some())
            .map(|n| n.text().unwrap())
            .collect();
        assert!(!rotated.is_empty() && rotated.iter().all(|l| l.ends_with(')')), "{kind:?}: {rotated:?}");
    }
}

#[test]
fn titles_say_what_is_plotted() {
    let doc = paper_svg("table3");
    let xml = Document::parse(&doc).unwrap();
    let title = xml.root_element().children().find(|n| n.has_tag_name("title")).unwrap().text().unwrap();
    assert!(title.contains("SPLmax") && !title.contains("U0max"), "{title}");
}

#[test]
fn text_grows_with_the_figure_s_size() {
    let sizes = |look: &Look| -> f64 {
        let table = paper::get("fig11").unwrap().unwrap();
        let doc = figures::paper_figure(&table, &Thresholds::default(), look).unwrap();
        let xml = Document::parse(&doc).unwrap();
        let s: Vec<f64> = xml.descendants().filter(|n| n.has_tag_name("text")).map(|n| attr(&n, "font-size")).collect();
        s.iter().sum::<f64>() / s.len() as f64
    };
    let small = sizes(&Look::default());
    let big = sizes(&Look { size: Some((1720.0, 1080.0)), title: true });
    assert!((big / small - 2.0).abs() < 0.05, "{small} → {big}");
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
