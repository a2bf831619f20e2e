"""A design-chart study as Dask tasks: impact mass × gap (× excitation level), one task per block
of designs, one table out.

Each task runs `thud.sweep` on a block of masses × every gap (the engine uses every core of its
worker and releases the GIL), so the study scales from a laptop to a cluster without changing a
line: by default a `dask.distributed.LocalCluster` on this machine; with `--scheduler ADDRESS`
the tasks go to an existing cluster, e.g. one started over SSH (`dask.distributed.SSHCluster`, or
`dask scheduler` / `dask worker` by hand) or on Slurm with dask-jobqueue:

    from dask_jobqueue import SLURMCluster
    cluster = SLURMCluster(cores=32, memory="16GB", walltime="01:00:00")
    cluster.scale(jobs=8)
    print(cluster.scheduler_address)   # pass this as --scheduler

Every worker needs the `thud` module installed (`pip install` the same wheel, or `maturin
develop` in a shared environment).

Robust designs: with `--v0 1.0,1.4,2.0` every design runs at each initial velocity of the
structure (the excitation level) and the summary lists the designs that stay in zone 3 (quiet
and strong) at every level. The numbers are those of `thud sweep --json` for the same grid: the
axes are computed by the engine from the same "FROM:TO:N" text.

Examples:
    python examples/python/dask_sweep.py --masses 30g:100g:20 --gaps 2cm:5cm:20 --workers 2
    python examples/python/dask_sweep.py --preset paper-table3 --v0 1.0,1.4,2.0 --out robust.parquet
    python examples/python/dask_sweep.py --scheduler tcp://head-node:8786 --masses 10g:200g:200 \\
        --gaps 5mm:6cm:200 --block 10

Output: one row per design, columns v0_m_s, mass_kg, gap_m and the metrics (n_impacts,
inclination_cm_s = e of Eq 27, inclination_fit_cm_s, u0_max_m_s, zdot_abs_max_m_s, spl_max_db,
contact_duration_s, restitution_mean, zone 1–4 or empty). CSV (numbers written exactly, empty =
no value), or Parquet when the file name ends in .parquet (needs pyarrow).
"""

import argparse
import csv
import math
import sys
import time

import thud

METRICS = [
    "n_impacts",
    "inclination_cm_s",
    "inclination_fit_cm_s",
    "u0_max_m_s",
    "zdot_abs_max_m_s",
    "spl_max_db",
    "contact_duration_s",
    "restitution_mean",
    "zone",
]
COLUMNS = ["v0_m_s", "mass_kg", "gap_m"] + METRICS


def run_block(masses_kg, gaps_m, v0s, design):
    """One Dask task: the chart of `masses_kg` × `gaps_m` at each v0 (None: the preset's), as
    rows (lists of plain Python numbers; None = no such value)."""
    import thud  # on the worker

    rows = []
    for v0 in v0s:
        chart = thud.sweep(list(masses_kg), list(gaps_m), v0=v0, **design)
        v0_used = chart.design["damper"]["v0_m_s"]
        for g, gap in enumerate(chart.gaps_m):
            for m, mass in enumerate(chart.masses_kg):
                row = [v0_used, float(mass), float(gap)]
                for key in METRICS:
                    value = getattr(chart, key)[g, m].item()
                    if key == "zone":
                        value = value or None
                    elif isinstance(value, float) and math.isnan(value):
                        value = None
                    row.append(value)
                rows.append(row)
    return rows


def blocks(values, size):
    return [values[i : i + size] for i in range(0, len(values), size)]


def write(rows, path):
    if path.endswith(".parquet"):
        import pyarrow as pa
        import pyarrow.parquet as pq

        table = pa.table({c: [r[i] for r in rows] for i, c in enumerate(COLUMNS)})
        pq.write_table(table, path)
        return
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in rows:
            # repr: the shortest text that reads back as the very same float.
            w.writerow(["" if v is None else repr(v) for v in r])


def default_out():
    try:
        import pyarrow  # noqa: F401

        return "dask_sweep.parquet"
    except ImportError:
        return "dask_sweep.csv"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--masses", default="30g:100g:20", help="impact masses FROM:TO:N (as thud sweep)")
    ap.add_argument("--gaps", default="2cm:5cm:20", help="gaps FROM:TO:N (as thud sweep)")
    ap.add_argument("--preset", default="default", help="the base design (thud presets)")
    ap.add_argument("--v0", default=None, help="comma-separated initial velocities (m/s) for a robust study")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster workers (ignored with --scheduler)")
    ap.add_argument("--scheduler", default=None, help="address of an existing Dask scheduler (SSH, Slurm, …)")
    ap.add_argument("--block", type=int, default=None, help="masses per task (default: about 4 tasks per worker)")
    ap.add_argument("--out", default=None, help="output table (.csv, or .parquet with pyarrow)")
    a = ap.parse_args(argv)

    masses = [float(m) for m in thud.axis("masses", a.masses)]
    gaps = [float(g) for g in thud.axis("gaps", a.gaps)]
    v0s = [float(v) for v in a.v0.split(",")] if a.v0 else [None]
    design = {"preset": a.preset}
    # Check the design and the work before any cluster starts (a bad value fails here, once).
    thud.sweep(masses[:1], gaps[:1], v0=v0s[0], **design)

    from dask.distributed import Client, LocalCluster

    t0 = time.perf_counter()
    if a.scheduler:
        client = Client(a.scheduler)
        cluster = None
    else:
        cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    try:
        n_workers = max(1, len(client.scheduler_info().get("workers", {})) or a.workers)
        size = a.block or max(1, math.ceil(len(masses) / (4 * n_workers)))
        futures = [client.submit(run_block, b, gaps, v0s, design, pure=False) for b in blocks(masses, size)]
        rows = [r for f in futures for r in f.result()]
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    rows.sort(key=lambda r: (r[0], r[2], r[1]))
    out = a.out or default_out()
    write(rows, out)
    elapsed = time.perf_counter() - t0
    print(f"{len(rows)} designs in {len(futures)} tasks on {n_workers} workers: {elapsed:.1f} s → {out}")

    # Robust zone 3: quiet and strong at every excitation level.
    by_design = {}
    for r in rows:
        by_design.setdefault((r[1], r[2]), []).append(r[COLUMNS.index("zone")])
    robust = sorted(k for k, zones in by_design.items() if all(z == 3 for z in zones))
    levels = "every v0" if len(v0s) > 1 else "the design's v0"
    print(f"{len(robust)} of {len(by_design)} designs are in zone 3 at {levels}")
    for mass, gap in robust[:10]:
        print(f"  m {mass * 1e3:.2f} g, d {gap * 1e2:.3f} cm")
    return 0


if __name__ == "__main__":
    sys.exit(main())
