//! The user's settings, `config.toml` in the config directory (on Linux
//! `$XDG_CONFIG_HOME/thud/config.toml`): theme, key overrides, default zone thresholds, the
//! marker style of plots, design defaults (`[design]`, whose keys are the rows of the
//! engine's parameter table, [`params::DESIGN`]: no key list is kept here) and whether the
//! explorer captures the mouse. Front-end support, not physics.
//!
//! A file that fails to parse is reported with its path, line and problem; the caller goes on
//! with the defaults and the file is never overwritten by loading.

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::design::{Design, Thresholds, ValidDesign};
use crate::error::ThudError;
use crate::fsio;
use crate::params::{self, Input, Spelling};
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "snake_case")]
pub enum Theme {
    /// Colours for a dark background.
    #[default]
    Default,
    /// Colours for a light background (dark text and curves, no yellow or white ink).
    Light,
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

/// The value of a design parameter in `config.toml`'s `[design]` table: what the command
/// line takes after the flag — a number in the row's plain unit, text with a unit or a name,
/// or a switch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ParamValue {
    Switch(bool),
    Number(f64),
    Text(String),
}

impl ParamValue {
    /// The value as the engine's parameter table takes it.
    fn input(&self) -> Input {
        match self {
            ParamValue::Switch(on) => Input::Switch(*on),
            ParamValue::Number(x) => Input::Num(*x),
            ParamValue::Text(t) => Input::Text(t.clone()),
        }
    }
}

/// The settings of `config.toml`. Every field may be left out.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    pub theme: Theme,
    pub markers: MarkerStyle,
    /// A table only: `thresholds = [1, 2]` is refused, not read by position.
    #[serde(deserialize_with = "table_only")]
    pub thresholds: ThresholdDefaults,
    /// Design defaults, set on the preset before the command line's flags: each key a row of
    /// the engine's parameter table [`params::DESIGN`] by its name, the long flag without
    /// dashes (`main-mass = 0.6`, `mass = "40.5g"`, `no-tension = true`), checked as the flag.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub design: BTreeMap<String, ParamValue>,
    /// Key overrides: action name → key (e.g. `save = "ctrl-s"`).
    pub keys: BTreeMap<ActionName, KeyBinding>,
    /// `mouse = false`: the explorer does not capture the mouse (left out: it does).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mouse: Option<bool>,
}

impl Config {
    /// Checks the values serde cannot: thresholds inside their ranges (the same table the
    /// command line and the explorer use, [`crate::limits`]), no key bound to two actions.
    pub fn validate(&self) -> Result<(), ThudError> {
        for (name, v) in [("l_star_db", self.thresholds.l_star_db), ("e_star_cm_s", self.thresholds.e_star_cm_s)] {
            if let (Some(x), Some(range)) = (v, threshold_range(name)) {
                range.check_as(name, x)?;
            }
        }
        for (key, value) in &self.design {
            check_design_key(key, &value.input())?;
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

    /// True unless the file says `mouse = false`.
    pub fn mouse_on(&self) -> bool {
        self.mouse.unwrap_or(true)
    }

    /// `base` with the design defaults of `[design]` set ([`params::design`]: each value
    /// checked as its flag, then the whole design); an error names the key and the file.
    pub fn design(&self, base: Design) -> Result<Design, ThudError> {
        if self.design.is_empty() {
            return Ok(base);
        }
        let given: Vec<(String, Input)> = self.design.iter().map(|(k, v)| (k.clone(), v.input())).collect();
        params::design(base, &given, Spelling::Flag).map(ValidDesign::into_design).map_err(|e| {
            let key = e.param().trim_start_matches("--").to_string();
            e.renamed(format!("{key} in {CONFIG_FILE} [design]"))
        })
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

/// Deserializes `T` from a TOML table only; serde's derived structs also accept an array read
/// by position, which would take `thresholds = [1, 2]` silently.
fn table_only<'de, D: serde::Deserializer<'de>, T: Deserialize<'de>>(d: D) -> Result<T, D::Error> {
    struct Table<T>(std::marker::PhantomData<T>);
    impl<'de, T: Deserialize<'de>> serde::de::Visitor<'de> for Table<T> {
        type Value = T;
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("a table")
        }
        fn visit_map<A: serde::de::MapAccess<'de>>(self, map: A) -> Result<T, A::Error> {
            T::deserialize(serde::de::value::MapAccessDeserializer::new(map))
        }
    }
    d.deserialize_map(Table(std::marker::PhantomData))
}

/// The top-level keys of `config.toml`.
const KEYS: [&str; 6] = ["theme", "markers", "thresholds", "design", "keys", "mouse"];

/// The range of a key of `[thresholds]` (the older spelling of `[design]`'s `l-star` and
/// `e-star`): its row's in the engine's table.
fn threshold_range(key: &str) -> Option<&'static crate::limits::Range> {
    let row = match key {
        "l_star_db" => "l-star",
        "e_star_cm_s" => "e-star",
        _ => return None,
    };
    params::design_param(row).and_then(params::Param::range)
}

/// Checks one key of `[design]` and its value against the engine's table: a row's name (or
/// alias), else "unknown" naming the nearest row; the value as that row's flag takes it.
fn check_design_key(key: &str, value: &Input) -> Result<(), ThudError> {
    let known = params::DESIGN.iter().any(|p| p.name == key || p.alias == Some(key));
    if !known {
        let near = params::nearest_design_param(key).map_or(String::new(), |n| format!("did you mean '{n}'? "));
        let all: Vec<&str> = params::DESIGN.iter().map(|p| p.name).collect();
        return Err(ThudError::invalid(
            key,
            format!("unknown design parameter; {near}(the keys of [design] are: {})", all.join(", ")),
        ));
    }
    params::check_named(&[(key.to_string(), value.clone())], Spelling::Flag).map_err(|e| e.renamed(key))
}

/// Every problem of the config `text` read from `path`, in the order they appear: TOML syntax,
/// unknown keys, values of the wrong type or shape, thresholds out of range, key bindings that
/// name no key or bind one key twice. Each has its line and column. Linear in the text.
pub fn check_text(path: &Path, text: &str) -> Vec<FileProblem> {
    check_text_with(path, text, false)
}

/// [`check_text`], and with `work` also a `[design]` whose one run is over a work cap
/// ([`work_problem`]): `thud config check` reports it at its key, while a command that loads the
/// config keeps it and refuses the run itself, naming the key (so `--no-limit` still runs it).
fn check_text_with(path: &Path, text: &str, work: bool) -> Vec<FileProblem> {
    use serde::de::IntoDeserializer;
    use toml::de::{DeTable, DeValue};
    type Value<'i> = toml::Spanned<DeValue<'i>>;
    let lines = store::Lines::new(text);
    let at = |span: std::ops::Range<usize>, message: String| {
        let (line, column) = lines.line_column(span.start);
        (span.start, FileProblem { path: path.to_path_buf(), line: Some(line), column: Some(column), message })
    };
    let (table, errors) = DeTable::parse_recoverable(text);
    let mut found: Vec<(usize, FileProblem)> =
        errors.iter().map(|e| at(e.span().unwrap_or(0..0), e.message().trim().to_string())).collect();
    let field = |value: &Value<'_>, check: &mut dyn FnMut(Value<'_>) -> Result<(), toml::de::Error>| {
        check(value.clone()).err().map(|e| at(e.span().unwrap_or(value.span()), e.message().trim().to_string()))
    };
    for (key, value) in table.get_ref() {
        let problem = match key.get_ref().as_ref() {
            "theme" => field(value, &mut |v| Theme::deserialize(v.into_deserializer()).map(drop)),
            "markers" => field(value, &mut |v| MarkerStyle::deserialize(v.into_deserializer()).map(drop)),
            "mouse" => field(value, &mut |v| bool::deserialize(v.into_deserializer()).map(drop)),
            "thresholds" => {
                let shape = field(value, &mut |v| table_only::<_, ThresholdDefaults>(v.into_deserializer()).map(drop));
                if shape.is_none() {
                    found.extend(threshold_problems(value, &at));
                }
                shape
            }
            "keys" => {
                found.extend(key_problems(value, &at));
                None
            }
            "design" => {
                let problems = design_problems(value, &at);
                if problems.is_empty() {
                    found.extend(whole_design_problem(text, value, &at, work));
                }
                found.extend(problems);
                None
            }
            other => Some(at(key.span(), format!("unknown key '{other}'; the settings are {}", KEYS.join(", ")))),
        };
        found.extend(problem);
    }
    found.sort_by_key(|(offset, _)| *offset);
    found.into_iter().map(|(_, p)| p).collect()
}

/// The most problems `thud config check` lists; the rest are counted in one last line.
pub const MAX_LISTED_PROBLEMS: usize = 100;

/// Keys of `[design]` that are no row of the engine's table (at the key) or values the row
/// refuses (at the value).
fn design_problems(
    value: &toml::Spanned<toml::de::DeValue<'_>>,
    at: &dyn Fn(std::ops::Range<usize>, String) -> (usize, FileProblem),
) -> Vec<(usize, FileProblem)> {
    use toml::de::DeValue;
    let Some(table) = value.get_ref().as_table() else {
        return vec![at(value.span(), "invalid type: expected a table of parameter = value".into())];
    };
    let mut found = Vec::new();
    for (key, v) in table {
        let name = key.get_ref().as_ref();
        let input = match v.get_ref() {
            DeValue::Boolean(on) => Some(Input::Switch(*on)),
            DeValue::String(t) => Some(Input::Text(t.to_string())),
            DeValue::Integer(_) | DeValue::Float(_) => toml_number(v.get_ref()).map(Input::Num),
            _ => None,
        };
        let Some(input) = input else {
            found.push(at(
                v.span(),
                format!("invalid {name}: expected a number, a text such as \"40.5g\" or true/false"),
            ));
            continue;
        };
        if let Err(e) = check_design_key(name, &input) {
            let span = if matches!(e, ThudError::Invalid { .. }) && e.detail().starts_with("unknown design parameter") {
                key.span()
            } else {
                v.span()
            };
            found.push(at(span, e.to_string()));
        }
    }
    found
}

/// The design every design command builds from `[design]` (the default preset with these
/// defaults, [`Config::design`]) when each key alone is fine: a value the whole design
/// refuses (`sphere = "bogus"`, a ball larger than the gap allows) is the problem the commands
/// would stop on, at the key it names (else at the table).
fn whole_design_problem(
    text: &str,
    value: &toml::Spanned<toml::de::DeValue<'_>>,
    at: &dyn Fn(std::ops::Range<usize>, String) -> (usize, FileProblem),
    work: bool,
) -> Option<(usize, FileProblem)> {
    #[derive(Deserialize)]
    struct DesignOnly {
        #[serde(default)]
        design: BTreeMap<String, ParamValue>,
    }
    let only: DesignOnly = toml::from_str(text).ok()?;
    let config = Config { design: only.design, ..Config::default() };
    let base = crate::presets::preset("default").ok()?;
    let (named, message) = match config.design(base) {
        Err(e) => (e.param().split(' ').next().unwrap_or_default().to_string(), e.to_string()),
        Ok(d) if work => work_problem(&d, &|n| config.design.contains_key(n))?,
        Ok(_) => return None,
    };
    let span = value
        .get_ref()
        .as_table()
        .and_then(|t| t.iter().find(|(k, _)| k.get_ref().as_ref() == named).map(|(_, v)| v.span()))
        .unwrap_or_else(|| value.span());
    Some(at(span, message))
}

/// The work cap one run of the design built from the config (the default preset with these
/// defaults) is over, as every command checks it before it runs ([`crate::limits::check_run`]):
/// the key to blame and the problem, or `None`.
fn work_problem(d: &Design, given: &dyn Fn(&str) -> bool) -> Option<(String, String)> {
    let valid = d.clone().check().ok()?;
    let r = crate::limits::check_run(&valid, given, 0).err()?;
    let (v, unit) = crate::limits::refused_value(d, r.param)?;
    let message = format!(
        "{} {} {unit}: {} (`thud limits`); a command would refuse it",
        r.param,
        crate::limits::short(v),
        r.estimate.describe()
    );
    Some((r.param.to_string(), message))
}

/// A TOML integer or float as a number.
fn toml_number(v: &toml::de::DeValue<'_>) -> Option<f64> {
    v.as_float()
        .and_then(|f| f.as_str().parse::<f64>().ok())
        .or_else(|| v.as_integer().and_then(|i| i.as_str().replace('_', "").parse::<f64>().ok()))
}

/// Thresholds outside their ranges (the table parsed), each at its value.
fn threshold_problems(
    value: &toml::Spanned<toml::de::DeValue<'_>>,
    at: &dyn Fn(std::ops::Range<usize>, String) -> (usize, FileProblem),
) -> Vec<(usize, FileProblem)> {
    let Some(table) = value.get_ref().as_table() else { return vec![] };
    let mut found = Vec::new();
    for name in ["l_star_db", "e_star_cm_s"] {
        let (Some(v), Some(range)) = (table.get(name), threshold_range(name)) else { continue };
        if let Some(Err(e)) = toml_number(v.get_ref()).map(|x| range.check_as(name, x)) {
            found.push(at(v.span(), e.to_string()));
        }
    }
    found
}

/// Entries of `[keys]` that are not an action name or a key, or bind a key already bound.
fn key_problems(
    value: &toml::Spanned<toml::de::DeValue<'_>>,
    at: &dyn Fn(std::ops::Range<usize>, String) -> (usize, FileProblem),
) -> Vec<(usize, FileProblem)> {
    let Some(table) = value.get_ref().as_table() else {
        return vec![at(value.span(), "invalid type: expected a table of action = \"key\"".into())];
    };
    let mut found = Vec::new();
    let mut seen: Vec<(KeySpec, String)> = Vec::new();
    // In file order, so a key bound twice is reported where it is bound the second time.
    let mut entries: Vec<_> = table.iter().collect();
    entries.sort_by_key(|(action, _)| action.span().start);
    for (action, key) in entries {
        let action_name = action.get_ref().as_ref();
        if let Err(e) = ActionName::new(action_name) {
            found.push(at(action.span(), e.to_string()));
        }
        let Some(text) = key.get_ref().as_str() else {
            found.push(at(key.span(), format!("the key of '{action_name}' must be a string like \"ctrl-s\"")));
            continue;
        };
        match KeySpec::parse(text) {
            Err(e) => found.push(at(key.span(), e.to_string())),
            Ok(spec) => match seen.iter().find(|(k, _)| *k == spec) {
                Some((_, other)) => found
                    .push(at(key.span(), format!("'{}' is bound to both '{other}' and '{action_name}'", text.trim()))),
                None => seen.push((spec, action_name.to_string())),
            },
        }
    }
    found
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
        Ok(Some(text)) => match check_text(&path, &text).into_iter().next() {
            // The first problem; `thud config check` lists them all.
            Some(first) => Err(first),
            None => store::parse_toml::<Config>(&path, &text)
                .and_then(|c| c.validate().map(|()| c).map_err(|e| problem(None, None, e.to_string()))),
        },
        Err(e) => Err(problem(None, None, e.reason())),
    };
    match parsed {
        Ok(config) => ConfigLoad { config, path, problem: None },
        Err(p) => ConfigLoad { config: Config::default(), path, problem: Some(p) },
    }
}

/// What `thud config check` found: where it looked, whether a file is there, every problem.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ConfigCheck {
    pub path: PathBuf,
    pub exists: bool,
    pub problems: Vec<FileProblem>,
}

/// Checks `config.toml` in `config_dir` ([`check_text`]); a file that cannot be read is one
/// problem. Never writes.
pub fn check_config(config_dir: &Path) -> ConfigCheck {
    let path = config_path(config_dir);
    match fsio::read_optional(&path, fsio::MAX_READ_BYTES) {
        Ok(None) => ConfigCheck { path, exists: false, problems: vec![] },
        Ok(Some(text)) => ConfigCheck { problems: check_text_with(&path, &text, true), path, exists: true },
        Err(e) => {
            let problem = FileProblem { path: path.clone(), line: None, column: None, message: e.reason() };
            ConfigCheck { path, exists: true, problems: vec![problem] }
        }
    }
}

/// [`check_config`] in the user's config directory (`None` without a home directory).
pub fn check_user_config() -> Option<ConfigCheck> {
    store::Dirs::project().map(|d| check_config(&d.config_dir))
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
    fn the_mouse_is_on_unless_the_file_says_mouse_false() {
        assert!(Config::default().mouse_on(), "no file, or no key: on");
        assert!(toml::from_str::<Config>("theme = \"mono\"").unwrap().mouse_on());
        assert!(!toml::from_str::<Config>("mouse = false").unwrap().mouse_on());
        assert!(toml::from_str::<Config>("mouse = true").unwrap().mouse_on());
        let problems = check_text(Path::new("c.toml"), "mouse = \"off\"\n");
        assert_eq!(problems.len(), 1, "a non-boolean is reported: {problems:?}");
        assert_eq!((problems[0].line, problems[0].column), (Some(1), Some(9)));
        assert!(check_text(Path::new("c.toml"), "mouse = false\n").is_empty());
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
    fn every_problem_is_listed_with_its_line_and_column() {
        let text = "theme = \"purple\"\nthresholds = [1, 2]\ncolour = 3\n[keys]\nsave = \"ctrl-\"\nsweep = \"s\"\nquit = \"s\"\n";
        let problems = check_text(Path::new("c.toml"), text);
        let at: Vec<String> = problems.iter().map(|p| format!("{}:{}", p.line.unwrap(), p.column.unwrap())).collect();
        assert_eq!(at, ["1:9", "2:14", "3:1", "5:8", "7:8"], "{problems:#?}");
        let text = problems.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n");
        assert!(text.contains("c.toml:2:14: invalid type: sequence, expected a table"), "{text}");
        assert!(text.contains("unknown key 'colour'") && text.contains("bound to both"), "{text}");
    }

    #[test]
    fn thresholds_as_an_array_are_refused_not_read_by_position() {
        assert!(toml::from_str::<Config>("thresholds = [100, 1]").is_err());
        let problems = check_text(Path::new("c.toml"), "[thresholds]\nl_star_db = 1e308\ne_star_cm_s = 1\n");
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert_eq!((problems[0].line, problems[0].column), (Some(2), Some(13)));
        assert!(check_text(Path::new("c.toml"), "theme = \"mono\"\n[thresholds]\nl_star_db = 100\n").is_empty());
    }

    #[test]
    fn one_key_for_two_actions_is_invalid() {
        let mut c = Config::default();
        c.keys.insert(ActionName::new("save").unwrap(), KeyBinding::new("s").unwrap());
        c.keys.insert(ActionName::new("sweep").unwrap(), KeyBinding::new("s").unwrap());
        assert!(c.validate().is_err());
    }
}
