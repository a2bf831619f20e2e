//! The editable parameters of the panel: how each one is shown (display units), stepped and
//! typed. Values live in the `Design` in SI units; conversions happen only here, at the edge.
//! The knobs turn a [`Tunable`]: a design alone, or a [`Setup`] (a design and the explorer's
//! ensemble size N, which is not part of a design: the command line's `--ensemble`).

use super::compute;
use crate::acoustics::{PulseShape, QuadSigns, Source};
use crate::contact::MATERIALS;
use crate::damper::Solver;
use crate::design::{Design, Materials};
use crate::error::ThudError;
use crate::limits;
use crate::params::{self, Accepts, Group, DESIGN};
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
    /// Amplitude F0 of the harmonic force on the main mass (`--force`).
    Force,
    /// Frequency f of the harmonic force (`--freq`).
    Freq,
    /// The ball's initial offset y0 from the enclosure's centre (`--ball-position`).
    BallPosition,
    /// Runs N of the ensemble (`--ensemble`): the readout's spread and the chart's shading.
    Runs,
    /// A field made from the engine's row `DESIGN[i]` alone (a number, a count or a switch no
    /// field above sets): its name, range, help, unit and accessor are the row's. Every row of
    /// [`params::DESIGN`] gets a field this way unless a field above already sets it, so a new
    /// parameter appears in the explorer without a line here.
    Row(usize),
}

/// The rows of [`params::DESIGN`] the named fields set ([`Knob::rows`] of each, in order).
const NAMED_ROWS: [&str; 24] = [
    "mass",
    "gap",
    "r",
    "theta",
    "v0",
    "main-mass",
    "k",
    "c",
    "c1",
    "k-hz",
    "sphere",
    "plate",
    "source",
    "quad-signs",
    "pulse",
    "no-tension",
    "solver",
    "dt",
    "duration",
    "l-star",
    "e-star",
    "force",
    "freq",
    "ball-position",
];

/// Whether the row `i` of [`params::DESIGN`] is set by a named field.
const fn named_row(i: usize) -> bool {
    let mut j = 0;
    while j < NAMED_ROWS.len() {
        if params::same_name(DESIGN[i].name, NAMED_ROWS[j]) {
            return true;
        }
        j += 1;
    }
    false
}

/// How many rows of [`params::DESIGN`] get a [`Knob::Row`] field.
const ROW_FIELDS: usize = {
    let mut n = 0;
    let mut i = 0;
    while i < DESIGN.len() {
        if !named_row(i) {
            n += 1;
        }
        i += 1;
    }
    n
};

/// The named fields of the panel, in panel order (the ensemble size last).
const NAMED: [Knob; 23] = [
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
    Knob::Force,
    Knob::Freq,
    Knob::BallPosition,
    Knob::Runs,
];

/// The row of [`params::DESIGN`] called `name` (its index; the table's length if none).
const fn design_row(name: &str) -> usize {
    let mut i = 0;
    while i < DESIGN.len() && !params::same_name(DESIGN[i].name, name) {
        i += 1;
    }
    i
}

/// The field that owns the row `i` of [`params::DESIGN`] and lists first there: a named field
/// at its first row (the materials at `sphere`, the solver at `solver`), else the row's own
/// [`Knob::Row`]; none at a named field's later rows (`plate`, `dt`).
const fn field_at_row(i: usize) -> Option<Knob> {
    if !named_row(i) {
        return Some(Knob::Row(i));
    }
    let mut n = 0;
    while n < NAMED.len() {
        if let Some((at, _)) = NAMED[n].named_span() {
            if design_row(NAMED_ROWS[at]) == i {
                return Some(NAMED[n]);
            }
        }
        n += 1;
    }
    None
}

/// Every field, grouped as the engine's table groups its rows ([`Group::ALL`] order: design,
/// forcing, listener, solver, study) and in table order inside a group (a field where its
/// first row is); the ensemble size N, the explorer's own, last in the study group.
const fn all_fields() -> [Knob; NAMED.len() + ROW_FIELDS] {
    let mut all = [Knob::Runs; NAMED.len() + ROW_FIELDS];
    let mut k = 0;
    let mut g = 0;
    while g < Group::ALL.len() {
        let mut i = 0;
        while i < DESIGN.len() {
            if DESIGN[i].group as usize == Group::ALL[g] as usize {
                if let Some(field) = field_at_row(i) {
                    all[k] = field;
                    k += 1;
                }
            }
            i += 1;
        }
        g += 1;
    }
    all
}

/// What the knobs turn: a design, or a design with the explorer's ensemble size.
pub trait Tunable: Clone {
    fn design(&self) -> &Design;
    fn design_mut(&mut self) -> &mut Design;
    /// Runs per design N (1 for a design alone: the single trajectory).
    fn runs(&self) -> usize;
    /// Sets N; false if this has no ensemble size (a design alone).
    fn set_runs(&mut self, n: usize) -> bool;
}

impl Tunable for Design {
    fn design(&self) -> &Design {
        self
    }

    fn design_mut(&mut self) -> &mut Design {
        self
    }

    fn runs(&self) -> usize {
        1
    }

    fn set_runs(&mut self, _: usize) -> bool {
        false
    }
}

/// Checks a setup that was loaded rather than typed (a saved design, a preset, a tour step)
/// as if each of its fields had been typed: every field's range, the work caps (named as the
/// duration, the field that usually carries them: a 1e6-s design is refused with the chart's
/// cap line, as typing 1e6 is), the whole-design checks and the engine's validation.
pub fn check_loaded<S: Tunable>(s: &S) -> Result<(), ThudError> {
    // The forcing and the ball's start only where they apply: the whole-design check has them.
    for k in Knob::ALL.into_iter().filter(|k| !matches!(k, Knob::Force | Knob::Freq | Knob::BallPosition)) {
        k.check_range(s)?;
    }
    params::check_design(s.design())?;
    Knob::Duration.checked(s.clone()).map(drop)
}

/// What the explorer runs: the design and the ensemble size N (runs from N ball offsets spread
/// over the clearance, [`crate::ensemble`]; 1 is the single trajectory).
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    pub design: Design,
    pub runs: usize,
}

impl Tunable for Setup {
    fn design(&self) -> &Design {
        &self.design
    }

    fn design_mut(&mut self) -> &mut Design {
        &mut self.design
    }

    fn runs(&self) -> usize {
        self.runs
    }

    fn set_runs(&mut self, n: usize) -> bool {
        self.runs = n;
        true
    }
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
    /// A count: double or halve (coarse), or ± 1 (fine).
    Count,
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
    std::iter::once(None).chain(MATERIALS.iter().map(|m| Some(Materials::new(m.name, "steel")))).collect()
}

impl Knob {
    /// All fields, in panel order: the named fields, a field for every other row of the
    /// engine's table, the ensemble size.
    pub const ALL: [Knob; NAMED.len() + ROW_FIELDS] = all_fields();

    /// The rows of the engine's table ([`params::DESIGN`]) this field sets (none for the
    /// ensemble size, which is the explorer's, not a design's).
    pub fn rows(self) -> &'static [&'static str] {
        match (self, self.named_span()) {
            (_, Some((at, n))) => &NAMED_ROWS[at..at + n],
            (Knob::Row(i), None) => DESIGN.get(i).map_or(&[], |p| std::slice::from_ref(&p.name)),
            _ => &[],
        }
    }

    /// Where a named field's rows are in [`NAMED_ROWS`]: (first, how many).
    const fn named_span(self) -> Option<(usize, usize)> {
        Some(match self {
            Knob::Mass => (0, 1),
            Knob::Gap => (1, 1),
            Knob::R => (2, 1),
            Knob::Theta => (3, 1),
            Knob::V0 => (4, 1),
            Knob::MainMass => (5, 1),
            Knob::K => (6, 1),
            Knob::C => (7, 1),
            Knob::C1 => (8, 1),
            Knob::KHz => (9, 1),
            Knob::Materials => (10, 2),
            Knob::Source => (12, 1),
            Knob::QuadSigns => (13, 1),
            Knob::Pulse => (14, 1),
            Knob::Clamp => (15, 1),
            Knob::Solver => (16, 2),
            Knob::Duration => (18, 1),
            Knob::LStar => (19, 1),
            Knob::EStar => (20, 1),
            Knob::Force => (21, 1),
            Knob::Freq => (22, 1),
            Knob::BallPosition => (23, 1),
            Knob::Runs | Knob::Row(_) => return None,
        })
    }

    /// The group the field is listed under: its first row's in the engine's table; the
    /// ensemble size N (the explorer's own) with the study.
    pub fn group(self) -> Group {
        self.rows().first().and_then(|n| params::design_param(n)).map_or(Group::Study, |p| p.group)
    }

    /// The engine's row of a field that sets exactly one.
    pub fn row(self) -> Option<&'static params::Param<params::DesignDraft>> {
        match self.rows() {
            [name] => params::design_param(name),
            _ => None,
        }
    }

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
            Knob::Force => "force F0",
            Knob::Freq => "freq f",
            Knob::BallPosition => "ball y0",
            Knob::Runs => "ensemble N",
            Knob::Row(_) => self.row().map_or("?", |r| r.label),
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
            Knob::Force => "force",
            Knob::Freq => "freq",
            Knob::BallPosition => "ball-position",
            Knob::Runs => "ensemble",
            Knob::Row(_) => self.rows().first().copied().unwrap_or("?"),
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
            Knob::Force => Kind::Force,
            Knob::Freq => Kind::Frequency,
            Knob::BallPosition => Kind::Length,
            Knob::Row(_) => match self.row()?.accepts {
                Accepts::Quantity { kind, .. } => kind,
                _ => return None,
            },
            _ => return None,
        })
    }

    /// The field's valid range: its row's in the engine's table ([`params::DESIGN`], whose
    /// ranges are [`crate::limits`]'s); the ensemble size's is [`limits::ENSEMBLE`].
    pub fn range(self) -> Option<limits::Range> {
        match self {
            Knob::Runs => Some(limits::ENSEMBLE),
            _ => self.row()?.range().copied(),
        }
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
            Knob::Force => ("N", 1.0),
            Knob::Freq => ("Hz", 1.0),
            Knob::BallPosition => ("cm", 1e-2),
            Knob::Runs => ("runs", 1.0),
            Knob::Row(_) => match self.row()?.accepts {
                Accepts::Quantity { kind, .. } => (kind.plain_unit(), 1.0),
                Accepts::Count { range, .. } => (range.unit, 1.0),
                _ => return None,
            },
            _ => return None,
        })
    }
    /// The valid range in the display unit: (lowest, highest). θ's is the current source's
    /// open side; y0's is inside the clearance, −d/2 to d/2 (both excluded).
    pub fn display_range(self, d: &Design) -> Option<(f64, f64)> {
        let (_, k) = self.display_unit()?;
        if self == Knob::Theta {
            let r = limits::theta_deg(d.radiation.source);
            return Some((r.min, r.max));
        }
        if self == Knob::BallPosition {
            let half = 0.5 * d.damper.gap_m;
            return Some((-half / k, half / k));
        }
        let r = self.range()?;
        Some((r.min / k, r.max / k))
    }

    /// Refuses a design whose runs in the explorer would exceed the work caps the command line
    /// uses ([`limits::design_run`] for the live design, [`limits::sweep_work`] for the chart's
    /// fine grid, and with N > 1 [`limits::ensemble_work`] for the live design's N runs and
    /// the chart's N runs a cell): the same estimates and limits, worded for the status line.
    /// This is what keeps a duration, a Newmark step or an ensemble typed here from running
    /// for hours or out of memory.
    fn check_work<S: Tunable>(self, s: &S) -> Result<(), ThudError> {
        // A design that fails its checks has no work to estimate: the checks after this one
        // ([`Design::check`] in [`Knob::checked`]) refuse it.
        let Ok(d) = s.design().clone().check() else { return Ok(()) };
        let d = &d;
        let cells = compute::Grids::default().fine.len();
        let runs = s.runs();
        // The field just changed is the parameter "given": the engine's one decision of
        // which cap a run is over ([`limits::check_run`], [`limits::check_sweep`],
        // [`limits::check_runs`]); the status line names this field.
        let given = |n: &str| self.rows().contains(&n);
        let refused = limits::check_run(d, &given, compute::HISTORY_SAMPLES)
            .and_then(|()| limits::check_sweep(d, &given, cells, 1))
            .and_then(|()| if runs > 1 { limits::check_runs(d, &given, 1, runs) } else { Ok(()) })
            .and_then(|()| if runs > 1 { limits::check_runs(d, &given, cells, runs) } else { Ok(()) });
        match refused {
            Err(r) => {
                // The solver field is named by its step, as the command line's --dt.
                let (name, shown) = match (self, d.solver) {
                    (Knob::Solver, Solver::Newmark { dt_s }) => ("dt", format!("{} s", limits::short(dt_s))),
                    _ => (self.param(), self.display(s)),
                };
                Err(ThudError::invalid(name, format!("{shown}: {}", r.estimate.describe())))
            }
            Ok(()) => Ok(()),
        }
    }

    fn check_range<S: Tunable>(self, s: &S) -> Result<(), ThudError> {
        let d = s.design();
        if let (Some(r), Some(v), Some((unit, k))) = (self.range(), self.value(s), self.display_unit()) {
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

    /// The checks every new value passes, in order: the field's own range (in the unit shown),
    /// the work caps, and the engine's check of the whole design ([`Design::check`]: the
    /// physics' own checks, then the one range table over the whole design, e.g. |y0| < d/2
    /// and a force's frequency, as the command line checks it), the check every job repeats.
    pub(crate) fn checked<S: Tunable>(self, next: S) -> Result<S, ThudError> {
        self.check_range(&next)?;
        self.check_work(&next)?;
        next.design().clone().check()?;
        Ok(next)
    }

    /// What a change of this field invalidates.
    pub fn scope(self) -> Scope {
        match self {
            Knob::R | Knob::Theta | Knob::Source | Knob::QuadSigns | Knob::Pulse => Scope::Acoustics,
            Knob::Mass | Knob::Gap => Scope::Design,
            Knob::LStar | Knob::EStar => Scope::Thresholds,
            Knob::Row(_) => match self.row().map(|p| p.group) {
                Some(Group::Listener) => Scope::Acoustics,
                Some(Group::Study) => Scope::Thresholds,
                _ => Scope::All,
            },
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
            Knob::Force => Stepping::Add(0.1, 0.01),
            Knob::Freq => Stepping::Mul(0.02, 0.002),
            Knob::BallPosition => Stepping::Add(1e-3, 1e-4),
            Knob::Runs => Stepping::Count,
            Knob::Row(_) => match self.row().map(|p| &p.accepts) {
                Some(Accepts::Quantity { range, .. }) if range.min > 0.0 => Stepping::Mul(0.1, 0.01),
                Some(Accepts::Quantity { .. }) => Stepping::Add(0.1, 0.01),
                Some(Accepts::Count { .. }) => Stepping::Count,
                _ => Stepping::Cycle,
            },
            _ => Stepping::Cycle,
        }
    }

    /// The numeric value in internal units (SI; degrees; dB; cm/s), if the field is numeric
    /// and part of a design (the ensemble size is not: see [`Knob::value`]).
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
            Knob::KHz => d.hertz_stiffness().unwrap_or(p.k_hz),
            Knob::Duration => p.duration_s,
            Knob::LStar => d.thresholds.spl_db,
            Knob::EStar => d.thresholds.inclination_cm_s,
            Knob::Force => p.force_n,
            Knob::Freq => p.freq_hz,
            Knob::BallPosition => p.ball_position_m,
            // NaN: the design does not use the row (a density while the radius is set).
            Knob::Row(_) => match self.row()? {
                row if matches!(row.accepts, Accepts::Quantity { .. } | Accepts::Count { .. }) => {
                    Some((row.get?)(d)).filter(|v| !v.is_nan())?
                }
                _ => return None,
            },
            _ => return None,
        })
    }

    /// The numeric value of this field of `s` (internal units), the ensemble size included.
    pub fn value<S: Tunable>(self, s: &S) -> Option<f64> {
        match self {
            Knob::Runs => Some(s.runs() as f64),
            _ => self.get(s.design()),
        }
    }

    /// Sets the numeric value (internal units) on a copy; the ensemble size is refused by a
    /// design alone (it is the explorer's, not the design's).
    fn set<S: Tunable>(self, s: &S, v: f64) -> Result<S, ThudError> {
        let mut s = s.clone();
        if self == Knob::Runs {
            // A count: rounded, and kept inside 1.. (the range check names a bad one).
            let n = if v.is_finite() && v >= 1.0 { v.round() as usize } else { 0 };
            if !s.set_runs(n) {
                return Err(ThudError::invalid(self.param(), "the ensemble size is the explorer's, not a design's"));
            }
            return Ok(s);
        }
        let d = s.design_mut();
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
            Knob::Force => p.force_n = v,
            Knob::Freq => p.freq_hz = v,
            Knob::BallPosition => p.ball_position_m = v,
            Knob::Row(_) => {
                if let Some(row) = self.row() {
                    *d = params::set_number(d, row, v);
                }
            }
            _ => {}
        }
        Ok(s)
    }

    /// The value as people read it: display units, a few significant digits.
    pub fn display<S: Tunable>(self, s: &S) -> String {
        let d = s.design();
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
            Knob::Force if p.force_n == 0.0 => "0 (free decay)".into(),
            Knob::Force => format!("{} N", sig(p.force_n, 3)),
            Knob::Freq if p.freq_hz == 0.0 => "— (no force)".into(),
            Knob::Freq => format!("{} Hz", sig(p.freq_hz, 4)),
            Knob::BallPosition if p.ball_position_m == 0.0 => "0 (centred)".into(),
            Knob::BallPosition => format!("{} cm", sig(p.ball_position_m * 1e2, 3)),
            Knob::Runs if s.runs() == 1 => "1 (single run)".into(),
            Knob::Runs => format!("{} runs", s.runs()),
            Knob::Row(_) => self.row_display(d),
        }
    }

    /// The design (or setup) with this field stepped once (`up`: increase), validated. A force
    /// stepped up from 0 while f is unset gets f at the structure's natural frequency (the
    /// engine's damped frequency of Eq 25), so that a force always has its frequency.
    pub fn stepped<S: Tunable>(self, s: &S, up: bool, fine: bool) -> Result<S, ThudError> {
        let next = match (self.step(), self.value(s)) {
            (Stepping::Add(c, f), Some(v)) => {
                let st = if fine { f } else { c };
                // Snap to the step grid so repeated steps give round numbers.
                let n = (v / st).round() + if up { 1.0 } else { -1.0 };
                let v = if ((v / st) - (v / st).round()).abs() < 1e-6 { n * st } else { v + if up { st } else { -st } };
                // A force stepped down to (near) zero is off, exactly.
                let v = if self == Knob::Force && v.abs() < 1e-9 { 0.0 } else { v };
                self.set(s, v)?
            }
            (Stepping::Mul(_, _), Some(v)) if self == Knob::Freq && v == 0.0 => {
                self.set(s, start_frequency_hz(s.design()))?
            }
            (Stepping::Mul(c, f), Some(v)) => {
                let k = 1.0 + if fine { f } else { c };
                self.set(s, if up { v * k } else { v / k })?
            }
            (Stepping::Count, Some(v)) => {
                let n = v.round();
                let next = match (up, fine) {
                    (true, false) => 2.0 * n,
                    (false, false) => (n / 2.0).floor(),
                    (true, true) => n + 1.0,
                    (false, true) => n - 1.0,
                };
                self.set(s, next)?
            }
            _ => self.cycled(s, up),
        };
        self.checked(with_frequency(self, next))
    }

    /// The design with a choice field moved to the next (`up`) or previous option.
    fn cycled<S: Tunable>(self, s: &S, up: bool) -> S {
        let mut s = s.clone();
        let d = s.design_mut();
        let turn = |i: usize, n: usize| if up { (i + 1) % n } else { (i + n - 1) % n };
        match self {
            Knob::Source => {
                let all = Source::ALL;
                let i = all.iter().position(|s| *s == d.radiation.source).unwrap_or(0);
                d.radiation.source = all[turn(i, all.len())];
                clamp_theta(d);
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
            Knob::Row(_) => match self.row() {
                Some(row) if matches!(row.accepts, Accepts::Switch { .. }) => {
                    let on = row.get.is_some_and(|get| get(d) != 0.0);
                    *d = params::set_number(d, row, if on { 0.0 } else { 1.0 });
                }
                // A choice that reads back its index (the model): the next or previous name.
                Some(row) => {
                    if let (Accepts::Choice { names, .. }, Some(get)) = (&row.accepts, row.get) {
                        let i = get(d).max(0.0) as usize;
                        *d = params::set_number(d, row, turn(i, names.len()) as f64);
                        // The physical model's ball follows its material (the one ball rule).
                        if let Ok(followed) = params::follow_material(d.clone()) {
                            *d = followed;
                        }
                    }
                }
                None => {}
            },
            Knob::Solver => {
                d.solver = match d.solver {
                    Solver::Event => Solver::Newmark { dt_s: TUI_NEWMARK_DT_S },
                    Solver::Newmark { .. } => Solver::Event,
                }
            }
            Knob::Materials => {
                // The next ball material from the current one (whatever its plate and ν); the
                // plate and a ν the user set are theirs and stay.
                let all = material_choices();
                let sphere = |m: &Option<Materials>| m.as_ref().map(|m| m.sphere.clone());
                let i = all.iter().position(|m| sphere(m) == sphere(&d.materials)).unwrap_or(0);
                let mut next = all[turn(i, all.len())].clone();
                if let (Some(next), Some(now)) = (next.as_mut(), d.materials.as_ref()) {
                    next.plate.clone_from(&now.plate);
                    next.sphere_nu = now.sphere_nu;
                }
                d.materials = next;
                // The ball's density follows its material (the engine's one ball rule).
                if let Ok(followed) = params::follow_material(d.clone()) {
                    *d = followed;
                }
            }
            _ => {}
        }
        s
    }

    /// The design (or setup) with this field set from typed text (units allowed), validated.
    pub fn parsed<S: Tunable>(self, s: &S, text: &str) -> Result<S, ThudError> {
        let t = text.trim();
        let next = match (self, self.kind(), self.display_unit()) {
            // A count, read as the command line reads --ensemble.
            (Knob::Runs, _, _) => {
                let n = limits::ENSEMBLE.parse_count(self.param(), t)?;
                self.set(s, n as f64)?
            }
            // A count of the engine's table, read as the command line reads its flag.
            (Knob::Row(_), None, Some(_)) => match self.range() {
                Some(r) => self.set(s, r.parse_count(self.param(), t)? as f64)?,
                None => self.parse_choice(s, t)?,
            },
            // A plain number is in the unit shown.
            (_, Some(_), Some((_, k))) if t.parse::<f64>().is_ok() => {
                self.set(s, t.parse::<f64>().unwrap_or(f64::NAN) * k)?
            }
            (_, Some(kind), _) => self.set(s, units::parse(self.param(), t, kind)?)?,
            (_, None, _) => self.parse_choice(s, t)?,
        };
        self.applies(&next, t)?;
        self.checked(with_frequency(self, next))
    }

    /// Refuses a number typed into a row the design still does not use after it (shown as —:
    /// the ball's ν without materials), naming the field that makes it apply.
    fn applies<S: Tunable>(self, next: &S, typed: &str) -> Result<(), ThudError> {
        let Some(row) = self.row().filter(|r| matches!(r.accepts, Accepts::Quantity { .. })) else { return Ok(()) };
        if self.get(next.design()).is_some() {
            return Ok(());
        }
        let needed = row.requires.and_then(|n| Knob::ALL.into_iter().find(|k| k.rows().contains(&n)));
        let why = needed.map_or("this design".to_string(), |k| format!("a design without {}", k.label()));
        Err(ThudError::invalid(self.param(), format!("'{typed}' does not apply to {why}")))
    }

    /// Parses a choice field: source names, signs, on/off, event/newmark/a time step, materials.
    fn parse_choice<S: Tunable>(self, s: &S, t: &str) -> Result<S, ThudError> {
        let mut s = s.clone();
        let d = s.design_mut();
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
                        Some(Materials {
                            sphere_nu: d.materials.as_ref().and_then(|m| m.sphere_nu),
                            ..Materials::new(s.name, p.name)
                        })
                    }
                };
                *d = params::follow_material(d.clone())?;
            }
            Knob::Row(_) if self.row().is_some_and(|r| matches!(r.accepts, Accepts::Choice { .. })) => {
                if let Some(row) = self.row() {
                    let Accepts::Choice { names, .. } = row.accepts else { return Err(bad("a number")) };
                    let i = names.iter().position(|n| *n == low).ok_or_else(|| bad(&names.join(" or ")))?;
                    *d = params::follow_material(params::set_number(d, row, i as f64))?;
                }
            }
            Knob::Row(_) if self.row().is_some_and(|r| matches!(r.accepts, Accepts::Switch { .. })) => {
                let on = match low.as_str() {
                    "on" | "yes" | "true" => 1.0,
                    "off" | "no" | "false" => 0.0,
                    _ => return Err(bad("on or off")),
                };
                if let Some(row) = self.row() {
                    *d = params::set_number(d, row, on);
                }
            }
            _ => return Err(bad("a number")),
        }
        Ok(s)
    }
}

/// The fields whose name matches `typed` (the `/` filter), best first: the label or the
/// command-line name equal to it, then starting with it, then a word of the label starting
/// with it, then containing it; in panel order within each (all fields for nothing typed).
/// Case is ignored; "th" finds θ (its name is `theta`).
pub fn find(typed: &str) -> Vec<Knob> {
    let q = typed.trim().to_lowercase();
    let rank = |k: Knob| -> Option<u8> {
        if q.is_empty() {
            return Some(0);
        }
        let names = [k.label().to_lowercase(), k.param().to_lowercase()];
        if names.contains(&q) {
            Some(0)
        } else if names.iter().any(|n| n.starts_with(&q)) {
            Some(1)
        } else if names[0].split([' ', '-']).any(|w| w.starts_with(&q)) {
            Some(2)
        } else if names.iter().any(|n| n.contains(&q)) {
            Some(3)
        } else {
            None
        }
    };
    let mut hits: Vec<(u8, usize, Knob)> =
        Knob::ALL.into_iter().enumerate().filter_map(|(i, k)| rank(k).map(|r| (r, i, k))).collect();
    hits.sort_by_key(|&(r, i, _)| (r, i));
    hits.into_iter().map(|(_, _, k)| k).collect()
}

impl Knob {
    /// The value of a [`Knob::Row`] field as people read it: a number in its plain unit
    /// (— when the design does not use it, e.g. a density while the radius is set), or on/off.
    fn row_display(self, d: &Design) -> String {
        let Some(row) = self.row() else { return "—".into() };
        let v = row.get.map_or(f64::NAN, |get| get(d));
        match row.accepts {
            Accepts::Switch { .. } => if v == 0.0 { "off" } else { "on" }.into(),
            Accepts::Choice { names, .. } if v.is_finite() => names.get(v as usize).copied().unwrap_or("—").into(),
            _ if !v.is_finite() => "—".into(),
            Accepts::Count { .. } => format!("{}", v.round()),
            _ => match row.unit() {
                "" => sig(v, 4),
                unit => format!("{} {unit}", sig(v, 4)),
            },
        }
    }
}

/// The forcing frequency a force starts at when none is set: the structure's natural
/// frequency, exactly the value the response band is centred on, or 1 Hz without one (no
/// spring, overdamped).
fn start_frequency_hz(d: &Design) -> f64 {
    let f = compute::natural_frequency_hz(d);
    if f > 0.0 {
        f
    } else {
        1.0
    }
}

/// `s` after a change of `knob`: a force switched on while f is unset gets f at
/// [`start_frequency_hz`] (a force needs a frequency; the status line shows both).
fn with_frequency<S: Tunable>(knob: Knob, mut s: S) -> S {
    let d = s.design_mut();
    if knob == Knob::Force && d.damper.force_n > 0.0 && d.damper.freq_hz == 0.0 {
        d.damper.freq_hz = start_frequency_hz(d);
    }
    s
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
    fn the_balls_poisson_ratio_applies_with_materials_only() {
        let nu = row_field("sphere-poisson");
        let d = Design::default();
        assert_eq!(nu.display(&d), "—", "no materials: no ball ν");
        assert_eq!(nu.stepped(&d, true, false).unwrap(), d, "a step changes nothing that is not there");
        let e = nu.parsed(&d, "0.28").unwrap_err().to_string();
        assert_eq!(e, "invalid sphere-poisson: '0.28' does not apply to a design without materials");
        let steel = Knob::Materials.parsed(&d, "steel/steel").unwrap();
        assert_eq!(nu.display(&steel), "0.3000", "the material's own ν");
        let given = nu.parsed(&steel, "0.28").unwrap();
        assert_eq!(given.materials.as_ref().unwrap().sphere_nu, Some(0.28));
        assert_eq!(nu.display(&given), "0.2800");
        assert!(
            given.clone().check().unwrap().damper.k_hz < steel.clone().check().unwrap().damper.k_hz,
            "softer: Eq 2"
        );
        assert!(nu.parsed(&steel, "0.7").unwrap_err().to_string().starts_with("invalid sphere-poisson: "));
    }

    /// → on the materials field goes to the ball material after the current one, whatever the
    /// plate and the ball's ν, and keeps both (they are the user's): it used to restart from the
    /// first material and drop them.
    #[test]
    fn cycling_the_materials_starts_from_the_current_ball_and_keeps_plate_and_nu() {
        let d = Design::default();
        let nu = row_field("sphere-poisson");
        let set = nu.parsed(&Knob::Materials.parsed(&d, "brass/aluminium").unwrap(), "0.28").unwrap();
        let next = Knob::Materials.stepped(&set, true, false).unwrap();
        let after = |name: &str| MATERIALS[MATERIALS.iter().position(|m| m.name == name).unwrap() + 1].name;
        let m = next.materials.as_ref().unwrap();
        assert_eq!((m.sphere.as_str(), m.plate.as_str(), m.sphere_nu), (after("brass"), "aluminium", Some(0.28)));
        let back = Knob::Materials.stepped(&next, false, false).unwrap();
        assert_eq!(back.materials, set.materials, "← undoes →");
    }

    /// The field of the engine's row `name` (a [`Knob::Row`]).
    fn row_field(name: &str) -> Knob {
        Knob::ALL.into_iter().find(|k| matches!(k, Knob::Row(_)) && k.rows() == [name]).unwrap()
    }

    #[test]
    fn fields_made_from_table_rows_set_the_design() {
        let d = Design::default();
        let w0 = row_field("ball-velocity");
        assert_eq!(w0.parsed(&d, "0.5").unwrap().damper.ball_velocity_m_s, 0.5);
        assert!(w0.parsed(&d, "1e3").is_err(), "out of the row's range");
        let rho = row_field("density");
        assert_eq!(rho.parsed(&d, "1000").unwrap().ball, crate::design::BallSize::Density(1000.0));
        let n = row_field("periods");
        assert_eq!(n.stepped(&d, true, false).unwrap().damper.steady_periods, 2 * d.damper.steady_periods);
        assert!(n.parsed(&d, "2.5").is_err(), "a count");
        let settle = row_field("settle");
        assert!(settle.stepped(&d, true, false).unwrap().damper.settle);
        assert_eq!(settle.display(&d), "off");
        assert_eq!(w0.display(&d), "0 m/s");
    }

    #[test]
    fn the_filter_finds_theta_from_th_and_each_field_from_its_name() {
        assert_eq!(find("th").first(), Some(&Knob::Theta));
        assert_eq!(find("θ").first(), Some(&Knob::Theta));
        assert_eq!(find("TH").first(), Some(&Knob::Theta), "case is ignored");
        assert_eq!(find("gap").first(), Some(&Knob::Gap));
        assert_eq!(find("").len(), Knob::ALL.len());
        assert!(find("zzz").is_empty());
        for k in Knob::ALL {
            assert_eq!(find(k.param()).first(), Some(&k), "{} finds itself first", k.param());
        }
    }

    #[test]
    fn step_below_zero_is_refused() {
        let mut d = Design::default();
        d.damper.impact_mass_kg = 0.001;
        assert!(Knob::Mass.stepped(&d, false, false).is_err());
    }
}
