#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Studies over any parameter and the dynamics of a forced design, through the built
//! binary: `sweep --vary` against `simulate` cell by cell, its shards merged back,
//! `bifurcation` on the forced-rattle preset (samples, figure, the period doubling
//! classified), `impact-map`, `basins`, and the bad input of the new flags.

use std::path::Path;
use std::time::Duration;

use crate::common::{self, Ran};

/// Runs thud in a private home `home` (cwd too); a run over 30 s fails the test.
fn thud_in(home: &Path, args: &[&str]) -> Ran {
    common::thud_within(home, args, Duration::from_secs(30))
}

fn thud(args: &[&str]) -> Ran {
    let home = tempfile::tempdir().unwrap();
    thud_in(home.path(), args)
}

fn ok(args: &[&str]) -> String {
    let r = thud(args);
    assert_eq!(r.code, 0, "{args:?}: {}", r.stderr);
    r.stdout
}

#[test]
fn a_study_cell_is_simulate_at_its_values() {
    let out = ok(&["sweep", "--vary", "v0=1:3:5", "--vary", "c1=10:60:6", "--json"]);
    let s: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(s["axes"][0]["name"], "v0");
    assert_eq!(s["axes"][0]["unit"], "m/s");
    assert_eq!(s["axes"][1]["values"].as_array().unwrap().len(), 6);
    let cells = s["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 30);
    // C order: the last --vary fastest. Cell 13 is v0 = 2 (index 2), c1 = 20 (index 1).
    assert_eq!(cells[13]["values"], serde_json::json!([2.0, 20.0]));
    for (i, v0, c1) in [(13, "2", "20"), (29, "3", "60"), (0, "1", "10")] {
        let sim: serde_json::Value =
            serde_json::from_str(&ok(&["simulate", "--v0", v0, "--c1", c1, "--json"])).unwrap();
        for key in ["n_impacts", "inclination_cm_s", "u0_max_m_s", "spl_max_db", "restitution_mean", "zone"] {
            assert_eq!(cells[i][key], sim[key], "cell {i} {key}");
        }
    }
}

#[test]
fn a_study_in_parts_merges_to_the_whole() {
    let home = tempfile::tempdir().unwrap();
    let h = home.path();
    let study = ["sweep", "--vary", "v0=1:3:3", "--vary", "mass=30g:60g:3"];
    let whole = thud_in(h, &[&study[..], &["--json"]].concat());
    assert_eq!(whole.code, 0, "{}", whole.stderr);
    for k in 0..3 {
        let part = format!("part{k}.jsonl");
        let shard = format!("{k}/3");
        let r = thud_in(h, &[&study[..], &["--shard", &shard, "--out", &part]].concat());
        assert_eq!(r.code, 0, "{}", r.stderr);
    }
    let merged = thud_in(h, &["merge", "part2.jsonl", "part0.jsonl", "part1.jsonl", "--json", "--out", "-"]);
    assert_eq!(merged.code, 0, "{}", merged.stderr);
    assert_eq!(merged.stdout, whole.stdout);
    let missing = thud_in(h, &["merge", "part2.jsonl", "part0.jsonl", "--json", "--out", "-"]);
    assert_eq!(missing.code, 2);
    assert!(missing.stderr.contains("part 1/3 is missing"), "{}", missing.stderr);
    // An edited cell is refused.
    let p1 = std::fs::read_to_string(h.join("part1.jsonl")).unwrap();
    let edited = p1.replacen("\"values\":[2.0", "\"values\":[2.5", 1);
    assert_ne!(edited, p1);
    std::fs::write(h.join("part1.jsonl"), edited).unwrap();
    let bad = thud_in(h, &["merge", "part2.jsonl", "part0.jsonl", "part1.jsonl", "--json", "--out", "-"]);
    assert_eq!(bad.code, 2, "{}", bad.stderr);
    assert!(bad.stderr.contains("part1.jsonl"), "{}", bad.stderr);
}

#[test]
fn the_forced_rattle_bifurcation_shows_its_period_doubling() {
    let home = tempfile::tempdir().unwrap();
    let h = home.path();
    let r = thud_in(
        h,
        &[
            "bifurcation",
            "--preset",
            "forced-rattle",
            "--vary",
            "f=7.4Hz:7.8Hz:17",
            "--csv",
            "--out",
            "bif.csv",
            "--svg",
            "bif.svg",
            "--pdf",
            "bif.pdf",
        ],
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    let csv = std::fs::read_to_string(h.join("bif.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "freq_hz,direction,orbit,record,period,x_m,v_m_s,z_m,zdot_m_s,phase,wall,u_in_m_s,u_out_m_s"
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // 100 samples a value.
    assert_eq!(rows.iter().filter(|r| r[3] == "sample").count(), 17 * 100);
    let orbit_at =
        |f: f64| rows.iter().find(|r| (r[0].parse::<f64>().unwrap() - f).abs() < 1e-9).map(|r| r[2]).unwrap();
    assert_eq!(orbit_at(7.7), "2/1");
    assert_eq!(orbit_at(7.55), "4/2");
    assert_eq!(orbit_at(7.425), "chaotic");
    let svg = std::fs::read_to_string(h.join("bif.svg")).unwrap();
    assert!(svg.contains("<title>Bifurcation diagram over freq") && svg.contains("4/2"));
    // The title names the range that varies, not the design's own f; numbers as typed.
    assert!(svg.contains("over freq 7.4–7.8 Hz — F0 "), "{}", &svg[..svg.len().min(600)]);
    assert!(!svg.contains(", f 7.") && !svg.contains(".0000"), "{}", &svg[..svg.len().min(600)]);
    // The legend's orbit list says when it leaves bands out (those of fewer than 3 values):
    // the bands are the runs of one orbit over consecutive values of the CSV.
    let mut values: Vec<(f64, &str)> = Vec::new();
    for r in &rows {
        let f: f64 = r[0].parse().unwrap();
        if values.last().is_none_or(|(g, _)| (f - g).abs() > 1e-12) {
            values.push((f, r[2]));
        }
    }
    let mut bands: Vec<usize> = Vec::new();
    for (i, (_, orbit)) in values.iter().enumerate() {
        if i > 0 && values[i - 1].1 == *orbit {
            *bands.last_mut().unwrap() += 1;
        } else {
            bands.push(1);
        }
    }
    let left_out = bands.len() - bands.iter().filter(|n| **n >= 3).count().min(24);
    if left_out > 0 {
        assert!(svg.contains(&format!("… and {left_out} band")), "{left_out} bands left out: {bands:?}");
    } else {
        assert!(!svg.contains("… and"), "{bands:?}");
    }
    assert!(std::fs::read(h.join("bif.pdf")).unwrap().starts_with(b"%PDF"));
    // The text names the bands.
    let text =
        thud_in(h, &["bifurcation", "--preset", "forced-rattle", "--vary", "f=7.5Hz:7.7Hz:5", "--periods", "40"]);
    assert!(text.stdout.contains("4/2") && text.stdout.contains("2/1"), "{}", text.stdout);
}

#[test]
fn continuation_runs_up_and_down() {
    let out = ok(&[
        "bifurcation",
        "--preset",
        "forced-rattle",
        "--vary",
        "f=7.6Hz:7.8Hz:3",
        "--continuation",
        "--transient",
        "100",
        "--periods",
        "30",
        "--json",
    ]);
    let b: serde_json::Value = serde_json::from_str(&out).unwrap();
    let dirs: Vec<(&str, f64)> = b["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p["direction"].as_str().unwrap(), p["value"].as_f64().unwrap()))
        .collect();
    assert_eq!(dirs.iter().map(|d| d.0).collect::<Vec<_>>(), ["up", "up", "up", "down", "down", "down"]);
    assert_eq!(dirs[3].1, 7.8);
    assert!(b["bands"].as_array().unwrap().len() >= 2);
}

#[test]
fn impact_map_and_basins() {
    let out = ok(&["impact-map", "--preset", "forced-rattle", "--freq", "7.7Hz", "--periods", "20", "--csv"]);
    let impacts: Vec<&str> = out.lines().filter(|l| l.contains(",impact,")).collect();
    assert_eq!(impacts.len(), 40, "two impacts a period at 7.7 Hz");
    let home = tempfile::tempdir().unwrap();
    let r = thud_in(
        home.path(),
        &[
            "basins",
            "--preset",
            "forced-rattle",
            "--freq",
            "7.7Hz",
            "--grid",
            "4",
            "--transient",
            "150",
            "--periods",
            "30",
            "--json",
            "--svg",
            "b.svg",
        ],
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    let b: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(b["cells"].as_array().unwrap().len(), 16);
    let shares: f64 = b["attractors"].as_array().unwrap().iter().map(|a| a["share"].as_f64().unwrap()).sum();
    assert!((shares - 1.0).abs() < 1e-12);
    assert!(std::fs::read_to_string(home.path().join("b.svg")).unwrap().contains("<title>Basins"));
}

/// Exit 2, one line on stderr naming `flag`, nothing on stdout.
fn refused(args: &[&str], flag: &str) {
    let r = thud(args);
    assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {}", r.stderr);
    assert!(r.stdout.is_empty(), "{args:?}: {}", r.stdout);
    assert!(
        r.stderr.starts_with(&format!("thud: invalid {flag}")) || r.stderr.starts_with(&format!("thud: {flag}")),
        "{args:?}: {}",
        r.stderr
    );
}

#[test]
fn bad_input_of_the_new_flags_is_one_line_naming_the_flag() {
    let forced = ["--preset", "forced-rattle"];
    refused(&["sweep", "--vary", "bogus=1:2:3"], "--vary");
    refused(&["sweep", "--vary", "v0=1:1e9:3"], "--vary v0");
    refused(&["sweep", "--vary", "solver=1:2:2"], "--vary");
    refused(&["sweep", "--vary", "v0"], "--vary");
    refused(&["sweep", "--vary", "c1=10:60"], "--vary c1");
    refused(&["sweep", "--vary", "freq=3xz:8Hz:3"], "--vary freq");
    refused(&["sweep", "--vary", "v0=1:3:0"], "--vary v0");
    refused(&["sweep", "--vary", "v0=1:3:3", "--vary", "v0=1:2:2"], "--vary v0");
    refused(&["sweep", "--vary", "v0=1:3:1000", "--vary", "c1=1:2:1000"], "--vary");
    refused(&["sweep", "--vary", "v0=1:3:3", "--ensemble", "4"], "--ensemble");
    refused(&["sweep", "--vary", "v0=1:3:3", "--shard", "5/3"], "--shard");
    refused(&["bifurcation", "--vary", "f=3Hz:8Hz:10"], "--force-amplitude");
    refused(&[&["bifurcation", "--vary", "f=3Hz:8Hz:10", "--transient", "-1"][..], &forced].concat(), "--transient");
    refused(&[&["bifurcation", "--vary", "f=3Hz:8Hz:10", "--transient", "x"][..], &forced].concat(), "--transient");
    refused(&[&["bifurcation", "--vary", "f=1:2:1000", "--transient", "1e5"][..], &forced].concat(), "--vary");
    refused(&[&["bifurcation", "--vary", "f=7:8:3", "--solver", "newmark"][..], &forced].concat(), "--solver");
    refused(&[&["basins", "--grid", "0"][..], &forced].concat(), "--grid");
    refused(&[&["basins", "--w0", "1"][..], &forced].concat(), "--w0");
    refused(&[&["basins", "--w0", "-1:1e9"][..], &forced].concat(), "--w0");
    refused(&[&["basins", "--ball-position", "1mm"][..], &forced].concat(), "--grid");
    refused(&["impact-map"], "--force-amplitude");
}

#[test]
fn a_bifurcation_in_parts_merges_to_the_whole() {
    let home = tempfile::tempdir().unwrap();
    let h = home.path();
    let study = [
        "bifurcation",
        "--preset",
        "forced-rattle",
        "--vary",
        "f=7.5Hz:7.8Hz:7",
        "--transient",
        "100",
        "--periods",
        "30",
    ];
    for format in ["--json", "--csv"] {
        let whole = thud_in(h, &[&study[..], &[format]].concat());
        assert_eq!(whole.code, 0, "{}", whole.stderr);
        let mut parts = Vec::new();
        for k in 0..2 {
            let part = format!("b{k}{format}.jsonl");
            let r = thud_in(h, &[&study[..], &["--shard", &format!("{k}/2"), "--out", &part]].concat());
            assert_eq!(r.code, 0, "{}", r.stderr);
            parts.push(part);
        }
        let merged = thud_in(h, &["merge", &parts[1], &parts[0], format, "--out", "-"]);
        assert_eq!(merged.code, 0, "{}", merged.stderr);
        assert_eq!(merged.stdout, whole.stdout, "{format}");
    }
    let alone = thud_in(h, &["merge", "b0--json.jsonl", "--json", "--out", "-"]);
    assert_eq!(alone.code, 2);
    assert!(alone.stderr.contains("part 1/2 is missing"), "{}", alone.stderr);
    let r = thud_in(h, &[&study[..], &["--shard", "0/2", "--continuation"]].concat());
    assert_eq!(r.code, 2, "{}", r.stderr);
}
