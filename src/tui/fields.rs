//! The editable parameters of the panel: how each one is shown (display units), stepped and
//! typed. Values live in the `Design` in SI units; conversions happen only here, at the edge.

use crate::acoustics::{PulseShape, QuadSigns, Source};
use crate::contact::MATERIALS;
use crate::damper::Solver;
use crate::design::{Design, Materials};
use crate::error::ThudError;
use crate::limits;
use crate::units::{self, sig, Kind};

/// One editable parameter of the design (a row of the parameter panel).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Knob {
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
pub enum Stepping {
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

impl Knob {
    /// All fields, in panel order.
    pub const ALL: [Knob; 19] = [
        Knob::Mass,
        Knob::Gap,
        Knob::R,
        Knob::Theta,
        Knob::V0,
        Knob::MainMass,
        Knob::K,
        Knob::C,
        Knob::C1,
        Knob::KHz,
        Knob::Materials,
        Knob::Source,
        Knob::QuadSigns,
        Knob::Pulse,
        Knob::Clamp,
        Knob::Solver,
        Knob::Duration,
        Knob::LStar,
        Knob::EStar,
    ];

    /// Short label for the panel.
    pub fn label(self) -> &'static str {
        match self {
            Knob::Mass => "mass m",
            Knob::Gap => "gap d",
            Knob::R => "r",
            Knob::Theta => "θ",
            Knob::V0 => "v0",
            Knob::MainMass => "M",
            Knob::K => "K",
            Knob::C => "C",
            Knob::C1 => "c1",
            Knob::KHz => "K_HZ",
            Knob::Materials => "materials",
            Knob::Source => "source",
            Knob::QuadSigns => "quad signs",
            Knob::Pulse => "pulse",
            Knob::Clamp => "clamp",
            Knob::Solver => "solver",
            Knob::Duration => "duration",
            Knob::LStar => "L*",
            Knob::EStar => "e*",
        }
    }

    /// The parameter's name in messages (as on the command line).
    pub fn param(self) -> &'static str {
        match self {
            Knob::Mass => "mass",
            Knob::Gap => "gap",
            Knob::R => "r",
            Knob::Theta => "theta",
            Knob::V0 => "v0",
            Knob::MainMass => "main-mass",
            Knob::K => "k",
            Knob::C => "c",
            Knob::C1 => "c1",
            Knob::KHz => "k-hz",
            Knob::Materials => "materials",
            Knob::Source => "source",
            Knob::QuadSigns => "quad-signs",
            Knob::Pulse => "pulse",
            Knob::Clamp => "no-tension",
            Knob::Solver => "solver",
            Knob::Duration => "duration",
            Knob::LStar => "L*",
            Knob::EStar => "e*",
        }
    }

    /// The unit a typed plain number is read in, and the unit the value is shown in.
    pub fn kind(self) -> Option<Kind> {
        Some(match self {
            Knob::Mass => Kind::Mass,
            Knob::Gap | Knob::R => Kind::Length,
            Knob::Theta => Kind::Angle,
            Knob::V0 => Kind::Speed,
            Knob::MainMass => Kind::Mass,
            Knob::K => Kind::Stiffness,
            Knob::C | Knob::C1 => Kind::Damping,
            Knob::KHz => Kind::HertzStiffness,
            Knob::Duration => Kind::Time,
            Knob::LStar => Kind::Level,
            Knob::EStar => Kind::Inclination,
            _ => return None,
        })
    }

    /// The field's valid range, from the one table of ranges ([`crate::limits`]).
    pub fn range(self) -> Option<limits::Range> {
        Some(match self {
            Knob::Mass => limits::MASS,
            Knob::Gap => limits::GAP,
            Knob::R => limits::R,
            Knob::Theta => limits::THETA,
            Knob::V0 => limits::V0,
            Knob::MainMass => limits::MAIN_MASS,
            Knob::K => limits::STIFFNESS,
            Knob::C => limits::DAMPING,
            Knob::C1 => limits::C1,
            Knob::KHz => limits::K_HZ,
            Knob::Duration => limits::DURATION,
            Knob::LStar => limits::L_STAR,
            Knob::EStar => limits::E_STAR,
            _ => return None,
        })
    }

    /// The unit the value is shown in, and the factor from it to the internal unit (SI;
    /// degrees; dB; cm/s): a typed plain number is read in this unit (`45` for the mass is
    /// 45 g, as shown), not in the internal one.
    pub fn display_unit(self) -> Option<(&'static str, f64)> {
        Some(match self {
            Knob::Mass => ("g", 1e-3),
            Knob::Gap => ("cm", 1e-2),
            Knob::R => ("m", 1.0),
            Knob::Theta => ("deg", 1.0),
            Knob::V0 => ("m/s", 1.0),
            Knob::MainMass => ("kg", 1.0),
            Knob::K => ("N/m", 1.0),
            Knob::C | Knob::C1 => ("N·s/m", 1.0),
            Knob::KHz => ("N/m^1.5", 1.0),
            Knob::Duration => ("s", 1.0),
            Knob::LStar => ("dB", 1.0),
            Knob::EStar => ("cm/s", 1.0),
            _ => return None,
        })
    }

    /// The valid range in the display unit: (lowest, highest). θ's is the current source's
    /// open side.
    pub fn display_range(self, d: &Design) -> Option<(f64, f64)> {
        let (_, k) = self.display_unit()?;
        if self == Knob::Theta {
            let r = limits::theta_deg(d.radiation.source);
            return Some((r.min, r.max));
        }
        let r = self.range()?;
        Some((r.min / k, r.max / k))
    }

    /// Checks this field's value in `d` against its range; the refusal names the field and
    /// gives the value and the range in the unit the field is shown in.
    /// Refuses a design whose runs in the explorer would exceed the work caps the command line
    /// uses ([`limits::design_run`] for the live design, [`limits::sweep_work`] for the chart's
    /// fine grid): the same estimate and limit, worded for the status line. This is what keeps a
    /// duration or a Newmark step typed here from running for hours or out of memory.
    fn check_work(self, d: &Design) -> Result<(), ThudError> {
        let cells = crate::tui::compute::Grids::default().fine.len();
        let over = limits::design_run(d, crate::tui::compute::HISTORY_SAMPLES)
            .into_iter()
            .chain(limits::sweep_work(d, cells))
            .find(limits::Estimate::exceeded);
        match over {
            Some(e) => {
                // The solver field is named by its step, as the command line's --dt.
                let (name, shown) = match (self, d.solver) {
                    (Knob::Solver, Solver::Newmark { dt_s }) => ("dt", format!("{} s", limits::short(dt_s))),
                    _ => (self.param(), self.display(d)),
                };
                Err(ThudError::invalid(name, format!("{shown}: {}", e.describe())))
            }
            None => Ok(()),
        }
    }

    fn check_range(self, d: &Design) -> Result<(), ThudError> {
        if let (Some(r), Some(v), Some((unit, k))) = (self.range(), self.get(d), self.display_unit()) {
            if !r.contains(v) {
                let (lo, hi) = (r.min / k, r.max / k);
                let shown = if v.is_finite() { format!("{} {unit}", limits::short(v / k)) } else { format!("{v}") };
                return Err(ThudError::invalid(
                    self.param(),
                    format!(
                        "{shown} is out of range; the {} must be {} to {} {unit} ({})",
                        r.what,
                        limits::short(lo),
                        limits::short(hi),
                        r.reason
                    ),
                ));
            }
        }
        if let Solver::Newmark { dt_s } = d.solver {
            limits::DT.check(dt_s)?;
        }
        Ok(())
    }

    /// What a change of this field invalidates.
    pub fn scope(self) -> Scope {
        match self {
            Knob::R | Knob::Theta | Knob::Source | Knob::QuadSigns | Knob::Pulse => Scope::Acoustics,
            Knob::Mass | Knob::Gap => Scope::Design,
            Knob::LStar | Knob::EStar => Scope::Thresholds,
            _ => Scope::All,
        }
    }

    /// How the field is stepped.
    pub fn step(self) -> Stepping {
        match self {
            Knob::Mass => Stepping::Add(1e-3, 1e-4),
            Knob::Gap => Stepping::Add(2e-3, 2e-4),
            Knob::R => Stepping::Add(0.05, 0.01),
            Knob::Theta => Stepping::Add(5.0, 1.0),
            Knob::V0 => Stepping::Add(0.1, 0.01),
            Knob::MainMass => Stepping::Add(0.05, 0.005),
            Knob::K | Knob::C | Knob::C1 | Knob::KHz => Stepping::Mul(0.1, 0.01),
            Knob::Duration => Stepping::Add(0.5, 0.1),
            Knob::LStar => Stepping::Add(1.0, 0.1),
            Knob::EStar => Stepping::Add(0.1, 0.01),
            _ => Stepping::Cycle,
        }
    }

    /// The numeric value in internal units (SI; degrees; dB; cm/s), if the field is numeric.
    pub fn get(self, d: &Design) -> Option<f64> {
        let p = &d.damper;
        Some(match self {
            Knob::Mass => p.impact_mass_kg,
            Knob::Gap => p.gap_m,
            Knob::R => d.observer.r_m,
            Knob::Theta => d.observer.theta_rad.to_degrees(),
            Knob::V0 => p.v0_m_s,
            Knob::MainMass => p.main_mass_kg,
            Knob::K => p.stiffness_n_m,
            Knob::C => p.damping_n_s_m,
            Knob::C1 => p.c1_n_s_m,
            Knob::KHz => d.resolved().map_or(p.k_hz, |r| r.damper.k_hz),
            Knob::Duration => p.duration_s,
            Knob::LStar => d.thresholds.spl_db,
            Knob::EStar => d.thresholds.inclination_cm_s,
            _ => return None,
        })
    }

    /// Sets the numeric value (internal units) on a copy of the design.
    fn set(self, d: &Design, v: f64) -> Design {
        let mut d = d.clone();
        let p = &mut d.damper;
        match self {
            Knob::Mass => p.impact_mass_kg = v,
            Knob::Gap => p.gap_m = v,
            Knob::R => d.observer.r_m = v,
            Knob::Theta => d.observer.theta_rad = v.to_radians(),
            Knob::V0 => p.v0_m_s = v,
            Knob::MainMass => p.main_mass_kg = v,
            Knob::K => p.stiffness_n_m = v,
            Knob::C => p.damping_n_s_m = v,
            Knob::C1 => p.c1_n_s_m = v,
            Knob::KHz => {
                p.k_hz = v;
                d.materials = None;
            }
            Knob::Duration => p.duration_s = v,
            Knob::LStar => d.thresholds.spl_db = v,
            Knob::EStar => d.thresholds.inclination_cm_s = v,
            _ => {}
        }
        d
    }

    /// The value as people read it: display units, a few significant digits.
    pub fn display(self, d: &Design) -> String {
        let p = &d.damper;
        match self {
            Knob::Mass => format!("{} g", sig(p.impact_mass_kg * 1e3, 4)),
            Knob::Gap => format!("{} cm", sig(p.gap_m * 1e2, 3)),
            Knob::R => format!("{} m", sig(d.observer.r_m, 3)),
            Knob::Theta => format!("{} deg", sig(d.observer.theta_rad.to_degrees(), 3)),
            Knob::V0 => format!("{} m/s", sig(p.v0_m_s, 3)),
            Knob::MainMass => format!("{} kg", sig(p.main_mass_kg, 3)),
            Knob::K => format!("{} N/m", sig(p.stiffness_n_m, 4)),
            Knob::C => format!("{} N·s/m", sig(p.damping_n_s_m, 3)),
            Knob::C1 => format!("{} N·s/m", sig(p.c1_n_s_m, 4)),
            Knob::KHz => format!("{:.3e}", self.get(d).unwrap_or(p.k_hz)),
            Knob::Materials => match &d.materials {
                None => "off (K_HZ)".into(),
                Some(m) => format!("{}/{}", m.sphere, m.plate),
            },
            Knob::Source => d.radiation.source.name().into(),
            Knob::QuadSigns => d.radiation.quad_signs.name().into(),
            Knob::Pulse => d.radiation.pulse.name().into(),
            Knob::Clamp => if p.no_tension { "no tension" } else { "off" }.into(),
            Knob::Solver => match d.solver {
                Solver::Event => "event".into(),
                Solver::Newmark { dt_s } => format!("newmark {}µs", sig(dt_s * 1e6, 2)),
            },
            Knob::Duration => format!("{} s", sig(p.duration_s, 3)),
            Knob::LStar => format!("{} dB", sig(d.thresholds.spl_db, 4)),
            Knob::EStar => format!("{} cm/s", sig(d.thresholds.inclination_cm_s, 3)),
        }
    }

    /// The design with this field stepped once (`up`: increase), validated.
    pub fn stepped(self, d: &Design, up: bool, fine: bool) -> Result<Design, ThudError> {
        let next = match (self.step(), self.get(d)) {
            (Stepping::Add(c, f), Some(v)) => {
                let s = if fine { f } else { c };
                // Snap to the step grid so repeated steps give round numbers.
                let n = (v / s).round() + if up { 1.0 } else { -1.0 };
                self.set(d, if ((v / s) - (v / s).round()).abs() < 1e-6 { n * s } else { v + if up { s } else { -s } })
            }
            (Stepping::Mul(c, f), Some(v)) => {
                let k = 1.0 + if fine { f } else { c };
                self.set(d, if up { v * k } else { v / k })
            }
            _ => self.cycled(d, up),
        };
        self.check_range(&next)?;
        self.check_work(&next)?;
        next.validate()?;
        next.resolved()?;
        Ok(next)
    }

    /// The design with a choice field moved to the next (`up`) or previous option.
    fn cycled(self, d: &Design, up: bool) -> Design {
        let mut d = d.clone();
        let turn = |i: usize, n: usize| if up { (i + 1) % n } else { (i + n - 1) % n };
        match self {
            Knob::Source => {
                let all = Source::ALL;
                let i = all.iter().position(|s| *s == d.radiation.source).unwrap_or(0);
                d.radiation.source = all[turn(i, all.len())];
                clamp_theta(&mut d);
            }
            Knob::QuadSigns => {
                d.radiation.quad_signs = match d.radiation.quad_signs {
                    QuadSigns::Paper => QuadSigns::Rigid,
                    QuadSigns::Rigid => QuadSigns::Paper,
                }
            }
            Knob::Pulse => {
                d.radiation.pulse = match d.radiation.pulse {
                    PulseShape::HalfSine => PulseShape::Hertz,
                    PulseShape::Hertz => PulseShape::HalfSine,
                }
            }
            Knob::Clamp => d.damper.no_tension = !d.damper.no_tension,
            Knob::Solver => {
                d.solver = match d.solver {
                    Solver::Event => Solver::Newmark { dt_s: TUI_NEWMARK_DT_S },
                    Solver::Newmark { .. } => Solver::Event,
                }
            }
            Knob::Materials => {
                let all = material_choices();
                let i = all.iter().position(|m| *m == d.materials).unwrap_or(0);
                d.materials.clone_from(&all[turn(i, all.len())]);
            }
            _ => {}
        }
        d
    }

    /// The design with this field set from typed text (units allowed), validated.
    pub fn parsed(self, d: &Design, text: &str) -> Result<Design, ThudError> {
        let t = text.trim();
        let next = match (self.kind(), self.display_unit()) {
            // A plain number is in the unit shown.
            (Some(_), Some((_, k))) if t.parse::<f64>().is_ok() => {
                self.set(d, t.parse::<f64>().unwrap_or(f64::NAN) * k)
            }
            (Some(kind), _) => self.set(d, units::parse(self.param(), t, kind)?),
            (None, _) => self.parse_choice(d, t)?,
        };
        self.check_range(&next)?;
        self.check_work(&next)?;
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
            Knob::Source => {
                d.radiation.source = Source::ALL
                    .into_iter()
                    .find(|s| s.name().starts_with(&low) && !low.is_empty())
                    .ok_or_else(|| bad("single, dipole or quadrupole"))?;
            }
            Knob::QuadSigns => {
                d.radiation.quad_signs = match low.as_str() {
                    "paper" => QuadSigns::Paper,
                    "rigid" => QuadSigns::Rigid,
                    _ => return Err(bad("paper or rigid")),
                }
            }
            Knob::Pulse => {
                d.radiation.pulse = match low.as_str() {
                    "half-sine" | "halfsine" | "sine" | "half sine" => PulseShape::HalfSine,
                    "hertz" | "exact" => PulseShape::Hertz,
                    _ => return Err(bad("half-sine or hertz")),
                }
            }
            Knob::Clamp => {
                d.damper.no_tension = match low.as_str() {
                    "on" | "yes" | "true" | "no tension" | "no-tension" => true,
                    "off" | "no" | "false" => false,
                    _ => return Err(bad("on or off")),
                }
            }
            Knob::Solver => {
                d.solver = match low.as_str() {
                    "event" => Solver::Event,
                    "newmark" => Solver::Newmark { dt_s: TUI_NEWMARK_DT_S },
                    _ => Solver::Newmark {
                        dt_s: units::parse("dt", t.trim_start_matches("newmark").trim(), Kind::Time)?,
                    },
                }
            }
            Knob::Materials => {
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
    let (lo, hi) = d.radiation.source.theta_range_deg();
    let deg = d.observer.theta_rad.to_degrees().clamp(lo, hi);
    d.observer.theta_rad = deg.to_radians();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mass_steps_in_grams_and_snaps() {
        let d = Design::default();
        let up = Knob::Mass.stepped(&d, true, false).unwrap();
        assert!((up.damper.impact_mass_kg - 0.0415).abs() < 1e-12, "{}", up.damper.impact_mass_kg);
        let fine = Knob::Mass.stepped(&d, true, true).unwrap();
        assert!((fine.damper.impact_mass_kg - 0.0406).abs() < 1e-12);
        assert_eq!(Knob::Mass.display(&d), "40.50 g");
    }

    #[test]
    fn typed_values_with_units_and_refusals() {
        let d = Design::default();
        assert!((Knob::Gap.parsed(&d, "3cm").unwrap().damper.gap_m - 0.03).abs() < 1e-15);
        assert!(Knob::Gap.parsed(&d, "-3cm").is_err());
        assert!(Knob::Mass.parsed(&d, "abc").is_err());
        assert!(Knob::Theta.parsed(&d, "120").is_err(), "quadrupole θ is 0–90°");
        assert_eq!(Knob::Source.parsed(&d, "dip").unwrap().radiation.source, Source::Dipole);
        let m = Knob::Materials.parsed(&d, "brass/steel").unwrap();
        assert_eq!(m.materials.as_ref().unwrap().sphere, "brass");
    }

    #[test]
    fn cycling_source_keeps_theta_valid() {
        let mut d = Design::default();
        d.radiation.source = Source::Single;
        d.observer.theta_rad = 150f64.to_radians();
        let q = Knob::Source.stepped(&d, false, false).unwrap();
        assert_eq!(q.radiation.source, Source::Quadrupole);
        assert!((q.observer.theta_rad.to_degrees() - 90.0).abs() < 1e-9);
    }

    #[test]
    fn step_below_zero_is_refused() {
        let mut d = Design::default();
        d.damper.impact_mass_kg = 0.001;
        assert!(Knob::Mass.stepped(&d, false, false).is_err());
    }
}
