"""thud.design beside pymoo's NSGA-II calling thud's Python module, on the issue's problem:
the paper's Table 3 damper, mass 20–120 g × gap 1–6 cm, SPLmax minimised and the damping
inclination e maximised, 400 evaluations, hypervolume against (106 dB, 0 cm/s).

Not run in CI (pymoo is not a dependency): `pip install pymoo`, then
`python crates/thud-py/bench/design_vs_pymoo.py [--seeds 5]`. Both are measured side by side in
one run, on the same machine, per seed: wall time and the hypervolume of the non-dominated set
of every design each evaluated (the definition `thud design` reports), and for pymoo also of
its final population. pymoo is run as a user would write it (one thud.simulate per design,
serially) and with its batch evaluated on a thread pool (thud releases the GIL).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from concurrent.futures import ThreadPoolExecutor
from typing import List, Optional, Tuple

import numpy as np

import thud

BUDGET = 400
REFERENCE = (106.0, 0.0)
BASE = dict(preset="paper-table3")
PROBLEM = dict(vary=["mass=20g:120g", "gap=1cm:6cm"], minimize="spl_max_db", maximize="inclination_cm_s")


def hypervolume(points: List[Tuple[float, float]]) -> float:
    """The area dominated by (spl, e) points (spl minimised, e maximised) up to REFERENCE."""
    pts = sorted((s, -e) for s, e in points if s < REFERENCE[0] and -e < -REFERENCE[1])
    area, y = 0.0, -REFERENCE[1]
    for x, fy in pts:
        if fy < y:
            area += (REFERENCE[0] - x) * (y - fy)
            y = fy
    return area


def evaluate(x: np.ndarray) -> Tuple[Optional[float], Optional[float]]:
    run = thud.simulate(**BASE, mass=float(x[0]), gap=float(x[1]), samples=2)
    return run.spl_max_db, run.inclination_cm_s


def run_pymoo(seed: int, threads: int) -> Tuple[float, float, float]:
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import Problem
    from pymoo.optimize import minimize

    archive: List[Tuple[float, float]] = []
    pool = ThreadPoolExecutor(threads) if threads > 1 else None

    class Damper(Problem):  # type: ignore[misc]
        def __init__(self) -> None:
            super().__init__(n_var=2, n_obj=2, n_ieq_constr=1, xl=np.array([0.02, 0.01]),
                             xu=np.array([0.12, 0.06]))

        def _evaluate(self, X: np.ndarray, out: dict, *args: object, **kwargs: object) -> None:
            res = list(pool.map(evaluate, X)) if pool else [evaluate(x) for x in X]
            F, G = [], []
            for s, e in res:
                ok = s is not None and e is not None
                if ok:
                    archive.append((s, e))
                F.append([s if ok else 1e12, -e if ok else 1e12])
                G.append([0.0 if ok else 1.0])
            out["F"], out["G"] = np.array(F), np.array(G)

    t0 = time.perf_counter()
    res = minimize(Damper(), NSGA2(pop_size=40), ("n_eval", BUDGET), seed=seed, verbose=False)
    wall = time.perf_counter() - t0
    if pool:
        pool.shutdown()
    final = [(f[0], -f[1]) for f in np.atleast_2d(res.F)] if res.F is not None else []
    return wall, hypervolume(archive), hypervolume(final)


def run_thud(seed: int) -> Tuple[float, float]:
    t0 = time.perf_counter()
    front = thud.design(**BASE, **PROBLEM, evaluations=BUDGET, seed=seed, reference=REFERENCE)
    wall = time.perf_counter() - t0
    assert front.hypervolume is not None
    return wall, front.hypervolume


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=5)
    a = ap.parse_args()
    threads = os.cpu_count() or 1
    rows = []
    print(f"{'seed':>4}  {'thud s':>7} {'thud HV':>8}  {'pymoo s':>7} {'pymoo HV':>8} {'(final)':>8}  "
          f"{'pymoo+threads s':>15} {'HV':>8}")
    for seed in range(1, a.seeds + 1):
        t = run_thud(seed)
        p = run_pymoo(seed, 1)
        q = run_pymoo(seed, threads)
        rows.append((t, p, q))
        print(f"{seed:>4}  {t[0]:>7.2f} {t[1]:>8.3f}  {p[0]:>7.2f} {p[1]:>8.3f} {p[2]:>8.3f}  {q[0]:>15.2f} {q[1]:>8.3f}")
    med = statistics.median
    # The medians of the first ten and thirty seeds too (the acceptance's ten), from the same run.
    parts = [(f"seeds 1-{k}", rows[:k]) for k in (10, 30) if len(rows) > k] + [(f"seeds 1-{len(rows)}", rows)]
    for name, part in parts:
        print(f"median over {name}:  thud {med(r[0][0] for r in part):.2f} s, HV {med(r[0][1] for r in part):.3f};  "
              f"pymoo {med(r[1][0] for r in part):.2f} s, HV {med(r[1][1] for r in part):.3f} "
              f"(final population {med(r[1][2] for r in part):.3f});  "
              f"pymoo on {threads} threads {med(r[2][0] for r in part):.2f} s, HV {med(r[2][1] for r in part):.3f}")


if __name__ == "__main__":
    main()
