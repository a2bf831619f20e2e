//! Named starting designs: the paper's set-ups, the physical default and a few realistic
//! designs. Each is a TOML file in `crates/thud-presets/presets/` (the format of saved designs) compiled
//! into the binary, so thud works from any directory.
//!
//! This small crate sits between the engine and its front ends: the engine stays free of TOML
//! (it reads no files and parses no file formats), and the Python module gets the presets
//! without the terminal app (no ratatui, crossterm or clap in its build).

use serde::Deserialize;
use thud_core::design::Design;
use thud_core::error::ThudError;

pub use thud_core::design::TABLE3_C1;

/// The compiled-in preset files: (name, TOML text), in the order `thud presets` lists them.
const SOURCES: &[(&str, &str)] = &[
    ("default", include_str!("../presets/default.toml")),
    ("paper-fig2", include_str!("../presets/paper-fig2.toml")),
    ("paper-table1", include_str!("../presets/paper-table1.toml")),
    ("paper-fig9", include_str!("../presets/paper-fig9.toml")),
    ("paper-table3", include_str!("../presets/paper-table3.toml")),
    ("machine-tool-fixture", include_str!("../presets/machine-tool-fixture.toml")),
    ("quiet-nylon", include_str!("../presets/quiet-nylon.toml")),
    ("steel-ball", include_str!("../presets/steel-ball.toml")),
    ("forced-rattle", include_str!("../presets/forced-rattle.toml")),
];

/// A preset's name and one-line description.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PresetInfo {
    pub name: &'static str,
    pub description: String,
}

/// One preset file: a description and a design (the saved-design format).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Preset {
    /// One line saying what the design is.
    #[serde(default)]
    pub description: String,
    pub design: Design,
}

/// A design file: what `thud … --save`, `thud fit … --save` and the explorer's save write (a
/// preset's format, with the explorer's ensemble size N when it saved one and the relative
/// uncertainties `fit structure --save` writes). Unknown keys are refused, in every table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct DesignFile {
    #[serde(default, rename = "description")]
    _description: String,
    #[serde(default, rename = "ensemble")]
    _ensemble: Option<usize>,
    #[serde(default)]
    uncertainty: std::collections::BTreeMap<String, f64>,
    design: Design,
}

/// The design of a design file's TOML `text`, validated; the error names `design` and says
/// where the text is wrong (line and column) and what is wrong.
pub fn design_file(text: &str) -> Result<Design, ThudError> {
    let file: DesignFile = toml::from_str(text).map_err(|e| {
        let at = e.span().map(|s| {
            let before = &text[..s.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
            format!("line {line}, column {column}: ")
        });
        ThudError::invalid("design", format!("{}{}", at.unwrap_or_default(), e.message().trim()))
    })?;
    file.design.validate()?;
    for (name, u) in &file.uncertainty {
        if thud_core::fit::damper::Input::from_name(name).is_none() {
            return Err(ThudError::invalid(
                "design",
                format!("unknown key `{name}` in [uncertainty]; expected one of main-mass, k, c, mass, gap, v0"),
            ));
        }
        if !(u.is_finite() && *u >= 0.0) {
            return Err(ThudError::invalid(
                "design",
                format!("[uncertainty] {name}: a relative standard uncertainty is a finite fraction ≥ 0"),
            ));
        }
    }
    Ok(file.design)
}

/// The names of all presets, in listing order.
pub fn names() -> impl Iterator<Item = &'static str> {
    SOURCES.iter().map(|(n, _)| *n)
}

/// Parses the compiled-in file of preset `name` and validates its design (a failure is a bug
/// the tests catch, but it is reported, not panicked on).
fn parse(name: &'static str, text: &str) -> Result<Preset, ThudError> {
    let bad = |what: String| ThudError::invalid("preset", format!("crates/thud-presets/presets/{name}.toml: {what}"));
    let file: Preset = toml::from_str(text).map_err(|e| bad(e.message().trim().to_string()))?;
    file.design.validate().map_err(|e| bad(e.to_string()))?;
    Ok(file)
}

/// Every preset with its description, in listing order.
pub fn list() -> Result<Vec<PresetInfo>, ThudError> {
    SOURCES.iter().map(|&(name, text)| Ok(PresetInfo { name, description: parse(name, text)?.description })).collect()
}

/// The preset called `name` (case-insensitive) with its description.
pub fn preset_file(name: &str) -> Result<Preset, ThudError> {
    let key = name.trim();
    let (n, text) = SOURCES.iter().find(|(n, _)| n.eq_ignore_ascii_case(key)).ok_or_else(|| {
        ThudError::invalid(
            "preset",
            format!("unknown preset '{name}'; one of: {}", names().collect::<Vec<_>>().join(", ")),
        )
    })?;
    parse(n, text)
}

/// The preset called `name` (case-insensitive).
pub fn preset(name: &str) -> Result<Design, ThudError> {
    preset_file(name).map(|f| f.design)
}

#[cfg(test)]
mod tests {
    use super::*;
    use thud_core::acoustics::{QuadSigns, Radiation, Source};
    use thud_core::design::{BallSize, U0MaxRule};

    /// The Rust-built presets these files replaced; their values must not change. The engine
    /// builds the paper's set-ups itself (its `paper` module runs without the app's files), so
    /// this also checks that the engine and the files agree.
    fn legacy(name: &str) -> Design {
        let mut d = Design::default();
        if name == "default" {
            return d;
        }
        d.radiation = Radiation { source: Source::Quadrupole, quad_signs: QuadSigns::Paper, ..Default::default() };
        if name == "paper-table3" {
            d.damper.v0_m_s = 1.4;
            d.damper.c1_n_s_m = TABLE3_C1;
            d.damper.no_tension = true;
            d.u0max_rule = U0MaxRule::WholeRun;
        }
        d
    }

    #[test]
    fn the_engines_paper_designs_equal_the_preset_files() {
        assert_eq!(preset("default").unwrap(), Design::default());
        assert_eq!(preset("paper-fig9").unwrap(), Design::paper_fig9());
        assert_eq!(preset("paper-table3").unwrap(), Design::paper_table3());
    }

    #[test]
    fn the_three_original_presets_are_unchanged() {
        for name in ["default", "paper-fig9", "paper-table3"] {
            assert_eq!(preset(name).unwrap(), legacy(name), "{name}");
        }
    }

    #[test]
    fn every_preset_parses_validates_and_has_a_description() {
        let list = list().unwrap();
        assert_eq!(list.len(), SOURCES.len());
        for p in list {
            assert!(!p.description.is_empty() && !p.description.contains('\n'), "{}", p.name);
            let d = preset(p.name).unwrap();
            d.check().unwrap();
        }
    }

    #[test]
    fn single_impact_presets_are_the_papers_dipole() {
        for name in ["paper-fig2", "paper-table1"] {
            let d = preset(name).unwrap();
            assert_eq!(d.ball, BallSize::Radius(0.01905));
            assert_eq!(d.radiation.source, Source::Dipole);
            assert_eq!(d.radiation.quad_signs, QuadSigns::Paper);
            assert_eq!(d.damper.impact_mass_kg, 0.0405);
        }
        assert_eq!(preset("paper-table1").unwrap().observer.r_m, 0.2828);
    }

    #[test]
    fn unknown_preset_names_the_choices() {
        let e = preset("nope").unwrap_err();
        assert_eq!(e.param(), "preset");
        assert!(e.to_string().contains("quiet-nylon"));
        assert!(preset(" Paper-Fig9 ").is_ok());
    }
}
