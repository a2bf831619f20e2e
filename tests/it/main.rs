#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The integration tests, one module per subject, in one test binary: each test binary links
//! thud and every dependency again, so one binary instead of one per file is most of a cold
//! `cargo test --release` (ARCHITECTURE.md, "Tests"). A new subject is a new module here
//! (`tests/it/<subject>.rs` and a `mod` line below); insta names its snapshots after the module
//! path (`tests/it/snapshots/it__tui__main_80x24.snap`), proptest its regressions after the file
//! (`tests/it/damper.proptest-regressions`).
//!
//! No test here changes what the process shares (the environment, the working folder, signal
//! handlers, a panic hook, the global thread pool): everything that needs that runs a `thud`
//! of its own. A test that must change it belongs in a binary of its own (`tests/<name>.rs`).

/// Running the built `thud` (shared by the command-line tests).
mod common;
/// Helpers of the file, process and pids-limit tests.
mod support {
    pub mod design_problem;
    pub mod explorer;
    pub mod home;
    pub mod impact_rk4;
    pub mod screen_svg;
    pub mod skip;
    pub mod stranger;
    pub mod wait;
}

mod acoustics_paper;
mod architecture;
mod architecture_house;
mod ascii_figures;
mod branch_figures;
mod chart_cells;
mod cli;
mod contact_scheme;
mod contact_sundman;
mod cvd;
mod damper;
mod design;
mod design_figure;
mod design_front;
mod design_paper;
mod docs;
mod ensemble;
mod export;
mod figure_checks;
mod figures;
mod files;
mod fit_cli;
mod fit_coverage;
mod fit_note;
mod fit_own_records;
mod flag_names;
mod forced;
mod forced_cli;
mod hostile_dynamics;
mod hostile_files;
mod hostile_inputs;
mod hostile_round3;
mod hostile_round4;
mod hostile_round5;
mod hostile_round6;
mod hostile_round7;
mod masri_caughey;
mod masri_caughey_stability;
mod one_schema;
mod orbit;
mod params_table;
mod pdf;
mod physical_model;
mod pictures;
mod pulse_table;
mod response_band;
mod restitution_scheme;
mod schema;
mod shards;
mod shared_rows;
mod shell;
mod store_config;
mod study;
mod sweep_figures;
mod tui;
mod tui_anim;
mod tui_bifurcation;
mod tui_find;
mod tui_forced;
mod tui_look;
mod tui_orbit;
mod tui_tmux;
mod tui_tour;
mod unforced_0_1;
