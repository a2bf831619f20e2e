//! The editable parameters of the panel: how each one is shown (display units), stepped and
//! typed. Values live in the `Design` in SI units; conversions happen only here, at the edge.

use crate::acoustics::{PulseShape, QuadSigns, Source};
use crate::contact::MATERIALS;
use crate::damper::Solver;
use crate::design::{Design, Materials};
use crate::error::ThudError;
use crate::limits;
use crate::units::{self, sig, Kind};

/// One editable parameter of the design.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    Mass,
    Gap,
    R,
    Theta,
    V0,
    MainMass,
    K,
    C,
    C1,
    KHz,
    Materials,
    Source,
    QuadSigns,
    Pulse,
    Clamp,
    Solver,
    Duration,
    LStar,
    EStar,
}

/// What kind of change a field takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Step {
    /// Add ± coarse or ± fine (internal units).
    Add(f64, f64),
    /// Multiply or divide by (1 + coarse) or (1 + fine).
    Mul(f64, f64),
    /// Cycle through choices.
    Cycle,
}

/// Which recomputation a change of this field needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// Only the sound at the observer (and the chart's levels).
    Acoustics,
    /// This one design (mass or gap): re-simulate it, the chart stays.
    Design,
    /// Everything shared by all cells: re-simulate and re-sweep.
    All,
    /// Only the zone thresholds: no physics at all.
    Thresholds,
}

/// Newmark step used when the solver is switched to Newmark in the explorer (s). Coarser than
/// the paper's 1e-7 s so the run stays interactive; type e.g. "1e-7" to change it.
pub const TUI_NEWMARK_DT_S: f64 = 1e-6;

/// Material choices offered by the materials field (sphere on a steel main mass).
fn material_choices() -> Vec<Option<Materials>> {
    std::iter::once(None)
        .chain(MATERIALS.iter().map(|m| Some(Materials { sphere: m.name.to_string(), plate: "steel".to_string() })))
        .collect()
}

impl Field {
    /// All fields, in panel order.
    pub const ALL: [Field; 19] = [
        Field::Mass,
        Field::Gap,
        Field::R,
        Field::Theta,
        Field::V0,
        Field::MainMass,
        Field::K,
        Field::C,
        Field::C1,
        Field::KHz,
        Field::Materials,
        Field::Source,
        Field::QuadSigns,
        Field::Pulse,
        Field::Clamp,
        Field::Solver,
        Field::Duration,
        Field::LStar,
        Field::EStar,
    ];

    /// Short label for the panel.
    pub fn label(self) -> &'static str {
        match self {
            Field::Mass => "mass m",
            Field::Gap => "gap d",
            Field::R => "r",
            Field::Theta => "θ",
            Field::V0 => "v0",
            Field::MainMass => "M",
            Field::K => "K",
            Field::C => "C",
            Field::C1 => "c1",
            Field::KHz => "K_HZ",
            Field::Materials => "materials",
            Field::Source => "source",
            Field::QuadSigns => "quad signs",
            Field::Pulse => "pulse",
            Field::Clamp => "clamp",
            Field::Solver => "solver",
            Field::Duration => "duration",
            Field::LStar => "L*",
            Field::EStar => "e*",
        }
    }

    /// The parameter's name in messages (as on the command line).
    pub fn param(self) -> &'static str {
        match self {
            Field::Mass => "mass",
            Field::Gap => "gap",
            Field::R => "r",
            Field::Theta => "theta",
            Field::V0 => "v0",
            Field::MainMass => "main-mass",
            Field::K => "k",
            Field::C => "c",
            Field::C1 => "c1",
            Field::KHz => "k-hz",
            Field::Materials => "materials",
            Field::Source => "source",
            Field::QuadSigns => "quad-signs",
            Field::Pulse => "pulse",
            Field::Clamp => "no-tension",
            Field::Solver => "solver",
            Field::Duration => "duration",
            Field::LStar => "L*",
            Field::EStar => "e*",
        }
    }

    /// The unit a typed plain number is read in, and the unit the value is shown in.
    pub fn kind(self) -> Option<Kind> {
        Some(match self {
            Field::Mass => Kind::Mass,
            Field::Gap | Field::R => Kind::Length,
            Field::Theta => Kind::Angle,
            Field::V0 => Kind::Speed,
            Field::MainMass => Kind::Mass,
            Field::K => Kind::Stiffness,
            Field::C | Field::C1 => Kind::Damping,
            Field::KHz => Kind::HertzStiffness,
            Field::Duration => Kind::Time,
            Field::LStar => Kind::Level,
            Field::EStar => Kind::Inclination,
            _ => return None,
        })
    }

    /// The field's valid range, from the one table of ranges ([`crate::limits`]).
    pub fn range(self) -> Option<limits::Range> {
        Some(match self {
            Field::Mass => limits::MASS,
            Field::Gap => limits::GAP,
            Field::R => limits::R,
            Field::Theta => limits::THETA,
            Field::V0 => limits::V0,
            Field::MainMass => limits::MAIN_MASS,
            Field::K => limits::STIFFNESS,
            Field::C => limits::DAMPING,
            Field::C1 => limits::C1,
            Field::KHz => limits::K_HZ,
            Field::Duration => limits::DURATION,
            Field::LStar => limits::L_STAR,
            Field::EStar => limits::E_STAR,
            _ => return None,
        })
    }

    /// Checks this field's value in `d` against its range.
    fn check_range(self, d: &Design) -> Result<(), ThudError> {
        if let (Some(r), Some(v)) = (self.range(), self.get(d)) {
            r.check_as(self.param(), v)?;
        }
        if let Solver::Newmark { dt_s } = d.solver {
            limits::DT.check(dt_s)?;
        }
        Ok(())
    }

    /// What a change of this field invalidates.
    pub fn scope(self) -> Scope {
        match self {
            Field::R | Field::Theta | Field::Source | Field::QuadSigns | Field::Pulse => Scope::Acoustics,
            Field::Mass | Field::Gap => Scope::Design,
            Field::LStar | Field::EStar => Scope::Thresholds,
            _ => Scope::All,
        }
    }

    /// How the field is stepped.
    pub fn step(self) -> Step {
        match self {
            Field::Mass => Step::Add(1e-3, 1e-4),
            Field::Gap => Step::Add(2e-3, 2e-4),
            Field::R => Step::Add(0.05, 0.01),
            Field::Theta => Step::Add(5.0, 1.0),
            Field::V0 => Step::Add(0.1, 0.01),
            Field::MainMass => Step::Add(0.05, 0.005),
            Field::K | Field::C | Field::C1 | Field::KHz => Step::Mul(0.1, 0.01),
            Field::Duration => Step::Add(0.5, 0.1),
            Field::LStar => Step::Add(1.0, 0.1),
            Field::EStar => Step::Add(0.1, 0.01),
            _ => Step::Cycle,
        }
    }

    /// The numeric value in internal units (SI; degrees; dB; cm/s), if the field is numeric.
    pub fn get(self, d: &Design) -> Option<f64> {
        let p = &d.damper;
        Some(match self {
            Field::Mass => p.impact_mass_kg,
            Field::Gap => p.gap_m,
            Field::R => d.observer.r_m,
            Field::Theta => d.observer.theta_rad.to_degrees(),
            Field::V0 => p.v0_m_s,
            Field::MainMass => p.main_mass_kg,
            Field::K => p.stiffness_n_m,
            Field::C => p.damping_n_s_m,
            Field::C1 => p.c1_n_s_m,
            Field::KHz => d.resolved().map(|r| r.damper.k_hz).unwrap_or(p.k_hz),
            Field::Duration => p.duration_s,
            Field::LStar => d.thresholds.spl_db,
            Field::EStar => d.thresholds.inclination_cm_s,
            _ => return None,
        })
    }

    /// Sets the numeric value (internal units) on a copy of the design.
    fn set(self, d: &Design, v: f64) -> Design {
        let mut d = d.clone();
        let p = &mut d.damper;
        match self {
            Field::Mass => p.impact_mass_kg = v,
            Field::Gap => p.gap_m = v,
            Field::R => d.observer.r_m = v,
            Field::Theta => d.observer.theta_rad = v.to_radians(),
            Field::V0 => p.v0_m_s = v,
            Field::MainMass => p.main_mass_kg = v,
            Field::K => p.stiffness_n_m = v,
            Field::C => p.damping_n_s_m = v,
            Field::C1 => p.c1_n_s_m = v,
            Field::KHz => {
                p.k_hz = v;
                d.materials = None;
            }
            Field::Duration => p.duration_s = v,
            Field::LStar => d.thresholds.spl_db = v,
            Field::EStar => d.thresholds.inclination_cm_s = v,
            _ => {}
        }
        d
    }

    /// The value as people read it: display units, a few significant digits.
    pub fn display(self, d: &Design) -> String {
        let p = &d.damper;
        match self {
            Field::Mass => format!("{} g", sig(p.impact_mass_kg * 1e3, 4)),
            Field::Gap => format!("{} cm", sig(p.gap_m * 1e2, 3)),
            Field::R => format!("{} m", sig(d.observer.r_m, 3)),
            Field::Theta => format!("{} deg", sig(d.observer.theta_rad.to_degrees(), 3)),
            Field::V0 => format!("{} m/s", sig(p.v0_m_s, 3)),
            Field::MainMass => format!("{} kg", sig(p.main_mass_kg, 3)),
            Field::K => format!("{} N/m", sig(p.stiffness_n_m, 4)),
            Field::C => format!("{} N·s/m", sig(p.damping_n_s_m, 3)),
            Field::C1 => format!("{} N·s/m", sig(p.c1_n_s_m, 4)),
            Field::KHz => format!("{:.3e}", self.get(d).unwrap_or(p.k_hz)),
            Field::Materials => match &d.materials {
                None => "off (K_HZ)".into(),
                Some(m) => format!("{}/{}", m.sphere, m.plate),
            },
            Field::Source => d.radiation.source.name().into(),
            Field::QuadSigns => d.radiation.quad_signs.name().into(),
            Field::Pulse => d.radiation.pulse.name().into(),
            Field::Clamp => if p.no_tension { "no tension" } else { "off" }.into(),
            Field::Solver => match d.solver {
                Solver::Event => "event".into(),
                Solver::Newmark { dt_s } => format!("newmark {}µs", sig(dt_s * 1e6, 2)),
            },
            Field::Duration => format!("{} s", sig(p.duration_s, 3)),
            Field::LStar => format!("{} dB", sig(d.thresholds.spl_db, 4)),
            Field::EStar => format!("{} cm/s", sig(d.thresholds.inclination_cm_s, 3)),
        }
    }

    /// The design with this field stepped once (`up`: increase), validated.
    pub fn stepped(self, d: &Design, up: bool, fine: bool) -> Result<Design, ThudError> {
        let next = match (self.step(), self.get(d)) {
            (Step::Add(c, f), Some(v)) => {
                let s = if fine { f } else { c };
                // Snap to the step grid so repeated steps give round numbers.
                let n = (v / s).round() + if up { 1.0 } else { -1.0 };
                self.set(d, if ((v / s) - (v / s).round()).abs() < 1e-6 { n * s } else { v + if up { s } else { -s } })
            }
            (Step::Mul(c, f), Some(v)) => {
                let k = 1.0 + if fine { f } else { c };
                self.set(d, if up { v * k } else { v / k })
            }
            _ => self.cycled(d, up),
        };
        self.check_range(&next)?;
        next.validate()?;
        next.resolved()?;
        Ok(next)
    }

    /// The design with a choice field moved to the next (`up`) or previous option.
    fn cycled(self, d: &Design, up: bool) -> Design {
        let mut d = d.clone();
        let turn = |i: usize, n: usize| if up { (i + 1) % n } else { (i + n - 1) % n };
        match self {
            Field::Source => {
                let all = Source::ALL;
                let i = all.iter().position(|s| *s == d.radiation.source).unwrap_or(0);
                d.radiation.source = all[turn(i, all.len())];
                clamp_theta(&mut d);
            }
            Field::QuadSigns => {
                d.radiation.quad_signs = match d.radiation.quad_signs {
                    QuadSigns::Paper => QuadSigns::Rigid,
                    QuadSigns::Rigid => QuadSigns::Paper,
                }
            }
            Field::Pulse => {
                d.radiation.pulse = match d.radiation.pulse {
                    PulseShape::HalfSine => PulseShape::Hertz,
                    PulseShape::Hertz => PulseShape::HalfSine,
                }
            }
            Field::Clamp => d.damper.no_tension = !d.damper.no_tension,
            Field::Solver => {
                d.solver = match d.solver {
                    Solver::Event => Solver::Newmark { dt_s: TUI_NEWMARK_DT_S },
                    Solver::Newmark { .. } => Solver::Event,
                }
            }
            Field::Materials => {
                let all = material_choices();
                let i = all.iter().position(|m| *m == d.materials).unwrap_or(0);
                d.materials = all[turn(i, all.len())].clone();
            }
            _ => {}
        }
        d
    }

    /// The design with this field set from typed text (units allowed), validated.
    pub fn parsed(self, d: &Design, text: &str) -> Result<Design, ThudError> {
        let t = text.trim();
        let next = match self.kind() {
            Some(kind) => self.set(d, units::parse(self.param(), t, kind)?),
            None => self.parse_choice(d, t)?,
        };
        self.check_range(&next)?;
        next.validate()?;
        next.resolved()?;
        Ok(next)
    }

    /// Parses a choice field: source names, signs, on/off, event/newmark/a time step, materials.
    fn parse_choice(self, d: &Design, t: &str) -> Result<Design, ThudError> {
        let mut d = d.clone();
        let low = t.to_ascii_lowercase();
        let bad = |what: &str| ThudError::invalid(self.param(), format!("'{t}'; expected {what}"));
        match self {
            Field::Source => {
                d.radiation.source = Source::ALL
                    .into_iter()
                    .find(|s| s.name().starts_with(&low) && !low.is_empty())
                    .ok_or_else(|| bad("single, dipole or quadrupole"))?;
            }
            Field::QuadSigns => {
                d.radiation.quad_signs = match low.as_str() {
                    "paper" => QuadSigns::Paper,
                    "rigid" => QuadSigns::Rigid,
                    _ => return Err(bad("paper or rigid")),
                }
            }
            Field::Pulse => {
                d.radiation.pulse = match low.as_str() {
                    "half-sine" | "halfsine" | "sine" | "half sine" => PulseShape::HalfSine,
                    "hertz" | "exact" => PulseShape::Hertz,
                    _ => return Err(bad("half-sine or hertz")),
                }
            }
            Field::Clamp => {
                d.damper.no_tension = match low.as_str() {
                    "on" | "yes" | "true" | "no tension" | "no-tension" => true,
                    "off" | "no" | "false" => false,
                    _ => return Err(bad("on or off")),
                }
            }
            Field::Solver => {
                d.solver = match low.as_str() {
                    "event" => Solver::Event,
                    "newmark" => Solver::Newmark { dt_s: TUI_NEWMARK_DT_S },
                    _ => Solver::Newmark {
                        dt_s: units::parse("dt", t.trim_start_matches("newmark").trim(), Kind::Time)?,
                    },
                }
            }
            Field::Materials => {
                d.materials = match low.as_str() {
                    "off" | "none" | "" => None,
                    _ => {
                        let (s, p) = low.split_once('/').unwrap_or((low.as_str(), "steel"));
                        let (s, p) = (crate::contact::material(s)?, crate::contact::material(p)?);
                        Some(Materials { sphere: s.name.to_string(), plate: p.name.to_string() })
                    }
                }
            }
            _ => return Err(bad("a number")),
        }
        Ok(d)
    }
}

/// Puts θ back inside the valid range of the source type after the source changed.
fn clamp_theta(d: &mut Design) {
    let (lo, hi) = theta_range_deg(d.radiation.source);
    let deg = d.observer.theta_rad.to_degrees().clamp(lo, hi);
    d.observer.theta_rad = deg.to_radians();
}

/// The valid observer angles (deg) of a source type: the open side of its walls.
pub fn theta_range_deg(source: Source) -> (f64, f64) {
    limits::theta_range_deg(source)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mass_steps_in_grams_and_snaps() {
        let d = Design::default();
        let up = Field::Mass.stepped(&d, true, false).unwrap();
        assert!((up.damper.impact_mass_kg - 0.0415).abs() < 1e-12, "{}", up.damper.impact_mass_kg);
        let fine = Field::Mass.stepped(&d, true, true).unwrap();
        assert!((fine.damper.impact_mass_kg - 0.0406).abs() < 1e-12);
        assert_eq!(Field::Mass.display(&d), "40.50 g");
    }

    #[test]
    fn typed_values_with_units_and_refusals() {
        let d = Design::default();
        assert!((Field::Gap.parsed(&d, "3cm").unwrap().damper.gap_m - 0.03).abs() < 1e-15);
        assert!(Field::Gap.parsed(&d, "-3cm").is_err());
        assert!(Field::Mass.parsed(&d, "abc").is_err());
        assert!(Field::Theta.parsed(&d, "120").is_err(), "quadrupole θ is 0–90°");
        assert_eq!(Field::Source.parsed(&d, "dip").unwrap().radiation.source, Source::Dipole);
        let m = Field::Materials.parsed(&d, "brass/steel").unwrap();
        assert_eq!(m.materials.as_ref().unwrap().sphere, "brass");
    }

    #[test]
    fn cycling_source_keeps_theta_valid() {
        let mut d = Design::default();
        d.radiation.source = Source::Single;
        d.observer.theta_rad = 150f64.to_radians();
        let q = Field::Source.stepped(&d, false, false).unwrap();
        assert_eq!(q.radiation.source, Source::Quadrupole);
        assert!((q.observer.theta_rad.to_degrees() - 90.0).abs() < 1e-9);
    }

    #[test]
    fn step_below_zero_is_refused() {
        let mut d = Design::default();
        d.damper.impact_mass_kg = 0.001;
        assert!(Field::Mass.stepped(&d, false, false).is_err());
    }
}
