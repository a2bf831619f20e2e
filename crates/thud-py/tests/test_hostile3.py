"""Nothing lost, round 3, from Python.

1. Ctrl-C during a NumPy conversion is a KeyboardInterrupt, never a PanicException.
2. Ctrl-C with runs in worker threads stops them within about a second.
3. An int too large for any count (`10**400`) is out of range, not "not an int".
4. A forged pickle state is a ValueError naming the field, never a RuntimeError.
"""

import json
import os
import signal
import subprocess
import sys
import time

import pytest

import thud

PULSE_LOOP = """
import sys, thud
print("ready", flush=True)
try:
    while True:
        thud.pulse(points=10**7)
except KeyboardInterrupt:
    print("interrupted", flush=True)
    sys.exit(0)
"""

THREADS = """
import sys, time, thud
from concurrent.futures import ThreadPoolExecutor
def long_run(_):
    # Newmark at a small step: tens of seconds of work, stopped only by a cancel.
    return thud.simulate(preset="paper-fig9", solver="newmark", dt=1e-8, duration=40, samples=2, no_limit=True)
pool = ThreadPoolExecutor(2)
futures = [pool.submit(long_run, i) for i in range(2)]
print("ready", flush=True)
try:
    for f in futures:
        f.result()
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
"""


def start(script):
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "ready"
    return p


@pytest.mark.parametrize("delay", [0.3, 0.7, 1.0, 1.3, 1.7])
def test_ctrl_c_during_a_large_pulse_is_a_keyboard_interrupt(delay):
    p = start(PULSE_LOOP)
    time.sleep(delay)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    assert "PanicException" not in err and "panicked" not in err, err
    assert "interrupted" in out, (out, err)


def test_ctrl_c_stops_runs_in_worker_threads_within_a_second():
    p = start(THREADS)
    time.sleep(1.0)
    t0 = time.perf_counter()
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    took = time.perf_counter() - t0
    assert "interrupted" in out, (out, err)
    assert "panicked" not in err, err
    # A poll of 100 ms and the engine's stop between impacts; 2 s of slack for a loaded machine.
    assert took < 3.0, f"the worker threads ran on for {took:.1f} s"


@pytest.mark.parametrize("value", [10**400, -(10**400)])
def test_a_huge_int_is_out_of_range(value):
    with pytest.raises(thud.ParameterError) as e:
        thud.pulse(points=value)
    assert "out of range" in str(e.value) and "not an int" not in str(e.value), str(e.value)
    assert e.value.param == "points"


def test_forged_states_are_value_errors_naming_the_field():
    run = thud.simulate(preset="paper-fig9", samples=50)
    kind, state = run.__reduce__()[1]
    good = json.loads(state)
    forged = dict(good)
    del forged["history"]
    with pytest.raises(ValueError, match="history"):
        thud._restore(kind, json.dumps(forged))
    forged = dict(good, record=dict(good["record"], final_time_s="soon"))
    with pytest.raises(ValueError, match="final_time_s"):
        thud._restore(kind, json.dumps(forged))
    chart = thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.2)
    kind, state = chart.__reduce__()[1]
    forged = json.loads(state)
    forged["design"] = {"nonsense": True}
    with pytest.raises(ValueError, match="Chart"):
        thud._restore(kind, json.dumps(forged))
    for bad in ("[]", "{}", '{"record": null}'):
        for k in ("Pulse", "Run", "Ensemble", "Chart", "Response"):
            with pytest.raises(ValueError):
                thud._restore(k, bad)


def test_a_forged_huge_number_does_not_load():
    """A chart whose cell is forged to 1e308 gave NaN Table 5 bands; it is refused on load."""
    chart = thud.sweep("30g:40g:2", "2cm:3cm:2", duration=0.2)
    kind, state = chart.__reduce__()[1]
    text = state.replace('"spl_max_db":', '"spl_max_db":1e308,"x_":', 1)
    assert text != state
    with pytest.raises(ValueError, match="spl_max_db"):
        thud._restore(kind, text)


@pytest.mark.parametrize("value", [10**400, -(10**400)])
def test_a_huge_int_in_an_axis_is_out_of_range(value):
    with pytest.raises(thud.ParameterError) as e:
        thud.restitution(masses_kg=[0.01, value])
    assert "out of range" in str(e.value) and "not an int" not in str(e.value), str(e.value)
    assert e.value.param == "masses_kg"
