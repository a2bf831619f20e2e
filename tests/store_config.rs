//! Settings and saved designs: round trips, corrupt files left intact, atomic writes.

use std::fs;
use std::io;

use thud::config::{self, ActionName, Config, KeyBinding, MarkerStyle, Theme, ThresholdDefaults};
use thud::presets;
use thud::store::{self, DesignFile, StoreError};

fn full_config() -> Config {
    let mut c = Config {
        theme: Theme::Mono,
        markers: MarkerStyle::Ascii,
        thresholds: ThresholdDefaults { l_star_db: Some(100.5), e_star_cm_s: Some(0.75) },
        ..Default::default()
    };
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
        store::save_design(dir.path(), name, &file).unwrap();
        let back = store::load_design(dir.path(), name).unwrap();
        assert_eq!(back, file, "{name}");
    }
    let mut edited = presets::preset_file("default").unwrap();
    edited.description = "my what-if: lighter ball".into();
    edited.design.damper.impact_mass_kg = 0.0301;
    edited.design.observer.theta_rad = 0.3;
    store::save_design(dir.path(), "what-if", &edited).unwrap();
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
    store::save_design(dir.path(), "good", &presets::preset_file("default").unwrap()).unwrap();
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
    let e = store::save_design(dir.path(), "../escape", &f).unwrap_err();
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
