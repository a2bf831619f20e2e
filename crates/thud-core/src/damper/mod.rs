//! The single-unit impact damper (paper section 4, Eqs 25–27).
//!
//! A main mass `M` (kg) on a spring `K` (N/m) with a viscous damper `C` (N·s/m) carries an
//! enclosure of total clearance `d` (m, `d/2` each side of the centred ball) in which an impact
//! mass `m` (kg) moves freely. `x` is the main mass's displacement, `y` the ball's, `z = y − x`.
//!
//! - Flight (Eq 25): `M·x'' + C·x' + K·x = F(t)`, `m·y'' = 0`, with the harmonic force
//!   `F(t) = F0·cos(2π·f·t)` on the main mass of a forced run (`F0 = 0`, the default, is the
//!   paper's free decay; docs/model.md §6.1).
//! - Contact (Eq 26) when the penetration `δ = |z| − d/2 > 0`: force on the ball
//!   `−sign(z)·(K_HZ·δ^{3/2} + c1·δ')` with `δ' = sign(z)·z'`, equal and opposite on `M`;
//!   with `no_tension` the bracket is clamped at ≥ 0. The contact ends when `δ` returns to 0.
//! - Initial state: `x(0) = 0`, `x'(0) = v0`, `y(0) = y0`, `y'(0) = w0` (the paper: `y0 = w0 = 0`).
//! - A forced run reports its steady state over its last `N` forcing periods ([`SteadyMotion`],
//!   docs/model.md §6.2), and can run on past its duration until that settles.
//!
//! Two solvers: [`Solver::Event`] (exact flights, root-found contact instants, an integrator
//! inside contacts, by default the Sundman–Adams scheme checked against an adaptive
//! Dormand–Prince reference, [`ContactScheme`]; fast and step-size free) and [`Solver::Newmark`]
//! (the paper's uniform Newmark-β reference). SI units everywhere.

mod adams;
mod adams_tableau;
mod contact;
mod dop853;
mod dop853_tableau;
mod event;
mod flight;
mod forced;
mod integrator;
mod newmark;
mod periodic;
mod record;
mod roots;
#[cfg(test)]
mod scheme_checks;
mod steady;
mod stepper;
mod strobe;
mod sundman;

#[cfg(feature = "timing")]
pub use event::timing;
pub(crate) use periodic::{chained_jacobian, flow, Flowed};
pub(crate) use steady::{floating, Floating, Start};
pub use steady::{linear_amplitude_m, SteadyMotion, SETTLE_PERIODS_MAX};
pub(crate) use strobe::strobe;

use serde::{Deserialize, Serialize};

use crate::contact::{contact_duration, peak_approach};
use crate::error::{check_non_negative, check_positive, ThudError};

/// The design and the run: paper Table 2 notation, SI units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DamperParams {
    /// Main mass M (kg).
    pub main_mass_kg: f64,
    /// Spring stiffness K (N/m, ≥ 0).
    pub stiffness_n_m: f64,
    /// Viscous damping C (N·s/m, ≥ 0).
    pub damping_n_s_m: f64,
    /// Impact mass m (kg).
    pub impact_mass_kg: f64,
    /// Total clearance d (m): the ball has d/2 each side when centred.
    pub gap_m: f64,
    /// Hertz stiffness K_HZ (N/m^1.5); read also as `k_hz` (thud 0.1's spelling).
    #[serde(rename = "k_hz_n_m1_5", alias = "k_hz")]
    pub k_hz: f64,
    /// Contact damping c1 (N·s/m, ≥ 0).
    pub c1_n_s_m: f64,
    /// Clamp the contact force at ≥ 0 (a contact cannot pull).
    pub no_tension: bool,
    /// Initial velocity of the main mass v0 (m/s); any finite value.
    pub v0_m_s: f64,
    /// Simulated time (s).
    pub duration_s: f64,
    /// Amplitude F0 (N, ≥ 0) of the harmonic force `F0·cos(2π·f·t)` on the main mass; 0 (the
    /// default) is the paper's free decay.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub force_n: f64,
    /// Frequency f (Hz) of the harmonic force; must be > 0 when `force_n` > 0 (0: no force).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub freq_hz: f64,
    /// The ball's initial offset y0 (m) from the enclosure's centre, |y0| < d/2; 0: centred, as
    /// the paper.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub ball_position_m: f64,
    /// The ball's initial velocity w0 (m/s); 0: at rest, as the paper.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub ball_velocity_m_s: f64,
    /// Forcing periods N (≥ 1) of each steady-state window of a forced run (default 10).
    #[serde(default = "default_steady_periods", skip_serializing_if = "is_default_steady_periods")]
    pub steady_periods: u32,
    /// Run a forced run on past `duration_s`, N periods at a time, until the amplitude of
    /// successive windows changes by less than 1e-3 (at most [`SETTLE_PERIODS_MAX`] periods more).
    #[serde(default, skip_serializing_if = "is_false")]
    pub settle: bool,
    /// Run without the solvers' work caps ([`SOLVER_CAPS`]: `--no-limit`, Python's
    /// `no_limit`): how a run is carried out, not part of the design (never written or read).
    #[serde(skip)]
    pub no_limit: bool,
}

/// The steady-state window's length in forcing periods when none is given.
pub const DEFAULT_STEADY_PERIODS: u32 = 10;

fn default_steady_periods() -> u32 {
    DEFAULT_STEADY_PERIODS
}

fn is_default_steady_periods(n: &u32) -> bool {
    *n == DEFAULT_STEADY_PERIODS
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// The damped natural frequency (Hz) of a mass `main_mass_kg` on a spring `stiffness_n_m` with
/// a dashpot `damping_n_s_m` (Eq 25): √(K/M − (C/2M)²)/2π; 0 without a spring or when
/// overdamped.
#[must_use]
pub fn damped_frequency_hz(main_mass_kg: f64, stiffness_n_m: f64, damping_n_s_m: f64) -> f64 {
    let gamma = damping_n_s_m / (2.0 * main_mass_kg);
    let wd2 = stiffness_n_m / main_mass_kg - gamma * gamma;
    if wd2 > 0.0 {
        wd2.sqrt() / (2.0 * std::f64::consts::PI)
    } else {
        0.0
    }
}

fn is_false(b: &bool) -> bool {
    !*b
}

impl DamperParams {
    /// Paper Table 2 with the Fig 9 run: C 0.05 N·s/m, K 500 N/m, c1 20 N·s/m,
    /// K_HZ 5.6e8 N/m^1.5, M 0.5 kg, m 40.5 g, v0 2 m/s, d 4 cm, 2 s, no tension clamp off.
    pub fn table2() -> Self {
        DamperParams {
            main_mass_kg: 0.5,
            stiffness_n_m: 500.0,
            damping_n_s_m: 0.05,
            impact_mass_kg: 0.0405,
            gap_m: 0.04,
            k_hz: 5.6e8,
            c1_n_s_m: 20.0,
            no_tension: false,
            v0_m_s: 2.0,
            duration_s: 2.0,
            force_n: 0.0,
            freq_hz: 0.0,
            ball_position_m: 0.0,
            ball_velocity_m_s: 0.0,
            steady_periods: DEFAULT_STEADY_PERIODS,
            settle: false,
            no_limit: false,
        }
    }

    /// The main structure's natural frequency (Hz): its damped cycles per second of Eq 25,
    /// √(K/M − (C/2M)²)/2π (5.0329 Hz for Table 2), or 0 without a spring or when overdamped.
    /// The explorer's default forcing frequency and its response band both take this value.
    #[must_use]
    pub fn natural_frequency_hz(&self) -> f64 {
        damped_frequency_hz(self.main_mass_kg, self.stiffness_n_m, self.damping_n_s_m)
    }

    /// Whether a harmonic force drives the main mass (`force_n > 0`).
    #[must_use]
    pub fn forced(&self) -> bool {
        self.force_n > 0.0
    }

    /// Checks every parameter; the error names the command-line parameter.
    pub fn validate(&self) -> Result<(), ThudError> {
        check_positive("main-mass", self.main_mass_kg, "kg")?;
        check_non_negative("k", self.stiffness_n_m, "N/m")?;
        check_non_negative("c", self.damping_n_s_m, "N·s/m")?;
        check_positive("mass", self.impact_mass_kg, "kg")?;
        check_positive("gap", self.gap_m, "m")?;
        check_positive("k-hz", self.k_hz, "N/m^1.5")?;
        check_non_negative("c1", self.c1_n_s_m, "N·s/m")?;
        if !self.v0_m_s.is_finite() {
            return Err(ThudError::invalid("v0", format!("{} m/s; must be a finite number", self.v0_m_s)));
        }
        check_positive("duration", self.duration_s, "s")?;
        check_non_negative("force", self.force_n, "N")?;
        check_non_negative("freq", self.freq_hz, "Hz")?;
        if self.force_n > 0.0 && self.freq_hz == 0.0 {
            return Err(ThudError::invalid("freq", "0 Hz; a force needs a frequency > 0 (give --freq)"));
        }
        if !(self.ball_position_m.is_finite() && self.ball_position_m.abs() < 0.5 * self.gap_m) {
            return Err(ThudError::invalid(
                "ball-position",
                format!(
                    "{} m; the ball must start inside the clearance, |y0| < d/2 = {} m",
                    self.ball_position_m,
                    0.5 * self.gap_m
                ),
            ));
        }
        if !self.ball_velocity_m_s.is_finite() {
            return Err(ThudError::invalid(
                "ball-velocity",
                format!("{} m/s; must be a finite number", self.ball_velocity_m_s),
            ));
        }
        if self.steady_periods == 0 {
            return Err(ThudError::invalid("periods", "0; a steady-state window needs at least 1 period"));
        }
        Ok(())
    }
}

/// Which solver integrates the motion.
/// Written as the `--solver` flag spells it (`"event"`, `{"newmark": {"dt_s": …}}`); read also
/// as thud 0.1 wrote it (`"Event"`, `{"Newmark": …}`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Solver {
    /// Event-driven: exact flights, root-found contacts, adaptive DOPRI5 inside contacts.
    #[serde(alias = "Event")]
    Event,
    /// The paper's uniform Newmark-β (average acceleration) with time step `dt_s` (s).
    #[serde(alias = "Newmark")]
    Newmark { dt_s: f64 },
}

impl Solver {
    /// Newmark at the paper's step, 1e-7 s.
    pub fn newmark_default() -> Self {
        Solver::Newmark { dt_s: 1e-7 }
    }

    /// Checks the solver settings (`dt` finite and > 0).
    pub fn validate(&self) -> Result<(), ThudError> {
        match self {
            Solver::Event => Ok(()),
            Solver::Newmark { dt_s } => check_positive("dt", *dt_s, "s"),
        }
    }
}

/// One of the enclosure's two walls. The ball meets [`Wall::Upper`] when `z = y − x > 0` (it
/// is above its centred position relative to the main mass) and [`Wall::Lower`] when `z < 0`.
///
/// Written as the sign of `z` at contact, `1` or `-1`, in JSON and CSV ([`Display`](std::fmt::Display)
/// and serde both use that number; `{:+}` gives `+1`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(into = "i8", try_from = "i8")]
pub enum Wall {
    /// The wall on the `z < 0` side (written `-1`).
    Lower,
    /// The wall on the `z > 0` side (written `1`).
    Upper,
}

impl Wall {
    /// The wall on the side of a relative position `z` (m): `Upper` if `z > 0`, else `Lower`.
    #[must_use]
    pub fn facing(z_m: f64) -> Self {
        if z_m > 0.0 {
            Wall::Upper
        } else {
            Wall::Lower
        }
    }

    /// The wall's sign `s` in the equations (Eq 26): `+1.0` for `Upper`, `−1.0` for `Lower`;
    /// the penetration at wall `s` is `δ = s·z − d/2`.
    #[must_use]
    pub fn sign(self) -> f64 {
        match self {
            Wall::Lower => -1.0,
            Wall::Upper => 1.0,
        }
    }
}

impl From<Wall> for i8 {
    fn from(w: Wall) -> i8 {
        match w {
            Wall::Lower => -1,
            Wall::Upper => 1,
        }
    }
}

/// A number that is not a wall (−1 or 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("wall {0}; must be -1 (lower) or 1 (upper)")]
pub struct NotAWall(pub i8);

impl TryFrom<i8> for Wall {
    type Error = NotAWall;

    fn try_from(n: i8) -> Result<Self, NotAWall> {
        match n {
            -1 => Ok(Wall::Lower),
            1 => Ok(Wall::Upper),
            _ => Err(NotAWall(n)),
        }
    }
}

impl std::fmt::Display for Wall {
    /// The wall's number, `-1` or `1`, with the formatter's flags (`{:+}` gives `+1`).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Display::fmt(&i8::from(*self), f)
    }
}

/// One completed contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ImpactEvent {
    /// Contact onset time (s).
    pub t_s: f64,
    /// The wall the ball struck.
    pub wall: Wall,
    /// Incoming relative normal speed δ' at onset (m/s, > 0).
    pub u_in_m_s: f64,
    /// Outgoing relative normal speed −δ' at exit (m/s).
    pub u_out_m_s: f64,
    /// Contact end time (s).
    pub t_end_s: f64,
    /// Peak penetration δ (m).
    pub penetration_max_m: f64,
}

impl ImpactEvent {
    /// A contact that has just begun at `t_s` on `wall` with incoming speed `u_in_m_s` and
    /// penetration `penetration_m` so far; [`ImpactEvent::ended`] fills in its exit. Both
    /// solvers build their impacts this way.
    pub(crate) fn onset(t_s: f64, wall: Wall, u_in_m_s: f64, penetration_m: f64) -> Self {
        Self { t_s, wall, u_in_m_s, u_out_m_s: 0.0, t_end_s: 0.0, penetration_max_m: penetration_m }
    }

    /// The contact, ended at `t_end_s` with outgoing speed `u_out_m_s`.
    pub(crate) fn ended(self, t_end_s: f64, u_out_m_s: f64) -> Self {
        Self { u_out_m_s, t_end_s, ..self }
    }
}

/// A cycle maximum of the main mass's displacement (s, m): the `X_k`, `t_k` of the damping
/// inclination `e = (X1 − X2)/(t2 − t1)`, paper Eq 27.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Maximum {
    pub t_s: f64,
    pub x_m: f64,
}

/// One history sample (s, m, m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HistoryPoint {
    pub t_s: f64,
    pub x_m: f64,
    pub y_m: f64,
}

/// Energy bookkeeping (J): `initial + forcing_work = final_mechanical + dissipated_viscous +
/// dissipated_contact` up to the solver's error. Mechanical energy is
/// `½Mx'² + ½my'² + ½Kx² + (2/5)K_HZ·δ^{5/2}`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct EnergyLedger {
    pub initial_j: f64,
    pub final_mechanical_j: f64,
    pub dissipated_viscous_j: f64,
    pub dissipated_contact_j: f64,
    /// Work done on the main mass by the harmonic force, `∫F(t)·x' dt` (J); absent from JSON
    /// when there is no force.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub forcing_work_j: f64,
}

/// Total in-contact integrator steps the event solver allows per run (a work cap: past it the
/// run stops with what it has and says so with [`Truncation::ContactSteps`]).
pub const CONTACT_STEP_CAP: usize = 400_000;
/// Total contact-search iterations (conservative advancement in flight) the event solver allows
/// per run ([`Truncation::FlightSearch`] past it).
pub const FLIGHT_SEARCH_CAP: usize = 2_000_000;
/// Grid steps the Newmark solver takes at most per run ([`Truncation::NewmarkSteps`] past it): a
/// backstop above any run worth waiting for (at about 30 ns a step, some five minutes; the paper's
/// 2 s at 1e-7 s is 2e7 steps), so that a vanishing `dt` cannot loop for ever.
pub const NEWMARK_STEP_CAP: u64 = 10_000_000_000;

/// Steps of [`NEWMARK_STEP_CAP`]'s grid (16 at a time) the Newmark solver takes at most to carry
/// a contact still open at a run's end on to its end (for the next run of a continuation).
pub const NEWMARK_FINISH_CAP: u64 = 16_000_000;

/// One work cap of the solvers: what it counts, its value, and why it is there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverCap {
    pub what: &'static str,
    pub max: f64,
    pub basis: &'static str,
}

/// The solvers' own work caps per run, as `thud limits` lists them: `--no-limit` lifts them,
/// and a run one stops is reported `truncated` ([`Truncation`]) by every output.
pub const SOLVER_CAPS: [SolverCap; 4] = [
    SolverCap {
        what: "event solver: in-contact steps",
        max: CONTACT_STEP_CAP as f64,
        basis: "a backstop against an endless chattering contact; a long rattle reaches it too (the forced rattle at 7.7236 Hz after about 6 000 impacts)",
    },
    SolverCap {
        what: "event solver: contact searches",
        max: FLIGHT_SEARCH_CAP as f64,
        basis: "a backstop against endless grazing flights",
    },
    SolverCap {
        what: "Newmark steps of one run",
        max: NEWMARK_STEP_CAP as f64,
        basis: "a backstop above any run worth waiting for (≈ 30 ns a step: some five minutes)",
    },
    SolverCap {
        what: "Newmark steps finishing a contact",
        max: NEWMARK_FINISH_CAP as f64,
        basis: "a contact still open at a run's end is carried on to its end for the next run of a continuation",
    },
];

/// Why a run stopped before its duration at a solver work cap.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Truncation {
    /// The event solver's in-contact steps ran out ([`CONTACT_STEP_CAP`]), e.g. a ball that
    /// rattles for a very long run, or an endless chattering contact.
    ContactSteps,
    /// The event solver's contact search ran out ([`FLIGHT_SEARCH_CAP`]): endless grazing flights.
    FlightSearch,
    /// The Newmark solver took [`NEWMARK_STEP_CAP`] steps.
    NewmarkSteps,
}

impl Truncation {
    /// One line for a summary: which cap stopped the run.
    #[must_use]
    pub fn describe(self) -> &'static str {
        match self {
            Truncation::ContactSteps => "the event solver's work cap (in-contact steps) stopped the run",
            Truncation::FlightSearch => "the event solver's work cap (contact searches) stopped the run",
            Truncation::NewmarkSteps => "the Newmark solver's work cap (time steps) stopped the run",
        }
    }
}

/// The result of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Run {
    /// Completed contacts in time order (a contact cut by the end of the run is not listed).
    pub impacts: Vec<ImpactEvent>,
    /// Cycle maxima of x: the largest positive x between successive upward zero crossings.
    pub maxima: Vec<Maximum>,
    /// Largest |z'| (m/s) over the whole run including t = 0.
    pub zdot_abs_max_m_s: f64,
    pub energy: EnergyLedger,
    /// Uniform samples over [0, duration]; empty unless asked for.
    pub history: Vec<HistoryPoint>,
    /// Time reached (s): the duration unless cancelled or truncated.
    pub final_time_s: f64,
    pub cancelled: bool,
    /// Set when a solver work cap stopped the run before its duration (then `final_time_s` is
    /// where it stopped). Absent from JSON when the run was not truncated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truncated: Option<Truncation>,
    /// The steady state of a forced run over its last window (absent without a force).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steady: Option<SteadyMotion>,
}

/// Run options: history sampling and cooperative cancellation.
#[derive(Debug, Clone, Copy, Default)]
pub struct RunOptions<'a> {
    /// Number of uniform history samples over [0, duration] (0: none).
    pub history_samples: usize,
    /// When it reads true the run stops and returns what it has, with `cancelled: true`
    /// (checked between impacts by the event solver, every 4096 steps by Newmark).
    pub cancel: Option<&'a std::sync::atomic::AtomicBool>,
}

/// Simulates one design with the chosen solver. A forced design (`force_n > 0`) also gets its
/// steady state ([`Run::steady`]), and with `settle` runs on past its duration until that settles.
pub fn simulate(p: &DamperParams, solver: Solver, opts: &RunOptions) -> Result<Run, ThudError> {
    simulate_with(p, solver, opts, ContactScheme::default())
}

/// How the event solver integrates a contact (docs/model.md §11). The shipped engine has the
/// reference and the default; the research schemes (`SundmanTaylor`, `SundmanDop853`), kept
/// reproducible for the measurements of docs/model.md §11, exist with the cargo feature
/// `research` only (the tests, benchmarks and examples turn it on).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum ContactScheme {
    /// Adaptive Dormand–Prince 5(4) on Eq 26 in `t` and `δ` as written; maxima and `|z'|` at
    /// the step ends. The reference the other schemes are checked against, and the scheme of a
    /// design with `no_tension`.
    DormandPrince,
    /// Experimental: Eq 26 in `σ = √δ` against the Sundman time `dθ = dt/σ`, where every
    /// right-hand side is a polynomial and the solution is analytic across the onset and the
    /// release, integrated by Taylor series of order 16 (about 13 steps a contact, release
    /// speeds exact to ~1e-12 where the Hertz law has a closed form); maxima and `|z'|` extrema
    /// located on the series. Slower than the reference (docs/model.md §11); a design with
    /// `no_tension` falls back to [`ContactScheme::DormandPrince`].
    #[cfg(feature = "research")]
    SundmanTaylor,
    /// The same Sundman form integrated by the Runge–Kutta pair DOP853 (order 8, dense output
    /// of order 7; Hairer, Nørsett & Wanner): about 15 steps a contact, each a few products a
    /// stage, so several times cheaper than the reference; maxima and `|z'|` extrema located on
    /// the dense output. A design with `no_tension` falls back to
    /// [`ContactScheme::DormandPrince`].
    #[cfg(feature = "research")]
    SundmanDop853,
    /// The same Sundman form integrated by an Adams–Bashforth–Moulton pair of order 12/13 on
    /// even steps (about 58 a Hertz contact, two evaluations a step), started from the Taylor
    /// series at the onset, and handed over to DOP853 (`SundmanDop853`'s pair) where the
    /// motion is not a Hertz hump (a ball pressed against a wall) and for the rest of a contact
    /// cut by a run's stretch; maxima and `|z'|` extrema located on the corrector's polynomial.
    /// The fastest scheme (2.3× the reference on the Fig 9 design, release speeds within ~1e-8
    /// m/s of it) and the default (docs/model.md §11). A design with `no_tension` falls back to
    /// [`ContactScheme::DormandPrince`].
    #[default]
    SundmanAdams,
}

impl ContactScheme {
    /// The scheme a design's contacts are integrated by: under "no tension" every contact is
    /// the reference's (the Taylor scheme does not yet handle the clamp's switches reliably, and
    /// the DOP853 and Adams schemes' rates have no clamp: their even or smooth steps would
    /// straddle its kinks).
    pub(crate) fn in_use(self, no_tension: bool) -> Self {
        if no_tension {
            ContactScheme::DormandPrince
        } else {
            self
        }
    }
}

/// [`simulate`] with the event solver's contact integrator chosen (`scheme`; Newmark has none
/// and ignores it).
///
/// # Errors
/// As [`simulate`].
pub fn simulate_with(
    p: &DamperParams,
    solver: Solver,
    opts: &RunOptions,
    scheme: ContactScheme,
) -> Result<Run, ThudError> {
    p.validate()?;
    solver.validate()?;
    Ok(steady::run(p, solver, opts, &Start::of(p), false, scheme).0)
}

/// Simulates `p` from `start` (a continuation's state and force phase); with `want_end`, also
/// the state the run ended in, off the record (a contact still open is finished first).
pub(crate) fn run_from(
    p: &DamperParams,
    solver: Solver,
    opts: &RunOptions,
    start: &Start,
    want_end: bool,
) -> Result<(Run, Option<Start>), ThudError> {
    p.validate()?;
    solver.validate()?;
    Ok(steady::run(p, solver, opts, start, want_end, ContactScheme::default()))
}

/// x(t) (m) of the same structure with no damper (closed form, Eq 25 alone): the Fig 9
/// comparison curve, from x(0) = 0, x'(0) = v0, under the design's force if it has one.
pub fn free_response(p: &DamperParams, t_s: f64) -> f64 {
    let osc = flight::Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    if p.forced() {
        let load = forced::Harmonic::new(p.force_n, p.main_mass_kg, p.freq_hz, 0.0);
        return forced::Forced::new(osc, load).advance(0.0, 0.0, p.v0_m_s, t_s).0;
    }
    osc.advance(0.0, p.v0_m_s, t_s).0
}

/// The cycle maxima `X_k` (s, m) of [`free_response`] over `[0, duration]`, by the rule of
/// [`Run::maxima`] (the largest positive maximum between upward zero crossings): the envelope of
/// the same structure without the damper, to set beside the damped run's (Eq 27).
pub fn free_maxima(p: &DamperParams) -> Vec<Maximum> {
    let osc = flight::Oscillator::new(p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    let mut rec = record::Recorder::new(0, p.duration_s);
    osc.for_each_event(0.0, p.v0_m_s, p.duration_s, |kind, t| match kind {
        flight::FlightEvent::MaxX => rec.local_max(t, osc.advance(0.0, p.v0_m_s, t).0),
        flight::FlightEvent::UpCross => rec.up_cross(),
        flight::FlightEvent::ZeroAccel => {}
    });
    rec.up_cross();
    rec.maxima
}

/// One isolated contact between ball `m` and main mass `M`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SingleContact {
    /// Outgoing relative speed (m/s); 0 if the contact never ended.
    pub u_out_m_s: f64,
    /// Contact duration (s).
    pub duration_s: f64,
    /// Peak penetration (m).
    pub penetration_max_m: f64,
}

/// One isolated contact between ball `m` (kg) and main mass `big_m` (kg), no spring: relative
/// coordinate `δ'' = −K*·(K_HZ·δ^{3/2} + c1·δ')`, `K* = (m+M)/(m·M)` (Eq 8, 26), contact damping
/// `c1` (N·s/m), with or without tension. Inputs are assumed positive and finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsolatedContact {
    pub m: f64,
    pub big_m: f64,
    pub k_hz: f64,
    pub c1: f64,
    pub no_tension: bool,
}

impl IsolatedContact {
    fn sys(&self) -> contact::Sys {
        let p = DamperParams {
            main_mass_kg: self.big_m,
            stiffness_n_m: 0.0,
            damping_n_s_m: 0.0,
            impact_mass_kg: self.m,
            gap_m: 0.02,
            k_hz: self.k_hz,
            c1_n_s_m: self.c1,
            no_tension: self.no_tension,
            v0_m_s: 0.0,
            duration_s: 1.0,
            ..DamperParams::table2()
        };
        contact::Sys::new(&p)
    }

    /// The contact at approach speed `u0` (m/s) by the contact scheme `scheme` (a design with
    /// `no_tension` falls back to [`ContactScheme::DormandPrince`], as in a run).
    #[must_use]
    pub fn by(&self, scheme: ContactScheme, u0: f64) -> SingleContact {
        let sys = self.sys();
        let tau = contact_duration(peak_approach(u0, sys.kstar, self.k_hz), u0);
        let mut budget = 200_000;
        let y0 = contact::State::new(0.0, 0.0, 0.0, u0, 0.0, 0.0);
        let start = contact::ContactStart::free(&sys, y0, 1e4 * tau);
        let e = event::onset_contact(scheme.in_use(self.no_tension), start, &mut budget, contact::Unobserved);
        SingleContact {
            u_out_m_s: if e.outcome == contact::ContactOutcome::Separated { -e.y[3] } else { 0.0 },
            duration_s: e.t,
            penetration_max_m: e.pen_max,
        }
    }

    /// The contact at approach speed `u0` (m/s) by the Newmark reference with step `dt_s` (s).
    #[must_use]
    pub fn newmark(&self, u0: f64, dt_s: f64) -> SingleContact {
        newmark::single(&self.sys(), u0, dt_s)
    }
}

/// The [`IsolatedContact`] at approach speed `u0` (m/s) by the event solver's default contact
/// scheme ([`ContactScheme::SundmanAdams`]; [`ContactScheme::DormandPrince`] with `no_tension`),
/// so that the restitution it gives is the one a run's contact has.
pub fn single_contact(m: f64, big_m: f64, k_hz: f64, c1: f64, no_tension: bool, u0: f64) -> SingleContact {
    IsolatedContact { m, big_m, k_hz, c1, no_tension }.by(ContactScheme::default(), u0)
}

/// The contact damping c1 (N·s/m) that gives restitution `r = u_out/u0` for one isolated contact
/// (bisection on [`single_contact`]; R falls as c1 rises). `r` must be in (0, 1].
pub fn c1_for_restitution(m: f64, big_m: f64, k_hz: f64, no_tension: bool, u0: f64, r: f64) -> Result<f64, ThudError> {
    check_positive("mass", m, "kg")?;
    check_positive("main-mass", big_m, "kg")?;
    check_positive("k-hz", k_hz, "N/m^1.5")?;
    check_positive("u0", u0, "m/s")?;
    if !(r.is_finite() && r > 0.0 && r <= 1.0) {
        return Err(ThudError::invalid("restitution", format!("{r}; must be in (0, 1]")));
    }
    if r == 1.0 {
        return Ok(0.0);
    }
    let rest = |c1: f64| single_contact(m, big_m, k_hz, c1, no_tension, u0).u_out_m_s / u0;
    // Scale: critical-like damping of the linearised contact, c ~ sqrt(k_lin / K*).
    let kstar = (m + big_m) / (m * big_m);
    let amax = peak_approach(u0, kstar, k_hz);
    let c_scale = (1.5 * k_hz * amax.sqrt() / kstar).sqrt();
    let (mut lo, mut hi) = (0.0, c_scale * 0.1);
    let mut n = 0;
    while rest(hi) > r {
        lo = hi;
        hi *= 2.0;
        n += 1;
        if n > 60 {
            return Err(ThudError::RestitutionUnreachable { restitution: r });
        }
    }
    // Bisection to a relative width of 1e-10 (R is smooth and monotone in c1).
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if hi - lo <= 1e-10 * hi {
            break;
        }
        if rest(mid) > r {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walls_are_written_as_the_sign_of_z() {
        assert_eq!(serde_json::to_string(&[Wall::Lower, Wall::Upper]).unwrap(), "[-1,1]");
        assert_eq!(serde_json::from_str::<Wall>("-1").unwrap(), Wall::Lower);
        assert!(serde_json::from_str::<Wall>("0").is_err());
        assert_eq!(format!("{} {:+}", Wall::Lower, Wall::Upper), "-1 +1");
        assert_eq!(Wall::facing(-0.01).sign(), -1.0);
        assert_eq!(Wall::facing(0.01), Wall::Upper);
    }

    /// A ball at rest off-centre at y0: the main mass flies free (Eq 25 alone) until it has
    /// closed the lower gap, x = y0 + d/2. Both solvers' first impact is at that instant of
    /// the closed form, found here by bisection.
    #[test]
    fn an_off_centre_ball_is_first_struck_where_the_free_flight_closes_its_gap() {
        let p = DamperParams { ball_position_m: 0.005, duration_s: 0.1, ..DamperParams::table2() };
        let reach = p.ball_position_m + 0.5 * p.gap_m;
        let (mut lo, mut hi) = (0.0, 0.25 * 2.0 * std::f64::consts::PI / (p.stiffness_n_m / p.main_mass_kg).sqrt());
        assert!(free_response(&p, hi) > reach, "the swing reaches the ball");
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if free_response(&p, mid) < reach {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        for solver in [Solver::Event, Solver::Newmark { dt_s: 1e-7 }] {
            let first = simulate(&p, solver, &RunOptions::default()).unwrap().impacts[0];
            assert_eq!(first.wall, Wall::Lower, "{solver:?}");
            assert!((first.t_s - lo).abs() < 1e-9, "{solver:?}: {} vs {lo}", first.t_s);
        }
        let centred = simulate(&DamperParams { ball_position_m: 0.0, ..p }, Solver::Event, &RunOptions::default());
        assert!(centred.unwrap().impacts[0].t_s < lo, "a centred ball is struck sooner");
    }

    #[test]
    fn the_ball_must_start_inside_the_clearance() {
        for y0 in [0.02, -0.02, 0.5, f64::NAN] {
            let p = DamperParams { ball_position_m: y0, ..DamperParams::table2() };
            assert!(p.validate().unwrap_err().to_string().starts_with("invalid ball-position: "), "{y0}");
        }
        assert!(DamperParams { ball_position_m: -0.0199, ..DamperParams::table2() }.validate().is_ok());
    }

    #[test]
    fn a_run_cut_by_a_work_cap_says_so() {
        // A violent, very long run: the in-contact step cap stops it long before 1e6 s.
        let p = DamperParams { duration_s: 1e6, v0_m_s: 200.0, ..DamperParams::table2() };
        let run = simulate(&p, Solver::Event, &RunOptions::default()).unwrap();
        assert_eq!(run.truncated, Some(Truncation::ContactSteps));
        assert!(!run.cancelled && run.final_time_s > 0.0 && run.final_time_s < p.duration_s, "{}", run.final_time_s);
        let json = serde_json::to_string(&run).unwrap();
        assert!(json.contains(r#""truncated":"contact_steps""#));
        // A run that reaches its end says nothing.
        let full = simulate(&DamperParams::table2(), Solver::Event, &RunOptions::default()).unwrap();
        assert_eq!(full.truncated, None);
        assert!(!serde_json::to_string(&full).unwrap().contains("truncated"));
    }
}

#[cfg(test)]
mod free_tests {
    use super::*;

    #[test]
    fn free_maxima_are_the_peaks_of_the_free_response_and_decay_as_exp_minus_gamma_t() {
        let p = DamperParams::table2();
        let maxima = free_maxima(&p);
        // ω0 = √(K/M) ≈ 31.6 rad/s: about 10 cycles in 2 s.
        assert!((9..=11).contains(&maxima.len()), "{}", maxima.len());
        let gamma = p.damping_n_s_m / (2.0 * p.main_mass_kg);
        for m in &maxima {
            let x = free_response(&p, m.t_s);
            assert!((x - m.x_m).abs() < 1e-15 && x > 0.0);
            assert!(free_response(&p, m.t_s - 1e-5) < x && free_response(&p, m.t_s + 1e-5) < x, "{m:?}");
        }
        for w in maxima.windows(2) {
            let ratio = w[1].x_m / w[0].x_m;
            assert!((ratio - (-gamma * (w[1].t_s - w[0].t_s)).exp()).abs() < 1e-12, "{ratio}");
        }
    }
}
