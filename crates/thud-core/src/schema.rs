//! The one data schema: every table thud writes (the command line's CSV files, the rows of its
//! JSON records, Python's DataFrames) as an ordered list of columns, each with its name, unit
//! and meaning. The CSV writers take their header from here, Python builds its DataFrames from
//! here (`thud.schema()`), and the tests check the JSON records, the guide's schema page
//! (docs/guide/schema.md) and Python's columns against it.
//!
//! Spelling: snake_case, SI, the unit in the name (`mass_kg`, `gap_m`, `spl_max_db`), a count as
//! `n_…`, a pure number with no suffix; an ensemble's percentiles of a metric `X` as `X_p10`,
//! `X_median`, `X_p90`. A table of a JSON record is that record flattened: the keys of a nested
//! `metrics` object in place, a `spread` object's `{X: {p10, median, p90}}` as `X_p10`,
//! `X_median`, `X_p90`, and a key of the enclosing record (a response's `direction`, an
//! ensemble's `runs`) in front.

/// One column: its name (the CSV header, the JSON key, the DataFrame column), its unit
/// (`"1"` for a pure number, `"—"` for text or a flag) and what it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Column {
    pub name: &'static str,
    pub unit: &'static str,
    pub doc: &'static str,
}

/// One table: an identifier (`thud.schema()`'s key), what writes it, and its columns in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Table {
    pub id: &'static str,
    pub written_by: &'static str,
    pub columns: &'static [Column],
}

impl Table {
    /// The column names in order.
    pub fn names(&self) -> Vec<&'static str> {
        self.columns.iter().map(|c| c.name).collect()
    }
}

const fn col(name: &'static str, unit: &'static str, doc: &'static str) -> Column {
    Column { name, unit, doc }
}

/// The columns of `parts` one after the other, as one array of `N`, their count (checked when
/// the crate is built): a table made of the column groups it shares with others.
const fn join<const N: usize>(parts: &[&[Column]]) -> [Column; N] {
    let mut out = [col("", "", ""); N];
    let (mut k, mut p) = (0, 0);
    while p < parts.len() {
        let mut i = 0;
        while i < parts[p].len() {
            out[k] = parts[p][i];
            k += 1;
            i += 1;
        }
        p += 1;
    }
    assert!(k == N, "a joined table's length is the count of its columns");
    out
}

// Time series.
const T_S: Column = col("t_s", "s", "time (of a sample; of an impact's onset)");
const P_PA: Column = col("p_pa", "Pa", "sound pressure at the observer");
const X_M: Column = col("x_m", "m", "main mass displacement");
const Y_M: Column = col("y_m", "m", "ball displacement");
const X_FREE_M: Column = col("x_free_m", "m", "main mass without the damper");

// One impact.
const WALL: Column = col("wall", "±1", "the wall hit: +1 upper, −1 lower");
const U_IN_M_S: Column = col("u_in_m_s", "m/s", "relative speed into the contact");
const U_OUT_M_S: Column = col("u_out_m_s", "m/s", "relative speed out of the contact");
const RESTITUTION: Column = col("restitution", "1", "u_out/u_in of the impact");
const T_END_S: Column = col("t_end_s", "s", "contact end");
const DURATION_S: Column = col("duration_s", "s", "contact duration");
const PENETRATION_MAX_M: Column = col("penetration_max_m", "m", "largest penetration δ");
const SPL_DB: Column = col("spl_db", "dB", "SPL, rms over τ from the direct arrival (re 20 µPa)");

// The metrics of a run (design::Metrics, in its serde order).
const N_IMPACTS: Column = col("n_impacts", "1", "impacts in the run");
const INCLINATION_CM_S: Column = col("inclination_cm_s", "cm/s", "damping inclination e (Eq 27)");
const INCLINATION_FIT_CM_S: Column = col("inclination_fit_cm_s", "cm/s", "the robust inclination e_fit");
const U0_MAX_M_S: Column = col("u0_max_m_s", "m/s", "largest contact speed U0max");
const ZDOT_ABS_MAX_M_S: Column = col("zdot_abs_max_m_s", "m/s", "largest relative speed |z'| including t = 0");
const SPL_MAX_DB: Column = col("spl_max_db", "dB", "SPLmax, the SPL of an impact at U0max");
const CONTACT_DURATION_S: Column = col("contact_duration_s", "s", "Hertz contact duration at U0max");
const RESTITUTION_MEAN: Column = col("restitution_mean", "1", "mean u_out/u_in over the impacts");
const ZONE: Column = col("zone", "1–4", "design-chart zone (empty when there is none)");
/// The metrics of a run, in order (every table of runs or cells carries them).
const METRICS: [Column; 9] = [
    N_IMPACTS,
    INCLINATION_CM_S,
    INCLINATION_FIT_CM_S,
    U0_MAX_M_S,
    ZDOT_ABS_MAX_M_S,
    SPL_MAX_DB,
    CONTACT_DURATION_S,
    RESTITUTION_MEAN,
    ZONE,
];

// Designs, ensembles, parts.
const MASS_KG: Column = col("mass_kg", "kg", "impact (ball) mass m");
const GAP_M: Column = col("gap_m", "m", "total clearance d");
const BALL_POSITION_M: Column = col("ball_position_m", "m", "initial offset y0 of the ball of one run");
const RUNS: Column = col("runs", "1", "runs N of an ensemble");
const RUN: Column = col("run", "1", "run k of an ensemble, from 0");
const INDEX: Column = col("index", "1", "cell number in the grid (row-major, gap outer), from 0");
const ZONE3_PROBABILITY: Column = col("zone3_probability", "1", "fraction of the runs in zone 3");
const AGREEMENT: Column = col("agreement", "1", "fraction of the runs in the zone of the medians");
const TRUNCATED_REASON: Column = col("truncated", "—", "the solver work cap that stopped the run (else empty)");

// A forced response.
const DIRECTION: Column = col("direction", "—", "the sweep: from_rest, up or down");
const FREQ_HZ: Column = col("freq_hz", "Hz", "forcing frequency f");
const PERIODS: Column = col("periods", "1", "forcing periods in the steady-state window");
const WINDOW_START_S: Column = col("window_start_s", "s", "start of the steady-state window");
const WINDOW_END_S: Column = col("window_end_s", "s", "end of the steady-state window");
const AMPLITUDE_M: Column = col("amplitude_m", "m", "steady amplitude of the main mass");
const AMPLITUDE_LINEAR_M: Column = col("amplitude_linear_m", "m", "the closed-form amplitude without the damper");
const REDUCTION_DB: Column = col("reduction_db", "dB", "20·log10(linear / damped amplitude)");
const IMPACTS_PER_PERIOD: Column = col("impacts_per_period", "1", "impacts per forcing period");
const LEQ_DB: Column = col("leq_db", "dB", "equivalent level Leq over the window");
const PERIODIC: Column = col("periodic", "—", "true when the steady state is periodic");
const SETTLED: Column = col("settled", "—", "true when the run settled");
const TRUNCATED: Column = col("truncated", "—", "true when a work cap stopped a run before its window's end");
const VERDICT: Column = col(
    "verdict",
    "—",
    "the verdict on the motion (docs/model.md §6.6): m/n (m impacts per n periods, sym when symmetric), settled, chaotic, not settled or truncated",
);
const FINAL_TIME_S: Column = col("final_time_s", "s", "where the run ended");
const PERIODIC_FRACTION: Column = col("periodic_fraction", "1", "fraction of the runs periodic");
const SETTLED_FRACTION: Column = col("settled_fraction", "1", "fraction of the runs settled");

/// The three percentiles of an ensemble of the metric `$name` (unit `$unit`).
macro_rules! spread {
    ($name:literal, $unit:literal) => {
        [
            col(concat!($name, "_p10"), $unit, concat!("10th percentile over the runs of ", $name)),
            col(concat!($name, "_median"), $unit, concat!("median over the runs of ", $name)),
            col(concat!($name, "_p90"), $unit, concat!("90th percentile over the runs of ", $name)),
        ]
    };
}

const INCLINATION_SPREAD: [Column; 3] = spread!("inclination_cm_s", "cm/s");
const FIT_SPREAD: [Column; 3] = spread!("inclination_fit_cm_s", "cm/s");
const U0_SPREAD: [Column; 3] = spread!("u0_max_m_s", "m/s");
const SPL_SPREAD: [Column; 3] = spread!("spl_max_db", "dB");
const AMPLITUDE_SPREAD: [Column; 3] = spread!("amplitude_m", "m");
/// The cut of the runs of the amplitude's percentiles (the cut falls as the amplitude grows).
const REDUCTION_SPREAD: [Column; 3] = [
    col("reduction_db_p10", "dB", "reduction_db of the run at the 90th percentile of amplitude_m"),
    col("reduction_db_median", "dB", "reduction_db of the run of median amplitude_m"),
    col("reduction_db_p90", "dB", "reduction_db of the run at the 10th percentile of amplitude_m"),
];
const IMPACTS_SPREAD: [Column; 3] = spread!("impacts_per_period", "1");
const LEQ_SPREAD: [Column; 3] = spread!("leq_db", "dB");

/// `thud pulse --csv`, `export csv waveform`; Python `Pulse.to_dataframe()`.
pub const PULSE: Table = Table { id: "pulse", written_by: "pulse --csv, export csv waveform", columns: &[T_S, P_PA] };

/// `thud simulate --csv`, `export csv history`; Python `Run.history_frame()`.
pub const HISTORY: Table =
    Table { id: "history", written_by: "simulate --csv, export csv history", columns: &[T_S, X_M, Y_M, X_FREE_M] };

/// `export csv impacts`, the rows of `simulate --json`'s `impacts`; Python `Run.impacts_frame()`.
pub const IMPACTS: Table = Table {
    id: "impacts",
    written_by: "export csv impacts, simulate --json impacts[]",
    columns: &[T_S, WALL, U_IN_M_S, U_OUT_M_S, RESTITUTION, T_END_S, DURATION_S, PENETRATION_MAX_M, SPL_DB],
};

/// `thud simulate --ensemble N --csv`, the rows of its JSON `ensemble`; Python
/// `Ensemble.to_dataframe()`.
pub const ENSEMBLE: Table = Table {
    id: "ensemble",
    written_by: "simulate --ensemble N --csv, simulate --ensemble N --json ensemble[]",
    columns: &join::<10>(&[&[BALL_POSITION_M], &METRICS]),
};

/// `thud sweep --csv`, `export csv sweep`, a cell of `sweep --json` (`mass_kg`, `gap_m`,
/// `metrics.*`); Python `Chart.to_dataframe()`.
pub const SWEEP: Table = Table {
    id: "sweep",
    written_by: "sweep --csv, export csv sweep, sweep --json chart.cells[]",
    columns: &join::<11>(&[&[MASS_KG, GAP_M], &METRICS]),
};

/// `thud sweep --ensemble N --csv` and `merge`, a cell of `sweep --ensemble N --json`
/// flattened (its metrics are the medians); Python `Chart.to_dataframe()` of an ensemble chart.
pub const SWEEP_ENSEMBLE: Table = Table {
    id: "sweep_ensemble",
    written_by: "sweep --ensemble N --csv, merge, sweep --ensemble N --json chart.cells[]",
    columns: &join::<26>(&[
        &[MASS_KG, GAP_M, RUNS],
        &METRICS,
        &INCLINATION_SPREAD,
        &FIT_SPREAD,
        &U0_SPREAD,
        &SPL_SPREAD,
        &[ZONE3_PROBABILITY, AGREEMENT],
    ]),
};

/// A CSV part of `thud sweep [--ensemble N] --shard K/N --csv --out FILE`: one row per run of each
/// cell; Python `Chart.runs_frame()` has these columns but `index` and `truncated`.
pub const SHARD_PART: Table = Table {
    id: "shard_part",
    written_by: "sweep --shard K/N --csv --out FILE, a part merge reads",
    columns: &join::<15>(&[&[INDEX, RUN, MASS_KG, GAP_M, BALL_POSITION_M], &METRICS, &[TRUNCATED_REASON]]),
};

/// `thud response --csv`: a point of `response --json` with its sweep's `direction` in
/// front; Python `Response.to_dataframe()`.
pub const RESPONSE: Table = Table {
    id: "response",
    written_by: "response --csv, response --json sweeps[].points[]",
    columns: &[
        DIRECTION,
        FREQ_HZ,
        PERIODS,
        WINDOW_START_S,
        WINDOW_END_S,
        AMPLITUDE_M,
        AMPLITUDE_LINEAR_M,
        REDUCTION_DB,
        IMPACTS_PER_PERIOD,
        LEQ_DB,
        PERIODIC,
        SETTLED,
        TRUNCATED,
        VERDICT,
        FINAL_TIME_S,
    ],
};

/// `thud response --ensemble N --csv`: a point of its JSON flattened, with the sweep's
/// `direction` and the `runs` in front; Python `Response.to_dataframe()` of an ensemble.
pub const RESPONSE_ENSEMBLE: Table = Table {
    id: "response_ensemble",
    written_by: "response --ensemble N --csv, response --ensemble N --json sweeps[].points[]",
    columns: &join::<19>(&[
        &[DIRECTION, FREQ_HZ, RUNS, AMPLITUDE_LINEAR_M],
        &AMPLITUDE_SPREAD,
        &REDUCTION_SPREAD,
        &IMPACTS_SPREAD,
        &LEQ_SPREAD,
        &[PERIODIC_FRACTION, SETTLED_FRACTION, TRUNCATED],
    ]),
};

// Studies, orbits and their maps.
/// A template, not a name: one column per varied parameter, named by its row and unit
/// ([`crate::study::column`]: `v0_m_s`, `freq_hz`, `c1_n_s_m`).
pub const VARIED: Column =
    col("{varied}", "—", "one column per varied parameter, its name and unit (v0_m_s, freq_hz, c1_n_s_m)");
const ORBIT: Column =
    col("orbit", "—", "the orbit's type: m/n (impacts per forcing periods), sym, chaotic, not settled");
const RECORD: Column = col("record", "—", "what the row holds: sample (x(kT)) or impact");
const PERIOD: Column = col("period", "1", "the forcing period of the sample or impact (from 0)");
const V_M_S: Column = col("v_m_s", "m/s", "main mass velocity x'");
const Z_M: Column = col("z_m", "m", "ball relative to the enclosure's centre, z = y − x");
const ZDOT_M_S: Column = col("zdot_m_s", "m/s", "z'");
const PHASE: Column = col("phase", "1", "the force's phase at the impact's onset (fraction of the period)");
const STABLE: Column = col("stable", "—", "every Floquet multiplier inside the unit circle");
const MULTIPLIER_ABS_MAX: Column = col("multiplier_abs_max", "1", "largest |λ| of the Floquet multipliers");
const IMPACTS_PER_ORBIT: Column = col("impacts_per_orbit", "1", "impacts over the orbit's n periods, m");
const ORBIT_AMPLITUDE_M: Column = col("amplitude_m", "m", "steady amplitude of the main mass");
const ORBIT_PERIODS: Column = col("periods", "1", "the orbit's period in forcing periods, n");
/// The samples x(kT) and the impacts of a forced run, one row each (an impact map's table).
const SAMPLES_AND_IMPACTS: [Column; 11] =
    [ORBIT, RECORD, PERIOD, X_M, V_M_S, Z_M, ZDOT_M_S, PHASE, WALL, U_IN_M_S, U_OUT_M_S];
const STUDY_INDEX: Column = col("index", "1", "cell number in the grid (C order over the varied parameters), from 0");

/// `thud sweep --vary … --csv`, a cell of `sweep --vary --json`; Python `thud.sweep(v0=[…], …)`
/// (its dimensions are these columns).
pub const STUDY: Table =
    Table { id: "study", written_by: "sweep --vary --csv", columns: &join::<11>(&[&[STUDY_INDEX, VARIED], &METRICS]) };

/// `thud bifurcation --csv`: per value its samples x(kT) and its impacts, one row each.
pub const BIFURCATION: Table = Table {
    id: "bifurcation",
    written_by: "bifurcation --csv",
    columns: &join::<13>(&[&[VARIED, DIRECTION], &SAMPLES_AND_IMPACTS]),
};

/// `thud impact-map --csv`: the samples x(kT) and the impacts, one row each; Python
/// `thud.impact_map(…)`.
pub const IMPACT_MAP: Table = Table { id: "impact_map", written_by: "impact-map --csv", columns: &SAMPLES_AND_IMPACTS };

/// `thud basins --csv`: one row per start.
pub const BASINS: Table = Table {
    id: "basins",
    written_by: "basins --csv",
    columns: &[
        col("y0_m", "m", "the ball's start offset from the enclosure's centre"),
        col("w0_m_s", "m/s", "the ball's start velocity"),
        col("attractor", "1", "the attractor the start settles on (its id)"),
        ORBIT,
        ORBIT_AMPLITUDE_M,
    ],
};

/// `thud restitution --csv`: the paper's restitution against the ball's mass (Fig 6), the
/// mass in grams as the paper's axis; the last column only with `--target`.
pub const RESTITUTION_TABLE: Table = Table {
    id: "restitution",
    written_by: "restitution --csv",
    columns: &[
        col("mass_g", "g", "ball mass m, in grams as the paper's axis"),
        RESTITUTION_OF_MASS,
        col("c1_for_target_n_s_m", "N·s/m", "with --target R: the contact damping c1 that gives R at that mass"),
    ],
};
const RESTITUTION_OF_MASS: Column = col("restitution", "1", "the coefficient of restitution at that mass (Fig 6)");

/// `thud orbit --csv`: the orbit's own columns on every row, then one impact per row; Python
/// `thud.orbit(…)`.
pub const ORBIT_TABLE: Table = Table {
    id: "orbit",
    written_by: "orbit --csv",
    columns: &[
        ORBIT,
        ORBIT_PERIODS,
        IMPACTS_PER_ORBIT,
        col("symmetric", "—", "x(t + T/2) = −x(t)"),
        ORBIT_AMPLITUDE_M,
        STABLE,
        col(
            "critical",
            "—",
            "how the largest multiplier crosses the unit circle: fold, period_doubling, neimark_sacker",
        ),
        MULTIPLIER_ABS_MAX,
        col("impact", "1", "the impact's number in the orbit (from 0)"),
        PERIOD,
        PHASE,
        WALL,
        U_IN_M_S,
        U_OUT_M_S,
    ],
};

/// `thud continue --csv`, a point of `continue --json`; Python `thud.continuation(…)`.
pub const CONTINUATION: Table = Table {
    id: "continuation",
    written_by: "continue --csv",
    columns: &[
        VARIED,
        ORBIT,
        ORBIT_PERIODS,
        IMPACTS_PER_ORBIT,
        STABLE,
        MULTIPLIER_ABS_MAX,
        ORBIT_AMPLITUDE_M,
        X_M,
        V_M_S,
        Z_M,
        ZDOT_M_S,
    ],
};

/// `thud continue --vary NAME=FROM:TO:N --csv`: every branch of the family, each point a row
/// with its branch's number in front.
pub const CONTINUATION_FAMILY: Table = Table {
    id: "continuation_family",
    written_by: "continue --vary NAME=FROM:TO:N --csv",
    columns: &join::<12>(&[&[col("branch", "1", "the branch's number in the family, from 1")], CONTINUATION.columns]),
};

// The JSON records whose keys are not a table's columns: each key of the record, in order.
const DESIGN_KEY: Column = col("design", "—", "the design as run (the keys of a saved design)");
const VALUE: Column = col("value", "—", "the varied parameter's value, in the unit of the record's `unit`");
/// The keys of the record of `thud orbit --json`; its `impacts[]` have the `orbit` table's
/// impact columns (period, phase, wall, u_in_m_s, u_out_m_s).
pub const ORBIT_RECORD: Table = Table {
    id: "orbit_record",
    written_by: "orbit --json",
    columns: &[
        DESIGN_KEY,
        ORBIT_PERIODS,
        IMPACTS_PER_ORBIT,
        col("symmetric", "—", "x(t + T/2) = −x(t)"),
        X_M,
        V_M_S,
        Z_M,
        ZDOT_M_S,
        ORBIT_AMPLITUDE_M,
        AMPLITUDE_LINEAR_M,
        col("impacts", "—", "the orbit's impacts, each with the orbit table's impact columns"),
        col("multipliers", "—", "the Floquet multipliers, largest modulus first, each {re, im}"),
        STABLE,
        col(
            "critical",
            "—",
            "how the largest multiplier crosses the unit circle: fold, period_doubling, neimark_sacker",
        ),
        col("residual", "m, m/s", "|Pⁿ(s) − s| at the orbit, the largest component (m or m/s)"),
        col("iterations", "1", "Newton iterations taken"),
        col("periods_simulated", "1", "forcing periods simulated to find the orbit and its multipliers"),
    ],
};

/// The keys of the record of `thud continue --json`; its `points[]` are the `continuation`
/// table's columns with the parameter as `value`, its `specials[]` the `special` table.
pub const CONTINUATION_RECORD: Table = Table {
    id: "continuation_record",
    written_by: "continue --json",
    columns: &[
        DESIGN_KEY,
        col("name", "—", "the varied parameter's name (freq, gap, …)"),
        col("unit", "—", "the varied parameter's unit (Hz, m, …; empty for a plain number)"),
        col("points", "—", "the branch's points, each with the continuation table's columns ({varied} as value)"),
        col("specials", "—", "the special points of the branch (the special table)"),
        col("ended", "—", "why the branch ended before the range's end (null when it reached it)"),
        col("branches", "—", "with a point count N: every branch, each with points, specials and ended"),
    ],
};

/// A special point of a continued branch: `thud continue --json` `specials[]`.
pub const SPECIAL: Table = Table {
    id: "special",
    written_by: "continue --json specials[]",
    columns: &[
        col("kind", "—", "fold, period_doubling, neimark_sacker, branch_point or grazing"),
        VALUE,
        ORBIT_AMPLITUDE_M,
    ],
};

/// A cap of `thud limits --json` (`caps[]`, `solver_caps[]`); its other keys are the
/// `limits` table.
pub const CAP: Table = Table {
    id: "cap",
    written_by: "limits --json caps[], solver_caps[]",
    columns: &[
        col("basis", "—", "what the cap was measured on"),
        col("max", "—", "the cap, in its own unit (steps, samples, cells, …)"),
        col("what", "—", "what the cap counts"),
    ],
};

/// The keys of `thud limits --json`; a `ranges[]` entry is the `range` table.
pub const LIMITS: Table = Table {
    id: "limits",
    written_by: "limits --json",
    columns: &[
        col("caps", "—", "the work caps (the cap table), lifted by --no-limit"),
        col("orbit_seed_impacts_max", "1", "most impacts of an orbit seed searched"),
        col("orbit_transient_periods_max", "1", "most forcing periods run to find an orbit's seed"),
        col("ranges", "—", "every parameter's range (the range table)"),
        col("settle_periods_max", "1", "most forcing periods a settling run adds"),
        col("solver_caps", "—", "the solver's work caps (the cap table)"),
    ],
};

/// A parameter's range: `thud limits --json` `ranges[]`.
pub const RANGE: Table = Table {
    id: "range",
    written_by: "limits --json ranges[]",
    columns: &[
        col("max", "—", "largest valid value, in unit"),
        col("min", "—", "smallest valid value, in unit"),
        col("param", "—", "the parameter as the command line names it, without dashes"),
        col("reason", "—", "why the range is what it is"),
        col("unit", "—", "the unit of min and max"),
        col("what", "—", "what the parameter is"),
    ],
};

/// The keys of `thud paper ID --json`: a table of the paper, self-describing: each row's keys
/// are its `columns[].key` (in the paper's units, stated in the key: `mass_g`, `gap_cm`).
pub const PAPER: Table = Table {
    id: "paper",
    written_by: "paper ID --json",
    columns: &[
        col("columns", "—", "the table's columns, each {key, label}: the keys of its rows"),
        col("id", "—", "the table's or figure's id (table3, fig10, …)"),
        col("notes", "—", "notes on how the numbers were made"),
        col("rows", "—", "the rows, each keyed by the columns' keys"),
        col("summary", "—", "summary rows, by name (only some tables)"),
        col("title", "—", "the table's title"),
    ],
};

// A design search (`thud design`): the front's columns follow the user's --vary, --minimize,
// --maximize and --require, so three of them are templates, as `{varied}` is.
/// A template: one column per `--vary` variable, named as `sweep --vary`'s column of its row
/// (`mass_kg`, `gap_m`), a choice variable by its row's name alone (`sphere`).
pub const VARIABLE: Column = col(
    "{variable}",
    "—",
    "one column per --vary variable, named as sweep --vary's column (mass_kg, gap_m), a choice bare (sphere)",
);
/// A template: one column per `--minimize`/`--maximize` objective, named as the result
/// column it is ([`crate::design::search::COLUMNS`]: `spl_max_db`, `steady_amplitude_m`).
pub const OBJECTIVE: Column = col(
    "{objective}",
    "—",
    "one column per --minimize/--maximize, named as the result column it is (spl_max_db, inclination_cm_s, steady_amplitude_m)",
);
/// A template: one column per `--require`, `margin_NAME_le` (NAME at most) or `margin_NAME_ge`
/// (at least), NAME the result column or the parameter (`-` as `_`).
pub const MARGIN: Column = col(
    "{margin}",
    "—",
    "one column per --require: margin_NAME_le or margin_NAME_ge, the constraint's margin in NAME's unit (≥ 0: met)",
);
const DESIGN_INDEX: Column = col("index", "1", "the design's number in the search, in evaluation order, from 0");
const DESIGN_FILE: Column = col("file", "—", "with --save DIR: the row's design file in DIR");

/// `thud design --csv`: one row per front design; its `{…}` columns as the search's flags name
/// them. `thud design --json` `front[]` holds the same values grouped (the `design_front` table).
pub const DESIGN: Table = Table {
    id: "design",
    written_by: "design --csv",
    columns: &[DESIGN_INDEX, VARIABLE, OBJECTIVE, MARGIN, DESIGN_FILE],
};

/// A front design of `thud design --json` (`front[]`).
pub const DESIGN_FRONT: Table = Table {
    id: "design_front",
    written_by: "design --json front[]",
    columns: &[
        DESIGN_INDEX,
        col("variables", "—", "each variable's value by its design table column ({variable})"),
        col("objectives", "—", "each objective's value by its column ({objective})"),
        col("margins", "—", "each constraint's margin (≥ 0: met), keyed by the constraint as typed"),
        DESIGN_FILE,
    ],
};

/// The keys of `thud design --json`.
pub const DESIGN_RECORD: Table = Table {
    id: "design_record",
    written_by: "design --json",
    columns: &[
        DESIGN_KEY,
        col("variables", "—", "each variable: {name, column, unit, from, to} or {name, column, options}"),
        col("objectives", "—", "each objective: {column, sense} (minimize or maximize)"),
        col("constraints", "—", "the --require constraints as typed"),
        col("band_hz", "Hz", "with a forced objective over a band: the band's frequencies"),
        col("ensemble", "—", "robust mode: {runs, quantile}, the ball starts and the quantile each result is taken at"),
        col("evaluations", "1", "designs run"),
        col("budget", "1", "designs the search was allowed (--evaluations)"),
        col("seed", "1", "the search's seed"),
        col("partial", "—", "true when the search stopped before its budget"),
        col("reference", "—", "the hypervolume's reference point, one value per objective (null without)"),
        col(
            "hypervolume",
            "—",
            "the front's hypervolume against the reference, in the objectives' units (null without)",
        ),
        col("front", "—", "the front's designs (the design_front table)"),
        col("binding", "—", "when no design is feasible: the constraint that binds, in words"),
    ],
};

// Fits (`thud fit structure|damper --json`). A residual is in the record's signal unit.
const RESIDUAL_RMS: Column =
    col("residual_rms", "m, m/s, m/s²", "RMS of data − model: in the record's unit (structure fit), in m (damper fit)");
const FIT_UNIT: Column = col("unit", "—", "the varied parameter's or the measured signal's unit");

/// The keys of `thud fit structure --json`; its `model` is the `decay_model` table. With
/// `--save` the fitted design is also written as a design file (TOML, a design's keys).
pub const STRUCTURE_FIT: Table = Table {
    id: "structure_fit",
    written_by: "fit structure --json",
    columns: &[
        col("f_n_hz", "Hz", "undamped natural frequency f_n"),
        col("f_n_hz_stderr", "Hz", "its standard error"),
        col("zeta", "1", "damping ratio ζ"),
        col("zeta_stderr", "1", "its standard error"),
        col("k_n_m", "N/m", "stiffness K = M·ω_n²"),
        col("k_n_m_stderr", "N/m", "its standard error"),
        col("c_n_s_m", "N·s/m", "viscous damping C = 2·M·σ"),
        col("c_n_s_m_stderr", "N·s/m", "its standard error"),
        col("main_mass_kg", "kg", "the main mass M given"),
        RESIDUAL_RMS,
        FIT_UNIT,
        col("converged", "—", "true when the least-squares fit converged (else its best estimate)"),
        col("termination", "—", "how the optimiser ended, in words"),
        col("samples", "1", "samples in the record"),
        col("cycles", "1", "whole cycles in the record"),
        col("start_f_hz", "Hz", "the fit's start: the spectrum's peak"),
        col("start_zeta", "1", "the fit's start: the log decrement's ζ"),
        col("model", "—", "the fitted free decay (the decay_model table)"),
    ],
};

/// The fitted free decay of `thud fit structure --json` (`model`): s(t) = e^{−στ}(a cos ω_d τ
/// + b sin ω_d τ) + offset + drift·τ, τ = t − t0, in the record's unit.
pub const DECAY_MODEL: Table = Table {
    id: "decay_model",
    written_by: "fit structure --json model",
    columns: &[
        col("t0_s", "s", "time origin t0: the record's first sample"),
        col("sigma_1_s", "1/s", "decay rate σ = ζ·ω_n"),
        col("omega_d_rad_s", "rad/s", "damped angular frequency ω_d"),
        col("a", "unit", "cosine amplitude, in the record's unit"),
        col("b", "unit", "sine amplitude, in the record's unit"),
        col("offset", "unit", "DC offset, in the record's unit"),
        col("drift_per_s", "unit/s", "drift, in the record's unit per second"),
    ],
};

/// The keys of `thud fit damper --json`; an `inputs[]` entry is the `input_shift` table. With
/// `--save` the design with the fitted c1 is also written as a design file (TOML).
pub const DAMPER_FIT: Table = Table {
    id: "damper_fit",
    written_by: "fit damper --json",
    columns: &[
        col("c1_n_s_m", "N·s/m", "the fitted contact damping c1"),
        col("c1_n_s_m_stderr", "N·s/m", "half its 95 % interval over 1.96"),
        col("c1_n_s_m_ci", "N·s/m", "its 95 % interval [low, high]"),
        col("ci_open", "—", "true when the interval reaches an end of the c1 grid (the data do not bound c1 there)"),
        col("restitution", "1", "restitution of one contact at the first impact's speed with the fitted c1"),
        col("restitution_stderr", "1", "half its 95 % interval over 1.96"),
        col("restitution_ci", "1", "its 95 % interval [low, high]"),
        col("first_impact_speed_m_s", "m/s", "the first impact's speed, the median run's at the fitted c1"),
        RESIDUAL_RMS,
        col("statistic", "1", "the data's statistic, mean ln(A_j/A_0)"),
        col("periods", "1", "the envelope's periods the statistic used"),
        col("records", "1", "records fitted"),
        col("starts", "1", "ball starts (runs) per value of c1"),
        col("grid_points", "1", "values of c1 in the grid"),
        col("envelope_period_s", "s", "the envelopes' period: one amplitude per period"),
        col("measured_envelope_m", "m", "the first record's amplitude per period"),
        col("model_envelope_m", "m", "the median run's amplitude per period at the fitted c1"),
        col("inputs", "—", "the given inputs' uncertainties carried into the interval (the input_shift table)"),
        col("v0_m_s_record", "m/s", "the strike's speed read from the records"),
        col("v0_m_s_record_stderr", "m/s", "its standard uncertainty"),
        col("note", "—", "where the data cannot bound c1 well: why and what to do"),
    ],
};

/// An input's uncertainty carried into a damper fit: `thud fit damper --json` `inputs[]`.
pub const INPUT_SHIFT: Table = Table {
    id: "input_shift",
    written_by: "fit damper --json inputs[]",
    columns: &[
        col("input", "—", "the input as its flag names it: main-mass, k, c, mass, gap or v0"),
        col("relative_sd", "1", "its relative standard uncertainty"),
        col("ln_c1_shift", "1", "how far one standard uncertainty moves ln c1"),
    ],
};

/// Every table, in the guide's order.
pub const TABLES: [Table; 31] = [
    PULSE,
    HISTORY,
    IMPACTS,
    ENSEMBLE,
    SWEEP,
    SWEEP_ENSEMBLE,
    SHARD_PART,
    RESPONSE,
    RESPONSE_ENSEMBLE,
    STUDY,
    BIFURCATION,
    IMPACT_MAP,
    BASINS,
    RESTITUTION_TABLE,
    ORBIT_TABLE,
    CONTINUATION,
    CONTINUATION_FAMILY,
    ORBIT_RECORD,
    CONTINUATION_RECORD,
    SPECIAL,
    LIMITS,
    CAP,
    RANGE,
    PAPER,
    DESIGN,
    DESIGN_FRONT,
    DESIGN_RECORD,
    STRUCTURE_FIT,
    DECAY_MODEL,
    DAMPER_FIT,
    INPUT_SHIFT,
];

/// The table `id`, if there is one.
pub fn table(id: &str) -> Option<&'static Table> {
    TABLES.iter().find(|t| t.id == id)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::{BTreeMap, BTreeSet};

    #[test]
    fn names_are_unique_snake_case_and_one_name_has_one_unit() {
        let mut unit_of: BTreeMap<&str, &str> = BTreeMap::new();
        for t in &TABLES {
            let names: BTreeSet<&str> = t.names().into_iter().collect();
            assert_eq!(names.len(), t.columns.len(), "{}: a name twice", t.id);
            for c in t.columns {
                assert!(
                    c.name.starts_with('{')
                        || c.name.chars().all(|ch| ch.is_ascii_lowercase() || ch.is_ascii_digit() || ch == '_'),
                    "{}",
                    c.name
                );
                assert!(!c.doc.is_empty() && !c.unit.is_empty(), "{}", c.name);
                if c.name != "truncated" {
                    let was = unit_of.insert(c.name, c.unit);
                    assert!(was.is_none_or(|u| u == c.unit), "{}: two units", c.name);
                }
            }
        }
        assert_eq!(table("sweep"), Some(&SWEEP));
        assert_eq!(table("nothing"), None);
    }

    #[test]
    fn a_sweep_cell_is_the_metrics_serde_order_after_mass_and_gap() {
        let m = crate::design::Metrics::default();
        // serde_json's map sorts its keys: read the order off the text, which keeps it.
        let text = serde_json::to_string(&m).unwrap_or_default();
        let mut keys: Vec<(usize, &str)> =
            text.split('"').skip(1).step_by(2).map(|k| (text.find(&format!("\"{k}\":")).unwrap_or(0), k)).collect();
        keys.sort_unstable();
        let keys: Vec<&str> = keys.into_iter().map(|(_, k)| k).collect();
        assert_eq!(keys, SWEEP.names()[2..].to_vec());
        assert_eq!(keys, ENSEMBLE.names()[1..].to_vec());
    }
}
