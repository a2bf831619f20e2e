//! What the numbers mean, said where they appear: the status-line hint of each parameter
//! (what it is, its equation, its unit and range from the one range table) and the glossary
//! of the help's second page (zones, e and e_fit, U0max, SPLmax, τ, R, K_HZ, c1, the sources).

use super::fields::Knob;
use crate::design::{Design, ZoneBy};
use crate::limits;

/// The status-line hint of parameter `p`: "c1 — contact damping in the Hertz contact force
/// (Eq 26), N·s/m, 0–1e+06". The range is the one table's ([`crate::limits`]), in the unit
/// the field shows; θ's is the current source's open side.
pub fn field_hint(p: Knob, d: &Design) -> String {
    let hint = unit_and_range(p, d);
    match p.idle(d) {
        Some(why) => format!("{hint} — {why}"),
        None => hint,
    }
}

/// [`field_hint`] without the word on a field the design does not use.
fn unit_and_range(p: Knob, d: &Design) -> String {
    match (p.display_unit(), p.display_range(d)) {
        (Some((unit, _)), Some((lo, hi))) => {
            format!("{} — {}, {unit}, {}–{}", p.label(), p.what(), limits::short(lo), limits::short(hi))
        }
        _ => format!("{} — {}; ←→ changes it", p.label(), p.what()),
    }
}

/// The title of the help's second page.
pub const GLOSSARY_TITLE: &str = "What the numbers mean";

/// The glossary: (term, explanation) pairs, explanations to be wrapped. `zone_by` is the rule
/// the current thresholds use, so the page says which inclination decides the zone.
pub fn glossary(zone_by: ZoneBy) -> Vec<(&'static str, String)> {
    let decides = match zone_by {
        ZoneBy::Paper => "Here e decides the zone (the paper's rule), so e_fit may pass e* while the zone says weak.",
        ZoneBy::Fit => "Here e_fit decides the zone (thresholds zone_by = \"fit\"), not the paper's e.",
    };
    vec![
        (
            "zones",
            "Each design has two numbers: SPLmax (how loud its loudest click is) and e (how fast it damps). \
             L* and e* split them into four zones: 1 noisy, weak (SPLmax ≥ L*, e < e*); 2 noisy, strong \
             (SPLmax ≥ L*, e ≥ e*); 3 quiet, strong (SPLmax < L*, e ≥ e*) — the target; 4 quiet, weak \
             (SPLmax < L*, e < e*). The chart shows each cell's zone; its marker [n] is the live design's own."
                .into(),
        ),
        (
            "e",
            "Damping inclination, Eq 27: e = (X1 − X2)/(t2 − t1), the drop between the first two positive \
             peaks X_k of the main mass's swing over their time apart, in cm/s. The rattle is chaotic: when an \
             impact lands near a peak, X2 can exceed X1 and e is negative (marked (!) in the readout) — that \
             first cycle grew; read the envelope and e_fit."
                .into(),
        ),
        (
            "e_fit",
            format!(
                "Minus the least-squares slope of all the peaks while X_k ≥ X1/2: steadier than e. {decides}"
            ),
        ),
        ("U0max", "The largest impact speed of the run (m/s): the ball against the main mass's wall.".into()),
        (
            "SPLmax",
            "The SPL of an impact at U0max at the listener (r, θ): 10·log10(mean p² / p_ref²) over one contact \
             duration τ from the arrival of the direct wave, p_ref = 20 µPa (the level of the paper's Table 1)."
                .into(),
        ),
        ("τ", "Contact duration of that impact (µs): τ = 2.943·α_max/U0 for the Hertz contact (Eqs 5–7).".into()),
        (
            "R",
            "Restitution u_out/u_in of one impact (R mean: over the run). c1 sets it; heavier balls rebound more (Fig 13)."
                .into(),
        ),
        ("K_HZ", "Hertz stiffness (N/m^1.5): the contact force is K_HZ·δ^1.5 + c1·δ' for a penetration δ (Eqs 1, 26).".into()),
        ("c1", "Contact damping (N·s/m): the viscous part of the contact force; it is what makes R < 1.".into()),
        (
            "sources",
            "single: a ball in free air. dipole: a ball on a plate, heard with its mirror image (Eq 20) — loud \
             along the normal, quiet along the plate. quadrupole: a ball in a wall–floor corner, three images \
             (Eq 22), θ only 0–90°."
                .into(),
        ),
    ]
}

/// The forced readout's terms, each said in one line (at most [`ONE_LINE`] characters): a
/// forced design (F0 > 0) is the main mass driven by F0·cos 2πft, its readout the steady state
/// of its last N = 10 forcing periods (the window).
pub fn forced_terms() -> Vec<(&'static str, String)> {
    [
        ("orbit", "In the title: m/n (m impacts in n periods), chaotic, not settled."),
        ("settled", "The window's amplitude is within 1e-3 of the window before it."),
        ("periodic", "x repeats from one forcing period to the next within 1e-3."),
        ("amp", "The main mass's largest |x| over the last 10 forcing periods."),
        ("alone", "The same without the ball: F0/√((K − MΩ²)² + (CΩ)²), Ω = 2πf."),
        ("cut", "What the ball takes off: 20·log10(alone/amp) dB (> 0: it helps)."),
        ("Leq", "Energy-average level at the listener of the window's impacts."),
        ("imp/T", "Impacts per forcing period in the window."),
    ]
    .into_iter()
    .map(|(t, x)| (t, x.to_string()))
    .collect()
}

/// The longest explanation of a one-line term: the glossary's text column at 80 columns (less
/// the borders and the term column, 9 wide with "periodic").
pub const ONE_LINE: usize = 68;

/// What is on screen beyond the paper's free decay: a force, an ensemble, the response view.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct OnScreen {
    pub forced: bool,
    pub runs: usize,
    pub response_view: bool,
}

/// The glossary for what is on screen: [`glossary`], then the terms of a forced design (the
/// steady figures), of the response view and of an ensemble, when they are shown (so the page
/// of the paper's free decay stays as it was).
pub fn glossary_for(zone_by: ZoneBy, cx: OnScreen) -> Vec<(&'static str, String)> {
    let mut g = glossary(zone_by);
    if cx.forced || cx.response_view {
        g.extend(forced_terms());
    }
    if cx.response_view {
        g.push((
            "f view",
            "The f view (key f): the steady amplitude with the damper and alone (in dB re 1 mm) and Leq against \
             the forcing frequency, over 0.6–1.6 × the structure's natural frequency (1–10 Hz without one), 61 \
             frequencies, each from rest (v0 = 0, the ball at y0) and run until it settles, as thud response. The \
             curve does not depend on f: changing f moves the marker (│) only; the line under it gives the point \
             nearest f. The readout is the run as set (with v0, for the duration), so it may differ until settled."
                .into(),
        ));
    }
    if cx.runs > 1 {
        g.push((
            "N runs",
            format!(
                "N = {} runs of the design from ball offsets y0 = −d/2 + (k + ½)·d/N spread over the clearance, at \
                 rest: the readout shows each number's median [p10–p90] (nearest rank: each is one run's value) and \
                 the % of runs in the zone of the medians. A forced design's amp and cut are one run's: cut's \
                 median [p10–p90] is the cut of the runs at amp's median [p90–p10]. The chart gives each cell the zone of its medians; a \
                 cell where fewer than 70 % of its runs agree is shaded ░ (: in ASCII) — that zone is luck.",
                cx.runs
            ),
        ));
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_c1_hint_says_what_unit_and_range() {
        let h = field_hint(Knob::C1, &Design::default());
        assert!(h.starts_with("c1 — contact damping"), "{h}");
        assert!(h.contains("(Eq 26)") && h.contains("N·s/m") && h.contains(&limits::short(limits::C1.max)), "{h}");
    }

    #[test]
    fn the_mass_hint_is_in_grams_and_theta_follows_the_source() {
        let d = Design::default();
        let h = field_hint(Knob::MASS, &d);
        assert!(h.contains(", g, 0.1–"), "{h}");
        assert!(field_hint(Knob::THETA, &d).contains("deg, 0–90"));
        let mut dip = d.clone();
        dip.radiation.source = crate::acoustics::Source::Dipole;
        assert!(field_hint(Knob::THETA, &dip).contains("deg, -90–90"));
        assert!(field_hint(Knob::SOURCE, &d).contains("quadrupole"));
    }

    #[test]
    fn the_air_says_it_is_unused_in_the_paper_model_only() {
        let air = Knob::ALL.into_iter().find(|k| k.rows() == ["air-temperature"]).unwrap();
        let paper = Design::default();
        assert!(field_hint(air, &paper).contains("unused by the paper's model"), "{}", field_hint(air, &paper));
        assert!(air.shown(&paper).ends_with(" (unused)"), "{}", air.shown(&paper));
        let mut physical = paper.clone();
        physical.model = crate::design::Model::Physical;
        assert!(!field_hint(air, &physical).contains("unused") && !air.shown(&physical).contains("unused"));
        assert!(!field_hint(Knob::MASS, &paper).contains("unused"), "a field the paper's model uses");
    }

    #[test]
    fn the_glossary_adds_the_terms_on_screen_only() {
        let plain = glossary_for(ZoneBy::Paper, OnScreen { runs: 1, ..OnScreen::default() });
        assert_eq!(plain, glossary(ZoneBy::Paper));
        let all = glossary_for(ZoneBy::Paper, OnScreen { forced: true, runs: 16, response_view: true });
        for term in ["orbit", "settled", "amp", "alone", "cut", "Leq", "imp/T", "f view", "N runs"] {
            assert!(all.iter().any(|(t, _)| *t == term), "{term}");
        }
        assert!(all.iter().any(|(_, x)| x.contains("N = 16 runs") && x.contains("70 %")));
        assert!(field_hint(Knob::RUNS, &Design::default()).contains("runs, 1–1000"));
        assert!(field_hint(Knob::BALL_POSITION, &Design::default()).contains("cm, -2–2"));
    }

    #[test]
    fn each_forced_term_is_one_line_at_80_columns() {
        for (term, text) in forced_terms() {
            assert!(text.chars().count() <= ONE_LINE, "{term}: {} characters", text.chars().count());
        }
    }

    #[test]
    fn the_glossary_says_which_inclination_decides() {
        let g = glossary(ZoneBy::Paper);
        for term in ["zones", "e", "e_fit", "U0max", "SPLmax", "τ", "R", "K_HZ", "c1", "sources"] {
            assert!(g.iter().any(|(t, _)| *t == term), "{term}");
        }
        assert!(g.iter().any(|(_, x)| x.contains("e decides the zone")));
        assert!(glossary(ZoneBy::Fit).iter().any(|(_, x)| x.contains("e_fit decides")));
    }
}
