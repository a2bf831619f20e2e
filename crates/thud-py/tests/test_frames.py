"""Tables and labelled arrays: Run.impacts_frame / history_frame,
Chart.to_dataframe (tidy) and to_xarray, Ensemble and Response tables, as_dict(json=True),
reprs naming the design, _repr_html_, and a clear ImportError without pandas or xarray."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest

import thud
from conftest import REPO

pd = pytest.importorskip("pandas", reason="pandas is not installed")


@pytest.fixture(scope="module")
def run():
    return thud.simulate(preset="paper-fig9", mass="50g", gap=0.03, samples=500)


@pytest.fixture(scope="module")
def chart():
    return thud.sweep("30g:100g:4", "2cm:5cm:3", duration=0.5)


@pytest.fixture(scope="module")
def echart():
    return thud.sweep("30g:100g:2", "2cm:5cm:3", duration=0.5, ensemble=3)


def test_impacts_frame_is_every_impact_t_s_first_in_the_record_s_order(run, cli_json):
    df = run.impacts_frame()
    assert len(df) == run.n_impacts > 0
    j = cli_json("simulate", "--preset", "paper-fig9", "--mass", "50g", "--gap", "0.03")
    # The columns are the record's keys in the order the command line writes them: t_s first.
    first = list(j["impacts"][0])
    assert list(df.columns) == first == [c[0] for c in thud.schema()["impacts"]] and df.columns[0] == "t_s"
    for k in df.columns:
        np.testing.assert_array_equal(df[k].to_numpy(), run.impacts[k])
    assert [i["t_s"] for i in j["impacts"]] == df["t_s"].tolist()


def test_history_frame_is_the_time_history(run):
    df = run.history_frame()
    assert list(df.columns) == ["t_s", "x_m", "y_m", "x_free_m"] and len(df) == 500
    for k in df.columns:
        np.testing.assert_array_equal(df[k].to_numpy(), run.history[k])


def test_chart_to_dataframe_is_tidy_one_row_per_cell(chart):
    df = chart.to_dataframe()
    g, m = len(chart.gaps_m), len(chart.masses_kg)
    assert len(df) == g * m and list(df.columns) == [c[0] for c in thud.schema()["sweep"]]
    assert list(df.columns[:2]) == ["mass_kg", "gap_m"]
    assert not df.duplicated(["gap_m", "mass_kg"]).any()
    for row in df.itertuples(index=False):
        gi = int(np.flatnonzero(chart.gaps_m == row.gap_m)[0])
        mi = int(np.flatnonzero(chart.masses_kg == row.mass_kg)[0])
        for k in ("zone", "n_impacts", "spl_max_db", "inclination_cm_s", "u0_max_m_s"):
            want, got = getattr(chart, k)[gi, mi], getattr(row, k)
            assert (math.isnan(want) and math.isnan(got)) if isinstance(want, float) and math.isnan(want) \
                else got == want, (k, got, want)
    assert df.attrs["thresholds"] == chart.thresholds


def test_chart_to_dataframe_with_an_ensemble_is_one_row_per_cell_and_runs_frame_one_per_run(echart):
    df = echart.to_dataframe()
    g, m, n = len(echart.gaps_m), len(echart.masses_kg), echart.runs
    assert len(df) == g * m and list(df.columns) == [c[0] for c in thud.schema()["sweep_ensemble"]]
    for row in df.itertuples(index=False):
        gi = int(np.flatnonzero(echart.gaps_m == row.gap_m)[0])
        mi = int(np.flatnonzero(echart.masses_kg == row.mass_kg)[0])
        assert row.runs == n
        assert row.u0_max_m_s == echart.u0_max_m_s[gi, mi]
        assert row.u0_max_m_s_p90 == echart.spread["u0_max_m_s"]["p90"][gi, mi]
        assert row.zone3_probability == echart.zone3_probability[gi, mi]
    rf = echart.runs_frame()
    assert len(rf) == g * m * n and list(rf.columns[:4]) == ["run", "mass_kg", "gap_m", "ball_position_m"]
    for row in rf.itertuples(index=False):
        gi = int(np.flatnonzero(echart.gaps_m == row.gap_m)[0])
        mi = int(np.flatnonzero(echart.masses_kg == row.mass_kg)[0])
        assert row.ball_position_m == echart.ensemble["ball_position_m"][gi, mi, row.run]
        assert row.u0_max_m_s == echart.ensemble["u0_max_m_s"][gi, mi, row.run]


def test_chart_to_xarray_is_gap_by_mass_by_run(chart, echart):
    xr = pytest.importorskip("xarray", reason="xarray is not installed")
    ds = chart.to_xarray()
    assert isinstance(ds, xr.Dataset)
    assert ds["zone"].dims == ("gap_m", "mass_kg") and ds["spl_max_db"].attrs["units"] == "dB"
    np.testing.assert_array_equal(ds["gap_m"].values, chart.gaps_m)
    np.testing.assert_array_equal(ds["u0_max_m_s"].values, chart.u0_max_m_s)
    cell = ds.sel(gap_m=chart.gaps_m[1], mass_kg=chart.masses_kg[2])
    assert int(cell["zone"]) == chart.zone[1, 2]
    es = echart.to_xarray()
    assert es["run_u0_max_m_s"].dims == ("gap_m", "mass_kg", "run") and es.sizes["run"] == echart.runs
    np.testing.assert_array_equal(es["run_u0_max_m_s"].values, echart.ensemble["u0_max_m_s"])
    np.testing.assert_array_equal(es["spl_max_db_median"].values, echart.spread["spl_max_db"]["median"])


def test_ensemble_response_and_pulse_tables():
    p = thud.pulse(points=200)
    pf = p.to_dataframe()
    assert list(pf.columns) == ["t_s", "p_pa"] and len(pf) == 200 and pf.attrs["spl_db"] == p.spl_db
    np.testing.assert_array_equal(pf["p_pa"].to_numpy(), p.p_pa)
    e = thud.simulate_ensemble(4, preset="paper-fig9")
    df = e.to_dataframe()
    assert list(df.columns) == [c[0] for c in thud.schema()["ensemble"]] and len(df) == 4
    assert df.index.name == "run" and df.index.tolist() == [0, 1, 2, 3]
    np.testing.assert_array_equal(df["inclination_cm_s"].to_numpy(), e.ensemble["inclination_cm_s"])
    r = thud.response("4.6Hz:5.4Hz:3", force=1, duration=4, continuation=True)
    rf = r.to_dataframe()
    assert list(rf.columns[:2]) == ["direction", "freq_hz"] and len(rf) == 6
    assert rf["direction"].tolist() == [r.sweeps[0]["direction"]] * 3 + [r.sweeps[1]["direction"]] * 3
    np.testing.assert_array_equal(rf["amplitude_m"].to_numpy()[:3], r.sweeps[0]["amplitude_m"])
    re = thud.response("4.6Hz:5.4Hz:2", force=1, duration=4, ensemble=2).to_dataframe()
    assert [c for c in re.columns if c.startswith("amplitude_m_")] == ["amplitude_m_p10", "amplitude_m_median",
                                                                     "amplitude_m_p90"]
    assert len(re) == 2 and (re["amplitude_m_p10"] <= re["amplitude_m_p90"]).all()


def test_as_dict_json_is_standard_json_with_none_for_missing_values(chart, run):
    for obj in (chart, run, thud.pulse(points=100)):
        d = obj.as_dict(json=True)
        text = json.dumps(d, allow_nan=False)  # NaN or a NumPy type would fail here
        assert json.loads(text) == d
    d = chart.as_dict(json=True)
    spl = chart.spl_max_db
    assert [[None if math.isnan(v) else v for v in row] for row in spl.tolist()] == d["spl_max_db"]
    assert d["zone"] == chart.zone.tolist()


def test_reprs_name_the_design(run, chart):
    assert repr(run).startswith("Run(mass=0.05 kg, gap=0.03 m: ")
    assert repr(chart).startswith("Chart(4 masses 0.03–0.1 kg × 3 gaps 0.02–0.05 m, ")
    e = thud.simulate(preset="paper-fig9", mass=0.04, ensemble=3)
    assert repr(e).startswith("Ensemble(mass=0.04 kg, gap=")
    html = run._repr_html_()
    assert html.startswith("<table") and "impact_mass_kg" in html and "n_impacts" in html
    assert "Chart(" in chart._repr_html_()


def test_without_pandas_or_xarray_the_error_says_what_to_install():
    code = (
        "import sys; sys.modules['pandas'] = None; sys.modules['xarray'] = None\n"
        "import thud\n"
        "r = thud.simulate(samples=10)\n"
        "for f in (r.impacts_frame, thud.sweep([0.04], [0.04], duration=0.2).to_xarray):\n"
        "    try:\n"
        "        f()\n"
        "    except ImportError as e:\n"
        "        print(e)\n"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=REPO, timeout=60)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[0].startswith("Run.impacts_frame() needs pandas") and "pip install pandas" in lines[0]
    assert lines[1].startswith("Chart.to_xarray() needs xarray") and "pip install xarray" in lines[1]
