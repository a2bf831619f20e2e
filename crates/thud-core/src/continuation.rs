// Over 800 lines: one continuation method (predictor, corrector, step control, special points) and its families.
//! Pseudo-arclength continuation of a family of periodic orbits in one numeric parameter
//! (docs/model.md §6.8; Keller 1977; Allgower & Georg, "Numerical Continuation Methods", 1990,
//! ch. 2 and 8), through folds and along unstable parts, with the fold, period-doubling,
//! Neimark–Sacker and grazing points located and labelled.
//!
//! The unknowns are the orbit's state at the section `u` (scaled as in [`crate::orbit`]) and the
//! parameter scaled to the range, `λ̃ = (λ − from)/(to − from)`; the family is the curve
//! `G(u, λ̃) = Pⁿ_λ(u) − u = 0` in these five unknowns. From a point `y_k` with unit tangent
//! `t_k` (the null vector of `[DG | ∂G/∂λ̃]`, oriented to go on), the predictor is
//! `y_k + h·t_k`; the corrector is quasi-Newton on `G = 0` and `t_k·(y − y_k) = h`, from the
//! Jacobian of `y_k` updated by Broyden's formula after each iteration. At each converged point
//! the Jacobian is taken anew ([`crate::orbit::JACOBIAN_STEP`]): it gives the multipliers, the
//! next tangent and the test functions. The step `h` follows the corrector's contraction, the
//! predictor's distance and the tangent's turn against nominal values (Allgower & Georg §6.1),
//! changing by at most a factor of 2 a step, and halves after a failed correction. The two
//! directions from a family's seed run on two threads.
//!
//! A special point lies between two points where a test function changes sign: the tangent's
//! `λ` component (a fold), `det(DPⁿ + I)` (a multiplier through −1: period doubling), the number
//! of complex multipliers outside the unit circle (Neimark–Sacker), or the impacts per orbit
//! (grazing: an impact appears or vanishes; the map is not smooth there and the branch may end).
//! Folds, doublings and torus points are then located by the secant method on the arclength,
//! each iterate corrected back onto the branch. At a period doubling, [`with_doublings`] switches
//! onto the doubled orbit's branch where the doubling is supercritical.

use std::sync::atomic::{AtomicBool, Ordering};

use nalgebra::{Matrix4, SMatrix, SVector, Vector4};
use serde::{Deserialize, Serialize};

use crate::design::ValidDesign;
use crate::error::ThudError;
use crate::orbit::{self, PeriodicOrbit, Request, Root, Section};
use crate::study::Vary;

type V5 = SVector<f64, 5>;
type M45 = SMatrix<f64, 4, 5>;

/// The most points one branch may have: [`crate::limits::BRANCH_POINTS`], lifted by the
/// design's `no_limit` (`--no-limit`).
pub const MAX_BRANCH_POINTS: usize = crate::limits::BRANCH_POINTS.max as usize;
/// The largest step along the branch, in the scaled unknowns (the parameter as a fraction of
/// its range).
const H_MAX: f64 = 0.05;
/// The step control's nominal values (Allgower & Georg 1990, §6.1): the corrector's
/// contraction, the predictor's distance from the branch (scaled unknowns) and the tangent's
/// turn (rad) per step. A step that exceeds them is followed by a shorter one, one well under
/// them by a longer one.
const NOMINAL_CONTRACTION: f64 = 0.3;
const NOMINAL_DISTANCE: f64 = 0.05;
const NOMINAL_TURN: f64 = 0.1;
/// The smallest: below it the branch ends.
const H_MIN: f64 = 1e-7;
/// Corrector iterations allowed per step.
const MAX_CHORD: u32 = 12;

/// What a special point is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Special {
    /// The branch turns back in the parameter (a multiplier at +1).
    Fold,
    /// A multiplier crosses −1.
    PeriodDoubling,
    /// A complex pair crosses the unit circle.
    NeimarkSacker,
    /// A real multiplier crosses +1 where the branch goes on (no fold): a branch point, e.g.
    /// the symmetry-breaking pitchfork of a symmetric orbit.
    BranchPoint,
    /// The impacts per orbit change: an impact appears or vanishes (a grazing contact).
    Grazing,
}

impl Special {
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Special::Fold => "fold",
            Special::PeriodDoubling => "period doubling",
            Special::NeimarkSacker => "Neimark-Sacker",
            Special::BranchPoint => "branch point",
            Special::Grazing => "grazing",
        }
    }
}

/// One point of a branch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BranchPoint {
    /// The parameter's value (its row's plain unit).
    pub value: f64,
    pub amplitude_m: f64,
    pub stable: bool,
    /// Largest |λ|.
    pub multiplier_abs_max: f64,
    pub impacts_per_orbit: u32,
    pub periods: u32,
    /// `3/1`, `2/1 sym`.
    pub orbit: String,
    /// The state at the force's phase 0 (m, m/s).
    pub x_m: f64,
    pub v_m_s: f64,
    pub z_m: f64,
    pub zdot_m_s: f64,
    /// x(kT) at each of the orbit's periods (m, [`PeriodicOrbit::strobe_m`]): what a
    /// bifurcation diagram's samples are, for drawing the branch over them. Not written to
    /// files (x_m is the first).
    #[serde(skip)]
    pub strobe_m: Vec<f64>,
}

/// A special point located on a branch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpecialPoint {
    pub kind: Special,
    /// The parameter's value there.
    pub value: f64,
    pub amplitude_m: f64,
}

/// A continued family of periodic orbits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Branch {
    /// The varied parameter: its row's name and plain unit.
    pub name: String,
    pub unit: String,
    pub points: Vec<BranchPoint>,
    pub specials: Vec<SpecialPoint>,
    /// Why the branch ended before the range's end, if it did.
    pub ended: Option<String>,
}

/// A converged point in the continuation's unknowns, with what it needs for the next step.
#[derive(Debug, Clone)]
struct Node {
    y: V5,
    /// `[DG | ∂G/∂λ̃]` at `y`.
    jac: M45,
    /// `DPⁿ` (scaled).
    dp: Matrix4<f64>,
    tangent: V5,
    orbit: PeriodicOrbit,
}

/// The continuation's problem: the design at each parameter value and the section.
struct Problem<'a> {
    base: ValidDesign,
    vary: &'a Vary,
    from: f64,
    to: f64,
    phase: f64,
    periods: u32,
    symmetric: bool,
    /// The scales of the state, fixed along the branch (those at `from`).
    l: f64,
    v: f64,
    cancel: Option<&'a AtomicBool>,
}

impl<'a> Problem<'a> {
    fn value(&self, lt: f64) -> f64 {
        self.from + lt * (self.to - self.from)
    }

    fn section(&self, lt: f64) -> Result<Section<'a>, ThudError> {
        // A step may pass the range's end before it is landed on it; where that end is the
        // row's own bound, the value is held at the bound, which the row's check accepts.
        let value = self.vary.row.range().map_or(self.value(lt), |r| self.value(lt).clamp(r.min, r.max));
        let d = crate::study::set(self.base.design().clone(), self.vary.row, value).check()?;
        let mut s = Section::new(d.damper, self.phase, self.periods, self.symmetric, self.cancel);
        s.l = self.l;
        s.v = self.v;
        Ok(s)
    }

    /// `G(y)`.
    fn g(&self, y: &V5) -> Result<Vector4<f64>, ThudError> {
        Ok(self.g_with(y)?.0)
    }

    /// `G(y)` and the section that mapped `y`, which keeps that run's contacts for the
    /// Jacobian there.
    fn g_with(&self, y: &V5) -> Result<(Vector4<f64>, Section<'a>), ThudError> {
        let u = y.fixed_rows::<4>(0).into_owned();
        let mut sec = self.section(y[4])?;
        let g = sec.map(&u)? - u;
        Ok((g, sec))
    }

    /// `[DG | ∂G/∂λ̃]` and `DPⁿ` at `y` (given `G(y)`, and `sec`, the section at `y`'s value),
    /// `∂G/∂λ̃` by a forward difference.
    fn jacobian(&self, y: &V5, gy: &Vector4<f64>, sec: &mut Section) -> Result<(M45, Matrix4<f64>), ThudError> {
        let u = y.fixed_rows::<4>(0).into_owned();
        let pu = gy + u;
        let dp = sec.jacobian(&u, &pu)?;
        let mut j = M45::zeros();
        j.fixed_view_mut::<4, 4>(0, 0).copy_from(&(dp - Matrix4::identity()));
        let h = orbit::JACOBIAN_STEP;
        let mut yl = *y;
        yl[4] += h;
        let gl = self.g(&yl)?;
        j.set_column(4, &((gl - gy) / h));
        Ok((j, dp))
    }

    /// The converged point `y` as a node: its Jacobian, tangent (oriented along `previous`)
    /// and orbit. `sec`: the section that mapped `y` last, if at hand (it saves a run).
    fn node(
        &self,
        y: V5,
        gy: &Vector4<f64>,
        previous: Option<&V5>,
        sec: Option<Section<'a>>,
    ) -> Result<Node, ThudError> {
        let mut sec = match sec {
            Some(s) => s,
            None => self.section(y[4])?,
        };
        let (jac, dp) = self.jacobian(&y, gy, &mut sec)?;
        let u = y.fixed_rows::<4>(0).into_owned();
        let root = Root { u, jac: dp, residual: gy.amax(), iterations: 0 };
        let orbit = orbit::report(&mut sec, &root)?;
        // An orbit without impacts: the ball floats (a second null direction of the Jacobian).
        let mut t = null_vector(&jac, orbit.impacts.is_empty());
        let forward = previous.map_or(t[4] >= 0.0, |p| t.dot(p) >= 0.0);
        if !forward {
            t = -t;
        }
        Ok(Node { y, jac, dp, tangent: t, orbit })
    }

    /// The point on the branch at arclength `h` from `n`: the predictor `n.y + h·t`, then
    /// quasi-Newton on `G = 0`, `t·(y − n.y) = h`, starting from `n`'s Jacobian and updated by
    /// Broyden's rank-one formula after each step (Allgower & Georg 1990, §7.2), so it converges
    /// superlinearly where the chord method with a frozen Jacobian converges only linearly.
    fn correct(&self, n: &Node, h: f64) -> Result<Corrected<'a>, ThudError> {
        let mut a = SMatrix::<f64, 5, 5>::zeros();
        a.fixed_view_mut::<4, 5>(0, 0).copy_from(&n.jac);
        a.set_row(4, &n.tangent.transpose());
        let mut y = n.y + n.tangent * h;
        let mut g = self.g(&y)?;
        let (mut first, mut second) = (0.0, 0.0);
        for it in 1..=MAX_CHORD {
            let arc = n.tangent.dot(&(y - n.y)) - h;
            let rhs = V5::new(g[0], g[1], g[2], g[3], arc);
            // Least squares (SVD): an orbit without impacts has a free ball position, and the
            // shortest correction leaves it where it is.
            let dy = a.svd(true, true).solve(&rhs, 1e-12).map_err(orbit::not_found)?;
            y -= dy;
            if !y.amax().is_finite() || dy.amax() > 0.5 {
                break;
            }
            match it {
                1 => first = dy.norm(),
                2 => second = dy.norm(),
                _ => {}
            }
            let (next, sec) = self.g_with(&y)?;
            if dy.amax() <= 1e-11 && next.amax() <= 1e-9 {
                let contraction = if first > 0.0 { second / first } else { 0.0 };
                return Ok(Corrected { y, g: next, sec, distance: first, contraction });
            }
            broyden(&mut a, &(-dy), &(next - g));
            g = next;
        }
        Err(orbit::not_found("the corrector did not converge"))
    }
}

/// A corrected point: `y` with `G(y)`, the predictor's distance from the branch (the first
/// correction's length) and the corrector's contraction (the second correction's length over
/// the first's), which set the next step.
struct Corrected<'a> {
    y: V5,
    g: Vector4<f64>,
    /// The section that mapped `y`.
    sec: Section<'a>,
    distance: f64,
    contraction: f64,
}

/// Broyden's update of the `G` rows of `a` for the step `s` that changed `G` by `dg`:
/// `A ← A + (dg − A·s)·sᵀ / (sᵀs)`, the arclength row (linear) left as it is.
fn broyden(a: &mut SMatrix<f64, 5, 5>, s: &V5, dg: &Vector4<f64>) {
    let ss = s.norm_squared();
    if ss == 0.0 {
        return;
    }
    let rows = a.fixed_view::<4, 5>(0, 0).into_owned();
    let update = (dg - rows * s) * s.transpose() / ss;
    let mut rows = a.fixed_view_mut::<4, 5>(0, 0);
    rows += update;
}

impl Problem<'_> {
    /// Steps over a point where the corrector fails (a grazing contact: an impact appearing or
    /// vanishing) by a jump in the parameter, `JUMPS` of the range in the tangent's direction,
    /// solving by Newton's method at the new value from the last state. The new node's tangent
    /// keeps the parameter's direction.
    fn jump(&self, n: &Node) -> Option<Node> {
        const JUMPS: [f64; 3] = [2e-4, 1e-3, 5e-3];
        let dir = if n.tangent[4] >= 0.0 { 1.0 } else { -1.0 };
        for dl in JUMPS {
            let lt = n.y[4] + dir * dl;
            let Ok(mut sec) = self.section(lt) else { continue };
            let u0 = n.y.fixed_rows::<4>(0).into_owned();
            let Ok(root) = orbit::newton(&mut sec, u0) else { continue };
            let y = V5::new(root.u[0], root.u[1], root.u[2], root.u[3], lt);
            let Ok((g, sec)) = self.g_with(&y) else { continue };
            let along = V5::new(0.0, 0.0, 0.0, 0.0, dir);
            if let Ok(node) = self.node(y, &g, Some(&along), Some(sec)) {
                return Some(node);
            }
        }
        None
    }
}

/// The unit null vector of a 4×5 matrix of rank 4; with `floats` (an orbit without impacts:
/// the ball's position is free, a second null direction) the one with no component along the
/// ball's position.
fn null_vector(j: &M45, floats: bool) -> V5 {
    let mut sq = SMatrix::<f64, 5, 5>::zeros();
    sq.fixed_view_mut::<4, 5>(0, 0).copy_from(j);
    if floats {
        sq[(4, 2)] = 1.0;
    }
    let svd = sq.svd(false, true);
    let vt = svd.v_t.unwrap_or_else(SMatrix::<f64, 5, 5>::identity);
    // The singular values are sorted in decreasing order: the last row spans the null space.
    let (k, _) = svd.singular_values.argmin();
    vt.row(k).transpose().normalize()
}

/// The test functions at a node: the tangent's λ component, det(DPⁿ + I), the complex
/// multipliers outside the unit circle, and the impacts per orbit.
fn tests(n: &Node) -> (f64, f64, usize, u32) {
    let pd = (n.dp + Matrix4::identity()).determinant();
    let ns = n.orbit.multipliers.iter().filter(|m| m.im.abs() > 1e-9 && m.abs > 1.0).count();
    (n.tangent[4], pd, ns, n.orbit.impacts_per_orbit)
}

fn point(p: &Problem, n: &Node) -> BranchPoint {
    let o = &n.orbit;
    BranchPoint {
        value: p.value(n.y[4]),
        amplitude_m: o.amplitude_m,
        stable: o.stable,
        multiplier_abs_max: o.multipliers.first().map_or(0.0, |m| m.abs),
        impacts_per_orbit: o.impacts_per_orbit,
        periods: o.periods,
        orbit: o.label(),
        x_m: o.x_m,
        v_m_s: o.v_m_s,
        z_m: o.z_m,
        zdot_m_s: o.zdot_m_s,
        strobe_m: o.strobe_m.clone(),
    }
}

/// Continues the orbit of `base` (found by [`orbit::find`] with `req` at the first value of
/// `vary`) over `vary`'s range (its first and last values), `on_point(λ)` called at each point.
pub fn continue_branch(
    base: &ValidDesign,
    vary: &Vary,
    req: &Request,
    cancel: Option<&AtomicBool>,
    on_point: &dyn Fn(f64),
) -> Result<Branch, ThudError> {
    let (p, node) = start(base, vary, req, cancel)?;
    follow(&p, node, cancel, on_point)
}

/// Follows the branch of problem `p` from `node` to the range's end (or until it ends).
fn follow(
    p: &Problem,
    mut node: Node,
    cancel: Option<&AtomicBool>,
    on_point: &dyn Fn(f64),
) -> Result<Branch, ThudError> {
    let vary = p.vary;
    let mut b = Branch {
        name: vary.name().to_string(),
        unit: vary.unit().to_string(),
        points: vec![point(p, &node)],
        specials: Vec::new(),
        ended: None,
    };
    on_point(p.value(node.y[4]));
    let first = node.y;
    let mut h = H_MAX / 4.0;
    let cap = if p.base.damper.no_limit { usize::MAX } else { MAX_BRANCH_POINTS };
    while b.points.len() < cap {
        if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return Err(ThudError::Cancelled);
        }
        let next = p.correct(&node, h).and_then(|c| {
            let (distance, contraction) = (c.distance, c.contraction);
            p.node(c.y, &c.g, Some(&node.tangent), Some(c.sec)).map(|n| (n, distance, contraction))
        });
        match next {
            Ok((next, distance, contraction)) => {
                let factor = step_factor(distance, contraction, node.tangent.dot(&next.tangent));
                // Back where it started: a closed branch (an isola), followed once round.
                let closes = b.points.len() > 2 && (next.y - first).norm() < h && (node.y - first).norm() >= h;
                if advance(p, &mut node, next, h, &mut b, on_point) {
                    return Ok(b);
                }
                if closes {
                    b.ended = Some(ISOLA.to_string());
                    return Ok(b);
                }
                h = (h / factor).min(H_MAX);
            }
            Err(ThudError::Cancelled) => return Err(ThudError::Cancelled),
            Err(e) => {
                h *= 0.5;
                if h >= H_MIN {
                    continue;
                }
                // The corrector fails at any step (a grazing contact: the map's derivatives
                // blow up): step over the point in the parameter.
                let Some(next) = p.jump(&node) else {
                    b.ended = Some(format!("at {} {}: {e}", num6(p.value(node.y[4])), vary.unit()));
                    return Ok(b);
                };
                if advance(p, &mut node, next, h, &mut b, on_point) {
                    return Ok(b);
                }
                h = H_MAX / 16.0;
            }
        }
    }
    b.ended = Some(CAPPED.to_string());
    Ok(b)
}

/// The branches of periodic orbits over `vary`'s range through the stable orbits the attractor
/// search finds from the design's own start at `seeds` evenly spaced values of it
/// (`orbit::settle_to`): each continued from its seed both ways
/// to the range's ends (or until it ends), through folds and along unstable parts. A seed
/// whose orbit lies on a branch already continued (the same orbit type, within 1e-6 of the
/// scale at the branch's point nearest in value) starts none. Seeds where the motion settles
/// to no periodic orbit (chaos, a long period) start none either. The branches come in the
/// order of their seeds, each point in the order of the parameter along its way.
pub fn continue_family(
    base: &ValidDesign,
    vary: &Vary,
    seeds: usize,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn(f64) + Sync),
) -> Result<Vec<Branch>, ThudError> {
    use rayon::prelude::*;
    let (from, to) = range(vary)?;
    if !(2..=MAX_SEEDS).contains(&seeds) {
        return Err(ThudError::invalid("vary", format!("{seeds} seed values; give 2 to {MAX_SEEDS}")));
    }
    let values = crate::design::linspace(from, to, seeds);
    let found: Vec<Option<(f64, PeriodicOrbit)>> = values
        .par_iter()
        .map(|&v| {
            let d = crate::study::set(base.design().clone(), vary.row, v).check().ok()?;
            let p = &d.damper;
            let start = [0.0, p.v0_m_s, p.ball_position_m, p.ball_velocity_m_s];
            orbit::settle_to(p, start, 0.0, cancel).ok().map(|o| (v, o))
        })
        .collect();
    if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
        return Err(ThudError::Cancelled);
    }
    let mut branches: Vec<Branch> = Vec::new();
    for (v, o) in found.into_iter().flatten() {
        if branches.iter().any(|b| passes(b, v, &o)) {
            continue;
        }
        branches.push(both_ways(base, vary, v, &o, cancel, on_point)?);
    }
    Ok(branches)
}

/// How far past a period doubling the doubled orbit is looked for: this share of the range.
const PAST_DOUBLING: f64 = 0.01;

/// `branches` with, for each period doubling on them (and on the branches this adds, while
/// the doubled period is at most [`orbit::MAX_ORBIT_PERIODS`]), the branch of the doubled orbit
/// born there, continued both ways: branch switching at a period doubling. The doubled orbit is
/// found by the attractor search from the undoubled orbit's state just past the doubling
/// (1 % of the range, on the side where the undoubled orbit is unstable), where a
/// supercritical doubling's doubled orbit is stable; a doubling where none is found there (a
/// subcritical one: its doubled orbit is unstable), or whose doubled orbit lies on a branch
/// already continued, adds none. The added branches come after the given ones, in the order of
/// their doublings.
pub fn with_doublings(
    base: &ValidDesign,
    vary: &Vary,
    mut branches: Vec<Branch>,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn(f64) + Sync),
) -> Result<Vec<Branch>, ThudError> {
    let (from, to) = range(vary)?;
    let mut k = 0;
    while k < branches.len() {
        let doublings: Vec<SpecialPoint> =
            branches[k].specials.iter().filter(|s| s.kind == Special::PeriodDoubling).cloned().collect();
        for pd in &doublings {
            let Some((value, o)) = doubled_orbit(base, vary, &branches[k], pd, (from, to), cancel)? else { continue };
            if branches.iter().any(|b| passes(b, value, &o)) {
                continue;
            }
            branches.push(both_ways(base, vary, value, &o, cancel, on_point)?);
        }
        k += 1;
    }
    Ok(branches)
}

/// The doubled orbit born at the period doubling `pd` of branch `b`, found just past it (see
/// [`with_doublings`]), with the value it was found at; `None` where there is none to find.
fn doubled_orbit(
    base: &ValidDesign,
    vary: &Vary,
    b: &Branch,
    pd: &SpecialPoint,
    (from, to): (f64, f64),
    cancel: Option<&AtomicBool>,
) -> Result<Option<(f64, PeriodicOrbit)>, ThudError> {
    // The step of the branch across the doubling: its unstable end gives the side and the state.
    let across = b.points.windows(2).find(|w| {
        let (p, q) = (&w[0], &w[1]);
        (p.value - pd.value) * (q.value - pd.value) <= 0.0 && p.stable != q.stable
    });
    let Some(w) = across else { return Ok(None) };
    let unstable = if w[0].stable { &w[1] } else { &w[0] };
    if 2 * unstable.periods > orbit::MAX_ORBIT_PERIODS {
        return Ok(None);
    }
    let side = if unstable.value >= pd.value { 1.0 } else { -1.0 };
    let value = (pd.value + side * PAST_DOUBLING * (to - from).abs()).clamp(from.min(to), from.max(to));
    let d = crate::study::set(base.design().clone(), vary.row, value).check()?;
    let s = [unstable.x_m, unstable.v_m_s, unstable.x_m + unstable.z_m, unstable.v_m_s + unstable.zdot_m_s];
    match orbit::settle_to(&d.damper, s, 0.0, cancel) {
        Ok(o) if o.periods == 2 * unstable.periods => Ok(Some((value, o))),
        Err(ThudError::Cancelled) => Err(ThudError::Cancelled),
        _ => Ok(None),
    }
}

/// Why a branch cut by its work cap ([`MAX_BRANCH_POINTS`]) ended.
pub const CAPPED: &str = "the work cap of 5000 points of a continued branch (thud limits)";

impl Branch {
    /// Whether the branch's work cap cut it short.
    #[must_use]
    pub fn truncated(&self) -> bool {
        self.ended.as_deref().is_some_and(|e| e.contains(CAPPED))
    }
}

/// Why a branch that closed on itself ended.
const ISOLA: &str = "the branch closed on itself (an isola), followed once round";

/// The most seed values of [`continue_family`].
pub const MAX_SEEDS: usize = 1000;

/// Whether branch `b` passes through the orbit `o` at `value`, or through its mirror image
/// (`s(t) → −s(t + T/2)`: the same type and amplitude): a step of the branch across `value`
/// (two successive points on either side of it) of `o`'s type whose amplitude, interpolated
/// to `value`, is `o`'s within 1e-3 (relative).
fn passes(b: &Branch, value: f64, o: &PeriodicOrbit) -> bool {
    b.points.windows(2).any(|w| {
        let (p, q) = (&w[0], &w[1]);
        let across = (p.value - value) * (q.value - value) <= 0.0 && p.value != q.value;
        let same = |x: &BranchPoint| x.periods == o.periods && x.impacts_per_orbit == o.impacts_per_orbit;
        if !across || !same(p) || !same(q) {
            return false;
        }
        let s = (value - p.value) / (q.value - p.value);
        let amplitude = p.amplitude_m + s * (q.amplitude_m - p.amplitude_m);
        (amplitude - o.amplitude_m).abs() <= 1e-3 * o.amplitude_m.max(1e-12)
    })
}

/// The branch through the orbit `o` at `value`, continued down and up the range and joined.
fn both_ways(
    base: &ValidDesign,
    vary: &Vary,
    value: f64,
    o: &PeriodicOrbit,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn(f64) + Sync),
) -> Result<Branch, ThudError> {
    let (p, up) = start_at(base, vary, value, o, false, cancel)?;
    let mut down_node = up.clone();
    down_node.tangent = -down_node.tangent;
    // The two directions on two threads; an isola's second one is dropped.
    let (b, down) = rayon::join(|| follow(&p, up, cancel, on_point), || follow(&p, down_node, cancel, on_point));
    let mut b = b?;
    if b.ended.as_deref() == Some(ISOLA) {
        return Ok(b);
    }
    let down = down?;
    let mut points: Vec<BranchPoint> = down.points.into_iter().skip(1).rev().collect();
    points.append(&mut b.points);
    b.points = points;
    let mut specials = down.specials;
    specials.reverse();
    specials.append(&mut b.specials);
    b.specials = specials;
    b.ended = match (down.ended, b.ended) {
        (Some(d), Some(u)) => Some(format!("{d}; {u}")),
        (d, u) => d.or(u),
    };
    Ok(b)
}

/// The step's change factor from the last step's corrector and the turn of the tangent
/// (Allgower & Georg 1990, §6.1): the largest of √(κ/κ̃), √(δ/δ̃) and α/α̃ against their
/// nominal values, held to [1/2, 2]; the next step is `h / factor`.
fn step_factor(distance: f64, contraction: f64, cos_turn: f64) -> f64 {
    let angle = cos_turn.clamp(-1.0, 1.0).acos();
    let f =
        (contraction / NOMINAL_CONTRACTION).sqrt().max((distance / NOMINAL_DISTANCE).sqrt()).max(angle / NOMINAL_TURN);
    f.clamp(0.5, 2.0)
}

/// Six significant digits.
fn num6(v: f64) -> String {
    format!("{v:.6}")
}

/// The range of `vary`: its first and last values, which must differ.
fn range(vary: &Vary) -> Result<(f64, f64), ThudError> {
    let (Some(&from), Some(&to)) = (vary.values.first(), vary.values.last()) else {
        return Err(ThudError::invalid("vary", "no values; give NAME=FROM:TO"));
    };
    if from == to {
        return Err(ThudError::invalid("vary", format!("FROM = TO = {from}; give a range")));
    }
    Ok((from, to))
}

/// The problem and its first node: the orbit at the range's start, its section in flight.
fn start<'a>(
    base: &ValidDesign,
    vary: &'a Vary,
    req: &Request,
    cancel: Option<&'a AtomicBool>,
) -> Result<(Problem<'a>, Node), ThudError> {
    let (from, _) = range(vary)?;
    let d0 = crate::study::set(base.design().clone(), vary.row, from).check()?;
    let first = orbit::find(&d0, req, cancel)?;
    start_at(base, vary, from, &first, req.symmetric, cancel)
}

/// The problem and its first node from the orbit `first` of the design at `value`, a value of
/// the range (the tangent pointing up the range).
fn start_at<'a>(
    base: &ValidDesign,
    vary: &'a Vary,
    value: f64,
    first: &PeriodicOrbit,
    symmetric: bool,
    cancel: Option<&'a AtomicBool>,
) -> Result<(Problem<'a>, Node), ThudError> {
    let (from, to) = range(vary)?;
    let d0 = crate::study::set(base.design().clone(), vary.row, value).check()?;
    let probe = Section::new(d0.damper, 0.0, 1, false, cancel);
    let omega = std::f64::consts::TAU * d0.damper.freq_hz;
    let s0 = [first.x_m, first.v_m_s, first.x_m + first.z_m, first.v_m_s + first.zdot_m_s];
    let n = first.periods;
    let run = crate::damper::flow(&d0.damper, s0, 0.0, &[f64::from(n) / d0.damper.freq_hz], cancel);
    let phase = orbit::flight_phase(&run.impacts, 0.0, omega);
    let at = crate::damper::flow(&d0.damper, s0, 0.0, &[phase / omega], cancel);
    let s_phase = at.states.first().copied().ok_or_else(|| orbit::not_found("the run to the section stopped"))?;
    let p = Problem {
        base: base.clone(),
        vary,
        from,
        to,
        phase,
        periods: n,
        symmetric: symmetric && first.symmetric,
        l: probe.l,
        v: probe.v,
        cancel,
    };
    let lt = (value - from) / (to - from);
    let mut y = V5::new(s_phase[0] / p.l, s_phase[1] / p.v, s_phase[2] / p.l, s_phase[3] / p.v, lt);
    // Polish the first point on the fixed scales (the symmetric map's fixed point, too).
    let mut g = p.g(&y)?;
    for _ in 0..3 {
        let (j, _) = p.jacobian(&y, &g, &mut p.section(y[4])?)?;
        let a = j.fixed_view::<4, 4>(0, 0).into_owned();
        if let Some(step) = a.lu().solve(&(-g)) {
            for k in 0..4 {
                y[k] += step[k];
            }
        }
        g = p.g(&y)?;
        if g.amax() <= 1e-11 {
            break;
        }
    }
    let node = p.node(y, &g, None, None)?;
    Ok((p, node))
}

/// Takes `next` as the branch's next point after `node`, with the special points between them;
/// on the range's end, the last point on it. Returns whether the branch is done.
fn advance(p: &Problem, node: &mut Node, next: Node, h: f64, b: &mut Branch, on_point: &dyn Fn(f64)) -> bool {
    locate(p, node, &next, h, &mut b.specials);
    if next.y[4] > 1.0 || next.y[4] < 0.0 {
        if let Ok(end) = land(p, node, &next) {
            b.points.push(point(p, &end));
            on_point(p.value(end.y[4]));
        }
        return true;
    }
    b.points.push(point(p, &next));
    on_point(p.value(next.y[4]));
    *node = next;
    false
}

/// The point where the step from `a` to `b` crosses the range's end (secant on λ̃).
fn land(p: &Problem, a: &Node, b: &Node) -> Result<Node, ThudError> {
    let target = if b.y[4] > 1.0 { 1.0 } else { 0.0 };
    let mut h = a.tangent.dot(&(b.y - a.y));
    let mut lo = (0.0, a.y[4] - target);
    let mut hi = (h, b.y[4] - target);
    let mut best = None;
    for _ in 0..6 {
        h = lo.0 - lo.1 * (hi.0 - lo.0) / (hi.1 - lo.1);
        let c = p.correct(a, h)?;
        let n = p.node(c.y, &c.g, Some(&a.tangent), Some(c.sec))?;
        let f = n.y[4] - target;
        best = Some(n);
        if f.abs() < 1e-10 {
            break;
        }
        if f.signum() == lo.1.signum() {
            lo = (h, f);
        } else {
            hi = (h, f);
        }
    }
    best.ok_or_else(|| orbit::not_found("the range's end was not reached"))
}

/// Finds the special points between `a` and `b` (one step `h` apart) and appends them.
fn locate(p: &Problem, a: &Node, b: &Node, h: f64, out: &mut Vec<SpecialPoint>) {
    let (ta, tb) = (tests(a), tests(b));
    let mut found = |kind: Special, f: &dyn Fn(&Node) -> f64| {
        let x = secant(p, a, h, f).unwrap_or_else(|| {
            // Linear interpolation where the secant could not be corrected.
            let (fa, fb) = (f(a), f(b));
            let s = fa / (fa - fb);
            (
                p.value(a.y[4] + s * (b.y[4] - a.y[4])),
                a.orbit.amplitude_m + s * (b.orbit.amplitude_m - a.orbit.amplitude_m),
            )
        });
        out.push(SpecialPoint { kind, value: x.0, amplitude_m: x.1 });
    };
    if ta.0.signum() != tb.0.signum() {
        found(Special::Fold, &|n: &Node| n.tangent[4]);
    }
    let bp = |n: &Node| (n.dp - Matrix4::identity()).determinant();
    if ta.0.signum() == tb.0.signum() && bp(a).signum() != bp(b).signum() && ta.3 == tb.3 {
        found(Special::BranchPoint, &bp);
    }
    if ta.1.signum() != tb.1.signum() && ta.3 == tb.3 {
        found(Special::PeriodDoubling, &|n: &Node| (n.dp + Matrix4::identity()).determinant());
    }
    if ta.2 != tb.2 && ta.3 == tb.3 {
        found(Special::NeimarkSacker, &|n: &Node| {
            n.orbit.multipliers.iter().find(|m| m.im.abs() > 1e-9).map_or(0.0, |m| m.abs - 1.0)
        });
    }
    if ta.3 != tb.3 {
        let s = 0.5;
        out.push(SpecialPoint {
            kind: Special::Grazing,
            value: p.value(a.y[4] + s * (b.y[4] - a.y[4])),
            amplitude_m: a.orbit.amplitude_m + s * (b.orbit.amplitude_m - a.orbit.amplitude_m),
        });
    }
}

/// The root of the test function `f` between `a` (arclength 0) and arclength `h` by the secant
/// method, each iterate corrected onto the branch: (value, amplitude).
fn secant(p: &Problem, a: &Node, h: f64, f: &dyn Fn(&Node) -> f64) -> Option<(f64, f64)> {
    let c = p.correct(a, h).ok()?;
    let b = p.node(c.y, &c.g, Some(&a.tangent), Some(c.sec)).ok()?;
    let (mut s0, mut f0) = (0.0, f(a));
    let (mut s1, mut f1) = (h, f(&b));
    let mut last = (p.value(b.y[4]), b.orbit.amplitude_m);
    for _ in 0..8 {
        if f1 == f0 {
            break;
        }
        let s = s1 - f1 * (s1 - s0) / (f1 - f0);
        let s = s.clamp(0.0, h);
        let c = p.correct(a, s).ok()?;
        let n = p.node(c.y, &c.g, Some(&a.tangent), Some(c.sec)).ok()?;
        last = (p.value(n.y[4]), n.orbit.amplitude_m);
        let fs = f(&n);
        if (s - s1).abs() <= 1e-9 * h.abs().max(1e-12) || fs == 0.0 {
            break;
        }
        (s0, f0, s1, f1) = (s1, f1, s, fs);
    }
    Some(last)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cap_s_note_names_the_cap_thud_limits_lists() {
        assert!(CAPPED.contains(&MAX_BRANCH_POINTS.to_string()));
        assert!(crate::limits::CAPS.iter().any(|c| c.max as usize == MAX_BRANCH_POINTS && CAPPED.contains(c.what)));
    }

    /// Broyden's update makes the matrix map the step to the change it saw, and leaves the
    /// arclength row alone.
    #[test]
    fn broyden_s_update_meets_the_secant_condition() {
        let mut a = SMatrix::<f64, 5, 5>::from_fn(|r, c| if r == c { 2.0 } else { 0.1 * (r + c) as f64 });
        let row = a.row(4).into_owned();
        let s = V5::new(0.1, -0.2, 0.3, 0.05, 0.01);
        let dg = Vector4::new(1.0, 2.0, -1.0, 0.5);
        broyden(&mut a, &s, &dg);
        let seen = a.fixed_view::<4, 5>(0, 0) * s;
        assert!((seen - dg).amax() < 1e-12, "{seen} vs {dg}");
        assert_eq!(a.row(4).into_owned(), row);
    }
}
