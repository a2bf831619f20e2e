//! One ball, one radius: its mass and size resolved from what was given (docs/model.md §10.1).

use crate::contact;
use crate::design::{BallSize, Design};
use crate::error::ThudError;
use crate::limits::{self, short};

/// The ball's size as a front end gave it: each of its three numbers, if given, and its
/// material's name and density (kg/m³), if the ball has a material.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct BallGiven {
    pub(super) mass_kg: Option<f64>,
    pub(super) radius_m: Option<f64>,
    pub(super) density_kg_m3: Option<f64>,
    pub(super) material: Option<(&'static str, f64)>,
}

/// A base's ball as its mass (kg) and how its size follows.
#[derive(Debug, Clone, Copy)]
pub(super) struct BaseBall {
    pub(super) mass_kg: f64,
    pub(super) size: BallSize,
}

pub(super) fn base_ball_of(size: &BallSize, mass_kg: f64) -> BaseBall {
    BaseBall { mass_kg, size: *size }
}

/// Relative disagreement (of the mass) tolerated between a mass, a radius and a density all
/// given: 0.1 %, what typing four significant digits of each allows.
const BALL_TOLERANCE: f64 = 1e-3;

/// THE resolution of one ball, the same for every command, Python and the explorer: its mass
/// (kg) and how its radius follows ([`BallSize`]), from the `base` ball and what was `given`.
/// A ball is fixed by two of mass, radius and density; a material names a density.
///
/// * mass, radius and density: all three must agree (to [`BALL_TOLERANCE`]), else refused in
///   one line naming the three (`spell` spells a row's name as the user typed it);
/// * two of them: the third follows (mass and radius given keep both, the material's density
///   aside: the ball is then not solid material);
/// * one, or none: the material's density (if it has one), else the base's, fills in; with a
///   material and only a radius (given, or the base's fixed radius) the mass follows.
pub(super) fn resolve_ball(
    base: BaseBall,
    g: &BallGiven,
    spell: impl Fn(&str) -> String,
) -> Result<(f64, BallSize), ThudError> {
    use contact::sphere_mass;
    let material = g.material.map(|(_, rho)| rho);
    let (mass, size, from) = match (g.mass_kg, g.radius_m, g.density_kg_m3) {
        (Some(m), Some(r), Some(rho)) => {
            let implied = sphere_mass(r, rho);
            if (implied - m).abs() > BALL_TOLERANCE * m {
                return Err(ThudError::invalid(
                    spell("density"),
                    format!(
                        "{} {} kg, {} {} m and {} {} kg/m^3 disagree: that radius and density make {} kg; give two of the three",
                        spell("mass"),
                        short(m),
                        spell("radius"),
                        short(r),
                        spell("density"),
                        short(rho),
                        short(implied)
                    ),
                ));
            }
            (m, BallSize::Density(rho), None)
        }
        (Some(m), Some(r), None) => (m, BallSize::Radius(r), None),
        (None, Some(r), Some(rho)) => (sphere_mass(r, rho), BallSize::Density(rho), Some(("radius", r, rho))),
        (None, Some(r), None) => match material {
            Some(rho) => (sphere_mass(r, rho), BallSize::Density(rho), Some(("radius", r, rho))),
            None => (base.mass_kg, BallSize::Radius(r), None),
        },
        (m, None, Some(rho)) => (m.unwrap_or(base.mass_kg), BallSize::Density(rho), None),
        (m, None, None) => match (material, base.size, m) {
            (Some(rho), BallSize::Radius(r), None) => {
                (sphere_mass(r, rho), BallSize::Density(rho), Some(("radius", r, rho)))
            }
            (Some(rho), _, m) => (m.unwrap_or(base.mass_kg), BallSize::Density(rho), None),
            (None, size, m) => (m.unwrap_or(base.mass_kg), size, None),
        },
    };
    // A mass that follows from a radius must be inside the mass range: named by the radius
    // when it was typed (else the material made it).
    if let Some((_, r, rho)) = from.filter(|_| !limits::MASS.contains(mass)) {
        let by = if g.radius_m.is_some() { "radius" } else { "sphere" };
        return Err(ThudError::invalid(
            spell(by),
            format!(
                "a ball of radius {} m at {} kg/m^3 weighs {} kg; the {} must be {}",
                short(r),
                short(rho),
                short(mass),
                limits::MASS.what,
                limits::MASS.describe()
            ),
        ));
    }
    Ok((mass, size))
}

/// `design` with its ball resolved for its material (`resolve_ball`, the rule every front end
/// uses): a design whose materials (or physical model) name a ball material takes that
/// material's density, its mass kept (or, for a ball of fixed radius, its radius kept and its
/// mass following). The explorer calls this when its materials field changes. A design
/// without a ball material is returned as it is; a mass outside its range is an error.
pub fn follow_material(mut design: Design) -> Result<Design, ThudError> {
    let Some(m) = design.materials_used() else { return Ok(design) };
    let s = m.sphere_material()?;
    let ball = BallGiven { material: Some((s.name, s.density_kg_m3)), ..BallGiven::default() };
    let (mass, size) =
        resolve_ball(base_ball_of(&design.ball, design.damper.impact_mass_kg), &ball, ToString::to_string)?;
    design.damper.impact_mass_kg = mass;
    design.ball = size;
    Ok(design)
}
