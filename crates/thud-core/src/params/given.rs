//! Named parameters as given: parsed in table order against a table's rows, unknown names
//! with the nearest (edit distance), relations between rows, and ranges `FROM:TO:N`.

use super::{Accepts, Input, Param, Spelling};
use crate::design::Model;
use crate::error::ThudError;
use crate::limits::{self, Range};
use crate::units::{self, Kind};

/// The named parameters a front end received, checked against a table: no unknown name, no
/// name twice.
pub(super) struct Given<'a, T: 'static> {
    table: &'static [Param<T>],
    /// Each parameter given, its value, and the name it was given under (its name or alias).
    values: Vec<(&'static Param<T>, &'a Input, &'static str)>,
    spelling: Spelling,
}

impl<'a, T> Given<'a, T> {
    pub(super) fn new(
        table: &'static [Param<T>],
        pairs: &'a [(String, Input)],
        spelling: Spelling,
    ) -> Result<Self, ThudError> {
        let mut values: Vec<(&'static Param<T>, &'a Input, &'static str)> = Vec::with_capacity(pairs.len());
        for (name, value) in pairs {
            let found = table.iter().find_map(|p| {
                std::iter::once(p.name).chain(p.alias).find(|n| spelling.key(n) == *name).map(|n| (p, n))
            });
            let Some((p, as_named)) = found else {
                return Err(unknown(table, name, spelling));
            };
            if values.iter().any(|(q, _, _)| q.name == p.name) {
                return Err(ThudError::invalid(spelling.spell(as_named), "is given twice"));
            }
            values.push((p, value, as_named));
        }
        // Table order, whatever the order given.
        values.sort_by_key(|(p, _, _)| table.iter().position(|q| q.name == p.name));
        Ok(Given { table, values, spelling })
    }

    pub(super) fn has(&self, name: &str) -> bool {
        self.values.iter().any(|(p, _, _)| p.name == name)
    }

    /// The parameter `name` (of the table) as the user typed it: under the alias they used,
    /// if they did.
    pub(super) fn spell(&self, name: &str) -> String {
        let typed = self.values.iter().find(|(p, _, _)| p.name == name).map_or(name, |(_, _, n)| n);
        self.spelling.spell(typed)
    }

    /// Parses every value and applies it to `draft`, in table order.
    pub(super) fn apply(&self, draft: &mut T) -> Result<(), ThudError> {
        for (p, value, _) in &self.values {
            let flag = self.spell(p.name);
            match (&p.accepts, value) {
                (Accepts::Quantity { range, set, .. }, Input::Num(v)) => set(draft, range.check_as(&flag, *v)?),
                (Accepts::Quantity { kind, range, set }, Input::Text(t)) => {
                    set(draft, range.check_as(&flag, units::parse(&flag, t, *kind)?)?);
                }
                (Accepts::Choice { names, set, .. }, Input::Text(t)) => match names.iter().position(|n| n == t) {
                    Some(i) => set(draft, i),
                    None => {
                        return Err(ThudError::invalid(
                            flag,
                            format!("unknown value '{t}'; one of: {}", names.join(", ")),
                        ))
                    }
                },
                (Accepts::Name { set }, Input::Text(t)) => set(draft, t),
                (Accepts::Switch { set }, Input::Switch(on)) => set(draft, *on),
                (Accepts::Count { range, set }, Input::Text(t)) => set(draft, range.parse_count(&flag, t)?),
                (Accepts::Count { range, set }, Input::Num(v)) => {
                    set(draft, range.parse_count(&flag, &format!("{v}"))?);
                }
                (accepts, v) => {
                    return Err(ThudError::invalid(
                        flag,
                        format!("expected {}, not {}", expected(accepts), v.describe()),
                    ))
                }
            }
        }
        Ok(())
    }

    /// An engine error that names a parameter of the table bare (`mass`) named as typed.
    pub(super) fn respell(&self, mut e: ThudError) -> ThudError {
        if self.table.iter().any(|p| p.name == e.param()) {
            let spelled = self.spell(e.param());
            e = e.renamed(spelled);
        }
        e
    }

    /// Refuses what the table's rows say cannot go together: a row given with the one it
    /// conflicts with, or without the one it needs (table order).
    pub(super) fn relations(&self) -> Result<(), ThudError> {
        for p in self.table {
            let Some(c) = p.conflicts else { continue };
            for with in c.with {
                if c.names_other {
                    self.conflict(p.name, with, c.why)?;
                } else {
                    self.conflict(with, p.name, c.why)?;
                }
            }
        }
        for p in self.table {
            if let Some(needed) = p.requires.filter(|n| self.has(p.name) && !self.has(n)) {
                return Err(ThudError::Requires { param: self.spell(p.name), needs: self.spell(needed) });
            }
        }
        Ok(())
    }

    /// Refuses two parameters given together that contradict each other.
    pub(super) fn conflict(&self, a: &str, b: &str, why: &'static str) -> Result<(), ThudError> {
        if self.has(a) && self.has(b) {
            return Err(ThudError::Conflict { param: self.spell(b), with: self.spell(a), why });
        }
        Ok(())
    }
}

/// What a parameter accepts, for a message about a value of the wrong type.
fn expected<T>(accepts: &Accepts<T>) -> String {
    match accepts {
        Accepts::Quantity { kind, .. } => match kind.plain_unit() {
            "" => "a number".to_string(),
            unit => format!("a number in {unit} or a text with a unit"),
        },
        Accepts::Choice { names, .. } => format!("one of: {}", names.join(", ")),
        Accepts::Name { .. } => "a name".to_string(),
        Accepts::Switch { .. } => "on or off (a switch)".to_string(),
        Accepts::Count { .. } => "a whole number".to_string(),
    }
}

/// "unknown parameter; did you mean …? (one of: …)".
fn unknown<T>(table: &[Param<T>], name: &str, spelling: Spelling) -> ThudError {
    let canonical = name.replace('_', "-");
    let near = table.iter().map(|p| (edit_distance(&canonical, p.name), p.name)).min_by_key(|&(d, _)| d);
    let all: Vec<String> = table.iter().map(|p| spelling.spell(p.name)).collect();
    let hint = match near {
        Some((d, n)) if d <= 2 => format!("did you mean {}? ", spelling.spell(n)),
        _ => String::new(),
    };
    let shown = match spelling {
        Spelling::Flag => spelling.spell(name),
        Spelling::Keyword => name.to_string(),
    };
    ThudError::invalid(shown, format!("unknown parameter; {hint}(one of: {})", all.join(", ")))
}

/// Levenshtein distance between two short names (for "did you mean").
pub(super) fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

/// Refuses a row given under a model it has no meaning in (its `only_in` column, [`Param`]):
/// with the physical model, what it derives itself (K_HZ from the materials, the exact Hertz
/// pulse, the air from its state); with the paper model, the air's state (its air is ρ0·c and
/// c). Table order.
pub(super) fn physical_conflicts<T>(given: &Given<T>, model: Model) -> Result<(), ThudError> {
    for p in given.table {
        let Some((only, why)) = p.only_in.filter(|(only, _)| *only != model && given.has(p.name)) else { continue };
        let with = match (only, given.has("model")) {
            (Model::Physical, true) => format!("{} paper", given.spell("model")),
            (Model::Physical, false) => {
                format!("the paper model (the default; give {} physical)", given.spell("model"))
            }
            (Model::Paper, true) => format!("{} physical", given.spell("model")),
            (Model::Paper, false) => "a physical-model design".to_string(),
        };
        return Err(ThudError::Conflict { param: given.spell(p.name), with, why });
    }
    Ok(())
}

/// "FROM:TO:N" (e.g. `30g:100g:20`) as N evenly spaced quantities of `kind` ([`crate::design::linspace`]);
/// both ends are checked against `range`, N against [`limits::GRID_N`]. `param` names the
/// parameter in errors, as typed (`--masses`).
pub fn parse_range(param: &str, text: &str, kind: Kind, range: &Range) -> Result<Vec<f64>, ThudError> {
    let parts: Vec<&str> = text.split(':').collect();
    let [from, to, n] = parts[..] else {
        let example = match kind {
            Kind::Mass => "30g:100g:20",
            Kind::Length => "2cm:5cm:20",
            Kind::Frequency => "3Hz:8Hz:101",
            _ => "1:10:10",
        };
        return Err(ThudError::invalid(param, format!("'{text}'; expected FROM:TO:N, e.g. {example}")));
    };
    let from = range.check_as(param, units::parse(param, from, kind)?)?;
    let to = range.check_as(param, units::parse(param, to, kind)?)?;
    let n = limits::GRID_N.parse_count(param, n)?;
    check_ends(param, text, from, to, n)?;
    Ok(crate::design::linspace(from, to, n))
}

/// Refuses a range FROM:TO:N whose two ends are one value while N > 1: its N values would be
/// the same, every row alike. The one rule of every FROM:TO:N ([`parse_range`],
/// [`crate::study::Vary::parse`]); `param` is the flag and `typed` what was typed.
pub fn check_ends(param: &str, typed: &str, from: f64, to: f64, n: usize) -> Result<(), ThudError> {
    if from == to && n > 1 {
        return Err(ThudError::invalid(
            param,
            format!(
                "'{typed}': FROM and TO are one value, so all its values would be the same; give two different ends"
            ),
        ));
    }
    Ok(())
}
