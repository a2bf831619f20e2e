#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! One data schema: every CSV column and every metric key of the JSON is documented in the
//! guide's one schema table (docs/guide/schema.md), with the same name and unit everywhere; zones are numbers; and
//! the licence and citation files say what Cargo.toml declares.

use crate::common;
use std::collections::BTreeSet;
use std::path::Path;

use common::thud;

/// The output of a successful `thud` run.
fn ok(args: &[&str]) -> String {
    let (code, out, err) = thud(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

fn repo_file(name: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(name)).unwrap()
}

/// The keys of the guide's schema table (first cell of each row, every `key` in backticks).
fn documented() -> BTreeSet<String> {
    let readme = repo_file("docs/guide/schema.md");
    let start = readme.find("<!-- schema:start -->").expect("the schema table's start marker");
    let end = readme.find("<!-- schema:end -->").expect("its end marker");
    let mut keys = BTreeSet::new();
    for row in readme[start..end].lines().filter(|l| l.starts_with("| `")) {
        let first = row.split(" | ").next().unwrap();
        keys.extend(first.split('`').skip(1).step_by(2).map(str::to_string));
    }
    assert!(keys.len() > 50, "{keys:?}");
    keys
}

/// The CSV header of `text`.
fn header(text: &str) -> Vec<String> {
    let line = text.lines().find(|l| !l.starts_with('#')).unwrap();
    line.split(',').map(str::to_string).collect()
}

/// `key` without an ensemble's percentile suffix.
fn base(key: &str) -> &str {
    ["_p10", "_median", "_p90"].iter().find_map(|s| key.strip_suffix(s)).unwrap_or(key)
}

const GRID: [&str; 4] = ["--masses", "30g:40g:2", "--gaps", "2cm:3cm:2"];

#[test]
fn every_csv_column_is_in_the_readme_schema_table() {
    let known = documented();
    let dir = tempfile::tempdir().unwrap();
    let mut headers: Vec<(String, Vec<String>)> = Vec::new();
    for what in ["waveform", "history", "impacts", "sweep"] {
        let out = dir.path().join(format!("{what}.csv"));
        let args = [&["export", "csv", what, "--points", "5", "--out", out.to_str().unwrap()][..], &GRID[..]].concat();
        ok(&args);
        headers.push((format!("export csv {what}"), header(&std::fs::read_to_string(&out).unwrap())));
    }
    let response = ["--force-amplitude", "1N", "--freqs", "5Hz:6Hz:2", "--duration", "2", "--csv"];
    for (name, args) in [
        ("sweep --csv", [&["sweep", "--csv"][..], &GRID[..]].concat()),
        (
            "sweep --ensemble --csv",
            [&["sweep", "--csv", "--ensemble", "2", "--duration", "0.5"][..], &GRID[..]].concat(),
        ),
        ("simulate --csv", vec!["simulate", "--csv", "--samples", "3"]),
        ("simulate --ensemble --csv", vec!["simulate", "--csv", "--ensemble", "3", "--duration", "0.5"]),
        ("pulse --csv", vec!["pulse", "--csv", "--points", "3"]),
        ("response --csv", [&["response"][..], &response[..]].concat()),
        ("response --ensemble --csv", [&["response", "--ensemble", "2"][..], &response[..]].concat()),
    ] {
        headers.push((name.to_string(), header(&ok(&args))));
    }
    let list = ok(&["paper", "--list"]);
    for id in list
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .filter(|id| id.starts_with("table") || id.starts_with("fig"))
    {
        headers.push((format!("paper {id}"), header(&ok(&["paper", id, "--csv"]))));
    }
    assert!(headers.len() > 25);
    for (name, cols) in &headers {
        for c in cols {
            assert!(known.contains(base(c)), "{name}: column `{c}` is not in the guide's schema table");
            for old in ["u0max", "splmax", "QuietWeak"] {
                assert!(!c.contains(old), "{name}: `{c}`");
            }
        }
    }
    // The paper's tables use the schema's names for the metrics they share with a sweep.
    let fig10 = &headers.iter().find(|(n, _)| n == "paper fig10").unwrap().1;
    for key in ["inclination_cm_s", "u0_max_m_s", "spl_max_db", "n_impacts", "zone"] {
        assert!(fig10.iter().any(|c| c == key), "{fig10:?}");
    }
}

#[test]
fn sweep_csv_has_every_key_of_a_sweep_json_cell_with_zones_as_numbers() {
    let json: serde_json::Value = serde_json::from_str(&ok(&[&["sweep", "--json"][..], &GRID[..]].concat())).unwrap();
    let csv = ok(&[&["sweep", "--csv"][..], &GRID[..]].concat());
    let cells = json["chart"]["cells"].as_array().unwrap();
    let cell = cells[0].as_object().unwrap();
    let mut want: Vec<String> = cell.keys().filter(|k| *k != "metrics").cloned().collect();
    want.extend(cell["metrics"].as_object().unwrap().keys().cloned());
    let (mut have, mut sorted) = (header(&csv), want.clone());
    have.sort();
    sorted.sort();
    assert_eq!(have, sorted, "sweep --csv: every key of the JSON cell, and no other");
    let want = header(&csv);
    let mut rows = csv::Reader::from_reader(csv.as_bytes());
    for (row, cell) in rows.records().map(Result::unwrap).zip(cells) {
        let zone = &cell["metrics"]["zone"];
        assert!(zone.is_u64() || zone.is_null(), "a zone is a number: {zone}");
        assert_eq!(
            &row[want.iter().position(|k| k == "zone").unwrap()],
            zone.as_u64().map_or(String::new(), |z| z.to_string())
        );
        for (i, key) in want.iter().enumerate().take(want.len() - 1) {
            let v = cell.get(key).unwrap_or(&cell["metrics"][key]);
            assert_eq!(row[i].parse::<f64>().ok(), v.as_f64(), "{key}");
        }
    }
    // Every metric key of the JSON outputs is documented too, and no zone is a name.
    let known = documented();
    let sim: serde_json::Value = serde_json::from_str(&ok(&["simulate", "--json", "--duration", "0.5"])).unwrap();
    let ens = ok(&["simulate", "--json", "--ensemble", "3", "--duration", "0.5"]);
    let ens: serde_json::Value = serde_json::from_str(&ens).unwrap();
    let scalar_keys = |v: &serde_json::Value| -> Vec<String> {
        v.as_object().unwrap().iter().filter(|(_, x)| !x.is_object() && !x.is_array()).map(|(k, _)| k.clone()).collect()
    };
    let mut keys = scalar_keys(&sim);
    keys.extend(scalar_keys(&sim["impacts"][0]));
    keys.extend(scalar_keys(&ens));
    keys.extend(scalar_keys(&ens["ensemble"][0]));
    keys.extend(want);
    for k in &keys {
        assert!(known.contains(k), "JSON key `{k}` is not in the guide's schema table");
    }
    for text in [sim.to_string(), ens.to_string(), json.to_string()] {
        for name in ["NoisyWeak", "NoisyStrong", "QuietStrong", "QuietWeak"] {
            assert!(!text.contains(name), "an internal zone name in the JSON");
        }
    }
}

#[test]
fn licence_and_citation_match_the_manifest() {
    let manifest = repo_file("Cargo.toml");
    assert!(manifest.contains("license = \"MIT\""));
    let licence = repo_file("LICENSE");
    assert!(licence.starts_with("MIT License"), "{licence}");
    assert!(licence.contains("Copyright (c)") && licence.contains("the thud authors"));
    assert!(licence.contains("THE SOFTWARE IS PROVIDED \"AS IS\""));
    let cff = repo_file("CITATION.cff");
    let field = |key: &str| -> Option<String> {
        cff.lines().find_map(|l| l.strip_prefix(&format!("{key}:")).map(|v| v.trim().trim_matches('"').to_string()))
    };
    assert_eq!(field("cff-version").as_deref(), Some("1.2.0"));
    for key in ["message", "title", "authors", "type"] {
        assert!(field(key).is_some(), "CITATION.cff needs `{key}`");
    }
    assert_eq!(field("license").as_deref(), Some("MIT"));
    let version = manifest.lines().find_map(|l| l.strip_prefix("version = ")).unwrap().trim_matches('"');
    assert_eq!(field("version").as_deref(), Some(version), "CITATION.cff's version is the crate's");
    // The README's first paragraph gives the source paper's citation (as far as the project's copy
    // states it) and points to the licence and the citation file.
    let readme = repo_file("README.md");
    let first = readme.split("\n\n").nth(1).unwrap();
    for want in ["2012", "Elsevier", "LICENSE", "CITATION.cff"] {
        assert!(first.contains(want), "`{want}` not in the README's first paragraph: {first}");
    }
    assert!(repo_file("docs/model.md").contains("2012 Elsevier"));
}
