"""Periodic orbits, continuation and impact maps from Python equal the command line's `thud
orbit`, `thud continue` and `thud impact-map`; `design=` loads what the command line's
`--design` loads; a varied frequency supplies the design's; an int beyond any float is refused
naming its keyword."""

import json
import pickle
from pathlib import Path

import numpy as np
import pytest

import thud

PRESETS = Path(__file__).resolve().parents[2] / "thud-presets" / "presets"


def test_orbit_equals_thud_orbit(cli_json):
    o = thud.orbit(preset="forced-rattle")
    assert o.as_dict() == cli_json("orbit", "--preset", "forced-rattle")
    assert o.label == f"{o.impacts_per_orbit}/{o.periods}"
    assert o.stable == bool(np.all(np.abs(o.multipliers) < 1))
    assert len(o.impacts["phase"]) == o.impacts_per_orbit


def test_the_unstable_symmetric_orbit_equals_thud_orbit(cli_json):
    o = thud.orbit(gap=0.02, force=2, freq=6, symmetric=True)
    j = cli_json("orbit", "--gap", "0.02", "--force-amplitude", "2", "--freq", "6", "--symmetric")
    assert o.as_dict() == j
    assert o.symmetric and not o.stable
    assert np.abs(o.multipliers).max() > 1


def test_orbit_with_a_guess_and_period_equals_thud_orbit(cli_json):
    first = thud.orbit(preset="forced-rattle")
    guess = (first.x_m, first.v_m_s, first.z_m, first.zdot_m_s)
    o = thud.orbit(preset="forced-rattle", period=first.periods, guess=guess)
    j = cli_json("orbit", "--preset", "forced-rattle", "--period", str(first.periods),
                 "--guess", ",".join(repr(g) for g in guess))
    assert o.as_dict() == j
    # Started on the orbit, Newton stays on it.
    assert o.label == first.label and abs(o.amplitude_m - first.amplitude_m) < 1e-9


def test_an_orbit_pickles_to_an_equal_orbit_and_tables():
    o = thud.orbit(preset="forced-rattle")
    back = pickle.loads(pickle.dumps(o))
    assert back == o and back is not o and back.as_dict() == o.as_dict()
    df = o.to_dataframe()
    assert list(df.columns) == ["impact", "period", "phase", "wall", "u_in_m_s", "u_out_m_s"]
    assert len(df) == o.impacts_per_orbit
    assert np.array_equal(o.to_xarray()["u_in_m_s"].values, o.impacts["u_in_m_s"])


def test_continuation_equals_thud_continue(cli, cli_json):
    ds = thud.continuation(preset="forced-rattle", freq=(5.5, 6.5))
    j = cli_json("continue", "--preset", "forced-rattle", "--vary", "f=5.5:6.5")
    points = j["points"]
    assert list(ds["freq_hz"].values) == [p["value"] for p in points]
    for k in ("amplitude_m", "multiplier_abs_max", "x_m", "v_m_s", "z_m", "zdot_m_s"):
        assert list(ds[k].values) == [p[k] for p in points], k
    assert list(ds["stable"].values) == [p["stable"] for p in points]
    assert list(ds["orbit"].values) == [p["orbit"] for p in points]
    assert list(ds["special_kind"].values) == [s["kind"] for s in j["specials"]]
    assert list(ds["special_freq_hz"].values) == [s["value"] for s in j["specials"]]
    # The coordinate is named as the CSV's first column.
    code, out, err = cli("continue", "--preset", "forced-rattle", "--vary", "f=5.5:6.5", "--csv")
    assert code == 0, err
    assert out.splitlines()[0].split(",")[0] in ds.coords


def test_impact_map_equals_thud_impact_map(cli_json):
    m = thud.impact_map(preset="forced-rattle", transient=100)
    j = cli_json("impact-map", "--preset", "forced-rattle", "--transient", "100")
    assert m.as_dict() == j
    assert list(m.impacts["u_in_m_s"]) == [i["u_in_m_s"] for i in j["impacts"]]
    assert list(m.samples["x_m"]) == [s["x_m"] for s in j["samples"]]
    assert pickle.loads(pickle.dumps(m)) == m


def test_a_varied_frequency_supplies_the_design_s(cli_json):
    ds = thud.bifurcation(freq=np.linspace(3, 8, 5), force=1)
    j = cli_json("bifurcation", "--vary", "f=3:8:5", "--force-amplitude", "1", "--freq", "3")
    assert list(ds["x_m"].values[:, 0]) == [p["samples"][0]["x_m"] for p in j["points"]]
    assert list(ds["orbit"].values) == [thud._frames._orbit_label(p["orbit"]) for p in j["points"]]


def test_design_loads_a_design_file_as_the_command_line_does(tmp_path, cli_json):
    f = tmp_path / "mine.toml"
    f.write_text((PRESETS / "paper-fig9.toml").read_text(encoding="utf-8"), encoding="utf-8")
    r = thud.simulate(design=str(f), mass="50g")
    assert r.as_dict()["design"] == thud.simulate(preset="paper-fig9", mass="50g").as_dict()["design"]
    j = cli_json("simulate", "--design", str(f), "--mass", "50g")
    assert r.inclination_cm_s == j["inclination_cm_s"] and r.design == j["design"]
    # A path object too, on every design function.
    assert thud.pulse(design=f).tau_s == thud.pulse(preset="paper-fig9").tau_s
    c = thud.sweep([0.04], [0.03], design=f)
    assert c.zone.shape == (1, 1)


def test_design_takes_a_saved_design_s_name(tmp_path, monkeypatch, cli_json, cli_env):
    data = Path(cli_env["XDG_DATA_HOME"]) / "thud" / "designs"
    data.mkdir(parents=True, exist_ok=True)
    (data / "mine.toml").write_text((PRESETS / "quiet-nylon.toml").read_text(encoding="utf-8"), encoding="utf-8")
    monkeypatch.setenv("XDG_DATA_HOME", cli_env["XDG_DATA_HOME"])
    monkeypatch.setenv("HOME", cli_env["HOME"])
    r = thud.simulate(design="mine")
    assert r.design == cli_json("simulate", "--design", "mine")["design"]
    assert r.design == thud.simulate(preset="quiet-nylon").design


def test_an_explorer_file_with_its_ensemble_size_loads(tmp_path):
    f = tmp_path / "saved.toml"
    f.write_text("ensemble = 8\n" + (PRESETS / "default.toml").read_text(encoding="utf-8"), encoding="utf-8")
    assert thud.simulate(design=f).design == thud.simulate().design


@pytest.mark.parametrize("text, says", [
    ("nonesuch = 1\n", "line 1"),
    ("[design]\nsolver = 3\n", "line 2"),
])
def test_a_bad_design_file_names_design_and_where(tmp_path, text, says):
    f = tmp_path / "bad.toml"
    f.write_text(text, encoding="utf-8")
    with pytest.raises(thud.ParameterError) as info:
        thud.simulate(design=f)
    assert info.value.param == "design"
    assert str(info.value).startswith("invalid design: ") and str(f) in str(info.value) and says in str(info.value)


@pytest.mark.parametrize("bad, says", [
    (dict(design="nonesuch"), "no file 'nonesuch' and no saved design of that name"),
    (dict(design="/nonexistent/x.toml"), "/nonexistent/x.toml"),
    (dict(design=3), "not an int"),
    (dict(design="x.toml", preset="default"), "give design or preset, not both"),
])
def test_design_refusals_name_design(bad, says):
    with pytest.raises(thud.ParameterError) as info:
        thud.simulate(**bad)
    assert info.value.param == "design" and says in str(info.value), str(info.value)


@pytest.mark.parametrize("fn", [thud.simulate, thud.pulse, thud.orbit])
def test_an_int_beyond_any_float_names_its_keyword(fn):
    for value in (10**400, -10**400):
        with pytest.raises(thud.ParameterError) as info:
            fn(main_mass=value)
        msg = str(info.value)
        assert info.value.param == "main_mass"
        assert msg.startswith("invalid main_mass: ") and "401 digits is out of range" in msg, msg
        assert "main mass M must be 0.001 to 1e6 kg" in msg and "not an int" not in msg


def test_orbit_refusals_name_their_keyword():
    with pytest.raises(thud.ParameterError) as info:
        thud.orbit(preset="forced-rattle", period=17)
    assert info.value.param == "period"
    with pytest.raises(thud.ParameterError) as info:
        thud.orbit(preset="forced-rattle", guess=(1, 2, 3))
    assert info.value.param == "guess"
    with pytest.raises(thud.ParameterError) as info:
        thud.continuation(preset="forced-rattle", freq=(5.5, 6.5), gap=[0.01, 0.02])
    assert "exactly one parameter" in str(info.value)


def test_basins_equal_thud_basins(cli, cli_json):
    b = thud.basins(3, (-0.5, 0.5), preset="forced-rattle", transient=20, periods=4)
    j = cli_json("basins", "--preset", "forced-rattle", "--grid", "3", "--w0", "-0.5:0.5", "--transient", "20",
                 "--periods", "4")
    assert b.as_dict() == j
    assert b.attractor.shape == (3, 3) and list(b.attractor.ravel()) == j["cells"]
    assert pickle.loads(pickle.dumps(b)) == b
    code, out, err = cli("basins", "--preset", "forced-rattle", "--grid", "3", "--w0", "-0.5:0.5", "--transient",
                         "20", "--periods", "4", "--csv")
    assert code == 0, err
    rows = [line.split(",") for line in out.splitlines()[1:]]
    df = b.to_dataframe()
    assert list(df.columns) == out.splitlines()[0].split(",")
    assert [float(r[0]) for r in rows] == list(df["y0_m"]) and [int(r[2]) for r in rows] == list(df["attractor"])
    assert [r[3] for r in rows] == list(df["orbit"])
    with pytest.raises(thud.ParameterError) as info:
        thud.basins(3, preset="forced-rattle", ball_velocity=0.1)
    assert info.value.param in ("grid", "ball_velocity")


def test_restitution_equals_thud_restitution(cli_json):
    r = thud.restitution("10g:20g:2", target=0.5)
    j = cli_json("restitution", "--masses", "10g:20g:2", "--target", "0.5")
    assert list(r.restitution) == [row["restitution"] for row in j["rows"]]
    assert list(r.c1_for_target_n_s_m) == [row["c1_for_target_n_s_m"] for row in j["rows"]]
    df = r.to_dataframe()
    assert list(df.columns) == [c["key"] for c in j["columns"]]
    assert list(df["mass_g"]) == [row["mass_g"] for row in j["rows"]]
    assert pickle.loads(pickle.dumps(r)) == r
    plain = thud.restitution([0.01, 0.02], u0="1.4m/s")
    assert list(plain.restitution) == list(r.restitution) and plain.c1_for_target_n_s_m is None
    with pytest.raises(thud.ParameterError) as info:
        thud.restitution(target=2)
    assert info.value.param == "target"
