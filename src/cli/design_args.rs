//! The design flags shared by `simulate`, `sweep` and `export`: a preset, then overrides.

use clap::{Args, ValueEnum};

use super::{CliError, Ctx, PulseArg, QuadSignsArg, SourceArg};
use crate::damper::Solver;
use crate::design::Design;
use crate::error::ThudError;
use crate::limits::{self, short, Estimate, Range};
use crate::params::{self, Input, Spelling};
use crate::presets;
use crate::units::Kind;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SolverArg {
    /// Exact flight between impacts, adaptive integration inside each contact (fast).
    Event,
    /// Uniform Newmark-β (β 1/4, γ 1/2) at --dt: the paper's method, the reference.
    Newmark,
}

/// The flag that sets the force amplitude F0: `--force` (with the alias `--force-amplitude`)
/// everywhere but `export`, whose `--force` replaces an existing file; there it is
/// `--force-amplitude` alone.
pub trait ForceFlag: Args + Clone + std::fmt::Debug {
    /// The flag's long name, without dashes.
    const NAME: &'static str;
    /// The value typed, if any.
    fn typed(&self) -> &Option<String>;
}

/// `--force F0` (alias `--force-amplitude`).
#[derive(Debug, Clone, Args)]
pub struct Force {
    /// Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq.
    #[arg(long = "force", visible_alias = "force-amplitude", value_name = "F0", allow_hyphen_values = true)]
    force: Option<String>,
}

impl ForceFlag for Force {
    const NAME: &'static str = "force";
    fn typed(&self) -> &Option<String> {
        &self.force
    }
}

/// `--force-amplitude F0` (for `export`, where `--force` replaces a file).
#[derive(Debug, Clone, Args)]
pub struct ForceAmplitude {
    /// Amplitude F0 of a harmonic force F0·cos(2π·f·t) on the main mass (N, or e.g. 2N) [default: 0, the paper's free decay]; needs --freq.
    #[arg(long = "force-amplitude", value_name = "F0", allow_hyphen_values = true)]
    force_amplitude: Option<String>,
}

impl ForceFlag for ForceAmplitude {
    const NAME: &'static str = "force-amplitude";
    fn typed(&self) -> &Option<String> {
        &self.force_amplitude
    }
}

/// A design: a preset, then any flag given explicitly overrides the preset's value.
#[derive(Debug, Clone, Args)]
pub struct DesignArgs<F: ForceFlag = Force> {
    /// Starting design (`thud presets` lists them: default, paper-fig9, paper-table3, quiet-nylon, …).
    #[arg(long, value_name = "P", default_value = "default")]
    preset: String,
    /// Impact mass m (kg, or e.g. 40.5g).
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    mass: Option<String>,
    /// Total clearance d (m, or e.g. 4cm).
    #[arg(long, value_name = "D", allow_hyphen_values = true)]
    gap: Option<String>,
    /// Initial velocity of the main mass (m/s).
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    v0: Option<String>,
    /// Main mass M (kg).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    main_mass: Option<String>,
    /// Spring stiffness K (N/m).
    #[arg(long, value_name = "K", allow_hyphen_values = true)]
    k: Option<String>,
    /// Viscous damping C (N·s/m).
    #[arg(long, value_name = "C", allow_hyphen_values = true)]
    c: Option<String>,
    /// Contact damping c1 (N·s/m).
    #[arg(long, value_name = "C1", allow_hyphen_values = true)]
    c1: Option<String>,
    /// Hertz stiffness K_HZ (N/m^1.5).
    #[arg(long, value_name = "KH", allow_hyphen_values = true, conflicts_with = "sphere")]
    k_hz: Option<String>,
    /// Ball material: K_HZ then follows from the materials and the ball's radius (Eq 2).
    #[arg(long, value_name = "MATERIAL")]
    sphere: Option<String>,
    /// Enclosure material (with --sphere) [default: steel].
    #[arg(long, value_name = "MATERIAL", requires = "sphere")]
    plate: Option<String>,
    /// Clamp the contact force at ≥ 0 (a contact cannot pull).
    #[arg(long)]
    no_tension: bool,
    /// Simulated time (s).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    duration: Option<String>,
    /// Solver.
    #[arg(long, value_enum)]
    solver: Option<SolverArg>,
    /// Newmark time step (s) [default: 1e-7].
    #[arg(long, value_name = "DT", allow_hyphen_values = true)]
    dt: Option<String>,
    /// Ball density (kg/m³): the radius follows from the mass.
    #[arg(long, value_name = "RHO", allow_hyphen_values = true, conflicts_with = "radius")]
    density: Option<String>,
    /// Ball radius (m), whatever the mass.
    #[arg(long, value_name = "A", allow_hyphen_values = true)]
    radius: Option<String>,
    /// Observer distance (m).
    #[arg(long, value_name = "R", allow_hyphen_values = true)]
    r: Option<String>,
    /// Observer angle (degrees).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    theta: Option<String>,
    /// Reflecting surfaces around the impact.
    #[arg(long, value_enum)]
    source: Option<SourceArg>,
    /// Quadrupole wall-image signs.
    #[arg(long, value_enum)]
    quad_signs: Option<QuadSignsArg>,
    /// Acceleration pulse of each impact's sound: half-sine (Eq 7) or the exact Hertz pulse.
    #[arg(long, value_enum)]
    pulse: Option<PulseArg>,
    /// Zone threshold L* on SPLmax (dB).
    #[arg(long, value_name = "DB", allow_hyphen_values = true)]
    l_star: Option<String>,
    /// Zone threshold e* on the damping inclination (cm/s).
    #[arg(long, value_name = "CM_S", allow_hyphen_values = true)]
    e_star: Option<String>,
    #[command(flatten)]
    force: F,
    /// Frequency f of the harmonic force (Hz, or e.g. 5Hz).
    #[arg(long, value_name = "F", allow_hyphen_values = true)]
    freq: Option<String>,
    /// The ball's initial offset y0 from the enclosure's centre (m, or e.g. -1cm; |y0| < d/2) [default: 0, centred].
    #[arg(long, value_name = "Y0", allow_hyphen_values = true)]
    ball_position: Option<String>,
    /// The ball's initial velocity w0 (m/s) [default: 0].
    #[arg(long, value_name = "W0", allow_hyphen_values = true)]
    ball_velocity: Option<String>,
    /// Forcing periods N of the steady-state window of a forced run [default: 10].
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    periods: Option<String>,
    /// Run a forced run on past --duration, N periods at a time, until its steady amplitude settles.
    #[arg(long)]
    settle: bool,
}

impl<F: ForceFlag> DesignArgs<F> {
    /// The design these flags describe, validated: each flag against its range (the error
    /// names the flag as typed), then the whole design (preset values too) and its derived
    /// quantities. The mapping from flags to the design is the engine's ([`params::design`]),
    /// shared with the Python module.
    pub fn design(&self) -> Result<Design, ThudError> {
        let mut d = presets::preset(&self.preset)?;
        d.thresholds = super::settings::load().thresholds(d.thresholds);
        params::design(d, &self.given(), Spelling::Flag)
    }

    /// The design of a frequency response from these flags at its first frequency
    /// ([`params::response_design`]).
    pub fn response_design(&self, first_hz: f64) -> Result<Design, ThudError> {
        let mut d = presets::preset(&self.preset)?;
        d.thresholds = super::settings::load().thresholds(d.thresholds);
        params::response_design(d, &self.given(), Spelling::Flag, first_hz, F::NAME)
    }

    /// The design flags given, as (name, value) pairs for [`params::design`]; the force
    /// amplitude under the name this command's flag has (`force` or `force-amplitude`).
    fn given(&self) -> Vec<(String, Input)> {
        let texts = [
            ("mass", &self.mass),
            ("gap", &self.gap),
            ("v0", &self.v0),
            ("main-mass", &self.main_mass),
            ("k", &self.k),
            ("c", &self.c),
            ("c1", &self.c1),
            ("k-hz", &self.k_hz),
            ("sphere", &self.sphere),
            ("plate", &self.plate),
            ("duration", &self.duration),
            ("dt", &self.dt),
            ("density", &self.density),
            ("radius", &self.radius),
            ("r", &self.r),
            ("theta", &self.theta),
            ("l-star", &self.l_star),
            ("e-star", &self.e_star),
            (F::NAME, self.force.typed()),
            ("freq", &self.freq),
            ("ball-position", &self.ball_position),
            ("ball-velocity", &self.ball_velocity),
            ("periods", &self.periods),
        ];
        let choices = [
            ("solver", choice_name(self.solver)),
            ("source", choice_name(self.source)),
            ("quad-signs", choice_name(self.quad_signs)),
            ("pulse", choice_name(self.pulse)),
        ];
        let switches = [("no-tension", self.no_tension), ("settle", self.settle)];
        texts
            .into_iter()
            .filter_map(|(n, t)| t.as_ref().map(|t| (n.to_string(), Input::Text(t.clone()))))
            .chain(choices.into_iter().filter_map(|(n, c)| c.map(|c| (n.to_string(), Input::Text(c)))))
            .chain(switches.into_iter().filter(|(_, on)| *on).map(|(n, _)| (n.to_string(), Input::Switch(true))))
            .collect()
    }

    /// The numeric flags the user typed, as `--name value`, for messages about the design as
    /// a whole.
    pub(crate) fn typed(&self) -> String {
        let all = [
            ("mass", &self.mass),
            ("gap", &self.gap),
            ("v0", &self.v0),
            ("main-mass", &self.main_mass),
            ("k", &self.k),
            ("c", &self.c),
            ("c1", &self.c1),
            ("k-hz", &self.k_hz),
            ("duration", &self.duration),
            ("dt", &self.dt),
            ("density", &self.density),
            ("radius", &self.radius),
            (F::NAME, self.force.typed()),
            ("freq", &self.freq),
            ("ball-position", &self.ball_position),
            ("ball-velocity", &self.ball_velocity),
            ("periods", &self.periods),
        ];
        let typed: Vec<String> = all
            .iter()
            .filter_map(|(n, t)| t.as_ref().map(|t| format!("--{n} {}", super::errors::cut_chars(t, 20))))
            .collect();
        typed.join(", ")
    }

    /// `--duration` as typed, if it was.
    pub(crate) fn duration_text(&self) -> Option<String> {
        self.duration.clone()
    }

    /// Refuses `--ensemble N` (N > 1) with `--ball-position`: the ensemble sets the offsets
    /// ([`params::check_ensemble`]).
    pub(crate) fn check_ensemble(&self, runs: usize) -> Result<(), ThudError> {
        params::check_ensemble(runs, self.ball_position.is_some(), Spelling::Flag)
    }

    /// What to show for a flag in a refusal: what the user typed, else the design's value.
    fn shown(text: &Option<String>, value: f64, unit: &str) -> String {
        text.clone().unwrap_or_else(|| format!("{} {unit}", short(value)))
    }

    /// Refuses one run of `d` whose work is over a cap (see [`limits::design_run`]), naming
    /// the flag that drives it; `samples_flag` is the flag that asked for `history_samples`.
    pub(crate) fn check_run(
        &self,
        ctx: &Ctx,
        d: &Design,
        history_samples: usize,
        samples_flag: &str,
    ) -> Result<(), CliError> {
        let [steps, cycles, history] = limits::design_run(d, history_samples);
        self.check_newmark(ctx, d, steps, "")?;
        self.check_cycles(ctx, d, cycles, "")?;
        ctx.enforce(
            history,
            samples_flag,
            &history_samples.to_string(),
            &format!("use {samples_flag} ≤ {}", short(history.cap.max)),
        )
    }

    /// Refuses Newmark steps over the cap (`per` says "per cell" sizes for sweeps).
    fn check_newmark(&self, ctx: &Ctx, d: &Design, steps: Estimate, cells: &str) -> Result<(), CliError> {
        let Solver::Newmark { dt_s } = d.solver else { return Ok(()) };
        let dur = d.damper.duration_s;
        let scale = steps.value / limits::newmark_steps(dur, dt_s);
        let (min_dt, max_dur) = (dur * scale / steps.cap.max, steps.cap.max * dt_s / scale);
        if self.duration.is_some() && self.dt.is_none() {
            let hint = format!("use --duration ≤ {} s{cells} or a larger --dt", short(max_dur));
            ctx.enforce(steps, "--duration", &Self::shown(&self.duration, dur, "s"), &hint)
        } else {
            let hint = format!("use --dt ≥ {} s{cells} or a shorter --duration", short(min_dt));
            ctx.enforce(steps, "--dt", &Self::shown(&self.dt, dt_s, "s"), &hint)
        }
    }

    /// Refuses main-mass cycles over the cap.
    fn check_cycles(&self, ctx: &Ctx, d: &Design, cycles: Estimate, cells: &str) -> Result<(), CliError> {
        let dur = d.damper.duration_s;
        let max_dur = dur * cycles.cap.max / cycles.value;
        let p = &d.damper;
        let (flag, shown) = if self.duration.is_none() && self.k.is_some() {
            ("--k", Self::shown(&self.k, p.stiffness_n_m, "N/m"))
        } else if self.duration.is_none() && self.main_mass.is_some() {
            ("--main-mass", Self::shown(&self.main_mass, p.main_mass_kg, "kg"))
        } else {
            ("--duration", Self::shown(&self.duration, dur, "s"))
        };
        ctx.enforce(cycles, flag, &shown, &format!("use --duration ≤ {} s{cells}", short(max_dur)))
    }

    /// Refuses a design chart of `n_masses` × `n_gaps` cells of `d` whose work is over a cap.
    pub(crate) fn check_sweep(&self, ctx: &Ctx, d: &Design, n_masses: usize, n_gaps: usize) -> Result<(), CliError> {
        let cells = limits::sweep_cells(n_masses, n_gaps);
        ctx.enforce(
            cells,
            "--masses/--gaps",
            &format!("{n_masses} × {n_gaps}"),
            &format!("use fewer values N on either axis (product ≤ {})", short(cells.cap.max)),
        )?;
        let n = n_masses * n_gaps;
        let [cell_seconds, steps, cycles] = limits::sweep_work(d, n);
        let per = format!(" with {n} cells");
        ctx.enforce(
            cell_seconds,
            "--duration",
            &Self::shown(&self.duration, d.damper.duration_s, "s"),
            &format!("use --duration ≤ {} s{per} or fewer cells", short(cell_seconds.cap.max / n as f64)),
        )?;
        self.check_newmark(ctx, d, steps, &per)?;
        self.check_cycles(ctx, d, cycles, &per)
    }
}

impl<F: ForceFlag> DesignArgs<F> {
    /// Refuses `cells` cells of `d` with `runs` ensemble runs each (a chart, a chart's part, or
    /// one design with `cells` = 1) whose work is over a cap (see [`limits::ensemble_work`]):
    /// the runs (named by `flag` typed as `value`), the simulated run-seconds, and the Newmark
    /// steps and main-mass cycles summed over the runs.
    pub(crate) fn check_runs(
        &self,
        ctx: &Ctx,
        d: &Design,
        cells: usize,
        runs: usize,
        flag: &str,
        value: &str,
    ) -> Result<(), CliError> {
        let [n, seconds, steps, cycles] = limits::ensemble_work(d, cells, runs);
        let hint = if cells > 1 {
            format!("use fewer runs ({cells} cells × {runs}; at most {} runs), e.g. more shards", short(n.cap.max))
        } else {
            format!("use at most {} runs", short(n.cap.max))
        };
        ctx.enforce(n, flag, value, &hint)?;
        let per = format!(" with {} runs", short(n.value));
        ctx.enforce(
            seconds,
            "--duration",
            &Self::shown(&self.duration, d.damper.duration_s, "s"),
            &format!("use --duration ≤ {} s{per} or fewer runs", short(seconds.cap.max / n.value)),
        )?;
        self.check_newmark(ctx, d, steps, &per)?;
        self.check_cycles(ctx, d, cycles, &per)
    }
}

/// Parses a range "FROM:TO:N" of quantities of `kind` (e.g. "30g:100g:20") for flag `--{name}`;
/// both ends are checked against `range`, N against [`limits::GRID_N`] ([`params::parse_range`]).
pub fn parse_range(name: &str, text: &str, kind: Kind, range: &Range) -> Result<Vec<f64>, ThudError> {
    params::parse_range(&format!("--{name}"), text, kind, range)
}

/// The name of a clap value (`half-sine`), as the engine's tables spell it.
fn choice_name<T: ValueEnum>(v: Option<T>) -> Option<String> {
    v.and_then(|v| v.to_possible_value()).map(|p| p.get_name().to_string())
}
