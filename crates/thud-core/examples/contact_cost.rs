#![allow(clippy::unwrap_used, clippy::expect_used)] // a measuring tool: a panic is how it fails
//! The event solver's contact schemes on the Fig 9 design, for instruction counts that do not
//! depend on the machine's load (docs/model.md §11):
//!
//! ```sh
//! cargo build --release -p thud-core --example contact_cost
//! valgrind --tool=callgrind target/release/examples/contact_cost SundmanDop853 20
//! ```
//!
//! Runs the design `REPS` times with the scheme named (`DormandPrince`, the reference,
//! `SundmanTaylor`, `SundmanDop853`, `SundmanAdams`, the default) and prints the impacts a run
//! and a digest of the runs' bits (equal digests: the same runs to the bit), with the digest of
//! the impacts' own numbers beside it (for a change meant to move only the ledger's bits);
//! divide the instructions by `REPS` × impacts.
//! A third argument `forced` runs the forced preset instead (the ensemble's and the
//! bifurcation diagram's designs).

use thud_core::damper::{simulate_with, ContactScheme, DamperParams, RunOptions, Solver};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scheme = match args.get(1).map_or("SundmanDop853", String::as_str) {
        "DormandPrince" => ContactScheme::DormandPrince,
        "SundmanTaylor" => ContactScheme::SundmanTaylor,
        "SundmanDop853" => ContactScheme::SundmanDop853,
        "SundmanAdams" => ContactScheme::SundmanAdams,
        other => panic!("unknown scheme {other}"),
    };
    let reps: usize = args.get(2).map_or(1, |r| r.parse().expect("REPS is a count"));
    let p = if args.get(3).is_some_and(|a| a == "forced") {
        DamperParams { v0_m_s: 0.0, force_n: 2.0, freq_hz: 5.0, duration_s: 2.0, ..DamperParams::table2() }
    } else {
        DamperParams::table2()
    };
    let mut n = 0;
    let mut digest = 0xcbf2_9ce4_8422_2325_u64;
    let mut motion = digest;
    for _ in 0..reps {
        let run = simulate_with(&p, Solver::Event, &RunOptions::default(), scheme).unwrap();
        n = run.impacts.len();
        // FNV-1a over the bits of every impact's numbers, the run's maxima and its ledger: two
        // builds that print the same digest computed the same run to the bit.
        let values = run.impacts.iter().flat_map(|i| [i.t_s, i.u_in_m_s, i.u_out_m_s, i.t_end_s, i.penetration_max_m]);
        // (The impacts' own numbers alone, for a change that moves only the ledger's bits.)
        for v in values.clone() {
            motion = (motion ^ v.to_bits()).wrapping_mul(0x0100_0000_01b3);
        }
        let values =
            values.chain([run.energy.final_mechanical_j, run.energy.dissipated_contact_j, run.zdot_abs_max_m_s]);
        for v in values {
            digest = (digest ^ v.to_bits()).wrapping_mul(0x0100_0000_01b3);
        }
    }
    println!("{scheme:?}: {n} impacts a run, {reps} runs, digest {digest:016x} (impacts {motion:016x})");
}
