//! The restitution of one isolated contact (Fig 13) and its inverse, c1 for a restitution.

use crate::damper;
use crate::error::{check_positive, ThudError};

use super::ValidDesign;

/// Restitution R = u_out/u0 of one isolated ball–main-mass contact at `u0` for each mass
/// (Fig 13), with the design's K_HZ (or materials), c1 and clamp.
pub fn restitution_curve(design: &ValidDesign, masses_kg: &[f64], u0: f64) -> Result<Vec<(f64, f64)>, ThudError> {
    check_positive("u0", u0, "m/s")?;
    masses_kg
        .iter()
        .map(|&m| {
            check_positive("mass", m, "kg")?;
            let d = design.variant(m, design.damper.gap_m)?;
            let p = &d.damper;
            let c = damper::single_contact(m, p.main_mass_kg, p.k_hz, p.c1_n_s_m, p.no_tension, u0);
            Ok((m, c.u_out_m_s / u0))
        })
        .collect()
}

/// The contact damping c1 (N·s/m) that gives the restitution `r` to one isolated contact of
/// this design's ball against its main mass at `u0` (the inverse of [`restitution_curve`]).
pub fn c1_for_restitution(design: &ValidDesign, u0: f64, r: f64) -> Result<f64, ThudError> {
    let p = &design.damper;
    damper::c1_for_restitution(p.impact_mass_kg, p.main_mass_kg, p.k_hz, p.no_tension, u0, r)
}
