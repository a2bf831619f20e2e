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

/// One scheme: its marker type, where a contact it cut resumes, and its contact function.
macro_rules! scheme {
    ($(#[$meta:meta])* $name:ident, $resume:ty, $integrate:path) => {
        $(#[$meta])*
        pub(crate) struct $name;

        $(#[$meta])*
        impl ContactIntegrator for $name {
            type Resume = $resume;

            #[inline(always)]
            fn integrate<L: Load, O: contact::Observer + sundman::Observer>(
                start: ContactStart<'_, L>,
                budget: &mut usize,
                obs: O,
            ) -> ContactEnd<Self::Resume> {
                $integrate(start, budget, obs)
            }
        }
    };
}

scheme!(
    /// Adaptive Dormand–Prince 5(4) on Eq 26 as written: the reference.
    Reference,
    contact::Resume,
    contact::integrate
);

scheme!(
    /// The Sundman form by Taylor series (research only).
    #[cfg(feature = "research")]
    SundmanTaylor,
    sundman::Resume,
    sundman::integrate
);

scheme!(
    /// The Sundman form by DOP853 from the onset (research only; the default scheme hands its
    /// contacts over to DOP853 midway).
    #[cfg(feature = "research")]
    SundmanDop853,
    dop853::Resume,
    dop853::integrate
);

scheme!(
    /// The Sundman form by the Adams–Bashforth–Moulton pair, handing over to DOP853 off the
    /// Hertz hump: the default.
    SundmanAdams,
    dop853::Resume,
    adams::integrate
);
