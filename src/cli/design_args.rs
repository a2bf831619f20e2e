//! The design flags shared by `simulate`, `sweep` and `export`: a preset, then overrides.

use clap::{Args, ValueEnum};

use super::{quantity, PulseArg, QuadSignsArg, SourceArg};
use crate::acoustics::Source;
use crate::damper::Solver;
use crate::design::{BallSize, Design, Materials};
use crate::error::ThudError;
use crate::presets;
use crate::units::Kind;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SolverArg {
    /// Exact flight between impacts, adaptive integration inside each contact (fast).
    Event,
    /// Uniform Newmark-β (β 1/4, γ 1/2) at --dt: the paper's method, the reference.
    Newmark,
}

/// A design: a preset, then any flag given explicitly overrides the preset's value.
#[derive(Debug, Clone, Args)]
pub struct DesignArgs {
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
}

impl DesignArgs {
    /// The design these flags describe, validated.
    pub fn design(&self) -> Result<Design, ThudError> {
        let mut d = presets::preset(&self.preset)?;
        d.thresholds = super::settings::load().thresholds(d.thresholds);
        let p = &mut d.damper;
        let set = |target: &mut f64, param: &str, text: &Option<String>, kind: Kind| -> Result<(), ThudError> {
            if let Some(v) = quantity(param, text, kind)? {
                *target = v;
            }
            Ok(())
        };
        set(&mut p.impact_mass_kg, "mass", &self.mass, Kind::Mass)?;
        set(&mut p.gap_m, "gap", &self.gap, Kind::Length)?;
        set(&mut p.v0_m_s, "v0", &self.v0, Kind::Speed)?;
        set(&mut p.main_mass_kg, "main-mass", &self.main_mass, Kind::Mass)?;
        set(&mut p.stiffness_n_m, "k", &self.k, Kind::Stiffness)?;
        set(&mut p.damping_n_s_m, "c", &self.c, Kind::Damping)?;
        set(&mut p.c1_n_s_m, "c1", &self.c1, Kind::Damping)?;
        set(&mut p.k_hz, "k-hz", &self.k_hz, Kind::HertzStiffness)?;
        set(&mut p.duration_s, "duration", &self.duration, Kind::Time)?;
        p.no_tension |= self.no_tension;
        if let Some(s) = &self.sphere {
            d.materials =
                Some(Materials { sphere: s.clone(), plate: self.plate.clone().unwrap_or_else(|| "steel".into()) });
        }
        let dt = quantity("dt", &self.dt, Kind::Time)?;
        d.solver = match (self.solver, dt, d.solver) {
            (Some(SolverArg::Event), _, _) => Solver::Event,
            (Some(SolverArg::Newmark), dt, _) => Solver::Newmark { dt_s: dt.unwrap_or(1e-7) },
            (None, Some(dt), Solver::Newmark { .. }) => Solver::Newmark { dt_s: dt },
            (None, Some(_), Solver::Event) => {
                return Err(ThudError::invalid("dt", "only the newmark solver has a time step; add --solver newmark"))
            }
            (None, None, s) => s,
        };
        if let Some(rho) = quantity("density", &self.density, Kind::Density)? {
            d.ball = BallSize::Density(rho);
        }
        if let Some(a) = quantity("radius", &self.radius, Kind::Length)? {
            d.ball = BallSize::Radius(a);
        }
        set(&mut d.observer.r_m, "r", &self.r, Kind::Length)?;
        if let Some(th) = quantity("theta", &self.theta, Kind::Angle)? {
            d.observer.theta_rad = th.to_radians();
        }
        if let Some(s) = self.source {
            d.radiation.source = Source::from(s);
        }
        if let Some(q) = self.quad_signs {
            d.radiation.quad_signs = q.into();
        }
        if let Some(p) = self.pulse {
            d.radiation.pulse = p.into();
        }
        set(&mut d.thresholds.spl_db, "l-star", &self.l_star, Kind::Level)?;
        set(&mut d.thresholds.inclination_cm_s, "e-star", &self.e_star, Kind::Inclination)?;
        d.validate()?;
        d.resolved()
    }
}

/// Parses a range "FROM:TO:N" of quantities of `kind` (e.g. "30g:100g:20").
pub fn parse_range(param: &str, text: &str, kind: Kind) -> Result<Vec<f64>, ThudError> {
    let parts: Vec<&str> = text.split(':').collect();
    let [from, to, n] = parts[..] else {
        return Err(ThudError::invalid(param, format!("'{text}'; expected FROM:TO:N, e.g. 30g:100g:20")));
    };
    let (from, to) = (crate::units::parse(param, from, kind)?, crate::units::parse(param, to, kind)?);
    let n: usize =
        n.trim().parse().ok().filter(|&n| (1..=1000).contains(&n)).ok_or_else(|| {
            ThudError::invalid(param, format!("'{n}' points; N must be a whole number from 1 to 1000"))
        })?;
    Ok(crate::design::linspace(from, to, n))
}
