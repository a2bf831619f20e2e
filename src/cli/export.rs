//! `thud export csv|svg|pdf|wav`: a design's data, figures and sound as files.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::{Args, Subcommand, ValueEnum};

use super::design_args::{parse_range, DesignArgs, ForceAmplitude};
use super::{budget, count, quantity, CliError, Ctx};
use crate::design::{Design, ValidDesign};
use crate::error::ThudError;
use crate::export::wav::{SampleFormat, WavError, WavOptions};
use crate::export::{self, pdf, svg, Artifact, ExportError, ExportOptions, RenderError};
use crate::fsio::{self, FsError, Overwrite, Plan, Sink};
use crate::limits::{self, short};
use crate::units::Kind as Unit;

#[derive(Debug, Clone, Args)]
pub struct ExportArgs {
    #[command(subcommand)]
    what: ExportCommand,
}

#[derive(Debug, Clone, Subcommand)]
enum ExportCommand {
    /// Data as CSV: waveform (t_s,p_pa), history (t_s,x_m,y_m,x_free_m), impacts, sweep, response.
    Csv(CsvArgs),
    /// Figures as SVG: waveform, directivity, history, restitution, chart, fig17, response, fit; `svg pulse`: the pulse of `thud pulse`.
    Svg(SvgArgs),
    /// Figures as PDF, one page the figure's size (1 px = 0.75 pt), text in an embedded DejaVu Sans: the figures of `svg`.
    Pdf(SvgArgs),
    /// The damper's sound at the observer: 48 kHz mono, 16-bit PCM (--format), 1.0 = --full-scale Pa; `wav pulse`: the pulse of `thud pulse`.
    Wav(WavArgs),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum CsvWhat {
    Waveform,
    History,
    Impacts,
    Sweep,
    Response,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum SvgWhat {
    Waveform,
    Directivity,
    History,
    Restitution,
    Chart,
    Fig17,
    Response,
    /// A measurement (--data) over the model `thud fit` fits to it (--damper: the damper's).
    Fit,
}

#[derive(Debug, Clone, Args)]
struct CsvArgs {
    #[arg(value_enum)]
    what: CsvWhat,
    #[command(flatten)]
    common: Common,
}

#[derive(Debug, Clone, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
struct SvgArgs {
    #[command(subcommand)]
    pulse: Option<PulseFigure>,
    #[arg(value_enum, required = true)]
    what: Option<SvgWhat>,
    #[command(flatten)]
    style: FigureStyle,
    /// The measurement of `fit` (CSV, as `thud fit --data`); repeated with --damper.
    #[arg(long, value_name = "FILE")]
    data: Vec<std::ffi::OsString>,
    /// With `fit`: the damper's fit (its envelopes) instead of the structure's.
    #[arg(long)]
    damper: bool,
    #[command(flatten)]
    common: Common,
}

/// How a figure looks: `--size`, `--no-title`, `--ascii`, the same for every figure.
#[derive(Debug, Clone, Args)]
struct FigureStyle {
    /// Figure size WxH in px, width 480 to 4000, height 320 to 4000 [default: 860x540; response 860x760].
    #[arg(long, value_name = "WxH", allow_hyphen_values = true)]
    size: Option<String>,
    /// Leave the title off the figure (for a caption of its own); an SVG keeps it as <title>.
    #[arg(long)]
    no_title: bool,
    #[command(flatten)]
    ascii: super::AsciiArgs,
}

impl FigureStyle {
    /// The figure's size and title as asked.
    fn look(&self) -> Result<svg::Look, CliError> {
        Ok(svg::Look { size: self.size.as_deref().map(parse_size).transpose()?, title: !self.no_title })
    }
}

/// The pulse's figure, a command of its own: its flags are `thud pulse`'s.
#[derive(Debug, Clone, Subcommand)]
enum PulseFigure {
    /// The pulse of `thud pulse` (same flags): the pressure of one impact at its observer.
    Pulse(PulseFigureArgs),
}

#[derive(Debug, Clone, Args)]
struct PulseFigureArgs {
    #[command(flatten)]
    source: super::pulse::PulseSource,
    /// Points of the waveform.
    #[arg(long, value_name = "N", default_value = "2000", allow_hyphen_values = true)]
    points: String,
    #[command(flatten)]
    style: FigureStyle,
    #[command(flatten)]
    target: Target,
}

/// The pulse's sound, a command of its own: its flags are `thud pulse`'s.
#[derive(Debug, Clone, Subcommand)]
enum PulseSound {
    /// The pulse of `thud pulse` (same flags) as sound: the impact's pressure at its observer from the contact's start, then 0.1 s of silence.
    Pulse(PulseSoundArgs),
}

#[derive(Debug, Clone, Args)]
struct PulseSoundArgs {
    #[command(flatten)]
    source: super::pulse::PulseSource,
    #[command(flatten)]
    sound: SoundArgs,
    #[command(flatten)]
    target: Target,
}

/// The file an export writes.
#[derive(Debug, Clone, Args)]
struct Target {
    /// The file to write (`-`: standard output). An existing file is kept unless --force.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// Replace the --out file if it exists (atomically; never a device, FIFO or folder).
    #[arg(long)]
    force: bool,
}

/// The figure size `--size WxH` asks for (px), each side within [`svg::MIN_SIZE`] and
/// [`svg::MAX_SIZE`].
fn parse_size(text: &str) -> Result<(f64, f64), ThudError> {
    let (min, max) = (svg::MIN_SIZE, svg::MAX_SIZE);
    let range = format!("WxH in px, width {} to {}, height {} to {} (e.g. 1200x800)", min.0, max.0, min.1, max.1);
    let side = |t: &str| t.trim().parse::<u32>().ok().map(f64::from);
    let (w, h) = text
        .split_once(['x', 'X', '×'])
        .and_then(|(w, h)| Some((side(w)?, side(h)?)))
        .ok_or_else(|| ThudError::invalid("--size", format!("{text}: must be {range}")))?;
    if !(min.0..=max.0).contains(&w) || !(min.1..=max.1).contains(&h) {
        return Err(ThudError::invalid("--size", format!("{text}: must be {range}")));
    }
    Ok((w, h))
}

/// How the samples of a WAV are stored (`--format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum WavFormat {
    /// 16-bit signed PCM, clipped at full scale: every reader opens it.
    Pcm16,
    /// 24-bit signed PCM, clipped at full scale.
    Pcm24,
    /// 32-bit IEEE float, not clipped.
    Float,
}

impl From<WavFormat> for SampleFormat {
    fn from(f: WavFormat) -> Self {
        match f {
            WavFormat::Pcm16 => SampleFormat::Pcm16,
            WavFormat::Pcm24 => SampleFormat::Pcm24,
            WavFormat::Float => SampleFormat::Float,
        }
    }
}

#[derive(Debug, Clone, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
struct WavArgs {
    #[command(subcommand)]
    pulse: Option<PulseSound>,
    #[command(flatten)]
    sound: SoundArgs,
    #[command(flatten)]
    common: Common,
}

/// How a WAV's samples are scaled and stored.
#[derive(Debug, Clone, Args)]
struct SoundArgs {
    /// Pressure written as sample value 1.0 (Pa; its range: `thud limits`); each sample is the mean pressure over
    /// its interval / this, the same for every design, so files compare by ear (never normalised to the loudest sample).
    #[arg(long, value_name = "PA", default_value = "20", allow_hyphen_values = true)]
    full_scale: String,
    /// Sample format: pcm16 or pcm24 (value/full scale clipped to ±1, times 2^(b−1)−1, rounded),
    /// or float (32-bit, unclipped).
    #[arg(long, value_enum, default_value = "pcm16")]
    format: WavFormat,
}

impl SoundArgs {
    /// The WAV options these flags ask for, checked.
    fn options(&self) -> Result<WavOptions, ThudError> {
        let full_scale_pa =
            quantity("full-scale", &Some(self.full_scale.clone()), Unit::Number, &limits::FULL_SCALE)?.unwrap_or(20.0);
        let opts = WavOptions { full_scale_pa, format: self.format.into(), ..WavOptions::default() };
        opts.validate()?;
        Ok(opts)
    }
}

/// The options every export takes.
#[derive(Debug, Clone, Args)]
struct Common {
    #[command(flatten)]
    design: DesignArgs<ForceAmplitude>,
    /// Impact speed U0 of waveform/directivity/restitution (m/s) [default: the design's largest impact speed; 1.4 for restitution].
    #[arg(long, value_name = "U", allow_hyphen_values = true)]
    u0: Option<String>,
    /// Impact masses FROM:TO:N of sweep/chart/fig17 [default: 30g:100g:20] and restitution [default: 5g:100g:20].
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true)]
    masses: Option<String>,
    /// Gaps FROM:TO:N of sweep/chart/fig17 [default: 2cm:5cm:20].
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true)]
    gaps: Option<String>,
    /// Forcing frequencies FROM:TO:N of a response (Hz) [default: 0.6–1.6 × the natural frequency, 101 points]; needs --force-amplitude.
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true)]
    freqs: Option<String>,
    /// A response from each frequency's predecessor, rising then falling (else each from rest).
    #[arg(long)]
    continuation: bool,
    /// Points of a waveform or time history (at most 1000000).
    #[arg(long, value_name = "N", default_value = "2001", allow_hyphen_values = true)]
    points: String,
    /// The file to write (`-`: standard output). An existing file is kept unless --force.
    #[arg(long, value_name = "FILE", required = true)]
    out: Option<PathBuf>,
    /// Replace the --out file if it exists (atomically; never a device, FIFO or folder).
    #[arg(long)]
    force: bool,
}

/// The most points an export renders (`export::render` draws at most this many).
const EXPORT_POINTS_MAX: usize = 1_000_000;

impl Common {
    /// The `--out` file (clap asks for it unless the command is `pulse`, which has its own).
    fn out(&self) -> Result<&Path, ThudError> {
        self.out.as_deref().ok_or_else(|| ThudError::invalid("--out", "missing: give the file to write, --out FILE"))
    }

    fn options(&self) -> Result<ExportOptions, ThudError> {
        let points = count("points", &self.points, &limits::POINTS)?;
        if points > EXPORT_POINTS_MAX {
            return Err(ThudError::invalid(
                "--points",
                format!("{points}; an export draws at most {EXPORT_POINTS_MAX} points"),
            ));
        }
        Ok(ExportOptions {
            u0_m_s: quantity("u0", &self.u0, Unit::Speed, &limits::U0)?,
            masses_kg: self
                .masses
                .as_deref()
                .map(|m| parse_range("masses", m, Unit::Mass, &limits::MASS))
                .transpose()?,
            gaps_m: self.gaps.as_deref().map(|g| parse_range("gaps", g, Unit::Length, &limits::GAP)).transpose()?,
            points,
            wav: WavOptions::default(),
            look: svg::Look::default(),
            freqs_hz: self
                .freqs
                .as_deref()
                .map(|f| parse_range("freqs", f, Unit::Frequency, &limits::FREQ))
                .transpose()?,
            continuation: self.continuation,
            ensemble_runs: 1,
        })
    }

    /// Refuses an export whose work is over a cap; says whether it is expected to be long.
    fn check_work(&self, ctx: &Ctx, kind: Artifact, d: &ValidDesign, opts: &ExportOptions) -> Result<bool, CliError> {
        let points = &self.points;
        if kind.is_response() {
            let freqs = export::response_freqs(opts, d);
            let text = self.freqs.clone().unwrap_or_else(|| super::response::freqs_text(&freqs));
            super::response::check_work(ctx, d, &freqs, &text, opts.continuation)?;
            return Ok(true);
        }
        let runs = !kind.needs_sweep() && kind != Artifact::SvgRestitution;
        let history = if matches!(kind, Artifact::CsvHistory | Artifact::SvgHistory) { opts.points } else { 0 };
        if runs {
            self.design.check_run(ctx, d, history, "--points")?;
        }
        let mut long = runs && limits::design_run(d, history).iter().any(|e| e.value > 0.1 * e.cap.max);
        if kind.needs_sweep() {
            let m = opts.masses_kg.as_ref().map_or(20, Vec::len);
            let g = opts.gaps_m.as_ref().map_or(20, Vec::len);
            self.design.check_sweep(ctx, d, m, g)?;
            long |= m * g >= 2000;
        }
        if matches!(kind, Artifact::CsvWaveform | Artifact::SvgWaveform) {
            let e = limits::waveform_points(opts.points);
            ctx.enforce(e, "--points", points, &format!("use --points ≤ {}", short(e.cap.max)))?;
        }
        if kind == Artifact::SvgRestitution {
            let n = opts.masses_kg.as_ref().map_or(20, Vec::len);
            let e = limits::restitution_contacts(n, false);
            let masses = self.masses.clone().unwrap_or_default();
            ctx.enforce(e, "--masses", &masses, &format!("use at most {} masses", short(e.cap.max)))?;
        }
        if kind == Artifact::Wav {
            let e = limits::wav_samples(d.damper.duration_s, f64::from(opts.wav.sample_rate));
            let shown = self.design_duration_text(d);
            let max = e.cap.max / f64::from(opts.wav.sample_rate);
            ctx.enforce(e, "--duration", &shown, &format!("use --duration ≤ {} s for a WAV", short(max)))?;
            long |= e.value > 0.1 * e.cap.max;
        }
        Ok(long)
    }

    /// The duration as typed, or the design's.
    fn design_duration_text(&self, d: &Design) -> String {
        self.design.duration_text().unwrap_or_else(|| format!("{} s", short(d.damper.duration_s)))
    }
}

/// "No impact to hear" is about the whole design: say which flags made it.
fn no_impact(e: ThudError, common: &Common) -> ThudError {
    let typed = common.design.typed();
    if common.u0.is_some() || typed.is_empty() || !e.to_string().contains("no impact") {
        return e;
    }
    ThudError::invalid("--u0", format!("the design ({typed}) has no impact to hear; give an impact speed with --u0"))
}

/// Checks rendered text holds no non-finite number (a WAV's pressures are checked before they
/// are encoded: [`WavError::NonFinite`]).
fn check_contents(kind: Artifact, bytes: &[u8]) -> Result<(), CliError> {
    if kind == Artifact::Wav {
        return Ok(());
    }
    super::output::check_text(&String::from_utf8_lossy(bytes))
}

/// Samples of a PCM WAV at the largest code (clipped at, or exactly at, full scale); 0 for float.
fn samples_at_full_scale(bytes: &[u8], format: SampleFormat) -> usize {
    let data = bytes.get(44..).unwrap_or_default();
    match format {
        SampleFormat::Pcm16 => {
            data.chunks_exact(2).filter(|c| i16::from_le_bytes([c[0], c[1]]).abs() == i16::MAX).count()
        }
        SampleFormat::Pcm24 => data
            .chunks_exact(3)
            .filter(|c| (i32::from_le_bytes([0, c[0], c[1], c[2]]) >> 8).abs() == (1 << 23) - 1)
            .count(),
        SampleFormat::Float => 0,
    }
}

/// Renders and writes one export; says on stderr what was written. The target and the work are
/// checked before the work starts, so a refused --out or an over-cap run costs nothing, and the
/// contents are checked for non-finite numbers before anything is written.
/// With `as_pdf` the figure's SVG is checked, then converted to PDF ([`pdf::from_svg`]); a
/// figure's text is spelled in ASCII with `ascii` (`--ascii`).
fn write(
    ctx: &Ctx,
    kind: Artifact,
    common: &Common,
    opts: &ExportOptions,
    as_pdf: bool,
    ascii: super::AsciiArgs,
) -> Result<(), CliError> {
    let (design, opts) = if kind.is_response() {
        // The design first, then its frequencies: --freqs, or the engine's default band.
        let (d, freqs) = common.design.response_setup(opts.freqs_hz.clone())?;
        (d, &ExportOptions { freqs_hz: Some(freqs), ..opts.clone() })
    } else {
        (common.design.design()?, opts)
    };
    let overwrite = Overwrite::from_force(common.force);
    let out = common.out()?;
    let plan = fsio::check_target(out, overwrite).map_err(|e| out_error(out, &e))?;
    // A terminal, however it is named (`-`, /dev/stdout, /dev/tty, /dev/pts/N), never gets
    // binary bytes.
    let to_stdout = matches!(plan, Plan::Through(Sink::Stdout));
    let terminal = match plan {
        Plan::Through(Sink::Stdout) => std::io::stdout().is_terminal(),
        Plan::Through(Sink::Stream { .. }) => fsio::is_terminal(out),
        _ => false,
    };
    if terminal && (kind == Artifact::Wav || as_pdf) {
        let (what, reader) = if as_pdf { ("a PDF", "a viewer") } else { ("a WAV", "a player") };
        let why =
            format!("{}: {what} file is binary; redirect standard output to a file or {reader}", fsio::shown(out));
        return Err(ThudError::invalid("--out", why).into());
    }
    let long = common.check_work(ctx, kind, &design, opts)?;
    let spinner = budget::spinner("exporting", long);
    let bytes = export::render(kind, &design, opts);
    spinner.finish_and_clear();
    let bytes = bytes.map_err(|e| export_error(out, e, common))?;
    check_contents(kind, &bytes)?;
    let bytes =
        if ascii.ascii { ascii.figure(String::from_utf8_lossy(&bytes).into_owned()).into_bytes() } else { bytes };
    let bytes = if as_pdf {
        pdf::from_svg(&String::from_utf8_lossy(&bytes))
            .map_err(|e| CliError::Io(format!("cannot write {}: {e}", fsio::shown(out))))?
    } else {
        bytes
    };
    if kind == Artifact::Wav {
        let clipped = samples_at_full_scale(&bytes, opts.wav.format);
        if clipped > 0 {
            super::warn(&format!(
                "{clipped} samples reached full scale ({} Pa) and were clipped; raise --full-scale or use --format float",
                short(opts.wav.full_scale_pa)
            ));
        }
    }
    if to_stdout {
        return Ok(fsio::write_stdout(&bytes)?);
    }
    fsio::write(out, &bytes, overwrite).map_err(|e| write_error(out, &e))?;
    super::warn(&format!("wrote {}", fsio::shown(out)));
    Ok(())
}

/// An export failure as the CLI's one-line error (a sample that is not a number is the
/// engine's bug, not bad input).
fn export_error(out: &Path, e: ExportError, common: &Common) -> CliError {
    let r = match e {
        ExportError::File(f) => return out_error(out, &f).into(),
        ExportError::Render(r) => *r,
    };
    let cannot =
        |why: &dyn std::fmt::Display| ThudError::invalid("--out", format!("cannot write {}: {why}", fsio::shown(out)));
    match r {
        RenderError::Invalid(t) => no_impact(t, common).into(),
        RenderError::Wav(WavError::NonFinite(p)) => CliError::NonFinite(format!("{p} Pa in a WAV sample")),
        RenderError::Csv(c) => cannot(&c).into(),
        RenderError::Wav(w) => cannot(&w).into(),
        RenderError::Pdf(p) => cannot(&p).into(),
    }
}

/// A write of `out` that failed or was refused, as the CLI's error: a refusal (the file exists,
/// is a link, is not writable through, a FIFO without a reader) is bad input (exit 2), a
/// failure of the write itself is I/O (exit 1); the line is [`out_error`]'s.
pub(super) fn write_error(out: &Path, e: &FsError) -> CliError {
    write_error_as("--out", out, e)
}

/// [`write_error`] naming the flag that gave the file (`--svg`, `--pdf`, `--out`).
pub(super) fn write_error_as(flag: &str, out: &Path, e: &FsError) -> CliError {
    match e {
        FsError::Exists(_) | FsError::NotRegular { .. } | FsError::Link(_) | FsError::NoReader(_) => {
            CliError::Input(out_error(out, e).renamed(flag))
        }
        FsError::Changed(_) | FsError::TooLarge { .. } | FsError::Io { .. } => {
            CliError::Io(out_error(out, e).renamed(flag).to_string())
        }
    }
}

/// A refused or failed write of `out` as the CLI's one-line error naming `--out`: what is at
/// the path and what to do. Paths are [`fsio::shown`] (escaped, a long one cut in its middle),
/// so the reason always survives.
pub(super) fn out_error(out: &Path, e: &FsError) -> ThudError {
    let message = match e {
        FsError::Exists(p) => format!("{} exists; add --force to replace it", fsio::shown(p)),
        FsError::NotRegular { path, kind } => format!(
            "{} is {kind}; thud writes through only a terminal, a FIFO or /dev/null, and replaces only a regular file (even with --force)",
            fsio::shown(path)
        ),
        FsError::Link(p) => format!(
            "{} is a symbolic link; thud neither follows nor replaces one (even with --force): name the file itself",
            fsio::shown(p)
        ),
        FsError::NoReader(p) => format!("{} is a FIFO with no reader; start the reader first", fsio::shown(p)),
        FsError::Changed(_) | FsError::TooLarge { .. } | FsError::Io { .. } => {
            format!("cannot write {}: {}", fsio::shown(out), e.reason())
        }
    };
    ThudError::invalid("--out", message)
}

/// `export svg` or (`as_pdf`) `export pdf`: one figure, sized and titled as asked.
fn figure(ctx: &Ctx, s: &SvgArgs, as_pdf: bool) -> Result<(), CliError> {
    if let Some(PulseFigure::Pulse(p)) = &s.pulse {
        return pulse_figure(ctx, p, as_pdf);
    }
    let Some(what) = s.what else {
        return Err(ThudError::invalid("WHAT", "missing: name the figure (e.g. waveform)").into());
    };
    let kind = match what {
        SvgWhat::Waveform => Artifact::SvgWaveform,
        SvgWhat::Directivity => Artifact::SvgDirectivity,
        SvgWhat::History => Artifact::SvgHistory,
        SvgWhat::Restitution => Artifact::SvgRestitution,
        SvgWhat::Chart => Artifact::SvgChart,
        SvgWhat::Fig17 => Artifact::SvgFig17,
        SvgWhat::Response => Artifact::SvgResponse,
        SvgWhat::Fit => return fit_figure(ctx, s, as_pdf),
    };
    if !s.data.is_empty() || s.damper {
        let flag = if s.damper { "--damper" } else { "--data" };
        return Err(ThudError::invalid(flag, "is for the figure `fit` only").into());
    }
    let mut opts = s.common.options()?;
    opts.look = s.style.look()?;
    write(ctx, kind, &s.common, &opts, as_pdf, s.style.ascii)
}

/// `export svg|pdf fit`: the measurement over its fitted model, by `thud fit`'s own reading
/// and fitting; the structure's with the design's main mass, or (`--damper`) the damper's.
fn fit_figure(ctx: &Ctx, s: &SvgArgs, as_pdf: bool) -> Result<(), CliError> {
    let Some(first) = s.data.first() else {
        return Err(ThudError::invalid("--data", "the figure `fit` needs a measurement: give --data FILE").into());
    };
    let look = s.style.look()?;
    let d = s.common.design.design()?;
    let out = s.common.out()?;
    let overwrite = Overwrite::from_force(s.common.force);
    let plan = fsio::check_target(out, overwrite).map_err(|e| out_error(out, &e))?;
    let to_stdout = matches!(plan, Plan::Through(Sink::Stdout));
    let name = fsio::shown(Path::new(first));
    let svg_text = if s.damper {
        let f = super::fit::damper_fit(ctx, &s.common.design, &d, &s.data)?;
        export::fit::damper(&f, &format!("Damper fit of {name}: c1 {} N·s/m", crate::units::sig(f.c1_n_s_m, 4)), &look)
    } else {
        if s.data.len() > 1 {
            return Err(
                ThudError::invalid("--data", "the structure's figure draws one record; give --data once").into()
            );
        }
        let (series, f) = super::fit::structure_fit(ctx, Path::new(first), d.damper.main_mass_kg)?;
        let title = format!(
            "Structure fit of {name}: f_n {} Hz, ζ {}",
            crate::units::sig(f.f_n_hz, 5),
            crate::units::sig(f.zeta, 3)
        );
        export::fit::structure(&series, &f, &title, &look)
    };
    super::output::check_text(&svg_text)?;
    let svg_text = s.style.ascii.figure(svg_text);
    let bytes = if as_pdf {
        pdf::from_svg(&svg_text).map_err(|e| CliError::Io(format!("cannot write {}: {e}", fsio::shown(out))))?
    } else {
        svg_text.into_bytes()
    };
    if to_stdout {
        return Ok(fsio::write_stdout(&bytes)?);
    }
    fsio::write(out, &bytes, overwrite).map_err(|e| write_error(out, &e))?;
    super::warn(&format!("wrote {}", fsio::shown(out)));
    Ok(())
}

/// `export svg|pdf pulse`: the pulse `thud pulse` computes for the same flags, as a figure.
fn pulse_figure(ctx: &Ctx, p: &PulseFigureArgs, as_pdf: bool) -> Result<(), CliError> {
    let look = p.style.look()?;
    let points = super::pulse::points(ctx, &p.points)?;
    let input = super::pulse::resolve(&p.source)?;
    let out = &p.target.out;
    let overwrite = Overwrite::from_force(p.target.force);
    let plan = fsio::check_target(out, overwrite).map_err(|e| out_error(out, &e))?;
    refuse_binary_terminal(out, &plan, as_pdf.then_some(("a PDF", "a viewer")))?;
    let svg_text = thud_render::pulse::svg(&thud_render::pulse::PulseSpec::new(&input, points)?, &look)?;
    super::output::check_text(&svg_text)?;
    let svg_text = p.style.ascii.figure(svg_text);
    let bytes = if as_pdf {
        pdf::from_svg(&svg_text).map_err(|e| CliError::Io(format!("cannot write {}: {e}", fsio::shown(out))))?
    } else {
        svg_text.into_bytes()
    };
    deliver(out, &plan, &bytes, overwrite)
}

/// `export wav pulse`: the pulse `thud pulse` computes for the same flags, as sound.
fn pulse_sound(p: &PulseSoundArgs) -> Result<(), CliError> {
    let opts = p.sound.options()?;
    let input = super::pulse::resolve(&p.source)?;
    let out = &p.target.out;
    let overwrite = Overwrite::from_force(p.target.force);
    let plan = fsio::check_target(out, overwrite).map_err(|e| out_error(out, &e))?;
    refuse_binary_terminal(out, &plan, Some(("a WAV", "a player")))?;
    let spec = thud_render::pulse::PulseSpec::new(&input, 2)?;
    let bytes = match thud_render::pulse::sound(&spec, &opts) {
        Ok(b) => b,
        Err(WavError::NonFinite(p)) => return Err(CliError::NonFinite(format!("{p} Pa in a WAV sample"))),
        Err(WavError::Invalid(t)) => return Err(t.into()),
    };
    warn_clipped(&bytes, &opts);
    deliver(out, &plan, &bytes, overwrite)
}

/// Refuses binary bytes (`binary`: what they are and what reads them) for a terminal,
/// however it is named (`-`, /dev/stdout, /dev/tty, /dev/pts/N).
fn refuse_binary_terminal(out: &Path, plan: &Plan, binary: Option<(&str, &str)>) -> Result<(), CliError> {
    let terminal = match plan {
        Plan::Through(Sink::Stdout) => std::io::stdout().is_terminal(),
        Plan::Through(Sink::Stream { .. }) => fsio::is_terminal(out),
        _ => false,
    };
    match binary {
        Some((what, reader)) if terminal => {
            let why =
                format!("{}: {what} file is binary; redirect standard output to a file or {reader}", fsio::shown(out));
            Err(ThudError::invalid("--out", why).into())
        }
        _ => Ok(()),
    }
}

/// Warns when samples of a PCM WAV reached full scale (clipped).
fn warn_clipped(bytes: &[u8], opts: &WavOptions) {
    let clipped = samples_at_full_scale(bytes, opts.format);
    if clipped > 0 {
        super::warn(&format!(
            "{clipped} samples reached full scale ({} Pa) and were clipped; raise --full-scale or use --format float",
            short(opts.full_scale_pa)
        ));
    }
}

/// Writes `bytes` to `out` as `plan` says (standard output, or the file atomically), saying on
/// stderr what was written.
fn deliver(out: &Path, plan: &Plan, bytes: &[u8], overwrite: Overwrite) -> Result<(), CliError> {
    if matches!(plan, Plan::Through(Sink::Stdout)) {
        return Ok(fsio::write_stdout(bytes)?);
    }
    fsio::write(out, bytes, overwrite).map_err(|e| write_error(out, &e))?;
    super::warn(&format!("wrote {}", fsio::shown(out)));
    Ok(())
}

pub fn run(a: &ExportArgs, ctx: &Ctx) -> Result<(), CliError> {
    match &a.what {
        ExportCommand::Csv(c) => {
            let kind = match c.what {
                CsvWhat::Waveform => Artifact::CsvWaveform,
                CsvWhat::History => Artifact::CsvHistory,
                CsvWhat::Impacts => Artifact::CsvImpacts,
                CsvWhat::Sweep => Artifact::CsvSweep,
                CsvWhat::Response => Artifact::CsvResponse,
            };
            write(ctx, kind, &c.common, &c.common.options()?, false, super::AsciiArgs::default())
        }
        ExportCommand::Svg(s) => figure(ctx, s, false),
        ExportCommand::Pdf(s) => figure(ctx, s, true),
        ExportCommand::Wav(w) => {
            if let Some(PulseSound::Pulse(p)) = &w.pulse {
                return pulse_sound(p);
            }
            let mut opts = w.common.options()?;
            opts.wav = w.sound.options()?;
            write(ctx, Artifact::Wav, &w.common, &opts, false, super::AsciiArgs::default())
        }
    }
}
