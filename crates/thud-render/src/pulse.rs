//! The pulse of `thud pulse` (one Hertzian impact heard at one observer) as a figure and a
//! sound: `thud export svg|pdf|wav pulse` and the Python `Pulse.to_svg/.to_pdf/.to_wav` draw
//! the same [`PulseSpec`], the impact as its record (`thud pulse --json`) states it, so both
//! write the same bytes.

use crate::acoustics::{Air, Field, Observer, Radiation};
use crate::contact::Contact;
use crate::error::ThudError;
use crate::svg::Look;
use crate::units::short;
use crate::{figures, wav};
use thud_core::params::PulseInput;
use thud_core::report::PulseReport;

/// One impact as its record states it: the engine's [`PulseReport`] (`thud pulse --json`,
/// the Python `Pulse`'s record), whose sphere, contact (Eqs 5–7), observer, radiation and
/// waveform's number of points are what the figure and the sound are drawn from.
#[derive(Debug, Clone, PartialEq)]
pub struct PulseSpec(PulseReport);

impl From<PulseReport> for PulseSpec {
    fn from(report: PulseReport) -> Self {
        PulseSpec(report)
    }
}

impl PulseSpec {
    /// The impact `input` (as [`thud_core::params::pulse`] resolved it) drawn with `points`
    /// waveform points: its record, exactly as `thud pulse --json` prints it. Refuses an impact
    /// without a field (an observer inside the ball) as `thud pulse` does, naming the parameter
    /// typed.
    pub fn new(input: &PulseInput, points: usize) -> Result<PulseSpec, ThudError> {
        let c = input.contact();
        let field = input.field(&c)?;
        Ok(PulseSpec(PulseReport::new(input, &c, &field, points)))
    }

    /// The record drawn.
    pub fn report(&self) -> &PulseReport {
        &self.0
    }

    /// The sound field at the observer (Eqs 9–24) of this contact.
    pub fn field(&self) -> Result<Field, ThudError> {
        let r = &self.0;
        let contact = Contact {
            alpha_max_m: r.alpha_max_m,
            accel_max_m_s2: r.accel_max_m_s2,
            tau_s: r.tau_s,
            force_max_n: r.force_max_n,
        };
        let radiation = Radiation {
            source: r.source,
            quad_signs: r.quad_signs,
            air: Air { rho_c_pa_s_m: r.rho_c_pa_s_m, c_m_s: r.c_m_s },
            pulse: r.pulse,
        };
        Field::new(r.radius_m, &contact, &Observer::new(r.r_m, r.theta_deg), &radiation)
    }

    /// The number of points the figure draws: the record's waveform's.
    pub fn points(&self) -> usize {
        self.0.waveform.t_s.len()
    }

    /// The figure's title: the sphere, its speed and where it is heard, each number as given
    /// (to 6 significant digits, no trailing zeros).
    pub fn title(&self) -> String {
        let r = &self.0;
        format!(
            "Sound pressure of one impact: sphere a {} mm, m {} g, U0 {} m/s (r {} m, θ {}°, {})",
            short(r.radius_m * 1e3),
            short(r.mass_kg * 1e3),
            short(r.u0_m_s),
            short(r.r_m),
            short(r.theta_deg),
            r.source.name()
        )
    }
}

/// The pulse's figure as SVG: its pressure against time after the direct arrival, at the
/// record's number of points.
pub fn svg(spec: &PulseSpec, look: &Look) -> Result<String, ThudError> {
    Ok(figures::waveform(&spec.field()?, spec.points(), &spec.title(), look))
}

/// The pulse's sound as WAV ([`wav::pulse_sound`]).
pub fn sound(spec: &PulseSpec, opts: &wav::WavOptions) -> Result<Vec<u8>, wav::WavError> {
    wav::pulse_sound(&spec.field()?, opts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use thud_core::params::{self, Input, Spelling};

    fn fig2() -> PulseInput {
        params::pulse(None, &[("theta".to_string(), Input::Num(30.0))], Spelling::Flag).unwrap()
    }

    #[test]
    fn the_spec_rebuilds_the_field_of_the_impact() {
        let input = fig2();
        let spec = PulseSpec::new(&input, 500).unwrap();
        let direct = input.field(&input.contact()).unwrap();
        let rebuilt = spec.field().unwrap();
        assert_eq!(rebuilt.arrival_s(), direct.arrival_s());
        for k in 0..50 {
            let t = direct.arrival_s() + f64::from(k) * 1e-5;
            assert_eq!(rebuilt.pressure(t), direct.pressure(t), "at {t} s");
        }
    }

    #[test]
    fn the_sound_lasts_the_pulse_and_its_tail_and_is_not_silent() {
        let spec = PulseSpec::new(&fig2(), 100).unwrap();
        let opts = wav::WavOptions::default();
        let b = sound(&spec, &opts).unwrap();
        let field = spec.field().unwrap();
        let n = wav::sample_count(field.end_s() + wav::PULSE_TAIL_S, opts.sample_rate);
        assert_eq!(b.len(), 44 + 2 * n);
        assert!(b[44..].chunks_exact(2).any(|c| i16::from_le_bytes([c[0], c[1]]) != 0));
    }

    #[test]
    fn the_title_names_the_sphere_speed_and_observer() {
        let t = PulseSpec::new(&fig2(), 100).unwrap().title();
        assert!(t.contains("a 19.05 mm") && t.contains("U0 1.4 m/s") && t.contains("θ 30°"), "{t}");
    }
}
