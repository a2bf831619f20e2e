#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Forced vibration on the command line: `--force`, `--freq`, `--ball-position`,
//! `--ball-velocity`, `--periods`, `--settle` on simulate, sweep and export; `thud response`
//! (the unforced outputs against those of v0.1: tests/it/unforced_0_1.rs). Runs the built
//! binary with HOME and the XDG folders in a temporary folder.

use std::path::Path;

use crate::common;

struct Ran {
    code: i32,
    stdout: String,
    stderr: String,
}

fn thud_in(home: &Path, args: &[&str]) -> Ran {
    let (code, stdout, stderr) = common::thud_in(home, args);
    Ran { code, stdout, stderr }
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

fn refused(args: &[&str], needles: &[&str]) {
    let r = thud(args);
    assert_eq!(r.code, 2, "{args:?}: exit {} {}", r.code, r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {}", r.stderr);
    assert!(r.stdout.is_empty());
    for n in needles {
        assert!(r.stderr.contains(n), "{args:?}: '{n}' not in {}", r.stderr);
    }
}

/// A file thud 0.1 wrote with the design block's keys and enums renamed as the one schema
/// spells them (CHANGELOG): every number and every other byte as it was.
#[test]
fn a_forced_simulation_reports_its_steady_state() {
    let out = ok(&["simulate", "--v0", "0", "--force-amplitude", "1N", "--freq", "5.5Hz", "--duration", "6", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let s = &v["steady"];
    for key in ["amplitude_m", "amplitude_linear_m", "reduction_db", "impacts_per_period", "leq_db", "window_start_s"] {
        assert!(s[key].is_number(), "steady.{key}: {s}");
    }
    for key in ["periodic", "settled", "truncated"] {
        assert!(s[key].is_boolean(), "steady.{key}");
    }
    assert_eq!(v["design"]["damper"]["force_n"], 1.0);
    assert_eq!(v["design"]["damper"]["freq_hz"], 5.5);
    assert!(v["energy"]["forcing_work_j"].is_number());
    // Today's keys are all there.
    for key in ["n_impacts", "impacts", "maxima", "energy", "final_time_s", "truncated", "u0_max_m_s"] {
        assert!(!v[key].is_null(), "{key}");
    }
    let text = ok(&["simulate", "--v0", "0", "--force-amplitude", "1N", "--freq", "5.5Hz", "--duration", "6"]);
    assert!(
        text.contains("steady    last 10 periods") && text.contains("Leq") && text.contains("force 1 N at 5.5 Hz"),
        "{text}"
    );
    // Without a force there is no steady object at all.
    let free: serde_json::Value = serde_json::from_str(&ok(&["simulate", "--json"])).unwrap();
    assert!(free.get("steady").is_none());
    // --settle runs on past --duration.
    let settled: serde_json::Value = serde_json::from_str(&ok(&[
        "simulate",
        "--v0",
        "0",
        "--force-amplitude",
        "1N",
        "--freq",
        "3Hz",
        "--gap",
        "1",
        "--duration",
        "5",
        "--settle",
        "--json",
    ]))
    .unwrap();
    assert!(settled["final_time_s"].as_f64().unwrap() > 5.0);
    assert_eq!(settled["steady"]["settled"], true);
}

#[test]
fn forcing_flags_are_checked_and_named() {
    refused(&["simulate", "--force-amplitude", "1N"], &["--freq"]);
    refused(&["simulate", "--force-amplitude", "-1"], &["--force-amplitude", "0 to 1e6 N"]);
    refused(&["simulate", "--force-amplitude", "1kg", "--freq", "5"], &["--force-amplitude", "unknown unit"]);
    refused(&["simulate", "--force-amplitude", "1", "--freq", "0"], &["--freq"]);
    refused(&["simulate", "--freq", "1e9Hz"], &["--freq"]);
    refused(&["simulate", "--ball-position", "2.5cm"], &["--ball-position", "d/2"]);
    refused(&["simulate", "--ball-position", "-2cm"], &["--ball-position"]);
    refused(&["simulate", "--ball-velocity", "NaN"], &["--ball-velocity"]);
    refused(&["simulate", "--periods", "0"], &["--periods"]);
    refused(&["simulate", "--periods", "2.5"], &["--periods"]);
    refused(&["response", "--freqs", "3:8:5"], &["--force-amplitude"]);
    refused(&["response", "--force-amplitude", "1", "--freq", "5"], &["--freq", "--freqs"]);
    refused(&["response", "--force-amplitude", "1", "--freqs", "3Hz:8N:5"], &["--freqs"]);
    refused(&["export", "svg", "response", "--out", "-", "--freqs", "3:4:3"], &["--force-amplitude"]);
    // Settling Newmark runs are budgeted before they start.
    refused(
        &["simulate", "--force-amplitude", "1", "--freq", "5", "--settle", "--solver", "newmark"],
        &["Newmark steps"],
    );
    refused(
        &["response", "--force-amplitude", "1", "--freqs", "3:8:1000", "--periods", "1000"],
        &["--freqs", "forcing periods"],
    );
}

#[test]
fn the_old_spelling_of_the_force_amplitude_names_the_new_one() {
    // `--force` replaces an output file; on the commands without one, the amplitude's old name
    // is refused with one line that names `--force-amplitude` and what was typed. (`fit damper`
    // fits a free decay: it takes no force at all, and clap refuses `--force` there.)
    for cmd in [&["simulate", "--freq", "5"][..], &["response"][..], &["restitution"][..]] {
        for old in [&["--force", "1N"][..], &["--force"][..], &["--force", "--json"][..]] {
            let args = [cmd, old].concat();
            let r = thud(&args);
            assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
            assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {}", r.stderr);
            assert!(r.stderr.contains("--force-amplitude"), "{args:?}: {}", r.stderr);
            if old == ["--force", "1N"] {
                assert!(r.stderr.contains("give --force-amplitude 1N"), "{args:?}: {}", r.stderr);
            } else {
                assert!(r.stderr.contains("give --force-amplitude F0"), "{args:?}: {}", r.stderr);
            }
            assert!(r.stdout.is_empty(), "{args:?}: {}", r.stdout);
        }
    }
}

#[test]
fn forcing_flags_keep_the_contract_at_their_bounds() {
    // Every bound of every new flag, on the commands that take it: finite output or one line.
    use thud::limits as L;
    for (flag, range, extra) in [
        ("force-amplitude", L::FORCE, vec!["--freq", "5"]),
        ("freq", L::FREQ, vec!["--force-amplitude", "1"]),
        ("ball-position", L::BALL_POSITION, vec![]),
        ("ball-velocity", L::BALL_VELOCITY, vec![]),
        ("periods", L::PERIODS, vec!["--force-amplitude", "1", "--freq", "5"]),
    ] {
        for v in [range.min, range.max] {
            let text = format!("{v}");
            for base in [
                vec!["simulate", "--json"],
                vec!["simulate"],
                vec!["sweep", "--masses", "30g:40g:2", "--gaps", "2cm:3cm:2"],
            ] {
                let flag_arg = format!("--{flag}");
                let mut args: Vec<&str> = base.clone();
                args.extend(extra.iter().copied());
                args.extend(["--duration", "0.5", &flag_arg, &text]);
                let r = thud(&args);
                match r.code {
                    0 => assert!(
                        !r.stdout.split(|c: char| !c.is_ascii_alphanumeric()).any(|w| w == "NaN" || w == "inf"),
                        "{args:?}: {}",
                        r.stdout
                    ),
                    2 => assert!(r.stderr.lines().count() == 1 && r.stderr.contains("--"), "{args:?}: {}", r.stderr),
                    c => panic!("{args:?}: exit {c}: {}", r.stderr),
                }
            }
        }
    }
}

#[test]
fn response_prints_a_table_a_plot_json_and_csv() {
    let base = ["response", "--force-amplitude", "1N", "--freqs", "4.5Hz:5.5Hz:5", "--periods", "5"];
    let text = ok(&base);
    assert!(
        text.contains("amplitude (mm, log scale) against f") && text.contains("4.500") && text.contains("5.500"),
        "{text}"
    );
    let json: serde_json::Value = serde_json::from_str(&ok(&[&base[..], &["--json"]].concat())).unwrap();
    let sweeps = json["sweeps"].as_array().unwrap();
    assert_eq!(sweeps.len(), 1);
    assert_eq!(sweeps[0]["direction"], "from_rest");
    let points = sweeps[0]["points"].as_array().unwrap();
    assert_eq!(points.len(), 5);
    for p in points {
        assert!(p["freq_hz"].is_number() && p["amplitude_m"].is_number() && p["settled"].is_boolean(), "{p}");
    }
    assert_eq!(json["design"]["damper"]["v0_m_s"], 0.0, "a response starts from rest");
    let csv = ok(&[&base[..], &["--csv"]].concat());
    let lines: Vec<&str> = csv.lines().collect();
    assert!(lines[0].starts_with(
        "direction,freq_hz,periods,window_start_s,window_end_s,amplitude_m,amplitude_linear_m,reduction_db,impacts_per_period,leq_db"
    ));
    assert_eq!(lines.len(), 6);
    assert!(lines[1].starts_with("from_rest,4.5,"));
    // With continuation: a rising and a falling sweep.
    let cont: serde_json::Value =
        serde_json::from_str(&ok(&[&base[..], &["--continuation", "--json"]].concat())).unwrap();
    let dirs: Vec<&str> = cont["sweeps"].as_array().unwrap().iter().map(|s| s["direction"].as_str().unwrap()).collect();
    assert_eq!(dirs, ["up", "down"]);
}

#[test]
fn response_exports_as_svg_and_csv() {
    let home = tempfile::tempdir().unwrap();
    let svg = home.path().join("r.svg");
    let args = ["export", "svg", "response", "--force-amplitude", "1N", "--freqs", "4.6Hz:5.4Hz:4", "--periods", "4"];
    let r = thud_in(home.path(), &[&args[..], &["--out", svg.to_str().unwrap()]].concat());
    assert_eq!(r.code, 0, "{}", r.stderr);
    let text = std::fs::read_to_string(&svg).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let title = doc.descendants().find(|n| n.has_tag_name("title")).unwrap().text().unwrap();
    assert!(title.starts_with("Frequency response under F0 1"), "{title}");
    assert!(text.contains("steady amplitude (mm)") && text.contains("Leq at the observer (dB)"));
    let clips: Vec<&str> =
        doc.descendants().filter(|n| n.has_tag_name("clipPath")).filter_map(|n| n.attribute("id")).collect();
    assert_eq!(clips, ["amplitude", "level"], "one clip path per panel");
    // The same response as CSV, to standard output, equals `thud response --csv`.
    let csv = thud_in(
        home.path(),
        &[
            "export",
            "csv",
            "response",
            "--force-amplitude",
            "1N",
            "--freqs",
            "4.6Hz:5.4Hz:4",
            "--periods",
            "4",
            "--out",
            "-",
        ],
    );
    assert_eq!(csv.code, 0, "{}", csv.stderr);
    assert_eq!(
        csv.stdout,
        ok(&["response", "--force-amplitude", "1N", "--freqs", "4.6Hz:5.4Hz:4", "--periods", "4", "--csv"])
    );
    // export's own --force still means "replace the file".
    let again = thud_in(home.path(), &[&args[..], &["--out", svg.to_str().unwrap()]].concat());
    assert_eq!(again.code, 2);
    let forced = thud_in(home.path(), &[&args[..], &["--out", svg.to_str().unwrap(), "--force"]].concat());
    assert_eq!(forced.code, 0, "{}", forced.stderr);
}

#[test]
fn limits_lists_the_new_ranges_and_the_response_cap() {
    let out = ok(&["limits"]);
    for needle in ["--force-amplitude", "--freq", "--ball-position", "--ball-velocity", "--periods", "forcing periods"]
    {
        assert!(out.contains(needle), "{needle}");
    }
}

/// The solvers' own work caps are listed, a run one stops says `truncated` (not "not
/// settled"), and `--no-limit` lifts them: the forced rattle at 7.7236 Hz reaches the event
/// solver's 400 000 in-contact steps after some 6 000 impacts, within 4 100 periods.
#[test]
fn a_run_cut_by_a_solver_cap_says_truncated_and_no_limit_lifts_the_cap() {
    let limits = ok(&["limits"]);
    for needle in ["event solver: in-contact steps", "event solver: contact searches", "Newmark steps of one run"] {
        assert!(limits.contains(needle), "{needle} in\n{limits}");
    }
    let caps: serde_json::Value = serde_json::from_str(&ok(&["limits", "--json"])).unwrap();
    let contact =
        caps["solver_caps"].as_array().unwrap().iter().find(|c| c["what"] == "event solver: in-contact steps");
    assert_eq!(contact.unwrap()["max"].as_f64(), Some(thud::damper::CONTACT_STEP_CAP as f64));
    let args = ["bifurcation", "--preset", "forced-rattle", "--vary", "f=7.7236Hz:7.7236Hz:1", "--transient", "4000"];
    let cut = ok(&args);
    let band = cut.lines().find(|l| l.trim_start().starts_with("from_rest")).unwrap_or_else(|| panic!("{cut}"));
    assert!(band.ends_with("truncated") && !cut.contains("not settled"), "{cut}");
    let json: serde_json::Value = serde_json::from_str(&ok(&[&args[..], &["--json"]].concat())).unwrap();
    assert_eq!(json["points"][0]["orbit"]["kind"], "truncated");
    assert_eq!(json["points"][0]["orbit"]["cap"], "contact_steps");
    let whole = ok(&[&args[..], &["--no-limit"]].concat());
    let band = whole.lines().find(|l| l.trim_start().starts_with("from_rest")).unwrap_or_else(|| panic!("{whole}"));
    assert!(!whole.contains("truncated"), "{whole}");
    // Whole, the run reaches its orbit: two impacts a period (docs/model.md §6.5, above 7.6 Hz).
    assert!(band.ends_with("2/1"), "{whole}");
}
