//! CSV files: a header of keys with their SI unit in the name, then one row per point. Numbers
//! are written in full precision (Rust's shortest round-trip form).

use crate::acoustics::Field;
use crate::damper::{free_response, DamperParams, Run};
use crate::design::Chart;
use crate::paper::{Table, Value};

/// An optional number: empty when absent.
fn opt(v: Option<f64>) -> String {
    v.map_or(String::new(), |x| x.to_string())
}

/// The pressure waveform of one impact, `n` uniform samples: `t_s,p_pa` (time after the
/// contact starts, so the first sound arrives at the propagation delay).
pub fn waveform(field: &Field, n: usize) -> String {
    let (t, p) = field.waveform(n);
    let mut s = String::from("t_s,p_pa\n");
    for (ti, pi) in t.iter().zip(&p) {
        s += &format!("{ti},{pi}\n");
    }
    s
}

/// The time history of a run: `t_s,x_m,y_m,x_free_m`, with the main mass's motion without the
/// damper (`x_free_m`) beside it.
pub fn history(run: &Run, damper: &DamperParams) -> String {
    let mut s = String::from("t_s,x_m,y_m,x_free_m\n");
    for h in &run.history {
        s += &format!("{},{},{},{}\n", h.t_s, h.x_m, h.y_m, free_response(damper, h.t_s));
    }
    s
}

/// The impacts of a run with the SPL of each (`spl_db[k]` for impact k, dB re 20 µPa, rms
/// over τ from the direct arrival).
pub fn impacts(run: &Run, spl_db: &[f64]) -> String {
    let mut s =
        String::from("index,t_s,wall,u_in_m_s,u_out_m_s,restitution,t_end_s,duration_s,penetration_max_m,spl_db\n");
    for (k, i) in run.impacts.iter().enumerate() {
        s += &format!(
            "{},{},{},{},{},{},{},{},{},{}\n",
            k + 1,
            i.t_s,
            i.wall,
            i.u_in_m_s,
            i.u_out_m_s,
            i.u_out_m_s / i.u_in_m_s,
            i.t_end_s,
            i.t_end_s - i.t_s,
            i.penetration_max_m,
            opt(spl_db.get(k).copied())
        );
    }
    s
}

/// The design chart, one row per computed cell (mass × gap).
pub fn sweep(chart: &Chart) -> String {
    let mut s = String::from(
        "mass_kg,gap_m,inclination_cm_s,inclination_fit_cm_s,u0_max_m_s,zdot_abs_max_m_s,spl_max_db,n_impacts,zone\n",
    );
    for c in chart.cells.iter().flatten() {
        let m = &c.metrics;
        s += &format!(
            "{},{},{},{},{},{},{},{},{}\n",
            c.mass_kg,
            c.gap_m,
            opt(m.inclination_cm_s),
            opt(m.inclination_fit_cm_s),
            m.u0_max_m_s,
            m.zdot_abs_max_m_s,
            opt(m.spl_max_db),
            m.n_impacts,
            m.zone.map_or(String::new(), |z| z.number().to_string())
        );
    }
    s
}

/// One cell of a table: numbers in full, text quoted when needed, nothing for a missing value.
fn cell(v: &Value) -> String {
    match v {
        Value::Num(x) => format!("{x}"),
        Value::Text(s) if s.contains([',', '"', '\n']) => format!("\"{}\"", s.replace('"', "\"\"")),
        Value::Text(s) => s.clone(),
        Value::Missing => String::new(),
    }
}

/// A reproduced paper table: a header of column keys, then the rows.
pub fn table(t: &Table) -> String {
    let mut s = t.columns.iter().map(|c| c.key).collect::<Vec<_>>().join(",") + "\n";
    for row in &t.rows {
        s += &(row.iter().map(cell).collect::<Vec<_>>().join(",") + "\n");
    }
    s
}
