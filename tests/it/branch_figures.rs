#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The figures of continued orbit branches: `thud continue --svg/--pdf` draws every point of
//! every branch (stable stretches solid, unstable ones dashed) and marks every special point
//! the JSON lists; `thud bifurcation --branches N` draws the branches over its samples, and
//! refuses N where it means nothing.

use super::common::thud;
use roxmltree::Document;

const STABLE: &str = thud::export::continuation::STABLE;
const UNSTABLE: &str = thud::export::continuation::UNSTABLE;

/// The polylines of `svg` stroked in `color`: their vertex counts and whether they are dashed.
fn lines(svg: &str, color: &str) -> Vec<(usize, bool)> {
    let doc = Document::parse(svg).unwrap();
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke") == Some(color))
        .map(|n| {
            let vertices = n.attribute("points").unwrap_or_default().split_whitespace().count();
            (vertices, n.attribute("stroke-dasharray").is_some())
        })
        .collect()
}

/// Every point of the branch is a vertex of its stability's curve (a stretch shares its last
/// vertex with the next one's first), unstable curves are dashed, stable ones solid, and the
/// figure marks as many special points as the JSON lists (all inside the frame: the axes fit
/// the branch).
#[test]
fn continue_s_figure_draws_every_point_and_marks_every_special_point() {
    let dir = tempfile::tempdir().unwrap();
    let svg_path = dir.path().join("branch.svg");
    let pdf_path = dir.path().join("branch.pdf");
    // forced-rattle's 3/1 orbit from 6.7 Hz down through its period doubling near 6.54 Hz:
    // stable and unstable parts.
    let args = ["continue", "--preset", "forced-rattle", "--vary", "f=6.7Hz:6.3Hz", "--json"];
    let mut with_files: Vec<&str> = args.to_vec();
    let (s, p) = (svg_path.to_str().unwrap(), pdf_path.to_str().unwrap());
    with_files.extend(["--svg", s, "--pdf", p]);
    let (code, out, err) = thud(&with_files);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    let points = j["points"].as_array().unwrap();
    let stable = points.iter().filter(|p| p["stable"] == true).count();
    let unstable = points.len() - stable;
    assert!(stable > 0 && unstable > 0, "{stable} stable and {unstable} unstable points");
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    let (solid, dashed) = (lines(&svg, STABLE), lines(&svg, UNSTABLE));
    assert!(solid.iter().all(|l| !l.1) && dashed.iter().all(|l| l.1), "{solid:?} {dashed:?}");
    // Each stretch but the branch's last carries the next stretch's first point too.
    let stretches = solid.len() + dashed.len();
    let vertices: usize = solid.iter().chain(&dashed).map(|l| l.0).sum();
    assert_eq!(vertices, points.len() + stretches - 1, "{solid:?} {dashed:?}");
    let changes = points.windows(2).filter(|w| w[0]["stable"] != w[1]["stable"]).count();
    assert_eq!(stretches, changes + 1);
    // The special points: one black marker each, in the frame.
    let specials = j["specials"].as_array().unwrap();
    assert!(!specials.is_empty(), "{specials:?}");
    let doc = Document::parse(&svg).unwrap();
    let frame = doc.descendants().find(|n| n.has_tag_name("rect") && n.attribute("fill") == Some("none")).unwrap();
    let num = |n: &roxmltree::Node, a: &str| n.attribute(a).unwrap().parse::<f64>().unwrap();
    let (fx, fy, fw, fh) = (num(&frame, "x"), num(&frame, "y"), num(&frame, "width"), num(&frame, "height"));
    let black_in_frame = doc
        .descendants()
        .filter(|n| (n.has_tag_name("polygon") || n.has_tag_name("rect")) && n.attribute("fill") == Some("#000000"))
        .filter(|n| {
            let pts: Vec<(f64, f64)> = match n.attribute("points") {
                Some(p) => p
                    .split_whitespace()
                    .filter_map(|xy| xy.split_once(','))
                    .map(|(x, y)| (x.parse().unwrap(), y.parse().unwrap()))
                    .collect(),
                None => vec![(num(n, "x"), num(n, "y"))],
            };
            let (cx, cy) = (pts[0].0, pts[0].1);
            cx >= fx - 6.0 && cx <= fx + fw + 6.0 && cy >= fy - 6.0 && cy <= fy + fh + 6.0
        })
        .count();
    assert_eq!(black_in_frame, specials.len(), "{specials:?}");
    assert!(svg.contains(">stable orbit<") && svg.contains(">unstable orbit<"));
    // Each kind marked is named in the legend.
    for s in specials {
        let words = match s["kind"].as_str().unwrap() {
            "neimark_sacker" => "Neimark–Sacker".to_string(),
            kind => kind.replace('_', " "),
        };
        assert!(svg.contains(&format!(">{words}")), "{words} not in the legend");
    }
    assert!(std::fs::read(&pdf_path).unwrap().starts_with(b"%PDF"));
    // The files are kept unless --force, refused before any work in one line naming the flag.
    let (code, _, err) = thud(&with_files);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("--svg"), "{err}");
}

/// `--branches N` draws the branches continued from N seeds over the x(kT) panel: stable
/// branches are drawn where the simulated samples are periodic (the 3/1 orbits of forced-rattle
/// near 7 Hz). Without a figure, with N not a count of 2 to 1000, with the Newmark solver or with
/// --shard it is refused with exit 2 in one line naming the flag.
#[test]
fn bifurcation_draws_the_branches_over_its_samples_and_refuses_them_without_a_figure() {
    let dir = tempfile::tempdir().unwrap();
    let svg_path = dir.path().join("b.svg");
    let s = svg_path.to_str().unwrap();
    let base = ["bifurcation", "--preset", "forced-rattle", "--vary", "f=6.9Hz:7.1Hz:5"];
    let mut args = base.to_vec();
    args.extend(["--branches", "2", "--svg", s]);
    let (code, _, err) = thud(&args);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    assert!(!lines(&svg, STABLE).is_empty(), "no stable branch drawn");
    assert!(svg.contains(">stable orbit<"));
    let (code, _, err) = thud(&[&base[..], &["--svg", &format!("{s}2")]].concat());
    assert_eq!(code, 0, "{err}");
    let plain = std::fs::read_to_string(format!("{s}2")).unwrap();
    assert!(lines(&plain, STABLE).is_empty() && !plain.contains(">stable orbit<"), "branches drawn unasked");
    let other = format!("{s}3");
    for (extra, flag) in [
        (vec!["--branches", "2"], "--branches"),
        (vec!["--branches", "1", "--svg", &other], "--branches"),
        (vec!["--branches", "1001", "--svg", &other], "--branches"),
        (vec!["--branches", "2.5", "--svg", &other], "--branches"),
        (vec!["--branches", "NaN", "--svg", &other], "--branches"),
        (vec!["--branches", "x", "--svg", &other], "--branches"),
        (vec!["--branches", "2", "--svg", &other, "--solver", "newmark"], "--solver"),
        (vec!["--branches", "2", "--svg", &other, "--shard", "0/2"], "--branches"),
    ] {
        let args = [&base[..], &extra[..]].concat();
        let (code, out, err) = thud(&args);
        assert_eq!(code, 2, "{extra:?}: {out} {err}");
        assert!(err.contains(flag), "{extra:?}: {err}");
        assert!(!std::path::Path::new(&other).exists(), "{extra:?}: wrote the figure");
    }
}
