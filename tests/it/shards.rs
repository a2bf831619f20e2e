#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! `thud sweep --shard K/N` and `thud merge`: the parts of a chart computed apart and joined
//! give the chart one `thud sweep` gives, byte for byte; a missing, doubled, foreign or cut part
//! is refused with one line naming it.

use crate::common;
use common::thud;
use std::path::{Path, PathBuf};

/// A small study: 5 masses × 4 gaps = 20 cells of 0.5 s.
const GRID: [&str; 6] = ["--masses", "30g:100g:5", "--gaps", "2cm:5cm:4", "--duration", "0.5"];

fn sweep(extra: &[&str]) -> String {
    let args: Vec<&str> = ["sweep"].iter().chain(&GRID).chain(extra).copied().collect();
    let (code, out, err) = thud(&args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

/// Writes the N parts of the study (`extra` flags added) into `dir` with `sweep --out`, as CSV
/// when `ext` is `csv`; returns their paths, part K at index K.
fn write_parts(dir: &Path, n: usize, ext: &str, extra: &[&str]) -> Vec<PathBuf> {
    (0..n)
        .map(|k| {
            let path = dir.join(format!("part-{k}-of-{n}.{ext}"));
            let shard = format!("{k}/{n}");
            let p = path.to_str().unwrap();
            let csv: &[&str] = if ext == "csv" { &["--csv"] } else { &[] };
            let args: Vec<&str> = ["sweep"]
                .iter()
                .chain(&GRID)
                .chain(extra)
                .chain(csv)
                .chain(&["--shard", &shard, "--out", p])
                .copied()
                .collect();
            let (code, out, err) = thud(&args);
            assert_eq!(code, 0, "{args:?}: {err}");
            assert!(out.is_empty(), "a part written to --out prints nothing on stdout");
            assert!(err.contains(&format!("wrote {p}")), "{err}");
            path
        })
        .collect()
}

/// `thud merge parts… --out - [flags]`: (exit code, stdout, stderr).
fn merge(parts: &[PathBuf], flags: &[&str]) -> (i32, String, String) {
    let mut args: Vec<&str> = vec!["merge"];
    args.extend(parts.iter().map(|p| p.to_str().unwrap()));
    args.extend(["--out", "-"]);
    args.extend(flags);
    thud(&args)
}

#[test]
fn merged_shards_are_byte_for_byte_the_sweep_json() {
    let whole = sweep(&["--json"]);
    let dir = tempfile::tempdir().unwrap();
    for n in [1, 3, 7] {
        let mut parts = write_parts(dir.path(), n, "jsonl", &[]);
        parts.reverse();
        let (code, out, err) = merge(&parts, &[]);
        assert_eq!(code, 0, "{n} parts: {err}");
        assert!(out == whole, "{n} parts: the merged JSON differs from `sweep --json`");
    }
}

#[test]
fn merged_csv_shards_are_the_sweep_csv_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let parts = write_parts(dir.path(), 3, "csv", &[]);
    let text = std::fs::read_to_string(&parts[1]).unwrap();
    assert!(text.starts_with("# {\"format\":\"thud-sweep-shard\""), "{}", &text[..80]);
    assert!(text.lines().nth(1).unwrap().starts_with("index,run,mass_kg,gap_m,ball_position_m,"));
    assert_eq!(text.lines().count(), 2 + 7, "shard 1/3 of 20 cells is cells 6–12, one row each");
    let (code, out, err) = merge(&parts, &[]);
    assert_eq!(code, 0, "{err}");
    assert!(out == sweep(&["--csv"]), "CSV parts merge to `sweep --csv` by default");
    let (code, out, _) = merge(&parts, &["--json"]);
    assert_eq!(code, 0);
    assert!(out == sweep(&["--json"]), "and to `sweep --json` with --json");
}

#[test]
fn merged_ensemble_shards_are_the_ensemble_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let parts = write_parts(dir.path(), 3, "jsonl", &["--ensemble", "3"]);
    let (code, out, err) = merge(&parts, &[]);
    assert_eq!(code, 0, "{err}");
    assert!(out == sweep(&["--ensemble", "3", "--json"]));
    let parts = write_parts(dir.path(), 7, "csv", &["--ensemble", "3"]);
    let (code, out, err) = merge(&parts, &[]);
    assert_eq!(code, 0, "{err}");
    assert!(out == sweep(&["--ensemble", "3", "--csv"]));
}

#[test]
fn a_missing_or_doubled_shard_is_refused_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let parts = write_parts(dir.path(), 7, "jsonl", &[]);
    let without_4: Vec<PathBuf> = parts.iter().enumerate().filter(|(k, _)| *k != 4).map(|(_, p)| p.clone()).collect();
    let (code, out, err) = merge(&without_4, &[]);
    assert_eq!(code, 2);
    assert!(out.is_empty());
    assert_eq!(err, "thud: merge: shard 4/7 is missing; run it and merge again\n");

    let copy = dir.path().join("copy-of-2.jsonl");
    std::fs::copy(&parts[2], &copy).unwrap();
    let mut doubled = parts.clone();
    doubled.push(copy.clone());
    let (code, _, err) = merge(&doubled, &[]);
    assert_eq!(code, 2);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains(&format!("{} repeats shard 2/7, already given as {}", copy.display(), parts[2].display())),
        "{err}"
    );
}

#[test]
fn parts_of_another_study_split_or_cut_short_are_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let parts = write_parts(dir.path(), 3, "jsonl", &[]);
    let other_dir = tempfile::tempdir().unwrap();
    let other = write_parts(other_dir.path(), 3, "jsonl", &["--l-star", "100"]);
    let (code, _, err) = merge(&[parts[0].clone(), other[1].clone(), parts[2].clone()], &[]);
    assert_eq!(code, 2);
    assert!(
        err.contains(&format!("{} is from a different study than {}", other[1].display(), parts[0].display())),
        "{err}"
    );

    let split = write_parts(other_dir.path(), 4, "jsonl", &[]);
    let (code, _, err) = merge(&[parts[0].clone(), split[1].clone()], &[]);
    assert_eq!(code, 2);
    assert!(err.contains("is shard 1/4 but") && err.contains("is shard 0/3"), "{err}");

    // A job killed while writing with `>` leaves a part without its last lines.
    let text = std::fs::read_to_string(&parts[1]).unwrap();
    let cut = dir.path().join("cut.jsonl");
    let keep: Vec<&str> = text.lines().take(4).collect();
    std::fs::write(&cut, keep.join("\n") + "\n").unwrap();
    let (code, _, err) = merge(&[parts[0].clone(), cut.clone(), parts[2].clone()], &[]);
    assert_eq!(code, 2);
    assert!(err.contains(&format!("{} holds 3 of the 7 cells of shard 1/3 (cells 6–12)", cut.display())), "{err}");

    let plain = dir.path().join("chart.csv");
    std::fs::write(&plain, sweep(&["--csv"])).unwrap();
    let (code, _, err) = merge(std::slice::from_ref(&plain), &[]);
    assert_eq!(code, 2);
    assert!(err.contains(&format!("{} is not a part written by `thud sweep --shard`", plain.display())), "{err}");
}

#[test]
fn bad_shard_values_are_one_line_naming_the_flag() {
    for (value, says) in [
        ("3", "expected K/N"),
        ("3/3", "K must be below N: 0 to 2"),
        ("-1/4", "K '-1' is not a whole number"),
        ("0/0", "N must be at least 1"),
        ("0/21", "21 parts of a chart of 20 cells"),
        ("a/b", "K 'a' is not a whole number"),
    ] {
        let args: Vec<&str> = ["sweep"].iter().chain(&GRID).chain(&["--shard", value]).copied().collect();
        let (code, out, err) = thud(&args);
        assert_eq!(code, 2, "{value}");
        assert!(out.is_empty());
        assert_eq!(err.lines().count(), 1, "{value}: {err}");
        assert!(
            err.starts_with(&format!("thud: invalid --shard: '{value}': ")) && err.contains(says),
            "{value}: {err}"
        );
    }
}

#[test]
fn outputs_are_never_clobbered_without_force() {
    let dir = tempfile::tempdir().unwrap();
    let parts = write_parts(dir.path(), 2, "jsonl", &[]);
    let before = std::fs::read(&parts[0]).unwrap();
    let p = parts[0].to_str().unwrap();
    let args: Vec<&str> = ["sweep"].iter().chain(&GRID).chain(&["--shard", "0/2", "--out", p]).copied().collect();
    let (code, _, err) = thud(&args);
    assert_eq!(code, 2);
    assert!(err.contains("exists; add --force to replace it"), "{err}");
    assert_eq!(std::fs::read(&parts[0]).unwrap(), before);

    let chart = dir.path().join("chart.json");
    std::fs::write(&chart, "keep me").unwrap();
    let c = chart.to_str().unwrap();
    let (code, _, err) = thud(&["merge", parts[0].to_str().unwrap(), parts[1].to_str().unwrap(), "--out", c]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(std::fs::read_to_string(&chart).unwrap(), "keep me");
    let (code, _, err) =
        thud(&["merge", parts[0].to_str().unwrap(), parts[1].to_str().unwrap(), "--out", c, "--force"]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read_to_string(&chart).unwrap() == sweep(&["--json"]));
    let leftovers = std::fs::read_dir(dir.path()).unwrap().count();
    assert_eq!(leftovers, 3, "two parts and the chart: no temporary file left");
}

/// Runs `sh -c script` with `$T` the built thud: (exit code, stdout, stderr).
fn sh(script: &str) -> (i32, String, String) {
    let out = std::process::Command::new("sh")
        .args(["-c", script])
        .env("T", env!("CARGO_BIN_EXE_thud"))
        .output()
        .expect("run sh");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The header of `part` as read back, and the rest of its text.
fn header_of(part: &Path) -> (thud::shard::Header, String) {
    let text = std::fs::read_to_string(part).unwrap();
    let (first, rest) = text.split_once('\n').unwrap();
    (serde_json::from_str(first).unwrap(), rest.to_string())
}

fn one_line_refusal(code: i32, out: &str, err: &str, needles: &[&str]) {
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty(), "{out}");
    assert_eq!(err.lines().count(), 1, "{err}");
    for n in needles {
        assert!(err.contains(n), "{n:?} not in {err}");
    }
}

#[test]
fn merge_refuses_an_over_cap_chart_from_the_headers_before_reading_a_cell() {
    let dir = tempfile::tempdir().unwrap();
    let real = write_parts(dir.path(), 1, "jsonl", &[]).remove(0);
    let (h, _) = header_of(&real);
    // A study of 1000 × 1000 cells × 100 runs (1e8 merged runs), with a valid hash, followed by
    // lines that are not cells: refused by its cap, not by the first bad cell.
    let mut study = h.study.clone();
    study.masses_kg = (0..1000).map(|i| 0.03 + 1e-5 * f64::from(i)).collect();
    study.gaps_m = (0..1000).map(|i| 0.02 + 1e-5 * f64::from(i)).collect();
    study.ensemble = 100;
    let big = thud::shard::Header::new(study, 0, 1);
    let forged = dir.path().join("forged.jsonl");
    std::fs::write(&forged, serde_json::to_string(&big).unwrap() + "\nnot a cell\n").unwrap();
    let p = forged.to_str().unwrap();
    // Under a 300 MB address-space limit: nothing is sized by the header's claims.
    let (code, out, err) = sh(&format!("ulimit -v 300000; exec \"$T\" merge '{p}' --out -"));
    one_line_refusal(code, &out, &err, &["1000000 cells × 100 runs", "1e8", "merged runs", "exceed the limit of 1e6"]);
    // With --no-limit the cells are read, and the first bad one is named with its line.
    let (code, out, err) = sh(&format!("ulimit -v 300000; exec \"$T\" --no-limit merge '{p}' --out -"));
    one_line_refusal(code, &out, &err, &[&format!("{p} line 2: not a cell")]);
}

#[test]
fn forged_headers_are_refused_by_range_before_any_allocation() {
    let dir = tempfile::tempdir().unwrap();
    let real = write_parts(dir.path(), 1, "jsonl", &[]).remove(0);
    let (h, rest) = header_of(&real);
    let text = std::fs::read_to_string(&real).unwrap();
    // Headers with a valid hash of a forged study (what a hand-made part would have) …
    let forge = |edit: &dyn Fn(&mut thud::shard::Study)| {
        let mut study = h.study.clone();
        edit(&mut study);
        serde_json::to_string(&thud::shard::Header::new(study, 0, 1)).unwrap() + "\n" + &rest
    };
    let mut cases: Vec<(String, &str)> = vec![
        (forge(&|s| s.ensemble = 1 << 63), "out of range (invalid ensemble"),
        (forge(&|s| s.ensemble = 1_000_000_000_000), "out of range (invalid ensemble"),
        (forge(&|s| s.band_cm_s = 1e-300), "out of range (invalid band"),
        (forge(&|s| s.masses_kg[0] = 1e300), "out of range (invalid mass"),
        (forge(&|s| s.gaps_m = vec![0.02; 5000]), "out of range (invalid gaps"),
    ];
    // … and numbers no count can be.
    for to in ["\"ensemble\":1e12}", "\"ensemble\":-1}", "\"ensemble\":18446744073709551616}"] {
        cases.push((text.replacen("\"ensemble\":1}", to, 1), "the header does not read"));
    }
    for (forged_text, says) in cases {
        let forged = dir.path().join("forged.jsonl");
        std::fs::write(&forged, forged_text).unwrap();
        let p = forged.to_str().unwrap();
        for no_limit in ["", "--no-limit"] {
            let (code, out, err) = sh(&format!("ulimit -v 300000; exec \"$T\" {no_limit} merge '{p}' --out -"));
            one_line_refusal(code, &out, &err, &[p, says]);
        }
    }
}

#[test]
fn non_finite_or_out_of_range_cells_are_refused_naming_the_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let json = write_parts(dir.path(), 1, "jsonl", &[]).remove(0);
    let csv = write_parts(dir.path(), 1, "csv", &[]).remove(0);
    let json_text = std::fs::read_to_string(&json).unwrap();
    let csv_text = std::fs::read_to_string(&csv).unwrap();
    // The third cell's U0max (JSON line 4; CSV line 5, after the header and the columns).
    let line4 = json_text.lines().nth(3).unwrap();
    let u0 = line4.split("\"u0_max_m_s\":").nth(1).unwrap().split(',').next().unwrap();
    let row = csv_text.lines().nth(4).unwrap();
    let fields: Vec<&str> = row.split(',').collect();
    for bad in ["1e308", "-1", "inf", "NaN", "1e999"] {
        let forged = dir.path().join("forged.jsonl");
        let edited = line4.replacen(&format!("\"u0_max_m_s\":{u0}"), &format!("\"u0_max_m_s\":{bad}"), 1);
        std::fs::write(&forged, json_text.replacen(line4, &edited, 1)).unwrap();
        let p = forged.to_str().unwrap();
        let (code, out, err) = merge(std::slice::from_ref(&forged), &["--no-limit"]);
        one_line_refusal(code, &out, &err, &[&format!("{p} line 4: ")]);

        let forged = dir.path().join("forged.csv");
        let mut f = fields.clone();
        f[8] = bad;
        std::fs::write(&forged, csv_text.replacen(row, &f.join(","), 1)).unwrap();
        let p = forged.to_str().unwrap();
        let (code, out, err) = merge(std::slice::from_ref(&forged), &[]);
        one_line_refusal(code, &out, &err, &[&format!("{p} line 5: "), "u0_max_m_s"]);
    }
    // A long string where a number belongs: the value is cut, the reason kept.
    let forged = dir.path().join("long.jsonl");
    let long = format!("\"u0_max_m_s\":\"{}\"", "x".repeat(5000));
    std::fs::write(&forged, json_text.replacen(line4, &line4.replacen(&format!("\"u0_max_m_s\":{u0}"), &long, 1), 1))
        .unwrap();
    let (code, out, err) = merge(std::slice::from_ref(&forged), &[]);
    one_line_refusal(
        code,
        &out,
        &err,
        &[&format!("{} line 4: not a cell (invalid type: string", forged.display()), "…\", expected f64, column"],
    );
    // Blank lines count: the same bad row after two blank lines is on line 7.
    let forged = dir.path().join("blank.csv");
    let mut f = fields.clone();
    f[8] = "inf";
    let mut lines: Vec<String> = csv_text.lines().map(str::to_string).collect();
    lines[4] = f.join(",");
    lines.insert(2, String::new());
    lines.insert(2, String::new());
    std::fs::write(&forged, lines.join("\n") + "\n").unwrap();
    let (code, out, err) = merge(std::slice::from_ref(&forged), &[]);
    one_line_refusal(code, &out, &err, &[&format!("{} line 7: ", forged.display())]);
}

#[test]
fn a_format_version_is_reported_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let real = write_parts(dir.path(), 1, "jsonl", &[]).remove(0);
    let text = std::fs::read_to_string(&real).unwrap();
    for written in ["1.0", "\"1\"", "2"] {
        let forged = dir.path().join("v.jsonl");
        std::fs::write(&forged, text.replacen("\"format_version\":1", &format!("\"format_version\":{written}"), 1))
            .unwrap();
        let (code, out, err) = merge(std::slice::from_ref(&forged), &[]);
        one_line_refusal(
            code,
            &out,
            &err,
            &[&format!("is a part of format version {written}; this thud reads version 1")],
        );
    }
}

/// A forced study: its inclinations span about 1e7 cm/s, so Table 5 at the default band is
/// over its cap; with --band it shards and merges to the chart `sweep --band` prints.
const FORCED: [&str; 10] =
    ["--force-amplitude", "1e6", "--freq", "5.03", "--masses", "30g:100g:3", "--gaps", "2cm:5cm:3", "--duration", "1"];

#[test]
fn a_forced_study_that_shards_also_merges_with_band() {
    let dir = tempfile::tempdir().unwrap();
    let parts: Vec<PathBuf> = (0..2)
        .map(|k| {
            let path = dir.path().join(format!("f{k}.jsonl"));
            let shard = format!("{k}/2");
            let mut args = vec!["sweep"];
            args.extend(FORCED);
            args.extend(["--shard", &shard, "--out", path.to_str().unwrap()]);
            let (code, _, err) = thud(&args);
            assert_eq!(code, 0, "{err}");
            path
        })
        .collect();
    let (code, out, err) = merge(&parts, &[]);
    one_line_refusal(code, &out, &err, &["--band 0.2 (the parts' band)", "use --band ≥"]);
    let (code, out, err) = merge(&parts, &["--band", "50"]);
    assert_eq!(code, 0, "{err}");
    let mut args = vec!["sweep"];
    args.extend(FORCED);
    args.extend(["--band", "50", "--json"]);
    let (code, whole, err) = thud(&args);
    assert_eq!(code, 0, "{err}");
    assert!(out == whole, "merge --band 50 is `sweep --band 50`");
    // Under --no-limit the narrowest band finishes at once (bands are found per cell, not
    // scanned over the whole span).
    let start = std::time::Instant::now();
    let (code, _, err) = merge(&parts, &["--band", "0.001", "--no-limit"]);
    assert_eq!(code, 0, "{err}");
    assert!(start.elapsed() < std::time::Duration::from_secs(10), "{:?}", start.elapsed());
    let (code, out, err) = merge(&parts, &["--band", "0"]);
    one_line_refusal(code, &out, &err, &["--band"]);
}

#[test]
fn sweep_shard_refuses_a_study_merge_could_never_join() {
    let (code, out, err) =
        thud(&["sweep", "--masses", "30g:100g:1000", "--gaps", "2cm:5cm:100", "--ensemble", "20", "--shard", "0/1000"]);
    one_line_refusal(
        code,
        &out,
        &err,
        &["--ensemble 20", "exceed the limit of 1e6", "`thud merge` joins", "100000 cells × 20 runs"],
    );
}
