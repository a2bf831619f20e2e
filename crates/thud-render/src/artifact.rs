//! One call from a design to a file's bytes: an [`Artifact`] kind, a design and
//! [`ExportOptions`] in; the CSV, SVG, PDF or WAV contents out ([`render`], [`render_pdf`]). What
//! `thud export` and the explorer write, and what the Python module's `to_svg`, `to_pdf` and
//! `to_wav` write: the same bytes for the same design.

use thiserror::Error;

use crate::{csv, figures, pdf, svg, wav};
use thud_core::acoustics::{self, Levels};
use thud_core::contact::{Impact, Target};
use thud_core::design::{self, linspace, Design, Evaluation, ValidDesign};
use thud_core::error::ThudError;

/// Why the bytes of an export were not made.
#[derive(Debug, Error)]
pub enum RenderError {
    /// The design or an option is not valid.
    #[error(transparent)]
    Invalid(#[from] ThudError),
    /// The table could not be written as CSV.
    #[error("cannot write the CSV: {0}")]
    Csv(#[from] ::csv::Error),
    /// The sound could not be encoded (a non-finite pressure: a bug).
    #[error("cannot write the WAV: {0}")]
    Wav(wav::WavError),
    /// The figure could not be converted to PDF (a glyph missing from the embedded font: a bug).
    #[error(transparent)]
    Pdf(#[from] pdf::PdfError),
}

/// Every file thud can export for a design.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Artifact {
    /// CSV `t_s,p_pa`: the pressure of one impact (the loudest, or at `u0_m_s`).
    CsvWaveform,
    /// CSV `t_s,x_m,y_m,x_free_m`: the time history with and without the damper.
    CsvHistory,
    /// CSV: every impact with its speeds, duration, penetration and SPL.
    CsvImpacts,
    /// CSV: the design chart over `masses_kg` × `gaps_m`.
    CsvSweep,
    /// SVG: the pressure of one impact.
    SvgWaveform,
    /// SVG: SPL and peak level against the observer angle.
    SvgDirectivity,
    /// SVG: the main mass's displacement with and without the damper.
    SvgHistory,
    /// SVG: restitution against impact mass (Fig 13).
    SvgRestitution,
    /// SVG: the mass × gap chart coloured by zone.
    SvgChart,
    /// SVG: e against SPLmax with the zones (Fig 17).
    SvgFig17,
    /// WAV: the damper's sound at the observer over the whole run.
    Wav,
    /// CSV: the frequency response of a forced design (`thud response --csv`).
    CsvResponse,
    /// SVG: the frequency response, amplitude with and without the damper, and Leq.
    SvgResponse,
}

impl Artifact {
    pub const ALL: [Artifact; 13] = [
        Artifact::CsvWaveform,
        Artifact::CsvHistory,
        Artifact::CsvImpacts,
        Artifact::CsvSweep,
        Artifact::SvgWaveform,
        Artifact::SvgDirectivity,
        Artifact::SvgHistory,
        Artifact::SvgRestitution,
        Artifact::SvgChart,
        Artifact::SvgFig17,
        Artifact::Wav,
        Artifact::CsvResponse,
        Artifact::SvgResponse,
    ];

    /// A file name to suggest, e.g. `thud-waveform.csv`.
    pub fn default_file_name(self) -> &'static str {
        match self {
            Artifact::CsvWaveform => "thud-waveform.csv",
            Artifact::CsvHistory => "thud-history.csv",
            Artifact::CsvImpacts => "thud-impacts.csv",
            Artifact::CsvSweep => "thud-sweep.csv",
            Artifact::SvgWaveform => "thud-waveform.svg",
            Artifact::SvgDirectivity => "thud-directivity.svg",
            Artifact::SvgHistory => "thud-history.svg",
            Artifact::SvgRestitution => "thud-restitution.svg",
            Artifact::SvgChart => "thud-chart.svg",
            Artifact::SvgFig17 => "thud-fig17.svg",
            Artifact::Wav => "thud-sound.wav",
            Artifact::CsvResponse => "thud-response.csv",
            Artifact::SvgResponse => "thud-response.svg",
        }
    }

    /// Whether this export needs the mass × gap grid (a sweep).
    pub fn needs_sweep(self) -> bool {
        matches!(self, Artifact::CsvSweep | Artifact::SvgChart | Artifact::SvgFig17)
    }

    /// Whether this export is an SVG figure (which [`render_pdf`] also makes as a PDF).
    pub fn is_figure(self) -> bool {
        matches!(
            self,
            Artifact::SvgWaveform
                | Artifact::SvgDirectivity
                | Artifact::SvgHistory
                | Artifact::SvgRestitution
                | Artifact::SvgChart
                | Artifact::SvgFig17
                | Artifact::SvgResponse
        )
    }

    /// Whether this export is a frequency response (a forced design over `freqs_hz`).
    pub fn is_response(self) -> bool {
        matches!(self, Artifact::CsvResponse | Artifact::SvgResponse)
    }
}

/// What to export besides the design. `Default` is what the CLI uses without flags.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportOptions {
    /// Impact speed (m/s) for the waveform, directivity and restitution; None: the design's
    /// largest impact speed (restitution: 1.4 m/s, Fig 13's).
    pub u0_m_s: Option<f64>,
    /// Impact masses (kg) of sweeps and of the restitution curve; None: 30–100 g (sweeps,
    /// 20 values) or 5–100 g (restitution, 20 values).
    pub masses_kg: Option<Vec<f64>>,
    /// Gaps (m) of sweeps; None: 2–5 cm, 20 values.
    pub gaps_m: Option<Vec<f64>>,
    /// Points of a waveform or history.
    pub points: usize,
    /// Sample rate and scale of WAV files.
    pub wav: wav::WavOptions,
    /// Forcing frequencies (Hz) of a response; None: the engine's default band of the design,
    /// 0.6–1.6 × its natural frequency in [`thud_core::response::DEFAULT_POINTS`] values.
    pub freqs_hz: Option<Vec<f64>>,
    /// A response from each frequency's predecessor, up then down (else each from rest).
    pub continuation: bool,
    /// Runs a cell of a sweep CSV: 1 the single trajectory; N > 1 the ensemble chart of N runs
    /// from spread ball offsets (the columns of `thud sweep --ensemble N --csv`).
    pub ensemble_runs: usize,
    /// Size and title of SVG figures.
    pub look: svg::Look,
}

impl Default for ExportOptions {
    fn default() -> Self {
        Self {
            u0_m_s: None,
            masses_kg: None,
            gaps_m: None,
            points: 2001,
            wav: wav::WavOptions::default(),
            freqs_hz: None,
            continuation: false,
            ensemble_runs: 1,
            look: svg::Look::default(),
        }
    }
}

/// The forcing frequencies of a response export of `design`: as given, else the engine's
/// default band of the design ([`thud_core::response::default_freqs_hz`]).
pub fn response_freqs(opts: &ExportOptions, design: &Design) -> Vec<f64> {
    opts.freqs_hz.clone().unwrap_or_else(|| thud_core::response::default_freqs_hz(design))
}

/// Runs `design` (with `points` history samples).
fn run(design: &ValidDesign, points: usize) -> Result<Evaluation, ThudError> {
    design::evaluate(design, points, None)
}

/// The impact speed to draw: `u0` if given, else the largest impact speed of the run.
fn impact_speed(design: &ValidDesign, u0: Option<f64>) -> Result<f64, ThudError> {
    if let Some(u) = u0 {
        thud_core::error::check_positive("u0", u, "m/s")?;
        return Ok(u);
    }
    let e = run(design, 0)?;
    let u = e.run.impacts.iter().map(|i| i.u_in_m_s).fold(0.0, f64::max);
    if u > 0.0 {
        Ok(u)
    } else {
        Err(ThudError::NoImpact)
    }
}

/// SPL and peak level of one impact of `design` at `u0` (m/s) for observer angles over the
/// open side of its reflecting surfaces (5° steps), at the design's distance.
pub fn directivity_points(design: &ValidDesign, u0: f64) -> Result<Vec<(f64, Levels)>, ThudError> {
    let d = design.clone();
    let (lo, hi) = d.radiation.source.theta_range_deg();
    let thetas: Vec<f64> = ((lo / 5.0) as i32..=(hi / 5.0) as i32).map(|k| (5.0 * f64::from(k)).to_radians()).collect();
    let impact = Impact {
        mass_kg: d.damper.impact_mass_kg,
        u0_m_s: u0,
        k_hz: d.damper.k_hz,
        target: Target::MovableMass(d.damper.main_mass_kg),
    };
    impact.validate()?;
    acoustics::directivity(d.ball_radius_m(), &impact.contact(), d.observer.r_m, &thetas, &d.radiation)
}

/// The sweep grid of `opts` (defaults as documented on [`ExportOptions`]).
fn grid(opts: &ExportOptions) -> (Vec<f64>, Vec<f64>) {
    (
        opts.masses_kg.clone().unwrap_or_else(|| linspace(0.030, 0.100, 20)),
        opts.gaps_m.clone().unwrap_or_else(|| linspace(0.02, 0.05, 20)),
    )
}

/// Where the sound is heard, for titles: "r 0.7 m, θ 45°, quadrupole".
fn listener(d: &Design) -> String {
    format!(
        "r {} m, θ {}°, {}",
        thud_core::units::short(d.observer.r_m),
        thud_core::units::short(d.observer.theta_rad.to_degrees()),
        d.radiation.source.name()
    )
}

/// The contents of an export of `kind` for `design`.
// Over 80 lines: one match arm per export kind, each a few lines.
pub fn render(kind: Artifact, design: &ValidDesign, opts: &ExportOptions) -> Result<Vec<u8>, RenderError> {
    let d = design.clone();
    let points = opts.points.clamp(2, 1_000_000);
    let text = match kind {
        Artifact::CsvWaveform | Artifact::SvgWaveform => {
            let u0 = impact_speed(&d, opts.u0_m_s)?;
            let field = d.impact_field(u0)?;
            if kind == Artifact::CsvWaveform {
                csv::waveform(&field, points)?
            } else {
                let title =
                    format!("Sound pressure of one impact, U0 {} m/s ({})", thud_core::units::short(u0), listener(&d));
                figures::waveform(&field, points, &title, &opts.look)
            }
        }
        Artifact::CsvHistory => csv::history(&run(&d, points)?.run, &d.damper)?,
        Artifact::SvgHistory => {
            // A forced run is not a free decay: its title names the force.
            let motion = if d.damper.forced() {
                format!(
                    "Forced vibration under F0 {} N at {} Hz",
                    thud_core::units::short(d.damper.force_n),
                    thud_core::units::short(d.damper.freq_hz)
                )
            } else {
                "Free vibration".to_string()
            };
            let title = format!(
                "{motion} with and without the damper (m {} g, d {} cm, v0 {} m/s)",
                thud_core::units::short(d.damper.impact_mass_kg * 1e3),
                thud_core::units::short(d.damper.gap_m * 1e2),
                thud_core::units::short(d.damper.v0_m_s)
            );
            figures::history(&run(&d, points)?.run, &d.damper, &title, &opts.look)
        }
        Artifact::CsvImpacts => {
            let e = run(&d, 0)?;
            csv::impacts(&e.run, &design::impact_spls(&e.run, &d)?)?
        }
        Artifact::SvgDirectivity => {
            let u0 = impact_speed(&d, opts.u0_m_s)?;
            let title = format!(
                "Directivity of one impact, U0 {} m/s, r {} m",
                thud_core::units::short(u0),
                thud_core::units::short(d.observer.r_m)
            );
            figures::directivity(&directivity_points(&d, u0)?, &title, &opts.look)
        }
        Artifact::SvgRestitution => {
            let masses = opts.masses_kg.clone().unwrap_or_else(|| linspace(0.005, 0.100, 20));
            let u0 = opts.u0_m_s.unwrap_or(1.4);
            let curve = design::restitution_curve(&d, &masses, u0)?;
            let title = format!(
                "Restitution against impact mass (U0 {} m/s, c1 {} N·s/m, M {} kg)",
                thud_core::units::short(u0),
                thud_core::units::short(d.damper.c1_n_s_m),
                thud_core::units::short(d.damper.main_mass_kg)
            );
            figures::restitution(&curve, &title, &opts.look)
        }
        Artifact::CsvSweep if opts.ensemble_runs > 1 => {
            let (masses, gaps) = grid(opts);
            let chart = thud_core::ensemble::sweep(&d, &masses, &gaps, opts.ensemble_runs, None, &|_, _| {})?;
            csv::sweep_ensemble(&chart)?
        }
        Artifact::CsvSweep | Artifact::SvgChart | Artifact::SvgFig17 => {
            let (masses, gaps) = grid(opts);
            let chart = design::sweep(&d, &masses, &gaps, None, &|_, _| {})?;
            match kind {
                Artifact::CsvSweep => csv::sweep(&chart)?,
                Artifact::SvgChart => {
                    figures::design_chart(&chart, "Design chart: zone of each impact mass × gap", &opts.look)
                }
                _ => figures::fig17(&chart, "Design chart: damping inclination against SPLmax (Fig 17)", &opts.look),
            }
        }
        Artifact::Wav => {
            let e = run(&d, 0)?;
            return wav::damper_sound(&d, &e.run, &opts.wav).map_err(|e| match e {
                wav::WavError::Invalid(t) => RenderError::Invalid(t),
                other @ wav::WavError::NonFinite(_) => RenderError::Wav(other),
            });
        }
        Artifact::CsvResponse | Artifact::SvgResponse => {
            let freqs = response_freqs(opts, &d);
            let ro = thud_core::response::ResponseOptions { continuation: opts.continuation, settle: true };
            let r = thud_core::response::response(&d, &freqs, &ro, None, &|| {})?;
            if kind == Artifact::CsvResponse {
                csv::response(&r)?
            } else {
                let title = format!(
                    "Frequency response under F0 {} N (m {} g, d {} cm, M {} kg)",
                    thud_core::units::short(r.force_n),
                    thud_core::units::short(d.damper.impact_mass_kg * 1e3),
                    thud_core::units::short(d.damper.gap_m * 1e2),
                    thud_core::units::short(d.damper.main_mass_kg)
                );
                figures::response(&r, &title, &opts.look)
            }
        }
    };
    Ok(text.into_bytes())
}

/// The figure `kind` (an SVG artifact, [`Artifact::is_figure`]) for `design` as a one-page PDF
/// ([`pdf::from_svg`] of [`render`]'s SVG); a kind that is no figure is refused.
pub fn render_pdf(kind: Artifact, design: &ValidDesign, opts: &ExportOptions) -> Result<Vec<u8>, RenderError> {
    if !kind.is_figure() {
        let name = kind.default_file_name();
        return Err(
            ThudError::invalid("format", format!("{name} is not a figure; only figures are made as PDF")).into()
        );
    }
    let bytes = render(kind, design, opts)?;
    Ok(pdf::from_svg(&String::from_utf8_lossy(&bytes))?)
}
