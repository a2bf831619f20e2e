//! The checked design: [`ValidDesign`], the only kind a solver takes.

use serde::Serialize;

use crate::error::ThudError;

use super::{variant, Design};

/// A design that passed [`Design::check`]: every range of the range table, the
/// cross-checks (|y0| < d/2, the observer outside the ball, finite thresholds, …) and K_HZ
/// resolved from its materials for its radius. Only the engine builds one ([`Design::check`],
/// the named-parameter builder [`crate::params::design`], and a chart's cells), and
/// every solver and evaluation takes one ([`evaluate`](super::evaluate), [`sweep`](super::sweep), [`crate::ensemble`],
/// [`crate::response`], the work checks of [`crate::limits`]), so an unchecked or unresolved
/// design cannot reach a solver.
///
/// Read it as a [`Design`] (it dereferences to one). To change it, take the design out
/// ([`ValidDesign::into_design`] or a clone), change it and check it again. It is written as
/// the design it holds; reading one (serde) checks it, so a file cannot skip the check.
///
/// Neither a struct literal nor a bare [`Design`] makes one:
///
/// ```compile_fail
/// use thud_core::design::{Design, ValidDesign};
/// let v = ValidDesign(Design::default());
/// ```
///
/// ```compile_fail
/// use thud_core::design::{Design, ValidDesign};
/// let v: ValidDesign = Design::default().into();
/// ```
///
/// ```compile_fail
/// use thud_core::design::{self, Design};
/// // A solver takes only a checked design.
/// let e = design::evaluate(&Design::default(), 0, None);
/// ```
///
/// ```
/// use thud_core::design::{self, Design};
/// let v = Design::default().check().unwrap();
/// let e = design::evaluate(&v, 0, None).unwrap();
/// assert!(e.metrics.n_impacts > 0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ValidDesign(Design);

impl ValidDesign {
    /// The checked design (K_HZ resolved).
    #[must_use]
    pub fn design(&self) -> &Design {
        &self.0
    }

    /// The design, to change and check again.
    #[must_use]
    pub fn into_design(self) -> Design {
        self.0
    }

    /// `d`, whose ranges [`Design::check`] has checked, after the physics' own checks
    /// ([`Design::validate`]) with K_HZ set from its materials for its radius: the one
    /// constructor, called by [`Design::check`] after the range table, and for a chart cell.
    pub(crate) fn from_ranges_checked(d: Design) -> Result<ValidDesign, ThudError> {
        d.validate()?;
        let mut d = d;
        d.damper.k_hz = d.hertz_stiffness()?;
        Ok(ValidDesign(d))
    }

    /// This design with impact mass `mass_kg` and gap `gap_m` (a chart cell or a restitution
    /// curve's mass), checked again by the physics' own checks with K_HZ resolved again: the
    /// ball's radius, and with it K_HZ from the materials and the observer's distance to the
    /// ball, follow the mass, and |y0| < d/2 the gap. The range table is not run again: every
    /// front end checks the axes against the mass and gap ranges (the sweep itself that they
    /// are > 0), and every mass and density inside their ranges gives a radius, and with
    /// materials a K_HZ, inside theirs ([`crate::limits::RADIUS`], [`crate::limits::K_HZ`]);
    /// nothing else changes. These checks are what [`evaluate`] ran on every cell before it
    /// took a checked design.
    pub(crate) fn variant(&self, mass_kg: f64, gap_m: f64) -> Result<ValidDesign, ThudError> {
        ValidDesign::from_ranges_checked(variant(self, mass_kg, gap_m))
    }
}

impl std::ops::Deref for ValidDesign {
    type Target = Design;

    fn deref(&self) -> &Design {
        &self.0
    }
}

impl From<ValidDesign> for Design {
    fn from(v: ValidDesign) -> Design {
        v.0
    }
}

impl PartialEq<Design> for ValidDesign {
    fn eq(&self, other: &Design) -> bool {
        self.0 == *other
    }
}

impl Serialize for ValidDesign {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}
