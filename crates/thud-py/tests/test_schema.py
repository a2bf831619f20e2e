"""One schema: Python's DataFrames have the columns of the engine's one
definition (``thud.schema()``), which are the command line's CSV headers for the same result —
pulse, simulate (history, impacts), ensemble, sweep, sweep of ensembles, shard parts, response,
response of ensembles — and every result compares equal after a pickle round trip."""

import copy
import pickle

import pytest

import thud

pd = pytest.importorskip("pandas", reason="pandas is not installed")

SCHEMA = thud.schema()
GRID = ["--masses", "30g:40g:2", "--gaps", "2cm:3cm:2"]
FORCED = ["--force-amplitude", "1N", "--freqs", "5Hz:6Hz:2", "--duration", "2"]


def names(table):
    return [c[0] for c in SCHEMA[table]]


def header(text):
    """The CSV header of a command's output (the first line not a `#` comment)."""
    return next(line for line in text.splitlines() if not line.startswith("#")).split(",")


def test_the_schema_is_every_table_with_name_unit_and_meaning():
    assert set(SCHEMA) == {"pulse", "history", "impacts", "ensemble", "sweep", "sweep_ensemble", "shard_part",
                           "response", "response_ensemble", "study", "bifurcation", "impact_map", "basins",
                           "restitution", "orbit", "continuation", "orbit_record", "continuation_record",
                           "continuation_family", "special", "limits", "cap", "range", "paper", "design",
                           "design_front", "design_record", "structure_fit", "decay_model", "damper_fit",
                           "input_shift",
                           # The JSON documents' keys, to the last level.
                           "design_file", "damper", "ball", "materials", "observer", "radiation", "air",
                           "thresholds", "atmosphere", "pulse_record", "metrics", "run_record", "maximum", "energy",
                           "steady", "verdict", "ensemble_record", "spread", "percentiles", "sweep_record", "chart",
                           "chart_cell", "table5", "response_record", "response_sweep", "response_point",
                           "response_spread", "response_run", "study_record", "axis", "study_cell", "settings",
                           "sample", "map_impact", "bifurcation_record", "bifurcation_point", "band",
                           "impact_map_record", "basins_record", "attractor", "multiplier", "preset", "paper_column"}
    for table, cols in SCHEMA.items():
        assert len({c[0] for c in cols}) == len(cols), table
        for name, unit, doc in cols:
            # `{varied}`, `{variable}`, …: a template, one column per varied parameter, variable, ….
            plain = name.startswith("{") or name == name.lower()
            assert plain and " " not in name and unit and doc, (table, name)
    assert names("sweep")[:2] == ["mass_kg", "gap_m"]
    assert names("response")[0] == "direction"


#: (table, the Python table, the command line writing the same table)
CASES = {
    "pulse": (lambda: thud.pulse(points=3).to_dataframe(), ["pulse", "--csv", "--points", "3"]),
    "history": (lambda: thud.simulate(samples=3).history_frame(), ["simulate", "--csv", "--samples", "3"]),
    "impacts": (lambda: thud.simulate(duration=0.5).impacts_frame(), None),
    "ensemble": (lambda: thud.simulate_ensemble(3, duration=0.5).to_dataframe(),
                 ["simulate", "--csv", "--ensemble", "3", "--duration", "0.5"]),
    "sweep": (lambda: thud.sweep("30g:40g:2", "2cm:3cm:2").to_dataframe(), ["sweep", "--csv", *GRID]),
    "sweep_ensemble": (lambda: thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.5, ensemble=2).to_dataframe(),
                       ["sweep", "--csv", "--ensemble", "2", "--duration", "0.5", *GRID]),
    "response": (lambda: thud.response("5Hz:6Hz:2", force=1, duration=2).to_dataframe(), ["response", "--csv", *FORCED]),
    "response_ensemble": (lambda: thud.response("5Hz:6Hz:2", force=1, duration=2, ensemble=2).to_dataframe(),
                          ["response", "--csv", "--ensemble", "2", *FORCED]),
}


@pytest.mark.parametrize("table", list(CASES))
def test_python_columns_are_the_schema_s_and_the_command_line_s(table, cli, tmp_path):
    frame, args = CASES[table]
    df = frame()
    assert list(df.columns) == names(table)
    if args is None:  # written to a file
        out = tmp_path / f"{table}.csv"
        code, _, err = cli("export", "csv", table, "--duration", "0.5", "--out", str(out))
        assert code == 0, err
        text = out.read_text()
    else:
        code, text, err = cli(*args)
        assert code == 0, err
    assert header(text) == list(df.columns), f"thud {args}: the CSV header is Python's columns"


def test_the_same_numbers_under_the_same_names(cli):
    """A DataFrame and the command line's CSV of the same sweep: equal column by column."""
    import io

    df = thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.5, ensemble=2).to_dataframe()
    code, text, err = cli("sweep", "--csv", "--ensemble", "2", "--duration", "0.5", *GRID)
    assert code == 0, err
    csv = pd.read_csv(io.StringIO(text))
    assert list(csv.columns) == list(df.columns)
    for k in df.columns:
        want = csv[k].fillna(0).to_numpy() if k == "zone" else csv[k].to_numpy()
        assert list(df[k].to_numpy()) == pytest.approx(list(want), rel=0, abs=0, nan_ok=True), k


def test_runs_frame_is_the_shard_part_but_its_place_in_the_part(cli, tmp_path):
    c = thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.5, ensemble=2)
    part = tmp_path / "part.csv"
    code, _, err = cli("sweep", "--csv", "--ensemble", "2", "--duration", "0.5", *GRID, "--shard", "0/1",
                       "--out", str(part))
    assert code == 0, err
    cols = header(part.read_text())
    assert cols == names("shard_part")
    assert list(c.runs_frame().columns) == [k for k in cols if k not in ("index", "truncated")]


RESULTS = {
    "Pulse": lambda: thud.pulse(points=100),
    "Run": lambda: thud.simulate(duration=0.5, samples=50),
    "Ensemble": lambda: thud.simulate_ensemble(3, duration=0.5),
    "Chart": lambda: thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.5),
    "ensemble Chart": lambda: thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.5, ensemble=2),
    "Response": lambda: thud.response("5Hz:6Hz:2", force=1, duration=2),
    "ensemble Response": lambda: thud.response("5Hz:6Hz:2", force=1, duration=2, ensemble=2),
}
OTHER = {
    "Pulse": lambda: thud.pulse(points=100, u0=1.5),
    "Run": lambda: thud.simulate(duration=0.5, samples=50, v0=1.5),
    "Ensemble": lambda: thud.simulate_ensemble(3, duration=0.5, v0=1.5),
    "Chart": lambda: thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.5, v0=1.5),
    "ensemble Chart": lambda: thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.5, ensemble=3),
    "Response": lambda: thud.response("5Hz:6Hz:2", force=1.5, duration=2),
    "ensemble Response": lambda: thud.response("5Hz:6Hz:2", force=1, duration=2, ensemble=3),
}


@pytest.mark.parametrize("what", list(RESULTS))
def test_a_result_equals_itself_after_a_pickle_round_trip_and_not_another(what):
    r = RESULTS[what]()
    for proto in (2, pickle.HIGHEST_PROTOCOL):
        back = pickle.loads(pickle.dumps(r, protocol=proto))
        assert back == r and not (back != r)
    assert copy.deepcopy(r) == r
    assert RESULTS[what]() == r, "the same computation twice is the same result"
    other = OTHER[what]()
    assert other != r and not (other == r)
    assert r != "a string" and r != None  # noqa: E711 — comparing with another type is False


#: (table, a command line writing it with --csv, the varied parameters' columns)
WRITERS = [
    ("study", ["sweep", "--vary", "v0=1:2:2", "--vary", "c1=10:20:2"], ["v0_m_s", "c1_n_s_m"]),
    ("bifurcation", ["bifurcation", "--preset", "forced-rattle", "--vary", "f=7.5:7.6:2", "--transient", "20",
                     "--periods", "4"], ["freq_hz"]),
    ("impact_map", ["impact-map", "--preset", "forced-rattle", "--transient", "20", "--periods", "4"], []),
    ("basins", ["basins", "--preset", "forced-rattle", "--grid", "2", "--transient", "20", "--periods", "4"], []),
    ("restitution", ["restitution", "--target", "0.8"], []),
    ("orbit", ["orbit", "--preset", "forced-rattle"], []),
    ("continuation", ["continue", "--preset", "forced-rattle", "--vary", "f=5.5:5.6"], ["freq_hz"]),
]


@pytest.mark.parametrize("table, args, varied", WRITERS, ids=[w[0] for w in WRITERS])
def test_every_csv_the_command_line_writes_has_the_schema_s_columns(cli, table, args, varied):
    code, out, err = cli(*args, "--csv")
    assert code == 0, err
    want = []
    for name in names(table):
        want += varied if name == "{varied}" else [name]
    assert header(out) == want


def test_python_s_names_are_the_csv_s_columns(cli):
    o = thud.orbit(preset="forced-rattle")
    assert list(o.to_dataframe().columns) == names("orbit")[names("orbit").index("impact"):]
    ds = thud.continuation(preset="forced-rattle", freq=(5.5, 5.6))
    assert "freq_hz" in ds.coords
    assert set(names("continuation")[1:]) - {"orbit"} <= set(ds.data_vars)
    b = thud.bifurcation(preset="forced-rattle", freq=[7.5, 7.6], transient=20, periods=4)
    assert "freq_hz" in b.coords and b["freq"].attrs["deprecated"] == "use freq_hz"


def test_a_structure_fit_has_the_schema_s_keys_in_order():
    # A free decay of M 2 kg, K 8e4 N/m, C 6 N·s/m struck at 0.3 m/s, sampled at 3 kHz.
    import math

    import numpy as np

    t = np.arange(3600) / 3000.0
    s, wd = 1.5, math.sqrt(4.0e4 - 1.5 ** 2)
    x = 0.3 / wd * np.exp(-s * t) * np.sin(wd * t) * (1 + 0.001 * np.sin(91.0 * t))
    f = thud.fit_structure(t, x, main_mass=2.0)
    assert list(f) == names("structure_fit")
    assert list(f["model"]) == names("decay_model")


def test_limits_is_the_command_line_s_limits_json(cli):
    """``thud.limits()`` is the table of ``thud limits --json``: the same keys in the same order,
    the same ranges and caps."""
    import json

    code, text, err = cli("limits", "--json")
    assert code == 0, err
    want = json.loads(text)
    have = thud.limits()
    assert list(have) == list(want)
    for key in ("ranges", "caps", "solver_caps"):
        assert [list(r) for r in have[key]] == [list(r) for r in want[key]], key
    assert have == want
    assert {r["param"] for r in have["ranges"]} >= {"mass", "gap", "main-mass"}


def test_every_paper_table_is_the_command_line_s_paper_json(cli):
    """``thud.paper(id)`` is ``thud paper ID --json`` for every id ``thud paper --list`` lists,
    and an unknown id is refused naming it."""
    import json

    code, text, err = cli("paper", "--list")
    assert code == 0, err
    listed = [line.split()[0] for line in text.splitlines() if line.split() and line.split()[0][:3] in ("tab", "fig")]
    assert thud.paper_ids() == listed
    for pid in listed:
        code, text, err = cli("paper", pid, "--json")
        assert code == 0, err
        want = json.loads(text)
        have = thud.paper(pid)
        assert list(have) == list(want), pid
        assert have == want, pid
    with pytest.raises(thud.ParameterError, match="table9"):
        thud.paper("table9")
