//! Quantities with units at the edges: parsing "40.5g", "19.05mm", "4cm", "45deg", and
//! formatting numbers for people. Inside, everything is SI (kg, m, s, Pa, rad).
//!
//! Hand-written: thud needs a dozen fixed suffixes per kind of quantity and an error that names
//! the parameter and shows an example; a units crate (dimensional analysis, unit algebra) would
//! be far larger than this table and still need the same parsing of what people type.

use crate::error::ThudError;

/// What kind of quantity a text stands for; decides the accepted unit suffixes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// kg (plain), g, mg.
    Mass,
    /// m (plain), cm, mm, um/µm.
    Length,
    /// m/s (plain), cm/s, mm/s.
    Speed,
    /// degrees (plain or deg/°), rad.
    Angle,
    /// s (plain), ms, us/µs.
    Time,
    /// N/m (plain), kN/m.
    Stiffness,
    /// N·s/m (plain; also "Ns/m").
    Damping,
    /// N/m^1.5 (plain).
    HertzStiffness,
    /// kg/m³ (plain), g/cm3.
    Density,
    /// Pa·s/m (plain; "rayl").
    Impedance,
    /// dB (plain).
    Level,
    /// cm/s (plain) — the unit of the damping inclination the paper uses.
    Inclination,
    /// N (plain), kN.
    Force,
    /// Hz (plain), kHz, rpm.
    Frequency,
    /// °C (plain; also "degC", "°C", "C"). A temperature on the Celsius scale: an offset from
    /// 273.15 K, so kelvin (a different zero) is not a suffix here.
    Temperature,
    /// Pa (plain), kPa, hPa, bar, atm.
    Pressure,
    /// m/s² (plain; "m/s2"), cm/s², mm/s², µm/s², g (standard gravity, 9.80665 m/s²).
    Acceleration,
    /// A plain number.
    Number,
}

impl Kind {
    /// (suffix, factor to the internal unit). The empty suffix is the plain-number unit.
    fn units(self) -> &'static [(&'static str, f64)] {
        match self {
            Kind::Mass => &[("", 1.0), ("kg", 1.0), ("g", 1e-3), ("mg", 1e-6)],
            Kind::Length => &[("", 1.0), ("m", 1.0), ("cm", 1e-2), ("mm", 1e-3), ("um", 1e-6), ("µm", 1e-6)],
            Kind::Speed => &[("", 1.0), ("m/s", 1.0), ("cm/s", 1e-2), ("mm/s", 1e-3), ("um/s", 1e-6), ("µm/s", 1e-6)],
            Kind::Angle => &[("", 1.0), ("deg", 1.0), ("°", 1.0), ("rad", 180.0 / std::f64::consts::PI)],
            Kind::Time => &[("", 1.0), ("s", 1.0), ("ms", 1e-3), ("us", 1e-6), ("µs", 1e-6), ("ns", 1e-9)],
            Kind::Stiffness => &[("", 1.0), ("n/m", 1.0), ("kn/m", 1e3)],
            Kind::Damping => &[("", 1.0), ("ns/m", 1.0), ("n.s/m", 1.0), ("n·s/m", 1.0), ("kg/s", 1.0)],
            Kind::HertzStiffness => &[("", 1.0), ("n/m^1.5", 1.0), ("n/m1.5", 1.0)],
            Kind::Density => &[("", 1.0), ("kg/m3", 1.0), ("kg/m^3", 1.0), ("g/cm3", 1e3), ("g/cm^3", 1e3)],
            Kind::Impedance => &[("", 1.0), ("rayl", 1.0), ("pa.s/m", 1.0), ("pas/m", 1.0)],
            Kind::Level => &[("", 1.0), ("db", 1.0)],
            Kind::Inclination => &[("", 1.0), ("cm/s", 1.0), ("mm/s", 0.1), ("m/s", 100.0)],
            Kind::Force => &[("", 1.0), ("n", 1.0), ("kn", 1e3)],
            Kind::Frequency => &[("", 1.0), ("hz", 1.0), ("khz", 1e3), ("rpm", 1.0 / 60.0)],
            Kind::Temperature => &[("", 1.0), ("degc", 1.0), ("°c", 1.0), ("c", 1.0)],
            Kind::Pressure => &[("", 1.0), ("pa", 1.0), ("hpa", 1e2), ("kpa", 1e3), ("bar", 1e5), ("atm", 101_325.0)],
            Kind::Acceleration => &[
                ("", 1.0),
                ("m/s^2", 1.0),
                ("m/s2", 1.0),
                ("cm/s^2", 1e-2),
                ("cm/s2", 1e-2),
                ("mm/s^2", 1e-3),
                ("mm/s2", 1e-3),
                ("um/s^2", 1e-6),
                ("um/s2", 1e-6),
                ("µm/s^2", 1e-6),
                ("µm/s2", 1e-6),
                ("g", STANDARD_GRAVITY),
            ],
            Kind::Number => &[("", 1.0)],
        }
    }

    /// The unit a plain number is read in, for messages.
    pub fn plain_unit(self) -> &'static str {
        match self {
            Kind::Mass => "kg",
            Kind::Length => "m",
            Kind::Speed => "m/s",
            Kind::Angle => "deg",
            Kind::Time => "s",
            Kind::Stiffness => "N/m",
            Kind::Damping => "N·s/m",
            Kind::HertzStiffness => "N/m^1.5",
            Kind::Density => "kg/m^3",
            Kind::Impedance => "Pa·s/m",
            Kind::Level => "dB",
            Kind::Inclination => "cm/s",
            Kind::Force => "N",
            Kind::Frequency => "Hz",
            Kind::Temperature => "degC",
            Kind::Pressure => "Pa",
            Kind::Acceleration => "m/s^2",
            Kind::Number => "",
        }
    }
}

/// Standard gravity g (m/s²), the unit `g` of an acceleration.
pub const STANDARD_GRAVITY: f64 = 9.806_65;

/// The factor from `unit` (a unit name of `kind`, any case; "" is the plain number's unit) to
/// the internal unit, if `unit` is one. The one table every unit thud reads goes through: the
/// values people type ([`parse`]) and the units in a data file's column names.
#[must_use]
pub fn unit_factor(kind: Kind, unit: &str) -> Option<f64> {
    let key = unit.trim().to_lowercase();
    kind.units().iter().find(|(u, _)| *u == key).map(|&(_, f)| f)
}

/// The unit names of `kind` (without the plain number's), for messages: "s, ms, us, µs, ns".
#[must_use]
pub fn unit_names(kind: Kind) -> String {
    let known: Vec<&str> = kind.units().iter().map(|(u, _)| *u).filter(|u| !u.is_empty()).collect();
    known.join(", ")
}

/// Parses `text` as a quantity of `kind` into the internal unit (SI; degrees for angles;
/// cm/s for inclinations). `param` names the parameter in the error message.
pub fn parse(param: &str, text: &str, kind: Kind) -> Result<f64, ThudError> {
    let t = text.trim();
    if t.eq_ignore_ascii_case("nan") {
        return Ok(f64::NAN);
    }
    let split = t
        .char_indices()
        .find(|&(i, c)| {
            !(c.is_ascii_digit()
                || c == '.'
                || c == '+'
                || c == '-'
                || ((c == 'e' || c == 'E') && looks_like_exponent(t, i)))
        })
        .map_or(t.len(), |(i, _)| i);
    let (num, unit) = t.split_at(split);
    let value: f64 = match num.parse() {
        Ok(v) => v,
        Err(_) => {
            return Err(ThudError::NotANumber { param: param.into(), text: text.into(), example: example(kind) });
        }
    };
    let factor = unit_factor(kind, unit).ok_or_else(|| ThudError::UnknownUnit {
        param: param.into(),
        unit: unit.trim().into(),
        text: text.into(),
        known: unit_names(kind),
        plain_unit: kind.plain_unit(),
    })?;
    overflow_checked(param, text, value * factor)
}

/// Splits a value typed with its uncertainty, `0.5kg±2%` or `0.5kg+-10g`, into the value's
/// text and the uncertainty's (`None` without `±` or `+-`).
#[must_use]
pub fn split_uncertainty(text: &str) -> (&str, Option<&str>) {
    for mark in ["±", "+-", "+/-"] {
        if let Some((value, u)) = text.split_once(mark) {
            return (value, Some(u));
        }
    }
    (text, None)
}

/// Parses a quantity of `kind` with an optional standard uncertainty after `±` (or the ASCII
/// `+-`): `0.5kg±2%` (relative), `0.5kg±10g` or `0.5±0.01` (in a unit of the same kind, a
/// plain number in the plain unit). Returns the value (as [`parse`]) and its standard
/// uncertainty in the same internal unit (0 without `±`). An uncertainty that is not a
/// finite non-negative number of the kind is refused, naming `param` and the text.
pub fn parse_uncertain(param: &str, text: &str, kind: Kind) -> Result<(f64, f64), ThudError> {
    let (value_text, u_text) = split_uncertainty(text);
    let value = parse(param, value_text, kind)?;
    let Some(u_text) = u_text else { return Ok((value, 0.0)) };
    let u_text = u_text.trim();
    let refuse = |why: &str| {
        ThudError::invalid(
            param,
            format!("'{}': {why}; give the uncertainty as e.g. 0.5kg±2% or 0.5kg+-10g", text.trim()),
        )
    };
    let sd = if let Some(pct) = u_text.strip_suffix('%') {
        let p: f64 = pct.trim().parse().map_err(|_| refuse("the uncertainty is not a number"))?;
        p / 100.0 * value.abs()
    } else {
        parse(param, u_text, kind)
            .map_err(|_| refuse("the uncertainty is not a number with a unit of the value's kind"))?
    };
    if !sd.is_finite() || sd < 0.0 {
        return Err(refuse("the uncertainty must be a finite number, 0 or more"));
    }
    Ok((value, sd))
}

/// `value`, unless the digits the user typed overflowed to ±∞ (`1e400`, `1e308km`): then an
/// error quoting the text, not the ∞ it became (explicit `inf` is refused by the ranges).
pub fn overflow_checked(param: &str, text: &str, value: f64) -> Result<f64, ThudError> {
    let typed_infinity = text.to_ascii_lowercase().contains("inf");
    if value.is_infinite() && !typed_infinity {
        return Err(ThudError::invalid(
            param,
            format!("'{}' is beyond the largest number thud holds (about 1.8e308)", text.trim()),
        ));
    }
    Ok(value)
}

fn looks_like_exponent(t: &str, i: usize) -> bool {
    let rest = &t[i + 1..];
    let next = rest.chars().next();
    i > 0 && matches!(next, Some(c) if c.is_ascii_digit() || c == '-' || c == '+')
}

fn example(kind: Kind) -> &'static str {
    match kind {
        Kind::Mass => "0.0405 or 40.5g",
        Kind::Length => "0.04 or 4cm",
        Kind::Speed => "1.4 or 140cm/s",
        Kind::Angle => "45 or 45deg",
        Kind::Time => "2 or 250ms",
        Kind::Force => "1 or 1N",
        Kind::Frequency => "5 or 5Hz",
        Kind::Temperature => "20 or 20degC",
        Kind::Pressure => "101325 or 101.325kPa",
        Kind::Acceleration => "9.81 or 1g",
        _ => "1.5",
    }
}

/// A number for people: 4 decimals in the ordinary range, scientific outside it.
pub fn num(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if !v.is_finite() {
        format!("{v}")
    } else if (1e-3..1e6).contains(&v.abs()) {
        format!("{v:.4}")
    } else {
        format!("{v:.4e}")
    }
}

/// Formats a value with a few significant digits, without noise like 0.30000000000000004.
pub fn sig(value: f64, digits: usize) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let mag = value.abs().log10().floor() as i32;
    let decimals = (digits as i32 - 1 - mag).max(0) as usize;
    format!("{value:.decimals$}")
}

/// A number for messages, to 6 significant digits: plain in the ordinary range, scientific
/// outside it (`0.0405`, `1.33651`, `1e-14`, `1e308`, `5.03292e11`).
pub fn short(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let r: f64 = format!("{v:.5e}").parse().unwrap_or(v);
    if (1e-4..1e5).contains(&r.abs()) {
        format!("{r}")
    } else {
        format!("{r:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Digits that overflow f64 are refused quoting what was typed, not the ∞ they became.
    #[test]
    fn overflowing_digits_are_quoted_as_typed() {
        for (text, kind) in [("1e400", Kind::Mass), ("-1e400 m/s", Kind::Speed), ("1e308kN", Kind::Force)] {
            let e = parse("mass", text, kind).unwrap_err().to_string();
            assert!(e.starts_with(&format!("invalid mass: '{}' is beyond", text.trim())), "{e}");
            assert!(!e.contains("inf"), "{e}");
        }
        assert!(parse("mass", "1e308", Kind::Mass).unwrap().is_finite());
    }

    #[test]
    fn suffixes_convert_to_si() {
        assert!((parse("mass", "40.5g", Kind::Mass).unwrap() - 0.0405).abs() < 1e-15);
        assert!((parse("radius", "19.05mm", Kind::Length).unwrap() - 0.01905).abs() < 1e-15);
        assert!((parse("gap", "4cm", Kind::Length).unwrap() - 0.04).abs() < 1e-15);
        assert_eq!(parse("theta", "45deg", Kind::Angle).unwrap(), 45.0);
        assert_eq!(parse("theta", "45", Kind::Angle).unwrap(), 45.0);
        assert_eq!(parse("k-hz", "5.6e8", Kind::HertzStiffness).unwrap(), 5.6e8);
        assert!((parse("dt", "1e-7", Kind::Time).unwrap() - 1e-7).abs() < 1e-22);
        assert!((parse("v0", "-1.5e-1 m/s", Kind::Speed).unwrap() + 0.15).abs() < 1e-15);
        assert_eq!(parse("force", "2.5N", Kind::Force).unwrap(), 2.5);
        assert_eq!(parse("force", "0.1kN", Kind::Force).unwrap(), 100.0);
        assert_eq!(parse("freq", "5Hz", Kind::Frequency).unwrap(), 5.0);
        assert_eq!(parse("freq", "3000rpm", Kind::Frequency).unwrap(), 50.0);
        assert!(parse("freq", "5N", Kind::Frequency).is_err());
        assert_eq!(parse("air-temperature", "-5degC", Kind::Temperature).unwrap(), -5.0);
        assert!((parse("air-pressure", "101.325kPa", Kind::Pressure).unwrap() - 101_325.0).abs() < 1e-9);
        assert_eq!(parse("air-pressure", "1atm", Kind::Pressure).unwrap(), 101_325.0);
        assert!(parse("air-temperature", "300K", Kind::Temperature).is_err());
    }

    #[test]
    fn unknown_units_and_garbage_are_errors() {
        let e = parse("mass", "40.5furlongs", Kind::Mass).unwrap_err();
        assert!(e.to_string().contains("unknown unit"), "{e}");
        assert_eq!(e.param(), "mass");
        assert_eq!(
            parse("mass", "abc", Kind::Mass).unwrap_err().to_string(),
            "invalid mass: 'abc' is not a number (expected e.g. 0.0405 or 40.5g)"
        );
        assert!(parse("mass", "", Kind::Mass).is_err());
        assert!(parse("mass", "NaN", Kind::Mass).unwrap().is_nan());
    }

    /// One table for typed values and the units in data files' column names: a unit name is
    /// found in any case; a number is not a unit.
    #[test]
    fn unit_names_are_looked_up_in_one_table() {
        assert_eq!(unit_factor(Kind::Time, "ms"), Some(1e-3));
        assert_eq!(unit_factor(Kind::Time, "US"), Some(1e-6));
        assert_eq!(unit_factor(Kind::Acceleration, "g"), Some(STANDARD_GRAVITY));
        assert_eq!(unit_factor(Kind::Acceleration, "mm/s2"), Some(1e-3));
        assert_eq!(unit_factor(Kind::Speed, "um/s"), Some(1e-6));
        for bad in ["0ms", "10us", "1ms", "m s"] {
            assert_eq!(unit_factor(Kind::Time, bad), None, "{bad}");
        }
        assert_eq!(parse("a", "2g", Kind::Acceleration).unwrap(), 2.0 * STANDARD_GRAVITY);
        assert!(unit_names(Kind::Time).starts_with("s, ms"));
    }

    #[test]
    fn sig_formats() {
        assert_eq!(sig(0.30000000000000004, 3), "0.300");
        assert_eq!(sig(264.28, 4), "264.3");
    }

    #[test]
    fn a_value_with_its_uncertainty_reads_by_the_same_units() {
        assert_eq!(parse_uncertain("main-mass", "0.5kg", Kind::Mass).unwrap(), (0.5, 0.0));
        let (v, u) = parse_uncertain("main-mass", "0.5kg±2%", Kind::Mass).unwrap();
        assert!((v - 0.5).abs() < 1e-15 && (u - 0.01).abs() < 1e-15, "{v} {u}");
        let (v, u) = parse_uncertain("main-mass", "500g+-10g", Kind::Mass).unwrap();
        assert!((v - 0.5).abs() < 1e-15 && (u - 0.01).abs() < 1e-15, "{v} {u}");
        let (v, u) = parse_uncertain("v0", "1.4 +/- 0.05", Kind::Speed).unwrap();
        assert!((v - 1.4).abs() < 1e-15 && (u - 0.05).abs() < 1e-15, "{v} {u}");
        let (v, u) = parse_uncertain("k", "-3kN/m±1%", Kind::Stiffness).unwrap();
        assert!((v + 3000.0).abs() < 1e-9 && (u - 30.0).abs() < 1e-9, "{v} {u}");
        for bad in ["0.5kg±", "0.5kg±two%", "0.5kg±-1%", "0.5kg±2cm", "0.5kg±inf", "0.5kg±1e400"] {
            let e = parse_uncertain("main-mass", bad, Kind::Mass).unwrap_err().to_string();
            assert!(e.contains("main-mass") && e.contains(bad), "{bad}: {e}");
        }
        assert!(parse_uncertain("main-mass", "0.5kq±1%", Kind::Mass).is_err());
    }
}
