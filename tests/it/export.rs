#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::case_sensitive_file_extension_comparisons,
    clippy::items_after_statements
)] // a panic is how a test fails; file names here are ours
//! Export: WAV, SVG, CSV, `paper all`, and the CLI commands that write them.

use std::fs;
use std::path::Path;
use std::process::Command;

use thud::design::{self, linspace};
use thud::export::{self, report, wav, Artifact, ExportOptions};
use thud::presets;

fn small_grid() -> ExportOptions {
    ExportOptions {
        masses_kg: Some(linspace(0.03, 0.06, 3)),
        gaps_m: Some(linspace(0.02, 0.04, 3)),
        points: 300,
        ..Default::default()
    }
}

#[test]
fn wav_parses_back_with_rate_length_and_a_peak_at_each_impact() {
    let d = presets::preset("default").unwrap().check().unwrap();
    let e = design::evaluate(&d, 0, None).unwrap();
    let bytes = export::render(Artifact::Wav, &d, &ExportOptions::default()).unwrap();
    let mut r = hound::WavReader::new(std::io::Cursor::new(bytes)).unwrap();
    let spec = r.spec();
    assert_eq!((spec.sample_rate, spec.channels, spec.bits_per_sample), (48_000, 1, 16), "16-bit PCM by default");
    assert_eq!(spec.sample_format, hound::SampleFormat::Int);
    let s: Vec<f32> = r.samples::<i16>().map(|v| f32::from(v.unwrap()) / 32767.0).collect();
    assert_eq!(s.len(), (d.damper.duration_s * 48_000.0).round() as usize);
    let field0 = d.impact_field(e.run.impacts[0].u_in_m_s).unwrap();
    let delay = field0.arrival_s();
    let rate = 48_000.0;
    let peak_in = |t0: f64, t1: f64| -> f32 {
        let (a, b) = ((t0 * rate) as usize, ((t1 * rate) as usize).min(s.len()));
        s[a..b].iter().fold(0.0f32, |m, v| m.max(v.abs()))
    };
    assert!(peak_in(0.0, e.run.impacts[0].t_s) == 0.0, "silence before the first impact");
    for (k, i) in e.run.impacts.iter().enumerate() {
        let t = i.t_s + delay;
        let expected = d.impact_field(i.u_in_m_s).unwrap().levels();
        let p_peak = expected.p_max_pa.max(-expected.p_min_pa) / wav::FULL_SCALE_PA;
        let got = f64::from(peak_in(t, t + 1e-3));
        assert!(got > 0.7 * p_peak && got < 1.05 * p_peak, "impact {k}: peak {got} vs {p_peak}");
        if e.run.impacts.get(k + 1).is_none_or(|n| n.t_s > i.t_s + 5e-3) {
            assert!(peak_in(t + 3e-3, t + 4e-3) < 0.01 * got as f32, "impact {k}: the pulse has died away");
        }
    }
}

fn svg_title(doc: &str) -> String {
    let xml = roxmltree::Document::parse(doc).expect("well-formed SVG");
    let root = xml.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    let title = root.children().find(|n| n.has_tag_name("title")).expect("a <title>");
    assert!(xml.descendants().any(|n| n.has_tag_name("text")), "labels");
    title.text().unwrap_or_default().to_string()
}

#[test]
fn every_svg_export_is_well_formed_with_its_title() {
    let d = presets::preset("default").unwrap().check().unwrap();
    for (kind, title, units) in [
        (Artifact::SvgWaveform, "Sound pressure of one impact", ["(ms)", "(Pa)"]),
        (Artifact::SvgDirectivity, "Directivity of one impact", ["(deg)", "(dB re 20 µPa)"]),
        (Artifact::SvgHistory, "Free vibration with and without the damper", ["(s)", "(cm)"]),
        (Artifact::SvgRestitution, "Restitution against impact mass", ["(g)", "(1)"]),
        (Artifact::SvgChart, "Design chart: zone of each impact mass × gap", ["(g)", "(cm)"]),
        (Artifact::SvgFig17, "Design chart: damping inclination against SPLmax (Fig 17)", ["(dB re 20 µPa)", "(cm/s)"]),
    ] {
        let doc = String::from_utf8(export::render(kind, &d, &small_grid()).unwrap()).unwrap();
        let t = svg_title(&doc);
        assert!(t.starts_with(title), "{kind:?}: {t}");
        for u in units {
            assert!(doc.contains(&format!("{u}</text>")), "{kind:?}: axis label with {u}");
        }
    }
}

#[test]
fn csv_exports_have_their_headers_and_rows() {
    let d = presets::preset("paper-fig9").unwrap().check().unwrap();
    for (kind, header, min_rows) in [
        (Artifact::CsvWaveform, "t_s,p_pa", 300),
        (Artifact::CsvHistory, "t_s,x_m,y_m,x_free_m", 300),
        (
            Artifact::CsvImpacts,
            "t_s,wall,u_in_m_s,u_out_m_s,restitution,t_end_s,duration_s,penetration_max_m,spl_db",
            10,
        ),
        (Artifact::CsvSweep, "mass_kg,gap_m,n_impacts,inclination_cm_s", 9),
    ] {
        let text = String::from_utf8(export::render(kind, &d, &small_grid()).unwrap()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[0].starts_with(header), "{kind:?}: {}", lines[0]);
        assert!(lines.len() > min_rows, "{kind:?}: {} rows", lines.len());
        let cols = lines[0].split(',').count();
        assert!(lines.iter().all(|l| l.split(',').count() == cols), "{kind:?}");
    }
    let impacts = String::from_utf8(export::render(Artifact::CsvImpacts, &d, &small_grid()).unwrap()).unwrap();
    let first: Vec<f64> = impacts.lines().nth(1).unwrap().split(',').map(|x| x.parse().unwrap()).collect();
    assert!((first[0] - 0.01018).abs() < 1e-6 && (first[2] - 1.89529).abs() < 1e-4, "{first:?}");
}

#[test]
fn paper_bundle_has_every_listed_file_and_a_report() {
    let files = report::paper_bundle();
    let names: Vec<&str> = files.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, report::expected_files().iter().map(String::as_str).collect::<Vec<_>>());
    let report = &files.last().unwrap().contents;
    for item in thud::paper::items() {
        assert!(report.contains(&format!("## {} —", item.id)), "{}", item.id);
        assert!(names.contains(&format!("{}.csv", item.id).as_str()));
    }
    assert!(!report.contains("**Error:**"));
    assert!(report.contains("| a (mm) | U0 (m/s) |"), "Table 1 as a markdown table");
    for f in files.iter().filter(|f| f.name.ends_with(".svg")) {
        svg_title(&f.contents);
    }
}

fn thud(args: &[&str], config_home: &Path) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_thud"))
        .args(args)
        .env("XDG_CONFIG_HOME", config_home)
        .env("XDG_DATA_HOME", config_home.join("data"))
        .output()
        .expect("run thud");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

#[test]
fn cli_export_commands_write_their_files() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).to_string_lossy().into_owned();
    let grid = ["--masses", "30g:60g:3", "--gaps", "2cm:4cm:3"];
    for what in ["waveform", "history", "impacts", "sweep"] {
        let out = p(&format!("{what}.csv"));
        let (code, _, err) = thud(&[&["export", "csv", what, "--out", &out][..], &grid[..]].concat(), dir.path());
        assert_eq!(code, 0, "{what}: {err}");
        assert!(fs::read_to_string(&out).unwrap().lines().count() > 3);
    }
    for what in ["waveform", "directivity", "history", "restitution", "chart", "fig17"] {
        let out = p(&format!("{what}.svg"));
        let (code, _, err) = thud(
            &[&["export", "svg", what, "--preset", "quiet-nylon", "--out", &out][..], &grid[..]].concat(),
            dir.path(),
        );
        assert_eq!(code, 0, "{what}: {err}");
        svg_title(&fs::read_to_string(&out).unwrap());
    }
    let out = p("sound.wav");
    let (code, _, err) =
        thud(&["export", "wav", "--preset", "steel-ball", "--duration", "0.5", "--out", &out], dir.path());
    assert_eq!(code, 0, "{err}");
    let r = hound::WavReader::open(&out).unwrap();
    assert_eq!((r.spec().sample_rate, r.len()), (48_000, 24_000));
}

#[test]
fn cli_export_pulse_draws_and_plays_the_impact_thud_pulse_computes() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).to_string_lossy().into_owned();
    let impact = ["--u0", "2", "--theta", "30", "--sphere", "steel"];
    let (code, json, err) = thud(&[&["pulse", "--json"][..], &impact[..]].concat(), dir.path());
    assert_eq!(code, 0, "{err}");
    let record: serde_json::Value = serde_json::from_str(&json).unwrap();
    let (arrival, p_max, p_min) = (
        record["arrival_s"].as_f64().unwrap(),
        record["p_max_pa"].as_f64().unwrap(),
        record["p_min_pa"].as_f64().unwrap(),
    );
    let svg = p("pulse.svg");
    let (code, _, err) = thud(&[&["export", "svg", "pulse", "--out", &svg][..], &impact[..]].concat(), dir.path());
    assert_eq!(code, 0, "{err}");
    let title = svg_title(&fs::read_to_string(&svg).unwrap());
    assert!(title.contains("U0 2 m/s") && title.contains("θ 30°"), "{title}");
    let wav = p("pulse.wav");
    let args = [&["export", "wav", "pulse", "--format", "float", "--full-scale", "1", "--out", &wav][..], &impact[..]];
    let (code, _, err) = thud(&args.concat(), dir.path());
    assert_eq!(code, 0, "{err}");
    let samples: Vec<f32> = hound::WavReader::open(&wav).unwrap().samples::<f32>().map(Result::unwrap).collect();
    // Silent until the direct wave arrives (in the interval of sample k, or, on its very end,
    // the next), then the pulse: each sample a mean over 1/48000 s, so within the pulse's
    // extremes and near them.
    let first = samples.iter().position(|&v| v != 0.0).unwrap();
    let k = (arrival * 48_000.0 + 0.5).floor() as usize;
    assert!(first == k || first == k + 1, "first sound at sample {first}, the wave arrives in {k}");
    let (hi, lo) = samples.iter().fold((0f32, 0f32), |(h, l), &v| (h.max(v), l.min(v)));
    assert!(f64::from(hi) <= p_max && f64::from(hi) > 0.8 * p_max, "{hi} against {p_max}");
    assert!(f64::from(lo) >= p_min && f64::from(lo) < 0.8 * p_min, "{lo} against {p_min}");
    // Then silence, for a tenth of a second after the pulse.
    assert!(samples.len() > first + 4800 && samples[samples.len() - 4000..].iter().all(|&v| v == 0.0));
    // The design's flags are not the pulse's; a ball that reaches the observer is named as typed.
    let (code, _, err) = thud(&["export", "svg", "pulse", "--gap", "2cm", "--out", &p("x.svg")], dir.path());
    assert_eq!((code, err.trim().lines().count()), (2, 1), "{err}");
    let (code, _, err) = thud(&["export", "wav", "pulse", "--radius", "1", "--out", &p("x.wav")], dir.path());
    assert_eq!(code, 2, "{err}");
    assert!(err.starts_with("thud: invalid --radius: the ball reaches the observer"), "{err}");
    assert!(!dir.path().join("x.svg").exists() && !dir.path().join("x.wav").exists());
}

#[test]
fn cli_export_errors_are_one_line_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let blocker = dir.path().join("file");
    fs::write(&blocker, "not a folder").unwrap();
    let bad = blocker.join("x.csv");
    for args in [
        vec!["export", "csv", "impacts", "--out", bad.to_str().unwrap()],
        vec!["export", "svg", "waveform", "--gap", "-1cm", "--out", "/tmp/never.svg"],
        vec!["export", "wav", "--full-scale", "0", "--out", "/tmp/never.wav"],
        vec!["export", "svg", "chart", "--masses", "30g:10", "--out", "/tmp/never.svg"],
    ] {
        let (code, out, err) = thud(&args, dir.path());
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty());
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.starts_with("thud: invalid ") && !err.contains("panicked"), "{err}");
    }
    let (_, _, err) = thud(&["export", "csv", "impacts", "--out", bad.to_str().unwrap()], dir.path());
    assert!(err.contains("invalid --out: cannot write") && err.contains("x.csv"), "{err}");
}

#[test]
fn cli_paper_all_writes_every_listed_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("paper");
    let (code, _, err) = thud(&["paper", "all", "--out", out.to_str().unwrap()], dir.path());
    assert_eq!(code, 0, "{err}");
    for name in report::expected_files() {
        assert!(out.join(&name).is_file(), "{name}");
    }
    let (code, _, err) = thud(&["paper", "all"], dir.path());
    assert_eq!(code, 2);
    assert!(err.contains("--out"), "{err}");
}

#[test]
fn cli_presets_lists_names_and_descriptions() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out, err) = thud(&["presets"], dir.path());
    assert_eq!(code, 0, "{err}");
    for name in
        ["default", "paper-fig2", "paper-table1", "paper-fig9", "paper-table3", "machine-tool-fixture", "quiet-nylon"]
    {
        assert!(out.lines().any(|l| l.starts_with(name)), "{name}");
    }
    assert!(err.is_empty(), "no config, no warning: {err}");
}

#[test]
fn cli_runs_on_with_a_warning_when_the_config_is_corrupt() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("thud").join("config.toml");
    fs::create_dir_all(cfg.parent().unwrap()).unwrap();
    let text = "theme = \"mono\"\n[thresholds\nl_star_db = 90\n";
    fs::write(&cfg, text).unwrap();
    for args in [&["presets"][..], &["simulate", "--preset", "paper-fig9", "--duration", "0.1"][..]] {
        let (code, out, err) = thud(args, dir.path());
        assert_eq!(code, 0, "{args:?}: {err}");
        assert!(!out.is_empty());
        assert!(err.contains("warning") && err.contains(&format!("{}:2:", cfg.display())), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    assert_eq!(fs::read(&cfg).unwrap(), text.as_bytes());
}

#[test]
fn cli_uses_the_config_thresholds_unless_flags_say_otherwise() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("thud").join("config.toml");
    fs::create_dir_all(cfg.parent().unwrap()).unwrap();
    fs::write(&cfg, "[thresholds]\nl_star_db = 90.0\n").unwrap();
    let json = |extra: &[&str]| -> serde_json::Value {
        let (code, out, err) = thud(&[&["simulate", "--duration", "0.2", "--json"][..], extra].concat(), dir.path());
        assert_eq!(code, 0, "{err}");
        serde_json::from_str(&out).unwrap()
    };
    let v = json(&[]);
    assert_eq!(v["design"]["thresholds"]["spl_db"], 90.0);
    assert_eq!(v["design"]["thresholds"]["inclination_cm_s"], 0.9);
    assert_eq!(json(&["--l-star", "95"])["design"]["thresholds"]["spl_db"], 95.0);
}

#[test]
fn cli_pulse_takes_the_single_impact_presets() {
    let dir = tempfile::tempdir().unwrap();
    let json = |args: &[&str]| -> serde_json::Value {
        let (code, out, err) = thud(&[&["pulse", "--json", "--points", "50"][..], args].concat(), dir.path());
        assert_eq!(code, 0, "{err}");
        serde_json::from_str(&out).unwrap()
    };
    let fig2 = json(&["--preset", "paper-fig2"]);
    assert!((fig2["p_max_pa"].as_f64().unwrap() - 1.853).abs() < 1e-3, "{}", fig2["p_max_pa"]);
    assert!((fig2["p_min_pa"].as_f64().unwrap() + 2.426).abs() < 1e-3, "{}", fig2["p_min_pa"]);
    let t1 = json(&["--preset", "paper-table1"]);
    assert!((t1["spl_db"].as_f64().unwrap() - 105.6063).abs() < 0.03, "{}", t1["spl_db"]);
    let slower = json(&["--preset", "paper-table1", "--u0", "0.99"]);
    assert!((slower["spl_db"].as_f64().unwrap() - 101.3914).abs() < 0.03, "{}", slower["spl_db"]);
}

/// Whether `python3` runs here (the Python checks are skipped, saying so, where it does not).
fn python3() -> bool {
    Command::new("python3").arg("-c").arg("pass").output().is_ok_and(|o| o.status.success())
}

#[test]
fn cli_wav_formats_parse_back_and_pcm_clips_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_string_lossy().into_owned();
    let write = |name: &str, extra: &[&str]| -> String {
        let out = p(name);
        let (code, _, err) = thud(
            &[&["export", "wav", "--preset", "steel-ball", "--duration", "0.2", "--out", &out][..], extra].concat(),
            dir.path(),
        );
        assert_eq!(code, 0, "{err}");
        err
    };
    write("f.wav", &["--format", "float"]);
    write("p24.wav", &["--format", "pcm24"]);
    write("p16.wav", &[]);
    let float: Vec<f32> = hound::WavReader::open(p("f.wav")).unwrap().samples::<f32>().map(Result::unwrap).collect();
    let mut r24 = hound::WavReader::open(p("p24.wav")).unwrap();
    assert_eq!((r24.spec().bits_per_sample, r24.spec().sample_format), (24, hound::SampleFormat::Int));
    let pcm24: Vec<i32> = r24.samples::<i32>().map(Result::unwrap).collect();
    let pcm16: Vec<i16> = hound::WavReader::open(p("p16.wav")).unwrap().samples::<i16>().map(Result::unwrap).collect();
    assert_eq!((float.len(), pcm24.len(), pcm16.len()), (9600, 9600, 9600));
    assert!(float.iter().any(|&v| v != 0.0), "the sound is not silence");
    for ((&f, &a), &b) in float.iter().zip(&pcm24).zip(&pcm16) {
        // Each PCM code is the float value (within full scale) times 2^(b−1)−1, rounded.
        let f = f64::from(f).clamp(-1.0, 1.0);
        assert!((f64::from(a) - f * 8_388_607.0).abs() <= 0.5 + 1e-6 * 8_388_607.0, "{f} → {a}");
        assert!((f64::from(b) - f * 32_767.0).abs() <= 0.51, "{f} → {b}");
    }
    // A full scale far below the loudest pulse clips PCM and says so; float keeps the values.
    let err = write("loud.wav", &["--full-scale", "0.01"]);
    assert!(err.contains("clipped") && err.contains("--full-scale"), "{err}");
    assert_eq!(err.lines().count(), 2, "the warning and `wrote`: {err}");
    let loud: Vec<i16> = hound::WavReader::open(p("loud.wav")).unwrap().samples::<i16>().map(Result::unwrap).collect();
    assert!(loud.iter().any(|&v| v == i16::MAX || v == -i16::MAX) && !loud.contains(&i16::MIN));
    if !python3() {
        crate::support::skip::skip("python3 is not installed: Python's `wave` check of the files");
        return;
    }
    // Python's standard `wave` module (which refuses WAVE_FORMAT_EXTENSIBLE before 3.12) reads the
    // default file and the 24-bit one, with the same length and the same samples.
    for (name, width) in [("p16.wav", 2), ("p24.wav", 3)] {
        let script = format!(
            "import wave,sys\nw=wave.open(sys.argv[1])\nprint(w.getnchannels(),w.getsampwidth(),w.getframerate(),w.getnframes())\nb=w.readframes(w.getnframes())\nprint(sum(1 for i in range(0,len(b),{width}) if int.from_bytes(b[i:i+{width}],'little',signed=True)!=0))"
        );
        let o = Command::new("python3").arg("-c").arg(&script).arg(p(name)).output().unwrap();
        assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        let text = String::from_utf8_lossy(&o.stdout).into_owned();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some(format!("1 {width} 48000 9600").as_str()), "{name}");
        let nonzero: usize = lines.next().unwrap().parse().unwrap();
        let want = if width == 2 {
            pcm16.iter().filter(|&&v| v != 0).count()
        } else {
            pcm24.iter().filter(|&&v| v != 0).count()
        };
        assert_eq!(nonzero, want, "{name}");
    }
}
