"""Forcing, the frequency response and ensembles through Python equal the command line's
--json bit for bit (exact equality of every float), on small cases; the forcing keywords come
from the engine's parameter table with the command line's messages."""

import numpy as np
import pytest

import thud
from test_agreement import check_chart, check_run, same
from test_errors import keyword

#: A short forced case: 3 frequencies around the Fig 9 resonance, windows of 4 periods.
FREQS = "4.6Hz:5.4Hz:3"
RESPONSE = ["--force-amplitude", "1N", "--periods", "4", "--duration", "1"]
RESPONSE_KW = dict(force="1N", periods=4, duration=1)


def compare(want, got, where):
    """A list of JSON values against a Python column: a dict of columns key by key (a key a
    record lacks, e.g. the `k` of a periodic verdict, as None), a 2-D array row by row (one list
    per row), a 1-D array or a list element by element (None as NaN or None)."""
    if isinstance(got, dict) and want and isinstance(want[0], list):
        # Lists of records per row (every run at each frequency): 2-D columns, row × item.
        for key in got:
            compare([[m.get(key) for m in w] for w in want], got[key], f"{where}.{key}")
    elif isinstance(got, dict):
        keys = set().union(*(w.keys() for w in want)) if want else set()
        assert keys == set(got), (where, keys, set(got))
        for key in got:
            compare([w.get(key) for w in want], got[key], f"{where}.{key}")
    elif np.ndim(got) == 2:
        assert len(want) == len(got), where
        for w, row in zip(want, got):
            compare(w, row, where)
    else:
        assert len(want) == len(got), where
        for a, b in zip(want, got):
            if a is None:
                assert b is None or np.isnan(b), (where, b)
            else:
                assert same(a, b.item() if hasattr(b, "item") else b), (where, a, b)


def check_response(j, r, runs):
    assert j["design"] == r.design and r.runs == runs
    for key in ("force_n", "periods", "continuation"):
        assert same(j[key], getattr(r, key)), key
    assert len(j["sweeps"]) == len(r.sweeps)
    for js, ps in zip(j["sweeps"], r.sweeps):
        assert js["direction"] == ps["direction"]
        compare(js["points"], {k: v for k, v in ps.items() if k != "direction"}, js["direction"])


def test_a_forced_simulation_equals_the_cli(cli_json):
    j = cli_json("simulate", "--v0", "0", "--force-amplitude", "1N", "--freq", "5.5Hz", "--duration", "2", "--periods", "5")
    r = thud.simulate(v0=0, force="1N", freq=5.5, duration=2, periods=5)
    assert r.steady is not None and r.steady["periods"] == 5 and r.n_impacts > 0
    check_run(j, r)
    assert j["steady"] == r.steady
    assert thud.simulate(duration=0.2).steady is None


def test_the_response_equals_the_cli(cli_json):
    j = cli_json("response", "--freqs", FREQS, *RESPONSE)
    r = thud.response(FREQS, **RESPONSE_KW)
    check_response(j, r, 1)
    s = r.sweeps[0]
    assert s["direction"] == "from_rest" and s["amplitude_m"].dtype == np.float64 and s["periodic"].dtype == bool
    # The same frequencies as numbers, and with continuation (up, then down).
    r2 = thud.response(list(np.linspace(4.6, 5.4, 3)), **RESPONSE_KW)
    assert np.array_equal(r2.sweeps[0]["amplitude_m"], s["amplitude_m"])
    j = cli_json("response", "--freqs", "4.8Hz:5.2Hz:2", *RESPONSE, "--continuation")
    r = thud.response("4.8Hz:5.2Hz:2", continuation=True, **RESPONSE_KW)
    check_response(j, r, 1)
    assert [s["direction"] for s in r.sweeps] == ["up", "down"]


def test_a_response_without_frequencies_runs_the_engine_s_band_as_the_cli(cli_json):
    # No freqs_hz is the command line's no --freqs: 101 points from 0.6 to
    # 1.6 × the damped natural frequency √(K/M − (C/2M)²)/2π of Table 2 (K 500, M 0.5, C 0.05).
    j = cli_json("response", "--force-amplitude", "1N", "--periods", "1", "--duration", "0.2")
    r = thud.response(force="1N", periods=1, duration=0.2)
    check_response(j, r, 1)
    f_n = np.sqrt(500.0 / 0.5 - (0.05 / (2 * 0.5)) ** 2) / (2 * np.pi)
    f = r.sweeps[0]["freq_hz"]
    assert len(f) == 101 and abs(f[0] - 0.6 * f_n) < 1e-9 and abs(f[-1] - 1.6 * f_n) < 1e-9
    assert np.array_equal(thud.response(None, force="1N", periods=1, duration=0.2).sweeps[0]["freq_hz"], f)


def test_a_response_ensemble_equals_the_cli(cli_json):
    j = cli_json("response", "--freqs", FREQS, *RESPONSE, "--ensemble", "3")
    r = thud.response(FREQS, ensemble=3, **RESPONSE_KW)
    check_response(j, r, 3)
    s = r.sweeps[0]
    assert s["ensemble"]["amplitude_m"].shape == (3, 3)
    assert np.array_equal(s["spread"]["amplitude_m"]["median"], np.median(s["ensemble"]["amplitude_m"], axis=1))


def test_a_simulate_ensemble_equals_the_cli(cli_json):
    j = cli_json("simulate", "--preset", "paper-fig9", "--duration", "0.6", "--ensemble", "4")
    e = thud.simulate(preset="paper-fig9", duration=0.6, ensemble=4)
    assert isinstance(e, thud.Ensemble) and e.runs == 4
    for key in ("ball_radius_m", "runs", "zone", "zone3_probability", "agreement", "truncated", "truncation_reason"):
        assert same(j[key], getattr(e, key)), key
    assert j["design"] == e.design and j["spread"] == e.spread
    for key, column in e.ensemble.items():
        want = [m[key] for m in j["ensemble"]]
        if key == "zone":
            assert column.dtype == np.int8 and list(column) == [z or 0 for z in want]
        else:
            assert same(want, column), key
    # Each run is the single run from its offset; one run is a plain Run.
    d = e.design["damper"]["gap_m"]
    for k, y0 in enumerate(e.ensemble["ball_position_m"]):
        assert y0 == -d / 2 + (k + 0.5) * d / 4
        alone = thud.simulate(preset="paper-fig9", duration=0.6, ball_position=float(y0), samples=2)
        assert same(alone.inclination_cm_s, float(e.ensemble["inclination_cm_s"][k]))
    assert isinstance(thud.simulate(duration=0.2, ensemble=1), thud.Run)


def test_a_sweep_of_ensembles_equals_the_cli(cli_json):
    grid = ["--masses", "30g:100g:3", "--gaps", "1cm:3cm:2", "--duration", "0.5", "--l-star", "105", "--e-star", "0.5"]
    j = cli_json("sweep", *grid, "--ensemble", "3")
    c = thud.sweep("30g:100g:3", "1cm:3cm:2", duration=0.5, l_star=105, e_star=0.5, ensemble=3)
    check_chart(j, c)
    assert c.runs == 3 and c.ensemble["zone"].shape == (2, 3, 3)
    n_m = 3
    for i, cell in enumerate(j["chart"]["cells"]):
        g, m = divmod(i, n_m)
        assert same(cell["zone3_probability"], float(c.zone3_probability[g, m]))
        assert same(cell["agreement"], float(c.agreement[g, m]))
        for metric, pct in cell["spread"].items():
            for name, want in pct.items():
                got = c.spread[metric][name][g, m]
                assert np.isnan(got) if want is None else same(want, float(got)), (metric, name)
        for k, run in enumerate(cell["ensemble"]):
            assert same(run["ball_position_m"], float(c.ensemble["ball_position_m"][g, m, k]))
            assert (run["zone"] or 0) == c.ensemble["zone"][g, m, k]
    plain = thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.2)
    assert plain.runs == 1 and plain.zone3_probability is None and plain.ensemble is None


# The command line's message for the same input, the flags spelled as keywords.
SAME_AS_CLI = [
    ("simulate", {"force": 1}, ["--force-amplitude", "1"]),
    ("simulate", {"force": -1, "freq": 5}, ["--force-amplitude", "-1", "--freq", "5"]),
    ("simulate", {"freq": "1e9Hz"}, ["--freq", "1e9Hz"]),
    ("simulate", {"ball_position": "2.5cm"}, ["--ball-position", "2.5cm"]),
    ("simulate", {"ball_velocity": float("nan")}, ["--ball-velocity", "NaN"]),
    ("simulate", {"periods": 2.5}, ["--periods", "2.5"]),
    ("simulate", {"periods": 0}, ["--periods", "0"]),
    ("simulate", {"ensemble": 3, "ball_position": 0.01}, ["--ensemble", "3", "--ball-position", "0.01"]),
]


@pytest.mark.parametrize("fn,kw,args", SAME_AS_CLI, ids=[str(i) for i in range(len(SAME_AS_CLI))])
def test_forcing_messages_are_the_command_line_s(cli, fn, kw, args):
    with pytest.raises(thud.ParameterError) as info:
        getattr(thud, fn)(**kw)
    code, out, err = cli(fn, *args)
    assert code == 2 and out == "", err
    assert str(info.value) == keyword(err)


def test_response_refusals_name_the_keyword():
    for kw, param in [(dict(), "force"), (dict(force=1, freq=5), "freq"), (dict(force=1, ensemble=2, ball_position=0), "ball_position"),
                      (dict(force=1, settle="yes"), "settle"), (dict(force=1, ensemble=0), "ensemble")]:
        with pytest.raises(thud.ParameterError) as info:
            thud.response([5.0], **kw)
        assert info.value.param == param and str(info.value).startswith(f"invalid {param}: "), str(info.value)
    # force_amplitude, the command line's other name, is the same parameter.
    a = thud.response([5.0], force_amplitude=1, periods=2, duration=0.5)
    b = thud.response([5.0], force=1, periods=2, duration=0.5)
    assert np.array_equal(a.sweeps[0]["amplitude_m"], b.sweeps[0]["amplitude_m"])
