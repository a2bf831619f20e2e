#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! One schema: every CSV header the command line writes and every record of
//! its JSON are the engine's one definition (`thud_core::schema`) — names and order — for
//! pulse, simulate (history, impacts), ensemble, sweep, sweep of ensembles, response, response
//! of ensembles, shard parts and merge; and the guide's schema page lists every table as the
//! definition has it.

use std::path::Path;

use serde_json::Value;
use thud_core::schema::{self, Table};

use crate::common::thud;

fn ok(args: &[&str]) -> String {
    let (code, out, err) = thud(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

/// The CSV header of `text` (the first line not a `#` comment).
fn header(text: &str) -> Vec<String> {
    text.lines().find(|l| !l.starts_with('#')).unwrap().split(',').map(str::to_string).collect()
}

fn names(t: &Table) -> Vec<String> {
    t.names().into_iter().map(str::to_string).collect()
}

/// The keys of a JSON record in their written order (serde_json's map sorts them, so they are
/// read off the text), nested `metrics` in place and a `spread` `{X: {p10, median, p90}}` as
/// `X_p10`, `X_median`, `X_p90`; lists (an ensemble's runs) left out.
fn flat_keys(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut de = serde_json::Deserializer::from_str(text);
    let v: indexed::Ordered = serde::Deserialize::deserialize(&mut de).unwrap();
    flatten(&v, "", &mut out);
    out
}

/// The top-level keys of a JSON object's text, in their written order, whatever their values.
fn top_keys(text: &str) -> Vec<String> {
    let mut de = serde_json::Deserializer::from_str(text);
    match serde::Deserialize::deserialize(&mut de).unwrap() {
        indexed::Ordered::Map(entries) => entries.into_iter().map(|(k, _)| k).collect(),
        _ => Vec::new(),
    }
}

/// The text of the first object in the list `list` of the JSON text `text`.
fn first_record(text: &str, list: &str) -> String {
    let at = text.find(&format!("\"{list}\": [")).or_else(|| text.find(&format!("\"{list}\":["))).unwrap();
    object_at(text, at)
}

/// The text of the object `key` of the JSON text `text`.
fn object(text: &str, key: &str) -> String {
    let at = text.find(&format!("\"{key}\": {{")).or_else(|| text.find(&format!("\"{key}\":{{"))).unwrap();
    object_at(text, at)
}

/// The first `{…}` of `text` after `at` (no braces inside strings in thud's records).
fn object_at(text: &str, at: usize) -> String {
    let open = at + text[at..].find('{').unwrap();
    let mut depth = 0;
    for (i, ch) in text[open..].char_indices() {
        match ch {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return text[open..=open + i].to_string();
                }
            }
            _ => {}
        }
    }
    panic!("an unclosed object")
}

fn flatten(v: &indexed::Ordered, prefix: &str, out: &mut Vec<String>) {
    if let indexed::Ordered::Map(entries) = v {
        for (k, x) in entries {
            match x {
                indexed::Ordered::Map(_) if k == "metrics" => flatten(x, "", out),
                indexed::Ordered::Map(_) if k == "spread" => {
                    if let indexed::Ordered::Map(metrics) = x {
                        for (metric, stats) in metrics {
                            flatten(stats, &format!("{metric}_"), out);
                        }
                    }
                }
                indexed::Ordered::List => {}
                _ => out.push(format!("{prefix}{k}")),
            }
        }
    }
}

/// A JSON value that keeps its keys' order (for the order check only).
mod indexed {
    use serde::de::{Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
    use std::fmt;

    pub enum Ordered {
        Map(Vec<(String, Ordered)>),
        List,
        Scalar,
    }

    impl<'de> Deserialize<'de> for Ordered {
        fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
            struct V;
            impl<'de> Visitor<'de> for V {
                type Value = Ordered;
                fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                    f.write_str("JSON")
                }
                fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<Ordered, A::Error> {
                    let mut v = Vec::new();
                    while let Some((k, x)) = m.next_entry::<String, Ordered>()? {
                        v.push((k, x));
                    }
                    Ok(Ordered::Map(v))
                }
                fn visit_seq<A: SeqAccess<'de>>(self, mut s: A) -> Result<Ordered, A::Error> {
                    while s.next_element::<Ordered>()?.is_some() {}
                    Ok(Ordered::List)
                }
                fn visit_bool<E>(self, _: bool) -> Result<Ordered, E> {
                    Ok(Ordered::Scalar)
                }
                fn visit_i64<E>(self, _: i64) -> Result<Ordered, E> {
                    Ok(Ordered::Scalar)
                }
                fn visit_u64<E>(self, _: u64) -> Result<Ordered, E> {
                    Ok(Ordered::Scalar)
                }
                fn visit_f64<E>(self, _: f64) -> Result<Ordered, E> {
                    Ok(Ordered::Scalar)
                }
                fn visit_str<E>(self, _: &str) -> Result<Ordered, E> {
                    Ok(Ordered::Scalar)
                }
                fn visit_unit<E>(self) -> Result<Ordered, E> {
                    Ok(Ordered::Scalar)
                }
                fn visit_none<E>(self) -> Result<Ordered, E> {
                    Ok(Ordered::Scalar)
                }
                fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<Ordered, D::Error> {
                    Ordered::deserialize(d)
                }
            }
            d.deserialize_any(V)
        }
    }
}

const GRID: [&str; 4] = ["--masses", "30g:40g:2", "--gaps", "2cm:3cm:2"];
const FORCED: [&str; 6] = ["--force-amplitude", "1N", "--freqs", "5Hz:6Hz:2", "--duration", "2"];

/// The CSV headers of studies and orbits, each the schema's table (`{varied}` stands for the
/// varied parameters' columns); their ids added to `checked`.
fn check_study_and_orbit_headers(checked: &mut Vec<&'static str>) {
    let forced = ["--preset", "forced-rattle", "--transient", "20", "--periods", "4"];
    let orbits: Vec<(&str, Vec<&str>, &Table, Vec<&str>)> = vec![
        (
            "sweep --vary --csv",
            vec!["sweep", "--csv", "--vary", "v0=1:2:2", "--vary", "c1=10:20:2"],
            &schema::STUDY,
            vec!["v0_m_s", "c1_n_s_m"],
        ),
        (
            "bifurcation --csv",
            [&["bifurcation", "--csv", "--vary", "f=7.5:7.6:2"][..], &forced[..]].concat(),
            &schema::BIFURCATION,
            vec!["freq_hz"],
        ),
        ("impact-map --csv", [&["impact-map", "--csv"][..], &forced[..]].concat(), &schema::IMPACT_MAP, vec![]),
        ("basins --csv", [&["basins", "--csv", "--grid", "2"][..], &forced[..]].concat(), &schema::BASINS, vec![]),
        (
            "restitution --csv --target",
            vec!["restitution", "--csv", "--target", "0.8"],
            &schema::RESTITUTION_TABLE,
            vec![],
        ),
        ("orbit --csv", vec!["orbit", "--csv", "--preset", "forced-rattle"], &schema::ORBIT_TABLE, vec![]),
        (
            "continue --csv",
            vec!["continue", "--csv", "--preset", "forced-rattle", "--vary", "f=5.5:5.6"],
            &schema::CONTINUATION,
            vec!["freq_hz"],
        ),
        (
            "continue N --csv",
            vec!["continue", "--csv", "--preset", "forced-rattle", "--vary", "f=5.5:5.6:2"],
            &schema::CONTINUATION_FAMILY,
            vec!["freq_hz"],
        ),
    ];
    for (what, args, t, varied) in orbits {
        let want: Vec<String> = t
            .columns
            .iter()
            .flat_map(|c| {
                if *c == schema::VARIED {
                    varied.iter().map(|v| (*v).to_string()).collect()
                } else {
                    vec![c.name.to_string()]
                }
            })
            .collect();
        assert_eq!(header(&ok(&args)), want, "{what}: the header is not the schema's `{}` table", t.id);
        checked.push(t.id);
    }
}

/// A design search's flags: two numeric variables and a choice, two objectives, a parameter's
/// and a result's constraint (a tiny search: only the columns matter here).
const DESIGN_SEARCH: [&str; 22] = [
    "design",
    "--vary",
    "mass=20g:80g",
    "--vary",
    "gap=2cm:4cm",
    "--choose",
    "sphere=steel,nylon",
    "--minimize",
    "spl_max_db",
    "--maximize",
    "inclination_cm_s",
    "--require",
    "mass<=60g",
    "--require",
    "spl_max_db>=10",
    "--evaluations",
    "8",
    "--seed",
    "1",
    "--duration",
    "0.5",
    "--no-limit",
];

/// The `design` table's templates expanded for [`DESIGN_SEARCH`]: a numeric variable named as
/// `sweep --vary` heads the same parameter, a choice bare, an objective as its result column, a
/// constraint `margin_NAME_le|ge`; `file` only with `--save`.
fn design_columns(saved: bool) -> Vec<String> {
    // The rule "named as sweep --vary's column": read the names off that command's header.
    let study = header(&ok(&["sweep", "--csv", "--vary", "mass=20g:80g:2", "--vary", "gap=2cm:4cm:2"]));
    let varied: Vec<String> = study[1..3].to_vec();
    assert_eq!(varied, ["mass_kg", "gap_m"], "sweep --vary's columns");
    let mut out = Vec::new();
    for c in schema::DESIGN.columns {
        match c.name {
            "{variable}" => out.extend(varied.iter().cloned().chain(["sphere".to_string()])),
            "{objective}" => out.extend(["spl_max_db", "inclination_cm_s"].map(String::from)),
            "{margin}" => out.extend(["margin_mass_le", "margin_spl_max_db_ge"].map(String::from)),
            "file" if !saved => {}
            name => out.push(name.to_string()),
        }
    }
    // An objective is a result column: the sweep table's column of the same name.
    for ob in ["spl_max_db", "inclination_cm_s"] {
        assert!(schema::SWEEP.names().contains(&ob), "{ob}");
    }
    out
}

/// `thud design --csv`, with and without `--save DIR` (which adds `file`), is the `design`
/// table with its templates expanded by the search's flags.
fn check_design_header(checked: &mut Vec<&'static str>, dir: &Path) {
    let home = dir.join("home");
    std::fs::create_dir_all(&home).unwrap();
    let plain = crate::common::thud_in(&home, &[&DESIGN_SEARCH[..], &["--csv"]].concat());
    assert_eq!(plain.0, 0, "{}", plain.2);
    assert_eq!(header(&plain.1), design_columns(false), "design --csv: the design table without file");
    let save = dir.join("front");
    let args = [&DESIGN_SEARCH[..], &["--csv", "--save", save.to_str().unwrap()]].concat();
    let saved = crate::common::thud_in(&home, &args);
    assert_eq!(saved.0, 0, "{}", saved.2);
    assert_eq!(header(&saved.1), design_columns(true), "design --csv --save: the design table");
    checked.push(schema::DESIGN.id);
}

#[test]
fn every_cli_csv_header_is_the_one_definition() {
    let dir = tempfile::tempdir().unwrap();
    let mut checked = Vec::new();
    let mut check = |what: String, text: &str, t: &Table| {
        assert_eq!(header(text), names(t), "{what}: the header is not the schema's `{}` table", t.id);
        checked.push(t.id);
    };
    for (what, t) in [
        ("waveform", &schema::PULSE),
        ("history", &schema::HISTORY),
        ("impacts", &schema::IMPACTS),
        ("sweep", &schema::SWEEP),
    ] {
        let out = dir.path().join(format!("{what}.csv"));
        ok(&[&["export", "csv", what, "--points", "5", "--out", out.to_str().unwrap()][..], &GRID[..]].concat());
        check(format!("export csv {what}"), &std::fs::read_to_string(&out).unwrap(), t);
    }
    let runs: Vec<(&str, Vec<&str>, &Table)> = vec![
        ("pulse --csv", vec!["pulse", "--csv", "--points", "3"], &schema::PULSE),
        ("simulate --csv", vec!["simulate", "--csv", "--samples", "3"], &schema::HISTORY),
        (
            "simulate --ensemble --csv",
            vec!["simulate", "--csv", "--ensemble", "3", "--duration", "0.5"],
            &schema::ENSEMBLE,
        ),
        ("sweep --csv", [&["sweep", "--csv"][..], &GRID[..]].concat(), &schema::SWEEP),
        (
            "sweep --ensemble --csv",
            [&["sweep", "--csv", "--ensemble", "2", "--duration", "0.5"][..], &GRID[..]].concat(),
            &schema::SWEEP_ENSEMBLE,
        ),
        ("response --csv", [&["response", "--csv"][..], &FORCED[..]].concat(), &schema::RESPONSE),
        (
            "response --ensemble --csv",
            [&["response", "--csv", "--ensemble", "2"][..], &FORCED[..]].concat(),
            &schema::RESPONSE_ENSEMBLE,
        ),
    ];
    for (what, args, t) in runs {
        check(what.to_string(), &ok(&args), t);
    }
    // Shard parts (CSV) and their merge.
    let parts: Vec<String> = (0..2)
        .map(|k| {
            let p = dir.path().join(format!("part-{k}.csv"));
            let shard = format!("{k}/2");
            let args = [
                &["sweep", "--csv", "--ensemble", "2", "--duration", "0.5", "--shard", &shard, "--out"][..],
                &[p.to_str().unwrap()][..],
                &GRID[..],
            ]
            .concat();
            ok(&args);
            std::fs::read_to_string(&p).unwrap()
        })
        .collect();
    for (k, part) in parts.iter().enumerate() {
        check(format!("sweep --shard {k}/2 --csv part"), part, &schema::SHARD_PART);
    }
    let paths: Vec<String> =
        (0..2).map(|k| dir.path().join(format!("part-{k}.csv")).to_str().unwrap().to_string()).collect();
    let merged = ok(&["merge", &paths[0], &paths[1], "--out", "-", "--csv"]);
    check("merge --csv".into(), &merged, &schema::SWEEP_ENSEMBLE);
    check_study_and_orbit_headers(&mut checked);
    check_design_header(&mut checked, dir.path());
    // Without --target, restitution's table stops before its target column.
    let plain = header(&ok(&["restitution", "--csv"]));
    assert_eq!(plain, names(&schema::RESTITUTION_TABLE)[..2], "restitution --csv without --target");
    let mut ids = checked.clone();
    ids.sort_unstable();
    ids.dedup();
    let mut csv: Vec<&str> = schema::TABLES.iter().filter(|t| t.written_by.contains("csv")).map(|t| t.id).collect();
    csv.sort_unstable();
    assert_eq!(ids, csv, "every CSV table of the schema is written by some command, and checked here");
}

/// `keys` are all columns of `t` (a record may leave out an optional key).
fn within(what: &str, keys: &[String], t: &Table) {
    let known = names(t);
    let unknown: Vec<&String> = keys.iter().filter(|k| !known.contains(k)).collect();
    assert!(unknown.is_empty(), "{what}: {unknown:?} not in the schema's `{}` table ({known:?})", t.id);
}

/// The JSON records that are not a CSV table's rows (orbit, continue, limits, paper): every key,
/// of the record and of its lists' entries, is in the schema, in order where the record is fixed.
#[test]
fn every_other_json_record_s_keys_are_in_the_schema() {
    let orbit = ok(&["orbit", "--json", "--preset", "forced-rattle"]);
    assert_eq!(top_keys(&orbit), names(&schema::ORBIT_RECORD), "orbit --json");
    within("orbit --json impacts[]", &top_keys(&first_record(&orbit, "impacts")), &schema::ORBIT_TABLE);

    let one = ok(&["continue", "--json", "--preset", "forced-rattle", "--vary", "f=5.5:5.6"]);
    within("continue --json", &top_keys(&one), &schema::CONTINUATION_RECORD);
    let mut point = top_keys(&first_record(&one, "points"));
    assert_eq!(point.first().map(String::as_str), Some("value"), "continue --json points[]: the parameter first");
    point.remove(0);
    within("continue --json points[]", &point, &schema::CONTINUATION);
    let v: Value = serde_json::from_str(&one).unwrap();
    assert!(!v["specials"].as_array().unwrap().is_empty(), "a special point to check: {one}");
    assert_eq!(top_keys(&first_record(&one, "specials")), names(&schema::SPECIAL), "continue --json specials[]");
    let family = ok(&["continue", "--json", "--preset", "forced-rattle", "--vary", "f=5.5:5.6:2"]);
    within("continue N --json", &top_keys(&family), &schema::CONTINUATION_RECORD);
    within("continue N --json branches[]", &top_keys(&first_record(&family, "branches")), &schema::CONTINUATION_RECORD);

    let limits = ok(&["limits", "--json"]);
    assert_eq!(top_keys(&limits), names(&schema::LIMITS), "limits --json");
    for list in ["caps", "solver_caps"] {
        assert_eq!(top_keys(&first_record(&limits, list)), names(&schema::CAP), "limits --json {list}[]");
    }
    assert_eq!(top_keys(&first_record(&limits, "ranges")), names(&schema::RANGE), "limits --json ranges[]");

    for id in ["table1", "table3", "table5", "fig2"] {
        let text = ok(&["paper", id, "--json"]);
        within(&format!("paper {id} --json"), &top_keys(&text), &schema::PAPER);
        // A paper table describes its own rows: their keys are its columns' keys.
        let v: Value = serde_json::from_str(&text).unwrap();
        let columns: Vec<String> =
            v["columns"].as_array().unwrap().iter().map(|c| c["key"].as_str().unwrap().to_string()).collect();
        let mut row = top_keys(&first_record(&text, "rows"));
        let mut want = columns.clone();
        row.sort_unstable();
        want.sort_unstable();
        assert_eq!(row, want, "paper {id} --json: a row's keys are its columns' keys");
    }
}

/// `thud design --json`: the record's keys, a front design's, and the keys inside a front
/// design: its variables and objectives by the `design` table's columns, its margins by the
/// constraints as typed.
#[test]
fn design_and_fit_json_records_are_the_schema_s() {
    let home = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let (code, out, err) = crate::common::thud_in(home.path(), args);
        assert_eq!(code, 0, "{args:?}: {err}");
        out
    };
    let text = run(&[&DESIGN_SEARCH[..], &["--json"]].concat());
    within("design --json", &top_keys(&text), &schema::DESIGN_RECORD);
    let front = first_record(&text, "front");
    within("design --json front[]", &top_keys(&front), &schema::DESIGN_FRONT);
    let v: Value = serde_json::from_str(&front).unwrap();
    let keys = |k: &str| -> Vec<String> {
        let mut ks: Vec<String> = v[k].as_object().unwrap().keys().cloned().collect();
        ks.sort();
        ks
    };
    let columns = design_columns(false);
    let (mut vars, mut obs) = (columns[1..4].to_vec(), columns[4..6].to_vec());
    vars.sort();
    obs.sort();
    assert_eq!(keys("variables"), vars, "design --json front[].variables");
    assert_eq!(keys("objectives"), obs, "design --json front[].objectives");
    assert_eq!(keys("margins"), ["mass<=60g", "spl_max_db>=10"], "design --json front[].margins");

    // A structure's free decay: M 2 kg, K 8e4 N/m, C 6 N·s/m, in mm, with a small ripple.
    let (m, k, c) = (2.0f64, 8.0e4f64, 6.0f64);
    let (s, wd) = (c / (2.0 * m), (k / m - (c / (2.0 * m)).powi(2)).sqrt());
    let mut csv = String::from("t_ms,x_mm\n");
    for i in 0..3000 {
        let t = f64::from(i) / 2000.0;
        let ripple = 0.01 * (f64::from(i) * 1.7).sin();
        csv += &format!("{},{}\n", t * 1e3, 0.3 / wd * (-s * t).exp() * (wd * t).sin() * 1e3 + ripple);
    }
    let decay = home.path().join("decay.csv");
    std::fs::write(&decay, csv).unwrap();
    let fit = run(&["fit", "structure", "--data", decay.to_str().unwrap(), "--main-mass", "2", "--json"]);
    assert_eq!(top_keys(&fit), names(&schema::STRUCTURE_FIT), "fit structure --json");
    assert_eq!(top_keys(&object(&fit, "model")), names(&schema::DECAY_MODEL), "fit structure --json model");

    // A damper's record: thud's own run, fitted with M's uncertainty carried (inputs[]).
    let record = run(&["simulate", "--c1", "60", "--csv", "--samples", "6001"]);
    let file = home.path().join("sim.csv");
    std::fs::write(&file, record).unwrap();
    let fit = run(&["fit", "damper", "--data", file.to_str().unwrap(), "--main-mass", "0.5kg±5%", "--json"]);
    // Optional keys (inputs, the record's v0, note) are left out when empty: a subset, in order.
    let keys = top_keys(&fit);
    within("fit damper --json", &keys, &schema::DAMPER_FIT);
    let order: Vec<String> = names(&schema::DAMPER_FIT).into_iter().filter(|k| keys.contains(k)).collect();
    assert_eq!(keys, order, "fit damper --json: the schema's order");
    assert!(keys.contains(&"inputs".to_string()), "an input carried: {fit}");
    assert_eq!(top_keys(&first_record(&fit, "inputs")), names(&schema::INPUT_SHIFT), "fit damper --json inputs[]");
}

#[test]
fn every_cli_json_record_is_the_one_definition() {
    let pulse = ok(&["pulse", "--json", "--points", "3"]);
    let v: Value = serde_json::from_str(&pulse).unwrap();
    assert_eq!(top_keys(&object(&pulse, "waveform")), names(&schema::PULSE), "pulse --json waveform");
    assert!(v.get("k_hz_n_m1_5").is_some() && v.get("k_hz").is_none(), "the unit in the key");

    let text = ok(&["simulate", "--json", "--duration", "0.5"]);
    assert_eq!(flat_keys(&first_record(&text, "impacts")), names(&schema::IMPACTS), "simulate --json impacts[]");
    let sim: Value = serde_json::from_str(&text).unwrap();
    let design = &sim["design"];
    assert_eq!(design["solver"], "event", "enums as the flags spell them");
    assert_eq!(design["radiation"]["pulse"], "half-sine");
    assert!(design["ball"].get("density_kg_m3").is_some() && design["damper"].get("k_hz_n_m1_5").is_some());

    let ens = ok(&["simulate", "--json", "--ensemble", "3", "--duration", "0.5"]);
    assert_eq!(flat_keys(&first_record(&ens, "ensemble")), names(&schema::ENSEMBLE), "simulate --ensemble --json");

    let sweep = ok(&[&["sweep", "--json"][..], &GRID[..]].concat());
    assert_eq!(flat_keys(&first_record(&sweep, "cells")), names(&schema::SWEEP), "sweep --json cells[]");
    let sweep_ens = ok(&[&["sweep", "--json", "--ensemble", "2", "--duration", "0.5"][..], &GRID[..]].concat());
    assert_eq!(
        flat_keys(&first_record(&sweep_ens, "cells")),
        names(&schema::SWEEP_ENSEMBLE),
        "sweep --ensemble --json cells[] (flattened)"
    );

    let resp = ok(&[&["response", "--json"][..], &FORCED[..]].concat());
    let mut keys = vec!["direction".to_string()];
    keys.extend(flat_keys(&first_record(&resp, "points")));
    assert_eq!(keys, names(&schema::RESPONSE), "response --json: direction, then a point");
    let resp: Value = serde_json::from_str(&resp).unwrap();
    assert_eq!(resp["sweeps"][0]["direction"], "from_rest");

    let resp_ens = ok(&[&["response", "--json", "--ensemble", "2"][..], &FORCED[..]].concat());
    let mut keys = vec!["direction".to_string()];
    keys.extend(flat_keys(&first_record(&resp_ens, "points")));
    keys.insert(2, "runs".into());
    assert_eq!(keys, names(&schema::RESPONSE_ENSEMBLE), "response --ensemble --json: direction, runs, a point");
    let resp_ens: Value = serde_json::from_str(&resp_ens).unwrap();
    assert_eq!(resp_ens["runs"], 2);
}

#[test]
fn a_json_lines_shard_part_holds_the_shard_table_s_fields() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("part.jsonl");
    let args = [
        &["sweep", "--ensemble", "2", "--duration", "0.5", "--shard", "0/1", "--out"][..],
        &[p.to_str().unwrap()][..],
        &GRID[..],
    ]
    .concat();
    ok(&args);
    let text = std::fs::read_to_string(&p).unwrap();
    let cell = text.lines().nth(1).unwrap();
    // A cell: index, mass_kg, gap_m, then its runs (each a run of an ensemble).
    assert_eq!(flat_keys(cell), ["index", "mass_kg", "gap_m"], "{cell}");
    let v: Value = serde_json::from_str(cell).unwrap();
    let run = serde_json::to_string(&v["runs"][0]).unwrap();
    let want: Vec<String> = names(&schema::SHARD_PART);
    let mut have: Vec<String> = v["runs"][0].as_object().unwrap().keys().cloned().collect();
    have.extend(["index", "run", "mass_kg", "gap_m", "truncated"].map(String::from));
    have.sort();
    have.dedup();
    let mut sorted = want.clone();
    sorted.sort();
    assert_eq!(have, sorted, "a run of a JSON part: the CSV part's columns but its place in the grid: {run}");
}

/// The guide's schema page lists every table of the definition: its id, then its columns in
/// order, between `<!-- tables:start -->` and `<!-- tables:end -->`.
fn tables_markdown() -> String {
    let mut s = String::new();
    for t in &schema::TABLES {
        s += &format!("- `{}` ({}): {}\n", t.id, t.written_by, t.names().join(", "));
    }
    s
}

#[test]
fn the_guide_s_schema_page_lists_every_table_of_the_definition() {
    let page = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/schema.md")).unwrap();
    let start =
        page.find("<!-- tables:start -->\n").expect("the tables' start marker") + "<!-- tables:start -->\n".len();
    let end = page.find("<!-- tables:end -->").expect("the tables' end marker");
    let want = tables_markdown();
    assert_eq!(page[start..end], want, "docs/guide/schema.md's tables must read:\n{want}");
    // And the page's column table documents every column with its unit.
    for t in &schema::TABLES {
        for c in t.columns {
            // A percentile column `X_p10` is documented as its metric `X`.
            let name = ["_p10", "_median", "_p90"].iter().find_map(|s| c.name.strip_suffix(s)).unwrap_or(c.name);
            // A key that is a list in one document and a count in another has a row for each.
            let units: Vec<&str> = page
                .lines()
                .filter(|l| l.starts_with("| `") && l.split(" | ").next().unwrap().contains(&format!("`{name}`")))
                .map(|row| row.split(" | ").nth(1).unwrap())
                .collect();
            assert!(!units.is_empty(), "`{}` ({}) has no row in the schema page's table", c.name, t.id);
            assert!(
                units.contains(&c.unit),
                "`{}` ({}): the page's units {units:?}, the schema's {}",
                c.name,
                t.id,
                c.unit
            );
        }
    }
}

/// Saved designs and presets in thud 0.1's spelling (`solver = "Event"`, `ball = { density =
/// … }`, `k_hz = …`) load as the same design as today's spelling.
#[test]
fn designs_saved_in_thud_0_1_s_spelling_still_load() {
    let dir = tempfile::tempdir().unwrap();
    let designs = thud::store::designs_dir(dir.path());
    std::fs::create_dir_all(&designs).unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/thud-presets/presets");
    let mut renamed = 0;
    for name in thud_presets::names() {
        let text = std::fs::read_to_string(root.join(format!("{name}.toml"))).unwrap();
        let old = text
            .replace("density_kg_m3 = ", "density = ")
            .replace("radius_m = ", "radius = ")
            .replace("solver = \"event\"", "solver = \"Event\"")
            .replace("k_hz_n_m1_5 = ", "k_hz = ");
        assert!(!text.contains("solver = \"Event\"") && !text.contains("\nk_hz = "), "{name}: today's spelling");
        renamed += usize::from(old != text);
        std::fs::write(designs.join(format!("{name}.toml")), &old).unwrap();
        let loaded = thud::store::load_design(dir.path(), name).unwrap();
        assert_eq!(loaded, thud::presets::preset_file(name).unwrap(), "{name}: the old spelling reads as the new");
    }
    assert_eq!(renamed, thud_presets::names().count(), "every preset had a renamed key");
}

/// Nested values no table's keys describe, each with why: a paper table's rows are keyed by its
/// own `columns`, a continued branch's points are the `continuation` table with the parameter as
/// `value` (checked above), a design search's values are keyed by its flags.
const DESCRIBED_ELSEWHERE: [(&str, &str); 7] = [
    ("paper", "rows"),
    ("paper", "summary"),
    ("continuation_record", "points"),
    ("design_front", "variables"),
    ("design_front", "objectives"),
    ("design_front", "margins"),
    ("design_record", "variables"),
];

/// Every key of the JSON value `v`, to the last level, is a column of `t` (the table of the
/// document, or of the object a key's `keys` names); each object's keys are added to `seen`
/// under its table's id. A nested object or list of objects under a key without `keys` fails,
/// unless [`DESCRIBED_ELSEWHERE`] says where it is described.
fn walk(what: &str, v: &Value, t: &'static Table, seen: &mut std::collections::BTreeMap<&'static str, Vec<String>>) {
    let Some(map) = v.as_object() else { return };
    for (k, x) in map {
        let c = t.columns.iter().find(|c| c.name == k);
        let c =
            c.unwrap_or_else(|| panic!("{what}: key `{k}` is not in the schema's `{}` table ({:?})", t.id, t.names()));
        let entry = seen.entry(t.id).or_default();
        if !entry.contains(k) {
            entry.push(k.clone());
        }
        let path = format!("{what}.{k}");
        let nested: Vec<&Value> = match x {
            Value::Object(_) => vec![x],
            Value::Array(list) => list.iter().filter(|e| e.is_object()).collect(),
            _ => Vec::new(),
        };
        match c.keys {
            Some(id) => {
                let inner = schema::table(id).unwrap();
                for e in nested {
                    walk(&path, e, inner, seen);
                }
            }
            None => assert!(
                nested.is_empty() || DESCRIBED_ELSEWHERE.contains(&(t.id, k.as_str())),
                "{path}: an object with keys, and no table of them in the schema's `{}` table's `{k}`",
                t.id
            ),
        }
    }
}

/// Every JSON document the command line writes, key by key to the last level, is the schema's:
/// each key a column of its table (a nested object's table named by the key), and every column
/// of each table reached written by some run here, but those [`UNSEEN`] says why not.
#[test]
fn every_json_document_s_keys_are_the_schema_s_to_the_last_level() {
    let dir = tempfile::tempdir().unwrap();
    let parts: Vec<String> = (0..2)
        .map(|k| {
            let p = dir.path().join(format!("part-{k}.csv"));
            let shard = format!("{k}/2");
            let args = [
                &["sweep", "--csv", "--ensemble", "2", "--duration", "0.5", "--shard", &shard, "--out"][..],
                &[p.to_str().unwrap()][..],
                &GRID[..],
            ]
            .concat();
            ok(&args);
            p.to_str().unwrap().to_string()
        })
        .collect();
    let runs = json_documents(&parts);
    let mut seen = std::collections::BTreeMap::new();
    for (what, args, t) in runs {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let v: Value = serde_json::from_str(&ok(&args)).unwrap();
        walk(what, &v, t, &mut seen);
    }
    // presets --json is a list of presets.
    let presets: Value = serde_json::from_str(&ok(&["presets", "--json"])).unwrap();
    let list = presets.as_array().unwrap();
    assert!(!list.is_empty());
    for p in list {
        walk("presets", p, &schema::PRESET, &mut seen);
    }
    // Restitution's rows are the restitution table, its columns name them.
    let rest: Value = serde_json::from_str(&ok(&["restitution", "--json", "--target", "0.8"])).unwrap();
    walk("restitution rows", &rest["rows"][0], &schema::RESTITUTION_TABLE, &mut seen);
    let mut missing = Vec::new();
    for (id, keys) in &seen {
        let t = schema::table(id).unwrap();
        for n in t.names() {
            if !keys.iter().any(|k| k == n) && !UNSEEN.iter().any(|(i, k, _)| i == id && *k == n) {
                missing.push(format!("{id}.{n}"));
            }
        }
    }
    assert!(missing.is_empty(), "the schema's {missing:?} written by none of the runs");
    let stale: Vec<String> = UNSEEN
        .iter()
        .filter(|(id, key, _)| seen.get(id).is_none_or(|keys| keys.iter().any(|k| k == key)))
        .map(|(id, key, why)| format!("{id}.{key} ({why})"))
        .collect();
    assert!(stale.is_empty(), "listed as unseen but written (or its table not reached): {stale:?}");
    assert!(seen.len() >= 40, "tables reached: {:?}", seen.keys().collect::<Vec<_>>());
}

/// Every optional key of a design: materials, the physical model and its air, a forced run with
/// a steady state, the ball's start.
const DESIGNED: [&str; 22] = [
    "--duration",
    "1",
    "--force-amplitude",
    "1N",
    "--freq",
    "5Hz",
    "--ball-position",
    "1mm",
    "--ball-velocity",
    "0.1",
    "--periods",
    "4",
    "--sphere",
    "steel",
    "--plate",
    "steel",
    "--sphere-poisson",
    "0.3",
    "--model",
    "physical",
    "--air-temperature",
    "30",
];

/// The runs of [`every_json_document_s_keys_are_the_schema_s_to_the_last_level`]: each command's
/// `--json` (small designs, few points), with the table of its document; `parts` two shard
/// parts for `merge`.
fn json_documents(parts: &[String]) -> Vec<(&'static str, Vec<String>, &'static Table)> {
    let forced = ["--preset", "forced-rattle", "--transient", "20", "--periods", "4"];
    let runs: Vec<(&str, Vec<&str>, &Table)> = vec![
        ("pulse", vec!["pulse", "--json", "--points", "3"], &schema::PULSE_RECORD),
        ("pulse physical", vec!["pulse", "--json", "--points", "3", "--model", "physical"], &schema::PULSE_RECORD),
        ("simulate", vec!["simulate", "--json", "--duration", "0.5", "--radius", "1cm"], &schema::RUN_RECORD),
        ("simulate forced", [&["simulate", "--json"][..], &DESIGNED[..]].concat(), &schema::RUN_RECORD),
        (
            "simulate --ensemble",
            vec!["simulate", "--json", "--ensemble", "3", "--duration", "0.5"],
            &schema::ENSEMBLE_RECORD,
        ),
        ("sweep", [&["sweep", "--json"][..], &GRID[..]].concat(), &schema::SWEEP_RECORD),
        (
            "sweep --ensemble",
            [&["sweep", "--json", "--ensemble", "2", "--duration", "0.5"][..], &GRID[..]].concat(),
            &schema::SWEEP_RECORD,
        ),
        ("merge", vec!["merge", parts[0].as_str(), parts[1].as_str(), "--out", "-", "--json"], &schema::SWEEP_RECORD),
        ("response", [&["response", "--json"][..], &FORCED[..]].concat(), &schema::RESPONSE_RECORD),
        (
            "response --ensemble",
            [&["response", "--json", "--ensemble", "2"][..], &FORCED[..]].concat(),
            &schema::RESPONSE_RECORD,
        ),
        ("sweep --vary", vec!["sweep", "--json", "--vary", "v0=1:2:2", "--vary", "c1=10:20:2"], &schema::STUDY_RECORD),
        (
            "sweep --vary forced",
            vec!["sweep", "--json", "--vary", "f=5:6:2", "--force-amplitude", "1N", "--duration", "1"],
            &schema::STUDY_RECORD,
        ),
        (
            "bifurcation",
            [&["bifurcation", "--json", "--vary", "f=7.5:7.6:2"][..], &forced[..]].concat(),
            &schema::BIFURCATION_RECORD,
        ),
        ("impact-map", [&["impact-map", "--json"][..], &forced[..]].concat(), &schema::IMPACT_MAP_RECORD),
        ("basins", [&["basins", "--json", "--grid", "2"][..], &forced[..]].concat(), &schema::BASINS_RECORD),
        ("restitution", vec!["restitution", "--json", "--target", "0.8"], &schema::PAPER),
        ("paper table3", vec!["paper", "table3", "--json"], &schema::PAPER),
        ("orbit", vec!["orbit", "--json", "--preset", "forced-rattle"], &schema::ORBIT_RECORD),
        (
            "continue",
            vec!["continue", "--json", "--preset", "forced-rattle", "--vary", "f=5.5:5.6"],
            &schema::CONTINUATION_RECORD,
        ),
        (
            "continue N",
            vec!["continue", "--json", "--preset", "forced-rattle", "--vary", "f=5.5:5.6:2"],
            &schema::CONTINUATION_RECORD,
        ),
        ("limits", vec!["limits", "--json"], &schema::LIMITS),
    ];
    runs.into_iter().map(|(what, args, t)| (what, args.into_iter().map(String::from).collect(), t)).collect()
}

/// The columns of the tables reached above that none of its runs writes, each with why.
const UNSEEN: [(&str, &str, &str); 3] = [
    ("damper", "settle", "written only when true: a run that settles takes seconds"),
    ("verdict", "cap", "only when a work cap stops a run"),
    ("paper", "summary", "only some tables of the paper (table 1's differences)"),
];
