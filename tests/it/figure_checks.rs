//! Figures that tell the truth, checked on every figure kind thud draws (the ones the gallery's
//! commands write, the paper's every figure among them: `pictures::made`; and the kinds the
//! gallery does not show, [`MORE`]):
//! - the legend is complete: every look a series is drawn with (a curve's colour and dash, a
//!   marker's colour and shape, a map cell's colour) is in the legend, or the legend says it
//!   leaves some out (an entry starting or ending with "…"); a figure of one look needs none;
//! - the looks' colours stay apart for people with red–green colour blindness (the check of
//!   `cvd`, on the colours each figure actually uses).
//!
//! A figure is read from its SVG: its plot areas are the frames (`rect` with `fill="none"`),
//! what is drawn inside them is data, what is drawn outside them is the legend. Continuous
//! colour scales (a colour bar of many steps) are not a legend of entries and are left out.

use crate::cvd::{closest_pair, MIN_DELTA_E};
use crate::pictures::made;
use roxmltree::{Document, Node};
use std::collections::{BTreeMap, BTreeSet};

/// The figure kinds the gallery does not show, each made by its command in a folder of its
/// own: the pulse of `export svg pulse` (a quadrupole's, and the physical model's), a
/// bifurcation diagram with continuation (its two sweeps told apart). The design front has its
/// own test below (`thud design --svg`, the same checks).
const MORE: &[(&str, &[&str])] = &[
    ("more/pulse.svg", &["export", "svg", "pulse", "--theta", "30", "--source", "quadrupole", "--out", "FILE"]),
    (
        "more/pulse-physical.svg",
        &["export", "svg", "pulse", "--model", "physical", "--sphere", "steel", "--r", "0.5", "--out", "FILE"],
    ),
    (
        "more/bifurcation-continuation.svg",
        &[
            "bifurcation",
            "--preset",
            "forced-rattle",
            "--vary",
            "f=7Hz:8Hz:6",
            "--continuation",
            "--transient",
            "20",
            "--periods",
            "4",
            "--svg",
            "FILE",
        ],
    ),
];

/// Every figure kind thud draws: the gallery's figures ([`made`]) and [`MORE`]'s.
fn figures() -> &'static BTreeMap<String, String> {
    static ALL: std::sync::OnceLock<BTreeMap<String, String>> = std::sync::OnceLock::new();
    ALL.get_or_init(|| {
        let mut all = made().figures.clone();
        for (name, args) in MORE {
            let home = tempfile::tempdir().unwrap();
            let mut args = args.to_vec();
            let out = home.path().join("figure.svg");
            let out = out.to_str().unwrap();
            *args.last_mut().unwrap() = out;
            let (code, _, err) = crate::common::thud_in(home.path(), &args);
            assert_eq!(code, 0, "{name}: {err}");
            all.insert((*name).to_string(), std::fs::read_to_string(out).unwrap());
        }
        all
    })
}

/// How one mark is drawn: what it is (a curve, a marker of a shape, a cell), its colour and
/// its dash pattern.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Look {
    kind: String,
    color: String,
    dash: String,
}

/// A plot area: x, y, width, height.
type Frame = (f64, f64, f64, f64);

/// A drawn mark: its look and where it is (its centre, or a curve's middle point).
type Mark = (Look, (f64, f64));

fn num(n: &Node, name: &str) -> f64 {
    n.attribute(name).and_then(|v| v.parse().ok()).unwrap_or(f64::NAN)
}

fn inside(frames: &[Frame], (x, y): (f64, f64)) -> bool {
    frames.iter().any(|&(fx, fy, w, h)| x >= fx - 0.5 && x <= fx + w + 0.5 && y >= fy - 0.5 && y <= fy + h + 0.5)
}

/// The points of a `points` attribute.
fn points(n: &Node) -> Vec<(f64, f64)> {
    n.attribute("points")
        .unwrap_or_default()
        .split_whitespace()
        .filter_map(|p| p.split_once(','))
        .filter_map(|(x, y)| Some((x.parse().ok()?, y.parse().ok()?)))
        .collect()
}

/// Each drawn mark of `doc` as (look, where it is): curves, markers and cells; lines of a grid,
/// axes, ticks and text are not marks. A legend's curve glyph is a short `line`.
fn marks(doc: &Document) -> (Vec<Frame>, Vec<Mark>) {
    let frames: Vec<Frame> = doc
        .descendants()
        .filter(|n| n.has_tag_name("rect") && n.attribute("fill") == Some("none"))
        .map(|n| (num(&n, "x"), num(&n, "y"), num(&n, "width"), num(&n, "height")))
        .collect();
    let in_defs = |n: &Node| n.ancestors().any(|a| a.has_tag_name("defs") || a.has_tag_name("clipPath"));
    let mut out = vec![];
    for n in doc.descendants().filter(|n| n.is_element() && !in_defs(n)) {
        let fill = n.attribute("fill").unwrap_or("black").to_string();
        let stroke = n.attribute("stroke").unwrap_or("none").to_string();
        let dash = n.attribute("stroke-dasharray").unwrap_or("solid").to_string();
        let look = |kind: &str, color: &str| Look { kind: kind.into(), color: color.into(), dash: dash.clone() };
        match n.tag_name().name() {
            "polyline" => {
                let pts = points(&n);
                if let Some(&p) = pts.get(pts.len() / 2) {
                    out.push((look("curve", &stroke), p));
                }
            }
            "line" => {
                // A short line away from every frame is a legend's curve glyph.
                let (x1, y1, x2, y2) = (num(&n, "x1"), num(&n, "y1"), num(&n, "x2"), num(&n, "y2"));
                let mid = (f64::midpoint(x1, x2), f64::midpoint(y1, y2));
                let short = (x2 - x1).hypot(y2 - y1) <= 40.0;
                if short && (y1 - y2).abs() < 0.01 && !inside(&frames, mid) && stroke != "black" {
                    out.push((look("curve", &stroke), mid));
                }
            }
            "circle" => out.push((look("marker circle", &fill), (num(&n, "cx"), num(&n, "cy")))),
            "polygon" => {
                let pts = points(&n);
                let c = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
                let k = pts.len().max(1) as f64;
                out.push((look(&format!("marker polygon{}", pts.len()), &fill), (c.0 / k, c.1 / k)));
            }
            "rect" if fill != "none" && fill != "white" => {
                let (x, y, w, h) = (num(&n, "x"), num(&n, "y"), num(&n, "width"), num(&n, "height"));
                let square_marker = (w - h).abs() < 0.01 && w < 12.0 && n.attribute("stroke").is_none();
                let kind = if square_marker { "marker square" } else { "cell" };
                out.push((Look { kind: kind.into(), color: fill, dash: "solid".into() }, (x + w / 2.0, y + h / 2.0)));
            }
            _ => {}
        }
    }
    (frames, out)
}

/// The texts of `doc` outside its frames (the legend's words, the axes' too).
fn texts_outside(doc: &Document, frames: &[Frame]) -> Vec<String> {
    doc.descendants()
        .filter(|n| n.has_tag_name("text") && !inside(frames, (num(n, "x"), num(n, "y"))))
        .filter_map(|n| n.text().map(str::to_string))
        .collect()
}

/// A map's cells or a colour bar: more than this many colours of cell is a continuous scale.
const SCALE_COLORS: usize = 12;

/// What one figure draws: its data looks and its legend's.
fn looks_of(svg: &str) -> (BTreeSet<Look>, BTreeSet<Look>, bool) {
    let doc = Document::parse(svg).unwrap();
    let (frames, marks) = marks(&doc);
    let (mut data, mut legend) = (BTreeSet::new(), BTreeSet::new());
    for (look, at) in marks {
        if inside(&frames, at) {
            data.insert(look);
        } else {
            legend.insert(look);
        }
    }
    let cell_colors = |s: &BTreeSet<Look>| s.iter().filter(|l| l.kind == "cell").count();
    let scale = cell_colors(&data) > SCALE_COLORS || cell_colors(&legend) > SCALE_COLORS;
    if scale {
        data.retain(|l| l.kind != "cell");
        legend.retain(|l| l.kind != "cell");
    }
    let says_more = texts_outside(&doc, &frames).iter().any(|t| t.trim().starts_with('…') || t.trim().ends_with('…'));
    (data, legend, says_more)
}

#[test]
fn every_figure_s_legend_names_every_look_it_draws() {
    let figures = figures();
    assert!(figures.len() >= 28, "every figure kind: {:?}", figures.keys());
    for (name, svg) in figures {
        let (data, legend, says_more) = looks_of(svg);
        // One series (one colour, one dash, one marker shape: a line with its markers) needs
        // no legend; its axes say what it is.
        let count = |f: &dyn Fn(&Look) -> Option<String>| data.iter().filter_map(f).collect::<BTreeSet<_>>().len();
        let one_series = count(&|l| Some(l.color.clone())) <= 1
            && count(&|l| (l.kind == "curve").then(|| l.dash.clone())) <= 1
            && count(&|l| (l.kind != "curve").then(|| l.kind.clone())) <= 1;
        if one_series || says_more {
            continue;
        }
        let missing: Vec<&Look> = data.iter().filter(|l| !legend.contains(l)).collect();
        assert!(missing.is_empty(), "{name}: drawn but not in the legend (nor a “…”): {missing:?}\nlegend: {legend:?}");
    }
}

#[test]
fn the_legend_check_fails_on_a_missing_entry_and_passes_on_an_ellipsis() {
    let frame = r#"<rect x="10" y="10" width="100" height="100" fill="none" stroke="black"/>"#;
    let curve = |c: &str| format!(r#"<polyline points="20,20 60,60 100,30" fill="none" stroke="{c}"/>"#);
    let glyph = |c: &str, y: u32| format!(r#"<line x1="120" y1="{y}" x2="144" y2="{y}" stroke="{c}"/>"#);
    let doc = |body: String| format!(r#"<svg xmlns="http://www.w3.org/2000/svg">{frame}{body}</svg>"#);
    let complete =
        doc(format!("{}{}{}{}", curve("#0072B2"), curve("#D55E00"), glyph("#0072B2", 20), glyph("#D55E00", 40)));
    let (data, legend, more) = looks_of(&complete);
    assert_eq!((data.len(), more), (2, false));
    assert!(data.is_subset(&legend));
    let short = doc(format!("{}{}{}", curve("#0072B2"), curve("#D55E00"), glyph("#0072B2", 20)));
    let (data, legend, more) = looks_of(&short);
    assert!(!data.is_subset(&legend) && !more, "a curve missing from the legend is seen");
    let said = short.replace("</svg>", r#"<text x="120" y="60">… and 1 more</text></svg>"#);
    assert!(looks_of(&said).2, "a legend that says it leaves some out");
}

#[test]
fn every_figure_s_colours_stay_apart_for_red_green_colour_blindness() {
    for (name, svg) in figures() {
        let (data, legend, _) = looks_of(svg);
        // The colours that tell series apart: of the data's looks, and the legend's entries.
        let colors: BTreeSet<&str> = data
            .iter()
            .chain(&legend)
            .map(|l| l.color.as_str())
            .filter(|c| c.starts_with('#') && c.len() == 7)
            .collect();
        let colors: Vec<&str> = colors.into_iter().collect();
        if colors.len() < 2 {
            continue;
        }
        let (d, vision, a, b) = closest_pair(&colors);
        assert!(d >= MIN_DELTA_E, "{name}: {a} and {b} are ΔE00 {d:.1} apart with {vision}");
    }
}

#[test]
fn titles_name_what_varies_over_the_whole_range_drawn() {
    // The bifurcation diagram of the gallery runs f over 6.5–8 Hz: its title says so, not the
    // design's own frequency.
    let svg = &made().pictures["bifurcation.svg"];
    let doc = Document::parse(svg).unwrap();
    let title = doc.descendants().find(|n| n.has_tag_name("title")).and_then(|n| n.text()).unwrap();
    assert!(title.contains("6.5–8 Hz") && !title.contains("7.5 Hz"), "{title}");
    // A forced run's history is not a free decay, and its force is printed as it was given.
    let svg = &made().pictures["forced.svg"];
    let doc = Document::parse(svg).unwrap();
    let title = doc.descendants().find(|n| n.has_tag_name("title")).and_then(|n| n.text()).unwrap();
    assert!(title.starts_with("Forced vibration under F0 1 N at 5.5 Hz"), "{title}");
    let svg = &made().pictures["history.svg"];
    assert!(svg.contains("<title>Free vibration with and without"), "the free decay's title");
}

/// The box a text covers (x0, y0, x1, y1): about 0.55 em a character, from its baseline up one
/// em and down a quarter.
fn text_box(n: &Node) -> (f64, f64, f64, f64) {
    let (x, y, size) =
        (num(n, "x"), num(n, "y"), n.attribute("font-size").and_then(|s| s.parse().ok()).unwrap_or(11.0));
    let w = 0.55 * size * n.text().unwrap_or_default().chars().count() as f64;
    let x0 = match n.attribute("text-anchor") {
        Some("middle") => x - w / 2.0,
        Some("end") => x - w,
        _ => x,
    };
    (x0, y - 0.75 * size, x0 + w, y + 0.25 * size)
}

#[test]
fn labels_inside_a_plot_sit_clear_of_its_data() {
    let mut checked = 0;
    for (name, svg) in figures() {
        let doc = Document::parse(svg).unwrap();
        let (frames, marks) = marks(&doc);
        // Every marker's centre and every point of every curve inside a plot.
        let mut data: Vec<(f64, f64)> =
            marks.iter().filter(|(l, at)| l.kind.starts_with("marker") && inside(&frames, *at)).map(|m| m.1).collect();
        for n in doc.descendants().filter(|n| n.has_tag_name("polyline")) {
            data.extend(points(&n).into_iter().filter(|p| inside(&frames, *p)));
        }
        // Texts drawn inside a plot on white (a cell's letter or digit is on its cell, not on data).
        for n in doc.descendants().filter(|n| n.has_tag_name("text") && n.attribute("transform").is_none()) {
            if !inside(&frames, (num(&n, "x"), num(&n, "y"))) || n.attribute("fill") == Some("white") {
                continue;
            }
            let is_digit = n.text().is_some_and(|t| t.len() <= 2 && t.chars().all(|c| c.is_ascii_alphanumeric()));
            if is_digit {
                continue;
            }
            // The text's box grown by a marker's radius (3 px): a marker's edge counts too.
            let (x0, y0, x1, y1) = text_box(&n);
            let (xs, ys) = (x0 - 3.0..=x1 + 3.0, y0 - 3.0..=y1 + 3.0);
            let on: Vec<&(f64, f64)> = data.iter().filter(|(x, y)| xs.contains(x) && ys.contains(y)).collect();
            assert!(on.is_empty(), "{name}: the label {:?} sits on data at {on:?}", n.text());
            checked += 1;
        }
    }
    assert!(checked >= 4, "the zone and threshold labels of Fig 17 are checked: {checked}");
}

#[test]
fn the_design_front_figure_names_every_look_and_keeps_its_colours_apart() {
    // `thud design --svg`: the front over every design evaluated, in the objectives and (two
    // numeric variables) in the variables; the same two checks as every gallery figure.
    let home = tempfile::tempdir().unwrap();
    let svg = home.path().join("front.svg");
    let args = crate::support::design_problem::paper_problem_with(&[
        "--evaluations",
        "40",
        "--seed",
        "1",
        "--svg",
        svg.to_str().unwrap(),
        "--json",
    ]);
    let (code, _, err) = crate::common::thud_in(home.path(), &args);
    assert_eq!(code, 0, "{err}");
    let doc = std::fs::read_to_string(&svg).unwrap();
    let (data, legend, _) = looks_of(&doc);
    assert!(data.len() >= 2, "the designs and the front: {data:?}");
    assert!(data.iter().any(|l| l.kind == "cell"), "the zone chart behind the variables' designs: {data:?}");
    let missing: Vec<&Look> = data.iter().filter(|l| !legend.contains(l)).collect();
    assert!(missing.is_empty(), "drawn but not in the legend: {missing:?}");
    let colors: Vec<&str> = data.iter().map(|l| l.color.as_str()).collect::<BTreeSet<_>>().into_iter().collect();
    let (d, vision, a, b) = closest_pair(&colors);
    assert!(d >= MIN_DELTA_E, "{a} and {b} are ΔE00 {d:.1} apart with {vision}");
}

/// The colour bars of `svg`, each its slices' colours top to bottom, and the swatches outside
/// every frame (a legend's cells, e.g. "no value"). A bar is a box (`fill="none"`) filled by
/// more than [`SCALE_COLORS`] colours of slices as wide as it.
fn color_bars(svg: &str) -> (Vec<Vec<String>>, Vec<String>) {
    let doc = Document::parse(svg).unwrap();
    let (frames, _) = marks(&doc);
    let filled: Vec<(f64, f64, f64, f64, String)> = doc
        .descendants()
        .filter(|n| n.has_tag_name("rect"))
        .filter(|n| !n.ancestors().any(|a| a.has_tag_name("clipPath") || a.has_tag_name("defs")))
        .filter_map(|n| {
            let fill = n.attribute("fill")?;
            (fill != "none" && fill != "white")
                .then(|| (num(&n, "x"), num(&n, "y"), num(&n, "width"), num(&n, "height"), fill.to_string()))
        })
        .collect();
    let mut bars = vec![];
    for &(fx, fy, fw, fh) in &frames {
        let mut slices: Vec<&(f64, f64, f64, f64, String)> = filled
            .iter()
            .filter(|r| {
                (r.0 - fx).abs() < 0.01 && (r.2 - fw).abs() < 0.01 && r.1 >= fy - 0.5 && r.1 + r.3 <= fy + fh + 1.0
            })
            .collect();
        slices.sort_by(|a, b| a.1.total_cmp(&b.1));
        let distinct: BTreeSet<&String> = slices.iter().map(|r| &r.4).collect();
        if distinct.len() > SCALE_COLORS {
            bars.push(slices.into_iter().map(|r| r.4.clone()).collect());
        }
    }
    let swatches = filled
        .iter()
        .filter(|r| r.2 < 40.0 && !inside(&frames, (r.0 + r.2 / 2.0, r.1 + r.3 / 2.0)))
        .map(|r| r.4.clone())
        .collect();
    (bars, swatches)
}

/// A colour bar is read by the order of its colours: two slices a quarter of the bar or more
/// apart stay ΔE00 [`MIN_DELTA_E`] apart for normal vision and with red–green colour
/// blindness, and so does a swatch beside it (a "no value" cell) from every slice.
fn bar_problems(name: &str, svg: &str) -> Vec<String> {
    let (bars, swatches) = color_bars(svg);
    let mut problems = vec![];
    for bar in &bars {
        let quarter = bar.len().div_ceil(4);
        for i in 0..bar.len() {
            for j in i + quarter..bar.len() {
                let (d, vision, a, b) = closest_pair(&[&bar[i], &bar[j]]);
                if d < MIN_DELTA_E {
                    problems.push(format!("{name}: the bar's {a} and {b} are ΔE00 {d:.1} apart with {vision}"));
                }
            }
        }
        for s in swatches.iter().filter(|s| s.starts_with('#') && s.len() == 7) {
            for c in bar {
                let (d, vision, a, b) = closest_pair(&[s, c]);
                if d < MIN_DELTA_E {
                    problems
                        .push(format!("{name}: the swatch {a} and the bar's {b} are ΔE00 {d:.1} apart with {vision}"));
                }
            }
        }
    }
    problems
}

#[test]
fn every_colour_bar_reads_in_order_with_red_green_colour_blindness() {
    let mut bars = 0;
    for (name, svg) in figures() {
        bars += color_bars(svg).0.len();
        let problems = bar_problems(name, svg);
        assert!(problems.is_empty(), "{}", problems.join("\n"));
    }
    // The paper's Fig 15, the study over two parameters (a map per metric) and the ensemble
    // chart (four maps) draw colour bars.
    assert!(bars >= 7, "{bars} colour bars");
}

#[test]
fn the_colour_bar_check_fails_on_a_bar_that_turns_back_to_its_start() {
    // A rainbow from blue through green back to blue: its ends are one colour.
    let frame = r#"<rect x="10" y="10" width="100" height="100" fill="none" stroke="black"/>"#;
    let slices: String = (0..16)
        .map(|k| {
            let c =
                if k < 8 { format!("#00{:02x}ff", k * 32) } else { format!("#{:02x}{:02x}ff", 2 * k, (15 - k) * 32) };
            format!(r#"<rect x="130" y="{}" width="18" height="5" fill="{c}"/>"#, 10 + 5 * k)
        })
        .collect();
    let bar = r#"<rect x="130" y="10" width="18" height="80" fill="none" stroke="black"/>"#;
    let svg = format!(r#"<svg xmlns="http://www.w3.org/2000/svg">{frame}{slices}{bar}</svg>"#);
    assert_eq!(color_bars(&svg).0.len(), 1);
    assert!(!bar_problems("test", &svg).is_empty(), "a bar whose ends look alike is seen");
    let viridis: String = (0..16)
        .map(|k| {
            let c = thud::export::studies::viridis(f64::from(k) / 15.0);
            format!(r#"<rect x="130" y="{}" width="18" height="5" fill="{c}"/>"#, 10 + 5 * k)
        })
        .collect();
    let svg = format!(r#"<svg xmlns="http://www.w3.org/2000/svg">{frame}{viridis}{bar}</svg>"#);
    assert!(bar_problems("viridis", &svg).is_empty(), "{:?}", bar_problems("viridis", &svg));
}

#[test]
fn the_gallery_s_basins_show_more_than_one_attractor() {
    // A basins figure of one flat colour tells nothing: the gallery's (and the guide's) run at
    // 7.5 Hz shows at least two attractors, each a colour of its own in the map and the legend.
    let svg = &made().pictures["basins.svg"];
    let (data, legend, _) = looks_of(svg);
    let cells: BTreeSet<&str> = data.iter().filter(|l| l.kind == "cell").map(|l| l.color.as_str()).collect();
    assert!(cells.len() >= 2, "one colour of cell: {cells:?}");
    assert!(cells.iter().all(|c| legend.iter().any(|l| l.color == *c)), "{cells:?} against {legend:?}");
}

/// The branch lines of a continuation figure's legend (`1: 6–8 Hz`) and whether it says it
/// leaves some out (`… and N more`).
fn branch_entries(svg: &str) -> (usize, bool) {
    let doc = Document::parse(svg).unwrap();
    let texts: Vec<String> =
        doc.descendants().filter(|n| n.has_tag_name("text")).filter_map(|n| n.text().map(str::to_string)).collect();
    let listed = texts
        .iter()
        .filter(|t| t.split_once(": ").is_some_and(|(k, _)| !k.is_empty() && k.chars().all(|c| c.is_ascii_digit())))
        .count();
    (listed, texts.iter().any(|t| t.starts_with("… and ") && t.ends_with("more (in the CSV)")))
}

/// `thud continue --svg` and `thud bifurcation --branches N --svg`: the legend lists every
/// branch the JSON has (or says how many it leaves out), and the stable and unstable colours
/// and the special points' markers stay apart for red–green colour blindness and are the ones
/// drawn.
#[test]
fn continued_branches_are_each_listed_and_their_looks_stay_apart() {
    let home = tempfile::tempdir().unwrap();
    let svg = home.path().join("continue.svg");
    let args = ["continue", "--preset", "forced-rattle", "--vary", "f=6Hz:8Hz:4", "--json", "--svg"];
    let (code, json, err) = crate::common::thud_in(home.path(), &[&args[..], &[svg.to_str().unwrap()]].concat());
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let n = v["branches"].as_array().unwrap().len();
    assert!(n >= 1, "{json}");
    let text = std::fs::read_to_string(&svg).unwrap();
    let (listed, more) = branch_entries(&text);
    assert!(listed == n || (more && listed == 10), "{n} branches, {listed} listed (more: {more})");
    // The gallery's family (f 6–8 Hz from 5 seeds): its branches listed too. (Over a
    // bifurcation diagram, `--branches N`, the legend names the stable and unstable looks, not
    // each branch: the legend check of every figure covers it.)
    let (listed, more) = branch_entries(&made().pictures["continue.svg"]);
    assert!((1..=10).contains(&listed), "continue.svg: {listed} listed, more {more}");
    // The looks: stable and unstable curves in their colours, the special points in black
    // markers of a shape per kind; all of them apart under red–green colour blindness.
    let stable = thud::export::continuation::STABLE;
    let unstable = thud::export::continuation::UNSTABLE;
    let (data, legend, _) = looks_of(&text);
    assert!(data.iter().any(|l| l.kind == "curve" && l.color == stable), "a stable stretch drawn: {data:?}");
    let colors: Vec<&str> = data.iter().chain(&legend).map(|l| l.color.as_str()).collect();
    for c in &colors {
        assert!([stable, unstable, "#000000"].contains(c), "an unexpected colour {c}");
    }
    let (d, vision, a, b) = crate::cvd::closest_pair(&[stable, unstable, "#000000"]);
    assert!(d >= MIN_DELTA_E, "{a} and {b}: ΔE00 {d:.1} with {vision}");
    let markers: BTreeSet<&str> = data.iter().filter(|l| l.kind != "curve").map(|l| l.kind.as_str()).collect();
    let kinds: BTreeSet<&str> = v["branches"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|b| b["specials"].as_array().unwrap().iter().map(|s| s["kind"].as_str().unwrap()))
        .collect();
    assert!(markers.len() <= kinds.len(), "a marker shape per kind of special point: {markers:?} for {kinds:?}");
}
