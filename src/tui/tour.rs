//! The guided tour: a few steps that tell the paper's story on screen with the real
//! computations. Each step sets the parameters (a preset, then fields typed as in the
//! explorer), says which panel it talks about and shows a caption of at most three lines.
//!
//! The steps live in TOML (`assets/tour.toml`, compiled in; `thud tui --tour FILE` reads a
//! lecturer's own). Every step is checked when the tour is loaded — its preset, each field and
//! value (with the field's range), its panel, the caption's length — so a bad file is refused
//! before the explorer starts, with one line naming the step and the problem.
//!
//! ```toml
//! title = "The impact damper"
//! [[step]]
//! title = "One impact, one M"
//! preset = "paper-fig2"        # optional: else the previous step's design (the first: default)
//! set = { theta = "30deg" }    # optional: fields as typed in the explorer (plain = unit shown)
//! pulse = "single"             # optional: "single" (one impact on a plate) or "loudest"
//! panel = "waveform"           # params, readout, waveform, polar, history or chart
//! best = false                 # optional: jump to the best zone-3 design once the chart is in
//! select = "theta"             # optional: the field the step talks about (else the first it sets)
//! animate = false              # optional: play the run in slow motion (the animation view)
//! speed = "1/10"               # optional, with animate: its playback speed, 1/1000 to 1
//! table1 = false               # optional: show Table 1 beside both models (the Table 1 view)
//! caption = "Two to three lines of text."
//! ```

use std::collections::BTreeMap;
use std::path::PathBuf;

use serde::Deserialize;

use super::anim;
use super::fields::{Knob, Setup};
use super::view::{Panel, PulseView};
use crate::design::Design;
use crate::{fsio, presets};

/// The built-in tour.
pub const BUILT_IN: &str = include_str!("../../assets/tour.toml");

/// Columns a caption is wrapped to when it is checked (the caption box at 80 columns).
pub const CAPTION_WIDTH: usize = 76;
/// Lines a caption may take at [`CAPTION_WIDTH`].
pub const CAPTION_LINES: usize = 3;
/// Most steps in a tour.
const MAX_STEPS: usize = 30;

/// Where a tour comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TourSource {
    BuiltIn,
    File(PathBuf),
}

/// Why a tour cannot be used: the file and the problem, for one line.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("tour {file}: {message}")]
pub struct TourError {
    pub file: String,
    pub message: String,
}

/// One step, checked: the design it shows and what it says.
#[derive(Debug, Clone, PartialEq)]
pub struct TourStep {
    pub title: String,
    pub caption: String,
    pub panel: Panel,
    pub pulse: PulseView,
    pub best: bool,
    /// The preset named by the step (or the one before it): the explorer's preset name.
    pub preset: String,
    pub design: Design,
    /// The ensemble size N the step runs (its `ensemble` field; else the step before's, 1 first).
    pub runs: usize,
    /// True if the step sets L* or e* itself (else the user's configured thresholds apply).
    pub sets_thresholds: bool,
    /// The field the step talks about, selected while it shows (its `select`, else the
    /// first field it sets, else the step before's; the mass first).
    pub select: Knob,
    /// The step plays the run in slow motion (the animation view) instead of its panel.
    pub animate: bool,
    /// The animation's speed (an index into [`crate::tui::anim::SPEEDS`]): the step's `speed`,
    /// else the animation's default.
    pub speed: usize,
    /// The step shows Table 1 beside both models (the Table 1 view) instead of its panel.
    pub table1: bool,
}

/// A checked tour.
#[derive(Debug, Clone, PartialEq)]
pub struct Tour {
    pub title: String,
    pub steps: Vec<TourStep>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TourFile {
    title: String,
    #[serde(rename = "step")]
    steps: Vec<StepFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StepFile {
    title: String,
    caption: String,
    panel: String,
    preset: Option<String>,
    pulse: Option<String>,
    #[serde(default)]
    best: bool,
    #[serde(default)]
    set: BTreeMap<String, toml::Value>,
    select: Option<String>,
    #[serde(default)]
    animate: bool,
    speed: Option<toml::Value>,
    #[serde(default)]
    table1: bool,
}

/// `text` wrapped greedily at spaces into lines of at most `width` columns (a longer word
/// gets a line of its own).
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// The panel a step names.
fn panel(name: &str) -> Option<Panel> {
    Some(match name {
        "params" | "parameters" => Panel::Params,
        "readout" => Panel::Readout,
        "waveform" | "pulse" => Panel::Waveform,
        "polar" | "directivity" => Panel::Polar,
        "history" => Panel::History,
        "chart" => Panel::Chart,
        _ => return None,
    })
}

impl Tour {
    /// The tour of `source` (the built-in one, or a file read through the bounded reader).
    pub fn load(source: &TourSource) -> Result<Tour, TourError> {
        match source {
            TourSource::BuiltIn => Tour::parse("assets/tour.toml", BUILT_IN),
            TourSource::File(path) => {
                let text = fsio::read_to_string(path, fsio::MAX_READ_BYTES)
                    .map_err(|e| TourError { file: fsio::shown(path), message: e.reason() })?;
                Tour::parse(&fsio::shown(path), &text)
            }
        }
    }

    /// Parses and checks a tour's TOML text; `file` names it in errors.
    pub fn parse(file: &str, text: &str) -> Result<Tour, TourError> {
        let err = |message: String| TourError { file: file.to_string(), message };
        let parsed: TourFile = toml::from_str(text).map_err(|e| {
            let at = e.span().map(|s| line_col(text, s.start)).map_or(String::new(), |(l, c)| format!("{l}:{c}: "));
            err(format!("{at}{}", e.message().trim()))
        })?;
        if parsed.steps.is_empty() || parsed.steps.len() > MAX_STEPS {
            return Err(err(format!("{} steps; a tour has 1 to {MAX_STEPS}", parsed.steps.len())));
        }
        let mut steps = Vec::new();
        let (mut setup, mut preset) = (Setup { design: Design::default(), runs: 1 }, "default".to_string());
        let mut select = Knob::MASS;
        for (i, s) in parsed.steps.into_iter().enumerate() {
            let at = |m: String| err(format!("step {} ({}): {m}", i + 1, shown_title(&s.title)));
            if let Some(p) = &s.preset {
                setup.design = presets::preset(p).map_err(|e| at(e.to_string()))?;
                preset = p.trim().to_ascii_lowercase();
            }
            setup = apply_sets(&setup, &s.set).map_err(|e| at(e.to_string()))?;
            crate::tui::fields::check_loaded(&setup).map_err(|e| at(e.to_string()))?;
            let panel = panel(&s.panel).ok_or_else(|| {
                at(format!("panel '{}'; one of params, readout, waveform, polar, history, chart", s.panel))
            })?;
            let pulse = match s.pulse.as_deref() {
                None | Some("loudest") => PulseView::Loudest,
                Some("single") => PulseView::Single,
                Some(other) => return Err(at(format!("pulse '{other}'; single or loudest"))),
            };
            let caption = s.caption.split_whitespace().collect::<Vec<_>>().join(" ");
            let lines = wrap(&caption, CAPTION_WIDTH).len();
            if lines == 0 || lines > CAPTION_LINES {
                return Err(at(format!(
                    "the caption takes {lines} lines at {CAPTION_WIDTH} columns; keep it to 1–{CAPTION_LINES}"
                )));
            }
            if s.animate && s.table1 {
                return Err(at("a step shows the animation or Table 1, not both".into()));
            }
            let speed = match &s.speed {
                None => anim::DEFAULT_SPEED,
                Some(_) if !s.animate => {
                    return Err(at("speed is the animation's playback speed: the step needs animate = true".into()))
                }
                Some(v) => speed(v).map_err(|e| at(e.to_string()))?,
            };
            if s.title.trim().is_empty() || s.title.chars().count() > 60 {
                return Err(at("a step title has 1 to 60 characters".into()));
            }
            select = match (&s.select, s.set.keys().next()) {
                (Some(name), _) => field(name).ok_or_else(|| at(format!("select '{name}': no such field")))?,
                (None, Some(first)) => field(first).unwrap_or(select),
                (None, None) => select,
            };
            let sets_thresholds = s.set.keys().any(|k| matches!(k.as_str(), "L*" | "e*" | "l-star" | "e-star"));
            steps.push(TourStep {
                title: s.title.trim().to_string(),
                caption,
                panel,
                pulse,
                best: s.best,
                preset: preset.clone(),
                design: setup.design.clone(),
                runs: setup.runs,
                sets_thresholds,
                select,
                animate: s.animate,
                speed,
                table1: s.table1,
            });
        }
        Ok(Tour { title: parsed.title, steps })
    }
}

/// The animation speed a step's `speed` names (its index in [`anim::SPEEDS`]): one of the
/// speeds `[` and `]` step through, written as a fraction ("1/30", "1/30×"), a number (0.1, 1)
/// or "1×".
fn speed(value: &toml::Value) -> Result<usize, SpeedRefused> {
    let shown = match value {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    let text = shown.trim().trim_end_matches(['×', 'x', 'X']).trim();
    let rate = match text.split_once('/') {
        Some((a, b)) => a.trim().parse::<f64>().ok().zip(b.trim().parse::<f64>().ok()).map(|(a, b)| a / b),
        None => text.parse::<f64>().ok(),
    };
    let names: Vec<String> = anim::SPEEDS.iter().map(|&r| anim::rate_text(r)).collect();
    rate.filter(|r| r.is_finite())
        .and_then(|r| anim::SPEEDS.iter().position(|&s| ((r - s) / s).abs() < 0.02))
        .ok_or_else(|| SpeedRefused { shown, names: names.join(", ") })
}

/// A step's `speed` that is none of the animation's speeds.
#[derive(Debug, thiserror::Error)]
#[error("speed '{shown}'; one of {names} (the speeds [ and ] step through)")]
struct SpeedRefused {
    shown: String,
    names: String,
}

/// The field a step's `set` key names (its name in messages, e.g. `mass`, `theta`, `L*`).
fn field(key: &str) -> Option<Knob> {
    let key = match key {
        "l-star" => "L*",
        "e-star" => "e*",
        k => k,
    };
    Knob::ALL.into_iter().find(|p| p.param() == key)
}

/// Why a step's `set` table cannot be applied.
#[derive(Debug, thiserror::Error)]
enum SetError {
    /// A key that names no field.
    #[error("unknown field '{key}'; one of: {names}")]
    Unknown { key: String, names: String },
    /// A value that is not text, a number or a switch.
    #[error("field '{key}': {value} is not a value (write it as text, e.g. \"45g\")")]
    NotAValue { key: String, value: String },
    /// The field refused the value.
    #[error(transparent)]
    Field(#[from] crate::error::ThudError),
}

/// `d` with the step's fields set, choices (like the source) first so that a value checked
/// against them (θ against the source's open side) sees the new choice.
fn apply_sets(d: &Setup, sets: &BTreeMap<String, toml::Value>) -> Result<Setup, SetError> {
    let mut fields = Vec::new();
    for (key, value) in sets {
        let p = field(key).ok_or_else(|| {
            let names: Vec<&str> = Knob::ALL.iter().map(|p| p.param()).collect();
            SetError::Unknown { key: key.clone(), names: names.join(", ") }
        })?;
        let text = match value {
            toml::Value::String(s) => s.clone(),
            toml::Value::Integer(n) => n.to_string(),
            toml::Value::Float(x) => x.to_string(),
            toml::Value::Boolean(b) => if *b { "on" } else { "off" }.to_string(),
            other => return Err(SetError::NotAValue { key: key.clone(), value: other.to_string() }),
        };
        fields.push((p, text));
    }
    fields.sort_by_key(|(p, _)| (p.kind().is_some(), Knob::ALL.iter().position(|q| q == p)));
    let mut d = d.clone();
    for (p, text) in fields {
        d = p.parsed(&d, &text)?;
    }
    Ok(d)
}

/// 1-based line and column of byte `at` in `text`.
fn line_col(text: &str, at: usize) -> (usize, usize) {
    let before = &text[..at.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// The file name of a tour source, for messages.
pub fn source_name(source: &TourSource) -> String {
    match source {
        TourSource::BuiltIn => "the built-in tour".into(),
        TourSource::File(p) => fsio::shown(p),
    }
}

/// Longest step title (in characters) a message names; a longer one is cut with "…", so the
/// problem after it is never cut away.
const SHOWN_TITLE_CHARS: usize = 24;

/// A step's title for a message: on one line, at most [`SHOWN_TITLE_CHARS`] characters.
fn shown_title(title: &str) -> String {
    let flat: String = title.trim().chars().map(|c| if c.is_control() { ' ' } else { c }).collect();
    if flat.chars().count() <= SHOWN_TITLE_CHARS {
        flat
    } else {
        flat.chars().take(SHOWN_TITLE_CHARS - 1).chain(['…']).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_tour_loads_with_six_to_ten_steps_of_three_lines_at_most() {
        let t = Tour::load(&TourSource::BuiltIn).unwrap();
        assert!((6..=10).contains(&t.steps.len()), "{}", t.steps.len());
        for s in &t.steps {
            let n = wrap(&s.caption, CAPTION_WIDTH).len();
            assert!((2..=3).contains(&n), "{}: {n} lines", s.title);
        }
        assert_eq!(t.steps[0].pulse, PulseView::Single, "it opens on one impact");
        assert!(t.steps.iter().any(|s| s.panel == Panel::Chart && s.best), "it ends by finding a zone-3 design");
    }

    #[test]
    fn bad_tours_name_the_step_and_the_problem() {
        let ok = "title = \"t\"\n[[step]]\ntitle = \"a\"\npanel = \"polar\"\ncaption = \"one line\"\n";
        assert!(Tour::parse("x.toml", ok).is_ok());
        for (text, want) in [
            (ok.replace("polar", "sideways"), "step 1 (a): panel 'sideways'"),
            (ok.replace("caption = \"one line\"", "caption = \"one line\"\nset = { mas = 3 }"), "unknown field 'mas'"),
            (ok.replace("caption = \"one line\"", "caption = \"one line\"\nset = { mass = \"1e9\" }"), "invalid mass"),
            (ok.replace("caption = \"one line\"", "caption = \"one line\"\npreset = \"nope\""), "unknown preset"),
            (ok.replace("one line", &"word ".repeat(80)), "keep it to 1–3"),
            (ok.replace("title = \"t\"\n", ""), "x.toml: "),
            ("title = \"t\"\nstep = []\n".to_string(), "0 steps"),
            (ok.replace("panel", "pannel"), "1:"),
            (ok.replace("caption = \"one line\"", "caption = \"one line\"\nspeed = \"1/10\""), "needs animate = true"),
            (
                ok.replace("caption = \"one line\"", "caption = \"one line\"\nanimate = true\nspeed = \"1/20\""),
                "speed '1/20'; one of 1/1000×, 1/300×, 1/100×, 1/30×, 1/10×, 1/3×, 1×",
            ),
            (ok.replace("caption = \"one line\"", "caption = \"one line\"\nanimate = true\nspeed = 2"), "speed '2'"),
        ] {
            let e = Tour::parse("x.toml", &text).unwrap_err().to_string();
            assert!(e.starts_with("tour x.toml: ") && e.contains(want), "{want}: {e}");
            assert!(!e.contains('\n'), "one line: {e}");
        }
    }

    #[test]
    fn an_animated_step_sets_its_speed_as_written_or_opens_at_the_default() {
        let step = |extra: &str| {
            let text =
                format!("title = \"t\"\n[[step]]\ntitle = \"a\"\npanel = \"history\"\ncaption = \"c\"\n{extra}\n");
            Tour::parse("x.toml", &text).unwrap().steps[0].speed
        };
        for (written, want) in
            [("\"1/30\"", 1.0 / 30.0), ("\"1/1000×\"", 1e-3), ("0.1", 0.1), ("1", 1.0), ("\"1x\"", 1.0)]
        {
            let i = step(&format!("animate = true\nspeed = {written}"));
            assert!((anim::SPEEDS[i] - want).abs() < 1e-12, "{written}: {}", anim::SPEEDS[i]);
        }
        assert_eq!(step("animate = true"), anim::DEFAULT_SPEED);
        let t = Tour::load(&TourSource::BuiltIn).unwrap();
        assert!(t.steps.iter().any(|s| s.animate), "the built-in tour plays the run");
    }

    #[test]
    fn a_step_sets_the_source_before_the_angle_it_allows() {
        let text = "title = \"t\"\n[[step]]\ntitle = \"a\"\npanel = \"polar\"\ncaption = \"c\"\n\
                    set = { theta = \"-60\", source = \"dipole\", mass = 45 }\n";
        let t = Tour::parse("x.toml", text).unwrap();
        let d = &t.steps[0].design;
        assert_eq!(d.radiation.source, crate::acoustics::Source::Dipole);
        assert!((d.observer.theta_rad.to_degrees() + 60.0).abs() < 1e-9);
        assert!((d.damper.impact_mass_kg - 0.045).abs() < 1e-12, "a plain 45 is 45 g, as the field shows");
    }

    /// The Table 1 step shows the Table 1 view (the engine's table beside both models) and its
    /// caption quotes the engine's mean differences as the view rounds them: the paper's model
    /// 7.6 dB low, the physical model's residual (the tour test checks both are on screen).
    #[test]
    fn the_table1_step_shows_what_its_caption_says() {
        let t = Tour::load(&TourSource::BuiltIn).unwrap();
        let step = t.steps.iter().find(|s| s.title.contains("measured world")).unwrap();
        assert!(step.table1 && !step.animate, "the step shows the Table 1 view");
        assert_eq!(step.design.model, crate::design::Model::Physical, "the header names the physical model");
        let view = super::super::table1::Table1::compute();
        let mean = view.summary.iter().find(|(n, _, _)| n == "mean").unwrap();
        let paper_low = mean.1.trim_start_matches('−');
        assert!(mean.1.starts_with('−'), "the paper's model is low: {}", mean.1);
        assert!(step.caption.contains(&format!("{paper_low} dB low")), "{paper_low}: {}", step.caption);
        assert!(step.caption.contains(&format!("leaves {} dB", mean.2)), "{}: {}", mean.2, step.caption);
    }

    #[test]
    fn wrap_keeps_lines_within_the_width() {
        let lines = wrap("aa bb cc dd ee", 5);
        assert_eq!(lines, vec!["aa bb", "cc dd", "ee"]);
        assert!(wrap("", 10).is_empty());
    }
}
