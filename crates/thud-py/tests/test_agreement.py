"""The same design through Python and through the command line's --json gives the same
numbers, bit for bit (exact equality of every float), on the paper's Fig 2 and Fig 9 designs."""

import math

import numpy as np
import pytest

import thud

FIGS = ["paper-fig2", "paper-fig9"]


def same(a, b):
    """Exact equality of a JSON value and a Python value: floats bit for bit (no tolerance),
    None as None, sequences element by element."""
    if a is None or b is None:
        return a is None and b is None
    if isinstance(b, np.ndarray):
        return len(a) == len(b) and np.array_equal(np.asarray(a, dtype=b.dtype), b)
    if isinstance(a, float) or isinstance(b, float):
        return float(a) == float(b) and math.copysign(1, a) == math.copysign(1, b)
    return a == b


@pytest.mark.parametrize("preset", FIGS)
def test_pulse_equals_the_cli(cli_json, preset):
    j = cli_json("pulse", "--preset", preset)
    p = thud.pulse(preset=preset)
    scalars = [k for k in j if k not in ("waveform", "extrema")]
    assert len(scalars) >= 20
    for key in scalars:
        assert same(j[key], getattr(p, key)), (key, j[key], getattr(p, key))
    assert same(j["waveform"]["t_s"], p.t_s) and same(j["waveform"]["p_pa"], p.p_pa)
    assert len(p.t_s) == 2000
    assert same([e["t_s"] for e in j["extrema"]], p.extrema["t_s"])
    assert same([e["p_pa"] for e in j["extrema"]], p.extrema["p_pa"])


def test_pulse_parameters_as_numbers_and_as_text_with_units(cli_json):
    j = cli_json("pulse", "--radius", "19.05mm", "--mass", "40.5g", "--u0", "1.4", "--theta", "30",
                 "--source", "quadrupole", "--quad-signs", "paper", "--pulse", "hertz", "--points", "500")
    p = thud.pulse(radius="19.05mm", mass="40.5g", u0=1.4, theta=30, source="quadrupole",
                   quad_signs="paper", pulse="hertz", points=500)
    for key in ("radius_m", "mass_kg", "tau_s", "spl_db", "spl_peak_db", "sel_db", "p_max_pa", "p_min_pa"):
        assert same(j[key], getattr(p, key)), key
    assert same(j["waveform"]["p_pa"], p.p_pa)
    # The Fig 2 numbers the paper prints: τ ≈ 264 µs, α_max ≈ 125.7 µm (model notes, Table 1).
    assert abs(p.tau_s - 264.3e-6) < 0.5e-6 and abs(p.alpha_max_m - 1.2571e-4) < 1e-8


def check_run(j, r):
    scalars = [k for k in j if k not in ("design", "impacts", "maxima", "energy")]
    for key in scalars:
        assert same(j[key], getattr(r, key)), (key, j[key], getattr(r, key))
    assert j["design"] == r.design
    assert len(j["impacts"]) == r.n_impacts == len(r.impacts["t_s"])
    for key in j["impacts"][0] if j["impacts"] else []:
        assert same([i[key] for i in j["impacts"]], r.impacts[key]), key
    assert r.impacts["wall"].dtype == np.int8
    assert same([m["t_s"] for m in j["maxima"]], r.maxima["t_s"])
    assert same([m["x_m"] for m in j["maxima"]], r.maxima["x_m"])
    assert j["energy"] == r.energy


@pytest.mark.parametrize("preset", FIGS)
def test_simulate_equals_the_cli(cli_json, preset):
    j = cli_json("simulate", "--preset", preset)
    r = thud.simulate(preset=preset)
    assert r.n_impacts > 10, "the Fig 9 run rattles"
    check_run(j, r)
    # The history (2001 samples by default, as --csv) does not change the run it samples.
    assert len(r.history["t_s"]) == 2001 and r.history["t_s"][-1] == r.design["damper"]["duration_s"]
    assert same(j["inclination_cm_s"], thud.simulate(preset=preset, samples=2).inclination_cm_s)


def test_simulate_with_overrides_newmark_and_materials(cli_json):
    args = ["--preset", "paper-fig9", "--mass", "50g", "--gap", "0.03", "--solver", "newmark", "--dt", "1e-6",
            "--duration", "0.5", "--sphere", "steel", "--source", "dipole", "--theta", "30", "--no-tension"]
    j = cli_json("simulate", *args)
    r = thud.simulate(preset="paper-fig9", mass="50g", gap=0.03, solver="newmark", dt=1e-6, duration=0.5,
                      sphere="steel", source="dipole", theta=30, no_tension=True)
    check_run(j, r)
    assert r.design["solver"] == {"newmark": {"dt_s": 1e-6}}
    assert r.design["materials"] == {"sphere": "steel", "plate": "steel"}


def check_chart(j, c):
    chart = j["chart"]
    assert same(chart["masses_kg"], c.masses_kg) and same(chart["gaps_m"], c.gaps_m)
    n_m = len(chart["masses_kg"])
    assert c.zone.shape == (len(chart["gaps_m"]), n_m)
    metrics = ["n_impacts", "inclination_cm_s", "inclination_fit_cm_s", "u0_max_m_s", "zdot_abs_max_m_s",
               "spl_max_db", "contact_duration_s", "restitution_mean"]
    for i, cell in enumerate(chart["cells"]):
        g, m = divmod(i, n_m)
        assert (cell["mass_kg"], cell["gap_m"]) == (c.masses_kg[m], c.gaps_m[g])
        for key in metrics:
            want = cell["metrics"][key]
            got = getattr(c, key)[g, m]
            if want is None:
                assert np.isnan(got), (key, g, m)
            else:
                assert same(want, float(got)), (key, g, m, want, got)
        zone = cell["metrics"]["zone"]
        assert c.zone[g, m] == (zone or 0)
    assert j["design"] == c.design
    assert chart["thresholds"] == c.thresholds


@pytest.mark.parametrize("preset", FIGS)
def test_sweep_equals_the_cli(cli_json, preset):
    j = cli_json("sweep", "--preset", preset, "--masses", "30g:100g:4", "--gaps", "2cm:5cm:4")
    c = thud.sweep("30g:100g:4", "2cm:5cm:4", preset=preset)
    check_chart(j, c)
    # The same grid given as numbers (the command line's axis values) gives the same chart.
    c2 = thud.sweep(list(thud.axis("masses", "30g:100g:4")), thud.axis("gaps", "2cm:5cm:4"), preset=preset)
    assert np.array_equal(c.spl_max_db, c2.spl_max_db, equal_nan=True) and np.array_equal(c.zone, c2.zone)
    t5 = c.table5()
    assert len(j["table5"]) == len(t5["count"])
    for key in ("e_lo_cm_s", "e_hi_cm_s", "count", "spl_min_db", "spl_max_db"):
        assert same([b[key] for b in j["table5"]], t5[key]), key


def test_sweep_with_overrides(cli_json):
    args = ["--preset", "paper-table3", "--masses", "20g:150g:3", "--gaps", "1cm:6cm:5", "--v0", "1.2",
            "--l-star", "100", "--e-star", "1.5"]
    j = cli_json("sweep", *args)
    c = thud.sweep("20g:150g:3", "1cm:6cm:5", preset="paper-table3", v0=1.2, l_star=100, e_star=1.5)
    check_chart(j, c)
    assert c.thresholds["spl_db"] == 100.0 and c.thresholds["inclination_cm_s"] == 1.5
