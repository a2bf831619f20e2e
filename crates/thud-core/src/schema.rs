// Over 800 lines: the one schema is data, a table of columns per file kind, read together.
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
/// (`"1"` for a pure number, `"—"` for text, a flag, an object or a list) and what it is; a
/// JSON key whose value is an object (or a list of objects) names the table of that object's
/// keys in `keys`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Column {
    pub name: &'static str,
    pub unit: &'static str,
    pub doc: &'static str,
    /// The id of the table of the value's keys (of each entry's, for a list), if it has keys.
    pub keys: Option<&'static str>,
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
    Column { name, unit, doc, keys: None }
}

/// A JSON key whose value (an object, or a list of objects) has the keys of the table `keys`.
const fn nest(name: &'static str, doc: &'static str, keys: &'static str) -> Column {
    Column { name, unit: "—", doc, keys: Some(keys) }
}

/// A metric's percentiles (the `percentiles` table), in the metric's unit `unit`.
const fn percentiles(name: &'static str, unit: &'static str, doc: &'static str) -> Column {
    Column { name, unit, doc, keys: Some("percentiles") }
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
const DESIGN_KEY: Column =
    nest("design", "the design as run: the keys of a saved design (the design_file table)", "design_file");
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
        nest("impacts", "the orbit's impacts (the map_impact table: the orbit table's impact columns)", "map_impact"),
        nest("multipliers", "the Floquet multipliers, largest modulus first (the multiplier table)", "multiplier"),
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
        nest("specials", "the special points of the branch (the special table)", "special"),
        col("ended", "—", "why the branch ended before the range's end (null when it reached it)"),
        nest(
            "branches",
            "with a point count N: every branch, each with name, unit, points, specials and ended",
            "continuation_record",
        ),
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
        nest("caps", "the work caps (the cap table), lifted by --no-limit", "cap"),
        col("orbit_seed_impacts_max", "1", "most impacts of an orbit seed searched"),
        col("orbit_transient_periods_max", "1", "most forcing periods run to find an orbit's seed"),
        nest("ranges", "every parameter's range (the range table)", "range"),
        col("settle_periods_max", "1", "most forcing periods a settling run adds"),
        nest("solver_caps", "the solver's work caps (the cap table)", "cap"),
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

/// The keys of `thud paper ID --json` and `thud restitution --json`: a table, self-describing:
/// each row's keys are its `columns[].key` (in the paper's units, stated in the key: `mass_g`,
/// `gap_cm`; restitution's rows are the `restitution` table).
pub const PAPER: Table = Table {
    id: "paper",
    written_by: "paper ID --json, restitution --json",
    columns: &[
        nest("columns", "the table's columns (the paper_column table): the keys of its rows", "paper_column"),
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
        nest("front", "the front's designs (the design_front table)", "design_front"),
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
        nest("model", "the fitted free decay (the decay_model table)", "decay_model"),
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
        nest(
            "inputs",
            "the given inputs' uncertainties carried into the interval (the input_shift table)",
            "input_shift",
        ),
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

// The other JSON documents, key by key: a key whose value has keys of its own names their table.
const METRICS_KEY: Column = nest("metrics", "the cell's metrics (the metrics table)", "metrics");
const SPREAD_KEY: Column = nest("spread", "per metric its percentiles over the runs (the spread table)", "spread");
const SETTINGS_KEY: Column = nest("settings", "the forced run's periods (the settings table)", "settings");
const ORBIT_VERDICT: Column =
    nest("orbit", "the verdict on the motion, as an object (the verdict table; its label in the CSV)", "verdict");
const SAMPLES_KEY: Column = nest("samples", "the samples x(kT), one a forcing period (the sample table)", "sample");
const MAP_IMPACTS_KEY: Column = nest("impacts", "the impacts after the transient (the map_impact table)", "map_impact");
const TRUNCATED_FLAG: Column = col("truncated", "—", "true when a work cap stopped the run before its end");
const TRUNCATION_REASON: Column =
    col("truncation_reason", "—", "the solver work cap that stopped the run, in words (null when none did)");
const BALL_RADIUS_M: Column = col("ball_radius_m", "m", "ball radius a (from its mass and density)");
const RUNS_KEY: Column = col("runs", "1", "runs N of an ensemble");

/// A saved design (TOML; `design --save`, `fit … --save`, `simulate --save`) and the `design`
/// of every JSON record.
pub const DESIGN_FILE_TABLE: Table = Table {
    id: "design_file",
    written_by: "--save FILE, the design of every --json",
    columns: &[
        nest("damper", "the structure, the damper and the run (the damper table)", "damper"),
        nest("ball", "the ball's size: its density or its radius (the ball table)", "ball"),
        nest("materials", "the ball's and the main mass's materials (the materials table; null without)", "materials"),
        nest("observer", "where the sound is heard (the observer table)", "observer"),
        nest("radiation", "how the sound is made (the radiation table)", "radiation"),
        col("solver", "—", "the solver: event or newmark"),
        col("u0max_rule", "—", "how U0max is read: impacts (the largest contact speed) or the paper's rule"),
        nest("thresholds", "the design chart's zone thresholds (the thresholds table)", "thresholds"),
        col("model", "—", "the model the design is heard through: physical (written only when not the paper's)"),
        nest(
            "atmosphere",
            "the physical model's air (the atmosphere table; written only when not room air)",
            "atmosphere",
        ),
    ],
};

/// A design's `damper`.
pub const DAMPER: Table = Table {
    id: "damper",
    written_by: "a design's damper",
    columns: &[
        col("main_mass_kg", "kg", "the main mass M given"),
        col("stiffness_n_m", "N/m", "spring stiffness K"),
        col("damping_n_s_m", "N·s/m", "viscous damping C"),
        col("impact_mass_kg", "kg", "impact (ball) mass m"),
        GAP_M,
        col("k_hz_n_m1_5", "N/m^1.5", "Hertz stiffness K_HZ"),
        col("c1_n_s_m", "N·s/m", "contact damping c1"),
        col("no_tension", "—", "true: the contact force is clamped at ≥ 0"),
        col("v0_m_s", "m/s", "initial velocity v0 of the main mass"),
        col("duration_s", "s", "simulated time"),
        col("force_n", "N", "amplitude F0 of the harmonic force (written only when forced)"),
        FREQ_HZ,
        col("ball_position_m", "m", "initial offset y0 of the ball of one run"),
        col("ball_velocity_m_s", "m/s", "the ball's initial velocity w0 (written only when not 0)"),
        col("steady_periods", "1", "forcing periods of each steady-state window (written only when not 10)"),
        col("settle", "—", "true: a forced run goes on until its amplitude settles (written only when true)"),
    ],
};

/// A design's `ball`: one of the two keys.
pub const BALL: Table = Table {
    id: "ball",
    written_by: "a design's ball",
    columns: &[
        col("density_kg_m3", "kg/m³", "the ball's density: its radius follows from its mass"),
        col("radius_m", "m", "sphere radius a (a fixed radius, whatever the mass)"),
    ],
};

/// A design's `materials`.
pub const MATERIALS: Table = Table {
    id: "materials",
    written_by: "a design's materials",
    columns: &[
        col("sphere", "—", "the ball's material"),
        col("plate", "—", "the main mass's material"),
        col("sphere_nu", "1", "the ball's Poisson ratio, when not its material's"),
    ],
};

/// A design's `observer`.
pub const OBSERVER: Table = Table {
    id: "observer",
    written_by: "a design's observer",
    columns: &[col("r_m", "m", "observer distance r"), col("theta_deg", "deg", "observer angle θ")],
};

/// A design's `radiation`.
pub const RADIATION: Table = Table {
    id: "radiation",
    written_by: "a design's radiation",
    columns: &[
        col("source", "—", "the source: single, dipole or quadrupole"),
        col("quad_signs", "—", "the quadrupole's signs: paper or rigid"),
        nest("air", "the paper model's air (the air table)", "air"),
        col("pulse", "—", "the acceleration pulse: half-sine or hertz"),
    ],
};

/// A design's `radiation.air`.
pub const AIR: Table = Table {
    id: "air",
    written_by: "a design's radiation.air",
    columns: &[col("rho_c_pa_s_m", "Pa·s/m", "air impedance ρ0·c"), col("c_m_s", "m/s", "speed of sound c")],
};

/// A design's (and a chart's) `thresholds`.
pub const THRESHOLDS: Table = Table {
    id: "thresholds",
    written_by: "a design's thresholds, sweep --json chart.thresholds",
    columns: &[
        col("spl_db", "dB", "the SPLmax between noisy and quiet"),
        col("inclination_cm_s", "cm/s", "the damping inclination e between weak and strong"),
        col("zone_by", "—", "how a zone is read: paper or the robust inclination"),
    ],
};

/// A design's `atmosphere`.
pub const ATMOSPHERE: Table = Table {
    id: "atmosphere",
    written_by: "a design's atmosphere",
    columns: &[
        col("temperature_c", "°C", "air temperature (the physical model)"),
        col("pressure_pa", "Pa", "air pressure (the physical model)"),
    ],
};

/// The keys of `thud pulse --json`.
pub const PULSE_RECORD: Table = Table {
    id: "pulse_record",
    written_by: "pulse --json",
    columns: &[
        col("radius_m", "m", "sphere radius a"),
        col("mass_kg", "kg", "impact (ball) mass m"),
        col("u0_m_s", "m/s", "impact speed U0"),
        col("k_hz_n_m1_5", "N/m^1.5", "Hertz stiffness K_HZ"),
        col("r_m", "m", "observer distance r"),
        col("theta_deg", "deg", "observer angle θ"),
        col("source", "—", "the source: single, dipole or quadrupole"),
        col("quad_signs", "—", "the quadrupole's signs: paper or rigid"),
        col("pulse", "—", "the acceleration pulse: half-sine or hertz"),
        col("rho_c_pa_s_m", "Pa·s/m", "air impedance ρ0·c"),
        col("c_m_s", "m/s", "speed of sound c"),
        col("alpha_max_m", "m", "peak approach α_max"),
        col("accel_max_m_s2", "m/s²", "peak acceleration A_max"),
        col("tau_s", "s", "contact duration τ"),
        col("force_max_n", "N", "peak contact force"),
        col("arrival_s", "s", "arrival of the direct wave after the contact starts"),
        col("spl_db", "dB", "SPL, as spl_definition says"),
        col("spl_definition", "—", "how spl_db is defined, in words"),
        col("spl_peak_db", "dB", "peak level"),
        col("sel_db", "dB", "sound exposure level"),
        col("p_rms_pa", "Pa", "rms pressure over the SPL window"),
        col("p_max_pa", "Pa", "largest pressure"),
        col("p_min_pa", "Pa", "smallest pressure"),
        nest("extrema", "the waveform's local extrema after the direct arrival (the pulse table)", "pulse"),
        nest("waveform", "the waveform: the pulse table's columns, each a list", "pulse"),
        col("model", "—", "the model the design is heard through: physical (written only when not the paper's)"),
    ],
};

/// The metrics of a run (design::Metrics): a sweep cell's `metrics`.
pub const METRICS_TABLE: Table =
    Table { id: "metrics", written_by: "sweep --json chart.cells[].metrics", columns: &METRICS };

/// The keys of `thud simulate --json`.
pub const RUN_RECORD: Table = Table {
    id: "run_record",
    written_by: "simulate --json",
    columns: &join::<18>(&[
        &[DESIGN_KEY, BALL_RADIUS_M],
        &METRICS,
        &[
            nest("impacts", "every impact (the impacts table)", "impacts"),
            nest("maxima", "the main mass's cycle maxima (the maximum table)", "maximum"),
            nest("energy", "the energy ledger (the energy table)", "energy"),
            FINAL_TIME_S,
            TRUNCATED_FLAG,
            TRUNCATION_REASON,
            nest("steady", "with a force: the steady state (the steady table; absent without)", "steady"),
        ],
    ]),
};

/// A cycle maximum of the main mass: `simulate --json` `maxima[]`.
pub const MAXIMUM: Table = Table { id: "maximum", written_by: "simulate --json maxima[]", columns: &[T_S, X_M] };

/// The energy ledger of a run: `simulate --json` `energy`.
pub const ENERGY: Table = Table {
    id: "energy",
    written_by: "simulate --json energy",
    columns: &[
        col("initial_j", "J", "the initial mechanical energy"),
        col("final_mechanical_j", "J", "the mechanical energy at the end"),
        col("dissipated_viscous_j", "J", "energy dissipated by the viscous damper C"),
        col("dissipated_contact_j", "J", "energy dissipated in the contacts"),
        col("forcing_work_j", "J", "work done by the harmonic force (only when forced)"),
    ],
};

/// The steady state of a forced run: `simulate --json` `steady`.
pub const STEADY: Table = Table {
    id: "steady",
    written_by: "simulate --force-amplitude F --json steady",
    columns: &[
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
        nest("verdict", "the verdict on the motion, as an object (the verdict table; its label in the CSV)", "verdict"),
    ],
};

/// A verdict on a forced motion as an object: its `kind` and that kind's own keys.
pub const VERDICT_TABLE: Table = Table {
    id: "verdict",
    written_by: "a response point's verdict, a map's orbit (--json)",
    columns: &[
        col("kind", "—", "periodic, settled, chaotic, not_settled or truncated"),
        col("impacts", "1", "periodic: impacts in each period"),
        col("periods", "1", "periodic: the period in forcing periods"),
        col("symmetric", "—", "x(t + T/2) = −x(t)"),
        col("source", "—", "periodic: exact when solved for as an orbit (absent: read off samples)"),
        col("k", "1", "chaotic or not_settled: the 0–1 test's K (null when not run)"),
        col("cap", "—", "truncated: the work cap that stopped the run (absent: cancelled)"),
    ],
};

/// The keys of `thud simulate --ensemble N --json`.
pub const ENSEMBLE_RECORD: Table = Table {
    id: "ensemble_record",
    written_by: "simulate --ensemble N --json",
    columns: &[
        DESIGN_KEY,
        BALL_RADIUS_M,
        RUNS_KEY,
        col("zone", "1–4", "design-chart zone (empty when there is none)"),
        ZONE3_PROBABILITY,
        AGREEMENT,
        SPREAD_KEY,
        nest("ensemble", "every run (the ensemble table; truncated, the cap, when one stopped it)", "ensemble"),
        TRUNCATED_FLAG,
        TRUNCATION_REASON,
    ],
};

/// The percentiles over an ensemble's runs of each metric: `spread`.
pub const SPREAD: Table = Table {
    id: "spread",
    written_by: "simulate --ensemble N --json spread, a sweep cell's spread",
    columns: &[
        percentiles("inclination_cm_s", "cm/s", "damping inclination e's percentiles (the percentiles table)"),
        percentiles("inclination_fit_cm_s", "cm/s", "the robust inclination's percentiles (the percentiles table)"),
        percentiles("u0_max_m_s", "m/s", "U0max's percentiles (the percentiles table)"),
        percentiles("spl_max_db", "dB", "SPLmax's percentiles (the percentiles table)"),
    ],
};

/// Three percentiles of a metric over an ensemble's runs, in the metric's unit.
pub const PERCENTILES: Table = Table {
    id: "percentiles",
    written_by: "a spread's metric",
    columns: &[
        col("p10", "unit", "10th percentile over the runs, in the metric's unit"),
        col("median", "unit", "median over the runs, in the metric's unit"),
        col("p90", "unit", "90th percentile over the runs, in the metric's unit"),
    ],
};

/// The keys of `thud sweep --json` (and `merge --json`).
pub const SWEEP_RECORD: Table = Table {
    id: "sweep_record",
    written_by: "sweep --json, sweep --ensemble N --json, merge --json",
    columns: &[
        DESIGN_KEY,
        nest("chart", "the design chart (the chart table)", "chart"),
        nest("table5", "Table 5 of the chart: its bands of e (the table5 table)", "table5"),
    ],
};

/// A design chart: `sweep --json` `chart`.
pub const CHART: Table = Table {
    id: "chart",
    written_by: "sweep --json chart",
    columns: &[
        col("masses_kg", "kg", "the chart's impact masses"),
        col("gaps_m", "m", "the chart's clearances"),
        RUNS_KEY,
        nest(
            "cells",
            "the cells, gap outer (the chart_cell table; flattened: the sweep or sweep_ensemble table)",
            "chart_cell",
        ),
        nest("thresholds", "the zone thresholds (the thresholds table)", "thresholds"),
    ],
};

/// A cell of a design chart: `sweep --json` `chart.cells[]` (`runs` onwards: of ensembles).
pub const CHART_CELL: Table = Table {
    id: "chart_cell",
    written_by: "sweep --json chart.cells[]",
    columns: &[
        MASS_KG,
        GAP_M,
        RUNS_KEY,
        METRICS_KEY,
        SPREAD_KEY,
        ZONE3_PROBABILITY,
        AGREEMENT,
        nest("ensemble", "every run (the ensemble table; truncated, the cap, when one stopped it)", "ensemble"),
    ],
};

/// A band of Table 5: `sweep --json` `table5[]`.
pub const TABLE5: Table = Table {
    id: "table5",
    written_by: "sweep --json table5[]",
    columns: &[
        col("e_lo_cm_s", "cm/s", "a band of e (Table 5): its lower end"),
        col("e_hi_cm_s", "cm/s", "a band of e (Table 5): its upper end"),
        col("count", "1", "designs in the band"),
        col("spl_min_db", "dB", "smallest SPLmax in the band"),
        SPL_MAX_DB,
    ],
};

/// The keys of `thud response --json` (`runs` only with `--ensemble N`).
pub const RESPONSE_RECORD: Table = Table {
    id: "response_record",
    written_by: "response --json, response --ensemble N --json",
    columns: &[
        DESIGN_KEY,
        col("force_n", "N", "amplitude F0 of the harmonic force (written only when forced)"),
        col("periods", "1", "forcing periods N of each steady-state window"),
        col("continuation", "—", "true when each frequency started from the previous one's final state"),
        RUNS_KEY,
        nest("sweeps", "the sweeps (the response_sweep table)", "response_sweep"),
    ],
};

/// A sweep of a response: `response --json` `sweeps[]`.
pub const RESPONSE_SWEEP: Table = Table {
    id: "response_sweep",
    written_by: "response --json sweeps[]",
    columns: &[
        DIRECTION,
        nest(
            "points",
            "one per frequency (the response_point table; flattened: response or response_ensemble)",
            "response_point",
        ),
    ],
};

/// A point of a response: `response --json` `sweeps[].points[]`; of a response of ensembles,
/// `freq_hz`, `amplitude_linear_m`, `spread`, the fractions, `truncated` and `ensemble`.
pub const RESPONSE_POINT: Table = Table {
    id: "response_point",
    written_by: "response --json sweeps[].points[]",
    columns: &[
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
        nest("verdict", "the verdict on the motion, as an object (the verdict table; its label in the CSV)", "verdict"),
        FINAL_TIME_S,
        nest("spread", "per quantity its percentiles over the runs (the response_spread table)", "response_spread"),
        PERIODIC_FRACTION,
        SETTLED_FRACTION,
        nest("ensemble", "every run (the response_run table)", "response_run"),
    ],
};

/// The percentiles of a response point of ensembles: `spread`.
pub const RESPONSE_SPREAD: Table = Table {
    id: "response_spread",
    written_by: "response --ensemble N --json sweeps[].points[].spread",
    columns: &[
        percentiles("amplitude_m", "m", "the amplitude's percentiles (the percentiles table)"),
        percentiles("reduction_db", "dB", "the reduction's, at the amplitude's percentiles (the percentiles table)"),
        percentiles("impacts_per_period", "1", "the impacts per period's percentiles (the percentiles table)"),
        percentiles("leq_db", "dB", "Leq's percentiles (the percentiles table)"),
    ],
};

/// A run of a response point of ensembles: `ensemble[]`.
pub const RESPONSE_RUN: Table = Table {
    id: "response_run",
    written_by: "response --ensemble N --json sweeps[].points[].ensemble[]",
    columns: &[
        BALL_POSITION_M,
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
        nest("verdict", "the verdict on the motion, as an object (the verdict table; its label in the CSV)", "verdict"),
        FINAL_TIME_S,
    ],
};

/// The keys of `thud sweep --vary … --json`.
pub const STUDY_RECORD: Table = Table {
    id: "study_record",
    written_by: "sweep --vary --json",
    columns: &[
        DESIGN_KEY,
        nest("axes", "the varied parameters, in order (the axis table)", "axis"),
        nest("cells", "the cells (the study_cell table)", "study_cell"),
    ],
};

/// A varied parameter: `sweep --vary --json` `axes[]`, `bifurcation --json` `axis`.
pub const AXIS: Table = Table {
    id: "axis",
    written_by: "sweep --vary --json axes[], bifurcation --json axis",
    columns: &[
        col("name", "—", "the varied parameter's name (freq, gap, …)"),
        col("unit", "—", "the varied parameter's unit (Hz, m, …; empty for a plain number)"),
        col("values", "—", "the parameter's values, in unit"),
    ],
};

/// A cell of a study: `sweep --vary --json` `cells[]`; its `values` are the `{varied}`
/// columns of the CSV, in the axes' order.
pub const STUDY_CELL: Table = Table {
    id: "study_cell",
    written_by: "sweep --vary --json cells[]",
    columns: &join::<12>(&[
        &[STUDY_INDEX, col("values", "—", "the cell's value of each varied parameter, in the axes' order and units")],
        &METRICS,
        &[nest("steady", "with a force: the steady state (the steady table; absent without)", "steady")],
    ]),
};

/// The periods of a forced map: `settings`.
pub const SETTINGS: Table = Table {
    id: "settings",
    written_by: "bifurcation, impact-map, basins --json settings",
    columns: &[
        col("transient_periods", "1", "forcing periods run before the samples (the transient)"),
        col("periods", "1", "forcing periods sampled after the transient"),
    ],
};

/// A sample x(kT) of a forced map.
pub const SAMPLE: Table = Table {
    id: "sample",
    written_by: "bifurcation, impact-map --json samples[]",
    columns: &[PERIOD, X_M, V_M_S, Z_M, ZDOT_M_S],
};

/// An impact of a forced map or orbit.
pub const MAP_IMPACT: Table = Table {
    id: "map_impact",
    written_by: "bifurcation, impact-map, orbit --json impacts[]",
    columns: &[PERIOD, PHASE, WALL, U_IN_M_S, U_OUT_M_S],
};

/// The keys of `thud bifurcation --json`.
pub const BIFURCATION_RECORD: Table = Table {
    id: "bifurcation_record",
    written_by: "bifurcation --json",
    columns: &[
        DESIGN_KEY,
        nest("axis", "the varied parameter (the axis table)", "axis"),
        SETTINGS_KEY,
        nest("points", "one per value and direction (the bifurcation_point table)", "bifurcation_point"),
        nest("bands", "the runs of values of one orbit type (the band table)", "band"),
    ],
};

/// A value of a bifurcation diagram: `bifurcation --json` `points[]`.
pub const BIFURCATION_POINT: Table = Table {
    id: "bifurcation_point",
    written_by: "bifurcation --json points[]",
    columns: &[VALUE, DIRECTION, ORBIT_VERDICT, ORBIT_AMPLITUDE_M, SAMPLES_KEY, MAP_IMPACTS_KEY, TRUNCATED_FLAG],
};

/// A band of one orbit type in a bifurcation diagram: `bifurcation --json` `bands[]`.
pub const BAND: Table = Table {
    id: "band",
    written_by: "bifurcation --json bands[]",
    columns: &[
        DIRECTION,
        col("from", "—", "the band's first value, in the axis's unit"),
        col("to", "—", "the band's last value, in the axis's unit"),
        col("values", "1", "how many values the band holds"),
        col("orbit", "—", "the orbit's type: m/n (impacts per forcing periods), sym, chaotic, not settled"),
    ],
};

/// The keys of `thud impact-map --json`.
pub const IMPACT_MAP_RECORD: Table = Table {
    id: "impact_map_record",
    written_by: "impact-map --json",
    columns: &[
        DESIGN_KEY,
        SETTINGS_KEY,
        ORBIT_VERDICT,
        ORBIT_AMPLITUDE_M,
        SAMPLES_KEY,
        MAP_IMPACTS_KEY,
        TRUNCATED_FLAG,
    ],
};

/// The keys of `thud basins --json`.
pub const BASINS_RECORD: Table = Table {
    id: "basins_record",
    written_by: "basins --json",
    columns: &[
        DESIGN_KEY,
        SETTINGS_KEY,
        col("y0_m", "m", "the ball's start offsets from the enclosure's centre (the grid's rows)"),
        col("w0_m_s", "m/s", "the ball's start velocities (the grid's columns)"),
        col("cells", "—", "per start (y0 outer) the id of the attractor it settles on"),
        col("amplitudes_m", "m", "per start (y0 outer) the steady amplitude of the main mass"),
        nest("attractors", "the attractors found (the attractor table)", "attractor"),
    ],
};

/// An attractor of a basins map: `basins --json` `attractors[]`.
pub const ATTRACTOR: Table = Table {
    id: "attractor",
    written_by: "basins --json attractors[]",
    columns: &[
        col("id", "—", "the attractor's number (as cells name it)"),
        ORBIT_VERDICT,
        col("label", "—", "the orbit's type in words, as the CSV's orbit"),
        ORBIT_AMPLITUDE_M,
        col("starts", "1", "the starts that settle on it"),
        col("share", "1", "the fraction of the starts that settle on it"),
    ],
};

/// A Floquet multiplier: `orbit --json` `multipliers[]`.
pub const MULTIPLIER: Table = Table {
    id: "multiplier",
    written_by: "orbit --json multipliers[]",
    columns: &[
        col("re", "1", "the multiplier's real part"),
        col("im", "1", "the multiplier's imaginary part"),
        col("abs", "1", "its modulus |λ|"),
    ],
};

/// A preset: `thud presets --json` (a list of them).
pub const PRESET: Table = Table {
    id: "preset",
    written_by: "presets --json[]",
    columns: &[col("name", "—", "the preset's name (--preset NAME)"), col("description", "—", "what the preset is")],
};

/// A column of a table of `thud paper ID --json`: `columns[]`.
pub const PAPER_COLUMN: Table = Table {
    id: "paper_column",
    written_by: "paper ID --json columns[]",
    columns: &[col("key", "—", "the column's key in each row"), col("label", "—", "the column's heading, as printed")],
};

/// Every table, in the guide's order.
pub const TABLES: [Table; 74] = [
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
    DESIGN_FILE_TABLE,
    DAMPER,
    BALL,
    MATERIALS,
    OBSERVER,
    RADIATION,
    AIR,
    THRESHOLDS,
    ATMOSPHERE,
    PULSE_RECORD,
    METRICS_TABLE,
    RUN_RECORD,
    MAXIMUM,
    ENERGY,
    STEADY,
    VERDICT_TABLE,
    ENSEMBLE_RECORD,
    SPREAD,
    PERCENTILES,
    SWEEP_RECORD,
    CHART,
    CHART_CELL,
    TABLE5,
    RESPONSE_RECORD,
    RESPONSE_SWEEP,
    RESPONSE_POINT,
    RESPONSE_SPREAD,
    RESPONSE_RUN,
    STUDY_RECORD,
    AXIS,
    STUDY_CELL,
    SETTINGS,
    SAMPLE,
    MAP_IMPACT,
    BIFURCATION_RECORD,
    BIFURCATION_POINT,
    BAND,
    IMPACT_MAP_RECORD,
    BASINS_RECORD,
    ATTRACTOR,
    MULTIPLIER,
    PRESET,
    PAPER_COLUMN,
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
                // A key that is a list in one record and a count or a flag in another.
                if !["truncated", "samples", "impacts", "values"].contains(&c.name) {
                    let was = unit_of.insert(c.name, c.unit);
                    assert!(was.is_none_or(|u| u == c.unit), "{}: two units", c.name);
                }
            }
        }
        assert_eq!(table("sweep"), Some(&SWEEP));
        assert_eq!(table("nothing"), None);
    }

    #[test]
    fn every_nested_key_names_a_table_and_every_table_is_reached() {
        let ids: BTreeSet<&str> = TABLES.iter().map(|t| t.id).collect();
        assert_eq!(ids.len(), TABLES.len(), "an id twice");
        let mut reached = BTreeSet::new();
        for t in &TABLES {
            for c in t.columns {
                if let Some(k) = c.keys {
                    assert!(ids.contains(k), "{}.{}: no table `{k}`", t.id, c.name);
                    reached.insert(k);
                }
            }
        }
        // A table no key points to is a whole file or document: something writes it.
        for t in TABLES.iter().filter(|t| !reached.contains(t.id)) {
            assert!(t.written_by.contains("csv") || t.written_by.contains("json"), "{}: {}", t.id, t.written_by);
        }
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
