//! `thud simulate`: one damper design through its impacts.

use clap::Args;

use super::budget;
use super::design_args::DesignArgs;
use super::format::num;
use super::{count, CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::damper::{free_response, Run, Solver};
use crate::design::{self, Design, Evaluation, ValidDesign};
use crate::ensemble::{self, Ensemble, Percentiles};
use crate::error::ThudError;
use crate::limits::{self, short};
use crate::report::{EnsembleReport, RunReport};

#[derive(Debug, Clone, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    design: DesignArgs,
    /// Time-history samples for --csv.
    #[arg(long, value_name = "N", default_value = "2001", allow_hyphen_values = true)]
    samples: String,
    /// Impacts listed in the text summary.
    #[arg(long, value_name = "N", default_value = "12", allow_hyphen_values = true)]
    show: String,
    /// Runs from ball offsets spread evenly over the clearance (y0 = −d/2 + (k + ½)·d/N, at
    /// rest): each metric as median [p10–p90], with every run (1: the single trajectory).
    #[arg(long, value_name = "N", default_value = "1", allow_hyphen_values = true)]
    ensemble: String,
    #[command(flatten)]
    output: OutputArgs,
}

/// Why `run` stopped before the design's duration `duration_s`, if it did: the engine's
/// [`design::truncation`] (shared with the Python module).
pub(crate) fn truncation(run: &Run, duration_s: f64) -> Option<String> {
    design::truncation(run, duration_s)
}

pub fn run(a: &SimulateArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let d = a.design.design()?;
    // Checked even when unused (only --csv writes the history), so a bad value is never ignored.
    let typed_samples = count("samples", &a.samples, &limits::SAMPLES)?;
    let samples = if a.output.csv { typed_samples } else { 0 };
    let show = count("show", &a.show, &limits::SHOW)?;
    let runs = count("ensemble", &a.ensemble, &limits::ENSEMBLE)?;
    a.design.check_ensemble(runs)?;
    if runs > 1 {
        return run_ensemble(a, ctx, out, &d, runs);
    }
    a.design.check_run(ctx, &d, samples, "--samples")?;
    let long = limits::design_run(&d, samples)[0].value > 4e7;
    let spinner = budget::spinner("simulating", long);
    let eval = design::evaluate(&d, samples, None)?;
    spinner.finish_and_clear();
    let truncated = truncation(&eval.run, d.damper.duration_s);
    match a.output.format() {
        OutputFormat::Csv => {
            if let Some(why) = &truncated {
                super::warn(&format!("warning: {why}"));
            }
            out.text("t_s,x_m,y_m,x_free_m\n")?;
            for h in &eval.run.history {
                out.csv_row(&[h.t_s, h.x_m, h.y_m, free_response(&d.damper, h.t_s)])?;
            }
        }
        OutputFormat::Json => out.json(&RunReport::new(&d, &eval)?)?,
        OutputFormat::Text => {
            // The summary prints these; check them as data too (the text check is the backstop).
            super::output::check_finite(&(&eval.metrics, &eval.run.energy))?;
            out.text(&summary(&d, &eval, show, truncated.as_deref())?)?;
        }
    }
    Ok(())
}

/// `thud simulate --ensemble N` (N > 1): the design from N ball offsets.
fn run_ensemble(a: &SimulateArgs, ctx: &Ctx, out: &mut Out, d: &ValidDesign, runs: usize) -> Result<(), CliError> {
    a.design.check_run(ctx, d, 0, "--samples")?;
    a.design.check_runs(ctx, d, 1, runs, "--ensemble", &a.ensemble)?;
    let long = limits::ensemble_work(d, 1, runs)[2].value > 4e7;
    let spinner = budget::spinner("simulating", long);
    let e = ensemble::evaluate(d, runs, None)?;
    spinner.finish_and_clear();
    let e = e.ok_or(ThudError::Cancelled)?;
    let report = EnsembleReport::new(d, &e);
    let truncated = report.truncation_reason.clone();
    match a.output.format() {
        OutputFormat::Csv => {
            if let Some(why) = &truncated {
                super::warn(&format!("warning: {why}"));
            }
            super::output::check_finite(&e.ensemble)?;
            let csv = crate::export::csv::ensemble_members(&e.ensemble)
                .map_err(|err| ThudError::invalid("csv", format!("cannot write: {err}")))?;
            out.text(&csv)?;
        }
        OutputFormat::Json => out.json(&report)?,
        OutputFormat::Text => {
            super::output::check_finite(&e)?;
            out.text(&ensemble_summary(d, &e, truncated.as_deref()))?;
        }
    }
    Ok(())
}

/// "0.6100 cm/s [0.5200–0.7000]": the median and [p10–p90] of one metric, with `digits`
/// decimals; "—" for a percentile among runs without the metric.
pub(crate) fn spread_text(p: &Percentiles, digits: usize, unit: &str) -> String {
    format!("{}{unit} [{}–{}]", opt(p.median, digits), opt(p.p10, digits), opt(p.p90, digits))
}

/// The text summary of an ensemble.
fn ensemble_summary(d: &Design, e: &Ensemble, truncated: Option<&str>) -> String {
    let s_ = &e.spread;
    let mut s = format!("design    {}\n", describe(d));
    if let Some(why) = truncated {
        s += &format!("TRUNCATED {why}\n");
    }
    let half = 0.5 * d.damper.gap_m;
    s += &format!(
        "ensemble  {} runs, the ball at rest from y0 = −d/2 + (k + ½)·d/{} ({} to {} cm); median [p10–p90] by nearest rank\n",
        e.runs,
        e.runs,
        num(-(half - half / e.runs as f64) * 1e2),
        num((half - half / e.runs as f64) * 1e2),
    );
    s += &format!(
        "damping   e {} (Eq 27), e_fit {}\n",
        spread_text(&s_.inclination_cm_s, 4, " cm/s"),
        spread_text(&s_.inclination_fit_cm_s, 4, " cm/s")
    );
    s += &format!(
        "noise     U0max {}, SPLmax {}\n",
        spread_text(&s_.u0_max_m_s, 4, " m/s"),
        spread_text(&s_.spl_max_db, 2, " dB")
    );
    s += &format!(
        "zone      {} of the medians; {:.0} % of the runs agree; zone 3 in {:.0} % of the runs\n",
        e.metrics.zone.map_or("—".into(), |z| format!("{} ({})", z.number(), z.describe())),
        100.0 * e.agreement,
        100.0 * e.zone3_probability
    );
    s += "runs:\n      k    y0 (cm)  impacts   e (cm/s)  e_fit (cm/s)  U0max (m/s)  SPLmax (dB)  zone\n";
    for (k, m) in e.ensemble.iter().enumerate() {
        s += &format!(
            "  {:>5}  {:>9.4}  {:>7}  {:>9}  {:>12}  {:>11.4}  {:>11}  {:>4}\n",
            k,
            m.ball_position_m * 1e2,
            m.metrics.n_impacts,
            opt(m.metrics.inclination_cm_s, 4),
            opt(m.metrics.inclination_fit_cm_s, 4),
            m.metrics.u0_max_m_s,
            opt(m.metrics.spl_max_db, 2),
            m.metrics.zone.map_or("—".into(), |z| z.number().to_string())
        );
    }
    if d.damper.forced() {
        // The runs' spread comes from the attractors their starts reach.
        s += "\n(runs that differ may have reached different orbits: `thud basins` maps which ball start reaches which)\n";
    }
    s
}

fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("—".into(), |x| format!("{x:.digits$}"))
}

/// One line describing a design, in the units people use, each number to the precision it
/// has (as typed: `M 0.5 kg`, not `0.5000 kg`; [`short`], the rule of the figures' titles).
pub fn describe(d: &Design) -> String {
    let p = &d.damper;
    let solver = match d.solver {
        Solver::Event => "event-driven solver".to_string(),
        Solver::Newmark { dt_s } => format!("Newmark-β solver, dt {} s", short(dt_s)),
    };
    let mut extra = String::new();
    if p.forced() {
        extra += &format!("; force {} N at {} Hz", short(p.force_n), short(p.freq_hz));
        if p.settle {
            extra += ", settling";
        }
    }
    if p.ball_position_m != 0.0 || p.ball_velocity_m_s != 0.0 {
        extra += &format!("; ball from y0 {} cm at {} m/s", short(p.ball_position_m * 1e2), short(p.ball_velocity_m_s));
    }
    format!(
        "m {} g (a {} mm), d {} cm, v0 {} m/s; M {} kg, K {} N/m, C {} N·s/m; c1 {} N·s/m{}, K_HZ {} N/m^1.5; {solver}, {} s{extra}",
        short(p.impact_mass_kg * 1e3),
        short(d.ball_radius_m() * 1e3),
        short(p.gap_m * 1e2),
        short(p.v0_m_s),
        short(p.main_mass_kg),
        short(p.stiffness_n_m),
        short(p.damping_n_s_m),
        short(p.c1_n_s_m),
        if p.no_tension { " (no tension)" } else { "" },
        short(p.k_hz),
        short(p.duration_s)
    )
}

// Over 80 lines: the report's lines in the order printed, one short block per figure.
fn summary(d: &ValidDesign, e: &Evaluation, show: usize, truncated: Option<&str>) -> Result<String, ThudError> {
    let m = &e.metrics;
    let mut s = format!("design    {}\n", describe(d));
    if let Some(why) = truncated {
        s += &format!("TRUNCATED {why}\n");
    }
    let level = match d.model {
        crate::design::Model::Paper => "SPL = rms over τ from the direct arrival".to_string(),
        crate::design::Model::Physical => {
            let air = d.sound().air;
            format!(
                "physical model: SPL = peak level, exact Hertz pulse, air ρ0c {} Pa·s/m, c {} m/s",
                num(air.rho_c_pa_s_m),
                num(air.c_m_s)
            )
        }
    };
    // The signs are the corner's second wall's: only a quadrupole has one.
    let signs = if d.radiation.source == crate::acoustics::Source::Quadrupole {
        format!(" ({} signs)", d.radiation.quad_signs.name())
    } else {
        String::new()
    };
    s += &format!(
        "listener  {} source{signs}, r {} m, θ {}°; {level}\n",
        d.radiation.source.name(),
        short(d.observer.r_m),
        short(d.observer.theta_rad.to_degrees())
    );
    s += &format!(
        "damping   e {} cm/s (Eq 27), e_fit {} cm/s; {} impacts; mean restitution {}\n",
        opt(m.inclination_cm_s, 4),
        opt(m.inclination_fit_cm_s, 4),
        m.n_impacts,
        opt(m.restitution_mean, 4)
    );
    s += &format!(
        "noise     U0max {} m/s ({}), SPLmax {} dB, contact {} µs; zone {}\n",
        format_args!("{:.4}", m.u0_max_m_s),
        match d.u0max_rule {
            design::U0MaxRule::Impacts => "largest impact speed",
            design::U0MaxRule::WholeRun => "largest |z'| incl. t = 0",
        },
        opt(m.spl_max_db, 2),
        opt(m.contact_duration_s.map(|t| t * 1e6), 2),
        m.zone.map_or("—".into(), |z| format!("{} ({})", z.number(), z.describe()))
    );
    let en = &e.run.energy;
    let work =
        if d.damper.forced() { format!(", work of the force {} J", num(en.forcing_work_j)) } else { String::new() };
    s += &format!(
        "energy    initial {} J{work}, final {} J, dissipated {} J viscous + {} J in contacts\n",
        num(en.initial_j),
        num(en.final_mechanical_j),
        num(en.dissipated_viscous_j),
        num(en.dissipated_contact_j)
    );
    if let Some(st) = &e.steady {
        s += &steady_line(st);
    }
    if !e.run.impacts.is_empty() {
        let spls = design::impact_spls(&e.run, d)?;
        s += &format!("impacts (first {} of {}):\n", show.min(e.run.impacts.len()), e.run.impacts.len());
        s += "      #       t (s)  wall  u_in (m/s)  u_out (m/s)       R     τ (µs)   δmax (µm)  SPL (dB)\n";
        for (k, (i, spl)) in e.run.impacts.iter().zip(spls).take(show).enumerate() {
            s += &format!(
                "  {:>5}  {:>10.7}  {:>+4}  {:>10.5}  {:>11.5}  {:>6.4}  {:>9.3}  {:>10.3}  {:>8.2}\n",
                k + 1,
                i.t_s,
                i.wall,
                i.u_in_m_s,
                i.u_out_m_s,
                i.u_out_m_s / i.u_in_m_s,
                (i.t_end_s - i.t_s) * 1e6,
                i.penetration_max_m * 1e6,
                spl
            );
        }
    }
    if !e.run.maxima.is_empty() {
        let list: Vec<String> =
            e.run.maxima.iter().take(6).map(|x| format!("{:.4} cm at {:.4} s", x.x_m * 1e2, x.t_s)).collect();
        s += &format!("maxima    {}{}\n", list.join(", "), if e.run.maxima.len() > 6 { ", …" } else { "" });
    }
    Ok(s)
}

/// The verdict on a forced motion as the text outputs print it: its label
/// ([`crate::verdict::Verdict::label`]), in capitals where its figures are not a steady
/// state's (`NOT SETTLED`, `TRUNCATED`), with `m/n` explained.
pub(crate) fn verdict_words(v: &crate::verdict::Verdict) -> String {
    match v {
        crate::verdict::Verdict::Periodic { .. } => format!("{} (impacts/periods)", v.label()),
        _ if v.is_marked() => v.label().to_uppercase(),
        _ => v.label(),
    }
}

/// The steady state of a forced run, in two lines.
pub(crate) fn steady_line(st: &crate::response::Steady) -> String {
    let linear = match (st.amplitude_linear_m, st.reduction_db) {
        (Some(a), Some(r)) => format!("without the ball {} mm, the damper cuts {:.2} dB", num(a * 1e3), r),
        _ => "without the ball unbounded (no damping at resonance)".into(),
    };
    format!(
        "steady    last {} periods (t {}–{} s): amplitude {} mm ({linear})\n          {:.3} impacts/period, Leq {} dB; orbit {}\n",
        st.periods,
        num(st.window_start_s),
        num(st.window_end_s),
        num(st.amplitude_m * 1e3),
        st.impacts_per_period,
        opt(st.leq_db, 2),
        verdict_words(&st.verdict),
    )
}
