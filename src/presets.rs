//! Named starting designs: the paper's set-ups and the physical default.

use crate::acoustics::{QuadSigns, Radiation, Source};
use crate::design::{Design, U0MaxRule};
use crate::error::ThudError;

/// A named design with a one-line description.
pub struct Preset {
    pub name: &'static str,
    pub description: &'static str,
    pub build: fn() -> Design,
}

/// The least-squares contact damping (N·s/m) that reproduces Table 3 with the no-tension clamp
/// (model notes §6).
pub const TABLE3_C1: f64 = 83.68;

fn physical() -> Design {
    Design::default()
}

fn paper_fig9() -> Design {
    Design {
        radiation: Radiation { source: Source::Quadrupole, quad_signs: QuadSigns::Paper, ..Default::default() },
        ..Design::default()
    }
}

fn paper_table3() -> Design {
    let mut d = paper_fig9();
    d.damper.v0_m_s = 1.4;
    d.damper.c1_n_s_m = TABLE3_C1;
    d.damper.no_tension = true;
    d.u0max_rule = U0MaxRule::WholeRun;
    d
}

pub const PRESETS: &[Preset] = &[
    Preset {
        name: "default",
        description: "Table 2 damper (M 0.5 kg, K 500 N/m, C 0.05, c1 20, K_HZ 5.6e8), m 40.5 g, d 4 cm, v0 2 m/s; rigid corner at r 0.7 m, θ 45°",
        build: physical,
    },
    Preset {
        name: "paper-fig9",
        description: "the paper's Fig 9: Table 2, v0 2 m/s, d 4 cm; the paper's quadrupole signs",
        build: paper_fig9,
    },
    Preset {
        name: "paper-table3",
        description: "the paper's Table 3 set-up: v0 1.4 m/s, c1 83.68 N·s/m with the no-tension clamp, U0max over the whole run including t = 0",
        build: paper_table3,
    },
];

/// The preset called `name`.
pub fn preset(name: &str) -> Result<Design, ThudError> {
    PRESETS.iter().find(|p| p.name.eq_ignore_ascii_case(name.trim())).map(|p| (p.build)()).ok_or_else(|| {
        let names: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
        ThudError::invalid("preset", format!("unknown preset '{name}'; one of: {}", names.join(", ")))
    })
}
