// Over 800 lines: the one table of every range and every cap, read together.
//! Every input's range and every run's work budget, in one table that the command line, the
//! terminal explorer and the config file all use. Pure: no I/O.
//!
//! **Ranges** ([`Range`]) are what is physically meaningful for each parameter, in the unit the
//! engine uses inside (SI; degrees for angles, dB for levels, cm/s for inclinations), each with a
//! one-line reason. A value outside its range (or NaN/∞) is refused with an error that names the
//! parameter, the value and the range ([`Range::check`]). The ranges are wide enough that every
//! combination of in-range values gives finite results; the few derived quantities that can
//! still go wrong (a ball radius from mass and density, K_HZ from materials, the observer inside
//! the ball) are checked by [`crate::params::check_design`], which checks every design against
//! the ranges of its rows.
//!
//! **Caps** ([`Cap`]) bound the work of one run before it starts: [`design_run`] estimates the
//! Newmark steps, main-mass cycles and history samples of a simulation; [`wav_samples`],
//! [`sweep_cells`], [`sweep_work`], [`ensemble_work`], [`merged_runs`], [`band_count`] and
//! [`restitution_contacts`] the rest.
//! Each cap is about the largest run that finishes in about a minute and fits in 1 GB on a
//! 2-core machine (measured on the release build; the numbers are in each cap's `basis`). Front
//! ends refuse an estimate over its cap unless the user lifts the caps (`--no-limit`).

use crate::acoustics::Source;
use crate::damper::Solver;
use crate::design::{Design, ValidDesign};
use crate::error::ThudError;
pub use crate::units::short;

/// The physically meaningful range of one parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// The parameter's name as on the command line, without dashes (`mass`, `k-hz`, …).
    pub param: &'static str,
    /// What it is, for people (`ball mass m`).
    pub what: &'static str,
    /// Smallest valid value (inclusive), in `unit`.
    pub min: f64,
    /// Largest valid value (inclusive), in `unit`.
    pub max: f64,
    /// The unit of `min`, `max` and of a plain number (`kg`, `m`, `deg`, … ; empty for counts).
    pub unit: &'static str,
    /// Why these bounds, in one line.
    pub reason: &'static str,
}

/// Shorthand for the table below.
const fn range(
    param: &'static str,
    what: &'static str,
    min: f64,
    max: f64,
    unit: &'static str,
    reason: &'static str,
) -> Range {
    Range { param, what, min, max, unit, reason }
}

/// Impact (ball) mass m (kg).
pub const MASS: Range = range(
    "mass",
    "ball mass m",
    1e-4,
    100.0,
    "kg",
    "a 0.1 g bead to a 100 kg slug: lighter, air drag and adhesion dominate; heavier is no single-unit damper",
);
/// Total clearance d (m).
pub const GAP: Range = range(
    "gap",
    "clearance d",
    1e-5,
    10.0,
    "m",
    "10 µm is machining tolerance (a smaller gap is a press fit); 10 m is no enclosure",
);
/// Initial velocity of the main mass v0 (m/s).
pub const V0: Range = range(
    "v0",
    "initial velocity v0",
    -100.0,
    100.0,
    "m/s",
    "structures vibrate at mm/s to a few m/s; beyond 100 m/s the elastic Hertz contact no longer holds",
);
/// Main mass M (kg).
pub const MAIN_MASS: Range = range("main-mass", "main mass M", 1e-3, 1e6, "kg", "a 1 g part to a 1000 t structure");
/// Spring stiffness K (N/m).
pub const STIFFNESS: Range =
    range("k", "stiffness K", 0.0, 1e10, "N/m", "0 is an unsupported mass; 1e10 N/m is a stiff machine frame");
/// Viscous damping C (N·s/m).
pub const DAMPING: Range = range(
    "c",
    "viscous damping C",
    0.0,
    1e6,
    "N·s/m",
    "0 is undamped; 1e6 N·s/m overdamps any structure in this table",
);
/// Contact damping c1 (N·s/m).
pub const C1: Range = range(
    "c1",
    "contact damping c1",
    0.0,
    1e6,
    "N·s/m",
    "0 is an elastic contact; 1e6 N·s/m is above critical for the heaviest, stiffest contact",
);
/// Hertz stiffness K_HZ (N/m^1.5).
pub const K_HZ: Range = range(
    "k-hz",
    "Hertz stiffness K_HZ",
    1e4,
    1e13,
    "N/m^1.5",
    "spans Eq 2 for every material pair and ball radius in this table (rubber 0.1 mm ≈ 4e5, carbide 2 m ≈ 6e11)",
);
/// Simulated time (s).
pub const DURATION: Range = range(
    "duration",
    "simulated time",
    1e-6,
    1e6,
    "s",
    "shorter than 1 µs sees no contact; 1e6 s (11 days) is far beyond any free decay",
);
/// Newmark time step (s).
pub const DT: Range = range(
    "dt",
    "Newmark time step",
    1e-14,
    1e-3,
    "s",
    "a contact lasts µs to ms, so a step must be ≤ 1 ms; below 1e-14 s, t + dt stops advancing in double precision",
);
/// Ball density (kg/m³).
pub const DENSITY: Range =
    range("density", "ball density", 10.0, 25_000.0, "kg/m^3", "from foam to osmium (22 590 kg/m³)");
/// Ball radius (m).
pub const RADIUS: Range = range(
    "radius",
    "ball radius a",
    1e-4,
    2.0,
    "m",
    "0.1 mm to 2 m: every mass and density in this table gives a radius inside it",
);
/// Observer distance r (m).
pub const R: Range = range(
    "r",
    "observer distance r",
    1e-3,
    1e3,
    "m",
    "closer than 1 mm is inside any ball; beyond 1 km air absorption (not modelled) dominates",
);
/// Observer angle θ (degrees), over all source types; see [`theta_deg`] for one source.
pub const THETA: Range = range(
    "theta",
    "observer angle θ",
    -180.0,
    180.0,
    "deg",
    "an angle from the plate's normal; a wall narrows it per source type",
);
/// Impact speed U0 (m/s).
pub const U0: Range = range(
    "u0",
    "impact speed U0",
    1e-4,
    100.0,
    "m/s",
    "below 0.1 mm/s surface roughness and adhesion dominate; beyond 100 m/s the contact is not elastic",
);
/// Air impedance ρ0·c (Pa·s/m).
pub const RHO_C: Range =
    range("rho-c", "air impedance ρ0·c", 1.0, 1e7, "Pa·s/m", "from thin gas (≈ 1) past air (413) to water (1.5e6)");
/// Speed of sound c (m/s).
pub const C_SOUND: Range = range(
    "sound-speed",
    "speed of sound c",
    1.0,
    1e4,
    "m/s",
    "every gas, liquid and solid is inside 1–10 000 m/s (air 343)",
);
/// Air temperature (°C), from which the physical model takes ρ0 and c.
pub const AIR_TEMPERATURE: Range = range(
    "air-temperature",
    "air temperature",
    -60.0,
    60.0,
    "degC",
    "the coldest to the hottest air people work in; dry air stays an ideal gas there (c 315–369 m/s)",
);
/// Air pressure (Pa), from which the physical model takes ρ0.
pub const AIR_PRESSURE: Range = range(
    "air-pressure",
    "air pressure",
    2e4,
    2e5,
    "Pa",
    "from above Everest's summit (≈ 33 kPa) to two atmospheres; air is an ideal gas throughout",
);
/// Zone threshold L* on SPLmax (dB).
pub const L_STAR: Range = range(
    "l-star",
    "zone threshold L*",
    0.0,
    200.0,
    "dB",
    "0 dB is the threshold of hearing; 194 dB is a pressure swing of one atmosphere",
);
/// Zone threshold e* on the damping inclination (cm/s).
pub const E_STAR: Range = range(
    "e-star",
    "zone threshold e*",
    0.0,
    1e3,
    "cm/s",
    "an inclination is a decay rate ≥ 0; 10 m/s per second is beyond any damper",
);
/// Pressure written as WAV sample value 1.0 (Pa).
pub const FULL_SCALE: Range = range(
    "full-scale",
    "WAV full scale",
    1e-5,
    1e6,
    "Pa",
    "from below the threshold of hearing (20 µPa) to 10 atmospheres",
);
/// A wanted restitution R (`restitution --target`).
pub const TARGET: Range = range(
    "target",
    "restitution R",
    1e-3,
    1.0,
    "",
    "R = u_out/u_in ≤ 1 for a passive contact; below 0.001 the ball sticks",
);
/// Width of the inclination bands of Table 5 (cm/s).
pub const BAND: Range = range(
    "band",
    "Table 5 band width",
    1e-3,
    1e3,
    "cm/s",
    "narrower than 0.01 mm/s is below the resolution of e; wider than 10 m/s is one band",
);
/// Points of a waveform or history curve.
pub const POINTS: Range = range(
    "points",
    "curve points",
    2.0,
    1e9,
    "",
    "a curve needs 2 points; the work cap (not this range) limits long ones",
);
/// History samples of `simulate --csv`.
pub const SAMPLES: Range = range(
    "samples",
    "history samples",
    2.0,
    1e9,
    "",
    "a history needs 2 samples; the work cap (not this range) limits long ones",
);
/// Impacts listed in the text summary.
pub const SHOW: Range = range("show", "impacts listed", 0.0, 1e9, "", "never more than the run's impacts are listed");
/// Values N of a FROM:TO:N sweep axis.
pub const GRID_N: Range = range(
    "N",
    "values on a sweep axis",
    1.0,
    1000.0,
    "",
    "1000 × 1000 cells is the most a chart can show; the work cap limits the product",
);

/// The period of a periodic orbit looked for by shooting (`thud orbit --period N`), in forcing
/// periods.
pub const ORBIT_PERIODS: Range = range(
    "period",
    "orbit's period",
    1.0,
    16.0,
    "periods",
    "the longest period the orbit classification looks for (dynamics::MAX_PERIOD); longer ones read as chaos or a torus",
);

/// Forcing periods run before a study of orbits samples its run (`--transient N`).
pub const TRANSIENT: Range = range(
    "transient",
    "transient before sampling",
    0.0,
    100_000.0,
    "periods",
    "0 samples from the start; 1e5 periods outlast any transient of a damped design, and the work cap bounds the total",
);

/// Worker threads of the parallel pool (`--threads N`, or `RAYON_NUM_THREADS`).
pub const THREADS: Range = range(
    "threads",
    "worker threads",
    1.0,
    1024.0,
    "threads",
    "1 runs the work on one thread; past the machine's cores more threads only cost memory, and 1024 is more cores than one machine has",
);

/// Runs of an ensemble (`--ensemble N`): the same design from N evenly spread initial ball
/// offsets (see [`crate::ensemble`]).
pub const ENSEMBLE: Range = range(
    "ensemble",
    "runs per design",
    1.0,
    1000.0,
    "",
    "1 is the paper's single trajectory; at 1000 runs one run moves p10 or p90 by 0.1 %, finer than any decision needs",
);

/// Designs one search evaluates (`thud design --evaluations N`).
pub const EVALUATIONS: Range = range(
    "evaluations",
    "designs a search evaluates",
    2.0,
    100_000.0,
    "",
    "a two-variable front settles within a few hundred; 1e5 runs of a 2 s design take minutes on a laptop",
);

/// Amplitude F0 of the harmonic force on the main mass (N).
pub const FORCE: Range = range(
    "force",
    "force amplitude F0",
    0.0,
    1e6,
    "N",
    "0 is the paper's free decay; 1e6 N (a 100 t shaker) is beyond any structure in this table",
);
/// Frequency f of the harmonic force (Hz); 0 (no force) is allowed only without a force.
pub const FREQ: Range = range(
    "freq",
    "forcing frequency f",
    1e-3,
    1e5,
    "Hz",
    "a period of 1000 s is a static load; at 100 kHz the period nears a contact's own µs",
);
/// The ball's initial offset y0 from the enclosure's centre (m); also |y0| < d/2.
pub const BALL_POSITION: Range = range(
    "ball-position",
    "initial ball offset y0",
    -5.0,
    5.0,
    "m",
    "the ball starts inside the clearance, |y0| < d/2 (checked against --gap), and d ≤ 10 m",
);
/// The ball's initial velocity w0 (m/s).
pub const BALL_VELOCITY: Range = range(
    "ball-velocity",
    "initial ball velocity w0",
    -100.0,
    100.0,
    "m/s",
    "as v0: beyond 100 m/s the elastic Hertz contact no longer holds",
);
/// Forcing periods N of a steady-state window.
pub const PERIODS: Range = range(
    "periods",
    "steady-state window",
    1.0,
    1000.0,
    "periods",
    "a window holds at least one forcing period; 1000 outlasts any transient worth averaging over",
);

/// The ball's Poisson ratio ν (dimensionless), overriding its material's.
pub const SPHERE_POISSON: Range = range(
    "sphere-poisson",
    "ball Poisson ratio ν",
    0.0,
    0.5,
    "",
    "an isotropic solid has −1 < ν ≤ 0.5 (0.5 incompressible); below 0 is auxetic, which no common ball material is",
);

/// Every range, in the order `thud` lists them.
pub const RANGES: [Range; 34] = [
    MASS,
    GAP,
    V0,
    MAIN_MASS,
    STIFFNESS,
    DAMPING,
    C1,
    K_HZ,
    DURATION,
    DT,
    DENSITY,
    RADIUS,
    SPHERE_POISSON,
    R,
    THETA,
    U0,
    RHO_C,
    C_SOUND,
    AIR_TEMPERATURE,
    AIR_PRESSURE,
    L_STAR,
    E_STAR,
    FULL_SCALE,
    TARGET,
    BAND,
    POINTS,
    SAMPLES,
    SHOW,
    ENSEMBLE,
    FORCE,
    FREQ,
    BALL_POSITION,
    BALL_VELOCITY,
    PERIODS,
];

/// The counts beside the design's ranges (sweep axes, threads, an orbit's period, a forced
/// study's transient, a design search's evaluations), listed after them by `thud limits`.
pub const COUNTS: [&Range; 5] = [&GRID_N, &THREADS, &ORBIT_PERIODS, &TRANSIENT, &EVALUATIONS];

impl Range {
    /// Whether `value` is finite and inside the range, to a relative 1e-9 (so `10um`, which
    /// parses to 9.999999999999999e-6 m, is inside a range from 1e-5 m).
    pub fn contains(&self, value: f64) -> bool {
        let slack = |b: f64| 1e-9 * b.abs();
        value.is_finite() && value >= self.min - slack(self.min) && value <= self.max + slack(self.max)
    }

    /// "0.0001 to 100 kg".
    pub fn describe(&self) -> String {
        let unit = if self.unit.is_empty() { String::new() } else { format!(" {}", self.unit) };
        format!("{} to {}{unit}", short(self.min), short(self.max))
    }

    /// `value` if it is inside the range; otherwise an error naming [`Range::param`].
    pub fn check(&self, value: f64) -> Result<f64, ThudError> {
        self.check_as(self.param, value)
    }

    /// `value` if it is inside the range; otherwise an error naming `param` (the flag, field or
    /// config key the user typed), the value and the range.
    pub fn check_as(&self, param: &str, value: f64) -> Result<f64, ThudError> {
        if self.contains(value) {
            return Ok(value);
        }
        Err(ThudError::OutOfRange {
            param: param.to_string(),
            value,
            shown: short(value),
            unit: self.unit,
            what: self.what,
            range: self.describe(),
        })
    }

    /// A whole number typed as `text` (plain or like `1e4`), checked against the range.
    pub fn parse_count(&self, param: &str, text: &str) -> Result<usize, ThudError> {
        let t = text.trim();
        let v: f64 = t.parse().map_err(|_| {
            ThudError::invalid(
                param,
                format!("'{t}' is not a whole number; the {} must be {}", self.what, self.describe()),
            )
        })?;
        let v = crate::units::overflow_checked(param, t, v)?;
        if v.fract() != 0.0 && v.is_finite() {
            return Err(ThudError::invalid(
                param,
                format!("'{t}' is not a whole number; the {} must be {}", self.what, self.describe()),
            ));
        }
        Ok(self.check_as(param, v)? as usize)
    }
}

/// The range of θ (deg) for one source type.
pub fn theta_deg(source: Source) -> Range {
    let (min, max) = source.theta_range_deg();
    let reason = match source {
        Source::Single => "a free sphere: every direction",
        Source::Dipole => "a sphere on a plate: the open half-space",
        Source::Quadrupole => "a sphere in a wall–floor corner: the open quarter-space",
    };
    Range { min, max, reason, ..THETA }
}

/// A cap on one kind of work of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cap {
    /// What is counted (`Newmark steps`).
    pub what: &'static str,
    /// The largest estimate allowed without `--no-limit`.
    pub max: f64,
    /// How the cap was set (measured time or memory on the release build).
    pub basis: &'static str,
}

/// Newmark-β steps of one run, or summed over a sweep: duration / dt per design.
pub const NEWMARK_STEPS: Cap = Cap {
    what: "Newmark steps",
    max: 1e9,
    basis: "≈ 25 ns a step in flight, up to 130 ns in contact: 2e8 steps took 4.9 s alone, 1e9 took 84 s with other builds running",
};
/// Cycles of the main mass in one run (each is a recorded maximum): duration × damped frequency.
pub const CYCLES: Cap = Cap {
    what: "main-mass cycles",
    max: 1e7,
    basis: "16 bytes and ≈ 0.7 µs a cycle with its JSON: 1e7 cycles took 6.9 s and 130 MB",
};
/// History samples kept of one run (`simulate --csv --samples`, history exports `--points`).
pub const HISTORY_SAMPLES: Cap = Cap {
    what: "history samples",
    max: 1e7,
    basis: "24 bytes each in memory, ≈ 1.2 µs each to write: 1e7 samples took 12 s and 240 MB",
};
/// Points of one waveform (`pulse --points`, waveform exports `--points`).
pub const WAVEFORM_POINTS: Cap = Cap {
    what: "waveform points",
    max: 1e7,
    basis: "the slowest kind (Hertz pulse, quadrupole, JSON): 1e7 points took 58 s and 160 MB",
};
/// Samples of one WAV file: duration × sample rate.
pub const WAV_SAMPLES: Cap = Cap {
    what: "WAV samples",
    max: 4.8e7,
    basis: "1000 s of sound at 48 kHz: at most 12 bytes a sample while rendering; took 2 s and 194 MB",
};
/// Cells of one design chart: masses × gaps.
pub const SWEEP_CELLS: Cap = Cap {
    what: "sweep cells",
    max: 1e5,
    basis: "≈ 0.6 ms a 2 s cell on each of 2 cores: 1e4 cells took 6 s, 1e5 took 90 s with other builds running",
};
/// Simulated seconds summed over the cells of one design chart: cells × duration.
pub const SWEEP_CELL_SECONDS: Cap = Cap {
    what: "simulated cell-seconds",
    max: 2e5,
    basis: "1e5 cells of 2 s; 1000 cells of 200 s took 6.7 s (a cell is also capped by the solver's own work cap)",
};
/// Bands of the Table 5 summary: (largest e − smallest e) / band width.
pub const BANDS: Cap =
    Cap { what: "Table 5 bands", max: 1e4, basis: "each band scans every cell: 1e4 bands × 1e5 cells is ≈ 1 s" };
/// Isolated contacts integrated by `restitution`: one per mass, ≈ 100 per mass with `--target`.
pub const RESTITUTION_CONTACTS: Cap = Cap {
    what: "isolated contacts",
    max: 2e5,
    basis:
        "≈ 5 µs a typical contact, up to 55 ms a heavily overdamped one (each is capped at 200 000 integrator steps)",
};

/// Runs of one command: cells × ensemble runs (`--ensemble`, `--shard`: the part's cells).
pub const RUNS: Cap = Cap {
    what: "runs (cells × ensemble)",
    max: 1e5,
    basis: "a run is one sweep cell's work, so the sweep-cell cap: ≈ 0.6 ms a 2 s run on each of 2 cores",
};
/// Simulated seconds summed over the runs of one command: runs × duration.
pub const RUN_SECONDS: Cap = Cap {
    what: "simulated run-seconds",
    max: 2e5,
    basis: "the sweep's cell-second cap, counted per run: 1e5 runs of 2 s",
};
/// Runs held in one merged chart (`thud merge`): cells × ensemble runs over all the parts.
pub const MERGED_RUNS: Cap = Cap {
    what: "merged runs (cells × ensemble)",
    max: 1e6,
    basis: "1e5 cells × 10 runs merged to 495 MB of JSON in 7.4 s with 730 MB peak memory (2e6 took 1.7 GB)",
};

/// Forcing periods of a response point's motion its periodic orbit is looked for over before
/// the motion is simulated on until it settles (most impacting orbits of the presets are found
/// within 30–170 periods).
pub const RESPONSE_SEARCH_PERIODS: u32 = 256;

/// Forcing periods simulated by one frequency response (`thud response`): over the
/// frequencies, with the event solver first the orbit search ([`RESPONSE_SEARCH_PERIODS`]),
/// then each run to its duration and settled (at most [`crate::damper::SETTLE_PERIODS_MAX`]
/// periods more), twice with `--continuation`.
pub const RESPONSE_PERIODS: Cap = Cap {
    what: "forcing periods",
    max: 2e6,
    basis: "15 µs a period at ½ impact a period (thud response --force-amplitude 1N: 112 638 periods, 1.7 s of CPU), up to ≈ 100 µs at 4 impacts a period: 2e6 periods is at most about 100 s on 2 cores",
};

/// Points of one continued branch (`thud continue`): each point is an orbit corrected onto the
/// branch with its Jacobian, about nine runs of the orbit's period.
pub const BRANCH_POINTS: Cap = Cap {
    what: "points of a continued branch",
    max: 5000.0,
    basis: "≈ 2 ms a point (forced-rattle's family over 3–8 Hz: 2 726 points in 5.9 s of one core): 5000 points is about 10 s a branch",
};

/// Forcing periods the seeds of a continued family may simulate (`thud continue --vary
/// NAME=FROM:TO:N`): the attractor search at each of the N values runs at most
/// [`crate::orbit::MAX_TRANSIENT_PERIODS`] periods. Each branch is then capped by
/// [`BRANCH_POINTS`] as it goes.
pub fn family_seed_periods(seeds: usize) -> Estimate {
    Estimate { cap: RESPONSE_PERIODS, value: seeds as f64 * f64::from(crate::orbit::MAX_TRANSIENT_PERIODS) }
}

/// Every cap, in the order `thud` lists them.
pub const CAPS: [Cap; 14] = [
    NEWMARK_STEPS,
    CYCLES,
    HISTORY_SAMPLES,
    WAVEFORM_POINTS,
    WAV_SAMPLES,
    SWEEP_CELLS,
    SWEEP_CELL_SECONDS,
    BANDS,
    RESTITUTION_CONTACTS,
    RUNS,
    RUN_SECONDS,
    MERGED_RUNS,
    RESPONSE_PERIODS,
    BRANCH_POINTS,
];

/// One estimate of the work of a run, against its cap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    pub cap: Cap,
    pub value: f64,
}

impl Estimate {
    /// Whether the estimate is over its cap (a NaN estimate is over).
    pub fn exceeded(&self) -> bool {
        self.value.is_nan() || self.value > self.cap.max
    }

    /// "2e12 Newmark steps exceed the limit of 1e9".
    pub fn describe(&self) -> String {
        format!("{} {} exceed the limit of {}", short(self.value.ceil()), self.cap.what, short(self.cap.max))
    }
}

/// Newmark steps of one run of `duration_s` at `dt_s`: ⌈duration / dt⌉.
pub fn newmark_steps(duration_s: f64, dt_s: f64) -> f64 {
    (duration_s / dt_s).ceil()
}

/// Cycles of the main mass over `duration_s`: duration × ω_d / 2π with the damped frequency
/// ω_d = √(K/M − (C/2M)²) (Eq 25 alone; zero when overdamped or without a spring).
pub fn cycles(duration_s: f64, main_mass_kg: f64, stiffness_n_m: f64, damping_n_s_m: f64) -> f64 {
    duration_s * crate::damper::damped_frequency_hz(main_mass_kg, stiffness_n_m, damping_n_s_m)
}

/// The longest a run of `d` can simulate (s): its duration, and for a forced run that settles
/// the most periods settling adds ([`crate::damper::SETTLE_PERIODS_MAX`]).
pub fn run_time_s(d: &Design) -> f64 {
    let p = &d.damper;
    if p.forced() && p.settle {
        p.duration_s + f64::from(crate::damper::SETTLE_PERIODS_MAX) / p.freq_hz
    } else {
        p.duration_s
    }
}

/// The work of one simulation of `d` keeping `history_samples` samples: its Newmark steps (0
/// with the event-driven solver), main-mass cycles and history samples. A forced run counts
/// the forcing cycles where they are faster than the free ones, and its settling time.
pub fn design_run(d: &Design, history_samples: usize) -> [Estimate; 3] {
    let p = &d.damper;
    let time = run_time_s(d);
    let steps = match d.solver {
        Solver::Event => 0.0,
        Solver::Newmark { dt_s } => newmark_steps(time, dt_s),
    };
    let mut cycles = cycles(time, p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    if p.forced() {
        cycles = cycles.max(time * p.freq_hz);
    }
    [
        Estimate { cap: NEWMARK_STEPS, value: steps },
        Estimate { cap: CYCLES, value: cycles },
        Estimate { cap: HISTORY_SAMPLES, value: history_samples as f64 },
    ]
}

/// The work of a frequency response of `d` over `freqs_hz` (each run at least two windows of
/// `N` periods, then settled; twice with `continuation`): forcing periods, and Newmark steps.
pub fn response_work(d: &Design, freqs_hz: &[f64], continuation: bool) -> [Estimate; 2] {
    let p = &d.damper;
    let n = f64::from(p.steady_periods);
    let settle = f64::from(crate::damper::SETTLE_PERIODS_MAX);
    let sweeps = if continuation { 2.0 } else { 1.0 };
    // The event solver first follows each point's motion looking for its orbit.
    let search = if d.solver == Solver::Event { f64::from(RESPONSE_SEARCH_PERIODS) } else { 0.0 };
    let periods: f64 = freqs_hz.iter().map(|f| (p.duration_s * f).max(2.0 * n) + settle + search).sum::<f64>() * sweeps;
    let steps = match d.solver {
        Solver::Event => 0.0,
        Solver::Newmark { dt_s } => {
            freqs_hz.iter().map(|f| newmark_steps(((p.duration_s * f).max(2.0 * n) + settle) / f, dt_s)).sum::<f64>()
                * sweeps
        }
    };
    [Estimate { cap: RESPONSE_PERIODS, value: periods }, Estimate { cap: NEWMARK_STEPS, value: steps }]
}

/// Samples of a WAV file `duration_s` long at `rate_hz`.
pub fn wav_samples(duration_s: f64, rate_hz: f64) -> Estimate {
    Estimate { cap: WAV_SAMPLES, value: (duration_s * rate_hz).round() }
}

/// Points of one waveform.
pub fn waveform_points(points: usize) -> Estimate {
    Estimate { cap: WAVEFORM_POINTS, value: points as f64 }
}

/// Cells of an `n_masses` × `n_gaps` chart.
pub fn sweep_cells(n_masses: usize, n_gaps: usize) -> Estimate {
    Estimate { cap: SWEEP_CELLS, value: n_masses as f64 * n_gaps as f64 }
}

/// The work of a design chart of `cells` cells of design `d` (mass and gap do not change it):
/// simulated cell-seconds, and the Newmark steps and main-mass cycles summed over the cells.
pub fn sweep_work(d: &Design, cells: usize) -> [Estimate; 3] {
    let n = cells as f64;
    let [steps, cycles, _] = design_run(d, 0);
    [
        Estimate { cap: SWEEP_CELL_SECONDS, value: n * d.damper.duration_s },
        Estimate { value: n * steps.value, ..steps },
        Estimate { value: n * cycles.value, ..cycles },
    ]
}

/// The work of `cells` cells of design `d` with `runs` ensemble runs each (mass, gap and the
/// ball's offset do not change it): the runs, simulated run-seconds, and the Newmark steps and
/// main-mass cycles summed over the runs.
pub fn ensemble_work(d: &Design, cells: usize, runs: usize) -> [Estimate; 4] {
    let n = cells as f64 * runs as f64;
    let [steps, cycles, _] = design_run(d, 0);
    [
        Estimate { cap: RUNS, value: n },
        Estimate { cap: RUN_SECONDS, value: n * d.damper.duration_s },
        Estimate { value: n * steps.value, ..steps },
        Estimate { value: n * cycles.value, ..cycles },
    ]
}

/// What the user can change to bring a refused run under its cap (the front end words it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Remedy {
    /// A duration of at most `max_s` (s).
    ShorterDuration { max_s: f64 },
    /// Newmark steps: a duration of at most `max_s` (s), or a larger time step.
    ShorterDurationOrLargerDt { max_s: f64 },
    /// Newmark steps: a time step of at least `min_s` (s), or a shorter duration.
    LargerDtOrShorterDuration { min_s: f64 },
    /// At most `max` history samples.
    FewerSamples { max: f64 },
    /// Fewer values on the chart's axes (their product at most `max`).
    FewerCells { max: f64 },
    /// A duration of at most `max_s` (s), or fewer cells.
    ShorterDurationOrFewerCells { max_s: f64 },
    /// At most `max` runs in all, over `cells` cells of `runs` runs each.
    FewerRuns { max: f64, cells: usize, runs: usize },
    /// A duration of at most `max_s` (s), or fewer runs.
    ShorterDurationOrFewerRuns { max_s: f64 },
    /// A response: at most `max` runs a frequency.
    FewerRunsPerFrequency { max: f64 },
    /// A response: fewer frequencies, or a shorter duration.
    FewerFrequencies,
    /// A response: lower frequencies, or a shorter duration.
    LowerFrequencies,
    /// Newmark steps of a response: the event solver, or a larger time step.
    EventSolverOrLargerDt,
}

/// The quantity a refusal asks the user to change, when it is not a row of the parameter
/// table: what the caller counts (history samples, chart cells, ensemble runs).
pub const SAMPLES_PARAM: &str = "samples";
/// See [`SAMPLES_PARAM`]: the cells of a chart (its two axes).
pub const CELLS_PARAM: &str = "cells";
/// See [`SAMPLES_PARAM`]: the ensemble's runs.
pub const RUNS_PARAM: &str = "runs";
/// See [`SAMPLES_PARAM`]: the frequencies of a response.
pub const FREQS_PARAM: &str = "freqs";

/// A run refused before it starts: one estimate over its cap, the parameter the user can
/// change (a row name of [`crate::params::DESIGN`] such as `duration`, `dt`, `k`, or one of
/// [`SAMPLES_PARAM`], [`CELLS_PARAM`], [`RUNS_PARAM`]), and what to change. The one decision
/// of every front end ([`check_run`], [`check_sweep`], [`check_runs`]); each words it itself.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{param}: {}", estimate.describe())]
pub struct Refusal {
    pub param: &'static str,
    pub estimate: Estimate,
    pub remedy: Remedy,
    /// What the estimate is summed over, for the hint: `" with 400 cells"`, `" with 16 runs"`,
    /// or empty for one run.
    pub per: String,
}

/// `Err` of `e` over its cap.
pub(crate) fn over(e: Estimate, param: &'static str, remedy: Remedy, per: &str) -> Result<(), Refusal> {
    if e.exceeded() {
        Err(Refusal { param, estimate: e, remedy, per: per.to_string() })
    } else {
        Ok(())
    }
}

/// Newmark steps over their cap: blames the duration when it was given without a step, else
/// the step.
fn newmark(d: &Design, given: &dyn Fn(&str) -> bool, steps: Estimate, per: &str) -> Result<(), Refusal> {
    let Solver::Newmark { dt_s } = d.solver else { return Ok(()) };
    let dur = d.damper.duration_s;
    let scale = steps.value / newmark_steps(dur, dt_s);
    if given("duration") && !given("dt") {
        over(steps, "duration", Remedy::ShorterDurationOrLargerDt { max_s: steps.cap.max * dt_s / scale }, per)
    } else {
        over(steps, "dt", Remedy::LargerDtOrShorterDuration { min_s: dur * scale / steps.cap.max }, per)
    }
}

/// Main-mass cycles over their cap: blames the stiffness or the main mass when one of them
/// was given and the duration was not (they set the cycles' rate), else the duration.
fn main_cycles(d: &Design, given: &dyn Fn(&str) -> bool, cycles: Estimate, per: &str) -> Result<(), Refusal> {
    let max_s = d.damper.duration_s * cycles.cap.max / cycles.value;
    let param = ["k", "main-mass"].into_iter().find(|n| !given("duration") && given(n)).unwrap_or("duration");
    over(cycles, param, Remedy::ShorterDuration { max_s }, per)
}

/// Refuses one run of `d` keeping `history_samples` history samples whose work
/// ([`design_run`]) is over a cap. `given` says which rows of the parameter table the user
/// gave (so the refusal names one they can change).
pub fn check_run(d: &ValidDesign, given: &dyn Fn(&str) -> bool, history_samples: usize) -> Result<(), Refusal> {
    let [steps, cycles, history] = design_run(d, history_samples);
    newmark(d, given, steps, "")?;
    main_cycles(d, given, cycles, "")?;
    over(history, SAMPLES_PARAM, Remedy::FewerSamples { max: history.cap.max }, "")
}

/// Refuses a design chart of `n_masses` × `n_gaps` cells of `d` whose work ([`sweep_cells`],
/// [`sweep_work`]) is over a cap.
pub fn check_sweep(
    d: &ValidDesign,
    given: &dyn Fn(&str) -> bool,
    n_masses: usize,
    n_gaps: usize,
) -> Result<(), Refusal> {
    let cells = sweep_cells(n_masses, n_gaps);
    over(cells, CELLS_PARAM, Remedy::FewerCells { max: cells.cap.max }, "")?;
    let n = n_masses * n_gaps;
    let [cell_seconds, steps, cycles] = sweep_work(d, n);
    let per = format!(" with {n} cells");
    let max_s = cell_seconds.cap.max / n as f64;
    over(cell_seconds, "duration", Remedy::ShorterDurationOrFewerCells { max_s }, &per)?;
    newmark(d, given, steps, &per)?;
    main_cycles(d, given, cycles, &per)
}

/// Refuses a study of `cells` cells (the product of every axis of `thud sweep --vary`, a
/// bifurcation's values, a basin map's grid) over the cap on cells ([`SWEEP_CELLS`]).
pub fn check_cells(cells: usize) -> Result<(), Refusal> {
    let e = Estimate { cap: SWEEP_CELLS, value: cells as f64 };
    over(e, CELLS_PARAM, Remedy::FewerCells { max: e.cap.max }, "")
}

/// Refuses a study of `cells` points whose summed work `total` (simulated seconds, Newmark
/// steps, main-mass cycles over every point, as [`sweep_work`] counts one) is over a cap;
/// `d` is the point with the longest run (the one the remedy names).
pub fn check_work_sum(d: &Design, given: &dyn Fn(&str) -> bool, cells: usize, total: [f64; 3]) -> Result<(), Refusal> {
    let [seconds, steps, cycles] = sweep_work(d, 1);
    let per = format!(" with {cells} cells");
    let seconds = Estimate { value: total[0], ..seconds };
    let max_s = d.damper.duration_s * seconds.cap.max / total[0].max(f64::MIN_POSITIVE);
    over(seconds, "duration", Remedy::ShorterDurationOrFewerCells { max_s }, &per)?;
    newmark(d, given, Estimate { value: total[1], ..steps }, &per)?;
    main_cycles(d, given, Estimate { value: total[2], ..cycles }, &per)
}

/// Refuses `cells` cells of `d` with `runs` ensemble runs each (a chart, a chart's part, or
/// one design with `cells` = 1) whose work ([`ensemble_work`]) is over a cap.
pub fn check_runs(d: &ValidDesign, given: &dyn Fn(&str) -> bool, cells: usize, runs: usize) -> Result<(), Refusal> {
    let [n, seconds, steps, cycles] = ensemble_work(d, cells, runs);
    over(n, RUNS_PARAM, Remedy::FewerRuns { max: n.cap.max, cells, runs }, "")?;
    let per = format!(" with {} runs", short(n.value));
    let max_s = seconds.cap.max / n.value;
    over(seconds, "duration", Remedy::ShorterDurationOrFewerRuns { max_s }, &per)?;
    newmark(d, given, steps, &per)?;
    main_cycles(d, given, cycles, &per)
}

/// The value of the parameter a refusal names, in the design, with its unit (for a message
/// about a parameter the user did not type): `(2, "s")` for the duration.
pub fn refused_value(d: &Design, param: &str) -> Option<(f64, &'static str)> {
    match (param, d.solver) {
        ("duration", _) => Some((d.damper.duration_s, "s")),
        ("dt", Solver::Newmark { dt_s }) => Some((dt_s, "s")),
        ("k", _) => Some((d.damper.stiffness_n_m, "N/m")),
        ("main-mass", _) => Some((d.damper.main_mass_kg, "kg")),
        _ => None,
    }
}

/// Runs in a merged chart of `cells` cells of `runs` ensemble runs each.
pub fn merged_runs(cells: usize, runs: usize) -> Estimate {
    Estimate { cap: MERGED_RUNS, value: cells as f64 * runs as f64 }
}

/// Bands of width `width_cm_s` between inclinations `e_min` and `e_max` (cm/s).
pub fn band_count(e_min_cm_s: f64, e_max_cm_s: f64, width_cm_s: f64) -> Estimate {
    let value = if e_max_cm_s >= e_min_cm_s {
        (e_max_cm_s / width_cm_s).floor() - (e_min_cm_s / width_cm_s).floor() + 1.0
    } else {
        0.0
    };
    Estimate { cap: BANDS, value }
}

/// Isolated contacts of a restitution curve over `n_masses` masses; with a target restitution
/// each mass also costs the bisection on c1 (≤ 60 doublings + ≤ 40 halvings to 1e-10).
pub fn restitution_contacts(n_masses: usize, with_target: bool) -> Estimate {
    let per_mass = if with_target { 101.0 } else { 1.0 };
    Estimate { cap: RESTITUTION_CONTACTS, value: n_masses as f64 * per_mass }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact;
    use crate::params::check_design;

    #[test]
    fn every_range_is_ordered_and_finite() {
        for r in RANGES.iter().chain(COUNTS) {
            assert!(r.min.is_finite() && r.max.is_finite() && r.min < r.max, "{}", r.param);
            assert!(!r.reason.is_empty() && !r.what.is_empty(), "{}", r.param);
        }
    }

    #[test]
    fn check_names_the_parameter_the_value_and_the_range() {
        let e = MASS.check_as("--mass", 1e308).unwrap_err().to_string();
        assert!(e.starts_with("invalid --mass: 1e308 kg is out of range"), "{e}");
        assert!(e.contains("0.0001 to 100 kg"), "{e}");
        let e = GAP.check(f64::NAN).unwrap_err().to_string();
        assert!(e.contains("invalid gap: NaN is not a finite number"), "{e}");
        assert_eq!(MASS.check(0.0405).unwrap(), 0.0405);
        assert!(STIFFNESS.check(0.0).is_ok() && STIFFNESS.check(-1.0).is_err());
        assert!(V0.check(-2.0).is_ok());
        assert!(GAP.check(10.0 * 1e-6).is_ok(), "10 µm as parsed is inside");
        assert!(GAP.check(0.99e-5).is_err());
    }

    #[test]
    fn counts_are_whole_numbers_in_range() {
        assert_eq!(POINTS.parse_count("--points", "1e3").unwrap(), 1000);
        assert_eq!(POINTS.parse_count("--points", " 50 ").unwrap(), 50);
        for bad in ["1", "2.5", "-3", "abc", "", "1e308", "NaN", "inf"] {
            let e = POINTS.parse_count("--points", bad).unwrap_err().to_string();
            assert!(e.starts_with("invalid --points: "), "{bad}: {e}");
        }
        assert_eq!(SHOW.parse_count("--show", "0").unwrap(), 0);
    }

    #[test]
    fn theta_depends_on_the_source() {
        assert!(theta_deg(Source::Quadrupole).check(-10.0).is_err());
        assert!(theta_deg(Source::Dipole).check(-10.0).is_ok());
        assert!(theta_deg(Source::Single).check(170.0).is_ok());
        assert!(theta_deg(Source::Dipole).check(170.0).is_err());
    }

    #[test]
    fn derived_radius_and_k_hz_stay_inside_their_ranges_at_the_corners() {
        // Every in-range mass and density gives an in-range radius ...
        for m in [MASS.min, MASS.max] {
            for rho in [DENSITY.min, DENSITY.max] {
                let a = contact::sphere_radius(m, rho);
                assert!(RADIUS.contains(a), "m {m} rho {rho}: a {a}");
            }
        }
        // ... and every material pair at every in-range radius an in-range K_HZ.
        for s in contact::MATERIALS {
            for p in contact::MATERIALS {
                for a in [RADIUS.min, RADIUS.max] {
                    let k = contact::hertz_stiffness(a, s, p);
                    assert!(K_HZ.contains(k), "{} on {} at {a}: {k}", s.name, p.name);
                }
            }
        }
    }

    #[test]
    fn newmark_work_is_duration_over_dt() {
        let mut d = Design { solver: Solver::Newmark { dt_s: 1e-12 }, ..Design::default() };
        let [steps, cycles, hist] = design_run(&d, 5);
        assert_eq!(steps.value, 2e12);
        assert!(steps.exceeded());
        assert_eq!(steps.describe(), "2e12 Newmark steps exceed the limit of 1e9");
        assert_eq!(short(1.336504617571976), "1.3365");
        assert_eq!(short(522761.01755734155), "5.22761e5");
        assert_eq!(short(0.0405), "0.0405");
        assert_eq!(short(-100.0), "-100");
        // Table 2: K 500 N/m, M 0.5 kg, C 0.05 N·s/m → ≈ 5.03 Hz, 2 s.
        assert!((cycles.value - 2.0 * (1000.0f64 - 0.0025).sqrt() / (2.0 * std::f64::consts::PI)).abs() < 1e-9);
        assert!(!cycles.exceeded() && !hist.exceeded());
        d.solver = Solver::Event;
        assert_eq!(design_run(&d, 0)[0].value, 0.0);
    }

    #[test]
    fn overdamped_or_springless_main_masses_have_no_cycles() {
        assert_eq!(cycles(1e6, 1.0, 0.0, 0.0), 0.0);
        assert_eq!(cycles(1e6, 1.0, 100.0, 1e3), 0.0);
    }

    #[test]
    fn other_estimates() {
        assert_eq!(wav_samples(2.0, 48_000.0).value, 96_000.0);
        assert!(wav_samples(1e308, 48_000.0).exceeded());
        assert!(sweep_cells(1000, 1000).exceeded() && !sweep_cells(20, 20).exceeded());
        let [cell_s, steps, cycles] = sweep_work(&Design::default(), 400);
        assert_eq!((cell_s.value, steps.value), (800.0, 0.0));
        assert!((cycles.value / 400.0 - design_run(&Design::default(), 0)[1].value).abs() < 1e-9);
        assert_eq!(band_count(0.1, 0.95, 0.2).value, 5.0);
        assert!(band_count(0.0, 1.0, 1e-308).exceeded());
        assert!(Estimate { cap: BANDS, value: f64::NAN }.exceeded());
        assert_eq!(restitution_contacts(20, true).value, 2020.0);
    }

    #[test]
    fn ensemble_work_is_the_sweep_work_times_the_runs() {
        let d = Design { solver: Solver::Newmark { dt_s: 1e-6 }, ..Design::default() };
        let [runs, seconds, steps, cycles] = ensemble_work(&d, 400, 16);
        assert_eq!((runs.value, seconds.value), (6400.0, 12_800.0));
        let [cell_s, cell_steps, cell_cycles] = sweep_work(&d, 400);
        assert_eq!(seconds.value, 16.0 * cell_s.value);
        assert_eq!(steps.value, 16.0 * cell_steps.value);
        assert!((cycles.value - 16.0 * cell_cycles.value).abs() < 1e-6);
        assert!(!runs.exceeded() && steps.exceeded(), "6400 Newmark runs of 2e6 steps are over the step cap");
        assert!(ensemble_work(&Design::default(), 1e5 as usize, 2)[0].exceeded());
        assert!(merged_runs(1000 * 1000, 16).exceeded() && !merged_runs(1000 * 1000, 1).exceeded());
        assert_eq!(ENSEMBLE.parse_count("--ensemble", "16").unwrap(), 16);
        assert!(ENSEMBLE.parse_count("--ensemble", "0").is_err());
    }

    #[test]
    fn forced_runs_count_forcing_cycles_and_settling() {
        let mut d = Design::default();
        d.damper.force_n = 1.0;
        d.damper.freq_hz = 50.0;
        // 2 s at 50 Hz: 100 forcing cycles, more than the ≈ 10 free ones.
        assert!((design_run(&d, 0)[1].value - 100.0).abs() < 1e-9);
        d.damper.settle = true;
        let settle = f64::from(crate::damper::SETTLE_PERIODS_MAX);
        assert!((design_run(&d, 0)[1].value - (100.0 + settle)).abs() < 1e-6);
        // Settling at 5 Hz may add 400 s: 4e9 Newmark steps at 1e-7 s.
        d.damper.freq_hz = 5.0;
        d.solver = Solver::Newmark { dt_s: 1e-7 };
        assert!((design_run(&d, 0)[0].value - (2.0 + settle / 5.0) * 1e7).abs() < 1.0);
        assert!(design_run(&d, 0)[0].exceeded(), "a settling Newmark run at 1e-7 s is over the cap");
        let [periods, _] = response_work(&Design::default(), &[3.0, 8.0], true);
        // 2 s at 3 Hz is 6 periods < 2N = 20; at 8 Hz 16 < 20: 2 × (20 + settle + the orbit
        // search's periods) per sweep, two sweeps.
        let search = f64::from(RESPONSE_SEARCH_PERIODS);
        assert!((periods.value - 4.0 * (20.0 + settle + search)).abs() < 1e-9);
    }

    #[test]
    fn a_refusal_names_the_parameter_the_user_can_change() {
        let mut d = Design::default();
        d.damper.stiffness_n_m = 1e10;
        let per_second = cycles(1.0, d.damper.main_mass_kg, 1e10, d.damper.damping_n_s_m);
        d.damper.duration_s = 2.0 * CYCLES.max / per_second;
        let d = d.check().unwrap();
        let param = |given: &[&str]| check_run(&d, &|n| given.contains(&n), 0).unwrap_err().param;
        assert_eq!(param(&["k"]), "k", "the stiffness typed alone sets the cycles' rate");
        assert_eq!(param(&["main-mass"]), "main-mass");
        assert_eq!(param(&["k", "duration"]), "duration");
        assert_eq!(param(&[]), "duration");
        let r = check_run(&d, &|_| false, 0).unwrap_err();
        assert!(matches!(r.remedy, Remedy::ShorterDuration { max_s } if max_s < d.damper.duration_s));
        let d = Design { solver: Solver::Newmark { dt_s: 1e-12 }, ..Design::default() }.check().unwrap();
        let r = check_run(&d, &|n| n == "duration", 0).unwrap_err();
        assert_eq!((r.param, r.estimate.cap.what), ("duration", NEWMARK_STEPS.what));
        assert_eq!(check_run(&d, &|_| false, 0).unwrap_err().param, "dt");
        let default = Design::default().check().unwrap();
        assert!(check_sweep(&default, &|_| false, 1000, 1000).is_err_and(|r| r.param == CELLS_PARAM));
        assert!(check_runs(&default, &|_| false, 1, 4).is_ok());
    }

    #[test]
    fn forcing_and_ball_start_are_range_checked() {
        let mut d = Design::default();
        d.damper.force_n = 1.0;
        assert!(check_design(&d).unwrap_err().to_string().starts_with("invalid freq: "), "a force needs a frequency");
        d.damper.freq_hz = 5.0;
        check_design(&d).unwrap();
        d.damper.ball_position_m = 0.02;
        assert!(check_design(&d).unwrap_err().to_string().starts_with("invalid ball-position: "), "on the wall");
        d.damper.ball_position_m = -0.0199;
        check_design(&d).unwrap();
        d.damper.steady_periods = 0;
        assert!(check_design(&d).unwrap_err().to_string().starts_with("invalid periods: "));
    }
}
