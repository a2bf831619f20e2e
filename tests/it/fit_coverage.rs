//! The damper fit's 95 % interval against records it has never seen: random designs, each
//! struck once with the ball at rest somewhere in its clearance, integrated by a second,
//! independent integrator (`support::impact_rk4`, not thud's solver) and measured as a
//! displacement, a velocity and an acceleration with realistic noise.

use rayon::prelude::*;
use thud::design::{self, Design};
use thud::fit::damper::{self, Table};
use thud::fit::strike;
use thud::fit::{Quantity, Series};

use crate::support::impact_rk4::{self, Draws};

/// One random design's records: its design, the true c1 and the three records.
struct Case {
    design: thud::design::ValidDesign,
    truth: f64,
    /// The ball's start (m).
    y0: f64,
    records: [Series; 3],
}

/// Design `seed`: M 0.3–2 kg, f_n 4–10 Hz, ζ 0.1–1 %, the ball 4–10 % of M, struck at
/// 0.5–2 m/s, the clearance 0.3–1.2 of the main mass's first swing v0/ω, the contact's
/// restitution at v0 0.35–0.85, the ball at rest anywhere in the clearance; 8 periods. The
/// records by the independent RK4 in 2 µs steps: x and x' at about 2 kHz and x'' at about
/// 10 kHz, each sample kept with probability 3/4 (uneven), each with white noise of 1–3 % of
/// its own peak (an acceleration's peak is an impact's spike), an offset of 5 % and a drift of
/// 2 % of the peak a second.
fn case(seed: u64) -> Case {
    case_with(seed, 1.0)
}

/// [`case`] with its noise scaled by `noise`.
fn case_with(seed: u64, noise: f64) -> Case {
    let mut g = Draws(seed);
    let mut des = Design::default();
    let p = &mut des.damper;
    p.main_mass_kg = g.between(0.3, 2.0);
    let omega = 2.0 * std::f64::consts::PI * g.between(4.0, 10.0);
    p.stiffness_n_m = p.main_mass_kg * omega * omega;
    p.damping_n_s_m = 2.0 * p.main_mass_kg * omega * g.between(0.001, 0.01);
    p.impact_mass_kg = p.main_mass_kg * g.between(0.04, 0.10);
    p.v0_m_s = g.between(0.5, 2.0);
    p.gap_m = p.v0_m_s / omega * g.between(0.3, 1.2);
    p.duration_s = 8.0 * 2.0 * std::f64::consts::PI / omega;
    let d0 = des.clone().check().unwrap();
    let truth = design::c1_for_restitution(&d0, des.damper.v0_m_s, g.between(0.35, 0.85)).unwrap();
    let d = des.check().unwrap();
    let p = d.damper;
    let y0 = (g.uniform() - 0.5) * p.gap_m * 0.999;
    let dt = 2e-6;
    let steps = (p.duration_s / dt).round() as usize;
    let (mut tx, mut x, mut tv, mut v, mut ta, mut a) = (vec![], vec![], vec![], vec![], vec![], vec![]);
    impact_rk4::run(&p, truth, y0, dt, steps, |i, s, r| {
        let t = i as f64 * dt;
        if i % 250 == 0 && (i == 0 || g.uniform() < 0.75) {
            tx.push(t);
            x.push(s[0]);
        }
        if i % 250 == 125 && g.uniform() < 0.75 || i == 0 {
            tv.push(t);
            v.push(s[1]);
        }
        if i % 50 == 0 && (i == 0 || g.uniform() < 0.75) {
            ta.push(t);
            a.push(r[1]);
        }
    });
    let mut measured = |t: Vec<f64>, y: Vec<f64>, q: Quantity| {
        let peak = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let level = noise * g.between(0.01, 0.03) * peak;
        let y = t.iter().zip(&y).map(|(&ti, &yi)| yi + level * g.normal() + 0.05 * peak + 0.02 * peak * ti).collect();
        Series::new(t, y, q).unwrap()
    };
    let records = [
        measured(tx, x, Quantity::Displacement),
        measured(tv, v, Quantity::Velocity),
        measured(ta, a, Quantity::Acceleration),
    ];
    Case { design: d, truth, y0, records }
}

/// One record's fit: (covered, high/low, missed by more than 5 % without a note, what it gave).
fn fitted(c: &Case, table: &Table, span: f64, s: &Series) -> (bool, f64, bool, String) {
    // A refusal is a failure: every record here is a valid decay of its design.
    let f = match damper::observe(s, &c.design).and_then(|mut o| {
        let keep = o.t_s.partition_point(|&t| t <= span);
        o.t_s.truncate(keep);
        o.x_m.truncate(keep);
        damper::compare(&c.design, table, &[o])
    }) {
        Ok(f) => f,
        Err(e) => return (false, f64::INFINITY, true, format!("truth {:.4}: refused: {e}", c.truth)),
    };
    let [lo, hi] = f.c1_n_s_m_ci;
    let covered = lo <= c.truth && c.truth <= hi;
    let far = c.truth < lo / 1.05 || c.truth > hi * 1.05;
    let mut line = format!("truth {:.4} [{lo:.4}, {hi:.4}] ×{:.2} note {:?}", c.truth, hi / lo, f.note.is_some());
    if c.truth < lo / 1.05 || c.truth > hi * 1.05 {
        line += &format!(
            "\n    stat {:.4} periods {} first impact {:.3} grid [{:.3}, {:.3}]\n    measured {:?}\n    model    {:?}",
            f.statistic,
            f.periods,
            f.first_impact_speed_m_s,
            table.c1_n_s_m[0],
            table.c1_n_s_m[table.c1_n_s_m.len() - 1],
            f.measured_envelope_m,
            f.model_envelope_m
        );
    }
    (covered, hi / lo, far && f.note.is_none(), line)
}

/// The acceptance: over 40 random designs (`case`), for each of the displacement, velocity
/// and acceleration records, the 95 % interval holds the truth in at least 37 (92 %; for a
/// correct 95 % interval P(count ≤ 36) = 14 %: the bar) and its median width
/// (high/low) is at most a factor 2. Measured: 38, 40 and 38 of 40, median widths ×1.35,
/// ×1.35 and ×1.98. No interval misses the truth by more than 5 % without a note (the issue's
/// rule; of the 3 of 120 that miss by far, 2 note a wide or open interval and 1, acceleration
/// case 11, truth 80.1 and [111, 188], that its low end rests on the first periods alone).
/// v0 read from each record's strike (`strike::strike_speed`) is within 3 of its stated
/// standard uncertainties for every record, and within 2 % of the truth in at least 38 of 40
/// (95 %) displacements and velocities (measured: 38 and 40 of 40, worst 2.04 % and 0.71 %,
/// worst 1.8 and 1.41 standard uncertainties; a velocity's by the damper model's path over its
/// first period, median error 0.08 %); an acceleration's share within 2 % is listed
/// (19 of 40, median 2.5 %, worst 2.7 standard uncertainties: its noise, not a bias; 15–22
/// of 40 with other seeds of the noise draws, which choose its window, so it is not asserted).
/// About 30 s of CPU (41 × 39 runs a design); 3 minutes on a busy 2-core machine.
/// Per record kind of one design: covered, width ratio, noted, and the note.
type Fits = Vec<(bool, f64, bool, String)>;
/// Per record kind of one design: v0 from the record's relative error and its uncertainty.
type Strikes = Vec<(f64, f64)>;

#[test]
fn the_damper_fit_s_interval_holds_the_truth_on_independent_records_of_every_kind() {
    let n = 40;
    let started = std::time::Instant::now();
    let results: Vec<_> = (0..n as u64)
        .into_par_iter()
        .map(|k| {
            let c = case(1000 + k);
            let span = damper::common_span_s(&c.records);
            let table = Table::build(&c.design, &damper::grid(&c.design).unwrap(), damper::STARTS, span, None)
                .unwrap()
                .unwrap();
            let fits: Vec<(bool, f64, bool, String)> = c.records.iter().map(|s| fitted(&c, &table, span, s)).collect();
            let strikes: Vec<(f64, f64)> = c
                .records
                .iter()
                .map(|s| match strike::strike_speed(s, c.design.design()) {
                    Ok(st) => (st.v0_m_s / c.design.damper.v0_m_s - 1.0, st.stderr_m_s / c.design.damper.v0_m_s),
                    Err(_) => (f64::INFINITY, 0.0),
                })
                .collect();
            (fits, strikes)
        })
        .collect();
    let (results, strikes): (Vec<Fits>, Vec<Strikes>) = results.into_iter().unzip();
    eprintln!("{n} designs in {:.1} s", started.elapsed().as_secs_f64());
    let mut failures = Vec::new();
    for (kind, name) in ["displacement", "velocity", "acceleration"].iter().enumerate() {
        let covered = results.iter().filter(|r| r[kind].0).count();
        let mut widths: Vec<f64> = results.iter().map(|r| r[kind].1).collect();
        widths.sort_by(f64::total_cmp);
        let median = 0.5 * (widths[n / 2 - 1] + widths[n / 2]);
        eprintln!("{name}: covered {covered}/{n}, median width ×{median:.2}");
        for (i, r) in results.iter().enumerate() {
            if !r[kind].0 {
                eprintln!("  {name} {i}: {}", r[kind].3);
            }
            if r[kind].2 {
                eprintln!("  {name} {i}: misses by more than 5 % without a note: {}", r[kind].3);
            }
        }
        // v0 read from the record's strike: within 3 of its stated standard uncertainties in
        // every case, and the share within 2 % of the truth.
        let errors: Vec<(f64, f64)> = strikes.iter().map(|s| s[kind]).collect();
        let within2 = errors.iter().filter(|(e, _)| e.abs() <= 0.02).count();
        let mut abs: Vec<f64> = errors.iter().map(|(e, _)| e.abs()).collect();
        abs.sort_by(f64::total_cmp);
        let worst_z = errors.iter().map(|(e, sd)| e.abs() / sd).fold(0.0f64, f64::max);
        eprintln!(
            "{name}: v0 from the record within 2 % in {within2}/{n}, median error {:.2} %, worst {:.2} %, worst {worst_z:.2} sd",
            100.0 * 0.5 * (abs[n / 2 - 1] + abs[n / 2]),
            100.0 * abs[n - 1]
        );
        // Its stated uncertainty holds for every kind (so a right --v0 is not warned of).
        if worst_z > strike::DISAGREE_SDS {
            failures.push(format!("{name}: a v0 from the record {worst_z:.2} of its standard uncertainties off"));
        }
        // The 2 % in 95 % of the cases (38 of 40) for a displacement and a velocity.
        // An acceleration's is listed: its noise, 1–3 % of an impact's spike, is as large as
        // the structure's own motion, and its stated uncertainty (about 3 %) says so.
        if kind < 2 && within2 < 38 {
            failures.push(format!("{name}: v0 from the record within 2 % in {within2} of {n}"));
        }
        // The rule: an interval that misses the truth by more than 5 % says so.
        let unflagged = results.iter().filter(|r| r[kind].2).count();
        if unflagged > 0 {
            failures.push(format!("{name}: {unflagged} intervals miss by more than 5 % without a note"));
        }
        if covered < 37 {
            failures.push(format!("{name}: covered {covered} of {n}"));
        }
        if median > 2.0 {
            failures.push(format!("{name}: median width ×{median}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The measurement behind docs/model.md §13.2, "v0 fitted with the damper model" (ignored in
/// the suite: seconds a record): v0 by the model's path (`fit::path`) over the first designs of
/// [`case`] for windows of the record, against the momentum identity's, with the misfit at
/// the truth beside the one found. `PATH_N` designs (40), `PATH_WINDOWS` (periods, `1`),
/// `PATH_KINDS` (0 x, 1 x', 2 x''), `PATH_NOISE` (a factor on the noise), and the search's
/// sizes `PATH_STARTS`, `PATH_C1_EVERY`, `PATH_SEARCHES`, `PATH_EVALS`, `PATH_FORCE` (1: an
/// acceleration compared with the contact force included). Every record must be fitted.
/// One record's measurement: kind, window, v0's relative error, its relative standard
/// uncertainty, the identity's relative error, seconds.
type Measured = (usize, f64, f64, f64, f64, f64);

///
/// Run in the suite at its smallest (2 designs, velocity records, one period: seconds), where
/// it asserts what the measurement over 40 found for velocity (every v0 within 2 % and within
/// 3 of its stated uncertainties); the measurement sets `PATH_N` and the rest.
#[test]
fn measure_v0_by_the_model_s_path() {
    let n: usize = std::env::var("PATH_N").map_or(2, |v| v.parse().unwrap());
    let windows: Vec<f64> = std::env::var("PATH_WINDOWS")
        .map_or_else(|_| vec![1.0], |w| w.split(',').map(|x| x.parse().unwrap()).collect());
    let kinds: Vec<usize> =
        std::env::var("PATH_KINDS").map_or_else(|_| vec![1], |w| w.split(',').map(|x| x.parse().unwrap()).collect());
    let started = std::time::Instant::now();
    let rows: Vec<Vec<Measured>> = (0..n as u64)
        .into_par_iter()
        .map(|k| {
            let noise: f64 = std::env::var("PATH_NOISE").map_or(1.0, |v| v.parse().unwrap());
            let c = case_with(1000 + k, noise);
            let grid = damper::grid(&c.design).unwrap();
            let v0 = c.design.damper.v0_m_s;
            let env = |k: &str, d: usize| std::env::var(k).map_or(d, |v| v.parse().unwrap());
            let mut out = vec![];
            for &kind in &kinds {
                let s = &c.records[kind];
                let id = strike::strike_speed(s, c.design.design()).unwrap();
                for &w in &windows {
                    let t = std::time::Instant::now();
                    let o = thud::fit::path::PathOptions {
                        periods: w,
                        contact_force: env("PATH_FORCE", 0) == 1,
                        starts: env("PATH_STARTS", 24),
                        c1_every: env("PATH_C1_EVERY", 4),
                        searches: env("PATH_SEARCHES", 3),
                        evals: env("PATH_EVALS", 200),
                    };
                    let f = thud::fit::path::path_speed(s, c.design.design(), id.v0_m_s, &grid, &o);
                    let el = t.elapsed().as_secs_f64();
                    let at_truth = thud::fit::path::misfit(s, c.design.design(), v0, c.y0, c.truth, &o);
                    eprintln!(
                        "case {k} kind {kind} w {w}: rss found {:.4e} truth {:.4e} n {}",
                        f.map_or(f64::NAN, |f| f.rss),
                        at_truth.unwrap_or(f64::NAN),
                        f.map_or(0, |f| f.samples)
                    );
                    let (e, sd) = f.map_or((f64::NAN, f64::NAN), |f| (f.v0_m_s / v0 - 1.0, f.stderr_m_s / v0));
                    eprintln!(
                        "case {k} kind {kind} w {w}: id {:+.4} ({:.4}) path {e:+.4} ({sd:.4}) c1 {:.1}/{:.1} z0 {:.3}/{:.3} {el:.2}s",
                        id.v0_m_s / v0 - 1.0,
                        id.stderr_m_s / v0,
                        f.map_or(f64::NAN, |f| f.c1_n_s_m),
                        c.truth,
                        f.map_or(f64::NAN, |f| f.z0_m / (0.5 * c.design.damper.gap_m)),
                        c.y0 / (0.5 * c.design.damper.gap_m),
                    );
                    assert!(e.is_finite() && sd > 0.0, "case {k} kind {kind} window {w}: not fitted");
                    if kind == 1 && w == 1.0 && noise == 1.0 {
                        assert!(e.abs() <= 0.02 && e.abs() <= 3.0 * sd, "case {k}: velocity v0 off by {e:+.4} ({sd:.4})");
                    }
                    out.push((kind, w, e, sd, id.v0_m_s / v0 - 1.0, el));
                }
            }
            out
        })
        .collect();
    eprintln!("{n} designs in {:.1} s", started.elapsed().as_secs_f64());
    for &kind in &kinds {
        for &w in &windows {
            let sel: Vec<_> = rows.iter().flatten().filter(|r| r.0 == kind && r.1 == w).collect();
            let mut abs: Vec<f64> = sel.iter().map(|r| if r.2.is_nan() { 9.0 } else { r.2.abs() }).collect();
            abs.sort_by(f64::total_cmp);
            let within = abs.iter().filter(|&&a| a <= 0.02).count();
            let z2 = sel.iter().filter(|r| r.2.abs() <= 2.0 * r.3).count();
            let z3 = sel.iter().filter(|r| r.2.abs() <= 3.0 * r.3).count();
            let cost: f64 = sel.iter().map(|r| r.5).sum::<f64>() / sel.len() as f64;
            eprintln!(
                "SUMMARY kind {kind} window {w}: within 2 % {within}/{}, median {:.2} %, worst {:.2} %, within 2 sd {z2}, 3 sd {z3}, {cost:.2} s a record",
                sel.len(),
                100.0 * 0.5 * (abs[abs.len() / 2 - 1] + abs[abs.len() / 2]),
                100.0 * abs[abs.len() - 1]
            );
        }
    }
}
