#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Hostile input for the commands added after the flag fuzzer was written (the contract
//! applied to the dynamics and fit commands): every own numeric flag of `bifurcation`, `impact-map`,
//! `basins` and `fit structure|damper`, fed each hostile value, either runs to exit 0 with only
//! finite numbers, or exits 2 with one stderr line naming the flag the user typed. Never a
//! panic, never a run past its work cap (each run is killed after 30 s, a failure).

use std::path::Path;
use std::time::Duration;

use crate::common::{self, Ran};

/// Runs thud with HOME, the XDG folders and the working folder inside `home`.
fn thud_in(home: &Path, args: &[&str]) -> Ran {
    common::thud_within(home, args, Duration::from_secs(30))
}

/// Values no numeric flag may turn into a panic, a hang or a non-finite number.
fn hostile_numbers() -> Vec<String> {
    [
        "NaN",
        "-inf",
        "inf",
        "0",
        "-1",
        "-0.5",
        "1e-308",
        "1e308",
        "1e400",
        "",
        "1 2",
        "3furlongs",
        "3kg",
        "1\n2",
        "\u{1b}[31m1",
    ]
    .iter()
    .map(|s| (*s).to_string())
    .chain([format!("1{}", "0".repeat(400)), "x".repeat(10_000)])
    .collect()
}

/// `--vary` texts with a bad part: the name, the range, the count, the unit.
const HOSTILE_VARY: &[&str] = &[
    "f=NaN:8Hz:3",
    "f=3Hz:inf:3",
    "f=3Hz:8Hz:0",
    "f=3Hz:8Hz:-3",
    "f=3Hz:8Hz:1e9",
    "f=3Hz:8Hz:2.5",
    "f=8Hz:3Hz:3",
    "f=3kg:8kg:3",
    "f=1e308:1e308:2",
    "bogus=1:2:3",
    "=1:2:3",
    "f",
    "f=",
    "f=3Hz:8Hz",
    "solver=1:2:2",
    "mass=-1g:2g:2",
];

/// Checks the contract for one run: exit 0 with finite numbers, or exit 2 naming `flag`.
fn check(home: &Path, args: &[&str], flag: &str) {
    let r = thud_in(home, args);
    let shown: Vec<String> = args.iter().map(|a| a.chars().take(40).collect()).collect();
    assert!(!r.stderr.contains("panicked") && r.code != 101, "{shown:?}: {}", r.stderr);
    match r.code {
        0 => {
            let bad = r.stdout.split(|c: char| !c.is_ascii_alphanumeric()).find(|w| *w == "NaN" || *w == "inf");
            assert!(bad.is_none(), "{shown:?} printed a non-finite number:\n{}", r.stdout);
        }
        2 => {
            assert_eq!(r.stderr.lines().count(), 1, "{shown:?}: {}", r.stderr);
            assert!(r.stdout.is_empty(), "{shown:?} printed: {}", r.stdout);
            assert!(r.stderr.contains(flag), "{shown:?}: does not name {flag}: {}", r.stderr);
            assert!(r.stderr.chars().count() < 400, "{shown:?}: {} characters", r.stderr.chars().count());
            // An overflowing number is quoted as typed, never as the ∞ it parsed to.
            let typed_inf = args.iter().any(|a| a.to_ascii_lowercase().contains("inf"));
            assert!(typed_inf || !r.stderr.contains("inf "), "{shown:?}: {}", r.stderr);
        }
        c => panic!("{shown:?}: exit {c}: {}", r.stderr),
    }
}

/// A short forced study whose own flags are replaced one at a time.
fn forced(cmd: &[&str], own: &[(&str, &str)], flag: &str, value: &str) -> Vec<String> {
    let mut args: Vec<String> = cmd.iter().map(ToString::to_string).collect();
    args.extend(["--preset", "forced-rattle", "--json"].map(String::from));
    for (f, v) in own {
        if *f != flag {
            args.extend([(*f).to_string(), (*v).to_string()]);
        }
    }
    args.extend([flag.to_string(), value.to_string()]);
    args
}

/// A command and its own flags with quick values.
type Study = (&'static [&'static str], &'static [(&'static str, &'static str)]);

#[test]
fn the_dynamics_commands_keep_the_contract_for_every_own_flag() {
    let home = tempfile::tempdir().unwrap();
    let studies: [Study; 3] = [
        (&["bifurcation"], &[("--vary", "f=7Hz:8Hz:2"), ("--periods", "4"), ("--transient", "2")]),
        (&["impact-map"], &[("--periods", "4"), ("--transient", "2")]),
        (&["basins"], &[("--grid", "2"), ("--periods", "4"), ("--transient", "2"), ("--w0", "-1:1")]),
    ];
    for (cmd, own) in studies {
        for (flag, _) in own {
            let values: Vec<String> = match *flag {
                "--vary" => HOSTILE_VARY.iter().map(ToString::to_string).collect(),
                "--w0" => ["NaN:1", "-1:inf", "1:-1", "1:1", "-1e308:1e308", "1", "", "-1m/s:1kg"]
                    .iter()
                    .map(ToString::to_string)
                    .collect(),
                _ => hostile_numbers(),
            };
            for v in values {
                let args = forced(cmd, own, flag, &v);
                let argv: Vec<&str> = args.iter().map(String::as_str).collect();
                check(home.path(), &argv, flag);
            }
        }
    }
}

/// A measured decay (t_s, x_m) of a 5 Hz structure, 2 % damping, 1 kHz for 4 s.
fn decay_csv() -> String {
    let mut s = String::from("t_s,x_m\n");
    for i in 0..4000 {
        let t = f64::from(i) * 1e-3;
        let w = std::f64::consts::TAU * 5.0;
        s.push_str(&format!("{t},{}\n", 0.01 * (-0.02 * w * t).exp() * (w * t).cos()));
    }
    s
}

#[test]
fn fit_keeps_the_contract_for_every_own_flag_and_hostile_files() {
    let home = tempfile::tempdir().unwrap();
    let good = home.path().join("decay.csv");
    std::fs::write(&good, decay_csv()).unwrap();
    let good = good.to_str().unwrap();
    for v in hostile_numbers() {
        check(home.path(), &["fit", "structure", "--data", good, "--main-mass", &v], "--main-mass");
    }
    // Files a careless or hostile user might give as the measurement.
    let dir = home.path().join("a-folder");
    std::fs::create_dir(&dir).unwrap();
    let link = home.path().join("link.csv");
    std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
    let mut files: Vec<(String, String)> = vec![
        ("empty".into(), String::new()),
        ("header-only".into(), "t_s,x_m\n".into()),
        ("nan".into(), decay_csv().replace("\n0.5,", "\n0.5,NaN\n0.5001,")),
        ("inf".into(), decay_csv().replace("\n0.5,", "\n0.5,inf\n0.5001,")),
        ("huge".into(), decay_csv().replace("\n0.5,", "\n0.5,1e308\n0.5001,")),
        ("no-unit".into(), decay_csv().replace("t_s,x_m", "t,x")),
        ("two-signals".into(), decay_csv().replace("t_s,x_m", "t_s,x_m,v_m_s")),
        ("binary".into(), "\u{0}\u{1}\u{2}\u{ff}".repeat(100)),
        ("one-row".into(), "t_s,x_m\n0,1\n".into()),
        ("constant-time".into(), "t_s,x_m\n".to_string() + &"0,1\n".repeat(3000)),
    ];
    files.push(("wrong-kind-unit".into(), decay_csv().replace("t_s,x_m", "t_kg,x_m")));
    let mut paths = vec![dir.to_str().unwrap().to_string(), link.to_str().unwrap().to_string()];
    for (name, text) in &files {
        let p = home.path().join(format!("{name}.csv"));
        std::fs::write(&p, text).unwrap();
        paths.push(p.to_str().unwrap().to_string());
    }
    for p in &paths {
        check(home.path(), &["fit", "structure", "--data", p, "--main-mass", "1kg"], "--data");
        check(home.path(), &["fit", "damper", "--data", p, "--main-mass", "1kg"], "--data");
    }
}
