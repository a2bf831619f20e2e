"""thud.fit_structure and thud.fit_damper: the command line's fits with the
same keys. A closed-form decay written here (not by thud) is recovered within 3 standard
errors; a damper record from thud.simulate is bracketed; bad data raises ParameterError."""

import math

import numpy as np
import pytest

import thud


def decay(m=2.0, k=8.0e4, c=6.0, v0=0.3, rate=3000.0, span=1.2, noise=0.01, seed=3):
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.6, 1.4, int(span * rate)) / rate)
    s = c / (2 * m)
    wd = math.sqrt(k / m - s * s)
    x = v0 / wd * np.exp(-s * t) * np.sin(wd * t)
    peak = np.abs(x).max()
    return t, x + noise * peak * rng.standard_normal(t.size) + 0.05 * peak + 0.02 * peak * t


def test_fit_structure_recovers_a_closed_form_decay():
    t, x = decay()
    f = thud.fit_structure(t, x, main_mass="2kg")
    wn = math.sqrt(8.0e4 / 2.0)
    truth = {"f_n_hz": wn / (2 * math.pi), "zeta": 6.0 / (2 * 2.0 * wn), "k_n_m": 8.0e4, "c_n_s_m": 6.0}
    for key, want in truth.items():
        assert abs(f[key] - want) <= 3 * f[key + "_stderr"], (key, f[key], f[key + "_stderr"], want)
    assert f["converged"] and f["residual_rms"] > 0


def test_fit_structure_refuses_bad_data():
    t, x = decay()
    x = x.copy()
    x[10] = float("nan")
    with pytest.raises(thud.ParameterError) as info:
        thud.fit_structure(t, x, main_mass=2.0)
    assert "finite" in str(info.value)
    with pytest.raises(thud.ParameterError):
        thud.fit_structure(t[::-1], x[::-1], main_mass=2.0)
    with pytest.raises(thud.ParameterError) as info:
        thud.fit_structure(t, decay()[1], main_mass=-1)
    assert info.value.param == "main_mass"


def test_fit_damper_brackets_the_c1_of_a_simulated_record():
    run = thud.simulate(c1=60, samples=6001)
    t, x = run.history["t_s"], run.history["x_m"]
    f = thud.fit_damper(t, x, k=500)
    low, high = f["c1_n_s_m_ci"]
    assert low <= 60 <= high and high / low <= 3
    for key in ["c1_n_s_m", "c1_n_s_m_stderr", "restitution", "restitution_stderr", "residual_rms"]:
        assert isinstance(f[key], float)
    with pytest.raises(thud.ParameterError) as info:
        thud.fit_damper(t, x, ball_position=0.001)
    assert info.value.param == "ball_position"
