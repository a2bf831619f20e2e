//! Research-grade dynamics of a forced impact damper (docs/model.md §6.5):
//! the bifurcation diagram over any numeric parameter, the type of each orbit, the impact map
//! (the Poincaré section on impacts) and the basins of attraction over the ball's start.
//!
//! Every run is the event solver's forced run ([`crate::damper`]), sampled stroboscopically:
//! after `transient` forcing periods, the state at every whole and half period of the force
//! over `periods` periods, and every impact with its phase, wall and relative speed.
//!
//! **The orbit's type** ([`classify`]): with `T` the forcing period, the smallest `n ≤`
//! [`MAX_PERIOD`] with `x((k+n)T) = x(kT)` and `x'((k+n)T) = x'(kT)` for every sample `k`
//! (within [`PERIODIC_TOLERANCE`] of the samples' largest |x| and |x'|) makes the orbit
//! periodic of period `nT`, with `m` impacts per `n` periods (the same in every block of `n`
//! periods), and symmetric when `x(t + T/2) = −x(t)`, `x'(t + T/2) = −x'(t)` at every sample.
//! Otherwise the 0–1 test for chaos (Gottwald & Melbourne 2004, 2009; [`zero_one_test`]) on
//! the samples `x(kT)` gives `K`; `K ≥` [`CHAOS_K`] is "chaotic", anything else "not settled"
//! (a transient still decaying, a quasi-periodic motion, or a period longer than
//! [`MAX_PERIOD`]).
//!
//! Everything is parallel on rayon's global pool and cancellable, as [`crate::design::sweep`].

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::damper::{self, Start, Wall};
use crate::design::{Design, ValidDesign};
use crate::error::ThudError;
use crate::limits::{self, Estimate, Refusal, Remedy};
use crate::params::Spelling;
use crate::response::Direction;
use crate::study::{Axis, Grid, Vary};
use crate::verdict::{self, find_period, Verdict};

/// Forcing periods run before sampling when none are given: enough for the designs of the
/// presets (light structural damping, the ball's impacts damping most) to reach their orbit.
pub const DEFAULT_TRANSIENT_PERIODS: u32 = 200;
/// Forcing periods sampled when none are given.
pub const DEFAULT_PERIODS: u32 = 100;
pub use crate::verdict::{MAX_PERIOD, PERIODIC_TOLERANCE};
/// The 0–1 test's K at or above which a motion counts as chaotic (Gottwald & Melbourne: K ≈ 1
/// for chaos, ≈ 0 for regular motion).
pub const CHAOS_K: f64 = 0.8;
/// The fewest samples the 0–1 test is run on (Gottwald & Melbourne use thousands; below 50
/// its K is no more than noise).
pub const MIN_TEST_SAMPLES: usize = 50;

/// How long each run is: the transient, then the sampled periods.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Settings {
    /// Forcing periods run before sampling.
    pub transient_periods: u32,
    /// Forcing periods sampled.
    pub periods: u32,
}

impl Default for Settings {
    fn default() -> Self {
        Settings { transient_periods: DEFAULT_TRANSIENT_PERIODS, periods: DEFAULT_PERIODS }
    }
}

/// One stroboscopic sample: the state at `t = kT` after the transient (the force's phase 0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    /// k: forcing periods after the transient.
    pub period: u32,
    /// Main-mass displacement x(kT) (m).
    pub x_m: f64,
    /// Main-mass velocity x'(kT) (m/s).
    pub v_m_s: f64,
    /// The ball relative to the enclosure's centre, z = y − x (m).
    pub z_m: f64,
    /// z' (m/s).
    pub zdot_m_s: f64,
}

/// One impact after the transient.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ImpactPoint {
    /// The forcing period it falls in (k, after the transient).
    pub period: u32,
    /// The force's phase at onset, as a fraction of the period (0 to 1).
    pub phase: f64,
    /// The wall struck (−1 or 1).
    pub wall: Wall,
    /// Relative normal speed at onset (m/s).
    pub u_in_m_s: f64,
    /// Relative normal speed at exit (m/s).
    pub u_out_m_s: f64,
}

/// What an orbit is: the one verdict on a forced motion ([`crate::verdict`]); [`classify`]
/// gives the pattern of its samples, and a run cut short is [`Verdict::Truncated`].
pub type Orbit = Verdict;

/// One run sampled after its transient, and what its orbit is.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OrbitRun {
    pub orbit: Orbit,
    /// Largest |x| over the sampled periods (m).
    pub amplitude_m: f64,
    pub samples: Vec<Sample>,
    pub impacts: Vec<ImpactPoint>,
    /// Whether a work cap or cancellation stopped the run before its end (then the orbit is
    /// "truncated").
    pub truncated: bool,
}

/// Refuses a design that has no force: a study of orbits needs one. `force` names the force's
/// parameter as the front end calls it.
fn check_forced(d: &Design, force: &str) -> Result<(), ThudError> {
    if !d.damper.forced() {
        return Err(ThudError::invalid(
            force,
            "0 N: orbits need a harmonic force; give a force F0 (N) and a frequency",
        ));
    }
    if d.solver != crate::damper::Solver::Event {
        return Err(ThudError::invalid(
            "solver",
            "newmark: orbits are sampled with the event solver; use --solver event",
        ));
    }
    Ok(())
}

/// Runs `d` from `start` ([`Settings`]) and classifies its orbit; also the end state.
fn run_orbit(d: &Design, start: &Start, s: Settings, cancel: Option<&AtomicBool>) -> (OrbitRun, Start) {
    let (run, end, _) = run_orbit_halves(d, start, s, cancel);
    (run, end)
}

/// [`run_orbit`], with the samples half a period after each `x(kT)`: `(x, x')` at `kT + T/2`.
fn run_orbit_halves(
    d: &Design,
    start: &Start,
    s: Settings,
    cancel: Option<&AtomicBool>,
) -> (OrbitRun, Start, Vec<[f64; 2]>) {
    let st = damper::strobe(&d.damper, start, s.transient_periods, s.periods, cancel);
    let tau = std::f64::consts::TAU;
    let samples: Vec<Sample> = st
        .samples
        .iter()
        .step_by(2)
        .enumerate()
        .map(|(k, s)| Sample {
            period: u32::try_from(k).unwrap_or(u32::MAX),
            x_m: s[0],
            v_m_s: s[1],
            z_m: s[2],
            zdot_m_s: s[3],
        })
        .collect();
    let halves: Vec<[f64; 2]> = st.samples.iter().skip(1).step_by(2).map(|s| [s[0], s[1]]).collect();
    let impacts: Vec<ImpactPoint> = st
        .impacts
        .iter()
        .map(|(i, theta, period)| ImpactPoint {
            period: *period,
            phase: theta / tau,
            wall: i.wall,
            u_in_m_s: i.u_in_m_s,
            u_out_m_s: i.u_out_m_s,
        })
        .collect();
    let cut = if st.cancelled { Some(None) } else { st.truncated.map(Some) };
    let truncated = cut.is_some();
    let pattern = if truncated { Orbit::NotSettled { k: None } } else { classify(&samples, &halves, st.impacts.len()) };
    // A sampled orbit has no settling test of its own: neither periodic nor chaotic is "not
    // settled".
    let orbit = verdict::judge(cut, pattern, None);
    (OrbitRun { orbit, amplitude_m: st.amplitude_m, samples, impacts, truncated }, st.end, halves)
}

/// The orbit's type from its stroboscopic samples `x(kT)`, `x'(kT)`, the samples half a period
/// later (`halves`) and the number of impacts over the sampled periods (see the module
/// documentation).
#[must_use]
pub fn classify(samples: &[Sample], halves: &[[f64; 2]], impacts: usize) -> Orbit {
    let n = samples.len();
    if n == 0 {
        return Orbit::NotSettled { k: None };
    }
    let sx = samples.iter().map(|s| s.x_m.abs()).chain(halves.iter().map(|h| h[0].abs())).fold(0.0, f64::max);
    let sv = samples.iter().map(|s| s.v_m_s.abs()).chain(halves.iter().map(|h| h[1].abs())).fold(0.0, f64::max);
    let (tx, tv) = (PERIODIC_TOLERANCE * sx.max(f64::MIN_POSITIVE), PERIODIC_TOLERANCE * sv.max(f64::MIN_POSITIVE));
    let same = |a: &Sample, b: &Sample| (a.x_m - b.x_m).abs() <= tx && (a.v_m_s - b.v_m_s).abs() <= tv;
    if let Some((m, p)) = find_period(n, impacts, |k, l| same(&samples[k], &samples[l])) {
        let symmetric = p == 1
            && halves.len() == n
            && samples.iter().zip(halves).all(|(s, h)| (s.x_m + h[0]).abs() <= tx && (s.v_m_s + h[1]).abs() <= tv);
        return Orbit::periodic(m, p, symmetric);
    }
    if n < MIN_TEST_SAMPLES {
        return Orbit::NotSettled { k: None };
    }
    let phi: Vec<f64> = samples.iter().map(|s| s.x_m).collect();
    let k = zero_one_test(&phi);
    if k >= CHAOS_K {
        Orbit::Chaotic { k }
    } else {
        Orbit::NotSettled { k: Some(k) }
    }
}

/// The 0–1 test for chaos of Gottwald & Melbourne (Proc. R. Soc. A 460 (2004) 603–611; the
/// correlation method of SIAM J. Appl. Dyn. Syst. 8 (2009) 129–145) on the observable `phi`
/// (N samples): for each of 100 frequencies `c` in (π/5, 4π/5) the translation variables
/// `p(n) = Σ_{j≤n} φ_j cos jc`, `q(n) = Σ_{j≤n} φ_j sin jc`, their mean square displacement
/// `M(n)` for `n ≤ N/10` less the oscillatory term `(Eφ)²(1 − cos nc)/(1 − cos c)`, and
/// `K_c` the correlation of that with `n`; K is the median of the `K_c`. K ≈ 1: chaotic;
/// K ≈ 0: regular. The frequencies are a golden-ratio sequence (deterministic, no random
/// numbers in the engine), as evenly spread as the random ones the authors use.
#[must_use]
pub fn zero_one_test(phi: &[f64]) -> f64 {
    let n_all = phi.len();
    let n_cut = n_all / 10;
    if n_cut < 3 {
        return 0.0;
    }
    let mean = phi.iter().sum::<f64>() / n_all as f64;
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    let pi = std::f64::consts::PI;
    let mut ks: Vec<f64> = (1..=100)
        .map(|j| {
            let c = pi / 5.0 + 3.0 * pi / 5.0 * (f64::from(j) * golden).fract();
            let (mut p, mut q) = (Vec::with_capacity(n_all), Vec::with_capacity(n_all));
            let (mut sp, mut sq) = (0.0, 0.0);
            for (i, f) in phi.iter().enumerate() {
                let a = (i + 1) as f64 * c;
                sp += f * a.cos();
                sq += f * a.sin();
                p.push(sp);
                q.push(sq);
            }
            let d: Vec<f64> = (1..=n_cut)
                .map(|n| {
                    let m = (0..n_all - n).map(|i| (p[i + n] - p[i]).powi(2) + (q[i + n] - q[i]).powi(2)).sum::<f64>()
                        / (n_all - n) as f64;
                    m - mean * mean * (1.0 - (n as f64 * c).cos()) / (1.0 - c.cos())
                })
                .collect();
            correlation(&d)
        })
        .collect();
    ks.sort_by(f64::total_cmp);
    let mid = ks.len() / 2;
    let k = if ks.len().is_multiple_of(2) { 0.5 * (ks[mid - 1] + ks[mid]) } else { ks[mid] };
    if k.is_finite() {
        k
    } else {
        0.0
    }
}

/// The correlation coefficient of `d` with its index 1, 2, …, n (0 when `d` is constant).
fn correlation(d: &[f64]) -> f64 {
    let n = d.len() as f64;
    let mx = f64::midpoint(n, 1.0);
    let md = d.iter().sum::<f64>() / n;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (i, v) in d.iter().enumerate() {
        let (dx, dy) = ((i + 1) as f64 - mx, v - md);
        sxy += dx * dy;
        sxx += dx * dx;
        syy += dy * dy;
    }
    if syy <= 0.0 || sxx <= 0.0 {
        return 0.0;
    }
    sxy / (sxx * syy).sqrt()
}

/// The impact map of `d` (the Poincaré section on impacts): one run from the design's own
/// start, sampled after its transient. `force` names the force's parameter (for a design
/// without one).
pub fn impact_map(
    d: &ValidDesign,
    s: Settings,
    force: &str,
    cancel: Option<&AtomicBool>,
) -> Result<OrbitRun, ThudError> {
    check_forced(d, force)?;
    let run = run_orbit(d, &Start::of(&d.damper), s, cancel).0;
    if run.truncated && cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
        return Err(ThudError::Cancelled);
    }
    Ok(run)
}

/// One value of a bifurcation diagram.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BifurcationPoint {
    /// The varied parameter's value (its unit is the axis').
    pub value: f64,
    pub direction: Direction,
    #[serde(flatten)]
    pub run: OrbitRun,
}

/// Consecutive values of one sweep whose orbits have the same type.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OrbitBand {
    pub direction: Direction,
    /// The first and last value of the band.
    pub from: f64,
    pub to: f64,
    pub values: usize,
    /// [`Orbit::label`].
    pub orbit: String,
}

/// A bifurcation diagram: per value of one parameter, the sampled orbit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Bifurcation {
    pub axis: Axis,
    pub settings: Settings,
    /// In sweep order: the values as given (from the design's own start, or rising with
    /// continuation), then with continuation the values falling.
    pub points: Vec<BifurcationPoint>,
    pub bands: Vec<OrbitBand>,
}

/// The bands of consecutive points of one direction with the same orbit type.
#[must_use]
pub fn bands(points: &[BifurcationPoint]) -> Vec<OrbitBand> {
    let mut out: Vec<OrbitBand> = Vec::new();
    for p in points {
        let label = p.run.orbit.label();
        match out.last_mut() {
            Some(b) if b.direction == p.direction && b.orbit == label => {
                b.to = p.value;
                b.values += 1;
            }
            _ => out.push(OrbitBand { direction: p.direction, from: p.value, to: p.value, values: 1, orbit: label }),
        }
    }
    out
}

/// The work of a bifurcation over `values` values (each `transient + periods` forcing periods,
/// twice with continuation): forcing periods against [`limits::RESPONSE_PERIODS`], and the
/// values against the cap on cells.
#[must_use]
pub fn work(values: usize, s: Settings, continuation: bool) -> [Estimate; 2] {
    let per = f64::from(s.transient_periods) + f64::from(s.periods);
    let sweeps = if continuation { 2.0 } else { 1.0 };
    [
        Estimate { cap: limits::SWEEP_CELLS, value: values as f64 * sweeps },
        Estimate { cap: limits::RESPONSE_PERIODS, value: values as f64 * per * sweeps },
    ]
}

/// Refuses a study of orbits over `values` values whose work ([`work`]) is over a cap.
pub fn check_work(values: usize, s: Settings, continuation: bool) -> Result<(), Refusal> {
    let [cells, periods] = work(values, s, continuation);
    limits::over(cells, limits::CELLS_PARAM, Remedy::FewerCells { max: cells.cap.max }, "")?;
    limits::over(periods, PERIODS_PARAM, Remedy::FewerCells { max: periods.cap.max }, "")
}

/// The quantity a refusal of [`check_work`] names for the forcing periods (`--periods`,
/// `--transient` and the values share it).
pub const PERIODS_PARAM: &str = "periods";

/// The bifurcation diagram of `base` over `vary` (each value's design checked again as a
/// whole, [`Grid::point`]): without `continuation` every value from the design's own start, in
/// parallel; with it, rising through the values each from the previous value's end state, then
/// falling from where the rise ended (hysteresis shows as two branches). `on_point(i)` is
/// called as each value finishes; `cancel` stops the work (`Err(Cancelled)`). `force` names
/// the force's parameter for a design without one.
pub fn bifurcation(
    base: &ValidDesign,
    vary: &Vary,
    s: Settings,
    continuation: bool,
    force: &str,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<Bifurcation, ThudError> {
    let grid = Grid::new(base.clone(), vec![vary.clone()], Spelling::Flag)?;
    let n = grid.cells();
    let designs: Vec<ValidDesign> = (0..n).map(|i| grid.point(i)).collect::<Result<_, _>>()?;
    for d in &designs {
        check_forced(d, force)?;
    }
    let cancelled = || cancel.is_some_and(|c| c.load(Ordering::Relaxed));
    let mut points = Vec::with_capacity(if continuation { 2 * n } else { n });
    if continuation {
        let mut start = Start::of(&designs[0].damper);
        let order: Vec<(usize, Direction)> =
            (0..n).map(|i| (i, Direction::Up)).chain((0..n).rev().map(|i| (i, Direction::Down))).collect();
        for (done, (i, direction)) in order.into_iter().enumerate() {
            if cancelled() {
                return Err(ThudError::Cancelled);
            }
            let (run, end) = run_orbit(&designs[i], &start, s, cancel);
            start = end;
            points.push(BifurcationPoint { value: vary.values[i], direction, run });
            on_point(done);
        }
    } else {
        points = bifurcation_points(&designs, vary, 0..n, s, cancel, on_point)?;
    }
    if cancelled() {
        return Err(ThudError::Cancelled);
    }
    let bands = bands(&points);
    Ok(Bifurcation { axis: vary.axis(), settings: s, points, bands })
}

/// The points `range` (indices into `vary`'s values) of a bifurcation without continuation,
/// each value's design from `designs`, from its own start, in parallel: the part one shard of
/// `thud bifurcation --shard K/N` computes. `Err(Cancelled)` when `cancel` stopped it.
fn bifurcation_points(
    designs: &[ValidDesign],
    vary: &Vary,
    range: std::ops::Range<usize>,
    s: Settings,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<Vec<BifurcationPoint>, ThudError> {
    let cancelled = || cancel.is_some_and(|c| c.load(Ordering::Relaxed));
    let runs: Vec<Option<OrbitRun>> = range
        .clone()
        .into_par_iter()
        .map(|i| {
            if cancelled() {
                return None;
            }
            let d = &designs[i];
            let run = run_orbit(d, &Start::of(&d.damper), s, cancel).0;
            on_point(i);
            Some(run)
        })
        .collect();
    let mut points = Vec::with_capacity(runs.len());
    for (i, run) in range.zip(runs) {
        let Some(run) = run else { return Err(ThudError::Cancelled) };
        points.push(BifurcationPoint { value: vary.values[i], direction: Direction::FromRest, run });
    }
    if cancelled() {
        return Err(ThudError::Cancelled);
    }
    Ok(points)
}

/// The points `range` of the bifurcation diagram of `base` over `vary` without continuation
/// ([`bifurcation`]'s, value for value): one part of `thud bifurcation --shard K/N`.
pub fn bifurcation_part(
    base: &ValidDesign,
    vary: &Vary,
    range: std::ops::Range<usize>,
    s: Settings,
    force: &str,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<Vec<BifurcationPoint>, ThudError> {
    let grid = Grid::new(base.clone(), vec![vary.clone()], Spelling::Flag)?;
    let range = range.start.min(grid.cells())..range.end.min(grid.cells());
    let mut designs = Vec::with_capacity(grid.cells());
    for i in 0..grid.cells() {
        // Only the part's own designs are run; every one is checked, as the whole would be.
        let d = grid.point(i)?;
        check_forced(&d, force)?;
        designs.push(d);
    }
    bifurcation_points(&designs, vary, range, s, cancel, on_point)
}

/// One attractor of a basin map: the orbit's type and amplitude, and how many starts reach it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Attractor {
    /// Its number on the map (0, 1, …: by type, then by amplitude).
    pub id: usize,
    pub orbit: Orbit,
    /// [`Orbit::label`].
    pub label: String,
    /// Its amplitude (m): the mean of its starts' largest |x| over the sampled periods.
    pub amplitude_m: f64,
    /// Starts that reach it, and their share of all starts.
    pub starts: usize,
    pub share: f64,
    /// The attractor that is its mirror image (`x → −x`, `z → −z` half a period later), where
    /// the map holds one: an asymmetric orbit and its mirror are two attractors.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mirror: Option<usize>,
}

/// Where one start of a basin map ends up: its orbit, amplitude, and for a periodic orbit of
/// period `n` its last `n` samples `x(kT)` and their mirror image's (`−x(kT + T/2)`), each
/// sorted (an orbit's points in any order of phase).
#[derive(Debug, Clone)]
struct Landing {
    orbit: Orbit,
    amplitude_m: f64,
    points: Vec<f64>,
    mirrored: Vec<f64>,
}

impl Landing {
    fn of(run: &OrbitRun, halves: &[[f64; 2]]) -> Self {
        let sorted = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v
        };
        let (points, mirrored) = match run.orbit {
            Orbit::Periodic { periods, .. } => {
                let n = (periods as usize).min(run.samples.len()).min(halves.len());
                let xs = run.samples[run.samples.len() - n..].iter().map(|s| s.x_m).collect();
                let ms = halves[halves.len() - n..].iter().map(|h| -h[0]).collect();
                (sorted(xs), sorted(ms))
            }
            _ => (Vec::new(), Vec::new()),
        };
        Landing { orbit: run.orbit, amplitude_m: run.amplitude_m, points, mirrored }
    }
}

/// Whether two sorted point sets are the same within `tol` (m), point by point.
fn same_points(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

/// The basins of attraction of a forced design over the ball's start: a grid of `y0` (across
/// the clearance) × `w0`, each start's attractor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Basins {
    pub settings: Settings,
    /// The ball's starting offsets (m): the centres of N equal cells of the clearance.
    pub y0_m: Vec<f64>,
    /// The ball's starting velocities (m/s).
    pub w0_m_s: Vec<f64>,
    /// The attractor ([`Attractor::id`]) of each start, `cells[i_w · y0.len() + i_y]`.
    pub cells: Vec<usize>,
    /// The amplitude (m) each start reached, in the same order.
    pub amplitudes_m: Vec<f64>,
    pub attractors: Vec<Attractor>,
}

/// How close two amplitudes (relative) must be for two starts of the same orbit type to count
/// as one attractor.
pub const SAME_ATTRACTOR: f64 = 0.01;

/// The basins of attraction of `d` over `n_y` ball offsets across the clearance (the centres
/// of `n_y` equal cells, as an ensemble's) × `w0_m_s` starting velocities; everything else
/// starts as the design says. Starts of the same orbit type whose amplitudes lie within
/// [`SAME_ATTRACTOR`] of each other (chained) are one attractor. Parallel on rayon's pool;
/// `on_cell` as each start finishes; `cancel` stops it (`Err(Cancelled)`).
pub fn basins(
    d: &ValidDesign,
    n_y: usize,
    w0_m_s: &[f64],
    s: Settings,
    force: &str,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize) + Sync),
) -> Result<Basins, ThudError> {
    check_forced(d, force)?;
    if n_y == 0 || w0_m_s.is_empty() {
        return Err(ThudError::invalid("grid", "an empty grid; give at least one start"));
    }
    let y0 = crate::ensemble::ball_positions(d.damper.gap_m, n_y);
    let cells = n_y * w0_m_s.len();
    let runs: Vec<Option<Landing>> = (0..cells)
        .into_par_iter()
        .map(|i| {
            if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                return None;
            }
            let mut start = Start::of(&d.damper);
            start.y = y0[i % n_y];
            start.w = w0_m_s[i / n_y];
            let (run, _, halves) = run_orbit_halves(d, &start, s, cancel);
            on_cell(i);
            Some(Landing::of(&run, &halves))
        })
        .collect();
    let runs: Vec<Landing> = runs.into_iter().collect::<Option<_>>().ok_or(ThudError::Cancelled)?;
    let (ids, attractors) = attractors_of(&runs);
    Ok(Basins {
        settings: s,
        y0_m: y0,
        w0_m_s: w0_m_s.to_vec(),
        cells: ids,
        amplitudes_m: runs.iter().map(|r| r.amplitude_m).collect(),
        attractors,
    })
}

/// The attractors the starts' landings `runs` reach, and each start's attractor id: grouped by
/// label, then (periodic) chains of amplitudes within [`SAME_ATTRACTOR`] whose points x(kT)
/// agree within [`SAME_ATTRACTOR`] of the amplitude (an orbit and its mirror image have the
/// same type and amplitude, not the same points); an asymmetric periodic attractor names its
/// mirror image where another attractor is it.
fn attractors_of(runs: &[Landing]) -> (Vec<usize>, Vec<Attractor>) {
    let cells = runs.len();
    // Group: by label, then (periodic) chains of amplitudes within SAME_ATTRACTOR whose points
    // x(kT) agree within SAME_ATTRACTOR of the amplitude (an orbit and its mirror image have
    // the same type and amplitude, not the same points).
    let mut order: Vec<usize> = (0..cells).collect();
    order.sort_by(|&a, &b| {
        runs[a].orbit.label().cmp(&runs[b].orbit.label()).then(runs[a].amplitude_m.total_cmp(&runs[b].amplitude_m))
    });
    let mut ids = vec![0usize; cells];
    let mut attractors: Vec<Attractor> = Vec::new();
    let mut sums: Vec<f64> = Vec::new();
    // Per attractor: its label and the last start that joined it.
    let mut last: Vec<(String, usize)> = Vec::new();
    for &i in &order {
        let r = &runs[i];
        let label = r.orbit.label();
        let regular = matches!(r.orbit, Orbit::Periodic { .. });
        let joins = |&(ref l, j): &(String, usize)| {
            let q = &runs[j];
            let scale = q.amplitude_m.abs().max(r.amplitude_m.abs());
            *l == label
                && (!regular
                    || ((r.amplitude_m - q.amplitude_m).abs() <= SAME_ATTRACTOR * scale
                        && same_points(&r.points, &q.points, SAME_ATTRACTOR * scale)))
        };
        let id = if let Some(id) = last.iter().position(joins) {
            id
        } else {
            attractors.push(Attractor {
                id: attractors.len(),
                orbit: r.orbit,
                label: label.clone(),
                amplitude_m: 0.0,
                starts: 0,
                share: 0.0,
                mirror: None,
            });
            sums.push(0.0);
            last.push((label, i));
            attractors.len() - 1
        };
        last[id].1 = i;
        ids[i] = id;
        attractors[id].starts += 1;
        sums[id] += r.amplitude_m;
    }
    for (a, sum) in attractors.iter_mut().zip(sums) {
        a.amplitude_m = sum / a.starts as f64;
        a.share = a.starts as f64 / cells as f64;
    }
    // An asymmetric periodic attractor's mirror image, where another attractor is it.
    for a in 0..attractors.len() {
        let ra = &runs[last[a].1];
        if !matches!(ra.orbit, Orbit::Periodic { symmetric: false, .. }) {
            continue;
        }
        let tol = SAME_ATTRACTOR * ra.amplitude_m.abs();
        attractors[a].mirror = (0..attractors.len()).find(|&b| {
            let rb = &runs[last[b].1];
            b != a && last[b].0 == last[a].0 && same_points(&ra.mirrored, &rb.points, tol)
        });
    }
    (ids, attractors)
}

#[cfg(test)]
mod tests;
