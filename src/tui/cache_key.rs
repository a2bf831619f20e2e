//! The keys the explorer's results are tagged and cached with: small hashable structs of what
//! each result depends on, one type per kind of result. A result whose key differs from the
//! live design's is stale; equal keys let the worker's caches answer.
//!
//! Each key is built from the design's serialized form ([`Fingerprint`]: serde's fields as
//! tokens, every `f64` as its bits), with what the result does not depend on set aside first
//! (the thresholds, which are applied on draw; a chart's mass and gap; a response curve's f).
//! So a parameter added to the engine's structs counts in every key without an edit here, as
//! it did when the keys were JSON texts, and two keys compare without formatting any text.

use std::sync::Arc;

use super::compute::{response_design, FreqBand, Grids};
pub use super::fingerprint::Bits;
use super::fingerprint::Fingerprint;
use crate::acoustics::{Observer, Radiation};
use crate::design::{self, Design, Thresholds};

/// What a simulation depends on: the damper, the ball, the materials and the solver (shared:
/// every report of a job carries its key, so a clone is a count).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct SimKey(Arc<Fingerprint>);

impl SimKey {
    /// The key of the simulation of `d`.
    pub fn of(d: &Design) -> Self {
        Self(Arc::new(Fingerprint::of(&(&d.damper, &d.ball, &d.materials, &d.solver))))
    }
}

/// What the sound at the observer depends on beyond each impact: the observer and the
/// radiation (source, quadrupole signs, air, pulse shape). Shared, as [`SimKey`].
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct SoundKey(Arc<Fingerprint>);

impl SoundKey {
    /// The key of the sound of `d` at its observer.
    pub fn of(d: &Design) -> Self {
        Self(Arc::new(Fingerprint::of(&(&d.observer, &d.radiation))))
    }
}

/// A whole design but its zone thresholds (zones are classified on draw, so a threshold edit
/// asks for nothing): what its acoustics depend on.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct DesignKey(Arc<Fingerprint>);

impl DesignKey {
    /// The key of `d` without its thresholds.
    pub fn of(d: &Design) -> Self {
        let mut d = d.clone();
        d.thresholds = Thresholds::default();
        Self(Arc::new(Fingerprint::of(&d)))
    }
}

/// What the readout of a design depends on: the design (thresholds aside) and, with N > 1,
/// the ensemble size (N = 0 and 1 both mean the single run).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct ReadoutKey {
    design: DesignKey,
    ensemble: Option<usize>,
}

impl ReadoutKey {
    /// The key of the readout of `d` with `runs` runs.
    pub fn of(d: &Design, runs: usize) -> Self {
        Self { design: DesignKey::of(d), ensemble: (runs > 1).then_some(runs) }
    }
}

/// What a chart depends on: the design but its mass, gap, thresholds and sound (a change of
/// observer relevels the chart instead of sweeping it again), the sizes of the grids, and with
/// N > 1 runs a cell the ensemble size and the sound (an ensemble chart is swept again for a new
/// observer: its runs' zones, and so how many agree, depend on it).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct ChartKey {
    /// The design with mass and gap zeroed, thresholds and sound at their defaults.
    sweep: DesignKey,
    /// (masses, gaps) of the coarse pass, if any.
    coarse: Option<(usize, usize)>,
    /// (masses, gaps) of the fine pass.
    fine: (usize, usize),
    ensemble: Option<(usize, SoundKey)>,
}

impl ChartKey {
    /// The key of the single-run chart of `d` over `grids` (what a relevel keeps).
    pub fn of(d: &Design, grids: &Grids) -> Self {
        let mut swept = design::variant(d, 0.0, 0.0);
        swept.observer = Observer::new(0.0, 0.0);
        swept.radiation = Radiation::default();
        let size = |masses: &[f64], gaps: &[f64]| (masses.len(), gaps.len());
        Self {
            sweep: DesignKey::of(&swept),
            coarse: grids.coarse.as_ref().map(|g| size(&g.masses_kg, &g.gaps_m)),
            fine: size(&grids.fine.masses_kg, &grids.fine.gaps_m),
            ensemble: None,
        }
    }

    /// The key of the chart of `d` over `grids` with `runs` runs a cell.
    pub fn with_runs(d: &Design, grids: &Grids, runs: usize) -> Self {
        Self { ensemble: (runs > 1).then(|| (runs, SoundKey::of(d))), ..Self::of(d, grids) }
    }
}

/// What a response curve depends on: the design from rest without its forcing frequency
/// ([`response_design`]: the curve does not depend on f, so a change of f moves the marker
/// only) and the band.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct ResponseKey {
    design: DesignKey,
    /// From and to (Hz).
    band: [Bits; 2],
    points: usize,
}

impl ResponseKey {
    /// The key of the response curve of `d` over `band`.
    pub fn of(d: &Design, band: &FreqBand) -> Self {
        let FreqBand { from_hz, to_hz, points } = *band;
        Self { design: DesignKey::of(&response_design(d)), band: [from_hz, to_hz].map(Bits::from), points }
    }
}

/// What a bifurcation pass depends on: the simulation of the design without its forcing
/// frequency (f is the varied value; the orbits do not depend on the observer) and the band.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct BifurcationKey {
    sim: SimKey,
    /// From and to (Hz).
    band: [Bits; 2],
    points: usize,
}

impl BifurcationKey {
    /// The key of the bifurcation diagram of `d` over `band`.
    pub fn of(d: &Design, band: &FreqBand) -> Self {
        let mut free_f = d.clone();
        free_f.damper.freq_hz = 0.0;
        let FreqBand { from_hz, to_hz, points } = *band;
        Self { sim: SimKey::of(&free_f), band: [from_hz, to_hz].map(Bits::from), points }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::acoustics::{PulseShape, QuadSigns, Source};
    use crate::damper::Solver;
    use crate::design::{BallSize, Materials, U0MaxRule};
    use crate::tui::compute::default_band;

    #[test]
    fn equal_designs_give_equal_keys() {
        let (a, b) = (Design::default(), Design::default());
        assert_eq!(SimKey::of(&a), SimKey::of(&b));
        assert_eq!(ReadoutKey::of(&a, 4), ReadoutKey::of(&b, 4));
        assert_eq!(ChartKey::with_runs(&a, &Grids::default(), 3), ChartKey::with_runs(&b, &Grids::default(), 3));
        assert_eq!(ResponseKey::of(&a, &default_band(&a)), ResponseKey::of(&b, &default_band(&b)));
        let mut c = Design::default();
        c.damper.force_n = -0.0;
        assert_eq!(SimKey::of(&a), SimKey::of(&c), "−0 is 0");
    }

    #[test]
    fn a_change_of_f_keeps_the_response_key_and_changes_the_sim_key() {
        let mut a = Design::default();
        a.damper.force_n = 1.0;
        a.damper.freq_hz = 5.0;
        let mut b = a.clone();
        b.damper.freq_hz = 6.5;
        let band = default_band(&a);
        assert_eq!(ResponseKey::of(&a, &band), ResponseKey::of(&b, &band), "the curve does not depend on f");
        assert_ne!(SimKey::of(&a), SimKey::of(&b), "the run does");
        let mut c = a.clone();
        c.damper.force_n = 2.0;
        assert_ne!(ResponseKey::of(&a, &band), ResponseKey::of(&c, &band), "the curve depends on F0");
    }

    #[test]
    fn a_change_of_mass_changes_the_sim_key_not_the_chart_key() {
        let a = Design::default();
        let b = design::variant(&a, a.damper.impact_mass_kg + 1e-3, a.damper.gap_m);
        assert_ne!(SimKey::of(&a), SimKey::of(&b));
        assert_ne!(ReadoutKey::of(&a, 1), ReadoutKey::of(&b, 1));
        assert_eq!(ChartKey::of(&a, &Grids::default()), ChartKey::of(&b, &Grids::default()), "a chart spans masses");
        let mut heavy = a.clone();
        heavy.damper.main_mass_kg *= 2.0;
        assert_ne!(ChartKey::of(&a, &Grids::default()), ChartKey::of(&heavy, &Grids::default()));
    }

    /// The keys as they were before they were typed: the serialized parameters.
    mod json_keys {
        use super::*;

        fn json<T: serde::Serialize>(v: &T) -> String {
            serde_json::to_string(v).unwrap()
        }

        pub fn sim(d: &Design) -> String {
            json(&(&d.damper, &d.ball, &d.materials, &d.solver))
        }

        pub fn readout(d: &Design, runs: usize) -> String {
            let mut a = d.clone();
            a.thresholds = Thresholds::default();
            if runs > 1 {
                format!("{}|ensemble {runs}", json(&a))
            } else {
                json(&a)
            }
        }

        pub fn sound(d: &Design) -> String {
            json(&(&d.observer, &d.radiation))
        }

        pub fn chart(d: &Design, grids: &Grids, runs: usize) -> String {
            let mut c = design::variant(d, 0.0, 0.0);
            c.thresholds = Thresholds::default();
            c.observer = Observer::new(0.0, 0.0);
            c.radiation = Radiation::default();
            let sizes = |g: &crate::tui::compute::Grid| (g.masses_kg.len(), g.gaps_m.len());
            let key = format!("{}|{:?}|{:?}", json(&c), grids.coarse.as_ref().map(sizes), sizes(&grids.fine));
            if runs > 1 {
                format!("{key}|ensemble {runs}|{}", sound(d))
            } else {
                key
            }
        }

        pub fn response(d: &Design, band: &FreqBand) -> String {
            format!("{}|{:?}", json(&response_design(d)), band)
        }
    }

    /// The base design (forced, so that f and F0 count) and one change of each of its inputs.
    fn changed_designs() -> (Design, Vec<(&'static str, Design)>) {
        let mut base = Design::default();
        base.damper.force_n = 1.0;
        base.damper.freq_hz = 5.0;
        let change = |what: &'static str, f: &dyn Fn(&mut Design)| {
            let mut d = base.clone();
            f(&mut d);
            (what, d)
        };
        let changes = vec![
            change("nothing", &|_| {}),
            change("M", &|d| d.damper.main_mass_kg *= 1.5),
            change("K", &|d| d.damper.stiffness_n_m *= 1.5),
            change("C", &|d| d.damper.damping_n_s_m *= 1.5),
            change("m", &|d| d.damper.impact_mass_kg *= 1.5),
            change("d", &|d| d.damper.gap_m *= 1.5),
            change("K_HZ", &|d| d.damper.k_hz *= 1.5),
            change("c1", &|d| d.damper.c1_n_s_m *= 1.5),
            change("no tension", &|d| d.damper.no_tension = !d.damper.no_tension),
            change("v0", &|d| d.damper.v0_m_s *= 1.5),
            change("duration", &|d| d.damper.duration_s *= 1.5),
            change("F0", &|d| d.damper.force_n *= 1.5),
            change("f", &|d| d.damper.freq_hz *= 1.5),
            change("y0", &|d| d.damper.ball_position_m = 0.001),
            change("w0", &|d| d.damper.ball_velocity_m_s = 0.1),
            change("periods", &|d| d.damper.steady_periods += 1),
            change("settle", &|d| d.damper.settle = !d.damper.settle),
            change("radius", &|d| d.ball = BallSize::Radius(0.01)),
            change("materials", &|d| {
                d.materials = Some(Materials::new("steel", "steel"));
            }),
            change("solver", &|d| d.solver = Solver::newmark_default()),
            change("r", &|d| d.observer.r_m *= 1.5),
            change("θ", &|d| d.observer.theta_rad *= 0.5),
            change("source", &|d| d.radiation.source = Source::Dipole),
            change("quad signs", &|d| d.radiation.quad_signs = QuadSigns::Paper),
            change("ρc", &|d| d.radiation.air.rho_c_pa_s_m *= 1.1),
            change("c", &|d| d.radiation.air.c_m_s *= 1.1),
            change("pulse", &|d| d.radiation.pulse = PulseShape::Hertz),
            change("U0max rule", &|d| d.u0max_rule = U0MaxRule::WholeRun),
            change("L*", &|d| d.thresholds.spl_db -= 5.0),
            change("e*", &|d| d.thresholds.inclination_cm_s *= 2.0),
        ];
        (base, changes)
    }

    #[test]
    fn typed_keys_tell_designs_apart_exactly_as_the_serialized_keys_did() {
        let (base, changes) = changed_designs();
        let grids = Grids::default();
        let band = default_band(&base);
        for (what, d) in &changes {
            let same = |typed: bool, json: bool, key: &str| {
                assert_eq!(typed, json, "{key} key after a change of {what}: typed equal {typed}, serialized {json}");
            };
            same(SimKey::of(&base) == SimKey::of(d), json_keys::sim(&base) == json_keys::sim(d), "sim");
            same(SoundKey::of(&base) == SoundKey::of(d), json_keys::sound(&base) == json_keys::sound(d), "sound");
            for runs in [1, 3] {
                same(
                    ReadoutKey::of(&base, runs) == ReadoutKey::of(d, runs),
                    json_keys::readout(&base, runs) == json_keys::readout(d, runs),
                    "readout",
                );
                same(
                    ChartKey::with_runs(&base, &grids, runs) == ChartKey::with_runs(d, &grids, runs),
                    json_keys::chart(&base, &grids, runs) == json_keys::chart(d, &grids, runs),
                    "chart",
                );
            }
            same(
                ResponseKey::of(&base, &band) == ResponseKey::of(d, &band),
                json_keys::response(&base, &band) == json_keys::response(d, &band),
                "response",
            );
        }
        // Each change is a change of something: the keys as a whole see every one but the thresholds.
        let seen = changes.iter().filter(|(_, d)| ReadoutKey::of(&base, 1) != ReadoutKey::of(d, 1)).count();
        assert_eq!(seen, changes.len() - 3, "all but nothing, L* and e*");
    }

    #[test]
    fn keys_separate_what_they_should() {
        let d = Design::default();
        let mut heard = d.clone();
        heard.observer.r_m = 1.0;
        assert_eq!(SimKey::of(&d), SimKey::of(&heard));
        assert_ne!(DesignKey::of(&d), DesignKey::of(&heard));
        assert_ne!(SoundKey::of(&d), SoundKey::of(&heard));
        assert_eq!(ChartKey::of(&d, &Grids::default()), ChartKey::of(&heard, &Grids::default()), "observer relevels");
        assert_ne!(
            ChartKey::with_runs(&d, &Grids::default(), 4),
            ChartKey::with_runs(&heard, &Grids::default(), 4),
            "an ensemble chart is swept again for a new observer"
        );
        assert_eq!(ReadoutKey::of(&d, 0), ReadoutKey::of(&d, 1), "N 0 and 1 are the single run");
        assert_ne!(ReadoutKey::of(&d, 1), ReadoutKey::of(&d, 2));
        let mut strict = d.clone();
        strict.thresholds.spl_db -= 10.0;
        assert_eq!(ReadoutKey::of(&d, 1), ReadoutKey::of(&strict, 1), "thresholds are applied on draw");
        let mut newmark = d.clone();
        newmark.solver = Solver::newmark_default();
        assert_ne!(SimKey::of(&d), SimKey::of(&newmark));
        let mut dipole = d.clone();
        dipole.radiation.source = Source::Dipole;
        assert_ne!(SoundKey::of(&d), SoundKey::of(&dipole));
    }
}
