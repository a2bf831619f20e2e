"""Studies over any parameter and the dynamics from Python:
thud.sweep(v0=…, c1=…) is the command line's `sweep --vary` to the last bit, as an xarray
Dataset with one dimension per varied keyword; thud.bifurcation is `thud bifurcation`'s;
to_xarray on every result; bad input named by its keyword."""

import json

import numpy as np
import pytest

import thud

xr = pytest.importorskip("xarray", reason="xarray is not installed")


def test_a_study_from_python_is_the_command_line_s(cli_json):
    cli = cli_json("sweep", "--vary", "v0=1:3:5", "--vary", "c1=10:60:6")
    ds = thud.sweep(v0=np.linspace(1, 3, 5), c1=[10, 20, 30, 40, 50, 60])
    # The dimensions are the CSV's columns.
    assert ds["u0_max_m_s"].dims == ("v0_m_s", "c1_n_s_m")
    assert ds["u0_max_m_s"].shape == (5, 6)
    assert ds["v0_m_s"].attrs["units"] == "m/s" and ds["c1_n_s_m"].attrs["units"] == "N·s/m"
    assert list(ds["c1_n_s_m"].values) == [a for a in cli["axes"][1]["values"]]
    for cell in cli["cells"]:
        i, j = divmod(cell["index"], 6)
        at = ds.isel(v0_m_s=i, c1_n_s_m=j)
        assert [float(at["v0_m_s"]), float(at["c1_n_s_m"])] == cell["values"]
        assert int(at["n_impacts"]) == cell["n_impacts"]
        for key in ("u0_max_m_s", "zdot_abs_max_m_s", "spl_max_db", "inclination_cm_s", "restitution_mean"):
            want = cell[key]
            got = float(at[key])
            assert (np.isnan(got) and want is None) or got == want, (cell["index"], key, got, want)
        assert int(at["zone"]) == (cell["zone"] or 0)


def test_a_study_s_dimensions_are_the_csv_s_columns_and_the_keywords_still_select(cli):
    code, out, err = cli("sweep", "--vary", "v0=1:3:3", "--vary", "c1=10:20:2", "--csv")
    assert code == 0, err
    header = out.splitlines()[0].split(",")
    ds = thud.sweep(v0=[1, 2, 3], c1=[10, 20])
    assert list(ds["u0_max_m_s"].dims) == header[1:3]
    # The keywords are deprecated aliases, still indexed.
    assert ds["v0"].attrs["deprecated"] == "use v0_m_s"
    assert float(ds["u0_max_m_s"].sel(c1=20, v0=2)) == float(ds["u0_max_m_s"].sel(c1_n_s_m=20, v0_m_s=2))


def test_mass_by_gap_is_a_study_too():
    ds = thud.sweep(mass=[0.03, 0.05], gap=[0.02, 0.04])
    chart = thud.sweep([0.03, 0.05], [0.02, 0.04])
    # The chart's arrays are gap × mass; the study's mass × gap.
    assert np.array_equal(ds["u0_max_m_s"].values, chart.u0_max_m_s.T)


def test_bifurcation_classifies_the_forced_rattle_s_period_doubling(cli_json):
    ds = thud.bifurcation(preset="forced-rattle", freq=[7.55, 7.7], periods=40)
    assert list(ds["orbit"].values) == ["4/2", "2/1"]
    assert ds["x_m"].dims == ("point", "period") and ds["x_m"].shape == (2, 40)
    cli = cli_json("bifurcation", "--preset", "forced-rattle", "--vary", "freq=7.55:7.7:2", "--periods", "40")
    assert [p["samples"][3]["x_m"] for p in cli["points"]] == list(ds["x_m"].values[:, 3])


def test_every_result_has_to_xarray():
    run = thud.simulate(preset="paper-fig9", samples=101)
    r = run.to_xarray()
    assert r["x_m"].dims == ("t_s",) and r["t_s"].attrs["units"] == "s" and len(r["t_s"]) == 101
    e = thud.simulate(preset="paper-fig9", ensemble=4).to_xarray()
    assert e["u0_max_m_s"].dims == ("run",) and e["ball_position_m"].attrs["units"] == "m"
    p = thud.pulse().to_xarray()
    assert p["p_pa"].dims == ("t_s",) and p["p_pa"].attrs["units"] == "Pa"
    resp = thud.response([4.0, 5.0, 6.0], force=1, continuation=True).to_xarray()
    assert resp["amplitude_m"].dims == ("direction", "freq_hz")
    assert list(resp["direction"].values) == ["up", "down"]
    assert resp["amplitude_m"].attrs["units"] == "m"


def test_bad_studies_are_named_by_their_keyword():
    with pytest.raises(thud.ParameterError) as info:
        thud.sweep(v0=[1, 1e9])
    assert info.value.param == "v0"
    with pytest.raises(thud.ParameterError) as info:
        thud.sweep(solver=["event", "newmark"])
    with pytest.raises(thud.ParameterError):
        thud.bifurcation(freq=[5.0], c1=[10, 20], force=1)
    with pytest.raises(thud.ParameterError) as info:
        thud.bifurcation(freq=[5.0, 6.0])
    assert info.value.param == "force"
