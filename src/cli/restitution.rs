//! `thud restitution`: R against impact mass (Fig 13) and the inverse, c1 for a wanted R.

use clap::Args;

use super::design_args::{parse_range, DesignArgs};
use super::{quantity, CliError, Ctx, Out, OutputArgs};
use crate::design;
use crate::limits::{self, short};
use crate::paper::{col, Table};
use crate::units::Kind;

#[derive(Debug, Clone, Args)]
pub struct RestitutionArgs {
    #[command(flatten)]
    design: DesignArgs,
    /// Approach speed U0 of the contact (m/s) [default: 1.4].
    #[arg(long, value_name = "U", allow_hyphen_values = true)]
    u0: Option<String>,
    /// Impact masses FROM:TO:N [default: 5g:100g:20].
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true, default_value = "5g:100g:20")]
    masses: String,
    /// A wanted restitution R in (0, 1]: print the c1 that gives it for each mass.
    #[arg(long, value_name = "R", allow_hyphen_values = true)]
    target: Option<String>,
    #[command(flatten)]
    output: OutputArgs,
}

pub fn run(a: &RestitutionArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let d = a.design.design()?;
    let u0 = quantity("u0", &a.u0, Kind::Speed, &limits::U0)?.unwrap_or(1.4);
    let masses = parse_range("masses", &a.masses, Kind::Mass, &limits::MASS)?;
    let target = quantity("target", &a.target, Kind::Number, &limits::TARGET)?;
    let contacts = limits::restitution_contacts(masses.len(), target.is_some());
    let per_mass = contacts.value / masses.len() as f64;
    ctx.enforce(
        contacts,
        "--masses",
        &a.masses,
        &format!("use at most {} masses", short((contacts.cap.max / per_mass).floor())),
    )?;
    let curve = design::restitution_curve(&d, &masses, u0)?;
    let mut rows = Vec::new();
    for &(m, r) in &curve {
        let mut row = vec![(m * 1e3).into(), r.into()];
        if let Some(t) = target {
            let c1 = design::c1_for_restitution(&design::variant(&d, m, d.damper.gap_m).check()?, u0, t)?;
            row.push(c1.into());
        }
        rows.push(row);
    }
    let mut columns = vec![col("mass_g", "m (g)"), col("restitution", "R")];
    if target.is_some() {
        columns.push(col("c1_for_target_n_s_m", "c1 for target (N·s/m)"));
    }
    let p = &d.damper;
    let table = Table {
        id: "restitution",
        title: format!(
            "Restitution of one contact at U0 {} m/s against M {} kg (c1 {} N·s/m{}, K_HZ {})",
            short(u0),
            short(p.main_mass_kg),
            short(p.c1_n_s_m),
            if p.no_tension { ", no tension" } else { "" },
            if d.materials.is_some() { "from materials".to_string() } else { format!("{} N/m^1.5", short(p.k_hz)) }
        ),
        notes: std::iter::once(
            "One isolated ball–main-mass contact: δ'' = −K*(K_HZ δ^1.5 + c1 δ'), K* = (m+M)/(mM), R = u_out/U0."
                .to_string(),
        )
        .chain(target.map(|t| format!("Last column: the c1 that gives R = {t} for each mass.")))
        .collect(),
        columns,
        rows,
        summary: Vec::new(),
    };
    out.table(&table, a.output.format())
}
