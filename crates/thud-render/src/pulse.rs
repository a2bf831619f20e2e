//! The pulse of `thud pulse` (one Hertzian impact heard at one observer) as a figure and a
//! sound: `thud export svg|pdf|wav pulse` and the Python `Pulse.to_svg/.to_pdf/.to_wav` draw
//! the same [`PulseSpec`], the impact as its record (`thud pulse --json`) states it, so both
//! write the same bytes.

use serde::de::IgnoredAny;
use serde::Deserialize;

use crate::acoustics::{Air, Field, Observer, PulseShape, QuadSigns, Radiation, Source};
use crate::contact::Contact;
use crate::error::ThudError;
use crate::svg::Look;
use crate::units::short;
use crate::{figures, wav};
use thud_core::params::PulseInput;

/// One impact as its record states it: the sphere, the contact (Eqs 5–7), the observer, the
/// radiation and the number of waveform points. Read from the record of `thud pulse --json`
/// (the Python `Pulse`'s), or made from the impact the command line resolved ([`PulseSpec::new`]).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct PulseSpec {
    /// Sphere radius a (m).
    pub radius_m: f64,
    /// Sphere mass m (kg).
    pub mass_kg: f64,
    /// Impact speed U0 (m/s).
    pub u0_m_s: f64,
    /// Observer distance r (m).
    pub r_m: f64,
    /// Observer angle θ (degrees).
    pub theta_deg: f64,
    /// The reflecting surfaces.
    pub source: Source,
    /// The quadrupole's wall-image signs.
    pub quad_signs: QuadSigns,
    /// The acceleration pulse.
    pub pulse: PulseShape,
    /// Air impedance ρ0·c (Pa·s/m).
    pub rho_c_pa_s_m: f64,
    /// Speed of sound c (m/s).
    pub c_m_s: f64,
    /// Peak approach α_max (m).
    pub alpha_max_m: f64,
    /// Peak acceleration A_max (m/s²).
    pub accel_max_m_s2: f64,
    /// Contact duration τ (s).
    pub tau_s: f64,
    /// Peak contact force (N).
    pub force_max_n: f64,
    /// The waveform's samples: only their number is read (the figure's points).
    #[serde(deserialize_with = "count")]
    pub waveform: usize,
}

/// The number of samples of a record's waveform `{"t_s": […], "p_pa": […]}`.
fn count<'de, D: serde::Deserializer<'de>>(d: D) -> Result<usize, D::Error> {
    #[derive(Deserialize)]
    struct Samples {
        t_s: Vec<IgnoredAny>,
    }
    Ok(Samples::deserialize(d)?.t_s.len())
}

impl PulseSpec {
    /// The impact `input` (as [`thud_core::params::pulse`] resolved it) drawn with `points`
    /// waveform points: the numbers its record holds, exactly. Refuses an impact without a field
    /// (an observer inside the ball) as `thud pulse` does, naming the parameter typed.
    pub fn new(input: &PulseInput, points: usize) -> Result<PulseSpec, ThudError> {
        let c = input.contact();
        input.field(&c)?;
        let r = &input.radiation;
        Ok(PulseSpec {
            radius_m: input.radius_m,
            mass_kg: input.impact.mass_kg,
            u0_m_s: input.impact.u0_m_s,
            r_m: input.observer.r_m,
            theta_deg: input.observer.theta_rad.to_degrees(),
            source: r.source,
            quad_signs: r.quad_signs,
            pulse: r.pulse,
            rho_c_pa_s_m: r.air.rho_c_pa_s_m,
            c_m_s: r.air.c_m_s,
            alpha_max_m: c.alpha_max_m,
            accel_max_m_s2: c.accel_max_m_s2,
            tau_s: c.tau_s,
            force_max_n: c.force_max_n,
            waveform: points,
        })
    }

    /// The sound field at the observer (Eqs 9–24) of this contact.
    pub fn field(&self) -> Result<Field, ThudError> {
        let contact = Contact {
            alpha_max_m: self.alpha_max_m,
            accel_max_m_s2: self.accel_max_m_s2,
            tau_s: self.tau_s,
            force_max_n: self.force_max_n,
        };
        let radiation = Radiation {
            source: self.source,
            quad_signs: self.quad_signs,
            air: Air { rho_c_pa_s_m: self.rho_c_pa_s_m, c_m_s: self.c_m_s },
            pulse: self.pulse,
        };
        Field::new(self.radius_m, &contact, &Observer::new(self.r_m, self.theta_deg), &radiation)
    }

    /// The figure's title: the sphere, its speed and where it is heard, each number as given
    /// (to 6 significant digits, no trailing zeros).
    pub fn title(&self) -> String {
        format!(
            "Sound pressure of one impact: sphere a {} mm, m {} g, U0 {} m/s (r {} m, θ {}°, {})",
            short(self.radius_m * 1e3),
            short(self.mass_kg * 1e3),
            short(self.u0_m_s),
            short(self.r_m),
            short(self.theta_deg),
            self.source.name()
        )
    }
}

/// The pulse's figure as SVG: its pressure against time after the direct arrival, at the
/// record's number of points.
pub fn svg(spec: &PulseSpec, look: &Look) -> Result<String, ThudError> {
    Ok(figures::waveform(&spec.field()?, spec.waveform, &spec.title(), look))
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
