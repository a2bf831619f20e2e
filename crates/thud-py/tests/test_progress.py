"""Progress and cancellation of long sweeps from Python: a callback
hears the engine's own count of finished cells (points), progress=True draws a bar, and a
callback that raises — KeyboardInterrupt, as Ctrl-C in a notebook — stops the work early."""

import time

import pytest

import thud
from conftest import REPORT


def test_a_callback_hears_the_engine_s_count_up_to_every_cell():
    calls = []
    chart = thud.sweep("30g:100g:6", "2cm:5cm:5", duration=1.0, progress=lambda d, t: calls.append((d, t)))
    assert calls, "the callback was never called"
    assert all(t == 30 for _, t in calls)
    done = [d for d, _ in calls]
    assert done == sorted(done) and len(set(done)) == len(done)  # rising, each count once
    assert done[-1] == 30 == chart.zone.size


def test_a_response_counts_every_point_of_every_run_and_sweep():
    calls = []
    thud.response("4.6Hz:5.4Hz:3", force=1, duration=3, continuation=True, ensemble=2,
                  progress=lambda d, t: calls.append((d, t)))
    assert calls[-1] == (12, 12)  # 3 frequencies × up and down × 2 runs


def test_progress_true_draws_a_bar_on_stderr(capfd, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "tqdm", None)  # the plain bar, whether or not tqdm is installed
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    thud.sweep("30g:100g:3", "2cm:5cm:2", duration=0.5, progress=True)
    err = capfd.readouterr().err
    assert err.endswith("sweep: 6/6 (100 %)\n"), repr(err)


def test_a_bad_progress_value_is_refused_with_one_line():
    with pytest.raises(thud.ParameterError) as info:
        thud.sweep([0.04], [0.04], progress=3)
    assert info.value.param == "progress"
    assert str(info.value) == "invalid progress: expected a callable progress(done, total) or True, not an int"


def test_a_callback_raising_keyboard_interrupt_stops_a_long_sweep_early():
    seen = []

    def stop(done, total):
        seen.append(done)
        if done >= 2:
            raise KeyboardInterrupt

    # 400 cells of 50 s each: about a minute of work on two cores.
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        thud.sweep("30g:100g:20", "2cm:5cm:20", duration=50, progress=stop)
    elapsed = time.perf_counter() - t0
    REPORT.append(("A progress callback's KeyboardInterrupt stopped a 400-cell sweep after", f"{elapsed:.2f} s"))
    assert seen[-1] < 400 and elapsed < 10, (seen[-1], elapsed)
    # The engine is free again: the next call runs normally.
    assert thud.sweep([0.04], [0.04], duration=0.2).zone.shape == (1, 1)


def test_a_callback_s_own_error_propagates_and_stops_the_sweep():
    def broken(done, total):
        raise RuntimeError("my bar broke")

    with pytest.raises(RuntimeError, match="my bar broke"):
        thud.sweep("30g:100g:20", "2cm:5cm:20", duration=50, progress=broken)
