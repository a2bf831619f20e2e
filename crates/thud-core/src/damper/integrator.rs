//! One contact's integrator, whatever its scheme: what every scheme does with the start of a
//! contact ([`ContactStart`]): [`ContactIntegrator`]. The event solver picks the scheme
//! ([`super::ContactScheme`]) in one place, `event::onset_contact`.

use super::contact::{self, ContactEnd, ContactStart, Load};
use super::{adams, dop853, sundman};

/// A scheme that integrates one contact from its onset until the exit, the end of the stretch
/// or the step budget.
pub(crate) trait ContactIntegrator {
    /// Where a contact this scheme cut at the end of a stretch stood.
    type Resume;

    /// One contact from `start`, charged to `budget` (steps), every accepted step shown to
    /// `obs`.
    fn integrate<L: Load, O: contact::Observer + sundman::Observer>(
        start: ContactStart<'_, L>,
        budget: &mut usize,
        obs: O,
    ) -> ContactEnd<Self::Resume>;
}

/// Adaptive Dormand–Prince 5(4) on Eq 26 as written: the reference.
pub(crate) struct Reference;

impl ContactIntegrator for Reference {
    type Resume = contact::Resume;

    #[inline(always)]
    fn integrate<L: Load, O: contact::Observer + sundman::Observer>(
        start: ContactStart<'_, L>,
        budget: &mut usize,
        obs: O,
    ) -> ContactEnd<Self::Resume> {
        contact::integrate(start, budget, obs)
    }
}

/// The Sundman form by Taylor series (research only).
#[cfg(feature = "research")]
pub(crate) struct SundmanTaylor;

#[cfg(feature = "research")]
impl ContactIntegrator for SundmanTaylor {
    type Resume = sundman::Resume;

    #[inline(always)]
    fn integrate<L: Load, O: contact::Observer + sundman::Observer>(
        start: ContactStart<'_, L>,
        budget: &mut usize,
        obs: O,
    ) -> ContactEnd<Self::Resume> {
        sundman::integrate(start, budget, obs)
    }
}

/// The Sundman form by DOP853 from the onset (research only; the default scheme hands its
/// contacts over to DOP853 midway).
#[cfg(feature = "research")]
pub(crate) struct SundmanDop853;

#[cfg(feature = "research")]
impl ContactIntegrator for SundmanDop853 {
    type Resume = dop853::Resume;

    #[inline(always)]
    fn integrate<L: Load, O: contact::Observer + sundman::Observer>(
        start: ContactStart<'_, L>,
        budget: &mut usize,
        obs: O,
    ) -> ContactEnd<Self::Resume> {
        dop853::integrate(start, budget, obs)
    }
}

/// The Sundman form by the Adams–Bashforth–Moulton pair, handing over to DOP853 off the Hertz
/// hump: the default.
pub(crate) struct SundmanAdams;

impl ContactIntegrator for SundmanAdams {
    type Resume = dop853::Resume;

    #[inline(always)]
    fn integrate<L: Load, O: contact::Observer + sundman::Observer>(
        start: ContactStart<'_, L>,
        budget: &mut usize,
        obs: O,
    ) -> ContactEnd<Self::Resume> {
        adams::integrate(start, budget, obs)
    }
}
