//! The user's settings, `config.toml` in the config directory (on Linux
//! `$XDG_CONFIG_HOME/thud/config.toml`): theme, key overrides, default zone thresholds and the
//! marker style of plots. Front-end support, not physics.
//!
//! A file that fails to parse is reported with its path, line and problem; the caller goes on
//! with the defaults and the file is never overwritten by loading.

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::design::Thresholds;
use crate::error::ThudError;
use crate::fsio;
use crate::store::{self, FileProblem, StoreError};

/// File name of the settings inside the config directory.
pub const CONFIG_FILE: &str = "config.toml";

/// A value in `config.toml` that cannot be used (serde reports it with the file's line).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ConfigError {
    /// A key binding that names no key.
    #[error("'{0}' is not a key; use a character, f1-f24 or a named key like enter, esc, tab, up, pagedown, optionally with ctrl-, alt-, shift-")]
    NotAKey(String),
    /// An entry of `[keys]` whose name cannot be an action.
    #[error("'{0}' is not an action name; use lower-case letters, digits, '-' or '_'")]
    NotAnAction(String),
}

/// Colour theme of the terminal interface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Theme {
    /// Colours.
    #[default]
    Default,
    /// No colours: bold and reverse video only.
    Mono,
}

/// How plot points are drawn in the terminal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MarkerStyle {
    /// Unicode braille dots (fine resolution).
    #[default]
    Braille,
    /// Plain ASCII characters (any terminal font).
    Ascii,
}

/// A key other than a printable character.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NamedKey {
    Enter,
    Esc,
    Tab,
    BackTab,
    Backspace,
    Delete,
    Insert,
    Space,
    Up,
    Down,
    Left,
    Right,
    Home,
    End,
    PageUp,
    PageDown,
}

const NAMED_KEYS: &[(&str, NamedKey)] = &[
    ("enter", NamedKey::Enter),
    ("esc", NamedKey::Esc),
    ("tab", NamedKey::Tab),
    ("backtab", NamedKey::BackTab),
    ("backspace", NamedKey::Backspace),
    ("delete", NamedKey::Delete),
    ("insert", NamedKey::Insert),
    ("space", NamedKey::Space),
    ("up", NamedKey::Up),
    ("down", NamedKey::Down),
    ("left", NamedKey::Left),
    ("right", NamedKey::Right),
    ("home", NamedKey::Home),
    ("end", NamedKey::End),
    ("pageup", NamedKey::PageUp),
    ("pagedown", NamedKey::PageDown),
];

/// The key itself of a key binding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyCode {
    /// A printable character, as typed (`S` is shift-s).
    Char(char),
    /// A function key F1–F24.
    F(u8),
    Named(NamedKey),
}

/// A parsed key: modifiers and the key, from text like `s`, `ctrl-s`, `alt-enter`, `F5`, `pagedown`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KeySpec {
    pub ctrl: bool,
    pub alt: bool,
    pub shift: bool,
    pub code: KeyCode,
}

impl KeySpec {
    /// Parses a key string: optional `ctrl-`, `alt-`, `shift-` prefixes (also with '+'), then one
    /// character, `f1`–`f24` or a named key (enter, esc, tab, backtab, backspace, delete, insert,
    /// space, up, down, left, right, home, end, pageup, pagedown). Names are case-insensitive.
    pub fn parse(text: &str) -> Result<KeySpec, ConfigError> {
        let mut rest = text.trim();
        let (mut ctrl, mut alt, mut shift) = (false, false, false);
        loop {
            let lower = rest.to_ascii_lowercase();
            let prefix =
                ["ctrl-", "ctrl+", "alt-", "alt+", "shift-", "shift+"].into_iter().find(|p| lower.starts_with(p));
            let Some(p) = prefix else { break };
            if rest.len() == p.len() {
                break;
            }
            match &p[..p.len() - 1] {
                "ctrl" => ctrl = true,
                "alt" => alt = true,
                _ => shift = true,
            }
            rest = &rest[p.len()..];
        }
        let code = key_code(rest).ok_or_else(|| ConfigError::NotAKey(text.to_string()))?;
        Ok(KeySpec { ctrl, alt, shift, code })
    }
}

/// The key code of `s` (one character, `fN`, or a name).
fn key_code(s: &str) -> Option<KeyCode> {
    let mut chars = s.chars();
    if let (Some(c), None) = (chars.next(), chars.clone().next()) {
        return (!c.is_whitespace() && !c.is_control()).then_some(KeyCode::Char(c));
    }
    let lower = s.to_ascii_lowercase();
    if let Some(n) = lower.strip_prefix('f').and_then(|n| n.parse::<u8>().ok()) {
        return (1..=24).contains(&n).then_some(KeyCode::F(n));
    }
    NAMED_KEYS.iter().find(|(name, _)| *name == lower).map(|&(_, k)| KeyCode::Named(k))
}

/// A key binding as written in the file, checked when read.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub struct KeyBinding {
    text: String,
    spec: KeySpec,
}

impl KeyBinding {
    /// The binding for key text `text` (see [`KeySpec::parse`]).
    pub fn new(text: &str) -> Result<KeyBinding, ConfigError> {
        Ok(KeyBinding { spec: KeySpec::parse(text)?, text: text.trim().to_string() })
    }

    /// The text as written.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The parsed key.
    pub fn spec(&self) -> KeySpec {
        self.spec
    }
}

impl TryFrom<String> for KeyBinding {
    type Error = ConfigError;
    fn try_from(s: String) -> Result<Self, ConfigError> {
        KeyBinding::new(&s)
    }
}

impl From<KeyBinding> for String {
    fn from(k: KeyBinding) -> String {
        k.text
    }
}

impl fmt::Display for KeyBinding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

/// The name of a TUI action in the `[keys]` table: lower-case letters, digits, '-' and '_',
/// starting with a letter (e.g. `save`, `load`, `export`, `next-panel`). Which names exist is
/// the TUI's business; it reports names it does not know.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub struct ActionName(String);

impl ActionName {
    /// Checks and wraps an action name.
    pub fn new(name: &str) -> Result<ActionName, ConfigError> {
        let ok = name.chars().next().is_some_and(|c| c.is_ascii_lowercase())
            && name.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-' || c == '_');
        if ok {
            Ok(ActionName(name.to_string()))
        } else {
            Err(ConfigError::NotAnAction(name.to_string()))
        }
    }

    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl TryFrom<String> for ActionName {
    type Error = ConfigError;
    fn try_from(s: String) -> Result<Self, ConfigError> {
        ActionName::new(&s)
    }
}

impl From<ActionName> for String {
    fn from(a: ActionName) -> String {
        a.0
    }
}

/// Default zone thresholds; each one left out keeps the design's own.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThresholdDefaults {
    /// L* on SPLmax (dB).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub l_star_db: Option<f64>,
    /// e* on the damping inclination (cm/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub e_star_cm_s: Option<f64>,
}

/// The settings of `config.toml`. Every field may be left out.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    pub theme: Theme,
    pub markers: MarkerStyle,
    pub thresholds: ThresholdDefaults,
    /// Key overrides: action name → key (e.g. `save = "ctrl-s"`).
    pub keys: BTreeMap<ActionName, KeyBinding>,
}

impl Config {
    /// Checks the values serde cannot: thresholds inside their ranges (the same table the
    /// command line and the explorer use, [`crate::limits`]), no key bound to two actions.
    pub fn validate(&self) -> Result<(), ThudError> {
        use crate::limits::{E_STAR, L_STAR};
        for (name, v, range) in
            [("l_star_db", self.thresholds.l_star_db, L_STAR), ("e_star_cm_s", self.thresholds.e_star_cm_s, E_STAR)]
        {
            if let Some(x) = v {
                range.check_as(name, x)?;
            }
        }
        let mut seen: Vec<(KeySpec, &ActionName)> = Vec::new();
        for (action, key) in &self.keys {
            if let Some((_, other)) = seen.iter().find(|(k, _)| *k == key.spec()) {
                return Err(ThudError::invalid(
                    "keys",
                    format!("'{key}' is bound to both '{}' and '{}'", other.as_str(), action.as_str()),
                ));
            }
            seen.push((key.spec(), action));
        }
        Ok(())
    }

    /// `base` with the thresholds this config sets.
    pub fn thresholds(&self, base: Thresholds) -> Thresholds {
        Thresholds {
            spl_db: self.thresholds.l_star_db.unwrap_or(base.spl_db),
            inclination_cm_s: self.thresholds.e_star_cm_s.unwrap_or(base.inclination_cm_s),
            zone_by: base.zone_by,
        }
    }

    /// The key override of `action`, if any.
    pub fn key(&self, action: &str) -> Option<&KeyBinding> {
        self.keys.iter().find(|(a, _)| a.as_str() == action).map(|(_, k)| k)
    }

    /// The settings as TOML text.
    pub fn to_toml(&self) -> Result<String, ThudError> {
        toml::to_string(self).map_err(|e| ThudError::invalid("config", format!("cannot be written as TOML: {e}")))
    }
}

/// A loaded config and what was wrong with the file (if anything). With a problem the config
/// is the default one and the file was left untouched.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ConfigLoad {
    pub config: Config,
    /// Where the settings were looked for.
    pub path: PathBuf,
    pub problem: Option<FileProblem>,
}

impl ConfigLoad {
    /// A one-line warning for the user, when the file was not usable.
    pub fn warning(&self) -> Option<String> {
        self.problem.as_ref().map(|p| format!("warning: {p}; using the default settings"))
    }
}

/// Path of `config.toml` inside `config_dir`.
pub fn config_path(config_dir: &Path) -> PathBuf {
    config_dir.join(CONFIG_FILE)
}

/// Loads `config.toml` from `config_dir`. A missing file gives the defaults silently; a file
/// that cannot be read, is not a regular file (a symlink to one is fine; a FIFO or a device such
/// as `/dev/zero` is not opened for reading), is larger than [`fsio::MAX_READ_BYTES`], does not
/// parse or holds invalid values gives the defaults and a [`FileProblem`]. Never writes.
pub fn load_config(config_dir: &Path) -> ConfigLoad {
    let path = config_path(config_dir);
    let problem = |line, column, message: String| FileProblem { path: path.clone(), line, column, message };
    let parsed = match fsio::read_optional(&path, fsio::MAX_READ_BYTES) {
        Ok(None) => Ok(Config::default()),
        Ok(Some(text)) => store::parse_toml::<Config>(&path, &text)
            .and_then(|c| c.validate().map(|()| c).map_err(|e| problem(None, None, e.to_string()))),
        Err(e) => Err(problem(None, None, e.reason())),
    };
    match parsed {
        Ok(config) => ConfigLoad { config, path, problem: None },
        Err(p) => ConfigLoad { config: Config::default(), path, problem: Some(p) },
    }
}

/// Saves `config` as `config.toml` in `config_dir`, atomically. Returns the path written.
pub fn save_config(config_dir: &Path, config: &Config) -> Result<PathBuf, StoreError> {
    config.validate()?;
    let path = config_path(config_dir);
    store::write_atomic(&path, config.to_toml()?.as_bytes())?;
    Ok(path)
}

/// [`load_config`] from the user's config directory (defaults when there is no home directory).
pub fn load_user_config() -> ConfigLoad {
    match store::Dirs::project() {
        Some(d) => load_config(&d.config_dir),
        None => ConfigLoad::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_parse() {
        let k = KeySpec::parse("ctrl-s").unwrap();
        assert!(k.ctrl && !k.alt && k.code == KeyCode::Char('s'));
        assert_eq!(KeySpec::parse("F5").unwrap().code, KeyCode::F(5));
        assert_eq!(KeySpec::parse("alt+PageDown").unwrap().code, KeyCode::Named(NamedKey::PageDown));
        assert_eq!(KeySpec::parse("-").unwrap().code, KeyCode::Char('-'));
        assert_eq!(KeySpec::parse("ctrl--").unwrap().code, KeyCode::Char('-'));
        for bad in ["", "ctrl-", "f25", "hyper-x", "enterr"] {
            assert!(KeySpec::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn thresholds_override_only_what_is_set() {
        let c = Config {
            thresholds: ThresholdDefaults { l_star_db: Some(100.0), e_star_cm_s: None },
            ..Default::default()
        };
        let t = c.thresholds(Thresholds::default());
        assert_eq!((t.spl_db, t.inclination_cm_s), (100.0, Thresholds::default().inclination_cm_s));
    }

    #[test]
    fn one_key_for_two_actions_is_invalid() {
        let mut c = Config::default();
        c.keys.insert(ActionName::new("save").unwrap(), KeyBinding::new("s").unwrap());
        c.keys.insert(ActionName::new("sweep").unwrap(), KeyBinding::new("s").unwrap());
        assert!(c.validate().is_err());
    }
}
