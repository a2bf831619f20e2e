use super::super::contact;
use super::super::contact::ContactStart;
use super::super::scheme_checks;
use super::*;

/// Isolated contacts from the same state: the release speed, time and dissipation of the
/// reference (Dormand–Prince in t, whose own error is ~1e-9 of the speed) within 2e-8.
#[test]
fn isolated_contacts_match_the_reference() {
    scheme_checks::with_reference(|s, y0, old| {
        let u0 = y0[3];
        let mut left = 100_000;
        let new = integrate(ContactStart::free(s, y0, 1.0), &mut left, contact::Unobserved);
        assert_eq!(old.outcome, ContactOutcome::Separated);
        assert_eq!(new.outcome, ContactOutcome::Separated);
        assert!((old.y[3] - new.y[3]).abs() < 2e-8 * u0, "{:?} vs {:?}", old.y, new.y);
        assert!((old.t / new.t - 1.0).abs() < 2e-8, "{} vs {}", old.t, new.t);
        assert!((old.pen_max / new.pen_max - 1.0).abs() < 2e-8);
        assert!((old.y[4] - new.y[4]).abs() < 2e-8 * 0.5 * u0 * u0 / s.kstar, "{:?} vs {:?}", old.y, new.y);
        if s.c1 == 0.0 && s.k == 0.0 {
            // Two free bodies, elastic: the relative speed comes back exactly.
            assert!((new.y[3] + u0).abs() < 1e-12 * u0, "{}", new.y[3]);
        }
    });
}

/// A contact cut by its time limit ends exactly there and carries on as if never cut.
#[test]
fn a_cut_contact_resumes_where_it_stopped() {
    scheme_checks::cut_contacts(
        &[0.1, 0.5, 0.93],
        [1e-12, 1e-11, 1e-10],
        |s, y0, t_limit, left| integrate(ContactStart::free(s, y0, t_limit), left, contact::Unobserved),
        |s, r, left| resume(Stretch::free(s, 1.0), r, left, contact::Unobserved),
    );
}
