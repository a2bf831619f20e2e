"""Every result pickles and deep-copies to an equal object, and results
travel between processes: a multiprocessing.Pool and a 2-worker Dask LocalCluster running
`thud.simulate` by `client.submit`."""

import copy
import json
import multiprocessing
import pickle

import numpy as np
import pytest

import thud


def same(a, b):
    """Two results hold the same fields: the same JSON-ready dict (every float exactly, NaN as
    None), the same repr, and the same array dtypes."""
    assert type(a) is type(b)
    assert json.dumps(a.as_dict(json=True)) == json.dumps(b.as_dict(json=True))
    assert repr(a) == repr(b)

    def dtypes(d):
        if isinstance(d, dict):
            return {k: dtypes(v) for k, v in d.items()}
        if isinstance(d, list):
            return [dtypes(v) for v in d]
        return str(d.dtype) if isinstance(d, np.ndarray) else type(d).__name__

    assert dtypes(a.as_dict()) == dtypes(b.as_dict())


RESULTS = {
    "Pulse": lambda: thud.pulse(points=300),
    "Run": lambda: thud.simulate(preset="paper-fig9", samples=300),
    "forced Run": lambda: thud.simulate(force=1, freq=5, duration=3, samples=100),
    "Ensemble": lambda: thud.simulate(preset="paper-fig9", ensemble=4),
    "Chart": lambda: thud.sweep("30g:100g:3", "2cm:5cm:2", duration=0.5),
    "ensemble Chart": lambda: thud.sweep("30g:100g:2", "2cm:5cm:2", duration=0.5, ensemble=3),
    "Response": lambda: thud.response("4.6Hz:5.4Hz:3", force=1, duration=4),
    "ensemble Response": lambda: thud.response("4.6Hz:5.4Hz:2", force=1, duration=4, ensemble=2),
}


@pytest.mark.parametrize("what", list(RESULTS))
def test_every_result_pickles_and_deep_copies(what):
    r = RESULTS[what]()
    for proto in (2, pickle.HIGHEST_PROTOCOL):
        back = pickle.loads(pickle.dumps(r, protocol=proto))
        same(r, back)
    same(r, copy.deepcopy(r))
    same(r, copy.copy(r))


def test_an_unpickled_chart_still_computes_table5():
    c = RESULTS["Chart"]()
    back = pickle.loads(pickle.dumps(c))
    t, u = c.table5(), back.table5()
    assert list(t) == list(u)
    for k in t:
        np.testing.assert_array_equal(t[k], u[k])


def test_a_forged_state_is_refused():
    with pytest.raises(ValueError):
        thud._restore("Run", "not json")
    with pytest.raises(ValueError):
        thud._restore("Nonesuch", "{}")


def simulate_mass(mass_kg):
    """A task of the pool (module level, so the pool can pickle it)."""
    return thud.simulate(preset="paper-fig9", mass=mass_kg, samples=50)


def test_multiprocessing_pool_returns_runs():
    masses = [0.03, 0.05]
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        runs = pool.map(simulate_mass, masses)
    for m, r in zip(masses, runs):
        assert isinstance(r, thud.Run)
        same(r, simulate_mass(m))


def test_dask_client_submit_simulate_on_a_2_worker_local_cluster():
    distributed = pytest.importorskip("distributed", reason="dask.distributed is not installed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    try:
        with distributed.Client(cluster) as client:
            futures = [client.submit(thud.simulate, preset="paper-fig9", mass=m, samples=50, pure=False)
                       for m in (0.03, 0.05)]
            chart = client.submit(thud.sweep, [0.03, 0.05], [0.02], duration=0.5).result()
            runs = [f.result() for f in futures]
    finally:
        cluster.close()
    for m, r in zip((0.03, 0.05), runs):
        same(r, simulate_mass(m))
    same(chart, thud.sweep([0.03, 0.05], [0.02], duration=0.5))
