//! One contact's integrator, whatever its scheme: where a contact starts ([`ContactStart`]) and
//! what every scheme does with it ([`ContactIntegrator`]). The event solver picks the scheme
//! ([`super::ContactScheme`]) in one place, `event::onset_contact`.

use super::contact::{self, ContactEnd, Load, NoLoad, State, Sys};
use super::{adams, dop853, sundman};

/// Where one contact starts: the system, the force on the main mass `load`, the wall `s = ±1`,
/// the onset time `t0` (s) and state `y0 = [x, x', 0, u0, 0, 0]` (u0 > 0), the end of the
/// stretch `t_limit` (s), and `a_bound` (m/s²), a bound on the non-contact relative
/// acceleration that sizes the reference's first step of a slow contact (the other schemes do
/// not use it).
#[derive(Clone, Copy)]
pub(crate) struct ContactStart<'a, L> {
    pub sys: &'a Sys,
    pub load: L,
    pub s: f64,
    pub t0: f64,
    pub y0: State,
    pub t_limit: f64,
    pub a_bound: f64,
}

impl<'a> ContactStart<'a, NoLoad> {
    /// An isolated contact without a force: at wall +1 from time 0, up to `t_limit` (s).
    pub(crate) fn free(sys: &'a Sys, y0: State, t_limit: f64) -> Self {
        ContactStart { sys, load: NoLoad, s: 1.0, t0: 0.0, y0, t_limit, a_bound: 0.0 }
    }
}

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
