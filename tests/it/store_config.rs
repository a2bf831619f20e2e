#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Settings and saved designs: round trips, corrupt files left intact, atomic writes.

use std::fs;
use std::io;
use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

use thud::config::{self, ActionName, Config, KeyBinding, MarkerStyle, ParamValue, Theme, ThresholdDefaults};
use thud::fsio::FileKind;
use thud::presets;
use thud::store::{self, DesignFile, StoreError};

fn full_config() -> Config {
    let mut c = Config {
        theme: Theme::Mono,
        markers: MarkerStyle::Ascii,
        thresholds: ThresholdDefaults { l_star_db: Some(100.5), e_star_cm_s: Some(0.75) },
        ..Default::default()
    };
    for (name, value) in [
        ("main-mass", ParamValue::Number(0.6)),
        ("mass", ParamValue::Text("50g".into())),
        ("no-tension", ParamValue::Switch(true)),
    ] {
        c.design.insert(name.into(), value);
    }
    for (a, k) in [("save", "ctrl-s"), ("load", "L"), ("export", "F5"), ("next-panel", "tab")] {
        c.keys.insert(ActionName::new(a).unwrap(), KeyBinding::new(k).unwrap());
    }
    c
}

#[test]
fn config_round_trips_through_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let c = full_config();
    let path = config::save_config(dir.path(), &c).unwrap();
    assert_eq!(path, dir.path().join("config.toml"));
    let loaded = config::load_config(dir.path());
    assert_eq!(loaded.problem, None);
    assert_eq!(loaded.config, c);
    assert_eq!(loaded.config.key("save").unwrap().text(), "ctrl-s");
    // The default config round-trips too, and a missing file is the default without a warning.
    let empty = tempfile::tempdir().unwrap();
    let l = config::load_config(empty.path());
    assert_eq!((l.config, l.problem), (Config::default(), None));
    config::save_config(empty.path(), &Config::default()).unwrap();
    assert_eq!(config::load_config(empty.path()).config, Config::default());
}

#[test]
fn corrupt_config_is_reported_with_line_and_left_byte_identical() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("config.toml");
    for (text, line, needle) in [
        ("theme = \"mono\"\nmarkers = \"braille\"\ntheme = = 3\n", 3, ""),
        ("theme = \"neon\"\n", 1, "neon"),
        ("[keys]\nsave = \"ctrl-\"\n", 2, "not a key"),
        ("[thresholds]\nl_star = 90\n", 2, "l_star"),
    ] {
        fs::write(&path, text).unwrap();
        let loaded = config::load_config(dir.path());
        assert_eq!(loaded.config, Config::default(), "{text}");
        let p = loaded.problem.clone().expect("a problem");
        assert_eq!(p.path, path);
        assert_eq!(p.line, Some(line), "{text}: {p}");
        assert!(p.message.contains(needle), "{p}");
        let warning = loaded.warning().unwrap();
        assert!(warning.contains(&format!("config.toml:{line}:")) && warning.contains("default"), "{warning}");
        assert_eq!(fs::read(&path).unwrap(), text.as_bytes());
    }
}

#[test]
fn design_round_trips_and_lists() {
    let dir = tempfile::tempdir().unwrap();
    for name in presets::names() {
        let file = presets::preset_file(name).unwrap();
        store::save_design(dir.path(), name, &file, false).unwrap();
        let back = store::load_design(dir.path(), name).unwrap();
        assert_eq!(back, file, "{name}");
    }
    let mut edited = presets::preset_file("default").unwrap();
    edited.description = "my what-if: lighter ball".into();
    edited.design.damper.impact_mass_kg = 0.0301;
    edited.design.observer.theta_rad = 0.3;
    store::save_design(dir.path(), "what-if", &edited, false).unwrap();
    let back = store::load_design(dir.path(), "what-if").unwrap();
    assert_eq!(back.design.damper.impact_mass_kg, 0.0301);
    assert!((back.design.observer.theta_rad - 0.3).abs() < 1e-15);
    let list = store::list_designs(dir.path()).unwrap();
    assert!(list.problems.is_empty());
    assert_eq!(list.designs.len(), presets::names().count() + 1);
    let entry = list.designs.iter().find(|e| e.name == "what-if").unwrap();
    assert_eq!(entry.description, "my what-if: lighter ball");
    store::delete_design(dir.path(), "what-if").unwrap();
    assert!(matches!(store::load_design(dir.path(), "what-if"), Err(StoreError::Io { .. })));
}

#[test]
fn corrupt_design_is_listed_as_a_problem_and_left_alone() {
    let dir = tempfile::tempdir().unwrap();
    store::save_design(dir.path(), "good", &presets::preset_file("default").unwrap(), false).unwrap();
    let bad = store::designs_dir(dir.path()).join("bad.toml");
    let text = "description = \"x\"\n[design]\nball = { density = \"heavy\" }\n";
    fs::write(&bad, text).unwrap();
    let list = store::list_designs(dir.path()).unwrap();
    assert_eq!(list.designs.iter().map(|e| e.name.as_str()).collect::<Vec<_>>(), ["good"]);
    assert_eq!(list.problems.len(), 1);
    assert_eq!(list.problems[0].line, Some(3));
    match store::load_design(dir.path(), "bad") {
        Err(StoreError::Invalid(p)) => assert!(p.to_string().starts_with(&format!("{}:3:", bad.display())), "{p}"),
        other => panic!("expected a parse problem, got {other:?}"),
    }
    assert_eq!(fs::read(&bad).unwrap(), text.as_bytes());
    // An invalid value that parses is reported too.
    let mut f = presets::preset_file("default").unwrap();
    f.design.damper.gap_m = -1.0;
    fs::write(&bad, toml::to_string(&f).unwrap()).unwrap();
    let e = store::load_design(dir.path(), "bad").unwrap_err().to_string();
    assert!(e.contains("gap"), "{e}");
}

#[test]
fn bad_design_names_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let f = presets::preset_file("default").unwrap();
    let e = store::save_design(dir.path(), "../escape", &f, false).unwrap_err();
    assert!(e.to_string().contains("name"), "{e}");
    assert!(!dir.path().join("escape.toml").exists());
}

#[test]
fn atomic_write_survives_a_failure_between_write_and_rename() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("config.toml");
    store::write_atomic(&path, b"theme = \"mono\"\n").unwrap();
    let mut seen_temp = None;
    let r = store::write_atomic_with(&path, b"theme = \"default\"\n# new\n", |tmp| {
        // The new contents are complete on disk next to the target before the rename.
        assert_eq!(tmp.parent(), path.parent());
        assert_eq!(fs::read(tmp).unwrap(), b"theme = \"default\"\n# new\n");
        seen_temp = Some(tmp.to_path_buf());
        Err(io::Error::other("simulated crash before rename"))
    });
    assert!(r.unwrap_err().to_string().contains("simulated crash"));
    assert_eq!(fs::read(&path).unwrap(), b"theme = \"mono\"\n");
    assert!(!seen_temp.unwrap().exists(), "the temporary file is cleaned up");
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
    assert_eq!(config::load_config(dir.path()).config.theme, Theme::Mono);
    // And a write that goes through replaces the file.
    store::write_atomic(&path, b"theme = \"default\"\n").unwrap();
    assert_eq!(config::load_config(dir.path()).config.theme, Theme::Default);
}

#[test]
fn preset_files_round_trip_through_toml_text() {
    for name in presets::names() {
        let f = presets::preset_file(name).unwrap();
        let back = DesignFile::parse(std::path::Path::new("x.toml"), &f.to_toml().unwrap()).unwrap();
        assert_eq!(back, f, "{name}");
    }
}

#[test]
fn saving_over_an_existing_design_is_refused_unless_overwrite() {
    let dir = tempfile::tempdir().unwrap();
    let first = presets::preset_file("default").unwrap();
    let path = store::save_design(dir.path(), "mine", &first, false).unwrap();
    let before = fs::read(&path).unwrap();
    let mut second = first.clone();
    second.description = "a different one".into();
    match store::save_design(dir.path(), "mine", &second, false) {
        Err(StoreError::Exists(p)) => assert_eq!(p, path),
        other => panic!("expected Exists, got {other:?}"),
    }
    assert_eq!(fs::read(&path).unwrap(), before, "the saved design is untouched");
    store::save_design(dir.path(), "mine", &second, true).unwrap();
    assert_eq!(store::load_design(dir.path(), "mine").unwrap().description, "a different one");
    assert_eq!(fs::read_dir(store::designs_dir(dir.path())).unwrap().count(), 1, "no temporary file left");
}

#[test]
fn saves_never_follow_a_symlink_planted_at_a_temporary_name() {
    let dir = tempfile::tempdir().unwrap();
    let designs = store::designs_dir(dir.path());
    fs::create_dir_all(&designs).unwrap();
    let victim = dir.path().join("victim.txt");
    fs::write(&victim, "do not touch\n").unwrap();
    // The old pattern `.NAME.PID-SEQ.tmp` for this process and many sequence numbers, and the
    // config's.
    let pid = std::process::id();
    for seq in 0..2000 {
        std::os::unix::fs::symlink(&victim, designs.join(format!(".mine.toml.{pid}-{seq}.tmp"))).unwrap();
        std::os::unix::fs::symlink(&victim, dir.path().join(format!(".config.toml.{pid}-{seq}.tmp"))).unwrap();
    }
    let file = presets::preset_file("default").unwrap();
    store::save_design(dir.path(), "mine", &file, false).unwrap();
    store::save_design(dir.path(), "mine", &file, true).unwrap();
    config::save_config(dir.path(), &full_config()).unwrap();
    assert_eq!(fs::read_to_string(&victim).unwrap(), "do not touch\n");
    assert_eq!(store::load_design(dir.path(), "mine").unwrap(), file);
    assert!(fs::symlink_metadata(designs.join("mine.toml")).unwrap().file_type().is_file());
    assert_eq!(config::load_config(dir.path()).config, full_config());
}

/// Runs `f` on a thread; fails (instead of hanging) if it takes longer than five seconds.
fn promptly<T: Send + 'static>(what: &str, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(Duration::from_secs(5)).unwrap_or_else(|_| panic!("{what} blocked"))
}

fn mkfifo(path: &Path) {
    assert!(std::process::Command::new("mkfifo").arg(path).status().unwrap().success());
}

#[test]
fn design_files_that_are_fifos_or_devices_are_reported_not_read() {
    let dir = tempfile::tempdir().unwrap();
    let designs = store::designs_dir(dir.path());
    fs::create_dir_all(&designs).unwrap();
    mkfifo(&designs.join("pipe.toml"));
    std::os::unix::fs::symlink("/dev/zero", designs.join("zero.toml")).unwrap();
    store::save_design(dir.path(), "good", &presets::preset_file("default").unwrap(), false).unwrap();
    let d = dir.path().to_path_buf();
    let (pipe, zero, list) = promptly("reading a FIFO or /dev/zero", move || {
        (store::load_design(&d, "pipe"), store::load_design(&d, "zero"), store::list_designs(&d))
    });
    assert!(matches!(pipe, Err(StoreError::NotRegular { kind: FileKind::Fifo, .. })), "{pipe:?}");
    assert!(matches!(zero, Err(StoreError::NotRegular { kind: FileKind::CharDevice, .. })), "{zero:?}");
    let list = list.unwrap();
    assert_eq!(list.designs.iter().map(|e| e.name.as_str()).collect::<Vec<_>>(), ["good"]);
    assert_eq!(list.problems.len(), 2, "{:?}", list.problems);
    assert!(list.problems.iter().any(|p| p.message.contains("FIFO")), "{:?}", list.problems);
}

#[test]
fn a_config_that_is_a_fifo_a_device_or_too_large_gives_the_defaults_and_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("config.toml");
    let check = |needle: &str| {
        let d = dir.path().to_path_buf();
        let loaded = promptly("loading the config", move || config::load_config(&d));
        assert_eq!(loaded.config, Config::default());
        let w = loaded.warning().expect("a warning");
        assert!(w.contains("config.toml") && w.contains(needle) && w.contains("default settings"), "{w}");
    };
    mkfifo(&path);
    check("FIFO");
    fs::remove_file(&path).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &path).unwrap();
    check("character device");
    fs::remove_file(&path).unwrap();
    fs::write(&path, "#".repeat(thud::fsio::MAX_READ_BYTES as usize + 1)).unwrap();
    check("larger than");
}

#[test]
fn store_errors_chain_their_io_source() {
    let dir = tempfile::tempdir().unwrap();
    let e = store::load_design(dir.path(), "absent").unwrap_err();
    let source = std::error::Error::source(&e).expect("the io::Error is the source");
    let io = source.downcast_ref::<io::Error>().expect("an io::Error");
    assert_eq!(io.kind(), io::ErrorKind::NotFound);
    assert!(e.to_string().contains("absent.toml"), "{e}");
}
