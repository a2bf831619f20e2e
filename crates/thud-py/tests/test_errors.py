"""Bad input raises thud.ParameterError (a ValueError) naming the parameter, one line — the
command line's message for the same value, with the flag spelled as the keyword."""

import math
import re

import numpy as np
import pytest

import thud

FUNCTIONS = {
    "pulse": lambda **kw: thud.pulse(**kw),
    "simulate": lambda **kw: thud.simulate(**kw),
    "sweep": lambda **kw: thud.sweep("30g:40g:2", "2cm:3cm:2", **kw),
}


def raised(fn, **kw):
    with pytest.raises(thud.ParameterError) as info:
        FUNCTIONS[fn](**kw)
    e = info.value
    assert isinstance(e, ValueError)
    message = str(e)
    assert "\n" not in message and message.startswith("invalid ")
    return e, message


def keyword(line):
    """A command-line error line as Python words it: no "thud: ", flags as keywords."""
    line = line.strip()
    assert line.startswith("thud: ") and "\n" not in line, line
    # The force amplitude is `--force-amplitude` on the command line and `force` in Python (which
    # replaces no file, so `force` has one meaning there).
    flag = lambda m: "force" if m.group(1) == "force-amplitude" else m.group(1).replace("-", "_")  # noqa: E731
    return re.sub(r"--([a-z0-9-]+)", flag, line[len("thud: "):])


# Each class of bad input, by function: (keywords, the same input on the command line).
SAME_AS_CLI = [
    ("simulate", {"mass": math.nan}, ["--mass", "NaN"], "mass"),
    ("simulate", {"gap": "1e999"}, ["--gap", "1e999"], "gap"),
    ("simulate", {"main_mass": 1e308}, ["--main-mass", "1e308"], "main_mass"),
    ("simulate", {"k_hz": -5}, ["--k-hz", "-5"], "k_hz"),
    ("simulate", {"theta": 100}, ["--theta", "100"], "theta"),
    ("simulate", {"mass": "40.5furlongs"}, ["--mass", "40.5furlongs"], "mass"),
    ("simulate", {"mass": "heavy"}, ["--mass", "heavy"], "mass"),
    ("simulate", {"mass": 100, "density": 10}, ["--mass", "100", "--density", "10"], "mass"),
    ("simulate", {"r": "1cm"}, ["--r", "1cm"], "r"),
    ("simulate", {"e_star": -1}, ["--e-star", "-1"], "e_star"),
    ("simulate", {"samples": 2.5}, ["--samples", "2.5", "--csv"], "samples"),
    ("simulate", {"preset": "nope"}, ["--preset", "nope"], "preset"),
    ("sweep", {"duration": 0}, ["--duration", "0", "--masses", "30g:40g:2", "--gaps", "2cm:3cm:2"], "duration"),
    ("pulse", {"u0": -1}, ["--u0", "-1"], "u0"),
    ("pulse", {"u0": math.nan}, ["--u0", "nan"], "u0"),
    ("pulse", {"rho_c": 0.5}, ["--rho-c", "0.5"], "rho_c"),
    ("pulse", {"sphere": "tungsten-carbide", "radius": 2}, ["--sphere", "tungsten-carbide", "--radius", "2"], "radius"),
    # An unknown material names the parameter that gave it.
    ("pulse", {"sphere": "cheese"}, ["--sphere", "cheese"], "sphere"),
    ("simulate", {"sphere": "cheese"}, ["--sphere", "cheese"], "sphere"),
    ("simulate", {"plate": "cheese"}, ["--plate", "cheese"], "plate"),
    ("pulse", {"points": 1}, ["--points", "1"], "points"),
]


@pytest.mark.parametrize("fn,kw,args,param", SAME_AS_CLI, ids=[f"{c[0]}-{c[3]}-{i}" for i, c in enumerate(SAME_AS_CLI)])
def test_the_message_is_the_command_line_s(cli, fn, kw, args, param):
    e, message = raised(fn, **kw)
    code, out, err = cli(fn, *args)
    assert code == 2 and out == "", err
    assert message == keyword(err)
    assert e.param == param and f"invalid {param}: " in message


@pytest.mark.parametrize("fn", FUNCTIONS)
def test_each_class_of_bad_input_names_the_parameter(fn):
    # NaN, ±inf, out of range: the value and the range.
    for value, words in [(math.nan, "NaN is not a finite number"), (math.inf, "inf is not a finite number"),
                         (-math.inf, "-inf is not a finite number"), (1e308, "1e308 kg is out of range"),
                         (0.0, "0 kg is out of range")]:
        e, m = raised(fn, mass=value)
        assert e.param == "mass" and m.startswith(f"invalid mass: {words}") and "0.0001 to 100 kg" in m, m
    # An unknown name, with the nearest known one.
    e, m = raised(fn, mas=0.05)
    assert e.param == "mas" and m.startswith("invalid mas: unknown parameter; did you mean mass?"), m
    e, m = raised(fn, **{"main-mass": 1.0})
    assert e.param == "main-mass" and "unknown parameter" in m
    # The wrong type: what was expected and what was given.
    for value, given in [([0.05], "a list"), ({"kg": 1}, "a dict"), (1j, "a complex"), (True, "a switch")]:
        e, m = raised(fn, mass=value)
        assert e.param == "mass" and "expected a number in kg or a text with a unit, not " + given in m, m


def test_wrong_types_and_unknown_values_of_the_other_kinds():
    e, m = raised("simulate", source="monopole")
    assert e.param == "source" and m == "invalid source: unknown value 'monopole'; one of: single, dipole, quadrupole"
    e, m = raised("simulate", solver=1)
    assert e.param == "solver" and m == "invalid solver: expected one of: event, newmark, not a number"
    e, m = raised("simulate", no_tension="yes")
    assert e.param == "no_tension" and "expected on or off (a switch), not 'yes'" in m
    e, m = raised("simulate", preset=3)
    assert e.param == "preset" and m == "invalid preset: expected a name, not an int"
    e, m = raised("simulate", no_limit="yes")
    assert e.param == "no_limit" and m == "invalid no_limit: expected True or False, not a str"
    e, m = raised("simulate", samples=[3])
    assert e.param == "samples" and m == "invalid samples: expected a whole number, not a list"
    e, m = raised("pulse", gap=0.04)
    assert e.param == "gap" and "unknown parameter" in m and "(one of: mass, u0, main_mass, k_hz, sphere, plate, density, radius" in m
    # radius and density make the mass; all three given and inconsistent over-determine the ball
    e, m = raised("simulate", mass=0.04, density=1000, radius=0.01)
    assert e.param == "density" and m.startswith("invalid density: mass 0.04 kg, radius 0.01 m and density")
    assert "disagree" in m and "give two of the three" in m
    e, m = raised("simulate", dt=1e-7)
    assert e.param == "dt" and m.endswith('add solver="newmark"')


def test_sweep_axes_are_checked_like_the_command_line_s(cli):
    for spec, flag in [("30g:100g", "masses"), ("30g:1e999g:3", "masses"), ("30g:100g:0", "masses")]:
        with pytest.raises(thud.ParameterError) as info:
            thud.sweep(spec, "2cm:3cm:2")
        code, _, err = cli("sweep", "--masses", spec, "--gaps", "2cm:3cm:2")
        assert code == 2
        assert str(info.value) == keyword(err).replace("invalid masses:", "invalid masses_kg:")
        assert info.value.param == "masses_kg"
    for bad, words in [([0.03, math.nan], "NaN is not a finite number"), ([], "0 values"),
                       ([0.03, -1.0], "-1 kg is out of range"), (3.0, "expected a sequence")]:
        with pytest.raises(thud.ParameterError, match=words) as info:
            thud.sweep(bad, [0.02])
        assert info.value.param == "masses_kg"
    with pytest.raises(thud.ParameterError, match="invalid gaps_m: 1e9 m is out of range"):
        thud.sweep([0.03], [1e9])


def test_work_caps_are_checked_before_the_run():
    e, m = raised("simulate", solver="newmark", dt=1e-12)
    assert e.param == "dt" and "2e12 Newmark steps exceed the limit of 1e9; use dt ≥ 2e-9 s" in m
    assert m.endswith("or pass no_limit=True")
    e, m = raised("simulate", samples=10**8)
    assert e.param == "samples" and "1e8 history samples exceed the limit of 1e7" in m
    e, m = raised("pulse", points="1e9")
    assert e.param == "points" and "waveform points exceed the limit" in m
    with pytest.raises(thud.ParameterError, match="sweep cells exceed the limit") as info:
        thud.sweep("30g:100g:1000", "2cm:5cm:1000")
    assert info.value.param == "masses_kg"
    e, m = raised("sweep", duration=1e5)
    assert e.param == "duration" and "4e5 simulated cell-seconds exceed the limit of 2e5" in m, m
    assert "use duration ≤ 50000 s with 4 cells or fewer cells" in m, m
    # no_limit lifts a cap: 2e6 steps of 1e-12 s run (2 µs of simulated time).
    r = thud.simulate(solver="newmark", dt=1e-12, duration=2e-6, no_limit=True, samples=2)
    assert r.final_time_s == 2e-6


def test_nan_in_a_chart_marks_only_a_value_that_does_not_exist():
    c = thud.sweep("1g:200g:5", "10um:10cm:5", v0=0.01)
    # A small v0 leaves the ball free in wide gaps: no impact, so no SPLmax and no zone.
    none = c.n_impacts == 0
    assert none.any() and (~none).any()
    assert np.isnan(c.spl_max_db[none]).all() and (c.zone[none] == 0).all()
    assert np.isfinite(c.spl_max_db[~none]).all()
    zoned = c.zone > 0
    assert np.isfinite(c.inclination_cm_s[zoned]).all() and np.isfinite(c.spl_max_db[zoned]).all()
    assert np.isfinite(c.u0_max_m_s).all() and np.isfinite(c.zdot_abs_max_m_s).all()
