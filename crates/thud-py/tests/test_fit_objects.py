"""thud.fit_structure and thud.fit_damper equal ``thud fit structure|damper --json`` for the same
record (exact equality of every number), and their results convert to pandas and xarray and
pickle like every other result."""

import pickle

import numpy as np

import thud
from test_fit import decay


def record_csv(path, t, x):
    """`t_s,x_m` rows in Python's shortest round-trip form: the command line reads the very floats."""
    path.write_text("t_s,x_m\n" + "".join(f"{a!r},{b!r}\n" for a, b in zip(map(float, t), map(float, x))))
    return str(path)


def test_fit_structure_equals_thud_fit_structure(cli_json, tmp_path):
    t, x = decay()
    f = thud.fit_structure(t, x, main_mass="2kg")
    j = cli_json("fit", "structure", "--data", record_csv(tmp_path / "decay.csv", t, x), "--main-mass", "2kg")
    assert isinstance(f, thud.StructureFit) and isinstance(f, dict)
    assert f.as_dict() == j
    assert pickle.loads(pickle.dumps(f)) == f and type(pickle.loads(pickle.dumps(f))) is thud.StructureFit
    df = f.to_dataframe()
    assert len(df) == 1 and df["zeta"][0] == j["zeta"] and df["k_n_m_stderr"][0] == j["k_n_m_stderr"]
    ds = f.to_xarray()
    assert float(ds["f_n_hz"]) == j["f_n_hz"] and ds.attrs["unit"] == j["unit"]


def test_fit_damper_equals_thud_fit_damper(cli_json, tmp_path):
    run = thud.simulate(c1=60, samples=6001)
    t, x = run.history["t_s"], run.history["x_m"]
    f = thud.fit_damper(t, x, k=500)
    j = cli_json("fit", "damper", "--data", record_csv(tmp_path / "strike.csv", t, x), "--k", "500")
    assert isinstance(f, thud.DamperFit)
    assert f.as_dict() == j
    df = f.to_dataframe()
    assert list(df["measured_envelope_m"][: len(j["measured_envelope_m"])]) == j["measured_envelope_m"]
    assert list(df["model_envelope_m"][: len(j["model_envelope_m"])]) == j["model_envelope_m"]
    assert df["t_s"][1] == j["envelope_period_s"] and df.attrs["c1_n_s_m"] == j["c1_n_s_m"]
    ds = f.to_xarray()
    assert list(ds["c1_n_s_m_ci"].values) == j["c1_n_s_m_ci"] and float(ds["c1_n_s_m"]) == j["c1_n_s_m"]
    assert np.array_equal(ds["measured_envelope_m"].values[: len(j["measured_envelope_m"])],
                          np.array(j["measured_envelope_m"]))
    assert pickle.loads(pickle.dumps(f)) == f
