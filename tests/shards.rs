#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! `thud sweep --shard K/N` and `thud merge`: the parts of a chart computed apart and joined
//! give the chart one `thud sweep` gives, byte for byte; a missing, doubled, foreign or cut part
//! is refused with one line naming it.

mod common;
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
